//! `viewray compare --scene`: the diagnoses in the lecture's terms, with the reference's
//! scene file (or a folder of them, matched to the images by file stem). The pairs are
//! planted mistakes from viewray-compare's test matrix, rendered here by viewray.

use std::path::Path;

use serde_json::Value;

use crate::support;
use support::{error_line, viewray};

use crate::planted;

use planted::{Base, Case, Mistake};

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// Renders `cases` into DIR/reference/NAME.png, DIR/student/NAME.png and writes the
/// reference scenes as DIR/scenes/NAME.ron.
fn write_cases(dir: &Path, cases: &[Case]) {
    for folder in ["reference", "student", "scenes"] {
        std::fs::create_dir_all(dir.join(folder)).unwrap();
    }
    for case in cases {
        let (reference, student) = case.render();
        reference
            .save(dir.join("reference").join(format!("{}.png", case.name)))
            .unwrap();
        student
            .save(dir.join("student").join(format!("{}.png", case.name)))
            .unwrap();
        std::fs::write(
            dir.join("scenes").join(format!("{}.ron", case.name)),
            case.reference_scene(),
        )
        .unwrap();
    }
}

/// The JSON lines of `viewray compare args --json`, by image name, and the exit code.
fn judged(args: &[&str]) -> (Vec<Value>, Option<i32>) {
    let mut args = args.to_vec();
    args.push("--json");
    let out = viewray(&args);
    let lines = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).expect("every line is JSON"))
        .collect();
    (lines, out.status.code())
}

fn diagnosis(line: &Value) -> String {
    line["diagnosis"]
        .as_array()
        .map_or_else(String::new, |messages| {
            messages
                .iter()
                .map(|m| m.as_str().unwrap().to_owned())
                .collect::<Vec<_>>()
                .join("; ")
        })
}

#[test]
fn a_folder_of_scenes_words_each_diagnosis_in_the_lectures_terms() {
    let size = (128, 96);
    let cases = [
        Case::new(Base::Boxes, size, 4, Mistake::ShiftFlipped),
        Case::new(Base::Boxes, size, 4, Mistake::ShiftMissing),
        Case::new(Base::Boxes, size, 4, Mistake::Distance(0.8)),
        Case::new(Base::Boxes, size, 1, Mistake::None),
        Case::new(Base::General, size, 4, Mistake::Roll(12.0)),
        Case::new(Base::General, size, 4, Mistake::MissingObject),
    ];
    let dir = tempfile::tempdir().unwrap();
    write_cases(dir.path(), &cases);
    let (reference, student, scenes) = (
        dir.path().join("reference"),
        dir.path().join("student"),
        dir.path().join("scenes"),
    );
    // The image judgement, worded with the scene (the camera judgement is the default
    // with a scene: judge_matrix.rs holds it to the catalogue).
    let (with_scene, code) = judged(&[
        "compare",
        s(&reference),
        s(&student),
        "--scene",
        s(&scenes),
        "--judge",
        "image",
    ]);
    assert_eq!(code, Some(1));
    let (in_pixels, _) = judged(&["compare", s(&reference), s(&student)]);
    for case in &cases {
        let name = format!("{}.png", case.name);
        for (lines, want) in [
            (&with_scene, &case.with_scene),
            (&in_pixels, &case.without_scene),
        ] {
            let line = lines.iter().find(|l| l["name"] == name).unwrap();
            let verdict = if case.passes { "pass" } else { "fail" };
            assert_eq!(line["verdict"], verdict, "{line}");
            let got = diagnosis(line);
            assert!(
                planted::same_message(&got, want),
                "{name}: {got:?}, want {want:?}"
            );
        }
    }
    // The pixel-space transform is there too: twice the shift, 2 * 0.2 * 96 / 0.9 px up.
    let flipped = with_scene
        .iter()
        .find(|l| l["name"] == format!("{}.png", cases[0].name))
        .unwrap();
    let shift_y = flipped["transform"]["shift"][1].as_f64().unwrap();
    assert!((shift_y + 2.0 * 0.2 * 96.0 / 0.9).abs() < 0.5, "{flipped}");
}

