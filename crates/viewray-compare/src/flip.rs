//! NVIDIA's LDR-FLIP, with the reference image's half of the work done once, and the
//! statistics this crate reads from its error map.
//!
//! FLIP (Andersson et al., "FLIP: A Difference Evaluator for Alternating Images", 2020)
//! filters each image by the contrast sensitivity of the eye, compares the colours in a
//! perceptually uniform space (Hunt-adjusted CIELab, HyAB distance), detects edges and
//! points in each image, and raises the colour difference to a power set by the feature
//! difference. Everything up to the last two steps concerns one image alone; a class of
//! students judged against one reference repeats the reference's half for every student.
//! [`FlipReference`] keeps it, so that [`FlipReference::compare`] computes the student's
//! half only.
//!
//! The arithmetic is that of NVIDIA's reference C++ code (`image.h`, `color.h` and
//! `sharedflip.h` of the FLIP repository, version 1.2, as the `nv-flip` crate bundles
//! it), operation for operation in `f32`, so the error maps are the same bit for bit
//! (a test holds them against `nv-flip`'s). The separable filters run over whole rows
//! (each output's sum is taken in the same order as the C++ loop, so the compiler may
//! vectorize across pixels without changing a bit). Where the student's image agrees with
//! the reference over a filter's whole support, the student's filtered values are the
//! reference's, bit for bit, and are taken from it.

#![allow(
    clippy::excessive_precision,
    clippy::approx_constant,
    reason = "the constants are written as NVIDIA's C++ code writes them"
)]

use std::sync::OnceLock;

use image::RgbImage;
use viewray_output::srgb_to_linear;

use crate::magma::magma;

/// A per-pixel FLIP error map: values in [0, 1], 0 where a viewer sees no difference.
#[derive(Clone, Debug)]
pub(crate) struct ErrorMap {
    pub(crate) width: usize,
    pub(crate) height: usize,
    pub(crate) values: Vec<f32>,
}

/// The side of the square window over which [`ErrorMap::peak`] averages: 3 x 3 pixels.
///
/// A lone pixel that differs (one sample that grazed an edge differently on another
/// machine) contributes at most a ninth of its error; an edge moved by a pixel fills the
/// window along its length and keeps most of its error.
pub(crate) const PEAK_WINDOW: usize = 3;

/// FLIP's default viewing condition: 67 pixels per degree (a 0.7 m viewing distance from
/// a 24-inch 4K monitor).
const PIXELS_PER_DEGREE: f32 = 67.0;

/// Runs LDR-FLIP on two sRGB-encoded RGB8 images of `width` x `height`.
pub(crate) fn flip(
    reference_rgb8: &[u8],
    test_rgb8: &[u8],
    width: usize,
    height: usize,
) -> ErrorMap {
    FlipReference::new(reference_rgb8, width, height).compare(test_rgb8)
}

/// FLIP's constants (`sharedflip.h`).
mod constants {
    pub(super) const PI: f32 = 3.141_592_653_589_79;
    pub(super) const GQC: f32 = 0.7;
    pub(super) const GPC: f32 = 0.4;
    pub(super) const GPT: f32 = 0.95;
    pub(super) const GW: f32 = 0.082;
    pub(super) const GQF: f32 = 0.5;
    /// The Gaussians of the contrast sensitivity functions, per channel (Y, Cx, Cz):
    /// `a1`, `b1`, and for Cz a second one `a2`, `b2`.
    pub(super) const A1: [f32; 3] = [1.0, 1.0, 34.1];
    pub(super) const B1: [f32; 3] = [0.0047, 0.0053, 0.04];
    pub(super) const A2: [f32; 3] = [0.0, 0.0, 13.5];
    pub(super) const B2: [f32; 3] = [1.0e-5, 1.0e-5, 0.025];
    pub(super) const ILLUMINANT: [f32; 3] = [0.950_428_545, 1.000_000_000, 1.088_900_371];
    pub(super) const INVERSE_ILLUMINANT: [f32; 3] = [1.052_156_925, 1.000_000_000, 0.918_357_670];
}

use constants::*;

