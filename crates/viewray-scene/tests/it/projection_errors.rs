//! Every way a scene file can get a projection's fields wrong, and every way two keys of an
//! animation can be written too differently to mix, with the sentence each gets. The
//! sentences are snapshots: the fields are read and mixed by code of their own, and this
//! table is what says that the scene format's words did not change with it.

use std::path::Path;

use viewray_scene::{SceneLoader, parse_camera};

/// `projection` inside an explicit camera, parsed alone for a 64 x 48 image.
fn camera_error(projection: &str) -> String {
    let text = format!("(eye: (0.0, 0.0, 5.0), view: (0.0, 0.0, -1.0), projection: {projection})");
    match parse_camera(&text, Path::new("camera"), 64, 48) {
        Ok(_) => "ok".to_owned(),
        Err(error) => error.to_string(),
    }
}

/// An animation of two keys, the first with projection `a` and the second with `b`.
fn mix_error(a: &str, b: &str) -> String {
    let key = |t: f64, projection: &str| {
        format!(
            "(t: {t:?}, camera: (eye: (0.0, 0.0, 5.0), view: (0.0, 0.0, -1.0), \
             projection: {projection}))"
        )
    };
    let text = format!(
        "(camera: (eye: (0.0, 0.0, 5.0), view: (0.0, 0.0, -1.0), projection: {a}),\n\
         animation: (keys: [\n{},\n{},\n]))",
        key(0.0, a),
        key(1.0, b)
    );
    match SceneLoader::text(&text, Path::new("mix.ron")).load() {
        Ok(_) => "ok".to_owned(),
        Err(error) => error.to_string(),
    }
}

const PROJECTIONS: &[&str] = &[
    // The fields themselves.
    "Perspective(fov_z: 40.0)",
    "Perspective(fov_y: 40.0, fov_y: 30.0)",
    "Perspective(distance: 1.0, distance: 2.0, viewport: (1.0, 1.0))",
    "Perspective(shift: (0.0, 0.1), shift: (0.0, 0.2), fov_y: 40.0)",
    "Perspective(fov_y: \"wide\")",
    "Perspective(fov_y: 40)",
    "Perspective(fov_y: None)",
    "Perspective(fov_y: Some(40.0))",
    "Perspective(viewport: (1.0))",
    "Perspective(viewport: (1.0, 1.0, 1.0))",
    "Perspective(shift: 1.0, fov_y: 40.0)",
    "Perspective(fov_y: 40.0, fit: Diagonal)",
    "Perspective(focal_length: 35.0, sensor: 36.0)",
    "Perspective(1.0, (1.0, 1.0))",
    "Perspective((fov_y: 40.0))",
    "Perspective",
    "Perspective()",
    "Perspective(fov_y: 40.0,)",
    "Perspective(fov_y: 40.0",
    "Perspective(fov_y: 40.0) x",
    "Perspective(fov_y: 40.0, aperture: 0.1)",
    "Perspective(fov_y: 40.0, focus: 2.0)",
    "ThinLens(fov_y: 40.0, aperture: 0.1)",
    "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 2.0, apperture: 0.2)",
    "ThinLens(fov_y: 40.0, aperture: 0.1, aperture: 0.2, focus: 2.0)",
    "ThinLens(fov_y: 40.0, fov_y: 30.0, aperture: 0.1, focus: 2.0)",
    "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 2.0, focus: 3.0)",
    "ThinLens(fov_y: 40.0, aperture: 0.1, focus: \"far\")",
    "ThinLens(fov_y: 40.0, aperture: 0.1, focus: None)",
    "ThinLens(fov_y: 40.0, f_number: 2.8, focus: 2.0)",
    "ThinLens(focal_length: 50.0, aperture: 0.1, f_number: 2.8, focus: 2.0)",
    "ThinLens(fov_y: 40.0, focus: 2.0)",
    "ThinLens(focus: 2.0, aperture: 0.1)",
    "ThinLens(aperture: 0.1, focus: 2.0, fov_x: 40.0, viewport: (1.0, 1.0))",
    "ThinLens",
    "ThinLens()",
    "Orthographic(viewport: (1.0, 1.0), zoom: 2.0)",
    "Orthographic(viewport: (1.0, 1.0), aperture: 0.1)",
    "Orthographic(height: 2.0, height: 3.0)",
    "Oblique(viewport: (1.0, 1.0), ratio: 0.5)",
    "Oblique(height: 2.0, ratio: 0.5, angle: 45.0, angle: 30.0)",
    "Fisheye(fov: 90.0, x: 1.0)",
    "Fisheye",
    "Fisheye()",
    "Equirectangular(fov: 1.0)",
    "Equirectangular()",
    "Equirectangular",
    "Perspectiv(fov_y: 40.0)",
    "5",
    "\"Perspective\"",
    "(fov_y: 40.0)",
    "ThinLens(aperture: None, aperture: None, fov_y: 40.0, focus: 2.0)",
    "ThinLens(fov_y: 40.0, focus: 2.0, aperture: 0.1, fov_y: 1.0)",
    "ThinLens(r#focus: 2.0, fov_y: 40.0, aperture: 0.1)",
    "ThinLens(fov_y: 40.0, f_number: 2.0, f_number: 2.0, focus: 1.0)",
    "ThinLens(\"fov_y\": 40.0, focus: 1.0)",
    "ThinLens(fov_y: 40.0, aperture: 0.1 focus: 2.0)",
    "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 2.0",
    "ThinLens(zz: 1, focus: 1.0)",
    "ThinLens(focus: 1.0, zz: 1)",
    "ThinLens(focus: 1.0, aperture: 0.1, fov_y: 40.0, sensor: 1.0)",
    "ThinLens(focus: 1e400, aperture: 0.1, fov_y: 40.0)",
    "Perspective(fov_y: 40.0, fov_y: 30.0, zz: 1)",
    "Perspective(fov_y: 40.0, r#distance: 2.0)",
    "Oblique(ratio: 0.5, angle: 45.0, height: 1.0, zz: 2)",
    "Fisheye(fov: 90.0, fov: 91.0)",
    // What the fields say together.
    "Perspective(fov_y: 40.0, viewport: (1.0, 1.0))",
    "Perspective(distance: 2.0)",
    "Perspective(sensor: (36.0, 24.0), fov_y: 40.0)",
    "Perspective(focal_length: 35.0, distance: 1.0)",
    "Perspective(fov_y: 180.0)",
    "Perspective(fov_y: 40.0, distance: -1.0)",
    "Perspective(viewport: (1.0, 0.0))",
    "Perspective(focal_length: 35.0, sensor: (36.0, 24.0), fit: Vertical, shift: (0.1, 0.0))",
    "ThinLens(fov_y: 40.0, aperture: -0.1, focus: 2.0)",
    "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 0.0)",
    "ThinLens(focal_length: 50.0, f_number: 0.0, focus: 2.0)",
    // A tilted lens and its blades.
    "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, lens_tilt: 5.0, lens_tilt: 6.0)",
    "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, blades: 6.0)",
    "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, blades: -6)",
    "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, blade_rotation: \"up\")",
    "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 2.0, lens_swing: 3.0)",
    "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, blades: 2)",
    "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, lens_tilt: -90.0)",
    "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 0.05, lens_tilt: 5.0)",
];

