//! Estimating the systematic transform between an expected and an actual image, and
//! naming the camera mistake it points to.
//!
//! The model: the actual image is the expected one, mirrored about the image centre (left-
//! right, upside down, or both), scaled about the centre (by `sx`, `sy`), then moved by
//! (`tx`, `ty`) pixels. In continuous image coordinates (x right, y down, c = (W/2, H/2)),
//! the actual pixel at X shows what the expected image shows at
//!
//! ```text
//! E(X) = c + M ((X - t - c) / s)        M = diag(+-1, +-1)
//! ```
//!
//! Each camera mistake is one such transform: u = w x up instead of up x w mirrors
//! left-right; a missing pixel-centre offset moves everything by +0.5 px in x and y; a wrong
//! vw, vh or d scales; a lens shift with the wrong sign moves by twice the shift.
//!
//! Estimation: both images are blurred (so antialiasing noise does not matter) and built
//! into pyramids; an exhaustive search over mirrors, uniform scales in [0.8, 1.25] and
//! whole-pixel moves of up to a quarter of the image runs on the coarsest level, then
//! Levenberg-Marquardt on the sum of squared differences refines the best candidates level
//! by level to sub-pixel moves and per-axis scales, sampling the expected image
//! bilinearly. A transform is reported only when it is clearly away from the identity and
//! explains most of the difference (see [`crate::InstructorThresholds`]).

use std::fmt;

use crate::raster::{AxisSample, FloatImage};

/// A camera mistake found in an actual image: how it is transformed from the expected one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diagnosis {
    /// Mirrored left-right (about the vertical centre line).
    pub mirrored_left_right: bool,
    /// Upside down (mirrored about the horizontal centre line).
    pub upside_down: bool,
    /// How many times larger the content appears in the actual image, along x and y
    /// (about the image centre): 1.1 when vw and vh are 1.1 times too small.
    pub scale: (f64, f64),
    /// How far the content moved in the actual image, in pixels: x right, y down.
    pub shift: (f64, f64),
    /// Which of the parts above are beyond the tolerances (the others are measurement
    /// noise and are not reported).
    pub significant: Significant,
    /// The fraction of the mean squared difference between the (blurred) images that the
    /// transform explains: 1 when undoing it leaves no difference.
    pub explained: f64,
}

/// Which parts of a [`Diagnosis`] are beyond the tolerances.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Significant {
    /// The scale along x differs from 1.
    pub scale_x: bool,
    /// The scale along y differs from 1.
    pub scale_y: bool,
    /// The move along x differs from 0.
    pub shift_x: bool,
    /// The move along y differs from 0.
    pub shift_y: bool,
}

impl Diagnosis {
    /// One message per mistake, each saying what is seen and what to check, e.g.
    /// `shifted +0.5 px in x and y: check the pixel-centre offset` or
    /// `mirrored left-right: check u = up x w`.
    pub fn messages(&self) -> Vec<String> {
        let mut messages = Vec::new();
        match (self.mirrored_left_right, self.upside_down) {
            (true, true) => messages.push(
                "rotated 180 degrees (mirrored left-right and upside down): check the sign of up"
                    .to_owned(),
            ),
            (true, false) => messages.push("mirrored left-right: check u = up x w".to_owned()),
            (false, true) => messages.push(
                "upside down: check v = w x u and the minus sign in v = -((row + sy)/H - 1/2) vh"
                    .to_owned(),
            ),
            (false, false) => {}
        }
        let (sx, sy) = self.scale;
        match (self.significant.scale_x, self.significant.scale_y) {
            (true, true) if (sx - sy).abs() < 0.01 => {
                messages.push(format!("scaled {:.2}x: check vw, vh or d", 0.5 * (sx + sy)))
            }
            (true, true) => messages.push(format!(
                "scaled {sx:.2}x in x and {sy:.2}x in y: check vw and vh (the aspect ratio)"
            )),
            (true, false) => messages.push(format!("scaled {sx:.2}x in x only: check vw")),
            (false, true) => messages.push(format!("scaled {sy:.2}x in y only: check vh")),
            (false, false) => {}
        }
        if let Some(message) = self.shift_message() {
            messages.push(message);
        }
        messages
    }

