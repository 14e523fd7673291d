//! The two images at every level of resolution, down to the search level: the expected
//! image's side prepared once ([`ExpectedPyramid`]), the actual image's made the same way
//! for each judgement ([`Pyramid`]).
//!
//! Each level is the one above blurred by one of its pixels and halved, so that level `k`
//! has `2^k` full-resolution pixels per pixel (its `factor`); the search works on the
//! coarsest, whose shorter side is [`SEARCH_SIDE`] to `2 SEARCH_SIDE - 1` pixels (unless
//! the images are smaller).

use std::borrow::Cow;

use crate::raster::FloatImage;

/// One level of the expected image's pyramid: `factor` full-resolution pixels per level
/// pixel.
#[derive(Clone, Debug)]
pub(super) struct ExpectedLevel {
    pub(super) factor: f64,
    pub(super) image: FloatImage,
    /// The image's colour and its x and y derivatives, per pixel: one bilinear lookup
    /// serves a fit's residual and its Jacobian.
    pub(super) fused: Vec<[f32; 9]>,
}

/// The expected image's side of the pyramids, down to the search level: it depends on
/// the expected image alone, so one serves every actual image judged against it.
#[derive(Clone, Debug)]
pub(crate) struct ExpectedPyramid {
    pub(super) levels: Vec<ExpectedLevel>,
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
pub(super) struct Level<'a> {
    pub(super) factor: f64,
    pub(super) expected: &'a FloatImage,
    /// The expected image's colour and its derivatives (see [`ExpectedLevel`]).
    pub(super) expected_fused: &'a [[f32; 9]],
    pub(super) actual: Cow<'a, FloatImage>,
}

/// The two images, blurred and sRGB-encoded, as pyramids.
pub(crate) struct Pyramid<'a> {
    pub(super) levels: Vec<Level<'a>>,
    /// The full-resolution size.
    pub(super) size: [f64; 2],
    /// How far from the borders a point must lie to count (full-resolution pixels, at
    /// level 0): the blur saw beyond the picture there.
    margin: f64,
}

/// Side of the search level: its shorter side is at least this (unless the images are
/// smaller), and halving once more would make it shorter.
pub(super) const SEARCH_SIDE: usize = 16;

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

    /// The centre of the full-resolution picture.
    pub(crate) fn centre(&self) -> [f64; 2] {
        [self.size[0] / 2.0, self.size[1] / 2.0]
    }

    /// The search level: the coarsest.
    pub(super) fn top(&self) -> usize {
        self.levels.len() - 1
    }

    /// The margin at a level: the blur's, plus a level pixel for the level's own.
    pub(super) fn margin(&self, level: usize) -> f64 {
        self.margin + self.levels[level].factor
    }

    /// The step between evaluated pixels at `level` that keeps about `budget` of them.
    pub(super) fn stride(&self, level: usize, budget: usize) -> usize {
        let l = &self.levels[level];
        let pixels = l.actual.width * l.actual.height;
        let mut stride = 1;
        while pixels / (stride * stride) > budget {
            stride += 1;
        }
        stride
    }
}
