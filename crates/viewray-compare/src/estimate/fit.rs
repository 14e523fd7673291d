//! Fitting a [`Model`] on the overlap: the sums of one evaluation ([`Fit`]), the
//! parameters the fit moves, Levenberg-Marquardt ([`refine`]), and how much of the
//! picture's edges an overlap holds ([`texture`]).
//!
//! The overlap of a model at a level is the set of the level's pixels whose centre and
//! preimage both lie inside the margins ([`for_each_overlap`]); every sum here is over it.

use crate::raster::FloatImage;

use super::model::Model;
use super::pyramid::Pyramid;

/// Which parts of a [`Model`] may differ from the identity while it is fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Free {
    /// A turn.
    pub(crate) rotation: bool,
    /// A uniform scale.
    pub(crate) scale: bool,
    /// Different scales along x and y.
    pub(crate) aspect: bool,
    /// The move `t` (else it stays as it is, usually zero about a chosen point).
    pub(crate) shift: bool,
}

impl Free {
    /// Every part free.
    pub(crate) const ALL: Free = Free {
        rotation: true,
        scale: true,
        aspect: true,
        shift: true,
    };

    /// Which of the fit's parameters (see [`parameters`]) are free.
    fn mask(self) -> [bool; 5] {
        [
            self.rotation,
            self.scale,
            self.aspect,
            self.shift,
            self.shift,
        ]
    }
}

/// The sums of one evaluation of a model on the overlap.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Fit {
    /// Pixels in the overlap.
    pub(crate) count: usize,
    /// Pixels evaluated in all.
    pub(crate) total: usize,
    /// Sum over the overlap's pixels and channels of the squared difference.
    pub(crate) sum_sq: f64,
    sum_actual: [f64; 3],
    sum_sq_actual: [f64; 3],
    sum_expected: [f64; 3],
    sum_sq_expected: [f64; 3],
}

impl Fit {
    /// The fraction of the picture in the overlap.
    pub(crate) fn overlap(&self) -> f64 {
        self.count as f64 / self.total.max(1) as f64
    }

    /// The mean squared difference per channel over the overlap (infinite without one).
    pub(crate) fn mean(&self) -> f64 {
        if self.count == 0 {
            f64::INFINITY
        } else {
            self.sum_sq / (3 * self.count) as f64
        }
    }

    /// The squared difference over the overlap relative to the contrast there (the
    /// variances of both images, with a floor): 0 for a perfect match, about 1 for
    /// unrelated pictures; a flat overlap explains nothing.
    pub(crate) fn normalized(&self, floor: f64) -> f64 {
        if self.count == 0 {
            return f64::INFINITY;
        }
        let n = self.count as f64;
        let variance = |sum: &[f64; 3], sum_sq: &[f64; 3]| -> f64 {
            (0..3).map(|c| sum_sq[c] - sum[c] * sum[c] / n).sum::<f64>()
        };
        let contrast = variance(&self.sum_actual, &self.sum_sq_actual)
            + variance(&self.sum_expected, &self.sum_sq_expected);
        self.sum_sq / contrast.max(floor * 3.0 * n)
    }
}

/// Bilinear interpolation of `image` at level coordinates (`x`, `y`).
pub(super) fn sample(image: &FloatImage, x: f64, y: f64) -> [f32; 3] {
    image.sample_bilinear(x, y)
}

/// Bilinear interpolation of a `width` x `height` array of `N` channels at level
/// coordinates (`x`, `y`) (pixel centres at half-integers), clamped to the array.
#[inline]
fn sample_n<const N: usize>(
    data: &[[f32; N]],
    width: usize,
    height: usize,
    x: f64,
    y: f64,
) -> [f32; N] {
    let fx = ((x - 0.5) as f32).clamp(0.0, (width - 1) as f32);
    let fy = ((y - 0.5) as f32).clamp(0.0, (height - 1) as f32);
    let (x0, y0) = (fx as usize, fy as usize);
    let (x1, y1) = ((x0 + 1).min(width - 1), (y0 + 1).min(height - 1));
    let (tx, ty) = (fx - x0 as f32, fy - y0 as f32);
    let (p00, p01) = (&data[y0 * width + x0], &data[y0 * width + x1]);
    let (p10, p11) = (&data[y1 * width + x0], &data[y1 * width + x1]);
    std::array::from_fn(|c| {
        let top = p00[c] + tx * (p01[c] - p00[c]);
        let bottom = p10[c] + tx * (p11[c] - p10[c]);
        top + ty * (bottom - top)
    })
}

