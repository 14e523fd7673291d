//! A student's numbers, checked: the planted matrix of the catalogue's mistakes.
//!
//! Every answers file here is printed by the tests' own student ray tracer
//! (`support::student`), which makes each mistake from the lecture's formulas and knows
//! nothing of viewray's code. The check must find every right answer right, in every
//! spelling, and explain every planted mistake by its own catalogue entry (or one that
//! makes the same numbers for that camera).

mod support;

use std::path::Path;

use support::student::{
    Aim, Answer, AnswerStyle, CameraSpec, Mistake, Number, Projection, Scene, Syntax, Vec3,
    write_answers,
};
use viewray_judge::{CheckOptions, Checker, IndexHint, Report, read_answers};

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

/// The scene's camera, loaded by viewray from the scene file the student tracer writes.
fn loaded_camera(camera: &CameraSpec, (w, h): (u32, u32)) -> viewray_camera::Camera {
    let ron = Scene::example().to_ron(camera, w, h, 1);
    *viewray_scene::SceneLoader::text(&ron, Path::new("homework.ron"))
        .load()
        .expect("the student's scene loads")
        .scene
        .camera()
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

fn check(camera: &viewray_camera::Camera, text: &str, options: CheckOptions) -> Report {
    let mut checker = Checker::new(camera, options);
    for item in read_answers(text.as_bytes()) {
        let (line, answer) = item.expect("the answers read");
        checker
            .check(line, &answer)
            .expect("every pixel is in the image");
    }
    checker.finish()
}

fn ids(report: &Report) -> Vec<String> {
    report
        .diagnosis
        .as_ref()
        .map(|d| d.alternatives.iter().map(ToString::to_string).collect())
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
            let camera = loaded_camera(&spec, size);
            let mut all = answers(&spec, &[], size);
            all.push(Answer::project(&spec, size, v(0.3, 0.4, -2.0)));
            all.push(Answer::project(&spec, size, v(0.0, 0.0, 50.0)));
            for style in styles {
                let text = write_answers(&all, &style);
                let one_based = style.one_based && style.syntax != Syntax::Json;
                let report = check(
                    &camera,
                    &text,
                    CheckOptions {
                        one_based,
                        ..CheckOptions::default()
                    },
                );
                assert!(
                    report.passed(),
                    "{name} {size:?} {style:?}: {report}\n{text}"
                );
                assert_eq!(report.answers, all.len() as u64);
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
            let camera = loaded_camera(&spec, size);
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
                let report = check(
                    &camera,
                    &write_answers(&wrong, &style),
                    CheckOptions::default(),
                );
                if wrong == right {
                    // This camera does not show the mistake (a shift left out where
                    // there is none): the numbers are right.
                    assert!(
                        report.passed(),
                        "{name} {size:?} {}: {report}",
                        mistake.id()
                    );
                    continue;
                }
                cells += 1;
                let found = ids(&report);
                if found.iter().any(|alternative| alternative == mistake.id()) {
                    explained += 1;
                } else {
                    failures.push(format!("{name} {size:?} {}: {report}", mistake.id()));
                }
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {cells} explained:\n{}",
        explained,
        failures.join("\n")
    );
    assert!(cells > 200, "{cells} cells");
}

#[test]
fn two_mistakes_together_are_named_together() {
    let (_, spec) = &cameras()[2];
    let size = (7, 5);
    let camera = loaded_camera(spec, size);
    for pair in [
        [Mistake::PixelCorner, Mistake::VSign],
        [Mistake::ShiftSign, Mistake::DistanceMissing],
        [Mistake::USign, Mistake::EyeMissing],
    ] {
        let text = write_answers(&answers(spec, &pair, size), &AnswerStyle::default());
        let report = check(&camera, &text, CheckOptions::default());
        let expected = format!("{} + {}", pair[0].id(), pair[1].id());
        let found = ids(&report);
        assert!(
            found.contains(&expected)
                || found
                    .iter()
                    .any(|f| f == &format!("{} + {}", pair[1].id(), pair[0].id())),
            "{expected}: {report}"
        );
    }
}

#[test]
fn the_other_index_convention_is_named() {
    let (_, spec) = &cameras()[1];
    let size = (7, 5);
    let camera = loaded_camera(spec, size);
    // 1-based rows, without --one-based: the last row is outside a 0-based image.
    let style = AnswerStyle {
        syntax: Syntax::Words,
        one_based: true,
        ..AnswerStyle::default()
    };
    let all = answers(spec, &[], size);
    // Pixels whose 1-based indices are inside the 0-based image too.
    let inside: Vec<Answer> = (0..size.1 - 1)
        .flat_map(|row| (0..size.0 - 1).map(move |col| (row, col)))
        .map(|pixel| Answer::ray(spec, &[], size, pixel))
        .collect();
    let text = write_answers(&inside, &style);
    let report = check(&camera, &text, CheckOptions::default());
    assert_eq!(report.index_hint, Some(IndexHint::OneBased), "{report}");
    assert!(report.to_string().contains("use --one-based"), "{report}");
    let mut checker = Checker::new(&camera, CheckOptions::default());
    let last = write_answers(&all[all.len() - 1..], &style);
    let (line, answer) = read_answers(last.as_bytes()).next().unwrap().unwrap();
    let error = checker.check(line, &answer).unwrap_err();
    assert_eq!(
        error.to_string(),
        "line 1: pixel 5,7 is outside the 7 x 5 image: expected row in 0..=4 and col in 0..=6 \
         (your rows look 1-based: use --one-based)"
    );
}
