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
//!   each update wait for the last). A split moves the items first and then folds each
//!   side's bounds, even and odd items in two chains (gathered while moving, both sides'
//!   eight accumulators spilled out of the SSE registers). The move is one pass without
//!   a branch on the side: each item is swapped with the first item not yet known to go
//!   left, and the count of left items grows by 0 or 1 (the two-ended partition it
//!   replaced branched on every item's side, which a processor cannot predict). Each of these
//!   leaves the nodes the same; the last one changes the order of a leaf's triangles,
//!   which matters only where a ray meets two of them at exactly the same distance (no
//!   image or hit checksum changed). Around the tree, a mesh writes its build items in
//!   place in parallel and fills its triangle packets in parallel too: on 2 threads
//!   these serial steps had been a fifth of the build.
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
//! after this session's changes (`VIEWRAY_BENCH_RUNS=3`, so each figure a median of 3),
//! and the three runs of the session before; Embree's own figures move by a tenth to a
//! third between runs and sessions (its 1-thread build took 0.212 to 0.250 s below,
//! 0.216 to 0.332 s the session before), so read the ratios within a run:
//!
//! | 1 thread unless stated | run 1 | run 2 | run 3 | session before (three runs) |
//! |---|---|---|---|---|
//! | build | 0.356 s (Embree 0.212: 0.59x) | 0.380 s (0.221: 0.58x) | 0.355 s (0.250: 0.70x) | 0.384 to 0.399 s: 0.78x, 0.55x, 0.83x |
//! | build, 2 threads | 0.191 s (0.212: 1.11x) | 0.220 s (0.245: 1.11x) | 0.208 s (0.224: 1.07x) | 1.03x, 0.83x, 1.03x |
//! | coherent, packets of 64 vs `rtcIntersect16` | 15.51 Mrays/s (0.82x) | 13.78 (0.77x) | 15.54 (0.83x) | 0.83x, 0.83x, 0.87x |
//! | coherent, packets of 64 vs `rtcIntersect8` | 1.00x | 0.92x | 1.01x | 1.00x, 1.01x, 1.04x |
//! | primary, ray by ray vs `rtcIntersect1` | 7.31 Mrays/s (0.78x) | 6.90 (0.75x) | 7.45 (0.80x) | 0.78x, 0.78x, 0.76x |
//! | incoherent vs `rtcIntersect1` | 1.84 Mrays/s (0.99x) | 1.83 (0.87x) | 1.71 (0.79x) | 0.97x, 0.81x, 0.85x |
//! | coherent, 2 threads, vs `rtcIntersect16` | 30.24 Mrays/s (0.83x) | 29.83 (0.80x) | 27.45 (0.74x) | 0.81x, 0.83x, 0.68x |
//! | incoherent, 2 threads, vs `rtcIntersect1` | 3.70 Mrays/s (0.87x) | 4.01 (0.99x) | 3.54 (0.77x) | 0.93x, 0.77x, 0.80x |
//!
//! Memory: 53.9 bytes per triangle (BVH + triangle packets; obvhs 60.3). viewray is
//! 1.5x to 3.7x faster than obvhs everywhere. The tracing did not change this session;
//! the build's partition lost its branch on each item's side (below), and the 1-thread
//! build went from 0.384-0.399 s to 0.355-0.380 s. The 2-thread build is at or above
//! Embree's in all three runs (1.07x to 1.11x), and 0.83x to 1.32x over fifteen runs in
//! four sessions.
//!
//! Because wall-clock time on a shared machine is this noisy, changes are decided on
//! instruction counts: `examples/profile.rs` is a fixed workload for callgrind (see its
//! doc). On its 81,920-triangle icosphere (6 subdivisions) the tracing of the 65,536
//! primary rays in packets of 64 (`--toggle-collect='*closest_triangles*'`) executes
//! 48.8 M instructions (49.6 M at the start of this round). Its `build` workload (the
//! icosphere generated once, then built five times) executes 1,187 M instructions for the
//! whole program (1,151 M before the partition lost its branches: more instructions, less
//! time; 1,179 M before a split's bounds were folded after the partition, 1,849 M before
//! the builder's rewrite); at 8 subdivisions (1.3 M triangles) it runs in 2.29 s on 1
//! thread against 2.46 s with the branching partition (medians of seven alternated runs),
//! and in 1.50 s against 1.57 s on 2 (nine, on a busy machine). Instruction counts are no
//! substitute for the table (Embree uses AVX-512 and its rays wait on memory), but two
//! builds of viewray compare reliably.
//!
//! Wider instruction sets, measured and left out:
//!
//! - A build of the whole crate for `x86-64-v4` (AVX-512) traces 10% to 20% faster
//!   (packets at 0.92x to 0.93x of `rtcIntersect16` against 0.77x to 0.81x), but glam
//!   then fuses multiplies and adds at compile time, which changes the bits of a hit.
//!   Compiling only the traversal loops for `x86-64-v3` and `x86-64-v4` beside the
//!   baseline, chosen at run time (the same bits), gained -1% to 5% (packets 15.62, 15.29
//!   and 14.38 Mrays/s against 15.19, 14.53 and 14.54 with the baseline, alternated
//!   runs): not worth three copies of every traversal.
//! - Two rays against a leaf's four triangles per 256-bit AVX instruction (each half
//!   exactly one ray's 128-bit test) cut the icosphere render's instructions by 4.4%
//!   (880 M to 841 M) and its time not at all (`render_s` 0.080 to 0.098 s against
//!   0.080 to 0.090 s, six alternated runs): the leaf tests wait on something other
//!   than their arithmetic, most likely the loads of their triangles.
//!
//! Also measured and left out: the SAH sweep with the three axes side by side (each
//! bin's three boxes unioned, the three half areas in one `Vec3A` with the same
//! operations in the same order, the choice then made axis by axis as before) builds the
//! same tree, node for node, but executes 5.6% more instructions (1,245 M against
//! 1,179 M for the `build` workload, before the partition change): the sweep axis by axis skips empty bins, and most
//! of the ranges a build sees are small ones with many.
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
//!   three runs each, the two versions alternated; the aim is 1.10x. The session before:
//!   1.15x by the fastest runs on 1 and 2 threads, 1.15x to 1.28x by the medians (two
//!   runs). This session (868.5 M instructions, 711.6 M of them tracing: 1.22x), two
//!   runs: 1.13x and 1.15x by the medians on 1 thread, 1.11x and 1.15x on 2, 1.14x by
//!   the fastest runs. What is left
//!   is the camera's `f64` arithmetic (two divisions a ray), the block's bookkeeping
//!   (clearing the tile's sums alone writes as many bytes as the image) and Flat
//!   shading, about 140 instructions a ray together.
//! - **The default scene, Lit** (`viewray render --size 320x180 --samples 4 --threads
//!   1`, 16 objects) executes about 1,760 instructions per sample (405.3 M, the render
//!   loop alone; 442.7 M two sessions ago, 414.3 M before the lights were worked out four
//!   samples at a time in `viewray-render`, 410.0 M before the surfaces were written in
//!   place): shadow-ray packets ([`World::any_hits`],
//!   79 M), primary and mirror packets (73 M), and shading and bookkeeping, which is
//!   more than half: grid lines filtered over each sample's footprint (`line_coverage`
//!   25 M; the footprint and the ray differentials about 30 M), surface details
//!   (`World::surface`, 27 M), Blinn-Phong (10 M, with `powf`), and each sample's
//!   view, offset origin and shadow-ray directions. With so few objects a packet's setup
//!   (its slab numbers and bounds, 43 M) costs as much as its traversal. In `perf`, at
//!   1280 x 720 x 16 on 1 thread, the largest single places are the footprint's two
//!   ray-plane divisions (about 6% of the time), the camera's `f64` ray (about 4%) and
//!   `powf` (2%). Copying each returned `Hit` into the batch took about 7% (the copy
//!   waited for the stores that had just written it) until [`World::shading_surface_into`]
//!   wrote the surfaces in place: 1.724 s to 1.696 s on 1 thread (medians of 7).
//!
//! At 1280 x 720, 16 samples, 2 threads (`viewray render --size 1280x720 --samples 16
//! --threads 2 --stats`, 38,387,820 rays), seven runs alternated with the renderer of
//! the start of this work (401e71b, before shadow and mirror rays went as packets): 0.867
//! to 0.951 s, median 0.886 s, against 1.408 to 1.471 s, median 1.416 s: 1.60x by the
//! medians, 1.62x by the fastest runs (after the lights four at a time alone: median
//! 0.898 s against 1.425 s, 1.59x; the session before: 1.57x). The 2x aimed for is
//! not reached; shading and ray generation, which packets do not touch, are most of
//! what is left, spread over many small steps. Measured and set aside:
//!
//! - `line_coverage` inlined into its caller (0.882 s against 0.884 s, medians of 7) and
//!   `World::surface` inlined across crates (0.962 s against 0.911 s).
//! - The ray prepared for triangles once per leaf rather than once per triangle:
//!   414.2 M to 417.1 M instructions, because the world's leaves hold one or two
//!   objects and there is nothing to share.
//! - The grid footprints four samples at a time, like the lights: 410.0 M to 422.4 M
//!   instructions and no faster (gathering each sample's differentials into lanes costs
//!   more than the divisions it shares).

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
