//! `viewray render` as a user runs it: an image file appears, or one error line and no
//! file at all.

use std::path::{Path, PathBuf};

use serde_json::Value;
use tempfile::TempDir;

use crate::support;
use support::{error_line, viewray, viewray_with_input};

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

#[test]
fn an_image_goes_to_standard_output_with_dash() {
    let dir = TempDir::new().unwrap();
    let file = path(&dir, "file.png");
    run_ok(&["render", "-o", &file, "--size", "32x24", "--samples", "1"]);
    // -o - writes the same PNG to stdout (PNG unless --format says otherwise), and no
    // file.
    let piped = viewray(&["render", "-o", "-", "--size", "32x24", "--samples", "1"]);
    assert!(piped.status.success());
    assert!(piped.stderr.is_empty());
    assert_eq!(piped.stdout, std::fs::read(&file).unwrap());
    // EXR by --format: its magic number (the image crate here decodes PNG only).
    let exr = viewray(&["render", "-o", "-", "--format", "exr", "--size", "32x24"]);
    assert!(exr.status.success());
    assert_eq!(exr.stdout[..4], [0x76, 0x2f, 0x31, 0x01]);
    assert_eq!(files(dir.path()), ["file.png"]);
}

#[test]
fn a_scene_on_standard_input_renders_as_its_file_does() {
    let dir = TempDir::new().unwrap();
    let scene = path(&dir, "red.ron");
    std::fs::write(&scene, RED_SPHERE).unwrap();
    let by_file = path(&dir, "by_file.png");
    let by_stdin = path(&dir, "by_stdin.png");
    run_ok(&["render", &scene, "-o", &by_file]);
    let out = viewray_with_input(
        dir.path(),
        &["render", "-", "-o", &by_stdin],
        RED_SPHERE.as_bytes(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(
        std::fs::read(&by_file).unwrap(),
        std::fs::read(&by_stdin).unwrap()
    );
    // And the default scene's text renders as the default scene does.
    let text = viewray(&["scene", "--default"]).stdout;
    let from_text = path(&dir, "from_text.png");
    let default = path(&dir, "default.png");
    let out = viewray_with_input(
        dir.path(),
        &[
            "render",
            "-",
            "-o",
            &from_text,
            "--size",
            "40x30",
            "--samples",
            "1",
        ],
        &text,
    );
    assert!(out.status.success());
    run_ok(&[
        "render",
        "-o",
        &default,
        "--size",
        "40x30",
        "--samples",
        "1",
    ]);
    assert_eq!(
        std::fs::read(&default).unwrap(),
        std::fs::read(&from_text).unwrap()
    );
}

#[test]
fn a_size_that_stretches_an_explicit_viewport_is_warned_about() {
    let dir = TempDir::new().unwrap();
    let scene = path(&dir, "red.ron");
    std::fs::write(&scene, RED_SPHERE).unwrap();
    let out = path(&dir, "square.png");
    // RED_SPHERE's viewport is 1.0 x 0.75: a square image stretches it.
    let square = viewray(&["render", &scene, "-o", &out, "--size", "64x64"]);
    assert!(square.status.success());
    let stderr = String::from_utf8(square.stderr).unwrap();
    assert_eq!(
        stderr,
        "warning: --size 64x64 stretches the picture: the scene's viewport is 1 x 0.75 \
         (aspect 1.333) but the image is 64 x 64 (aspect 1.000), so pixels are no longer \
         square; to keep them square, use --size 64x48 (the viewport's aspect ratio), or \
         give a field of view (`fov_y` or `fov_x`) instead of `viewport`\n"
    );
    assert_eq!(
        image::open(&out).unwrap().width(),
        64,
        "the image is still made"
    );
    // The viewport's own aspect ratio, a field of view and a preset: no warning.
    run_ok(&["render", &scene, "-o", &out, "--size", "64x48"]);
    let fov = path(&dir, "fov.ron");
    std::fs::write(
        &fov,
        RED_SPHERE.replace("distance: 1.0, viewport: (1.0, 0.75)", "fov_y: 40.0"),
    )
    .unwrap();
    run_ok(&["render", &fov, "-o", &out, "--size", "64x64"]);
    let preset = path(&dir, "preset.ron");
    std::fs::write(
        &preset,
        "(camera: Isometric(target: (0.0, 0.0, 0.0), size: 2.0))",
    )
    .unwrap();
    run_ok(&["render", &preset, "-o", &out, "--size", "64x16"]);
    // A parallel camera's viewport is stretched alike; its remedy is `height`.
    let ortho = path(&dir, "ortho.ron");
    std::fs::write(
        &ortho,
        "(camera: (eye: (0.0, 0.0, 5.0), view: (0.0, 0.0, -1.0),
                   projection: Orthographic(viewport: (4.0, 3.0))))",
    )
    .unwrap();
    let wide = viewray(&["render", &ortho, "-o", &out, "--size", "90x30"]);
    let stderr = String::from_utf8(wide.stderr).unwrap();
    assert!(stderr.contains("use --size 90x68"), "{stderr}");
    assert!(
        stderr.ends_with("or give `height` instead of `viewport`\n"),
        "{stderr}"
    );
}