#[test]
fn one_scene_file_serves_a_pair_of_files() {
    let case = Case::new(Base::Boxes, (128, 96), 4, Mistake::ShiftMissing);
    let dir = tempfile::tempdir().unwrap();
    write_cases(dir.path(), std::slice::from_ref(&case));
    let file = |folder: &str, extension: &str| {
        dir.path()
            .join(folder)
            .join(format!("{}.{extension}", case.name))
    };
    let out = viewray(&[
        "compare",
        s(&file("reference", "png")),
        s(&file("student", "png")),
        "--scene",
        s(&file("scenes", "ron")),
        "--judge",
        "image",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains(
            "shifted 21 px up: the shift is missing (the scene's shift (sx, sy) is (0, 0.2))"
        ),
        "{stdout}"
    );
    // Judged by its camera (the default with a scene), the catalogue's entry is named
    // with the line to fix.
    let out = viewray(&[
        "compare",
        s(&file("reference", "png")),
        s(&file("student", "png")),
        "--scene",
        s(&file("scenes", "ron")),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert!(
        stdout.contains(
            "wrong     0.976      -              not shifted: shift-missing (the shift left out): \
             fix direction = (u + sx) U + (v + sy) V - d W"
        ),
        "{stdout}"
    );
}

#[test]
fn a_scene_that_is_missing_or_bad_is_bad_input() {
    let case = Case::new(Base::Boxes, (64, 48), 1, Mistake::None);
    let dir = tempfile::tempdir().unwrap();
    write_cases(dir.path(), std::slice::from_ref(&case));
    let (reference, student, scenes) = (
        dir.path().join("reference"),
        dir.path().join("student"),
        dir.path().join("scenes"),
    );
    let missing = dir.path().join("nowhere.ron");
    let line = error_line(&[
        "compare",
        s(&reference),
        s(&student),
        "--scene",
        s(&missing),
    ]);
    assert!(line.contains("does not exist"), "{line}");
    // A folder without the scene of a reference image.
    let empty = dir.path().join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let line = error_line(&["compare", s(&reference), s(&student), "--scene", s(&empty)]);
    assert!(
        line.contains("no scene for") && line.contains(&format!("{}.ron", case.name)),
        "{line}"
    );
    // A scene file that does not parse names its file, line and column.
    std::fs::write(
        scenes.join(format!("{}.ron", case.name)),
        "(\n    camera: (eye: (0.0, 0.0, 1.0), look_at: 7),\n)\n",
    )
    .unwrap();
    let line = error_line(&["compare", s(&reference), s(&student), "--scene", s(&scenes)]);
    assert!(line.contains(".ron:2:"), "{line}");
}

/// The scenes of docs/mistakes.md judge viewray's own renders of them right, by camera.
#[test]
fn the_mistakes_pages_scenes_judge_their_own_renders_right() {
    let dir = tempfile::tempdir().unwrap();
    for scene in [
        "fixtures/mistakes/perspective.ron",
        "fixtures/mistakes/oblique.ron",
    ] {
        let path = support::repository().join(scene);
        let png = dir.path().join("render.png");
        let out = viewray(&["render", s(&path), "-o", s(&png)]);
        assert!(out.status.success(), "{scene}");
        let out = viewray(&["compare", s(&png), s(&png), "--scene", s(&path), "--json"]);
        let stdout = String::from_utf8(out.stdout).unwrap();
        let line: Value = serde_json::from_str(stdout.lines().next().unwrap()).unwrap();
        assert_eq!(line["camera"], "right", "{scene}: {line}");
        assert_eq!(out.status.code(), Some(0), "{scene}: {stdout}");
    }
}
