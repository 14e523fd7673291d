//! Analytic shapes: sphere, infinite plane and single triangle, plus the watertight
//! ray/triangle test that meshes share.

use std::ops::Range;

use glam::{Vec2, Vec3};

use crate::hit::{Hit, RawHit, face_toward};
use crate::{Aabb, Ray};

mod lanes;

pub(crate) use self::lanes::WatertightLanes;

/// A sphere `|p - center| = radius`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    /// The center.
    pub center: Vec3,
    /// The radius (positive).
    pub radius: f32,
}

/// An infinite plane through `point` with normal `normal` (any nonzero length); its
/// front is the side the normal points to.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// A point on the plane.
    pub point: Vec3,
    /// The normal, not necessarily of unit length.
    pub normal: Vec3,
}

/// A triangle with vertices `a, b, c`; its front is the side from which they run
/// counter-clockwise, where `(b - a) x (c - a)` points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Triangle {
    /// The first vertex.
    pub a: Vec3,
    /// The second vertex.
    pub b: Vec3,
    /// The third vertex.
    pub c: Vec3,
}

impl Sphere {
    /// The sphere around `center` with radius `radius`.
    pub const fn new(center: Vec3, radius: f32) -> Self {
        Self { center, radius }
    }

    /// The sphere's bounding box.
    pub fn bounds(&self) -> Aabb {
        Aabb::new(self.center - self.radius, self.center + self.radius)
    }

    /// The smallest root `t` in `t_range` of `|o + t d - center|^2 = radius^2`.
    ///
    /// The discriminant is computed in the cancellation-free form of Haines et al.,
    /// "Precision Improvements for Ray/Sphere Intersection" (Ray Tracing Gems, 2019):
    ///
    /// ```text
    /// f = o - center,  a = d.d,  b = f.d,  c = f.f - r^2
    /// disc = a (r^2 - |f - (b / a) d|^2)
    /// q = -(b + sign(b) sqrt(disc));   t0 = c / q,  t1 = q / a
    /// ```
    ///
    /// A ray starting inside gets the far root (the exit), a tangent ray the double root.
    pub(crate) fn intersect_t(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        let f = ray.origin - self.center;
        let d = ray.direction;
        let a = d.length_squared();
        if a == 0.0 {
            return None;
        }
        let b = f.dot(d);
        let r2 = self.radius * self.radius;
        let l = f - (b / a) * d;
        let disc = a * (r2 - l.length_squared());
        if disc < 0.0 {
            return None;
        }
        let c = f.length_squared() - r2;
        let q = -(b + b.signum() * disc.sqrt());
        let (mut t0, mut t1) = if q == 0.0 {
            // The origin is on the sphere and the ray is tangent (b = disc = 0).
            (0.0, 0.0)
        } else {
            (c / q, q / a)
        };
        if t0 > t1 {
            std::mem::swap(&mut t0, &mut t1);
        }
        [t0, t1].into_iter().find(|t| *t >= t_min && *t < t_max)
    }

    /// The closest hit with `t` in `t_range` (`t_range.start <= t < t_range.end`).
    ///
    /// The uv are the spherical angles of the outward normal `n`, each in [0, 1]:
    ///
    /// ```text
    /// u = 1/2 + atan2(n.x, n.z) / (2 pi),   v = 1/2 + asin(n.y) / pi
    /// ```
    pub fn closest_hit(&self, ray: &Ray, t_range: Range<f32>) -> Option<Hit> {
        let t = self.intersect_t(ray, t_range.start, t_range.end)?;
        Some(self.surface(ray, t))
    }

    pub(crate) fn surface(&self, ray: &Ray, t: f32) -> Hit {
        self.surface_with(ray, t, true)
    }

    /// [`Sphere::surface`], with the uv (an arc tangent and an arc sine) only if
    /// `with_uv`, else zero.
    #[inline(always)]
    pub(crate) fn surface_with(&self, ray: &Ray, t: f32, with_uv: bool) -> Hit {
        let point = ray.at(t);
        let outward = ((point - self.center) / self.radius).normalize_or(Vec3::Y);
        let uv = if with_uv {
            Vec2::new(
                0.5 + outward.x.atan2(outward.z) / std::f32::consts::TAU,
                0.5 + outward.y.clamp(-1.0, 1.0).asin() / std::f32::consts::PI,
            )
        } else {
            Vec2::ZERO
        };
        let (normal, shading_normal, front_face) = face_toward(ray.direction, outward, outward);
        Hit {
            t,
            point,
            normal,
            shading_normal,
            front_face,
            uv,
            primitive: 0,
            object: 0,
        }
    }
}

