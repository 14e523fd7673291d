//! The conventions at the edges, pinned down by hand-worked values: which pixel an edge
//! belongs to, what lies exactly on a fisheye's image circle, where the equirectangular
//! image wraps, and which points on a parallel camera's image plane are seen.
//!
//! The crate's docs (`# Boundaries` in `lib.rs`) and `docs/cameras.md` state the same rules.

use std::f64::consts::{FRAC_1_SQRT_2, FRAC_PI_2, FRAC_PI_4, PI, TAU};

use glam::{DVec2, DVec3};
use viewray_camera::{Camera, CameraError, Fisheye, Frame, Oblique, Orthographic, Projection};

fn camera(projection: Projection, width: u32, height: u32) -> Camera {
    Camera::new(Frame::CANONICAL, projection, width, height).unwrap()
}

fn fisheye(degrees: f64, width: u32, height: u32) -> Camera {
    camera(
        Projection::Fisheye(Fisheye {
            fov: degrees.to_radians(),
        }),
        width,
        height,
    )
}

/// The camera-space direction of the ray through the continuous image point `(x, y)`.
#[track_caller]
fn direction(camera: &Camera, (x, y): (f64, f64)) -> Option<DVec3> {
    camera
        .generate_ray_through(DVec2::new(x, y), DVec2::splat(0.5))
        .map(|ray| ray.direction)
}

#[track_caller]
fn check_direction(camera: &Camera, image: (f64, f64), expected: [f64; 3]) {
    let got = direction(camera, image).expect("a ray");
    assert!(
        got.abs_diff_eq(DVec3::from(expected), 1e-12),
        "through {image:?}: got {got}, expected {expected:?}"
    );
}

#[track_caller]
fn check_project(camera: &Camera, point: [f64; 3], expected: Option<(f64, f64)>) {
    let got = camera.project(DVec3::from(point));
    let ok = match (got, expected) {
        (Some(got), Some((x, y))) => got.abs_diff_eq(DVec2::new(x, y), 1e-12),
        (None, None) => true,
        _ => false,
    };
    assert!(ok, "{point:?}: got {got:?}, expected {expected:?}");
}

#[test]
fn a_pixel_holds_its_left_and_top_edges_but_not_its_right_and_bottom() {
    // Pixel (row, col) spans [col, col + 1) x [row, row + 1); a 4 x 3 image spans
    // [0, 4) x [0, 3).
    let camera = Camera::canonical(4, 3).unwrap();
    let check = |x: f64, y: f64, expected: Option<(u32, u32)>| {
        assert_eq!(camera.pixel_at(DVec2::new(x, y)), expected, "({x}, {y})");
    };
    check(0.0, 0.0, Some((0, 0)));
    check(1.0, 2.0, Some((2, 1)));
    check(3.5, 0.5, Some((0, 3)));
    check(3.999, 2.999, Some((2, 3)));
    // The right and bottom edges belong to no pixel, whatever the other coordinate.
    check(4.0, 1.0, None);
    check(1.0, 3.0, None);
    check(4.0, 3.0, None);
    // Nor does anything left of or above the image.
    check(-1e-9, 1.0, None);
    check(1.0, -1e-9, None);
    check(5.0, 1.0, None);
    check(1.0, 4.0, None);
}

#[test]
fn a_point_on_the_right_edge_of_the_view_projects_to_x_equals_w() {
    // Canonical camera, 4 x 2 image: u = 1/2 at depth 1 is x = (1/2 + 1/2) 4 = 4, the
    // right edge, in no pixel; u = -1/2 is x = 0, the left edge, in column 0.
    let camera = Camera::canonical(4, 2).unwrap();
    check_project(&camera, [0.5, 0.0, -1.0], Some((4.0, 1.0)));
    check_project(&camera, [-1.0, 0.0, -2.0], Some((0.0, 1.0)));
    check_project(&camera, [0.0, -1.5, -3.0], Some((2.0, 2.0)));
    assert_eq!(camera.pixel_at(DVec2::new(4.0, 1.0)), None);
    assert_eq!(camera.pixel_at(DVec2::new(0.0, 1.0)), Some((1, 0)));
    assert_eq!(camera.pixel_at(DVec2::new(2.0, 2.0)), None);
}

