//! Packets of coherent rays, traversed together through the upper levels of a BVH and
//! one by one through its lower subtrees.
//!
//! A packet holds up to 64 rays whose directions share one sign pattern (octant). Its
//! upper-level box tests bound every ray at once with interval arithmetic (one test per
//! node, as for a single ray). Leaves, and the children of nodes where the packet
//! enters [`MANY_CHILDREN`] or more (boxes small next to the packet), are first tested
//! against each ray of the packet (four rays per SIMD instruction) and then handed to
//! the rays that hit their box, which finish them with the ordinary single-ray
//! traversal. Every packet test is conservative with respect to the single-ray one, and
//! each ray's own tests are exactly the single-ray arithmetic, so a packet finds the
//! same hits as its rays traced alone.
//!
//! An incoherent packet (directions spread too far for a shared test) is traced ray by
//! ray; in a tree too large for the caches its rays walk side by side, taking turns one
//! node each, so that their waits for memory overlap.

use std::cell::RefCell;

use glam::{BVec4A, Vec4};

use crate::Ray;
use crate::bvh::{
    BoxRay, Bvh, ChildBoxes, GROUPS, LEAF, Node, RayTraversal, STACK_ROOM, STACK_SIZE, Stack,
    WALKS, WIDTH, Walk, decode_leaf, node_planes, per_axis, plane_distances, plane_index, prefetch,
    slab_numbers, slab_test, with_stack, with_walk_stacks,
};
use crate::hit::RawHit;

/// The most rays in a packet: one bit each of a `u64` mask.
pub(crate) const PACKET_SIZE: usize = 64;
/// SIMD groups of four rays in a packet.
pub(crate) const PACKET_GROUPS: usize = PACKET_SIZE / 4;

/// One number per ray of a packet, four rays per SIMD vector.
pub(crate) type Lanes = [Vec4; PACKET_GROUPS];

/// The largest spread of a packet's unit directions (on any axis) for which it is
/// traversed as a packet. Beyond it the packet's bounds grow so loose that it would
/// visit many nodes none of its rays needs, and its rays are traced one by one (or side
/// by side, see [`Bvh::closest_walks`]).
const MAX_DIRECTION_SPREAD: f32 = 0.05;

/// When the packet enters this many children of a node or more, they are small next to
/// the packet, and its rays finish them one by one, unless [`KEEP_PACKET`] of them enter
/// the same child.
const MANY_CHILDREN: u32 = 6;
/// A child marked for single rays stays with the packet if at least this many of its
/// rays (a quarter of a full packet) enter its box: a subtree that many rays need is
/// walked once more cheaply than by each of them.
const KEEP_PACKET: u32 = 16;
/// Stack entry flag: the child is to be handed to single rays.
const SINGLE: u32 = 1 << 31;

/// Each lane's ray and slab numbers (see [`slab_numbers`]), per axis, four lanes per
/// vector.
#[derive(Clone, Debug)]
struct LaneNumbers {
    origin: [Lanes; 3],
    direction: [Lanes; 3],
    origin_near: [Lanes; 3],
    origin_far: [Lanes; 3],
    inverse: [Lanes; 3],
}

impl LaneNumbers {
    const EMPTY: Self = Self {
        origin: [[Vec4::ZERO; PACKET_GROUPS]; 3],
        direction: [[Vec4::ZERO; PACKET_GROUPS]; 3],
        origin_near: [[Vec4::ZERO; PACKET_GROUPS]; 3],
        origin_far: [[Vec4::ZERO; PACKET_GROUPS]; 3],
        inverse: [[Vec4::ZERO; PACKET_GROUPS]; 3],
    };
}

/// The rays of a packet prepared for box tests: each ray's slab numbers (as in
/// [`BoxRay`]), four rays per vector, and their bounds for the packet's interval test.
#[derive(Clone, Debug)]
pub(crate) struct BoxPacket<'a> {
    len: usize,
    /// The index of each lane's ray in the slice the packet was filled from.
    rays: [u8; PACKET_SIZE],
    octant: u8,
    /// Whether the directions are close enough for the interval test to pay (see
    /// [`MAX_DIRECTION_SPREAD`]); otherwise each ray is traced alone.
    coherent: bool,
    /// The lanes' slab numbers: the chunk's own when the packet holds all of its rays
    /// (the common case, with no copy), else gathered from them.
    numbers: &'a LaneNumbers,
    /// Per axis, the origin that makes the near plane's distance smallest for every
    /// ray (the largest `origin_near` on a positive axis, the smallest on a negative one).
    pub(crate) bound_origin_near: [Vec4; 3],
    /// Likewise the origin that makes the far plane's distance largest.
    pub(crate) bound_origin_far: [Vec4; 3],
    pub(crate) inverse_min: [Vec4; 3],
    pub(crate) inverse_max: [Vec4; 3],
}

impl<'a> BoxPacket<'a> {
    /// The mask of all the packet's rays.
    pub(crate) fn all_lanes(&self) -> u64 {
        lanes_below(self.len)
    }

