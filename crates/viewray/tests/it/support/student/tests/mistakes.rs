//! Each of the lecture's mistakes against its ray worked by hand from the catalogue's
//! formula, on a camera where it matters; and mistakes made together.

use super::{assert_vec, v};
use crate::support::student::{Aim, CameraSpec, Mistake, Projection, Vec3, frame, ray};

const CENTRE: (f64, f64) = (0.5, 0.5);

/// The ids of the catalogue, in its order.
const IDS: [&str; 22] = [
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
];

#[test]
fn the_ids_are_the_catalogues() {
    let ids: Vec<&str> = Mistake::ALL.iter().map(|m| m.id()).collect();
    assert_eq!(ids, IDS);
    for m in Mistake::ALL {
        assert_eq!(Mistake::from_id(m.id()), Some(m));
    }
    assert_eq!(Mistake::from_id("pixel-centre"), None);
}

/// Perspective, axis-aligned, with everything the pixel's mistakes can get wrong: a 4 x 2
/// image, eye (1, 2, 3) looking down -z, d = 2, a 2 x 1 viewport, shift (0.5, 0.25).
/// Pixel (row, col) = (0, 1): u = (1.5/4 - 1/2) 2 = -0.25, v = -(0.5/2 - 1/2) 1 = 0.25,
/// direction (u + 0.5, v + 0.25, -2) = (0.25, 0.5, -2).
fn pixels() -> CameraSpec {
    CameraSpec {
        eye: v(1.0, 2.0, 3.0),
        aim: Aim::View(v(0.0, 0.0, -1.0)),
        up: Vec3::Y,
        projection: Projection::Perspective {
            d: 2.0,
            viewport: (2.0, 1.0),
            shift: (0.5, 0.25),
        },
    }
}

/// Perspective, canonical but for the frame: eye (1, 2, 3) looking along -x, so
/// w = (1, 0, 0), u = up x w = (0, 0, -1), v = w x u = (0, 1, 0). In a 2 x 2 image pixel
/// (0, 0) has u = -0.25, v = 0.25 and the direction -0.25 U + 0.25 V - W = (-1, 0.25, 0.25).
fn turned() -> CameraSpec {
    CameraSpec {
        eye: v(1.0, 2.0, 3.0),
        aim: Aim::View(v(-1.0, 0.0, 0.0)),
        ..CameraSpec::canonical()
    }
}

/// Orthographic: a 4 x 2 image of a 4 x 2 viewport from (1, 2, 3) down -z. Pixel (0, 0)
/// has u = -1.5, v = 0.5: origin (-0.5, 2.5, 3), direction (0, 0, -1).
fn ortho() -> CameraSpec {
    CameraSpec {
        projection: Projection::Orthographic {
            viewport: (4.0, 2.0),
        },
        ..pixels()
    }
}

/// As [`ortho`], oblique with L = 1/2 at 60 degrees: direction
/// -W - L (cos phi U + sin phi V) = (-1/4, -sqrt(3)/4, -1).
fn oblique() -> CameraSpec {
    CameraSpec {
        projection: Projection::Oblique {
            viewport: (4.0, 2.0),
            ratio: 0.5,
            angle_degrees: 60.0,
        },
        ..pixels()
    }
}

/// One mistake's hand-worked ray: the camera, image size, pixel, and origin and
/// direction.
struct Case {
    mistakes: &'static [Mistake],
    camera: CameraSpec,
    size: (u32, u32),
    pixel: (u32, u32),
    origin: Vec3,
    direction: Vec3,
}

