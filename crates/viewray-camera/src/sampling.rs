//! Mapping lens samples to the aperture: the unit disk of a round lens, or the regular
//! polygon of a lens with blades.

use std::f64::consts::{FRAC_PI_4, PI, TAU};

use glam::DVec2;

/// Maps a point of the unit square `[0, 1)^2` to the unit disk by Shirley and Chiu's
/// concentric mapping, which keeps strata compact and adjacent points adjacent.
///
/// ```text
/// (a, b) = 2 p - 1
/// |a| >= |b|: r = a, theta = (pi/4) (b / a)
/// otherwise:  r = b, theta = pi/2 - (pi/4) (a / b)
/// disk point = r (cos theta, sin theta)
/// ```
///
/// The square's centre `(0.5, 0.5)` maps to the disk's centre.
///
/// The second rule's point is `r (sin phi, cos phi)` with `phi = (pi/4) (a / b)`, the
/// same point, and both angles lie in `[-pi/4, pi/4]`, where `sin_cos_quarter` needs no
/// range reduction: every thin-lens sample maps one lens point, and the system's
/// `sincos` had been a ninth of a thin-lens render's time.
pub fn sample_unit_disk_concentric(p: DVec2) -> DVec2 {
    let offset = 2.0 * p - DVec2::ONE;
    if offset == DVec2::ZERO {
        return DVec2::ZERO;
    }
    // On the diagonals (|a| = |b|) both rules give the same point.
    if offset.x.abs() >= offset.y.abs() {
        let (sin, cos) = sin_cos_quarter(FRAC_PI_4 * (offset.y / offset.x));
        offset.x * DVec2::new(cos, sin)
    } else {
        let (sin, cos) = sin_cos_quarter(FRAC_PI_4 * (offset.x / offset.y));
        offset.y * DVec2::new(sin, cos)
    }
}

/// `(sin x, cos x)` for `|x| <= pi/4`, within an ulp: the polynomial kernels of fdlibm
/// (`__kernel_sin` and `__kernel_cos`, as in musl and Rust's `libm`), written with plain
/// multiplications and additions, never fused, so that they give the same bits on every
/// machine (a system's `sincos` may differ from one C library to the next).
#[inline]
pub(crate) fn sin_cos_quarter(x: f64) -> (f64, f64) {
    // fdlibm's `sin` and `cos` below 2^-27, where `x` and 1 are the rounded values (and
    // `sin(-0)` is `-0`, which the polynomial would make `+0`).
    if x.abs() < 1.0 / (1u64 << 27) as f64 {
        return (x, 1.0);
    }
    sin_cos_kernels(x)
}

/// The coefficients `S1..S6` of fdlibm's `__kernel_sin`.
const KERNEL_SIN: [f64; 6] = [
    -1.666_666_666_666_663_2e-1,
    8.333_333_333_322_49e-3,
    -1.984_126_982_985_795e-4,
    2.755_731_370_707_006_8e-6,
    -2.505_076_025_340_686_3e-8,
    1.589_690_995_211_55e-10,
];

/// The coefficients `C1..C6` of fdlibm's `__kernel_cos`.
const KERNEL_COS: [f64; 6] = [
    4.166_666_666_666_66e-2,
    -1.388_888_888_887_411e-3,
    2.480_158_728_947_673e-5,
    -2.755_731_435_139_066_3e-7,
    2.087_572_321_298_175e-9,
    -1.135_964_755_778_819_5e-11,
];

/// fdlibm's `__kernel_sin(x, 0, 0)` and `__kernel_cos(x, 0)` for `|x| <= pi/4`, without
/// the small-angle rule of [`sin_cos_quarter`].
#[inline(always)]
fn sin_cos_kernels(x: f64) -> (f64, f64) {
    let [s1, s2, s3, s4, s5, s6] = KERNEL_SIN;
    let [c1, c2, c3, c4, c5, c6] = KERNEL_COS;
    let z = x * x;
    // __kernel_sin(x, 0, 0).
    let r = s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)));
    let sin = x + z * x * (s1 + z * r);
    // __kernel_cos(x, 0).
    let r = z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * c6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let cos = w + (((1.0 - w) - hz) + z * r);
    (sin, cos)
}

