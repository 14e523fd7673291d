//! Packets of coherent rays, traversed together through the upper levels of a BVH and
//! one by one through its lower subtrees.
//!
//! A packet holds up to 64 rays whose directions share one sign pattern (octant). Its
//! upper-level box tests bound every ray at once with interval arithmetic (one test per
//! node, as for a single ray); subtrees low enough, and leaves, are first tested against
//! each ray of the packet (four rays per SIMD instruction) and then handed to the rays
//! that hit their box, which finish them with the ordinary single-ray traversal. Every
//! test is conservative with respect to the single-ray one, and each ray's own tests
//! are exactly the single-ray arithmetic, so a packet finds the same hits as its rays
//! traced alone.

use glam::{BVec4A, Vec3, Vec4};

use crate::Ray;
use crate::bvh::{
    BoxRay, Bvh, GROUPS, LEAF, Node, STACK_SIZE, SlabNumbers, Stack, WIDTH, decode_leaf, prefetch,
    with_stack,
};

/// The most rays in a packet: one bit each of a `u64` mask.
pub(crate) const PACKET_SIZE: usize = 64;
/// SIMD groups of four rays in a packet.
pub(crate) const PACKET_GROUPS: usize = PACKET_SIZE / 4;

/// One number per ray of a packet, four rays per SIMD vector.
pub(crate) type Lanes = [Vec4; PACKET_GROUPS];

/// The largest spread of a packet's unit directions (on any axis) for which it is
/// traversed as a packet. Beyond it the packet's bounds grow so loose that it would
/// visit many nodes none of its rays needs, and its rays are traced one by one.
const MAX_DIRECTION_SPREAD: f32 = 0.05;

/// When the packet enters this many children of a node or more, they are small next to
/// the packet, and its rays finish them one by one.
const MANY_CHILDREN: u32 = 5;
/// Stack entry flag: the child is to be handed to single rays.
const SINGLE: u32 = 1 << 31;

/// The robust enlargement of box exits (see [`BoxRay::hit_children`]).
const ROBUST: f32 = 1.0 + 2.0 * 3.0 * f32::EPSILON;

/// The rays of a packet prepared for box tests: each ray's slab numbers (as in
/// [`BoxRay`]), four rays per vector, and their bounds for the packet's interval test.
#[derive(Clone, Debug)]
pub(crate) struct BoxPacket {
    len: usize,
    /// The index of each lane's ray in the slice the packet was filled from.
    rays: [u8; PACKET_SIZE],
    octant: u8,
    /// Whether the directions are close enough for the interval test to pay (see
    /// [`MAX_DIRECTION_SPREAD`]); otherwise each ray is traced alone.
    coherent: bool,
    origin_near: [Lanes; 3],
    origin_far: [Lanes; 3],
    inverse: [Lanes; 3],
    /// Per axis, the origin that makes the near plane's distance smallest for every
    /// ray (the largest `origin_near` on a positive axis, the smallest on a negative one).
    bound_origin_near: [Vec4; 3],
    /// Likewise the origin that makes the far plane's distance largest.
    bound_origin_far: [Vec4; 3],
    inverse_min: [Vec4; 3],
    inverse_max: [Vec4; 3],
}

impl BoxPacket {
    /// An empty packet, to be filled with [`BoxPacket::fill`].
    pub(crate) fn new() -> Self {
        Self {
            len: 0,
            rays: [0; PACKET_SIZE],
            octant: 0,
            coherent: false,
            origin_near: [[Vec4::ZERO; PACKET_GROUPS]; 3],
            origin_far: [[Vec4::ZERO; PACKET_GROUPS]; 3],
            inverse: [[Vec4::ZERO; PACKET_GROUPS]; 3],
            bound_origin_near: [Vec4::ZERO; 3],
            bound_origin_far: [Vec4::ZERO; 3],
            inverse_min: [Vec4::ZERO; 3],
            inverse_max: [Vec4::ZERO; 3],
        }
    }

    /// The mask of all the packet's rays.
    pub(crate) fn all_lanes(&self) -> u64 {
        lanes_below(self.len)
    }

