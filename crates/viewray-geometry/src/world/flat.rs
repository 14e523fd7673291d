//! Small worlds: a world of one bounded object (and any planes), or of a few whose
//! BVH is one leaf, none of them a mesh. Made into packets, each batch of its rays paid
//! for slab numbers, octant masks and bounds (a division per axis and ray, and
//! gathers) only to meet that one object, or to walk a root with one child.
//!
//! Here rays go four at a time, straight from the slice, into lanes of origins and
//! directions; they meet the planes, then the leaf's box (as the walk tests it), then
//! each object in the leaf's order, with the arithmetic of the packets' lanes and in
//! their order (`closest_planes`, `BoxPacket::rays_hitting`, the loose shapes' lanes,
//! the same strict comparisons), so they find the same hits bit for bit, ties at equal
//! `t` included: of shapes met at the same distance the plane listed first, then the
//! object first in the leaf, wins. Each object is first tested against its own box,
//! enlarged far beyond any rounding (see `enlarged`): a lane that misses it cannot hit
//! the object, which is then not tested for it.
//!
//! Worlds of several leaves keep their packets: tried flat, in one leaf, the lecture's
//! scenes took more instructions, not fewer (docs/performance.md, "Small worlds"): a
//! packet's one interval test of a node stands for 64 rays' box tests, which four rays
//! at a time repeat for every object.

use std::ops::Range;

use glam::{BVec4A, Vec2, Vec4};

use super::loose::{GroupBest, Loose, RayLanes};
use super::{Object, ObjectHit, World, enlarged};
use crate::Ray;
use crate::bvh::{Bvh, slab_numbers, slab_test};
use crate::hit::RawHit;
use crate::packet::{at, at_mut, lane_mask, lanes_of};

/// How a small world's batches of rays meet its bounded objects.
#[derive(Clone, Debug)]
pub(super) struct Flat {
    /// The box of the BVH's one leaf, tested as the walk tests it; `None` for no
    /// object or one, which rays meet without a box test, as the single-ray query does.
    leaf: Option<BoxLanes>,
    /// The bounded objects in leaf order, each with its box enlarged (see `enlarged`):
    /// a lane that misses that box cannot hit the object, which is then not tested for
    /// it.
    objects: Vec<(u32, BoxLanes)>,
}

impl Flat {
    /// How `bvh` over the objects `leaf_objects` (in leaf order) of `objects` is met
    /// flat, if it is: when it holds one object or one leaf, and no mesh.
    pub(super) fn of(objects: &[Object], bvh: &Bvh, leaf_objects: &[u32]) -> Option<Self> {
        let mesh = |&object: &u32| matches!(objects[object as usize], Object::Instance(_));
        if leaf_objects.iter().any(mesh) {
            return None;
        }
        let leaf = match leaf_objects.len() {
            0 | 1 => None,
            _ => {
                let leaf = bvh.one_leaf_box()?;
                Some(BoxLanes::new(leaf.min.to_array(), leaf.max.to_array()))
            }
        };
        let objects = leaf_objects
            .iter()
            .map(|&object| {
                let bounds = objects[object as usize].bounds();
                (
                    object,
                    enlarged(bounds.expect("a leaf's objects are bounded")),
                )
            })
            .collect();
        Some(Self { leaf, objects })
    }
}

/// Four rays' slab numbers per axis (see [`slab_numbers`]) and the lanes whose
/// direction is negative on each axis: what their box tests start from.
#[derive(Clone, Copy, Debug)]
pub(super) struct SlabLanes {
    origin_near: [Vec4; 3],
    origin_far: [Vec4; 3],
    inverse: [Vec4; 3],
    negative: [BVec4A; 3],
}

impl SlabLanes {
    /// The numbers of four rays, from their origins and directions per axis.
    #[inline(always)]
    pub(super) fn new(origin: [Vec4; 3], direction: [Vec4; 3]) -> Self {
        let numbers = [0, 1, 2].map(|axis| slab_numbers(origin[axis], direction[axis]));
        Self {
            origin_near: numbers.map(|n| n.0),
            origin_far: numbers.map(|n| n.1),
            inverse: numbers.map(|n| n.2),
            negative: direction.map(|d| lane_mask(d.is_negative_bitmask())),
        }
    }
}

/// A box's lowest and highest planes per axis, each in every lane.
#[derive(Clone, Copy, Debug)]
pub(super) struct BoxLanes {
    low: [Vec4; 3],
    high: [Vec4; 3],
}

impl BoxLanes {
    /// The box from `low` to `high`.
    pub(super) fn new(low: [f32; 3], high: [f32; 3]) -> Self {
        Self {
            low: low.map(Vec4::splat),
            high: high.map(Vec4::splat),
        }
    }

