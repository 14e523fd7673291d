//! A world's loose spheres and triangles against rays four lanes at a time
//! ([`Sphere::intersect_t_lanes`], [`WatertightLanes`]): the same hits, bit for bit, as
//! each lane's ray tested alone, for a fraction of the instructions (the single-ray
//! triangle test prepares its ray again for every triangle). A packet's groups of four
//! and a small world's four rays at a time (`flat.rs`) both come here.

use glam::{Vec2, Vec4};

use super::{Object, World};
use crate::hit::RawHit;
use crate::packet::{BoxPacket, PacketQuery, at, at_mut, lane_mask, lanes_of};
use crate::shapes::WatertightLanes;
use crate::{Ray, Sphere, Triangle};

/// A loose shape four rays can be tested against together.
#[derive(Clone, Copy)]
pub(super) enum Loose<'a> {
    Sphere(&'a Sphere),
    Triangle(&'a Triangle),
}

/// Four rays, one per lane: their origins and directions per axis.
#[derive(Clone, Copy, Debug)]
pub(super) struct RayLanes {
    pub(super) origin: [Vec4; 3],
    pub(super) direction: [Vec4; 3],
}

/// What one shape gives four lanes: the lanes hit and their `t` and barycentrics, and
/// the lanes left to test ray by ray.
struct GroupHits {
    hit: u32,
    undecided: u32,
    t: Vec4,
    barycentric: [Vec4; 2],
}

impl<'a> Loose<'a> {
    /// The loose shape `object` is, if it is one.
    #[inline(always)]
    pub(super) fn of(object: &'a Object) -> Option<Self> {
        match object {
            Object::Sphere(sphere) => Some(Loose::Sphere(sphere)),
            Object::Triangle(triangle) => Some(Loose::Triangle(triangle)),
            Object::Plane(_) | Object::Box(_) | Object::Instance(_) => None,
        }
    }

    /// The shape against the rays of `lanes` (low four bits) of `rays`.
    #[inline(always)]
    fn group_hits(self, rays: &RayLanes, lanes: u32, (t_min, t_max): (Vec4, Vec4)) -> GroupHits {
        let RayLanes { origin, direction } = *rays;
        match self {
            Loose::Sphere(sphere) => {
                let (hit, t) = sphere.intersect_t_lanes(origin, direction, t_min, t_max);
                GroupHits {
                    hit: hit & lanes,
                    undecided: 0,
                    t,
                    barycentric: [Vec4::ZERO; 2],
                }
            }
            Loose::Triangle(triangle) => {
                let rays = WatertightLanes::new(origin, direction);
                let hits = rays.intersect([triangle.a, triangle.b, triangle.c], t_min, t_max);
                GroupHits {
                    hit: hits.hit & lanes,
                    undecided: !hits.decided & lanes,
                    t: hits.t,
                    barycentric: [hits.b1, hits.b2],
                }
            }
        }
    }
}

/// Four lanes' closest hits so far: the distances and the hits (one slot per lane).
pub(super) struct GroupBest<'b> {
    pub(super) t_max: &'b mut Vec4,
    pub(super) best: &'b mut [Option<RawHit>],
}

impl World {
    /// [`World::intersect_object`] of object `object`, the loose shape `shape`, for
    /// each lane of `query`, four lanes at a time.
    pub(super) fn closest_loose(&self, shape: Loose<'_>, object: u32, query: PacketQuery<'_>) {
        let PacketQuery {
            packet,
            rays,
            lanes,
            t_min,
            t_max,
            best,
        } = query;
        for ((group, t_max), best) in t_max.iter_mut().enumerate().zip(best.chunks_mut(4)) {
            let group_lanes = ((lanes >> (4 * group)) & 0xf) as u32;
            if group_lanes == 0 {
                continue;
            }
            let lane_rays = packet_group(packet, group);
            let ray = |j: usize| &rays[usize::from(packet.rays()[4 * group + j])];
            let group_best = GroupBest { t_max, best };
            self.closest_loose_group(
                (shape, object),
                (&lane_rays, ray),
                group_lanes,
                t_min,
                group_best,
            );
        }
    }

    /// [`World::intersect_object`] of object `object`, the loose shape `shape`, for the
    /// rays of `lanes` (low four bits) of `rays`, given lane by lane by `ray`: each hit
    /// closer than the lane's `t_max` goes into its slot of `best` and lowers it.
    #[inline(always)]
    pub(super) fn closest_loose_group<'r>(
        &self,
        (shape, object): (Loose<'_>, u32),
        (rays, ray): (&RayLanes, impl Fn(usize) -> &'r Ray),
        lanes: u32,
        t_min: f32,
        GroupBest { t_max, best }: GroupBest<'_>,
    ) {
        let hits = shape.group_hits(rays, lanes, (Vec4::splat(t_min), *t_max));
        for j in lanes_of(u64::from(hits.hit)) {
            best[j] = Some(RawHit {
                t: at(&hits.t, j),
                object,
                primitive: 0,
                barycentric: Vec2::new(at(&hits.barycentric[0], j), at(&hits.barycentric[1], j)),
            });
        }
        *t_max = Vec4::select(lane_mask(hits.hit), hits.t, *t_max);
        for j in lanes_of(u64::from(hits.undecided)) {
            if let Some(hit) = self.intersect_object(object, ray(j), t_min, at(t_max, j)) {
                *at_mut(t_max, j) = hit.t;
                best[j] = Some(hit);
            }
        }
    }

    /// [`World::any_object`] of object `object`, the loose shape `shape`, for each lane
    /// of `lanes` of `packet` (filled from `rays`): the mask of the lanes it blocks.
    pub(super) fn any_loose(
        &self,
        (shape, object): (Loose<'_>, u32),
        (packet, rays): (&BoxPacket<'_>, &[Ray]),
        lanes: u64,
        t_range: (f32, f32),
    ) -> u64 {
        let mut found = 0;
        for group in 0..packet.rays().len().div_ceil(4) {
            let group_lanes = ((lanes >> (4 * group)) & 0xf) as u32;
            if group_lanes == 0 {
                continue;
            }
            let lane_rays = packet_group(packet, group);
            let ray = |j: usize| &rays[usize::from(packet.rays()[4 * group + j])];
            let hit =
                self.any_loose_group((shape, object), (&lane_rays, ray), group_lanes, t_range);
            found |= u64::from(hit) << (4 * group);
        }
        found
    }

    /// [`World::any_object`] of object `object`, the loose shape `shape`, for the rays
    /// of `lanes` (low four bits) of `rays`, given lane by lane by `ray`: the mask of
    /// the lanes it blocks.
    #[inline(always)]
    pub(super) fn any_loose_group<'r>(
        &self,
        (shape, object): (Loose<'_>, u32),
        (rays, ray): (&RayLanes, impl Fn(usize) -> &'r Ray),
        lanes: u32,
        (t_min, t_max): (f32, f32),
    ) -> u32 {
        let hits = shape.group_hits(rays, lanes, (Vec4::splat(t_min), Vec4::splat(t_max)));
        let mut found = hits.hit;
        for j in lanes_of(u64::from(hits.undecided)) {
            if self.any_object(object, ray(j), t_min, t_max) {
                found |= 1 << j;
            }
        }
        found
    }
}

/// The rays of group `group` of `packet` (lanes past its last ray repeat one of its rays).
#[inline(always)]
fn packet_group(packet: &BoxPacket<'_>, group: usize) -> RayLanes {
    let (origin, direction) = packet.group_rays(group);
    RayLanes { origin, direction }
}
