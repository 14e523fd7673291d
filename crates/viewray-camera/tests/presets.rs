//! The taxonomy presets show the numbers their definitions promise.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use viewray_camera::{Camera, Preset, Projection};

const W: u32 = 400;
const H: u32 = 300;

/// How a world vector `a` at `target` appears: its image vector, in world units per
/// viewport unit (so a vector parallel to the image plane has length |a|), with image y
/// pointing up.
fn image_vector(camera: &Camera, target: DVec3, a: DVec3) -> DVec2 {
    let vh = camera.projection().viewport().unwrap().y;
    let scale = vh / f64::from(camera.height());
    let p0 = camera.project(target).unwrap();
    let p1 = camera.project(target + a).unwrap();
    let d = (p1 - p0) * scale;
    DVec2::new(d.x, -d.y)
}

/// The foreshortening of the x, y and z axes.
fn scales(camera: &Camera, target: DVec3) -> [f64; 3] {
    [DVec3::X, DVec3::Y, DVec3::Z].map(|a| image_vector(camera, target, a).length())
}

/// The angle below the horizontal, in degrees, at which an image vector points, to the
/// left or to the right.
fn angle_below_horizontal(v: DVec2) -> f64 {
    (-v.y).atan2(v.x.abs()).to_degrees()
}

#[track_caller]
fn close(got: f64, expected: f64, what: &str) {
    assert!(
        (got - expected).abs() < 1e-4,
        "{what}: got {got}, expected {expected}"
    );
}

fn camera(preset: Preset, target: DVec3, size: f64) -> Camera {
    preset.camera(target, size, W, H).unwrap()
}

