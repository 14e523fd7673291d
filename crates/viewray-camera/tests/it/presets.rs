//! The taxonomy presets show the numbers their definitions promise.

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use viewray_camera::{Camera, Oblique, Orthographic, Perspective, Preset, Projection};

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

/// Checks a preset camera's frame and projection against the numbers its definition
/// gives, worked by hand for `target`, `size` and a 400 x 300 image.
#[track_caller]
fn check_preset(
    preset: Preset,
    eye: DVec3,
    (u, v, w): (DVec3, DVec3, DVec3),
    projection: Projection,
) {
    let got = camera(preset, DVec3::new(1.0, 2.0, 3.0), 2.0);
    let f = got.frame();
    let close = |a: DVec3, b: DVec3| a.abs_diff_eq(b, 1e-12);
    assert!(
        close(f.e(), eye) && close(f.u(), u) && close(f.v(), v) && close(f.w(), w),
        "{}: got {f:?}, expected e = {eye}, u = {u}, v = {v}, w = {w}",
        preset.name()
    );
    let same = match (got.projection(), &projection) {
        (Projection::Perspective(a), Projection::Perspective(b)) => {
            (a.distance - b.distance).abs() < 1e-12
                && a.viewport.abs_diff_eq(b.viewport, 1e-12)
                && a.shift.abs_diff_eq(b.shift, 1e-12)
        }
        (a, b) => a == b,
    };
    assert!(
        same,
        "{}: got {:?}, expected {projection:?}",
        preset.name(),
        got.projection()
    );
    assert_eq!((got.width(), got.height()), (W, H));
}

#[test]
fn each_preset_is_its_definition_worked_by_hand() {
    // Target (1, 2, 3), size 2, a 4:3 image: parallel viewports are 8/3 x 2 and their
    // eyes 10 sizes = 20 units from the target.
    let t = DVec3::new(1.0, 2.0, 3.0);
    let viewport = DVec2::new(8.0 / 3.0, 2.0);
    let ortho = Projection::Orthographic(Orthographic {
        viewport,
        lens: None,
    });
    let (x, y, z) = (DVec3::X, DVec3::Y, DVec3::Z);
    check_preset(Preset::Front, t + 20.0 * z, (x, y, z), ortho);
    // Top: w = +y, up = -z gives u = (-z) x y = x and v = y x x = -z.
    check_preset(Preset::Top, t + 20.0 * y, (x, -z, y), ortho);
    // Side: w = +x, u = y x x = -z, v = x x -z = y.
    check_preset(Preset::Side, t + 20.0 * x, (-z, y, x), ortho);
    // Isometric: w = (1, 1, 1)/sqrt 3, u = y x w normalized = (1, 0, -1)/sqrt 2,
    // v = w x u = (-1, 2, -1)/sqrt 6.
    let (s2, s3, s6) = (2f64.sqrt(), 3f64.sqrt(), 6f64.sqrt());
    check_preset(
        Preset::Isometric,
        t + 20.0 * DVec3::ONE / s3,
        (
            DVec3::new(1.0, 0.0, -1.0) / s2,
            DVec3::new(-1.0, 2.0, -1.0) / s6,
            DVec3::ONE / s3,
        ),
        ortho,
    );
    // Dimetric: w = (1, 1, sqrt 7)/3, u = (sqrt 7, 0, -1)/sqrt 8,
    // v = w x u = (-1, 8, -sqrt 7)/sqrt 72.
    let s7 = 7f64.sqrt();
    check_preset(
        Preset::Dimetric,
        t + 20.0 * DVec3::new(1.0, 1.0, s7) / 3.0,
        (
            DVec3::new(s7, 0.0, -1.0) / 8f64.sqrt(),
            DVec3::new(-1.0, 8.0, -s7) / 72f64.sqrt(),
            DVec3::new(1.0, 1.0, s7) / 3.0,
        ),
        ortho,
    );
    // Trimetric: w = (1, 2, 3)/sqrt 14 (the frame test's eye-at-(1, 2, 3) basis).
    check_preset(
        Preset::Trimetric,
        t + 20.0 * DVec3::new(1.0, 2.0, 3.0) / 14f64.sqrt(),
        (
            DVec3::new(3.0, 0.0, -1.0) / 10f64.sqrt(),
            DVec3::new(-2.0, 10.0, -6.0) / 140f64.sqrt(),
            DVec3::new(1.0, 2.0, 3.0) / 14f64.sqrt(),
        ),
        ortho,
    );

    // Oblique at phi = 30 degrees: the eye slides along the projectors, 20 units deep,
    // by L (cos phi, sin phi) per unit: e = t + 20 (L cos phi, L sin phi, 1).
    let phi = 30f64.to_radians();
    let (sin, cos) = phi.sin_cos();
    for (preset, ratio) in [
        (Preset::Cavalier { angle: phi }, 1.0),
        (Preset::Cabinet { angle: phi }, 0.5),
    ] {
        check_preset(
            preset,
            t + 20.0 * DVec3::new(ratio * cos, ratio * sin, 1.0),
            (x, y, z),
            Projection::Oblique(Oblique {
                viewport,
                ratio,
                angle: phi,
            }),
        );
    }

    // Perspective presets: d = 1, vh = 2 tan 25 degrees, vw = 4/3 vh, and the eye at
    // D = size / vh from the target's plane, so the view there is `size` tall.
    let vh = 2.0 * 25f64.to_radians().tan();
    let depth = 2.0 / vh;
    let perspective = |shift: DVec2| {
        Projection::Perspective(Perspective {
            distance: 1.0,
            viewport: DVec2::new(4.0 / 3.0 * vh, vh),
            shift,
        })
    };
    // One-point: the eye 0.35 size right of and 0.25 size above the target, looking
    // along -z; the target at camera (-0.7, -0.5, -D) is centred by the shift
    // d (-0.7, -0.5) / D = -(0.35, 0.25) vh.
    check_preset(
        Preset::OnePoint,
        t + DVec3::new(0.7, 0.5, depth),
        (x, y, z),
        perspective(-DVec2::new(0.35, 0.25) * vh),
    );
    // Two-point: level, turned 30 degrees about y: w = (sin 30, 0, cos 30); the eye D
    // along w and 0.25 size = 0.5 up; the shift d tan(theta) with tan(theta) = -0.5 / D.
    let w = DVec3::new(0.5, 0.0, s3 / 2.0);
    check_preset(
        Preset::TwoPoint,
        t + depth * w + 0.5 * y,
        (DVec3::new(s3 / 2.0, 0.0, -0.5), y, w),
        perspective(DVec2::new(0.0, -0.5 / depth)),
    );
    // Three-point: 30 degrees about y and 30 up: w = (cos 30 sin 30, sin 30, cos 30 cos 30)
    // = (sqrt 3 / 4, 1/2, 3/4), the eye D along it, looking at the target.
    let w = DVec3::new(s3 / 4.0, 0.5, 0.75);
    let u = DVec3::new(0.75, 0.0, -s3 / 4.0) / (0.75f64.hypot(s3 / 4.0));
    check_preset(
        Preset::ThreePoint,
        t + depth * w,
        (u, w.cross(u), w),
        perspective(DVec2::ZERO),
    );
}