    /// The message about the move, if it is significant.
    fn shift_message(&self) -> Option<String> {
        let (tx, ty) = self.shift;
        let (moved_x, moved_y) = (self.significant.shift_x, self.significant.shift_y);
        if !moved_x && !moved_y {
            return None;
        }
        // Half a pixel (within a fifth of a pixel) on each moved axis, nothing on the others:
        // the samples are taken at a pixel corner instead of its centre.
        let half = |t: f64| (t.abs() - 0.5).abs() < 0.2;
        let is_centre_offset = (!moved_x || half(tx)) && (!moved_y || half(ty));
        if is_centre_offset {
            let axes = match (moved_x, moved_y) {
                (true, true) if tx.signum() == ty.signum() => {
                    format!("{:+.1} px in x and y", 0.5 * tx.signum())
                }
                (true, true) => format!(
                    "{:+.1} px in x and {:+.1} px in y",
                    0.5 * tx.signum(),
                    0.5 * ty.signum()
                ),
                (true, false) => format!("{:+.1} px in x", 0.5 * tx.signum()),
                _ => format!("{:+.1} px in y", 0.5 * ty.signum()),
            };
            return Some(format!("shifted {axes}: check the pixel-centre offset"));
        }
        let amount = |t: f64| {
            if t.abs() >= 2.0 {
                format!("{:.0}", t.abs())
            } else {
                format!("{:.1}", t.abs())
            }
        };
        let mut parts = Vec::new();
        if moved_y {
            parts.push(format!(
                "{} px {}",
                amount(ty),
                if ty < 0.0 { "up" } else { "down" }
            ));
        }
        if moved_x {
            parts.push(format!(
                "{} px {}",
                amount(tx),
                if tx < 0.0 { "left" } else { "right" }
            ));
        }
        Some(format!(
            "shifted {}: check the sign of the shift",
            parts.join(" and ")
        ))
    }
}

impl fmt::Display for Diagnosis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.messages().join("; "))
    }
}

/// A mirror-scale-move transform from actual to expected coordinates (see the module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Transform {
    pub(crate) mirror_x: bool,
    pub(crate) mirror_y: bool,
    /// The content's magnification in the actual image along x and y.
    pub(crate) scale: [f64; 2],
    /// The content's move in the actual image, in full-resolution pixels.
    pub(crate) shift: [f64; 2],
}

impl Transform {
    const IDENTITY: Transform = Transform {
        mirror_x: false,
        mirror_y: false,
        scale: [1.0, 1.0],
        shift: [0.0, 0.0],
    };

    fn signs(&self) -> [f64; 2] {
        [
            if self.mirror_x { -1.0 } else { 1.0 },
            if self.mirror_y { -1.0 } else { 1.0 },
        ]
    }
}

/// One level of the image pyramids: `factor` full-resolution pixels per level pixel.
struct Level {
    factor: f64,
    expected: FloatImage,
    expected_dx: FloatImage,
    expected_dy: FloatImage,
    actual: FloatImage,
}

/// The result of estimating the transform: the best one, and what it and the identity
/// leave unexplained.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Estimate {
    pub(crate) transform: Transform,
    /// The mean squared difference after undoing the transform.
    pub(crate) residual: f64,
    /// The mean squared difference as the images are.
    pub(crate) identity_residual: f64,
}

/// Side of the coarsest pyramid level (its shorter side is at least this, and halving once
/// more would make it shorter).
const COARSEST_SIDE: usize = 24;

