//! The scene-level structure: a list of objects with a top-level BVH.

use std::ops::Range;

use glam::Vec2;

use crate::bvh::{BoxRay, BuildParams, Bvh};
use crate::hit::{Hit, RawHit};
use crate::shapes::WatertightRay;
use crate::{Aabb, GeometryError, Instance, Plane, Ray, Sphere, Triangle};

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
    /// The object index at each leaf position of the BVH.
    leaf_objects: Vec<u32>,
    planes: Vec<u32>,
    triangle_count: usize,
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
        for (i, object) in objects.iter().enumerate() {
            match object.bounds() {
                Some(b) => {
                    bounded.push(i as u32);
                    bounds.push(b);
                }
                None => planes.push(i as u32),
            }
        }
        let bvh = Bvh::build(&bounds, BuildParams::default());
        let leaf_objects = bvh
            .item_order()
            .iter()
            .map(|&i| bounded[i as usize])
            .collect();
        let triangle_count = objects
            .iter()
            .map(|o| match o {
                Object::Triangle(_) => 1,
                Object::Instance(i) => i.mesh().triangle_count(),
                _ => 0,
            })
            .sum();
        Ok(Self {
            objects,
            bvh,
            leaf_objects,
            planes,
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
        let t_min = t_range.start;
        let mut best: Option<RawHit> = None;
        let mut t_max = t_range.end;
        for &object in &self.planes {
            if let Object::Plane(plane) = &self.objects[object as usize]
                && let Some(t) = plane.intersect_t(ray, t_min, t_max)
            {
                t_max = t;
                best = Some(RawHit {
                    t,
                    object,
                    primitive: 0,
                    barycentric: Vec2::ZERO,
                });
            }
        }
        let watertight = WatertightRay::new(ray);
        self.bvh.closest_prepared(
            &BoxRay::new(ray),
            t_min,
            t_max,
            |start, count, mut t_max| {
                for &object in &self.leaf_objects[start as usize..(start + count) as usize] {
                    if let Some(hit) = self.intersect_object(object, ray, &watertight, t_min, t_max)
                    {
                        t_max = hit.t;
                        best = Some(hit);
                    }
                }
                t_max
            },
            |_, _| {},
        );
        best.map(|raw| self.surface(ray, &raw))
    }

    /// Whether anything is hit with `t` in `t_range`: the shadow-ray query, which stops
    /// at the first hit found rather than the closest.
    pub fn any_hit(&self, ray: &Ray, t_range: Range<f32>) -> bool {
        let (t_min, t_max) = (t_range.start, t_range.end);
        let planes = self
            .planes
            .iter()
            .any(|&object| match &self.objects[object as usize] {
                Object::Plane(plane) => plane.intersect_t(ray, t_min, t_max).is_some(),
                _ => false,
            });
        if planes {
            return true;
        }
        let watertight = WatertightRay::new(ray);
        self.bvh
            .any_prepared(&BoxRay::new(ray), t_min, t_max, |start, count| {
                self.leaf_objects[start as usize..(start + count) as usize]
                    .iter()
                    .any(|&object| match &self.objects[object as usize] {
                        Object::Instance(instance) => instance.any_hit(ray, t_min..t_max),
                        _ => self
                            .intersect_object(object, ray, &watertight, t_min, t_max)
                            .is_some(),
                    })
            })
    }

    fn intersect_object(
        &self,
        object: u32,
        ray: &Ray,
        watertight: &WatertightRay,
        t_min: f32,
        t_max: f32,
    ) -> Option<RawHit> {
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
            Object::Triangle(tri) => watertight
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

    fn surface(&self, ray: &Ray, raw: &RawHit) -> Hit {
        let hit = match &self.objects[raw.object as usize] {
            Object::Sphere(s) => s.surface(ray, raw.t),
            Object::Plane(p) => p.surface(ray, raw.t),
            Object::Triangle(tri) => tri.surface(ray, raw),
            Object::Box(b) => b.surface(ray, raw.t, raw.primitive / 2, raw.primitive % 2 == 1),
            Object::Instance(i) => i.surface(ray, raw),
        };
        Hit {
            object: raw.object,
            ..hit
        }
    }
}
