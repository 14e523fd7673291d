//! A world's loose spheres and triangles against a packet's rays, four lanes at a time
//! ([`Sphere::intersect_t_lanes`], [`WatertightLanes`]): the same hits, bit for bit, as
//! each lane's ray tested alone, for a fraction of the instructions (the single-ray
//! triangle test prepares its ray again for every triangle).

use glam::{Vec2, Vec4};

use super::{Object, World};
use crate::hit::RawHit;
use crate::packet::{BoxPacket, PacketQuery, at, at_mut, lane_mask, lanes_of};
use crate::shapes::WatertightLanes;
use crate::{Sphere, Triangle};

/// A loose shape a packet's lanes can be tested against together.
#[derive(Clone, Copy)]
pub(super) enum Loose<'a> {
    Sphere(&'a Sphere),
    Triangle(&'a Triangle),
}

/// What one shape gives the four lanes of a group: the lanes hit and their `t` and
/// barycentrics, and the lanes left to test ray by ray.
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

    /// The shape against the lanes `lanes` (low four bits) of group `group`.
    #[inline(always)]
    fn group_hits(
        self,
        packet: &BoxPacket<'_>,
        group: usize,
        lanes: u32,
        (t_min, t_max): (Vec4, Vec4),
    ) -> GroupHits {
        let (origin, direction) = packet.group_rays(group);
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
        let t_min_lanes = Vec4::splat(t_min);
        for (group, t_max) in t_max.iter_mut().enumerate() {
            let group_lanes = ((lanes >> (4 * group)) & 0xf) as u32;
            if group_lanes == 0 {
                continue;
            }
            let hits = shape.group_hits(packet, group, group_lanes, (t_min_lanes, *t_max));
            for j in lanes_of(u64::from(hits.hit)) {
                best[4 * group + j] = Some(RawHit {
                    t: at(&hits.t, j),
                    object,
                    primitive: 0,
                    barycentric: Vec2::new(
                        at(&hits.barycentric[0], j),
                        at(&hits.barycentric[1], j),
                    ),
                });
            }
            *t_max = Vec4::select(lane_mask(hits.hit), hits.t, *t_max);
            for j in lanes_of(u64::from(hits.undecided)) {
                let lane = 4 * group + j;
                let ray = &rays[usize::from(packet.rays()[lane])];
                if let Some(hit) = self.intersect_object(object, ray, t_min, at(t_max, j)) {
                    *at_mut(t_max, j) = hit.t;
                    best[lane] = Some(hit);
                }
            }
        }
    }

    /// [`World::any_object`] of object `object`, the loose shape `shape`, for each lane
    /// of `lanes` of `packet` (filled from `rays`): the mask of the lanes it blocks.
    pub(super) fn any_loose(
        &self,
        (shape, object): (Loose<'_>, u32),
        (packet, rays): (&BoxPacket<'_>, &[crate::Ray]),
        lanes: u64,
        t_range: (f32, f32),
    ) -> u64 {
        let (t_min, t_max) = (Vec4::splat(t_range.0), Vec4::splat(t_range.1));
        let mut found = 0;
        for group in 0..packet.rays().len().div_ceil(4) {
            let group_lanes = ((lanes >> (4 * group)) & 0xf) as u32;
            if group_lanes == 0 {
                continue;
            }
            let hits = shape.group_hits(packet, group, group_lanes, (t_min, t_max));
            found |= u64::from(hits.hit) << (4 * group);
            for j in lanes_of(u64::from(hits.undecided)) {
                let lane = 4 * group + j;
                let ray = &rays[usize::from(packet.rays()[lane])];
                if self.any_object(object, ray, t_range.0, t_range.1) {
                    found |= 1 << lane;
                }
            }
        }
        found
    }
}
