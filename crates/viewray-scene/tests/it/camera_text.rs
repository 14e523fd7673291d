//! A camera on its own: the `camera:` value of a scene file, read back with
//! `parse_camera`, is the camera the whole file loads, at any image size.

use std::path::{Path, PathBuf};

use viewray_scene::{LoadOptions, SceneLoader, Shading, camera_text, parse_camera};

fn fixture_scenes() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root.join("scenes"))
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    paths.push(root.join("default.ron"));
    paths
}

#[test]
fn a_scene_files_camera_text_parses_to_the_camera_the_file_loads() {
    let scenes = fixture_scenes();
    assert!(scenes.len() > 10, "the fixtures are there");
    for path in scenes {
        let text = std::fs::read_to_string(&path).unwrap();
        let camera = camera_text(&text, &path).unwrap();
        assert!(
            camera.starts_with('(') || camera.starts_with(char::is_uppercase),
            "{}: {camera}",
            path.display()
        );
        // At the file's own size, and at another aspect ratio (fields of view and
        // presets follow it).
        for size in [None, Some((97, 31))] {
            let scene = SceneLoader::file(&path)
                .options(LoadOptions {
                    size,
                    samples: None,
                })
                .load()
                .unwrap()
                .scene;
            let (width, height) = (scene.camera().width(), scene.camera().height());
            let parsed = parse_camera(camera, Path::new("camera"), width, height)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            assert_eq!(&parsed, scene.camera(), "{} at {size:?}", path.display());
        }
    }
}

#[track_caller]
fn check_error(text: &str, expected: &str) {
    let error = parse_camera(text, Path::new("camera"), 64, 48).unwrap_err();
    assert_eq!(error.to_string(), expected);
}

#[test]
fn camera_errors_are_placed_in_the_camera_text() {
    check_error(
        "(eye: (0.0, 0.0, 0.0), eyes: (1.0, 0.0, 0.0))",
        "camera:1:24: unknown field `eyes` in `camera`, expected `eye`, `look_at`, `view`, `up` or `projection`",
    );
    check_error(
        "(\n  eye: (0.0, 0.0, 0.0),\n  look_at: (0.0, 0.0, 0.0),\n  projection: Perspective(fov_y: 40.0),\n)",
        "camera:1:1: camera: the view direction is zero (is the look-at point the eye itself?)",
    );
    check_error(
        "Isometric(target: (0.0, 0.0, 0.0))",
        "camera:1:34: missing field `size` in `Isometric`",
    );
    check_error("", "camera:1:1: unexpected end of file");
    check_error(
        "(eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0), projection: Fisheye(fov: 90.0)) x",
        "camera:1:80: non-whitespace trailing characters",
    );
    let error = parse_camera(
        "Top(target: (0.0, 0.0, 0.0), size: 2.0)",
        Path::new("camera"),
        0,
        10,
    )
    .unwrap_err();
    assert_eq!(
        error.message(),
        "image: the image must be at least 1 x 1 pixels, found 0 x 10"
    );
}

#[test]
fn shadings_are_named_as_scene_files_name_them() {
    for shading in Shading::ALL {
        assert_eq!(shading.name().parse::<Shading>(), Ok(shading));
        assert_eq!(format!("{shading:?}"), shading.name());
    }
    assert_eq!(
        "lit".parse::<Shading>(),
        Err(
            "unknown shading `lit`, expected one of `Flat`, `Normals`, `Depth` or `Lit`".to_owned()
        )
    );
}
