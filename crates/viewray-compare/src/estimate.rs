//! Estimating the camera transform between an expected and an actual image.
//!
//! The model: the actual picture is the expected one mirrored (left-right, upside down, or
//! both), scaled (per axis) and rotated about a point `p`, then moved by `t`. In
//! continuous image coordinates (x right, y down, pixel (row, col) covering
//! [col, col + 1) x [row, row + 1)), what the expected image shows at `X_e` the actual one
//! shows at
//!
//! ```text
//! X_a = p + R(theta) S M (X_e - p) + t      M = diag(+-1, +-1), S = diag(sx, sy)
//! ```
//!
//! with `R(theta)` turning clockwise as seen (x towards y). Only the overlap counts: the
//! actual pixels whose preimage lies inside the expected image (both away from the
//! borders, where the blur saw beyond the picture). What enters the picture at an edge
//! (a lens shift slides the window over the image plane) is no evidence either way.
//!
//! 1. Search (the coarsest pyramid level, about 24 to 48 pixels on the shorter side):
//!    for every mirror and each of a grid of rotations (up to 30 degrees) and of scales
//!    (0.68x to 1.45x), the expected image is warped about the centre and its masked
//!    normalized cross-correlation with the actual image is computed for every whole-pixel
//!    move at once with FFTs (Padfield's masked NCC, so that the score counts the overlap
//!    only). Moves of up to the whole image are seen; a candidate needs an overlap of
//!    [`MIN_OVERLAP`] of the picture.
//! 2. Refinement: the best candidates are refined by Levenberg-Marquardt on the sum of
//!    squared differences over the overlap (rotation, per-axis scale and move), level by
//!    level down to full resolution, sampling the expected image bilinearly.
//! 3. Model selection ([`select`]): each component (rotation, aspect ratio, scale, the
//!    move) is removed in turn and the rest refitted; a component stays only if removing
//!    it clearly raises the residual on the overlap.

use std::borrow::Cow;
use std::sync::Arc;

use rustfft::num_complex::Complex32;
use rustfft::{Fft, FftPlanner};

use crate::raster::FloatImage;

/// The smallest overlap, as a fraction of the picture, on which a transform found by the
/// search is judged: a move of half the picture in x and y at once leaves a quarter.
pub(crate) const MIN_OVERLAP: f64 = 0.2;

/// A mirror-scale-rotation-move transform from expected to actual coordinates (see the
/// module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Model {
    /// Mirrored left-right, upside down.
    pub(crate) mirror: [bool; 2],
    /// The turn, in radians, clockwise as seen.
    pub(crate) rotation: f64,
    /// The natural logarithm of the scale along x and y.
    pub(crate) log_scale: [f64; 2],
    /// The point `p` the mirrors, scale and rotation are about, in pixels.
    pub(crate) about: [f64; 2],
    /// The move `t` after them, in pixels.
    pub(crate) shift: [f64; 2],
}

impl Model {
    /// The identity, written about `about`.
    pub(crate) fn identity(about: [f64; 2]) -> Self {
        Self {
            mirror: [false; 2],
            rotation: 0.0,
            log_scale: [0.0; 2],
            about,
            shift: [0.0; 2],
        }
    }

    fn signs(&self) -> [f64; 2] {
        self.mirror.map(|m| if m { -1.0 } else { 1.0 })
    }

    /// The scales along x and y.
    pub(crate) fn scale(&self) -> [f64; 2] {
        self.log_scale.map(f64::exp)
    }

    /// `A = R(theta) S M`, rows first.
    pub(crate) fn matrix(&self) -> [[f64; 2]; 2] {
        let (s, c) = self.rotation.sin_cos();
        let signs = self.signs();
        let k = [
            self.log_scale[0].exp() * signs[0],
            self.log_scale[1].exp() * signs[1],
        ];
        [[c * k[0], -s * k[1]], [s * k[0], c * k[1]]]
    }

    /// `A^-1 = M S^-1 R(-theta)`, rows first.
    fn inverse_matrix(&self) -> [[f64; 2]; 2] {
        let (s, c) = self.rotation.sin_cos();
        let signs = self.signs();
        let k = [
            signs[0] * (-self.log_scale[0]).exp(),
            signs[1] * (-self.log_scale[1]).exp(),
        ];
        [[k[0] * c, k[0] * s], [-k[1] * s, k[1] * c]]
    }

    /// The same transform written about `q`: `t' = t + (A - I)(q - p)`.
    pub(crate) fn about_point(&self, q: [f64; 2]) -> Self {
        let a = self.matrix();
        let d = [q[0] - self.about[0], q[1] - self.about[1]];
        Self {
            about: q,
            shift: [
                self.shift[0] + (a[0][0] - 1.0) * d[0] + a[0][1] * d[1],
                self.shift[1] + a[1][0] * d[0] + (a[1][1] - 1.0) * d[1],
            ],
            ..*self
        }
    }

    /// The point the transform leaves where it is, `p + (I - A)^-1 t`, when `I - A` is
    /// well conditioned (a scale or a rotation; not a pure move, and not a mirror alone).
    pub(crate) fn fixed_point(&self) -> Option<[f64; 2]> {
        let a = self.matrix();
        let m = [[1.0 - a[0][0], -a[0][1]], [-a[1][0], 1.0 - a[1][1]]];
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        // Both singular values of I - A must be clearly away from zero: at least a 2%
        // scale or a turn of a degree.
        let norm = m.iter().flatten().map(|v| v * v).sum::<f64>();
        if det.abs() < 1e-4 || det.abs() < 0.02 * norm.sqrt() * 0.02 {
            return None;
        }
        let t = self.shift;
        Some([
            self.about[0] + (m[1][1] * t[0] - m[0][1] * t[1]) / det,
            self.about[1] + (-m[1][0] * t[0] + m[0][0] * t[1]) / det,
        ])
    }

