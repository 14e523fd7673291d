//! A tilted thin lens: the plane of focus by the Scheimpflug and hinge rules, checked
//! against hand-worked values, and its rays, which meet on that plane.

use std::f64::consts::FRAC_PI_2;

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use viewray_camera::{
    Camera, CameraError, CameraSample, Frame, Iris, Perspective, Plane3, Projection, SensorFit,
    ThinLens,
};

/// A physical thin lens: `focal_length` mm on a 36 x 24 mm sensor, 36 x 24 pixels, at
/// f/4, focused at `focus` metres, tilted and swung by the angles in degrees.
fn lens(focal_length: f64, focus: f64, tilt: f64, swing: f64) -> ThinLens {
    let pinhole = Perspective::from_focal_length(
        focal_length,
        DVec2::new(36.0, 24.0),
        SensorFit::Horizontal,
        1.5,
    )
    .unwrap();
    ThinLens {
        tilt: tilt.to_radians(),
        swing: swing.to_radians(),
        ..ThinLens::new(pinhole, focal_length / 8000.0, focus)
    }
}

fn camera_with(frame: Frame, lens: ThinLens) -> Camera {
    Camera::new(frame, Projection::ThinLens(lens), 36, 24).unwrap()
}

fn camera(lens: ThinLens) -> Camera {
    camera_with(Frame::CANONICAL, lens)
}

#[track_caller]
fn close(actual: f64, expected: f64, tolerance: f64) {
    assert!(
        (actual - expected).abs() <= tolerance,
        "{actual} != {expected} (expected, within {tolerance})"
    );
}

#[track_caller]
fn near(actual: DVec3, expected: DVec3, tolerance: f64) {
    assert!(
        actual.abs_diff_eq(expected, tolerance),
        "{actual} != {expected} (expected, within {tolerance})"
    );
}

/// The signed distance of `p` from `plane`.
fn off(plane: &Plane3, p: DVec3) -> f64 {
    plane.normal.dot(p - plane.point)
}

#[test]
fn a_90mm_lens_tilted_3_degrees_hinges_1720mm_below_its_centre() {
    let camera = camera(lens(90.0, 5.0, 3.0, 0.0));
    let tilted = camera.tilted_focus().unwrap();
    // J = F / sin(tilt) = 90 mm / sin 3 deg = 1719.66 mm, straight down (-v), the line
    // running along u.
    let hinge = tilted.hinge_line;
    let j = 0.09 / 3f64.to_radians().sin();
    close(j, 1.71966, 1e-5);
    near(hinge.point, DVec3::new(0.0, -j, 0.0), 1e-12);
    near(hinge.direction, DVec3::X, 1e-15);
    // The sensor: 1/s + 1/f = 1/F, s = 90 * 5000 / 4910 mm = 91.6497 mm behind the lens.
    let s = 0.09 * 5.0 / (5.0 - 0.09);
    close(s, 0.091_649_69, 1e-8);
    near(tilted.sensor.point, DVec3::new(0.0, 0.0, s), 1e-15);
    near(tilted.sensor.normal, DVec3::Z, 0.0);
    // The lens plane contains u and (0, cos 3, -sin 3): its top leans toward the scene.
    let (sin, cos) = 3f64.to_radians().sin_cos();
    near(tilted.lens.normal, DVec3::new(0.0, -sin, -cos), 1e-15);
    near(tilted.lens.point, DVec3::ZERO, 0.0);
    near(
        tilted.front_focal.point,
        0.09 * DVec3::new(0.0, -sin, -cos),
        1e-15,
    );
    // The Scheimpflug line: the sensor plane z = s meets the lens plane z = -y tan 3 at
    // y = -s / tan 3 = -1748.8 mm.
    let scheimpflug = tilted.scheimpflug_line;
    near(scheimpflug.point, DVec3::new(0.0, -s * cos / sin, s), 1e-12);
    close(scheimpflug.point.y, -1.748_78, 1e-5);
    near(scheimpflug.direction, DVec3::X, 1e-15);
    // The plane of focus holds both lines: through (y, z) = (-J, 0) and (-s cot 3, s),
    // so it crosses the axis (y = 0) at z = F s / (F - s cos 3) = -5.4121 m.
    let focus = camera.focus_plane().unwrap();
    assert_eq!(focus, tilted.focus);
    for line in [hinge, scheimpflug] {
        for k in [-3.0, 0.0, 2.0] {
            close(off(&focus, line.point + k * line.direction), 0.0, 1e-12);
        }
    }
    let crossing = 0.09 * s / (0.09 - s * cos);
    close(crossing, -5.4121, 1e-4);
    close(off(&focus, DVec3::new(0.0, 0.0, crossing)), 0.0, 1e-12);
    // Its normal is a unit vector toward the lens, and its point the nearest to it.
    close(focus.normal.length(), 1.0, 1e-15);
    assert!(off(&focus, DVec3::ZERO) > 0.0);
    near(focus.point, -off(&focus, DVec3::ZERO) * focus.normal, 1e-12);
    // The direction of the line (y, z) from (-J, 0) to (-s cot 3, s) lies in the plane.
    let along = DVec3::new(0.0, -s * cos / sin + j, s);
    close(focus.normal.dot(along), 0.0, 1e-12);
}