/// Four lens samples at once, in the lanes of AVX2 registers:
/// [`sample_unit_disk_concentric`] of each lane's point `(x, y)`, bit for bit.
///
/// The same operations on every lane in the same order, the rule's branches made
/// selections (blends): each lane divides the smaller offset by the larger (`b / a` or
/// `a / b`), takes both quarter kernels of `pi/4` times that, and scales `(cos, sin)` or
/// `(sin, cos)` by the larger; the disk's centre is selected where both offsets are 0.
/// One at a time, a thin-lens sample's iris had been about 70 instructions.
///
/// The kernels' small-angle rule (`(x, 1)` below `2^-27`) is needed only at `x = 0`:
/// below `2^-27` the polynomials already round to `x` and 1 (the first correction of
/// `sin` is under a sixth of an ulp of `x` there, of `cos` under a quarter of an ulp of
/// 1), except that `sin(-0)` would be `+0`. So the lanes select `x` only where `x` is 0.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) fn sample_unit_disk_concentric_avx2(x: F64x4, y: F64x4) -> (F64x4, F64x4) {
    use std::arch::x86_64::{
        _CMP_EQ_OQ, _CMP_GE_OQ, _mm256_and_pd, _mm256_blendv_pd, _mm256_cmp_pd, _mm256_div_pd,
        _mm256_mul_pd, _mm256_set1_pd, _mm256_setzero_pd, _mm256_sub_pd,
    };
    let (two, one, zero) = (
        _mm256_set1_pd(2.0),
        _mm256_set1_pd(1.0),
        _mm256_setzero_pd(),
    );
    let a = _mm256_sub_pd(_mm256_mul_pd(two, x), one);
    let b = _mm256_sub_pd(_mm256_mul_pd(two, y), one);
    let wide = _mm256_cmp_pd::<_CMP_GE_OQ>(abs_avx2(a), abs_avx2(b));
    // `_mm256_blendv_pd(if_not, if_so, mask)`.
    let r = _mm256_blendv_pd(b, a, wide);
    let q = _mm256_blendv_pd(a, b, wide);
    let angle = _mm256_mul_pd(_mm256_set1_pd(FRAC_PI_4), _mm256_div_pd(q, r));
    let (sin, cos) = sin_cos_kernels_avx2(angle);
    let sin = _mm256_blendv_pd(sin, angle, _mm256_cmp_pd::<_CMP_EQ_OQ>(angle, zero));
    let first = _mm256_blendv_pd(sin, cos, wide);
    let second = _mm256_blendv_pd(cos, sin, wide);
    let centre = _mm256_and_pd(
        _mm256_cmp_pd::<_CMP_EQ_OQ>(a, zero),
        _mm256_cmp_pd::<_CMP_EQ_OQ>(b, zero),
    );
    (
        _mm256_blendv_pd(_mm256_mul_pd(r, first), zero, centre),
        _mm256_blendv_pd(_mm256_mul_pd(r, second), zero, centre),
    )
}

/// Four `f64` lanes of an AVX register.
#[cfg(target_arch = "x86_64")]
pub(crate) type F64x4 = std::arch::x86_64::__m256d;

/// Four `f64` lanes in memory.
#[cfg(target_arch = "x86_64")]
pub(crate) type Lanes = [f64; 4];

/// The lanes of `values` in a register.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) fn load(values: &Lanes) -> F64x4 {
    std::arch::x86_64::_mm256_set_pd(values[3], values[2], values[1], values[0])
}

/// The lanes of `register` in memory.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
pub(crate) fn store(register: F64x4) -> Lanes {
    use std::arch::x86_64::{
        _mm_cvtsd_f64, _mm_unpackhi_pd, _mm256_castpd256_pd128, _mm256_extractf128_pd,
    };
    let (low, high) = (
        _mm256_castpd256_pd128(register),
        _mm256_extractf128_pd::<1>(register),
    );
    [
        _mm_cvtsd_f64(low),
        _mm_cvtsd_f64(_mm_unpackhi_pd(low, low)),
        _mm_cvtsd_f64(high),
        _mm_cvtsd_f64(_mm_unpackhi_pd(high, high)),
    ]
}

/// `|x|` of each lane: its sign bit cleared, as `f64::abs`.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn abs_avx2(x: F64x4) -> F64x4 {
    use std::arch::x86_64::{_mm256_and_pd, _mm256_castsi256_pd, _mm256_set1_epi64x};
    _mm256_and_pd(x, _mm256_castsi256_pd(_mm256_set1_epi64x(i64::MAX)))
}

