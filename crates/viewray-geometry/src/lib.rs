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
//! # Invariant
//!
//! Every query answers as the plain single-ray arithmetic does. A packet query
//! ([`Mesh::closest_triangles`], [`World::closest_objects`], [`World::any_hits`]) finds
//! the hits its rays find traced one by one (of two surfaces at exactly the same `t`,
//! either), because a packet's tests only cull what every ray's own test would, and each
//! ray's own tests are the single-ray ones. Where the processor has AVX, the box tests run
//! in 256-bit registers with the SSE test's operations in its order and no fused
//! multiply-add, so hits and images are the same bits on every x86-64 processor. A
//! [`Mesh`] exists only for data that passed its checks ([`GeometryError`] otherwise).
//! The tests compare packets with single rays, AVX with SSE, and the BVH with brute force.
//!
//! # Map
//!
//! - [`Ray`], [`DRay`]: rays in `f32` (tracing) and `f64` (camera arithmetic);
//!   [`RayBounds`]: a box of rays, whose [`Reach`] in a world [`World::reach`] tells.
//! - [`Sphere`], [`Plane`], [`Triangle`], [`Aabb`] (the `Box` primitive and the BVH's
//!   bound; [`Aabb::corners`] is the one home of a box's corners): analytic shapes, each
//!   with `closest_hit`.
//! - [`MeshData`] (vertex data, from vectors or tobj's flat arrays, plus the
//!   [`MeshData::icosphere`] and [`MeshData::cuboid`] generators) and [`Mesh`] (validated,
//!   with its BVH); [`Instance`]: a shared mesh placed by an affine transform.
//! - [`World`]: a list of [`Object`]s with a top-level BVH; hits name the object's index.
//! - [`Hit`]: what a closest-hit query reports; [`TriangleHit`] and [`ObjectHit`]: the
//!   closest triangle or object before its surface details are computed;
//!   [`GeometryError`]: why data was refused.
//! - [`Bvh`]: the hierarchy itself, generic over anything [`Bounded`].
//!
//! # Where to start reading
//!
//! `ray.rs` and [`Aabb::slab_interval`] hold the lecture's formulas; `shapes/mod.rs` the
//! watertight triangle test every mesh shares. Then `bvh/mod.rs`, the hierarchy's map:
//! `bvh/traverse.rs` walks a single ray through it (`Bvh::closest_step` is one step of
//! that walk) and `bvh/build.rs` builds it. `mesh/mod.rs` and `world/mod.rs` put triangles
//! and objects in it; `packet/mod.rs` traces many rays through it together. `tests.rs`
//! states what the crate promises, checked against brute force.
//!
//! # Modules
//!
//! - `ray`, `hit`, `error`: the rays, what queries report, why data was refused.
//! - `aabb`: boxes, their slab test and their corners.
//! - `shapes`: sphere, plane, triangle, and the watertight ray/triangle test; four
//!   rays at once against a sphere or a triangle (`shapes/lanes.rs`).
//! - `bvh`: the eight-wide hierarchy: node layout, build, a single ray's walks, and the
//!   prefetch and huge-pages hints.
//! - `mesh`: mesh data and its checks, the build into triangle packets in leaf order,
//!   the four-triangle test, and the mesh's queries.
//! - `instance`: meshes placed by transforms, rays carried into object space.
//! - `world`: the objects of a scene under a top-level hierarchy, with the packet
//!   queries a renderer uses for primary, mirror and shadow rays (`world/loose.rs`: a
//!   packet's lanes against loose spheres and triangles, four at a time; `world/flat.rs`:
//!   a world of one object, or of one leaf, takes its rays four at a time without
//!   packets).
//! - `packet`: up to 64 rays of one octant traced together, and incoherent rays walked
//!   side by side.
//! - `avx`: the box tests in AVX registers, chosen at run time.
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
//! - **An eight-wide BVH by binned SAH.** Nodes store their children's boxes as rows of
//!   planes, tested several at once; leaves point at packets of four triangles in
//!   structure-of-arrays layout, stored in leaf order and tested at once. A ray visits
//!   the children it enters nearest first and skips those beyond its closest hit.
//! - **Packets.** Coherent rays (a renderer's 8 x 8 block, its shadow rays toward a
//!   light) walk the upper levels once, with one interval test per node that bounds
//!   every ray; leaves and fine subtrees go to the rays that enter them.
//! - **Deferred surfaces.** Traversal keeps only `t`, face and barycentrics; normals and
//!   texture coordinates are computed once, for the winner.
//!
//! Why each choice was made, what it gained and what was measured and left out, with
//! the date, commit and command of every figure: `docs/performance.md` in the
//! repository.
//!
//! # Unsafe code
//!
//! The workspace denies `unsafe_code`; this crate opts in at 16 sites (13 in the
//! library, 3 in tests), each with a `SAFETY` comment and allowed where it stands
//! (`avx.rs` allows it for the whole module), all for x86_64 intrinsics or one system
//! call. (The triangle packets reuse the build
//! items' buffer through bytemuck, with no unsafe code.)
//!
//! - `bvh/memory.rs` (two): the prefetch hint (`_mm_prefetch`, which reads nothing and
//!   never faults) and the `madvise` that asks Linux for huge pages (a hint about pages
//!   the buffer owns, which never changes their contents).
//! - `bvh/build.rs` (one): the builder's SSE2 conversion of an item's three bins to
//!   integers (register arithmetic; SSE2 is part of the x86_64 baseline).
//! - `bvh/traverse.rs` (two), `packet/closest.rs` (one) and `packet/any.rs` (one): calls
//!   into the traversals compiled for AVX, made only where AVX and POPCNT were detected
//!   at run time.
//! - `avx.rs` (six, and one in its tests), the only home of the AVX intrinsics: an
//!   unaligned 256-bit load of a node's row of eight planes and a store of eight entry
//!   distances, each exactly eight `f32`, and four calls that need AVX, made through an
//!   `AvxRay` or `AvxPacket`, which exist only where AVX was detected.
//! - `packet/tests.rs` (two): a test's `AvxPacket`s, made after the same detection.

mod aabb;
#[cfg(target_arch = "x86_64")]
mod avx;
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
pub use ray::{DRay, Ray, RayBounds};
pub use shapes::{Plane, Sphere, Triangle};
pub use world::{Object, ObjectHit, Reach, World};
