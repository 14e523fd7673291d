//! viewray -> tool -> viewray is the identity on rays, for every camera each format can
//! hold, and an export is refused exactly when the format cannot hold the camera.

use std::path::Path;

use glam::{DVec2, DVec3};
use proptest::prelude::*;
use viewray_camera::{Camera, Projection};
use viewray_interop::Format;
use viewray_scene::Scene;

/// A camera-only scene with `projection` (RON) on a `width x height` image.
fn scene(
    eye: DVec3,
    view: DVec3,
    up: DVec3,
    width: u32,
    height: u32,
    projection: &str,
) -> Option<Scene> {
    let text = format!(
        "(image: (width: {width}, height: {height}, samples: 3),
          camera: (eye: ({:?}, {:?}, {:?}), view: ({:?}, {:?}, {:?}), up: ({:?}, {:?}, {:?}),
                   projection: {projection}),
          objects: [Sphere(center: (0.0, 0.0, 0.0), radius: 1.0)])",
        eye.x, eye.y, eye.z, view.x, view.y, view.z, up.x, up.y, up.z
    );
    viewray_scene::SceneLoader::text(&text, Path::new("case.ron"))
        .load()
        .map(|loaded| loaded.scene)
        .ok()
}

/// The file name an export is written under, by format.
fn file_name(format: Format) -> &'static str {
    match format {
        Format::Mitsuba => "scene.xml",
        Format::Pbrt => "scene.pbrt",
        Format::Blender => "scene.py",
        Format::Three => "scene.json",
        Format::Gltf => "scene.gltf",
    }
}

/// Whether `format` can hold `camera`, by the conventions (written independently of
/// the exporters).
fn expressible(format: Format, camera: &Camera) -> bool {
    let square = |viewport: DVec2| {
        let a = viewport.x * f64::from(camera.height());
        let b = viewport.y * f64::from(camera.width());
        (a - b).abs() <= 1e-12 * a.max(b)
    };
    match (format, camera.projection()) {
        (_, Projection::Oblique(_)) => false,
        // No tool tilts a lens; only Blender has blades, at most 16.
        (_, Projection::ThinLens(t)) if t.tilt != 0.0 || t.swing != 0.0 => false,
        (Format::Blender, Projection::ThinLens(t)) => t.iris.blades <= 16,
        (Format::Mitsuba | Format::Pbrt, Projection::ThinLens(t)) if t.iris.blades != 0 => false,
        (Format::Mitsuba, Projection::Perspective(p)) => square(p.viewport),
        (Format::Mitsuba, Projection::ThinLens(t)) => square(t.viewport) && t.shift == DVec2::ZERO,
        (Format::Mitsuba | Format::Three | Format::Gltf, Projection::Orthographic(o)) => {
            o.lens.is_none()
        }
        (Format::Three | Format::Gltf, Projection::ThinLens(_)) => false,
        (Format::Gltf, Projection::Perspective(p)) => p.shift == DVec2::ZERO,
        (
            Format::Mitsuba | Format::Three | Format::Gltf,
            Projection::Equirectangular | Projection::Fisheye(_),
        ) => false,
        (Format::Pbrt, Projection::Fisheye(_)) => false,
        (Format::Blender, Projection::Fisheye(f)) => {
            camera.width() == camera.height() && f.fov >= 10f64.to_radians()
        }
        _ => true,
    }
}

/// The largest difference between the two cameras' rays (unit directions, and origins
/// relative to the eye's distance from the world origin) over a grid of image points and
/// lens samples.
fn ray_difference(a: &Camera, b: &Camera) -> f64 {
    let size = DVec2::new(f64::from(a.width()), f64::from(a.height()));
    let mut worst: f64 = 0.0;
    for j in 0..5 {
        for i in 0..5 {
            let image =
                DVec2::new(f64::from(i) / 4.0, f64::from(j) / 4.0) * size * 0.98 + size * 0.01;
            for lens in [
                DVec2::splat(0.5),
                DVec2::new(0.1, 0.8),
                DVec2::new(0.9, 0.3),
            ] {
                let (ra, rb) = (
                    a.generate_ray_through(image, lens),
                    b.generate_ray_through(image, lens),
                );
                match (ra, rb) {
                    (Some(ra), Some(rb)) => {
                        let scale = ra.origin.length().max(1.0);
                        worst = worst
                            .max((ra.direction.normalize() - rb.direction.normalize()).length())
                            .max((ra.origin - rb.origin).length() / scale);
                    }
                    (None, None) => {}
                    _ => return f64::INFINITY,
                }
            }
        }
    }
    worst
}

