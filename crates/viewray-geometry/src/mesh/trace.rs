//! A mesh's ray queries: closest hit, closest triangle (its surface details deferred),
//! any hit, and the packet query that traces 64 rays together.

use std::ops::Range;

use glam::{Vec2, Vec3, Vec4};

use super::Mesh;
use super::packets::PacketRay;
use crate::Ray;
use crate::bvh::{BoxRay, prefetch};
use crate::hit::{Hit, RawHit, face_toward};
use crate::packet::{
    BoxPacket, PACKET_GROUPS, PACKET_SIZE, PacketQuery, PacketVisitor, for_each_packet, lanes_of,
};
use crate::shapes::WatertightRay;

/// The closest triangle of a mesh that a ray meets, before the surface details are
/// computed (see [`Mesh::closest_triangle`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// The ray parameter, in units of the ray's direction.
    pub t: f32,
    /// The face index.
    pub primitive: u32,
    /// The barycentric coordinates `(b1, b2)` of the face's second and third vertices:
    ///
    /// ```text
    /// point = (1 - b1 - b2) a + b1 b + b2 c
    /// ```
    pub barycentric: Vec2,
}

impl Mesh {
    /// The closest hit with `t` in `t_range` (`t_range.start <= t < t_range.end`).
    ///
    /// [`Hit::primitive`] is the face index; [`Hit::object`] is 0.
    pub fn closest_hit(&self, ray: &Ray, t_range: Range<f32>) -> Option<Hit> {
        let raw = self.intersect(ray, t_range.start, t_range.end)?;
        Some(self.surface_of(ray, &raw))
    }

    /// The closest triangle hit with `t` in `t_range`: its distance, face and
    /// barycentrics, without the surface details (no vertex data is read), for
    /// visibility queries and deferred shading; [`Mesh::surface`] completes it.
    pub fn closest_triangle(&self, ray: &Ray, t_range: Range<f32>) -> Option<TriangleHit> {
        self.intersect(ray, t_range.start, t_range.end)
            .map(|raw| TriangleHit {
                t: raw.t,
                primitive: raw.primitive,
                barycentric: raw.barycentric,
            })
    }

    /// The full [`Hit`] for a triangle hit of `ray` found by [`Mesh::closest_triangle`]:
    /// the normals, shading normal and uv interpolated at its barycentrics.
    pub fn surface(&self, ray: &Ray, hit: &TriangleHit) -> Hit {
        self.surface_of(
            ray,
            &RawHit {
                t: hit.t,
                object: 0,
                primitive: hit.primitive,
                barycentric: hit.barycentric,
            },
        )
    }

    /// Whether any triangle is hit with `t` in `t_range`; stops at the first one found.
    pub fn any_hit(&self, ray: &Ray, t_range: Range<f32>) -> bool {
        let packet_ray = PacketRay::new(&WatertightRay::new(ray));
        let (t_min, t_max) = (Vec4::splat(t_range.start), Vec4::splat(t_range.end));
        self.bvh.any_prepared(
            &BoxRay::new(ray),
            t_range.start,
            t_range.end,
            |start, count| self.any_in_leaf(&packet_ray, start, count, t_min, t_max),
        )
    }

    /// Which rays of `lanes` of a packet (in the mesh's space, filled from `rays`) hit a
    /// triangle with `t_min <= t < t_max`: the answers of [`Mesh::any_hit`] ray by ray.
    /// The packet walks the BVH together (see [`Bvh::any_packet`](crate::Bvh)), and each
    /// leaf is tested by the rays that reach it, one by one, with the single ray's test.
    pub(crate) fn any_packet(
        &self,
        packet: &BoxPacket<'_>,
        rays: &[Ray],
        lanes: u64,
        t_range: Range<f32>,
    ) -> u64 {
        // Each lane's triangle test is set up at its first leaf: most rays of a packet
        // reach few of a mesh's leaves, or none.
        let mut packet_rays = [None; PACKET_SIZE];
        let (t_min, t_max) = (Vec4::splat(t_range.start), Vec4::splat(t_range.end));
        self.bvh.any_packet(
            packet,
            lanes,
            t_range.start,
            t_range.end,
            |reaching, start, count| {
                let mut found = 0;
                for lane in lanes_of(reaching) {
                    let packet_ray: &PacketRay = packet_rays[lane].get_or_insert_with(|| {
                        let ray = &rays[usize::from(packet.rays()[lane])];
                        PacketRay::new(&WatertightRay::new(ray))
                    });
                    if self.any_in_leaf(packet_ray, start, count, t_min, t_max) {
                        found |= 1 << lane;
                    }
                }
                found
            },
        )
    }