#[test]
fn the_hinge_rule_puts_the_ground_in_focus() {
    // A camera 1.5 m above the ground, level: tilting a 90 mm lens by asin(F / h) puts
    // its hinge line on the ground, and focusing at f = F / (1 - cos(tilt)) turns the
    // plane of focus down onto the ground itself (Merklinger's landscape rule).
    let (h, focal_length): (f64, f64) = (1.5, 0.09);
    let tilt = (focal_length / h).asin();
    let focus = focal_length / (1.0 - tilt.cos());
    close(focus, 49.95, 0.01);
    let frame = Frame::from_eye_view_up(DVec3::new(2.0, h, 1.0), DVec3::NEG_Z, DVec3::Y).unwrap();
    let ground = camera_with(frame, lens(90.0, focus, tilt.to_degrees(), 0.0));
    let plane = ground.focus_plane().unwrap();
    near(plane.normal, DVec3::Y, 1e-9);
    near(plane.point, DVec3::new(2.0, 0.0, 1.0), 1e-9);
    let hinge = ground.tilted_focus().unwrap().hinge_line;
    near(hinge.point, DVec3::new(2.0, 0.0, 1.0), 1e-12);
    // Every pixel below the horizon is sharp on the ground: its rays meet there.
    for row in 13..24 {
        for col in [0, 17, 35] {
            let ray = |p_lens| {
                ground
                    .generate_ray(
                        row,
                        col,
                        CameraSample {
                            p_film: DVec2::splat(0.5),
                            p_lens,
                        },
                    )
                    .unwrap()
            };
            let meet = ray(DVec2::splat(0.5)).at(1.0);
            close(meet.y, 0.0, 1e-9 * meet.length());
            for p_lens in [DVec2::ZERO, DVec2::new(0.9, 0.1), DVec2::new(0.3, 0.99)] {
                near(ray(p_lens).at(1.0), meet, 1e-9 * meet.length());
            }
        }
    }
    // A swing does the same for a wall on the left: positive swing turns the lens's
    // right side toward the scene and puts the hinge line at x = -F / sin(swing).
    let wall = camera(lens(90.0, focus, 0.0, tilt.to_degrees()));
    let plane = wall.focus_plane().unwrap();
    near(plane.normal, DVec3::X, 1e-9);
    near(plane.point, DVec3::new(-h, 0.0, 0.0), 1e-9);
    let hinge = wall.tilted_focus().unwrap().hinge_line;
    near(hinge.point, DVec3::new(-h, 0.0, 0.0), 1e-12);
    near(hinge.direction, DVec3::NEG_Y, 1e-15);
}

