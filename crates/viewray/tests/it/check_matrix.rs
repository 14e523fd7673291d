//! `viewray check`: the planted matrix of the catalogue's mistakes.
//!
//! Every answers file here is printed by the tests' own student ray tracer
//! (`support::student`), which makes each mistake from the lecture's formulas and knows
//! nothing of viewray's code, and every scene file is the one that tracer writes. The
//! command must find every right answer right, in every spelling, and explain every
//! planted mistake by its own catalogue entry (or by one that makes the same numbers for
//! that camera).

use crate::support;

use std::path::Path;

use serde_json::Value;
use support::student::{
    Aim, Answer, AnswerStyle, CameraSpec, Mistake, Number, Projection, Scene, Syntax, Vec3,
    write_answers,
};
use tempfile::TempDir;

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(x, y, z)
}

/// The cameras of the matrix: every family, d != 1, a non-square viewport, a shift, a
/// rolled and tilted frame with an up that is neither unit nor perpendicular.
fn cameras() -> Vec<(&'static str, CameraSpec)> {
    let spec = |eye, aim, up, projection| CameraSpec {
        eye,
        aim,
        up,
        projection,
    };
    vec![
        ("canonical", CameraSpec::canonical()),
        (
            "general",
            spec(
                v(1.0, 2.0, 3.0),
                Aim::LookAt(v(0.2, 0.5, -1.0)),
                v(0.1, 2.0, 0.3),
                Projection::Perspective {
                    d: 1.7,
                    viewport: (1.2, 0.8),
                    shift: (0.0, 0.0),
                },
            ),
        ),
        (
            "shifted",
            spec(
                v(0.5, 1.0, 6.0),
                Aim::View(v(0.0, 0.0, -1.0)),
                Vec3::Y,
                Projection::Perspective {
                    d: 2.0,
                    viewport: (3.0, 1.0),
                    shift: (0.3, -0.2),
                },
            ),
        ),
        (
            "orthographic",
            spec(
                v(2.0, 3.0, 6.0),
                Aim::LookAt(v(0.3, 0.5, 0.0)),
                v(0.0, 3.0, 0.0),
                Projection::Orthographic {
                    viewport: (5.0, 3.75),
                },
            ),
        ),
        (
            "oblique",
            spec(
                v(0.3, 0.8, 6.0),
                Aim::View(v(0.1, -0.1, -1.0)),
                Vec3::Y,
                Projection::Oblique {
                    viewport: (5.0, 3.75),
                    ratio: 0.5,
                    angle_degrees: 30.0,
                },
            ),
        ),
    ]
}

const SIZES: [(u32, u32); 3] = [(4, 3), (7, 5), (16, 9)];

/// A folder holding the scene file the student tracer writes for `camera` at `size`.
fn scene_file(camera: &CameraSpec, (w, h): (u32, u32)) -> TempDir {
    let dir = TempDir::new().unwrap();
    std::fs::write(
        dir.path().join("homework.ron"),
        Scene::example().to_ron(camera, w, h, 1),
    )
    .unwrap();
    dir
}

/// The student's answers with `mistakes`: the frame, and the rays of every pixel.
fn answers(camera: &CameraSpec, mistakes: &[Mistake], (w, h): (u32, u32)) -> Vec<Answer> {
    let mut answers = vec![Answer::frame(camera, mistakes)];
    for row in 0..h {
        for col in 0..w {
            answers.push(Answer::ray(camera, mistakes, (w, h), (row, col)));
        }
    }
    answers
}

/// What `viewray check homework.ron answers.txt --json [extra]` said: its exit code and
/// its last line's summary.
fn check(dir: &Path, text: &str, extra: &[&str]) -> (i32, Value) {
    std::fs::write(dir.join("answers.txt"), text).unwrap();
    let mut args = vec!["check", "homework.ron", "answers.txt", "--json"];
    args.extend_from_slice(extra);
    let out = support::viewray_in(dir, &args);
    let stdout = String::from_utf8(out.stdout).unwrap();
    let last = stdout
        .lines()
        .last()
        .unwrap_or_else(|| panic!("no output: {}", String::from_utf8_lossy(&out.stderr)));
    let summary: Value = serde_json::from_str(last).unwrap();
    (out.status.code().unwrap(), summary["summary"].clone())
}

