//! Camera frames: the lecture's worked cases and the laws every frame obeys.

use glam::DVec3;
use proptest::prelude::*;
use viewray_camera::Frame;

#[track_caller]
fn check(frame: Frame, e: [f64; 3], u: [f64; 3], v: [f64; 3], w: [f64; 3]) {
    let expected = [e, u, v, w].map(DVec3::from);
    let close = |a: DVec3, b: DVec3| a.abs_diff_eq(b, 1e-12);
    assert!(
        close(frame.e(), expected[0])
            && close(frame.u(), expected[1])
            && close(frame.v(), expected[2])
            && close(frame.w(), expected[3]),
        "got {frame:?}\nexpected e, u, v, w = {expected:?}"
    );
}

#[test]
fn canonical_frame_from_eye_view_up() {
    let frame = Frame::from_eye_view_up(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y).unwrap();
    check(
        frame,
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    );
    assert_eq!(frame, Frame::CANONICAL);
}

#[test]
fn camera_tilted_down_by_45_degrees() {
    // view = (0, -1, -1): w = (0, 1, 1)/sqrt 2, u = up x w = (1, 0, 0) after normalizing,
    // v = w x u = (0, 1, -1)/sqrt 2: image-up leans forward, away from the eye.
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let frame =
        Frame::from_eye_view_up(DVec3::ZERO, DVec3::new(0.0, -1.0, -1.0), DVec3::Y).unwrap();
    check(frame, [0.0; 3], [1.0, 0.0, 0.0], [0.0, h, -h], [0.0, h, h]);
}

#[test]
fn eye_looking_at_the_origin() {
    // eye (1, 2, 3), look_at (0, 0, 0): view = (-1, -2, -3), w = (1, 2, 3)/sqrt 14,
    // up x w = (3, 0, -1)/sqrt 14 so u = (3, 0, -1)/sqrt 10,
    // v = w x u = (-2, 10, -6)/sqrt 140.
    let frame =
        Frame::from_eye_look_at_up(DVec3::new(1.0, 2.0, 3.0), DVec3::ZERO, DVec3::Y).unwrap();
    let s14 = 14f64.sqrt();
    let s10 = 10f64.sqrt();
    let s140 = 140f64.sqrt();
    check(
        frame,
        [1.0, 2.0, 3.0],
        [3.0 / s10, 0.0, -1.0 / s10],
        [-2.0 / s140, 10.0 / s140, -6.0 / s140],
        [1.0 / s14, 2.0 / s14, 3.0 / s14],
    );
}

