//! The matrix of planted camera mistakes (see `planted/mod.rs`): every case rendered by
//! viewray, judged with and without the reference's scene, with the exact diagnosis each
//! must give.

mod planted;

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
    let thresholds = InstructorThresholds::default();
    let mut wrong = Vec::new();
    for case in &cases {
        let (reference, student) = case.render();
        for (with_scene, want) in [(false, &case.without_scene), (true, &case.with_scene)] {
            let expectations = with_scene.then(|| expectations(case));
            let verdict = judge_with(&reference, &student, &thresholds, expectations.as_ref());
            let got = verdict.diagnosis.map(|d| d.to_string()).unwrap_or_default();
            let ok = verdict.passed() == case.passes && planted::same_message(&got, want);
            println!(
                "{} {:<45} {:<5} {} | {got}",
                if ok { "ok  " } else { "FAIL" },
                case.name,
                if with_scene { "scene" } else { "" },
                verdict.verdict()
            );
            if !ok {
                wrong.push(format!(
                    "{} ({}): {} {got:?}, want {} {want:?} {:?}",
                    case.name,
                    if with_scene {
                        "with the scene"
                    } else {
                        "in pixels"
                    },
                    verdict.verdict(),
                    if case.passes { "PASS" } else { "FAIL" },
                    verdict.diagnosis
                ));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "{} of {} wrong:\n{}",
        wrong.len(),
        2 * cases.len(),
        wrong.join("\n")
    );
}