#[test]
fn tilt_and_swing_turn_the_lens_axis_in_that_order() {
    // Tilt 30 about u, then swing 45 about v: n = (-cos 30 sin 45, -sin 30, -cos 30 cos 45).
    let lens = lens(50.0, 4.0, 30.0, 45.0);
    let (c30, s45) = (30f64.to_radians().cos(), 45f64.to_radians().sin());
    near(
        lens.lens_normal(),
        DVec3::new(-c30 * s45, -0.5, -c30 * s45),
        1e-15,
    );
    // The hinge line lies F / sin(theta) from the lens centre, cos(theta) = cos 30 cos 45.
    let camera = camera(lens);
    let hinge = camera.tilted_focus().unwrap().hinge_line;
    let theta = (c30 * s45).acos();
    close(hinge.point.length(), 0.05 / theta.sin(), 1e-12);
    close(hinge.point.z, 0.0, 0.0);
    // ... perpendicular to its direction, which is w x n.
    close(hinge.point.dot(hinge.direction), 0.0, 1e-15);
    let n = camera.tilted_focus().unwrap().lens.normal;
    near(hinge.direction, DVec3::Z.cross(n).normalize(), 1e-15);
    // s = F f / (f - F) = 50 * 4000 / 3950 mm.
    close(lens.sensor_distance(), 0.05 * 4.0 / 3.95, 1e-15);
}

#[test]
fn an_untilted_lens_keeps_the_lecture_s_focus_plane_and_rays() {
    let frame = Frame::from_eye_view_up(
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(-1.0, -0.5, -2.0),
        DVec3::Y,
    )
    .unwrap();
    let flat = lens(50.0, 4.0, 0.0, 0.0);
    assert!(!flat.is_tilted());
    near(flat.lens_normal(), DVec3::NEG_Z, 0.0);
    let camera = camera_with(frame, flat);
    // e - f w, normal w: exactly.
    assert_eq!(
        camera.focus_plane(),
        Some(Plane3 {
            point: frame.e() - 4.0 * frame.w(),
            normal: frame.w(),
        })
    );
    assert_eq!(camera.tilted_focus(), None);
    // A tilt of a billionth of a degree moves the rays by little more (the plane of
    // focus leans by the tilt times f / F = 80).
    let barely = camera_with(
        frame,
        ThinLens {
            tilt: 1e-9f64.to_radians(),
            ..flat
        },
    );
    assert!(barely.tilted_focus().is_some());
    let sample = CameraSample {
        p_film: DVec2::new(0.2, 0.7),
        p_lens: DVec2::new(0.9, 0.3),
    };
    for (row, col) in [(0, 0), (12, 18), (23, 35)] {
        let a = camera.generate_ray(row, col, sample).unwrap();
        let b = barely.generate_ray(row, col, sample).unwrap();
        assert_eq!(a.origin, b.origin);
        near(b.direction, a.direction, 1e-8 * a.direction.length());
    }
    // Other cameras have no focus plane; an orthographic lens has one at f.
    assert_eq!(Camera::canonical(2, 2).unwrap().focus_plane(), None);
    assert_eq!(Camera::canonical(2, 2).unwrap().tilted_focus(), None);
    let ortho = Camera::new(
        frame,
        Projection::Orthographic(viewray_camera::Orthographic {
            viewport: DVec2::ONE,
            lens: Some(viewray_camera::Lens {
                aperture: 0.1,
                focus: 2.5,
            }),
        }),
        2,
        2,
    )
    .unwrap();
    assert_eq!(
        ortho.focus_plane(),
        Some(Plane3 {
            point: frame.e() - 2.5 * frame.w(),
            normal: frame.w(),
        })
    );
    assert_eq!(ortho.tilted_focus(), None);
}

