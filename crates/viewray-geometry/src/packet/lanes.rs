//! A packet's numbers, one per ray, four rays per SIMD vector: the lane type, lane
//! masks, and reading and writing single lanes.

use glam::{BVec4A, Vec4};

/// The most rays in a packet: one bit each of a `u64` mask.
pub(crate) const PACKET_SIZE: usize = 64;
/// SIMD groups of four rays in a packet.
pub(crate) const PACKET_GROUPS: usize = PACKET_SIZE / 4;

/// One number per ray of a packet, four rays per SIMD vector.
pub(crate) type Lanes = [Vec4; PACKET_GROUPS];

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
pub(super) fn max_lane(values: &Lanes, mask: u64) -> f32 {
    // Every group, without branches (a group outside the mask gives -inf), in two
    // chains of maxima that run side by side.
    let mut max = [Vec4::NEG_INFINITY; 2];
    for (group, v) in values.iter().enumerate() {
        let bits = (mask >> (4 * group)) as u32;
        max[group % 2] = max[group % 2].max(Vec4::select(lane_mask(bits), *v, Vec4::NEG_INFINITY));
    }
    max[0].max(max[1]).max_element()
}
