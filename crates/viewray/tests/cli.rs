//! The `viewray` command as a student uses it: homework numbers in, JSON lines out, one
//! clear error line for bad input.

use std::path::PathBuf;

use serde_json::Value;

mod support;
use support::{error_line, viewray};

/// Runs `viewray` expecting success; returns the JSON lines it printed.
#[track_caller]
fn json_lines(args: &[&str]) -> Vec<Value> {
    let out = viewray(args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "viewray {args:?} failed: {stderr}");
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str(line).expect("every line is JSON"))
        .collect()
}

#[track_caller]
fn assert_vec(value: &Value, expected: [f64; 3]) {
    let got: Vec<f64> = value
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    for (g, e) in got.iter().zip(expected) {
        assert!((g - e).abs() < 1e-12, "got {got:?}, expected {expected:?}");
    }
    assert_eq!(got.len(), 3);
}

fn fixture(name: &str) -> String {
    let path: PathBuf = [
        env!("CARGO_MANIFEST_DIR"),
        "..",
        "..",
        "fixtures",
        "homework",
        name,
    ]
    .iter()
    .collect();
    path.to_str().unwrap().to_owned()
}

#[test]
fn frame_from_homework_numbers() {
    // eye (1, 2, 3) looking at the origin: w = (1, 2, 3)/sqrt 14,
    // u = (3, 0, -1)/sqrt 10, v = (-2, 10, -6)/sqrt 140.
    let lines = json_lines(&[
        "frame",
        "--eye",
        "1,2,3",
        "--look-at",
        "0,0,0",
        "--up",
        "0,1,0",
    ]);
    assert_eq!(lines.len(), 1);
    let f = &lines[0];
    let (s14, s10, s140) = (14f64.sqrt(), 10f64.sqrt(), 140f64.sqrt());
    assert_vec(&f["e"], [1.0, 2.0, 3.0]);
    assert_vec(&f["u"], [3.0 / s10, 0.0, -1.0 / s10]);
    assert_vec(&f["v"], [-2.0 / s140, 10.0 / s140, -6.0 / s140]);
    assert_vec(&f["w"], [1.0 / s14, 2.0 / s14, 3.0 / s14]);
    // The same camera given by its view direction, with a negative eye coordinate.
    let lines = json_lines(&[
        "frame", "--eye", "-1,0,5", "--view", "0,0,-1", "--up", "0,1,0",
    ]);
    assert_vec(&lines[0]["e"], [-1.0, 0.0, 5.0]);
    assert_vec(&lines[0]["w"], [0.0, 0.0, 1.0]);
    // Keys come in the lecture's order.
    let out = viewray(&["frame", "--eye", "0,0,0", "--view", "0,0,-1"]);
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        "{\"e\":[0.0,0.0,0.0],\"u\":[1.0,0.0,0.0],\"v\":[0.0,1.0,0.0],\"w\":[0.0,0.0,1.0]}\n"
    );
}

#[test]
fn rays_of_the_canonical_camera() {
    // The canonical camera with a 2 x 2 image: u, v = +-1/4, direction (u, v, -1).
    let scene = fixture("canonical_2x2.ron");
    let lines = json_lines(&["rays", &scene]);
    assert_eq!(lines.len(), 4);
    let expected = [
        (0, 0, [-0.25, 0.25, -1.0]),
        (0, 1, [0.25, 0.25, -1.0]),
        (1, 0, [-0.25, -0.25, -1.0]),
        (1, 1, [0.25, -0.25, -1.0]),
    ];
    for (line, (row, col, direction)) in lines.iter().zip(expected) {
        assert_eq!(line["row"], row);
        assert_eq!(line["col"], col);
        assert_vec(&line["origin"], [0.0; 3]);
        assert_vec(&line["direction"], direction);
    }
    // The lecture's (i, j) = (2, 1) is row 1, col 0; several pixels after one --pixel.
    let lines = json_lines(&["rays", &scene, "--one-based", "--pixel", "2,1", "1,2"]);
    assert_eq!(
        (lines[0]["row"].as_i64(), lines[0]["col"].as_i64()),
        (Some(2), Some(1))
    );
    assert_vec(&lines[0]["direction"], [-0.25, -0.25, -1.0]);
    assert_vec(&lines[1]["direction"], [0.25, 0.25, -1.0]);
    // A sample at the pixel's top-left corner: u = 0/2 - 1/2 = -1/2, v = +1/2.
    let lines = json_lines(&["rays", &scene, "--pixel", "0,0", "--sample", "0,0"]);
    assert_vec(&lines[0]["direction"], [-0.5, 0.5, -1.0]);
}

