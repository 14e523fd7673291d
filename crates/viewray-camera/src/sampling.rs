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
    const S1: f64 = -1.666_666_666_666_663_2e-1;
    const S2: f64 = 8.333_333_333_322_49e-3;
    const S3: f64 = -1.984_126_982_985_795e-4;
    const S4: f64 = 2.755_731_370_707_006_8e-6;
    const S5: f64 = -2.505_076_025_340_686_3e-8;
    const S6: f64 = 1.589_690_995_211_55e-10;
    const C1: f64 = 4.166_666_666_666_66e-2;
    const C2: f64 = -1.388_888_888_887_411e-3;
    const C3: f64 = 2.480_158_728_947_673e-5;
    const C4: f64 = -2.755_731_435_139_066_3e-7;
    const C5: f64 = 2.087_572_321_298_175e-9;
    const C6: f64 = -1.135_964_755_778_819_5e-11;
    // fdlibm's `sin` and `cos` below 2^-27, where `x` and 1 are the rounded values (and
    // `sin(-0)` is `-0`, which the polynomial would make `+0`).
    if x.abs() < 1.0 / (1u64 << 27) as f64 {
        return (x, 1.0);
    }
    let z = x * x;
    // __kernel_sin(x, 0, 0).
    let r = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    let sin = x + z * x * (S1 + z * r);
    // __kernel_cos(x, 0).
    let r = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let cos = w + (((1.0 - w) - hz) + z * r);
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
