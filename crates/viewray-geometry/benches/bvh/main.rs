//! Build and trace benchmarks of viewray-geometry's BVH on icospheres of 20,480,
//! 81,920, 327,680 and 1,310,720 triangles (5 to 8 subdivisions), with `--features
//! embree` side by side with Embree 3 on the same triangles and rays, in one run that
//! prints one table.
//!
//! `cargo bench -p viewray-geometry --features bench,embree` prints, for each mesh, a
//! check that viewray, Embree and obvhs (CWBVH) find the same hits and the memory per
//! triangle of viewray's and obvhs's structures, then the table. Its cases, each on a
//! pool of 1 thread and of 2:
//!
//! - **build**: `Mesh::new` against Embree's build (default quality, as many build
//!   threads), with viewray's bytes per triangle;
//! - **primary, coherent**: 1024 x 1024 primary rays (eye (0, 0, 3) looking down -z)
//!   through viewray-render's `render` of the mesh (Flat shading, one sample: what
//!   `viewray render --stats` times, called as it calls it), the same rays bare through
//!   the packet kernel (`Mesh::closest_triangles` on tiles of 8 x 8, as the renderer
//!   hands them over), and Embree's `rtcIntersect16` on tiles of 4 x 4 (coherent
//!   context);
//! - **incoherent**: a million random rays one by one (`Mesh::closest_triangle` against
//!   `rtcIntersect1`) and together (`Mesh::closest_triangles`, 64 at a time, against
//!   `rtcIntersect16` in an incoherent context);
//! - **world**: a world of several objects (the mesh, three small icospheres placed by
//!   instances and a ground of two triangles; Embree is given the same triangles in
//!   world space, one geometry per object): the mirror rays and the shadow rays toward
//!   a sun from the primary rays' hits, and the million random rays as shadow rays of
//!   length 0.5, one by one (`World::closest_object`, `World::any_hit` against
//!   `rtcIntersect1`, `rtcOccluded1`) and together (`World::closest_objects`,
//!   `World::any_hits` on the rays of 8 x 8 tiles against `rtcIntersect16`,
//!   `rtcOccluded16` on those of 4 x 4 tiles, in an incoherent context).
//!
//! Each figure is the median of `VIEWRAY_BENCH_RUNS` runs (default 3) after a warm-up
//! run, with the spread (slowest to fastest) beside it. A case's contenders take turns,
//! one run each per round, so that a slow spell of a shared machine weighs on all of
//! them alike; viewray's lines carry the ratio of viewray's speed to Embree's, of the
//! medians and as the median of each round's ratio. `VIEWRAY_BENCH_SUBDIVISIONS` picks
//! the meshes (such as `8` or `5,6`; default `5,6,7,8`). Embree needs the system's
//! Embree 3 (Debian's `libembree-dev`); without `--features embree` the table holds
//! viewray's figures alone.

mod obvhs;
mod rays;
mod render;
mod timing;
mod world;

#[cfg(feature = "embree")]
mod embree;

use std::sync::Arc;

use rayon::prelude::*;
use viewray_geometry::{Mesh, MeshData, Ray, World};

use timing::{Case, Contender, Table};

/// A case's contenders: viewray's, then Embree's when the benchmark has Embree (its
/// expression is left out, unevaluated and unresolved, when it has not).
macro_rules! contenders {
    ([$($ours:expr),+ $(,)?], $embree:expr $(,)?) => {{
        #[cfg_attr(not(feature = "embree"), allow(unused_mut))]
        let mut contenders = vec![$($ours),+];
        #[cfg(feature = "embree")]
        contenders.push($embree);
        contenders
    }};
}

/// The rays every mesh is traced with.
struct Rays {
    /// 1024 x 1024 primary rays, row after row.
    primary: Vec<Ray>,
    /// The same in tiles of 8 x 8 pixels.
    primary_8x8: Vec<Ray>,
    /// The same in tiles of 4 x 4 pixels, for Embree's packets of 16.
    #[cfg(feature = "embree")]
    primary_4x4: Vec<Ray>,
    /// A million random rays.
    incoherent: Vec<Ray>,
}

