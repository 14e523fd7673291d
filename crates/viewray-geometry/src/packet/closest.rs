//! The closest-hit traversal of a packet: together through the upper levels, one ray
//! at a time through the subtrees and leaves its rays enter apart; an incoherent
//! packet's rays walk the whole tree on their own, side by side in a large one.

use super::boxes::PacketBoxes;
use super::lanes::{Lanes, PACKET_SIZE, lane, lanes_of, max_lane, set_lane};
use super::rays::BoxPacket;
use crate::Ray;
use crate::bvh::{
    Bvh, LEAF, RayTraversal, STACK_SIZE, Stack, WALKS, WIDTH, Walk, decode_leaf, prefetch,
    with_stack, with_walk_stacks,
};
use crate::hit::RawHit;

/// When the packet enters this many children of a node or more, they are small next to
/// the packet, and its rays finish them one by one, unless [`KEEP_PACKET`] of them enter
/// the same child.
const MANY_CHILDREN: u32 = 6;
/// A child marked for single rays stays with the packet if at least this many of its
/// rays (a quarter of a full packet) enter its box: a subtree that many rays need is
/// walked once more cheaply than by each of them.
pub(super) const KEEP_PACKET: u32 = 16;
/// Stack entry flag: the child is to be handed to single rays.
pub(super) const SINGLE: u32 = 1 << 31;

/// A closest-hit query of some of a packet's rays: which lanes, from where along the
/// rays, and each lane's closest hit so far, which the query lowers.
pub(crate) struct PacketQuery<'a> {
    /// The packet, filled from `rays`.
    pub(crate) packet: &'a BoxPacket<'a>,
    /// The rays the packet was filled from (see [`BoxPacket::rays`]).
    pub(crate) rays: &'a [Ray],
    /// The lanes to trace.
    pub(crate) lanes: u64,
    /// Hits closer than this are ignored.
    pub(crate) t_min: f32,
    /// Each lane's closest distance so far.
    pub(crate) t_max: &'a mut Lanes,
    /// Each lane's closest hit so far.
    pub(crate) best: &'a mut [Option<RawHit>; PACKET_SIZE],
}

impl<'a> PacketQuery<'a> {
    /// The ray of lane `lane`.
    #[inline(always)]
    pub(crate) fn ray(&self, lane: usize) -> &'a Ray {
        &self.rays[usize::from(self.packet.rays()[lane])]
    }
}

/// What a packet traversal does at the leaves: a mesh intersects its triangles, a
/// world its objects.
pub(crate) trait PacketVisitor {
    /// Intersects the items `start..start + count` with the ray of lane `lane`, whose
    /// closest hit so far is at `t_max`; returns the new closest distance (or `t_max`).
    fn leaf(&mut self, lane: usize, start: u32, count: u32, t_max: f32) -> f32;

    /// Intersects the items `start..start + count` with the rays of `lanes`, updating
    /// their closest distances in `t_max`.
    #[inline]
    fn leaf_lanes(&mut self, lanes: u64, start: u32, count: u32, t_max: &mut Lanes) {
        for i in lanes_of(lanes) {
            let t = self.leaf(i, start, count, lane(t_max, i));
            set_lane(t_max, i, t);
        }
    }
}

/// What a packet traversal carries down the tree besides each ray's closest distance:
/// the packet and its box tests, where hits may start, what happens at leaves, and a
/// stack for the rays that finish subtrees on their own.
struct PacketTraversal<'a, B, V, P> {
    boxes: &'a B,
    t_min: f32,
    visitor: &'a mut V,
    /// Starts loading the items of a leaf a ray will visit.
    prefetch_leaf: P,
    ray_stack: &'a mut Stack,
}

/// What the walks side by side of an incoherent packet's rays share (see
/// [`Bvh::closest_walks`]): the packet's box tests, which give each lane's ray, where
/// hits may start, and what happens at leaves. Each walk has its own stack.
struct Walks<'a, B, V, P> {
    boxes: &'a B,
    t_min: f32,
    visitor: &'a mut V,
    /// Starts loading the items of a leaf a ray will visit.
    prefetch_leaf: P,
}