/// The summary's diagnosis as `a + b` strings, one per alternative.
fn ids(summary: &Value) -> Vec<String> {
    summary["diagnosis"]
        .as_array()
        .map(|alternatives| {
            alternatives
                .iter()
                .map(|set| {
                    let ids: Vec<&str> = set
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|id| id.as_str().unwrap())
                        .collect();
                    ids.join(" + ")
                })
                .collect()
        })
        .unwrap_or_default()
}

#[test]
fn right_answers_pass_in_every_spelling() {
    let styles = [
        AnswerStyle::default(),
        AnswerStyle {
            syntax: Syntax::Words,
            normalized: true,
            crlf: true,
            comments: true,
            ..AnswerStyle::default()
        },
        AnswerStyle {
            syntax: Syntax::Csv,
            extra_spaces: true,
            number: Number::Fixed(9),
            ..AnswerStyle::default()
        },
        AnswerStyle {
            syntax: Syntax::Words,
            extra_spaces: true,
            number: Number::Exponent,
            ..AnswerStyle::default()
        },
        AnswerStyle {
            syntax: Syntax::Json,
            one_based: true,
            extra_spaces: true,
            ..AnswerStyle::default()
        },
    ];
    let mut cells = 0;
    for (name, spec) in cameras() {
        for size in SIZES {
            let dir = scene_file(&spec, size);
            let mut all = answers(&spec, &[], size);
            all.push(Answer::project(&spec, size, v(0.3, 0.4, -2.0)));
            all.push(Answer::project(&spec, size, v(0.0, 0.0, 50.0)));
            for style in styles {
                let text = write_answers(&all, &style);
                let one_based = style.one_based && style.syntax != Syntax::Json;
                let extra: &[&str] = if one_based { &["--one-based"] } else { &[] };
                let (code, summary) = check(dir.path(), &text, extra);
                assert_eq!(code, 0, "{name} {size:?} {style:?}: {summary}\n{text}");
                assert_eq!(summary["answers"], all.len());
                assert_eq!(summary["wrong"], 0);
                cells += 1;
            }
        }
    }
    assert_eq!(cells, 5 * 3 * 5);
}

