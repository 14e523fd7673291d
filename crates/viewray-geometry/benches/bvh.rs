//! Build and trace benchmarks of viewray-geometry's BVH on a 1,310,720-triangle
//! icosphere, side by side with the obvhs crate (CWBVH) and, with `--features embree`,
//! Embree 3, on the same mesh and rays, in one run.
//!
//! `cargo bench -p viewray-geometry --features bench` prints the memory per triangle of
//! both structures, a check that they find the same hits, then one table: each case
//! (build; coherent primary rays; primary and incoherent rays ray by ray; incoherent
//! rays in batches; on 1 thread and on all) with viewray's line first, then its peers'
//! with the ratio of viewray's speed to theirs (above 1: viewray is faster). Each
//! figure is the median of `VIEWRAY_BENCH_RUNS` runs (default 5) after a warm-up run,
//! with the spread (slowest to fastest) beside it. A case's contenders take turns, one
//! run each per round, so that a slow spell of a shared machine weighs on all of them
//! alike; the ratio is given both ways, of the medians and as the median of each
//! round's ratio (runs moments apart, so a spell over one round moves both of its runs).
//!
//! viewray traces coherent rays with `Mesh::closest_triangles`, 64 at a time (the
//! primary rays in tiles of 8 x 8 pixels, as the renderer does), and single rays with
//! `Mesh::closest_triangle` (t and face, as the peers report them); the incoherent rays
//! also 64 at a time with `Mesh::closest_triangles`, which walks a large mesh's
//! incoherent packets ray by ray, several rays side by side. With `--features embree`
//! (needs the system's Embree 3, e.g. Debian's `libembree-dev`) Embree traces the
//! coherent rays with its packet kernels, `rtcIntersect16` on tiles of 4 x 4 pixels and
//! `rtcIntersect8` on 4 x 2, in a coherent context, single rays with `rtcIntersect1`,
//! and the incoherent batches with both `rtcIntersect1` and `rtcIntersect16` (in an
//! incoherent context). Set `VIEWRAY_BENCH_SUBDIVISIONS` to bench a smaller icosphere
//! (default 8: 20 * 4^8 triangles).

use std::hint::black_box;
use std::time::{Duration, Instant};

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

