//! Fields of view on every axis and physical cameras, checked against hand-worked values.

use glam::DVec2;
use viewray_camera::{CameraError, FovAxis, Perspective, SensorFit, aperture_from_f_number};

/// Within a few units in the last place of numbers near 1.
#[track_caller]
fn close(actual: f64, expected: f64) {
    assert!(
        (actual - expected).abs() <= 1e-12 * expected.abs().max(1.0),
        "{actual} != {expected}"
    );
}

#[track_caller]
fn check_fov(axis: FovAxis, degrees: f64, aspect: f64, (vw, vh): (f64, f64)) {
    let p = Perspective::from_fov(axis, degrees.to_radians(), aspect).unwrap();
    assert_eq!(p.distance, 1.0);
    assert_eq!(p.shift, DVec2::ZERO);
    close(p.viewport.x, vw);
    close(p.viewport.y, vh);
}

#[test]
fn a_field_of_view_spans_the_extent_it_names() {
    // 90 degrees: 2 tan(45) = 2 across the named extent.
    check_fov(FovAxis::X, 90.0, 2.0, (2.0, 1.0));
    check_fov(FovAxis::Y, 90.0, 2.0, (4.0, 2.0));
    // A 4:3 viewport with a diagonal of 2 is 1.6 x 1.2 (the 3-4-5 triangle).
    check_fov(FovAxis::Diagonal, 90.0, 4.0 / 3.0, (1.6, 1.2));
    // Landscape: the smaller side is the height, the larger the width.
    check_fov(FovAxis::Smaller, 90.0, 2.0, (4.0, 2.0));
    check_fov(FovAxis::Larger, 90.0, 2.0, (2.0, 1.0));
    // Portrait (1:2): the other way round.
    check_fov(FovAxis::Smaller, 90.0, 0.5, (2.0, 4.0));
    check_fov(FovAxis::Larger, 90.0, 0.5, (1.0, 2.0));
    // Square: every side-bound axis gives the same viewport.
    for axis in [FovAxis::X, FovAxis::Y, FovAxis::Smaller, FovAxis::Larger] {
        check_fov(axis, 90.0, 1.0, (2.0, 2.0));
    }
    // 60 degrees vertically on 16:9: vh = 2 tan(30) = 2 / sqrt 3.
    let vh = 2.0 / 3f64.sqrt();
    check_fov(FovAxis::Y, 60.0, 16.0 / 9.0, (16.0 / 9.0 * vh, vh));
}

#[test]
fn fov_reads_back_the_angle_on_each_axis() {
    let p = Perspective::from_fov(FovAxis::Diagonal, 1.0, 1.5).unwrap();
    close(p.fov(FovAxis::Diagonal), 1.0);
    let p = Perspective::from_fov(FovAxis::X, 0.7, 0.8).unwrap();
    close(p.fov(FovAxis::X), 0.7);
    close(p.fov(FovAxis::Larger), p.fov(FovAxis::Y));
}

#[test]
fn mitsuba_35mm_equivalent_focal_length_is_a_diagonal_field_of_view() {
    // Mitsuba 3 turns `focal_length="50mm"` into a diagonal field of view of a 36 x 24 mm
    // frame, 2 atan(sqrt(36^2 + 24^2) / 100); on a 3:2 image that is the horizontal
    // 2 atan(18 / 50) = 39.5977 degrees (Mitsuba's own test_sensor.py).
    let diagonal = 2.0 * (36f64.hypot(24.0) / 100.0).atan();
    let p = Perspective::from_fov(FovAxis::Diagonal, diagonal, 1.5).unwrap();
    // Mitsuba computes it in single precision: 39.597713; in double it is 39.5977527.
    assert!((p.fov(FovAxis::X).to_degrees() - 39.597_713).abs() < 1e-4);
    close(p.fov(FovAxis::X), 2.0 * (0.36f64).atan());
}

#[track_caller]
fn check_physical(sensor: (f64, f64), fit: SensorFit, aspect: f64, (vw, vh): (f64, f64)) {
    let p = Perspective::from_focal_length(50.0, DVec2::from(sensor), fit, aspect).unwrap();
    close(p.distance, 0.05);
    close(p.viewport.x, vw);
    close(p.viewport.y, vh);
}

