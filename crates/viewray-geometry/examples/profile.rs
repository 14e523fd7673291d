//! A small, deterministic workload for instruction counts (callgrind), where timings on a
//! shared machine are too noisy for A/B decisions:
//!
//! ```text
//! RAYON_NUM_THREADS=1 valgrind --tool=callgrind \
//!     target/release/examples/profile WORKLOAD [SUBDIVISIONS]
//! ```
//!
//! `WORKLOAD` is `build` (build the icosphere's mesh), `coherent` (256 x 256 primary rays
//! in packets of 8 x 8), `single` (the same rays one by one) or `incoherent` (100,000
//! random rays one by one). The bench's world of several objects (the icosphere, three
//! small ones placed by instances, a ground of two triangles) gives the workloads
//! `sun-shadow` (the shadow rays toward the sun from the hits of a sixteenth of the
//! bench's 1024 x 1024 primary rays, every fourth tile of 8 x 8 pixels, one by one), `sun-shadows` (the same 64 at a time), `random-shadow` and
//! `random-shadows` (the 100,000 random rays as shadow rays of length 0.5), `mirror` and
//! `mirrors` (the mirror rays from the primary rays' hits). The icosphere has
//! `20 * 4^SUBDIVISIONS` triangles (default 6). It prints a checksum of the hits, so that
//! two builds can be compared.

use std::sync::Arc;

use glam::Vec3;
use viewray_geometry::{Mesh, MeshData, Ray, World};

// The bench's rays and world: a profile traces the same rays the bench times.
#[path = "../benches/bvh/rays.rs"]
#[allow(dead_code)]
mod rays;
#[path = "../benches/bvh/world.rs"]
mod world;

/// The length of the random shadow rays, as in the bench.
const SHADOW_LENGTH: f32 = 0.5;

fn main() {
    let mut args = std::env::args().skip(1);
    let workload = args.next().unwrap_or_else(|| "coherent".to_owned());
    let subdivisions = args.next().and_then(|s| s.parse().ok()).unwrap_or(6);
    let data = MeshData::icosphere(subdivisions, 1.0);
    let mesh = Mesh::new(data.clone()).expect("a valid icosphere");
    let sum: f64 = match workload.as_str() {
        "build" => (0..4)
            .map(|_| {
                Mesh::new(data.clone())
                    .expect("a valid icosphere")
                    .acceleration_bytes() as f64
            })
            .sum(),
        "coherent" => {
            let rays = primary_rays(256);
            let mut hits = vec![None; rays.len()];
            mesh.closest_triangles(&rays, 0.0..f32::INFINITY, &mut hits);
            hits.iter().flatten().map(|h| f64::from(h.t)).sum()
        }
        "single" => primary_rays(256)
            .iter()
            .filter_map(|r| mesh.closest_triangle(r, 0.0..f32::INFINITY))
            .map(|h| f64::from(h.t))
            .sum(),
        "incoherent" => rays::incoherent_rays(100_000)
            .iter()
            .filter_map(|r| mesh.closest_triangle(r, 0.0..f32::INFINITY))
            .map(|h| f64::from(h.t))
            .sum(),
        "sun-shadow" | "sun-shadows" | "random-shadow" | "random-shadows" | "mirror"
        | "mirrors" => world_workload(&workload, &Arc::new(mesh), &data),
        other => {
            eprintln!(
                "error: unknown workload {other:?}: build, coherent, single, incoherent, \
                 sun-shadow, sun-shadows, random-shadow, random-shadows, mirror or mirrors"
            );
            std::process::exit(2);
        }
    };
    println!("{workload}: checksum {sum}");
}

/// A workload on the bench's world: the shadow or mirror rays one by one or 64 at a time.
/// Making the world and the rays is in the count too, the same in both builds compared
/// (`callgrind_annotate --inclusive=yes` gives the queries' own share).
fn world_workload(workload: &str, mesh: &Arc<Mesh>, data: &MeshData) -> f64 {
    let (world, _) = world::world(mesh, data);
    let primary = bench_tiles();
    let (rays, t_max) = match workload {
        "sun-shadow" | "sun-shadows" => (
            world::secondary_rays(&world, &primary, world::shadow),
            f32::INFINITY,
        ),
        "random-shadow" | "random-shadows" => (rays::incoherent_rays(100_000), SHADOW_LENGTH),
        _ => (
            world::secondary_rays(&world, &primary, world::mirror),
            f32::INFINITY,
        ),
    };
    match workload {
        "mirror" => rays
            .iter()
            .filter_map(|r| world.closest_object(r, 0.0..t_max))
            .map(|h| f64::from(h.t))
            .sum(),
        "mirrors" => {
            let mut hits = vec![None; rays.len()];
            world.closest_objects(&rays, 0.0..t_max, &mut hits);
            hits.iter().flatten().map(|h| f64::from(h.t)).sum()
        }
        "sun-shadow" | "random-shadow" => blocked(&world, &rays, t_max, false),
        _ => blocked(&world, &rays, t_max, true),
    }
}

/// How many of `rays` are blocked in `world` within `[0, t_max)`, asked one by one or
/// 64 at a time (`together`).
fn blocked(world: &World, rays: &[Ray], t_max: f32, together: bool) -> f64 {
    if together {
        let mut hits = vec![false; rays.len()];
        world.any_hits(rays, 0.0..t_max, &mut hits);
        hits.iter().filter(|&&hit| hit).count() as f64
    } else {
        rays.iter()
            .filter(|ray| world.any_hit(ray, 0.0..t_max))
            .count() as f64
    }
}

/// A sixteenth of the bench's 1024 x 1024 primary rays in tiles of 8 x 8 (every fourth
/// tile of every fourth row of tiles), so that the secondary rays from their hits are as
/// coherent as the bench's.
fn bench_tiles() -> Vec<Ray> {
    let tiles = rays::in_tiles(&rays::primary_rays(1024, 1024), 1024, 8, 8);
    tiles
        .chunks(64)
        .enumerate()
        .filter(|(tile, _)| (tile / 128) % 4 == 0 && (tile % 128) % 4 == 0)
        .flat_map(|(_, tile)| tile.iter().copied())
        .collect()
}

/// The benchmark's camera (eye (0, 0, 3), d = 1, a 1 x 1 viewport) at `size x size`
/// pixels, in tiles of 8 x 8 pixels.
fn primary_rays(size: usize) -> Vec<Ray> {
    let eye = Vec3::new(0.0, 0.0, 3.0);
    let mut rays = Vec::with_capacity(size * size);
    for tile_row in (0..size).step_by(8) {
        for tile_col in (0..size).step_by(8) {
            for row in tile_row..tile_row + 8 {
                for col in tile_col..tile_col + 8 {
                    let u = (col as f32 + 0.5) / size as f32 - 0.5;
                    let v = -((row as f32 + 0.5) / size as f32 - 0.5);
                    rays.push(Ray::new(eye, Vec3::new(u, v, -1.0)));
                }
            }
        }
    }
    rays
}