/// The length of the random shadow rays (their directions are unit vectors).
const SHADOW_LENGTH: f32 = 0.5;

fn main() {
    let subdivisions: Vec<u32> = match std::env::var("VIEWRAY_BENCH_SUBDIVISIONS") {
        Ok(list) => list
            .split(',')
            .map(|s| {
                s.trim()
                    .parse()
                    .expect("VIEWRAY_BENCH_SUBDIVISIONS: numbers such as 5,6")
            })
            .collect(),
        Err(_) => vec![5, 6, 7, 8],
    };
    let runs = std::env::var("VIEWRAY_BENCH_RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(3usize)
        .max(1);
    let pools: Vec<rayon::ThreadPool> = [1, 2]
        .map(|threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("a pool")
        })
        .into();
    let primary = rays::primary_rays(1024, 1024);
    let rays = Rays {
        primary_8x8: rays::in_tiles(&primary, 1024, 8, 8),
        #[cfg(feature = "embree")]
        primary_4x4: rays::in_tiles(&primary, 1024, 4, 4),
        primary,
        incoherent: rays::incoherent_rays(1_000_000),
    };
    println!("{runs} runs per contender, on pools of 1 and 2 threads");
    let mut table = Table::new(runs);
    for subdivisions in subdivisions {
        bench_mesh(
            &mut table,
            &MeshData::icosphere(subdivisions, 1.0),
            &pools,
            &rays,
        );
    }
    table.print();
}