    /// Whether a ray hits one of the triangle packets `start..start + count` with
    /// `t_min <= t < t_max` (all four lanes of each bound alike).
    #[inline(always)]
    fn any_in_leaf(
        &self,
        packet_ray: &PacketRay,
        start: u32,
        count: u32,
        t_min: Vec4,
        t_max: Vec4,
    ) -> bool {
        // A loop rather than `Iterator::any`, whose call was no longer inlined once two
        // traversals shared this test (2% more instructions for single shadow rays).
        for packet in &self.packets[start as usize..(start + count) as usize] {
            if let Some(edges) = packet_ray.edges(packet)
                && edges.hits(t_min, t_max).0.any()
            {
                return true;
            }
        }
        false
    }

    /// The closest hit as a raw hit: `t`, face and barycentrics.
    pub(crate) fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<RawHit> {
        self.intersect_prepared(ray, &BoxRay::new(ray), t_min, t_max)
    }

    /// [`Mesh::intersect`] with the ray's box numbers already worked out.
    #[inline]
    pub(crate) fn intersect_prepared(
        &self,
        ray: &Ray,
        box_ray: &BoxRay,
        t_min: f32,
        t_max: f32,
    ) -> Option<RawHit> {
        // The triangle test's setup waits for the first leaf: most rays of a typical
        // image miss a given mesh's boxes altogether.
        let mut packet_ray = None;
        let t_min4 = Vec4::splat(t_min);
        let mut best = None;
        self.bvh.closest_prepared(
            box_ray,
            t_min,
            t_max,
            |start, count, t_max| {
                let packet_ray =
                    packet_ray.get_or_insert_with(|| PacketRay::new(&WatertightRay::new(ray)));
                match self.intersect_leaf(packet_ray, start, count, t_min4, t_max) {
                    Some(hit) => {
                        best = Some(hit);
                        hit.t
                    }
                    None => t_max,
                }
            },
            |start, count| self.prefetch_leaf(start, count),
        );
        best
    }

    /// Intersects the triangle packets `start..start + count` with a ray whose closest
    /// hit so far is at `t_max`: the closest hit below it, as a hit on object 0.
    #[inline(always)]
    fn intersect_leaf(
        &self,
        packet_ray: &PacketRay,
        start: u32,
        count: u32,
        t_min4: Vec4,
        mut t_max: f32,
    ) -> Option<RawHit> {
        let mut best = None;
        for packet in &self.packets[start as usize..(start + count) as usize] {
            let Some(edges) = packet_ray.edges(packet) else {
                continue;
            };
            let (valid, t, [_, v, w], det) = edges.hits(t_min4, Vec4::splat(t_max));
            if valid.any() {
                let t_valid = Vec4::select(valid, t, Vec4::INFINITY);
                t_max = t_valid.min_element();
                let lane = t_valid.cmpeq(Vec4::splat(t_max)).bitmask().trailing_zeros() as usize;
                let (v, w, det) = (v.to_array()[lane], w.to_array()[lane], det.to_array()[lane]);
                best = Some(RawHit {
                    t: t_max,
                    object: 0,
                    primitive: packet.faces[lane],
                    barycentric: Vec2::new(v / det, w / det),
                });
            }
        }
        best
    }

    /// Starts loading the first triangle packets of a leaf.
    #[inline(always)]
    fn prefetch_leaf(&self, start: u32, count: u32) {
        // Packets are 160 bytes, 16-byte aligned: the first of a leaf touches at most 4
        // cache lines, the first two at most 6.
        if count == 1 {
            prefetch(&self.packets, start as usize, [0, 64, 128, 159]);
        } else {
            prefetch(&self.packets, start as usize, [0, 64, 128, 192, 256, 319]);
        }
    }

