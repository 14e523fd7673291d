//! A single ray's test against a node's eight boxes in one AVX instruction per slab
//! plane, for processors that have AVX (chosen at run time).
//!
//! [`BoxRay::hit_children_sse`] tests the eight boxes as two groups of four with SSE, the
//! x86-64 baseline. An incoherent ray spends most of its instructions there: the same
//! test in 256-bit registers does the work of both groups at once. It runs exactly the
//! same operations, lane for lane and operand for operand (subtract, multiply, minimum
//! and maximum in the same order, no fused multiply-add), so it gives the same bits:
//! the same hits, the same traversal order and the same images on every processor.
//!
//! The intrinsics of the AVX path live in this module only; each `unsafe` block says
//! why it is sound.

#![allow(unsafe_code)]

use std::arch::x86_64::{
    __m256, _CMP_LE_OS, _mm256_cmp_ps, _mm256_loadu_ps, _mm256_max_ps, _mm256_min_ps,
    _mm256_movemask_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_setr_m128, _mm256_storeu_ps,
    _mm256_sub_ps,
};

use glam::Vec4;

use crate::bvh::{BoxRay, ChildBoxes, Node, ROBUST, WIDTH, plane_index};
use crate::packet::Lanes;
use crate::packet::{BoxPacket, PacketBoxes};

/// Whether this processor runs AVX, and POPCNT, which every processor with AVX has
/// and the traversals use to count a node's hit children (detected once, then cached
/// loads).
#[inline(always)]
pub(crate) fn detected() -> bool {
    #[cfg(test)]
    if BASELINE_ONLY.get() {
        return false;
    }
    std::arch::is_x86_feature_detected!("avx") && std::arch::is_x86_feature_detected!("popcnt")
}

#[cfg(test)]
thread_local! {
    /// Tests set this to run the SSE traversal on this thread where AVX is present.
    pub(crate) static BASELINE_ONLY: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// A [`BoxRay`]'s numbers in both halves of 256-bit registers.
///
/// Only made by [`AvxRay::new`], which needs AVX: holding one proves that the
/// processor runs AVX, which is what makes [`ChildBoxes::hit_children`] sound.
#[derive(Clone, Copy)]
pub(crate) struct AvxRay {
    origin_near: [__m256; 3],
    origin_far: [__m256; 3],
    inverse: [__m256; 3],
}

impl AvxRay {
    #[target_feature(enable = "avx")]
    #[inline]
    pub(crate) fn new(ray: &BoxRay) -> Self {
        let [n, f, i] = [ray.origin_near, ray.origin_far, ray.inverse];
        Self {
            origin_near: [wide(n[0]), wide(n[1]), wide(n[2])],
            origin_far: [wide(f[0]), wide(f[1]), wide(f[2])],
            inverse: [wide(i[0]), wide(i[1]), wide(i[2])],
        }
    }
}

/// A packet's bounding numbers (see [`BoxPacket::hit_children_sse`]) in both halves of
/// 256-bit registers, for its test of a node's eight boxes in one register per plane,
/// and its lanes' rays as [`AvxRay`]s.
///
/// Only made by [`AvxPacket::new`], which needs AVX: holding one proves that the
/// processor runs AVX.
pub(crate) struct AvxPacket<'a> {
    packet: &'a BoxPacket<'a>,
    bound_origin_near: [__m256; 3],
    bound_origin_far: [__m256; 3],
    inverse_min: [__m256; 3],
    inverse_max: [__m256; 3],
}

impl<'a> AvxPacket<'a> {
    #[target_feature(enable = "avx")]
    #[inline]
    pub(crate) fn new(packet: &'a BoxPacket<'a>) -> Self {
        let [n, f] = [packet.bound_origin_near, packet.bound_origin_far];
        let [low, high] = [packet.inverse_min, packet.inverse_max];
        Self {
            packet,
            bound_origin_near: [wide(n[0]), wide(n[1]), wide(n[2])],
            bound_origin_far: [wide(f[0]), wide(f[1]), wide(f[2])],
            inverse_min: [wide(low[0]), wide(low[1]), wide(low[2])],
            inverse_max: [wide(high[0]), wide(high[1]), wide(high[2])],
        }
    }
}