    /// The packet of the rays of `chunk` in `mask` (at least one): valid rays of octant
    /// `octant`. Unless they are all of the chunk's rays, their numbers are gathered
    /// into `gathered`.
    fn new(chunk: &'a ChunkNumbers, gathered: &'a mut LaneNumbers, octant: u8, mask: u64) -> Self {
        let mut rays = [0; PACKET_SIZE];
        let mut direction_min = [Vec4::INFINITY; 3];
        let mut direction_max = [Vec4::NEG_INFINITY; 3];
        let mut length_squared_min = Vec4::INFINITY;
        let (len, numbers) = if mask == chunk.all {
            // The whole chunk, the common case: its own numbers.
            for (lane, ray) in rays.iter_mut().enumerate().take(chunk.len) {
                *ray = lane as u8;
            }
            for group in 0..chunk.len.div_ceil(4) {
                let d = [0, 1, 2].map(|axis| chunk.numbers.direction[axis][group]);
                for axis in 0..3 {
                    direction_min[axis] = direction_min[axis].min(d[axis]);
                    direction_max[axis] = direction_max[axis].max(d[axis]);
                }
                length_squared_min =
                    length_squared_min.min(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            }
            (chunk.len, &chunk.numbers)
        } else {
            // Gather the rays of `mask`, lane by lane.
            let (source, target) = (&chunk.numbers, gathered);
            let mut lane = 0;
            for i in lanes_of(mask) {
                let (from, to) = ((i / 4, i % 4), (lane / 4, lane % 4));
                let d = [0, 1, 2].map(|axis| at(&source.direction[axis][from.0], from.1));
                length_squared_min =
                    length_squared_min.min(Vec4::splat(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
                for axis in 0..3 {
                    let copy = |to_lanes: &mut Lanes, from_lanes: &Lanes| {
                        *at_mut(&mut to_lanes[to.0], to.1) = at(&from_lanes[from.0], from.1);
                    };
                    copy(&mut target.origin[axis], &source.origin[axis]);
                    copy(&mut target.direction[axis], &source.direction[axis]);
                    copy(&mut target.origin_near[axis], &source.origin_near[axis]);
                    copy(&mut target.origin_far[axis], &source.origin_far[axis]);
                    copy(&mut target.inverse[axis], &source.inverse[axis]);
                    direction_min[axis] = direction_min[axis].min(Vec4::splat(d[axis]));
                    direction_max[axis] = direction_max[axis].max(Vec4::splat(d[axis]));
                }
                rays[lane] = i as u8;
                lane += 1;
            }
            // Fill the last group's unused lanes with copies of the first ray: they are
            // never in a mask, but must not widen the bounds.
            for slot in lane..lane.next_multiple_of(4) {
                for axis in 0..3 {
                    for lanes in [
                        &mut target.origin[axis],
                        &mut target.direction[axis],
                        &mut target.origin_near[axis],
                        &mut target.origin_far[axis],
                        &mut target.inverse[axis],
                    ] {
                        set_lane(lanes, slot, lanes[0].x);
                    }
                }
            }
            let target: &'a LaneNumbers = target;
            (lane, target)
        };
        debug_assert!(len > 0);
        let groups = len.div_ceil(4);
        let mut bound_origin_near = [Vec4::ZERO; 3];
        let mut bound_origin_far = [Vec4::ZERO; 3];
        let mut inverse_min = [Vec4::ZERO; 3];
        let mut inverse_max = [Vec4::ZERO; 3];
        for axis in 0..3 {
            let (mut near_min, mut near_max) = (Vec4::INFINITY, Vec4::NEG_INFINITY);
            let (mut far_min, mut far_max) = (Vec4::INFINITY, Vec4::NEG_INFINITY);
            let (mut low, mut high) = (Vec4::INFINITY, Vec4::NEG_INFINITY);
            for group in 0..groups {
                near_min = near_min.min(numbers.origin_near[axis][group]);
                near_max = near_max.max(numbers.origin_near[axis][group]);
                far_min = far_min.min(numbers.origin_far[axis][group]);
                far_max = far_max.max(numbers.origin_far[axis][group]);
                low = low.min(numbers.inverse[axis][group]);
                high = high.max(numbers.inverse[axis][group]);
            }
            // Rounding is monotonic, so (plane - o) * inverse computed for the bounding
            // numbers bounds it for every ray of the packet (see `hit_children`).
            let (near, far) = if (octant >> axis) & 1 == 1 {
                (near_min.min_element(), far_max.max_element())
            } else {
                (near_max.max_element(), far_min.min_element())
            };
            bound_origin_near[axis] = Vec4::splat(near);
            bound_origin_far[axis] = Vec4::splat(far);
            inverse_min[axis] = Vec4::splat(low.min_element());
            inverse_max[axis] = Vec4::splat(high.max_element());
        }
        // The spread of the unit directions is at most the spread of the directions
        // over the shortest one's length. (A chunk's padding lanes copy a ray of the
        // packet whenever the packet is the whole chunk; a lone lane is never padding.)
        let spread = (0..3)
            .map(|axis| direction_max[axis].max_element() - direction_min[axis].min_element())
            .fold(0.0, f32::max);
        Self {
            len,
            rays,
            octant,
            coherent: spread <= MAX_DIRECTION_SPREAD * length_squared_min.min_element().sqrt(),
            numbers,
            bound_origin_near,
            bound_origin_far,
            inverse_min,
            inverse_max,
        }
    }

    /// For each lane, the index of its ray in the slice the packet was filled from.
    pub(crate) fn rays(&self) -> &[u8] {
        &self.rays[..self.len]
    }

    /// The origins and directions of the four lanes of group `group` (lanes past the
    /// last ray repeat a ray of the packet).
    #[inline(always)]
    pub(crate) fn group_rays(&self, group: usize) -> ([Vec4; 3], [Vec4; 3]) {
        let numbers = self.numbers;
        (
            [0, 1, 2].map(|axis| numbers.origin[axis][group]),
            [0, 1, 2].map(|axis| numbers.direction[axis][group]),
        )
    }

    /// The single ray of lane `lane`.
    #[inline(always)]
    pub(crate) fn lane_ray(&self, lane: usize) -> BoxRay {
        let (group, i) = (lane / 4, lane % 4);
        let numbers = self.numbers;
        let (o, f, v) = (&numbers.origin_near, &numbers.origin_far, &numbers.inverse);
        let lane_of = |lanes: &[Lanes; 3]| [0, 1, 2].map(|axis| at(&lanes[axis][group], i));
        BoxRay::from_lanes(lane_of(o), lane_of(f), lane_of(v), self.octant)
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
    fn hit_children_sse<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: Vec4,
        t_max: Vec4,
    ) -> (u32, [f32; WIDTH]) {
        let mut mask = 0;
        let mut t_near_all = [0.0; WIDTH];
        for group in 0..GROUPS {
            let lanes = 4 * group..4 * group + 4;
            let (near_plane, far_plane) = node_planes::<OCTANT>(&node.planes, lanes.clone());
            let near = per_axis(|axis| {
                let near = near_plane[axis] - self.bound_origin_near[axis];
                (near * self.inverse_min[axis]).min(near * self.inverse_max[axis])
            });
            let far = per_axis(|axis| {
                let far = far_plane[axis] - self.bound_origin_far[axis];
                (far * self.inverse_min[axis]).max(far * self.inverse_max[axis])
            });
            let (hit, t_near) = slab_test(near, far, t_min, t_max);
            mask |= hit << (4 * group);
            t_near.write_to_slice(&mut t_near_all[lanes]);
        }
        (mask, t_near_all)
    }

    /// The rays of `lanes` that hit child `slot` of `node` with `t` in `[t_min,
    /// t_max[lane]]`: for each ray exactly the test of [`BoxRay::hit_children_sse`], four
    /// rays at a time.
    #[inline(always)]
    fn rays_hitting<const OCTANT: u8>(
        &self,
        node: &Node,
        slot: usize,
        lanes: u64,
        t_min: Vec4,
        t_max: &Lanes,
    ) -> u64 {
        let plane = |axis: usize, far: bool| {
            Vec4::splat(node.planes[plane_index::<OCTANT>(axis, far)][slot])
        };
        let near_plane = per_axis(|axis| plane(axis, false));
        let far_plane = per_axis(|axis| plane(axis, true));
        let mut hit = 0;
        let mut rest = lanes;
        while rest != 0 {
            let group = rest.trailing_zeros() as usize / 4;
            rest &= !(0xf << (4 * group));
            let (near, far) = plane_distances(
                near_plane,
                far_plane,
                per_axis(|axis| self.numbers.origin_near[axis][group]),
                per_axis(|axis| self.numbers.origin_far[axis][group]),
                per_axis(|axis| self.numbers.inverse[axis][group]),
            );
            let (group_hit, _) = slab_test(near, far, t_min, t_max[group]);
            hit |= u64::from(group_hit) << (4 * group);
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
    at(&lanes[lane / 4], lane % 4)
}

/// Sets lane `lane` of `lanes`.
#[inline(always)]
pub(crate) fn set_lane(lanes: &mut Lanes, lane: usize, value: f32) {
    *at_mut(&mut lanes[lane / 4], lane % 4) = value;
}

/// The mask of the lanes whose bits are set in the low four bits of `bits`.
///
/// One load from a table: built lane by lane, each mask took four loads and the
/// shuffles to join them (7% of a coherent packet's instructions, in `max_lane`).
#[inline(always)]
pub(crate) fn lane_mask(bits: u32) -> BVec4A {
    const MASKS: [BVec4A; 16] = {
        let mut masks = [BVec4A::splat(false); 16];
        let mut bits = 0;
        while bits < 16 {
            masks[bits] = BVec4A::new(bits & 1 != 0, bits & 2 != 0, bits & 4 != 0, bits & 8 != 0);
            bits += 1;
        }
        masks
    };
    MASKS[bits as usize & 0xf]
}

/// Lane `i` of `v`, read through its array: indexing a `Vec4` by a lane not known at
/// compile time is a `match`, which compiles to a jump table.
#[inline(always)]
pub(crate) fn at(v: &Vec4, i: usize) -> f32 {
    AsRef::<[f32; 4]>::as_ref(v)[i]
}

/// Lane `i` of `v`, to write (see [`at`]).
#[inline(always)]
pub(crate) fn at_mut(v: &mut Vec4, i: usize) -> &mut f32 {
    &mut AsMut::<[f32; 4]>::as_mut(v)[i]
}

/// The largest number among the lanes of `mask`.
#[inline]
fn max_lane(values: &Lanes, mask: u64) -> f32 {
    // Every group, without branches (a group outside the mask gives -inf), in two
    // chains of maxima that run side by side.
    let mut max = [Vec4::NEG_INFINITY; 2];
    for (group, v) in values.iter().enumerate() {
        let bits = (mask >> (4 * group)) as u32;
        max[group % 2] = max[group % 2].max(Vec4::select(lane_mask(bits), *v, Vec4::NEG_INFINITY));
    }
    max[0].max(max[1]).max_element()
}

/// The slab numbers (see [`slab_numbers`]) of up to [`PACKET_SIZE`] rays, four rays per
/// vector, before they are sorted into packets by octant.
struct ChunkNumbers {
    len: usize,
    /// The mask of all the chunk's rays.
    all: u64,
    /// The masks of the valid rays of each octant.
    octants: [u64; 8],
    numbers: LaneNumbers,
}

impl ChunkNumbers {
    /// Numbers to be filled with [`ChunkNumbers::fill`].
    const EMPTY: Self = Self {
        len: 0,
        all: 0,
        octants: [0; 8],
        numbers: LaneNumbers::EMPTY,
    };

    /// Makes these the numbers of `rays`, as [`BoxRay::new`] computes them ray by ray,
    /// four rays at a time. Lanes past the last ray copy the first one; groups past
    /// the last are left as they were (nothing reads them).
    fn fill(&mut self, rays: &[Ray]) {
        debug_assert!(!rays.is_empty() && rays.len() <= PACKET_SIZE);
        let chunk = self;
        chunk.len = rays.len();
        chunk.all = lanes_below(rays.len());
        // Per lane, one bit each: valid, and a negative direction on x, y and z; the
        // octants' masks come from these at the end, a few operations for the chunk.
        let (mut valid_lanes, mut negative_lanes) = (0u64, [0u64; 3]);
        for group in 0..rays.len().div_ceil(4) {
            let ray = |i: usize| rays.get(4 * group + i).unwrap_or(&rays[0]);
            let (r0, r1, r2, r3) = (ray(0), ray(1), ray(2), ray(3));
            let mut valid = BVec4A::splat(true);
            let mut nonzero = BVec4A::splat(false);
            for (axis, negative) in negative_lanes.iter_mut().enumerate() {
                let o = Vec4::new(
                    r0.origin[axis],
                    r1.origin[axis],
                    r2.origin[axis],
                    r3.origin[axis],
                );
                let d = Vec4::new(
                    r0.direction[axis],
                    r1.direction[axis],
                    r2.direction[axis],
                    r3.direction[axis],
                );
                valid &= o.is_finite_mask() & d.is_finite_mask();
                nonzero |= d.cmpne(Vec4::ZERO);
                *negative |= u64::from(d.is_negative_bitmask()) << (4 * group);
                let (near, far, inverse) = slab_numbers(o, d);
                chunk.numbers.origin_near[axis][group] = near;
                chunk.numbers.origin_far[axis][group] = far;
                chunk.numbers.inverse[axis][group] = inverse;
                chunk.numbers.origin[axis][group] = o;
                chunk.numbers.direction[axis][group] = d;
            }
            valid_lanes |= u64::from((valid & nonzero).bitmask()) << (4 * group);
        }
        // A lane's octant has bit `axis` set where its direction is negative on `axis`.
        let valid_lanes = valid_lanes & chunk.all;
        for (octant, mask) in chunk.octants.iter_mut().enumerate() {
            *mask = (0..3).fold(valid_lanes, |lanes, axis| {
                let negative = negative_lanes[axis];
                let side = if (octant >> axis) & 1 == 1 {
                    negative
                } else {
                    !negative
                };
                lanes & side
            });
        }
    }
}

/// What splitting rays into packets works in: a chunk's numbers and room for the
/// numbers of a packet gathered from some of them, some seven kilobytes, reused from a
/// thread-local (zeroing them for every batch of shadow rays cost more than tracing
/// the batch).
struct PacketBuffers {
    chunk: ChunkNumbers,
    gathered: LaneNumbers,
}

impl PacketBuffers {
    const EMPTY: Self = Self {
        chunk: ChunkNumbers::EMPTY,
        gathered: LaneNumbers::EMPTY,
    };
}

thread_local! {
    /// Three sets of buffers per thread: a world's packets, an instance's packets in
    /// object space nested in them, and one spare.
    static PACKET_BUFFERS: [RefCell<PacketBuffers>; 3] = const {
        [
            RefCell::new(PacketBuffers::EMPTY),
            RefCell::new(PacketBuffers::EMPTY),
            RefCell::new(PacketBuffers::EMPTY),
        ]
    };
}

/// Splits `rays` (at most [`PACKET_SIZE`]) into packets of one octant each and calls
/// `trace(packet)` for each (see [`BoxPacket::rays`]). Rays that hit nothing by
/// definition (a non-finite origin or direction, a zero direction) are in no packet.
pub(crate) fn for_each_packet(rays: &[Ray], mut trace: impl FnMut(&BoxPacket<'_>)) {
    if rays.is_empty() {
        return;
    }
    let mut split = |buffers: &mut PacketBuffers| {
        let PacketBuffers { chunk, gathered } = buffers;
        chunk.fill(rays);
        let chunk = &*chunk;
        for (octant, &mask) in chunk.octants.iter().enumerate() {
            if mask != 0 {
                trace(&BoxPacket::new(chunk, gathered, octant as u8, mask));
            }
        }
    };
    let done = PACKET_BUFFERS.with(|all| {
        for cell in all {
            if let Ok(mut buffers) = cell.try_borrow_mut() {
                split(&mut buffers);
                return true;
            }
        }
        false
    });
    if !done {
        let mut fresh = PacketBuffers::EMPTY;
        split(&mut fresh);
    }
}

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

/// A packet's box tests: the whole packet's test of a node's eight boxes (see
/// [`BoxPacket::hit_children_sse`]) and its lanes' single rays, with SSE
/// ([`BoxPacket`]) or in AVX registers where the processor has them
/// (`avx::AvxPacket`), with the same bits.
pub(crate) trait PacketBoxes {
    /// A lane's ray.
    type Ray: ChildBoxes;

    /// The packet tested.
    fn packet(&self) -> &BoxPacket<'_>;

    /// The mask of the boxes some ray of the packet may hit with `t` in `[t_min,
    /// t_max]`, and a lower bound of their entry distances.
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]);

    /// The ray of lane `lane`.
    fn lane_ray(&self, lane: usize) -> Self::Ray;
}

impl PacketBoxes for BoxPacket<'_> {
    type Ray = BoxRay;

    #[inline(always)]
    fn packet(&self) -> &BoxPacket<'_> {
        self
    }

    #[inline(always)]
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]) {
        self.hit_children_sse::<OCTANT>(node, Vec4::splat(t_min), Vec4::splat(t_max))
    }

