//! The renderer's scene of the benchmark's mesh and camera, rendered as `viewray
//! render` renders a scene.

use std::sync::Arc;
use std::time::Instant;

use glam::{DVec2, DVec3, Vec3};
use viewray_camera::{Camera, Frame, Perspective, Projection};
use viewray_geometry::{Instance, Mesh, Object, World};
use viewray_render::{RenderSettings, render};
use viewray_scene::{Material, ObjectMaterial, Scene, SceneParts, Shading};

/// The scene `cargo xtask icosphere` writes, for any mesh: the benchmark's camera (eye
/// (0, 0, 3) looking down -z, d = 1, a 1 x 1 viewport) at `size x size` pixels, Flat
/// shading, one sample, one white material.
pub(crate) fn scene(mesh: &Arc<Mesh>, size: u32) -> Scene {
    let world = World::new(vec![Object::Instance(Instance::from_mesh(Arc::clone(
        mesh,
    )))])
    .expect("a world");
    let frame = Frame::from_eye_view_up(DVec3::new(0.0, 0.0, 3.0), DVec3::NEG_Z, DVec3::Y)
        .expect("a frame");
    let projection = Projection::Perspective(Perspective {
        distance: 1.0,
        viewport: DVec2::ONE,
        shift: DVec2::ZERO,
    });
    let camera = Camera::new(frame, projection, size, size).expect("a camera");
    Scene::new(SceneParts {
        camera,
        samples: 1,
        background: Vec3::ZERO,
        shading: Shading::Flat,
        materials: vec![Material::default()],
        lights: Vec::new(),
        world,
        object_materials: vec![ObjectMaterial::Single(0)],
    })
    .expect("one object, one material")
}

/// Renders `scene` on `pool` as `viewray render` does (default settings on the pool it
/// is called on) and returns the seconds up to the finished image, as `--stats` times
/// them: the image's release (12 MB at 1024 x 1024) is not timed.
pub(crate) fn render_seconds(scene: &Scene, pool: &rayon::ThreadPool) -> f64 {
    let settings = RenderSettings::default();
    let start = Instant::now();
    let rendered = pool
        .install(|| render(scene, &settings, |_, _| {}))
        .expect("a render");
    let seconds = start.elapsed().as_secs_f64();
    drop(std::hint::black_box(rendered));
    seconds
}
