//! The student's scene files load in viewray, and viewray's rays, frames and projections
//! of them are the student's correct ones, to 1e-9: the two were written apart, from the
//! same lecture.

use serde_json::Value;

use super::v;
use crate::support::student::{Aim, CameraSpec, Projection, Scene, Vec3, frame, project, ray};
use crate::support::viewray;

/// A camera and the size of the image it makes.
struct Shot {
    name: &'static str,
    camera: CameraSpec,
    size: (u32, u32),
}

fn shots() -> Vec<Shot> {
    let turned = CameraSpec {
        // A coordinate RON writes with an exponent.
        eye: v(2.5e-7, 2.2, 5.5),
        aim: Aim::LookAt(v(0.2, 0.5, 0.0)),
        up: v(0.1, 1.0, 0.05),
        projection: Projection::Perspective {
            d: 1.7,
            viewport: (1.2, 0.7),
            shift: (0.15, -0.1),
        },
    };
    vec![
        Shot {
            name: "canonical",
            camera: CameraSpec::canonical(),
            size: (2, 2),
        },
        Shot {
            name: "shifted, d = 2, a 3 x 1 viewport",
            camera: CameraSpec {
                eye: v(1.0, 0.0, 0.0),
                projection: Projection::Perspective {
                    d: 2.0,
                    viewport: (3.0, 1.0),
                    shift: (0.5, 0.25),
                },
                ..CameraSpec::canonical()
            },
            size: (5, 3),
        },
        Shot {
            name: "perspective, turned, rolled and shifted",
            camera: turned,
            size: (7, 4),
        },
        Shot {
            name: "orthographic, turned",
            camera: CameraSpec {
                eye: v(3.0, 4.0, 5.0),
                aim: Aim::LookAt(Vec3::ZERO),
                up: Vec3::Y,
                projection: Projection::Orthographic {
                    viewport: (4.0, 3.0),
                },
            },
            size: (6, 5),
        },
        Shot {
            name: "oblique, turned",
            camera: CameraSpec {
                eye: v(0.0, 1.0, 3.0),
                aim: Aim::View(v(-0.2, -0.1, -1.0)),
                up: Vec3::Y,
                projection: Projection::Oblique {
                    viewport: (5.0, 2.5),
                    ratio: 0.5,
                    angle_degrees: 30.0,
                },
            },
            size: (8, 4),
        },
    ]
}

/// Writes the example scene through `shot`'s camera to a file in `dir`.
fn scene_file(dir: &tempfile::TempDir, shot: &Shot) -> String {
    let path = dir.path().join("student.ron");
    let (width, height) = shot.size;
    let ron = Scene::example().to_ron(&shot.camera, width, height, 1);
    std::fs::write(&path, ron).unwrap();
    path.to_str().unwrap().to_owned()
}

/// Runs `viewray args`, which must succeed quietly; its JSON lines.
#[track_caller]
fn json_lines(args: &[&str]) -> Vec<Value> {
    let out = viewray(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "viewray {args:?}: {stderr}");
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str(line).unwrap())
        .collect()
}

