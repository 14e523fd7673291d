//! `cargo xtask icosphere`: the geometry benchmark's mesh and camera as a scene file, so
//! that `viewray render --stats` measures the renderer on exactly the benchmark's rays.

use std::path::{Path, PathBuf};

use anyhow::Result;
use viewray_geometry::MeshData;
use viewray_scene::obj_text;

/// The benchmark's subdivision level: 20 * 4^8 = 1,310,720 triangles.
const SUBDIVISIONS: u32 = 8;

/// The command line of `cargo xtask icosphere`.
#[derive(Debug, Default, clap::Args)]
pub struct IcosphereArgs {
    /// The folder to write icosphere.obj and icosphere.ron into [default:
    /// target/icosphere/].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// The benchmark's view: 1024 x 1024 primary rays from eye (0, 0, 3) looking down -z,
/// d = 1, a 1 x 1 viewport; Flat shading and one sample, so every ray is a primary ray.
const SCENE: &str = "\
// The geometry benchmark's scene: a radius-1 icosphere of 1,310,720 triangles seen by
// the benchmark's camera. Written by `cargo xtask icosphere`.
(
    image: (width: 1024, height: 1024, samples: 1),
    camera: (
        eye: (0.0, 0.0, 3.0),
        view: (0.0, 0.0, -1.0),
        up: (0.0, 1.0, 0.0),
        projection: Perspective(distance: 1.0, viewport: (1.0, 1.0)),
    ),
    shading: Flat,
    materials: { \"white\": (color: (1.0, 1.0, 1.0)) },
    objects: [Mesh(path: \"icosphere.obj\", material: \"white\")],
)
";

/// Writes `icosphere.obj` and `icosphere.ron` into the output folder, each atomically.
///
/// # Errors
/// When a file cannot be written.
pub fn icosphere(root: &Path, args: &IcosphereArgs) -> Result<()> {
    let out = match &args.out {
        Some(out) => out.clone(),
        None => crate::target_dir(root)?.join("icosphere"),
    };
    let mesh = MeshData::icosphere(SUBDIVISIONS, 1.0);
    let obj = out.join("icosphere.obj");
    let comment = format!("icosphere: {} triangles", mesh.triangles.len());
    crate::write_atomically(&obj, obj_text(&mesh, &comment).as_bytes())?;
    let scene = out.join("icosphere.ron");
    crate::write_atomically(&scene, SCENE.as_bytes())?;
    eprintln!(
        "wrote {} ({} triangles) and {}\n\
         measure the renderer on it with\n  \
         cargo run --release -p viewray -- render {} -o icosphere.png --stats --threads 1",
        obj.display(),
        mesh.triangles.len(),
        scene.display(),
        scene.display(),
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use viewray_scene::SceneLoader;

    /// The scene and the mesh as `obj_text` writes it load back: the same triangles, the
    /// benchmark's camera.
    #[test]
    fn the_scene_and_its_mesh_load_back() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let mesh = MeshData::icosphere(2, 1.0);
        std::fs::write(
            dir.path().join("icosphere.obj"),
            obj_text(&mesh, "icosphere"),
        )
        .expect("an OBJ");
        std::fs::write(dir.path().join("icosphere.ron"), SCENE).expect("a scene");
        let scene = SceneLoader::file(&dir.path().join("icosphere.ron"))
            .load()
            .expect("a valid scene")
            .scene;
        assert_eq!(scene.world().triangle_count(), 320);
        assert_eq!(scene.world().triangle_count(), mesh.triangles.len());
        assert_eq!(
            (scene.camera().width(), scene.camera().height()),
            (1024, 1024)
        );
        assert_eq!(scene.samples(), 1);
        // The eye at (0, 0, 3) looking down -z: the centre ray meets the sphere near
        // z = 1, a little below it, since the flat facets lie inside the sphere.
        let centre = scene
            .camera()
            .generate_ray(512, 512, viewray_camera::CameraSample::CENTER)
            .expect("a ray");
        let hit = scene
            .world()
            .closest_hit(&centre.as_ray(), 0.0..f32::INFINITY)
            .expect("the sphere straight ahead");
        let z = hit.point.z;
        assert!(z <= 1.0 + 1e-5 && z > 0.9, "hit at z = {z}");
    }
}
