//! A packet's rays prepared for box tests: each ray's slab numbers worked out four rays
//! at a time, bit for bit as for a single ray, sorted into packets of one octant, with the
//! bounds the packet's interval test starts from.

use std::cell::RefCell;

use glam::{BVec4A, Vec4};

use super::lanes::{
    Lanes, PACKET_GROUPS, PACKET_SIZE, at, at_mut, lanes_below, lanes_of, set_lane,
};
use crate::Ray;
use crate::bvh::{BoxRay, slab_numbers};

/// The largest spread of a packet's unit directions (on any axis) for which it is
/// traversed as a packet. Beyond it the packet's bounds grow so loose that it would
/// visit many nodes none of its rays needs, and its rays are traced one by one (or side
/// by side, see [`Bvh::closest_walks`](crate::Bvh::closest_walks)).
///
/// A thin lens's block of viewing rays spreads by roughly the aperture over the focus
/// distance (a block's rays each start at their own lens point), beyond 0.05 for the lens
/// demos; traced as packets up to 0.2, their render took 9% fewer instructions and the
/// default scene's 3% (docs/performance.md, "Lit renders"). Random directions spread by
/// about 2 and stay apart.
const MAX_DIRECTION_SPREAD: f32 = 0.2;

/// Each lane's ray and slab numbers (see [`slab_numbers`]), per axis, four lanes per
/// vector.
#[derive(Clone, Debug)]
pub(super) struct LaneNumbers {
    pub(super) origin: [Lanes; 3],
    pub(super) direction: [Lanes; 3],
    pub(super) origin_near: [Lanes; 3],
    pub(super) origin_far: [Lanes; 3],
    pub(super) inverse: [Lanes; 3],
}

