//! Four rays at once against one plane, sphere or triangle, from the rays' origins and
//! directions per axis (as a packet holds them): what a world's packets do at a leaf of
//! loose shapes. Every lane works out what the single-ray test does, with the same
//! operations in the same order, so its `t` (and barycentrics) have the same bits.

use glam::{BVec4A, Vec3, Vec4};

#[cfg(doc)]
use super::WatertightRay;
use super::{Plane, Sphere};

/// `Vec3::dot` of four pairs of vectors given per axis: (x x') + (y y') + (z z').
#[inline(always)]
fn dot(p: &[Vec4; 3], q: &[Vec4; 3]) -> Vec4 {
    (p[0] * q[0]) + (p[1] * q[1]) + (p[2] * q[2])
}

impl Plane {
    /// [`Plane::intersect_t`] of four rays at once, from their origins and directions
    /// per axis: the mask of the lanes that meet the plane with `t_min <= t < t_max`,
    /// and each lane's `t`. Every lane works out what the single-ray test does, in the
    /// same order, so its `t` has the same bits.
    #[inline(always)]
    pub(crate) fn intersect_t_lanes(
        &self,
        origin: [Vec4; 3],
        direction: [Vec4; 3],
        t_min: Vec4,
        t_max: Vec4,
    ) -> (u32, Vec4) {
        let n = self.normal.to_array().map(Vec4::splat);
        let p = self.point.to_array().map(Vec4::splat);
        let denominator = dot(&n, &direction);
        let numerator = dot(&n, &[0, 1, 2].map(|axis| p[axis] - origin[axis]));
        let t = numerator / denominator;
        let hit = denominator.cmpne(Vec4::ZERO) & t.cmpge(t_min) & t.cmplt(t_max);
        (hit.bitmask(), t)
    }
}

impl Sphere {
    /// [`Sphere::intersect_t`] of four rays: the mask of the lanes that meet the sphere
    /// with `t_min <= t < t_max`, and each lane's `t`.
    #[inline(always)]
    pub(crate) fn intersect_t_lanes(
        &self,
        origin: [Vec4; 3],
        direction: [Vec4; 3],
        t_min: Vec4,
        t_max: Vec4,
    ) -> (u32, Vec4) {
        let center = self.center.to_array().map(Vec4::splat);
        let f = [0, 1, 2].map(|axis| origin[axis] - center[axis]);
        let d = direction;
        let a = dot(&d, &d);
        let b = dot(&f, &d);
        let r2 = Vec4::splat(self.radius * self.radius);
        let b_over_a = b / a;
        let l = [0, 1, 2].map(|axis| f[axis] - b_over_a * d[axis]);
        let disc = a * (r2 - dot(&l, &l));
        let c = dot(&f, &f) - r2;
        // `f32::signum` of a number is 1 with its sign (a NaN `b` makes `q` NaN either way).
        let q = -(b + Vec4::ONE.copysign(b) * disc.sqrt());
        // `q = 0`: the origin is on the sphere and the ray is tangent (b = disc = 0).
        let tangent = q.cmpeq(Vec4::ZERO);
        let t0 = Vec4::select(tangent, Vec4::ZERO, c / q);
        let t1 = Vec4::select(tangent, Vec4::ZERO, q / a);
        let swap = t0.cmpgt(t1);
        let (t0, t1) = (Vec4::select(swap, t1, t0), Vec4::select(swap, t0, t1));
        let first = t0.cmpge(t_min) & t0.cmplt(t_max);
        let second = t1.cmpge(t_min) & t1.cmplt(t_max);
        let met = a.cmpne(Vec4::ZERO) & !disc.cmplt(Vec4::ZERO) & (first | second);
        (met.bitmask(), Vec4::select(first, t0, t1))
    }
}

/// Four rays prepared for the watertight ray/triangle test (see [`WatertightRay`]),
/// each lane with its own axes: the masks that pick each lane's `kx`, `ky` and `kz`
/// from x, y and z, and its shears.
#[derive(Clone, Copy, Debug)]
pub(crate) struct WatertightLanes {
    origin: [Vec4; 3],
    /// Per permuted axis (`kx`, `ky`, `kz`): the lanes where it is x, and where it is y
    /// (z elsewhere).
    picks: [[BVec4A; 2]; 3],
    shear: [Vec4; 3],
}

/// What a triangle gives four rays: the lanes it is surely decided for (hit or missed;
/// the others are to be tested ray by ray), the lanes hit with `t_min <= t < t_max`,
/// and each lane's `t` and barycentrics `(b1, b2)`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TriangleLanes {
    pub(crate) decided: u32,
    pub(crate) hit: u32,
    pub(crate) t: Vec4,
    pub(crate) b1: Vec4,
    pub(crate) b2: Vec4,
}

