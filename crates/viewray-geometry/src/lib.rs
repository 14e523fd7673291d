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
//!   count, which bounds the depth and so the traversal stack.
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
//!   as their boxes are hit (the crate's one `unsafe`: the x86_64 prefetch hint).
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
//! `cargo bench -p viewray-geometry --features bench` measures build time, memory and
//! throughput on a 1,310,720-triangle icosphere side by side with the obvhs crate
//! (CWBVH), and with `--features embree` Embree 3 too (called ray by ray,
//! `rtcIntersect1`). On the 2-core
//! development machine, idle, the last full run gave (ratios come from one run):
//!
//! | | viewray | obvhs | Embree 3 |
//! |---|---|---|---|
//! | build, 1 / 2 threads | 0.71 s / 0.48 s | 1.06 s / 0.87 s | 0.25 s / 0.28 s |
//! | bytes per triangle | 54 | 60 | |
//! | primary, packets, 1 / 2 threads | 14.0 / 26.2 Mrays/s | | |
//! | primary, ray by ray, 1 / 2 threads | 6.0 / 11.1 Mrays/s | 3.2 / 6.5 | 9.1 / 17.9 |
//! | incoherent, ray by ray, 1 / 2 threads | 1.62 / 3.29 Mrays/s | 0.92 / 1.84 | 1.94 / 3.93 |
//!
//! Runs vary: over several runs, primary packets on 1 thread gave 11.1 to 14.0 Mrays/s
//! and the incoherent ratio to obvhs 1.5 to 1.8. Computing the full [`Hit`]
//! costs a twentieth more on primary rays and half again on incoherent ones, for the
//! vertex data it reads.

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