#[test]
fn a_physical_camera_puts_its_sensor_at_the_focal_length() {
    // Blender's default: 50 mm on a 36 mm sensor, horizontally, sees 39.598 degrees.
    let p =
        Perspective::from_focal_length(50.0, DVec2::new(36.0, 24.0), SensorFit::Horizontal, 1.5)
            .unwrap();
    assert_eq!(p.distance, 0.05);
    close(p.viewport.x, 0.036);
    close(p.viewport.y, 0.024);
    assert!((p.fov(FovAxis::X).to_degrees() - 39.598).abs() < 5e-4);
    close(p.fov(FovAxis::X), 2.0 * (0.36f64).atan());
    // 16:9 with horizontal fit: the sensor's width, 36 x 20.25 mm of it.
    check_physical(
        (36.0, 24.0),
        SensorFit::Horizontal,
        16.0 / 9.0,
        (0.036, 0.020_25),
    );
    // Vertical fit: the sensor's height spans the image's height.
    check_physical(
        (36.0, 24.0),
        SensorFit::Vertical,
        16.0 / 9.0,
        (0.024 * 16.0 / 9.0, 0.024),
    );
    // Auto: the sensor WIDTH spans the longer side, whichever it is (Blender's AUTO).
    check_physical((36.0, 24.0), SensorFit::Auto, 1.5, (0.036, 0.024));
    check_physical((36.0, 24.0), SensorFit::Auto, 0.5, (0.018, 0.036));
    check_physical((36.0, 24.0), SensorFit::Auto, 1.0, (0.036, 0.036));
}

#[test]
fn the_f_number_gives_the_lens_radius_in_metres() {
    // 50 mm at f/2.8: a 17.86 mm wide opening, radius 8.93 mm.
    close(aperture_from_f_number(50.0, 2.8).unwrap(), 0.05 / 5.6);
    close(aperture_from_f_number(35.0, 1.0).unwrap(), 0.0175);
}

#[test]
fn bad_values_are_errors() {
    assert_eq!(
        Perspective::from_fov(FovAxis::Diagonal, std::f64::consts::PI, 1.0),
        Err(CameraError::OutOfRange {
            name: "fov_diagonal",
            expected: "between 0 and 180 degrees",
            value: 180.0
        })
    );
    assert_eq!(
        Perspective::from_focal_length(0.0, DVec2::new(36.0, 24.0), SensorFit::Auto, 1.0),
        Err(CameraError::NotPositive {
            name: "focal_length",
            value: 0.0
        })
    );
    assert_eq!(
        aperture_from_f_number(50.0, -1.0),
        Err(CameraError::NotPositive {
            name: "f_number",
            value: -1.0
        })
    );
}

#[test]
fn fov_reads_back_wide_and_narrow_angles_on_every_axis() {
    // 120 degrees across x, d = 1: vw = 2 tan 60 = 2 sqrt 3, wider than 2 d.
    let p = Perspective::from_fov(FovAxis::X, 120f64.to_radians(), 2.0).unwrap();
    close(p.viewport.x, 2.0 * 3f64.sqrt());
    close(p.fov(FovAxis::X).to_degrees(), 120.0);
    close(p.fov(FovAxis::Larger).to_degrees(), 120.0);
    // vh = sqrt 3: 2 atan(sqrt 3 / 2).
    close(p.fov(FovAxis::Y), 2.0 * (3f64.sqrt() / 2.0).atan());
    close(p.fov(FovAxis::Smaller), 2.0 * (3f64.sqrt() / 2.0).atan());
    // The diagonal: sqrt(12 + 3) = sqrt 15.
    close(p.fov(FovAxis::Diagonal), 2.0 * (15f64.sqrt() / 2.0).atan());

    // Blender's 50 mm lens on 36 x 24 mm: d = 0.05, a landscape viewport 0.036 x 0.024.
    let p =
        Perspective::from_focal_length(50.0, DVec2::new(36.0, 24.0), SensorFit::Horizontal, 1.5)
            .unwrap();
    close(p.fov(FovAxis::Larger), 2.0 * (18.0f64 / 50.0).atan());
    close(p.fov(FovAxis::Smaller), 2.0 * (12.0f64 / 50.0).atan());
    close(p.fov(FovAxis::Y), 2.0 * (12.0f64 / 50.0).atan());
    close(
        p.fov(FovAxis::Diagonal),
        2.0 * (36f64.hypot(24.0) / 100.0).atan(),
    );
    // Portrait, 24 x 36 mm of sensor (Auto fit, aspect 2/3): the larger side is y.
    let p =
        Perspective::from_focal_length(50.0, DVec2::new(36.0, 24.0), SensorFit::Auto, 2.0 / 3.0)
            .unwrap();
    close(p.viewport.x, 0.024);
    close(p.viewport.y, 0.036);
    close(p.fov(FovAxis::Larger), 2.0 * (18.0f64 / 50.0).atan());
    close(p.fov(FovAxis::Smaller), 2.0 * (12.0f64 / 50.0).atan());
}