impl PacketBoxes for AvxPacket<'_> {
    type Ray = AvxRay;

    #[inline(always)]
    fn packet(&self) -> &BoxPacket<'_> {
        self.packet
    }

    #[inline(always)]
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]) {
        // SAFETY: an `AvxPacket` is only made where AVX was detected (see its doc).
        unsafe { packet_hit_children::<OCTANT>(self, node, t_min, t_max) }
    }

    #[inline(always)]
    fn lane_ray(&self, lane: usize) -> AvxRay {
        // SAFETY: as above.
        unsafe { AvxRay::new(&self.packet.lane_ray(lane)) }
    }

    #[inline(always)]
    fn rays_hitting<const OCTANT: u8>(
        &self,
        node: &Node,
        slot: usize,
        lanes: u64,
        t_min: f32,
        t_max: &Lanes,
    ) -> u64 {
        // SAFETY: as above.
        unsafe { packet_rays_hitting::<OCTANT>(self.packet, node, slot, lanes, t_min, t_max) }
    }
}

/// [`BoxPacket::rays_hitting`] eight rays per instruction (two groups of four lanes in
/// one register): for each ray `(plane - origin) * inverse` on each axis, then the
/// entry, exit and mask of [`crate::bvh::slab_test`], the same operations lane for lane.
#[target_feature(enable = "avx")]
#[inline]
fn packet_rays_hitting<const OCTANT: u8>(
    packet: &BoxPacket<'_>,
    node: &Node,
    slot: usize,
    lanes: u64,
    t_min: f32,
    t_max: &Lanes,
) -> u64 {
    let plane = |axis: usize, far: bool| {
        _mm256_set1_ps(node.planes[plane_index::<OCTANT>(axis, far)][slot])
    };
    let [origin_near, origin_far, inverse] = packet.slab_lanes();
    // Groups `2 * pair` and `2 * pair + 1` of some lanes, in one register.
    let pair_of = |lanes: &Lanes, pair: usize| {
        _mm256_setr_m128(lanes[2 * pair].into(), lanes[2 * pair + 1].into())
    };
    let mut hit = 0;
    let mut rest = lanes;
    while rest != 0 {
        let pair = rest.trailing_zeros() as usize / 8;
        rest &= !(0xff << (8 * pair));
        let distance = |axis: usize, far: bool| {
            let origin = if far { origin_far } else { origin_near };
            _mm256_mul_ps(
                _mm256_sub_ps(plane(axis, far), pair_of(&origin[axis], pair)),
                pair_of(&inverse[axis], pair),
            )
        };
        let t_near = _mm256_max_ps(
            _mm256_max_ps(
                _mm256_max_ps(distance(0, false), distance(1, false)),
                distance(2, false),
            ),
            _mm256_set1_ps(t_min),
        );
        let t_far = _mm256_min_ps(
            _mm256_mul_ps(
                _mm256_min_ps(
                    _mm256_min_ps(distance(0, true), distance(1, true)),
                    distance(2, true),
                ),
                _mm256_set1_ps(ROBUST),
            ),
            pair_of(t_max, pair),
        );
        let mask = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OS>(t_near, t_far)) as u64;
        hit |= mask << (8 * pair);
    }
    hit & lanes
}

/// `v` in both halves.
#[target_feature(enable = "avx")]
#[inline]
fn wide(v: Vec4) -> __m256 {
    _mm256_setr_m128(v.into(), v.into())
}

impl ChildBoxes for AvxRay {
    #[inline(always)]
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]) {
        // SAFETY: an `AvxRay` is only made where AVX was detected (see its doc).
        unsafe { hit_children::<OCTANT>(self, node, t_min, t_max) }
    }
}

/// [`BoxRay::hit_children_sse`] with the eight boxes in one register per plane: for each
/// box, `near = (plane - origin_near) * inverse` per axis, entry `max(max(max(near_x,
/// near_y), near_z), t_min)`, exit `min(min(min(far_x, far_y), far_z) * ROBUST, t_max)`,
/// hit when entry <= exit.
#[target_feature(enable = "avx")]
#[inline]
fn hit_children<const OCTANT: u8>(
    ray: &AvxRay,
    node: &Node,
    t_min: f32,
    t_max: f32,
) -> (u32, [f32; WIDTH]) {
    let planes = &node.planes;
    let near = [
        distances::<OCTANT>(ray, planes, 0, false),
        distances::<OCTANT>(ray, planes, 1, false),
        distances::<OCTANT>(ray, planes, 2, false),
    ];
    let far = [
        distances::<OCTANT>(ray, planes, 0, true),
        distances::<OCTANT>(ray, planes, 1, true),
        distances::<OCTANT>(ray, planes, 2, true),
    ];
    slab_test(near, far, t_min, t_max)
}