/// Checks the hits and races every case on the icosphere `data`.
fn bench_mesh(table: &mut Table, data: &MeshData, pools: &[rayon::ThreadPool], rays: &Rays) {
    let triangles = data.triangles.len();
    let mesh = Arc::new(Mesh::new(data.clone()).expect("the icosphere is valid"));
    let (world, world_triangles) = world::world(&mesh, data);
    // On one thread, and alive through the build cases (see `Embree::build`).
    #[cfg(feature = "embree")]
    let embree = embree::Embree::build(std::slice::from_ref(data), 1);
    #[cfg(feature = "embree")]
    let embree_world = embree::Embree::build(&world_triangles, 1);
    println!(
        "icosphere: {triangles} triangles ({} in the world)",
        world.triangle_count()
    );
    #[cfg(feature = "embree")]
    let embree_closest = |ray: &Ray| Some(embree.closest_t(ray));
    #[cfg(not(feature = "embree"))]
    let embree_closest = |_: &Ray| None;
    check_hits(&mesh, data, rays, embree_closest);
    drop(world_triangles);

    for pool in pools {
        let threads = pool.current_num_threads();
        let bytes = mesh.acceleration_bytes() as f64 / triangles as f64;
        let contenders = contenders!(
            [Contender::new(
                "viewray",
                format!("Mesh::new ({bytes:.1} bytes a triangle)"),
                || data.clone(),
                |data| drop(pool.install(|| Mesh::new(data))),
            )],
            Contender::new(
                "embree",
                "rtcCommitScene (default quality)",
                || (),
                |()| drop(embree::Embree::build(
                    std::slice::from_ref(data),
                    threads as u32
                )),
            ),
        );
        let case = Case {
            triangles,
            name: "build".to_owned(),
            threads,
            rays: None,
        };
        table.race(case, contenders);
    }

    let scene = render::scene(&mesh, 1024);
    let mirror_8x8 = world::secondary_rays(&world, &rays.primary_8x8, world::mirror);
    let shadow_8x8 = world::secondary_rays(&world, &rays.primary_8x8, world::shadow);
    #[cfg(feature = "embree")]
    let mirror_4x4 = world::secondary_rays(&world, &rays.primary_4x4, world::mirror);
    #[cfg(feature = "embree")]
    let shadow_4x4 = world::secondary_rays(&world, &rays.primary_4x4, world::shadow);
    for pool in pools {
        let threads = pool.current_num_threads();
        let case = |name: &str, rays: &[Ray]| Case {
            triangles,
            name: name.to_owned(),
            threads,
            rays: Some(rays.len()),
        };
        let world = &world;
        #[cfg(feature = "embree")]
        let embree_world = &embree_world;

        let contenders = contenders!(
            [
                Contender::timed("viewray", "render (Flat, 1 sample)", || {
                    render::render_seconds(&scene, pool)
                }),
                Contender::traced(pool, "viewray", "closest_triangles (8 x 8)", || parallel(
                    &rays.primary_8x8,
                    |r| packets(&mesh, r)
                ),),
            ],
            Contender::traced(pool, "embree", "rtcIntersect16 (4 x 4)", || parallel(
                &rays.primary_4x4,
                |r| embree.trace_16(r, true)
            ),),
        );
        table.race(case("primary, coherent", &rays.primary), contenders);

        let incoherent = &rays.incoherent;
        let contenders = contenders!(
            [Contender::traced(
                pool,
                "viewray",
                "closest_triangle",
                || parallel(incoherent, |r| one_by_one(&mesh, r)),
            )],
            Contender::traced(pool, "embree", "rtcIntersect1", || parallel(
                incoherent,
                |r| embree.trace_single(r)
            ),),
        );
        table.race(case("incoherent, one by one", incoherent), contenders);
        let contenders = contenders!(
            [Contender::traced(
                pool,
                "viewray",
                "closest_triangles (64)",
                || parallel(incoherent, |r| packets(&mesh, r)),
            )],
            Contender::traced(pool, "embree", "rtcIntersect16", || parallel(
                incoherent,
                |r| embree.trace_16(r, false)
            ),),
        );
        table.race(case("incoherent, together", incoherent), contenders);

        let contenders = contenders!(
            [Contender::traced(
                pool,
                "viewray",
                "World::closest_object",
                || parallel(&mirror_8x8, |r| world_one_by_one(world, r)),
            )],
            Contender::traced(pool, "embree", "rtcIntersect1", || parallel(
                &mirror_8x8,
                |r| embree_world.trace_single(r)
            ),),
        );
        table.race(case("world: mirror, one by one", &mirror_8x8), contenders);
        let contenders = contenders!(
            [Contender::traced(
                pool,
                "viewray",
                "World::closest_objects (64)",
                || parallel(&mirror_8x8, |r| world_packets(world, r)),
            )],
            Contender::traced(pool, "embree", "rtcIntersect16", || parallel(
                &mirror_4x4,
                |r| embree_world.trace_16(r, false)
            ),),
        );
        table.race(case("world: mirror, together", &mirror_8x8), contenders);

        let shadow_cases = [
            ("world: sun shadow", &shadow_8x8, f32::INFINITY),
            ("world: random shadow", incoherent, SHADOW_LENGTH),
        ];
        for (name, shadow, t_max) in shadow_cases {
            #[cfg(feature = "embree")]
            let shadow_16 = if t_max.is_finite() {
                incoherent
            } else {
                &shadow_4x4
            };
            let contenders = contenders!(
                [Contender::traced(
                    pool,
                    "viewray",
                    "World::any_hit",
                    move || parallel(shadow, |r| any_one_by_one(world, r, t_max)),
                )],
                Contender::traced(pool, "embree", "rtcOccluded1", move || parallel(
                    shadow,
                    |r| embree_world.occluded_single(r, t_max)
                ),),
            );
            table.race(case(&format!("{name}, one by one"), shadow), contenders);
            let contenders = contenders!(
                [Contender::traced(
                    pool,
                    "viewray",
                    "World::any_hits (64)",
                    move || parallel(shadow, |r| any_packets(world, r, t_max)),
                )],
                Contender::traced(
                    pool,
                    "embree",
                    "rtcOccluded16",
                    Box::new(move || {
                        parallel(shadow_16, |r| embree_world.occluded_16(r, t_max, false))
                    }),
                ),
            );
            table.race(case(&format!("{name}, together"), shadow), contenders);
        }
    }
}