/// [`sin_cos_kernels`] of each lane: the same multiplications and additions in the same
/// order, never fused.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
#[inline]
fn sin_cos_kernels_avx2(x: F64x4) -> (F64x4, F64x4) {
    use std::arch::x86_64::{_mm256_add_pd, _mm256_mul_pd, _mm256_set1_pd, _mm256_sub_pd};
    let c = |value| _mm256_set1_pd(value);
    let (add, mul, sub) = (_mm256_add_pd, _mm256_mul_pd, _mm256_sub_pd);
    let [s1, s2, s3, s4, s5, s6] = KERNEL_SIN.map(c);
    let [c1, c2, c3, c4, c5, c6] = KERNEL_COS.map(c);
    let z = mul(x, x);
    // S2 + z * (S3 + z * (S4 + z * (S5 + z * S6))).
    let r = add(
        s2,
        mul(z, add(s3, mul(z, add(s4, mul(z, add(s5, mul(z, s6))))))),
    );
    // x + z * x * (S1 + z * r).
    let sin = add(x, mul(mul(z, x), add(s1, mul(z, r))));
    // z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))).
    let inner = add(c4, mul(z, add(c5, mul(z, c6))));
    let r = mul(z, add(c1, mul(z, add(c2, mul(z, add(c3, mul(z, inner)))))));
    let hz = mul(c(0.5), z);
    let w = sub(c(1.0), hz);
    // w + (((1 - w) - hz) + z * r).
    let cos = add(w, add(sub(sub(c(1.0), w), hz), mul(z, r)));
    (sin, cos)
}

