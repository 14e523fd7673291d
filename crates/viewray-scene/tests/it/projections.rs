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
            tilt: 0.0,
            swing: 0.0,
            iris: viewray_camera::Iris::ROUND,
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

#[test]
fn a_thin_lens_tilts_swings_and_has_blades_in_degrees() {
    let lens = |text: &str| match projection(300, 200, text, None) {
        Projection::ThinLens(lens) => lens,
        other => panic!("{text}: {other:?}"),
    };
    let physical = "focal_length: 90.0, sensor: (36.0, 24.0), f_number: 4.0, focus: 5.0";
    let plain = lens(&format!("ThinLens({physical})"));
    assert_eq!((plain.tilt, plain.swing), (0.0, 0.0));
    assert_eq!(plain.iris, viewray_camera::Iris::ROUND);
    let moved = lens(&format!(
        "ThinLens({physical}, lens_tilt: 3.0, lens_swing: -2.5, blades: 6, blade_rotation: 15.0)"
    ));
    assert_eq!(moved.tilt, 3f64.to_radians());
    assert_eq!(moved.swing, (-2.5f64).to_radians());
    assert_eq!(
        moved.iris,
        viewray_camera::Iris::from_degrees(6, 15.0).unwrap()
    );
    // Everything else is the untilted lens's.
    assert_eq!(
        ThinLens {
            tilt: 0.0,
            swing: 0.0,
            iris: viewray_camera::Iris::ROUND,
            ..moved
        },
        plain
    );
    // A negative rotation, or more than a turn, is the same polygon: wrapped into
    // [-180, 180) degrees.
    let wrapped = |degrees: &str| {
        lens(&format!(
            "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0, blades: 5, blade_rotation: {degrees})"
        ))
        .iris
        .rotation
    };
    assert_eq!(wrapped("-30.0"), (-30f64).to_radians());
    assert_eq!(wrapped("330.0"), (-30f64).to_radians());
    assert_eq!(wrapped("690.0"), (-30f64).to_radians());
    assert_eq!(wrapped("180.0"), (-180f64).to_radians());
    // Blades without a physical lens are fine; a tilt is not.
    assert_eq!(
        lens("ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0, blades: 3)")
            .iris
            .blades,
        3
    );
}

#[test]
fn bad_tilts_and_blades_name_the_camera_s_line_and_column() {
    let error = |projection: &str| {
        let text = format!(
            "(image: (width: 30, height: 20),\n camera: (eye: (0.0, 0.0, 5.0), \
             look_at: (0.0, 0.0, 0.0),\n    projection: {projection}))"
        );
        SceneLoader::text(&text, Path::new("lens.ron"))
            .load()
            .unwrap_err()
            .to_string()
    };
    let physical = "focal_length: 90.0, f_number: 4.0, focus: 5.0";
    assert_eq!(
        error(&format!("ThinLens({physical}, lens_tilt: 90.0)")),
        "lens.ron:2:10: camera: lens_tilt must be strictly between -90 and 90 degrees, found 90"
    );
    assert_eq!(
        error(&format!("ThinLens({physical}, lens_swing: -95.5)")),
        "lens.ron:2:10: camera: lens_swing must be strictly between -90 and 90 degrees, found \
         -95.5"
    );
    assert_eq!(
        error(&format!("ThinLens({physical}, blades: 1)")),
        "lens.ron:2:10: camera: blades must be 0 (a round lens) or 3 to 64 (a polygon), found 1"
    );
    assert_eq!(
        error(&format!("ThinLens({physical}, blades: 65)")),
        "lens.ron:2:10: camera: blades must be 0 (a round lens) or 3 to 64 (a polygon), found 65"
    );
    assert_eq!(
        error("ThinLens(focal_length: 90.0, f_number: 4.0, focus: 0.05, lens_tilt: 1.0)"),
        "lens.ron:2:10: camera: a tilted lens focuses beyond its focal length: focus must be \
         greater than the focal length d = 0.09, found 0.05"
    );
    assert!(
        error("ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0, lens_swing: 1.0)").starts_with(
            "lens.ron:2:10: camera: `lens_tilt` and `lens_swing` tilt the lens of \
                          a physical camera: give `focal_length` (mm)"
        )
    );
    // A blade count is a whole number.
    assert!(
        error(&format!("ThinLens({physical}, blades: 5.5)")).starts_with("lens.ron:3:"),
        "{}",
        error(&format!("ThinLens({physical}, blades: 5.5)"))
    );
}
