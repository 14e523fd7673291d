//! Axis-aligned boxes: the BVH's bound type and the scene's `Box` primitive.

use glam::{Vec2, Vec3};

use std::ops::Range;

use crate::Ray;
use crate::hit::{Hit, face_toward};

/// An axis-aligned box `[min.x, max.x] x [min.y, max.y] x [min.z, max.z]`.
///
/// The same type bounds BVH nodes and is the scene's solid `Box` primitive (see
/// [`Aabb::closest_hit`]). [`Aabb::EMPTY`] (min = +inf, max = -inf) contains nothing and is
/// the identity of [`Aabb::union`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The corner with the smallest coordinates.
    pub min: Vec3,
    /// The corner with the largest coordinates.
    pub max: Vec3,
}

/// Where a ray meets a solid box: the parameter, the face and which side it came from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct BoxCrossing {
    pub(crate) t: f32,
    /// The axis (0 = x, 1 = y, 2 = z) of the face that was hit.
    pub(crate) axis: u32,
    /// Whether the face hit is the `max` face of that axis.
    pub(crate) max_face: bool,
    /// Whether the ray entered the box there (it started outside).
    pub(crate) entering: bool,
}

impl Default for Aabb {
    fn default() -> Self {
        Self::EMPTY
    }
}

impl Aabb {
    /// The empty box, which contains no point: `min = +inf`, `max = -inf`.
    pub const EMPTY: Self = Self {
        min: Vec3::INFINITY,
        max: Vec3::NEG_INFINITY,
    };

    /// The box with corners `min` and `max` (expected `min <= max` on every axis).
    #[inline]
    pub const fn new(min: Vec3, max: Vec3) -> Self {
        Self { min, max }
    }

    /// The smallest box holding every point of `points` ([`Aabb::EMPTY`] for none).
    pub fn from_points(points: impl IntoIterator<Item = Vec3>) -> Self {
        points.into_iter().fold(Self::EMPTY, Self::grow)
    }

    /// This box grown to hold `point`.
    #[inline]
    #[must_use]
    pub fn grow(self, point: Vec3) -> Self {
        Self::new(self.min.min(point), self.max.max(point))
    }

    /// The smallest box holding both boxes.
    #[inline]
    #[must_use]
    pub fn union(self, other: Self) -> Self {
        Self::new(self.min.min(other.min), self.max.max(other.max))
    }