    /// The lanes of four rays that enter the box with `t` in `[t_min, t_max]`: each
    /// lane exactly a single ray's test of a node's child (`BoxRay`): its slab numbers,
    /// the near plane picked by the sign of its direction (as its octant does), the
    /// robust slab test.
    #[inline(always)]
    pub(super) fn rays_hitting(&self, rays: &SlabLanes, t_min: Vec4, t_max: Vec4) -> u32 {
        let mut near = [Vec4::ZERO; 3];
        let mut far = [Vec4::ZERO; 3];
        for axis in 0..3 {
            // Toward `-axis` the near plane is the box's high side.
            let negative = rays.negative[axis];
            let (low, high) = (self.low[axis], self.high[axis]);
            let inverse = rays.inverse[axis];
            near[axis] = (Vec4::select(negative, high, low) - rays.origin_near[axis]) * inverse;
            far[axis] = (Vec4::select(negative, low, high) - rays.origin_far[axis]) * inverse;
        }
        slab_test(near, far, t_min, t_max).0
    }
}

/// Up to four rays in lanes (see [`ray_lanes`](crate::packet::ray_lanes)) and the mask of
/// the lanes that hold a ray that can hit anything.
#[inline(always)]
pub(super) fn ray_lanes(rays: &[Ray]) -> (RayLanes, u32) {
    debug_assert!(rays.len() <= 4);
    let (origin, direction, traceable) = crate::packet::ray_lanes(rays, 0);
    let present = (1 << rays.len()) - 1;
    (
        RayLanes { origin, direction },
        traceable.bitmask() & present,
    )
}

/// The raw hit of a plane, object `object`, at `t`.
#[inline(always)]
pub(super) fn plane_hit(t: f32, object: u32) -> RawHit {
    RawHit {
        t,
        object,
        primitive: 0,
        barycentric: Vec2::ZERO,
    }
}

impl World {
    /// [`World::closest_objects`] of a small world, four rays at a time (see the
    /// module's notes).
    pub(super) fn closest_flat(
        &self,
        flat: &Flat,
        rays: &[Ray],
        t_range: Range<f32>,
        hits: &mut [Option<ObjectHit>],
    ) {
        self.closest_flat_among(flat.leaf.as_ref(), &flat.objects, rays, t_range, hits);
    }

    /// The closest hits of `rays` with the planes and the bounded objects of
    /// `objects` (in their order, each behind its own enlarged box), four rays at a
    /// time, after the leaf's box `leaf` if there is one: [`World::closest_flat`]'s
    /// query, for any few objects that are all a batch of rays can meet.
    pub(super) fn closest_flat_among(
        &self,
        leaf: Option<&BoxLanes>,
        objects: &[(u32, BoxLanes)],
        rays: &[Ray],
        t_range: Range<f32>,
        hits: &mut [Option<ObjectHit>],
    ) {
        let t_min = t_range.start;
        let t_min_lanes = Vec4::splat(t_min);
        for (rays, hits) in rays.chunks(4).zip(hits.chunks_mut(4)) {
            let (lanes, valid) = ray_lanes(rays);
            let mut t_max = Vec4::splat(t_range.end);
            let mut best = [None; 4];
            // Planes first, as the packets' `closest_planes`.
            let (found, planes) = self.closest_plane_lanes(&lanes, valid, t_min_lanes, &mut t_max);
            for lane in lanes_of(u64::from(found)) {
                best[lane] = Some(plane_hit(at(&t_max, lane), planes[lane]));
            }
            let slabs = SlabLanes::new(lanes.origin, lanes.direction);
            let mut searching = valid;
            if let Some(leaf) = leaf {
                searching &= leaf.rays_hitting(&slabs, t_min_lanes, t_max);
            }
            if searching != 0 {
                for (object, bounds) in objects {
                    let inside = searching & bounds.rays_hitting(&slabs, t_min_lanes, t_max);
                    if inside != 0 {
                        let group = GroupBest {
                            t_max: &mut t_max,
                            best: &mut best,
                        };
                        self.closest_flat_object(*object, (&lanes, rays), inside, t_min, group);
                    }
                }
            }
            for (hit, raw) in hits.iter_mut().zip(&best) {
                *hit = raw.as_ref().map(|raw| self.object_hit(*raw));
            }
        }
    }