const MIXES: &[(&str, &str)] = &[
    ("Perspective(fov_y: 40.0)", "Perspective(fov_y: 60.0)"),
    (
        "Perspective(distance: 1.0, viewport: (1.0, 1.0))",
        "Perspective(viewport: (1.0, 1.0))",
    ),
    (
        "Perspective(viewport: (1.0, 1.0))",
        "Perspective(fov_y: 40.0)",
    ),
    ("Perspective(fov_x: 40.0)", "Perspective(fov_y: 40.0)"),
    (
        "Perspective(fov_y: 40.0)",
        "Perspective(fov_diagonal: 40.0)",
    ),
    (
        "Perspective(fov_diagonal: 40.0)",
        "Perspective(fov_smaller: 40.0)",
    ),
    (
        "Perspective(fov_smaller: 40.0)",
        "Perspective(fov_larger: 40.0)",
    ),
    (
        "Perspective(fov_larger: 40.0)",
        "Perspective(focal_length: 40.0)",
    ),
    (
        "Perspective(focal_length: 40.0, sensor: (36.0, 24.0))",
        "Perspective(focal_length: 40.0)",
    ),
    (
        "Perspective(focal_length: 40.0, fit: Auto)",
        "Perspective(focal_length: 40.0)",
    ),
    (
        "Perspective(fov_y: 40.0, shift: (0.0, 0.1))",
        "Perspective(fov_y: 40.0)",
    ),
    (
        "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 2.0)",
        "ThinLens(fov_y: 40.0, aperture: 0.2, focus: 4.0)",
    ),
    (
        "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 2.0)",
        "ThinLens(fov_x: 40.0, aperture: 0.1, focus: 2.0)",
    ),
    (
        "ThinLens(focal_length: 50.0, aperture: 0.1, focus: 2.0)",
        "ThinLens(focal_length: 50.0, f_number: 2.8, focus: 2.0)",
    ),
    (
        "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, fit: Vertical)",
        "ThinLens(focal_length: 50.0, f_number: 2.8, focus: 2.0, fit: Horizontal)",
    ),
    (
        "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 2.0)",
        "Perspective(fov_y: 40.0)",
    ),
    (
        "Orthographic(viewport: (1.0, 1.0))",
        "Orthographic(height: 1.0)",
    ),
    (
        "Orthographic(height: 1.0, aperture: 0.1, focus: 2.0)",
        "Orthographic(height: 1.0)",
    ),
    (
        "Oblique(height: 1.0, ratio: 0.5, angle: 30.0)",
        "Oblique(viewport: (1.0, 1.0), ratio: 1.0, angle: 45.0)",
    ),
    (
        "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, blades: 6)",
        "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, blades: 5)",
    ),
    (
        "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, lens_tilt: 4.0)",
        "ThinLens(focal_length: 50.0, f_number: 2.0, focus: 2.0, blade_rotation: 30.0)",
    ),
    ("Fisheye(fov: 90.0)", "Fisheye(fov: 180.0)"),
    ("Equirectangular", "Equirectangular"),
    ("Equirectangular", "Fisheye(fov: 180.0)"),
];

#[test]
fn every_projection_field_error_is_worded_as_before() {
    let mut report = String::new();
    for projection in PROJECTIONS {
        report += &format!("{projection}\n    {}\n", camera_error(projection));
    }
    for (a, b) in MIXES {
        report += &format!("{a} -> {b}\n    {}\n", mix_error(a, b));
    }
    insta::assert_snapshot!(report);
}
