//! Triangle meshes: validated vertex data, triangle packets in leaf order, and the BVH.
//!
//! - `data`: [`MeshData`], the vertex and face data before validation, with its
//!   generators ([`MeshData::icosphere`], [`MeshData::cuboid`]) and its checks.
//! - `build`: [`Mesh`], built once from the data: the BVH over the triangles that have
//!   an area, and the triangles stored leaf by leaf in packets of four.
//! - `packets`: the triangle packets' layout and the watertight test of one ray against
//!   four triangles at once.
//! - `trace`: the ray queries, one ray at a time and in packets ([`TriangleHit`]).

mod build;
mod data;
mod packets;
mod trace;

pub use build::Mesh;
pub use data::MeshData;
#[cfg(test)]
pub(crate) use packets::{ITEMS_PER_PACKET, items_capacity, packets_bound};
pub use trace::TriangleHit;