impl Plane {
    /// The plane through `point` with normal `normal`.
    pub const fn new(point: Vec3, normal: Vec3) -> Self {
        Self { point, normal }
    }

    /// The parameter where the ray meets the plane, `None` for a parallel ray:
    ///
    /// ```text
    /// t = n.(point - o) / n.d
    /// ```
    pub(crate) fn intersect_t(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<f32> {
        let denominator = self.normal.dot(ray.direction);
        if denominator == 0.0 {
            return None;
        }
        let t = self.normal.dot(self.point - ray.origin) / denominator;
        (t >= t_min && t < t_max).then_some(t)
    }

    /// The hit with `t` in `t_range`, `None` when the ray is parallel to the plane.
    ///
    /// The uv are the hit point's coordinates, in world units, along two perpendicular
    /// unit vectors `(s1, s2)` in the plane (glam's `any_orthonormal_pair` of the normal):
    ///
    /// ```text
    /// uv = ((p - point).s1, (p - point).s2)
    /// ```
    pub fn closest_hit(&self, ray: &Ray, t_range: Range<f32>) -> Option<Hit> {
        let t = self.intersect_t(ray, t_range.start, t_range.end)?;
        Some(self.surface(ray, t))
    }

    pub(crate) fn surface(&self, ray: &Ray, t: f32) -> Hit {
        self.surface_in(ray, t, &self.frame(), true)
    }

    /// The unit normal and the uv axes, which every hit on the plane shares.
    pub(crate) fn frame(&self) -> PlaneFrame {
        let normal = self.normal.normalize_or(Vec3::Y);
        let (s1, s2) = normal.any_orthonormal_pair();
        PlaneFrame { normal, s1, s2 }
    }

    /// [`Plane::surface`] with the plane's [`Plane::frame`] already worked out, and the
    /// uv only if `with_uv` (else zero).
    #[inline]
    pub(crate) fn surface_in(&self, ray: &Ray, t: f32, frame: &PlaneFrame, with_uv: bool) -> Hit {
        let point = ray.at(t);
        let PlaneFrame { normal: n, s1, s2 } = *frame;
        let offset = point - self.point;
        let (normal, shading_normal, front_face) = face_toward(ray.direction, n, n);
        Hit {
            t,
            point,
            normal,
            shading_normal,
            front_face,
            uv: if with_uv {
                Vec2::new(offset.dot(s1), offset.dot(s2))
            } else {
                Vec2::ZERO
            },
            primitive: 0,
            object: 0,
        }
    }
}

/// What every hit on a plane shares: its unit normal and the unit uv axes `(s1, s2)`
/// (see [`Plane::closest_hit`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PlaneFrame {
    normal: Vec3,
    s1: Vec3,
    s2: Vec3,
}

impl Triangle {
    /// The triangle with vertices `a, b, c`.
    pub const fn new(a: Vec3, b: Vec3, c: Vec3) -> Self {
        Self { a, b, c }
    }

    /// The triangle's bounding box.
    pub fn bounds(&self) -> Aabb {
        Aabb::from_points([self.a, self.b, self.c])
    }

    /// The unnormalized geometric normal `(b - a) x (c - a)`, twice the area long.
    pub fn area_normal(&self) -> Vec3 {
        (self.b - self.a).cross(self.c - self.a)
    }

    /// The watertight hit with `t` in `t_range` (see the [crate's design](crate#design)).
    ///
    /// The uv are the barycentric coordinates `(b1, b2)` of `b` and `c`:
    /// `point = (1 - b1 - b2) a + b1 b + b2 c`.
    pub fn closest_hit(&self, ray: &Ray, t_range: Range<f32>) -> Option<Hit> {
        let raw = WatertightRay::new(ray).intersect(
            self.a,
            self.b,
            self.c,
            t_range.start,
            t_range.end,
        )?;
        Some(self.surface(ray, &raw))
    }

