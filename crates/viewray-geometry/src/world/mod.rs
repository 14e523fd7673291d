//! The scene-level structure: a list of objects with a top-level BVH.

use std::ops::Range;

use glam::{Vec2, Vec4};

use crate::bvh::{BoxRay, BuildParams, Bvh};
use crate::hit::{Hit, RawHit};
use crate::packet::{
    BoxPacket, Lanes, PACKET_GROUPS, PACKET_SIZE, PacketQuery, PacketVisitor, at, for_each_packet,
    for_each_packet_unless_scattered, lane as lane_value, lane_mask, lanes_of, set_lane,
};
use crate::shapes::{PlaneFrame, WatertightRay};
use crate::{Aabb, GeometryError, Instance, Plane, Ray, Sphere, Triangle};

mod flat;
mod loose;
mod region;

use self::flat::{BoxLanes, Flat, SlabLanes};
use self::loose::Loose;
pub use self::region::Reach;

/// How much larger than the box around a world's bounded objects the box of
/// [`World::surely_clear`] is, per unit of the largest coordinate (plus one); a small
/// world's objects are each tested behind their own box enlarged so (see `flat.rs`).
const CLEAR_MARGIN: f32 = 1e-3;

/// `bounds` enlarged by [`CLEAR_MARGIN`] per unit of its largest coordinate (plus one):
/// a margin far above the rounding of any test of a shape or box inside.
fn enlarged(bounds: Aabb) -> BoxLanes {
    let size = bounds.min.abs().max(bounds.max.abs()).max_element();
    let margin = CLEAR_MARGIN * (1.0 + size);
    BoxLanes::new(
        (bounds.min - margin).to_array(),
        (bounds.max + margin).to_array(),
    )
}

/// One object of a [`World`]: an analytic shape or a placed mesh.
#[derive(Clone, Debug)]
pub enum Object {
    /// A sphere.
    Sphere(Sphere),
    /// An infinite plane (unbounded: kept beside the BVH).
    Plane(Plane),
    /// A single triangle.
    Triangle(Triangle),
    /// A solid axis-aligned box; its uv follow [`Aabb`]'s face coordinates.
    Box(Aabb),
    /// A shared mesh placed by a transform.
    Instance(Instance),
}

impl Object {
    /// The object's bounding box; `None` for a plane, which has none.
    pub fn bounds(&self) -> Option<Aabb> {
        match self {
            Self::Sphere(s) => Some(s.bounds()),
            Self::Plane(_) => None,
            Self::Triangle(t) => Some(t.bounds()),
            Self::Box(b) => Some(*b),
            Self::Instance(i) => Some(i.bounds()),
        }
    }

    /// Why the object describes no surface, if it does not.
    fn invalid_reason(&self) -> Option<String> {
        match self {
            Self::Sphere(s)
                if !(s.center.is_finite() && s.radius.is_finite() && s.radius > 0.0) =>
            {
                Some(format!(
                    "sphere with center {} and radius {} needs a finite center and a positive radius",
                    s.center, s.radius
                ))
            }
            Self::Plane(p)
                if !(p.point.is_finite()
                    && p.normal.is_finite()
                    && p.normal.length_squared() > 0.0) =>
            {
                Some(format!(
                    "plane through {} with normal {} needs a finite point and a nonzero normal",
                    p.point, p.normal
                ))
            }
            Self::Triangle(t) if !(t.a.is_finite() && t.b.is_finite() && t.c.is_finite()) => Some(
                format!("triangle {}, {}, {} has a non-finite vertex", t.a, t.b, t.c),
            ),
            Self::Box(b)
                if !(b.min.is_finite() && b.max.is_finite() && b.min.cmple(b.max).all()) =>
            {
                Some(format!(
                    "box from {} to {} needs finite corners with min <= max",
                    b.min, b.max
                ))
            }
            _ => None,
        }
    }
}

