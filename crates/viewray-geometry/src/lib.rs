//! viewray's ray-casting core: rays, shapes, triangle meshes and the BVH.
//!
//! This crate owns the geometry a viewing ray meets. It knows nothing about cameras,
//! scene files or images, and it does no I/O.
//!
//! Rays keep the lecture's *unnormalized* directions: a ray is `origin + t * direction`
//! and every `t` this crate reports is in units of the ray's own direction, whatever
//! its length. Queries take a range `t_range` and accept `t_range.start <= t <
//! t_range.end`; a shadow ray toward a light at `p = origin + direction` is
//! `any_hit(&ray, 1e-4..1.0)`.
//!
//! # Map
//!
//! - [`Ray`], [`DRay`]: rays in `f32` (tracing) and `f64` (camera arithmetic).
//! - [`Sphere`], [`Plane`], [`Triangle`], [`Aabb`] (the `Box` primitive and the BVH's
//!   bound): analytic shapes, each with `closest_hit`.
//! - [`MeshData`] (vertex data, from vectors or tobj's flat arrays, plus the
//!   [`MeshData::icosphere`] and [`MeshData::cuboid`] generators) and [`Mesh`] (validated,
//!   with its BVH); [`Instance`]: a shared mesh placed by an affine transform.
//! - [`World`]: a list of [`Object`]s with a top-level BVH; hits name the object's index.
//! - [`Hit`]: what a closest-hit query reports; [`TriangleHit`] and [`ObjectHit`]: the
//!   closest triangle or object before its surface details are computed;
//!   [`GeometryError`]: why data was refused.
//! - [`Bvh`]: the hierarchy itself, generic over anything [`Bounded`].
//!
//! # Design
//!
//! Robustness first, then speed; every choice below is covered by the tests in
//! `src/tests.rs` (brute-force agreement, watertightness, edge cases).
//!
//! - **Watertight triangles.** Ray/triangle tests follow Woop, Benthin and Wald,
//!   "Watertight Ray/Triangle Intersection" (JCGT 2013): the ray is sheared onto +z,
//!   edge functions of a shared edge are bit-identical in both triangles, and exact
//!   zeros are recomputed in `f64`. A ray through an edge or vertex of a closed mesh
//!   never slips through; zero-area faces are dropped when a mesh is built.
//! - **Robust boxes.** Box exits are widened by `1 + 2 gamma(3)` (Ize, "Robust BVH Ray
//!   Traversal", JCGT 2013), and a direction component of zero is handled without NaN,
//!   so that axis-parallel rays along box faces (common with orthographic cameras and
//!   axis-aligned meshes) still enter the boxes they graze.
//! - **Binned SAH, eight children per node.** 32 bins per axis; a node is opened by
//!   repeatedly splitting its largest child until it has eight, splits that fill a free
//!   slot cost no extra node, leaves hold at most 8 triangles. Large ranges are binned
//!   and built in parallel with rayon. After a depth of 40 the build halves ranges by
//!   count, which bounds the depth and so the traversal stack. The build is shaped by
//!   its small ranges, of which there are as many as leaves: a range no bigger than one
//!   block becomes a leaf without binning (no split can be cheaper), sweeps skip empty
//!   bins (a split behind one costs what the split before it did), build items are two
//!   aligned SIMD registers with the index in a spare lane, and the three bins of an item
//!   are one SSE2 conversion. Large ranges bin their even and odd items into two sets of
//!   bins merged after (neighbouring items fall in the same bins, and one set would make
//!   each update wait for the last). Each of these leaves the tree the same, node for
//!   node. Around the tree, a mesh writes its build items in place in parallel and fills
//!   its triangle packets in parallel too: on 2 threads these serial steps had been a
//!   fifth of the build.
//! - **Structure-of-arrays nodes and triangle packets.** A node stores its children's
//!   boxes as rows of eight floats, tested four at a time with SSE (glam's `Vec4`, the
//!   x86_64 baseline: no `target-cpu=native`). Leaves point at packets of four triangles
//!   in structure-of-arrays layout, stored in leaf order, tested at once.
//! - **Ordered, allocation-free traversal.** Children hit are visited nearest first, and
//!   subtrees entered beyond the closest hit so far are skipped. The traversal is
//!   compiled once per sign pattern of the direction, so the near and far plane of each
//!   slab are constants. Its stack is a fixed array reused from a thread-local (zeroing
//!   a fresh one per ray cost a quarter of a primary ray), with a node's row to spare so
//!   that a node's sorted children are pushed by one fixed-size copy (a copy of the
//!   exact length was a call to `memcpy` per node). On large meshes rays are
//!   bound by memory latency, so the children a ray will visit are prefetched as soon
//!   as their boxes are hit (one of the crate's two `unsafe` blocks: the x86_64
//!   prefetch hint; the other is the builder's SSE2 float-to-integer conversion).
//! - **Packets for coherent rays.** [`Mesh::closest_triangles`] and
//!   [`World::closest_objects`] trace up to 64 rays of one octant (a renderer's 8 x 8
//!   pixel block) together. One interval-arithmetic test per node bounds every ray of
//!   the packet at once; rounded subtraction and multiplication are monotonic, so it
//!   never culls a box that a ray's own test would enter. Leaves, and the children of a
//!   node where the packet enters six or more (geometry fine next to the packet), are
//!   tested against each ray, four rays per SSE instruction with exactly the single-ray
//!   arithmetic, and the rays that hit finish them alone. A packet therefore finds the
//!   hits its rays find alone (of two surfaces at exactly the same `t`, either may be
//!   reported), for a fraction of the node visits: the upper levels, which every ray of
//!   a block repeats, are walked once. Packets whose unit directions spread more than
//!   0.05 (random rays) are traced ray by ray. A packet's slab numbers are set up four
//!   rays at a time, bit for bit as for single rays.
//! - **Packets for shadow rays.** [`World::any_hits`] traces up to 64 rays of one octant
//!   (a block's shadow rays toward one light) together: the packet's interval test walks
//!   the top-level BVH once, each leaf goes to the rays whose own box test enters it,
//!   and a ray that hits stops searching; every ray gets the answer [`World::any_hit`]
//!   gives it. The numbers a packet is set up from (seven kilobytes) are reused from a
//!   thread-local: zeroing them for each batch of shadow rays cost more than tracing it.
//! - **Short cuts for simple worlds.** A world with one bounded object skips its
//!   top-level BVH (whose one box only repeats the object's own first test), and an
//!   instance with the identity transform does not carry rays into object space.
//! - **Deferred surfaces.** Traversal keeps only `t`, face and barycentrics; normals and
//!   texture coordinates are computed once, for the winner ([`Mesh::closest_triangle`],
//!   [`World::closest_object`] and the packet queries skip them altogether).
//!
//! # Speed
//!
//! `cargo bench -p viewray-geometry --features bench` measures build time, memory and
//! throughput on a 1,310,720-triangle icosphere side by side with the obvhs crate
//! (CWBVH); `--features bench,embree` adds Embree 3 (the system's libembree3) in the
//! same run: its packet kernels `rtcIntersect16` (tiles of 4 x 4 pixels) and
//! `rtcIntersect8` (4 x 2) on the coherent primary rays, `rtcIntersect1` ray by ray, and
//! its build. It prints one table with the ratio of viewray's speed to each peer's
//! (above 1.00x: viewray is faster). Three full runs on the 2-core development machine
//! (`VIEWRAY_BENCH_RUNS=3`, so each figure a median of 3; load average about 1.5), with
//! the code as of this writing, and the two runs of the version before its last round
//! of build and traversal work; Embree's own figures move by a tenth to a third between
//! runs, so read the ratios within a run:
//!
//! | 1 thread unless stated | run 1 | run 2 | run 3 | before (two runs) |
//! |---|---|---|---|---|
//! | build | 0.434 s (Embree 0.229: 0.53x) | 0.427 s (0.216: 0.51x) | 0.446 s (0.246: 0.55x) | 0.469 s (0.52x), 0.549 s (0.75x) |
//! | build, 2 threads | 0.259 s (0.240: 0.92x) | 0.236 s (0.232: 0.98x) | 0.263 s (0.241: 0.92x) | 0.315 s (0.80x), 0.311 s (0.81x) |
//! | coherent, packets of 64 vs `rtcIntersect16` | 12.86 Mrays/s (0.72x) | 15.27 (0.81x) | 14.74 (0.80x) | 14.89 (0.82x), 11.14 (0.62x) |
//! | coherent, packets of 64 vs `rtcIntersect8` | 0.85x | 1.01x | 0.97x | 0.99x, 0.76x |
//! | primary, ray by ray vs `rtcIntersect1` | 6.77 Mrays/s (0.73x) | 6.53 (0.71x) | 7.08 (0.78x) | 6.41 (0.71x), 6.84 (0.77x) |
//! | incoherent vs `rtcIntersect1` | 1.56 Mrays/s (0.84x) | 1.60 (0.82x) | 1.41 (0.74x) | 1.30 (0.68x), 1.22 (0.75x) |
//! | coherent, 2 threads, vs `rtcIntersect16` | 22.66 Mrays/s (0.67x) | 20.74 (0.69x) | 29.63 (0.81x) | 21.40 (0.64x), 20.73 (0.70x) |
//! | incoherent, 2 threads, vs `rtcIntersect1` | 3.66 Mrays/s (0.95x) | 3.46 (0.93x) | 3.80 (0.96x) | 3.53 (0.80x), 2.33 (0.70x) |
//!
//! Memory: 53.9 bytes per triangle (BVH + triangle packets; obvhs 60.3). viewray is
//! 1.4x to 2.7x faster than obvhs everywhere. The tree is the same, node for node, as
//! before this round (its steps change how the tree is built, not which), so the
//! packets' figures moved with the machine: callgrind counts 50.1 M instructions for
//! the packets of `examples/profile.rs`'s `coherent` workload before and 49.5 M after.
//! The build's serial steps went parallel and its binning waits less, so 2 threads
//! gained most (0.80x to 0.92-0.98x); single rays and incoherent rays execute about 5%
//! fewer instructions (the children pushed by one fixed-size copy).
//!
//! Because wall-clock time on a shared machine is this noisy, changes are decided on
//! instruction counts: `examples/profile.rs` is a fixed workload for callgrind (see its
//! doc). On its 81,920-triangle icosphere (6 subdivisions) the tracing of the 65,536
//! primary rays executes 49.5 M instructions in packets of 64 (`Bvh::closest_packet`),
//! 77.5 M one by one (`Bvh::closest_prepared`, 81.4 M before the fixed-size push), and
//! of 100,000 incoherent rays 151.8 M (158.5 M before). Its `build` workload (the
//! icosphere generated once, then built five times) executes 1,223 M instructions (1,849 M
//! before the builder's rewrite). Instruction counts are no substitute for the table
//! (Embree uses AVX-512 and its rays wait on memory), but two builds of viewray compare
//! reliably. A build of the whole crate for `x86-64-v3` (AVX2, FMA, BMI) instead of the
//! x86_64 baseline gained only about 5% in one run (coherent 0.85x, ray by ray 0.85x),
//! not enough to close the gap by itself: the packets would need eight-wide node and
//! leaf tests, with runtime dispatch, to reach Embree's.
//!
//! Where the time goes (callgrind, one thread):
//!
//! - **A render of the icosphere** (`viewray render target/icosphere/icosphere.ron
//!   --stats --threads 1`, Flat shading, 1024 x 1024 primary rays) executes 887 M
//!   instructions, of which packet tracing ([`World::closest_objects`], which hands the
//!   packets straight to the mesh) is 735 M: the render costs 1.21x its tracing in
//!   instructions (1.39x before a perspective camera shared its eye and `-d w` across
//!   rays and the block loop stopped building film points it does not use). In wall-clock
//!   time, `viewray-render`'s `examples/icosphere.rs` times the render against the same
//!   rays traced as the same packets: the fastest of 11 runs gives 1.07x to 1.14x on 1
//!   thread (before: 1.34x to 1.39x), the medians 1.16x to 1.18x (before: 1.31x to 1.40x),
//!   three runs each, the two versions alternated; the aim is 1.10x. What is left is the
//!   camera's `f64` arithmetic (two divisions a ray), the block's bookkeeping and Flat
//!   shading, about 150 instructions a ray together.
//! - **The default scene, Lit** (`viewray render --size 320x180 --samples 4 --threads
//!   1`, 16 objects) executes about 2,000 instructions per sample (459.8 M), down from
//!   2,170: shadow-ray packets ([`World::any_hits`]), primary and mirror packets, camera
//!   rays and sampling, and shading and bookkeeping, which is half: grid lines filtered
//!   over each sample's footprint (`line_coverage`, the footprint and the ray
//!   differentials: 89 M), surface details (`World::surface`, 38 M, which also works out
//!   texture coordinates that Lit shading never reads), Blinn-Phong with `powf`, the
//!   batch's buffers (about 27 M in allocation and `Vec` upkeep; stack buffers in their
//!   place cost more). With so few objects a packet's setup (its slab numbers, 35 M)
//!   costs as much as its traversal.
//!
//! At 1280 x 720, 16 samples, 2 threads (`viewray render --size 1280x720 --samples 16
//! --threads 2 --stats`, 38,387,820 rays, the image byte-identical), five alternated runs
//! give 1.05 to 1.57 s against the previous version's 1.15 to 1.75 s (medians 1.36 and
//! 1.38 s; the fastest runs 8% apart); the machine was too busy for a finer figure. The
//! renderer before packets for shadow and mirror rays took 4.91 s (median) on the
//! machine of that day against 3.91 s after; the 2x aimed for against it is far off,
//! and shading and ray generation, which packets do not touch, are most of what is left.

mod aabb;
mod bvh;
mod error;
mod hit;
mod instance;
mod mesh;
mod packet;
mod ray;
mod shapes;
#[cfg(test)]
mod tests;
mod world;

pub use aabb::Aabb;
pub use bvh::{Bounded, BuildParams, Bvh};
pub use error::GeometryError;
pub use hit::Hit;
pub use instance::Instance;
pub use mesh::{Mesh, MeshData, TriangleHit};
pub use ray::{DRay, Ray};
pub use shapes::{Plane, Sphere, Triangle};
pub use world::{Object, ObjectHit, World};