#[test]
fn rays_through_a_chosen_lens_point_start_there() {
    let frame = Frame::from_eye_view_up(DVec3::new(0.0, 1.0, 5.0), DVec3::NEG_Z, DVec3::Y).unwrap();
    let tilted = lens(90.0, 5.0, 3.0, 0.0);
    let camera = camera_with(frame, tilted);
    let r = tilted.aperture;
    let image = DVec2::new(10.5, 20.5);
    let ray = camera
        .generate_ray_at_lens(image, DVec2::new(0.6, -0.8))
        .unwrap();
    near(
        ray.origin,
        frame.e() + r * DVec3::new(0.6, -0.8, 0.0),
        1e-15,
    );
    // Its t = 1 is where the centre ray meets the plane of focus.
    let centre = camera.generate_ray_at_lens(image, DVec2::ZERO).unwrap();
    assert_eq!(centre.origin, frame.e());
    near(ray.at(1.0), centre.at(1.0), 1e-12);
    let plane = camera.focus_plane().unwrap();
    close(off(&plane, centre.at(1.0)), 0.0, 1e-12);
    // The centre ray is the pinhole ray: project sends its points back to the pixel.
    let seen = camera.project(centre.at(0.5)).unwrap();
    assert!(seen.abs_diff_eq(image, 1e-9), "{seen}");
    // The lens sample's mapping is not applied: (0.5, 0.5) is a lens point here, not
    // the square's centre.
    let off_centre = camera
        .generate_ray_at_lens(image, DVec2::splat(0.5))
        .unwrap();
    near(
        off_centre.origin,
        frame.e() + r * DVec3::new(0.5, 0.5, 0.0),
        1e-15,
    );
    // A camera without a lens ignores the lens point.
    let pinhole = Camera::canonical(4, 4).unwrap();
    assert_eq!(
        pinhole.generate_ray_at_lens(DVec2::splat(1.5), DVec2::new(0.5, 0.5)),
        pinhole.generate_ray_through(DVec2::splat(1.5), DVec2::splat(0.5))
    );
}

#[test]
fn rays_whose_sharp_point_is_not_ahead_spread_from_it() {
    // Tilted 40 degrees, focused at 1 m: the plane of focus leans so far that the top of
    // the image looks over it; the rays of those pixels leave the lens spreading from a
    // point behind the eye (or parallel, at its horizon), never crossing the centre ray.
    let tilted = lens(50.0, 1.0, 40.0, 0.0);
    let camera = camera(tilted);
    let plane = camera.focus_plane().unwrap();
    let top = DVec2::new(18.5, 0.5);
    let centre = camera.generate_ray_at_lens(top, DVec2::ZERO).unwrap();
    // The centre ray meets the plane behind the eye: t < 0.
    let t = -off(&plane, DVec3::ZERO) / plane.normal.dot(centre.direction);
    assert!(t < 0.0, "{t}");
    let meeting = centre.at(t);
    for lens in [DVec2::new(0.0, 1.0), DVec2::new(-0.7, 0.2)] {
        let ray = camera.generate_ray_at_lens(top, lens).unwrap();
        // The line through the ray passes through the virtual meeting point ...
        let back = meeting - ray.origin;
        close(
            back.normalize().cross(ray.direction.normalize()).length(),
            0.0,
            1e-9,
        );
        // ... which lies behind the ray's start: the ray leads away from it.
        assert!(back.dot(ray.direction) < 0.0);
        // Written as the pinhole direction plus the spread.
        close(ray.direction.z, centre.direction.z, 1e-15);
    }
    // Near the horizon (the centre ray almost parallel to the plane) the rays almost run
    // parallel.
    let horizon = lens(50.0, 1.0, 40.0, 0.0);
    let m = DVec3::new(
        0.0,
        -(40f64.to_radians().sin()),
        1.0 - 40f64.to_radians().cos() - 0.05,
    );
    // c = (u, v, -d) with m . c = 0 and u = 0: v = -d m_z / m_y.
    let v = 0.05 * m.z / m.y;
    let vh = horizon.viewport.y;
    let y = (0.5 - v / vh) * 24.0;
    let image = DVec2::new(18.0, y);
    let camera = self::camera(horizon);
    let centre = camera.generate_ray_at_lens(image, DVec2::ZERO).unwrap();
    // Within rounding of the horizon the meeting point is very far (the direction very
    // long, on either side of it) and the rays nearly parallel.
    close(m.dot(centre.direction.normalize()), 0.0, 1e-12);
    let side = camera
        .generate_ray_at_lens(image, DVec2::new(1.0, 0.0))
        .unwrap();
    assert!(side.direction.is_finite());
    near(
        side.direction.normalize(),
        centre.direction.normalize(),
        1e-12,
    );
}