/// Everything a ray can meet: a list of [`Object`]s, a top-level BVH over the bounded
/// ones (spheres, triangles, boxes, instances) and the unbounded planes beside it.
///
/// [`Hit::object`] is the object's index in the list the world was built from.
#[derive(Clone, Debug)]
pub struct World {
    objects: Vec<Object>,
    bvh: Bvh,
    /// The only bounded object, when there is exactly one: rays then skip the
    /// top-level BVH, whose one box only repeats the object's own first test.
    single: Option<u32>,
    /// The object index at each leaf position of the BVH.
    leaf_objects: Vec<u32>,
    /// How batches of rays meet the bounded objects of a world of one of them or of one
    /// leaf of them, four rays at a time (see `flat.rs`); `None` where they walk the
    /// BVH as packets.
    flat: Option<Flat>,
    /// The planes' object indices, in increasing order, and each one's frame (worked
    /// out once: the normal's length and the uv axes cost a hit more than the rest of
    /// its surface details).
    planes: Vec<u32>,
    plane_frames: Vec<PlaneFrame>,
    triangle_count: usize,
    /// What [`World::surely_clear`] tests rays against.
    clear_box: ClearBox,
}

/// The box of [`World::surely_clear`].
#[derive(Clone, Copy, Debug)]
enum ClearBox {
    /// No bounded objects: every ray misses them.
    Nothing,
    /// A single bounded object, which rays meet without a box test: no ray is known
    /// to miss it.
    Unknown,
    /// The box around every bounded object, enlarged by [`CLEAR_MARGIN`].
    Around(BoxLanes),
}

impl ClearBox {
    fn new(bvh: &Bvh, single: Option<u32>) -> Self {
        if single.is_some() {
            return ClearBox::Unknown;
        }
        if bvh.nodes().is_empty() {
            return ClearBox::Nothing;
        }
        // A margin far above the rounding of any box test inside, so that no test
        // the traversal makes is looser than this one.
        ClearBox::Around(enlarged(bvh.bounds()))
    }
}

impl World {
    /// Checks the objects and builds the top-level BVH.
    ///
    /// # Errors
    ///
    /// [`GeometryError::InvalidObject`] naming the first object that describes no
    /// surface: a sphere without a positive radius, a plane with a zero normal, a box
    /// with `min > max`, or a shape with non-finite numbers.
    pub fn new(objects: Vec<Object>) -> Result<Self, GeometryError> {
        if let Some((object, reason)) = objects
            .iter()
            .enumerate()
            .find_map(|(i, o)| o.invalid_reason().map(|r| (i, r)))
        {
            return Err(GeometryError::InvalidObject { object, reason });
        }
        let mut bounded = Vec::new();
        let mut bounds = Vec::new();
        let mut planes = Vec::new();
        let mut plane_frames = Vec::new();
        for (i, object) in objects.iter().enumerate() {
            if let Object::Plane(plane) = object {
                planes.push(i as u32);
                plane_frames.push(plane.frame());
            } else if let Some(b) = object.bounds() {
                bounded.push(i as u32);
                bounds.push(b);
            }
        }
        let bvh = Bvh::build(&bounds, BuildParams::default());
        let leaf_objects: Vec<u32> = bvh
            .item_order()
            .iter()
            .map(|&i| bounded[i as usize])
            .collect();
        let flat = Flat::of(&objects, &bvh, &leaf_objects);
        let triangle_count = objects
            .iter()
            .map(|o| match o {
                Object::Triangle(_) => 1,
                Object::Instance(i) => i.mesh().triangle_count(),
                _ => 0,
            })
            .sum();
        let single = (bounded.len() == 1).then(|| bounded[0]);
        let clear_box = ClearBox::new(&bvh, single);
        Ok(Self {
            clear_box,
            objects,
            bvh,
            single,
            leaf_objects,
            flat,
            planes,
            plane_frames,
            triangle_count,
        })
    }

    /// The objects, in the order they were given.
    pub fn objects(&self) -> &[Object] {
        &self.objects
    }

    /// The number of triangles: single triangles plus each instance's mesh triangles
    /// (an instanced mesh counts once per instance).
    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// The box around all bounded objects; planes, being infinite, are left out
    /// ([`Aabb::EMPTY`] when there is nothing else).
    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// The closest hit with `t` in `t_range` (`t_range.start <= t < t_range.end`).
    pub fn closest_hit(&self, ray: &Ray, t_range: Range<f32>) -> Option<Hit> {
        let raw = self.intersect(ray, t_range.start, t_range.end)?;
        Some(self.surface_of(ray, &raw))
    }

