//! Instructor mode on real renders: viewray renders a fixture scene as the reference and
//! as students would, right and wrong, and `judge` must pass the right ones whatever their
//! sampling and fail the camera mistakes with the right diagnosis.

use std::path::Path;

use glam::DVec2;
use image::RgbaImage;
use viewray_camera::{Camera, Perspective, Projection};
use viewray_compare::{InstructorThresholds, judge};
use viewray_render::RenderSettings;
use viewray_scene::{LoadOptions, SceneLoader};

const W: u32 = 160;
const H: u32 = 120;

/// The fixture scene at `samples` per pixel, its perspective projection changed by `edit`.
fn render(samples: u32, edit: impl Fn(&mut Perspective)) -> RgbaImage {
    let path =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes/perspective_general.ron");
    let options = LoadOptions {
        size: Some((W, H)),
        samples: Some(samples),
    };
    let scene = SceneLoader::file(&path)
        .options(options)
        .load()
        .unwrap()
        .scene;
    let Projection::Perspective(mut perspective) = *scene.camera().projection() else {
        panic!("the fixture is a perspective camera");
    };
    edit(&mut perspective);
    let camera = Camera::new(
        *scene.camera().frame(),
        Projection::Perspective(perspective),
        W,
        H,
    )
    .unwrap();
    let scene = scene.with_camera(camera);
    let image = viewray_render::render(&scene, &RenderSettings::default(), |_, _| {})
        .unwrap()
        .image;
    image::DynamicImage::ImageRgb8(image.to_rgb_image()).to_rgba8()
}

fn correct(_: &mut Perspective) {}

#[track_caller]
fn check(reference: &RgbaImage, student: &RgbaImage, passes: bool, diagnosis: &str) {
    let verdict = judge(reference, student, &InstructorThresholds::default());
    let messages = verdict
        .diagnosis
        .as_ref()
        .map(|d| d.messages())
        .unwrap_or_default();
    assert_eq!(
        verdict.passed(),
        passes,
        "{}; {messages:?}",
        verdict.reasons()
    );
    if diagnosis.is_empty() {
        assert!(messages.is_empty(), "unexpected diagnosis {messages:?}");
    } else {
        assert!(
            messages.iter().any(|m| m.contains(diagnosis)),
            "expected a diagnosis containing {diagnosis:?}, got {messages:?}"
        );
    }
}

#[test]
fn correct_renders_pass_whatever_their_sampling() {
    let reference = render(16, correct);
    for samples in [1, 4, 9] {
        check(&reference, &render(samples, correct), true, "");
    }
}

#[test]
fn camera_mistakes_fail_with_their_diagnosis() {
    let reference = render(16, correct);
    // The wrong field of view: vw and vh 1.1 times too small show everything 1.1x larger.
    let narrow = render(4, |p| p.viewport /= 1.1);
    check(&reference, &narrow, false, "scaled 1.10x");
    // No half-pixel offset: u = (j/W - 1/2) vw and v = -(i/H - 1/2) vh with 1-based i, j
    // sample the image plane half a pixel right of and below each centre.
    let uncentred = render(1, |p| {
        p.shift += DVec2::new(
            0.5 * p.viewport.x / f64::from(W),
            -0.5 * p.viewport.y / f64::from(H),
        );
    });
    check(&reference, &uncentred, false, "pixel-centre offset");
    // u = w x up instead of up x w mirrors the picture.
    let mirrored = image::imageops::flip_horizontal(&render(4, correct));
    check(&reference, &mirrored, false, "mirrored left-right");
}

#[test]
fn a_shift_with_the_wrong_sign_fails() {
    let up = |p: &mut Perspective| p.shift = DVec2::new(0.0, 0.06);
    let reference = render(16, up);
    let down = render(4, |p| p.shift = DVec2::new(0.0, -0.06));
    // 0.12 of a 0.6-high viewport on 120 rows: the picture moves 24 rows.
    check(&reference, &down, false, "shift");
    check(&reference, &render(1, up), true, "");
}
