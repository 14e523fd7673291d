//! Every spelling of a perspective camera in a scene file gives the camera crate's
//! projection for the image's aspect ratio (the formulas are tested there).

use std::path::Path;

use glam::DVec2;
use viewray_camera::{FovAxis, Perspective, Projection, SensorFit, ThinLens};
use viewray_scene::{LoadOptions, SceneLoader};

fn projection(width: u32, height: u32, projection: &str, size: Option<(u32, u32)>) -> Projection {
    let text = format!(
        "(image: (width: {width}, height: {height}), camera: (eye: (0.0, 0.0, 5.0), \
         look_at: (0.0, 0.0, 0.0), projection: {projection}))"
    );
    let options = LoadOptions {
        size,
        ..LoadOptions::default()
    };
    let scene = SceneLoader::text(&text, Path::new("test.ron"))
        .options(options)
        .load()
        .unwrap_or_else(|e| panic!("{projection}: {e}"))
        .scene;
    *scene.camera().projection()
}

#[track_caller]
fn check(text: &str, expected: Perspective) {
    assert_eq!(
        projection(640, 480, text, None),
        Projection::Perspective(expected),
        "{text}"
    );
}

#[test]
fn fields_of_view_on_every_axis() {
    let aspect = 640.0 / 480.0;
    for (name, axis) in [
        ("fov_x", FovAxis::X),
        ("fov_y", FovAxis::Y),
        ("fov_diagonal", FovAxis::Diagonal),
        ("fov_smaller", FovAxis::Smaller),
        ("fov_larger", FovAxis::Larger),
    ] {
        let expected = Perspective::from_fov(axis, 50f64.to_radians(), aspect).unwrap();
        check(&format!("Perspective({name}: 50.0)"), expected);
    }
}

#[test]
fn a_field_of_view_keeps_its_angle_at_any_distance() {
    let mut expected = Perspective::from_fov(FovAxis::Y, 40f64.to_radians(), 4.0 / 3.0).unwrap();
    expected.distance = 2.0;
    expected.viewport *= 2.0;
    expected.shift = DVec2::new(0.1, 0.2);
    check(
        "Perspective(distance: 2.0, fov_y: 40.0, shift: (0.1, 0.2))",
        expected,
    );
}

#[test]
fn physical_cameras_fit_their_sensor_to_the_image() {
    let aspect = 640.0 / 480.0;
    let sensor = DVec2::new(36.0, 24.0);
    for (name, fit) in [
        ("Auto", SensorFit::Auto),
        ("Horizontal", SensorFit::Horizontal),
        ("Vertical", SensorFit::Vertical),
    ] {
        let expected = Perspective::from_focal_length(35.0, sensor, fit, aspect).unwrap();
        check(
            &format!("Perspective(focal_length: 35.0, sensor: (36.0, 24.0), fit: {name})"),
            expected,
        );
    }
    // The sensor defaults to Blender's 36 x 24 mm and the fit to Auto.
    check(
        "Perspective(focal_length: 35.0)",
        Perspective::from_focal_length(35.0, sensor, SensorFit::Auto, aspect).unwrap(),
    );
}

#[test]
fn a_thin_lens_takes_an_f_number() {
    let text = "ThinLens(focal_length: 50.0, sensor: (36.0, 24.0), f_number: 2.8, focus: 5.0)";
    let pinhole =
        Perspective::from_focal_length(50.0, DVec2::new(36.0, 24.0), SensorFit::Auto, 1.5).unwrap();
    assert_eq!(
        projection(300, 200, text, None),
        Projection::ThinLens(ThinLens {
            distance: 0.05,
            viewport: pinhole.viewport,
            shift: DVec2::ZERO,
            aperture: viewray_camera::aperture_from_f_number(50.0, 2.8).unwrap(),
            focus: 5.0,
        })
    );
}

#[test]
fn the_viewport_follows_a_new_image_size() {
    // As for fov_y: --size changes the aspect ratio, and the viewport follows it.
    for text in [
        "Perspective(fov_diagonal: 60.0)",
        "Perspective(focal_length: 50.0, fit: Vertical)",
    ] {
        let Projection::Perspective(p) = projection(640, 480, text, Some((200, 400))) else {
            panic!("{text}: not a perspective camera");
        };
        assert!((p.viewport.x / p.viewport.y - 0.5).abs() < 1e-12, "{text}");
    }
}