impl WatertightLanes {
    /// [`WatertightRay::new`] of four rays, from their origins and directions per axis.
    #[inline(always)]
    pub(crate) fn new(origin: [Vec4; 3], direction: [Vec4; 3]) -> Self {
        let [x, y, z] = direction.map(Vec4::abs);
        // kz: x where it is largest, else y where it is at least z, else z.
        let z_is_x = x.cmpge(y) & x.cmpge(z);
        let z_is_y = !z_is_x & y.cmpge(z);
        let z_is_z = !(z_is_x | z_is_y);
        let pick = |v: &[Vec4; 3], is_x: BVec4A, is_y: BVec4A| {
            Vec4::select(is_x, v[0], Vec4::select(is_y, v[1], v[2]))
        };
        let d_z = pick(&direction, z_is_x, z_is_y);
        // (kx, ky) follow kz cyclically, swapped where d_kz < 0: kz = x gives (y, z) or
        // (z, y), kz = y gives (z, x) or (x, z), kz = z gives (x, y) or (y, x).
        let negative = d_z.cmplt(Vec4::ZERO);
        let positive = !negative;
        let x_is_x = (z_is_z & positive) | (z_is_y & negative);
        let x_is_y = (z_is_x & positive) | (z_is_z & negative);
        let y_is_x = (z_is_y & positive) | (z_is_z & negative);
        let y_is_y = (z_is_z & positive) | (z_is_x & negative);
        let d_x = pick(&direction, x_is_x, x_is_y);
        let d_y = pick(&direction, y_is_x, y_is_y);
        Self {
            origin,
            picks: [[x_is_x, x_is_y], [y_is_x, y_is_y], [z_is_x, z_is_y]],
            shear: [d_x / d_z, d_y / d_z, Vec4::ONE / d_z],
        }
    }

    /// Sheared coordinates `(x, y, z_unscaled)` of vertex `p` relative to the origins
    /// (see `WatertightRay::project`).
    #[inline(always)]
    fn project(&self, p: Vec3) -> [Vec4; 3] {
        let p = p.to_array();
        let rel = [0, 1, 2].map(|axis| Vec4::splat(p[axis]) - self.origin[axis]);
        let [px, py, pz] = self
            .picks
            .map(|[is_x, is_y]| Vec4::select(is_x, rel[0], Vec4::select(is_y, rel[1], rel[2])));
        [px - self.shear[0] * pz, py - self.shear[1] * pz, pz]
    }