#[test]
fn project_points_into_the_canonical_camera() {
    let scene = fixture("canonical_2x2.ron");
    let lines = json_lines(&[
        "project",
        &scene,
        "--point",
        "0,0,-5",
        "--point",
        "0.25,0.25,-1",
        "-1,0,1",
        "9,0,-1",
    ]);
    assert_eq!(lines.len(), 4);
    // Straight ahead: the image centre, the corner shared by four pixels.
    assert_eq!(lines[0]["x"], 1.0);
    assert_eq!(lines[0]["y"], 1.0);
    assert_eq!(
        (lines[0]["row"].as_i64(), lines[0]["col"].as_i64()),
        (Some(1), Some(1))
    );
    // The centre of pixel (0, 1).
    assert_eq!(
        (lines[1]["x"].as_f64(), lines[1]["y"].as_f64()),
        (Some(1.5), Some(0.5))
    );
    assert_eq!(
        (lines[1]["row"].as_i64(), lines[1]["col"].as_i64()),
        (Some(0), Some(1))
    );
    // Behind the eye: all null.
    for key in ["x", "y", "row", "col"] {
        assert!(lines[2][key].is_null(), "{key}: {}", lines[2]);
    }
    // Visible but outside the image: coordinates, no pixel.
    assert_eq!(lines[3]["x"], 19.0);
    assert!(lines[3]["row"].is_null() && lines[3]["col"].is_null());
    // One-based pixels.
    let lines = json_lines(&["project", &scene, "--one-based", "--point", "0.25,0.25,-1"]);
    assert_eq!(
        (lines[0]["row"].as_i64(), lines[0]["col"].as_i64()),
        (Some(1), Some(2))
    );
}

#[test]
fn bad_input_gets_one_clear_line() {
    let scene = fixture("canonical_2x2.ron");
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "frame", "--eye", "0,0,0", "--view", "0,1,0", "--up", "0,2,0",
            ],
            "up vector is parallel to the view direction",
        ),
        (
            &["frame", "--eye", "0,0,0", "--view", "0,0,0"],
            "view direction is zero",
        ),
        (
            &["frame", "--eye", "0,0", "--view", "0,0,-1"],
            "expected 3 numbers",
        ),
        (
            &["frame", "--eye", "1,2,nan", "--view", "0,0,-1"],
            "not a finite number",
        ),
        (&["frame", "--view", "0,0,-1"], "--eye"),
        (
            &["rays", &scene, "--pixel", "2,0"],
            "outside the 2 x 2 image",
        ),
        (
            &["rays", &scene, "--pixel", "0,0", "--one-based"],
            "outside the 2 x 2 image",
        ),
        (&["rays", &scene, "--pixel", "a,b"], "two whole numbers"),
        (
            &["rays", "no/such/scene.ron"],
            "no/such/scene.ron: no such scene file",
        ),
        (&["project", &scene], "--point"),
        (&["teleport"], "unrecognized subcommand"),
    ];
    for (args, expected) in cases {
        let line = error_line(args);
        assert!(line.contains(expected), "viewray {args:?}: {line}");
    }
}

#[test]
fn help_explains_the_conventions() {
    let out = viewray(&["--help"]);
    assert!(out.status.success());
    let help = String::from_utf8(out.stdout).unwrap();
    for phrase in [
        "u = ((j - 1/2)/W - 1/2) vw",
        "0-based",
        "--one-based",
        "Exit codes",
    ] {
        assert!(help.contains(phrase), "--help lacks {phrase:?}");
    }
    for command in ["frame", "rays", "project"] {
        let out = viewray(&[command, "--help"]);
        assert!(out.status.success());
        assert!(
            String::from_utf8(out.stdout)
                .unwrap()
                .contains("u = ((j - 1/2)/W - 1/2) vw")
        );
    }
}
