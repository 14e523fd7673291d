//! Build and trace benchmarks of viewray-geometry's BVH on a 1,310,720-triangle
//! icosphere, side by side with the obvhs crate (CWBVH) on the same mesh and rays.
//!
//! `cargo bench -p viewray-geometry --features bench` prints, before criterion's timings, the memory per
//! triangle of both structures and a check that both find the same hits. Criterion's
//! `thrpt` lines are rays (or triangles, for the build) per second. `viewray` traces
//! with `Mesh::closest_triangle` (t and face, as obvhs reports them); `viewray packets`
//! with `Mesh::closest_triangles`, which traces 64 rays at a time (the primary rays in
//! blocks of 8 x 8 pixels, as the renderer does); `viewray full Hit` with
//! `Mesh::closest_hit`, which also interpolates normals and uv.
//!
//! With `--features embree` (needs the system's Embree 3, e.g. Debian's
//! `libembree-dev`), Embree joins the comparison: build and single-ray queries. Set `VIEWRAY_BENCH_SUBDIVISIONS` to bench a
//! smaller icosphere (default 8: 20 * 4^8 triangles).

use std::hint::black_box;
use std::time::Duration;

use criterion::{BatchSize, Criterion, Throughput};
use glam::{Vec3, Vec3A};
use rayon::prelude::*;
use viewray_geometry::{Mesh, MeshData, Ray};

/// The lecture's perspective camera: eye (0, 0, 3) looking down -z, d = 1, a 1 x 1
/// viewport; pixel (i, j), 1-based, gets the direction
/// (u, v, -1) with u = (j - 1/2)/W - 1/2, v = -((i - 1/2)/H - 1/2).
fn primary_rays(width: usize, height: usize) -> Vec<Ray> {
    let eye = Vec3::new(0.0, 0.0, 3.0);
    (1..=height)
        .flat_map(|i| {
            (1..=width).map(move |j| {
                let u = (j as f32 - 0.5) / width as f32 - 0.5;
                let v = -((i as f32 - 0.5) / height as f32 - 0.5);
                Ray::new(eye, Vec3::new(u, v, -1.0))
            })
        })
        .collect()
}

/// The same rays reordered into blocks of 8 x 8 pixels, block after block, as a
/// renderer hands them to [`Mesh::closest_triangles`].
fn in_blocks(rays: &[Ray], width: usize) -> Vec<Ray> {
    let height = rays.len() / width;
    let mut blocked = Vec::with_capacity(rays.len());
    for block_row in (0..height).step_by(8) {
        for block_col in (0..width).step_by(8) {
            for row in block_row..(block_row + 8).min(height) {
                let start = row * width + block_col;
                blocked.extend_from_slice(&rays[start..start + 8.min(width - block_col)]);
            }
        }
    }
    blocked
}

