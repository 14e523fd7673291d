//! A material's colour with its grid lines: lines of constant world coordinate,
//! box-filtered over the sample's footprint so that they stay smooth to the horizon.
//! [`surface_color`] is the rule for one sample; Lit batches use [`surface_colors`], the
//! same operations four samples at a time in lanes.

use glam::{BVec4A, Vec3, Vec4};
use viewray_geometry::Hit;
use viewray_scene::{Grid, Material};

use super::footprint::Footprint;
use super::record::Recorder;
use crate::lanes::Vec3x4;
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
    let widths = footprint().widths();
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

/// [`surface_color`] of four samples at once: lane `j` is sample `j`, of material
/// `materials[j]`, hit at lane `j` of `point` where the geometric normal is lane `j` of
/// `normal`. The widths of the footprints ([`Footprint::widths`]) are asked of `widths`
/// only if a material has grid lines, for the lanes whose bit is set in its argument
/// (its other lanes may hold anything).
///
/// Every lane does the scalar code's operations in the same order (its branches become
/// selects: each lane takes the value its branch would have returned), so it holds the
/// bits [`surface_color`] gives its sample, as the tests check; recorders take the
/// scalar path.
#[inline]
pub(super) fn surface_colors(
    materials: [&Material; 4],
    point: Vec3x4,
    normal: Vec3x4,
    widths: impl FnOnce(u32) -> Vec3x4,
) -> Vec3x4 {
    let grid_lanes = (0..4)
        .filter(|&j| materials[j].grid.is_some())
        .fold(0, |lanes, j| lanes | 1 << j);
    if grid_lanes == 0 {
        return Vec3x4::gather(materials.map(|m| &m.color));
    }
    // Most groups lie on one material with lines. Lanes without lines compute with a
    // placeholder grid and keep their colour.
    let one_material = grid_lanes == 0b1111
        && materials[1..]
            .iter()
            .all(|m| std::ptr::eq(*m, materials[0]));
    let (color, spacing, half, line_color) = if one_material {
        let (material, grid) = (materials[0], materials[0].grid.unwrap_or(NO_GRID));
        (
            Vec3x4::splat(material.color),
            Vec4::splat(grid.spacing),
            Vec4::splat(0.5 * grid.line_width.min(grid.spacing)),
            Vec3x4::splat(grid.color),
        )
    } else {
        let grids = materials.map(|m| m.grid.unwrap_or(NO_GRID));
        (
            Vec3x4::gather(materials.map(|m| &m.color)),
            Vec4::from_array(grids.map(|g| g.spacing)),
            Vec4::from_array(grids.map(|g| 0.5 * g.line_width.min(g.spacing))),
            Vec3x4::gather(grids.each_ref().map(|g| &g.color)),
        )
    };
    // The two axes closest to the surface's plane: (y, z) where x is nearest the normal,
    // (x, z) where y is, else (x, y).
    let n = Vec3x4 {
        x: normal.x.abs(),
        y: normal.y.abs(),
        z: normal.z.abs(),
    };
    let along_x = n.x.cmpge(n.y) & n.x.cmpge(n.z);
    let second_is_z = along_x | n.y.cmpge(n.z);
    let first = |v: Vec3x4| Vec4::select(along_x, v.y, v.x);
    let second = |v: Vec3x4| Vec4::select(second_is_z, v.z, v.y);
    let widths = widths(grid_lanes);
    let coverage_a = line_coverage_x4(first(point), first(widths), spacing, half);
    let coverage_b = line_coverage_x4(second(point), second(widths), spacing, half);
    let coverage = Vec4::ONE - (Vec4::ONE - coverage_a) * (Vec4::ONE - coverage_b);
    // `Vec3::lerp`: `color (1 - s) + line_color s`.
    let lined = color * (Vec4::ONE - coverage) + line_color * coverage;
    if grid_lanes == 0b1111 {
        lined
    } else {
        Vec3x4::select(crate::lanes::mask(grid_lanes), lined, color)
    }
}

