//! Instructor mode judged on renders whose right answer is known: a small analytic scene
//! rendered with several antialiasing patterns, with and without the classic camera
//! mistakes.

use crate::scene;

use image::RgbaImage;
use scene::{Mistake, Pattern, Scene};
use viewray_compare::{Comparison, Diagnosis, Failure, InstructorThresholds, judge};

const W: u32 = 128;
const H: u32 = 96;

/// The instructor's reference: 64 samples per pixel on a grid.
fn reference() -> RgbaImage {
    Scene::default().render(W, H, Mistake::NONE, Pattern::Grid(8))
}

fn judged(actual: &RgbaImage) -> Comparison {
    judge(&reference(), actual, &InstructorThresholds::default())
}

#[test]
fn correct_renders_pass_whatever_their_samples() {
    let patterns = [
        ("one sample at the centre", Pattern::Center),
        ("2 x 2 grid", Pattern::Grid(2)),
        ("4 x 4 jittered", Pattern::Jittered(4, 7)),
        ("16 random", Pattern::Random(16, 3)),
        ("one random sample", Pattern::Random(1, 5)),
    ];
    for (name, pattern) in patterns {
        let comparison = judged(&Scene::default().render(W, H, Mistake::NONE, pattern));
        assert!(
            comparison.passed(),
            "{name}: {} {:?}",
            comparison.reasons(),
            comparison.metrics
        );
        assert_eq!(comparison.diagnosis, None, "{name}");
    }
}

/// Checks that `mistake`, rendered with one sample and with 16 jittered ones, fails with
/// `message`, and that the estimated transform is close to the true one: moves within
/// 0.1 px (and 2% of a large move, where new content enters at the border), scales within
/// 0.5%.
#[track_caller]
fn check(mistake: Mistake, message: &str) {
    for pattern in [Pattern::Center, Pattern::Jittered(4, 11)] {
        let comparison = judged(&Scene::default().render(W, H, mistake, pattern));
        assert!(!comparison.passed(), "{mistake:?} {pattern:?} passed");
        assert!(comparison.failures.contains(&Failure::CameraMistake));
        let diagnosis = comparison
            .diagnosis
            .and_then(|d| d.camera_mistake().copied())
            .unwrap_or_else(|| panic!("{mistake:?} {pattern:?}: no camera mistake"));
        assert_eq!(diagnosis.to_string(), message, "{pattern:?} {diagnosis:?}");
        assert_eq!(diagnosis.mirrored_left_right, mistake.mirror_x);
        assert_eq!(diagnosis.upside_down, mistake.mirror_y);
        let close = |got: f64, want: f64, tolerance: f64| (got - want).abs() <= tolerance;
        assert!(
            close(
                diagnosis.shift.0,
                mistake.shift.0,
                0.1 + 0.02 * mistake.shift.0.abs()
            ) && close(
                diagnosis.shift.1,
                mistake.shift.1,
                0.1 + 0.02 * mistake.shift.1.abs()
            ) && close(diagnosis.scale.0, mistake.scale, 0.005)
                && close(diagnosis.scale.1, mistake.scale, 0.005),
            "{mistake:?} {pattern:?}: {diagnosis:?}"
        );
        assert!(diagnosis.explained > 0.8, "{diagnosis:?}");
    }
}

#[test]
fn a_missing_pixel_centre_offset_is_diagnosed() {
    check(
        Mistake {
            shift: (0.5, 0.5),
            ..Mistake::NONE
        },
        "shifted +0.5 px in x and y: check the pixel-centre offset (j - 1/2, i - 1/2)",
    );
}

#[test]
fn mirrors_are_diagnosed() {
    check(
        Mistake {
            mirror_x: true,
            ..Mistake::NONE
        },
        "mirrored left-right: check u = up x w",
    );
    check(
        Mistake {
            mirror_y: true,
            ..Mistake::NONE
        },
        "upside down: check v = w x u and the minus sign in v = -((i - 1/2)/H - 1/2) vh",
    );
    check(
        Mistake {
            mirror_x: true,
            mirror_y: true,
            ..Mistake::NONE
        },
        "rotated 180 degrees (mirrored left-right and upside down): check the sign of up",
    );
}

#[test]
fn a_wrong_field_of_view_is_diagnosed() {
    check(
        Mistake {
            scale: 1.1,
            ..Mistake::NONE
        },
        "scaled 1.10x: check vw, vh or d",
    );
}

#[test]
fn a_shift_with_the_wrong_sign_is_diagnosed() {
    check(
        Mistake {
            shift: (0.0, -12.0),
            ..Mistake::NONE
        },
        "shifted 12 px up: check the shift (sx, sy)",
    );
}

#[test]
fn a_missing_object_fails_with_no_camera_transform_named() {
    let missing = Scene {
        white_disc: false,
        ..Scene::default()
    }
    .render(W, H, Mistake::NONE, Pattern::Center);
    let comparison = judged(&missing);
    assert!(
        matches!(comparison.failures[..], [Failure::PeakFlip { .. }]),
        "{:?}",
        comparison.failures
    );
    assert_eq!(
        comparison.diagnosis,
        Some(Diagnosis::Unexplained { whole_view: false })
    );
}

#[test]
fn the_threshold_moves_the_verdict_of_a_one_pixel_change() {
    let moved = Scene {
        triangle_offset: (4.0 / f64::from(W), 0.0),
        ..Scene::default()
    }
    .render(W, H, Mistake::NONE, Pattern::Grid(4));
    assert!(!judged(&moved).passed());
    let loose = InstructorThresholds {
        max_peak_flip: 0.6,
        ..InstructorThresholds::default()
    };
    let comparison = judge(&reference(), &moved, &loose);
    assert!(comparison.passed(), "{}", comparison.reasons());
}

#[test]
fn different_sizes_and_blank_references_fail() {
    let small = Scene::default().render(W / 2, H / 2, Mistake::NONE, Pattern::Center);
    assert!(matches!(
        judged(&small).failures[..],
        [Failure::SizeMismatch { .. }]
    ));
    let blank = RgbaImage::from_pixel(W, H, image::Rgba([0, 0, 0, 255]));
    let comparison = judge(&blank, &blank, &InstructorThresholds::default());
    assert_eq!(comparison.failures, [Failure::UniformExpected]);
}

#[test]
fn tiny_and_odd_sized_images_are_judged_without_panicking() {
    for (w, h) in [(1, 1), (10, 10), (16, 16), (21, 17), (50, 31), (97, 33)] {
        let reference = Scene::default().render(w, h, Mistake::NONE, Pattern::Grid(4));
        let same = judge(&reference, &reference, &InstructorThresholds::default());
        assert_eq!(same.diagnosis, None, "{w}x{h}");
        let mirrored = Scene::default().render(
            w,
            h,
            Mistake {
                mirror_x: true,
                ..Mistake::NONE
            },
            Pattern::Grid(4),
        );
        let comparison = judge(&reference, &mirrored, &InstructorThresholds::default());
        assert_eq!(comparison.metrics.unwrap().pixel_count, u64::from(w * h));
    }
}
