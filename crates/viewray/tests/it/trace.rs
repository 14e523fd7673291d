//! `viewray trace` as a student uses it: one pixel's numbers, as text and as JSON lines,
//! ending with the 8-bit value `viewray render --samples 1` writes for that pixel.

use std::path::{Path, PathBuf};

use serde_json::Value;

use crate::support;
use support::{error_line_in, repository, viewray_in};

/// Runs `viewray args` in the repository, expecting success and nothing on stderr;
/// returns what it printed.
#[track_caller]
fn run(args: &[&str]) -> String {
    let out = viewray_in(&repository(), args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "viewray {args:?}: {stderr}");
    assert!(stderr.is_empty(), "viewray {args:?}: {stderr}");
    String::from_utf8(out.stdout).unwrap()
}

/// The JSON lines of `viewray trace SCENE --pixel PIXEL --json` (and more `args`).
#[track_caller]
fn json_trace(scene: &str, pixel: &str, args: &[&str]) -> Vec<Value> {
    let mut all = vec!["trace", scene, "--pixel", pixel, "--json"];
    all.extend(args);
    run(&all)
        .lines()
        .map(|line| serde_json::from_str(line).expect("every line is JSON"))
        .collect()
}

/// Every scene file of the repository, relative to it: `fixtures/scenes/*.ron`, the
/// homework scenes and the default scene.
fn fixture_scenes() -> Vec<String> {
    let mut paths = Vec::new();
    for folder in ["fixtures/scenes", "fixtures/homework"] {
        let entries = std::fs::read_dir(repository().join(folder)).unwrap();
        let mut names: Vec<String> = entries
            .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|name| name.ends_with(".ron"))
            .map(|name| format!("{folder}/{name}"))
            .collect();
        names.sort();
        paths.extend(names);
    }
    paths.push("fixtures/default.ron".to_owned());
    paths
}

/// The 8-bit pixels of `viewray render SCENE --samples 1`.
fn render(scene: &str, dir: &Path) -> image::RgbImage {
    let output: PathBuf = dir.join("render.png");
    run(&[
        "render",
        scene,
        "--samples",
        "1",
        "-o",
        output.to_str().unwrap(),
    ]);
    image::open(&output).unwrap().to_rgb8()
}

/// The pixels to trace in `image`: the corners, the centre, an even 4 x 4 spread, and
/// the 8 pixels whose colour differs most from their right or lower neighbour (an
/// object's outline, a shadow's edge), earliest first where they tie.
fn pixels_to_trace(image: &image::RgbImage) -> Vec<(u32, u32)> {
    let (width, height) = image.dimensions();
    let (w, h) = (width - 1, height - 1);
    let mut pixels = vec![(0, 0), (0, w), (h, 0), (h, w), (h / 2, w / 2)];
    for r in 0..4 {
        for c in 0..4 {
            pixels.push(((2 * r + 1) * height / 8, (2 * c + 1) * width / 8));
        }
    }
    let difference = |a: &image::Rgb<u8>, b: &image::Rgb<u8>| -> u32 {
        a.0.iter()
            .zip(b.0)
            .map(|(&x, y)| u32::from(x.abs_diff(y)))
            .sum()
    };
    let mut edges: Vec<(u32, (u32, u32))> = Vec::new();
    for row in 0..height {
        for col in 0..width {
            let here = image.get_pixel(col, row);
            let right = (col < w).then(|| difference(here, image.get_pixel(col + 1, row)));
            let below = (row < h).then(|| difference(here, image.get_pixel(col, row + 1)));
            let most = right.unwrap_or(0).max(below.unwrap_or(0));
            if most > 0 {
                edges.push((most, (row, col)));
            }
        }
    }
    edges.sort_by_key(|&(most, pixel)| (std::cmp::Reverse(most), pixel));
    pixels.extend(edges.iter().take(8).map(|&(_, pixel)| pixel));
    pixels.sort_unstable();
    pixels.dedup();
    pixels
}

#[test]
fn the_traced_value_is_what_render_writes_for_the_pixel_in_every_scene() {
    // The renderer's own test traces thousands of pixels of every scene in every shading
    // against its image in memory; this one goes through the two commands: each scene
    // file rendered once with `viewray render --samples 1`, then about 25 of its pixels
    // traced (a grid, the corners and the sharpest edges), in the scene's own camera and
    // shading.
    let dir = tempfile::tempdir().unwrap();
    let mut traced = 0;
    for scene in fixture_scenes() {
        let image = render(&scene, dir.path());
        for (row, col) in pixels_to_trace(&image) {
            let pixel = format!("{row},{col}");
            let lines = json_trace(&scene, &pixel, &[]);
            let expected = image.get_pixel(col, row).0;
            let last = lines.last().unwrap();
            assert_eq!(
                last["srgb8"],
                serde_json::json!(expected),
                "{scene} pixel {pixel}: {last}"
            );
            assert_eq!(
                (last["row"].as_u64(), last["col"].as_u64()),
                (Some(row.into()), Some(col.into()))
            );
            // Every other line is a step, the viewing ray first.
            assert_eq!(lines[0]["step"], "viewing-ray", "{scene}");
            assert!(
                lines[..lines.len() - 1]
                    .iter()
                    .all(|l| l["step"].is_string())
            );
            traced += 1;
        }
        // The text ends with the same 8 bits.
        let text = run(&["trace", &scene, "--pixel", "0,0"]);
        let expected = image.get_pixel(0, 0).0;
        let last = text.lines().last().unwrap();
        assert!(
            last.ends_with(&format!(
                "({}, {}, {})",
                expected[0], expected[1], expected[2]
            )),
            "{scene}: {last}"
        );
    }
    assert!(traced > 600, "{traced} pixels traced");
}