/// The slab test of eight boxes from the distances to their near and far planes on
/// each axis (see [`crate::bvh::slab_test`]): entry `max(max(max(near_x, near_y),
/// near_z), t_min)`, exit `min(min(min(far_x, far_y), far_z) * ROBUST, t_max)`, the
/// mask of the boxes where entry <= exit, and the entries.
#[target_feature(enable = "avx")]
#[inline]
fn slab_test(near: [__m256; 3], far: [__m256; 3], t_min: f32, t_max: f32) -> (u32, [f32; WIDTH]) {
    let t_near = _mm256_max_ps(
        _mm256_max_ps(_mm256_max_ps(near[0], near[1]), near[2]),
        _mm256_set1_ps(t_min),
    );
    let t_far = _mm256_min_ps(
        _mm256_mul_ps(
            _mm256_min_ps(_mm256_min_ps(far[0], far[1]), far[2]),
            _mm256_set1_ps(ROBUST),
        ),
        _mm256_set1_ps(t_max),
    );
    let mask = _mm256_movemask_ps(_mm256_cmp_ps::<_CMP_LE_OS>(t_near, t_far)) as u32;
    let mut t_near_all = [0.0; WIDTH];
    // SAFETY: `t_near_all` holds eight f32, exactly what an unaligned 256-bit store
    // writes.
    unsafe { _mm256_storeu_ps(t_near_all.as_mut_ptr(), t_near) };
    (mask, t_near_all)
}

/// [`BoxPacket::hit_children_sse`] with the eight boxes in one register per plane: per
/// axis, `d = plane - bound_origin`, the near distance `min(d * inverse_min, d *
/// inverse_max)` and the far one `max(...)`, then the entry, exit and mask as for a
/// single ray.
#[target_feature(enable = "avx")]
#[inline]
fn packet_hit_children<const OCTANT: u8>(
    packet: &AvxPacket<'_>,
    node: &Node,
    t_min: f32,
    t_max: f32,
) -> (u32, [f32; WIDTH]) {
    let planes = &node.planes;
    let near = [
        interval::<OCTANT>(packet, planes, 0, false),
        interval::<OCTANT>(packet, planes, 1, false),
        interval::<OCTANT>(packet, planes, 2, false),
    ];
    let far = [
        interval::<OCTANT>(packet, planes, 0, true),
        interval::<OCTANT>(packet, planes, 1, true),
        interval::<OCTANT>(packet, planes, 2, true),
    ];
    slab_test(near, far, t_min, t_max)
}

/// The bounds of the distances along a packet's rays to the eight boxes' near (or, with
/// `far`, far) planes on `axis`: `d = plane - bound_origin`, then `min(d * inverse_min,
/// d * inverse_max)`, or for the far planes the `max`.
#[target_feature(enable = "avx")]
#[inline]
fn interval<const OCTANT: u8>(
    packet: &AvxPacket<'_>,
    planes: &[[f32; WIDTH]; 6],
    axis: usize,
    far: bool,
) -> __m256 {
    let d = from_origin::<OCTANT>(
        planes,
        axis,
        far,
        &packet.bound_origin_near,
        &packet.bound_origin_far,
    );
    let (low, high) = (
        _mm256_mul_ps(d, packet.inverse_min[axis]),
        _mm256_mul_ps(d, packet.inverse_max[axis]),
    );
    if far {
        _mm256_max_ps(low, high)
    } else {
        _mm256_min_ps(low, high)
    }
}

/// The distances along the ray to the eight boxes' near (or, with `far`, far) planes on
/// `axis`: `(plane - origin) * inverse`, with the origin moved for that plane.
#[target_feature(enable = "avx")]
#[inline]
fn distances<const OCTANT: u8>(
    ray: &AvxRay,
    planes: &[[f32; WIDTH]; 6],
    axis: usize,
    far: bool,
) -> __m256 {
    let d = from_origin::<OCTANT>(planes, axis, far, &ray.origin_near, &ray.origin_far);
    _mm256_mul_ps(d, ray.inverse[axis])
}