#[test]
fn preset_names_taxonomy_and_errors() {
    let names = [
        "Front",
        "Top",
        "Side",
        "Isometric",
        "Dimetric",
        "Trimetric",
        "Cavalier",
        "Cabinet",
        "OnePoint",
        "TwoPoint",
        "ThreePoint",
    ];
    let multiview: &[&str] = &["parallel", "orthographic", "multiview"];
    let axonometric: &[&str] = &["parallel", "orthographic", "axonometric"];
    let oblique: &[&str] = &["parallel", "oblique"];
    let perspective: &[&str] = &["perspective"];
    let taxonomy = [
        multiview,
        multiview,
        multiview,
        axonometric,
        axonometric,
        axonometric,
        oblique,
        oblique,
        perspective,
        perspective,
        perspective,
    ];
    for ((preset, name), path) in Preset::ALL.into_iter().zip(names).zip(taxonomy) {
        assert_eq!(preset.name(), name);
        assert_eq!(preset.taxonomy(), path, "{name}");
    }

    use viewray_camera::CameraError::{Image, NotFinite, NotPositive};
    use viewray_camera::ImageLimitError::Empty;
    let target = DVec3::ZERO;
    for preset in Preset::ALL {
        // A zero side is an empty image, whichever side and whatever the family.
        for (width, height) in [(0, 300), (400, 0), (0, 0)] {
            assert_eq!(
                preset.camera(target, 1.0, width, height),
                Err(Image(Empty {
                    width: u64::from(width),
                    height: u64::from(height)
                })),
                "{}",
                preset.name()
            );
        }
        assert_eq!(
            preset.camera(target, 0.0, W, H),
            Err(NotPositive {
                name: "size",
                value: 0.0
            })
        );
        assert_eq!(
            preset.camera(DVec3::new(f64::NAN, 0.0, 0.0), 1.0, W, H),
            Err(NotFinite {
                name: "target",
                value: "(NaN, 0, 0)".into()
            })
        );
    }
    assert_eq!(
        Preset::Cabinet { angle: f64::NAN }.camera(target, 1.0, W, H),
        Err(NotFinite {
            name: "phi",
            value: "NaN".into()
        })
    );
}