#[test]
fn a_fisheye_sees_between_0_and_360_degrees_both_180_and_360_included() {
    let check = |fov: f64, valid: bool| {
        let got = Projection::Fisheye(Fisheye { fov }).validate();
        assert_eq!(got.is_ok(), valid, "fov {fov}: {got:?}");
    };
    check(PI, true);
    check(TAU, true);
    check(360f64.to_radians(), true);
    check(1e-6, true);
    check(0.0, false);
    check(-1.0, false);
    check(TAU + 1e-9, false);
    assert_eq!(
        Projection::Fisheye(Fisheye { fov: 0.0 }).validate(),
        Err(CameraError::OutOfRange {
            name: "fov",
            expected: "in (0, 360] degrees",
            value: 0.0
        })
    );
}

#[test]
fn a_180_degree_fisheye_sees_exactly_sideways_on_its_image_circle() {
    // W = 8, H = 4, F = pi: a = x/4 - 1, b = (1 - y/2)/2, theta = r pi/2. The circle
    // touches the left and right edges; the top and bottom edges are at r = 1/2.
    let camera = fisheye(180.0, 8, 4);
    let h = FRAC_1_SQRT_2;
    check_direction(&camera, (4.0, 2.0), [0.0, 0.0, -1.0]);
    // The right edge's midpoint is on the circle (r = 1): theta = pi/2, along +U.
    check_direction(&camera, (8.0, 2.0), [1.0, 0.0, 0.0]);
    check_direction(&camera, (0.0, 2.0), [-1.0, 0.0, 0.0]);
    // a = 1/2: theta = pi/4; the top edge's midpoint, b = 1/2: theta = pi/4 up.
    check_direction(&camera, (6.0, 2.0), [h, 0.0, -h]);
    check_direction(&camera, (4.0, 0.0), [0.0, h, -h]);
    check_direction(&camera, (4.0, 4.0), [0.0, -h, -h]);
    // a = -3/4: theta = 3 pi/8.
    let (sin, cos) = (3.0 * PI / 8.0).sin_cos();
    check_direction(&camera, (1.0, 2.0), [-sin, 0.0, -cos]);
    // a = 1/2, b = 1/4: r = sqrt(5)/4, theta = r pi/2, the direction along (a, b)/r.
    let r = 5f64.sqrt() / 4.0;
    let (sin, cos) = (r * FRAC_PI_2).sin_cos();
    check_direction(&camera, (6.0, 1.0), [sin * 0.5 / r, sin * 0.25 / r, -cos]);
    // Just outside the circle there is no ray; the corners are far outside.
    assert_eq!(direction(&camera, (8.001, 2.0)), None);
    assert_eq!(direction(&camera, (0.0, 0.0)), None);

    // The inverse: what the circle's edge sees projects onto it.
    check_project(&camera, [0.0, 0.0, -3.0], Some((4.0, 2.0)));
    check_project(&camera, [1.0, 0.0, 0.0], Some((8.0, 2.0)));
    check_project(&camera, [2.0, 0.0, -2.0], Some((6.0, 2.0)));
    check_project(&camera, [0.0, 1.0, -1.0], Some((4.0, 0.0)));
    // Straight down is on the circle too, below the image (b = -1: y = 2 + 4).
    check_project(&camera, [0.0, -1.0, 0.0], Some((4.0, 6.0)));
    // Behind the 180-degree hemisphere: not seen.
    check_project(&camera, [1.0, 0.0, 1e-6], None);
    check_project(&camera, [0.0, 0.0, 1.0], None);
    check_project(&camera, [0.0, 0.0, 0.0], None);
}

#[test]
fn a_360_degree_fisheye_sees_straight_back_on_its_image_circle() {
    // F = 2 pi: theta = r pi. The circle's edge (r = 1) looks along +W, and r = 1/2
    // looks sideways.
    let camera = fisheye(360.0, 8, 4);
    let h = FRAC_1_SQRT_2;
    check_direction(&camera, (4.0, 2.0), [0.0, 0.0, -1.0]);
    check_direction(&camera, (6.0, 2.0), [1.0, 0.0, 0.0]);
    check_direction(&camera, (4.0, 0.0), [0.0, 1.0, 0.0]);
    check_direction(&camera, (7.0, 2.0), [h, 0.0, h]);
    check_direction(&camera, (8.0, 2.0), [0.0, 0.0, 1.0]);
    check_direction(&camera, (0.0, 2.0), [0.0, 0.0, 1.0]);

    check_project(&camera, [1.0, 0.0, 0.0], Some((6.0, 2.0)));
    check_project(&camera, [0.0, 3.0, 0.0], Some((4.0, 0.0)));
    check_project(&camera, [1.0, 0.0, 1.0], Some((7.0, 2.0)));
    check_project(&camera, [-1.0, 0.0, 1.0], Some((1.0, 2.0)));
    // Straight back is the whole circle's edge; project names its rightmost point,
    // where the ray through (W, H/2) looks.
    check_project(&camera, [0.0, 0.0, 1.0], Some((8.0, 2.0)));
    check_project(&camera, [0.0, 0.0, 0.0], None);
}