    /// The closest object hit with `t` in `t_range`: its distance, object and face,
    /// without the surface details, for visibility queries and deferred shading;
    /// [`World::surface`] completes it.
    pub fn closest_object(&self, ray: &Ray, t_range: Range<f32>) -> Option<ObjectHit> {
        self.intersect(ray, t_range.start, t_range.end)
            .map(|raw| self.object_hit(raw))
    }

    /// The full [`Hit`] for a hit of `ray` found by [`World::closest_object`] or
    /// [`World::closest_objects`]: normals, shading normal and uv.
    pub fn surface(&self, ray: &Ray, hit: &ObjectHit) -> Hit {
        self.surface_of(ray, &hit.raw)
    }

    /// What shading reads of [`World::surface`], written into `out`: every field but
    /// `uv`, which is left zero (a sphere's takes an arc tangent and an arc sine, a
    /// few percent of a Lit render, and shading never reads it). For filling a buffer
    /// of hits (made with [`Hit::default`]): a returned [`Hit`] would be copied into
    /// place straight after it was written, and the copy would wait for those writes
    /// to finish (about a twentieth of a Lit render's time).
    #[inline(never)]
    pub fn shading_surface_into(&self, ray: &Ray, hit: &ObjectHit, out: &mut Hit) {
        // The ground plane is most hits' surface: its frame is found without a search.
        if let Object::Plane(plane) = &self.objects[hit.raw.object as usize]
            && let Some(slot) = self.plane_slot(hit.raw.object)
        {
            *out = plane.surface_in(ray, hit.raw.t, &self.plane_frames[slot], false);
            out.object = hit.raw.object;
            return;
        }
        self.write_surface_cold(ray, &hit.raw, out);
    }

    /// [`World::write_surface`] without the uv, kept out of line so that the planes' path
    /// above needs no room for the other shapes' numbers.
    #[inline(never)]
    fn write_surface_cold(&self, ray: &Ray, raw: &RawHit, out: &mut Hit) {
        self.write_surface(ray, raw, false, out);
    }

    /// The slot of plane `object` among the planes, if it is one: a world has few
    /// planes, looked through in order, or many, searched.
    #[inline(always)]
    fn plane_slot(&self, object: u32) -> Option<usize> {
        if self.planes.len() <= 8 {
            self.planes.iter().position(|&plane| plane == object)
        } else {
            self.planes.binary_search(&object).ok()
        }
    }

    /// The closest object hit of each ray of `rays` with `t` in `t_range`, into `hits`:
    /// the same hits as [`World::closest_object`] ray by ray, found faster when the rays
    /// are coherent (neighbouring pixels' viewing rays, in blocks of up to 64 such as
    /// 8 x 8 pixels), because each block is traced as a packet through the upper levels
    /// of the BVHs. (Of two surfaces hit at exactly the same `t`, either may be
    /// reported.)
    ///
    /// # Panics
    ///
    /// When `rays` and `hits` differ in length.
    pub fn closest_objects(
        &self,
        rays: &[Ray],
        t_range: Range<f32>,
        hits: &mut [Option<ObjectHit>],
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit per ray");
        match &self.flat {
            Some(flat) => self.closest_flat(flat, rays, t_range, hits),
            None => self.closest_packets(rays, t_range, hits),
        }
    }

