//! `viewray export` and `viewray import` through the real binary: files written
//! atomically, refusals and bad foreign files as one `error:` line with exit code 2 and
//! nothing written, and a round trip that gives back the rays.

use std::path::Path;

use crate::support;
use support::{error_line, viewray};

fn fixture(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(name)
        .to_str()
        .unwrap()
        .to_owned()
}

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn export_writes_the_file_and_its_meshes() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("houses.xml");
    let result = viewray(&[
        "export",
        &fixture("scenes/mesh_houses.ron"),
        "--to",
        "mitsuba",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(
        result.status.success(),
        "{}",
        String::from_utf8_lossy(&result.stderr)
    );
    let names = files_in(dir.path());
    assert!(names.contains(&"houses.xml".to_owned()), "{names:?}");
    assert!(
        names
            .iter()
            .any(|n| n.starts_with("houses-mesh") && n.ends_with(".obj")),
        "{names:?}"
    );
    assert!(!names.iter().any(|n| n.ends_with(".tmp")), "{names:?}");
}

#[test]
fn a_camera_the_tool_cannot_express_is_refused_and_nothing_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cabinet.xml");
    let line = error_line(&[
        "export",
        &fixture("scenes/oblique_cabinet.ron"),
        "--to",
        "mitsuba",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(
        line.contains(
            "oblique_cabinet.ron: cannot export to Mitsuba 3, which has no oblique camera"
        ),
        "{line}"
    );
    assert_eq!(files_in(dir.path()), Vec::<String>::new());
    let out = dir.path().join("shifted.gltf");
    let line = error_line(&[
        "export",
        &fixture("scenes/distortion_shifted.ron"),
        "--to",
        "gltf",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(
        line.contains("cannot export to glTF, which has no shift"),
        "{line}"
    );
    assert_eq!(files_in(dir.path()), Vec::<String>::new());
}

#[test]
fn every_bad_foreign_file_is_one_error_line() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/bad/interop");
    for name in files_in(&dir) {
        let path = dir.join(&name);
        let line = error_line(&["import", path.to_str().unwrap()]);
        assert!(line.contains(&name), "{name}: {line}");
    }
    let line = error_line(&["import", "no/such/file.xml"]);
    assert_eq!(line, "error: no/such/file.xml: no such file");
    let line = error_line(&[
        "export",
        &fixture("homework/canonical_2x2.ron"),
        "--to",
        "maya",
        "-o",
        "x",
    ]);
    assert!(
        line.contains("unknown tool `maya`, expected one of mitsuba, pbrt, blender, three, gltf"),
        "{line}"
    );
}

#[test]
fn export_then_import_gives_back_the_rays() {
    let dir = tempfile::tempdir().unwrap();
    let scene = fixture("scenes/perspective_two_point.ron");
    for (tool, name) in [
        ("mitsuba", "two.xml"),
        ("pbrt", "two.pbrt"),
        ("three", "two.json"),
    ] {
        let out = dir.path().join(name);
        let result = viewray(&["export", &scene, "--to", tool, "-o", out.to_str().unwrap()]);
        assert!(
            result.status.success(),
            "{}",
            String::from_utf8_lossy(&result.stderr)
        );
        let imported = viewray(&["import", out.to_str().unwrap()]);
        assert!(
            imported.status.success(),
            "{tool}: {}",
            String::from_utf8_lossy(&imported.stderr)
        );
        let ron = dir.path().join(format!("{name}.ron"));
        std::fs::write(&ron, &imported.stdout).unwrap();
        let pixels = ["--pixel", "0,0", "90,120", "179,239"];
        let ours = viewray(&[&["rays", &scene][..], &pixels].concat());
        let theirs = viewray(&[&["rays", ron.to_str().unwrap()][..], &pixels].concat());
        let parse = |out: &[u8]| -> Vec<Vec<f64>> {
            String::from_utf8_lossy(out)
                .lines()
                .map(|l| {
                    let v: serde_json::Value = serde_json::from_str(l).unwrap();
                    let mut numbers: Vec<f64> = v["origin"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_f64().unwrap())
                        .collect();
                    numbers.extend(
                        v["direction"]
                            .as_array()
                            .unwrap()
                            .iter()
                            .map(|x| x.as_f64().unwrap()),
                    );
                    numbers
                })
                .collect()
        };
        for (a, b) in parse(&ours.stdout).iter().zip(parse(&theirs.stdout)) {
            for (x, y) in a.iter().zip(&b) {
                assert!(
                    (x - y).abs() < 1e-12 * x.abs().max(1.0),
                    "{tool}: {a:?} != {b:?}"
                );
            }
        }
    }
}