    /// Makes this the packet of the rays `rays[i]` for the bits `i` of `mask` (at
    /// least one): valid rays of octant `octant`.
    pub(crate) fn fill(&mut self, octant: u8, rays: &[Ray], mask: u64) {
        let mut len = 0;
        let mut direction_min = Vec3::INFINITY;
        let mut direction_max = Vec3::NEG_INFINITY;
        let mut length_squared_min = f32::INFINITY;
        let mut near_min = Vec3::INFINITY;
        let mut near_max = Vec3::NEG_INFINITY;
        let mut far_min = Vec3::INFINITY;
        let mut far_max = Vec3::NEG_INFINITY;
        let mut inverse_min = Vec3::INFINITY;
        let mut inverse_max = Vec3::NEG_INFINITY;
        for i in lanes_of(mask) {
            let ray = &rays[i];
            let numbers = SlabNumbers::new(ray);
            debug_assert!(numbers.valid && numbers.octant == octant);
            let direction = ray.direction;
            direction_min = direction_min.min(direction);
            direction_max = direction_max.max(direction);
            length_squared_min = length_squared_min.min(direction.length_squared());
            near_min = near_min.min(numbers.origin_near);
            near_max = near_max.max(numbers.origin_near);
            far_min = far_min.min(numbers.origin_far);
            far_max = far_max.max(numbers.origin_far);
            inverse_min = inverse_min.min(numbers.inverse);
            inverse_max = inverse_max.max(numbers.inverse);
            let (group, lane) = (len / 4, len % 4);
            for axis in 0..3 {
                self.origin_near[axis][group][lane] = numbers.origin_near[axis];
                self.origin_far[axis][group][lane] = numbers.origin_far[axis];
                self.inverse[axis][group][lane] = numbers.inverse[axis];
            }
            self.rays[len] = i as u8;
            len += 1;
        }
        debug_assert!(len > 0);
        // Fill the last group's unused lanes with copies of the first ray: they are
        // never in a mask, but stay harmless numbers.
        for slot in len..len.next_multiple_of(4) {
            for axis in 0..3 {
                self.origin_near[axis][slot / 4][slot % 4] = self.origin_near[axis][0][0];
                self.origin_far[axis][slot / 4][slot % 4] = self.origin_far[axis][0][0];
                self.inverse[axis][slot / 4][slot % 4] = self.inverse[axis][0][0];
            }
        }
        for axis in 0..3 {
            let negative = (octant >> axis) & 1 == 1;
            // Rounding is monotonic, so (plane - o) * inverse computed for the bounding
            // numbers bounds it for every ray of the packet (see `hit_children`).
            let (near, far) = if negative {
                (near_min[axis], far_max[axis])
            } else {
                (near_max[axis], far_min[axis])
            };
            self.bound_origin_near[axis] = Vec4::splat(near);
            self.bound_origin_far[axis] = Vec4::splat(far);
            self.inverse_min[axis] = Vec4::splat(inverse_min[axis]);
            self.inverse_max[axis] = Vec4::splat(inverse_max[axis]);
        }
        self.len = len;
        self.octant = octant;
        // The spread of the unit directions is at most the spread of the directions
        // over the shortest one's length.
        let spread = (direction_max - direction_min).max_element();
        self.coherent = spread <= MAX_DIRECTION_SPREAD * length_squared_min.sqrt();
    }

    /// For each lane, the index of its ray in the slice the packet was filled from.
    pub(crate) fn rays(&self) -> &[u8] {
        &self.rays[..self.len]
    }

    /// The single ray of lane `lane`.
    #[inline(always)]
    fn lane_ray(&self, lane: usize) -> BoxRay {
        let (group, i) = (lane / 4, lane % 4);
        let (o, f, v) = (&self.origin_near, &self.origin_far, &self.inverse);
        BoxRay::from_lanes(
            [o[0][group][i], o[1][group][i], o[2][group][i]],
            [f[0][group][i], f[1][group][i], f[2][group][i]],
            [v[0][group][i], v[1][group][i], v[2][group][i]],
            self.octant,
        )
    }