/// The body of [`Bvh::closest_packet`] and its AVX twin: the packet's octant picks the
/// monomorphized traversal. A macro rather than a function, so that the closures are
/// written (and compiled) inside each: a closure is compiled with its enclosing
/// function's instruction set.
macro_rules! closest_packet_octants {
    ($bvh:expr, $boxes:expr, $lanes:expr, $t_min:expr, $t_max:expr, $visitor:expr, $prefetch_leaf:expr) => {{
        macro_rules! octant {
            ($octant:literal) => {
                with_stack(|stack| {
                    with_stack(|ray_stack| {
                        let mut traversal = PacketTraversal {
                            boxes: $boxes,
                            t_min: $t_min,
                            visitor: $visitor,
                            prefetch_leaf: $prefetch_leaf,
                            ray_stack,
                        };
                        $bvh.closest_packet_with_stack::<$octant, _, _, _>(
                            &mut traversal,
                            $lanes,
                            $t_max,
                            stack,
                        )
                    })
                })
            };
        }
        macro_rules! walks {
            ($octant:literal) => {
                // The stacks are taken here, as in `octant!`: in a closure of
                // `closest_walks`, the box tests were no longer inlined.
                with_walk_stacks(|stacks| {
                    let walks = Walks {
                        boxes: $boxes,
                        t_min: $t_min,
                        visitor: $visitor,
                        prefetch_leaf: $prefetch_leaf,
                    };
                    $bvh.closest_walks::<$octant, _, _, _>(walks, $lanes, $t_max, stacks)
                })
            };
        }
        macro_rules! by_octant {
            ($traversal:ident) => {
                match $boxes.packet().octant {
                    0 => $traversal!(0),
                    1 => $traversal!(1),
                    2 => $traversal!(2),
                    3 => $traversal!(3),
                    4 => $traversal!(4),
                    5 => $traversal!(5),
                    6 => $traversal!(6),
                    _ => $traversal!(7),
                }
            };
        }
        if $boxes.packet().coherent || !$bvh.walks_pay() {
            by_octant!(octant)
        } else {
            by_octant!(walks)
        }
    }};
}

impl Bvh {
    /// The closest-hit traversal of a packet: visits, nearest first, the nodes that
    /// some ray of `lanes` may reach, and hands leaves, and the children of nodes where
    /// the packet enters [`MANY_CHILDREN`] or more (unless [`KEEP_PACKET`] rays enter
    /// the child), to the rays that hit their box, which finish them one by one; leaves
    /// go to `visitor`. `t_max[lane]` holds each ray's closest hit so far and is
    /// updated. `prefetch_leaf(start, count)` may start
    /// loading the items of a leaf a ray will visit.
    pub(crate) fn closest_packet(
        &self,
        packet: &BoxPacket<'_>,
        lanes: u64,
        t_min: f32,
        t_max: &mut Lanes,
        visitor: &mut impl PacketVisitor,
        prefetch_leaf: impl Fn(u32, u32) + Copy,
    ) {
        if self.nodes().is_empty() || lanes == 0 {
            return;
        }
        #[cfg(target_arch = "x86_64")]
        if crate::avx::detected() {
            #[allow(unsafe_code)]
            // SAFETY: the processor runs AVX and POPCNT.
            unsafe {
                self.closest_packet_avx(packet, lanes, t_min, t_max, visitor, prefetch_leaf);
            }
            return;
        }
        closest_packet_octants!(self, packet, lanes, t_min, t_max, visitor, prefetch_leaf);
    }

