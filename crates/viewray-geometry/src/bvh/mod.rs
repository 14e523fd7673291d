//! An eight-wide bounding volume hierarchy, built by binned SAH and traversed front to
//! back.
//!
//! One [`Bvh`] type serves every level: a [`Mesh`](crate::Mesh) indexes its triangles
//! (leaves point at packets of four), and a [`World`](crate::World) indexes its bounded
//! objects. The BVH only knows boxes: callers build it from a slice of anything
//! [`Bounded`] and intersect the items of a leaf themselves, in a closure.
//!
//! - `node`: the layout. Nodes of eight children with their boxes as rows of planes, the
//!   refs that name a child node or a leaf's run of items, and [`Bvh`] itself.
//! - `build`: the binned SAH builder ([`Bvh::build`], [`BuildParams`], [`Bounded`]).
//! - `traverse`: a single ray's box test against a node's children and its walks,
//!   closest hit ([`Bvh::closest`], one step at a time) and any hit ([`Bvh::any`]), with
//!   the stacks they reuse.
//! - `memory`: the prefetch and huge-pages hints, which change no result.
//!
//! The packets' walks through the same nodes are in `crate::packet`, the AVX box tests
//! in `crate::avx`.

mod build;
mod memory;
mod node;
mod traverse;

#[cfg(test)]
mod tests;

pub use build::{Bounded, BuildParams};
pub use node::Bvh;

pub(crate) use build::BuildItem;
pub(crate) use memory::{advise_huge_pages, prefetch};
pub(crate) use node::{GROUPS, LEAF, MAX_ITEMS, Node, WIDTH, decode_leaf};
#[cfg(test)]
pub(crate) use traverse::WALK_ALWAYS;
pub(crate) use traverse::{
    BoxRay, ChildBoxes, ROBUST, RayTraversal, STACK_ROOM, STACK_SIZE, Stack, WALKS, Walk,
    node_planes, per_axis, plane_distances, plane_index, slab_numbers, slab_test, with_stack,
    with_walk_stacks,
};
