//! Four samples' vectors side by side, for shading a batch of samples four at a time.
//!
//! [`Vec3x4`] holds the x, y and z of four vectors in three SIMD registers (glam's
//! [`Vec4`]: SSE2 on x86_64), structure-of-arrays. Every operation is the one glam's
//! [`Vec3`] does, lane by lane and in the same order (a dot product is `(x x') + (y y')
//! + (z z')`, a normalization multiplies by `1 / length`), and IEEE arithmetic rounds
//! each lane exactly as the scalar operation, so a lane holds the same bits as the
//! scalar computation of its sample. Comparisons that reject a sample are written as
//! the scalar code's `if x <= 0.0 { return }`, negated, so a NaN passes in both.

use std::ops::{Add, Div, Mul, Neg, Sub};

use glam::{BVec4A, Vec3, Vec4};

/// Three coordinates of four vectors: lane `j` of `x`, `y` and `z` is vector `j`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Vec3x4 {
    pub(crate) x: Vec4,
    pub(crate) y: Vec4,
    pub(crate) z: Vec4,
}

impl Vec3x4 {
    pub(crate) const ZERO: Self = Self::splat(Vec3::ZERO);

    /// The same vector in every lane.
    #[inline]
    pub(crate) const fn splat(v: Vec3) -> Self {
        Self {
            x: Vec4::splat(v.x),
            y: Vec4::splat(v.y),
            z: Vec4::splat(v.z),
        }
    }

    /// Four vectors, one per lane, read where they lie. (Copied first into an array
    /// written just before, they would be read back sixteen bytes at a time from
    /// stores of four or eight, which the processor cannot forward: it waits for the
    /// stores to reach the cache.)
    #[inline]
    pub(crate) fn gather(v: [&Vec3; 4]) -> Self {
        Self {
            x: Vec4::new(v[0].x, v[1].x, v[2].x, v[3].x),
            y: Vec4::new(v[0].y, v[1].y, v[2].y, v[3].y),
            z: Vec4::new(v[0].z, v[1].z, v[2].z, v[3].z),
        }
    }

    /// The vector of lane `lane`.
    #[inline]
    pub(crate) fn lane(&self, lane: usize) -> Vec3 {
        // Through arrays: indexing a `Vec4` by a variable lane is a `match`.
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        Vec3::new(x[lane], y[lane], z[lane])
    }

    /// The four vectors, lane by lane.
    #[inline]
    pub(crate) fn to_lanes(self) -> [Vec3; 4] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        std::array::from_fn(|j| Vec3::new(x[j], y[j], z[j]))
    }

    /// Lane by lane, [`Vec3::dot`].
    #[inline]
    pub(crate) fn dot(self, rhs: Self) -> Vec4 {
        (self.x * rhs.x) + (self.y * rhs.y) + (self.z * rhs.z)
    }

    /// Lane by lane, [`Vec3::normalize_or_zero`]: `self * (1 / length)` where that factor
    /// is finite and positive, else zero.
    #[inline]
    pub(crate) fn normalize_or_zero(self) -> Self {
        let rcp = Vec4::ONE / self.dot(self).sqrt();
        let ok = rcp.is_finite_mask() & rcp.cmpgt(Vec4::ZERO);
        Self::select(ok, self * rcp, Self::ZERO)
    }

    /// Lane by lane, [`Vec3::abs`] then [`Vec3::max_element`] (`max(max(x, y), z)` with
    /// `max(a, b) = if a > b { a } else { b }`).
    #[inline]
    pub(crate) fn abs_max_element(self) -> Vec4 {
        let max = |a: Vec4, b: Vec4| Vec4::select(a.cmpgt(b), a, b);
        max(max(self.x.abs(), self.y.abs()), self.z.abs())
    }

    /// `if_true` in the lanes of `mask`, `if_false` in the others.
    #[inline]
    pub(crate) fn select(mask: BVec4A, if_true: Self, if_false: Self) -> Self {
        Self {
            x: Vec4::select(mask, if_true.x, if_false.x),
            y: Vec4::select(mask, if_true.y, if_false.y),
            z: Vec4::select(mask, if_true.z, if_false.z),
        }
    }
}

impl Add for Vec3x4 {
    type Output = Self;
    #[inline]
    fn add(self, rhs: Self) -> Self {
        Self {
            x: self.x + rhs.x,
            y: self.y + rhs.y,
            z: self.z + rhs.z,
        }
    }
}

impl Sub for Vec3x4 {
    type Output = Self;
    #[inline]
    fn sub(self, rhs: Self) -> Self {
        Self {
            x: self.x - rhs.x,
            y: self.y - rhs.y,
            z: self.z - rhs.z,
        }
    }
}

/// Lane by lane and coordinate by coordinate, as `Vec3 * Vec3`.
impl Mul for Vec3x4 {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Self) -> Self {
        Self {
            x: self.x * rhs.x,
            y: self.y * rhs.y,
            z: self.z * rhs.z,
        }
    }
}

/// Each lane's vector times that lane's number, as `Vec3 * f32`.
impl Mul<Vec4> for Vec3x4 {
    type Output = Self;
    #[inline]
    fn mul(self, rhs: Vec4) -> Self {
        Self {
            x: self.x * rhs,
            y: self.y * rhs,
            z: self.z * rhs,
        }
    }
}