/// Estimates the mirror-scale-move transform that best maps `expected` onto `actual`, two
/// images of the same size that are already blurred and sRGB-encoded.
///
/// Returns `None` for images too small to estimate anything (either side below 16 pixels).
pub(crate) fn estimate(expected: &FloatImage, actual: &FloatImage) -> Option<Estimate> {
    if expected.width < 16 || expected.height < 16 {
        return None;
    }
    let centre = [expected.width as f64 / 2.0, expected.height as f64 / 2.0];
    let levels = build_pyramid(expected, actual);
    let top = levels.len() - 1;

    // Search the coarsest level exhaustively; keep the best few per mirror.
    let coarse = &levels[top];
    let reach_x = (coarse.actual.width / 4) as i64;
    let reach_y = (coarse.actual.height / 4) as i64;
    let mut starts: Vec<(f64, Transform)> = Vec::new();
    for (mirror_x, mirror_y) in [(false, false), (true, false), (false, true), (true, true)] {
        // The best three so far, cheapest first; a candidate is abandoned as soon as its
        // partial sum exceeds the third's cost.
        let mut best: Vec<(f64, Transform)> = Vec::new();
        for step in -4..=4 {
            let s = 1.25f64.powf(f64::from(step) / 4.0);
            for ty in -reach_y..=reach_y {
                for tx in -reach_x..=reach_x {
                    let transform = Transform {
                        mirror_x,
                        mirror_y,
                        scale: [s, s],
                        shift: [tx as f64 * coarse.factor, ty as f64 * coarse.factor],
                    };
                    let bound = if best.len() < 3 {
                        f64::INFINITY
                    } else {
                        best[2].0
                    };
                    if let Some(cost) =
                        bounded_mean_squared_difference(coarse, &transform, centre, bound)
                    {
                        best.push((cost, transform));
                        best.sort_by(|a, b| a.0.total_cmp(&b.0));
                        best.truncate(3);
                    }
                }
            }
        }
        starts.extend(best);
    }

    // Refine every start on the coarsest level; keep the best per mirror (and the
    // identity, which must be heard even when the coarse search prefers a move).
    let mut per_mirror: Vec<(f64, Transform)> = Vec::new();
    for &(_, start) in &starts {
        let transform = refine(coarse, start, centre);
        let cost = mean_squared_difference(coarse, &transform, centre);
        let same_mirror =
            |t: &Transform| (t.mirror_x, t.mirror_y) == (transform.mirror_x, transform.mirror_y);
        match per_mirror.iter_mut().find(|(_, t)| same_mirror(t)) {
            Some(slot) if cost < slot.0 => *slot = (cost, transform),
            Some(_) => {}
            None => per_mirror.push((cost, transform)),
        }
    }
    per_mirror.push((0.0, refine(coarse, Transform::IDENTITY, centre)));
    // Refine those down to the second-finest level; keep the best plain and mirrored.
    let mut best_plain: Option<(f64, Transform)> = None;
    let mut best_mirrored: Option<(f64, Transform)> = None;
    for &(_, start) in &per_mirror {
        let mut transform = start;
        for level in levels[1.min(top)..top].iter().rev() {
            transform = refine(level, transform, centre);
        }
        let cost = mean_squared_difference(&levels[1.min(top)], &transform, centre);
        let slot = if transform.mirror_x || transform.mirror_y {
            &mut best_mirrored
        } else {
            &mut best_plain
        };
        if slot.is_none_or(|(best, _)| cost < best) {
            *slot = Some((cost, transform));
        }
    }
    // Finish the best plain and the best mirrored candidates at full resolution.
    let finish = |candidate: Option<(f64, Transform)>| {
        candidate.map(|(_, transform)| {
            let transform = refine(&levels[0], transform, centre);
            (
                mean_squared_difference(&levels[0], &transform, centre),
                transform,
            )
        })
    };
    let (best_plain, best_mirrored) = (finish(best_plain), finish(best_mirrored));
    let identity_residual = mean_squared_difference(&levels[0], &Transform::IDENTITY, centre);
    let (mut residual, mut transform) =
        best_plain.unwrap_or((identity_residual, Transform::IDENTITY));
    // A mirror must do clearly better than the best plain transform: a nearly symmetric
    // picture looks much the same mirrored, and then the simpler answer stands.
    if let Some((mirrored_cost, mirrored)) = best_mirrored
        && mirrored_cost < 0.5 * residual
    {
        (residual, transform) = (mirrored_cost, mirrored);
    }
    if residual > identity_residual {
        (residual, transform) = (identity_residual, Transform::IDENTITY);
    }
    Some(Estimate {
        transform,
        residual,
        identity_residual,
    })
}

fn build_pyramid(expected: &FloatImage, actual: &FloatImage) -> Vec<Level> {
    let mut levels = Vec::new();
    let (mut e, mut a, mut factor) = (expected.clone(), actual.clone(), 1.0);
    loop {
        let (dx, dy) = e.gradients();
        let next_side = e.width.min(e.height) / 2;
        levels.push(Level {
            factor,
            expected: e.clone(),
            expected_dx: dx,
            expected_dy: dy,
            actual: a.clone(),
        });
        if next_side < COARSEST_SIDE {
            return levels;
        }
        e = e.gaussian_blur(1.0).downsample_2x();
        a = a.gaussian_blur(1.0).downsample_2x();
        factor *= 2.0;
    }
}