    /// [`Bvh::closest_packet`] compiled for AVX, with the AVX box tests.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,popcnt")]
    fn closest_packet_avx(
        &self,
        packet: &BoxPacket<'_>,
        lanes: u64,
        t_min: f32,
        t_max: &mut Lanes,
        visitor: &mut impl PacketVisitor,
        prefetch_leaf: impl Fn(u32, u32) + Copy,
    ) {
        let boxes = crate::avx::AvxPacket::new(packet);
        closest_packet_octants!(self, &boxes, lanes, t_min, t_max, visitor, prefetch_leaf);
    }

    #[inline(always)]
    fn closest_packet_with_stack<
        const OCTANT: u8,
        B: PacketBoxes,
        V: PacketVisitor,
        P: Fn(u32, u32) + Copy,
    >(
        &self,
        traversal: &mut PacketTraversal<'_, B, V, P>,
        lanes: u64,
        t_max: &mut Lanes,
        stack: &mut Stack,
    ) {
        let nodes = self.nodes();
        let packet = traversal.boxes.packet();
        if !packet.coherent {
            self.single_rays::<OCTANT, B, V, P>(traversal, 0, lanes, t_max);
            return;
        }

        let Stack {
            refs: stack_entries,
            t: stack_t,
        } = stack;
        debug_assert!(nodes.len() < (1 << 28), "entries are node * 8 + slot");
        let mut sp = 0usize;
        let mut t_max_all = max_lane(t_max, lanes);
        let mut current = 0usize;
        'nodes: loop {
            // Test the node's children with the packet, push all but the nearest hit
            // and take that one next.
            let node = &nodes[current];
            let (mask, t_near) =
                traversal
                    .boxes
                    .hit_children::<OCTANT>(node, traversal.t_min, t_max_all);
            let mut next = None;
            if mask != 0 {
                let single = if mask.count_ones() >= MANY_CHILDREN {
                    SINGLE
                } else {
                    0
                };
                let mut bits = mask;
                let mut entries = [0u32; WIDTH];
                let mut dists = [0f32; WIDTH];
                let mut k = 0;
                while bits != 0 {
                    let slot = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let child = node.children[slot];
                    if child & LEAF == 0 {
                        prefetch(nodes, child as usize, [0, 64, 128, 192]);
                    } else {
                        let (start, count) = decode_leaf(child);
                        (traversal.prefetch_leaf)(start, count);
                    }
                    let (entry, dist) = ((current * WIDTH + slot) as u32 | single, t_near[slot]);
                    let mut j = k;
                    while j > 0 && dists[j - 1] < dist {
                        entries[j] = entries[j - 1];
                        dists[j] = dists[j - 1];
                        j -= 1;
                    }
                    entries[j] = entry;
                    dists[j] = dist;
                    k += 1;
                }
                debug_assert!(sp + k <= STACK_SIZE);
                stack_entries[sp..sp + WIDTH].copy_from_slice(&entries);
                stack_t[sp..sp + WIDTH].copy_from_slice(&dists);
                sp += k - 1;
                next = Some(entries[k - 1]);
            }
            loop {
                let entry = match next.take() {
                    Some(entry) => entry as usize,
                    None => loop {
                        // Pop the nearest pending child that a ray may still reach
                        // before its closest hit so far.
                        if sp == 0 {
                            return;
                        }
                        sp -= 1;
                        if stack_t[sp] <= t_max_all {
                            break stack_entries[sp] as usize;
                        }
                    },
                };
                let single = entry & SINGLE as usize != 0;
                let entry = entry & !(SINGLE as usize);
                let (parent, slot) = (&nodes[entry / WIDTH], entry % WIDTH);
                let child = parent.children[slot];
                if !single && child & LEAF == 0 {
                    current = child as usize;
                    continue 'nodes;
                }
                let rays = traversal.boxes.rays_hitting::<OCTANT>(
                    parent,
                    slot,
                    lanes,
                    traversal.t_min,
                    t_max,
                );
                // A subtree a quarter of the packet enters is still the packet's.
                if child & LEAF == 0 && rays.count_ones() >= KEEP_PACKET {
                    current = child as usize;
                    continue 'nodes;
                }
                if rays != 0 {
                    self.single_rays::<OCTANT, B, V, P>(traversal, child, rays, t_max);
                    t_max_all = max_lane(t_max, lanes);
                }
            }
        }
    }

    /// The closest hits of an incoherent packet's rays (see `MAX_DIRECTION_SPREAD` in
    /// `rays.rs`): each ray walks the whole tree on its own, as [`Bvh::closest`] does,
    /// but [`WALKS`] of them take turns, one node or leaf each, so that while one waits
    /// for the node it goes to next (whose loading its previous step started), the
    /// others work. One ray's walk waits for memory at every level of a tree larger than
    /// the caches; several walks side by side keep several loads in flight.
    #[inline(always)]
    fn closest_walks<const OCTANT: u8, B: PacketBoxes, V: PacketVisitor, P: Fn(u32, u32)>(
        &self,
        walks: Walks<'_, B, V, P>,
        lanes: u64,
        t_max: &mut Lanes,
        stacks: &mut [Stack; WALKS],
    ) {
        let Walks {
            boxes,
            t_min,
            visitor,
            prefetch_leaf,
        } = walks;
        // Each slot's lane and walk; `active` has a bit per slot with a walk under way,
        // `pending` yields the lanes still to start.
        let mut slot_lane = [0usize; WALKS];
        let mut walks = [Walk::new(0, 0.0); WALKS];
        let mut active = 0u32;
        let mut pending = lanes_of(lanes);
        // The slots first: `zip` stops at the first that ends, and a lane taken from
        // `pending` for a slot that does not exist would be lost.
        for (k, ((slot, walk), i)) in slot_lane
            .iter_mut()
            .zip(&mut walks)
            .zip(&mut pending)
            .enumerate()
        {
            *slot = i;
            *walk = Walk::new(0, lane(t_max, i));
            active |= 1 << k;
        }
        while active != 0 {
            let mut bits = active;
            while bits != 0 {
                let k = bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let i = slot_lane[k];
                let more = self.closest_step::<OCTANT, _, _, _>(
                    &boxes.lane_ray(i),
                    t_min,
                    &mut walks[k],
                    &mut stacks[k],
                    &mut |start, count, t_max| visitor.leaf(i, start, count, t_max),
                    &prefetch_leaf,
                );
                if !more {
                    set_lane(t_max, i, walks[k].t_max);
                    match pending.next() {
                        Some(next) => {
                            slot_lane[k] = next;
                            walks[k] = Walk::new(0, lane(t_max, next));
                        }
                        None => active &= !(1 << k),
                    }
                }
            }
        }
    }

    /// Each ray of `rays` finishes the subtree `child` (a node or a leaf) on its own.
    #[inline(always)]
    fn single_rays<const OCTANT: u8, B: PacketBoxes, V: PacketVisitor, P: Fn(u32, u32) + Copy>(
        &self,
        traversal: &mut PacketTraversal<'_, B, V, P>,
        child: u32,
        rays: u64,
        t_max: &mut Lanes,
    ) {
        let visitor = &mut *traversal.visitor;
        if child & LEAF != 0 {
            let (start, count) = decode_leaf(child);
            visitor.leaf_lanes(rays, start, count, t_max);
            return;
        }
        for i in lanes_of(rays) {
            let ray = traversal.boxes.lane_ray(i);
            let mut ray_traversal = RayTraversal {
                ray: &ray,
                t_min: traversal.t_min,
                leaf: |start, count, t_max| visitor.leaf(i, start, count, t_max),
                prefetch_leaf: traversal.prefetch_leaf,
            };
            let t = self.closest_with_stack::<OCTANT, _, _, _>(
                &mut ray_traversal,
                child,
                lane(t_max, i),
                traversal.ray_stack,
            );
            set_lane(t_max, i, t);
        }
    }
}
