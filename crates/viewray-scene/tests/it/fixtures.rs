//! Every scene in `fixtures/` loads, and its camera is what the file says: the loaded
//! frame and projection of each are snapshots, so a change in how presets or defaults
//! resolve is a visible decision.

use std::fmt::Write;
use std::path::{Path, PathBuf};

use glam::DVec3;
use viewray_scene::{LoadOptions, SceneLoader};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

fn ron_files(dir: &Path) -> Vec<PathBuf> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    paths
}

/// A number rounded for a stable, readable snapshot.
fn num(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// `text` with every decimal number in it rounded by [`num`], so last-bit differences in
/// `tan` or `sin` between platforms do not change the snapshot.
fn round_numbers(text: &str) -> String {
    let mut out = String::new();
    let mut number = String::new();
    for c in text.chars().chain(std::iter::once(' ')) {
        if c.is_ascii_digit()
            || c == '.'
            || (c == '-' && number.is_empty())
            || c == 'e' && !number.is_empty()
        {
            number.push(c);
            continue;
        }
        match number.parse::<f64>() {
            Ok(x) if number.contains('.') => out += &num(x),
            _ => out += &number,
        }
        number.clear();
        out.push(c);
    }
    out.pop();
    out
}

fn vec3(v: DVec3) -> String {
    format!("({}, {}, {})", num(v.x), num(v.y), num(v.z))
}

#[test]
fn every_fixture_scene_loads() {
    let mut report = String::new();
    let mut scenes = ron_files(&fixtures().join("scenes"));
    assert!(scenes.len() >= 25, "expected a scene per projection family");
    // `viewray render`'s built-in scene is tested like the others.
    scenes.insert(0, fixtures().join("default.ron"));
    for path in scenes {
        let scene = SceneLoader::file(&path)
            .load()
            .unwrap_or_else(|e| panic!("{e}"))
            .scene;
        let camera = &scene.camera();
        let f = camera.frame();
        let name = path.file_stem().unwrap().to_str().unwrap();
        writeln!(
            report,
            "{name}: {} x {}, {} samples, {} objects, {} triangles\n  e = {}, u = {}, v = {}, w = {}\n  {}",
            camera.width(),
            camera.height(),
            scene.samples(),
            scene.world().objects().len(),
            scene.world().triangle_count(),
            vec3(f.e()),
            vec3(f.u()),
            vec3(f.v()),
            vec3(f.w()),
            round_numbers(&format!("{:?}", camera.projection())),
        )
        .unwrap();
    }
    insta::assert_snapshot!(report);
}

#[test]
fn size_and_samples_can_be_overridden() {
    let path = fixtures().join("scenes/perspective_general.ron");
    let options = LoadOptions {
        size: Some((64, 32)),
        samples: Some(3),
    };
    let scene = SceneLoader::file(&path)
        .options(options)
        .load()
        .unwrap()
        .scene;
    assert_eq!((scene.camera().width(), scene.camera().height()), (64, 32));
    assert_eq!(scene.samples(), 3);
    // A field-of-view camera follows the new aspect ratio.
    let path = fixtures().join("scenes/primitives_lit.ron");
    let scene = SceneLoader::file(&path)
        .options(options)
        .load()
        .unwrap()
        .scene;
    let viewport = scene.camera().projection().viewport().unwrap();
    assert!((viewport.x / viewport.y - 2.0).abs() < 1e-12);
    let too_big = LoadOptions {
        size: Some((20_000, 10)),
        samples: None,
    };
    let error = SceneLoader::file(&path)
        .options(too_big)
        .load()
        .unwrap_err()
        .to_string();
    assert!(error.contains("too large"), "{error}");
}

#[test]
fn a_mesh_placed_twice_is_loaded_once() {
    let scene = SceneLoader::file(&fixtures().join("scenes/mesh_houses.ron"))
        .load()
        .unwrap()
        .scene;
    let meshes: Vec<_> = scene
        .world()
        .objects()
        .iter()
        .filter_map(|o| match o {
            viewray_geometry::Object::Instance(i) => Some(i.mesh().clone()),
            _ => None,
        })
        .collect();
    assert_eq!(meshes.len(), 3);
    assert!(std::sync::Arc::ptr_eq(&meshes[0], &meshes[1]));
    assert!(std::sync::Arc::ptr_eq(&meshes[0], &meshes[2]));
}

#[test]
fn the_readme_example_scene_loads() {
    let readme = std::fs::read_to_string(fixtures().join("../README.md")).unwrap();
    // The first RON block of the section on scene files (other sections show other RON
    // files, such as an assignment).
    let section = readme
        .find("## Scene files")
        .expect("README has a section on scene files");
    let start = section
        + readme[section..]
            .find("```ron\n")
            .expect("README shows a scene")
        + "```ron\n".len();
    let length = readme[start..].find("```").unwrap();
    // Its mesh path is relative to a file in fixtures/, as the fixtures' are.
    let path = fixtures().join("readme_example.ron");
    let scene = SceneLoader::text(&readme[start..start + length], &path)
        .load()
        .unwrap_or_else(|e| panic!("{e}"))
        .scene;
    assert_eq!(scene.world().objects().len(), 5);
    assert_eq!(scene.lights().len(), 3);
}

#[test]
fn the_scene_format_examples_load() {
    let doc = std::fs::read_to_string(fixtures().join("../docs/scene-format.md")).unwrap();
    let blocks: Vec<&str> = doc
        .split("```ron\n")
        .skip(1)
        .map(|rest| rest.split("```").next().unwrap())
        .collect();
    assert!(blocks.len() >= 2, "the scene format shows whole scenes");
    for block in blocks {
        let scene = SceneLoader::text(block, &fixtures().join("scene-format.ron"))
            .load()
            .unwrap_or_else(|e| panic!("{e}\n{block}"))
            .scene;
        assert!(scene.camera().width() > 0);
    }
}