/// The same rays reordered into tiles of `tile_width x tile_height` pixels, tile after
/// tile (8 x 8 as a renderer hands them to [`Mesh::closest_triangles`]; 4 x 4 and 4 x 2
/// for Embree's packets of 16 and 8).
fn in_tiles(rays: &[Ray], width: usize, tile_width: usize, tile_height: usize) -> Vec<Ray> {
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

/// Embree 3 (the system library) on the same mesh, with its default build quality:
/// only with `--features embree`.
#[cfg(feature = "embree")]
struct Embree {
    // Declared before the device so that it is released first.
    scene: embree3::Scene<'static>,
    _device: embree3::Device,
}

#[cfg(feature = "embree")]
impl Embree {
    /// Builds the scene with `threads` build threads (0: all).
    ///
    /// Embree runs a build on as many threads as the most any live device asked for
    /// (`getMaxNumThreads` in its `device.cpp`), not on the count of the device that
    /// builds: while a device of all threads lives, a one-thread device builds on all
    /// of them too.
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

    /// `rtcIntersect1`: the closest hit's `t`.
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

    /// The sum of the hit distances of `rays` traced one by one (`rtcIntersect1`).
    fn trace_single(&self, rays: &[Ray]) -> f32 {
        rays.iter().filter_map(|ray| self.closest_t(ray)).sum()
    }

    /// The same with the rays traced 8 at a time (`rtcIntersect8`, coherent context):
    /// `rays` holds tiles of 4 x 2 pixels, tile after tile.
    fn trace_8(&self, rays: &[Ray]) -> f32 {
        let mut context = embree3::IntersectContext::coherent();
        let valid = embree3::ValidMaskN::<8>::all_active();
        let mut sum = 0.0;
        for tile in rays.chunks_exact(8) {
            let mut ray_hit = embree3::RayHit8 {
                ray: embree3::Ray8::new(
                    std::array::from_fn(|i| tile[i].origin.to_array()),
                    std::array::from_fn(|i| tile[i].direction.to_array()),
                ),
                hit: embree3::Hit8::new(),
            };
            self.scene.intersect8(&mut context, &mut ray_hit, &valid);
            sum += hit_sum(&ray_hit.ray.tfar, &ray_hit.hit.geomID);
        }
        sum
    }

    /// The same 16 at a time (`rtcIntersect16`), in a coherent context when `rays`
    /// holds tiles of 4 x 4 pixels, else in an incoherent one.
    fn trace_16(&self, rays: &[Ray], coherent: bool) -> f32 {
        let mut context = if coherent {
            embree3::IntersectContext::coherent()
        } else {
            embree3::IntersectContext::incoherent()
        };
        let valid = embree3::ValidMaskN::<16>::all_active();
        let mut sum = 0.0;
        for tile in rays.chunks_exact(16) {
            let mut ray_hit = embree3::RayHit16 {
                ray: embree3::Ray16::new(
                    std::array::from_fn(|i| tile[i].origin.to_array()),
                    std::array::from_fn(|i| tile[i].direction.to_array()),
                ),
                hit: embree3::Hit16::new(),
            };
            self.scene.intersect16(&mut context, &mut ray_hit, &valid);
            sum += hit_sum(&ray_hit.ray.tfar, &ray_hit.hit.geomID);
        }
        sum
    }
}

/// The sum of the distances of a packet's lanes that hit something.
#[cfg(feature = "embree")]
fn hit_sum(tfar: &[f32], geometry: &[u32]) -> f32 {
    tfar.iter()
        .zip(geometry)
        .filter(|&(_, &g)| g != embree3::INVALID_ID)
        .map(|(t, _)| t)
        .sum()
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

fn trace_obvhs(bvh: &Obvhs, rays: &[Ray]) -> f32 {
    rays.iter().filter_map(|ray| bvh.closest_t(ray)).sum()
}

fn parallel(rays: &[Ray], chunk: usize, trace: impl Fn(&[Ray]) -> f32 + Sync) -> f32 {
    rays.par_chunks(chunk).map(&trace).sum()
}

/// Seconds per run: the median, fastest and slowest of a benchmark's runs, and every
/// run in its round's order.
#[derive(Clone, Debug)]
struct Timing {
    median: f64,
    min: f64,
    max: f64,
    rounds: Vec<f64>,
}

/// One way of running a case: who runs it, how, and one run that reports its own
/// time in seconds (so that a setup, such as copying the mesh for a build, is not
/// timed).
struct Contender<'a> {
    who: &'static str,
    how: &'static str,
    run: Box<dyn FnMut() -> f64 + 'a>,
}

impl<'a> Contender<'a> {
    /// Times `run` on a fresh `setup()` each time.
    fn new<T>(
        who: &'static str,
        how: &'static str,
        mut setup: impl FnMut() -> T + 'a,
        mut run: impl FnMut(T) + 'a,
    ) -> Self {
        Self {
            who,
            how,
            run: Box::new(move || {
                let input = setup();
                let start = Instant::now();
                run(input);
                start.elapsed().as_secs_f64()
            }),
        }
    }

    /// Times `trace` on `pool`.
    fn traced(
        pool: &'a rayon::ThreadPool,
        who: &'static str,
        how: &'static str,
        trace: Box<dyn Fn() -> f32 + Sync + 'a>,
    ) -> Self {
        Self::new(
            who,
            how,
            || (),
            move |()| {
                black_box(pool.install(&trace));
            },
        )
    }
}

/// Runs a case's contenders in turns: a warm-up run of each, then `runs` rounds in
/// which each runs once. On a shared machine slow spells last seconds; taking turns
/// lets a spell fall on every contender of the case rather than on whichever ran then,
/// so the ratios hold even when the figures move.
fn race(table: &mut Table, case: &str, mut contenders: Vec<Contender<'_>>) {
    let runs = table.runs;
    for contender in &mut contenders {
        (contender.run)();
    }
    let mut seconds = vec![Vec::with_capacity(runs); contenders.len()];
    for _ in 0..runs {
        for (contender, seconds) in contenders.iter_mut().zip(&mut seconds) {
            seconds.push((contender.run)());
        }
    }
    for (contender, rounds) in contenders.into_iter().zip(seconds) {
        let mut seconds = rounds.clone();
        seconds.sort_by(f64::total_cmp);
        let timing = Timing {
            median: seconds[seconds.len() / 2],
            min: seconds[0],
            max: seconds[seconds.len() - 1],
            rounds,
        };
        table.add(case, contender.who, contender.how, timing);
    }
}

/// One line of the table: who ran a case, how, and how long it took.
struct Line {
    case: String,
    who: &'static str,
    how: &'static str,
    timing: Timing,
}

/// The benchmark's results: each case's viewray line first, then its peers.
struct Table {
    runs: usize,
    lines: Vec<Line>,
}

impl Table {
    fn add(&mut self, case: &str, who: &'static str, how: &'static str, timing: Timing) {
        eprintln!(
            "  {case}: {who} {how}: {:.4} s (median of {})",
            timing.median, self.runs
        );
        self.lines.push(Line {
            case: case.to_owned(),
            who,
            how,
            timing,
        });
    }

    /// Prints every line with its figure (seconds for builds, Mrays/s for tracing), the
    /// spread of its runs, and the ratio of viewray's speed to the peer's (above 1:
    /// viewray is faster): of the two medians, and the median of each round's ratio
    /// (the peer's run against viewray's in the same round, moments apart: the steadier
    /// of the two when the machine has slow spells).
    fn print(&self, rays_of: impl Fn(&str) -> Option<usize>) {
        println!();
        println!("ratio: viewray's speed over the peer's (above 1.00x: viewray is faster)");
        println!("paired: the median of each round's ratio");
        let how = self
            .lines
            .iter()
            .map(|line| line.how.len())
            .max()
            .unwrap_or(0);
        println!(
            "{:<34} {:<8} {:<how$} {:>14} {:>12} {:>6} {:>6}",
            "case", "who", "how", "median", "spread", "ratio", "paired"
        );
        let mut ours: Option<&Line> = None;
        for line in &self.lines {
            if line.who == "viewray" {
                ours = Some(line);
            }
            let (figure, low, high) = match rays_of(&line.case) {
                Some(rays) => {
                    let speed = |s: f64| rays as f64 / s / 1e6;
                    (
                        format!("{:.2} Mrays/s", speed(line.timing.median)),
                        speed(line.timing.max),
                        speed(line.timing.min),
                    )
                }
                None => (
                    format!("{:.3} s", line.timing.median),
                    line.timing.min,
                    line.timing.max,
                ),
            };
            let (ratio, paired) = match ours {
                Some(ours) if line.who != "viewray" && ours.case == line.case => {
                    let mut rounds: Vec<f64> = (line.timing.rounds.iter())
                        .zip(&ours.timing.rounds)
                        .map(|(theirs, ours)| theirs / ours)
                        .collect();
                    rounds.sort_by(f64::total_cmp);
                    (
                        format!("{:.2}x", line.timing.median / ours.timing.median),
                        format!("{:.2}x", rounds[rounds.len() / 2]),
                    )
                }
                _ => (String::new(), String::new()),
            };
            println!(
                "{:<34} {:<8} {:<how$} {:>14} {:>12} {:>6} {:>6}",
                line.case,
                line.who,
                line.how,
                figure,
                format!("{low:.2}-{high:.2}"),
                ratio,
                paired
            );
        }
    }
}

fn main() {
    let subdivisions = std::env::var("VIEWRAY_BENCH_SUBDIVISIONS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(8);
    let runs = std::env::var("VIEWRAY_BENCH_RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(5usize)
        .max(1);
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
    // On one thread: it lives through the build cases (see `Embree::build`).
    #[cfg(feature = "embree")]
    let embree = Embree::build(&data, 1);
    let primary = primary_rays(1024, 1024);
    let primary_8x8 = in_tiles(&primary, 1024, 8, 8);
    let incoherent = incoherent_rays(1_000_000);

    println!("icosphere: {triangles} triangles, {threads} threads, {runs} runs per case");
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
        let same = |a: &Option<f32>, b: &Option<f32>| match (a, b) {
            (Some(a), Some(b)) => (a - b).abs() <= 1e-4 * a.max(1.0),
            (None, None) => true,
            _ => false,
        };
        #[cfg(feature = "embree")]
        {
            let embree_agrees = rays
                .par_iter()
                .zip(&ours)
                .filter(|(ray, ours)| same(&embree.closest_t(ray), ours))
                .count();
            println!(
                "{name} rays: Embree agrees on {embree_agrees} ({:.4}%)",
                100.0 * embree_agrees as f64 / rays.len() as f64
            );
        }
        let agree = ours.iter().zip(&theirs).filter(|(a, b)| same(a, b)).count();
        println!(
            "{name} rays: {} rays, {hits} hits, obvhs agrees on {agree} ({:.4}%)",
            rays.len(),
            100.0 * agree as f64 / rays.len() as f64
        );
    }

    let mut table = Table {
        runs,
        lines: Vec::new(),
    };
    let thread_counts = [
        (1, "1 thread".to_owned()),
        (threads, format!("{threads} threads")),
    ];
    for (count, label) in &thread_counts {
        let pool = if *count == 1 {
            &one_thread
        } else {
            &rayon::ThreadPoolBuilder::new()
                .num_threads(*count)
                .build()
                .expect("a pool")
        };
        let mut contenders = vec![Contender::new(
            "viewray",
            "binned SAH, 8 wide",
            || data.clone(),
            |data| drop(pool.install(|| Mesh::new(data))),
        )];
        #[cfg(feature = "embree")]
        contenders.push(Contender::new(
            "embree",
            "default quality",
            || (),
            |()| drop(Embree::build(&data, *count as u32)),
        ));
        contenders.push(Contender::new(
            "obvhs",
            "CWBVH, medium",
            || (),
            |()| drop(pool.install(|| Obvhs::build(&obvhs_input))),
        ));
        race(&mut table, &format!("build, {label}"), contenders);
    }

    #[cfg(feature = "embree")]
    let (primary_4x4, primary_4x2) = (
        in_tiles(&primary, 1024, 4, 4),
        in_tiles(&primary, 1024, 4, 2),
    );
    for (count, label) in &thread_counts {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(*count)
            .build()
            .expect("a pool");
        let traced = |who, how, trace| Contender::traced(&pool, who, how, trace);
        #[cfg_attr(not(feature = "embree"), allow(unused_mut))]
        let mut contenders = vec![traced(
            "viewray",
            "packets of 64 (8 x 8)",
            Box::new(|| parallel(&primary_8x8, 1024, |r| trace_viewray_packets(&mesh, r))),
        )];
        #[cfg(feature = "embree")]
        {
            contenders.push(traced(
                "embree",
                "rtcIntersect16 (4 x 4)",
                Box::new(|| parallel(&primary_4x4, 1024, |r| embree.trace_16(r, true))),
            ));
            contenders.push(traced(
                "embree",
                "rtcIntersect8 (4 x 2)",
                Box::new(|| parallel(&primary_4x2, 1024, |r| embree.trace_8(r))),
            ));
        }
        race(
            &mut table,
            &format!("primary, coherent, {label}"),
            contenders,
        );
        for (name, rays) in [("primary", &primary), ("incoherent", &incoherent)] {
            let mut contenders = vec![traced(
                "viewray",
                "closest_triangle",
                Box::new(|| parallel(rays, 1024, |r| trace_viewray(&mesh, r))),
            )];
            #[cfg(feature = "embree")]
            contenders.push(traced(
                "embree",
                "rtcIntersect1",
                Box::new(|| parallel(rays, 1024, |r| embree.trace_single(r))),
            ));
            contenders.push(traced(
                "obvhs",
                "ray_traverse",
                Box::new(|| parallel(rays, 1024, |r| trace_obvhs(&peer, r))),
            ));
            race(
                &mut table,
                &format!("{name}, ray by ray, {label}"),
                contenders,
            );
        }
        // Incoherent rays handed over many at a time: viewray walks each packet's rays
        // side by side; Embree's packet kernel, beside its single-ray one.
        #[cfg_attr(not(feature = "embree"), allow(unused_mut))]
        let mut contenders = vec![traced(
            "viewray",
            "closest_triangles, 64 at a time",
            Box::new(|| parallel(&incoherent, 1024, |r| trace_viewray_packets(&mesh, r))),
        )];
        #[cfg(feature = "embree")]
        {
            contenders.push(traced(
                "embree",
                "rtcIntersect1",
                Box::new(|| parallel(&incoherent, 1024, |r| embree.trace_single(r))),
            ));
            contenders.push(traced(
                "embree",
                "rtcIntersect16, incoherent",
                Box::new(|| parallel(&incoherent, 1024, |r| embree.trace_16(r, false))),
            ));
        }
        race(
            &mut table,
            &format!("incoherent, batches, {label}"),
            contenders,
        );
    }
    table.print(|case| {
        if case.starts_with("primary") {
            Some(primary.len())
        } else if case.starts_with("incoherent") {
            Some(incoherent.len())
        } else {
            None
        }
    });
}