    /// Tests the whole packet against a node's eight boxes: returns the mask of boxes
    /// that some ray of the packet may hit with `t` in `[t_min, t_max]`, and a lower
    /// bound of the distances at which the rays enter them.
    ///
    /// For each slab plane the distance `(plane - o) * inverse` of every ray lies
    /// between the products of the packet's bounding origin and its two extreme
    /// reciprocals, because rounded subtraction and multiplication are monotonic; so
    /// a box culled here is culled by the single-ray test of every ray in the packet.
    #[inline(always)]
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: Vec4,
        t_max: Vec4,
    ) -> (u32, [f32; WIDTH]) {
        let p = &node.planes;
        let mut mask = 0;
        let mut t_near_all = [0.0; WIDTH];
        for group in 0..GROUPS {
            let lanes = 4 * group..4 * group + 4;
            let slab = |axis: usize| {
                let negative = usize::from((OCTANT >> axis) & 1 == 1);
                let (near, far) = (axis + 3 * negative, axis + 3 * (1 - negative));
                let near = Vec4::from_slice(&p[near][lanes.clone()]) - self.bound_origin_near[axis];
                let far = Vec4::from_slice(&p[far][lanes.clone()]) - self.bound_origin_far[axis];
                (
                    (near * self.inverse_min[axis]).min(near * self.inverse_max[axis]),
                    (far * self.inverse_min[axis]).max(far * self.inverse_max[axis]),
                )
            };
            let (nx, fx) = slab(0);
            let (ny, fy) = slab(1);
            let (nz, fz) = slab(2);
            let t_near = nx.max(ny).max(nz).max(t_min);
            let t_far = (fx.min(fy).min(fz) * ROBUST).min(t_max);
            mask |= t_near.cmple(t_far).bitmask() << (4 * group);
            t_near.write_to_slice(&mut t_near_all[lanes]);
        }
        (mask, t_near_all)
    }

    /// The rays of `lanes` that hit child `slot` of `node` with `t` in `[t_min,
    /// t_max[lane]]`: for each ray exactly the test of [`BoxRay::hit_children`], four
    /// rays at a time.
    #[inline(always)]
    fn rays_hitting(
        &self,
        node: &Node,
        slot: usize,
        lanes: u64,
        t_min: Vec4,
        t_max: &Lanes,
    ) -> u64 {
        let negative = |axis: usize| usize::from((self.octant >> axis) & 1 == 1);
        let plane = |index: usize| Vec4::splat(node.planes[index][slot]);
        let near_plane = [0, 1, 2].map(|axis| plane(axis + 3 * negative(axis)));
        let far_plane = [0, 1, 2].map(|axis| plane(axis + 3 * (1 - negative(axis))));
        let mut hit = 0;
        let mut rest = lanes;
        while rest != 0 {
            let group = rest.trailing_zeros() as usize / 4;
            rest &= !(0xf << (4 * group));
            let slab = |axis: usize| {
                let near =
                    (near_plane[axis] - self.origin_near[axis][group]) * self.inverse[axis][group];
                let far =
                    (far_plane[axis] - self.origin_far[axis][group]) * self.inverse[axis][group];
                (near, far)
            };
            let (nx, fx) = slab(0);
            let (ny, fy) = slab(1);
            let (nz, fz) = slab(2);
            let t_near = nx.max(ny).max(nz).max(t_min);
            let t_far = (fx.min(fy).min(fz) * ROBUST).min(t_max[group]);
            hit |= u64::from(t_near.cmple(t_far).bitmask()) << (4 * group);
        }
        hit & lanes
    }
}

/// The mask of lanes `0..len`.
#[inline]
pub(crate) fn lanes_below(len: usize) -> u64 {
    if len >= PACKET_SIZE {
        u64::MAX
    } else {
        (1 << len) - 1
    }
}

/// The lanes of a mask, lowest first.
#[inline]
pub(crate) fn lanes_of(mask: u64) -> impl Iterator<Item = usize> {
    let mut rest = mask;
    std::iter::from_fn(move || {
        (rest != 0).then(|| {
            let lane = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            lane
        })
    })
}

/// Lane `lane` of `lanes`.
#[inline(always)]
pub(crate) fn lane(lanes: &Lanes, lane: usize) -> f32 {
    lanes[lane / 4][lane % 4]
}

/// Sets lane `lane` of `lanes`.
#[inline(always)]
pub(crate) fn set_lane(lanes: &mut Lanes, lane: usize, value: f32) {
    lanes[lane / 4][lane % 4] = value;
}

/// The largest number among the lanes of `mask`.
#[inline]
fn max_lane(values: &Lanes, mask: u64) -> f32 {
    let mut max = Vec4::NEG_INFINITY;
    for (group, v) in values.iter().enumerate() {
        let bits = (mask >> (4 * group)) & 0xf;
        if bits != 0 {
            let selected = BVec4A::new(bits & 1 != 0, bits & 2 != 0, bits & 4 != 0, bits & 8 != 0);
            max = max.max(Vec4::select(selected, *v, Vec4::NEG_INFINITY));
        }
    }
    max.max_element()
}

