//! The benchmark's rays: the lecture camera's primary rays, in tiles, and incoherent
//! rays from a fixed seed.

use glam::Vec3;
use viewray_geometry::Ray;

/// The eye of the benchmark's camera.
pub(crate) const EYE: Vec3 = Vec3::new(0.0, 0.0, 3.0);

/// The lecture's perspective camera: eye (0, 0, 3) looking down -z, d = 1, a 1 x 1
/// viewport; pixel (i, j), 1-based, gets the direction
/// (u, v, -1) with u = (j - 1/2)/W - 1/2, v = -((i - 1/2)/H - 1/2).
pub(crate) fn primary_rays(width: usize, height: usize) -> Vec<Ray> {
    (1..=height)
        .flat_map(|i| {
            (1..=width).map(move |j| {
                let u = (j as f32 - 0.5) / width as f32 - 0.5;
                let v = -((i as f32 - 0.5) / height as f32 - 0.5);
                Ray::new(EYE, Vec3::new(u, v, -1.0))
            })
        })
        .collect()
}

/// The same rays reordered into tiles of `tile_width x tile_height` pixels, tile after
/// tile (8 x 8 as a renderer hands them to `Mesh::closest_triangles`; 4 x 4 for
/// Embree's packets of 16).
pub(crate) fn in_tiles(
    rays: &[Ray],
    width: usize,
    tile_width: usize,
    tile_height: usize,
) -> Vec<Ray> {
    let height = rays.len() / width;
    let mut tiled = Vec::with_capacity(rays.len());
    for tile_row in (0..height).step_by(tile_height) {
        for tile_col in (0..width).step_by(tile_width) {
            for row in tile_row..(tile_row + tile_height).min(height) {
                let start = row * width + tile_col;
                tiled.extend_from_slice(&rays[start..start + tile_width.min(width - tile_col)]);
            }
        }
    }
    tiled
}

/// `count` rays with origins uniform in `[-1, 1]^3` and directions uniform on the
/// sphere, from a fixed seed (SplitMix64).
pub(crate) fn incoherent_rays(count: usize) -> Vec<Ray> {
    let mut state = 0x5eed_u64;
    let mut uniform = move || {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    };
    (0..count)
        .map(|_| {
            let origin = Vec3::new(uniform(), uniform(), uniform()) * 2.0 - 1.0;
            let z = 2.0 * uniform() - 1.0;
            let phi = std::f32::consts::TAU * uniform();
            let r = (1.0 - z * z).max(0.0).sqrt();
            Ray::new(origin, Vec3::new(r * phi.cos(), r * phi.sin(), z))
        })
        .collect()
}
