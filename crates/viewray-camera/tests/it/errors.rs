//! Every invalid parameter of every family is an error that names it in the lecture's
//! notation, and the smallest valid values are accepted.

use std::f64::consts::PI;

use glam::{DVec2, DVec3};
use viewray_camera::CameraError::{self, Image, NotFinite, NotPositive, OutOfRange};
use viewray_camera::ImageLimitError::Empty;
use viewray_camera::{
    Camera, Fisheye, Frame, Lens, Oblique, Orthographic, Perspective, Projection, ThinLens,
};

#[track_caller]
fn check(projection: Projection, expected: Result<(), CameraError>) {
    assert_eq!(projection.validate(), expected, "{projection:?}");
    // Camera::new checks the same, and says the same.
    assert_eq!(
        Camera::new(Frame::CANONICAL, projection, 4, 3).map(|_| ()),
        expected,
        "{projection:?}"
    );
}

fn not_positive(name: &'static str, value: f64) -> Result<(), CameraError> {
    Err(NotPositive { name, value })
}

fn not_finite(name: &'static str, value: &str) -> Result<(), CameraError> {
    Err(NotFinite {
        name,
        value: value.to_owned(),
    })
}

fn perspective(distance: f64, viewport: (f64, f64), shift: (f64, f64)) -> Perspective {
    Perspective {
        distance,
        viewport: viewport.into(),
        shift: shift.into(),
    }
}

#[test]
fn perspective_parameters() {
    let p = |d, viewport, shift| Projection::Perspective(perspective(d, viewport, shift));
    check(p(1.0, (1.0, 1.0), (0.0, 0.0)), Ok(()));
    check(p(1e-9, (1e-9, 1e-9), (-5.0, 5.0)), Ok(()));
    check(p(0.0, (1.0, 1.0), (0.0, 0.0)), not_positive("d", 0.0));
    check(p(-2.0, (1.0, 1.0), (0.0, 0.0)), not_positive("d", -2.0));
    check(p(f64::NAN, (1.0, 1.0), (0.0, 0.0)), not_finite("d", "NaN"));
    check(p(1.0, (0.0, 1.0), (0.0, 0.0)), not_positive("vw", 0.0));
    check(p(1.0, (1.0, -1.0), (0.0, 0.0)), not_positive("vh", -1.0));
    check(
        p(1.0, (1.0, f64::INFINITY), (0.0, 0.0)),
        not_finite("vh", "inf"),
    );
    check(
        p(1.0, (1.0, 1.0), (f64::NAN, 0.0)),
        not_finite("shift", "(NaN, 0)"),
    );
    check(
        p(1.0, (1.0, 1.0), (0.0, f64::NEG_INFINITY)),
        not_finite("shift", "(0, -inf)"),
    );
}

#[test]
fn thin_lens_parameters() {
    let lens = |pinhole: Perspective, aperture, focus| {
        Projection::ThinLens(ThinLens {
            distance: pinhole.distance,
            viewport: pinhole.viewport,
            shift: pinhole.shift,
            aperture,
            focus,
            tilt: 0.0,
            swing: 0.0,
            iris: viewray_camera::Iris::ROUND,
        })
    };
    let good = perspective(1.0, (1.0, 1.0), (0.0, 0.0));
    check(lens(good, 0.1, 5.0), Ok(()));
    // The pinhole's own parameters first.
    check(
        lens(perspective(0.0, (1.0, 1.0), (0.0, 0.0)), 0.1, 5.0),
        not_positive("d", 0.0),
    );
    check(
        lens(perspective(1.0, (1.0, 0.0), (0.0, 0.0)), 0.1, 5.0),
        not_positive("vh", 0.0),
    );
    check(lens(good, 0.0, 5.0), not_positive("aperture", 0.0));
    check(lens(good, f64::NAN, 5.0), not_finite("aperture", "NaN"));
    check(lens(good, 0.1, -1.0), not_positive("focus", -1.0));
    check(lens(good, 0.1, f64::INFINITY), not_finite("focus", "inf"));
}

