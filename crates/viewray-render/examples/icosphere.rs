//! How much the renderer adds on top of `World::closest_hit`: renders the geometry
//! benchmark's scene (a 1,310,720-triangle icosphere, eye (0, 0, 3) looking down -z,
//! d = 1, a 1 x 1 viewport, 1024 x 1024, Flat shading, one sample) on 1 and 2 threads,
//! and traces the same primary rays with a bare `closest_hit` loop for comparison.
//!
//! `cargo run --release -p viewray-render --example icosphere`; set
//! `VIEWRAY_BENCH_SUBDIVISIONS` for a smaller icosphere (default 8).

use std::sync::Arc;
use std::time::Instant;

use glam::{DVec2, DVec3, Vec3};
use rayon::prelude::*;
use viewray_camera::{Camera, CameraSample, Frame, Perspective, Projection};
use viewray_geometry::{Instance, Mesh, Object, Ray, World};
use viewray_render::{RenderSettings, render};
use viewray_scene::{Material, ObjectMaterial, Scene, SceneParts, Shading};

const SIZE: u32 = 1024;
const RUNS: usize = 5;

fn main() {
    let subdivisions = std::env::var("VIEWRAY_BENCH_SUBDIVISIONS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(8);
    let start = Instant::now();
    let mesh = Arc::new(Mesh::icosphere(subdivisions, 1.0));
    println!(
        "icosphere({subdivisions}): {} triangles, built in {:.3} s",
        mesh.triangle_count(),
        start.elapsed().as_secs_f64()
    );
    let world = World::new(vec![Object::Instance(Instance::from_mesh(mesh))]).expect("a world");
    let frame = Frame::from_eye_view_up(DVec3::new(0.0, 0.0, 3.0), DVec3::NEG_Z, DVec3::Y)
        .expect("a frame");
    let projection = Projection::Perspective(Perspective {
        distance: 1.0,
        viewport: DVec2::ONE,
        shift: DVec2::ZERO,
    });
    let camera = Camera::new(frame, projection, SIZE, SIZE).expect("a camera");
    let scene = Scene::new(SceneParts {
        camera,
        samples: 1,
        background: Vec3::ZERO,
        shading: Shading::Flat,
        materials: vec![Material::default()],
        lights: Vec::new(),
        world,
        object_materials: vec![ObjectMaterial::Single(0)],
    })
    .expect("one object, one material");
    let rays = f64::from(SIZE * SIZE);

    // The bare loop: precomputed rays, closest_hit only.
    let primary: Vec<Ray> = (0..SIZE)
        .flat_map(|row| (0..SIZE).map(move |col| (row, col)))
        .map(|(row, col)| {
            camera
                .generate_ray(row, col, CameraSample::CENTER)
                .expect("a perspective ray")
                .as_ray()
        })
        .collect();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool");
        let best = (0..RUNS)
            .map(|_| {
                let start = Instant::now();
                let hits = pool.install(|| {
                    primary
                        .par_chunks(256)
                        .map(|chunk| {
                            chunk
                                .iter()
                                .filter(|ray| {
                                    scene.world().closest_hit(ray, 0.0..f32::INFINITY).is_some()
                                })
                                .count()
                        })
                        .sum::<usize>()
                });
                std::hint::black_box(hits);
                start.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min);
        println!(
            "closest_hit loop, {threads} thread(s): {:.3} s, {:.2} Mrays/s",
            best,
            rays / best / 1e6
        );
    }

    // The renderer: ray generation, tracing, shading, tiles, image.
    for threads in [1, 2] {
        let settings = RenderSettings {
            threads: Some(threads),
            ..RenderSettings::default()
        };
        let best = (0..RUNS)
            .map(|_| {
                let start = Instant::now();
                let rendered = render(&scene, &settings, |_, _| {}).expect("a render");
                std::hint::black_box(rendered);
                start.elapsed().as_secs_f64()
            })
            .fold(f64::INFINITY, f64::min);
        println!(
            "render, {threads} thread(s):           {:.3} s, {:.2} Mrays/s",
            best,
            rays / best / 1e6
        );
    }
}
