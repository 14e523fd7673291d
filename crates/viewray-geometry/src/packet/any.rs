//! The any-hit traversal of a packet (shadow rays): together through the upper levels,
//! one ray at a time through the subtrees its rays enter apart, as the closest-hit
//! traversal does; every ray gets the answer its single-ray walk gives.

use glam::Vec4;

use super::boxes::PacketBoxes;
use super::closest::{KEEP_PACKET, SINGLE};
use super::lanes::{PACKET_GROUPS, lanes_of};
use super::rays::BoxPacket;
use crate::bvh::{Bvh, LEAF, STACK_ROOM, STACK_SIZE, WIDTH, decode_leaf, prefetch, with_stack};

/// When the packet enters this many children of a node or more, its rays search them
/// one by one (unless `KEEP_PACKET` of them enter the same child). Fewer than the
/// closest-hit traversal's `MANY_CHILDREN` (6): an any-hit packet has no nearest child to
/// take first, and handing the children to single rays sooner took 6% fewer
/// instructions for the bench world's sun shadow rays (82k-triangle icosphere; 3% at 20k;
/// thresholds 2 to 5 within 2% of each other, 9, never, 4.5 times as many).
const MANY_CHILDREN: u32 = 4;

/// What an any-hit packet traversal carries down the tree: the packet and its box
/// tests, the range of `t`, what happens at leaves, and a stack for the rays that finish
/// subtrees on their own.
struct AnyTraversal<'a, B, L> {
    boxes: &'a B,
    t_min: f32,
    t_max: f32,
    /// `leaf(rays, start, count)`: which of `rays` hit one of the leaf's items.
    leaf: L,
    ray_stack: &'a mut [u32; STACK_ROOM],
}

/// The body of [`Bvh::any_packet`] and its AVX twin: the packet's octant picks the
/// monomorphized traversal (a macro, as `closest_packet_octants` in `closest.rs`, so
/// that the closures are compiled inside each).
macro_rules! any_packet_octants {
    ($bvh:expr, $boxes:expr, $lanes:expr, $t_min:expr, $t_max:expr, $leaf:expr) => {{
        macro_rules! octant {
            ($octant:literal) => {
                with_stack(|stack| {
                    with_stack(|ray_stack| {
                        let mut traversal = AnyTraversal {
                            boxes: $boxes,
                            t_min: $t_min,
                            t_max: $t_max,
                            leaf: $leaf,
                            ray_stack: &mut ray_stack.refs,
                        };
                        $bvh.any_packet_with_stack::<$octant, _, _>(
                            &mut traversal,
                            $lanes,
                            &mut stack.refs,
                        )
                    })
                })
            };
        }
        match $boxes.packet().octant {
            0 => octant!(0),
            1 => octant!(1),
            2 => octant!(2),
            3 => octant!(3),
            4 => octant!(4),
            5 => octant!(5),
            6 => octant!(6),
            _ => octant!(7),
        }
    }};
}