    #[inline(always)]
    fn lane_ray(&self, lane: usize) -> BoxRay {
        BoxPacket::lane_ray(self, lane)
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
                    $bvh.closest_walks::<$octant, _, _, _>(
                        $boxes,
                        $t_min,
                        $visitor,
                        $prefetch_leaf,
                        $lanes,
                        $t_max,
                        stacks,
                    )
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
        let t_min4 = Vec4::splat(traversal.t_min);
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
                let rays = packet.rays_hitting::<OCTANT>(parent, slot, lanes, t_min4, t_max);
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

    /// The closest hits of an incoherent packet's rays (see [`MAX_DIRECTION_SPREAD`]):
    /// each ray walks the whole tree on its own, as [`Bvh::closest`] does, but
    /// [`WALKS`] of them take turns, one node or leaf each, so that while one waits for
    /// the node it goes to next (whose loading its previous step started), the others
    /// work. One ray's walk waits for memory at every level of a tree larger than the
    /// caches; several walks side by side keep several loads in flight.
    #[inline(always)]
    #[allow(clippy::too_many_arguments)]
    fn closest_walks<const OCTANT: u8, B: PacketBoxes, V: PacketVisitor, P: Fn(u32, u32)>(
        &self,
        boxes: &B,
        t_min: f32,
        visitor: &mut V,
        prefetch_leaf: P,
        lanes: u64,
        t_max: &mut Lanes,
        stacks: &mut [Stack; WALKS],
    ) {
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

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use crate::Aabb;

    use super::*;

    #[test]
    fn a_lane_mask_holds_the_lanes_of_its_bits() {
        for bits in 0..16 {
            assert_eq!(lane_mask(bits).bitmask(), bits);
            assert_eq!(
                lane_mask(bits | 0xf0).bitmask(),
                bits,
                "only the low four bits"
            );
        }
    }

    /// The largest number among the lanes a mask selects, and only those.
    #[test]
    fn max_lane_reads_only_the_masked_lanes() {
        let mut values: Lanes = [Vec4::ZERO; PACKET_GROUPS];
        // Lane i holds 100 - i: the lowest selected lane holds the largest number.
        for i in 0..PACKET_SIZE {
            set_lane(&mut values, i, 100.0 - i as f32);
        }
        assert_eq!(max_lane(&values, 0b10), 99.0);
        assert_eq!(max_lane(&values, 0b1000), 97.0);
        assert_eq!(max_lane(&values, 0b1100), 98.0);
        assert_eq!(max_lane(&values, (1 << 5) | (1 << 40)), 95.0);
        assert_eq!(max_lane(&values, 1 << 63), 37.0);
        assert_eq!(max_lane(&values, 0), f32::NEG_INFINITY);
        // Lane i holds i: now every unselected lane of a group holds more than the
        // selected one below it.
        for i in 0..PACKET_SIZE {
            set_lane(&mut values, i, i as f32);
        }
        for lane in [0, 1, 2, 4, 41, 62] {
            assert_eq!(max_lane(&values, 1 << lane), lane as f32);
        }
        assert_eq!(max_lane(&values, 0b101), 2.0);
    }

    proptest::proptest! {
        /// The packet's interval test bounds its rays' own tests: every child a ray
        /// enters, the packet enters, and no earlier than the ray; where the processor
        /// runs AVX, its AVX test gives the same bits (for rays of one
        /// octant whose directions differ in length and in angle, so that the extreme
        /// reciprocals differ, against boxes ahead, around and behind the origins).
        #[test]
        fn the_packet_box_test_bounds_each_ray_box_test(
            rays in proptest::collection::vec(
                (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0, 0.1f32..3.0, 0.1f32..3.0, 0.1f32..3.0),
                1..=PACKET_SIZE,
            ),
            boxes in proptest::collection::vec(
                (-4.0f32..8.0, -4.0f32..8.0, -4.0f32..8.0, 0.01f32..3.0, 0.01f32..3.0, 0.01f32..3.0),
                WIDTH,
            ),
            t_max in 0.5f32..20.0,
        ) {
            let rays: Vec<Ray> = rays
                .iter()
                .map(|&(ox, oy, oz, dx, dy, dz)| Ray::new(Vec3::new(ox, oy, oz), Vec3::new(dx, dy, dz)))
                .collect();
            let mut node = Node::EMPTY;
            for (slot, &(x, y, z, w, h, d)) in boxes.iter().enumerate() {
                let min = Vec3::new(x, y, z);
                node.set_child(slot, &Aabb::new(min, min + Vec3::new(w, h, d)), slot as u32);
            }
            let mut chunk = ChunkNumbers::EMPTY;
            chunk.fill(&rays);
            // Every direction is positive: octant 0.
            let mut gathered = LaneNumbers::EMPTY;
            let packet = BoxPacket::new(&chunk, &mut gathered, 0, chunk.octants[0]);
            let (t_min4, t_max4) = (Vec4::ZERO, Vec4::splat(t_max));
            let (packet_mask, packet_near) = packet.hit_children_sse::<0>(&node, t_min4, t_max4);
            #[cfg(target_arch = "x86_64")]
            if crate::avx::detected() {
                // The AVX test is the SSE test to the bit.
                #[allow(unsafe_code)]
                // SAFETY: the processor runs AVX and POPCNT.
                let avx = unsafe { crate::avx::AvxPacket::new(&packet) };
                let (mask, near) = avx.hit_children::<0>(&node, 0.0, t_max);
                proptest::prop_assert_eq!(
                    (mask, near.map(f32::to_bits)),
                    (packet_mask, packet_near.map(f32::to_bits))
                );
            }
            for ray in &rays {
                let (mask, near) = BoxRay::new(ray).hit_children_sse::<0>(&node, t_min4, t_max4);
                proptest::prop_assert_eq!(mask & !packet_mask, 0, "{:?}", ray);
                for slot in lanes_of(u64::from(mask)) {
                    proptest::prop_assert!(packet_near[slot] <= near[slot], "{:?} slot {}", ray, slot);
                }
            }
        }
    }

    /// Directions `(1, 1, -2) L` and `(1 + s, 1, -2) L` spread by `s L` on x over a
    /// shortest length of `sqrt(6) L`: traced as a packet while `s <= 0.05 sqrt(6) =
    /// 0.1225`, whatever `L`, whether they are the whole chunk or are gathered from a
    /// chunk that also holds a ray of another octant. The spread is measured across the
    /// lanes, not lane by lane (in lanes 0 and 1, each ray spreads nothing on its own).
    #[test]
    fn a_packet_is_coherent_while_its_directions_spread_at_most_a_twentieth() {
        let coherent = |s: f32, length: f32, gathered: bool| {
            let mut rays = vec![
                Ray::new(Vec3::ZERO, Vec3::new(1.0, 1.0, -2.0) * length),
                Ray::new(Vec3::ZERO, Vec3::new(1.0 + s, 1.0, -2.0) * length),
            ];
            if gathered {
                rays.push(Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0)));
            }
            let mut chunk = ChunkNumbers::EMPTY;
            chunk.fill(&rays);
            // Octant 0b100: negative z only.
            assert_eq!(chunk.octants[4], 0b11);
            assert_eq!(chunk.octants[4] == chunk.all, !gathered);
            let mut gathered = LaneNumbers::EMPTY;
            let packet = BoxPacket::new(&chunk, &mut gathered, 4, chunk.octants[4]);
            packet.coherent
        };
        for (length, gathered) in [(1.0, false), (3.0, false), (1.0, true), (3.0, true)] {
            assert!(coherent(0.12, length, gathered), "L {length}, {gathered}");
            assert!(!coherent(0.125, length, gathered), "L {length}, {gathered}");
        }
    }