    /// [`World::closest_objects`] in packets, through the BVH.
    fn closest_packets(&self, rays: &[Ray], t_range: Range<f32>, hits: &mut [Option<ObjectHit>]) {
        let t_min = t_range.start;
        for (rays, hits) in rays.chunks(PACKET_SIZE).zip(hits.chunks_mut(PACKET_SIZE)) {
            hits.fill(None);
            for_each_packet(rays, |packet| {
                let mut t_max = [Vec4::splat(t_range.end); PACKET_GROUPS];
                let mut best = [None; PACKET_SIZE];
                let lanes = packet.all_lanes();
                // Planes first, as `intersect` does, four rays at a time.
                if !self.planes.is_empty() {
                    self.closest_planes(packet, t_min, &mut t_max, &mut best);
                }
                match self.single {
                    Some(object) => self.intersect_object_packet(
                        object,
                        PacketQuery {
                            packet,
                            rays,
                            lanes,
                            t_min,
                            t_max: &mut t_max,
                            best: &mut best,
                        },
                    ),
                    None => {
                        let mut visitor = WorldVisitor {
                            world: self,
                            packet,
                            rays,
                            t_min,
                            best: &mut best,
                        };
                        self.bvh.closest_packet(
                            packet,
                            lanes,
                            t_min,
                            &mut t_max,
                            &mut visitor,
                            |_, _| {},
                        );
                    }
                }
                // By reference: moving `best` into the loop copied it whole, reading
                // back the hits just written field by field (a store-forwarding stall).
                for (&i, raw) in packet.rays().iter().zip(&best) {
                    hits[usize::from(i)] = raw.as_ref().map(|raw| self.object_hit(*raw));
                }
            });
        }
    }

    /// The closest hit as a raw hit.
    fn intersect(&self, ray: &Ray, t_min: f32, mut t_max: f32) -> Option<RawHit> {
        if !is_traceable(ray) {
            return None;
        }
        let mut best = self.intersect_planes(ray, t_min, &mut t_max);
        if let Some(object) = self.single {
            return self.intersect_object(object, ray, t_min, t_max).or(best);
        }
        self.bvh.closest_prepared(
            &BoxRay::new(ray),
            t_min,
            t_max,
            |start, count, mut t_max| {
                for &object in &self.leaf_objects[start as usize..(start + count) as usize] {
                    if let Some(hit) = self.intersect_object(object, ray, t_min, t_max) {
                        t_max = hit.t;
                        best = Some(hit);
                    }
                }
                t_max
            },
            |_, _| {},
        );
        best
    }

    /// The world's planes, with their object indices.
    #[inline]
    fn plane_objects(&self) -> impl Iterator<Item = (u32, &Plane)> {
        self.planes
            .iter()
            .filter_map(|&object| match &self.objects[object as usize] {
                Object::Plane(plane) => Some((object, plane)),
                _ => None,
            })
    }

    /// The closest plane hit with `t_min <= t < t_max`, lowering `t_max` to it.
    #[inline]
    fn intersect_planes(&self, ray: &Ray, t_min: f32, t_max: &mut f32) -> Option<RawHit> {
        let mut best = None;
        for (object, plane) in self.plane_objects() {
            if let Some(t) = plane.intersect_t(ray, t_min, *t_max) {
                *t_max = t;
                best = Some(RawHit {
                    t,
                    object,
                    primitive: 0,
                    barycentric: Vec2::ZERO,
                });
            }
        }
        best
    }

    /// Whether anything is hit with `t` in `t_range`: the shadow-ray query, which stops
    /// at the first hit found rather than the closest.
    pub fn any_hit(&self, ray: &Ray, t_range: Range<f32>) -> bool {
        let (t_min, t_max) = (t_range.start, t_range.end);
        if !is_traceable(ray) {
            return false;
        }
        if self.any_plane(ray, t_min, t_max) {
            return true;
        }
        let any_object = |object: u32| self.any_object(object, ray, t_min, t_max);
        if let Some(object) = self.single {
            return any_object(object);
        }
        self.bvh
            .any_prepared(&BoxRay::new(ray), t_min, t_max, |start, count| {
                self.leaf_objects[start as usize..(start + count) as usize]
                    .iter()
                    .any(|&object| any_object(object))
            })
    }

    /// For each ray of `rays`, whether anything is hit with `t` in `t_range`, into
    /// `hits`: the same answers as [`World::any_hit`] ray by ray, found faster when the
    /// rays are coherent (the shadow rays of neighbouring pixels toward one light, in
    /// batches of up to 64), because each batch walks the top-level BVH as a packet and
    /// the rays that reach a mesh walk its BVH as a packet too. A batch whose directions
    /// are scattered over most octants (random rays) is asked ray by ray.
    ///
    /// # Panics
    ///
    /// When `rays` and `hits` differ in length.
    pub fn any_hits(&self, rays: &[Ray], t_range: Range<f32>, hits: &mut [bool]) {
        assert_eq!(rays.len(), hits.len(), "one answer per ray");
        match &self.flat {
            Some(flat) => self.any_flat(flat, rays, t_range, hits),
            None => self.any_packets(rays, t_range, hits),
        }
    }