    pub(crate) fn surface(&self, ray: &Ray, raw: &RawHit) -> Hit {
        let n = self.area_normal().normalize_or(Vec3::Z);
        let (normal, shading_normal, front_face) = face_toward(ray.direction, n, n);
        Hit {
            t: raw.t,
            point: ray.at(raw.t),
            normal,
            shading_normal,
            front_face,
            uv: raw.barycentric,
            primitive: 0,
            object: 0,
        }
    }
}

/// A ray prepared for the watertight ray/triangle test of Woop, Benthin and Wald,
/// "Watertight Ray/Triangle Intersection" (JCGT 2013).
///
/// The ray is moved to the origin and sheared so that it runs along +z; a triangle is
/// then hit when the origin of the xy plane lies inside its sheared 2D projection:
///
/// ```text
/// kz = the axis of the largest |d_k|, kx = kz + 1, ky = kx + 1 (mod 3),
///      kx and ky swapped when d_kz < 0 (keeps the winding)
/// Sx = d_kx / d_kz,  Sy = d_ky / d_kz,  Sz = 1 / d_kz
/// A = a - o:  Ax = A_kx - Sx A_kz,  Ay = A_ky - Sy A_kz   (likewise B, C)
/// U = Cx By - Cy Bx,  V = Ax Cy - Ay Cx,  W = Bx Ay - By Ax     (edge functions)
/// hit when U, V, W are all >= 0 or all <= 0, and det = U + V + W != 0
/// t = (U Sz A_kz + V Sz B_kz + W Sz C_kz) / det,  barycentrics (U, V, W) / det
/// ```
///
/// A shared edge is evaluated with bit-identical products in both triangles, with
/// opposite signs, and an edge function that rounds to exactly zero is recomputed in
/// `f64`; so a ray through an edge or vertex of a closed mesh can never pass between
/// its triangles. Because the ray is not normalized, `t` is in units of `d`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WatertightRay {
    pub(crate) origin: Vec3,
    pub(crate) k: [usize; 3],
    pub(crate) shear: Vec3,
}

impl WatertightRay {
    pub(crate) fn new(ray: &Ray) -> Self {
        // Arrays, not glam's `Index` on `Vec3`, which is a `match` on the axis: branches
        // for every lookup below.
        let d = ray.direction.to_array();
        let abs = ray.direction.abs();
        let kz = if abs.x >= abs.y && abs.x >= abs.z {
            0
        } else if abs.y >= abs.z {
            1
        } else {
            2
        };
        // The two axes after `kz`, cyclically.
        const NEXT: [[usize; 2]; 3] = [[1, 2], [2, 0], [0, 1]];
        let [mut kx, mut ky] = NEXT[kz];
        if d[kz] < 0.0 {
            std::mem::swap(&mut kx, &mut ky);
        }
        // A zero direction gives infinite shears; every test then fails cleanly because
        // the edge functions are NaN and NaN compares false.
        let shear = Vec3::new(d[kx] / d[kz], d[ky] / d[kz], 1.0 / d[kz]);
        Self {
            origin: ray.origin,
            k: [kx, ky, kz],
            shear,
        }
    }

    /// Sheared coordinates `(x, y, z_unscaled)` of vertex `p` relative to the origin.
    #[inline]
    fn project(&self, p: Vec3) -> (f32, f32, f32) {
        let [kx, ky, kz] = self.k;
        let rel = (p - self.origin).to_array();
        let z = rel[kz];
        (rel[kx] - self.shear.x * z, rel[ky] - self.shear.y * z, z)
    }

    /// The hit with triangle `(a, b, c)` and `t_min <= t < t_max`, as a raw hit with
    /// barycentrics `(b1, b2)`.
    pub(crate) fn intersect(
        &self,
        a: Vec3,
        b: Vec3,
        c: Vec3,
        t_min: f32,
        t_max: f32,
    ) -> Option<RawHit> {
        let (ax, ay, az) = self.project(a);
        let (bx, by, bz) = self.project(b);
        let (cx, cy, cz) = self.project(c);
        let (mut u, mut v, mut w) = (cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax);
        if u == 0.0 || v == 0.0 || w == 0.0 {
            (u, v, w) = edge_functions_f64([ax, ay], [bx, by], [cx, cy]);
        }
        if (u < 0.0 || v < 0.0 || w < 0.0) && (u > 0.0 || v > 0.0 || w > 0.0) {
            return None;
        }
        let det = u + v + w;
        if det == 0.0 {
            return None;
        }
        let sz = self.shear.z;
        let t = (u * (sz * az) + v * (sz * bz) + w * (sz * cz)) / det;
        if !(t >= t_min && t < t_max) {
            return None;
        }
        Some(RawHit {
            t,
            object: 0,
            primitive: 0,
            barycentric: Vec2::new(v / det, w / det),
        })
    }
}