fn target() -> impl Strategy<Value = DVec3> {
    (-50.0..50.0f64, -50.0..50.0f64, -50.0..50.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

proptest! {
    #[test]
    fn axonometric_foreshortening(target in target(), size in 0.1..100.0f64) {
        let iso = camera(Preset::Isometric, target, size);
        for s in scales(&iso, target) {
            close(s, (2.0f64 / 3.0).sqrt(), "isometric scale");
        }
        // The projected axes are 120 degrees apart.
        let [x, y, z] = [DVec3::X, DVec3::Y, DVec3::Z].map(|a| image_vector(&iso, target, a));
        for (a, b) in [(x, y), (y, z), (z, x)] {
            close(a.angle_to(b).abs().to_degrees(), 120.0, "isometric axis angle");
        }

        let dim = camera(Preset::Dimetric, target, size);
        let [sx, sy, sz] = scales(&dim, target);
        close(sx, (8.0f64 / 9.0).sqrt(), "dimetric x");
        close(sy, (8.0f64 / 9.0).sqrt(), "dimetric y");
        close(sz, (2.0f64 / 9.0).sqrt(), "dimetric z");
        close(angle_below_horizontal(image_vector(&dim, target, DVec3::X)), 7.1808, "dimetric x angle");
        close(angle_below_horizontal(image_vector(&dim, target, DVec3::Z)), 41.4096, "dimetric z angle");

        let tri = camera(Preset::Trimetric, target, size);
        let [sx, sy, sz] = scales(&tri, target);
        close(sx, (13.0f64 / 14.0).sqrt(), "trimetric x");
        close(sy, (10.0f64 / 14.0).sqrt(), "trimetric y");
        close(sz, (5.0f64 / 14.0).sqrt(), "trimetric z");
    }

    #[test]
    fn multiview_shows_two_axes_at_full_scale(target in target(), size in 0.1..100.0f64) {
        for (preset, hidden) in [(Preset::Front, 2), (Preset::Top, 1), (Preset::Side, 0)] {
            let s = scales(&camera(preset, target, size), target);
            for (axis, scale) in s.into_iter().enumerate() {
                close(scale, if axis == hidden { 0.0 } else { 1.0 }, preset.name());
            }
        }
        // The top view has -z up and +x right; the side view has -z right.
        let top = camera(Preset::Top, target, size);
        prop_assert!(image_vector(&top, target, DVec3::NEG_Z).abs_diff_eq(DVec2::Y, 1e-9));
        prop_assert!(image_vector(&top, target, DVec3::X).abs_diff_eq(DVec2::X, 1e-9));
        let side = camera(Preset::Side, target, size);
        prop_assert!(image_vector(&side, target, DVec3::NEG_Z).abs_diff_eq(DVec2::X, 1e-9));
    }

    #[test]
    fn oblique_depth_recedes_by_the_ratio(target in target(), size in 0.1..100.0f64, angle in 0.0..360.0f64) {
        for (preset, ratio) in [
            (Preset::Cavalier { angle: angle.to_radians() }, 1.0),
            (Preset::Cabinet { angle: angle.to_radians() }, 0.5),
        ] {
            let cam = camera(preset, target, size);
            // The face parallel to the image plane is true size and shape.
            prop_assert!(image_vector(&cam, target, DVec3::X).abs_diff_eq(DVec2::X, 1e-9));
            prop_assert!(image_vector(&cam, target, DVec3::Y).abs_diff_eq(DVec2::Y, 1e-9));
            // A unit of depth away from the viewer appears as L units along phi.
            let (sin, cos) = angle.to_radians().sin_cos();
            let depth = image_vector(&cam, target, DVec3::NEG_Z);
            prop_assert!(depth.abs_diff_eq(ratio * DVec2::new(cos, sin), 1e-9), "{depth}");
        }
    }

    #[test]
    fn every_preset_centres_its_target(target in target(), size in 0.1..100.0f64) {
        for preset in Preset::ALL {
            let cam = camera(preset, target, size);
            let centre = cam.project(target).unwrap();
            prop_assert!(centre.abs_diff_eq(DVec2::new(200.0, 150.0), 1e-6), "{}: {centre}", preset.name());
        }
    }
}

/// The image direction of the world line through `p` along `a`, normalized.
fn line_direction(camera: &Camera, p: DVec3, a: DVec3) -> DVec2 {
    let p0 = camera.project(p).unwrap();
    let p1 = camera.project(p + 0.01 * a).unwrap();
    (p1 - p0).normalize()
}

/// Whether parallel world lines along `a` stay parallel in the image, tested at points
/// spread around `target`.
fn stays_parallel(camera: &Camera, target: DVec3, a: DVec3) -> bool {
    let reference = line_direction(camera, target, a);
    [
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(-1.0, 0.5, -1.0),
        DVec3::new(0.8, -1.0, 0.3),
    ]
    .into_iter()
    .all(|offset| {
        let d = line_direction(camera, target + 0.3 * offset, a);
        d.perp_dot(reference).abs() < 1e-9
    })
}

#[test]
fn perspective_presets_have_one_two_and_three_vanishing_points() {
    let target = DVec3::new(0.0, 1.0, 0.0);
    let check = |preset: Preset, parallel: [bool; 3]| {
        let cam = camera(preset, target, 3.0);
        assert!(matches!(cam.projection(), Projection::Perspective(_)));
        let got = [DVec3::X, DVec3::Y, DVec3::Z].map(|a| stays_parallel(&cam, target, a));
        assert_eq!(got, parallel, "{}: which axes stay parallel", preset.name());
    };
    check(Preset::OnePoint, [true, true, false]);
    check(Preset::TwoPoint, [false, true, false]);
    check(Preset::ThreePoint, [false, false, false]);
    // The verticals of a two-point view are vertical in the image.
    let two = camera(Preset::TwoPoint, target, 3.0);
    assert!(line_direction(&two, target, DVec3::Y).abs_diff_eq(DVec2::NEG_Y, 1e-9));
}

#[test]
fn parallel_presets_keep_every_axis_parallel() {
    for preset in Preset::ALL {
        let cam = camera(preset, DVec3::ZERO, 2.0);
        let parallel = cam.projection().is_parallel();
        assert_eq!(
            parallel,
            preset.taxonomy()[0] == "parallel",
            "{}",
            preset.name()
        );
        if parallel {
            for a in [DVec3::X, DVec3::Y, DVec3::Z] {
                // Multiview hides one axis entirely; skip the zero-length one.
                if image_vector(&cam, DVec3::ZERO, a).length() > 1e-9 {
                    assert!(
                        stays_parallel(&cam, DVec3::ZERO, a),
                        "{} {a}",
                        preset.name()
                    );
                }
            }
        }
    }
}