#[test]
fn rolled_camera() {
    // Up tilted 90 degrees to +x: the image's up is world +x and its right is world -y.
    let frame = Frame::from_eye_view_up(DVec3::ZERO, DVec3::NEG_Z, DVec3::X).unwrap();
    check(
        frame,
        [0.0; 3],
        [0.0, -1.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
    );
}

fn vector() -> impl Strategy<Value = DVec3> {
    (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

proptest! {
    #[test]
    fn frames_are_orthonormal_right_handed_with_v_towards_up(
        eye in vector(), view in vector(), up in vector()
    ) {
        let sin = view.normalize_or_zero().cross(up.normalize_or_zero()).length();
        prop_assume!(view.length() > 1e-3 && up.length() > 1e-3 && sin > 1e-3);
        let f = Frame::from_eye_view_up(eye, view, up).unwrap();
        for (a, name) in [(f.u(), "u"), (f.v(), "v"), (f.w(), "w")] {
            prop_assert!((a.length() - 1.0).abs() < 1e-12, "|{}| = {}", name, a.length());
        }
        prop_assert!(f.u().dot(f.v()).abs() < 1e-12);
        prop_assert!(f.v().dot(f.w()).abs() < 1e-12);
        prop_assert!(f.w().dot(f.u()).abs() < 1e-12);
        // Right-handed: u x v = w.
        prop_assert!(f.u().cross(f.v()).abs_diff_eq(f.w(), 1e-12));
        // w points away from view; v lies in the plane of up and view, on up's side.
        prop_assert!(f.w().abs_diff_eq(-view.normalize(), 1e-12));
        prop_assert!(f.v().dot(up.cross(view).normalize()).abs() < 1e-9);
        prop_assert!(f.v().dot(up) > 0.0);
        prop_assert_eq!(f.e(), eye);
    }

    #[test]
    fn camera_coordinates_round_trip(eye in vector(), view in vector(), up in vector(), p in vector()) {
        let Ok(f) = Frame::from_eye_view_up(eye, view, up) else { return Ok(()) };
        let back = f.world_from_camera_point(f.camera_from_world_point(p));
        prop_assert!(back.abs_diff_eq(p, 1e-9));
    }
}

#[test]
fn up_counts_as_parallel_to_view_below_a_sine_of_1e_9() {
    // view = -z, up = (s, 0, 1): |up x w| = s (up is normalized to itself: |up| rounds to
    // 1). At s = 1e-9 the roll is still defined: u = up x w / s = -y, v = w x u = x.
    let frame =
        Frame::from_eye_view_up(DVec3::ZERO, DVec3::NEG_Z, DVec3::new(1e-9, 0.0, 1.0)).unwrap();
    check(
        frame,
        [0.0; 3],
        [0.0, -1.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 0.0, 1.0],
    );
    // Just below it is parallel.
    assert_eq!(
        Frame::from_eye_view_up(DVec3::ZERO, DVec3::NEG_Z, DVec3::new(0.9e-9, 0.0, 1.0)),
        Err(viewray_camera::CameraError::UpParallelToView)
    );
}

#[test]
fn look_at_means_view_is_target_minus_eye() {
    // eye (1, 2, 3), look_at (1, 2, 1): view = (0, 0, -2), the canonical orientation.
    let frame = Frame::from_eye_look_at_up(
        DVec3::new(1.0, 2.0, 3.0),
        DVec3::new(1.0, 2.0, 1.0),
        DVec3::Y,
    )
    .unwrap();
    check(
        frame,
        [1.0, 2.0, 3.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    );
    // Camera coordinates (a, b, c) are e + a u + b v + c w, and back.
    let frame = Frame::from_eye_view_up(DVec3::new(1.0, 2.0, 3.0), DVec3::X, DVec3::Y).unwrap();
    // w = -x, u = y x -x = z, v = -x x z = y.
    let p = frame.world_from_camera_point(DVec3::new(2.0, 3.0, 5.0));
    assert!(
        p.abs_diff_eq(DVec3::new(1.0 - 5.0, 2.0 + 3.0, 3.0 + 2.0), 1e-12),
        "{p}"
    );
    let c = frame.camera_from_world_point(DVec3::new(-4.0, 5.0, 5.0));
    assert!(c.abs_diff_eq(DVec3::new(2.0, 3.0, 5.0), 1e-12), "{c}");
    let v = frame.world_from_camera_vector(DVec3::new(2.0, 3.0, 5.0));
    assert!(v.abs_diff_eq(DVec3::new(-5.0, 3.0, 2.0), 1e-12), "{v}");
    assert_eq!(
        Frame::from_eye_look_at_up(DVec3::ZERO, DVec3::new(0.0, f64::INFINITY, 0.0), DVec3::Y),
        Err(viewray_camera::CameraError::NotFinite {
            name: "look_at",
            value: "(0, inf, 0)".into()
        })
    );
}

#[test]
fn a_frame_keeps_its_up_as_given_and_moves_its_eye_alone() {
    let up = DVec3::new(0.1, 2.0, 0.3);
    let frame = Frame::from_eye_view_up(DVec3::ONE, DVec3::new(0.0, 0.0, -2.0), up).unwrap();
    assert_eq!(frame.up(), up);
    assert_eq!(Frame::CANONICAL.up(), DVec3::Y);
    let moved = frame.with_eye(DVec3::new(4.0, 5.0, 6.0)).unwrap();
    assert_eq!(moved.e(), DVec3::new(4.0, 5.0, 6.0));
    assert_eq!(
        (moved.u(), moved.v(), moved.w(), moved.up()),
        (frame.u(), frame.v(), frame.w(), frame.up())
    );
    assert!(frame.with_eye(DVec3::new(f64::INFINITY, 0.0, 0.0)).is_err());
}
