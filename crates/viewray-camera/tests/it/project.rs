//! `project` inverts ray generation for every family, and thin-lens rays focus.

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use viewray_camera::{
    Camera, CameraSample, Fisheye, Frame, Lens, Oblique, Orthographic, Perspective, Projection,
    ThinLens,
};

fn vector(range: f64) -> impl Strategy<Value = DVec3> {
    (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn frame() -> impl Strategy<Value = Frame> {
    (vector(10.0), vector(1.0), vector(1.0)).prop_filter_map(
        "degenerate frame",
        |(eye, view, up)| {
            let sin = view
                .normalize_or_zero()
                .cross(up.normalize_or_zero())
                .length();
            (sin > 1e-2).then(|| Frame::from_eye_view_up(eye, view, up).ok())?
        },
    )
}

fn viewport() -> impl Strategy<Value = DVec2> {
    (0.1..10.0f64, 0.1..10.0f64).prop_map(|(w, h)| DVec2::new(w, h))
}

fn shift() -> impl Strategy<Value = DVec2> {
    (-1.0..1.0f64, -1.0..1.0f64).prop_map(|(x, y)| DVec2::new(x, y))
}

fn planar_projection() -> impl Strategy<Value = Projection> {
    prop_oneof![
        (0.1..5.0f64, viewport(), shift()).prop_map(|(distance, viewport, shift)| {
            Projection::Perspective(Perspective {
                distance,
                viewport,
                shift,
            })
        }),
        (0.1..5.0f64, viewport(), shift(), 0.01..1.0f64, 0.5..20.0f64).prop_map(
            |(distance, viewport, shift, aperture, focus)| {
                Projection::ThinLens(ThinLens {
                    distance,
                    viewport,
                    shift,
                    aperture,
                    focus,
                    tilt: 0.0,
                    swing: 0.0,
                    iris: viewray_camera::Iris::ROUND,
                })
            }
        ),
        (
            viewport(),
            proptest::option::of((0.01..1.0f64, 0.5..20.0f64))
        )
            .prop_map(|(viewport, lens)| {
                Projection::Orthographic(Orthographic {
                    viewport,
                    lens: lens.map(|(aperture, focus)| Lens { aperture, focus }),
                })
            }),
        (viewport(), 0.0..2.0f64, -PI..PI).prop_map(|(viewport, ratio, angle)| {
            Projection::Oblique(Oblique {
                viewport,
                ratio,
                angle,
            })
        }),
    ]
}

fn projection() -> impl Strategy<Value = Projection> {
    prop_oneof![
        4 => planar_projection(),
        1 => Just(Projection::Equirectangular),
        1 => (0.1..TAU).prop_map(|fov| Projection::Fisheye(Fisheye { fov })),
    ]
}

fn unit_square() -> impl Strategy<Value = DVec2> {
    (0.0..1.0f64, 0.0..1.0f64).prop_map(|(x, y)| DVec2::new(x, y))
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// project(ray(row, col, (ox, oy)).at(t)) == (col + ox, row + oy) for every t > 0.
    #[test]
    fn project_inverts_ray_generation(
        frame in frame(),
        projection in projection(),
        (width, height) in (1..64u32, 1..64u32),
        (row_f, col_f) in (0.0..1.0f64, 0.0..1.0f64),
        p_film in unit_square(),
        t in 0.01..100.0f64,
    ) {
        let camera = Camera::new(frame, projection, width, height).unwrap();
        let row = (row_f * f64::from(height)) as u32;
        let col = (col_f * f64::from(width)) as u32;
        let sample = CameraSample { p_film, p_lens: DVec2::splat(0.5) };
        let Some(ray) = camera.generate_ray(row, col, sample) else {
            // Only a fisheye lacks rays, and only outside its image circle.
            let Projection::Fisheye(_) = projection else { panic!("no ray from {projection:?}") };
            return Ok(());
        };
        let expected = DVec2::new(f64::from(col), f64::from(row)) + p_film;
        if projection == Projection::Equirectangular {
            // At the poles the longitude, and so x, is undefined.
            let latitude = PI * (0.5 - expected.y / f64::from(height));
            prop_assume!(latitude.cos() > 1e-6);
        }
        let got = camera.project(ray.at(t));
        prop_assert!(got.is_some(), "{:?} not visible", ray.at(t));
        let mut got = got.unwrap();
        if projection == Projection::Equirectangular && (got.x - expected.x).abs() > f64::from(width) / 2.0 {
            // The seam: longitude -pi and pi are the same column.
            got.x += f64::from(width) * (expected.x - got.x).signum();
        }
        let tolerance = 1e-6 * (1.0 + f64::from(width.max(height)));
        prop_assert!(got.abs_diff_eq(expected, tolerance), "got {got}, expected {expected}");
    }

    /// Points behind a perspective eye (or a parallel camera's image plane) are not visible.
    #[test]
    fn points_behind_the_camera_do_not_project(
        frame in frame(),
        projection in planar_projection(),
        p in vector(10.0),
    ) {
        let camera = Camera::new(frame, projection, 16, 9).unwrap();
        let depth = -frame.camera_from_world_point(p).z;
        prop_assert_eq!(camera.project(p).is_some(), depth > 0.0);
    }

    /// All rays of one pixel through a thin lens meet where the lens-centre ray meets the
    /// focus plane, `f` in front of the lens.
    #[test]
    fn thin_lens_rays_of_a_pixel_meet_on_the_focus_plane(
        frame in frame(),
        projection in projection(),
        p_film in unit_square(),
        p_lens in unit_square(),
    ) {
        let focus = match projection {
            Projection::ThinLens(p) => p.focus,
            Projection::Orthographic(Orthographic { lens: Some(lens), .. }) => lens.focus,
            _ => return Ok(()),
        };
        let camera = Camera::new(frame, projection, 8, 6).unwrap();
        let center = camera.generate_ray(3, 5, CameraSample { p_film, p_lens: DVec2::splat(0.5) }).unwrap();
        let through_lens = camera.generate_ray(3, 5, CameraSample { p_film, p_lens }).unwrap();
        // The focus plane is at camera depth f; find where each ray crosses it.
        let crossing = |ray: viewray_geometry::DRay| {
            let origin_depth = -frame.camera_from_world_point(ray.origin).z;
            let speed = -ray.direction.dot(frame.w());
            ray.at((focus - origin_depth) / speed)
        };
        let a = crossing(center);
        let b = crossing(through_lens);
        prop_assert!(a.abs_diff_eq(b, 1e-9 * (1.0 + a.length())), "{a} != {b}");
        // The origin lies on the lens: within r of where the lens-centre ray starts.
        prop_assert!(through_lens.origin.distance(center.origin) <= 1.0 + 1e-12);
    }
}

#[test]
fn perspective_does_not_project_the_eye_or_points_beside_it() {
    let camera = Camera::canonical(4, 4).unwrap();
    assert_eq!(camera.project(DVec3::ZERO), None);
    assert_eq!(camera.project(DVec3::new(1.0, 0.0, 0.0)), None);
    assert_eq!(camera.project(DVec3::new(0.0, 0.0, 1.0)), None);
    assert_eq!(
        camera.project(DVec3::new(0.0, 0.0, -5.0)),
        Some(DVec2::new(2.0, 2.0))
    );
    // Half a viewport to the right at depth 1 is the right edge of the image.
    assert_eq!(
        camera.project(DVec3::new(0.5, 0.5, -1.0)),
        Some(DVec2::new(4.0, 0.0))
    );
    assert_eq!(camera.pixel_at(DVec2::new(4.0, 0.0)), None);
    assert_eq!(camera.pixel_at(DVec2::new(3.999, 0.0)), Some((0, 3)));
}

#[test]
fn fisheye_has_no_rays_outside_its_circle() {
    let camera = Camera::new(
        Frame::CANONICAL,
        Projection::Fisheye(Fisheye { fov: PI }),
        100,
        100,
    )
    .unwrap();
    // The corners lie outside the inscribed circle; the centre looks straight ahead.
    assert_eq!(camera.generate_ray(0, 0, CameraSample::CENTER), None);
    let centre = camera
        .generate_ray_through(DVec2::new(50.0, 50.0), DVec2::splat(0.5))
        .unwrap();
    assert_eq!(centre.direction, DVec3::NEG_Z);
    // A 180-degree fisheye sees the whole front hemisphere and nothing behind.
    assert!(camera.project(DVec3::new(1.0, 0.0, -1e-9)).is_some());
    assert_eq!(camera.project(DVec3::new(1.0, 0.0, 0.1)), None);
}

#[test]
fn invalid_parameters_are_errors() {
    use viewray_camera::CameraError::{Image, NotFinite, NotPositive, OutOfRange};
    use viewray_camera::ImageLimitError::Empty;
    let perspective = |distance, vw, vh| {
        Projection::Perspective(Perspective {
            distance,
            viewport: DVec2::new(vw, vh),
            shift: DVec2::ZERO,
        })
    };
    let new = |p| Camera::new(Frame::CANONICAL, p, 4, 3).map(|_| ());
    assert_eq!(
        new(perspective(0.0, 1.0, 1.0)),
        Err(NotPositive {
            name: "d",
            value: 0.0
        })
    );
    assert_eq!(
        new(perspective(1.0, -1.0, 1.0)),
        Err(NotPositive {
            name: "vw",
            value: -1.0
        })
    );
    assert_eq!(
        new(perspective(1.0, 1.0, f64::INFINITY)),
        Err(NotFinite {
            name: "vh",
            value: "inf".into()
        })
    );
    assert!(matches!(
        new(Projection::ThinLens(ThinLens {
            distance: 1.0,
            viewport: DVec2::ONE,
            shift: DVec2::ZERO,
            aperture: 0.1,
            focus: 0.0,
            tilt: 0.0,
            swing: 0.0,
            iris: viewray_camera::Iris::ROUND,
        })),
        Err(NotPositive { name: "focus", .. })
    ));
    assert!(matches!(
        new(Projection::Fisheye(Fisheye { fov: 7.0 })),
        Err(OutOfRange { name: "fov", .. })
    ));
    assert_eq!(
        Camera::new(Frame::CANONICAL, perspective(1.0, 1.0, 1.0), 0, 3),
        Err(Image(Empty {
            width: 0,
            height: 3
        }))
    );
    assert!(matches!(
        Perspective::from_fov_y(PI, 1.0),
        Err(OutOfRange { name: "fov_y", .. })
    ));
}

#[test]
fn field_of_view_constructors() {
    // A 90-degree vertical field of view is a viewport 2 tall at d = 1.
    let p = Perspective::from_fov_y(PI / 2.0, 1.5).unwrap();
    assert!((p.viewport - DVec2::new(3.0, 2.0)).abs().max_element() < 1e-12);
    assert_eq!(p.distance, 1.0);
    let p = Perspective::from_fov_x(PI / 2.0, 2.0).unwrap();
    assert!((p.viewport - DVec2::new(2.0, 1.0)).abs().max_element() < 1e-12);
    let o = Orthographic::from_height(3.0, 4.0 / 3.0).unwrap();
    assert!((o.viewport - DVec2::new(4.0, 3.0)).abs().max_element() < 1e-12);
}

/// The principal point, worked by hand: the homework's shifted camera (vw = 3, vh = 1,
/// shift (0.5, 0.25)) has its optical axis at x / W = 1/2 - 0.5/3 = 1/3 and
/// y / H = 1/2 + 0.25/1 = 3/4, and a ray there goes straight along -w.
#[test]
fn the_principal_point_is_where_the_optical_axis_meets_the_image() {
    use viewray_camera::{Camera, Frame, Oblique, Perspective, Projection, ThinLens};
    let shift = DVec2::new(0.5, 0.25);
    let viewport = DVec2::new(3.0, 1.0);
    let perspective = Projection::Perspective(Perspective {
        distance: 2.0,
        viewport,
        shift,
    });
    let expected = DVec2::new(1.0 / 3.0, 0.75);
    let found = perspective.principal_point().unwrap();
    assert!((found - expected).length() < 1e-15, "{found}");
    let camera = Camera::new(Frame::CANONICAL, perspective, 30, 20).unwrap();
    let ray = camera
        .generate_ray_through(found * DVec2::new(30.0, 20.0), DVec2::splat(0.5))
        .unwrap();
    assert!(ray.direction.truncate().length() < 1e-12, "{ray:?}");
    let thin = Projection::ThinLens(ThinLens::new(
        Perspective {
            distance: 2.0,
            viewport,
            shift,
        },
        0.1,
        4.0,
    ));
    assert_eq!(thin.principal_point(), Some(found));
    let oblique = Projection::Oblique(Oblique {
        viewport,
        ratio: 0.5,
        angle: 0.3,
    });
    assert_eq!(oblique.principal_point(), Some(DVec2::splat(0.5)));
    let ortho = Projection::Orthographic(viewray_camera::Orthographic {
        viewport,
        lens: None,
    });
    assert_eq!(ortho.principal_point(), Some(DVec2::splat(0.5)));
    assert_eq!(Projection::Equirectangular.principal_point(), None);
    let fisheye = Projection::Fisheye(viewray_camera::Fisheye { fov: 3.0 });
    assert_eq!(fisheye.principal_point(), None);
}
