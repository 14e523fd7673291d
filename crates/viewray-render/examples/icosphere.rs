//! How much the renderer adds on top of tracing: renders the geometry benchmark's scene
//! (a 1,310,720-triangle icosphere, eye (0, 0, 3) looking down -z, d = 1, a 1 x 1
//! viewport, 1024 x 1024, Flat shading, one sample) on 1 and 2 threads, and traces the
//! same primary rays, generated beforehand, as the same packets of 8 x 8 with
//! `World::closest_objects` alone, both on the same pool. Prints medians of 21 runs of
//! each, alternated, and the ratio of the render's time to the bare tracing's: the
//! median of each run's ratio to the bare run before it (with the middle half of those
//! ratios), by the medians and by the fastest runs.
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
const RUNS: usize = 21;

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

    // The bare loop: the same primary rays, precomputed in the renderer's order (tiles
    // of 16 x 16, blocks of 8 x 8), each block traced as one packet with
    // `closest_objects`.
    let blocks: Vec<Vec<Ray>> = (0..SIZE)
        .step_by(16)
        .flat_map(|tile_row| {
            (0..SIZE)
                .step_by(16)
                .map(move |tile_col| (tile_row, tile_col))
        })
        .flat_map(|(tile_row, tile_col)| {
            [(0, 0), (0, 8), (8, 0), (8, 8)].map(|(r, c)| (tile_row + r, tile_col + c))
        })
        .map(|(block_row, block_col)| {
            (block_row..block_row + 8)
                .flat_map(|row| (block_col..block_col + 8).map(move |col| (row, col)))
                .map(|(row, col)| {
                    camera
                        .generate_ray(row, col, CameraSample::CENTER)
                        .expect("a perspective ray")
                        .as_ray()
                })
                .collect()
        })
        .collect();
    // Alternate the two, run by run, so that both see the same machine.
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool");
        // The render on the same pool as the bare loop (`threads: None` renders on the
        // current pool), as `viewray render` does on rayon's global pool: a pool of its
        // own per render would add the threads' start to every run.
        let settings = RenderSettings {
            threads: None,
            ..RenderSettings::default()
        };
        let (mut bare, mut rendered) = (Vec::new(), Vec::new());
        for _ in 0..RUNS {
            let start = Instant::now();
            let hits = pool.install(|| {
                blocks
                    .par_iter()
                    .map_init(Vec::new, |hits, block| {
                        hits.clear();
                        hits.resize(block.len(), None);
                        scene
                            .world()
                            .closest_objects(block, 0.0..f32::INFINITY, hits);
                        hits.iter().flatten().count()
                    })
                    .sum::<usize>()
            });
            std::hint::black_box(hits);
            bare.push(start.elapsed().as_secs_f64());

            let start = Instant::now();
            let image = pool
                .install(|| render(&scene, &settings, |_, _| {}))
                .expect("a render");
            // Timed as `viewray render --stats` times it: up to the finished image, not
            // its release (12 MB handed back to the system).
            rendered.push(start.elapsed().as_secs_f64());
            drop(std::hint::black_box(image));
        }
        // Each run's ratio to the bare run just before it: both saw the same moment of
        // the machine, so their median is steadier than the ratio of two medians.
        let mut ratios: Vec<f64> = rendered.iter().zip(&bare).map(|(r, b)| r / b).collect();
        ratios.sort_by(f64::total_cmp);
        let bare = report(&format!("packets, {threads} thread(s)"), &bare, rays);
        let rendered = report(&format!("render, {threads} thread(s)"), &rendered, rays);
        println!(
            "render / packets, {threads} thread(s): {:.3}x by the runs' ratios (middle half \
             {:.3}x to {:.3}x), {:.3}x by the medians, {:.3}x by the fastest runs",
            ratios[ratios.len() / 2],
            ratios[ratios.len() / 4],
            ratios[ratios.len() * 3 / 4],
            rendered.0 / bare.0,
            rendered.1 / bare.1
        );
    }
}

/// Prints the median of `times` (seconds) and its spread, in Mrays/s for `rays` rays;
/// returns the median and the fastest run (on a shared machine, other work only ever
/// adds time).
fn report(what: &str, times: &[f64], rays: f64) -> (f64, f64) {
    let mut sorted = times.to_vec();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    println!(
        "{what:<22} median {median:.4} s, {:.2} Mrays/s (runs {:.4} to {:.4} s)",
        rays / median / 1e6,
        sorted[0],
        sorted[sorted.len() - 1]
    );
    (median, sorted[0])
}