#[test]
fn every_planted_mistake_is_explained_by_its_entry() {
    let mut explained = 0;
    let mut cells = 0;
    let mut failures = Vec::new();
    for (name, spec) in cameras() {
        for size in SIZES {
            let dir = scene_file(&spec, size);
            let right = answers(&spec, &[], size);
            for mistake in Mistake::ALL {
                if !mistake.applies_to(&spec.projection) {
                    continue;
                }
                let wrong = answers(&spec, &[mistake], size);
                let style = AnswerStyle {
                    syntax: Syntax::Words,
                    ..AnswerStyle::default()
                };
                let (code, summary) = check(dir.path(), &write_answers(&wrong, &style), &[]);
                if wrong == right {
                    // This camera does not show the mistake (a shift left out where
                    // there is none): the numbers are right.
                    assert_eq!(code, 0, "{name} {size:?} {}: {summary}", mistake.id());
                    continue;
                }
                cells += 1;
                assert_eq!(code, 1, "{name} {size:?} {}: {summary}", mistake.id());
                if ids(&summary)
                    .iter()
                    .any(|alternative| alternative == mistake.id())
                {
                    explained += 1;
                } else {
                    failures.push(format!("{name} {size:?} {}: {summary}", mistake.id()));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{explained} of {cells} explained:\n{}",
        failures.join("\n")
    );
    // Five cameras, three sizes, every entry that fits each family and shows in it.
    assert_eq!(cells, 222);
}

#[test]
fn two_mistakes_together_are_named_together() {
    let (_, spec) = &cameras()[2];
    let size = (7, 5);
    let dir = scene_file(spec, size);
    for pair in [
        [Mistake::PixelCorner, Mistake::VSign],
        [Mistake::ShiftSign, Mistake::DistanceMissing],
        [Mistake::USign, Mistake::EyeMissing],
    ] {
        let text = write_answers(&answers(spec, &pair, size), &AnswerStyle::default());
        let (code, summary) = check(dir.path(), &text, &[]);
        assert_eq!(code, 1);
        let found = ids(&summary);
        let both = |a: Mistake, b: Mistake| format!("{} + {}", a.id(), b.id());
        assert!(
            found.contains(&both(pair[0], pair[1])) || found.contains(&both(pair[1], pair[0])),
            "{pair:?}: {summary}"
        );
    }
}

#[test]
fn the_other_index_convention_is_named() {
    let (_, spec) = &cameras()[1];
    let size = (7, 5);
    let dir = scene_file(spec, size);
    let style = AnswerStyle {
        syntax: Syntax::Words,
        one_based: true,
        ..AnswerStyle::default()
    };
    // Pixels whose 1-based indices are inside the 0-based image too: 1-based rows
    // without --one-based are wrong answers that the other convention makes right.
    let inside: Vec<Answer> = (0..size.1 - 1)
        .flat_map(|row| (0..size.0 - 1).map(move |col| (row, col)))
        .map(|pixel| Answer::ray(spec, &[], size, pixel))
        .collect();
    let (code, summary) = check(dir.path(), &write_answers(&inside, &style), &[]);
    assert_eq!(
        (code, &summary["index_hint"]),
        (1, &Value::from("one-based"))
    );
    let text = support::viewray_in(dir.path(), &["check", "homework.ron", "answers.txt"]).stdout;
    let text = String::from_utf8(text).unwrap();
    assert!(
        text.ends_with(
            "your rows and columns look 1-based (the lecture's i, j): use --one-based\n"
        ),
        "{text}"
    );
    // And the last row, which a 0-based image does not have, is bad input that says so.
    let all = answers(spec, &[], size);
    std::fs::write(
        dir.path().join("answers.txt"),
        write_answers(&all[all.len() - 1..], &style),
    )
    .unwrap();
    let line = support::error_line_in(dir.path(), &["check", "homework.ron", "answers.txt"]);
    assert_eq!(
        line,
        "error: answers.txt: line 1: pixel 5,7 is outside the 7 x 5 image: expected row in \
         0..=4 and col in 0..=6 (your rows look 1-based: use --one-based)"
    );
}

#[test]
fn bad_answers_are_one_line_naming_the_line() {
    let dir = scene_file(&CameraSpec::canonical(), (4, 3));
    let check_error = |text: &str, expected: &str| {
        std::fs::write(dir.path().join("answers.txt"), text).unwrap();
        let line = support::error_line_in(dir.path(), &["check", "homework.ron", "answers.txt"]);
        assert_eq!(line, format!("error: answers.txt: {expected}"), "{text:?}");
    };
    check_error(
        "",
        "no answers: expected lines such as `ray 0 0 ox oy oz dx dy dz` or viewray's JSON lines",
    );
    check_error(
        "ray 0 0 0 0 0 0 0 -1\n{\"e\":[0,0,0],\"u\":[1,0,0],\"v\":[0,1,0],\"w\":[0,0,1]}\n",
        "line 2: a JSON line in a file of plain lines: expected one spelling throughout",
    );
    check_error(
        "# mine\nray 0 0 0 0 0 -0.375\n",
        "line 2: expected `ray ROW COL ox oy oz dx dy dz` (8 numbers after `ray`), found 6",
    );
    check_error(
        "ray 0 0 0 0 0 NaN 0.25 -1\n",
        "line 1: `dx` of `ray ROW COL ox oy oz dx dy dz` is `NaN`: expected a finite number",
    );
    check_error(
        "ray 0 0 0 0 0 -0.375 0.333 -1\nray 3 4 0 0 0 0 0 -1\n",
        "line 2: pixel 3,4 is outside the 4 x 3 image: expected row in 0..=2 and col in 0..=3 \
         (your rows look 1-based: use --one-based)",
    );
    let missing = support::error_line_in(dir.path(), &["check", "homework.ron", "nothing.txt"]);
    assert!(
        missing.starts_with("error: nothing.txt: cannot read the answers"),
        "{missing}"
    );
    let both = support::error_line_in(dir.path(), &["check", "-", "-"]);
    assert_eq!(
        both,
        "error: the scene and the answers cannot both come from standard input"
    );
}

/// Answers through a pipe are judged as they come, in constant memory: a hundred
/// thousand rays of a 400 x 250 image, all right.
#[test]
fn answers_stream_from_standard_input() {
    let spec = CameraSpec::canonical();
    let size = (400, 250);
    let dir = scene_file(&spec, size);
    let all = answers(&spec, &[], size);
    let text = write_answers(
        &all,
        &AnswerStyle {
            syntax: Syntax::Words,
            ..AnswerStyle::default()
        },
    );
    let out = support::viewray_with_input(
        dir.path(),
        &["check", "homework.ron", "-", "--json"],
        text.as_bytes(),
    );
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8(out.stdout).unwrap();
    let summary: Value = serde_json::from_str(stdout.lines().last().unwrap()).unwrap();
    assert_eq!(summary["summary"]["answers"], 100_001);
    assert_eq!(stdout.lines().count(), 100_002);
}
