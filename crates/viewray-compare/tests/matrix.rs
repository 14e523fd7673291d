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
            let ok = verdict.passed() == case.passes && same_message(&got, want);
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

/// Whether two messages say the same, numbers allowed to differ by one unit of their last
/// printed digit (or 2% of a fixed point's coordinates).
fn same_message(got: &str, want: &str) -> bool {
    let split = |s: &str| -> Vec<String> {
        let mut parts = Vec::new();
        let mut current = String::new();
        let mut numeric = false;
        for ch in s.chars() {
            let is_num = ch.is_ascii_digit() || (ch == '.' && numeric);
            if is_num != numeric && !current.is_empty() {
                parts.push(std::mem::take(&mut current));
            }
            numeric = is_num;
            current.push(ch);
        }
        parts.push(current);
        parts
    };
    let (a, b) = (split(got), split(want));
    a.len() == b.len()
        && a.iter().zip(&b).all(|(x, y)| {
            if x == y {
                return true;
            }
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(u), Ok(v)) => {
                    let decimals = y.split('.').nth(1).map_or(0, str::len);
                    let unit = 10f64.powi(-(decimals as i32));
                    (u - v).abs() <= unit * 1.001 || (u - v).abs() <= 0.02 * v.abs()
                }
                _ => false,
            }
        })
}