/// The three edge functions recomputed in double precision, where the products of two
/// `f32`s are exact, for the rays that pass exactly through an edge or a vertex.
#[inline(never)]
#[cold]
pub(crate) fn edge_functions_f64(a: [f32; 2], b: [f32; 2], c: [f32; 2]) -> (f32, f32, f32) {
    let [ax, ay] = a.map(f64::from);
    let [bx, by] = b.map(f64::from);
    let [cx, cy] = c.map(f64::from);
    (
        (cx * by - cy * bx) as f32,
        (ax * cy - ay * cx) as f32,
        (bx * ay - by * ax) as f32,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What a test expects of a hit: `t` and the unit geometric normal facing the ray.
    #[derive(Debug)]
    struct Expected {
        t: f32,
        normal: Vec3,
        front_face: bool,
    }

    #[track_caller]
    fn check(hit: Option<Hit>, expected: Option<Expected>) {
        match (hit, expected) {
            (None, None) => {}
            (Some(hit), Some(e)) => {
                assert!(
                    (hit.t - e.t).abs() <= 1e-5 * e.t.abs().max(1.0),
                    "t {} != {}",
                    hit.t,
                    e.t
                );
                assert!(
                    hit.normal.abs_diff_eq(e.normal, 1e-5),
                    "normal {} != {}",
                    hit.normal,
                    e.normal
                );
                assert_eq!(hit.front_face, e.front_face);
                assert!(hit.uv.is_finite());
            }
            (hit, e) => panic!("hit {hit:?}, expected {e:?}"),
        }
    }

    fn hit(t: f32, normal: Vec3, front_face: bool) -> Option<Expected> {
        Some(Expected {
            t,
            normal,
            front_face,
        })
    }

    #[test]
    fn sphere_cases() {
        let s = Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0);
        let down = |z: f32, len: f32| Ray::new(Vec3::new(0.0, 0.0, z), Vec3::new(0.0, 0.0, -len));
        let all = 0.0..f32::INFINITY;
        // From outside, with directions of length 1 and 2 (t halves).
        check(
            s.closest_hit(&down(0.0, 1.0), all.clone()),
            hit(4.0, Vec3::Z, true),
        );
        check(
            s.closest_hit(&down(0.0, 2.0), all.clone()),
            hit(2.0, Vec3::Z, true),
        );
        // From inside: the exit, back face, normal still facing the ray.
        check(
            s.closest_hit(&down(-5.0, 1.0), all.clone()),
            hit(1.0, Vec3::Z, false),
        );
        // Behind the ray: nothing.
        check(s.closest_hit(&down(-10.0, 1.0), all.clone()), None);
        // Tangent: touches at x = 1.
        let tangent = Ray::new(Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, -1.0));
        check(
            s.closest_hit(&tangent, all.clone()),
            hit(5.0, Vec3::X, true),
        );
        // A miss, and a hit cut off by the range.
        let miss = Ray::new(Vec3::new(1.5, 0.0, 0.0), Vec3::new(0.0, 0.0, -1.0));
        check(s.closest_hit(&miss, all), None);
        check(s.closest_hit(&down(0.0, 1.0), 0.0..3.9), None);
        // Starting on the surface, leaving: the far side with t > 0 only.
        check(
            s.closest_hit(&down(-4.0, 1.0), 1e-4..f32::INFINITY),
            hit(2.0, Vec3::Z, false),
        );
    }

    #[test]
    fn plane_cases() {
        let p = Plane::new(Vec3::new(0.0, -1.0, 0.0), Vec3::new(0.0, 3.0, 0.0));
        let all = 0.0..f32::INFINITY;
        let from_above = Ray::new(Vec3::ZERO, Vec3::new(0.0, -0.5, -1.0));
        check(
            p.closest_hit(&from_above, all.clone()),
            hit(2.0, Vec3::Y, true),
        );
        let from_below = Ray::new(Vec3::new(0.0, -3.0, 0.0), Vec3::new(1.0, 4.0, 0.0));
        check(
            p.closest_hit(&from_below, all.clone()),
            hit(0.5, Vec3::NEG_Y, false),
        );
        // Parallel rays, in the plane or beside it: no hit and no NaN.
        let parallel = Ray::new(Vec3::ZERO, Vec3::new(1.0, 0.0, 1.0));
        check(p.closest_hit(&parallel, all.clone()), None);
        let in_plane = Ray::new(Vec3::new(0.0, -1.0, 0.0), Vec3::new(1.0, 0.0, 1.0));
        check(p.closest_hit(&in_plane, all.clone()), None);
        // Pointing away.
        check(p.closest_hit(&Ray::new(Vec3::ZERO, Vec3::Y), all), None);
    }

    #[test]
    fn box_cases() {
        let b = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        let all = 0.0..f32::INFINITY;
        let cases = [
            // From outside along -z with a long direction.
            (
                Ray::new(Vec3::new(0.2, 0.3, 5.0), Vec3::new(0.0, 0.0, -4.0)),
                hit(1.0, Vec3::Z, true),
            ),
            // From inside: the exit face, back face, normal facing the ray.
            (
                Ray::new(Vec3::ZERO, Vec3::new(0.5, 0.0, 0.0)),
                hit(2.0, Vec3::NEG_X, false),
            ),
            (
                Ray::new(Vec3::ZERO, Vec3::new(0.0, -2.0, 0.1)),
                hit(0.5, Vec3::Y, false),
            ),
            // Along a face (grazing): the slab is closed, so it counts as a hit.
            (
                Ray::new(Vec3::new(1.0, 0.0, 5.0), Vec3::new(0.0, 0.0, -1.0)),
                hit(4.0, Vec3::Z, true),
            ),
            (
                Ray::new(Vec3::new(1.5, 0.0, 5.0), Vec3::new(0.0, 0.0, -1.0)),
                None,
            ),
            (
                Ray::new(Vec3::new(0.0, 0.0, 5.0), Vec3::new(0.0, 0.0, 1.0)),
                None,
            ),
        ];
        for (ray, expected) in cases {
            check(b.closest_hit(&ray, all.clone()), expected);
        }
    }

    #[test]
    fn triangle_cases() {
        let tri = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::Y);
        let all = 0.0..f32::INFINITY;
        let front = Ray::new(Vec3::new(0.25, 0.25, 2.0), Vec3::new(0.0, 0.0, -0.5));
        check(
            tri.closest_hit(&front, all.clone()),
            hit(4.0, Vec3::Z, true),
        );
        let back = Ray::new(Vec3::new(0.25, 0.25, -2.0), Vec3::new(0.0, 0.0, 3.0));
        check(
            tri.closest_hit(&back, all.clone()),
            hit(2.0 / 3.0, Vec3::NEG_Z, false),
        );
        // Exactly through a vertex and an edge.
        check(
            tri.closest_hit(
                &Ray::new(Vec3::new(1.0, 0.0, 1.0), Vec3::NEG_Z),
                all.clone(),
            ),
            hit(1.0, Vec3::Z, true),
        );
        check(
            tri.closest_hit(
                &Ray::new(Vec3::new(0.5, 0.5, 1.0), Vec3::NEG_Z),
                all.clone(),
            ),
            hit(1.0, Vec3::Z, true),
        );
        // Parallel to the face, in its plane and beside it.
        check(
            tri.closest_hit(&Ray::new(Vec3::new(-1.0, 0.25, 0.0), Vec3::X), all.clone()),
            None,
        );
        check(
            tri.closest_hit(&Ray::new(Vec3::new(-1.0, 0.25, 1.0), Vec3::X), all.clone()),
            None,
        );
        // A zero-area triangle is never hit.
        let flat = Triangle::new(Vec3::ZERO, Vec3::X, Vec3::X * 2.0);
        check(
            flat.closest_hit(&Ray::new(Vec3::new(0.5, 0.0, 1.0), Vec3::NEG_Z), all),
            None,
        );
        // Barycentrics: the hit point is (1 - b1 - b2) a + b1 b + b2 c.
        let h = tri.closest_hit(&front, 0.0..10.0).unwrap();
        assert!(h.uv.abs_diff_eq(Vec2::new(0.25, 0.25), 1e-6));
    }
}
