//! Appearance, apart from the camera: when a picture's FLIP fails, what differs in its
//! look, named as the lecture's catalogue names it (`gamma-missing`, `gamma-twice`,
//! `brighter`, `darker`, `shading`, `noise`).
//!
//! The difference is measured inside surfaces, away from every boundary (the right
//! camera's label map says where, when the scene is known; else the reference's own
//! flat parts), so that neither the edges' sampling nor a camera's small error counts:
//!
//! - **noise**: the picture's fine detail (what a blur of 2 px takes away) is several
//!   times the reference's, and the blurred pictures agree better than that: fewer samples
//!   per pixel;
//! - **gamma-missing**, **gamma-twice**: the picture is the reference's values run through
//!   the sRGB decoding (linear values written as if encoded: too dark) or its encoding
//!   once more (too bright, washed out), within a few codes, clearly better than any
//!   exposure;
//! - **brighter**, **darker**: one factor of light (an exposure, a light's intensity)
//!   makes the picture, or the picture is lighter (darker) on average by 10% or more and
//!   everywhere ([`EVERYWHERE`]), or almost everywhere with values that follow the
//!   reference's (a correlation of at least [`FOLLOWS`]): an ambient light, a light's
//!   intensity, where a light moved elsewhere lights other surfaces and is `shading`;
//! - **shading**: anything else: another light, another material or shading model.

use crate::raster::FloatImage;

/// How a picture looks beside the reference, apart from its camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Appearance {
    /// No visible difference (FLIP passes).
    Same,
    /// Linear values written as if sRGB-encoded: too dark.
    GammaMissing,
    /// Values sRGB-encoded twice: too bright, washed out.
    GammaTwice,
    /// Brighter: a stronger light, a brighter ambient, an exposure.
    Brighter,
    /// Darker.
    Darker,
    /// Another light, material or shading model.
    Shading,
    /// Noisier: fewer samples per pixel.
    Noise,
}

impl Appearance {
    /// Every appearance, `same` first.
    pub const ALL: [Appearance; 7] = [
        Appearance::Same,
        Appearance::GammaMissing,
        Appearance::GammaTwice,
        Appearance::Brighter,
        Appearance::Darker,
        Appearance::Shading,
        Appearance::Noise,
    ];

    /// The id, as every output prints it: `same`, `gamma-missing`, `gamma-twice`,
    /// `brighter`, `darker`, `shading`, `noise`.
    pub fn id(self) -> &'static str {
        match self {
            Appearance::Same => "same",
            Appearance::GammaMissing => "gamma-missing",
            Appearance::GammaTwice => "gamma-twice",
            Appearance::Brighter => "brighter",
            Appearance::Darker => "darker",
            Appearance::Shading => "shading",
            Appearance::Noise => "noise",
        }
    }

    /// The appearance whose id is `id`.
    pub fn from_id(id: &str) -> Option<Appearance> {
        Appearance::ALL.into_iter().find(|a| a.id() == id)
    }

    /// What it means and what to check, in a sentence.
    pub fn sentence(self) -> &'static str {
        match self {
            Appearance::Same => "looks as the reference does",
            Appearance::GammaMissing => {
                "too dark: linear values written as if sRGB-encoded (encode each channel \
                 with the sRGB transfer function before writing 8-bit values)"
            }
            Appearance::GammaTwice => {
                "too bright and washed out: the values are sRGB-encoded twice (encode once, \
                 just before writing)"
            }
            Appearance::Brighter => {
                "brighter than the reference: check the lights' intensities, the ambient \
                 light and any exposure"
            }
            Appearance::Darker => {
                "darker than the reference: check the lights' intensities, the ambient light \
                 and any exposure"
            }
            Appearance::Shading => {
                "shaded differently: another light, material or shading model (or an object \
                 or a colour differs)"
            }
            Appearance::Noise => {
                "noisier than the reference: fewer samples per pixel (not an error of the \
                 camera)"
            }
        }
    }
}

/// The pictures appearance is measured on, in linear light, sharp and blurred, and where.
pub(crate) struct Pictures<'a> {
    pub(crate) expected: &'a FloatImage,
    pub(crate) actual: &'a FloatImage,
    pub(crate) expected_blurred: &'a FloatImage,
    pub(crate) actual_blurred: &'a FloatImage,
    /// The pixels inside surfaces, away from boundaries.
    pub(crate) interior: &'a [bool],
}

