//! Viewing rays checked against the lecture's formulas: hand-worked homework cases and
//! snapshot tables of every family.

use std::f64::consts::FRAC_PI_4;

use glam::{DVec2, DVec3};
use viewray_camera::{
    Camera, CameraSample, Fisheye, Frame, Lens, Oblique, Orthographic, Perspective, Projection,
    ThinLens, pixel_to_image_plane,
};

/// Formats a number for a student: at most six decimals, no trailing zeros, no `-0`.
fn num(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

fn vec3(v: DVec3) -> String {
    format!("({}, {}, {})", num(v.x), num(v.y), num(v.z))
}

/// The table of viewing rays of every pixel at `sample`, one line per pixel, with both
/// index conventions.
fn ray_table(camera: &Camera, sample: CameraSample) -> String {
    let f = camera.frame();
    let mut out = format!(
        "{:?}\ne = {}, u = {}, v = {}, w = {}; image {} x {}\n",
        camera.projection(),
        vec3(f.e()),
        vec3(f.u()),
        vec3(f.v()),
        vec3(f.w()),
        camera.width(),
        camera.height()
    );
    out += "row col (i, j) | origin | direction\n";
    for row in 0..camera.height() {
        for col in 0..camera.width() {
            let ray = camera.generate_ray(row, col, sample);
            let text = match ray {
                Some(ray) => format!("{} | {}", vec3(ray.origin), vec3(ray.direction)),
                None => "no ray".to_owned(),
            };
            out += &format!("{row:>3} {col:>3} ({}, {}) | {text}\n", row + 1, col + 1);
        }
    }
    out
}

fn camera(frame: Frame, projection: Projection) -> Camera {
    Camera::new(frame, projection, 3, 2).unwrap()
}

fn tilted_frame() -> Frame {
    Frame::from_eye_look_at_up(DVec3::new(1.0, 2.0, 3.0), DVec3::ZERO, DVec3::Y).unwrap()
}

#[track_caller]
fn check_ray(camera: &Camera, (i, j): (u32, u32), origin: [f64; 3], direction: [f64; 3]) {
    let ray = camera
        .generate_ray(i - 1, j - 1, CameraSample::CENTER)
        .unwrap();
    let (origin, direction) = (DVec3::from(origin), DVec3::from(direction));
    assert!(
        ray.origin.abs_diff_eq(origin, 1e-12) && ray.direction.abs_diff_eq(direction, 1e-12),
        "pixel (i, j) = ({i}, {j}): got {ray:?}, expected origin {origin}, direction {direction}"
    );
}

#[test]
fn canonical_camera_two_by_two_by_hand() {
    // u = (j - 1/2)/W - 1/2 and v = -((i - 1/2)/H - 1/2) with W = H = 2: u, v = +-1/4.
    let camera = Camera::canonical(2, 2).unwrap();
    let o = [0.0; 3];
    check_ray(&camera, (1, 1), o, [-0.25, 0.25, -1.0]);
    check_ray(&camera, (1, 2), o, [0.25, 0.25, -1.0]);
    check_ray(&camera, (2, 1), o, [-0.25, -0.25, -1.0]);
    check_ray(&camera, (2, 2), o, [0.25, -0.25, -1.0]);
}

#[test]
fn breaking_the_assumptions_one_by_one() {
    // d = 2, vw = 4, vh = 2, eye at (1, 2, 3), W = 4, H = 2; pixel (i, j) = (1, 4):
    // u = ((4 - 1/2)/4 - 1/2) 4 = 1.5, v = -((1 - 1/2)/2 - 1/2) 2 = 0.5.
    let frame = Frame::CANONICAL
        .with_eye(DVec3::new(1.0, 2.0, 3.0))
        .unwrap();
    let projection = Projection::Perspective(Perspective {
        distance: 2.0,
        viewport: DVec2::new(4.0, 2.0),
        shift: DVec2::ZERO,
    });
    let camera = Camera::new(frame, projection, 4, 2).unwrap();
    check_ray(&camera, (1, 4), [1.0, 2.0, 3.0], [1.5, 0.5, -2.0]);
    assert_eq!(
        pixel_to_image_plane(0, 3, DVec2::splat(0.5), (4, 2), DVec2::new(4.0, 2.0)),
        DVec2::new(1.5, 0.5)
    );
}

#[test]
fn general_basis_by_hand() {
    // Eye (1, 2, 3) looking at the origin with up = y (worked in the frame tests):
    // w = (1, 2, 3)/sqrt 14, u = (3, 0, -1)/sqrt 10, v = (-2, 10, -6)/sqrt 140.
    // The centre pixel of a 1 x 1 image with d = 1 looks along -w.
    let camera = Camera::new(
        tilted_frame(),
        Projection::Perspective(Perspective::CANONICAL),
        1,
        1,
    )
    .unwrap();
    let w = DVec3::new(1.0, 2.0, 3.0) / 14f64.sqrt();
    check_ray(&camera, (1, 1), [1.0, 2.0, 3.0], (-w).to_array());
}

#[test]
fn orthographic_and_oblique_by_hand() {
    // vw = 4, vh = 2, W = 2, H = 1: the pixel centres are at u = -1 and u = +1, v = 0.
    let viewport = DVec2::new(4.0, 2.0);
    let ortho = Camera::new(
        Frame::CANONICAL,
        Projection::Orthographic(Orthographic {
            viewport,
            lens: None,
        }),
        2,
        1,
    )
    .unwrap();
    check_ray(&ortho, (1, 1), [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]);
    check_ray(&ortho, (1, 2), [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]);
    // Cabinet at 90 degrees: depth recedes straight up at half length.
    let cabinet = Camera::new(
        Frame::CANONICAL,
        Projection::Oblique(Oblique::cabinet(viewport, std::f64::consts::FRAC_PI_2)),
        2,
        1,
    )
    .unwrap();
    let ray = cabinet.generate_ray(0, 1, CameraSample::CENTER).unwrap();
    assert!(
        ray.direction
            .abs_diff_eq(DVec3::new(0.0, -0.5, -1.0), 1e-12)
    );
}

fn families() -> Vec<(&'static str, Camera)> {
    let viewport = DVec2::new(1.5, 1.0);
    vec![
        (
            "perspective_canonical",
            camera(
                Frame::CANONICAL,
                Projection::Perspective(Perspective::CANONICAL),
            ),
        ),
        (
            "perspective_general",
            camera(
                tilted_frame(),
                Projection::Perspective(Perspective {
                    distance: 2.0,
                    viewport,
                    shift: DVec2::new(0.0, 0.25),
                }),
            ),
        ),
        (
            "thin_lens",
            camera(
                Frame::CANONICAL,
                Projection::ThinLens(ThinLens {
                    distance: 1.0,
                    viewport,
                    shift: DVec2::ZERO,
                    aperture: 0.1,
                    focus: 4.0,
                    tilt: 0.0,
                    swing: 0.0,
                    iris: viewray_camera::Iris::ROUND,
                }),
            ),
        ),
        (
            "orthographic",
            camera(
                Frame::CANONICAL,
                Projection::Orthographic(Orthographic {
                    viewport,
                    lens: None,
                }),
            ),
        ),
        (
            "orthographic_lens",
            camera(
                Frame::CANONICAL,
                Projection::Orthographic(Orthographic {
                    viewport,
                    lens: Some(Lens {
                        aperture: 0.1,
                        focus: 4.0,
                    }),
                }),
            ),
        ),
        (
            "oblique_cavalier",
            camera(
                Frame::CANONICAL,
                Projection::Oblique(Oblique::cavalier(viewport, FRAC_PI_4)),
            ),
        ),
        (
            "oblique_cabinet",
            camera(
                Frame::CANONICAL,
                Projection::Oblique(Oblique::cabinet(viewport, FRAC_PI_4)),
            ),
        ),
        (
            "equirectangular",
            camera(Frame::CANONICAL, Projection::Equirectangular),
        ),
        (
            "fisheye",
            camera(
                Frame::CANONICAL,
                Projection::Fisheye(Fisheye {
                    fov: 180f64.to_radians(),
                }),
            ),
        ),
    ]
}

#[test]
fn ray_tables_of_every_family() {
    for (name, camera) in families() {
        let mut table = ray_table(&camera, CameraSample::CENTER);
        if camera.projection().has_lens() {
            table += "\nlens sample (1, 0.5), the right edge of the lens:\n";
            table += &ray_table(
                &camera,
                CameraSample {
                    p_film: DVec2::splat(0.5),
                    p_lens: DVec2::new(1.0, 0.5),
                },
            );
        }
        insta::assert_snapshot!(name, table);
    }
}

#[test]
fn ray_differentials_step_by_the_lecture_pixel_size() {
    // With vw = 4, vh = 2, W = 8, H = 4 a pixel is vw / W = 0.5 wide and vh / H = 0.5
    // tall on the image plane: a step of `s` pixels moves u by 0.5 s and v by -0.5 s
    // (y runs down, v up), whatever the eye, d, shift or image point.
    let viewport = DVec2::new(4.0, 2.0);
    let frame = tilted_frame();
    let (u, v) = (frame.u(), frame.v());
    let step = 0.25;
    let (du, dv) = (0.5 * step * u, -0.5 * step * v);
    let image = DVec2::new(1.3, 2.9);
    let lens_centre = DVec2::splat(0.5);
    let camera = |projection| Camera::new(frame, projection, 8, 4).unwrap();

    // Perspective (d = 3, a shift): the directions differ by du and dv, origins agree;
    // the thin lens scales the direction by f / d (the lens centre's ray).
    let perspective = camera(Projection::Perspective(Perspective {
        distance: 3.0,
        viewport,
        shift: DVec2::new(0.2, -0.1),
    }));
    let thin_lens = camera(Projection::ThinLens(ThinLens {
        distance: 3.0,
        viewport,
        shift: DVec2::ZERO,
        aperture: 0.2,
        focus: 6.0,
        tilt: 0.0,
        swing: 0.0,
        iris: viewray_camera::Iris::ROUND,
    }));
    for (camera, scale) in [(perspective, 1.0), (thin_lens, 6.0 / 3.0)] {
        let d = camera
            .generate_ray_differential(image, lens_centre, step)
            .unwrap();
        assert!((d.rx.direction - d.ray.direction).abs_diff_eq(scale * du, 1e-12));
        assert!((d.ry.direction - d.ray.direction).abs_diff_eq(scale * dv, 1e-12));
        assert_eq!((d.rx.origin, d.ry.origin), (d.ray.origin, d.ray.origin));
    }

    // Parallel cameras: the origins move by du and dv, the directions agree.
    let orthographic = camera(Projection::Orthographic(Orthographic {
        viewport,
        lens: None,
    }));
    let oblique = camera(Projection::Oblique(Oblique::cabinet(viewport, FRAC_PI_4)));
    for camera in [orthographic, oblique] {
        let d = camera
            .generate_ray_differential(image, lens_centre, step)
            .unwrap();
        assert!((d.rx.origin - d.ray.origin).abs_diff_eq(du, 1e-12));
        assert!((d.ry.origin - d.ray.origin).abs_diff_eq(dv, 1e-12));
        assert!(d.rx.direction.abs_diff_eq(d.ray.direction, 1e-12));
        assert!(d.ry.direction.abs_diff_eq(d.ray.direction, 1e-12));
    }

    // A fisheye has no neighbour outside its image circle: none for the whole set.
    let fisheye = camera(Projection::Fisheye(Fisheye {
        fov: 180f64.to_radians(),
    }));
    assert!(
        fisheye
            .generate_ray_differential(DVec2::new(4.0, 2.0), lens_centre, 1.0)
            .is_some()
    );
    // The top-left corner lies outside the circle.
    assert_eq!(
        fisheye.generate_ray_differential(DVec2::new(0.1, 0.1), lens_centre, 1.0),
        None
    );
}

#[test]
fn lenses_and_slanted_rays_by_hand() {
    // d = 2, vw = 4, vh = 2, W = 4, H = 2: pixel (i, j) = (1, 4) is u = 1.5, v = 0.5.
    // The lens sample (1, 1/2) is the right edge of the unit disk, (lx, ly) = (1, 0).
    let viewport = DVec2::new(4.0, 2.0);
    let camera = |projection| Camera::new(Frame::CANONICAL, projection, 4, 2).unwrap();
    let right_of_lens = CameraSample {
        p_film: DVec2::splat(0.5),
        p_lens: DVec2::new(1.0, 0.5),
    };
    #[track_caller]
    fn check(camera: &Camera, sample: CameraSample, origin: [f64; 3], direction: [f64; 3]) {
        let ray = camera.generate_ray(0, 3, sample).unwrap();
        assert!(
            ray.origin.abs_diff_eq(origin.into(), 1e-12)
                && ray.direction.abs_diff_eq(direction.into(), 1e-12),
            "got {ray:?}, expected {origin:?} + t {direction:?}"
        );
    }

    // Thin lens, r = 0.1, f = 6, shift (0.5, 0): origin r (lx, ly, 0) = (0.1, 0, 0),
    // direction (f / d)(u + sx, v + sy, -d) - (0.1, 0, 0) = 3 (2, 0.5, -2) - (0.1, 0, 0).
    let thin_lens = camera(Projection::ThinLens(ThinLens {
        distance: 2.0,
        viewport,
        shift: DVec2::new(0.5, 0.0),
        aperture: 0.1,
        focus: 6.0,
        tilt: 0.0,
        swing: 0.0,
        iris: viewray_camera::Iris::ROUND,
    }));
    check(&thin_lens, right_of_lens, [0.1, 0.0, 0.0], [5.9, 1.5, -6.0]);
    check(&thin_lens, CameraSample::CENTER, [0.0; 3], [6.0, 1.5, -6.0]);

    // Orthographic with a lens, r = 0.1, f = 4: origin (u, v, 0) + (0.1, 0, 0), direction
    // -W - (r / f)(lx, ly, 0) = (-0.025, 0, -1).
    let orthographic = camera(Projection::Orthographic(Orthographic {
        viewport,
        lens: Some(Lens {
            aperture: 0.1,
            focus: 4.0,
        }),
    }));
    check(
        &orthographic,
        right_of_lens,
        [1.6, 0.5, 0.0],
        [-0.025, 0.0, -1.0],
    );
    check(
        &orthographic,
        CameraSample::CENTER,
        [1.5, 0.5, 0.0],
        [0.0, 0.0, -1.0],
    );

    // Oblique, L = 2, phi = 30 degrees: direction (-L cos phi, -L sin phi, -1).
    let oblique = camera(Projection::Oblique(Oblique {
        viewport,
        ratio: 2.0,
        angle: 30f64.to_radians(),
    }));
    let cos30 = 3f64.sqrt() / 2.0;
    check(
        &oblique,
        right_of_lens,
        [1.5, 0.5, 0.0],
        [-2.0 * cos30, -1.0, -1.0],
    );
    // Cavalier and cabinet are L = 1 and L = 1/2.
    assert_eq!(Oblique::cavalier(viewport, 0.3).ratio, 1.0);
    assert_eq!(Oblique::cabinet(viewport, 0.3).ratio, 0.5);
    assert_eq!(Oblique::cabinet(viewport, 0.3).angle, 0.3);
    assert_eq!(Oblique::cavalier(viewport, 0.3).viewport, viewport);
}

#[test]
fn a_lens_shift_centres_a_point_at_an_elevation() {
    // sy = d tan(theta): d = 3 and 30 degrees give sqrt 3; d = 2 and 45 degrees give 2.
    let close = |a: f64, b: f64| assert!((a - b).abs() < 1e-12, "{a} != {b}");
    close(
        Perspective::shift_for_elevation(3.0, 30f64.to_radians()),
        3f64.sqrt(),
    );
    close(Perspective::shift_for_elevation(0.5, FRAC_PI_4), 0.5);
    close(
        Perspective::shift_for_elevation(2.0, -(0.25f64.atan())),
        -0.5,
    );
    // The point at that elevation, at any depth, appears at the image centre.
    let d = 3.0;
    let theta = 30f64.to_radians();
    let camera = Camera::new(
        Frame::CANONICAL,
        Projection::Perspective(Perspective {
            distance: d,
            viewport: DVec2::new(2.0, 2.0),
            shift: DVec2::new(0.0, Perspective::shift_for_elevation(d, theta)),
        }),
        4,
        4,
    )
    .unwrap();
    let point = 7.0 * DVec3::new(0.0, theta.sin(), -theta.cos());
    assert!(
        camera
            .project(point)
            .unwrap()
            .abs_diff_eq(DVec2::splat(2.0), 1e-12)
    );
}

#[test]
fn what_each_family_is() {
    let viewport = DVec2::new(1.5, 1.0);
    let cases = [
        (
            "perspective_canonical",
            "Perspective",
            Some(viewport),
            false,
            false,
        ),
        (
            "perspective_general",
            "Perspective",
            Some(viewport),
            false,
            false,
        ),
        ("thin_lens", "ThinLens", Some(viewport), false, true),
        ("orthographic", "Orthographic", Some(viewport), true, false),
        (
            "orthographic_lens",
            "Orthographic",
            Some(viewport),
            true,
            true,
        ),
        ("oblique_cavalier", "Oblique", Some(viewport), true, false),
        ("oblique_cabinet", "Oblique", Some(viewport), true, false),
        ("equirectangular", "Equirectangular", None, false, false),
        ("fisheye", "Fisheye", None, false, false),
    ];
    let families = families();
    assert_eq!(families.len(), cases.len());
    for ((name, camera), (expected, family, viewport, parallel, lens)) in
        families.into_iter().zip(cases)
    {
        assert_eq!(name, expected);
        let projection = camera.projection();
        // The canonical camera's viewport is 1 x 1.
        let viewport = if name == "perspective_canonical" {
            Some(DVec2::ONE)
        } else {
            viewport
        };
        assert_eq!(projection.family_name(), family, "{name}");
        assert_eq!(projection.viewport(), viewport, "{name}");
        assert_eq!(projection.is_parallel(), parallel, "{name}");
        assert_eq!(projection.has_lens(), lens, "{name}");
    }
}