fn cases() -> Vec<Case> {
    use Mistake::*;
    let eye = v(1.0, 2.0, 3.0);
    let s3 = 3f64.sqrt();
    let case = |mistakes, camera, size, pixel, origin, direction| Case {
        mistakes,
        camera,
        size,
        pixel,
        origin,
        direction,
    };
    let on_pixels = |mistakes, direction| case(mistakes, pixels(), (4, 2), (0, 1), eye, direction);
    let on_turned = |mistakes, direction| case(mistakes, turned(), (2, 2), (0, 0), eye, direction);
    vec![
        // u = (1/4 - 1/2) 2 = -0.5, v = -(0/2 - 1/2) = 0.5.
        on_pixels(&[PixelCorner], v(0.0, 0.75, -2.0)),
        // u = (2/4 - 1/2) 2 = 0, v = -(1/2 - 1/2) = 0.
        on_pixels(&[PixelOneBased], v(0.5, 0.25, -2.0)),
        // u = (1/3 - 1/2) 2 = -1/3, v = -(0/1 - 1/2) = 0.5.
        on_pixels(&[SizeMinusOne], v(1.0 / 6.0, 0.75, -2.0)),
        // v = +(0.5/2 - 1/2) = -0.25.
        on_pixels(&[VSign], v(0.25, 0.0, -2.0)),
        // u = -(1.5/4 - 1/2) 2 = 0.25.
        on_pixels(&[USign], v(0.75, 0.5, -2.0)),
        // u = (0.5/4 - 1/2) 2 = -0.75, v = -(1.5/2 - 1/2) 1 = -0.25.
        on_pixels(&[IJSwapped], v(-0.25, 0.0, -2.0)),
        // u = (1.5/4 - 1/2) = -0.125, v = 0.25.
        on_pixels(&[ViewportMissing], v(0.375, 0.5, -2.0)),
        // vw = 1, vh = 2: u = -0.125, v = 0.5.
        on_pixels(&[ViewportSwapped], v(0.375, 0.75, -2.0)),
        on_pixels(&[DistanceMissing], v(0.25, 0.5, -1.0)),
        on_pixels(&[DistanceSign], v(0.25, 0.5, 2.0)),
        case(
            &[EyeMissing],
            pixels(),
            (4, 2),
            (0, 1),
            Vec3::ZERO,
            v(0.25, 0.5, -2.0),
        ),
        // Orthographic: 0 + u U + v V.
        case(
            &[EyeMissing],
            ortho(),
            (4, 2),
            (0, 0),
            v(-1.5, 0.5, 0.0),
            v(0.0, 0.0, -1.0),
        ),
        // (u, v, -d) in world coordinates.
        on_turned(&[BasisMissing], v(-0.25, 0.25, -1.0)),
        // Orthographic, looking along -x: e + (u, v, 0) and (0, 0, -1), where the frame
        // gives e + u (0, 0, -1) + v (0, 1, 0) = (1, 2.5, 4.5) and (-1, 0, 0).
        case(
            &[BasisMissing],
            CameraSpec {
                aim: Aim::View(v(-1.0, 0.0, 0.0)),
                ..ortho()
            },
            (4, 2),
            (0, 0),
            v(-0.5, 2.5, 3.0),
            v(0.0, 0.0, -1.0),
        ),
        // w = (-1, 0, 0), u = up x w = (0, 0, 1), v = w x u = (0, 1, 0).
        on_turned(&[WView], v(1.0, 0.25, -0.25)),
        // u = w x up = (0, 0, 1), v = w x u = (0, -1, 0).
        on_turned(&[UCrossOrder], v(-1.0, -0.25, -0.25)),
        // v = u x w = (0, -1, 0).
        on_turned(&[VCrossOrder], v(-1.0, -0.25, 0.25)),
        // up = (0, 2, 0): u = up x w = (0, 0, -2), v = w x u = (0, 2, 0).
        case(
            &[UNotNormalized],
            CameraSpec {
                up: v(0.0, 2.0, 0.0),
                ..turned()
            },
            (2, 2),
            (0, 0),
            eye,
            v(-1.0, 0.5, 0.5),
        ),
        // Shift (-0.5, -0.25).
        on_pixels(&[ShiftSign], v(-0.75, 0.0, -2.0)),
        on_pixels(&[ShiftMissing], v(-0.25, 0.25, -2.0)),
        case(
            &[OrthoOriginFixed],
            ortho(),
            (4, 2),
            (0, 0),
            eye,
            v(0.0, 0.0, -1.0),
        ),
        // u U + v V - W from e.
        case(
            &[OrthoAsPerspective],
            ortho(),
            (4, 2),
            (0, 0),
            eye,
            v(-1.5, 0.5, -1.0),
        ),
        case(
            &[ObliqueSign],
            oblique(),
            (4, 2),
            (0, 0),
            v(-0.5, 2.5, 3.0),
            v(0.25, s3 / 4.0, -1.0),
        ),
        case(
            &[ObliqueAsOrtho],
            oblique(),
            (4, 2),
            (0, 0),
            v(-0.5, 2.5, 3.0),
            v(0.0, 0.0, -1.0),
        ),
        // Together, each at its step. u = -0.5 (corner), v = +(0/2 - 1/2) = -0.5 (sign).
        on_pixels(&[PixelCorner, VSign], v(0.0, -0.25, -2.0)),
        on_pixels(&[USign, VSign], v(0.75, 0.0, -2.0)),
        // vw = 1, vh = 2 and u from the row: u = (0.5/4 - 1/2) 1, v = -(1.5/2 - 1/2) 2.
        on_pixels(&[ViewportSwapped, IJSwapped], v(0.125, -0.25, -2.0)),
        case(
            &[ShiftMissing, DistanceMissing, EyeMissing],
            pixels(),
            (4, 2),
            (0, 1),
            Vec3::ZERO,
            v(-0.25, 0.25, -1.0),
        ),
        on_pixels(&[ShiftSign, DistanceSign], v(-0.75, 0.0, 2.0)),
        // The frame is wrong, but not used.
        on_turned(&[WView, BasisMissing], v(-0.25, 0.25, -1.0)),
        // u = (w x up) unnormalized = (0, 0, 2) with up = (0, 2, 0), v = w x u = (0, -2, 0).
        case(
            &[UCrossOrder, UNotNormalized],
            CameraSpec {
                up: v(0.0, 2.0, 0.0),
                ..turned()
            },
            (2, 2),
            (0, 0),
            eye,
            v(-1.0, -0.5, -0.5),
        ),
    ]
}