#[test]
fn exactly_at_the_horizon_the_rays_run_parallel_to_the_centre_ray() {
    // Tilted 60 degrees with d = F = 1 - cos 60 and f = 1, the plane of focus is
    // m . P = F with m = n + (1 - F/f) w = (0, -sin 60, 0): level, F / sin 60 below the
    // lens. The middle row's centre ray (v = 0) runs along it, m . c = 0 exactly: its
    // sharp point is at infinity and every lens ray is parallel to it.
    let (sin, cos) = 60f64.to_radians().sin_cos();
    let lens = ThinLens {
        tilt: 60f64.to_radians(),
        ..ThinLens::new(
            Perspective {
                distance: 1.0 - cos,
                viewport: DVec2::new(0.4, 0.3),
                shift: DVec2::ZERO,
            },
            0.1,
            1.0,
        )
    };
    let camera = Camera::new(Frame::CANONICAL, Projection::ThinLens(lens), 4, 3).unwrap();
    let plane = camera.focus_plane().unwrap();
    near(plane.normal, DVec3::Y, 1e-15);
    close(plane.point.y, -(1.0 - cos) / sin, 1e-15);
    let image = DVec2::new(2.5, 1.5);
    let centre = camera.generate_ray_at_lens(image, DVec2::ZERO).unwrap();
    assert_eq!(centre.direction.y, 0.0);
    for lens_point in [DVec2::new(1.0, 0.0), DVec2::new(-0.3, 0.8)] {
        let ray = camera.generate_ray_at_lens(image, lens_point).unwrap();
        assert!(ray.direction.is_finite(), "{}", ray.direction);
        assert_eq!(ray.direction, centre.direction);
        near(ray.origin, 0.1 * lens_point.extend(0.0), 1e-15);
    }
}

#[test]
fn an_untilted_lens_is_the_lecture_s_formula_bit_for_bit() {
    // d = 0.05, f = 3: direction (f / d) (u U + v V - d W) - r (lx U + ly V), in this
    // order of operations, through the canonical frame (which changes no bit).
    let pinhole = Perspective {
        distance: 0.05,
        viewport: DVec2::new(0.036, 0.024),
        shift: DVec2::ZERO,
    };
    let camera = Camera::new(
        Frame::CANONICAL,
        Projection::ThinLens(ThinLens::new(pinhole, 0.01, 3.0)),
        36,
        24,
    )
    .unwrap();
    for (row, col, p_lens) in [(5, 7, DVec2::new(0.9, 0.3)), (20, 33, DVec2::new(0.2, 0.6))] {
        let sample = CameraSample {
            p_film: DVec2::splat(0.5),
            p_lens,
        };
        let uv = viewray_camera::pixel_to_image_plane(
            row,
            col,
            sample.p_film,
            (36, 24),
            pinhole.viewport,
        );
        let lens = (0.01 * viewray_camera::sample_unit_disk_concentric(p_lens)).extend(0.0);
        let expected = (3.0 / 0.05) * uv.extend(-0.05) - lens;
        let ray = camera.generate_ray(row, col, sample).unwrap();
        assert_eq!(ray.direction.to_array(), expected.to_array());
        assert_eq!(ray.origin.to_array(), lens.to_array());
    }
}