#[test]
fn a_field_of_view_lies_strictly_between_0_and_180_degrees() {
    let check = |axis: FovAxis, fov: f64, name: &'static str| {
        assert_eq!(
            Perspective::from_fov(axis, fov, 1.5),
            Err(CameraError::OutOfRange {
                name,
                expected: "between 0 and 180 degrees",
                value: fov.to_degrees(),
            })
        );
    };
    check(FovAxis::X, 0.0, "fov_x");
    check(FovAxis::Y, -0.5, "fov_y");
    check(FovAxis::Smaller, std::f64::consts::PI, "fov_smaller");
    check(FovAxis::Larger, 4.0, "fov_larger");
    check(FovAxis::Diagonal, 0.0, "fov_diagonal");
    assert_eq!(
        Perspective::from_fov(FovAxis::X, f64::NAN, 1.0),
        Err(CameraError::NotFinite {
            name: "fov_x",
            value: "NaN".into()
        })
    );
    assert_eq!(
        Perspective::from_fov(FovAxis::Y, 1.0, 0.0),
        Err(CameraError::NotPositive {
            name: "aspect",
            value: 0.0
        })
    );
    // Just inside both ends is fine: 2 tan(fov / 2) of a tiny and of a huge angle.
    let tiny = Perspective::from_fov(FovAxis::Y, 1e-6, 1.0).unwrap();
    assert!((tiny.viewport.y - 1e-6).abs() < 1e-15);
    let wide = Perspective::from_fov(FovAxis::Y, std::f64::consts::PI - 1e-6, 1.0).unwrap();
    assert!((wide.viewport.y - 2.0 / (0.5e-6f64).tan()).abs() < 1.0);
}

#[test]
fn from_fov_x_and_from_fov_y_name_their_axis() {
    // 2 tan(30 degrees) = 2 / sqrt 3 across the named side, the other from a = 16/9.
    let t = 2.0 / 3f64.sqrt();
    let a = 16.0 / 9.0;
    let x = Perspective::from_fov_x(60f64.to_radians(), a).unwrap();
    close(x.viewport.x, t);
    close(x.viewport.y, t / a);
    let y = Perspective::from_fov_y(60f64.to_radians(), a).unwrap();
    close(y.viewport.x, a * t);
    close(y.viewport.y, t);
    assert_eq!((x.distance, y.distance), (1.0, 1.0));
}

#[test]
fn axes_and_fits_are_spelled_as_scene_files_spell_them() {
    let axes = [
        (FovAxis::X, "x"),
        (FovAxis::Y, "y"),
        (FovAxis::Diagonal, "diagonal"),
        (FovAxis::Smaller, "smaller"),
        (FovAxis::Larger, "larger"),
    ];
    for (axis, name) in axes {
        assert_eq!(axis.name(), name);
    }
    let fits = [
        (SensorFit::Auto, "Auto"),
        (SensorFit::Horizontal, "Horizontal"),
        (SensorFit::Vertical, "Vertical"),
    ];
    for (fit, name) in fits {
        assert_eq!(fit.name(), name);
    }
    assert_eq!(SensorFit::default(), SensorFit::Auto);
    // Smaller and Larger resolve by the aspect ratio; a square counts as landscape.
    for (aspect, smaller, larger) in [
        (1.5, FovAxis::Y, FovAxis::X),
        (1.0, FovAxis::Y, FovAxis::X),
        (0.75, FovAxis::X, FovAxis::Y),
    ] {
        assert_eq!(FovAxis::Smaller.resolve(aspect), smaller, "{aspect}");
        assert_eq!(FovAxis::Larger.resolve(aspect), larger, "{aspect}");
        for axis in [FovAxis::X, FovAxis::Y, FovAxis::Diagonal] {
            assert_eq!(axis.resolve(aspect), axis);
        }
    }
}

#[test]
fn every_bad_physical_value_is_named() {
    let sensor = DVec2::new(36.0, 24.0);
    let check = |got: Result<Perspective, CameraError>, name: &'static str, value: f64| {
        assert_eq!(got, Err(CameraError::NotPositive { name, value }));
    };
    let physical = Perspective::from_focal_length;
    check(
        physical(-50.0, sensor, SensorFit::Auto, 1.5),
        "focal_length",
        -50.0,
    );
    check(
        physical(50.0, DVec2::new(0.0, 24.0), SensorFit::Auto, 1.5),
        "sensor width",
        0.0,
    );
    check(
        physical(50.0, DVec2::new(36.0, -1.0), SensorFit::Auto, 1.5),
        "sensor height",
        -1.0,
    );
    check(
        physical(50.0, sensor, SensorFit::Vertical, 0.0),
        "aspect",
        0.0,
    );
    assert_eq!(
        aperture_from_f_number(0.0, 2.8),
        Err(CameraError::NotPositive {
            name: "focal_length",
            value: 0.0
        })
    );
    // r = f / (2 N) / 1000: 80 mm at f/4 is 10 mm.
    close(aperture_from_f_number(80.0, 4.0).unwrap(), 0.01);
}
