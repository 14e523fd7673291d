//! Packets of coherent rays, traversed together through the upper levels of a BVH and
//! one by one through its lower subtrees.
//!
//! A packet holds up to 64 rays whose directions share one sign pattern (octant). Its
//! upper-level box tests bound every ray at once with interval arithmetic (one test per
//! node, as for a single ray). Leaves, and the children of nodes where the packet
//! enters six or more for closest hits, four for any hits (`MANY_CHILDREN` in
//! `closest.rs` and `any.rs`; boxes small next to the packet),
//! are first tested against each ray of the packet (four rays per SIMD instruction) and
//! then handed to the rays that hit their box, which finish them with the ordinary
//! single-ray traversal. Every packet test is conservative with respect to the
//! single-ray one, and each ray's own tests are exactly the single-ray arithmetic, so a
//! packet finds the same hits as its rays traced alone.
//!
//! An incoherent packet (directions spread too far for a shared test) is traced ray by
//! ray; in a tree too large for the caches its rays walk side by side, taking turns one
//! node each, so that their waits for memory overlap.
//!
//! - `lanes`: one number per ray, four rays per vector ([`Lanes`]), and lane masks.
//! - `rays`: a packet's rays and their slab numbers ([`BoxPacket`]), and
//!   [`for_each_packet`], which sorts up to 64 rays into packets of one octant
//!   ([`for_each_packet_unless_scattered`] declines rays spread over five octants or
//!   more).
//! - `boxes`: the packet's interval test of a node's boxes and its rays' own tests,
//!   behind [`PacketBoxes`] (the AVX versions are in `crate::avx`).
//! - `closest`: the closest-hit traversal ([`PacketQuery`], [`PacketVisitor`]).
//! - `any`: the any-hit traversal, for shadow rays (a world's top level and each mesh
//!   its rays reach).

mod any;
mod boxes;
mod closest;
mod lanes;
mod rays;

#[cfg(test)]
mod tests;

pub(crate) use boxes::PacketBoxes;
pub(crate) use closest::{PacketQuery, PacketVisitor};
pub(crate) use lanes::{
    Lanes, PACKET_GROUPS, PACKET_SIZE, at, at_mut, lane, lane_mask, lanes_of, set_lane,
};
pub(crate) use rays::{BoxPacket, for_each_packet, for_each_packet_unless_scattered, ray_lanes};