/// Exports `scene` to every format and reads it back, checking the rays.
fn check_all_formats(scene: &Scene) -> Result<(), TestCaseError> {
    for format in Format::ALL {
        let export = viewray_interop::export(scene, format, file_name(format));
        let expected = expressible(format, scene.camera());
        prop_assert_eq!(
            export.is_ok(),
            expected,
            "{:?}: {:?} for {:?}",
            format,
            export.as_ref().err(),
            scene.camera()
        );
        let Ok(export) = export else { continue };
        if format == Format::Blender {
            continue; // a Python script: checked against Blender by `cargo xtask interop`
        }
        let path = Path::new(file_name(format));
        let document = viewray_interop::import(&export.main, path, format)
            .map_err(|e| TestCaseError::fail(format!("{format:?}: {e}")))?;
        // The camera is what must come back exactly; the objects are compared elsewhere
        // (and Mitsuba's meshes live in files this test does not write).
        let document = viewray_scene::SceneDocument {
            objects: Vec::new(),
            ..document
        };
        let text = document.to_ron();
        let back = viewray_scene::SceneLoader::text(&text, path)
            .load()
            .map(|loaded| loaded.scene)
            .map_err(|e| TestCaseError::fail(format!("{format:?}: {e}\n{text}")))?;
        prop_assert_eq!(
            (back.camera().width(), back.camera().height()),
            (scene.camera().width(), scene.camera().height())
        );
        let difference = ray_difference(scene.camera(), back.camera());
        prop_assert!(
            difference < 1e-9,
            "{:?}: rays differ by {} for {:?}\n{}",
            format,
            difference,
            scene.camera(),
            text
        );
    }
    Ok(())
}

fn vector() -> impl Strategy<Value = DVec3> {
    (-10.0..10.0f64, -10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y, z)| DVec3::new(x, y, z))
}

fn projection() -> impl Strategy<Value = String> {
    let axis = prop_oneof![
        Just("x"),
        Just("y"),
        Just("diagonal"),
        Just("smaller"),
        Just("larger")
    ];
    let fit = prop_oneof![Just("Auto"), Just("Horizontal"), Just("Vertical")];
    prop_oneof![
        (axis, 5.0..170.0f64).prop_map(|(axis, fov)| format!("Perspective(fov_{axis}: {fov:?})")),
        (0.1..3.0f64, 0.1..4.0f64, 0.1..4.0f64, -1.0..1.0f64, -1.0..1.0f64).prop_map(|(d, w, h, sx, sy)| {
            format!("Perspective(distance: {d:?}, viewport: ({w:?}, {h:?}), shift: ({sx:?}, {sy:?}))")
        }),
        (10.0..200.0f64, fit).prop_map(|(f, fit)| format!("Perspective(focal_length: {f:?}, sensor: (36.0, 24.0), fit: {fit})")),
        (10.0..120.0f64, 0.01..0.5f64, 0.5..20.0f64, -0.3..0.3f64).prop_map(|(fov, r, focus, s)| {
            format!("ThinLens(fov_y: {fov:?}, shift: ({s:?}, 0.0), aperture: {r:?}, focus: {focus:?})")
        }),
        (10.0..200.0f64, 1.0..22.0f64, 0.5..20.0f64).prop_map(|(f, n, focus)| {
            format!("ThinLens(focal_length: {f:?}, f_number: {n:?}, focus: {focus:?})")
        }),
        (0.1..20.0f64).prop_map(|h| format!("Orthographic(height: {h:?})")),
        (0.1..20.0f64, 0.1..20.0f64).prop_map(|(w, h)| format!("Orthographic(viewport: ({w:?}, {h:?}))")),
        (0.1..20.0f64, 0.01..1.0f64, 0.5..20.0f64).prop_map(|(h, r, f)| format!("Orthographic(height: {h:?}, aperture: {r:?}, focus: {f:?})")),
        (0.1..20.0f64, 0.0..1.5f64, -180.0..180.0f64).prop_map(|(h, l, a)| format!("Oblique(height: {h:?}, ratio: {l:?}, angle: {a:?})")),
        Just("Equirectangular".to_owned()),
        (5.0..360.0f64).prop_map(|f| format!("Fisheye(fov: {f:?})")),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn every_format_gives_back_the_rays(
        eye in vector(),
        view in vector(),
        up in vector(),
        width in 1u32..300,
        height in 1u32..300,
        square in any::<bool>(),
        projection in projection(),
    ) {
        let height = if square { width } else { height };
        let Some(scene) = scene(eye, view, up, width, height, &projection) else {
            // A degenerate frame (zero view, up parallel to view) is not a camera.
            return Ok(());
        };
        check_all_formats(&scene)?;
    }
}

#[test]
fn every_fixture_scene_survives_every_format() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/scenes");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    assert!(files.len() > 20);
    for file in files {
        let scene = viewray_scene::SceneLoader::file(&file)
            .load()
            .unwrap()
            .scene;
        check_all_formats(&scene).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
    }
}