/// What lanes without grid lines compute with.
const NO_GRID: Grid = Grid {
    spacing: 1.0,
    line_width: 0.0,
    color: Vec3::ZERO,
};

/// [`line_coverage`] of four positions `x` and widths `width` on grids of `spacing`
/// with lines `2 half` wide, lane by lane, bit for bit. The cases of the scalar code
/// are masks; the overlaps with the three nearest lines and the integral over wide
/// windows are worked out only if a lane needs them.
#[inline(always)]
fn line_coverage_x4(x: Vec4, width: Vec4, spacing: Vec4, half: Vec4) -> Vec4 {
    let d = x - round_x4(x / spacing) * spacing;
    let point = width.cmple(Vec4::splat(1e-6) * spacing);
    let huge = width.cmpge(Vec4::splat(64.0) * spacing);
    let (a, b) = (d - Vec4::splat(0.5) * width, d + Vec4::splat(0.5) * width);
    let narrow = width.cmplt(spacing);
    let inside = a.cmpge(-half) & b.cmple(half);
    let between =
        (a.cmpge(half) & b.cmple(spacing - half)) | (a.cmpge(-spacing + half) & b.cmple(-half));
    let decided = point | huge;
    // Narrow windows inside a line cover it all, those between lines nothing.
    let mut coverage = Vec4::select(inside, Vec4::ONE, Vec4::ZERO);
    let overlapping = narrow & !inside & !between & !decided;
    if overlapping.any() {
        let overlap = |centre: Vec4| (b.min(centre + half) - a.max(centre - half)).max(Vec4::ZERO);
        let sum = overlap(-spacing) + overlap(Vec4::ZERO) + overlap(spacing);
        coverage = Vec4::select(overlapping, clamp(sum / width, Vec4::ONE), coverage);
    }
    let wide = !narrow & !decided;
    if wide.any() {
        let two_half = Vec4::splat(2.0) * half;
        let integral = |y: Vec4| {
            let k = floor_x4(y / spacing);
            (k, clamp(y - k * spacing, spacing).min(two_half))
        };
        let (k0, m0) = integral(a + half);
        let (k1, m1) = integral(b + half);
        let covered = (k1 - k0) * Vec4::splat(2.0) * half + m1 - m0;
        coverage = Vec4::select(wide, clamp(covered / width, Vec4::ONE), coverage);
    }
    let average = Vec4::splat(2.0) * half / spacing;
    let on_line = Vec4::select(d.abs().cmplt(half), Vec4::ONE, Vec4::ZERO);
    Vec4::select(point, on_line, Vec4::select(huge, average, coverage))
}

/// Lane by lane, `x.clamp(0.0, max)` as `f32::clamp` does it: `0` below, `max` above,
/// a NaN as it is.
#[inline(always)]
fn clamp(x: Vec4, max: Vec4) -> Vec4 {
    let x = Vec4::select(x.cmplt(Vec4::ZERO), Vec4::ZERO, x);
    Vec4::select(x.cmpgt(max), max, x)
}

/// Lane by lane, [`round`] and [`floor`]'s truncation toward zero: `(x as i32) as f32`
/// with the sign of `x`, for `|x|` below [`ALL_INTEGERS`] (other lanes hold anything),
/// and the mask of those lanes. Adding and taking away 2^23 rounds `|x|` to the nearest
/// integer exactly; one less where that is above `|x|` is its truncation.
#[inline(always)]
fn truncate_x4(x: Vec4) -> (Vec4, BVec4A) {
    let magnitude = x.abs();
    let all_integers = Vec4::splat(ALL_INTEGERS);
    let nearest = (magnitude + all_integers) - all_integers;
    let above = Vec4::select(nearest.cmpgt(magnitude), Vec4::ONE, Vec4::ZERO);
    ((nearest - above).copysign(x), magnitude.cmplt(all_integers))
}

