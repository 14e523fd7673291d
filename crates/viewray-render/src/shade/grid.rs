//! A material's colour with its grid lines: lines of constant world coordinate,
//! box-filtered over the sample's footprint so that they stay smooth to the horizon.

use glam::Vec3;
use viewray_geometry::Hit;
use viewray_scene::{Grid, Material};

use super::footprint::Footprint;
use super::record::Recorder;
use crate::trace::GridLines;

/// The surface colour of `material` at `hit`: its colour, with grid lines over it; for
/// a recorder that records (`R::ACTIVE`), how the lines were mixed in, into `lines`.
///
/// Grid lines are lines of constant world coordinate every `spacing` along the two
/// world axes closest to the surface's plane (the axis nearest the normal is left out),
/// `line_width` wide, centred on the multiples of `spacing`. Each sample averages the
/// lines over its own footprint on the surface (`footprint`, computed only for grid
/// materials), so they stay smooth toward the horizon; without a footprint (reflected
/// rays) they are point-sampled.
#[inline]
pub(super) fn surface_color<R: Recorder>(
    material: &Material,
    hit: &Hit,
    footprint: impl FnOnce() -> Footprint,
    lines: &mut Option<GridLines>,
) -> Vec3 {
    let Some(grid) = material.grid else {
        return material.color;
    };
    let n = hit.normal.abs();
    let (a, b) = if n.x >= n.y && n.x >= n.z {
        (1, 2)
    } else if n.y >= n.z {
        (0, 2)
    } else {
        (0, 1)
    };
    let widths = match footprint() {
        Footprint::Point => Vec3::ZERO,
        Footprint::Area(dx, dy) => dx.abs() + dy.abs(),
        Footprint::Unbounded => Vec3::INFINITY,
    };
    let coverage_a = line_coverage(hit.point[a], widths[a], &grid);
    let coverage_b = line_coverage(hit.point[b], widths[b], &grid);
    let coverage = 1.0 - (1.0 - coverage_a) * (1.0 - coverage_b);
    let color = material.color.lerp(grid.color, coverage);
    if R::ACTIVE {
        *lines = Some(GridLines {
            axes: [a, b],
            footprint: [widths[a], widths[b]],
            coverage: [coverage_a, coverage_b],
            total: coverage,
            line_color: grid.color,
            base: material.color,
            color,
        });
    }
    color
}

/// The fraction of the interval `[x - width/2, x + width/2]` covered by grid lines
/// (centred on multiples of `spacing`, `line_width` wide): the box-filtered line
/// pattern. Width 0 point-samples it; a width of many spacings gives the average,
/// `line_width / spacing`.
#[inline]
fn line_coverage(x: f32, width: f32, grid: &Grid) -> f32 {
    let spacing = grid.spacing;
    let half = 0.5 * grid.line_width.min(spacing);
    // The offset from the nearest line's centre, in [-spacing/2, spacing/2].
    let d = x - round(x / spacing) * spacing;
    if width <= 1e-6 * spacing {
        return f32::from(u8::from(d.abs() < half));
    }
    if width >= 64.0 * spacing {
        return 2.0 * half / spacing;
    }
    let (a, b) = (d - 0.5 * width, d + 0.5 * width);
    if width < spacing {
        // The window meets at most the nearest line and its two neighbours.
        if a >= -half && b <= half {
            return 1.0;
        }
        // Between two lines, touching neither (most samples): every overlap below is
        // zero, and so is the coverage. (The far edge's test decides only where rounding
        // put `d` a little past half a spacing, far from the origin: there a window
        // can reach the next line.)
        if (a >= half && b <= spacing - half) || (a >= -spacing + half && b <= -half) {
            return 0.0;
        }
        let overlap = |centre: f32| (b.min(centre + half) - a.max(centre - half)).max(0.0);
        return ((overlap(-spacing) + overlap(0.0) + overlap(spacing)) / width).clamp(0.0, 1.0);
    }
    // Wider windows: the pattern's integral from 0 to y, with lines shifted to occupy
    // [k spacing, k spacing + 2 half), is k 2 half + min(y - k spacing, 2 half) for
    // k = floor(y / spacing); the coverage is its difference over the window / width.
    let integral = |y: f32| {
        let k = floor(y / spacing);
        (k, (y - k * spacing).clamp(0.0, spacing).min(2.0 * half))
    };
    let (k0, m0) = integral(a + half);
    let (k1, m1) = integral(b + half);
    (((k1 - k0) * 2.0 * half + m1 - m0) / width).clamp(0.0, 1.0)
}

