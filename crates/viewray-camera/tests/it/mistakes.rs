//! The catalogue of the lecture's mistakes, checked against each entry's own formula.
//!
//! Every expected ray here is the mistaken formula of the catalogue's table written out
//! by hand for one pixel (the student's code, in effect), never the crate's way of making
//! the mistake (a change of the image point, the parameters or the frame).

use std::f64::consts::PI;

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use viewray_camera::{
    Camera, CameraError, CameraSample, Frame, Mistake, Mistakes, Oblique, Orthographic,
    Perspective, Projection, ThinLens,
};

const EYE: DVec3 = DVec3::new(1.0, 2.0, 3.0);
const VIEW: DVec3 = DVec3::new(-0.3, -0.2, -1.0);
/// Not a unit vector and not perpendicular to view, so that `u-not-normalized` shows.
const UP: DVec3 = DVec3::new(0.1, 2.0, 0.3);
const W: u32 = 8;
const H: u32 = 6;
const D: f64 = 1.5;
const VIEWPORT: DVec2 = DVec2::new(1.2, 0.8);
const SHIFT: DVec2 = DVec2::new(0.1, -0.05);
const RATIO: f64 = 0.5;
const ANGLE: f64 = PI / 6.0;

/// The lecture's basis, written out: w = -view/|view|, u = (up x w)/|up x w|, v = w x u.
fn basis() -> (DVec3, DVec3, DVec3) {
    let w = -VIEW / VIEW.length();
    let u = UP.cross(w) / UP.cross(w).length();
    (u, w.cross(u), w)
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Family {
    Perspective,
    Orthographic,
    Oblique,
}

fn right_camera(family: Family) -> Camera {
    let frame = Frame::from_eye_view_up(EYE, VIEW, UP).unwrap();
    let projection = match family {
        Family::Perspective => Projection::Perspective(Perspective {
            distance: D,
            viewport: VIEWPORT,
            shift: SHIFT,
        }),
        Family::Orthographic => Projection::Orthographic(Orthographic {
            viewport: VIEWPORT,
            lens: None,
        }),
        Family::Oblique => Projection::Oblique(Oblique {
            viewport: VIEWPORT,
            ratio: RATIO,
            angle: ANGLE,
        }),
    };
    Camera::new(frame, projection, W, H).unwrap()
}

/// The student's ray for pixel (row, col) at its centre, with `mistake` (or none),
/// written from the catalogue's table.
fn student_ray(family: Family, mistake: Option<Mistake>, row: u32, col: u32) -> (DVec3, DVec3) {
    use Mistake as M;
    let (width, height) = (f64::from(W), f64::from(H));
    let (row, col) = (f64::from(row), f64::from(col));
    let (i, j) = (row + 1.0, col + 1.0);
    let (mut vw, mut vh) = (VIEWPORT.x, VIEWPORT.y);
    match mistake {
        Some(M::ViewportMissing) => (vw, vh) = (1.0, 1.0),
        Some(M::ViewportSwapped) => (vw, vh) = (vh, vw),
        _ => {}
    }
    // Step 1: (i, j) -> (u, v).
    let (u, v) = match mistake {
        Some(M::PixelCorner) => ((col / width - 0.5) * vw, -(row / height - 0.5) * vh),
        Some(M::PixelOneBased) => ((j / width - 0.5) * vw, -(i / height - 0.5) * vh),
        Some(M::SizeMinusOne) => (
            (col / (width - 1.0) - 0.5) * vw,
            -(row / (height - 1.0) - 0.5) * vh,
        ),
        Some(M::VSign) => (
            ((j - 0.5) / width - 0.5) * vw,
            ((i - 0.5) / height - 0.5) * vh,
        ),
        Some(M::USign) => (
            -((j - 0.5) / width - 0.5) * vw,
            -((i - 0.5) / height - 0.5) * vh,
        ),
        Some(M::IJSwapped) => (
            ((i - 0.5) / width - 0.5) * vw,
            -((j - 0.5) / height - 0.5) * vh,
        ),
        _ => (
            ((j - 0.5) / width - 0.5) * vw,
            -((i - 0.5) / height - 0.5) * vh,
        ),
    };
    // Step 2: the basis.
    let (mut e, (mut bu, mut bv, mut bw)) = (EYE, basis());
    match mistake {
        Some(M::EyeMissing) => e = DVec3::ZERO,
        Some(M::BasisMissing) => (bu, bv, bw) = (DVec3::X, DVec3::Y, DVec3::Z),
        Some(M::WView) => {
            bw = VIEW / VIEW.length();
            bu = UP.cross(bw) / UP.cross(bw).length();
            bv = bw.cross(bu);
        }
        Some(M::UCrossOrder) => {
            bu = bw.cross(UP) / bw.cross(UP).length();
            bv = bw.cross(bu);
        }
        Some(M::VCrossOrder) => bv = bu.cross(bw),
        Some(M::UNotNormalized) => {
            bu = UP.cross(bw);
            bv = bw.cross(bu);
        }
        _ => {}
    }
    // Step 3: the family's rule.
    match family {
        Family::Perspective => {
            let (sx, sy) = match mistake {
                Some(M::ShiftMissing) => (0.0, 0.0),
                Some(M::ShiftSign) => (-SHIFT.x, -SHIFT.y),
                _ => (SHIFT.x, SHIFT.y),
            };
            let direction = match mistake {
                Some(M::DistanceMissing) => (u + sx) * bu + (v + sy) * bv - bw,
                Some(M::DistanceSign) => (u + sx) * bu + (v + sy) * bv + D * bw,
                _ => (u + sx) * bu + (v + sy) * bv - D * bw,
            };
            (e, direction)
        }
        Family::Orthographic => match mistake {
            Some(M::OrthoOriginFixed) => (e, -bw),
            Some(M::OrthoAsPerspective) => (e, u * bu + v * bv - bw),
            _ => (e + u * bu + v * bv, -bw),
        },
        Family::Oblique => {
            let slant = RATIO * (ANGLE.cos() * bu + ANGLE.sin() * bv);
            let direction = match mistake {
                Some(M::ObliqueSign) => -bw + slant,
                Some(M::ObliqueAsOrtho) => -bw,
                _ => -bw - slant,
            };
            (e + u * bu + v * bv, direction)
        }
    }
}

#[track_caller]
fn assert_close(actual: DVec3, expected: DVec3, what: &str) {
    assert!(
        (actual - expected).length() <= 1e-12 * (1.0 + expected.length()),
        "{what}: {actual} != {expected}"
    );
}

/// The family in which each entry is checked.
fn family_of(mistake: Mistake) -> Family {
    match mistake {
        Mistake::OrthoOriginFixed | Mistake::OrthoAsPerspective => Family::Orthographic,
        Mistake::ObliqueSign | Mistake::ObliqueAsOrtho => Family::Oblique,
        _ => Family::Perspective,
    }
}

#[test]
fn every_entry_makes_the_rays_of_its_formula() {
    for mistake in Mistake::ALL {
        let family = family_of(mistake);
        let camera = right_camera(family).with_mistakes(mistake.into()).unwrap();
        assert_eq!(camera.mistakes(), Mistakes::one(mistake));
        for (row, col) in [(0, 0), (0, W - 1), (H - 1, 0), (2, 5), (H - 1, W - 1)] {
            let ray = camera.generate_ray(row, col, CameraSample::CENTER).unwrap();
            let (origin, direction) = student_ray(family, Some(mistake), row, col);
            let what = format!("{mistake} at ({row}, {col})");
            assert_close(ray.origin, origin, &what);
            assert_close(ray.direction, direction, &what);
            // The block of rays goes the same way.
            camera.generate_block_rays(
                row..row + 1,
                col..col + 1,
                CameraSample::CENTER,
                |_, _, r| {
                    assert_eq!(r, Some(ray), "{what}: block");
                },
            );
        }
    }
}

#[test]
fn the_written_out_formulas_are_the_contract_without_a_mistake() {
    for family in [Family::Perspective, Family::Orthographic, Family::Oblique] {
        let camera = right_camera(family);
        for (row, col) in [(0, 0), (3, 4), (H - 1, W - 1)] {
            let ray = camera.generate_ray(row, col, CameraSample::CENTER).unwrap();
            let (origin, direction) = student_ray(family, None, row, col);
            assert_close(ray.origin, origin, "origin");
            assert_close(ray.direction, direction, "direction");
        }
    }
}

/// A pixel entry moves the image point, not only the centre: with any film offset
/// `(ox, oy)` the student's `u` is the entry's formula with `col + ox - 1/2` for `col`.
#[test]
fn pixel_entries_follow_the_sample_inside_the_pixel() {
    let camera = right_camera(Family::Perspective);
    let corner = camera.with_mistakes(Mistake::PixelCorner.into()).unwrap();
    let sample = CameraSample {
        p_film: DVec2::new(0.25, 0.75),
        p_lens: DVec2::splat(0.5),
    };
    let ray = corner.generate_ray(2, 5, sample).unwrap();
    let (u, v) = (
        ((5.25 - 0.5) / 8.0 - 0.5) * VIEWPORT.x,
        -((2.75 - 0.5) / 6.0 - 0.5) * VIEWPORT.y,
    );
    let (bu, bv, bw) = basis();
    assert_close(
        ray.direction,
        (u + SHIFT.x) * bu + (v + SHIFT.y) * bv - D * bw,
        "corner",
    );
}

#[test]
fn entries_combine_each_at_its_own_step() {
    // pixel-corner with v-sign: v = +(row/H - 1/2) vh.
    let camera = right_camera(Family::Perspective);
    let both: Mistakes = [Mistake::PixelCorner, Mistake::VSign].into_iter().collect();
    let mistaken = camera.with_mistakes(both).unwrap();
    let ray = mistaken.generate_ray(1, 6, CameraSample::CENTER).unwrap();
    let (u, v) = (
        (6.0 / 8.0 - 0.5) * VIEWPORT.x,
        (1.0 / 6.0 - 0.5) * VIEWPORT.y,
    );
    let (bu, bv, bw) = basis();
    assert_close(
        ray.direction,
        (u + SHIFT.x) * bu + (v + SHIFT.y) * bv - D * bw,
        "both",
    );
    assert_eq!(both.to_string(), "pixel-corner + v-sign");

    // distance-missing with shift-sign and eye-missing.
    let three: Mistakes = [
        Mistake::ShiftSign,
        Mistake::DistanceMissing,
        Mistake::EyeMissing,
    ]
    .into_iter()
    .collect();
    let mistaken = camera.with_mistakes(three).unwrap();
    let ray = mistaken.generate_ray(4, 2, CameraSample::CENTER).unwrap();
    let (u, v) = (
        (2.5 / 8.0 - 0.5) * VIEWPORT.x,
        -(4.5 / 6.0 - 0.5) * VIEWPORT.y,
    );
    assert_eq!(ray.origin, DVec3::ZERO);
    assert_close(
        ray.direction,
        (u - SHIFT.x) * bu + (v - SHIFT.y) * bv - bw,
        "three",
    );
    assert_eq!(three.len(), 3);
}

#[test]
fn a_mistaken_camera_reports_its_mistaken_frame_and_projection() {
    let camera = right_camera(Family::Perspective);
    let mistaken = camera.with_mistakes(Mistake::UCrossOrder.into()).unwrap();
    let (u, v, w) = basis();
    assert_close(mistaken.frame().u(), -u, "u");
    assert_close(mistaken.frame().v(), -v, "v");
    assert_close(mistaken.frame().w(), w, "w");
    let swapped = camera
        .with_mistakes(Mistake::ViewportSwapped.into())
        .unwrap();
    assert_eq!(
        swapped.projection().viewport(),
        Some(DVec2::new(VIEWPORT.y, VIEWPORT.x))
    );
    // A mistaken camera does not project; the right one does.
    let p = EYE + VIEW;
    assert!(camera.project(p).is_some());
    assert_eq!(mistaken.project(p), None);
    // No mistake: the same camera.
    assert_eq!(camera.with_mistakes(Mistakes::NONE).unwrap(), camera);
    // eye-missing and basis-missing leave e or the basis out of the rays, not out of
    // the frame: a student's Problem 2 answer is right.
    let no_eye = camera.with_mistakes(Mistake::EyeMissing.into()).unwrap();
    assert_eq!(no_eye.frame(), camera.frame());
    let no_basis = camera.with_mistakes(Mistake::BasisMissing.into()).unwrap();
    assert_eq!(no_basis.frame(), camera.frame());
}

#[test]
fn entries_that_do_not_fit_the_camera_are_errors() {
    let check = |camera: &Camera, mistake: Mistake, expected: &str| {
        let error = camera.with_mistakes(mistake.into()).unwrap_err();
        assert_eq!(error.to_string(), expected);
    };
    let ortho = right_camera(Family::Orthographic);
    check(
        &ortho,
        Mistake::DistanceMissing,
        "the mistake distance-missing cannot be made in this Orthographic camera",
    );
    check(
        &right_camera(Family::Perspective),
        Mistake::ObliqueSign,
        "the mistake oblique-sign cannot be made in this Perspective camera",
    );
    let narrow = right_camera(Family::Perspective)
        .with_image_size(1, 4)
        .unwrap();
    check(
        &narrow,
        Mistake::SizeMinusOne,
        "the mistake size-minus-one cannot be made in this Perspective camera of 1 x 4 pixels",
    );
    let fine = right_camera(Family::Perspective)
        .with_mistakes(Mistake::SizeMinusOne.into())
        .unwrap();
    assert!(matches!(
        fine.with_image_size(4, 1),
        Err(CameraError::MistakeDoesNotFit { .. })
    ));
    assert_eq!(fine.with_image_size(5, 4).unwrap().width(), 5);
    // Two pixels each way is the least the mistake needs: one fewer either way is refused,
    // whether the size or the mistake comes first.
    for (width, height, fits) in [(2, 2, true), (1, 2, false), (2, 1, false)] {
        let sized = right_camera(Family::Perspective)
            .with_image_size(width, height)
            .unwrap();
        let made = sized.with_mistakes(Mistake::SizeMinusOne.into());
        assert_eq!(made.is_ok(), fits, "{width} x {height}");
    }
    assert_eq!(fine.with_image_size(2, 2).unwrap().height(), 2);
    assert!(matches!(
        fine.with_image_size(1, 4),
        Err(CameraError::MistakeDoesNotFit { .. })
    ));
    let fisheye = Camera::new(
        Frame::CANONICAL,
        Projection::Fisheye(viewray_camera::Fisheye { fov: PI }),
        4,
        4,
    )
    .unwrap();
    for mistake in Mistake::ALL {
        assert!(!mistake.fits(fisheye.projection()), "{mistake}");
    }
}

#[test]
fn which_family_each_entry_fits() {
    let thin = Projection::ThinLens(ThinLens {
        distance: 1.0,
        viewport: DVec2::ONE,
        shift: DVec2::ZERO,
        aperture: 0.1,
        focus: 3.0,
        tilt: 0.0,
        swing: 0.0,
        iris: viewray_camera::Iris::ROUND,
    });
    let fits = |projection: &Projection| -> Vec<&str> {
        Mistake::ALL
            .into_iter()
            .filter(|m| m.fits(projection))
            .map(Mistake::id)
            .collect()
    };
    let basic = [
        "pixel-corner",
        "pixel-one-based",
        "size-minus-one",
        "v-sign",
        "u-sign",
        "i-j-swapped",
        "viewport-missing",
        "viewport-swapped",
    ];
    let basis = [
        "eye-missing",
        "basis-missing",
        "w-view",
        "u-cross-order",
        "v-cross-order",
        "u-not-normalized",
    ];
    let perspective = [
        &basic[..],
        &["distance-missing", "distance-sign"],
        &basis,
        &["shift-sign", "shift-missing"],
    ]
    .concat();
    assert_eq!(
        fits(right_camera(Family::Perspective).projection()),
        perspective
    );
    let thin_lens = [
        &basic[..],
        &["distance-missing"],
        &basis,
        &["shift-sign", "shift-missing"],
    ]
    .concat();
    assert_eq!(fits(&thin), thin_lens);
    let ortho = [
        &basic[..],
        &basis,
        &["ortho-origin-fixed", "ortho-as-perspective"],
    ]
    .concat();
    assert_eq!(fits(right_camera(Family::Orthographic).projection()), ortho);
    let oblique = [&basic[..], &basis, &["oblique-sign", "oblique-as-ortho"]].concat();
    assert_eq!(fits(right_camera(Family::Oblique).projection()), oblique);
}

#[test]
fn a_set_holds_each_mistake_once() {
    for mistake in Mistake::ALL {
        let once = Mistakes::default().with(mistake);
        let twice = once.with(mistake);
        assert!(twice.contains(mistake), "{mistake}");
        assert_eq!(twice, once, "{mistake}");
        assert_eq!(twice.len(), 1, "{mistake}");
    }
    let two = Mistakes::default()
        .with(Mistake::PixelCorner)
        .with(Mistake::VSign)
        .with(Mistake::PixelCorner);
    assert_eq!(
        two.iter().collect::<Vec<_>>(),
        [Mistake::PixelCorner, Mistake::VSign]
    );
}

#[test]
fn ids_are_the_catalogues_and_name_their_entry() {
    let ids: Vec<&str> = Mistake::ALL.iter().map(|m| m.id()).collect();
    assert_eq!(
        ids,
        [
            "pixel-corner",
            "pixel-one-based",
            "size-minus-one",
            "v-sign",
            "u-sign",
            "i-j-swapped",
            "viewport-missing",
            "viewport-swapped",
            "distance-missing",
            "distance-sign",
            "eye-missing",
            "basis-missing",
            "w-view",
            "u-cross-order",
            "v-cross-order",
            "u-not-normalized",
            "shift-sign",
            "shift-missing",
            "ortho-origin-fixed",
            "ortho-as-perspective",
            "oblique-sign",
            "oblique-as-ortho",
        ]
    );
    for mistake in Mistake::ALL {
        assert_eq!(Mistake::from_id(mistake.id()), Some(mistake));
        assert_eq!(mistake.to_string(), mistake.id());
        let entry = mistake.entry();
        for text in [
            entry.looks,
            entry.summary,
            entry.mistaken,
            entry.fix,
            entry.picture,
        ] {
            assert!(
                !text.is_empty() && !text.ends_with('.'),
                "{mistake}: {text:?}"
            );
        }
        assert_ne!(entry.mistaken, entry.fix, "{mistake}");
    }
    assert_eq!(Mistake::from_id("pixel-centre"), None);
    assert_eq!(Mistakes::NONE.to_string(), "none");
    assert!(Mistakes::NONE.is_empty());
    let all: Mistakes = Mistake::ALL.into_iter().collect();
    assert_eq!(all.len(), 22);
    assert!(all.iter().eq(Mistake::ALL));
}

proptest! {
    /// Whatever the camera, a mistaken camera's rays are finite and its block rays are
    /// its single rays, bit for bit.
    #[test]
    fn mistaken_rays_are_finite_and_blocks_agree(
        which in 0usize..22,
        second in 0usize..22,
        family in 0usize..3,
        size in (2u32..40, 2u32..40),
        pixel in (0u32..40, 0u32..40),
        film in (0u32..1024, 0u32..1024),
    ) {
        let family = [Family::Perspective, Family::Orthographic, Family::Oblique][family];
        let mistakes: Mistakes = [Mistake::ALL[which], Mistake::ALL[second]]
            .into_iter()
            .filter(|m| m.fits(right_camera(family).projection()))
            .collect();
        let camera = right_camera(family)
            .with_image_size(size.0, size.1)
            .unwrap()
            .with_mistakes(mistakes)
            .unwrap();
        let sample = CameraSample {
            p_film: DVec2::new(f64::from(film.0), f64::from(film.1)) / 1024.0,
            p_lens: DVec2::splat(0.5),
        };
        let (row, col) = (pixel.0 % size.1, pixel.1 % size.0);
        let ray = camera.generate_ray(row, col, sample).unwrap();
        prop_assert!(ray.origin.is_finite() && ray.direction.is_finite());
        prop_assert!(ray.direction.length() > 0.0);
        camera.generate_block_rays(0..size.1, 0..size.0.min(20), sample, |r, c, block| {
            assert_eq!(block, camera.generate_ray(r, c, sample));
        });
    }
}

/// `(u, v)` of a pixel, as the lecture computes it, at any film offset; a pixel entry
/// moves it as the student's formula does; the panoramic cameras have none.
#[test]
fn the_image_plane_point_is_the_lectures_u_v() {
    let camera = right_camera(Family::Perspective);
    let uv = camera
        .image_plane_point(2, 5, DVec2::new(0.25, 0.75))
        .unwrap();
    let expected = DVec2::new(
        ((5.25) / 8.0 - 0.5) * VIEWPORT.x,
        -((2.75) / 6.0 - 0.5) * VIEWPORT.y,
    );
    assert!((uv - expected).length() < 1e-15, "{uv} != {expected}");
    let corner = camera.with_mistakes(Mistake::PixelCorner.into()).unwrap();
    let uv = corner
        .image_plane_point(2, 5, CameraSample::CENTER.p_film)
        .unwrap();
    let expected = DVec2::new(
        (5.0 / 8.0 - 0.5) * VIEWPORT.x,
        -(2.0 / 6.0 - 0.5) * VIEWPORT.y,
    );
    assert!((uv - expected).length() < 1e-15, "{uv} != {expected}");
    let fisheye = Camera::new(
        Frame::CANONICAL,
        Projection::Fisheye(viewray_camera::Fisheye { fov: PI }),
        4,
        4,
    )
    .unwrap();
    assert_eq!(fisheye.image_plane_point(1, 1, DVec2::splat(0.5)), None);
}

/// `basis-missing` in the parallel families: the camera's coordinates taken as the
/// world's, so a ray starts at e + (u, v, 0) and runs along (0, 0, -1) (or the oblique
/// slant in world axes).
#[test]
fn basis_missing_takes_the_parallel_cameras_coordinates_as_the_worlds() {
    let (row, col) = (1, 6);
    let (u, v) = (
        ((6.5) / 8.0 - 0.5) * VIEWPORT.x,
        -((1.5) / 6.0 - 0.5) * VIEWPORT.y,
    );
    let ortho = right_camera(Family::Orthographic)
        .with_mistakes(Mistake::BasisMissing.into())
        .unwrap();
    let ray = ortho.generate_ray(row, col, CameraSample::CENTER).unwrap();
    assert_close(ray.origin, EYE + DVec3::new(u, v, 0.0), "ortho origin");
    assert_close(ray.direction, DVec3::NEG_Z, "ortho direction");
    let oblique = right_camera(Family::Oblique)
        .with_mistakes(Mistake::BasisMissing.into())
        .unwrap();
    let ray = oblique
        .generate_ray(row, col, CameraSample::CENTER)
        .unwrap();
    assert_close(ray.origin, EYE + DVec3::new(u, v, 0.0), "oblique origin");
    let slant = DVec3::new(-RATIO * ANGLE.cos(), -RATIO * ANGLE.sin(), -1.0);
    assert_close(ray.direction, slant, "oblique direction");
    // And without the eye too: 0 + (u, v, 0).
    let both: Mistakes = [Mistake::BasisMissing, Mistake::EyeMissing]
        .into_iter()
        .collect();
    let ray = right_camera(Family::Orthographic)
        .with_mistakes(both)
        .unwrap()
        .generate_ray(row, col, CameraSample::CENTER)
        .unwrap();
    assert_close(ray.origin, DVec3::new(u, v, 0.0), "no eye, no basis");
}
