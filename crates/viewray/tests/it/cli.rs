//! The `viewray` command as a student uses it: homework numbers in, JSON lines out, one
//! clear error line for bad input.

use std::path::PathBuf;

use serde_json::Value;

use crate::support;
use support::{command, repository, viewray, viewray_with_input};

/// Runs `viewray` expecting success; returns the JSON lines it printed.
#[track_caller]
fn json_lines(args: &[&str]) -> Vec<Value> {
    parse_lines(viewray(args), args)
}

/// Runs `viewray` with the scene text `scene` on standard input, expecting success;
/// returns the JSON lines it printed.
#[track_caller]
fn json_lines_from(scene: &str, args: &[&str]) -> Vec<Value> {
    parse_lines(
        viewray_with_input(&repository(), args, scene.as_bytes()),
        args,
    )
}

#[track_caller]
fn parse_lines(out: std::process::Output, args: &[&str]) -> Vec<Value> {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "viewray {args:?} failed: {stderr}");
    // Not a terminal: no notes on stderr.
    assert!(stderr.is_empty(), "viewray {args:?}: {stderr}");
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str(line).expect("every line is JSON"))
        .collect()
}

/// The keys of a JSON object, in order.
fn keys(value: &Value) -> Vec<&str> {
    value
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect()
}

#[track_caller]
fn assert_number(value: &Value, expected: f64) {
    let got = value
        .as_f64()
        .unwrap_or_else(|| panic!("{value} is not a number"));
    assert!(
        (got - expected).abs() < 1e-12,
        "got {got}, expected {expected}"
    );
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
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "..", "..", "fixtures", name]
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

/// A 3 x 2 image through a perspective camera with d = 2, a 3 x 1 viewport and a lens
/// shift of (0.5, 0.25), looking down -z from (1, 0, 0).
const SHIFTED_3X2: &str = "(
    image: (width: 3, height: 2),
    camera: (eye: (1.0, 0.0, 0.0), view: (0.0, 0.0, -1.0), up: (0.0, 1.0, 0.0),
             projection: Perspective(distance: 2.0, viewport: (3.0, 1.0), shift: (0.5, 0.25))),
)";

#[test]
fn frame_of_a_scene_camera_presets_included() {
    // An explicit camera: the frame of its eye, look-at and up (the homework numbers).
    let scene = "(camera: (eye: (1.0, 2.0, 3.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0),
                 projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))))";
    let by_scene = json_lines_from(scene, &["frame", "-"]);
    let by_hand = json_lines(&["frame", "--eye", "1,2,3", "--look-at", "0,0,0"]);
    assert_eq!(by_scene, by_hand);
    // TwoPoint: a level camera turned 30 degrees about the vertical, so
    // w = (sin 30, 0, cos 30), u = up x w = (cos 30, 0, -sin 30), v = (0, 1, 0).
    let lines = json_lines(&["frame", &fixture("scenes/perspective_two_point.ron")]);
    let (sin, cos) = 30f64.to_radians().sin_cos();
    assert_vec(&lines[0]["w"], [sin, 0.0, cos]);
    assert_vec(&lines[0]["u"], [cos, 0.0, -sin]);
    assert_vec(&lines[0]["v"], [0.0, 1.0, 0.0]);
    assert_eq!(keys(&lines[0]), ["e", "u", "v", "w"]);
}