/// The C++ `Max` and `Min` macros: `(x) > (y) ? (x) : (y)` and `(x) > (y) ? (y) : (x)`.
#[inline]
fn max(x: f32, y: f32) -> f32 {
    if x > y { x } else { y }
}

#[inline]
fn min(x: f32, y: f32) -> f32 {
    if x > y { y } else { x }
}

/// `color3::clamp`: each channel into [0, 1].
#[inline]
fn clamp(c: [f32; 3]) -> [f32; 3] {
    c.map(|v| min(max(v, 0.0), 1.0))
}

#[inline]
fn linear_rgb_to_xyz(rgb: [f32; 3]) -> [f32; 3] {
    let a11 = 10_135_552.0f32 / 24_577_794.0;
    let a12 = 8_788_810.0f32 / 24_577_794.0;
    let a13 = 4_435_075.0f32 / 24_577_794.0;
    let a21 = 2_613_072.0f32 / 12_288_897.0;
    let a22 = 8_788_810.0f32 / 12_288_897.0;
    let a23 = 887_015.0f32 / 12_288_897.0;
    let a31 = 1_425_312.0f32 / 73_733_382.0;
    let a32 = 8_788_810.0f32 / 73_733_382.0;
    let a33 = 70_074_185.0f32 / 73_733_382.0;
    [
        a11 * rgb[0] + a12 * rgb[1] + a13 * rgb[2],
        a21 * rgb[0] + a22 * rgb[1] + a23 * rgb[2],
        a31 * rgb[0] + a32 * rgb[1] + a33 * rgb[2],
    ]
}

#[inline]
fn xyz_to_linear_rgb(xyz: [f32; 3]) -> [f32; 3] {
    let (a11, a12, a13) = (3.241_003_275f32, -1.537_398_934f32, -0.498_615_861f32);
    let (a21, a22, a23) = (-0.969_224_334f32, 1.875_930_071f32, 0.041_554_224f32);
    let (a31, a32, a33) = (0.055_639_423f32, -0.204_011_202f32, 1.057_148_933f32);
    [
        a11 * xyz[0] + a12 * xyz[1] + a13 * xyz[2],
        a21 * xyz[0] + a22 * xyz[1] + a23 * xyz[2],
        a31 * xyz[0] + a32 * xyz[1] + a33 * xyz[2],
    ]
}

#[inline]
fn xyz_to_ycxcz(xyz: [f32; 3]) -> [f32; 3] {
    let x = xyz[0] * INVERSE_ILLUMINANT[0];
    let y = xyz[1] * INVERSE_ILLUMINANT[1];
    let z = xyz[2] * INVERSE_ILLUMINANT[2];
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

#[inline]
fn ycxcz_to_xyz(ycxcz: [f32; 3]) -> [f32; 3] {
    let y = (ycxcz[0] + 16.0) / 116.0;
    let cx = ycxcz[1] / 500.0;
    let cz = ycxcz[2] / 200.0;
    let x = y + cx;
    let z = y - cz;
    [x * ILLUMINANT[0], y * ILLUMINANT[1], z * ILLUMINANT[2]]
}

#[inline]
fn xyz_to_cielab(xyz: [f32; 3]) -> [f32; 3] {
    let delta = 6.0f32 / 29.0;
    let delta_square = delta * delta;
    let delta_cube = delta * delta_square;
    let factor = 1.0 / (3.0 * delta_square);
    let term = 4.0f32 / 29.0;
    let f = |v: f32| {
        if v > delta_cube {
            v.powf(1.0 / 3.0)
        } else {
            factor * v + term
        }
    };
    let x = f(xyz[0] * INVERSE_ILLUMINANT[0]);
    let y = f(xyz[1] * INVERSE_ILLUMINANT[1]);
    let z = f(xyz[2] * INVERSE_ILLUMINANT[2]);
    [116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)]
}

#[inline]
fn hunt(luminance: f32, chrominance: f32) -> f32 {
    0.01 * luminance * chrominance
}

#[inline]
fn hyab(reference: [f32; 3], test: [f32; 3]) -> f32 {
    let city_block = (reference[0] - test[0]).abs();
    let euclidean = ((reference[1] - test[1]) * (reference[1] - test[1])
        + (reference[2] - test[2]) * (reference[2] - test[2]))
        .sqrt();
    city_block + euclidean
}

