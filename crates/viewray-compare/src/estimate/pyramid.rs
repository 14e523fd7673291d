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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimate::test_images::{pattern, picture};

    fn mean(image: &FloatImage) -> [f64; 3] {
        let n = image.pixels.len() as f64;
        [0, 1, 2].map(|c| image.pixels.iter().map(|p| f64::from(p[c])).sum::<f64>() / n)
    }

    #[test]
    fn each_level_halves_the_size_and_keeps_the_mean() {
        let image = picture(320, 240, pattern);
        let pyramid = ExpectedPyramid::new(&image);
        // 240, 120, 60, 30: halving 30 would make the shorter side 15.
        assert_eq!(pyramid.levels.len(), 4);
        assert_eq!(pyramid.levels[0].image.pixels, image.pixels);
        for pair in pyramid.levels.windows(2) {
            let (fine, coarse) = (&pair[0], &pair[1]);
            assert_eq!(coarse.image.width, fine.image.width / 2);
            assert_eq!(coarse.image.height, fine.image.height / 2);
            assert_eq!(coarse.factor, 2.0 * fine.factor);
            // The blur extends the edges, so the mean moves, but by little.
            let (a, b) = (mean(&fine.image), mean(&coarse.image));
            for c in 0..3 {
                assert!((a[c] - b[c]).abs() < 2e-3 * a[c], "{a:?} {b:?}");
            }
        }
    }

    #[test]
    fn a_uniform_picture_keeps_its_value_at_every_level() {
        let mut image = FloatImage::new(100, 64);
        image.pixels.fill([0.25, 0.5, 0.75]);
        for level in ExpectedPyramid::new(&image).levels {
            for p in &level.image.pixels {
                for (c, want) in [0.25f32, 0.5, 0.75].into_iter().enumerate() {
                    assert!((p[c] - want).abs() < 1e-6);
                }
            }
            // Flat: no derivative anywhere.
            assert!(level.fused.iter().all(|f| f[3..].iter().all(|&d| d == 0.0)));
        }
    }

    #[test]
    fn the_search_level_is_the_last_whose_half_is_under_the_search_side() {
        for (width, height, levels) in [(320, 240, 4), (64, 64, 3), (64, 31, 1), (10, 10, 1)] {
            let pyramid = ExpectedPyramid::new(&FloatImage::new(width, height));
            assert_eq!(pyramid.levels.len(), levels, "{width} x {height}");
            let top = pyramid.levels.last().unwrap();
            let side = top.image.width.min(top.image.height);
            assert!(side / 2 < SEARCH_SIDE);
            assert!(side >= SEARCH_SIDE || levels == 1);
        }
    }

    #[test]
    fn the_fused_levels_hold_the_colour_and_its_derivatives() {
        let pyramid = ExpectedPyramid::new(&picture(160, 120, pattern));
        for level in &pyramid.levels {
            let (dx, dy) = level.image.gradients();
            for (i, fused) in level.fused.iter().enumerate() {
                assert_eq!(fused[..3], level.image.pixels[i]);
                assert_eq!(fused[3..6], dx.pixels[i]);
                assert_eq!(fused[6..], dy.pixels[i]);
            }
        }
    }

    #[test]
    fn the_actual_pyramid_is_made_as_the_expected_one_and_capped() {
        let image = picture(160, 120, pattern);
        let expected = ExpectedPyramid::new(&image);
        let pyramid = Pyramid::new(&expected, &image, 2.0, usize::MAX);
        assert_eq!(pyramid.levels.len(), expected.levels.len());
        assert_eq!(pyramid.top(), expected.levels.len() - 1);
        for (level, e) in pyramid.levels.iter().zip(&expected.levels) {
            assert_eq!(level.actual.pixels, e.image.pixels);
            assert_eq!(level.factor, e.factor);
        }
        assert_eq!(pyramid.centre(), [80.0, 60.0]);
        // The blur's margin (2.5 sigma), plus a level pixel.
        assert_eq!(pyramid.margin(0), 6.0);
        assert_eq!(pyramid.margin(2), 9.0);
        assert_eq!(Pyramid::new(&expected, &image, 2.0, 2).levels.len(), 2);
        assert_eq!(Pyramid::new(&expected, &image, 2.0, 0).levels.len(), 1);
    }

    #[test]
    fn the_stride_is_the_smallest_that_keeps_within_the_budget() {
        let image = picture(160, 120, pattern);
        let expected = ExpectedPyramid::new(&image);
        let pyramid = Pyramid::new(&expected, &image, 2.0, usize::MAX);
        let pixels = 160 * 120;
        for budget in [1, 100, 6_000, 19_200, 50_000] {
            let stride = pyramid.stride(0, budget);
            assert!(pixels / (stride * stride) <= budget, "{budget}");
            assert!(stride == 1 || pixels / ((stride - 1) * (stride - 1)) > budget);
        }
        assert_eq!(pyramid.stride(0, pixels), 1);
    }
}