#[test]
fn bad_tilts_are_refused_with_their_names() {
    let build = |lens: ThinLens| Camera::new(Frame::CANONICAL, Projection::ThinLens(lens), 4, 3);
    for (tilt, swing, name) in [
        (90.0, 0.0, "lens_tilt"),
        (-90.0, 0.0, "lens_tilt"),
        (120.0, 0.0, "lens_tilt"),
        (0.0, 90.0, "lens_swing"),
        (0.0, -95.0, "lens_swing"),
    ] {
        let error = build(lens(50.0, 4.0, tilt, swing)).unwrap_err();
        assert!(
            matches!(error, CameraError::OutOfRange { name: n, .. } if n == name),
            "{error}"
        );
    }
    assert_eq!(
        build(lens(50.0, 4.0, 90.0, 0.0)).unwrap_err().to_string(),
        "lens_tilt must be strictly between -90 and 90 degrees, found 90"
    );
    assert!(build(lens(50.0, 4.0, 89.9, -89.9)).is_ok());
    let nan = ThinLens {
        tilt: f64::NAN,
        ..lens(50.0, 4.0, 0.0, 0.0)
    };
    assert!(matches!(
        build(nan),
        Err(CameraError::NotFinite {
            name: "lens_tilt",
            ..
        })
    ));
    let nan = ThinLens {
        swing: f64::INFINITY,
        ..lens(50.0, 4.0, 0.0, 0.0)
    };
    assert!(matches!(
        build(nan),
        Err(CameraError::NotFinite {
            name: "lens_swing",
            ..
        })
    ));
    // Tilted, the lens must focus beyond its focal length (F = d = 0.05).
    assert_eq!(
        build(lens(50.0, 0.05, 2.0, 0.0)),
        Err(CameraError::FocusWithinFocalLength {
            focus: 0.05,
            focal_length: 0.05
        })
    );
    assert_eq!(
        build(lens(50.0, 0.04, 0.0, -2.0)).unwrap_err().to_string(),
        "a tilted lens focuses beyond its focal length: focus must be greater than the \
         focal length d = 0.05, found 0.04"
    );
    assert!(build(lens(50.0, 0.0501, 0.0, -2.0)).is_ok());
    // Untilted, the lecture's thin lens may focus anywhere in front.
    assert!(build(lens(50.0, 0.04, 0.0, 0.0)).is_ok());
}

/// Tilts and swings in degrees, now and then zero.
fn angle() -> impl Strategy<Value = f64> {
    prop_oneof![Just(0.0), -60.0..60.0f64]
}

