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
//! random rays one by one). The icosphere has `20 * 4^SUBDIVISIONS` triangles (default
//! 6). It prints a checksum of the hits, so that two builds can be compared.

use glam::Vec3;
use viewray_geometry::{Mesh, MeshData, Ray};

// The bench's rays: a profile traces the same incoherent rays the bench times.
#[path = "../benches/bvh/rays.rs"]
#[allow(dead_code)]
mod rays;

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
        other => {
            eprintln!("error: unknown workload {other:?}: build, coherent, single or incoherent");
            std::process::exit(2);
        }
    };
    println!("{workload}: checksum {sum}");
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