#[test]
fn the_equirectangular_image_wraps_at_its_left_edge() {
    // W = 8, H = 4: longitude = 2 pi (x/8 - 1/2), latitude = pi (1/2 - y/4),
    // direction = (sin lon cos lat, sin lat, -cos lon cos lat).
    let camera = camera(Projection::Equirectangular, 8, 4);
    check_direction(&camera, (4.0, 2.0), [0.0, 0.0, -1.0]);
    check_direction(&camera, (6.0, 2.0), [1.0, 0.0, 0.0]);
    check_direction(&camera, (2.0, 2.0), [-1.0, 0.0, 0.0]);
    // Longitude -pi and pi, the left and right edges, both look straight back.
    check_direction(&camera, (0.0, 2.0), [0.0, 0.0, 1.0]);
    check_direction(&camera, (8.0, 2.0), [0.0, 0.0, 1.0]);
    check_direction(&camera, (4.0, 0.0), [0.0, 1.0, 0.0]);
    check_direction(&camera, (4.0, 4.0), [0.0, -1.0, 0.0]);
    // Longitude and latitude pi/4: (1/2, sqrt(1/2), -1/2).
    check_direction(&camera, (5.0, 1.0), [0.5, FRAC_1_SQRT_2, -0.5]);
    check_direction(&camera, (3.0, 3.0), [-0.5, -FRAC_1_SQRT_2, -0.5]);
    // The centre column looks exactly ahead, with no rounding in the last place.
    assert_eq!(direction(&camera, (4.0, 2.0)), Some(DVec3::NEG_Z));

    check_project(&camera, [0.0, 0.0, -5.0], Some((4.0, 2.0)));
    check_project(&camera, [2.0, 0.0, 0.0], Some((6.0, 2.0)));
    check_project(&camera, [-2.0, 0.0, 0.0], Some((2.0, 2.0)));
    check_project(&camera, [0.0, 1.0, -1.0], Some((4.0, 1.0)));
    check_project(&camera, [1.0, 2f64.sqrt(), -1.0], Some((5.0, 1.0)));
    check_project(&camera, [-1.0, -(2f64.sqrt()), -1.0], Some((3.0, 3.0)));
    // Straight back is longitude pi: the left edge x = 0, not x = W, so that every
    // point lands in [0, W). Just right of straight back is just left of x = W.
    check_project(&camera, [0.0, 0.0, 1.0], Some((0.0, 2.0)));
    let x = |point: [f64; 3]| camera.project(DVec3::from(point)).unwrap().x;
    let epsilon = 1e-3_f64;
    let beside = 8.0 * epsilon.atan() / TAU;
    assert!((x([epsilon, 0.0, 1.0]) - (8.0 - beside)).abs() < 1e-12);
    assert!((x([-epsilon, 0.0, 1.0]) - beside).abs() < 1e-12);
    check_project(&camera, [0.0, 0.0, 0.0], None);
}

#[test]
fn a_parallel_camera_does_not_see_its_own_image_plane() {
    // Rays start on the image plane (t = 0 is excluded), so a point on the plane is not
    // seen; a point just in front of it is.
    let viewport = DVec2::new(4.0, 2.0);
    let orthographic = camera(
        Projection::Orthographic(Orthographic {
            viewport,
            lens: None,
        }),
        4,
        2,
    );
    check_project(&orthographic, [1.0, 0.5, 0.0], None);
    check_project(&orthographic, [1.0, 0.5, -1e-9], Some((3.0, 0.5)));
    check_project(&orthographic, [1.0, 0.5, 1e-9], None);
    // Cavalier at 45 degrees: depth D moves a point by (D cos 45, D sin 45).
    let oblique = camera(
        Projection::Oblique(Oblique::cavalier(viewport, FRAC_PI_4)),
        4,
        2,
    );
    check_project(&oblique, [1.0, 0.5, 0.0], None);
    let d = FRAC_1_SQRT_2;
    // x = (u / vw + 1/2) W = u + 2, y = (1/2 - v / vh) H = 1 - v.
    check_project(&oblique, [0.0, 0.0, -1.0], Some((2.0 + d, 1.0 - d)));
    check_project(
        &oblique,
        [-1.0, 0.5, -2.0],
        Some((1.0 + 2.0 * d, 0.5 - 2.0 * d)),
    );
}