#[test]
fn each_mistake_gives_its_hand_worked_ray() {
    for c in cases() {
        let what = format!(
            "{:?}",
            c.mistakes.iter().map(|m| m.id()).collect::<Vec<_>>()
        );
        let mistaken = ray(&c.camera, c.mistakes, c.size, c.pixel, CENTRE);
        assert_vec(mistaken.origin, c.origin, &format!("{what}: origin"));
        assert_vec(
            mistaken.direction,
            c.direction,
            &format!("{what}: direction"),
        );
        // The camera is one where the mistake matters.
        let right = ray(&c.camera, &[], c.size, c.pixel, CENTRE);
        assert!(
            right != mistaken,
            "{what} changes nothing on {:?}",
            c.camera
        );
    }
}

#[test]
fn every_mistake_has_a_hand_worked_case_of_its_own() {
    let cases = cases();
    for m in Mistake::ALL {
        assert!(
            cases.iter().any(|c| c.mistakes == [m]),
            "{} has no case of its own",
            m.id()
        );
    }
}

#[test]
fn the_frames_mistakes() {
    use Mistake::*;
    let f = |mistakes: &[Mistake]| {
        let f = frame(&turned(), mistakes);
        [f.u, f.v, f.w]
    };
    let x = Vec3::X;
    assert_eq!(f(&[]), [v(0.0, 0.0, -1.0), Vec3::Y, x]);
    assert_eq!(f(&[WView]), [Vec3::Z, Vec3::Y, -x]);
    assert_eq!(f(&[UCrossOrder]), [Vec3::Z, -Vec3::Y, x]);
    assert_eq!(f(&[VCrossOrder]), [v(0.0, 0.0, -1.0), -Vec3::Y, x]);
    // The eye is the eye whatever the mistakes: eye-missing is the ray's.
    assert_eq!(frame(&turned(), &[EyeMissing]).e, v(1.0, 2.0, 3.0));
}

/// The mistakes that drop the 1/2 keep a sample's offset from the centre: the sample at
/// (0.25, 0.75) of pixel (0, 1) is at x = 1 - 0.25, y = 0 + 0.25 with pixel-corner, where
/// it is at x = 1.25, y = 0.75 without.
#[test]
fn a_samples_offset_moves_with_the_mistaken_point() {
    let offset = (0.25, 0.75);
    let right = ray(&pixels(), &[], (4, 2), (0, 1), offset);
    // u = (1.25/4 - 1/2) 2 = -0.375, v = -(0.75/2 - 1/2) = 0.125.
    assert_vec(right.direction, v(0.125, 0.375, -2.0), "correct");
    let corner = ray(&pixels(), &[Mistake::PixelCorner], (4, 2), (0, 1), offset);
    // u = (0.75/4 - 1/2) 2 = -0.625, v = -(0.25/2 - 1/2) = 0.375.
    assert_vec(corner.direction, v(-0.125, 0.625, -2.0), "pixel-corner");
}

/// A mistake of another family leaves the rays alone.
#[test]
fn a_mistake_of_another_family_changes_nothing() {
    for m in Mistake::ALL {
        for camera in [pixels(), ortho(), oblique()] {
            if !m.applies_to(&camera.projection) {
                assert_eq!(
                    ray(&camera, &[m], (4, 2), (0, 1), CENTRE),
                    ray(&camera, &[], (4, 2), (0, 1), CENTRE),
                    "{} on {:?}",
                    m.id(),
                    camera.projection
                );
            }
        }
    }
    assert!(!Mistake::ShiftSign.applies_to(&ortho().projection));
    assert!(!Mistake::OrthoOriginFixed.applies_to(&oblique().projection));
    assert!(Mistake::ObliqueSign.applies_to(&oblique().projection));
    assert!(Mistake::EyeMissing.applies_to(&ortho().projection));
}