/// `color3::computeMaxDistance`: the HyAB distance between green and blue, to the power
/// `gqc`.
fn max_distance() -> f32 {
    let lab_hunt = |rgb: [f32; 3]| {
        let lab = xyz_to_cielab(linear_rgb_to_xyz(rgb));
        [lab[0], hunt(lab[0], lab[1]), hunt(lab[0], lab[2])]
    };
    hyab(lab_hunt([0.0, 1.0, 0.0]), lab_hunt([0.0, 0.0, 1.0])).powf(GQC)
}

/// The 8-bit sRGB code as FLIP reads it, `code / 255`, in linear light, for every code.
///
/// FLIP's `color3::sRGB2LinearRGB` is viewray-output's [`srgb_to_linear`] operation for
/// operation in `f32` (the same breakpoint, constants and `powf`), so the table is the
/// same bit for bit as NVIDIA's code computes it.
fn srgb8_to_linear_table() -> &'static [f32; 256] {
    static TABLE: OnceLock<[f32; 256]> = OnceLock::new();
    TABLE.get_or_init(|| std::array::from_fn(|code| srgb_to_linear(code as f32 / 255.0)))
}

/// FLIP's separable filters at its default viewing condition.
struct Filters {
    /// The contrast sensitivity filters of Y, Cx and the two Gaussians of Cz, each
    /// normalized as the C++ code does (`setSpatialFilters`).
    spatial: [Vec<f32>; 4],
    /// The feature detectors: a Gaussian, its first and its second derivative
    /// (`setFeatureFilter`).
    feature: [Vec<f32>; 3],
    /// `cmax` and `gpc * cmax` of the colour difference's remapping.
    cmax: f32,
    pccmax: f32,
}

fn filters() -> &'static Filters {
    static FILTERS: OnceLock<Filters> = OnceLock::new();
    FILTERS.get_or_init(|| Filters::new(PIXELS_PER_DEGREE))
}

impl Filters {
    fn new(ppd: f32) -> Self {
        let pi = PI;
        let pi_sq = PI * PI;
        // calculateSpatialFilterRadius: the largest scale parameter sets the radius.
        let max_scale = max(max(max(B1[0], B1[1]), max(B1[2], B2[0])), max(B2[1], B2[2]));
        let radius = (3.0 * (max_scale / (2.0 * pi_sq)).sqrt() * ppd).ceil() as i32;
        let gaussian = |x2: f32, a: f32, b: f32| a * (pi / b).sqrt() * (-pi_sq * x2 / b).exp();
        let gaussian_sqrt =
            |x2: f32, a: f32, b: f32| (a * (pi / b).sqrt()).sqrt() * (-pi_sq * x2 / b).exp();
        let delta_x = 1.0 / ppd;
        let (mut y, mut cx, mut cz1, mut cz2) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        let mut sums = [0.0f32; 4];
        for x in 0..2 * radius + 1 {
            let ix = (x - radius) as f32 * delta_x;
            let ix2 = ix * ix;
            let values = [
                gaussian(ix2, A1[0], B1[0]),
                gaussian(ix2, A1[1], B1[1]),
                gaussian_sqrt(ix2, A1[2], B1[2]),
                gaussian_sqrt(ix2, A2[2], B2[2]),
            ];
            y.push(values[0]);
            cx.push(values[1]);
            cz1.push(values[2]);
            cz2.push(values[3]);
            for (sum, value) in sums.iter_mut().zip(values) {
                *sum += value;
            }
        }
        let (norm_y, norm_cx) = (1.0 / sums[0], 1.0 / sums[1]);
        let norm_cz = 1.0 / (sums[2] * sums[2] + sums[3] * sums[3]).sqrt();
        y.iter_mut().for_each(|v| *v *= norm_y);
        cx.iter_mut().for_each(|v| *v *= norm_cx);
        cz1.iter_mut().for_each(|v| *v *= norm_cz);
        cz2.iter_mut().for_each(|v| *v *= norm_cz);

        // setFeatureFilter.
        let std_dev = 0.5 * GW * ppd;
        let radius = (3.0 * std_dev).ceil() as i32;
        let (mut g, mut dg, mut ddg) = (Vec::new(), Vec::new(), Vec::new());
        let (mut g_sum, mut dg_negative, mut dg_positive, mut ddg_negative, mut ddg_positive) =
            (0.0f32, 0.0f32, 0.0f32, 0.0f32, 0.0f32);
        for x in 0..2 * radius + 1 {
            let xx = (x - radius) as f32;
            let value = (-(xx * xx) / (2.0 * std_dev * std_dev)).exp();
            g_sum += value;
            let first = -xx * value;
            if first > 0.0 {
                dg_positive += first;
            } else {
                dg_negative -= first;
            }
            let second = (xx * xx / (std_dev * std_dev) - 1.0) * value;
            if second > 0.0 {
                ddg_positive += second;
            } else {
                ddg_negative -= second;
            }
            g.push(value);
            dg.push(first);
            ddg.push(second);
        }
        g.iter_mut().for_each(|v| *v /= g_sum);
        dg.iter_mut().for_each(|v| {
            *v /= if *v > 0.0 { dg_positive } else { dg_negative };
        });
        ddg.iter_mut().for_each(|v| {
            *v /= if *v > 0.0 { ddg_positive } else { ddg_negative };
        });

        let cmax = max_distance();
        Self {
            spatial: [y, cx, cz1, cz2],
            feature: [g, dg, ddg],
            cmax,
            pccmax: GPC * cmax,
        }
    }
}