    /// [`World::any_hits`] in packets, through the BVH.
    fn any_packets(&self, rays: &[Ray], t_range: Range<f32>, hits: &mut [bool]) {
        let (t_min, t_max) = (t_range.start, t_range.end);
        for (rays, hits) in rays.chunks(PACKET_SIZE).zip(hits.chunks_mut(PACKET_SIZE)) {
            hits.fill(false);
            let packets = for_each_packet_unless_scattered(rays, |packet| {
                // Planes first, as `any_hit` does, four rays at a time.
                let mut searching = packet.all_lanes();
                if !self.planes.is_empty() {
                    searching &= !self.any_planes(packet, t_min, t_max);
                }
                let any_object = |object: u32, lanes: u64| {
                    // A mesh takes the packet's rays together, as for closest hits; a
                    // lone ray (an incoherent packet's, for one) goes on alone.
                    // Loose spheres and triangles take them four at a time.
                    if lanes & lanes.wrapping_sub(1) != 0 {
                        let shape = &self.objects[object as usize];
                        if let Object::Instance(instance) = shape {
                            return instance.any_packet(packet, rays, lanes, t_min..t_max);
                        }
                        if let Some(shape) = Loose::of(shape) {
                            let (packet, t_range) = ((packet, rays), (t_min, t_max));
                            return self.any_loose((shape, object), packet, lanes, t_range);
                        }
                    }
                    lanes_of(lanes).fold(0, |found, lane| {
                        let ray = &rays[usize::from(packet.rays()[lane])];
                        if self.any_object(object, ray, t_min, t_max) {
                            found | 1 << lane
                        } else {
                            found
                        }
                    })
                };
                let found = match self.single {
                    Some(object) => any_object(object, searching),
                    None => self.bvh.any_packet(
                        packet,
                        searching,
                        t_min,
                        t_max,
                        |lanes, start, count| {
                            let mut found = 0;
                            for &object in
                                &self.leaf_objects[start as usize..(start + count) as usize]
                            {
                                found |= any_object(object, lanes & !found);
                                if found == lanes {
                                    break;
                                }
                            }
                            found
                        },
                    ),
                };
                let blocked = !searching | found;
                for (lane, &i) in packet.rays().iter().enumerate() {
                    hits[usize::from(i)] = blocked & (1 << lane) != 0;
                }
            });
            if !packets {
                for (ray, hit) in rays.iter().zip(hits.iter_mut()) {
                    *hit = self.any_hit(ray, t_range.clone());
                }
            }
        }
    }

    /// [`World::intersect_planes`] for each ray of a packet, four at a time: each
    /// lane's closest plane hit into `best`, and its `t` into `t_max`. (The spare lanes
    /// of the last group repeat a ray of the packet; what they record is never read.)
    #[inline]
    fn closest_planes(
        &self,
        packet: &BoxPacket<'_>,
        t_min: f32,
        t_max: &mut Lanes,
        best: &mut [Option<RawHit>; PACKET_SIZE],
    ) {
        let t_min = Vec4::splat(t_min);
        for (group, t_max) in t_max
            .iter_mut()
            .enumerate()
            .take(packet.rays().len().div_ceil(4))
        {
            let (origin, direction) = packet.group_rays(group);
            for (object, plane) in self.plane_objects() {
                let (hit, t) = plane.intersect_t_lanes(origin, direction, t_min, *t_max);
                if hit != 0 {
                    *t_max = Vec4::select(lane_mask(hit), t, *t_max);
                    for lane in lanes_of(u64::from(hit)) {
                        best[4 * group + lane] = Some(RawHit {
                            t: at(&t, lane),
                            object,
                            primitive: 0,
                            barycentric: Vec2::ZERO,
                        });
                    }
                }
            }
        }
    }