impl Bvh {
    /// The any-hit traversal of a packet: which rays of `lanes` meet an item with `t`
    /// in `[t_min, t_max]`. The packet visits the nodes that some ray still searching
    /// may reach (in no particular order); the leaves, and the children of nodes where
    /// it enters [`MANY_CHILDREN`] or more (unless `KEEP_PACKET` rays enter the child), go
    /// to the rays that hit their box, which finish them one by one. A leaf is handed to
    /// `leaf(rays, start, count)`, which returns those of `rays` that hit one of its
    /// items; a ray that hits stops searching. A ray is given exactly the leaves its
    /// single-ray traversal ([`Bvh::any`]) would visit (up to the order and to where it
    /// stops), and so gets its answer.
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
        #[cfg(target_arch = "x86_64")]
        if crate::avx::detected() {
            #[allow(unsafe_code)]
            // SAFETY: the processor runs AVX and POPCNT.
            return unsafe { self.any_packet_avx(packet, lanes, t_min, t_max, leaf) };
        }
        any_packet_octants!(self, packet, lanes, t_min, t_max, leaf)
    }

    /// [`Bvh::any_packet`] compiled for AVX, with the AVX box tests.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,popcnt")]
    fn any_packet_avx(
        &self,
        packet: &BoxPacket<'_>,
        lanes: u64,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u64, u32, u32) -> u64,
    ) -> u64 {
        let boxes = crate::avx::AvxPacket::new(packet);
        any_packet_octants!(self, &boxes, lanes, t_min, t_max, leaf)
    }

    #[inline(always)]
    fn any_packet_with_stack<const OCTANT: u8, B: PacketBoxes, L: FnMut(u64, u32, u32) -> u64>(
        &self,
        traversal: &mut AnyTraversal<'_, B, L>,
        lanes: u64,
        stack: &mut [u32; STACK_ROOM],
    ) -> u64 {
        let packet = traversal.boxes.packet();
        if !packet.coherent {
            // Ray by ray: the interval test would visit many nodes no ray needs.
            return self.any_single_rays::<OCTANT, B, L>(traversal, 0, lanes);
        }
        let nodes = self.nodes();
        debug_assert!(nodes.len() < (1 << 28), "entries are node * 8 + slot");
        let (t_min, t_max) = (traversal.t_min, traversal.t_max);
        let t_max_lanes = [Vec4::splat(t_max); PACKET_GROUPS];
        let mut hit = 0;
        let mut searching = lanes;
        let mut sp = 0usize;
        let mut current = 0usize;
        loop {
            // Push every child some ray may hit, marked for single rays when there are
            // many.
            let node = &nodes[current];
            let (mut mask, _) = traversal.boxes.hit_children::<OCTANT>(node, t_min, t_max);
            let single = if mask.count_ones() >= MANY_CHILDREN {
                SINGLE
            } else {
                0
            };
            debug_assert!(sp + mask.count_ones() as usize <= STACK_SIZE);
            while mask != 0 {
                let slot = mask.trailing_zeros() as usize;
                mask &= mask - 1;
                let child = node.children[slot];
                if child & LEAF == 0 {
                    prefetch(nodes, child as usize, [0, 64, 128, 192]);
                }
                stack[sp] = (current * WIDTH + slot) as u32 | single;
                sp += 1;
            }
            // Pop children until the next node the packet takes; leaves and single
            // rays' subtrees go to the rays that hit their box.
            loop {
                if sp == 0 {
                    return hit;
                }
                sp -= 1;
                let entry = stack[sp];
                let single = entry & SINGLE != 0;
                let entry = (entry & !SINGLE) as usize;
                let (parent, slot) = (&nodes[entry / WIDTH], entry % WIDTH);
                let child = parent.children[slot];
                if !single && child & LEAF == 0 && searching == lanes {
                    current = child as usize;
                    break;
                }
                let rays = traversal.boxes.rays_hitting::<OCTANT>(
                    parent,
                    slot,
                    searching,
                    t_min,
                    &t_max_lanes,
                );
                if child & LEAF == 0 && (!single || rays.count_ones() >= KEEP_PACKET) {
                    // The packet's subtree (skipped when none of the rays still
                    // searching enters it).
                    if rays != 0 {
                        current = child as usize;
                        break;
                    }
                    continue;
                }
                if rays != 0 {
                    let found = self.any_single_rays::<OCTANT, B, L>(traversal, child, rays);
                    hit |= found;
                    searching &= !found;
                    if searching == 0 {
                        return hit;
                    }
                }
            }
        }
    }

    /// Each ray of `rays` searches the subtree `child` (a node or a leaf) on its own:
    /// the mask of those that hit an item.
    #[inline(always)]
    fn any_single_rays<const OCTANT: u8, B: PacketBoxes, L: FnMut(u64, u32, u32) -> u64>(
        &self,
        traversal: &mut AnyTraversal<'_, B, L>,
        child: u32,
        rays: u64,
    ) -> u64 {
        let leaf = &mut traversal.leaf;
        if child & LEAF != 0 {
            let (start, count) = decode_leaf(child);
            return leaf(rays, start, count) & rays;
        }
        let mut hit = 0;
        for i in lanes_of(rays) {
            if self.any_with_stack::<OCTANT, _>(
                &traversal.boxes.lane_ray(i),
                child,
                traversal.t_min,
                traversal.t_max,
                |start, count| leaf(1 << i, start, count) & (1 << i) != 0,
                traversal.ray_stack,
            ) {
                hit |= 1 << i;
            }
        }
        hit
    }
}
