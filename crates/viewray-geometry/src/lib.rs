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
//!   are one SSE2 conversion. Each of these leaves the tree the same, node for node.
//! - **Structure-of-arrays nodes and triangle packets.** A node stores its children's
//!   boxes as rows of eight floats, tested four at a time with SSE (glam's `Vec4`, the
//!   x86_64 baseline: no `target-cpu=native`). Leaves point at packets of four triangles
//!   in structure-of-arrays layout, stored in leaf order, tested at once.
//! - **Ordered, allocation-free traversal.** Children hit are visited nearest first, and
//!   subtrees entered beyond the closest hit so far are skipped. The traversal is
//!   compiled once per sign pattern of the direction, so the near and far plane of each
//!   slab are constants. Its stack is a fixed array reused from a thread-local (zeroing
//!   a fresh one per ray cost a quarter of a primary ray). On large meshes rays are
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
//! (`VIEWRAY_BENCH_RUNS=3`, so each figure a median of 3; load average 1.7 to 3 while
//! they ran), the first two with the current code, the third with the code before its
//! builder work; Embree's own figures move by a third between runs, so read the ratios
//! within a run:
//!
//! | 1 thread unless stated | run 1 | run 2 | before (run 3) |
//! |---|---|---|---|
//! | build | 0.469 s (Embree 0.243: 0.52x) | 0.549 s (0.410: 0.75x) | 0.674 s (0.322: 0.48x) |
//! | build, 2 threads | 0.315 s (0.251: 0.80x) | 0.311 s (0.251: 0.81x) | 0.382 s (0.239: 0.62x) |
//! | coherent, packets of 64 vs `rtcIntersect16` | 14.89 Mrays/s (0.82x) | 11.14 (0.62x) | 13.16 (0.77x) |
//! | coherent, packets of 64 vs `rtcIntersect8` | 0.99x | 0.76x | 0.96x |
//! | primary, ray by ray vs `rtcIntersect1` | 6.41 Mrays/s (0.71x) | 6.84 (0.77x) | 6.27 (0.69x) |
//! | incoherent vs `rtcIntersect1` | 1.30 Mrays/s (0.68x) | 1.22 (0.75x) | 1.43 (0.80x) |
//! | coherent, 2 threads, vs `rtcIntersect16` | 21.40 Mrays/s (0.64x) | 20.73 (0.70x) | 24.86 (0.73x) |
//! | incoherent, 2 threads, vs `rtcIntersect1` | 3.53 Mrays/s (0.80x) | 2.33 (0.70x) | 2.57 (0.77x) |
//!
//! Memory: 53.9 bytes per triangle (BVH + triangle packets; obvhs 60.3). viewray is
//! 1.4x to 2.7x faster than obvhs everywhere. The tree is the same in all three runs,
//! node for node, and so are the traces' instructions (callgrind counts the same
//! 60,682,020 for the packets of the `coherent` workload at 7 subdivisions before and
//! after), so the spread of the tracing figures is the machine's, not the code's;
//! the build went from 0.674 s to 0.47-0.55 s on 1 thread and from 0.38 to 0.31 s on 2.
//! An earlier run on an idle machine gave Embree 18.6 Mrays/s with `rtcIntersect16`,
//! 9.1 ray by ray, 1.8-1.9 incoherent and a 0.25-0.32 s build.
//!
//! Because wall-clock time on a shared machine is this noisy, changes are decided on
//! instruction counts: `examples/profile.rs` is a fixed workload for callgrind (see its
//! doc). On its 81,920-triangle icosphere (6 subdivisions) the code as of this writing
//! executes, per ray, about 656 instructions for a coherent primary ray in packets of
//! 64 (`Bvh::closest_packet`), 1,124 for the same ray alone (`Bvh::closest_prepared`)
//! and 1,468 for an incoherent ray. Its `build` workload (the icosphere generated once,
//! then built five times) executes 1,209 M instructions, down from 1,849 M before the
//! builder work (about 2,800 instead of 4,400 per triangle and build). Instruction
//! counts are no substitute for the table (Embree uses AVX-512 and its rays wait on
//! memory), but two builds of viewray compare reliably.
//!
//! Where the time goes (callgrind, one thread):
//!
//! - **A render of the icosphere** (`viewray render target/icosphere/icosphere.ron
//!   --stats --threads 1`, Flat shading, 1024 x 1024 primary rays) executes 1,013 M
//!   instructions, of which packet tracing ([`World::closest_objects`], which hands
//!   the packets straight to the mesh) is 735 M (72.5%): the render costs 1.38x its
//!   tracing in instructions, short of the 1.10x aimed for. The rest is the camera's
//!   `f64` ray generation (125 M, 119 instructions a ray: two `f64` frame transforms
//!   and the projection), the block's bookkeeping (about 125 M: film points, hit and
//!   colour buffers, accumulation) and Flat shading (29 M). In wall-clock time, where
//!   tracing waits on memory, the share lost is smaller: `render_s` gave 5.3 Mrays/s
//!   (median of 3, spread 4.9 to 7.0) while the benchmark's packets gave 6.7 to 10.9
//!   in the same hour.
//! - **The default scene, Lit** (`viewray render --size 320x180 --samples 4 --threads
//!   1`, 16 objects) executes about 2,170 instructions per sample: shadow-ray packets
//!   ([`World::any_hits`], 350), primary and mirror packets (350), camera rays and
//!   sampling (about 300), and about 1,150 of shading and bookkeeping: grid lines
//!   filtered over each sample's footprint (540 per sample that sees the ground),
//!   surface details, Blinn-Phong with `powf`, the block's buffers. With so few objects
//!   a packet's setup (its slab numbers) costs as much as its traversal.
//!
//! Shadow and mirror rays now go as packets and Lit samples are shaded a block at a
//! time; cameras without a lens draw no lens samples. On the default scene at 1280 x
//! 720, 16 samples, 2 threads (`viewray render --size 1280x720 --samples 16 --threads 2
//! --stats`, 38,387,820 rays, the image byte-identical), the renderer before this work
//! took 4.73 / 4.91 / 5.45 s and now takes 3.81 / 3.91 / 4.19 s: 1.25x by the medians
//! (4.91 s against 3.91 s), short of the 2x aimed for by a factor of 1.6. Its
//! instruction count at 320 x 180 and 4 samples fell from 574 M to 501 M (1.15x):
//! shadow rays from 125 M (`any_hit` ray by ray) to 84 M, all tracing from about 225 M
//! to 165 M; shading and ray generation, which packets do not touch, are two thirds of
//! what is left, so even free tracing would not give 2x.

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
