//! The assignment file: the contract's example read exactly, the extra fields, and every
//! broken file named with its place and what is wrong.

use std::path::{Path, PathBuf};

use viewray_autograde::{HandIn, Judge, Visibility, load_assignment};

const CANONICAL: &str = "(image: (width: 2, height: 2), camera: (eye: (0.0, 0.0, 0.0), \
     view: (0.0, 0.0, -1.0), up: (0.0, 1.0, 0.0), \
     projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))))";

fn folder() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("scenes")).unwrap();
    for name in ["canonical", "general"] {
        std::fs::write(dir.path().join(format!("scenes/{name}.ron")), CANONICAL).unwrap();
    }
    dir
}

fn write(dir: &Path, text: &str) -> PathBuf {
    let path = dir.join("hw3.ron");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn the_contracts_example_reads_as_written() {
    let dir = folder();
    let path = write(
        dir.path(),
        r#"(
  title: "Homework 3: general perspective cameras",
  judge: Camera,                                  // Camera | Image | Both
  run: Some((command: "julia raytracer.jl {scene} {output}", timeout_s: 30)),
  tests: [
    (name: "canonical", scene: "scenes/canonical.ron", image: "canonical.png", points: 2.0),
    (name: "general rays", scene: "scenes/general.ron", answers: "general.txt", points: 3.0,
     visibility: AfterDueDate),                   // Visible (default) | AfterDueDate | Hidden
  ],
)"#,
    );
    let assignment = load_assignment(&path).unwrap();
    assert_eq!(assignment.title, "Homework 3: general perspective cameras");
    assert_eq!(assignment.judge, Judge::Camera);
    let run = assignment.run.as_ref().unwrap();
    assert_eq!(run.command, "julia raytracer.jl {scene} {output}");
    assert_eq!(run.timeout_s, 30.0);
    let [canonical, general] = assignment.tests.as_slice() else {
        panic!("two tests")
    };
    assert_eq!(canonical.name, "canonical");
    assert_eq!(canonical.hand_in, HandIn::Image("canonical.png".to_owned()));
    assert_eq!(canonical.points, 2.0);
    assert_eq!(canonical.visibility, Visibility::Visible);
    assert_eq!(
        canonical.scene_file,
        dir.path().join("scenes/canonical.ron")
    );
    assert_eq!(canonical.scene.camera().width(), 2);
    assert_eq!(general.hand_in, HandIn::Answers("general.txt".to_owned()));
    assert_eq!(general.visibility, Visibility::AfterDueDate);
    assert_eq!(assignment.max_score(), 5.0);
    assert_eq!(
        assignment.inputs(),
        ["scenes/canonical.ron", "scenes/general.ron"]
    );
}

#[test]
fn partial_credit_references_and_answer_options_read() {
    let dir = folder();
    let reference = image::RgbaImage::from_pixel(2, 2, image::Rgba([1, 2, 3, 255]));
    reference.save(dir.path().join("canonical.png")).unwrap();
    let path = write(
        dir.path(),
        r#"(title: "Both", judge: Both, files: ["scenes"], tests: [
            (name: "a", scene: "scenes/canonical.ron", image: "a.png", points: 2.0,
             partial: Some(0.5), reference: Some("canonical.png"), visibility: Hidden),
            (name: "b", scene: "scenes/general.ron", answers: "b.txt", points: 1.0,
             one_based: true, tolerance: 1e-4),
        ])"#,
    );
    let assignment = load_assignment(&path).unwrap();
    let [a, b] = assignment.tests.as_slice() else {
        panic!("two tests")
    };
    assert_eq!(a.partial, Some(0.5));
    assert_eq!(a.visibility, Visibility::Hidden);
    assert_eq!(a.reference.as_ref().unwrap().1, reference);
    assert!(b.one_based);
    assert_eq!(b.tolerance, 1e-4);
    assert_eq!(
        assignment.inputs(),
        [
            "scenes/canonical.ron",
            "canonical.png",
            "scenes/general.ron",
            "scenes"
        ]
    );
}

#[track_caller]
fn error(text: &str) -> String {
    let dir = folder();
    let path = write(dir.path(), text);
    let message = load_assignment(&path).unwrap_err().to_string();
    message.replace(&dir.path().display().to_string(), "DIR")
}

#[test]
fn broken_files_say_where_and_what() {
    let test = |fields: &str| {
        format!(r#"(title: "T", tests: [(name: "a", scene: "scenes/canonical.ron", {fields})])"#)
    };
    assert_eq!(
        error("(title: \"T\", tests: [(name: \"a\", scene: 3)])"),
        "DIR/hw3.ron:1:40: Expected string"
    );
    assert_eq!(
        error("(title: \"T\", tests: [])"),
        "DIR/hw3.ron: has no tests: give `tests: [(name: ..., scene: ..., image: ..., points: ...)]`"
    );
    assert_eq!(
        error(&test(r#"image: "a.png", answers: "a.txt", points: 1.0"#)),
        "DIR/hw3.ron: test `a`: give `image` or `answers`, not both"
    );
    assert_eq!(
        error(&test("points: 1.0")),
        "DIR/hw3.ron: test `a`: give what the student hands in: `image: \"NAME.png\"` or `answers: \"NAME.txt\"`"
    );
    assert_eq!(
        error(&test(r#"image: "../a.png", points: 1.0"#)),
        "DIR/hw3.ron: test `a`: `image`: `../a.png` leaves its folder (`..`): paths stay inside it"
    );
    assert_eq!(
        error(&test(r#"image: "a.png", points: -1.0"#)),
        "DIR/hw3.ron: test `a`: points is -1: expected a number, 0 or more"
    );
    assert_eq!(
        error(&test(r#"image: "a.png", points: 1.0, partial: Some(0.5)"#)),
        "DIR/hw3.ron: test `a`: partial credit needs `judge: Both` or `judge: Image`: with `judge: \
         Camera` the appearance never costs points"
    );
    assert_eq!(
        error(r#"(title: "T", tests: [(name: "a", scene: "scenes/nowhere.ron", image: "a.png", points: 1.0)])"#)
            .split(" (")
            .next()
            .unwrap(),
        "DIR/hw3.ron: test `a`: its scene: DIR/scenes/nowhere.ron: no such scene file"
    );
    assert_eq!(
        error(
            r#"(title: "T", tests: [(name: "a", scene: "scenes/canonical.ron", image: "a.png", points: 1.0), (name: "a", scene: "scenes/canonical.ron", image: "b.png", points: 1.0)])"#
        ),
        "DIR/hw3.ron: two tests are named `a`: each name must be unique"
    );
    assert_eq!(
        error(
            r#"(title: "T", run: Some((command: "./a.out", timeout_s: 5)), tests: [(name: "a", scene: "scenes/canonical.ron", image: "a.png", points: 1.0)])"#
        ),
        "DIR/hw3.ron: `run`: the command must pass `{output}`, the picture's path, to the program \
         (only answers may come from its standard output)"
    );
    assert_eq!(
        error(
            r#"(title: "T", run: Some((command: "x {output}", timeout_s: 0)), tests: [(name: "a", scene: "scenes/canonical.ron", image: "a.png", points: 1.0)])"#
        ),
        "DIR/hw3.ron: `run`: timeout_s is 0: expected seconds above 0, at most 3600"
    );
    assert!(error(r#"(title: "T", colour: 1, tests: [])"#).contains("colour"));
}