impl LaneNumbers {
    pub(super) const EMPTY: Self = Self {
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
    pub(super) len: usize,
    /// The index of each lane's ray in the slice the packet was filled from.
    pub(super) rays: [u8; PACKET_SIZE],
    pub(super) octant: u8,
    /// Whether the directions are close enough for the interval test to pay (see
    /// [`MAX_DIRECTION_SPREAD`]); otherwise each ray is traced alone.
    pub(super) coherent: bool,
    /// The lanes' slab numbers: the chunk's own when the packet holds all of its rays
    /// (the common case, with no copy), else gathered from them.
    pub(super) numbers: &'a LaneNumbers,
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
    pub(super) fn new(
        chunk: &'a ChunkNumbers,
        gathered: &'a mut LaneNumbers,
        octant: u8,
        mask: u64,
    ) -> Self {
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

    /// Each lane's slab numbers (see [`slab_numbers`]): the origins moved for the near
    /// and the far planes and the reciprocal directions, per axis.
    #[inline(always)]
    pub(crate) fn slab_lanes(&self) -> [&[Lanes; 3]; 3] {
        let numbers = self.numbers;
        [&numbers.origin_near, &numbers.origin_far, &numbers.inverse]
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
}

/// The rays `rays[first..first + 4]` side by side, per axis (lanes past the last ray
/// repeat `rays[0]`), and the lanes whose ray can hit anything: a finite origin and
/// direction and a nonzero direction, the rays packets take.
#[inline(always)]
pub(crate) fn ray_lanes(rays: &[Ray], first: usize) -> ([Vec4; 3], [Vec4; 3], BVec4A) {
    debug_assert!(first < rays.len());
    let ray = |i: usize| rays.get(first + i).unwrap_or(&rays[0]);
    let (r0, r1, r2, r3) = (ray(0), ray(1), ray(2), ray(3));
    let lanes = |v: [&glam::Vec3; 4], axis: usize| {
        Vec4::new(v[0][axis], v[1][axis], v[2][axis], v[3][axis])
    };
    let origins = [&r0.origin, &r1.origin, &r2.origin, &r3.origin];
    let directions = [&r0.direction, &r1.direction, &r2.direction, &r3.direction];
    let origin = [0, 1, 2].map(|axis| lanes(origins, axis));
    let direction = [0, 1, 2].map(|axis| lanes(directions, axis));
    let finite =
        |v: [Vec4; 3]| v[0].is_finite_mask() & v[1].is_finite_mask() & v[2].is_finite_mask();
    let nonzero = direction[0].cmpne(Vec4::ZERO)
        | direction[1].cmpne(Vec4::ZERO)
        | direction[2].cmpne(Vec4::ZERO);
    (
        origin,
        direction,
        finite(origin) & finite(direction) & nonzero,
    )
}

/// The slab numbers (see [`slab_numbers`]) of up to [`PACKET_SIZE`] rays, four rays per
/// vector, before they are sorted into packets by octant.
pub(super) struct ChunkNumbers {
    pub(super) len: usize,
    /// The mask of all the chunk's rays.
    pub(super) all: u64,
    /// The masks of the valid rays of each octant.
    pub(super) octants: [u64; 8],
    pub(super) numbers: LaneNumbers,
}

impl ChunkNumbers {
    /// Numbers to be filled with [`ChunkNumbers::fill`].
    pub(super) const EMPTY: Self = Self {
        len: 0,
        all: 0,
        octants: [0; 8],
        numbers: LaneNumbers::EMPTY,
    };

    /// Makes these the numbers of `rays`, as [`BoxRay::new`] computes them ray by ray,
    /// four rays at a time. Lanes past the last ray copy the first one; groups past
    /// the last are left as they were (nothing reads them).
    pub(super) fn fill(&mut self, rays: &[Ray]) {
        debug_assert!(!rays.is_empty() && rays.len() <= PACKET_SIZE);
        let chunk = self;
        chunk.len = rays.len();
        chunk.all = lanes_below(rays.len());
        // Per lane, one bit each: valid, and a negative direction on x, y and z; the
        // octants' masks come from these at the end, a few operations for the chunk.
        let (mut valid_lanes, mut negative_lanes) = (0u64, [0u64; 3]);
        for group in 0..rays.len().div_ceil(4) {
            let (origin, direction, traceable) = ray_lanes(rays, 4 * group);
            for (axis, negative) in negative_lanes.iter_mut().enumerate() {
                let (o, d) = (origin[axis], direction[axis]);
                *negative |= u64::from(d.is_negative_bitmask()) << (4 * group);
                let (near, far, inverse) = slab_numbers(o, d);
                chunk.numbers.origin_near[axis][group] = near;
                chunk.numbers.origin_far[axis][group] = far;
                chunk.numbers.inverse[axis][group] = inverse;
                chunk.numbers.origin[axis][group] = o;
                chunk.numbers.direction[axis][group] = d;
            }
            valid_lanes |= u64::from(traceable.bitmask()) << (4 * group);
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
pub(crate) fn for_each_packet(rays: &[Ray], trace: impl FnMut(&BoxPacket<'_>)) {
    split_into_packets(rays, 8, trace);
}

/// [`for_each_packet`], unless the rays' directions fall into [`SCATTERED_OCTANTS`] or
/// more octants: then no packet is traced, and `false` says that the rays are to be
/// traced one by one.
pub(crate) fn for_each_packet_unless_scattered(
    rays: &[Ray],
    trace: impl FnMut(&BoxPacket<'_>),
) -> bool {
    split_into_packets(rays, SCATTERED_OCTANTS - 1, trace)
}

/// Rays whose directions fall into this many of the eight octants or more are scattered:
/// they split into packets of a few incoherent rays each (random rays, about eight to an
/// octant in 64), which are traced ray by ray anyway after being gathered and set up (a
/// sixth of the instructions of the bench's random shadow rays, `BoxPacket::new`). The
/// rays toward one light from a block of neighbouring points take one to four.
const SCATTERED_OCTANTS: u32 = 5;

/// [`for_each_packet`] if the rays fall into at most `max_octants` octants (returning
/// `true`); else `false`, with no packet traced.
fn split_into_packets(
    rays: &[Ray],
    max_octants: u32,
    mut trace: impl FnMut(&BoxPacket<'_>),
) -> bool {
    if rays.is_empty() {
        return true;
    }
    let mut split = |buffers: &mut PacketBuffers| {
        let PacketBuffers { chunk, gathered } = buffers;
        chunk.fill(rays);
        let chunk = &*chunk;
        let octants = chunk.octants.iter().filter(|&&mask| mask != 0).count();
        if octants as u32 > max_octants {
            return false;
        }
        for (octant, &mask) in chunk.octants.iter().enumerate() {
            if mask != 0 {
                trace(&BoxPacket::new(chunk, gathered, octant as u8, mask));
            }
        }
        true
    };
    let done = PACKET_BUFFERS.with(|all| {
        for cell in all {
            if let Ok(mut buffers) = cell.try_borrow_mut() {
                return Some(split(&mut buffers));
            }
        }
        None
    });
    done.unwrap_or_else(|| {
        let mut fresh = PacketBuffers::EMPTY;
        split(&mut fresh)
    })
}