    /// Where the actual image's point `x` comes from in the expected image.
    fn preimage(&self, inverse: &[[f64; 2]; 2], x: [f64; 2]) -> [f64; 2] {
        let y = [
            x[0] - self.about[0] - self.shift[0],
            x[1] - self.about[1] - self.shift[1],
        ];
        [
            self.about[0] + inverse[0][0] * y[0] + inverse[0][1] * y[1],
            self.about[1] + inverse[1][0] * y[0] + inverse[1][1] * y[1],
        ]
    }
}

/// Which parts of a [`Model`] may differ from the identity while it is fitted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Free {
    pub(crate) rotation: bool,
    /// A uniform scale.
    pub(crate) scale: bool,
    /// Different scales along x and y.
    pub(crate) aspect: bool,
    /// The move `t` (else it stays as it is, usually zero about a chosen point).
    pub(crate) shift: bool,
}

impl Free {
    pub(crate) const ALL: Free = Free {
        rotation: true,
        scale: true,
        aspect: true,
        shift: true,
    };

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

/// One level of the expected image's pyramid: `factor` full-resolution pixels per level
/// pixel.
#[derive(Clone, Debug)]
pub(crate) struct ExpectedLevel {
    factor: f64,
    image: FloatImage,
    /// The image's colour and its x and y derivatives, per pixel: one bilinear lookup
    /// serves a fit's residual and its Jacobian.
    fused: Vec<[f32; 9]>,
}

/// The expected image's side of the pyramids, down to the search level: it depends on
/// the expected image alone, so one serves every actual image judged against it.
#[derive(Clone, Debug)]
pub(crate) struct ExpectedPyramid {
    levels: Vec<ExpectedLevel>,
}

impl ExpectedPyramid {
    /// The pyramid of the blurred, sRGB-encoded expected image: each level blurred by 1
    /// level pixel and halved, down to the search level.
    pub(crate) fn new(expected: &FloatImage) -> Self {
        let mut levels = Vec::new();
        let (mut image, mut factor) = (expected.clone(), 1.0);
        loop {
            let (dx, dy) = image.gradients();
            let fused = image
                .pixels
                .iter()
                .zip(&dx.pixels)
                .zip(&dy.pixels)
                .map(|((v, x), y)| [v[0], v[1], v[2], x[0], x[1], x[2], y[0], y[1], y[2]])
                .collect();
            let next_side = image.width.min(image.height) / 2;
            let next = (next_side >= SEARCH_SIDE).then(|| image.gaussian_blur(1.0).downsample_2x());
            levels.push(ExpectedLevel {
                factor,
                image,
                fused,
            });
            let Some(next) = next else { break };
            image = next;
            factor *= 2.0;
        }
        Self { levels }
    }
}

/// One level of the image pyramids: `factor` full-resolution pixels per level pixel.
pub(crate) struct Level<'a> {
    factor: f64,
    expected: &'a FloatImage,
    /// The expected image's colour and its derivatives (see [`ExpectedLevel`]).
    expected_fused: &'a [[f32; 9]],
    actual: Cow<'a, FloatImage>,
}

/// The two images, blurred and sRGB-encoded, as pyramids.
pub(crate) struct Pyramid<'a> {
    levels: Vec<Level<'a>>,
    /// The full-resolution size.
    size: [f64; 2],
    /// How far from the borders a point must lie to count (full-resolution pixels, at
    /// level 0): the blur saw beyond the picture there.
    margin: f64,
}

/// Side of the search level: its shorter side is at least this (unless the images are
/// smaller), and halving once more would make it shorter.
const SEARCH_SIDE: usize = 16;

impl<'a> Pyramid<'a> {
    /// Builds the pyramids of two images of the same size, blurred by `blur_sigma` pixels,
    /// down to the search level or to at most `max_levels` levels: the expected image's
    /// from its prepared pyramid, the actual image's here, the same way.
    pub(crate) fn new(
        expected: &'a ExpectedPyramid,
        actual: &'a FloatImage,
        blur_sigma: f32,
        max_levels: usize,
    ) -> Self {
        let count = expected.levels.len().min(max_levels.max(1));
        let mut levels: Vec<Level<'a>> = Vec::with_capacity(count);
        for e in &expected.levels[..count] {
            let actual = match levels.last() {
                None => Cow::Borrowed(actual),
                Some(previous) => Cow::Owned(previous.actual.gaussian_blur(1.0).downsample_2x()),
            };
            levels.push(Level {
                factor: e.factor,
                expected: &e.image,
                expected_fused: &e.fused,
                actual,
            });
        }
        Self {
            levels,
            size: [actual.width as f64, actual.height as f64],
            margin: (2.5 * f64::from(blur_sigma)).max(1.0),
        }
    }

    pub(crate) fn centre(&self) -> [f64; 2] {
        [self.size[0] / 2.0, self.size[1] / 2.0]
    }

    fn top(&self) -> usize {
        self.levels.len() - 1
    }

    /// The margin at a level: the blur's, plus a level pixel for the level's own.
    fn margin(&self, level: usize) -> f64 {
        self.margin + self.levels[level].factor
    }

