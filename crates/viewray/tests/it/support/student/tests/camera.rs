//! The correct camera's numbers, worked by hand from the lecture's formulas.

use super::{assert_vec, v};
use crate::support::student::{
    Aim, CameraSpec, Projection, Vec3, frame, image_plane, project, ray,
};

const CENTRE: (f64, f64) = (0.5, 0.5);

#[test]
fn the_canonical_camera_gives_the_lectures_rays() {
    let camera = CameraSpec::canonical();
    // u = ((j - 1/2)/W - 1/2), v = -((i - 1/2)/H - 1/2) for the lecture's (i, j) = (1, 1).
    let cases = [
        ((0, 0), v(-0.25, 0.25, -1.0)),
        ((0, 1), v(0.25, 0.25, -1.0)),
        ((1, 0), v(-0.25, -0.25, -1.0)),
        ((1, 1), v(0.25, -0.25, -1.0)),
    ];
    for (pixel, direction) in cases {
        let r = ray(&camera, &[], (2, 2), pixel, CENTRE);
        assert_vec(r.origin, Vec3::ZERO, "origin");
        assert_vec(r.direction, direction, &format!("pixel {pixel:?}"));
    }
}

/// A 3 x 2 image, eye (1, 0, 0) looking down -z, d = 2, a 3 x 1 viewport shifted by
/// (0.5, 0.25): the lecture's pixel (1, 3) has u = ((3 - 1/2)/3 - 1/2) 3 = 1,
/// v = -((1 - 1/2)/2 - 1/2) 1 = 1/4 and the direction (1 + 0.5, 1/4 + 1/4, -2).
#[test]
fn a_shifted_camera_adds_the_shift_to_u_and_v() {
    let camera = CameraSpec {
        eye: v(1.0, 0.0, 0.0),
        aim: Aim::View(v(0.0, 0.0, -1.0)),
        up: Vec3::Y,
        projection: Projection::Perspective {
            d: 2.0,
            viewport: (3.0, 1.0),
            shift: (0.5, 0.25),
        },
    };
    let (u, v_) = image_plane(&camera, &[], (3, 2), (0, 2), CENTRE);
    assert!(
        (u - 1.0).abs() < 1e-12 && (v_ - 0.25).abs() < 1e-12,
        "{u} {v_}"
    );
    let r = ray(&camera, &[], (3, 2), (0, 2), CENTRE);
    assert_vec(r.origin, v(1.0, 0.0, 0.0), "origin");
    assert_vec(r.direction, v(1.5, 0.5, -2.0), "direction");
}

/// Eye (1, 2, 3) looking at the origin: view = (-1, -2, -3), so w = (1, 2, 3)/sqrt 14;
/// up x w = (3, 0, -1)/sqrt 14, so u = (3, 0, -1)/sqrt 10; v = w x u = (-2, 10, -6)/sqrt 140.
#[test]
fn the_frame_from_eye_look_at_and_up() {
    let camera = CameraSpec {
        eye: v(1.0, 2.0, 3.0),
        aim: Aim::LookAt(Vec3::ZERO),
        ..CameraSpec::canonical()
    };
    let f = frame(&camera, &[]);
    assert_vec(f.e, v(1.0, 2.0, 3.0), "e");
    assert_vec(f.w, v(1.0, 2.0, 3.0) * (1.0 / 14f64.sqrt()), "w");
    assert_vec(f.u, v(3.0, 0.0, -1.0) * (1.0 / 10f64.sqrt()), "u");
    assert_vec(f.v, v(-2.0, 10.0, -6.0) * (1.0 / 140f64.sqrt()), "v");
}