/// For each pixel index along one axis of a level: its centre in full-resolution
/// coordinates X, and where E(X) = c + m (X - t - c) / s falls in the expected level.
fn axis_samples(
    level: &Level,
    count: usize,
    size: usize,
    centre: f64,
    sign: f64,
    shift: f64,
    scale: f64,
) -> Vec<(f64, AxisSample)> {
    (0..count)
        .map(|i| {
            let x = (i as f64 + 0.5) * level.factor;
            let e = centre + sign * (x - shift - centre) / scale;
            (x, AxisSample::new(e / level.factor, size))
        })
        .collect()
}

/// The mean over the actual level's pixels and channels of the squared difference from
/// the expected level sampled through `transform`.
fn mean_squared_difference(level: &Level, transform: &Transform, centre: [f64; 2]) -> f64 {
    bounded_mean_squared_difference(level, transform, centre, f64::INFINITY)
        .expect("an infinite bound is never exceeded")
}

/// [`mean_squared_difference`], or `None` as soon as it is sure to exceed `bound`.
fn bounded_mean_squared_difference(
    level: &Level,
    transform: &Transform,
    centre: [f64; 2],
    bound: f64,
) -> Option<f64> {
    let (w, h) = (level.actual.width, level.actual.height);
    let [mx, my] = transform.signs();
    let columns = axis_samples(
        level,
        w,
        level.expected.width,
        centre[0],
        mx,
        transform.shift[0],
        transform.scale[0],
    );
    let rows = axis_samples(
        level,
        h,
        level.expected.height,
        centre[1],
        my,
        transform.shift[1],
        transform.scale[1],
    );
    let count = (w * h * 3) as f64;
    let bound_sum = bound * count;
    let mut sum = 0.0f64;
    for (row, &(_, ys)) in rows.iter().enumerate() {
        let mut row_sum = 0.0f32;
        for (col, &(_, xs)) in columns.iter().enumerate() {
            let e = level.expected.sample_separable(ys, xs);
            let a = level.actual.at(row, col);
            for c in 0..3 {
                let r = e[c] - a[c];
                row_sum += r * r;
            }
        }
        sum += f64::from(row_sum);
        if sum > bound_sum {
            return None;
        }
    }
    Some(sum / count)
}

