//! Instructor mode: judge a student's render as an instructor would.

use image::RgbaImage;

use crate::comparison::{Comparison, Failure, Metrics, Mode, count_bad_pixels, is_nearly_blank};
use crate::diagnosis::{self, Diagnosis, Significant};
use crate::flip::{self, PEAK_WINDOW};
use crate::golden::Thresholds;
use crate::raster::FloatImage;

/// The thresholds of [`judge`]; the default is what `viewray compare` uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct InstructorThresholds {
    /// The largest FLIP error allowed in the worst 3 x 3 window, measured after both
    /// images are blurred by [`InstructorThresholds::blur_sigma`] (`viewray compare
    /// --threshold`).
    ///
    /// Default 0.3. On the test scenes (128 x 96, against a 64-sample reference), correct
    /// renders measure 0.05 to 0.12 with 4 to 16 samples, 0.19 with one sample at the pixel
    /// centre and up to 0.27 with one random sample; an object moved by one pixel measures
    /// 0.46, a missing object 0.98, a clearly different colour 0.33, colours written
    /// without sRGB encoding 0.70.
    pub max_peak_flip: f32,
    /// The standard deviation, in pixels, of the Gaussian blur applied in linear light to
    /// both images before FLIP and before estimating the transform.
    ///
    /// Default 2.0. Where an edge crosses a pixel, the sample pattern and count decide that
    /// pixel's coverage (one sample or 64, a grid or random: the same on average, different
    /// pixel by pixel); the blur averages each edge pixel with its neighbours along the
    /// edge, so that noise cancels, while a camera mistake moves whole edges, or every
    /// edge the same way, and survives it. (At 1.0 a one-sample render still measures up
    /// to 0.40; at 2.0, 0.27.)
    pub blur_sigma: f32,
    /// A move of the content is a mistake when it exceeds this many pixels along x or y.
    ///
    /// Default 0.25: half the smallest classic mistake (the missing pixel-centre offset,
    /// +0.5 px, measured 0.49 to 0.55 on the test scenes), and six times what
    /// antialiasing noise fakes (at most 0.04 px on correct renders with 1 to 64 samples).
    pub max_shift: f64,
    /// A scale is a mistake when it differs from 1 by more than this along x or y.
    ///
    /// Default 0.01 (1%): a tenth of the classic wrong field of view (1.1x, measured 1.097
    /// to 1.099), and over three times the measurement noise (at most 0.26% on correct
    /// renders).
    pub max_scale_error: f64,
    /// A transform is reported only when undoing it removes at least this fraction of the
    /// mean squared difference between the blurred images.
    ///
    /// Default 0.5: a camera mistake explains nearly all of the difference (0.93 and more
    /// on the test scenes), while the transform fitted to a correct render's antialiasing
    /// noise explains at most 0.14, and one fitted to an unrelated change (a missing
    /// object) little.
    pub min_explained: f64,
}

impl Default for InstructorThresholds {
    fn default() -> Self {
        Self {
            max_peak_flip: 0.3,
            blur_sigma: 2.0,
            max_shift: 0.25,
            max_scale_error: 0.01,
            min_explained: 0.5,
        }
    }
}

/// Judges a student's render (`actual`) against the instructor's reference (`expected`):
/// antialiasing and sample count are not errors, camera mistakes are.
///
/// 1. Both images are blurred in linear light (`blur_sigma`), which makes renders with any
///    sample pattern and count agree, then compared with FLIP: it fails when the worst
///    3 x 3 window is above `max_peak_flip` (a missing object, a wrong colour, a moved
///    edge).
/// 2. The systematic transform between the blurred images is estimated (mirrors, per-axis
///    scale about the centre, sub-pixel move; see [`Diagnosis`]); it fails when the
///    transform is beyond `max_shift` / `max_scale_error` or mirrored, and explains at
///    least `min_explained` of the difference. This catches what the blur hides: a
///    half-pixel move of every edge.
///
/// The diagnosis is reported whenever such a transform is found, with messages like
/// `mirrored left-right: check u = up x w`. A blank expected image and images of
/// different sizes fail, as in [`crate::compare`]. Never panics.
pub fn judge(
    expected: &RgbaImage,
    actual: &RgbaImage,
    thresholds: &InstructorThresholds,
) -> Comparison {
    if expected.dimensions() != actual.dimensions() {
        return Comparison::size_mismatch(Mode::Instructor, expected, actual);
    }
    let mut failures = Vec::new();
    let pixel_count = u64::from(expected.width()) * u64::from(expected.height());
    let golden = Thresholds::GOLDEN;
    if is_nearly_blank(
        expected,
        golden.channel_tolerance,
        golden.max_bad_pixels(pixel_count),
    ) {
        failures.push(Failure::UniformExpected);
    }
    let (bad_pixels, max_channel_difference) =
        count_bad_pixels(expected, actual, golden.channel_tolerance);

    // Blur in linear light, where a pixel's samples are averaged, then encode for FLIP.
    let blurred = |image: &RgbaImage| {
        FloatImage::linear_from_rgba8(image)
            .gaussian_blur(thresholds.blur_sigma)
            .encoded_as_srgb()
    };
    let (expected_blurred, actual_blurred) = (blurred(expected), blurred(actual));
    let map = flip::flip(
        &expected_blurred.to_rgb8_bytes(),
        &actual_blurred.to_rgb8_bytes(),
        expected_blurred.width,
        expected_blurred.height,
    );
    let (mean_flip, peak_flip) = (map.mean(), map.peak(PEAK_WINDOW));
    if peak_flip > thresholds.max_peak_flip {
        failures.push(Failure::PeakFlip {
            peak: peak_flip,
            threshold: thresholds.max_peak_flip,
        });
    }

    let diagnosis = diagnosis::estimate(&expected_blurred, &actual_blurred)
        .and_then(|estimate| diagnose(&estimate, thresholds));
    if diagnosis.is_some() {
        failures.push(Failure::CameraMistake);
    }

    Comparison {
        mode: Mode::Instructor,
        failures,
        metrics: Some(Metrics {
            pixel_count,
            bad_pixels,
            max_channel_difference,
            mean_flip,
            peak_flip,
        }),
        diagnosis,
        heatmap: Some(map.heatmap()),
    }
}

/// The diagnosis an estimate supports: `None` when the transform is within the tolerances
/// of the identity or explains too little of the difference.
fn diagnose(
    estimate: &diagnosis::Estimate,
    thresholds: &InstructorThresholds,
) -> Option<Diagnosis> {
    let t = estimate.transform;
    let significant = Significant {
        scale_x: (t.scale[0] - 1.0).abs() > thresholds.max_scale_error,
        scale_y: (t.scale[1] - 1.0).abs() > thresholds.max_scale_error,
        shift_x: t.shift[0].abs() > thresholds.max_shift,
        shift_y: t.shift[1].abs() > thresholds.max_shift,
    };
    let mistaken = t.mirror_x || t.mirror_y || significant != Significant::default();
    // Below this mean squared difference (an RMS of a tenth of an 8-bit code) the images
    // are the same: there is nothing to explain.
    let noise_floor = (0.1f64 / 255.0).powi(2);
    if !mistaken || estimate.identity_residual < noise_floor {
        return None;
    }
    let explained = 1.0 - estimate.residual / estimate.identity_residual;
    (explained >= thresholds.min_explained).then_some(Diagnosis {
        mirrored_left_right: t.mirror_x,
        upside_down: t.mirror_y,
        scale: (t.scale[0], t.scale[1]),
        shift: (t.shift[0], t.shift[1]),
        significant,
        explained,
    })
}
