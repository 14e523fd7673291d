//! The any-hit traversal of a packet (shadow rays): every ray gets the answer its
//! single-ray walk gives.

use glam::Vec4;

use super::lanes::{PACKET_GROUPS, lanes_of};
use super::rays::BoxPacket;
use crate::bvh::{Bvh, LEAF, STACK_ROOM, WIDTH, decode_leaf, with_stack};

impl Bvh {
    /// The any-hit traversal of a packet: which rays of `lanes` meet an item with `t`
    /// in `[t_min, t_max]`. Visits the nodes that some ray still searching may reach
    /// (in no particular order) and hands each leaf to the rays that hit its box,
    /// `leaf(rays, start, count)`, which returns those of `rays` that hit one of the
    /// leaf's items; a ray that hits stops searching. A ray is given exactly the leaves
    /// its single-ray traversal ([`Bvh::any`]) would visit, and so gets its answer.
    pub(crate) fn any_packet(
        &self,
        packet: &BoxPacket<'_>,
        lanes: u64,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u64, u32, u32) -> u64,
    ) -> u64 {
        if self.nodes().is_empty() || lanes == 0 {
            return 0;
        }
        macro_rules! octant {
            ($octant:literal) => {
                with_stack(|stack| {
                    self.any_packet_with_stack::<$octant>(
                        packet,
                        lanes,
                        t_min,
                        t_max,
                        leaf,
                        &mut stack.refs,
                    )
                })
            };
        }
        match packet.octant {
            0 => octant!(0),
            1 => octant!(1),
            2 => octant!(2),
            3 => octant!(3),
            4 => octant!(4),
            5 => octant!(5),
            6 => octant!(6),
            _ => octant!(7),
        }
    }

    fn any_packet_with_stack<const OCTANT: u8>(
        &self,
        packet: &BoxPacket<'_>,
        lanes: u64,
        t_min: f32,
        t_max: f32,
        mut leaf: impl FnMut(u64, u32, u32) -> u64,
        stack: &mut [u32; STACK_ROOM],
    ) -> u64 {
        let nodes = self.nodes();
        let mut hit = 0;
        if !packet.coherent {
            // Ray by ray: the interval test would visit many nodes no ray needs.
            for i in lanes_of(lanes) {
                let ray = packet.lane_ray(i);
                if self.any_with_stack::<OCTANT, _>(
                    &ray,
                    t_min,
                    t_max,
                    |start, count| leaf(1 << i, start, count) != 0,
                    stack,
                ) {
                    hit |= 1 << i;
                }
            }
            return hit;
        }
        debug_assert!(nodes.len() < (1 << 28), "entries are node * 8 + slot");
        let (t_min4, t_max4) = (Vec4::splat(t_min), Vec4::splat(t_max));
        let t_max_lanes = [t_max4; PACKET_GROUPS];
        let mut searching = lanes;
        let mut sp = 0usize;
        let mut current = 0usize;
        loop {
            // Push every child some ray may hit.
            let node = &nodes[current];
            let (mut mask, _) = packet.hit_children_sse::<OCTANT>(node, t_min4, t_max4);
            while mask != 0 {
                let slot = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                stack[sp] = (current * WIDTH + slot) as u32;
                sp += 1;
            }
            // Pop children until the next node; leaves go to the rays that hit them.
            loop {
                if sp == 0 {
                    return hit;
                }
                sp -= 1;
                let entry = stack[sp] as usize;
                let (parent, slot) = (&nodes[entry / WIDTH], entry % WIDTH);
                let child = parent.children[slot];
                if child & LEAF == 0 {
                    current = child as usize;
                    break;
                }
                let rays =
                    packet.rays_hitting::<OCTANT>(parent, slot, searching, t_min4, &t_max_lanes);
                if rays != 0 {
                    let (start, count) = decode_leaf(child);
                    let found = leaf(rays, start, count) & rays;
                    hit |= found;
                    searching &= !found;
                    if searching == 0 {
                        return hit;
                    }
                }
            }
        }
    }
}