/// A 4 x 2 image of a 4 x 2 viewport seen from (1, 2, 3) down -z: pixel (0, 0) has
/// u = (0.5/4 - 1/2) 4 = -1.5 and v = -(0.5/2 - 1/2) 2 = 0.5.
#[test]
fn parallel_cameras_start_their_rays_on_the_viewport() {
    let ortho = CameraSpec {
        eye: v(1.0, 2.0, 3.0),
        aim: Aim::View(v(0.0, 0.0, -1.0)),
        up: Vec3::Y,
        projection: Projection::Orthographic {
            viewport: (4.0, 2.0),
        },
    };
    let r = ray(&ortho, &[], (4, 2), (0, 0), CENTRE);
    assert_vec(r.origin, v(-0.5, 2.5, 3.0), "orthographic origin");
    assert_vec(r.direction, v(0.0, 0.0, -1.0), "orthographic direction");
    // Oblique, L = 1/2 at 60 degrees: -W - L (cos phi U + sin phi V).
    let oblique = CameraSpec {
        projection: Projection::Oblique {
            viewport: (4.0, 2.0),
            ratio: 0.5,
            angle_degrees: 60.0,
        },
        ..ortho
    };
    let r = ray(&oblique, &[], (4, 2), (0, 0), CENTRE);
    assert_vec(r.origin, v(-0.5, 2.5, 3.0), "oblique origin");
    assert_vec(
        r.direction,
        v(-0.25, -(3f64.sqrt()) / 4.0, -1.0),
        "oblique direction",
    );
}

#[test]
fn project_gives_continuous_image_coordinates() {
    let canonical = CameraSpec::canonical();
    // The centre of pixel (0, 1); the image centre; behind the eye.
    assert_eq!(
        project(&canonical, (2, 2), v(0.25, 0.25, -1.0)),
        Some((1.5, 0.5))
    );
    assert_eq!(
        project(&canonical, (2, 2), v(0.0, 0.0, -5.0)),
        Some((1.0, 1.0))
    );
    assert_eq!(project(&canonical, (2, 2), v(-1.0, 0.0, 1.0)), None);
    assert_eq!(project(&canonical, (2, 2), v(1.0, 1.0, 0.0)), None);
    // An orthographic camera sees a point where its u, v are, whatever its depth; not at
    // or behind its image plane.
    let ortho = CameraSpec {
        projection: Projection::Orthographic {
            viewport: (4.0, 2.0),
        },
        ..canonical
    };
    // u = 1, v = -0.5: x = (1/4 + 1/2) 4 = 3, y = (1/2 + 0.5/2) 2 = 1.5.
    assert_eq!(
        project(&ortho, (4, 2), v(1.0, -0.5, -7.0)),
        Some((3.0, 1.5))
    );
    assert_eq!(project(&ortho, (4, 2), v(1.0, -0.5, 0.0)), None);
    // Oblique, L = 1/2 at 0 degrees: a point 2 behind the plane moves by L D = 1 along u.
    let oblique = CameraSpec {
        projection: Projection::Oblique {
            viewport: (4.0, 2.0),
            ratio: 0.5,
            angle_degrees: 0.0,
        },
        ..canonical
    };
    assert_eq!(
        project(&oblique, (4, 2), v(0.0, -0.5, -2.0)),
        Some((3.0, 1.5))
    );
}

/// Every point of a sample's ray projects back to the sample: project(ray(row, col,
/// (ox, oy)).at(t)) = (col + ox, row + oy).
#[test]
fn project_undoes_ray_for_every_family() {
    let tilted = CameraSpec {
        eye: v(0.5, 1.5, 4.0),
        aim: Aim::LookAt(v(-0.3, 0.2, -1.0)),
        up: v(0.1, 1.0, 0.2),
        projection: Projection::Perspective {
            d: 1.7,
            viewport: (1.2, 0.7),
            shift: (0.15, -0.1),
        },
    };
    let cameras = [
        tilted,
        CameraSpec {
            projection: Projection::Orthographic {
                viewport: (3.0, 2.0),
            },
            ..tilted
        },
        CameraSpec {
            projection: Projection::Oblique {
                viewport: (3.0, 2.0),
                ratio: 1.0,
                angle_degrees: 30.0,
            },
            ..tilted
        },
    ];
    for camera in cameras {
        for (pixel, offset) in [
            ((0, 0), (0.5, 0.5)),
            ((4, 7), (0.1, 0.9)),
            ((9, 2), (0.0, 0.0)),
        ] {
            let r = ray(&camera, &[], (12, 10), pixel, offset);
            for t in [0.25, 1.0, 3.5] {
                let (x, y) = project(&camera, (12, 10), r.at(t)).expect("the ray is seen");
                let (ex, ey) = (f64::from(pixel.1) + offset.0, f64::from(pixel.0) + offset.1);
                assert!(
                    (x - ex).abs() < 1e-9 && (y - ey).abs() < 1e-9,
                    "{camera:?} {pixel:?} {offset:?} t = {t}: ({x}, {y}), expected ({ex}, {ey})"
                );
            }
        }
    }
}
