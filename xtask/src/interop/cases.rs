//! The cases: every fixture scene, and a scene per camera convention no fixture covers,
//! each with the image points, lens samples and world points its checks compare.

use std::path::{Path, PathBuf};

use anyhow::Result;
use glam::{DVec2, DVec3};
use viewray_scene::{Scene, SceneLoader};

use super::report::size_of;

/// A scene exported to the tools.
pub(super) struct Case {
    /// The file stem of a fixture, or `camera_` and the convention.
    pub(super) name: String,
    pub(super) scene: Scene,
    /// Image points `(x, y)` whose rays are compared.
    pub(super) pixels: Vec<DVec2>,
    /// Lens samples for the thin lens, one per pixel.
    pub(super) lens: Vec<DVec2>,
    /// World points and the image points where viewray sees them.
    pub(super) points: Vec<(DVec3, DVec2)>,
    /// Whether Mitsuba's coverage is compared (scenes of fixtures/scenes/).
    pub(super) coverage: bool,
}

/// Image points spread over an image of `size`: a 9 x 7 grid from corner to corner and the
/// pixel centres of the corners.
pub(super) fn grid(size: DVec2) -> Vec<DVec2> {
    let mut out = Vec::new();
    for j in 0..7 {
        for i in 0..9 {
            out.push(DVec2::new(f64::from(i) / 8.0, f64::from(j) / 6.0) * size);
        }
    }
    out.extend([
        DVec2::new(0.5, 0.5),
        DVec2::new(size.x - 0.5, 0.5),
        DVec2::new(0.5, size.y - 0.5),
        DVec2::new(size.x - 0.5, size.y - 0.5),
    ]);
    out
}

/// The fixture scenes and camera cases for the conventions no fixture covers.
pub(super) fn cases(root: &Path) -> Result<Vec<Case>> {
    let mut scenes: Vec<(String, Scene, bool)> = Vec::new();
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("fixtures/scenes"))?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    files.sort();
    for file in files
        .iter()
        .filter(|f| f.extension().is_some_and(|e| e == "ron"))
    {
        let name = file
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scene")
            .to_owned();
        let scene = SceneLoader::file(file)
            .load()
            .map_err(|e| anyhow::anyhow!("{e}"))?
            .scene;
        scenes.push((name, scene, true));
    }
    let world = format!(
        "background: (0.5, 0.6, 0.8),
         materials: {{ \"red\": (color: (0.8, 0.1, 0.1)), \"grey\": (color: (0.6, 0.6, 0.6)) }},
         lights: [Point(position: (3.0, 5.0, 4.0), intensity: (20.0, 20.0, 20.0)), Ambient(intensity: (0.1, 0.1, 0.1))],
         objects: [
             Plane(point: (0.0, -1.0, 0.0), normal: (0.0, 1.0, 0.0), material: \"grey\"),
             Sphere(center: (0.0, 0.0, 0.0), radius: 1.0, material: \"red\"),
             Box(min: (1.5, -1.0, -1.0), max: (2.5, 0.5, 0.0)),
             Triangle(a: (-2.5, -1.0, 0.5), b: (-1.5, -1.0, 0.5), c: (-2.0, 0.5, 0.5)),
             Mesh(path: \"{}\", transform: (translate: (-1.0, -0.5, -2.0), rotate: (0.0, 30.0, 0.0), scale: 0.5)),
         ]",
        root.join("fixtures/meshes/cube.obj").display()
    );
    let cameras = [
        ("fov_x", 64, 48, "Perspective(fov_x: 50.0)"),
        (
            "fov_diagonal_portrait",
            48,
            64,
            "Perspective(fov_diagonal: 60.0)",
        ),
        ("fov_smaller", 64, 40, "Perspective(fov_smaller: 35.0)"),
        (
            "physical_vertical",
            64,
            36,
            "Perspective(focal_length: 35.0, sensor: (36.0, 24.0), fit: Vertical)",
        ),
        (
            "physical_auto_portrait",
            36,
            64,
            "Perspective(focal_length: 50.0)",
        ),
        (
            "shift",
            64,
            48,
            "Perspective(fov_y: 40.0, shift: (0.1, -0.25))",
        ),
        (
            "non_square_pixels",
            64,
            48,
            "Perspective(distance: 1.0, viewport: (2.0, 1.0))",
        ),
        (
            "non_square_pixels_shift",
            40,
            60,
            "Perspective(distance: 2.0, viewport: (1.0, 3.0), shift: (0.3, 0.2))",
        ),
        (
            "thin_lens_f_number",
            64,
            48,
            "ThinLens(focal_length: 50.0, f_number: 2.8, focus: 6.0)",
        ),
        (
            "thin_lens_shift",
            64,
            48,
            "ThinLens(fov_y: 40.0, shift: (0.05, 0.1), aperture: 0.1, focus: 6.0)",
        ),
        ("orthographic", 64, 48, "Orthographic(height: 6.0)"),
        (
            "orthographic_non_square",
            64,
            48,
            "Orthographic(viewport: (8.0, 3.0))",
        ),
        (
            "orthographic_lens",
            64,
            48,
            "Orthographic(viewport: (8.0, 6.0), aperture: 0.2, focus: 5.0)",
        ),
        (
            "oblique",
            64,
            48,
            "Oblique(height: 6.0, ratio: 0.5, angle: 30.0)",
        ),
        ("equirectangular", 64, 32, "Equirectangular"),
        ("fisheye_square", 48, 48, "Fisheye(fov: 200.0)"),
        ("fisheye_wide", 64, 48, "Fisheye(fov: 180.0)"),
    ];
    for (name, width, height, projection) in cameras {
        let text = format!(
            "(image: (width: {width}, height: {height}, samples: 4),
              camera: (eye: (1.5, 1.2, 6.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), projection: {projection}),
              {world})"
        );
        let scene = SceneLoader::text(&text, &root.join(format!("{name}.ron")))
            .load()
            .map(|loaded| loaded.scene)
            .map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
        scenes.push((format!("camera_{name}"), scene, true));
    }
    Ok(scenes
        .into_iter()
        .map(|(name, scene, coverage)| {
            let camera = scene.camera();
            let size = size_of(camera);
            let pixels = grid(size);
            let lens: Vec<DVec2> = (0..pixels.len())
                .map(|i| {
                    let t = i as f64 * 0.618_033_988_749_895;
                    DVec2::new(t.fract(), (t * 1.7).fract().mul_add(0.98, 0.01))
                })
                .collect();
            let mut points = Vec::new();
            for &p in &pixels {
                let Some(ray) = camera.generate_ray_through(p, DVec2::splat(0.5)) else {
                    continue;
                };
                // Points 1, 3 and 10 units along the ray: far enough from the eye that
                // single-precision tools resolve them.
                for distance in [1.0, 3.0, 10.0] {
                    let world = ray.at(distance / ray.direction.length());
                    if let Some(image) = camera.project(world) {
                        points.push((world, image));
                    }
                }
            }
            Case {
                name,
                scene,
                pixels,
                lens,
                points,
                coverage,
            }
        })
        .collect())
}