#[test]
fn rays_print_the_image_plane_point_of_each_pixel() {
    // u = ((col + 1/2)/W - 1/2) vw, v = -((row + 1/2)/H - 1/2) vh; the direction adds
    // the shift: (u + sx, v + sy, -d).
    let lines = json_lines_from(SHIFTED_3X2, &["rays", "-"]);
    assert_eq!(lines.len(), 6, "every pixel, row by row");
    for (n, line) in lines.iter().enumerate() {
        let (row, col) = (n / 3, n % 3);
        assert_eq!(keys(line), ["row", "col", "u", "v", "origin", "direction"]);
        assert_eq!(
            (line["row"].as_u64(), line["col"].as_u64()),
            (Some(row as u64), Some(col as u64))
        );
        let u = ((col as f64 + 0.5) / 3.0 - 0.5) * 3.0;
        let v = -((row as f64 + 0.5) / 2.0 - 0.5) * 1.0;
        assert_number(&line["u"], u);
        assert_number(&line["v"], v);
        assert_vec(&line["origin"], [1.0, 0.0, 0.0]);
        assert_vec(&line["direction"], [u + 0.5, v + 0.25, -2.0]);
    }
    // Another point of the pixel: its top-left corner (ox, oy) = (0, 0).
    let lines = json_lines_from(
        SHIFTED_3X2,
        &["rays", "-", "--pixel", "1,2", "--sample", "0,0"],
    );
    assert_number(&lines[0]["u"], (2.0 / 3.0 - 0.5) * 3.0);
    assert_number(&lines[0]["v"], -(1.0 / 2.0 - 0.5));
    // Parallel cameras have an image plane too: the ray starts on it.
    let lines = json_lines(&[
        "rays",
        &fixture("scenes/orthographic.ron"),
        "--pixel",
        "0,0",
    ]);
    assert!(
        lines[0]["u"].is_f64() && lines[0]["v"].is_f64(),
        "{}",
        lines[0]
    );
    // Panoramic cameras have none: u and v are null, the ray is there.
    let lines = json_lines(&[
        "rays",
        &fixture("scenes/panoramic_equirectangular.ron"),
        "--pixel",
        "0,0",
    ]);
    assert!(
        lines[0]["u"].is_null() && lines[0]["v"].is_null(),
        "{}",
        lines[0]
    );
    assert!(lines[0]["direction"].is_array());
}