/// Each lane's vector divided by that lane's number, as `Vec3 / f32`.
impl Div<Vec4> for Vec3x4 {
    type Output = Self;
    #[inline]
    fn div(self, rhs: Vec4) -> Self {
        Self {
            x: self.x / rhs,
            y: self.y / rhs,
            z: self.z / rhs,
        }
    }
}

impl Neg for Vec3x4 {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        Self {
            x: -self.x,
            y: -self.y,
            z: -self.z,
        }
    }
}

/// The lanes of `mask` as bits: bit `j` for lane `j`.
#[inline]
pub(crate) fn bits(mask: BVec4A) -> u32 {
    mask.bitmask()
}

/// The mask with lane `j` set where bit `j` of `bits` is (bits above the fourth are
/// ignored).
#[inline]
pub(crate) fn mask(bits: u32) -> BVec4A {
    MASKS[(bits & 0xf) as usize]
}

/// The set bits of `mask`, lowest first: the lanes it holds.
#[inline]
pub(crate) fn lanes_of(mask: u32) -> impl Iterator<Item = usize> {
    (0..4).filter(move |j| mask & (1 << j) != 0)
}

/// [`mask`] of each four bits, looked up rather than built lane by lane.
const MASKS: [BVec4A; 16] = {
    let mut masks = [BVec4A::new(false, false, false, false); 16];
    let mut bits = 0;
    while bits < 16 {
        masks[bits] = BVec4A::new(bits & 1 != 0, bits & 2 != 0, bits & 4 != 0, bits & 8 != 0);
        bits += 1;
    }
    masks
};

#[cfg(test)]
mod tests {
    use super::*;

    /// Vectors that reach every branch: ordinary, tiny (whose length squared
    /// underflows), huge (overflows), zero, negative zero, infinite and NaN.
    fn awkward_vectors() -> Vec<Vec3> {
        let mut state = 0x1234_5678_u32;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state
        };
        let mut vectors = vec![
            Vec3::ZERO,
            Vec3::splat(-0.0),
            Vec3::new(1e-30, -2e-30, 0.0),
            Vec3::new(3e30, 1.0, -2e30),
            Vec3::new(f32::INFINITY, 0.0, 1.0),
            Vec3::new(f32::NAN, 1.0, 2.0),
            Vec3::new(0.3, -0.0, 0.4),
        ];
        for _ in 0..2000 {
            // Random bit patterns, and random ordinary numbers.
            vectors.push(Vec3::new(
                f32::from_bits(next()),
                f32::from_bits(next()),
                f32::from_bits(next()),
            ));
            let small = |bits: u32| (bits >> 8) as f32 / (1 << 24) as f32 * 20.0 - 10.0;
            vectors.push(Vec3::new(small(next()), small(next()), small(next())));
        }
        vectors
    }

    #[track_caller]
    fn same(got: Vec3, expected: Vec3) {
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        // NaNs may differ in payload and sign; everything else bit for bit.
        let nan = |v: Vec3| v.to_array().map(f32::is_nan);
        assert_eq!(nan(got), nan(expected), "{got} against {expected}");
        for ((g, e), is_nan) in bits(got).into_iter().zip(bits(expected)).zip(nan(got)) {
            assert!(is_nan || g == e, "{got} against {expected}");
        }
    }

    #[test]
    fn lanes_compute_what_vec3_computes_bit_for_bit() {
        let vectors = awkward_vectors();
        for window in vectors.windows(8).step_by(3) {
            let a: [Vec3; 4] = window[..4].try_into().unwrap();
            let b: [Vec3; 4] = window[4..].try_into().unwrap();
            let (la, lb) = (Vec3x4::gather(a.each_ref()), Vec3x4::gather(b.each_ref()));
            let s = Vec4::from_array(b.map(|v| v.y));
            for j in 0..4 {
                assert_eq!(
                    la.lane(j).to_array().map(f32::to_bits),
                    a[j].to_array().map(f32::to_bits)
                );
                same((la + lb).lane(j), a[j] + b[j]);
                same((la - lb).lane(j), a[j] - b[j]);
                same((la * lb).lane(j), a[j] * b[j]);
                same((la * s).lane(j), a[j] * b[j].y);
                same((la / s).lane(j), a[j] / b[j].y);
                same((-la).lane(j), -a[j]);
                same(la.normalize_or_zero().lane(j), a[j].normalize_or_zero());
                let dot = la.dot(lb)[j];
                let expected = a[j].dot(b[j]);
                assert!(dot.to_bits() == expected.to_bits() || (dot.is_nan() && expected.is_nan()));
                let m = la.abs_max_element()[j];
                let expected = a[j].abs().max_element();
                assert!(m.to_bits() == expected.to_bits() || (m.is_nan() && expected.is_nan()));
            }
        }
    }

    #[test]
    fn select_and_masks_pick_lanes() {
        let a = Vec3x4::splat(Vec3::ONE);
        let b = Vec3x4::splat(Vec3::NEG_ONE);
        for m in 0..16 {
            assert_eq!(bits(mask(m)), m);
            let picked = Vec3x4::select(mask(m), a, b);
            for j in 0..4 {
                let expected = if m & (1 << j) != 0 {
                    Vec3::ONE
                } else {
                    Vec3::NEG_ONE
                };
                assert_eq!(picked.lane(j), expected);
            }
        }
    }
}