/// The share of interior values lighter (darker) than the reference's that counts as
/// everywhere: a light moved elsewhere leaves some surfaces lit that were not (in the
/// planted matrix, at most 95% darker), a brighter light or ambient none (100%).
const EVERYWHERE: f64 = 0.98;

/// The least correlation of the picture's encoded values with the reference's for a
/// picture lighter or darker almost everywhere to be called `brighter` or `darker`.
const FOLLOWS: f64 = 0.9;

/// The fewest interior pixels the tone models are fitted on: below it, `shading`.
const FEWEST: usize = 64;

/// Names how `pictures.actual` differs from `pictures.expected` when FLIP failed
/// (`differs`); [`Appearance::Same`] when it did not.
pub(crate) fn classify(pictures: &Pictures<'_>, differs: bool) -> Appearance {
    if !differs {
        return Appearance::Same;
    }
    let inside: Vec<usize> = (0..pictures.expected.pixels.len())
        .filter(|&p| pictures.interior.get(p).copied().unwrap_or(false))
        .collect();
    if inside.len() < FEWEST {
        return Appearance::Shading;
    }
    if noisier(pictures, &inside) {
        return Appearance::Noise;
    }
    tone(pictures, &inside)
}

/// Whether the picture's fine detail inside surfaces is several times the reference's
/// while the blurred pictures agree better than the detail differs.
fn noisier(pictures: &Pictures<'_>, inside: &[usize]) -> bool {
    let detail = |sharp: &FloatImage, blurred: &FloatImage| -> f64 {
        mean(inside.iter().map(|&p| {
            let (s, b) = (sharp.pixels[p], blurred.pixels[p]);
            (0..3).map(|c| f64::from(s[c] - b[c]).powi(2)).sum::<f64>()
        }))
    };
    let expected = detail(pictures.expected, pictures.expected_blurred);
    let actual = detail(pictures.actual, pictures.actual_blurred);
    let blurred = mean(inside.iter().map(|&p| {
        let (e, a) = (
            pictures.expected_blurred.pixels[p],
            pictures.actual_blurred.pixels[p],
        );
        (0..3).map(|c| f64::from(a[c] - e[c]).powi(2)).sum::<f64>()
    }));
    actual > 3.0 * expected + 1e-5 && blurred < actual
}

/// The tone models: the sRGB decoding or encoding once more, one factor of light, or
/// lighter or darker almost everywhere; else shading.
fn tone(pictures: &Pictures<'_>, inside: &[usize]) -> Appearance {
    let encode = |l: f64| f64::from(viewray_output::linear_to_srgb(l.clamp(0.0, 1.0) as f32));
    let decode = |s: f64| f64::from(viewray_output::srgb_to_linear(s.clamp(0.0, 1.0) as f32));
    // Each interior channel: the reference's and the picture's linear values.
    let samples: Vec<(f64, f64)> = inside
        .iter()
        .flat_map(|&p| {
            let (e, a) = (pictures.expected.pixels[p], pictures.actual.pixels[p]);
            (0..3).map(move |c| (f64::from(e[c]), f64::from(a[c])))
        })
        .collect();
    // The mean distance, in encoded values, between the picture and a model of it.
    let residual = |model: &dyn Fn(f64) -> f64| {
        mean(
            samples
                .iter()
                .map(|&(e, a)| (encode(a) - encode(model(e))).abs()),
        )
    };
    let same = residual(&|e| e);
    // Linear values written as if encoded: the file holds `e` where `encode(e)` belongs,
    // which reads back as the linear value decode(e).
    let gamma_missing = residual(&|e| decode(e));
    let gamma_twice = residual(&|e| encode(e));
    // One factor of light, the median of the ratios where both are lit.
    let mut ratios: Vec<f64> = samples
        .iter()
        .filter(|&&(e, a)| e > 0.01 && a > 0.002 && a < 0.99)
        .map(|&(e, a)| (a / e).ln())
        .collect();
    let factor = median(&mut ratios).map_or(1.0, f64::exp);
    let exposure = residual(&|e| factor * e);
    let fits = |model: f64, others: &[f64]| {
        model < 0.02 && model < 0.5 * same && others.iter().all(|&o| model < 0.8 * o)
    };
    if fits(gamma_missing, &[exposure, gamma_twice]) {
        return Appearance::GammaMissing;
    }
    if fits(gamma_twice, &[exposure, gamma_missing]) {
        return Appearance::GammaTwice;
    }
    if exposure < 0.02 && exposure < 0.5 * same && (factor - 1.0).abs() > 0.05 {
        return if factor > 1.0 {
            Appearance::Brighter
        } else {
            Appearance::Darker
        };
    }
    // Lighter (darker) almost everywhere, and on average by 10% or more.
    let total = |pick: fn(&(f64, f64)) -> f64| samples.iter().map(pick).sum::<f64>();
    let (expected, actual) = (total(|s| s.0), total(|s| s.1));
    let share = |lighter: bool| {
        let count = samples
            .iter()
            .filter(|&&(e, a)| if lighter { a >= e } else { a <= e })
            .count();
        count as f64 / samples.len() as f64
    };
    let follows = correlation(
        samples
            .iter()
            .map(|&(e, a)| (encode(e), encode(a)))
            .collect::<Vec<_>>()
            .as_slice(),
    ) >= FOLLOWS;
    // Lighter (darker) everywhere, or almost everywhere with values that follow.
    let everywhere = |lighter: bool| {
        let share = share(lighter);
        share > EVERYWHERE || (share > 0.8 && follows)
    };
    if actual > 1.1 * expected && everywhere(true) {
        Appearance::Brighter
    } else if actual < expected / 1.1 && everywhere(false) {
        Appearance::Darker
    } else {
        Appearance::Shading
    }
}