/// Maps a point of the unit square `[0, 1)^2` to the regular polygon of `blades` corners
/// inscribed in the unit circle and turned by `rotation` (radians), uniformly: equal
/// areas of the square go to equal areas of the polygon.
///
/// The polygon is Blender Cycles' (`regular_polygon_sample`): its corners lie on the unit
/// circle at the angles `rotation + (2k + 1) pi / N`, so the middle of one edge lies at
/// the angle `rotation` from `u` (toward `v`), at the distance `cos(pi / N)` from the
/// centre. Cycles picks the polygon's wedge from the first number and a point of that
/// triangle from both; here the square goes first to the unit disk by the concentric
/// mapping (the disk point at radius `r` and angle `theta`), and then
///
/// ```text
/// x = ((theta - rotation) / (2 pi / N) + 1/2) mod N,   k = floor(x),   t = x - k
/// a = rotation + (2k - 1) pi / N,   b = rotation + (2k + 1) pi / N
/// point = r ((1 - t) (cos a, sin a) + t (cos b, sin b))
/// ```
///
/// the wedge `k` of the disk to the polygon's triangle between the centre and the edge
/// from corner `a` to corner `b`. `r^2` and `theta` are uniform and independent on the
/// disk, and `r^2` and `t` are the same in the triangle, so the density is the same
/// everywhere in the polygon (Cycles' density, from other points of the square). What
/// the concentric start keeps: the square's centre `(0.5, 0.5)` is the polygon's centre
/// (the lens centre of one sample per pixel), neighbouring points stay neighbours, and
/// the square's edges land exactly on the polygon's edges.
pub fn sample_regular_polygon(p: DVec2, blades: u32, rotation: f64) -> DVec2 {
    let disk = sample_unit_disk_concentric(p);
    let (r, theta) = (disk.length(), disk.y.atan2(disk.x));
    let corners = f64::from(blades);
    let x = ((theta - rotation) / (TAU / corners) + 0.5).rem_euclid(corners);
    let k = x.floor();
    let t = x - k;
    let corner = |j: f64| {
        let (sin, cos) = (rotation + j * PI / corners).sin_cos();
        DVec2::new(cos, sin)
    };
    r * corner(2.0 * k - 1.0).lerp(corner(2.0 * k + 1.0), t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check(p: (f64, f64), expected: (f64, f64)) {
        let got = sample_unit_disk_concentric(DVec2::new(p.0, p.1));
        assert!(
            got.abs_diff_eq(DVec2::new(expected.0, expected.1), 1e-12),
            "{p:?} -> {got}, expected {expected:?}"
        );
    }

    #[test]
    fn the_quarter_kernels_are_within_an_ulp_of_the_system() {
        // Every angle the concentric mapping asks for lies in [-pi/4, pi/4]. Each is
        // within an ulp of the true value, so within two of each other.
        let steps = 200_000;
        for i in 0..=steps {
            let x = FRAC_PI_4 * (2.0 * f64::from(i) / f64::from(steps) - 1.0);
            let (sin, cos) = sin_cos_quarter(x);
            let (want_sin, want_cos) = x.sin_cos();
            let ulps = |got: f64, want: f64| (got.to_bits() as i64 - want.to_bits() as i64).abs();
            assert!(
                ulps(sin, want_sin) <= 2,
                "sin {x}: {sin} against {want_sin}"
            );
            assert!(
                ulps(cos, want_cos) <= 2,
                "cos {x}: {cos} against {want_cos}"
            );
        }
        assert_eq!(sin_cos_quarter(0.0), (0.0, 1.0));
        assert_eq!(sin_cos_quarter(-0.0).0.to_bits(), (-0.0f64).to_bits());
    }

    /// The concentric mapping in AVX2 lanes is the mapping one point at a time, bit for
    /// bit, in every lane: at the centre, on the diagonals and the axes, a hair off
    /// them, near the square's edges, with tiny offsets of either sign, and at random.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn concentric_lanes_are_the_single_mapping_bit_for_bit() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        /// The lanes' disk points of four points.
        #[target_feature(enable = "avx2")]
        fn lanes(x: Lanes, y: Lanes) -> (Lanes, Lanes) {
            let (disk_x, disk_y) = sample_unit_disk_concentric_avx2(load(&x), load(&y));
            (store(disk_x), store(disk_y))
        }
        // A xorshift64 of a fixed seed.
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut unit = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let tiny = [
            0.0,
            1e-300,
            1e-20,
            3.7e-9,
            2f64.powi(-28),
            2f64.powi(-27),
            1e-6,
        ];
        let mut points = vec![(0.5, 0.5), (0.0, 0.0), (1.0, 1.0), (0.0, 1.0), (1.0, 0.0)];
        for &t in &tiny {
            for (a, b) in [(t, 0.3), (0.3, t), (-t, 0.3), (0.3, -t), (t, -t), (-t, t)] {
                points.push((0.5 + a, 0.5 + b));
                points.push((0.5 + b, 0.5 - a));
            }
        }
        for _ in 0..4000 {
            let (p, q) = (unit(), unit());
            let hair = f64::EPSILON * (unit() - 0.5);
            points.extend([
                (p, q),
                (p, p),
                (p, 1.0 - p),
                (0.5, p),
                (p, 0.5),
                (p, p + hair),
            ]);
        }
        let bits = |p: DVec2| p.to_array().map(f64::to_bits);
        // Each point in each lane, beside three others.
        for start in 0..points.len() {
            let four: [(f64, f64); 4] =
                std::array::from_fn(|i| points[(start + i * 7) % points.len()]);
            // SAFETY: the processor runs AVX2 (asked above), all `lanes` needs.
            #[allow(unsafe_code)]
            let (disk_x, disk_y) = unsafe { lanes(four.map(|p| p.0), four.map(|p| p.1)) };
            for (lane, &(x, y)) in four.iter().enumerate() {
                let single = sample_unit_disk_concentric(DVec2::new(x, y));
                let got = DVec2::new(disk_x[lane], disk_y[lane]);
                assert_eq!(bits(got), bits(single), "({x}, {y}) in lane {lane}");
            }
        }
    }

    #[test]
    fn square_edges_map_to_the_circle() {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        check((0.5, 0.5), (0.0, 0.0));
        check((1.0, 0.5), (1.0, 0.0));
        check((0.0, 0.5), (-1.0, 0.0));
        check((0.5, 1.0), (0.0, 1.0));
        check((0.5, 0.0), (0.0, -1.0));
        check((1.0, 1.0), (h, h));
        check((0.0, 0.0), (-h, -h));
        check((0.75, 0.5), (0.5, 0.0));
    }

    #[test]
    fn points_off_the_axes_and_diagonals_keep_their_angle_ratio() {
        // cos 15 = (sqrt 6 + sqrt 2) / 4, sin 15 = (sqrt 6 - sqrt 2) / 4 (degrees).
        let (c, s) = (
            (6f64.sqrt() + 2f64.sqrt()) / 4.0,
            (6f64.sqrt() - 2f64.sqrt()) / 4.0,
        );
        // (a, b) = (0.75, 0.25): r = 0.75, theta = (pi/4)(1/3) = 15 degrees.
        check((0.875, 0.625), (0.75 * c, 0.75 * s));
        // (a, b) = (0.25, 0.75): r = 0.75, theta = 90 - 45/3 = 75 degrees.
        check((0.625, 0.875), (0.75 * s, 0.75 * c));
        // (a, b) = (-0.75, -0.25): r = -0.75, theta = 15 degrees: the opposite point.
        check((0.125, 0.375), (-0.75 * c, -0.75 * s));
        // (a, b) = (0.5, -0.5), a diagonal: r = 0.5, theta = -45 degrees.
        let h = std::f64::consts::FRAC_1_SQRT_2;
        check((0.75, 0.25), (0.5 * h, -0.5 * h));
    }
}