    /// [`World::any_plane`] for each ray of a packet, four at a time: the mask of the
    /// lanes that hit a plane.
    #[inline]
    fn any_planes(&self, packet: &BoxPacket<'_>, t_min: f32, t_max: f32) -> u64 {
        let (t_min, t_max) = (Vec4::splat(t_min), Vec4::splat(t_max));
        let mut found = 0;
        for group in 0..packet.rays().len().div_ceil(4) {
            let (origin, direction) = packet.group_rays(group);
            for (_, plane) in self.plane_objects() {
                let (hit, _) = plane.intersect_t_lanes(origin, direction, t_min, t_max);
                found |= u64::from(hit) << (4 * group);
            }
        }
        found & packet.all_lanes()
    }

    /// Of four rays (origins and directions on each axis, one ray per lane), the lanes
    /// that surely meet nothing with `t` in `t_range`: each passes outside a box a little
    /// larger than the one around every bounded object and meets no plane.
    /// [`World::any_hits`] would answer `false` for each of them, since it tests them
    /// against the same planes and only against boxes inside that one; ask it about
    /// the others. A renderer's shadow rays far from the objects then cost one box test
    /// instead of being made into packets and traced.
    ///
    /// A world with a single bounded object, which rays meet without a box test first,
    /// clears no lane by the box.
    #[inline]
    pub fn surely_clear(
        &self,
        origin: [Vec4; 3],
        direction: [Vec4; 3],
        t_range: Range<f32>,
    ) -> u32 {
        let (t_min, t_max) = (Vec4::splat(t_range.start), Vec4::splat(t_range.end));
        let mut clear = match &self.clear_box {
            ClearBox::Nothing => 0b1111,
            ClearBox::Unknown => return 0,
            ClearBox::Around(around) => {
                !around.rays_hitting(&SlabLanes::new(origin, direction), t_min, t_max) & 0b1111
            }
        };
        for (_, plane) in self.plane_objects() {
            if clear == 0 {
                break;
            }
            clear &= !plane.intersect_t_lanes(origin, direction, t_min, t_max).0;
        }
        clear
    }

    /// Whether a plane is hit with `t_min <= t < t_max`.
    #[inline]
    fn any_plane(&self, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        self.plane_objects()
            .any(|(_, plane)| plane.intersect_t(ray, t_min, t_max).is_some())
    }

    /// Whether the bounded object `object` is hit with `t_min <= t < t_max`.
    #[inline]
    fn any_object(&self, object: u32, ray: &Ray, t_min: f32, t_max: f32) -> bool {
        match &self.objects[object as usize] {
            Object::Instance(instance) => instance.any_hit(ray, t_min..t_max),
            _ => self.intersect_object(object, ray, t_min, t_max).is_some(),
        }
    }

    fn intersect_object(&self, object: u32, ray: &Ray, t_min: f32, t_max: f32) -> Option<RawHit> {
        let raw = |t, primitive, barycentric| RawHit {
            t,
            object,
            primitive,
            barycentric,
        };
        match &self.objects[object as usize] {
            Object::Sphere(s) => s
                .intersect_t(ray, t_min, t_max)
                .map(|t| raw(t, 0, Vec2::ZERO)),
            Object::Plane(p) => p
                .intersect_t(ray, t_min, t_max)
                .map(|t| raw(t, 0, Vec2::ZERO)),
            Object::Triangle(tri) => WatertightRay::new(ray)
                .intersect(tri.a, tri.b, tri.c, t_min, t_max)
                .map(|h| raw(h.t, 0, h.barycentric)),
            Object::Box(b) => b
                .intersect_solid(ray, t_min, t_max)
                .map(|c| raw(c.t, c.axis * 2 + u32::from(c.max_face), Vec2::ZERO)),
            Object::Instance(i) => i
                .intersect(ray, t_min, t_max)
                .map(|h| RawHit { object, ..h }),
        }
    }

    /// The closest hits of a query's rays with object `object`: an instance traces them
    /// as packets, other shapes ray by ray.
    fn intersect_object_packet(&self, object: u32, query: PacketQuery<'_>) {
        let shape = &self.objects[object as usize];
        if let Object::Instance(instance) = shape {
            return instance.intersect_packet(query, object);
        }
        if let Some(shape) = Loose::of(shape) {
            return self.closest_loose(shape, object, query);
        }
        for lane in lanes_of(query.lanes) {
            let t_max = lane_value(query.t_max, lane);
            if let Some(hit) = self.intersect_object(object, query.ray(lane), query.t_min, t_max) {
                set_lane(query.t_max, lane, hit.t);
                query.best[lane] = Some(hit);
            }
        }
    }