    /// [`WatertightRay::intersect`] of four rays with triangle `(a, b, c)`. A lane whose
    /// edge function rounds to exactly zero (a ray through an edge or a vertex, which
    /// the single-ray test recomputes in `f64`) is left undecided.
    #[inline(always)]
    pub(crate) fn intersect(
        &self,
        [a, b, c]: [Vec3; 3],
        t_min: Vec4,
        t_max: Vec4,
    ) -> TriangleLanes {
        let [ax, ay, az] = self.project(a);
        let [bx, by, bz] = self.project(b);
        let [cx, cy, cz] = self.project(c);
        let u = cx * by - cy * bx;
        let v = ax * cy - ay * cx;
        let w = bx * ay - by * ax;
        let zero = Vec4::ZERO;
        let on_edge = u.cmpeq(zero) | v.cmpeq(zero) | w.cmpeq(zero);
        let outside = (u.cmplt(zero) | v.cmplt(zero) | w.cmplt(zero))
            & (u.cmpgt(zero) | v.cmpgt(zero) | w.cmpgt(zero));
        let det = u + v + w;
        let sz = self.shear[2];
        let t = (u * (sz * az) + v * (sz * bz) + w * (sz * cz)) / det;
        let inside = !outside & det.cmpne(zero) & t.cmpge(t_min) & t.cmplt(t_max);
        TriangleLanes {
            decided: (!on_edge).bitmask(),
            hit: (inside & !on_edge).bitmask(),
            t,
            b1: v / det,
            b2: w / det,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Ray;
    use crate::shapes::{Triangle, WatertightRay};

    /// Numbers from a fixed seed (xorshift32): uniform in `[0, 1)`, or in a range.
    struct Numbers(u32);

    impl Numbers {
        fn uniform(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 17;
            self.0 ^= self.0 << 5;
            (self.0 >> 8) as f32 / (1 << 24) as f32
        }

        fn within(&mut self, low: f32, high: f32) -> f32 {
            low + (high - low) * self.uniform()
        }

        fn vector(&mut self, size: f32) -> Vec3 {
            Vec3::new(
                self.within(-size, size),
                self.within(-size, size),
                self.within(-size, size),
            )
        }
    }

    /// The lanes of four rays, per axis, as a packet holds them.
    fn lanes(rays: &[Ray; 4]) -> ([Vec4; 3], [Vec4; 3]) {
        let per_axis = |v: [Vec3; 4]| [0, 1, 2].map(|axis| Vec4::from_array(v.map(|v| v[axis])));
        (
            per_axis(rays.map(|r| r.origin)),
            per_axis(rays.map(|r| r.direction)),
        )
    }

    #[test]
    fn four_lanes_meet_a_sphere_as_each_ray_alone_bit_for_bit() {
        let mut numbers = Numbers(0x51ee_d5ed);
        let mut hits = 0;
        for round in 0..20_000 {
            let sphere = Sphere::new(numbers.vector(4.0), numbers.within(0.05, 2.0));
            let rays: [Ray; 4] = std::array::from_fn(|j| {
                // From outside toward a point near the sphere, from inside, from a point
                // on it, and tangent-ish grazing rays.
                let target = sphere.center + numbers.vector(sphere.radius * 1.2);
                let origin = match (round + j) % 4 {
                    0 => sphere.center + numbers.vector(sphere.radius * 0.5),
                    1 => {
                        let outward = numbers.vector(1.0).normalize_or(Vec3::X);
                        sphere.center + outward * sphere.radius
                    }
                    _ => numbers.vector(10.0),
                };
                let direction = (target - origin) * numbers.within(0.1, 3.0);
                Ray::new(
                    origin,
                    if round % 97 == 0 {
                        Vec3::ZERO
                    } else {
                        direction
                    },
                )
            });
            let t_min = if round % 3 == 0 {
                0.0
            } else {
                numbers.within(0.0, 0.5)
            };
            let t_max = if round % 5 == 0 {
                f32::INFINITY
            } else {
                numbers.within(0.5, 4.0)
            };
            let (origin, direction) = lanes(&rays);
            let (met, t) =
                sphere.intersect_t_lanes(origin, direction, Vec4::splat(t_min), Vec4::splat(t_max));
            for (j, ray) in rays.iter().enumerate() {
                let alone = sphere.intersect_t(ray, t_min, t_max);
                assert_eq!(met & 1 << j != 0, alone.is_some(), "{sphere:?} {ray:?}");
                if let Some(expected) = alone {
                    hits += 1;
                    assert_eq!(t.to_array()[j].to_bits(), expected.to_bits(), "{ray:?}");
                }
            }
        }
        assert!(hits > 20_000, "too few hits to tell: {hits}");
    }

    #[test]
    fn four_lanes_meet_a_triangle_as_each_ray_alone_bit_for_bit() {
        let mut numbers = Numbers(0x7a1a_9e11);
        let (mut hits, mut undecided) = (0, 0);
        for round in 0..20_000 {
            let a = numbers.vector(3.0);
            let triangle = Triangle::new(a, a + numbers.vector(2.0), a + numbers.vector(2.0));
            let [a, b, c] = [triangle.a, triangle.b, triangle.c];
            let rays: [Ray; 4] = std::array::from_fn(|j| {
                // Toward a point of the triangle's plane inside or near it, and now and
                // then exactly at a vertex, where an edge function is zero.
                let (u, v) = (numbers.within(-0.3, 1.1), numbers.within(-0.3, 1.1));
                let target = match (round + j) % 16 {
                    0 => a,
                    1 => c,
                    _ => a + u * (b - a) + v * (c - a),
                };
                let origin = numbers.vector(8.0);
                // Every axis comes to lead the direction, in either sense.
                Ray::new(origin, (target - origin) * numbers.within(0.2, 2.0))
            });
            let t_min = numbers.within(0.0, 0.3);
            let t_max = if round % 4 == 0 {
                f32::INFINITY
            } else {
                numbers.within(0.3, 3.0)
            };
            let (origin, direction) = lanes(&rays);
            let got = WatertightLanes::new(origin, direction).intersect(
                [a, b, c],
                Vec4::splat(t_min),
                Vec4::splat(t_max),
            );
            for (j, ray) in rays.iter().enumerate() {
                let single = WatertightRay::new(ray);
                if got.decided & 1 << j == 0 {
                    // Left to the single-ray test only where an edge function is zero.
                    let [(ax, ay, _), (bx, by, _), (cx, cy, _)] =
                        [a, b, c].map(|p| single.project(p));
                    let edges = [cx * by - cy * bx, ax * cy - ay * cx, bx * ay - by * ax];
                    assert!(edges.contains(&0.0), "undecided off the edges: {ray:?}");
                    undecided += 1;
                    continue;
                }
                let alone = single.intersect(a, b, c, t_min, t_max);
                assert_eq!(
                    got.hit & 1 << j != 0,
                    alone.is_some(),
                    "{triangle:?} {ray:?}"
                );
                if let Some(expected) = alone {
                    hits += 1;
                    let lane = |v: Vec4| v.to_array()[j].to_bits();
                    assert_eq!(lane(got.t), expected.t.to_bits(), "{ray:?}");
                    assert_eq!(lane(got.b1), expected.barycentric.x.to_bits(), "{ray:?}");
                    assert_eq!(lane(got.b2), expected.barycentric.y.to_bits(), "{ray:?}");
                }
            }
        }
        assert!(hits > 10_000, "too few hits to tell: {hits}");
        assert!(undecided > 0, "no ray met an edge function of zero");
    }
}