/// Which pixels of `expected` (linear) lie in its flat parts: no neighbour within two
/// pixels differs by more than a few codes. Appearance is measured there when the scene
/// is not known.
pub(crate) fn flat_parts(expected: &FloatImage) -> Vec<bool> {
    let (w, h) = (expected.width, expected.height);
    let encoded = expected.encoded_as_srgb();
    // Edge pixels: some channel differs from the right or lower neighbour by 8 codes.
    let mut edge = vec![false; w * h];
    for row in 0..h {
        for col in 0..w {
            let p = row * w + col;
            let differs = |q: usize| {
                (0..3).any(|c| (encoded.pixels[p][c] - encoded.pixels[q][c]).abs() > 8.0 / 255.0)
            };
            if col + 1 < w && differs(p + 1) {
                edge[p] = true;
                edge[p + 1] = true;
            }
            if row + 1 < h && differs(p + w) {
                edge[p] = true;
                edge[p + w] = true;
            }
        }
    }
    grow(&edge, w, h, 2).into_iter().map(|e| !e).collect()
}

/// `marked` grown by `radius` pixels (a square neighbourhood).
pub(crate) fn grow(marked: &[bool], width: usize, height: usize, radius: usize) -> Vec<bool> {
    let mut rows = vec![false; marked.len()];
    for row in 0..height {
        for col in 0..width {
            let lo = col.saturating_sub(radius);
            let hi = (col + radius).min(width - 1);
            rows[row * width + col] = (lo..=hi).any(|c| marked[row * width + c]);
        }
    }
    let mut grown = vec![false; marked.len()];
    for row in 0..height {
        let lo = row.saturating_sub(radius);
        let hi = (row + radius).min(height - 1);
        for col in 0..width {
            grown[row * width + col] = (lo..=hi).any(|r| rows[r * width + col]);
        }
    }
    grown
}

/// The (Pearson) correlation of the pairs' two values; 1 when either is constant.
fn correlation(pairs: &[(f64, f64)]) -> f64 {
    let n = pairs.len() as f64;
    if pairs.is_empty() {
        return 1.0;
    }
    let (mx, my) = (
        pairs.iter().map(|p| p.0).sum::<f64>() / n,
        pairs.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for &(x, y) in pairs {
        sxy += (x - mx) * (y - my);
        sxx += (x - mx) * (x - mx);
        syy += (y - my) * (y - my);
    }
    if sxx <= f64::EPSILON || syy <= f64::EPSILON {
        1.0
    } else {
        sxy / (sxx * syy).sqrt()
    }
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0_u64), |(s, n), v| (s + v, n + 1));
    if n == 0 { 0.0 } else { sum / n as f64 }
}