#[test]
fn one_based_pixels_are_the_lectures_i_and_j() {
    let scene = "fixtures/homework/lit_4x4.ron";
    let zero = json_trace(scene, "3,1", &[]);
    let one = json_trace(scene, "4,2", &["--one-based"]);
    assert_eq!(zero.len(), one.len());
    let (first, last) = (&one[0], one.last().unwrap());
    assert_eq!(
        (first["i"].as_u64(), first["j"].as_u64()),
        (Some(4), Some(2))
    );
    assert_eq!((last["i"].as_u64(), last["j"].as_u64()), (Some(4), Some(2)));
    assert!(first.get("row").is_none() && last.get("col").is_none());
    assert_eq!(zero.last().unwrap()["srgb8"], last["srgb8"]);
    assert_eq!(zero[1..zero.len() - 1], one[1..one.len() - 1]);
}

#[test]
fn the_homework_scene_traced_as_text() {
    // A pixel on the glossy sphere, lit; a pixel of the mirroring ground in the sphere's
    // shadow, reflecting the sphere's underside.
    let sphere = run(&["trace", "fixtures/homework/lit_4x4.ron", "--pixel", "1,2"]);
    insta::assert_snapshot!("text_sphere", sphere);
    let ground = run(&[
        "trace",
        "fixtures/homework/lit_4x4.ron",
        "--pixel",
        "4,2",
        "--one-based",
    ]);
    insta::assert_snapshot!("text_ground", ground);
}

#[test]
fn the_homework_scene_traced_as_json() {
    let lines = run(&[
        "trace",
        "fixtures/homework/lit_4x4.ron",
        "--pixel",
        "3,1",
        "--json",
    ]);
    insta::assert_snapshot!("json_ground", lines);
}

#[test]
fn other_shadings_and_cameras_name_their_steps() {
    // Flat, Normals and Depth: the closest hit, then the mode's rule.
    for (scene, step) in [
        ("fixtures/scenes/shading_flat.ron", "flat"),
        ("fixtures/scenes/shading_normals.ron", "normals"),
        ("fixtures/scenes/shading_depth.ron", "depth"),
    ] {
        let lines = json_trace(scene, "60,60", &[]);
        let steps: Vec<&str> = lines.iter().filter_map(|l| l["step"].as_str()).collect();
        assert!(steps.contains(&"closest"), "{scene}: {steps:?}");
        assert_eq!(steps.last(), Some(&step), "{scene}: {steps:?}");
    }
    // The panoramic cameras give their angles instead of u, v; outside a fisheye's
    // circle there is no ray, and the pixel is the background.
    let lines = json_trace("fixtures/scenes/panoramic_equirectangular.ron", "0,0", &[]);
    for key in ["x", "y", "longitude", "latitude"] {
        assert!(lines[0][key].is_number(), "{key}: {}", lines[0]);
    }
    assert!(lines[0].get("u").is_none());
    let lines = json_trace("fixtures/scenes/panoramic_fisheye.ron", "0,0", &[]);
    assert!(lines[0]["r"].as_f64().unwrap() > 1.0);
    assert!(lines[0]["direction"].is_null());
    assert_eq!(lines[1]["step"], "background");
    let text = run(&[
        "trace",
        "fixtures/scenes/panoramic_fisheye.ron",
        "--pixel",
        "0,0",
    ]);
    assert!(text.contains("outside the image circle"), "{text}");
}

#[test]
fn pixels_outside_the_image_and_bad_options_are_one_line() {
    let scene = "fixtures/homework/lit_4x4.ron";
    let dir = repository();
    let cases: &[&[&str]] = &[
        &["trace", scene, "--pixel", "4,0"],
        &["trace", scene, "--pixel", "0,0", "--one-based"],
        &["trace", scene, "--pixel=-1,2"],
        &["trace", scene, "--pixel", "9223372036854775807,0"],
        &["trace", scene, "--pixel", "1,1", "2,2"],
        &["trace", scene, "--pixel", "a,b"],
        &["trace", scene, "--pixel", "1,2,3"],
        &["trace", scene, "--pixel", "1.5,2"],
        &["trace", scene, "--pixel"],
        &["trace", scene, "--pixel", "1", "1"],
        &["trace", scene],
        &["trace", "--pixel", "0,0"],
        &["trace", scene, "--pixel", "0,0", "--eye", "1,2,3"],
        &["trace", "no/such/scene.ron", "--pixel", "0,0"],
        &["trace", "fixtures/homework", "--pixel", "0,0"],
        &["trace", "fixtures/bad/empty.ron", "--pixel", "0,0"],
    ];
    let report: Vec<String> = cases
        .iter()
        .map(|args| {
            format!(
                "$ viewray {}\n{}",
                args.join(" "),
                error_line_in(&dir, args)
            )
        })
        .collect();
    insta::assert_snapshot!("bad_input", report.join("\n"));
}
