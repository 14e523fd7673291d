//! `viewray diagram` as a lecturer runs it on their own scene: the side view of its
//! camera as a PNG or an SVG, the same figure the library draws, or one error line and
//! no file.

use std::path::Path;

use tempfile::TempDir;
use viewray_diagram::{SideViewCanvas, SideWindow, side_view};
use viewray_scene::SceneLoader;

use crate::support;
use support::{error_line_in as error_line, viewray_in};

fn fixtures() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

#[track_caller]
fn run_ok(dir: &Path, args: &[&str]) {
    let out = viewray_in(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "viewray {args:?} failed: {stderr}");
    assert!(out.stderr.is_empty(), "stderr: {stderr}");
    assert!(out.stdout.is_empty(), "stdout: {:?}", out.stdout);
}

#[test]
fn a_scenes_side_view_is_written_as_the_library_draws_it() {
    let dir = TempDir::new().unwrap();
    let scene_path = fixtures().join("scenes/thin_lens_large_aperture.ron");
    let scene_arg = scene_path.to_str().unwrap();
    run_ok(dir.path(), &["diagram", scene_arg, "-o", "side.png"]);
    run_ok(
        dir.path(),
        &["diagram", scene_arg, "-o", "side.svg", "--pixel", "10,20"],
    );
    run_ok(
        dir.path(),
        &[
            "diagram",
            scene_arg,
            "-o",
            "same.svg",
            "--pixel",
            "11,21",
            "--one-based",
        ],
    );

    // The PNG is the library's figure, painted.
    let scene = SceneLoader::file(&scene_path).load().unwrap().scene;
    let camera = scene.camera();
    let window = SideWindow::fit(&scene, std::slice::from_ref(camera));
    let figure = side_view(&scene, camera, &window, SideViewCanvas::Slide, None);
    let expected = viewray_draw::raster::render(&figure);
    let written = image::open(dir.path().join("side.png")).unwrap().to_rgba8();
    assert_eq!((written.width(), written.height()), (1600, 900));
    assert!(written == expected, "the PNG is not the library's figure");

    // The SVG is the library's figure with pixel (10, 20) highlighted, and --one-based
    // names the same pixel as (11, 21).
    let figure = side_view(
        &scene,
        camera,
        &window,
        SideViewCanvas::Slide,
        Some((10, 20)),
    );
    let svg = std::fs::read_to_string(dir.path().join("side.svg")).unwrap();
    assert_eq!(
        svg,
        viewray_draw::svg::document(&figure, viewray_draw::svg::SvgText::Paths)
    );
    assert_eq!(
        svg,
        std::fs::read_to_string(dir.path().join("same.svg")).unwrap()
    );
    roxmltree::Document::parse(&svg).unwrap();
}

#[test]
fn bad_diagram_requests_are_one_error_line_and_no_file() {
    let dir = TempDir::new().unwrap();
    let scene = fixtures().join("default.ron");
    let scene = scene.to_str().unwrap();
    for (args, expected) in [
        (
            vec!["diagram", scene, "-o", "side.jpg"],
            "error: cannot write side.jpg: the output must be a .png or .svg file",
        ),
        (
            vec!["diagram", "missing.ron", "-o", "side.png"],
            "error: missing.ron: no such scene file",
        ),
        (
            vec!["diagram", scene, "-o", "side.png", "--pixel", "480,0"],
            "error: pixel 480,0 is outside the 640 x 480 image: rows run 0..=479 and columns 0..=639",
        ),
        (
            vec![
                "diagram",
                scene,
                "-o",
                "side.png",
                "--pixel",
                "0,1",
                "--one-based",
            ],
            "error: pixel 0,1 is outside the 640 x 480 image: rows run 1..=480 and columns 1..=640",
        ),
    ] {
        assert_eq!(error_line(dir.path(), &args), expected, "{args:?}");
    }
    let bad = fixtures().join("bad");
    let first_bad = std::fs::read_dir(&bad)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "ron"))
        .unwrap();
    let line = error_line(
        dir.path(),
        &["diagram", first_bad.to_str().unwrap(), "-o", "side.png"],
    );
    assert!(line.contains(".ron:"), "{line}");
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "a file was left"
    );
}