fn vec3(value: &Value) -> Vec3 {
    let a: Vec<f64> = value
        .as_array()
        .unwrap_or_else(|| panic!("not an array: {value}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    v(a[0], a[1], a[2])
}

/// Checks that viewray's `actual` is the student's `expected` to 1e-9 (relative where
/// the numbers are large).
#[track_caller]
fn assert_close(actual: Vec3, expected: Vec3, what: &str) {
    let close = actual
        .to_array()
        .iter()
        .zip(expected.to_array())
        .all(|(a, e)| (a - e).abs() <= 1e-9 * e.abs().max(1.0));
    assert!(
        close,
        "{what}: viewray says {actual:?}, the student {expected:?}"
    );
}

#[test]
fn viewray_reads_the_students_scene_and_gives_the_same_rays() {
    let dir = tempfile::tempdir().unwrap();
    for shot in shots() {
        let file = scene_file(&dir, &shot);
        let (width, height) = shot.size;
        let pixels = [
            (0, 0),
            (height - 1, width - 1),
            (1, width / 2),
            (height / 2, 1),
        ];
        for offset in [(0.5, 0.5), (0.25, 0.75), (0.0, 0.0)] {
            let sample = format!("{},{}", offset.0, offset.1);
            let mut args = vec!["rays", &file, "--sample", &sample];
            let texts: Vec<String> = pixels.iter().map(|(r, c)| format!("{r},{c}")).collect();
            for text in &texts {
                args.extend(["--pixel", text]);
            }
            let lines = json_lines(&args);
            assert_eq!(lines.len(), pixels.len(), "{}", shot.name);
            for (line, &pixel) in lines.iter().zip(&pixels) {
                assert_eq!(
                    (line["row"].as_u64(), line["col"].as_u64()),
                    (Some(u64::from(pixel.0)), Some(u64::from(pixel.1)))
                );
                let expected = ray(&shot.camera, &[], shot.size, pixel, offset);
                let what = format!("{}, pixel {pixel:?} at {offset:?}", shot.name);
                assert_close(
                    vec3(&line["origin"]),
                    expected.origin,
                    &format!("{what}: origin"),
                );
                assert_close(
                    vec3(&line["direction"]),
                    expected.direction,
                    &format!("{what}: direction"),
                );
            }
        }
    }
}

#[test]
fn viewray_gives_the_students_frame() {
    let dir = tempfile::tempdir().unwrap();
    for shot in shots() {
        let file = scene_file(&dir, &shot);
        let line = &json_lines(&["frame", &file])[0];
        let f = frame(&shot.camera, &[]);
        for (key, expected) in [("e", f.e), ("u", f.u), ("v", f.v), ("w", f.w)] {
            assert_close(vec3(&line[key]), expected, &format!("{}: {key}", shot.name));
        }
    }
}

#[test]
fn viewray_projects_as_the_student_does() {
    let dir = tempfile::tempdir().unwrap();
    let points = [
        v(0.3, 0.4, -2.0),
        v(-1.0, 0.5, 0.2),
        v(0.0, 2.0, 9.0),
        v(1.5, 1.0, -0.5),
    ];
    for shot in shots() {
        let file = scene_file(&dir, &shot);
        let texts: Vec<String> = points
            .iter()
            .map(|p| format!("{},{},{}", p.x, p.y, p.z))
            .collect();
        let mut args = vec!["project", file.as_str()];
        for text in &texts {
            args.extend(["--point", text]);
        }
        let lines = json_lines(&args);
        assert_eq!(lines.len(), points.len());
        for (line, &point) in lines.iter().zip(&points) {
            let what = format!("{}: {point:?}", shot.name);
            match project(&shot.camera, shot.size, point) {
                Some((x, y)) => {
                    let seen = v(
                        line["x"].as_f64().unwrap(),
                        line["y"].as_f64().unwrap(),
                        0.0,
                    );
                    assert_close(seen, v(x, y, 0.0), &what);
                }
                None => assert!(line["x"].is_null() && line["y"].is_null(), "{what}: {line}"),
            }
        }
    }
}

/// The whole scene loads: viewray renders it (materials, lights and objects included).
#[test]
fn viewray_renders_the_students_scene() {
    let dir = tempfile::tempdir().unwrap();
    for shot in shots() {
        let file = scene_file(&dir, &shot);
        let png = dir.path().join("viewray.png");
        let png = png.to_str().unwrap();
        let out = viewray(&["render", &file, "-o", png, "--size", "16x12"]);
        assert!(
            out.status.success(),
            "{}: {}",
            shot.name,
            String::from_utf8_lossy(&out.stderr)
        );
        let image = image::open(png).unwrap();
        assert_eq!((image.width(), image.height()), (16, 12), "{}", shot.name);
    }
}
