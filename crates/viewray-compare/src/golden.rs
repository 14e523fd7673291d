//! The golden gates: a render must match its committed reference up to last-bit noise.

use image::RgbaImage;

use crate::comparison::{Comparison, Failure, Metrics, Mode, count_bad_pixels, is_nearly_blank};
use crate::flip::{self, PEAK_WINDOW};
use crate::raster::FloatImage;

/// The thresholds of [`compare`]. [`Thresholds::GOLDEN`] (the default) is what
/// `cargo xtask golden` uses; each field says why its value is what it is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Thresholds {
    /// A pixel is bad when some channel differs by more than this many 8-bit codes.
    ///
    /// Golden: 2. The same scene rendered on another machine (another CPU's fused
    /// multiply-add, another libm) differs in the last bits of the floats, which moves a
    /// quantized code by 1 and, where sRGB encoding is steep, rarely by 2.
    pub channel_tolerance: u8,
    /// At most this fraction of the pixels may be bad (see [`Thresholds::max_bad_pixels`]).
    ///
    /// Golden: 0.05%, and at least [`Thresholds::min_allowed_bad_pixels`]. A last-bit
    /// difference can flip whether one sample of a pixel grazes an edge, changing that pixel
    /// by a sample's share (up to 1/samples of the contrast): a handful of such pixels is
    /// noise, an edge moved by one pixel is hundreds.
    pub bad_pixel_fraction: f64,
    /// The floor on the number of bad pixels allowed, for small images.
    pub min_allowed_bad_pixels: u64,
    /// The mean FLIP error may be at most this.
    ///
    /// Golden: 0.01. FLIP sees a change of one 8-bit code in dark regions: last-bit noise
    /// on every pixel measures 0.003 to 0.006 on the test scenes. This gate catches a
    /// change spread thin over the whole image; local changes are the peak's job.
    pub max_mean_flip: f32,
    /// The FLIP error averaged over the worst 3 x 3 window may be at most this.
    ///
    /// Golden: 0.05. Last-bit noise measures below 0.016 on the test scenes, and the window
    /// divides a lone stray pixel's error by nine (one of 16 samples grazing an edge
    /// differently on another machine); an edge moved by one pixel fills the window along
    /// its length and measures 0.65, a colour change a person would notice (the disc's red
    /// 12% darker) 0.21.
    pub max_peak_flip: f32,
}

impl Thresholds {
    /// The strict gates for golden images: see each field for its value and why.
    pub const GOLDEN: Thresholds = Thresholds {
        channel_tolerance: 2,
        bad_pixel_fraction: 0.0005,
        min_allowed_bad_pixels: 4,
        max_mean_flip: 0.01,
        max_peak_flip: 0.05,
    };

    /// How many bad pixels an image of `pixel_count` pixels may have:
    ///
    /// ```text
    /// max(min_allowed_bad_pixels, floor(bad_pixel_fraction * pixel_count))
    /// ```
    pub fn max_bad_pixels(&self, pixel_count: u64) -> u64 {
        let by_fraction = (self.bad_pixel_fraction * pixel_count as f64).floor() as u64;
        by_fraction.max(self.min_allowed_bad_pixels)
    }
}

impl Default for Thresholds {
    fn default() -> Self {
        Self::GOLDEN
    }
}

/// Compares a render (`actual`) with its golden reference (`expected`) through two gates,
/// after decoding: never the PNG bytes.
///
/// 1. Per pixel: a pixel is bad when any channel differs by more than
///    `channel_tolerance`; the comparison fails with more than
///    [`Thresholds::max_bad_pixels`] bad pixels.
/// 2. Perceptual: NVIDIA's LDR-FLIP on the RGB channels (alpha composited over black) at
///    67 pixels per degree; it fails when the mean or the worst 3 x 3 window is above its
///    threshold.
///
/// A blank expected image fails (one colour but for at most the pixels gate 1 forgives:
/// it would pass a blank render), and so do images of
/// different sizes (no metrics then). Never panics.
pub fn compare(expected: &RgbaImage, actual: &RgbaImage, thresholds: &Thresholds) -> Comparison {
    if expected.dimensions() != actual.dimensions() {
        return Comparison::size_mismatch(Mode::Golden, expected, actual);
    }
    let mut failures = Vec::new();
    let pixel_count = u64::from(expected.width()) * u64::from(expected.height());
    let allowed = thresholds.max_bad_pixels(pixel_count);
    if is_nearly_blank(expected, thresholds.channel_tolerance, allowed) {
        failures.push(Failure::UniformExpected);
    }

    // Gate 1: per-pixel differences.
    let (bad_pixels, max_channel_difference) =
        count_bad_pixels(expected, actual, thresholds.channel_tolerance);
    if bad_pixels > allowed {
        failures.push(Failure::TooManyBadPixels {
            bad: bad_pixels,
            allowed,
            tolerance: thresholds.channel_tolerance,
        });
    }

    // Gate 2: FLIP on the images as a viewer sees them.
    let (width, height) = (expected.width() as usize, expected.height() as usize);
    let map = flip::flip(
        &FloatImage::linear_from_rgba8(expected)
            .encoded_as_srgb()
            .to_rgb8_bytes(),
        &FloatImage::linear_from_rgba8(actual)
            .encoded_as_srgb()
            .to_rgb8_bytes(),
        width,
        height,
    );
    let (mean_flip, peak_flip) = (map.mean(), map.peak(PEAK_WINDOW));
    if mean_flip > thresholds.max_mean_flip {
        failures.push(Failure::MeanFlip {
            mean: mean_flip,
            threshold: thresholds.max_mean_flip,
        });
    }
    if peak_flip > thresholds.max_peak_flip {
        failures.push(Failure::PeakFlip {
            peak: peak_flip,
            threshold: thresholds.max_peak_flip,
        });
    }

    Comparison {
        mode: Mode::Golden,
        failures,
        metrics: Some(Metrics {
            pixel_count,
            bad_pixels,
            max_channel_difference,
            mean_flip,
            peak_flip,
        }),
        diagnosis: None,
        camera: None,
        appearance: None,
        judge: crate::camera::Judge::Image,
        error_map: Some(map),
    }
}