/// One image's half of FLIP: its filtered colours and its features.
#[derive(Clone, Debug)]
struct Half {
    /// The spatially filtered image in YCxCz, per pixel.
    filtered: Vec<[f32; 3]>,
    /// The same in Hunt-adjusted CIELab.
    lab: Vec<[f32; 3]>,
    /// The feature filters' responses per pixel: d/dx, d2/dx2, d/dy, d2/dy2.
    responses: Vec<[f32; 4]>,
    /// The edge and point strengths per pixel.
    features: Vec<[f32; 2]>,
}

/// A reference image with its half of FLIP computed, to compare any number of test
/// images of its size against.
#[derive(Clone, Debug)]
pub(crate) struct FlipReference {
    width: usize,
    height: usize,
    half: Half,
}

impl FlipReference {
    /// Prepares the sRGB-encoded RGB8 image `rgb8` of `width` x `height` (at least one
    /// pixel each way) as a reference.
    pub(crate) fn new(rgb8: &[u8], width: usize, height: usize) -> Self {
        assert_eq!(rgb8.len(), 3 * width * height, "RGB8 bytes of the image");
        Self {
            width,
            height,
            half: half(rgb8, width, height, None),
        }
    }

    /// FLIP's error map of the sRGB-encoded RGB8 image `test_rgb8` (the reference's size)
    /// against this reference.
    pub(crate) fn compare(&self, test_rgb8: &[u8]) -> ErrorMap {
        let (width, height) = (self.width, self.height);
        assert_eq!(
            test_rgb8.len(),
            3 * width * height,
            "RGB8 bytes of the image"
        );
        let test = half(test_rgb8, width, height, Some(&self.half));
        let filters = filters();
        let (cmax, pccmax) = (filters.cmax, filters.pccmax);
        let normalization = 1.0 / 2.0f32.sqrt();
        let reference = &self.half;
        let values = (0..width * height)
            .map(|i| {
                let same_colour = same(&reference.lab[i], &test.lab[i]);
                let same_features = same(&reference.features[i], &test.features[i]);
                if same_colour && same_features {
                    // HyAB 0, and 0 to any positive power: what the formula gives.
                    return 0.0;
                }
                // computeColorDifference, after the filters.
                let mut colour = hyab(reference.lab[i], test.lab[i]).powf(GQC);
                if colour < pccmax {
                    colour *= GPT / pccmax;
                } else {
                    colour = GPT + ((colour - pccmax) / (cmax - pccmax)) * (1.0 - GPT);
                }
                // computeFeatureDifferenceAndFinalError, after the filters.
                let [edge_reference, point_reference] = reference.features[i];
                let [edge_test, point_test] = test.features[i];
                let edge = (edge_reference - edge_test).abs();
                let point = (point_reference - point_test).abs();
                let feature = (normalization * max(edge, point)).powf(GQF);
                colour.powf(1.0 - feature)
            })
            .collect();
        ErrorMap {
            width,
            height,
            values,
        }
    }
}