/// Levenberg-Marquardt on the move and the per-axis scales at one level, mirrors fixed.
///
/// The parameters are p = (tx, ty, kx, ky) with k = 1/s, so that E is linear in each:
/// E_x = c_x + m_x k_x (X_x - t_x - c_x).
#[allow(
    clippy::needless_range_loop,
    reason = "matrix indices read as the algebra does"
)]
fn refine(level: &Level, start: Transform, centre: [f64; 2]) -> Transform {
    let [mx, my] = start.signs();
    let mut p = [
        start.shift[0],
        start.shift[1],
        1.0 / start.scale[0],
        1.0 / start.scale[1],
    ];
    let to_transform = |p: &[f64; 4]| Transform {
        scale: [1.0 / p[2], 1.0 / p[3]],
        shift: [p[0], p[1]],
        ..start
    };
    let mut cost = mean_squared_difference(level, &to_transform(&p), centre);
    let mut lambda = 1e-3;
    let (w, h) = (level.actual.width, level.actual.height);
    for _ in 0..30 {
        // Build the normal equations J^T J and J^T r.
        let columns = axis_samples(
            level,
            w,
            level.expected.width,
            centre[0],
            mx,
            p[0],
            1.0 / p[2],
        );
        let rows = axis_samples(
            level,
            h,
            level.expected.height,
            centre[1],
            my,
            p[1],
            1.0 / p[3],
        );
        let mut jtj = [[0.0f64; 4]; 4];
        let mut jtr = [0.0f64; 4];
        for (row, &(y, ys)) in rows.iter().enumerate() {
            // dE_y/dp for ty and ky; E_x depends only on tx and kx.
            let dey = [-my * p[3], my * (y - p[1] - centre[1])];
            for (col, &(x, xs)) in columns.iter().enumerate() {
                let e = level.expected.sample_separable(ys, xs);
                let gx = level.expected_dx.sample_separable(ys, xs);
                let gy = level.expected_dy.sample_separable(ys, xs);
                let a = level.actual.at(row, col);
                let dex = [-mx * p[2], mx * (x - p[0] - centre[0])];
                for c in 0..3 {
                    let r = f64::from(e[c] - a[c]);
                    // Level gradients are per level pixel; the parameters are in
                    // full-resolution pixels.
                    let gxc = f64::from(gx[c]) / level.factor;
                    let gyc = f64::from(gy[c]) / level.factor;
                    let j = [gxc * dex[0], gyc * dey[0], gxc * dex[1], gyc * dey[1]];
                    for a in 0..4 {
                        jtr[a] += j[a] * r;
                        for b in a..4 {
                            jtj[a][b] += j[a] * j[b];
                        }
                    }
                }
            }
        }
        for a in 0..4 {
            for b in 0..a {
                jtj[a][b] = jtj[b][a];
            }
        }
        // Try damped steps until one lowers the cost.
        let mut improved = false;
        for _ in 0..8 {
            let mut system = jtj;
            for (k, row) in system.iter_mut().enumerate() {
                row[k] += lambda * jtj[k][k].max(1e-12);
            }
            let Some(step) = solve4(system, jtr.map(|v| -v)) else {
                break;
            };
            let candidate: [f64; 4] = std::array::from_fn(|k| p[k] + step[k]);
            if candidate[2] <= 0.0 || candidate[3] <= 0.0 {
                lambda *= 10.0;
                continue;
            }
            let candidate_cost = mean_squared_difference(level, &to_transform(&candidate), centre);
            if candidate_cost < cost {
                let small = step[0].abs() < 1e-3
                    && step[1].abs() < 1e-3
                    && step[2].abs() < 1e-6
                    && step[3].abs() < 1e-6;
                p = candidate;
                cost = candidate_cost;
                lambda = (lambda * 0.3).max(1e-7);
                improved = !small;
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    to_transform(&p)
}

/// Solves the 4 x 4 linear system `a x = b` by Gaussian elimination with partial
/// pivoting; `None` when it is singular.
#[allow(
    clippy::needless_range_loop,
    reason = "matrix indices read as the algebra does"
)]
fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for col in 0..4 {
        let pivot = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..4 {
            let factor = a[row][col] / a[col][col];
            for k in col..4 {
                a[row][k] -= factor * a[col][k];
            }
            b[row] -= factor * b[col];
        }
    }
    let mut x = [0.0; 4];
    for row in (0..4).rev() {
        let tail: f64 = (row + 1..4).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - tail) / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn solve4_solves_a_known_system_and_rejects_a_singular_one() {
        let a = [
            [4.0, 1.0, 0.0, 0.0],
            [1.0, 3.0, 1.0, 0.0],
            [0.0, 1.0, 2.0, 1.0],
            [0.0, 0.0, 1.0, 5.0],
        ];
        let x = [1.0, -2.0, 0.5, 3.0];
        let b: [f64; 4] = std::array::from_fn(|r| (0..4).map(|c| a[r][c] * x[c]).sum());
        let solved = solve4(a, b).unwrap();
        for k in 0..4 {
            assert!((solved[k] - x[k]).abs() < 1e-12);
        }
        assert_eq!(solve4([[1.0; 4]; 4], [1.0; 4]), None);
    }

    fn diagnosis(shift: (f64, f64), scale: (f64, f64), significant: Significant) -> Diagnosis {
        Diagnosis {
            mirrored_left_right: false,
            upside_down: false,
            scale,
            shift,
            significant,
            explained: 0.9,
        }
    }

    #[test]
    fn messages_name_the_classic_mistakes() {
        let both = Significant {
            shift_x: true,
            shift_y: true,
            ..Significant::default()
        };
        let only_y = Significant {
            shift_y: true,
            ..Significant::default()
        };
        let scaled = Significant {
            scale_x: true,
            scale_y: true,
            ..Significant::default()
        };
        let cases = [
            (
                diagnosis((0.48, 0.53), (1.0, 1.0), both),
                "shifted +0.5 px in x and y: check the pixel-centre offset",
            ),
            (
                diagnosis((0.02, -12.2), (1.0, 1.0), only_y),
                "shifted 12 px up: check the sign of the shift",
            ),
            (
                diagnosis((3.0, 1.2), (1.0, 1.0), both),
                "shifted 1.2 px down and 3 px right: check the sign of the shift",
            ),
            (
                diagnosis((0.0, 0.0), (1.098, 1.101), scaled),
                "scaled 1.10x: check vw, vh or d",
            ),
            (
                Diagnosis {
                    mirrored_left_right: true,
                    ..diagnosis((0.0, 0.0), (1.0, 1.0), Significant::default())
                },
                "mirrored left-right: check u = up x w",
            ),
        ];
        for (diagnosis, expected) in cases {
            assert_eq!(diagnosis.to_string(), expected);
        }
    }
}