/// Prints how many of the primary and the random rays' closest hits Embree (when
/// `embree` gives `Some`) and obvhs agree on with viewray's (within 1e-4 of `t`), and
/// the memory per triangle of viewray's and obvhs's structures.
fn check_hits(
    mesh: &Mesh,
    data: &MeshData,
    rays: &Rays,
    embree: impl Fn(&Ray) -> Option<Option<f32>> + Sync,
) {
    let peer = obvhs::Obvhs::build(data);
    let triangles = data.triangles.len() as f64;
    println!(
        "memory per triangle: viewray {:.1} bytes (BVH + triangle packets), obvhs {:.1} bytes (CWBVH + indices + triangles)",
        mesh.acceleration_bytes() as f64 / triangles,
        peer.bytes() as f64 / triangles,
    );
    let same = |a: Option<f32>, b: Option<f32>| match (a, b) {
        (Some(a), Some(b)) => (a - b).abs() <= 1e-4 * a.max(1.0),
        (None, None) => true,
        _ => false,
    };
    for (name, rays) in [("primary", &rays.primary), ("random", &rays.incoherent)] {
        let (hits, obvhs_agrees, embree_agrees) = rays
            .par_iter()
            .map(|ray| {
                let ours = mesh.closest_hit(ray, 0.0..f32::INFINITY).map(|h| h.t);
                let embree = embree(ray).map(|theirs| same(ours, theirs));
                let obvhs = same(ours, peer.closest_t(ray));
                (
                    usize::from(ours.is_some()),
                    usize::from(obvhs),
                    usize::from(embree == Some(true)),
                )
            })
            .reduce(|| (0, 0, 0), |a, b| (a.0 + b.0, a.1 + b.1, a.2 + b.2));
        let share = |n: usize| 100.0 * n as f64 / rays.len() as f64;
        let embree_agrees = if cfg!(feature = "embree") {
            format!(", Embree on {embree_agrees} ({:.4}%)", share(embree_agrees))
        } else {
            String::new()
        };
        println!(
            "{name} rays: {} rays, {hits} hits; obvhs agrees on {obvhs_agrees} ({:.4}%){embree_agrees}",
            rays.len(),
            share(obvhs_agrees),
        );
    }
}

/// Traces `rays` in chunks of 1024 on the current pool and sums what `trace` returns.
fn parallel(rays: &[Ray], trace: impl Fn(&[Ray]) -> f32 + Sync) -> f32 {
    rays.par_chunks(1024).map(&trace).sum()
}

/// The sum of the hit distances of `rays` traced one by one (`t` and face, what the
/// peers report too), so that no work can be optimized away.
fn one_by_one(mesh: &Mesh, rays: &[Ray]) -> f32 {
    rays.iter()
        .filter_map(|ray| mesh.closest_triangle(ray, 0.0..f32::INFINITY))
        .map(|hit| hit.t)
        .sum()
}

/// The same with the rays traced in packets of 64 by [`Mesh::closest_triangles`].
fn packets(mesh: &Mesh, rays: &[Ray]) -> f32 {
    let mut hits = vec![None; rays.len()];
    mesh.closest_triangles(rays, 0.0..f32::INFINITY, &mut hits);
    hits.iter().flatten().map(|hit| hit.t).sum()
}

/// The sum of the hit distances of `rays` traced one by one through `world`.
fn world_one_by_one(world: &World, rays: &[Ray]) -> f32 {
    rays.iter()
        .filter_map(|ray| world.closest_object(ray, 0.0..f32::INFINITY))
        .map(|hit| hit.t)
        .sum()
}

/// The same with the rays traced in packets of 64 by [`World::closest_objects`].
fn world_packets(world: &World, rays: &[Ray]) -> f32 {
    let mut hits = vec![None; rays.len()];
    world.closest_objects(rays, 0.0..f32::INFINITY, &mut hits);
    hits.iter().flatten().map(|hit| hit.t).sum()
}

/// How many of `rays` hit something in `world` with `t` in `[0, t_max)`, asked one by
/// one.
fn any_one_by_one(world: &World, rays: &[Ray], t_max: f32) -> f32 {
    rays.iter()
        .filter(|ray| world.any_hit(ray, 0.0..t_max))
        .count() as f32
}

/// The same asked in packets of 64 by [`World::any_hits`].
fn any_packets(world: &World, rays: &[Ray], t_max: f32) -> f32 {
    let mut hits = vec![false; rays.len()];
    world.any_hits(rays, 0.0..t_max, &mut hits);
    hits.iter().filter(|&&hit| hit).count() as f32
}