/// Floats from 2^23 up in magnitude are all integers (and NaN and the infinities round
/// to themselves), so [`round`] and [`floor`] return them as they are.
const ALL_INTEGERS: f32 = 8_388_608.0;

/// `x.round()`, half-way cases away from zero, bit for bit (a NaN stays a NaN, though
/// perhaps not as quiet a one), without the call into the
/// maths library that `f32::round` makes on CPUs before SSE4.1 (every grid sample
/// rounds once). Below 2^23 the truncation `x as i32` is exact, and so are `x - t`
/// and `t +- 1`.
#[inline]
fn round(x: f32) -> f32 {
    if x.is_nan() || x.abs() >= ALL_INTEGERS {
        return x;
    }
    // Truncate toward zero, keeping the sign of a zero result (`-0.3` rounds to `-0`).
    let t = ((x as i32) as f32).copysign(x);
    if (x - t).abs() >= 0.5 {
        t + 1.0f32.copysign(x)
    } else {
        t
    }
}

/// `x.floor()`, bit for bit, without a call into the maths library (see [`round`]).
#[inline]
fn floor(x: f32) -> f32 {
    if x.is_nan() || x.abs() >= ALL_INTEGERS {
        return x;
    }
    let t = ((x as i32) as f32).copysign(x);
    if t > x { t - 1.0 } else { t }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check_rounding(x: f32) {
        if x.is_nan() {
            assert!(round(x).is_nan() && floor(x).is_nan());
            return;
        }
        assert_eq!(round(x).to_bits(), x.round().to_bits(), "round({x:e})");
        assert_eq!(floor(x).to_bits(), x.floor().to_bits(), "floor({x:e})");
    }

    #[test]
    fn round_and_floor_are_the_standard_ones_bit_for_bit() {
        let edges = [
            0.0,
            0.5,
            1.5,
            2.5,
            0.499_999_97,
            0.3,
            1.0,
            8_388_607.5,
            8_388_608.0,
            8_388_609.0,
            1e30,
            f32::MIN_POSITIVE,
            1e-45,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
        ];
        for x in edges {
            check_rounding(x);
            check_rounding(-x);
        }
        // Every float of a few binades around the integers, and a spread of bit patterns.
        let mut bits = 0x3e00_0000_u32; // 0.125
        while bits < 0x4b80_0000 {
            // up to 2^24
            check_rounding(f32::from_bits(bits));
            check_rounding(-f32::from_bits(bits));
            bits += 97;
        }
        let mut state = 0x9e37_79b9_u32;
        for _ in 0..1_000_000 {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            check_rounding(f32::from_bits(state));
        }
    }

    const GRID: Grid = Grid {
        spacing: 1.0,
        line_width: 0.1,
        color: Vec3::ZERO,
    };

    #[track_caller]
    fn check(x: f32, width: f32, expected: f32) {
        check_grid(&GRID, x, width, expected);
    }

    #[track_caller]
    fn check_grid(grid: &Grid, x: f32, width: f32, expected: f32) {
        let got = line_coverage(x, width, grid);
        assert!(
            (got - expected).abs() < 1e-5,
            "x {x} width {width}: {got}, expected {expected}"
        );
    }

    #[test]
    fn line_coverage_is_the_box_filtered_pattern() {
        // Point samples: on a line within 0.05 of an integer.
        check(0.0, 0.0, 1.0);
        check(2.04, 0.0, 1.0);
        check(-3.04, 0.0, 1.0);
        check(0.5, 0.0, 0.0);
        check(0.06, 0.0, 0.0);
        // A footprint of one spacing always covers one line.
        for x in [0.0, 0.3, 0.77, -5.2] {
            check(x, 1.0, 0.1);
        }
        // Half a line in a window of 0.1 centred on a line's edge.
        check(0.05, 0.1, 0.5);
        // Entirely inside a line, or entirely between lines.
        check(1.0, 0.05, 1.0);
        check(1.5, 0.5, 0.0);
        // Huge footprints: the average.
        check(0.3, 1e9, 0.1);
        check(0.3, f32::INFINITY, 0.1);
    }

    #[test]
    fn line_coverage_follows_the_grid_spacing() {
        // Lines 0.2 wide every 2 units: a spacing of 1 would hide a position divided
        // where it should be multiplied.
        let grid = Grid {
            spacing: 2.0,
            line_width: 0.2,
            color: Vec3::ZERO,
        };
        let check = |x, width, expected| check_grid(&grid, x, width, expected);
        // Point samples: on a line within 0.1 of a multiple of 2.
        check(0.0, 0.0, 1.0);
        check(4.08, 0.0, 1.0);
        check(-6.09, 0.0, 1.0);
        check(1.0, 0.0, 0.0);
        check(2.12, 0.0, 0.0);
        // A footprint of one spacing covers a tenth; half a line at a line's edge.
        for x in [0.0, 0.7, 1.5, -3.3] {
            check(x, 2.0, 0.1);
        }
        check(2.1, 0.2, 0.5);
        check(1.0, 0.5, 0.0);
        // Two and a half spacings around a midpoint, [-1.5, 3.5]: the lines at 0 and 2.
        check(1.0, 5.0, 0.08);
    }

    /// Windows narrower than a spacing: the coverage is the window's overlap with the
    /// nearest line and its two neighbours, bit for bit, also where a window lies between
    /// two lines and the overlaps are not computed. Windows are placed with an edge within
    /// ulps of a line's edge, also far from the origin, where the offset from the nearest
    /// line can come out a little over half a spacing.
    #[test]
    fn narrow_windows_cover_the_three_nearest_lines() {
        let grids = [
            GRID,
            Grid {
                spacing: 2.0,
                line_width: 0.2,
                color: Vec3::ZERO,
            },
            Grid {
                spacing: 0.25,
                line_width: 0.0,
                color: Vec3::ZERO,
            },
            // Spacings that are not powers of two round `x / spacing`.
            Grid {
                spacing: 0.1,
                line_width: 0.006,
                color: Vec3::ZERO,
            },
            Grid {
                spacing: 3.0,
                line_width: 0.4,
                color: Vec3::ZERO,
            },
        ];
        let mut state = 0x2545_f491_u32;
        let mut random = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32
        };
        let mut beyond_half = 0;
        for grid in &grids {
            let (spacing, half) = (grid.spacing, 0.5 * grid.line_width.min(grid.spacing));
            for _ in 0..100_000 {
                // Up to 2,000 spacings from the origin, on a line, half-way between two,
                // or anywhere.
                let line = (4000.0 * random()).floor() - 2000.0;
                let x = match (random() * 3.0) as u32 {
                    0 => line * spacing,
                    1 => (line + 0.5) * spacing,
                    _ => (line + random()) * spacing,
                };
                let d = x - round(x / spacing) * spacing;
                if d.abs() > 0.5 * spacing {
                    beyond_half += 1;
                }
                // Windows anywhere, and windows whose left edge is on the right edge of
                // the nearest line or of the one before, or whose right edge is on the
                // left edge of the nearest line or of the one after.
                let edges = [
                    spacing * (1e-5 + 0.99 * random()),
                    2.0 * (d - half),
                    2.0 * (d + spacing - half),
                    2.0 * (-half - d),
                    2.0 * (spacing - half - d),
                ];
                for edge in edges {
                    let nudge = (random() * 8.0) as u32;
                    let width = f32::from_bits(edge.to_bits().wrapping_add(nudge).wrapping_sub(4));
                    if !(width > 1e-6 * spacing && width < spacing) {
                        continue;
                    }
                    let (a, b) = (d - 0.5 * width, d + 0.5 * width);
                    let expected = if a >= -half && b <= half {
                        1.0
                    } else {
                        let overlap =
                            |centre: f32| (b.min(centre + half) - a.max(centre - half)).max(0.0);
                        ((overlap(-spacing) + overlap(0.0) + overlap(spacing)) / width)
                            .clamp(0.0, 1.0)
                    };
                    let got = line_coverage(x, width, grid);
                    assert_eq!(
                        got.to_bits(),
                        expected.to_bits(),
                        "x {x} width {width}: {got}, expected {expected}"
                    );
                }
            }
        }
        assert!(beyond_half > 0, "no offset past half a spacing was tried");
    }
}