/// `plane - origin` for the eight boxes' near (or, with `far`, far) planes on `axis`,
/// the origin moved for that plane (`origin_near` or `origin_far`): what the single
/// ray's distances and the packet's intervals both start from.
#[target_feature(enable = "avx")]
#[inline]
fn from_origin<const OCTANT: u8>(
    planes: &[[f32; WIDTH]; 6],
    axis: usize,
    far: bool,
    origin_near: &[__m256; 3],
    origin_far: &[__m256; 3],
) -> __m256 {
    // SAFETY: a row of `planes` is eight f32, exactly what an unaligned 256-bit load
    // reads.
    let plane = unsafe { _mm256_loadu_ps(planes[plane_index::<OCTANT>(axis, far)].as_ptr()) };
    let origin = if far {
        origin_far[axis]
    } else {
        origin_near[axis]
    };
    _mm256_sub_ps(plane, origin)
}

#[cfg(test)]
mod tests {
    use glam::Vec3;
    use proptest::prelude::*;

    use super::*;
    use crate::{Aabb, Ray};

    /// A coordinate that is often special: on a grid of halves, so that rays run
    /// through boxes' edges and corners and graze their faces (where the exit's
    /// enlargement decides), zero of either sign, tiny or huge.
    fn coordinate() -> impl Strategy<Value = f32> {
        prop_oneof![
            4 => (-6i32..=6).prop_map(|i| i as f32 * 0.5),
            2 => -4.0f32..4.0,
            1 => prop_oneof![Just(-0.0), Just(1e-31), Just(-1e-31), Just(3e38)],
        ]
    }