/// The mean squared difference per channel of `model` over its overlap at `level`
/// (infinite without an overlap): [`evaluate`]'s [`Fit::mean`], cheaper.
pub(super) fn cost(pyramid: &Pyramid, level: usize, model: &Model, stride: usize) -> f64 {
    cost_and_count(pyramid, level, model, stride).0
}

/// [`cost`], and how many pixels the overlap has.
fn cost_and_count(pyramid: &Pyramid, level: usize, model: &Model, stride: usize) -> (f64, usize) {
    let l = &pyramid.levels[level];
    let (w, h) = (l.expected.width, l.expected.height);
    let mut sum = 0.0f64;
    let mut count = 0usize;
    for_each_overlap(pyramid, level, model, stride, |[row, col], _, e| {
        let expected = sample_n(&l.expected.pixels, w, h, e[0] / l.factor, e[1] / l.factor);
        let actual = l.actual.at(row, col);
        let d = [0, 1, 2].map(|c| expected[c] - actual[c]);
        sum += f64::from(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        count += 1;
    });
    if count == 0 {
        (f64::INFINITY, 0)
    } else {
        (sum / (3 * count) as f64, count)
    }
}

/// The range of the fitted parameters: turns of up to 45 degrees, scales from 0.55x to
/// 1.8x and an aspect ratio off by up to 35%, a little beyond what the search looks for.
/// Outside it a fit has lost its way (a tiny overlap matching anything).
fn plausible(p: &[f64; 5]) -> bool {
    p[0].abs() <= std::f64::consts::FRAC_PI_4 && p[1].abs() <= 0.6 && p[2].abs() <= 0.3
}

/// Calls `visit(actual pixel, its centre, its preimage)` for every `stride`-th pixel of the
/// level whose centre and preimage both lie inside the margins; returns how many of the
/// pixels looked at lie inside the margins (the picture the overlap is a part of).
pub(super) fn for_each_overlap(
    pyramid: &Pyramid,
    level: usize,
    model: &Model,
    stride: usize,
    mut visit: impl FnMut([usize; 2], [f64; 2], [f64; 2]),
) -> usize {
    let l = &pyramid.levels[level];
    let margin = pyramid.margin(level);
    let [w, h] = pyramid.size;
    let inverse = model.inverse_matrix();
    let inside =
        |p: [f64; 2]| p[0] >= margin && p[0] <= w - margin && p[1] >= margin && p[1] <= h - margin;
    let mut total = 0;
    for row in (0..l.actual.height).step_by(stride) {
        let y = (row as f64 + 0.5) * l.factor;
        for col in (0..l.actual.width).step_by(stride) {
            let x = [(col as f64 + 0.5) * l.factor, y];
            if !inside(x) {
                continue;
            }
            total += 1;
            let e = model.preimage(&inverse, x);
            if inside(e) {
                visit([row, col], x, e);
            }
        }
    }
    total
}

/// The sums of `model` on the overlap at `level`.
pub(super) fn evaluate(pyramid: &Pyramid, level: usize, model: &Model, stride: usize) -> Fit {
    let l = &pyramid.levels[level];
    let mut fit = Fit::default();
    fit.total = for_each_overlap(pyramid, level, model, stride, |[row, col], _, e| {
        let expected = sample(l.expected, e[0] / l.factor, e[1] / l.factor);
        let actual = l.actual.at(row, col);
        fit.count += 1;
        for c in 0..3 {
            let (a, x) = (f64::from(actual[c]), f64::from(expected[c]));
            fit.sum_sq += (x - a) * (x - a);
            fit.sum_actual[c] += a;
            fit.sum_sq_actual[c] += a * a;
            fit.sum_expected[c] += x;
            fit.sum_sq_expected[c] += x * x;
        }
    });
    fit
}

/// The parameters the fit moves: (theta, ln s, aspect, tx, ty), with the scales along x
/// and y `exp(ln s + aspect)` and `exp(ln s - aspect)`.
fn parameters(model: &Model) -> [f64; 5] {
    let [lx, ly] = model.log_scale;
    [
        model.rotation,
        0.5 * (lx + ly),
        0.5 * (lx - ly),
        model.shift[0],
        model.shift[1],
    ]
}

/// `model` with the parameters `p` (see [`parameters`]).
fn with_parameters(model: &Model, p: &[f64; 5]) -> Model {
    Model {
        rotation: p[0],
        log_scale: [p[1] + p[2], p[1] - p[2]],
        shift: [p[3], p[4]],
        ..*model
    }
}

/// Levenberg-Marquardt on the squared differences over the overlap at one level: the
/// parameters `free` says, from `start` (mirrors and the point `about` fixed).
#[allow(
    clippy::needless_range_loop,
    reason = "matrix indices read as the algebra does"
)]
pub(super) fn refine(
    pyramid: &Pyramid,
    level: usize,
    start: Model,
    free: Free,
    stride: usize,
    iterations: usize,
) -> Model {
    let mask = free.mask();
    let indices: Vec<usize> = (0..5).filter(|&k| mask[k]).collect();
    let n = indices.len();
    if n == 0 {
        return start;
    }
    let l = &pyramid.levels[level];
    let mut p = parameters(&start);
    let (mut current, mut count) = cost_and_count(pyramid, level, &start, stride);
    let mut lambda = 1e-3;
    let (w, h) = (l.expected.width, l.expected.height);
    for _ in 0..iterations {
        let model = with_parameters(&start, &p);
        let inverse = model.inverse_matrix();
        let signs = model.signs();
        let k = [
            (-model.log_scale[0]).exp() * signs[0],
            (-model.log_scale[1]).exp() * signs[1],
        ];
        let (sin, cos) = model.rotation.sin_cos();
        let mut jtj = [[0.0f64; 5]; 5];
        let mut jtr = [0.0f64; 5];
        for_each_overlap(pyramid, level, &model, stride, |[row, col], x, e| {
            let fused = sample_n(l.expected_fused, w, h, e[0] / l.factor, e[1] / l.factor);
            let actual = l.actual.at(row, col);
            // Z = R(-theta) (X - p - t); X_e = p + M S^-1 Z.
            let y = [
                x[0] - model.about[0] - model.shift[0],
                x[1] - model.about[1] - model.shift[1],
            ];
            let z = [cos * y[0] + sin * y[1], -sin * y[0] + cos * y[1]];
            // dX_e/dp for each parameter, as (x, y) pairs.
            let d = [
                [k[0] * z[1], -k[1] * z[0]],
                [-k[0] * z[0], -k[1] * z[1]],
                [-k[0] * z[0], k[1] * z[1]],
                [-inverse[0][0], -inverse[1][0]],
                [-inverse[0][1], -inverse[1][1]],
            ];
            for c in 0..3 {
                let r = f64::from(fused[c] - actual[c]);
                // Level gradients are per level pixel; X_e is in full-resolution pixels.
                let (gxc, gyc) = (
                    f64::from(fused[3 + c]) / l.factor,
                    f64::from(fused[6 + c]) / l.factor,
                );
                let mut j = [0.0; 5];
                for (slot, &index) in j.iter_mut().zip(&indices) {
                    *slot = gxc * d[index][0] + gyc * d[index][1];
                }
                for a in 0..n {
                    jtr[a] += j[a] * r;
                    for b in a..n {
                        jtj[a][b] += j[a] * j[b];
                    }
                }
            }
        });
        for a in 0..n {
            for b in 0..a {
                jtj[a][b] = jtj[b][a];
            }
        }
        // Try damped steps until one lowers the cost.
        let mut improved = false;
        for _ in 0..8 {
            let mut system = jtj;
            for (i, row) in system.iter_mut().enumerate().take(n) {
                row[i] += lambda * jtj[i][i].max(1e-12);
            }
            let Some(step) = solve(system, jtr.map(|v| -v), n) else {
                break;
            };
            let mut candidate = p;
            for (i, &index) in indices.iter().enumerate() {
                candidate[index] += step[i];
            }
            let candidate_model = with_parameters(&start, &candidate);
            let (candidate_cost, candidate_count) =
                cost_and_count(pyramid, level, &candidate_model, stride);
            // A step may not give up more than a tenth of the overlap: a lower mean on a
            // much smaller overlap is no better fit.
            let keeps_overlap = candidate_count * 10 >= count * 9;
            if candidate_cost < current && keeps_overlap && plausible(&candidate) {
                let small = indices.iter().enumerate().all(|(i, &index)| {
                    let tolerance = if index >= 3 { 1e-3 } else { 1e-6 };
                    step[i].abs() < tolerance
                });
                p = candidate;
                current = candidate_cost;
                count = candidate_count;
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
    with_parameters(&start, &p)
}

/// Solves the `n` x `n` system `a x = b` (the top-left of the arrays) by Gaussian
/// elimination with partial pivoting; `None` when it is singular.
#[allow(
    clippy::needless_range_loop,
    reason = "matrix indices read as the algebra does"
)]
fn solve(mut a: [[f64; 5]; 5], mut b: [f64; 5], n: usize) -> Option<[f64; 5]> {
    for col in 0..n {
        let pivot = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[pivot][col].abs() < 1e-300 {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..n {
            let factor = a[row][col] / a[col][col];
            for k in col..n {
                a[row][k] -= factor * a[col][k];
            }
            b[row] -= factor * b[col];
        }
    }
    let mut x = [0.0; 5];
    for row in (0..n).rev() {
        let tail: f64 = (row + 1..n).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - tail) / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// How much of the picture's edges, along x and along y, the overlap of a transform has:
/// the mean squared derivative of the expected image over the overlap relative to its
/// mean over the whole picture, per axis. A match is determined along an axis only where
/// the overlap has edges across it: a strip of sky above a horizon matches itself slid
/// sideways (its x derivatives are nil, a thousandth of the picture's).
pub(super) fn texture(pyramid: &Pyramid, level: usize, model: &Model, stride: usize) -> [f64; 2] {
    let l = &pyramid.levels[level];
    let (w, h) = (l.expected.width, l.expected.height);
    let mut sums = [0.0f64; 2];
    let mut count = 0usize;
    for_each_overlap(pyramid, level, model, stride, |_, _, e| {
        let fused = sample_n(l.expected_fused, w, h, e[0] / l.factor, e[1] / l.factor);
        for c in 0..3 {
            sums[0] += f64::from(fused[3 + c]).powi(2);
            sums[1] += f64::from(fused[6 + c]).powi(2);
        }
        count += 1;
    });
    let mut whole = [0.0f64; 2];
    for p in l.expected_fused {
        for c in 0..3 {
            whole[0] += f64::from(p[3 + c]).powi(2);
            whole[1] += f64::from(p[6 + c]).powi(2);
        }
    }
    let n = count.max(1) as f64;
    let all = l.expected_fused.len().max(1) as f64;
    [0, 1].map(|axis| (sums[axis] / n) / (whole[axis] / all).max(1e-12))
}

/// The least [`texture`] along either axis for a match to be determined by its overlap:
/// a fiftieth of the picture's.
const MIN_TEXTURE: f64 = 0.02;

/// Whether an overlap with `texture` determines a match along both axes.
pub(crate) fn textured(texture: [f64; 2]) -> bool {
    texture[0].min(texture[1]) >= MIN_TEXTURE
}

/// A floor on the contrast of an overlap for [`Fit::normalized`]: 2% of the actual
/// image's variance, per channel.
pub(super) fn contrast_floor(pyramid: &Pyramid) -> f64 {
    let image = &pyramid.levels[0].actual;
    let n = image.pixels.len().max(1) as f64;
    let mut variance = 0.0;
    for c in 0..3 {
        let mean: f64 = image.pixels.iter().map(|p| f64::from(p[c])).sum::<f64>() / n;
        variance += image
            .pixels
            .iter()
            .map(|p| (f64::from(p[c]) - mean).powi(2))
            .sum::<f64>()
            / n;
    }
    0.02 * variance / 3.0 + 1e-8
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimate::FINE_BUDGET;
    use crate::estimate::pyramid::ExpectedPyramid;
    use crate::estimate::test_images::{pattern, picture, transformed};

    const SIZE: (usize, usize) = (160, 120);

    /// The expected picture (the pattern) and the actual one `model` makes of it.
    fn pictures(model: &Model) -> (FloatImage, FloatImage) {
        (
            picture(SIZE.0, SIZE.1, pattern),
            transformed(SIZE.0, SIZE.1, model),
        )
    }

    /// `start` refined with `free` from the coarsest level to the finest.
    fn refined(pyramid: &Pyramid, start: Model, free: Free) -> Model {
        let mut model = start;
        for level in (0..=pyramid.top()).rev() {
            model = refine(
                pyramid,
                level,
                model,
                free,
                pyramid.stride(level, FINE_BUDGET),
                20,
            );
        }
        model
    }

    #[test]
    fn solve_solves_a_known_system_and_refuses_a_singular_one() {
        let mut a = [[0.0; 5]; 5];
        a[0][..3].copy_from_slice(&[2.0, 1.0, -1.0]);
        a[1][..3].copy_from_slice(&[-3.0, -1.0, 2.0]);
        a[2][..3].copy_from_slice(&[-2.0, 1.0, 2.0]);
        let x = solve(a, [8.0, -11.0, -3.0, 0.0, 0.0], 3).unwrap();
        for (got, want) in x.iter().zip([2.0, 3.0, -1.0]) {
            assert!((got - want).abs() < 1e-12, "{x:?}");
        }
        // The third row the first again.
        a[2] = a[0];
        assert_eq!(solve(a, [8.0, -11.0, -3.0, 0.0, 0.0], 3), None);
    }

    #[test]
    fn the_parameters_round_trip_through_a_model() {
        let model = Model {
            mirror: [true, false],
            rotation: 0.2,
            log_scale: [0.1, -0.05],
            about: [3.0, 4.0],
            shift: [-1.5, 2.5],
        };
        let p = parameters(&model);
        assert!((p[1] - 0.025).abs() < 1e-15 && (p[2] - 0.075).abs() < 1e-15);
        let back = with_parameters(&Model::identity([3.0, 4.0]), &p);
        assert_eq!(back.rotation, model.rotation);
        assert_eq!(back.shift, model.shift);
        for axis in 0..2 {
            assert!((back.log_scale[axis] - model.log_scale[axis]).abs() < 1e-15);
        }
        // The mirrors and the point stay the start's.
        assert_eq!(back.mirror, [false, false]);
        let masked = Free {
            rotation: true,
            scale: false,
            aspect: true,
            shift: false,
        };
        assert_eq!(masked.mask(), [true, false, true, false, false]);
    }

    #[test]
    fn the_identity_fits_the_same_picture_perfectly_over_all_of_it() {
        let image = picture(SIZE.0, SIZE.1, pattern);
        let expected = ExpectedPyramid::new(&image);
        let pyramid = Pyramid::new(&expected, &image, 2.0, usize::MAX);
        let identity = Model::identity(pyramid.centre());
        for level in 0..=pyramid.top() {
            let fit = evaluate(&pyramid, level, &identity, 1);
            assert_eq!(fit.sum_sq, 0.0);
            assert_eq!(fit.count, fit.total);
            assert_eq!(fit.overlap(), 1.0);
            assert_eq!(fit.mean(), 0.0);
            assert_eq!(fit.normalized(contrast_floor(&pyramid)), 0.0);
            assert_eq!(cost(&pyramid, level, &identity, 1), 0.0);
        }
        // The margins: a 160 x 120 picture less 6 pixels each side at full resolution.
        assert_eq!(evaluate(&pyramid, 0, &identity, 1).total, 148 * 108);
    }

    #[test]
    fn a_move_keeps_only_the_part_both_pictures_show() {
        let image = picture(SIZE.0, SIZE.1, pattern);
        let expected = ExpectedPyramid::new(&image);
        let pyramid = Pyramid::new(&expected, &image, 2.0, 1);
        // Moved 74 pixels right: of the 148 columns inside the margins (pixel centres
        // 6.5 to 153.5), the 74 from 80.5 on keep a preimage inside them.
        let moved = Model {
            shift: [74.0, 0.0],
            ..Model::identity(pyramid.centre())
        };
        let fit = evaluate(&pyramid, 0, &moved, 1);
        assert_eq!(fit.count, 74 * 108);
        assert_eq!(fit.overlap(), 0.5);
        // Moved off the picture: no overlap, an infinite residual.
        let gone = Model {
            shift: [200.0, 0.0],
            ..moved
        };
        let fit = evaluate(&pyramid, 0, &gone, 1);
        assert_eq!((fit.count, fit.mean()), (0, f64::INFINITY));
    }

    #[test]
    fn unrelated_pictures_leave_a_normalized_residual_near_one() {
        // The pattern against itself mirrored both ways: the same colours, elsewhere.
        let flipped = Model {
            mirror: [true, true],
            ..Model::identity([80.0, 60.0])
        };
        let (image, other) = pictures(&flipped);
        let expected = ExpectedPyramid::new(&image);
        let pyramid = Pyramid::new(&expected, &other, 2.0, 1);
        let fit = evaluate(&pyramid, 0, &Model::identity(pyramid.centre()), 1);
        let normalized = fit.normalized(contrast_floor(&pyramid));
        assert!((0.6..1.6).contains(&normalized), "{normalized}");
        // The right transform explains it.
        let fit = evaluate(&pyramid, 0, &flipped, 1);
        assert!(fit.normalized(contrast_floor(&pyramid)) < 1e-4);
    }

    #[test]
    fn the_fit_recovers_a_known_similarity_transform() {
        let truth = Model {
            rotation: 2f64.to_radians(),
            log_scale: [1.04f64.ln(); 2],
            shift: [3.2, -1.7],
            ..Model::identity([80.0, 60.0])
        };
        let (image, actual) = pictures(&truth);
        let expected = ExpectedPyramid::new(&image);
        let pyramid = Pyramid::new(&expected, &actual, 2.0, usize::MAX);
        let found = refined(&pyramid, Model::identity(pyramid.centre()), Free::ALL);
        assert!((found.rotation - truth.rotation).abs() < 0.01f64.to_radians());
        for axis in 0..2 {
            assert!((found.scale()[axis] - 1.04).abs() < 5e-4, "{found:?}");
            assert!(
                (found.shift[axis] - truth.shift[axis]).abs() < 0.02,
                "{found:?}"
            );
        }
        assert!(evaluate(&pyramid, 0, &found, 1).mean() < 1e-7);
    }

    #[test]
    fn refinement_moves_only_the_free_parameters() {
        let truth = Model {
            shift: [-4.5, 2.25],
            ..Model::identity([80.0, 60.0])
        };
        let (image, actual) = pictures(&truth);
        let expected = ExpectedPyramid::new(&image);
        let pyramid = Pyramid::new(&expected, &actual, 2.0, usize::MAX);
        let start = Model {
            rotation: 0.01,
            log_scale: [0.02, 0.02],
            ..Model::identity(pyramid.centre())
        };
        let moves_only = Free {
            rotation: false,
            scale: false,
            aspect: false,
            shift: true,
        };
        let found = refined(&pyramid, start, moves_only);
        assert_eq!((found.rotation, found.log_scale), (0.01, [0.02, 0.02]));
        assert_ne!(found.shift, start.shift);
        // With nothing free, nothing moves.
        let nothing = Free {
            shift: false,
            ..moves_only
        };
        assert_eq!(refined(&pyramid, start, nothing), start);
        // Everything free finds the move, and undoes the wrong start.
        let found = refined(&pyramid, start, Free::ALL);
        assert!(found.rotation.abs() < 1e-4 && found.log_scale[0].abs() < 1e-4);
        assert!((found.shift[0] + 4.5).abs() < 0.02 && (found.shift[1] - 2.25).abs() < 0.02);
    }

    #[test]
    fn texture_sees_no_edges_across_a_picture_that_varies_along_one_axis() {
        // Horizontal bands: edges across y, none across x.
        let bands = picture(SIZE.0, SIZE.1, |p| {
            [((p[1] / 9.0).sin() * 0.4 + 0.5) as f32; 3]
        });
        let expected = ExpectedPyramid::new(&bands);
        let pyramid = Pyramid::new(&expected, &bands, 2.0, 1);
        let identity = Model::identity(pyramid.centre());
        let [along_x, along_y] = texture(&pyramid, 0, &identity, 1);
        assert!(
            along_x < MIN_TEXTURE && along_y > 0.5,
            "{along_x} {along_y}"
        );
        assert!(!textured([along_x, along_y]));
        // The pattern has edges both ways over most of it.
        let image = picture(SIZE.0, SIZE.1, pattern);
        let expected = ExpectedPyramid::new(&image);
        let pyramid = Pyramid::new(&expected, &image, 2.0, 1);
        let both = texture(&pyramid, 0, &identity, 1);
        assert!(both[0] > 0.5 && both[1] > 0.5, "{both:?}");
        assert!(textured(both));
    }
}