    /// Boxes traced by test visitors: each lane's ray, and the boxes in the BVH's item
    /// order.
    struct BoxScene<'a> {
        boxes: &'a [Aabb],
        order: &'a [u32],
        rays: &'a [Ray],
    }

    impl BoxScene<'_> {
        /// A leaf for lane `lane`: the nearest entry into the boxes at positions
        /// `start..start + count`, if nearer than `t_max`.
        fn nearest(&self, lane: usize, start: u32, count: u32, t_max: f32) -> f32 {
            (start..start + count)
                .filter_map(|p| {
                    self.boxes[self.order[p as usize] as usize].slab_interval(&self.rays[lane])
                })
                .map(|(t_enter, _)| t_enter)
                .fold(t_max, f32::min)
        }
    }

    /// The packet walk, like the single-ray one, goes front to back: 200 boxes in a row
    /// along x seen end on by four parallel rays, the nearest box hides the others, so
    /// each ray's leaf test runs once (`Bvh::closest`'s test, for packets). From inside
    /// the row, the nearest child is in the middle of a node, not at one end.
    #[test]
    fn the_packet_walk_visits_only_the_nearest_leaf_of_a_row_of_boxes() {
        struct Nearest<'a> {
            scene: BoxScene<'a>,
            visits: [u32; PACKET_SIZE],
        }
        impl PacketVisitor for Nearest<'_> {
            fn leaf(&mut self, lane: usize, start: u32, count: u32, t_max: f32) -> f32 {
                self.visits[lane] += 1;
                self.scene.nearest(lane, start, count, t_max)
            }
        }
        let boxes: Vec<Aabb> = (0..200)
            .map(|k| {
                let x = 2.0 * k as f32;
                Aabb::new(Vec3::new(x, -0.5, -0.5), Vec3::new(x + 1.0, 0.5, 0.5))
            })
            .collect();
        let bvh = Bvh::build(&boxes, crate::BuildParams::default());
        // From either end, and from between boxes 99 and 100 (x = 199 to 200) either way.
        for (x, direction, nearest_t) in [
            (-10.0, Vec3::X, 10.0),
            (410.0, Vec3::NEG_X, 11.0),
            (199.25, Vec3::X, 0.75),
            (199.5, Vec3::NEG_X, 0.5),
        ] {
            let rays: Vec<Ray> = (0..4)
                .map(|k| Ray::new(Vec3::new(x, 0.1 * k as f32, 0.2), direction))
                .collect();
            let mut chunk = ChunkNumbers::EMPTY;
            chunk.fill(&rays);
            let octant = usize::from(direction.x < 0.0);
            let mut gathered = LaneNumbers::EMPTY;
            let packet = BoxPacket::new(&chunk, &mut gathered, octant as u8, chunk.octants[octant]);
            assert!(packet.coherent);
            let mut t_max = [Vec4::INFINITY; PACKET_GROUPS];
            let mut nearest = Nearest {
                scene: BoxScene {
                    boxes: &boxes,
                    order: bvh.item_order(),
                    rays: &rays,
                },
                visits: [0; PACKET_SIZE],
            };
            bvh.closest_packet(&packet, chunk.all, 0.0, &mut t_max, &mut nearest, |_, _| {});
            for (i, ray) in rays.iter().enumerate() {
                let lane_ray = packet.rays[i] as usize;
                assert_eq!(lane_ray, i, "whole chunk: lane i holds ray i");
                assert_eq!(lane(&t_max, i), nearest_t, "{ray:?}");
                assert_eq!(nearest.visits[i], 1, "{ray:?}");
            }
        }
    }

    /// A subtree that a quarter of the packet enters stays with the packet even where
    /// the packet enters many children of a node: eight plates stacked along the view,
    /// each of sixteen tiles, seen by an 8 x 8 packet of parallel rays. The root's
    /// children are the plates, all entered by every ray; the nearest plate is walked by
    /// the packet, so its leaves are tested through `leaf_lanes` and never by a ray
    /// finishing the plate alone.
    #[test]
    fn a_subtree_most_rays_enter_is_walked_as_a_packet() {
        struct Counting<'a> {
            scene: BoxScene<'a>,
            in_lanes: bool,
            alone: u32,
            together: u32,
        }
        impl PacketVisitor for Counting<'_> {
            fn leaf(&mut self, lane: usize, start: u32, count: u32, t_max: f32) -> f32 {
                if !self.in_lanes {
                    self.alone += 1;
                }
                self.scene.nearest(lane, start, count, t_max)
            }
            fn leaf_lanes(&mut self, lanes: u64, start: u32, count: u32, t_max: &mut Lanes) {
                self.in_lanes = true;
                for i in lanes_of(lanes) {
                    self.together += 1;
                    let t = self.leaf(i, start, count, lane(t_max, i));
                    set_lane(t_max, i, t);
                }
                self.in_lanes = false;
            }
        }
        // Plates at z = 0, -1, ..., -7, each 4 x 4 tiles of 2 x 2 over [0, 8]^2.
        let boxes: Vec<Aabb> = (0..8)
            .flat_map(|plate| (0..16).map(move |tile| (plate, tile)))
            .map(|(plate, tile)| {
                let (x, y, z) = (
                    2.0 * (tile % 4) as f32,
                    2.0 * (tile / 4) as f32,
                    -(plate as f32),
                );
                Aabb::new(Vec3::new(x, y, z - 0.1), Vec3::new(x + 2.0, y + 2.0, z))
            })
            .collect();
        let bvh = Bvh::build(&boxes, crate::BuildParams::default());
        let root = &bvh.nodes()[0];
        assert!(
            root.children.iter().all(|&c| c & LEAF == 0),
            "the root's children are the plates' nodes"
        );
        let rays: Vec<Ray> = (0..64)
            .map(|k| {
                let (x, y) = ((k % 8) as f32 + 0.5, (k / 8) as f32 + 0.5);
                Ray::new(Vec3::new(x, y, 10.0), Vec3::NEG_Z)
            })
            .collect();
        let mut chunk = ChunkNumbers::EMPTY;
        chunk.fill(&rays);
        let octant = 0b100;
        let mut gathered = LaneNumbers::EMPTY;
        let packet = BoxPacket::new(
            &chunk,
            &mut gathered,
            octant,
            chunk.octants[octant as usize],
        );
        assert!(packet.coherent);
        let mut t_max = [Vec4::INFINITY; PACKET_GROUPS];
        let mut counting = Counting {
            scene: BoxScene {
                boxes: &boxes,
                order: bvh.item_order(),
                rays: &rays,
            },
            in_lanes: false,
            alone: 0,
            together: 0,
        };
        bvh.closest_packet(
            &packet,
            chunk.all,
            0.0,
            &mut t_max,
            &mut counting,
            |_, _| {},
        );
        for i in 0..64 {
            assert_eq!(lane(&t_max, i), 10.0, "ray {i} stops at the nearest plate");
        }
        assert_eq!(counting.alone, 0, "no ray finished a plate alone");
        assert!(counting.together >= 64, "{} lane tests", counting.together);
    }

    /// The four-at-a-time slab numbers are bit for bit those of single rays, octants
    /// and validity included, for directions with zero, negative-zero, tiny and
    /// non-finite components.
    #[test]
    fn chunk_numbers_are_the_single_ray_numbers() {
        let components = [
            0.0,
            -0.0,
            1e-31,
            -1e-31,
            1e-30,
            0.5,
            -2.0,
            3e-7,
            f32::INFINITY,
            f32::NAN,
        ];
        let origins = [
            Vec3::ZERO,
            Vec3::new(1.0, -2.0, 1e-25),
            Vec3::new(-0.0, 3e5, 0.25),
        ];
        let mut rays = Vec::new();
        for &x in &components {
            for &y in &components {
                for (i, &z) in components.iter().enumerate() {
                    rays.push(Ray::new(origins[i % 3], Vec3::new(x, y, z)));
                }
            }
        }
        for chunk_rays in rays.chunks(37) {
            let mut chunk = ChunkNumbers::EMPTY;
            chunk.fill(chunk_rays);
            // Each lane in at most one octant, and no lane past the last ray.
            let mut seen = 0;
            for &mask in &chunk.octants {
                assert_eq!(mask & seen, 0, "octants overlap");
                assert_eq!(mask & !chunk.all, 0, "a lane past the last ray");
                seen |= mask;
            }
            for (i, ray) in chunk_rays.iter().enumerate() {
                let single_ray = BoxRay::new(ray);
                let in_octant = chunk.octants.iter().position(|mask| mask & (1 << i) != 0);
                assert_eq!(in_octant.is_some(), single_ray.valid, "{ray:?}");
                if !single_ray.valid {
                    continue;
                }
                assert_eq!(in_octant, Some(usize::from(single_ray.octant)), "{ray:?}");
                for axis in 0..3 {
                    let lane = |lanes: &[Lanes; 3]| lane(&lanes[axis], i).to_bits();
                    let single = |lanes: &[Vec4; 3]| lanes[axis].x.to_bits();
                    assert_eq!(
                        lane(&chunk.numbers.origin_near),
                        single(&single_ray.origin_near)
                    );
                    assert_eq!(
                        lane(&chunk.numbers.origin_far),
                        single(&single_ray.origin_far)
                    );
                    assert_eq!(lane(&chunk.numbers.inverse), single(&single_ray.inverse));
                }
            }
        }
    }
}