/// Lane by lane, [`round`], bit for bit.
#[inline(always)]
fn round_x4(x: Vec4) -> Vec4 {
    let (t, small) = truncate_x4(x);
    let rounded = Vec4::select(
        (x - t).abs().cmpge(Vec4::splat(0.5)),
        t + Vec4::ONE.copysign(x),
        t,
    );
    Vec4::select(small, rounded, x)
}

/// Lane by lane, [`floor`], bit for bit.
#[inline(always)]
fn floor_x4(x: Vec4) -> Vec4 {
    let (t, small) = truncate_x4(x);
    Vec4::select(small, Vec4::select(t.cmpgt(x), t - Vec4::ONE, t), x)
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
    use crate::shade::NoRecorder;
    use crate::test_numbers::Numbers;

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

    /// Grids of every kind: powers of two and not, lines wider than their spacing (a
    /// solid colour), lines of no width.
    fn grids() -> Vec<Grid> {
        [
            (1.0, 0.1),
            (2.0, 0.2),
            (0.25, 0.0),
            (0.1, 0.006),
            (3.0, 0.4),
            (0.7, 0.05),
            (1.0, 1.5),
            (1e-3, 2e-4),
            (250.0, 1.0),
        ]
        .into_iter()
        .enumerate()
        .map(|(k, (spacing, line_width))| Grid {
            spacing,
            line_width,
            color: Vec3::new(0.1 * k as f32, 0.9 - 0.1 * k as f32, 0.5),
        })
        .collect()
    }

    /// A position on `grid` near what decides its coverage: on a line's centre or edge,
    /// half-way between lines, or anywhere, nudged by a few ulps, up to a million
    /// spacings from the origin (where the offset from the nearest line rounds past half
    /// a spacing).
    fn position(numbers: &mut Numbers, grid: &Grid) -> f32 {
        let (spacing, half) = (grid.spacing, 0.5 * grid.line_width.min(grid.spacing));
        let reach = [10.0, 2000.0, 1e6][numbers.pick(3) as usize];
        let line = ((2.0 * numbers.uniform() - 1.0) * reach).floor();
        let x = match numbers.pick(6) {
            0 => line * spacing,
            1 => line * spacing + half,
            2 => line * spacing - half,
            3 => (line + 0.5) * spacing,
            4 => -0.0,
            _ => (line + numbers.uniform()) * spacing,
        };
        numbers.nudge(x)
    }

    /// A window width at `x` on `grid` near what decides its coverage: none, about the
    /// point-sample limit, one spacing or 64, infinite, huge, or with an edge on a line's
    /// edge (the nearest line or its neighbours), nudged by a few ulps; or anywhere.
    fn width(numbers: &mut Numbers, grid: &Grid, x: f32) -> f32 {
        let (spacing, half) = (grid.spacing, 0.5 * grid.line_width.min(grid.spacing));
        let d = x - round(x / spacing) * spacing;
        let width = match numbers.pick(12) {
            0 => 0.0,
            1 => 1e-6 * spacing,
            2 => spacing,
            3 => 64.0 * spacing,
            4 => f32::INFINITY,
            5 => 1e30,
            6 => 2.0 * (d - half),
            7 => 2.0 * (d + spacing - half),
            8 => 2.0 * (-half - d),
            9 => 2.0 * (spacing - half - d),
            10 => spacing * 100.0 * numbers.uniform(),
            _ => spacing * numbers.uniform(),
        };
        numbers.nudge(width).abs()
    }

    /// Which case of [`line_coverage`] decides a window, for counting that every one was
    /// tried.
    fn case(x: f32, width: f32, grid: &Grid) -> usize {
        let (spacing, half) = (grid.spacing, 0.5 * grid.line_width.min(grid.spacing));
        let d = x - round(x / spacing) * spacing;
        let (a, b) = (d - 0.5 * width, d + 0.5 * width);
        if width <= 1e-6 * spacing {
            0
        } else if width >= 64.0 * spacing {
            1
        } else if width < spacing {
            if a >= -half && b <= half {
                2
            } else if (a >= half && b <= spacing - half) || (a >= -spacing + half && b <= -half) {
                3
            } else {
                4
            }
        } else {
            5
        }
    }

    #[test]
    fn round_and_floor_in_lanes_are_round_and_floor_bit_for_bit() {
        let mut numbers = Numbers(0x0dd_ba11);
        let mut values = vec![
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            2.5,
            0.499_999_97,
            8_388_607.5,
            8_388_608.0,
            -8_388_609.0,
            1e30,
            1e-45,
            f32::MIN_POSITIVE,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
        ];
        for _ in 0..200_000 {
            let bits = numbers.bits();
            values.push(f32::from_bits(bits));
            // Ordinary numbers up to 2^25, and halves.
            let x = (numbers.uniform() - 0.5) * (1 << (bits % 26)) as f32;
            values.push(x);
            values.push((2.0 * x).round() * 0.5);
        }
        for chunk in values.chunks_exact(4) {
            let x = Vec4::from_slice(chunk);
            let (rounded, floored) = (round_x4(x).to_array(), floor_x4(x).to_array());
            for (j, &x) in chunk.iter().enumerate() {
                assert_eq!(rounded[j].to_bits(), round(x).to_bits(), "round({x:e})");
                assert_eq!(floored[j].to_bits(), floor(x).to_bits(), "floor({x:e})");
            }
        }
        // A NaN stays a NaN.
        let nan = Vec4::new(f32::NAN, -f32::NAN, 1.0, 2.0);
        assert!(round_x4(nan).x.is_nan() && round_x4(nan).y.is_nan());
        assert!(floor_x4(nan).x.is_nan() && floor_x4(nan).y.is_nan());
    }

    /// Four different windows on four different grids at once: each lane's coverage has
    /// the bits [`line_coverage`] gives it, in every case of the scalar code, the edges
    /// between cases within ulps.
    #[test]
    fn line_coverage_in_lanes_is_line_coverage_bit_for_bit() {
        let grids = grids();
        let mut numbers = Numbers(0x1ce_b00da);
        let mut cases = [0; 6];
        for _ in 0..400_000 {
            let grid: [&Grid; 4] =
                std::array::from_fn(|_| &grids[numbers.pick(grids.len() as u32) as usize]);
            let x = grid.map(|grid| position(&mut numbers, grid));
            let width = std::array::from_fn(|j| width(&mut numbers, grid[j], x[j]));
            let spacing = Vec4::from_array(grid.map(|g| g.spacing));
            let half = Vec4::from_array(grid.map(|g| 0.5 * g.line_width.min(g.spacing)));
            let got = line_coverage_x4(Vec4::from_array(x), Vec4::from_array(width), spacing, half);
            for j in 0..4 {
                let expected = line_coverage(x[j], width[j], grid[j]);
                assert_eq!(
                    got[j].to_bits(),
                    expected.to_bits(),
                    "lane {j}: x {x:e} width {width:e} on {grid:?}: {got}, expected {expected}",
                    x = x[j],
                    width = width[j],
                    grid = grid[j],
                    got = got[j],
                );
                cases[case(x[j], width[j], grid[j])] += 1;
            }
        }
        // Point samples, huge windows, narrow windows inside a line, between lines and
        // overlapping them, and wide windows: every case often.
        assert!(cases.iter().all(|&n| n > 1000), "cases tried: {cases:?}");
    }

    /// Four samples at once, of grid and plain materials, on surfaces facing every way
    /// (ties between the normal's coordinates included), with footprints of every kind:
    /// each lane holds the bits of [`surface_color`] for its sample.
    #[test]
    fn surface_colours_in_lanes_are_surface_color_bit_for_bit() {
        let plain = Material {
            color: Vec3::new(0.8, 0.3, 0.2),
            ..Material::default()
        };
        let materials: Vec<Material> = grids()
            .into_iter()
            .map(|grid| Material {
                color: Vec3::new(0.2, 0.4, 0.9),
                grid: Some(grid),
                ..Material::default()
            })
            .chain([plain])
            .collect();
        let mut numbers = Numbers(0x5eed_c0de);
        let unit = |numbers: &mut Numbers| {
            let v = Vec3::new(numbers.uniform(), numbers.uniform(), numbers.uniform()) * 2.0 - 1.0;
            match numbers.pick(4) {
                // Two or three coordinates of the same size, signs either way.
                0 => Vec3::new(1.0, -1.0, 0.0).normalize(),
                1 => Vec3::new(-0.0, 1.0, 1.0).normalize() * v.signum(),
                2 => Vec3::splat(1.0).normalize() * v.signum(),
                _ => v.normalize_or(Vec3::Y),
            }
        };
        let mut tried = [0; 3];
        for _ in 0..200_000 {
            // A quarter of the groups on one material, the others on four random ones.
            let mut material: [&Material; 4] =
                std::array::from_fn(|_| &materials[numbers.pick(materials.len() as u32) as usize]);
            if numbers.pick(4) == 0 {
                material = [material[0]; 4];
            }
            let lanes: [(Hit, Footprint); 4] = std::array::from_fn(|j| {
                let grid = material[j].grid.unwrap_or(NO_GRID);
                let normal = unit(&mut numbers);
                let point = Vec3::new(
                    position(&mut numbers, &grid),
                    position(&mut numbers, &grid),
                    position(&mut numbers, &grid),
                );
                // An area whose widths along the axes (|dx| + |dy|) are near what decides
                // the coverage, a point, or unbounded.
                let footprint = match numbers.pick(8) {
                    0 => Footprint::Point,
                    1 => Footprint::Unbounded,
                    _ => {
                        let w = Vec3::new(
                            width(&mut numbers, &grid, point.x),
                            width(&mut numbers, &grid, point.y),
                            width(&mut numbers, &grid, point.z),
                        )
                        .min(Vec3::splat(1e30));
                        let share = numbers.uniform();
                        let sign = unit(&mut numbers).signum();
                        Footprint::Area(w * share * sign, w * (1.0 - share))
                    }
                };
                let hit = Hit {
                    point,
                    normal,
                    ..Hit::default()
                };
                (hit, footprint)
            });
            let point = Vec3x4::gather(lanes.each_ref().map(|(hit, _)| &hit.point));
            let normal = Vec3x4::gather(lanes.each_ref().map(|(hit, _)| &hit.normal));
            let widths = lanes.map(|(_, footprint)| footprint.widths());
            let got = surface_colors(material, point, normal, |_| {
                Vec3x4::gather(widths.each_ref())
            });
            for (j, (hit, footprint)) in lanes.iter().enumerate() {
                let mut lines = None;
                let expected =
                    surface_color::<NoRecorder>(material[j], hit, || *footprint, &mut lines);
                assert_eq!(
                    got.lane(j).to_array().map(f32::to_bits),
                    expected.to_array().map(f32::to_bits),
                    "lane {j}: {hit:?} with {footprint:?} on {material:?}",
                    material = material[j],
                );
                tried[usize::from(material[j].grid.is_some())
                    + usize::from(matches!(footprint, Footprint::Area(..)))] += 1;
            }
        }
        assert!(tried.iter().all(|&n| n > 1000), "{tried:?}");
    }

    /// The widths are asked for only where a material has lines, and only for its lanes.
    #[test]
    fn surface_colours_ask_for_the_widths_of_grid_lanes_only() {
        let grid = Material {
            grid: Some(GRID),
            ..Material::default()
        };
        let plain = Material::default();
        let (point, normal) = (Vec3x4::ZERO, Vec3x4::splat(Vec3::Y));
        let mut asked = None;
        surface_colors([&plain, &grid, &plain, &grid], point, normal, |lanes| {
            asked = Some(lanes);
            Vec3x4::ZERO
        });
        assert_eq!(asked, Some(0b1010));
        let colors = surface_colors([&plain; 4], point, normal, |_| unreachable!());
        assert_eq!(colors, Vec3x4::splat(plain.color));
    }
}