    /// The closest hits of four rays `lanes` (those of `valid`) with the planes, from
    /// `t_min` to below `t_max`, with the arithmetic and order of the packets'
    /// `closest_planes`: `t_max` is brought down to each hit's `t`; returns the lanes
    /// that hit a plane and each one's plane. (Kept in registers: hits written to memory
    /// lane by lane and read back whole waited on the stores.)
    #[inline(always)]
    pub(super) fn closest_plane_lanes(
        &self,
        lanes: &RayLanes,
        valid: u32,
        t_min: Vec4,
        t_max: &mut Vec4,
    ) -> (u32, [u32; 4]) {
        let (mut found, mut objects) = (0, [0; 4]);
        for (object, plane) in self.plane_objects() {
            let (hit, t) = plane.intersect_t_lanes(lanes.origin, lanes.direction, t_min, *t_max);
            let hit = hit & valid;
            if hit != 0 {
                *t_max = Vec4::select(lane_mask(hit), t, *t_max);
                for lane in lanes_of(u64::from(hit)) {
                    objects[lane] = object;
                }
                found |= hit;
            }
        }
        (found, objects)
    }

    /// The closest hits of the rays of `lanes` (low four bits) of `rays` with the
    /// bounded object `object`: a sphere or a triangle in lanes, a box ray by ray, as in
    /// the packets' `intersect_object_packet`.
    #[inline(always)]
    fn closest_flat_object(
        &self,
        object: u32,
        (lanes_rays, rays): (&RayLanes, &[Ray]),
        lanes: u32,
        t_min: f32,
        group: GroupBest<'_>,
    ) {
        if let Some(shape) = Loose::of(&self.objects[object as usize]) {
            let rays = (lanes_rays, |j: usize| &rays[j]);
            return self.closest_loose_group((shape, object), rays, lanes, t_min, group);
        }
        for j in lanes_of(u64::from(lanes)) {
            if let Some(hit) = self.intersect_object(object, &rays[j], t_min, at(group.t_max, j)) {
                *at_mut(group.t_max, j) = hit.t;
                group.best[j] = Some(hit);
            }
        }
    }

    /// [`World::any_hits`] of a small world, four rays at a time (see the module's
    /// notes).
    pub(super) fn any_flat(
        &self,
        flat: &Flat,
        rays: &[Ray],
        t_range: Range<f32>,
        hits: &mut [bool],
    ) {
        let (t_min, t_max) = (t_range.start, t_range.end);
        let (t_min_lanes, t_max_lanes) = (Vec4::splat(t_min), Vec4::splat(t_max));
        for (rays, hits) in rays.chunks(4).zip(hits.chunks_mut(4)) {
            let (lanes, valid) = ray_lanes(rays);
            let mut found = 0;
            for (_, plane) in self.plane_objects() {
                let (hit, _) = plane.intersect_t_lanes(
                    lanes.origin,
                    lanes.direction,
                    t_min_lanes,
                    t_max_lanes,
                );
                found |= hit;
            }
            found &= valid;
            let mut searching = valid & !found;
            if searching == 0 {
                hits.iter_mut()
                    .enumerate()
                    .for_each(|(lane, hit)| *hit = found & (1 << lane) != 0);
                continue;
            }
            let slabs = SlabLanes::new(lanes.origin, lanes.direction);
            if let Some(leaf) = &flat.leaf {
                searching &= leaf.rays_hitting(&slabs, t_min_lanes, t_max_lanes);
            }
            for (object, bounds) in &flat.objects {
                if searching == 0 {
                    break;
                }
                let inside = searching & bounds.rays_hitting(&slabs, t_min_lanes, t_max_lanes);
                if inside != 0 {
                    let blocked =
                        self.any_flat_object(*object, (&lanes, rays), inside, (t_min, t_max));
                    found |= blocked;
                    searching &= !blocked;
                }
            }
            for (lane, hit) in hits.iter_mut().enumerate() {
                *hit = found & (1 << lane) != 0;
            }
        }
    }

    /// Which rays of `lanes` (low four bits) of `rays` the bounded object `object`
    /// blocks with `t` in `t_range`: a sphere or a triangle in lanes, a box ray by ray.
    #[inline(always)]
    fn any_flat_object(
        &self,
        object: u32,
        (lanes_rays, rays): (&RayLanes, &[Ray]),
        lanes: u32,
        t_range: (f32, f32),
    ) -> u32 {
        if let Some(shape) = Loose::of(&self.objects[object as usize]) {
            let rays = (lanes_rays, |j: usize| &rays[j]);
            return self.any_loose_group((shape, object), rays, lanes, t_range) & lanes;
        }
        lanes_of(u64::from(lanes)).fold(0, |found, j| {
            if self.any_object(object, &rays[j], t_range.0, t_range.1) {
                found | 1 << j
            } else {
                found
            }
        })
    }
}

#[cfg(test)]
mod tests;