    /// The public face of a raw hit.
    fn object_hit(&self, raw: RawHit) -> ObjectHit {
        let primitive = match self.objects[raw.object as usize] {
            Object::Instance(_) => raw.primitive,
            _ => 0,
        };
        ObjectHit {
            t: raw.t,
            object: raw.object,
            primitive,
            raw,
        }
    }

    fn surface_of(&self, ray: &Ray, raw: &RawHit) -> Hit {
        let mut hit = Hit::default();
        self.write_surface(ray, raw, true, &mut hit);
        hit
    }

    /// The surface details of `raw` into `out`, each shape's written straight into it;
    /// the uv only if `with_uv`, else zero.
    #[inline(always)]
    fn write_surface(&self, ray: &Ray, raw: &RawHit, with_uv: bool, out: &mut Hit) {
        match &self.objects[raw.object as usize] {
            Object::Sphere(s) => *out = s.surface_with(ray, raw.t, with_uv),
            Object::Plane(p) => match self.plane_slot(raw.object) {
                Some(slot) => *out = p.surface_in(ray, raw.t, &self.plane_frames[slot], with_uv),
                None => *out = p.surface_in(ray, raw.t, &p.frame(), with_uv),
            },
            Object::Triangle(tri) => *out = tri.surface(ray, raw),
            Object::Box(b) => {
                *out = b.surface(ray, raw.t, raw.primitive / 2, raw.primitive % 2 == 1);
            }
            Object::Instance(i) => *out = i.surface(ray, raw),
        }
        if !with_uv {
            // Spheres and planes skipped it; the others' is a by-product.
            out.uv = Vec2::ZERO;
        }
        out.object = raw.object;
    }
}

/// Whether a ray can hit anything: a finite origin and direction, and a nonzero
/// direction (the BVH's own test; an infinite direction would otherwise meet a plane
/// at `t = 0`).
fn is_traceable(ray: &Ray) -> bool {
    ray.origin.is_finite() && ray.direction.is_finite() && ray.direction != glam::Vec3::ZERO
}

/// The closest object a ray meets, before the surface details are computed (see
/// [`World::closest_object`]); [`World::surface`] turns it into a [`Hit`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ObjectHit {
    /// The ray parameter, in units of the ray's direction.
    pub t: f32,
    /// The object's index in the list the world was built from, as [`Hit::object`].
    pub object: u32,
    /// The face index for meshes, else 0, as [`Hit::primitive`].
    pub primitive: u32,
    /// What the surface details are computed from.
    raw: RawHit,
}

/// A world's leaves for packet traversal: each object is intersected with the packet's
/// rays that reach the leaf.
struct WorldVisitor<'a> {
    world: &'a World,
    packet: &'a BoxPacket<'a>,
    rays: &'a [Ray],
    t_min: f32,
    best: &'a mut [Option<RawHit>; PACKET_SIZE],
}

impl PacketVisitor for WorldVisitor<'_> {
    fn leaf(&mut self, lane: usize, start: u32, count: u32, mut t_max: f32) -> f32 {
        let ray = &self.rays[usize::from(self.packet.rays()[lane])];
        for &object in &self.world.leaf_objects[start as usize..(start + count) as usize] {
            if let Some(hit) = self.world.intersect_object(object, ray, self.t_min, t_max) {
                t_max = hit.t;
                self.best[lane] = Some(hit);
            }
        }
        t_max
    }

    fn leaf_lanes(&mut self, lanes: u64, start: u32, count: u32, t_max: &mut Lanes) {
        for &object in &self.world.leaf_objects[start as usize..(start + count) as usize] {
            let query = PacketQuery {
                packet: self.packet,
                rays: self.rays,
                lanes,
                t_min: self.t_min,
                t_max: &mut *t_max,
                best: &mut *self.best,
            };
            self.world.intersect_object_packet(object, query);
        }
    }
}