#[test]
fn orthographic_parameters() {
    let ortho = |viewport: (f64, f64), lens: Option<(f64, f64)>| {
        Projection::Orthographic(Orthographic {
            viewport: viewport.into(),
            lens: lens.map(|(aperture, focus)| Lens { aperture, focus }),
        })
    };
    check(ortho((4.0, 3.0), None), Ok(()));
    check(ortho((4.0, 3.0), Some((0.1, 2.0))), Ok(()));
    check(ortho((0.0, 3.0), None), not_positive("vw", 0.0));
    check(ortho((4.0, f64::NAN), None), not_finite("vh", "NaN"));
    check(
        ortho((4.0, 3.0), Some((0.0, 2.0))),
        not_positive("aperture", 0.0),
    );
    check(
        ortho((4.0, 3.0), Some((0.1, -2.0))),
        not_positive("focus", -2.0),
    );
    check(
        ortho((4.0, 3.0), Some((0.1, f64::NAN))),
        not_finite("focus", "NaN"),
    );
    // The viewport is checked before the lens.
    check(
        ortho((4.0, -3.0), Some((0.0, 2.0))),
        not_positive("vh", -3.0),
    );

    // vw = aspect * height, vh = height.
    assert_eq!(
        Orthographic::from_height(2.0, 1.5),
        Ok(Orthographic {
            viewport: DVec2::new(3.0, 2.0),
            lens: None
        })
    );
    assert_eq!(
        Orthographic::from_height(0.0, 1.5),
        Err(NotPositive {
            name: "height",
            value: 0.0
        })
    );
    assert_eq!(
        Orthographic::from_height(2.0, -1.0),
        Err(NotPositive {
            name: "aspect",
            value: -1.0
        })
    );
}

#[test]
fn oblique_parameters() {
    let oblique = |viewport: (f64, f64), ratio, angle| {
        Projection::Oblique(Oblique {
            viewport: viewport.into(),
            ratio,
            angle,
        })
    };
    check(oblique((4.0, 3.0), 0.5, 1.0), Ok(()));
    // L = 0 is an orthographic projection: allowed. So is any angle.
    check(oblique((4.0, 3.0), 0.0, -7.0), Ok(()));
    check(oblique((-4.0, 3.0), 0.5, 1.0), not_positive("vw", -4.0));
    check(oblique((4.0, 0.0), 0.5, 1.0), not_positive("vh", 0.0));
    check(
        oblique((4.0, 3.0), -0.5, 1.0),
        Err(OutOfRange {
            name: "L",
            expected: "zero or positive",
            value: -0.5,
        }),
    );
    check(oblique((4.0, 3.0), f64::NAN, 1.0), not_finite("L", "NaN"));
    check(
        oblique((4.0, 3.0), 0.5, f64::INFINITY),
        not_finite("phi", "inf"),
    );
}

#[test]
fn panoramic_parameters() {
    check(Projection::Equirectangular, Ok(()));
    check(Projection::Fisheye(Fisheye { fov: PI }), Ok(()));
    check(
        Projection::Fisheye(Fisheye { fov: f64::NAN }),
        not_finite("fov", "NaN"),
    );
    check(
        Projection::Fisheye(Fisheye { fov: 7.0 }),
        Err(OutOfRange {
            name: "fov",
            expected: "in (0, 360] degrees",
            value: 7f64.to_degrees(),
        }),
    );
}

#[test]
fn image_size_and_eye() {
    let projection = Projection::Perspective(Perspective::CANONICAL);
    let new = |frame, width, height| Camera::new(frame, projection, width, height);
    assert_eq!(
        new(Frame::CANONICAL, 0, 3),
        Err(Image(Empty {
            width: 0,
            height: 3
        }))
    );
    assert_eq!(
        new(Frame::CANONICAL, 4, 0),
        Err(Image(Empty {
            width: 4,
            height: 0
        }))
    );
    // A frame is finite where it is made, so no camera has a NaN eye.
    assert_eq!(
        Frame::CANONICAL.with_eye(DVec3::new(0.0, f64::NAN, 0.0)),
        Err(NotFinite {
            name: "eye",
            value: "(0, NaN, 0)".into()
        })
    );
    // One pixel is enough.
    let camera = new(Frame::CANONICAL, 1, 1).unwrap();
    assert_eq!((camera.width(), camera.height()), (1, 1));
    let camera = new(Frame::CANONICAL, 4, 3).unwrap();
    assert_eq!((camera.width(), camera.height()), (4, 3));
    assert_eq!(*camera.frame(), Frame::CANONICAL);
    assert_eq!(*camera.projection(), projection);
    assert_eq!(Camera::canonical(4, 3), Ok(camera));
    // Resizing keeps the camera and checks the new size.
    let resized = camera.with_image_size(8, 2).unwrap();
    assert_eq!((resized.width(), resized.height()), (8, 2));
    assert_eq!(*resized.projection(), projection);
    assert_eq!(
        camera.with_image_size(8, 0),
        Err(Image(Empty {
            width: 8,
            height: 0
        }))
    );
    assert_eq!(
        Camera::canonical(0, 0),
        Err(Image(Empty {
            width: 0,
            height: 0
        }))
    );
}