proptest! {
    /// Every lens ray of a pixel meets the pixel's centre ray on the plane of focus, at
    /// t = 1, wherever the centre ray meets the plane in front of the lens; elsewhere
    /// the lines still pass through the (virtual) meeting point.
    #[test]
    fn lens_rays_meet_on_the_plane_of_focus(
        tilt in angle(),
        swing in angle(),
        focal_length in 20.0..200.0f64,
        focus_over_focal_length in 1.05..2000.0f64,
        eye in (-5.0..5.0f64, -5.0..5.0f64, -5.0..5.0f64),
        view in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
        image in (0.0..36.0f64, 0.0..24.0f64),
        p_lens in (0.0..1.0f64, 0.0..1.0f64),
        blades in prop_oneof![Just(0u32), 3u32..9],
    ) {
        let frame = Frame::from_eye_view_up(eye.into(), view.into(), DVec3::Y);
        prop_assume!(frame.is_ok());
        let frame = frame.unwrap();
        let focus = focal_length / 1000.0 * focus_over_focal_length;
        let projection = ThinLens {
            iris: Iris::new(blades, 0.4).unwrap(),
            ..lens(focal_length, focus, tilt, swing)
        };
        let camera = camera_with(frame, projection);
        let plane = camera.focus_plane().unwrap();
        let image = DVec2::from(image);
        let centre = camera.generate_ray_through(image, DVec2::splat(0.5)).unwrap();
        prop_assert_eq!(centre.origin, frame.e());
        let ray = camera.generate_ray_through(image, DVec2::from(p_lens)).unwrap();
        // The lens point lies on the aperture, in the plane of u and v through e.
        let lens_point = ray.origin - frame.e();
        prop_assert!(lens_point.dot(frame.w()).abs() < 1e-15);
        let lx = lens_point.dot(frame.u()) / projection.aperture;
        let ly = lens_point.dot(frame.v()) / projection.aperture;
        prop_assert!(projection.iris.contains(DVec2::new(lx, ly)));
        // Where the centre ray meets the plane of focus.
        let along = plane.normal.dot(centre.direction);
        let t = plane.normal.dot(plane.point - centre.origin) / along;
        let scale = centre.direction.length();
        if t > 0.0 && t * scale < 1e6 {
            let meet = centre.at(t);
            let tolerance = 1e-9 * (1.0 + meet.distance(frame.e()));
            prop_assert!(centre.at(1.0).distance(meet) < tolerance, "{} {}", centre.at(1.0), meet);
            prop_assert!(ray.at(1.0).distance(meet) < tolerance, "{} {}", ray.at(1.0), meet);
            prop_assert!(off(&plane, ray.at(1.0)).abs() < tolerance);
        } else if along.abs() > 1e-9 * scale {
            // Behind the eye: the ray's line passes through the meeting point, and
            // leads away from it.
            let meet = centre.at(t);
            let back = meet - ray.origin;
            let sine = back.normalize().cross(ray.direction.normalize()).length();
            prop_assert!(sine < 1e-9, "{sine}");
            prop_assert!(t > 0.0 || back.dot(ray.direction) <= 0.0);
        }
    }

    /// A round lens's rays do not depend on how the lens is rotated; a polygon's
    /// points are those of the sampler, turned by the rotation.
    #[test]
    fn the_iris_decides_only_where_rays_start(
        p_lens in (0.0..1.0f64, 0.0..1.0f64),
        rotation in -180.0..180.0f64,
        blades in 3u32..12,
    ) {
        let base = lens(50.0, 3.0, 5.0, -4.0);
        let turned = Iris::from_degrees(blades, rotation).unwrap();
        let camera = camera(ThinLens { iris: turned, ..base });
        let p_lens = DVec2::from(p_lens);
        let ray = camera.generate_ray_through(DVec2::new(3.5, 7.5), p_lens).unwrap();
        let expected = base.aperture
            * viewray_camera::sample_regular_polygon(p_lens, blades, turned.rotation);
        prop_assert!(ray.origin.truncate().abs_diff_eq(expected, 1e-15));
        let at_lens = camera.generate_ray_at_lens(DVec2::new(3.5, 7.5), expected / base.aperture);
        prop_assert_eq!(Some(ray), at_lens);
        let round = self::camera(ThinLens { iris: Iris::new(0, rotation.to_radians()).unwrap(), ..base });
        let unturned = self::camera(base);
        prop_assert_eq!(
            round.generate_ray_through(DVec2::new(3.5, 7.5), p_lens),
            unturned.generate_ray_through(DVec2::new(3.5, 7.5), p_lens)
        );
    }
}

#[test]
fn the_tilt_s_rays_are_checked_at_the_right_angle() {
    // A tilt just under 90 degrees still makes finite rays.
    let steep = camera(lens(50.0, 4.0, 89.999, 0.0));
    for row in [0, 12, 23] {
        let ray = steep
            .generate_ray(
                row,
                5,
                CameraSample {
                    p_film: DVec2::splat(0.5),
                    p_lens: DVec2::new(0.1, 0.9),
                },
            )
            .unwrap();
        assert!(ray.origin.is_finite() && ray.direction.is_finite());
    }
    close(FRAC_PI_2.to_degrees(), 90.0, 0.0);
}