    fn vector() -> impl Strategy<Value = Vec3> {
        (coordinate(), coordinate(), coordinate()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    /// A node with eight children, some of them empty slots, some with a corner on the
    /// ray (at `origin + t direction`, rounded), where the ray's entry and exit are a
    /// few units in the last place apart and the exit's enlargement decides.
    fn node(origin: Vec3, direction: Vec3, boxes: Vec<Option<(Vec3, Vec3, Option<f32>)>>) -> Node {
        let mut node = Node::EMPTY;
        for (slot, corners) in boxes.into_iter().enumerate() {
            if let Some((a, b, on_ray)) = corners {
                let a = on_ray.map_or(a, |t| origin + direction * t);
                node.set_child(slot, &Aabb::new(a.min(b), a.max(b)), slot as u32);
            }
        }
        node
    }

    fn boxes() -> impl Strategy<Value = Vec<Option<(Vec3, Vec3, Option<f32>)>>> {
        let corner_on_ray = proptest::option::of(0.0f32..4.0);
        proptest::collection::vec(
            proptest::option::of((vector(), vector(), corner_on_ray)),
            WIDTH,
        )
    }

    fn hit_children_both<const OCTANT: u8>(
        ray: &BoxRay,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> ((u32, [u32; WIDTH]), (u32, [u32; WIDTH])) {
        let bits = |(mask, t): (u32, [f32; WIDTH])| (mask, t.map(f32::to_bits));
        let sse = bits(ray.hit_children::<OCTANT>(node, t_min, t_max));
        // SAFETY: only called after `detected()`.
        let avx = unsafe { AvxRay::new(ray) };
        (sse, bits(avx.hit_children::<OCTANT>(node, t_min, t_max)))
    }

    proptest! {
        /// The AVX test gives the SSE test's hit mask and entry distances bit for bit,
        /// for rays and boxes with zero, tiny, huge and shared coordinates.
        #[test]
        fn the_avx_box_test_is_the_sse_box_test_to_the_bit(
            origin in vector(),
            direction in vector(),
            boxes in boxes(),
            t_min in prop_oneof![Just(0.0f32), 0.0f32..2.0],
            t_max in prop_oneof![Just(f32::INFINITY), 0.0f32..8.0],
        ) {
            prop_assume!(detected());
            let ray = BoxRay::new(&Ray::new(origin, direction));
            prop_assume!(ray.valid);
            let node = node(origin, direction, boxes);
            let (sse, avx) = match ray.octant {
                0 => hit_children_both::<0>(&ray, &node, t_min, t_max),
                1 => hit_children_both::<1>(&ray, &node, t_min, t_max),
                2 => hit_children_both::<2>(&ray, &node, t_min, t_max),
                3 => hit_children_both::<3>(&ray, &node, t_min, t_max),
                4 => hit_children_both::<4>(&ray, &node, t_min, t_max),
                5 => hit_children_both::<5>(&ray, &node, t_min, t_max),
                6 => hit_children_both::<6>(&ray, &node, t_min, t_max),
                _ => hit_children_both::<7>(&ray, &node, t_min, t_max),
            };
            prop_assert_eq!(sse, avx);
        }
    }

    /// The tests' switch to the SSE path works (the traversal test below relies on it).
    #[test]
    fn the_baseline_switch_turns_the_avx_path_off() {
        BASELINE_ONLY.set(true);
        let on = detected();
        BASELINE_ONLY.set(false);
        assert!(!on);
    }

    /// Whole traversals, closest and any hit, single rays and packets, give the same
    /// answers to the bit with the AVX box tests and without them, on a mesh deep
    /// enough for every path of the traversal (one, two and more children hit).
    #[test]
    fn the_avx_traversal_finds_the_hits_of_the_baseline_traversal() {
        let mesh = crate::Mesh::icosphere(4, 1.0);
        let mut state = 0x2545_f491_u32;
        let mut uniform = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            (state >> 8) as f32 / (1 << 24) as f32 * 2.0 - 1.0
        };
        let rays: Vec<Ray> = (0..2000)
            .map(|_| {
                let origin = Vec3::new(uniform(), uniform(), uniform()) * 1.5;
                let direction = Vec3::new(uniform(), uniform(), uniform());
                Ray::new(origin, direction)
            })
            .collect();
        let trace = |baseline: bool| {
            BASELINE_ONLY.set(baseline);
            let answers: Vec<_> = rays
                .iter()
                .map(|ray| {
                    let hit = mesh.closest_triangle(ray, 0.0..f32::INFINITY);
                    let any = mesh.any_hit(ray, 0.0..0.5);
                    (
                        hit.map(|h| {
                            (
                                h.t.to_bits(),
                                h.primitive,
                                h.barycentric.to_array().map(f32::to_bits),
                            )
                        }),
                        any,
                    )
                })
                .collect();
            BASELINE_ONLY.set(false);
            answers
        };
        let (avx, baseline) = (trace(false), trace(true));
        let hits = baseline.iter().filter(|(hit, _)| hit.is_some()).count();
        let anys = baseline.iter().filter(|(_, any)| *any).count();
        assert!(
            hits > 500 && anys > 100,
            "{hits} hits and {anys} any hits of 2000 rays"
        );
        assert_eq!(avx, baseline);
        // Packets: coherent rays from one eye (the packet test) and the random rays
        // above (handed to single rays).
        // Tiles of 8 x 8 pixels of a 64 x 64 image through a viewport of 0.32 x 0.32 at
        // distance 1: each tile's directions spread by 0.04, a coherent packet.
        let eye = Vec3::new(0.1, 0.2, 3.0);
        let primary: Vec<Ray> = (0..64 * 64)
            .map(|i| {
                let (tile, k) = (i / 64, i % 64);
                let col = (tile % 8) * 8 + k % 8;
                let row = (tile / 8) * 8 + k / 8;
                let (x, y) = (col as f32 / 200.0 - 0.16, row as f32 / 200.0 - 0.16);
                Ray::new(eye, Vec3::new(x, y, -1.0))
            })
            .collect();
        // The random rays also walked side by side (see `Bvh::walks_pay`).
        for (rays, walk) in [(&primary, false), (&rays, false), (&rays, true)] {
            let trace = |baseline: bool| {
                BASELINE_ONLY.set(baseline);
                crate::bvh::WALK_ALWAYS.set(walk);
                let mut hits = vec![None; rays.len()];
                mesh.closest_triangles(rays, 0.0..f32::INFINITY, &mut hits);
                BASELINE_ONLY.set(false);
                crate::bvh::WALK_ALWAYS.set(false);
                hits.iter()
                    .map(|hit| hit.map(|h| (h.t.to_bits(), h.primitive)))
                    .collect::<Vec<_>>()
            };
            let (avx, baseline) = (trace(false), trace(true));
            assert!(baseline.iter().flatten().count() > 500);
            assert_eq!(avx, baseline);
        }
    }
}
