//! Mapping lens samples to the unit disk.

use std::f64::consts::FRAC_PI_4;

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
pub fn sample_unit_disk_concentric(p: DVec2) -> DVec2 {
    let offset = 2.0 * p - DVec2::ONE;
    if offset == DVec2::ZERO {
        return DVec2::ZERO;
    }
    // On the diagonals (|a| = |b|) both rules give the same point.
    let (r, theta) = if offset.x.abs() >= offset.y.abs() {
        (offset.x, FRAC_PI_4 * (offset.y / offset.x))
    } else {
        (
            offset.y,
            2.0 * FRAC_PI_4 - FRAC_PI_4 * (offset.x / offset.y),
        )
    };
    let (sin, cos) = theta.sin_cos();
    r * DVec2::new(cos, sin)
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