    /// The closest hits of a query's rays (in the mesh's space), as hits on object
    /// `object`: lowers each lane's `t_max` and `best`.
    pub(crate) fn intersect_packet(&self, query: PacketQuery<'_>, object: u32) {
        struct Visitor<'a> {
            mesh: &'a Mesh,
            rays: &'a [Ray],
            rays_of_lanes: &'a [u8],
            packet_rays: [Option<PacketRay>; PACKET_SIZE],
            t_min4: Vec4,
            object: u32,
            best: &'a mut [Option<RawHit>; PACKET_SIZE],
        }
        impl PacketVisitor for Visitor<'_> {
            #[inline(always)]
            fn leaf(&mut self, lane: usize, start: u32, count: u32, t_max: f32) -> f32 {
                let ray = &self.rays[usize::from(self.rays_of_lanes[lane])];
                let packet_ray = self.packet_rays[lane]
                    .get_or_insert_with(|| PacketRay::new(&WatertightRay::new(ray)));
                match self
                    .mesh
                    .intersect_leaf(packet_ray, start, count, self.t_min4, t_max)
                {
                    Some(hit) => {
                        self.best[lane] = Some(RawHit {
                            object: self.object,
                            ..hit
                        });
                        hit.t
                    }
                    None => t_max,
                }
            }
        }
        let PacketQuery {
            packet,
            rays,
            lanes,
            t_min,
            t_max,
            best,
        } = query;
        let mut visitor = Visitor {
            mesh: self,
            rays,
            rays_of_lanes: packet.rays(),
            packet_rays: [None; PACKET_SIZE],
            t_min4: Vec4::splat(t_min),
            object,
            best,
        };
        self.bvh
            .closest_packet(packet, lanes, t_min, t_max, &mut visitor, |start, count| {
                self.prefetch_leaf(start, count)
            });
    }

    /// The closest triangle hit of each ray of `rays` with `t` in `t_range`, into
    /// `hits`: the same hits as [`Mesh::closest_triangle`] ray by ray, found faster
    /// when the rays are coherent (neighbouring pixels' viewing rays, in blocks of up to
    /// 64 such as 8 x 8 pixels), because each block is traced as a packet through the
    /// upper levels of the BVH. Incoherent rays (origins and directions all over) gain
    /// too on meshes too large for the caches (from about 150k triangles): their walks
    /// down the BVH take turns, so that their waits for memory overlap.
    ///
    /// # Panics
    ///
    /// When `rays` and `hits` differ in length.
    pub fn closest_triangles(
        &self,
        rays: &[Ray],
        t_range: Range<f32>,
        hits: &mut [Option<TriangleHit>],
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit per ray");
        for (rays, hits) in rays.chunks(PACKET_SIZE).zip(hits.chunks_mut(PACKET_SIZE)) {
            hits.fill(None);
            for_each_packet(rays, |packet| {
                let mut t_max = [Vec4::splat(t_range.end); PACKET_GROUPS];
                let mut best = [None; PACKET_SIZE];
                let query = PacketQuery {
                    packet,
                    rays,
                    lanes: packet.all_lanes(),
                    t_min: t_range.start,
                    t_max: &mut t_max,
                    best: &mut best,
                };
                self.intersect_packet(query, 0);
                for (&ray, raw) in packet.rays().iter().zip(&best) {
                    hits[usize::from(ray)] = raw.map(|raw| TriangleHit {
                        t: raw.t,
                        primitive: raw.primitive,
                        barycentric: raw.barycentric,
                    });
                }
            });
        }
    }

    /// The surface details of a raw hit on face `raw.primitive`.
    pub(crate) fn surface_of(&self, ray: &Ray, raw: &RawHit) -> Hit {
        let data = &self.data;
        let [ia, ib, ic] = data.triangles[raw.primitive as usize].map(|i| i as usize);
        let [a, b, c] = [ia, ib, ic].map(|i| data.positions[i]);
        let Vec2 { x: b1, y: b2 } = raw.barycentric;
        let b0 = 1.0 - b1 - b2;
        let geometric = (b - a).cross(c - a).normalize_or(Vec3::Z);
        let shading = data
            .normals
            .as_ref()
            .and_then(|n| (b0 * n[ia] + b1 * n[ib] + b2 * n[ic]).try_normalize())
            .unwrap_or(geometric);
        let uv = data.uvs.as_ref().map_or(raw.barycentric, |uv| {
            b0 * uv[ia] + b1 * uv[ib] + b2 * uv[ic]
        });
        let (normal, shading_normal, front_face) = face_toward(ray.direction, geometric, shading);
        Hit {
            t: raw.t,
            point: ray.at(raw.t),
            normal,
            shading_normal,
            front_face,
            uv,
            primitive: raw.primitive,
            object: 0,
        }
    }

    /// The closest hit by testing every triangle, without the BVH: the reference the
    /// tests hold the BVH to.
    #[cfg(test)]
    pub(crate) fn brute_force(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<RawHit> {
        let w = WatertightRay::new(ray);
        let mut best: Option<RawHit> = None;
        for (face, tri) in self.data.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|i| self.data.positions[i as usize]);
            let limit = best.map_or(t_max, |b| b.t);
            if (b - a).cross(c - a) == Vec3::ZERO {
                continue;
            }
            if let Some(hit) = w.intersect(a, b, c, t_min, limit) {
                best = Some(RawHit {
                    primitive: face as u32,
                    ..hit
                });
            }
        }
        best
    }
}
