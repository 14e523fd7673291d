//! `viewray render` as a user runs it: an image file appears, or one error line and no
//! file at all.

use std::path::{Path, PathBuf};

use serde_json::Value;
use tempfile::TempDir;

mod support;
use support::{error_line, viewray};

#[track_caller]
fn run_ok(args: &[&str]) -> String {
    let out = viewray(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "viewray {args:?} failed: {stderr}");
    // Not a terminal: no progress bar, no chatter.
    assert!(out.stderr.is_empty(), "stderr: {stderr}");
    String::from_utf8(out.stdout).unwrap()
}

fn path(dir: &TempDir, name: &str) -> String {
    dir.path().join(name).to_str().unwrap().to_owned()
}

/// The names of the files in `dir`, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    names
}

const RED_SPHERE: &str = "(
    image: (width: 320, height: 240), shading: Flat,
    camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
             projection: Perspective(distance: 1.0, viewport: (1.0, 0.75))),
    materials: { \"red\": (color: (1.0, 0.0, 0.0)) },
    objects: [Sphere(center: (0.0, 0.0, -5.0), radius: 1.0, material: \"red\")],
)";

#[test]
fn the_default_scene_renders_to_a_png_of_the_asked_size() {
    let dir = TempDir::new().unwrap();
    let out = path(&dir, "default.png");
    let stdout = run_ok(&["render", "-o", &out, "--size", "64x48", "--samples", "2"]);
    assert!(stdout.is_empty());
    let image = image::open(&out).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (64, 48));
    // Sky at the top, something else further down.
    assert_ne!(image.get_pixel(32, 0), image.get_pixel(32, 40));
    // The temporary file is gone.
    assert_eq!(files(dir.path()), ["default.png"]);
}

#[test]
fn a_scene_file_renders_the_same_on_one_and_two_threads() {
    let dir = TempDir::new().unwrap();
    let scene = path(&dir, "red.ron");
    std::fs::write(&scene, RED_SPHERE).unwrap();
    let (one, two) = (path(&dir, "one.png"), path(&dir, "two.png"));
    run_ok(&[
        "render",
        &scene,
        "-o",
        &one,
        "--threads",
        "1",
        "--samples",
        "4",
    ]);
    run_ok(&[
        "render",
        &scene,
        "-o",
        &two,
        "--threads",
        "2",
        "--samples",
        "4",
    ]);
    let bytes = std::fs::read(&one).unwrap();
    assert!(bytes == std::fs::read(&two).unwrap(), "the PNGs differ");
    let image = image::load_from_memory(&bytes).unwrap().to_rgb8();
    assert_eq!(image.dimensions(), (320, 240));
    assert_eq!(image.get_pixel(120, 160).0, [255, 0, 0]);
    assert_eq!(image.get_pixel(0, 0).0, [0, 0, 0]);
}

#[test]
fn an_exr_output_holds_linear_floats() {
    let dir = TempDir::new().unwrap();
    let scene = path(&dir, "red.ron");
    std::fs::write(
        &scene,
        RED_SPHERE.replace("1.0, 0.0, 0.0", "0.5, 0.25, 0.0"),
    )
    .unwrap();
    let out = path(&dir, "red.exr");
    run_ok(&["render", &scene, "-o", &out, "--size", "32x24"]);
    let image = image::open(&out).unwrap().to_rgb32f();
    assert_eq!(image.dimensions(), (32, 24));
    assert_eq!(image.get_pixel(16, 12).0, [0.5, 0.25, 0.0]);
}

#[test]
fn stats_print_one_json_line() {
    let dir = TempDir::new().unwrap();
    let out = path(&dir, "stats.png");
    let stdout = run_ok(&["render", "-o", &out, "--size", "40x30", "--stats"]);
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    let line: Value = serde_json::from_str(stdout.trim_end()).unwrap();
    let keys: Vec<&str> = line
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    assert_eq!(keys, ["triangles", "load_s", "build_s", "render_s", "rays"]);
    // The default scene's cube is twelve triangles; the rest is analytic.
    assert_eq!(line["triangles"], 12);
    for key in ["load_s", "build_s", "render_s"] {
        let seconds = line[key].as_f64().unwrap();
        assert!((0.0..60.0).contains(&seconds), "{key}: {seconds}");
    }
    // At least one primary ray per sample (16 per pixel), plus shadow rays.
    let rays = line["rays"].as_u64().unwrap();
    assert!(rays > 40 * 30 * 16, "{rays} rays");
}

#[test]
fn bad_input_gets_one_line_and_leaves_no_file() {
    let dir = TempDir::new().unwrap();
    let out = path(&dir, "out.png");
    let scene = path(&dir, "red.ron");
    std::fs::write(&scene, RED_SPHERE).unwrap();
    let bad_scene = path(&dir, "bad.ron");
    std::fs::write(
        &bad_scene,
        "(image: (width: 10, height: 10), camera: ( eye: 1.0 ))",
    )
    .unwrap();
    let missing = path(&dir, "missing.ron");
    let no_folder = path(&dir, "no/such/folder/out.png");
    let not_a_folder = path(&dir, "red.ron/out.png");
    let jpeg = path(&dir, "out.jpg");
    let folder = dir.path().to_str().unwrap().to_owned();
    let cases: &[(&[&str], &str)] = &[
        (&["render", &missing, "-o", &out], "missing.ron: "),
        (&["render", &bad_scene, "-o", &out], "bad.ron:1:"),
        (
            &["render", "-o", &out, "--size", "0x10"],
            "at least 1 x 1 pixels",
        ),
        (
            &["render", "-o", &out, "--size", "100000x10"],
            "at most 16384 pixels",
        ),
        (
            &["render", "-o", &out, "--size", "640by480"],
            "WIDTHxHEIGHT",
        ),
        (&["render", "-o", &out, "--samples", "0"], "from 1 to 65536"),
        (&["render", "-o", &out, "--threads", "0"], "threads"),
        (&["render", &scene, "-o", &no_folder], "cannot write"),
        (&["render", &scene, "-o", &not_a_folder], "cannot write"),
        (
            &["render", &scene, "-o", &jpeg],
            "must be a .png or .exr file",
        ),
        (&["render", &scene, "-o", &folder], "it is a directory"),
    ];
    for (args, expected) in cases {
        let line = error_line(args);
        assert!(line.contains(expected), "{args:?}: {line}");
        assert_eq!(files(dir.path()), ["bad.ron", "red.ron"], "{args:?}");
    }
}

#[test]
fn a_failed_render_keeps_the_previous_image() {
    let dir = TempDir::new().unwrap();
    let out = path(&dir, "keep.png");
    std::fs::write(&out, b"a good image").unwrap();
    let missing: PathBuf = dir.path().join("missing.ron");
    error_line(&["render", missing.to_str().unwrap(), "-o", &out]);
    assert_eq!(std::fs::read(&out).unwrap(), b"a good image");
    assert_eq!(files(dir.path()), ["keep.png"]);
}