    /// The step between evaluated pixels at `level` that keeps about `budget` of them.
    fn stride(&self, level: usize, budget: usize) -> usize {
        let l = &self.levels[level];
        let pixels = l.actual.width * l.actual.height;
        let mut stride = 1;
        while pixels / (stride * stride) > budget {
            stride += 1;
        }
        stride
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
fn sample(image: &FloatImage, x: f64, y: f64) -> [f32; 3] {
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
fn cost(pyramid: &Pyramid, level: usize, model: &Model, stride: usize) -> f64 {
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
fn for_each_overlap(
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
pub(crate) fn evaluate(pyramid: &Pyramid, level: usize, model: &Model, stride: usize) -> Fit {
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
pub(crate) fn refine(
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
pub(crate) fn solve(mut a: [[f64; 5]; 5], mut b: [f64; 5], n: usize) -> Option<[f64; 5]> {
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

/// A candidate of the search: a model and its score there (higher is better).
#[derive(Clone, Copy, Debug)]
struct Candidate {
    score: f64,
    model: Model,
}

/// The masked normalized cross-correlation of the actual image with warped expected
/// images, for every whole-pixel move at once (Padfield, "Masked object registration in
/// the Fourier domain", 2012).
struct Correlator {
    width: usize,
    height: usize,
    padded: [usize; 2],
    row_forward: Arc<dyn Fft<f32>>,
    column_forward: Arc<dyn Fft<f32>>,
    row_inverse: Arc<dyn Fft<f32>>,
    column_inverse: Arc<dyn Fft<f32>>,
    scratch: Vec<Complex32>,
    transposed: Vec<Complex32>,
    /// Spectra of the actual image's mask m_f, of m_f f and of m_f f^2.
    mask_spectrum: Vec<Complex32>,
    value_spectrum: Vec<Complex32>,
    square_spectrum: Vec<Complex32>,
    /// The floor on either side's variance over an overlap, per pixel: a flat overlap
    /// correlates with nothing.
    variance_floor: f64,
}

impl Correlator {
    fn new(actual: &[f32], mask: &[f32], width: usize, height: usize) -> Self {
        let padded = [2 * width, 2 * height];
        let mut planner = FftPlanner::new();
        let row_forward = planner.plan_fft_forward(padded[0]);
        let column_forward = planner.plan_fft_forward(padded[1]);
        let row_inverse = planner.plan_fft_inverse(padded[0]);
        let column_inverse = planner.plan_fft_inverse(padded[1]);
        let scratch_len = [&row_forward, &column_forward, &row_inverse, &column_inverse]
            .iter()
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        let mut correlator = Self {
            width,
            height,
            padded,
            row_forward,
            column_forward,
            row_inverse,
            column_inverse,
            scratch: vec![Complex32::default(); scratch_len],
            transposed: vec![Complex32::default(); padded[0] * padded[1]],
            mask_spectrum: Vec::new(),
            value_spectrum: Vec::new(),
            square_spectrum: Vec::new(),
            variance_floor: 0.0,
        };
        let (count, sum, sum_sq) =
            actual
                .iter()
                .zip(mask)
                .fold((0.0f64, 0.0f64, 0.0f64), |(n, s, q), (&v, &m)| {
                    let (v, m) = (f64::from(v), f64::from(m));
                    (n + m, s + m * v, q + m * v * v)
                });
        let variance = if count > 0.0 {
            (sum_sq / count - (sum / count).powi(2)).max(0.0)
        } else {
            0.0
        };
        correlator.variance_floor = 0.02 * variance + 1e-6;
        correlator.mask_spectrum = correlator.spectrum(mask, None);
        correlator.value_spectrum = correlator.spectrum(actual, Some(mask));
        let squares: Vec<f32> = actual.iter().map(|v| v * v).collect();
        correlator.square_spectrum = correlator.spectrum(&squares, Some(mask));
        correlator
    }

    /// The 2D FFT of `values` (times `mask`), zero-padded.
    fn spectrum(&mut self, values: &[f32], mask: Option<&[f32]>) -> Vec<Complex32> {
        let mut data = self.pad(|i| values[i] * mask.map_or(1.0, |m| m[i]), |_| 0.0);
        self.fft2(&mut data, false);
        data
    }

    /// The zero-padded complex image with real part `re(i)` and imaginary part `im(i)` at
    /// pixel index `i`.
    fn pad(&self, re: impl Fn(usize) -> f32, im: impl Fn(usize) -> f32) -> Vec<Complex32> {
        let [pw, ph] = self.padded;
        let mut data = vec![Complex32::default(); pw * ph];
        for row in 0..self.height {
            for col in 0..self.width {
                let i = row * self.width + col;
                data[row * pw + col] = Complex32::new(re(i), im(i));
            }
        }
        data
    }

    fn fft2(&mut self, data: &mut [Complex32], inverse: bool) {
        let [pw, ph] = self.padded;
        let (rows, columns) = if inverse {
            (&self.row_inverse, &self.column_inverse)
        } else {
            (&self.row_forward, &self.column_forward)
        };
        rows.process_with_scratch(data, &mut self.scratch);
        transpose(data, &mut self.transposed, pw, ph);
        columns.process_with_scratch(&mut self.transposed, &mut self.scratch);
        transpose(&self.transposed, data, ph, pw);
    }

    /// The masked NCC of the actual image with the moving image `g` (valid where `mask`
    /// is 1) for every move u: actual(x) against g(x - u). Calls `visit(u, ncc, overlap
    /// pixels)` for every move whose overlap has at least `min_count` pixels.
    fn correlate(
        &mut self,
        g: &[f32],
        mask: &[f32],
        min_count: f64,
        mut visit: impl FnMut([i64; 2], f64, f64),
    ) {
        let [pw, ph] = self.padded;
        let size = pw * ph;
        // One complex FFT carries two real images: m_g + i m_g g, then m_g g^2.
        let mut pair = self.pad(|i| mask[i], |i| mask[i] * g[i]);
        self.fft2(&mut pair, false);
        let mut squares = self.pad(|i| mask[i] * g[i] * g[i], |_| 0.0);
        self.fft2(&mut squares, false);
        let mirror_index = |k: usize| {
            let (row, col) = (k / pw, k % pw);
            ((ph - row) % ph) * pw + (pw - col) % pw
        };
        // Products whose inverses are real, packed two to a complex inverse FFT.
        let mut first = vec![Complex32::default(); size];
        let mut second = vec![Complex32::default(); size];
        let mut third = vec![Complex32::default(); size];
        let i = Complex32::new(0.0, 1.0);
        for k in 0..size {
            let z = pair[k];
            let zc = pair[mirror_index(k)].conj();
            let mask_g = (z + zc) * 0.5;
            let value_g = (z - zc) * (-0.5 * i);
            let (mask_g, value_g, square_g) = (mask_g.conj(), value_g.conj(), squares[k].conj());
            let (mf, ff, f2) = (
                self.mask_spectrum[k],
                self.value_spectrum[k],
                self.square_spectrum[k],
            );
            // n + i S_f
            first[k] = mf * mask_g + i * (ff * mask_g);
            // S_g + i S_ff
            second[k] = mf * value_g + i * (f2 * mask_g);
            // S_gg + i S_fg
            third[k] = mf * square_g + i * (ff * value_g);
        }
        self.fft2(&mut first, true);
        self.fft2(&mut second, true);
        self.fft2(&mut third, true);
        let scale = 1.0 / size as f64;
        let floor = self.variance_floor;
        for uy in -(self.height as i64 - 1)..self.height as i64 {
            for ux in -(self.width as i64 - 1)..self.width as i64 {
                let k =
                    (uy.rem_euclid(ph as i64) as usize) * pw + ux.rem_euclid(pw as i64) as usize;
                let n = f64::from(first[k].re) * scale;
                if n < min_count {
                    continue;
                }
                let s_f = f64::from(first[k].im) * scale;
                let s_g = f64::from(second[k].re) * scale;
                let s_ff = f64::from(second[k].im) * scale;
                let s_gg = f64::from(third[k].re) * scale;
                let s_fg = f64::from(third[k].im) * scale;
                let var_f = (s_ff - s_f * s_f / n).max(floor * n);
                let var_g = (s_gg - s_g * s_g / n).max(floor * n);
                let ncc = (s_fg - s_f * s_g / n) / (var_f * var_g).sqrt();
                visit([ux, uy], ncc, n);
            }
        }
    }
}

fn transpose(input: &[Complex32], output: &mut [Complex32], width: usize, height: usize) {
    for row in 0..height {
        for col in 0..width {
            output[col * height + row] = input[row * width + col];
        }
    }
}

/// The luminance-like mean of the channels.
fn grey(p: [f32; 3]) -> f32 {
    (p[0] + p[1] + p[2]) / 3.0
}

/// The search's grid: rotations (degrees) at scale 1, and scales at no rotation.
fn search_grid() -> Vec<(f64, f64)> {
    let mut grid = vec![(0.0, 1.0)];
    for step in 1..=6 {
        let degrees = 5.0 * f64::from(step);
        grid.push((degrees, 1.0));
        grid.push((-degrees, 1.0));
    }
    // 0.68x to 1.47x, 8% apart.
    for step in -5..=5 {
        if step != 0 {
            grid.push((0.0, 1.08f64.powi(step)));
        }
    }
    grid
}

/// Searches the coarsest level for the best starts: for every mirror, rotation and scale
/// of the grid, the best moves by masked NCC. Returns them best first.
fn search(pyramid: &Pyramid) -> Vec<Candidate> {
    let level = pyramid.top();
    let l = &pyramid.levels[level];
    let (w, h) = (l.actual.width, l.actual.height);
    let centre = pyramid.centre();
    let margin = pyramid.margin(level);
    let [full_w, full_h] = pyramid.size;
    let inside = |p: [f64; 2]| {
        p[0] >= margin && p[0] <= full_w - margin && p[1] >= margin && p[1] <= full_h - margin
    };
    let actual: Vec<f32> = l.actual.pixels.iter().map(|&p| grey(p)).collect();
    let actual_mask: Vec<f32> = (0..w * h)
        .map(|i| {
            let x = [
                ((i % w) as f64 + 0.5) * l.factor,
                ((i / w) as f64 + 0.5) * l.factor,
            ];
            if inside(x) { 1.0 } else { 0.0 }
        })
        .collect();
    let expected: Vec<f32> = l.expected.pixels.iter().map(|&p| grey(p)).collect();
    let mut correlator = Correlator::new(&actual, &actual_mask, w, h);
    let inside_count: f32 = actual_mask.iter().sum();
    let min_count = MIN_OVERLAP * f64::from(inside_count);
    let mut candidates = Vec::new();
    let mut warped = vec![0.0f32; w * h];
    let mut mask = vec![0.0f32; w * h];
    for mirror in [[false, false], [true, false], [false, true], [true, true]] {
        for (degrees, scale) in search_grid() {
            let model = Model {
                mirror,
                rotation: f64::to_radians(degrees),
                log_scale: [scale.ln(); 2],
                about: centre,
                shift: [0.0; 2],
            };
            let inverse = model.inverse_matrix();
            for row in 0..h {
                for col in 0..w {
                    let x = [(col as f64 + 0.5) * l.factor, (row as f64 + 0.5) * l.factor];
                    let e = model.preimage(&inverse, x);
                    let i = row * w + col;
                    if inside(e) {
                        let ex = ((e[0] / l.factor - 0.5).clamp(0.0, (w - 1) as f64)) as f32;
                        let ey = ((e[1] / l.factor - 0.5).clamp(0.0, (h - 1) as f64)) as f32;
                        let (x0, y0) = (ex.floor() as usize, ey.floor() as usize);
                        let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
                        let (tx, ty) = (ex - x0 as f32, ey - y0 as f32);
                        let top = expected[y0 * w + x0] * (1.0 - tx) + expected[y0 * w + x1] * tx;
                        let bottom =
                            expected[y1 * w + x0] * (1.0 - tx) + expected[y1 * w + x1] * tx;
                        warped[i] = top * (1.0 - ty) + bottom * ty;
                        mask[i] = 1.0;
                    } else {
                        warped[i] = 0.0;
                        mask[i] = 0.0;
                    }
                }
            }
            // The two best moves of this warp, at least two level pixels apart.
            let mut best: [Option<([i64; 2], f64)>; 2] = [None, None];
            correlator.correlate(&warped, &mask, min_count, |u, ncc, _| {
                let beats = |slot: &Option<([i64; 2], f64)>| slot.is_none_or(|(_, s)| ncc > s);
                if beats(&best[0]) {
                    let near = best[0]
                        .is_some_and(|(v, _)| (v[0] - u[0]).abs() <= 2 && (v[1] - u[1]).abs() <= 2);
                    if !near {
                        best[1] = best[0];
                    }
                    best[0] = Some((u, ncc));
                } else if beats(&best[1]) {
                    let near = best[0]
                        .is_some_and(|(v, _)| (v[0] - u[0]).abs() <= 2 && (v[1] - u[1]).abs() <= 2);
                    if !near {
                        best[1] = Some((u, ncc));
                    }
                }
            });
            for (u, ncc) in best.into_iter().flatten() {
                candidates.push(Candidate {
                    score: ncc,
                    model: Model {
                        shift: [u[0] as f64 * l.factor, u[1] as f64 * l.factor],
                        ..model
                    },
                });
            }
        }
    }
    candidates.sort_by(|a, b| b.score.total_cmp(&a.score));
    candidates
}

/// The outcome of estimating the transform.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Estimate {
    /// The transform with only the components the evidence supports (see [`select`]).
    pub(crate) model: Model,
    /// Which components it keeps.
    pub(crate) kept: Free,
    /// Its fit on its overlap at full resolution.
    pub(crate) fit: Fit,
    /// The identity's fit on the same pixels.
    pub(crate) identity_mean: f64,
    /// The normalized residual of the model (see [`Fit::normalized`]).
    pub(crate) normalized: f64,
    /// The edges in its overlap (see [`texture`]).
    pub(crate) texture: [f64; 2],
    /// Whether the picture repeats, so that another move explains it about as well
    /// (see [`ambiguous`]).
    pub(crate) ambiguous: bool,
}

/// How much of the picture's edges, along x and along y, the overlap of a transform has:
/// the mean squared derivative of the expected image over the overlap relative to its
/// mean over the whole picture, per axis. A match is determined along an axis only where
/// the overlap has edges across it: a strip of sky above a horizon matches itself slid
/// sideways (its x derivatives are nil, a thousandth of the picture's).
pub(crate) fn texture(pyramid: &Pyramid, level: usize, model: &Model, stride: usize) -> [f64; 2] {
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

/// How many of the search's best candidates are ranked again by their coverage.
const CANDIDATES: usize = 24;

/// How much of the picture's edges a match covers, from 0 to 1: its overlap's share of
/// the picture times the edges there along the poorer axis (see [`texture`]).
fn coverage(texture: [f64; 2], overlap: f64) -> f64 {
    (texture[0].min(texture[1]) * overlap).min(1.0)
}

/// The rank of a refined match (lower is better): its normalized residual (see
/// [`Fit::normalized`]), plus a hundredth for what of the picture's edges it leaves
/// uncovered. Two right answers differ in the residual; a right answer and a strip that
/// matches itself slid sideways, in the coverage.
fn rank(fit: &Fit, texture: [f64; 2], floor: f64) -> f64 {
    fit.normalized(floor) + 0.01 * (1.0 - coverage(texture, fit.overlap()))
}

/// Two matches are as good as each other when the worse one's normalized residual is at
/// most `AMBIGUITY` times the better one's plus `AMBIGUITY_FLOOR`: a repeat of a tiled
/// wall leaves twice what the right move leaves (the sampling differs), a wrong repeat
/// where the overlap also holds the ground or an edge thirty times as much.
const AMBIGUITY: f64 = 3.0;
const AMBIGUITY_FLOOR: f64 = 0.0005;

/// The pixels to evaluate at full resolution.
const FINE_BUDGET: usize = 6_000;

/// How much lower the best mirrored candidate's normalized residual must be than the best
/// unmirrored one's to be believed: a nearly symmetric picture looks much the same
/// mirrored, and then the simpler answer stands.
const MIRROR_ADVANTAGE: f64 = 0.5;

/// Estimates the transform by the full search (see the module doc), then selects the
/// components the evidence supports. `anchors` are the points a scale, rotation or mirror
/// may be about without a move (the image centre, and the principal point when known);
/// `extra` are starts to refine besides the search's (the moves a scene predicts).
pub(crate) fn estimate_search(
    pyramid: &Pyramid,
    anchors: &[[f64; 2]],
    extra: &[Model],
    tolerances: &Tolerances,
) -> Estimate {
    let top = pyramid.top();
    let mut candidates = search(pyramid);
    let floor = contrast_floor(pyramid);
    // The best by correlation, ranked again by how much of the picture's edges they
    // match: a strip of sky and ground slid sideways correlates as well as the right
    // move, but covers little.
    candidates.truncate(CANDIDATES);
    let mut ranked: Vec<(f64, Candidate)> = candidates
        .into_iter()
        .map(|c| {
            let fit = evaluate(pyramid, top, &c.model, 1);
            let cover = coverage(texture(pyramid, top, &c.model, 1), fit.overlap());
            (c.score - 0.1 * (1.0 - cover), c)
        })
        .collect();
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0));
    // Refine the best few of each mirror class at the search level.
    let mut refined: Vec<(f64, Model)> = Vec::new();
    let mut taken = [0usize; 4];
    let class = |m: &Model| usize::from(m.mirror[0]) + 2 * usize::from(m.mirror[1]);
    let mut starts: Vec<Model> = vec![Model::identity(pyramid.centre())];
    starts.extend_from_slice(extra);
    for (_, candidate) in &ranked {
        let c = class(&candidate.model);
        let limit = if c == 0 { 4 } else { 1 };
        if taken[c] < limit && textured(texture(pyramid, top, &candidate.model, 1)) {
            taken[c] += 1;
            starts.push(candidate.model);
        }
    }
    for start in starts {
        let model = refine(pyramid, top, start, Free::ALL, 1, 12);
        let fit = evaluate(pyramid, top, &model, 1);
        let texture = texture(pyramid, top, &model, 1);
        if fit.overlap() >= MIN_OVERLAP && textured(texture) {
            refined.push((rank(&fit, texture, floor), model));
        }
    }
    refined.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Carry down the pyramid the best unmirrored start, the runner-up when it comes near
    // (within twice the residual), and the best mirrored one when it could still win.
    let plain: Vec<(f64, Model)> = refined
        .iter()
        .copied()
        .filter(|(_, m)| class(m) == 0)
        .collect();
    let mirrored = refined.iter().copied().find(|(_, m)| class(m) != 0);
    let mut carried: Vec<Model> = Vec::new();
    if let Some(&(first, model)) = plain.first() {
        carried.push(model);
        if let Some(&(second, model)) = plain.get(1)
            && second < 2.0 * first
        {
            carried.push(model);
        }
    }
    if let Some((score, model)) = mirrored
        && plain.first().is_none_or(|&(first, _)| score < first)
    {
        carried.push(model);
    }
    if carried.is_empty() {
        carried.push(Model::identity(pyramid.centre()));
    }
    let mut best_plain: Option<(f64, Model)> = None;
    let mut best_mirrored: Option<(f64, Model)> = None;
    for start in carried {
        let mut model = start;
        for level in (0..top).rev() {
            let budget = if level == 0 {
                FINE_BUDGET
            } else {
                FINE_BUDGET / 2
            };
            model = refine(
                pyramid,
                level,
                model,
                Free::ALL,
                pyramid.stride(level, budget),
                5,
            );
        }
        let stride = pyramid.stride(0, FINE_BUDGET);
        let fit = evaluate(pyramid, 0, &model, stride);
        let texture = texture(pyramid, 0, &model, stride);
        if fit.overlap() < MIN_OVERLAP || !textured(texture) {
            continue;
        }
        let score = rank(&fit, texture, floor);
        let slot = if class(&model) == 0 {
            &mut best_plain
        } else {
            &mut best_mirrored
        };
        if slot.is_none_or(|(s, _)| score < s) {
            *slot = Some((score, model));
        }
    }
    let mut best = best_plain;
    if let Some((mirrored_score, _)) = best_mirrored
        && best_plain.is_none_or(|(plain, _)| mirrored_score < MIRROR_ADVANTAGE * plain)
    {
        best = best_mirrored;
    }
    // Another repeat of a repeating pattern may match better (take it) or as well (then
    // the move is not determined).
    let mut ambiguous = false;
    if let Some((_, model)) = best
        && let Some((other_score, other)) = other_move(pyramid, &model)
    {
        let score = evaluate(pyramid, 0, &model, pyramid.stride(0, FINE_BUDGET)).normalized(floor);
        if other_score < 0.5 * score {
            let again = other_move(pyramid, &other);
            ambiguous = again.is_some_and(|(s, _)| s < AMBIGUITY * other_score + AMBIGUITY_FLOOR);
            best = Some((other_score, other));
        } else {
            ambiguous = other_score < AMBIGUITY * score + AMBIGUITY_FLOOR;
        }
    }
    let best = best.map_or(Model::identity(pyramid.centre()), |(_, m)| m);
    let mut estimate = select(pyramid, best, anchors, tolerances);
    estimate.ambiguous = ambiguous;
    estimate
}

/// The best other move near `model`'s: a repeating pattern (a tiled wall filling what
/// is left in common) matches itself moved by its period, and a search on a blurred
/// level may have taken the wrong repeat. Along x and along y, from 3 search-level pixels
/// up to a quarter of the picture away, the dips of the squared difference that come
/// near `model`'s at the search level (the repeats) are refined, the move alone, down to
/// full resolution. Returns the best one's normalized residual there (see
/// [`Fit::normalized`]) and its model.
fn other_move(pyramid: &Pyramid, model: &Model) -> Option<(f64, Model)> {
    let top = pyramid.top();
    let l = &pyramid.levels[top];
    let floor = contrast_floor(pyramid);
    let moves_only = Free {
        rotation: false,
        scale: false,
        aspect: false,
        shift: true,
    };
    let here = evaluate(pyramid, top, model, 1).normalized(floor);
    let mut best: Option<(f64, Model)> = None;
    for (axis, size) in [l.actual.width, l.actual.height].into_iter().enumerate() {
        let reach = (size / 4).max(3) as i64;
        let moved = |k: i64| {
            let mut m = *model;
            m.shift[axis] += k as f64 * l.factor;
            m
        };
        let scores: Vec<(i64, f64)> = (-reach - 1..=reach + 1)
            .map(|k| {
                let fit = evaluate(pyramid, top, &moved(k), 1);
                let score = if fit.overlap() >= MIN_OVERLAP {
                    fit.normalized(floor)
                } else {
                    f64::INFINITY
                };
                (k, score)
            })
            .collect();
        let mut dips: Vec<(i64, f64)> = scores
            .windows(3)
            .filter(|w| w[1].0.abs() >= 3 && w[1].1 <= w[0].1 && w[1].1 <= w[2].1)
            .map(|w| w[1])
            .filter(|&(_, score)| score < 4.0 * here + 0.002)
            .collect();
        dips.sort_by(|a, b| a.1.total_cmp(&b.1));
        for &(k, _) in dips.iter().take(3) {
            // Refined at the search level first: only a repeat that still comes near is
            // followed down to full resolution.
            let mut other = refine(pyramid, top, moved(k), moves_only, 1, 6);
            if evaluate(pyramid, top, &other, 1).normalized(floor) > 3.0 * here + 0.002 {
                continue;
            }
            for level in (0..top).rev() {
                let stride = pyramid.stride(level, FINE_BUDGET);
                other = refine(pyramid, level, other, moves_only, stride, 6);
            }
            let apart = (other.shift[axis] - model.shift[axis]).abs() >= 2.0 * l.factor;
            let stride = pyramid.stride(0, FINE_BUDGET);
            let fit = evaluate(pyramid, 0, &other, stride);
            if apart && fit.overlap() >= MIN_OVERLAP {
                let score = fit.normalized(floor);
                if best.is_none_or(|(b, _)| score < b) {
                    best = Some((score, other));
                }
            }
        }
    }
    best
}

/// Estimates a small transform without a search, for images that already look alike:
/// refines from the identity at the finer levels, then selects the components.
pub(crate) fn estimate_local(
    pyramid: &Pyramid,
    anchors: &[[f64; 2]],
    tolerances: &Tolerances,
) -> Estimate {
    let mut model = Model::identity(pyramid.centre());
    let start = 1.min(pyramid.top());
    for level in (0..=start).rev() {
        let stride = pyramid.stride(level, FINE_BUDGET);
        model = refine(pyramid, level, model, Free::ALL, stride, 10);
    }
    select(pyramid, model, anchors, tolerances)
}

/// A floor on the contrast of an overlap for [`Fit::normalized`]: 2% of the actual
/// image's variance, per channel.
fn contrast_floor(pyramid: &Pyramid) -> f64 {
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

/// How much a component must raise the mean squared difference on the overlap, when it
/// is removed, to be kept: by half, and by more than an RMS of a third of an 8-bit code.
fn clearly_worse(reduced: f64, full: f64) -> bool {
    reduced > 1.5 * full + (0.33f64 / 255.0).powi(2)
}

/// The sizes below which a component is measurement noise, whatever the residual says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tolerances {
    /// Pixels of move along x or y.
    pub(crate) shift: f64,
    /// Relative scale error along x or y.
    pub(crate) scale: f64,
    /// Radians of turn.
    pub(crate) rotation: f64,
}

/// How a reduced model treats the move: free, or none about an anchor.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Move {
    Free,
    About([f64; 2]),
}

/// How a reduced model scales.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scaling {
    None,
    Uniform,
    PerAxis,
}

/// Model selection: every reduction of `model` (the turn kept or dropped; the scale per
/// axis, uniform or none; the move free or none about one of the `anchors`) is refitted,
/// and the simplest whose residual on the overlap is not clearly worse than the full
/// model's wins (the lowest residual among equally simple ones). Components within their
/// tolerance are dropped without a test: they would not be named, and the others are
/// refitted without them.
pub(crate) fn select(
    pyramid: &Pyramid,
    model: Model,
    anchors: &[[f64; 2]],
    tolerances: &Tolerances,
) -> Estimate {
    let stride = pyramid.stride(0, FINE_BUDGET);
    let model = model.about_point(pyramid.centre());
    let full = cost(pyramid, 0, &model, stride);
    let [sx, sy] = model.scale();
    let turned = model.rotation.abs() >= tolerances.rotation;
    let per_axis = (sx / sy - 1.0).abs() >= tolerances.scale;
    let scaled = per_axis || (sx - 1.0).abs().max((sy - 1.0).abs()) >= tolerances.scale;
    let moved = |anchor: [f64; 2]| {
        let t = model.about_point(anchor).shift;
        t[0].abs().max(t[1].abs()) >= tolerances.shift
    };
    let mut moves: Vec<Move> = anchors.iter().map(|&a| Move::About(a)).collect();
    if anchors.iter().all(|&a| moved(a)) {
        moves.push(Move::Free);
    }
    let scalings: &[Scaling] = match (scaled, per_axis) {
        (_, true) => &[Scaling::PerAxis, Scaling::Uniform, Scaling::None],
        (true, false) => &[Scaling::Uniform, Scaling::None],
        (false, false) => &[Scaling::None],
    };
    let turns: &[bool] = if turned { &[true, false] } else { &[false] };
    // (parameters, cost, what stays free, the refitted model)
    let mut best: Option<(usize, f64, Free, Model)> = None;
    for &turn in turns {
        for &scaling in scalings {
            for &how in &moves {
                let mut start = model;
                if !turn {
                    start.rotation = 0.0;
                }
                match scaling {
                    Scaling::None => start.log_scale = [0.0; 2],
                    Scaling::Uniform => {
                        let mean = 0.5 * (start.log_scale[0] + start.log_scale[1]);
                        start.log_scale = [mean; 2];
                    }
                    Scaling::PerAxis => {}
                }
                if let Move::About(anchor) = how {
                    start = start.about_point(anchor);
                    start.shift = [0.0; 2];
                }
                let free = Free {
                    rotation: turn,
                    scale: scaling != Scaling::None,
                    aspect: scaling == Scaling::PerAxis,
                    shift: how == Move::Free,
                };
                let refit = refine(pyramid, 0, start, free, stride, 8);
                let c = cost(pyramid, 0, &refit, stride);
                if clearly_worse(c, full) {
                    continue;
                }
                // A scale per axis counts as much as a uniform scale about a point of its
                // own: when the two fit alike, the lower residual decides.
                let parameters = usize::from(turn)
                    + match scaling {
                        Scaling::None => 0,
                        Scaling::Uniform => 1,
                        Scaling::PerAxis => 3,
                    }
                    + if how == Move::Free { 2 } else { 0 };
                if best.is_none_or(|(p, bc, _, _)| (parameters, c) < (p, bc)) {
                    best = Some((parameters, c, free, refit));
                }
            }
        }
    }
    // The full model itself, when every reduction is clearly worse.
    let (kept, model) = best.map_or(
        (
            Free {
                rotation: turned,
                scale: scaled,
                aspect: per_axis,
                shift: true,
            },
            model,
        ),
        |(_, _, free, refit)| (free, refit),
    );
    let fit = evaluate(pyramid, 0, &model, stride);
    // The identity's squared difference on the model's overlap.
    let l = &pyramid.levels[0];
    let mut identity_fit = Fit::default();
    for_each_overlap(pyramid, 0, &model, stride, |[row, col], x, _| {
        let e = sample(l.expected, x[0], x[1]);
        let a = l.actual.at(row, col);
        identity_fit.count += 1;
        for c in 0..3 {
            let d = f64::from(e[c] - a[c]);
            identity_fit.sum_sq += d * d;
        }
    });
    Estimate {
        model,
        kept,
        fit,
        identity_mean: identity_fit.mean(),
        normalized: fit.normalized(contrast_floor(pyramid)),
        texture: texture(pyramid, 0, &model, stride),
        ambiguous: false,
    }
}

/// A move the scene predicts, checked on the sharp (unblurred) images where the search
/// cannot see it: when so little is left in common that the blur's margins would leave
/// nothing. The move is measured to half a pixel within 3 pixels of the prediction; it
/// stands when the images agree there and clearly disagree 2 pixels further in any
/// direction (the part in common has structure, and it is where the scene says).
/// Returns the measured move, the fraction of the picture in common and the fraction of
/// the difference there that the move explains.
pub(crate) fn verify_move(
    expected: &FloatImage,
    actual: &FloatImage,
    predicted: [f64; 2],
) -> Option<([f64; 2], f64, f64)> {
    let (w, h) = (expected.width as f64, expected.height as f64);
    // The mean squared difference over the pixels whose preimage lies inside the expected
    // image (or, with `identity`, of the same pixels unmoved), and their count.
    let residual = |t: [f64; 2], identity: bool| -> (f64, usize) {
        let mut sum = 0.0;
        let mut count = 0;
        for row in 0..actual.height {
            let y = row as f64 + 0.5;
            let ey = y - t[1];
            if !(0.5..=h - 0.5).contains(&ey) {
                continue;
            }
            for col in 0..actual.width {
                let x = col as f64 + 0.5;
                let ex = x - t[0];
                if !(0.5..=w - 0.5).contains(&ex) {
                    continue;
                }
                let e = if identity {
                    expected.at(row, col)
                } else {
                    expected.sample_bilinear(ex, ey)
                };
                let a = actual.at(row, col);
                for c in 0..3 {
                    let d = f64::from(e[c] - a[c]);
                    sum += d * d;
                }
                count += 1;
            }
        }
        (
            if count == 0 {
                f64::INFINITY
            } else {
                sum / (3 * count) as f64
            },
            count,
        )
    };
    let mut best = (f64::INFINITY, predicted);
    for dy in -6..=6 {
        for dx in -6..=6 {
            let t = [
                predicted[0] + 0.5 * f64::from(dx),
                predicted[1] + 0.5 * f64::from(dy),
            ];
            let (r, count) = residual(t, false);
            if count > 0 && r < best.0 {
                best = (r, t);
            }
        }
    }
    let (r0, t) = best;
    let (_, count) = residual(t, false);
    let fraction = count as f64 / (w * h);
    // At least a sliver of the picture: 2% of it, and 200 pixels.
    if fraction < 0.02 || count < 200 {
        return None;
    }
    let ring = [
        [2.0, 0.0],
        [-2.0, 0.0],
        [0.0, 2.0],
        [0.0, -2.0],
        [2.0, 2.0],
        [-2.0, -2.0],
        [2.0, -2.0],
        [-2.0, 2.0],
    ];
    let nearest_other = ring
        .iter()
        .map(|d| residual([t[0] + d[0], t[1] + d[1]], false).0)
        .fold(f64::INFINITY, f64::min);
    // The identity on the same pixels of the actual image.
    let identity = residual(t, true).0;
    let explained = 1.0 - r0 / identity;
    (r0 < 0.25 * nearest_other && explained >= 0.8).then_some((t, fraction, explained))
}