    /// Whether the box holds no point (some `min` exceeds its `max`).
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.min.cmpgt(self.max).any()
    }

    /// Whether `point` lies inside or on the boundary of the box.
    #[inline]
    pub fn contains(&self, point: Vec3) -> bool {
        point.cmpge(self.min).all() && point.cmple(self.max).all()
    }

    /// The edge lengths `max - min` (zero for an empty box).
    #[inline]
    pub fn extent(&self) -> Vec3 {
        if self.is_empty() {
            Vec3::ZERO
        } else {
            self.max - self.min
        }
    }

    /// The center `(min + max) / 2`.
    #[inline]
    pub fn center(&self) -> Vec3 {
        0.5 * (self.min + self.max)
    }

    /// The surface area (zero for an empty box), the measure the SAH weighs children by:
    ///
    /// ```text
    /// area = 2 (dx dy + dy dz + dz dx),   (dx, dy, dz) = max - min
    /// ```
    #[inline]
    pub fn surface_area(&self) -> f32 {
        let d = self.extent();
        2.0 * (d.x * d.y + d.y * d.z + d.z * d.x)
    }

    /// The box's eight corners, `min` first and `max` last: corner `i` takes `max` on
    /// the axes whose bit is set in `i` (bit 0 x, bit 1 y, bit 2 z) and `min` on the
    /// others, so corners `i` and `i ^ 1` differ only in x.
    ///
    /// ```text
    /// 0 (min.x, min.y, min.z)   1 (max.x, min.y, min.z)   2 (min.x, max.y, min.z)
    /// 3 (max.x, max.y, min.z)   4 (min.x, min.y, max.z)   5 (max.x, min.y, max.z)
    /// 6 (min.x, max.y, max.z)   7 (max.x, max.y, max.z)
    /// ```
    ///
    /// This is the one place that spells out a box's corners: [`MeshData::cuboid`]
    /// indexes its faces by this order, and code that draws or exports a box asks here.
    ///
    /// [`MeshData::cuboid`]: crate::MeshData::cuboid
    pub fn corners(&self) -> [Vec3; 8] {
        std::array::from_fn(|i| {
            Vec3::new(
                if i & 1 == 0 { self.min.x } else { self.max.x },
                if i & 2 == 0 { self.min.y } else { self.max.y },
                if i & 4 == 0 { self.min.z } else { self.max.z },
            )
        })
    }

    /// The parameter interval `(t_enter, t_exit)` where the line of `ray` is inside the
    /// box (slab method), or `None` when the line misses it.
    ///
    /// ```text
    /// t_enter = max over axes of min((min_k - o_k) / d_k, (max_k - o_k) / d_k)
    /// t_exit  = min over axes of max((min_k - o_k) / d_k, (max_k - o_k) / d_k)
    /// ```
    ///
    /// An axis with `d_k = 0` constrains nothing when `o_k` is within the slab and
    /// rejects the ray otherwise, so no NaN arises. The interval is not clipped to
    /// `t >= 0`.
    pub fn slab_interval(&self, ray: &Ray) -> Option<(f32, f32)> {
        self.crossings(ray)
            .map(|((t_enter, _), (t_exit, _))| (t_enter, t_exit))
    }

    /// The entry and exit parameters with the axis of the face each one crosses.
    fn crossings(&self, ray: &Ray) -> Option<((f32, usize), (f32, usize))> {
        let mut enter = (f32::NEG_INFINITY, 0);
        let mut exit = (f32::INFINITY, 0);
        for axis in 0..3 {
            let (o, d) = (ray.origin[axis], ray.direction[axis]);
            let (lo, hi) = (self.min[axis], self.max[axis]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let (t_lo, t_hi) = ((lo - o) / d, (hi - o) / d);
            let (t0, t1) = (t_lo.min(t_hi), t_lo.max(t_hi));
            // On a tie (the ray meets an edge or a corner) the lowest axis names the face.
            if t0 > enter.0 {
                enter = (t0, axis);
            }
            if t1 < exit.0 {
                exit = (t1, axis);
            }
        }
        (enter.0 <= exit.0).then_some((enter, exit))
    }

    /// The first crossing of the box's surface with `t` in `t_min <= t < t_max`: the
    /// entry when the ray starts outside, the exit when it starts inside.
    pub(crate) fn intersect_solid(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<BoxCrossing> {
        let ((t_enter, enter_axis), (t_exit, exit_axis)) = self.crossings(ray)?;
        let (t, axis, entering) = if t_enter >= t_min && t_enter.is_finite() {
            (t_enter, enter_axis, true)
        } else if t_exit >= t_min && t_exit.is_finite() {
            (t_exit, exit_axis, false)
        } else {
            return None;
        };
        if t >= t_max {
            return None;
        }
        // Entering through a face whose outward normal opposes the direction: the max face
        // when the direction is negative on that axis; leaving, the other way round. (The
        // face's axis is one the direction is not zero on.)
        let negative = ray.direction[axis].is_sign_negative();
        Some(BoxCrossing {
            t,
            axis: axis as u32,
            max_face: negative == entering,
            entering,
        })
    }

    /// The closest hit of `ray` with the solid box with `t` in `t_range`: the entry face
    /// from outside, the exit face from inside (a back face).
    ///
    /// The uv are the hit point's two other coordinates on the face, relative to the
    /// box, each in [0, 1]:
    ///
    /// ```text
    /// uv = ((p_a - min_a) / (max_a - min_a), (p_b - min_b) / (max_b - min_b)),
    /// a = (k + 1) mod 3, b = (k + 2) mod 3   for a face perpendicular to axis k
    /// ```
    pub fn closest_hit(&self, ray: &Ray, t_range: Range<f32>) -> Option<Hit> {
        let crossing = self.intersect_solid(ray, t_range.start, t_range.end)?;
        Some(self.surface(ray, crossing.t, crossing.axis, crossing.max_face))
    }

    /// The surface details where `ray` crosses face `axis` / `max_face` at `t`.
    pub(crate) fn surface(&self, ray: &Ray, t: f32, axis: u32, max_face: bool) -> Hit {
        let point = ray.at(t);
        let outward = Self::face_normal(axis, max_face);
        let (normal, shading_normal, front_face) = face_toward(ray.direction, outward, outward);
        Hit {
            t,
            point,
            normal,
            shading_normal,
            front_face,
            uv: self.face_uv(axis, point),
            primitive: 0,
            object: 0,
        }
    }

    /// The outward unit normal of the face `axis` / `max_face`.
    pub(crate) fn face_normal(axis: u32, max_face: bool) -> Vec3 {
        let mut n = Vec3::ZERO;
        n[axis as usize] = if max_face { 1.0 } else { -1.0 };
        n
    }

    /// Texture coordinates of `point` on face `axis` (see [`Aabb::closest_hit`]).
    pub(crate) fn face_uv(&self, axis: u32, point: Vec3) -> Vec2 {
        let relative = |k: usize| {
            let size = self.max[k] - self.min[k];
            if size > 0.0 {
                ((point[k] - self.min[k]) / size).clamp(0.0, 1.0)
            } else {
                0.0
            }
        };
        let axis = axis as usize;
        Vec2::new(relative((axis + 1) % 3), relative((axis + 2) % 3))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_is_the_identity_of_union() {
        let b = Aabb::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(1.0, 3.0, 4.0));
        assert_eq!(Aabb::EMPTY.union(b), b);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.surface_area(), 0.0);
        assert_eq!(b.surface_area(), 2.0 * (2.0 * 3.0 + 3.0 * 2.0 + 2.0 * 2.0));
        assert_eq!(Aabb::from_points(b.corners()), b);
    }

    /// The corners come in the documented order: bit 0 of the index picks x's side, bit
    /// 1 y's, bit 2 z's (the box's extents differ on each axis, so no two coincide).
    #[test]
    fn corners_take_max_on_the_axes_of_their_index_bits() {
        let b = Aabb::new(Vec3::new(-1.0, 0.0, 2.0), Vec3::new(1.0, 3.0, 4.0));
        assert_eq!(
            b.corners(),
            [
                Vec3::new(-1.0, 0.0, 2.0),
                Vec3::new(1.0, 0.0, 2.0),
                Vec3::new(-1.0, 3.0, 2.0),
                Vec3::new(1.0, 3.0, 2.0),
                Vec3::new(-1.0, 0.0, 4.0),
                Vec3::new(1.0, 0.0, 4.0),
                Vec3::new(-1.0, 3.0, 4.0),
                Vec3::new(1.0, 3.0, 4.0),
            ]
        );
    }

    #[test]
    fn face_uv_runs_along_the_next_two_axes_in_turn() {
        // The point is a quarter, a half and three quarters of the way along x, y, z.
        let b = Aabb::new(Vec3::new(0.0, 10.0, 100.0), Vec3::new(2.0, 14.0, 108.0));
        let p = Vec3::new(0.5, 12.0, 106.0);
        assert_eq!(b.face_uv(0, p), Vec2::new(0.5, 0.75)); // y, z
        assert_eq!(b.face_uv(1, p), Vec2::new(0.75, 0.25)); // z, x
        assert_eq!(b.face_uv(2, p), Vec2::new(0.25, 0.5)); // x, y
        // Without extent along an axis, the coordinate along it is 0 (not 0 / 0).
        let flat = Aabb::new(Vec3::new(0.0, 3.0, 0.0), Vec3::new(4.0, 3.0, 4.0));
        assert_eq!(
            flat.face_uv(2, Vec3::new(1.0, 3.0, 2.0)),
            Vec2::new(0.25, 0.0)
        );
    }

    #[test]
    fn slab_interval_handles_axis_parallel_rays() {
        let b = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        // A ray lying in the plane of a face (o_x = max.x, d_x = 0) still gets an interval.
        let ray = Ray::new(Vec3::new(1.0, 0.0, 5.0), Vec3::new(0.0, 0.0, -2.0));
        assert_eq!(b.slab_interval(&ray), Some((2.0, 3.0)));
        // And in the plane of the min face (o_y = min.y, d_y = 0): the slab is closed.
        let ray = Ray::new(Vec3::new(0.0, -1.0, 5.0), Vec3::new(0.0, 0.0, -2.0));
        assert_eq!(b.slab_interval(&ray), Some((2.0, 3.0)));
        let outside = Ray::new(Vec3::new(1.5, 0.0, 5.0), Vec3::new(0.0, 0.0, -2.0));
        assert_eq!(b.slab_interval(&outside), None);
    }

    #[test]
    fn at_an_edge_or_a_corner_the_lowest_axis_names_the_face() {
        let b = Aabb::new(Vec3::splat(-1.0), Vec3::splat(1.0));
        let crossing = |origin: Vec3, direction: Vec3| {
            let c = b
                .intersect_solid(&Ray::new(origin, direction), 0.0, f32::INFINITY)
                .unwrap();
            (c.t, c.axis, c.max_face, c.entering)
        };
        // From (-3, -3, 0) along (1, 1, 0): x = -1 and y = -1 both at t = 2, the edge
        // (-1, -1, 0); the x face (min side) is reported.
        assert_eq!(
            crossing(Vec3::new(-3.0, -3.0, 0.0), Vec3::new(1.0, 1.0, 0.0)),
            (2.0, 0, false, true)
        );
        // Along (-1, -1, -1) from (3, 3, 3): the corner (1, 1, 1) at t = 2, the x face.
        assert_eq!(
            crossing(Vec3::splat(3.0), Vec3::splat(-1.0)),
            (2.0, 0, true, true)
        );
        // From inside, along (0, 1, 1): y = 1 and z = 1 both at t = 1; leaving by y.
        assert_eq!(
            crossing(Vec3::ZERO, Vec3::new(0.0, 1.0, 1.0)),
            (1.0, 1, true, false)
        );
        // From the centre along (0, 0, -4): out through the min z face at t = 1/4.
        assert_eq!(
            crossing(Vec3::ZERO, Vec3::new(0.0, 0.0, -4.0)),
            (0.25, 2, false, false)
        );
    }
}