#[test]
fn a_tilted_lens_prints_its_plane_of_focus_hinge_line_and_lens_rays() {
    // A 90 mm lens tilted 3 degrees, focused at 5 m: its hinge line lies
    // 90 / sin 3 = 1719.66 mm below the lens centre, along u.
    let scene = fixture("homework/tilted_90mm.ron");
    let lines = json_lines(&["frame", &scene]);
    let frame = &lines[0];
    assert_eq!(
        keys(frame),
        ["e", "u", "v", "w", "focus_plane", "hinge_line"]
    );
    let j = 0.09 / 3f64.to_radians().sin();
    assert_vec(&frame["hinge_line"]["point"], [0.0, -j, 0.0]);
    assert_vec(&frame["hinge_line"]["direction"], [1.0, 0.0, 0.0]);
    // The plane of focus holds the hinge line and the Scheimpflug line, where the sensor
    // (s = 90 * 5000 / 4910 mm behind the lens) meets the lens plane: y = -s / tan 3.
    let value = |v: &Value| -> Vec<f64> {
        v.as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let (point, normal) = (
        value(&frame["focus_plane"]["point"]),
        value(&frame["focus_plane"]["normal"]),
    );
    let off = |p: [f64; 3]| (0..3).map(|k| normal[k] * (p[k] - point[k])).sum::<f64>();
    let s = 0.09 * 5.0 / 4.91;
    let (sin, cos) = 3f64.to_radians().sin_cos();
    assert!(off([0.0, -j, 0.0]).abs() < 1e-12);
    assert!(off([0.0, -s * cos / sin, s]).abs() < 1e-12);
    // The lens ray from (LX, LY) = (0, 1) starts at e + r v (r = 90 / 8 mm) and meets
    // the centre ray at t = 1, on the plane of focus.
    let centre = &json_lines(&["rays", &scene, "--pixel", "0,1"])[0];
    let lens = &json_lines(&["rays", &scene, "--pixel", "0,1", "--lens", "0,1"])[0];
    assert_eq!(keys(lens), keys(centre));
    assert_vec(&lens["origin"], [0.0, 0.01125, 0.0]);
    let meet: Vec<f64> = value(&centre["direction"]);
    let (o, d) = (value(&lens["origin"]), value(&lens["direction"]));
    for k in 0..3 {
        assert!(
            (o[k] + d[k] - meet[k]).abs() < 1e-12,
            "{o:?} + {d:?} != {meet:?}"
        );
    }
    assert!(off([meet[0], meet[1], meet[2]]).abs() < 1e-12);
    // An untilted lens: the plane at f along -w, no hinge line.
    let frame = &json_lines(&["frame", &fixture("scenes/thin_lens_small_aperture.ron")])[0];
    assert_eq!(keys(frame), ["e", "u", "v", "w", "focus_plane"]);
    // A pinhole: the frame alone.
    let frame = &json_lines(&["frame", &fixture("homework/canonical_2x2.ron")])[0];
    assert_eq!(keys(frame), ["e", "u", "v", "w"]);
}

#[test]
fn one_based_pixels_are_the_lectures_i_and_j() {
    let scene = fixture("homework/canonical_2x2.ron");
    // The lecture's pixel (i, j) = (2, 1) is row 1, col 0: u = -1/4, v = -1/4.
    let one = json_lines(&["rays", &scene, "--one-based", "--pixel", "2,1", "1,2"]);
    let zero = json_lines(&["rays", &scene, "--pixel", "1,0", "0,1"]);
    assert_eq!(keys(&one[0]), ["i", "j", "u", "v", "origin", "direction"]);
    assert_eq!(
        (one[0]["i"].as_u64(), one[0]["j"].as_u64()),
        (Some(2), Some(1))
    );
    assert_eq!(
        (one[1]["i"].as_u64(), one[1]["j"].as_u64()),
        (Some(1), Some(2))
    );
    assert_vec(&one[0]["direction"], [-0.25, -0.25, -1.0]);
    assert_vec(&one[1]["direction"], [0.25, 0.25, -1.0]);
    for (one, zero) in one.iter().zip(&zero) {
        for key in ["u", "v", "origin", "direction"] {
            assert_eq!(one[key], zero[key], "{key}");
        }
    }
    // Every pixel, 1-based: (1, 1) first, (2, 2) last.
    let all = json_lines(&["rays", &scene, "--one-based"]);
    assert_eq!(
        (all[0]["i"].as_u64(), all[0]["j"].as_u64()),
        (Some(1), Some(1))
    );
    assert_eq!(
        (all[3]["i"].as_u64(), all[3]["j"].as_u64()),
        (Some(2), Some(2))
    );

    // project: the pixel as i, j; x and y are the same continuous coordinates.
    let one = json_lines(&["project", &scene, "--one-based", "--point", "0.25,0.25,-1"]);
    let zero = json_lines(&["project", &scene, "--point", "0.25,0.25,-1"]);
    assert_eq!(keys(&one[0]), ["point", "x", "y", "i", "j"]);
    assert_eq!(keys(&zero[0]), ["point", "x", "y", "row", "col"]);
    // The centre of the lecture's pixel (1, 2): x = j - 1/2, y = i - 1/2.
    assert_eq!(
        (one[0]["x"].as_f64(), one[0]["y"].as_f64()),
        (Some(1.5), Some(0.5))
    );
    assert_eq!(
        (one[0]["i"].as_u64(), one[0]["j"].as_u64()),
        (Some(1), Some(2))
    );
    assert_eq!((&zero[0]["x"], &zero[0]["y"]), (&one[0]["x"], &one[0]["y"]));
    assert_eq!(
        (zero[0]["row"].as_u64(), zero[0]["col"].as_u64()),
        (Some(0), Some(1))
    );
}

#[test]
fn a_scene_on_standard_input_finds_meshes_from_the_current_folder() {
    let scene = "(camera: Front(target: (0.0, 0.0, 0.0), size: 3.0),
                 objects: [Mesh(path: \"meshes/cube.obj\")])";
    let from_stdin = viewray_with_input(
        &repository().join("fixtures"),
        &["rays", "-", "--pixel", "0,0"],
        scene.as_bytes(),
    );
    assert!(
        from_stdin.status.success(),
        "{}",
        String::from_utf8_lossy(&from_stdin.stderr)
    );
    // Elsewhere, the mesh is looked for in that folder, and the error says so.
    let elsewhere = viewray_with_input(&repository(), &["rays", "-"], scene.as_bytes());
    let stderr = String::from_utf8(elsewhere.stderr).unwrap();
    assert_eq!(elsewhere.status.code(), Some(2));
    assert!(
        stderr.starts_with(
            "error: <stdin>:2:28: mesh `meshes/cube.obj`: no such file (looked for meshes/cube.obj)"
        ),
        "{stderr}"
    );
}

/// `$ viewray ARGS` and what it printed on stderr, for the snapshot of every error.
fn transcript(args: &[&str], input: Option<&str>) -> String {
    let out = match input {
        Some(input) => viewray_with_input(&repository(), args, input.as_bytes()),
        None => command()
            .args(args)
            .current_dir(repository())
            .output()
            .unwrap(),
    };
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "viewray {args:?}: {stderr}");
    assert!(out.stdout.is_empty(), "viewray {args:?} printed on stdout");
    assert_eq!(
        stderr.lines().count(),
        1,
        "viewray {args:?}: not one line: {stderr}"
    );
    assert!(stderr.starts_with("error: "), "{stderr}");
    let shown = args.join(" ");
    let piped = input.map_or(String::new(), |i| format!("{i:?} | "));
    format!("$ {piped}viewray {shown}\n{stderr}")
}

#[test]
fn usage_and_input_errors_say_what_to_write() {
    let scene = "fixtures/homework/canonical_2x2.ron";
    let cases: &[&[&str]] = &[
        // Numbers separated by spaces instead of commas.
        &["frame", "--eye", "1", "2", "3", "--view", "0,0,-1"],
        &["rays", scene, "--pixel", "1", "1"],
        &["project", scene, "--point", "1,", "2,", "3"],
        // A value of the wrong shape.
        &["frame", "--eye", "0,0", "--view", "0,0,-1"],
        &["frame", "--eye", "1,2,nan", "--view", "0,0,-1"],
        &["rays", scene, "--pixel", "a,b"],
        &["rays", scene, "--sample", "1,0"],
        &["rays", scene, "--lens", "0.5"],
        // A lens point without a lens, or off the aperture (round, and with blades).
        &["rays", scene, "--lens", "0,0"],
        &[
            "rays",
            "fixtures/scenes/thin_lens_small_aperture.ron",
            "--lens",
            "0.8,0.8",
        ],
        &[
            "rays",
            "fixtures/scenes/thin_lens_blades.ron",
            "--lens",
            "1,0",
        ],
        // What is missing, and what conflicts.
        &["frame"],
        &["frame", "--eye", "1,2,3"],
        &["frame", "--view", "0,0,-1"],
        &["frame", scene, "--eye", "1,2,3"],
        &[
            "frame",
            "--eye",
            "0,0,0",
            "--view",
            "0,0,-1",
            "--look-at",
            "1,1,1",
        ],
        &["project", scene],
        &["rays"],
        &["scene"],
        // frame's options given to rays.
        &["rays", "--eye", "1,2,3"],
        &["rays", scene, "--look-at", "0,0,0"],
        // Cameras that cannot be built.
        &[
            "frame", "--eye", "0,0,0", "--view", "0,1,0", "--up", "0,2,0",
        ],
        &["frame", "--eye", "0,0,0", "--view", "0,0,0"],
        // Pixels outside the image, in both conventions; no overflow for any i64.
        &["rays", scene, "--pixel", "2,0"],
        &["rays", scene, "--pixel", "0,0", "--one-based"],
        &[
            "rays",
            scene,
            "--pixel=-9223372036854775808,0",
            "--one-based",
        ],
        &[
            "rays",
            scene,
            "--pixel=9223372036854775807,9223372036854775807",
        ],
        &["rays", scene, "--pixel", "9223372036854775808,0"],
        // Files.
        &["rays", "no/such/scene.ron"],
        &["rays", "fixtures/bad/image_float_width.ron"],
        &["frame", "fixtures/bad/image_negative_width.ron"],
        &["project", "fixtures/bad/empty.ron", "--point", "0,0,0"],
        // Output.
        &["render", "-o", "-", "--stats"],
        &["render", "-o", "picture.exr", "--format", "png"],
        &["render", "-o", "picture.jpg"],
        &["render", "--size", "640by480"],
        &["man", "teleport"],
        &["completions", "tcsh"],
        &["teleport"],
    ];
    let mut report: Vec<String> = cases.iter().map(|args| transcript(args, None)).collect();
    report.push(transcript(&["rays", "-"], Some("")));
    report.push(transcript(
        &["rays", "-"],
        Some("(image: (width: 8.0, height: 6), camera: Top(target: (0.0, 0.0, 0.0), size: 1.0))"),
    ));
    insta::assert_snapshot!(report.join("\n"));
}

#[test]
fn help_of_every_command_at_80_columns() {
    let mut commands = vec![vec!["--help"]];
    for name in [
        "render",
        "animate",
        "frame",
        "rays",
        "project",
        "trace",
        "compare",
        "grade",
        "autograde",
        "figure",
        "figures",
        "scene",
        "completions",
        "man",
    ] {
        commands.push(vec![name, "--help"]);
    }
    for args in commands {
        let out = viewray(&args);
        assert!(out.status.success(), "viewray {args:?}");
        let help = String::from_utf8(out.stdout).unwrap();
        for line in help.lines() {
            assert!(line.chars().count() <= 80, "viewray {args:?}: {line:?}");
        }
        let name = format!("help_{}", args[0].trim_start_matches('-'));
        insta::assert_snapshot!(name, help);
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
    for command in ["frame", "rays", "project", "trace"] {
        let out = viewray(&[command, "--help"]);
        assert!(out.status.success());
        assert!(
            String::from_utf8(out.stdout)
                .unwrap()
                .contains("u = ((j - 1/2)/W - 1/2) vw")
        );
    }
}

#[test]
fn the_version_names_the_commit_when_built_from_git() {
    let out = viewray(&["--version"]);
    assert!(out.status.success());
    let version = String::from_utf8(out.stdout).unwrap();
    let expected = format!("viewray {}", env!("CARGO_PKG_VERSION"));
    let commit = std::process::Command::new("git")
        .args(["rev-parse", "--short", "HEAD"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .ok()
        .filter(|out| out.status.success())
        .map(|out| String::from_utf8(out.stdout).unwrap().trim().to_owned());
    match commit {
        Some(commit) => assert_eq!(version, format!("{expected} ({commit})\n")),
        None => assert_eq!(version, format!("{expected}\n")),
    }
}

#[test]
fn completions_and_man_pages_come_from_the_command_line_definition() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let out = viewray(&["completions", shell]);
        assert!(out.status.success(), "{shell}");
        let script = String::from_utf8(out.stdout).unwrap();
        for word in ["--one-based", "--look-at", "completions", "trace"] {
            assert!(script.contains(word), "{shell} completions lack {word}");
        }
    }
    let out = viewray(&["man"]);
    let page = String::from_utf8(out.stdout).unwrap();
    assert!(page.contains(".TH viewray 1"), "{page}");
    assert!(
        page.contains("viewray\\-rays(1)"),
        "the commands' pages are named"
    );
    let out = viewray(&["man", "rays"]);
    let page = String::from_utf8(out.stdout).unwrap();
    assert!(page.contains(".TH viewray-rays 1"), "{page}");
    assert!(page.contains("\\-\\-one\\-based"), "{page}");
    let out = viewray(&["man", "trace"]);
    let page = String::from_utf8(out.stdout).unwrap();
    assert!(page.contains(".TH viewray-trace 1"), "{page}");
    assert!(page.contains("\\-\\-json"), "{page}");
}

#[test]
fn the_default_scene_is_printed_to_start_from() {
    let out = viewray(&["scene", "--default"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let file = std::fs::read_to_string(fixture("default.ron")).unwrap();
    assert_eq!(text, file);
    // It is a scene: rays read it from standard input.
    let lines = json_lines_from(&text, &["rays", "-", "--pixel", "0,0"]);
    assert_eq!(lines.len(), 1);
}

/// Every pixel of a 16384 x 16384 image (2^28 rays): the lines stream out as they are
/// computed, in little memory, and a reader that stops early (`| head`) ends the command
/// quietly with exit code 0.
#[cfg(target_os = "linux")]
#[test]
fn rays_of_every_pixel_stream_and_stop_quietly_when_the_reader_does() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("huge.ron");
    std::fs::write(
        &scene,
        "(image: (width: 16384, height: 16384),
          camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                   projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))))",
    )
    .unwrap();
    let mut child = command()
        .args(["rays", scene.to_str().unwrap()])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = BufReader::new(child.stdout.take().unwrap());
    let mut first = String::new();
    lines.read_line(&mut first).unwrap();
    let first: Value = serde_json::from_str(&first).unwrap();
    assert_eq!(
        (first["row"].as_u64(), first["col"].as_u64()),
        (Some(0), Some(0))
    );
    // The command is still printing, and has never held more than a few MiB: it does
    // not gather the 2^28 pixels (2 GiB as pairs of u32) before printing.
    let status = std::fs::read_to_string(format!("/proc/{}/status", child.id())).unwrap();
    let peak_kib: u64 = status
        .lines()
        .find_map(|line| line.strip_prefix("VmHWM:"))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|kib| kib.parse().ok())
        .expect("VmHWM in /proc/PID/status");
    assert!(peak_kib < 64 * 1024, "peak memory {peak_kib} KiB");
    // Stop reading, as `head` does.
    drop(lines);
    let out = child.wait_with_output().unwrap();
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(String::from_utf8_lossy(&out.stderr), "");
}