/// The median of `values` (reordered), `None` when there are none.
fn median(values: &mut [f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    let middle = values.len() / 2;
    let (_, m, _) = values.select_nth_unstable_by(middle, f64::total_cmp);
    Some(*m)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A smooth picture in linear light: three flat-shaded regions with gradients.
    fn scene(width: usize, height: usize) -> FloatImage {
        let mut image = FloatImage::new(width, height);
        for row in 0..height {
            for col in 0..width {
                let t = col as f32 / width as f32;
                let s = row as f32 / height as f32;
                image.pixels[row * width + col] = if col < width / 3 {
                    [0.05 + 0.5 * t, 0.02, 0.01]
                } else if col < 2 * width / 3 {
                    [0.02, 0.1 + 0.3 * s, 0.6 * t]
                } else {
                    [0.5 * s + 0.2, 0.45, 0.35 * t + 0.1]
                };
            }
        }
        image
    }

    fn changed(image: &FloatImage, f: impl Fn(usize, f32) -> f32) -> FloatImage {
        let mut out = image.clone();
        for (p, pixel) in out.pixels.iter_mut().enumerate() {
            *pixel = pixel.map(|c| f(p, c));
        }
        out
    }

    fn classify_pair(expected: &FloatImage, actual: &FloatImage) -> Appearance {
        let interior = vec![true; expected.pixels.len()];
        let (eb, ab) = (expected.gaussian_blur(2.0), actual.gaussian_blur(2.0));
        classify(
            &Pictures {
                expected,
                actual,
                expected_blurred: &eb,
                actual_blurred: &ab,
                interior: &interior,
            },
            true,
        )
    }

    #[test]
    fn each_tone_change_is_named() {
        let reference = scene(60, 40);
        let encode = |l: f32| viewray_output::linear_to_srgb(l.clamp(0.0, 1.0));
        let decode = viewray_output::srgb_to_linear;
        let cases: [(Appearance, FloatImage); 5] = [
            (
                Appearance::GammaMissing,
                changed(&reference, |_, c| decode(c)),
            ),
            (
                Appearance::GammaTwice,
                changed(&reference, |_, c| decode(encode(encode(c)))),
            ),
            (Appearance::Brighter, changed(&reference, |_, c| 1.6 * c)),
            (Appearance::Darker, changed(&reference, |_, c| 0.6 * c)),
            (
                Appearance::Brighter,
                changed(&reference, |_, c| c + 0.15 * c.sqrt()),
            ),
        ];
        for (want, picture) in cases {
            assert_eq!(classify_pair(&reference, &picture), want);
        }
    }

    #[test]
    fn noise_and_other_shading_are_named_and_a_pass_is_the_same() {
        let reference = scene(60, 40);
        let noisy = changed(&reference, |p, c| {
            let jitter = if (p * 7919) % 5 < 2 { 0.12 } else { -0.08 };
            (c + jitter).max(0.0)
        });
        assert_eq!(classify_pair(&reference, &noisy), Appearance::Noise);
        // Another light: the left part brighter, the right part darker.
        let relit = changed(
            &reference,
            |p, c| if p % 60 < 30 { c * 1.5 } else { c * 0.5 },
        );
        assert_eq!(classify_pair(&reference, &relit), Appearance::Shading);
        let interior = vec![true; reference.pixels.len()];
        let blurred = reference.gaussian_blur(2.0);
        let pictures = Pictures {
            expected: &reference,
            actual: &reference,
            expected_blurred: &blurred,
            actual_blurred: &blurred,
            interior: &interior,
        };
        assert_eq!(classify(&pictures, false), Appearance::Same);
        for appearance in Appearance::ALL {
            assert_eq!(Appearance::from_id(appearance.id()), Some(appearance));
        }
    }

    #[test]
    fn flat_parts_leave_out_edges_and_their_neighbours() {
        let mut image = FloatImage::new(20, 10);
        for (p, pixel) in image.pixels.iter_mut().enumerate() {
            *pixel = if p % 20 < 10 { [0.1; 3] } else { [0.8; 3] };
        }
        let flat = flat_parts(&image);
        // Columns 9 and 10 hold the edge; two more on each side are left out.
        let row: Vec<bool> = flat[..20].to_vec();
        let want: Vec<bool> = (0..20).map(|c| !(7..=12).contains(&c)).collect();
        assert_eq!(row, want);
    }
}