/// Splits `rays` (at most [`PACKET_SIZE`]) into packets of one octant each and calls
/// `trace(packet)` for each (see [`BoxPacket::rays`]). Rays that hit nothing by
/// definition (a non-finite origin or direction, a zero direction) are in no packet.
pub(crate) fn for_each_packet(
    rays: &[Ray],
    packet: &mut BoxPacket,
    mut trace: impl FnMut(&BoxPacket),
) {
    debug_assert!(rays.len() <= PACKET_SIZE);
    // The rays of each octant, as a mask.
    let mut octants = [0u64; 8];
    for (i, ray) in rays.iter().enumerate() {
        let (o, d) = (ray.origin, ray.direction);
        if o.is_finite() && d.is_finite() && d != Vec3::ZERO {
            let octant = usize::from(d.x.is_sign_negative())
                | usize::from(d.y.is_sign_negative()) << 1
                | usize::from(d.z.is_sign_negative()) << 2;
            octants[octant] |= 1 << i;
        }
    }
    for (octant, &mask) in octants.iter().enumerate() {
        if mask != 0 {
            packet.fill(octant as u8, rays, mask);
            trace(packet);
        }
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

impl Bvh {
    /// The closest-hit traversal of a packet: visits, nearest first, the nodes that
    /// some ray of `lanes` may reach, and hands leaves, and the children of nodes where
    /// the packet enters [`MANY_CHILDREN`] or more, to the rays that hit their box,
    /// which finish them one by one; leaves go to `visitor`. `t_max[lane]` holds each ray's closest hit
    /// so far and is updated. `prefetch_leaf(start, count)` may start loading the items
    /// of a leaf a ray will visit.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn closest_packet(
        &self,
        packet: &BoxPacket,
        lanes: u64,
        t_min: f32,
        t_max: &mut Lanes,
        visitor: &mut impl PacketVisitor,
        prefetch_leaf: impl Fn(u32, u32) + Copy,
    ) {
        if self.nodes().is_empty() || lanes == 0 {
            return;
        }
        macro_rules! octant {
            ($octant:literal) => {
                with_stack(|stack| {
                    with_stack(|ray_stack| {
                        self.closest_packet_with_stacks::<$octant>(
                            packet,
                            lanes,
                            t_min,
                            t_max,
                            visitor,
                            prefetch_leaf,
                            stack,
                            ray_stack,
                        )
                    })
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

    #[allow(clippy::too_many_arguments)]
    fn closest_packet_with_stacks<const OCTANT: u8>(
        &self,
        packet: &BoxPacket,
        lanes: u64,
        t_min: f32,
        t_max: &mut Lanes,
        visitor: &mut impl PacketVisitor,
        prefetch_leaf: impl Fn(u32, u32) + Copy,
        stack: &mut Stack,
        ray_stack: &mut Stack,
    ) {
        let nodes = self.nodes();
        let t_min4 = Vec4::splat(t_min);
        if !packet.coherent {
            self.single_rays::<OCTANT>(
                packet,
                0,
                lanes,
                t_min,
                t_max,
                visitor,
                prefetch_leaf,
                ray_stack,
            );
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
                packet.hit_children::<OCTANT>(node, t_min4, Vec4::splat(t_max_all));
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
                        prefetch_leaf(start, count);
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
                stack_entries[sp..sp + k - 1].copy_from_slice(&entries[..k - 1]);
                stack_t[sp..sp + k - 1].copy_from_slice(&dists[..k - 1]);
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
                let rays = packet.rays_hitting(parent, slot, lanes, t_min4, t_max);
                if rays != 0 {
                    self.single_rays::<OCTANT>(
                        packet,
                        child,
                        rays,
                        t_min,
                        t_max,
                        visitor,
                        prefetch_leaf,
                        ray_stack,
                    );
                    t_max_all = max_lane(t_max, lanes);
                }
            }
        }
    }
}

impl Bvh {
    /// Each ray of `rays` finishes the subtree `child` (a node or a leaf) on its own.
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn single_rays<const OCTANT: u8>(
        &self,
        packet: &BoxPacket,
        child: u32,
        rays: u64,
        t_min: f32,
        t_max: &mut Lanes,
        visitor: &mut impl PacketVisitor,
        prefetch_leaf: impl Fn(u32, u32) + Copy,
        ray_stack: &mut Stack,
    ) {
        if child & LEAF != 0 {
            let (start, count) = decode_leaf(child);
            visitor.leaf_lanes(rays, start, count, t_max);
            return;
        }
        for i in lanes_of(rays) {
            let visitor = &mut *visitor;
            let t = self.closest_with_stack::<OCTANT>(
                &packet.lane_ray(i),
                child,
                t_min,
                lane(t_max, i),
                |start, count, t_max| visitor.leaf(i, start, count, t_max),
                prefetch_leaf,
                ray_stack,
            );
            set_lane(t_max, i, t);
        }
    }
}

impl Default for BoxPacket {
    fn default() -> Self {
        Self::new()
    }
}