#[test]
fn colour_only_on_request_and_never_with_no_color() {
    let error_args = ["frame", "--eye", "0,0,0", "--view", "0,0,0"];
    // Piped: plain text (every other test checks that too).
    let plain = viewray(&error_args);
    assert!(
        String::from_utf8(plain.stderr)
            .unwrap()
            .starts_with("error: ")
    );
    // Forced, as a terminal would have it: `error:` in bold red.
    let forced = command()
        .args(error_args)
        .env("CLICOLOR_FORCE", "1")
        .output()
        .unwrap();
    let stderr = String::from_utf8(forced.stderr).unwrap();
    assert!(
        stderr.starts_with("\u{1b}[1m\u{1b}[31merror:\u{1b}[0m "),
        "{stderr:?}"
    );
    // NO_COLOR wins.
    let no_color = command()
        .args(error_args)
        .env("CLICOLOR_FORCE", "1")
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    assert!(
        String::from_utf8(no_color.stderr)
            .unwrap()
            .starts_with("error: ")
    );
}

/// Every `$ viewray frame|rays|project|trace ...` example in the user docs prints exactly
/// what the docs show under it (blank lines aside), so the docs cannot drift from the
/// program.
#[test]
fn the_documented_examples_print_what_the_docs_show() {
    for doc in ["docs/cameras.md", "README.md"] {
        let text = std::fs::read_to_string(repository().join(doc)).unwrap();
        let mut checked = 0;
        for block in text.split("```console\n").skip(1) {
            let block = block.split("```").next().unwrap();
            let mut lines = block.lines().peekable();
            while let Some(line) = lines.next() {
                let Some(command) = line.strip_prefix("$ viewray ") else {
                    continue;
                };
                let mut expected = String::new();
                while let Some(next) = lines.next_if(|l| !l.starts_with("$ ")) {
                    if !next.is_empty() {
                        expected += next;
                        expected += "\n";
                    }
                }
                let args: Vec<&str> = command.split_whitespace().collect();
                if !["frame", "rays", "project", "trace"].contains(&args[0]) {
                    continue;
                }
                let out = support::viewray_in(&repository(), &args);
                assert!(out.status.success(), "{doc}: viewray {command}");
                let stdout: String = String::from_utf8(out.stdout)
                    .unwrap()
                    .lines()
                    .filter(|line| !line.is_empty())
                    .map(|line| format!("{line}\n"))
                    .collect();
                assert_eq!(stdout, expected, "{doc}: viewray {command}");
                checked += 1;
            }
        }
        assert!(checked >= 3, "{doc}: only {checked} examples found");
    }
}

#[test]
fn compare_colours_its_verdicts_only_on_request() {
    let dir = tempfile::tempdir().unwrap();
    let image = dir.path().join("a.png");
    let image = image.to_str().unwrap();
    let out = viewray(&["render", "-o", image, "--size", "16x12", "--samples", "1"]);
    assert!(out.status.success());
    let plain = viewray(&["compare", image, image]);
    let table = String::from_utf8(plain.stdout).unwrap();
    assert!(table.contains("a.png  PASS "), "{table}");
    assert!(!table.contains('\u{1b}'), "{table:?}");
    let forced = command()
        .args(["compare", image, image])
        .env("CLICOLOR_FORCE", "1")
        .output()
        .unwrap();
    let table = String::from_utf8(forced.stdout).unwrap();
    // PASS in bold green, padded outside the colour so the columns still line up.
    assert!(
        table.contains("a.png  \u{1b}[1m\u{1b}[32mPASS\u{1b}[0m     "),
        "{table:?}"
    );
}
