//! The matrix of planted camera mistakes (see `planted/mod.rs`): every case rendered by
//! viewray, judged with and without the reference's scene, with the exact diagnosis each
//! must give.

use crate::planted;

use std::collections::HashMap;

use image::RgbaImage;
use viewray_compare::{CameraKind, Expectations, InstructorThresholds, judge_with};

use planted::{Base, Case};

/// The scene's facts as the `viewray` command passes them.
fn expectations(case: &Case) -> Expectations {
    let (w, h) = (f64::from(case.size.0), f64::from(case.size.1));
    let (px, py) = case.base.principal_point(case.size);
    Expectations {
        principal_point: (px / w, py / h),
        shift: case.base.shift(),
        camera: if case.base == Base::Orthographic {
            CameraKind::Parallel
        } else {
            CameraKind::Perspective
        },
    }
}

#[test]
fn every_planted_mistake_gets_its_diagnosis() {
    let cases = planted::cases();
    // The references, one per base scene and size.
    let mut references = HashMap::new();
    for case in &cases {
        references
            .entry((case.base, case.size))
            .or_insert_with(|| case.render_reference());
    }
    // Judging takes one core; two threads share the cases.
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get().min(4));
    let chunk = cases.len().div_ceil(threads);
    let wrong: Vec<String> = std::thread::scope(|scope| {
        let workers: Vec<_> = cases
            .chunks(chunk)
            .map(|chunk| {
                scope.spawn(|| {
                    chunk
                        .iter()
                        .flat_map(|case| check(case, &references[&(case.base, case.size)]))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        workers
            .into_iter()
            .flat_map(|worker| worker.join().expect("a worker panicked"))
            .collect()
    });
    assert!(
        wrong.is_empty(),
        "{} of {} judgements wrong:\n{}",
        wrong.len(),
        2 * cases.len(),
        wrong.join("\n")
    );
}

/// Judges one case with and without its scene; returns what came out wrong.
fn check(case: &Case, reference: &RgbaImage) -> Vec<String> {
    let student = case.render_student();
    let thresholds = InstructorThresholds::default();
    let mut wrong = Vec::new();
    for (with_scene, want) in [(false, &case.without_scene), (true, &case.with_scene)] {
        let expectations = with_scene.then(|| expectations(case));
        let verdict = judge_with(reference, &student, &thresholds, expectations.as_ref());
        let got = verdict.diagnosis.map(|d| d.to_string()).unwrap_or_default();
        if verdict.passed() != case.passes || !planted::same_message(&got, want) {
            wrong.push(format!(
                "{} ({}): {} {got:?}, want {} {want:?}",
                case.name,
                if with_scene {
                    "with the scene"
                } else {
                    "in pixels"
                },
                verdict.verdict(),
                if case.passes { "PASS" } else { "FAIL" },
            ));
        }
    }
    wrong
}