/// `count` rays with origins uniform in `[-1, 1]^3` and directions uniform on the
/// sphere, from a fixed seed (SplitMix64).
fn incoherent_rays(count: usize) -> Vec<Ray> {
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

/// obvhs's CWBVH with its triangles stored in BVH order, as its examples recommend.
struct Obvhs {
    bvh: obvhs::cwbvh::CwBvh,
    triangles: Vec<obvhs::triangle::Triangle>,
}

impl Obvhs {
    fn build(triangles: &[obvhs::triangle::Triangle]) -> Self {
        let bvh = obvhs::cwbvh::builder::build_cwbvh_from_tris(
            triangles,
            obvhs::BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let triangles = bvh
            .primitive_indices
            .iter()
            .map(|&i| triangles[i as usize])
            .collect();
        Self { bvh, triangles }
    }

    fn closest_t(&self, ray: &Ray) -> Option<f32> {
        let ray = obvhs::ray::Ray::new_inf(ray.origin.into(), ray.direction.into());
        let mut hit = obvhs::ray::RayHit::none();
        self.bvh
            .ray_traverse(ray, &mut hit, |ray, id| self.triangles[id].intersect(ray))
            .then_some(hit.t)
    }

    fn bytes(&self) -> usize {
        self.bvh.nodes.len() * std::mem::size_of::<obvhs::cwbvh::node::CwBvhNode>()
            + self.bvh.primitive_indices.len() * 4
            + self.triangles.len() * std::mem::size_of::<obvhs::triangle::Triangle>()
    }
}

/// Embree 3 (the system library) on the same mesh, with its default build quality and
/// single-ray queries: only with `--features embree`.
#[cfg(feature = "embree")]
struct Embree {
    // Declared before the device so that it is released first.
    scene: embree3::Scene<'static>,
    _device: embree3::Device,
}

#[cfg(feature = "embree")]
impl Embree {
    /// Builds the scene with `threads` build threads (0: all).
    fn build(data: &MeshData, threads: u32) -> Self {
        use embree3::{BufferUsage, Config, Device, Format, GeometryKind};
        let device = Device::with_config(Config {
            threads,
            ..Config::default()
        })
        .expect("an Embree device");
        let mut scene = device.create_scene().expect("an Embree scene");
        let mut mesh = device
            .create_geometry(GeometryKind::TRIANGLE)
            .expect("an Embree triangle mesh");
        let positions: Vec<[f32; 3]> = data.positions.iter().map(|p| p.to_array()).collect();
        mesh.set_new_buffer::<[f32; 3]>(
            BufferUsage::VERTEX,
            0,
            Format::FLOAT3,
            12,
            positions.len(),
        )
        .expect("a vertex buffer")
        .copy_from_slice(&positions);
        mesh.set_new_buffer::<[u32; 3]>(
            BufferUsage::INDEX,
            0,
            Format::UINT3,
            12,
            data.triangles.len(),
        )
        .expect("an index buffer")
        .copy_from_slice(&data.triangles);
        let mesh = mesh.commit();
        scene.attach_geometry(&mesh);
        scene.commit();
        Self {
            scene,
            _device: device,
        }
    }

    fn closest_t(&self, ray: &Ray) -> Option<f32> {
        let mut context = embree3::IntersectContext::incoherent();
        let mut ray_hit = embree3::RayHit::from(embree3::Ray::segment(
            ray.origin.to_array(),
            ray.direction.to_array(),
            0.0,
            f32::INFINITY,
        ));
        self.scene.intersect(&mut context, &mut ray_hit);
        ray_hit.hit.is_valid().then_some(ray_hit.ray.tfar)
    }
}

fn obvhs_triangles(data: &MeshData) -> Vec<obvhs::triangle::Triangle> {
    data.triangles
        .iter()
        .map(|t| {
            let [v0, v1, v2] = t.map(|i| Vec3A::from(data.positions[i as usize]));
            obvhs::triangle::Triangle { v0, v1, v2 }
        })
        .collect()
}

/// Sum of the hit distances, so that no work can be optimized away: the closest
/// triangle's `t` and face, what obvhs reports too.
fn trace_viewray(mesh: &Mesh, rays: &[Ray]) -> f32 {
    rays.iter()
        .filter_map(|ray| mesh.closest_triangle(ray, 0.0..f32::INFINITY))
        .map(|hit| hit.t)
        .sum()
}

/// The same with the rays traced in packets of 64 by [`Mesh::closest_triangles`].
fn trace_viewray_packets(mesh: &Mesh, rays: &[Ray]) -> f32 {
    let mut hits = vec![None; rays.len().min(1024)];
    rays.chunks(1024)
        .map(|rays| {
            let hits = &mut hits[..rays.len()];
            mesh.closest_triangles(rays, 0.0..f32::INFINITY, hits);
            hits.iter().flatten().map(|hit| hit.t).sum::<f32>()
        })
        .sum()
}

/// The same with the full [`viewray_geometry::Hit`] (normals, shading normal, uv).
fn trace_viewray_full_hit(mesh: &Mesh, rays: &[Ray]) -> f32 {
    rays.iter()
        .filter_map(|ray| mesh.closest_hit(ray, 0.0..f32::INFINITY))
        .map(|hit| hit.t)
        .sum()
}

fn trace_obvhs(bvh: &Obvhs, rays: &[Ray]) -> f32 {
    rays.iter().filter_map(|ray| bvh.closest_t(ray)).sum()
}

fn parallel(rays: &[Ray], trace: impl Fn(&[Ray]) -> f32 + Sync) -> f32 {
    rays.par_chunks(1024).map(&trace).sum()
}

fn main() {
    let subdivisions = std::env::var("VIEWRAY_BENCH_SUBDIVISIONS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(8);
    let data = MeshData::icosphere(subdivisions, 1.0);
    let triangles = data.triangles.len();
    let threads = rayon::current_num_threads();
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool");

    let mesh = Mesh::new(data.clone()).expect("the icosphere is valid");
    let obvhs_input = obvhs_triangles(&data);
    let peer = Obvhs::build(&obvhs_input);
    #[cfg(feature = "embree")]
    let embree = Embree::build(&data, 0);
    let primary = primary_rays(1024, 1024);
    let primary_blocks = in_blocks(&primary, 1024);
    let incoherent = incoherent_rays(1_000_000);

    println!("icosphere: {triangles} triangles, {threads} threads");
    println!(
        "memory per triangle: viewray {:.1} bytes (BVH + triangle packets), obvhs {:.1} bytes (CWBVH + indices + triangles)",
        mesh.acceleration_bytes() as f64 / triangles as f64,
        peer.bytes() as f64 / triangles as f64,
    );
    for (name, rays) in [("primary", &primary), ("incoherent", &incoherent)] {
        let ours: Vec<Option<f32>> = rays
            .par_iter()
            .map(|r| mesh.closest_hit(r, 0.0..f32::INFINITY).map(|h| h.t))
            .collect();
        let theirs: Vec<Option<f32>> = rays.par_iter().map(|r| peer.closest_t(r)).collect();
        let hits = ours.iter().flatten().count();
        #[cfg(feature = "embree")]
        {
            let embree_agrees = rays
                .par_iter()
                .zip(&ours)
                .filter(|(ray, ours)| match (embree.closest_t(ray), ours) {
                    (Some(a), Some(b)) => (a - b).abs() <= 1e-4 * a.max(1.0),
                    (None, None) => true,
                    _ => false,
                })
                .count();
            println!(
                "{name} rays: Embree agrees on {embree_agrees} ({:.4}%)",
                100.0 * embree_agrees as f64 / rays.len() as f64
            );
        }
        let agree = ours
            .iter()
            .zip(&theirs)
            .filter(|(a, b)| match (a, b) {
                (Some(a), Some(b)) => (a - b).abs() <= 1e-4 * a.max(1.0),
                (None, None) => true,
                _ => false,
            })
            .count();
        println!(
            "{name} rays: {} rays, {hits} hits, obvhs agrees on {agree} ({:.4}%)",
            rays.len(),
            100.0 * agree as f64 / rays.len() as f64
        );
    }

    let mut criterion = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(4))
        .configure_from_args();

    {
        let mut group = criterion.benchmark_group("build");
        group.throughput(Throughput::Elements(triangles as u64));
        group.bench_function("viewray/1 thread", |b| {
            b.iter_batched(
                || data.clone(),
                |data| one_thread.install(|| Mesh::new(data)),
                BatchSize::LargeInput,
            )
        });
        group.bench_function(format!("viewray/{threads} threads"), |b| {
            b.iter_batched(|| data.clone(), Mesh::new, BatchSize::LargeInput)
        });
        group.bench_function("obvhs/1 thread", |b| {
            b.iter(|| one_thread.install(|| Obvhs::build(&obvhs_input)))
        });
        group.bench_function(format!("obvhs/{threads} threads"), |b| {
            b.iter(|| Obvhs::build(&obvhs_input))
        });
        #[cfg(feature = "embree")]
        {
            group.bench_function("embree/1 thread", |b| b.iter(|| Embree::build(&data, 1)));
            group.bench_function(format!("embree/{threads} threads"), |b| {
                b.iter(|| Embree::build(&data, 0))
            });
        }
        group.finish();
    }

    for (name, rays, packet_rays) in [
        ("primary", &primary, &primary_blocks),
        ("incoherent", &incoherent, &incoherent),
    ] {
        let mut group = criterion.benchmark_group(name);
        group.throughput(Throughput::Elements(rays.len() as u64));
        group.bench_function("viewray/1 thread", |b| {
            b.iter(|| black_box(trace_viewray(&mesh, rays)))
        });
        group.bench_function(format!("viewray/{threads} threads"), |b| {
            b.iter(|| black_box(parallel(rays, |r| trace_viewray(&mesh, r))))
        });
        group.bench_function("viewray packets/1 thread", |b| {
            b.iter(|| black_box(trace_viewray_packets(&mesh, packet_rays)))
        });
        group.bench_function(format!("viewray packets/{threads} threads"), |b| {
            b.iter(|| black_box(parallel(packet_rays, |r| trace_viewray_packets(&mesh, r))))
        });
        group.bench_function("viewray full Hit/1 thread", |b| {
            b.iter(|| black_box(trace_viewray_full_hit(&mesh, rays)))
        });
        group.bench_function("obvhs/1 thread", |b| {
            b.iter(|| black_box(trace_obvhs(&peer, rays)))
        });
        group.bench_function(format!("obvhs/{threads} threads"), |b| {
            b.iter(|| black_box(parallel(rays, |r| trace_obvhs(&peer, r))))
        });
        #[cfg(feature = "embree")]
        {
            let trace_embree =
                |rays: &[Ray]| -> f32 { rays.iter().filter_map(|ray| embree.closest_t(ray)).sum() };
            group.bench_function("embree/1 thread", |b| {
                b.iter(|| black_box(trace_embree(rays)))
            });
            group.bench_function(format!("embree/{threads} threads"), |b| {
                b.iter(|| black_box(parallel(rays, trace_embree)))
            });
        }
        group.finish();
    }
    criterion.final_summary();
}