/// Whether two arrays of floats are the same bit for bit.
#[inline]
fn same<const N: usize>(a: &[f32; N], b: &[f32; N]) -> bool {
    a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// One image's half of FLIP. With `reference`, a pixel whose filter inputs are the
/// reference's over the filter's whole support takes the reference's results, which are
/// the same bit for bit.
fn half(rgb8: &[u8], width: usize, height: usize, reference: Option<&Half>) -> Half {
    let filters = filters();
    let table = srgb8_to_linear_table();
    let n = width * height;
    // sRGB2YCxCz, as planes.
    let mut planes = [vec![0.0f32; n], vec![0.0f32; n], vec![0.0f32; n]];
    for (i, pixel) in rgb8.chunks_exact(3).enumerate() {
        let linear = [0, 1, 2].map(|c| table[usize::from(pixel[c])]);
        let ycxcz = xyz_to_ycxcz(linear_rgb_to_xyz(linear));
        for c in 0..3 {
            planes[c][i] = ycxcz[c];
        }
    }
    let [y, cx, cz] = &planes;

    // computeColorDifference's filtering: along rows, then along columns.
    let [f_y, f_cx, f_cz1, f_cz2] = &filters.spatial;
    let filtered_y = convolve_columns(&convolve_rows(y, width, f_y), width, f_y);
    let filtered_cx = convolve_columns(&convolve_rows(cx, width, f_cx), width, f_cx);
    let filtered_cz1 = convolve_columns(&convolve_rows(cz, width, f_cz1), width, f_cz1);
    let filtered_cz2 = convolve_columns(&convolve_rows(cz, width, f_cz2), width, f_cz2);
    let mut filtered = Vec::with_capacity(n);
    let mut lab = Vec::with_capacity(n);
    for i in 0..n {
        let value = [
            filtered_y[i],
            filtered_cx[i],
            filtered_cz1[i] + filtered_cz2[i],
        ];
        filtered.push(value);
        if let Some(reference) = reference
            && same(&reference.filtered[i], &value)
        {
            lab.push(reference.lab[i]);
            continue;
        }
        let rgb = clamp(xyz_to_linear_rgb(ycxcz_to_xyz(value)));
        let l = xyz_to_cielab(linear_rgb_to_xyz(rgb));
        lab.push([l[0], hunt(l[0], l[1]), hunt(l[0], l[2])]);
    }

    // computeFeatureDifferenceAndFinalError's filtering, on Y made [0, 1].
    let one_over_116 = 1.0f32 / 116.0;
    let sixteen_over_116 = 16.0f32 / 116.0;
    let grey: Vec<f32> = y
        .iter()
        .map(|&v| v * one_over_116 + sixteen_over_116)
        .collect();
    let [g, dg, ddg] = &filters.feature;
    let rows_dx = convolve_rows(&grey, width, dg);
    let rows_ddx = convolve_rows(&grey, width, ddg);
    let rows_gaussian = convolve_rows(&grey, width, g);
    let dx = convolve_columns(&rows_dx, width, g);
    let ddx = convolve_columns(&rows_ddx, width, g);
    let dy = convolve_columns(&rows_gaussian, width, dg);
    let ddy = convolve_columns(&rows_gaussian, width, ddg);
    let mut responses = Vec::with_capacity(n);
    let mut features = Vec::with_capacity(n);
    for i in 0..n {
        let response = [dx[i], ddx[i], dy[i], ddy[i]];
        responses.push(response);
        if let Some(reference) = reference
            && same(&reference.responses[i], &response)
        {
            features.push(reference.features[i]);
            continue;
        }
        let edge = (dx[i] * dx[i] + dy[i] * dy[i]).sqrt();
        let point = (ddx[i] * ddx[i] + ddy[i] * ddy[i]).sqrt();
        features.push([edge, point]);
    }
    debug_assert_eq!(height * width, n);
    Half {
        filtered,
        lab,
        responses,
        features,
    }
}

/// Convolves each row of the `width`-wide image `plane` with the odd-length `kernel`,
/// edge pixels extended: output x is the sum over k of `kernel[k] * plane[clamp(x + k -
/// r)]`, summed from k = 0 up, starting from 0 (the C++ loop's order).
fn convolve_rows(plane: &[f32], width: usize, kernel: &[f32]) -> Vec<f32> {
    let r = kernel.len() / 2;
    let mut out = vec![0.0f32; plane.len()];
    let mut padded = vec![0.0f32; width + 2 * r];
    for (line, out_line) in plane.chunks_exact(width).zip(out.chunks_exact_mut(width)) {
        for (i, slot) in padded.iter_mut().enumerate() {
            *slot = line[i.saturating_sub(r).min(width - 1)];
        }
        for (k, &weight) in kernel.iter().enumerate() {
            for (o, &p) in out_line.iter_mut().zip(&padded[k..k + width]) {
                *o += weight * p;
            }
        }
    }
    out
}

/// Convolves each column of the `width`-wide image `plane` with the odd-length `kernel`,
/// edge pixels extended, in the order of [`convolve_rows`].
fn convolve_columns(plane: &[f32], width: usize, kernel: &[f32]) -> Vec<f32> {
    let r = kernel.len() / 2;
    let height = plane.len() / width;
    let mut out = vec![0.0f32; plane.len()];
    for (row, out_line) in out.chunks_exact_mut(width).enumerate() {
        for (k, &weight) in kernel.iter().enumerate() {
            let source = (row + k).saturating_sub(r).min(height - 1);
            let line = &plane[source * width..(source + 1) * width];
            for (o, &p) in out_line.iter_mut().zip(line) {
                *o += weight * p;
            }
        }
    }
    out
}

impl ErrorMap {
    /// The mean error over all pixels (the single number FLIP's authors recommend).
    pub(crate) fn mean(&self) -> f32 {
        let sum: f64 = self.values.iter().map(|&v| f64::from(v)).sum();
        (sum / self.values.len().max(1) as f64) as f32
    }

    /// The largest mean error over any `window` x `window` block of pixels (windows
    /// clipped at the image's edges still divide by the full window area).
    pub(crate) fn peak(&self, window: usize) -> f32 {
        let (w, h) = (self.width, self.height);
        // A summed-area table: table[(r) * (w + 1) + c] sums rows < r, columns < c.
        let mut table = vec![0.0f64; (w + 1) * (h + 1)];
        for r in 0..h {
            let mut row_sum = 0.0;
            for c in 0..w {
                row_sum += f64::from(self.values[r * w + c]);
                table[(r + 1) * (w + 1) + c + 1] = table[r * (w + 1) + c + 1] + row_sum;
            }
        }
        let area = (window * window) as f64;
        let mut peak = 0.0f64;
        let (win_w, win_h) = (window.min(w), window.min(h));
        for r in 0..=(h - win_h) {
            for c in 0..=(w - win_w) {
                let (r1, c1) = (r + win_h, c + win_w);
                let sum =
                    table[r1 * (w + 1) + c1] - table[r * (w + 1) + c1] - table[r1 * (w + 1) + c]
                        + table[r * (w + 1) + c];
                peak = peak.max(sum / area);
            }
        }
        peak as f32
    }

    /// The error map through FLIP's magma colour map ([`magma`]): black where nothing
    /// differs, through purple and orange to pale yellow at the largest error.
    pub(crate) fn heatmap(&self) -> RgbImage {
        let (w, h) = (self.width as u32, self.height as u32);
        let colored = self.values.iter().flat_map(|&v| magma(v)).collect();
        RgbImage::from_raw(w, h, colored).expect("the colour map keeps the image size")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `nv-flip`'s error map: NVIDIA's C++ code.
    fn nv_flip(reference: &[u8], test: &[u8], width: usize, height: usize) -> Vec<f32> {
        let (w, h) = (width as u32, height as u32);
        let reference = nv_flip::FlipImageRgb8::with_data(w, h, reference);
        let test = nv_flip::FlipImageRgb8::with_data(w, h, test);
        nv_flip::flip(reference, test, nv_flip::DEFAULT_PIXELS_PER_DEGREE).to_vec()
    }

    /// A deterministic pseudo-random byte stream.
    fn bytes(seed: u64, count: usize) -> Vec<u8> {
        let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
        (0..count)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 7;
                state ^= state << 17;
                (state >> 24) as u8
            })
            .collect()
    }

    #[test]
    fn the_error_map_is_nvidias_bit_for_bit() {
        assert_eq!(PIXELS_PER_DEGREE, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
        // Noise, smooth gradients with a block changed, and tiny and narrow images (the
        // filters are wider than them).
        let (w, h) = (37, 23);
        let noise = (bytes(1, 3 * w * h), bytes(2, 3 * w * h));
        let gradient: Vec<u8> = (0..w * h)
            .flat_map(|i| {
                let (x, y) = (i % w, i / w);
                [(x * 6) as u8, (y * 11) as u8, ((x + y) * 4) as u8]
            })
            .collect();
        let mut changed = gradient.clone();
        for y in 5..12 {
            for x in 10..20 {
                changed[3 * (y * w + x)] = 250;
            }
        }
        let cases: Vec<(Vec<u8>, Vec<u8>, usize, usize)> = vec![
            (noise.0.clone(), noise.1.clone(), w, h),
            (gradient.clone(), changed.clone(), w, h),
            (changed, gradient.clone(), w, h),
            (gradient.clone(), gradient, w, h),
            (bytes(3, 3), bytes(4, 3), 1, 1),
            (bytes(5, 3 * 40), bytes(6, 3 * 40), 40, 1),
            (bytes(7, 3 * 40), bytes(8, 3 * 40), 1, 40),
        ];
        for (reference, test, width, height) in cases {
            let ours = flip(&reference, &test, width, height).values;
            let theirs = nv_flip(&reference, &test, width, height);
            assert_eq!(ours.len(), theirs.len());
            for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
                assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "{width}x{height}, pixel {i}: {a} {b}"
                );
            }
        }
    }

    #[test]
    fn a_prepared_reference_serves_many_tests() {
        let (w, h) = (30, 20);
        let reference = bytes(11, 3 * w * h);
        let prepared = FlipReference::new(&reference, w, h);
        for seed in 12..15 {
            let mut test = reference.clone();
            // A patch of noise: most pixels agree with the reference's over their support.
            let noise = bytes(seed, 3 * w * h);
            for y in 8..12 {
                for x in 3..9 {
                    let i = 3 * (y * w + x);
                    test[i..i + 3].copy_from_slice(&noise[i..i + 3]);
                }
            }
            let ours = prepared.compare(&test).values;
            let theirs = nv_flip(&reference, &test, w, h);
            assert!(
                ours.iter()
                    .zip(&theirs)
                    .all(|(a, b)| a.to_bits() == b.to_bits())
            );
            assert!(ours.iter().any(|&v| v > 0.0) && ours.contains(&0.0));
        }
    }

    #[test]
    fn identical_images_have_zero_error_and_a_black_heatmap() {
        let pixels: Vec<u8> = (0..16 * 8 * 3).map(|i| (i * 7 % 256) as u8).collect();
        let map = flip(&pixels, &pixels, 16, 8);
        assert_eq!(map.mean(), 0.0);
        assert_eq!(map.peak(PEAK_WINDOW), 0.0);
        let heatmap = map.heatmap();
        assert_eq!(heatmap.dimensions(), (16, 8));
        assert!(heatmap.pixels().all(|p| p.0 == heatmap.get_pixel(0, 0).0));
    }

    #[test]
    fn the_peak_window_averages_a_lone_pixel_away_but_not_a_block() {
        let mut map = ErrorMap {
            width: 10,
            height: 10,
            values: vec![0.0; 100],
        };
        map.values[55] = 0.9;
        assert!((map.peak(3) - 0.1).abs() < 1e-6);
        for r in 2..5 {
            for c in 2..5 {
                map.values[r * 10 + c] = 0.6;
            }
        }
        assert!((map.peak(3) - 0.6).abs() < 1e-6);
        assert!((map.mean() - (0.9 + 9.0 * 0.6) / 100.0).abs() < 1e-6);
    }
}
