//! The result of comparing two images, shared by the golden and the instructor modes.

use std::collections::HashMap;
use std::fmt;

use image::{RgbImage, RgbaImage};

use crate::appearance::Appearance;
use crate::camera::{CameraFinding, Judge};
use crate::diagnosis::Diagnosis;
use crate::flip::ErrorMap;
use crate::outcome::Verdict;

/// Which rules judged a comparison.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// [`crate::compare`]: the strict gates for golden images (same renderer, same
    /// samples; only last-bit differences may pass).
    Golden,
    /// [`crate::judge`]: an instructor's judgement of a student's render (antialiasing and
    /// sample count are not errors; camera mistakes are).
    Instructor,
}

impl Mode {
    /// A lowercase name: `golden` or `instructor`.
    pub fn name(self) -> &'static str {
        match self {
            Mode::Golden => "golden",
            Mode::Instructor => "instructor",
        }
    }
}

/// The figures measured on a pair of images of the same size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Metrics {
    /// Width times height.
    pub pixel_count: u64,
    /// Pixels where some channel (R, G, B or A, 8-bit codes) differs by more than the
    /// golden channel tolerance, [`crate::Thresholds::channel_tolerance`].
    pub bad_pixels: u64,
    /// The largest difference of any channel of any pixel, in 8-bit codes.
    pub max_channel_difference: u8,
    /// The mean of the FLIP error map, in [0, 1] (0: no visible difference).
    pub mean_flip: f32,
    /// The largest mean FLIP error over any 3 x 3 window of pixels, in [0, 1]: how bad the
    /// worst small region is, while a lone stray pixel counts for a ninth.
    pub peak_flip: f32,
}

/// One reason a comparison failed.
#[derive(Clone, Debug, PartialEq)]
pub enum Failure {
    /// The images differ in size; nothing else is compared.
    SizeMismatch {
        /// Width and height of the expected image.
        expected: (u32, u32),
        /// Width and height of the actual image.
        actual: (u32, u32),
    },
    /// The expected image is (nearly) one flat colour: no more of its pixels differ from
    /// its most common colour than the per-pixel gate forgives
    /// ([`crate::Thresholds::max_bad_pixels`]). Such a reference would pass a blank
    /// render, so it proves nothing.
    UniformExpected,
    /// More pixels than allowed differ by more than the channel tolerance.
    TooManyBadPixels {
        /// Pixels beyond the tolerance.
        bad: u64,
        /// The most that may be.
        allowed: u64,
        /// The channel tolerance, in 8-bit codes.
        tolerance: u8,
    },
    /// The mean FLIP error is above its threshold.
    MeanFlip {
        /// The measured mean.
        mean: f32,
        /// The threshold.
        threshold: f32,
    },
    /// The worst 3 x 3 window's FLIP error is above its threshold.
    PeakFlip {
        /// The measured peak.
        peak: f32,
        /// The threshold.
        threshold: f32,
    },
    /// The actual image is the expected one moved, mirrored or scaled: a camera mistake
    /// (see [`Comparison::diagnosis`]).
    CameraMistake,
    /// The camera judgement failed: the picture's edges are not where the scene's are
    /// (see [`Comparison::camera`]).
    WrongCamera {
        /// The camera's diagnosis ([`CameraFinding::diagnosis`]).
        diagnosis: String,
    },
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::SizeMismatch { expected, actual } => write!(
                f,
                "sizes differ: expected {}x{}, actual {}x{}",
                expected.0, expected.1, actual.0, actual.1
            ),
            Failure::UniformExpected => write!(
                f,
                "the expected image is one flat colour: it would pass a blank render, so it \
                 proves nothing"
            ),
            Failure::TooManyBadPixels {
                bad,
                allowed,
                tolerance,
            } => write!(
                f,
                "{bad} pixels differ by more than {tolerance}/255 in some channel (at most \
                 {allowed} may)"
            ),
            Failure::MeanFlip { mean, threshold } => {
                write!(f, "mean FLIP {mean:.4} is above {threshold}")
            }
            Failure::PeakFlip { peak, threshold } => {
                write!(f, "peak FLIP (3x3 window) {peak:.4} is above {threshold}")
            }
            Failure::CameraMistake => write!(
                f,
                "the whole picture is moved, mirrored or scaled: a camera mistake"
            ),
            Failure::WrongCamera { diagnosis } => write!(f, "the camera is wrong: {diagnosis}"),
        }
    }
}

/// The outcome of comparing an expected image with an actual one.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// The rules that judged it.
    pub mode: Mode,
    /// Why it failed; empty when it passed.
    pub failures: Vec<Failure>,
    /// The measured figures; `None` when the sizes differ.
    pub metrics: Option<Metrics>,
    /// The camera mistake that explains the difference, if one does (instructor mode):
    /// the transform between the pictures, measured on their pixels.
    pub diagnosis: Option<Diagnosis>,
    /// The camera judgement (instructor mode, with a [`crate::CameraJudge`]): the
    /// picture's edges against the scene's; `None` when not judged.
    pub camera: Option<CameraFinding>,
    /// How the picture looks beside the reference, apart from its camera (instructor
    /// mode); `None` when not judged (a wrong camera's picture, or other sizes).
    pub appearance: Option<Appearance>,
    /// Which judgement decided [`Comparison::failures`].
    pub judge: Judge,
    /// The FLIP error map, for [`Comparison::heatmap`]; `None` when the sizes differ.
    pub(crate) error_map: Option<ErrorMap>,
}

impl Comparison {
    /// Whether the actual image passed.
    pub fn passed(&self) -> bool {
        self.failures.is_empty()
    }

    /// `PASS` or `FAIL` ([`Verdict::label`]).
    pub fn verdict(&self) -> &'static str {
        let verdict = if self.passed() {
            Verdict::Pass
        } else {
            Verdict::Fail
        };
        verdict.label()
    }

    /// The FLIP error map in the magma colour map (black: no difference; pale yellow: the
    /// largest), made when asked for; `None` when the sizes differ.
    pub fn heatmap(&self) -> Option<RgbImage> {
        self.error_map.as_ref().map(ErrorMap::heatmap)
    }

    /// This comparison without the FLIP error map [`Comparison::heatmap`] draws from (a
    /// float per pixel), for keeping many comparisons: its heatmap is then `None`.
    pub fn without_error_map(self) -> Self {
        Self {
            error_map: None,
            ..self
        }
    }

    /// What a row says after the figures: under [`Judge::Image`] the transform's diagnosis,
    /// else why it failed; under [`Judge::Camera`] the camera's diagnosis; under
    /// [`Judge::Both`] both (`""` when there is nothing to say).
    pub fn note(&self) -> String {
        let image = || match self.diagnosis {
            Some(d) => d.to_string(),
            None => self.reasons(),
        };
        let camera = || {
            self.camera
                .as_ref()
                .filter(|c| !c.passed())
                .map(CameraFinding::diagnosis)
        };
        match self.judge {
            Judge::Image => image(),
            // A camera not judged leaves the verdict to the image judgement: both speak.
            Judge::Camera if self.camera.as_ref().is_some_and(|c| !c.judged()) => {
                [camera(), Some(image())]
                    .into_iter()
                    .flatten()
                    .filter(|note| !note.is_empty())
                    .collect::<Vec<_>>()
                    .join("; ")
            }
            Judge::Camera => camera().unwrap_or_default(),
            Judge::Both => {
                let image = self
                    .failures
                    .iter()
                    .any(|f| !matches!(f, Failure::WrongCamera { .. }))
                    .then(|| match self.diagnosis {
                        Some(d) => d.to_string(),
                        None => self
                            .failures
                            .iter()
                            .filter(|f| !matches!(f, Failure::WrongCamera { .. }))
                            .map(ToString::to_string)
                            .collect::<Vec<_>>()
                            .join("; "),
                    });
                [camera(), image]
                    .into_iter()
                    .flatten()
                    .collect::<Vec<_>>()
                    .join("; ")
            }
        }
    }

    /// The reasons for failing, as one line (`""` when it passed).
    pub fn reasons(&self) -> String {
        self.failures
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join("; ")
    }

    pub(crate) fn size_mismatch(mode: Mode, expected: &RgbaImage, actual: &RgbaImage) -> Self {
        Self {
            mode,
            failures: vec![Failure::SizeMismatch {
                expected: expected.dimensions(),
                actual: actual.dimensions(),
            }],
            metrics: None,
            diagnosis: None,
            camera: None,
            appearance: None,
            judge: Judge::Image,
            error_map: None,
        }
    }
}

/// Whether `image` is one flat colour but for at most `allowed` pixels: no more pixels
/// differ from its most common colour by more than `tolerance` than the per-pixel gate
/// forgives, so a blank render would pass against it.
pub(crate) fn is_nearly_blank(image: &RgbaImage, tolerance: u8, allowed: u64) -> bool {
    let mut counts: HashMap<[u8; 4], u64> = HashMap::new();
    for pixel in image.pixels() {
        *counts.entry(pixel.0).or_default() += 1;
    }
    let Some((&common, _)) = counts.iter().max_by_key(|&(color, count)| (*count, *color)) else {
        return true;
    };
    let different = image
        .pixels()
        .filter(|p| (0..4).any(|c| p[c].abs_diff(common[c]) > tolerance))
        .count() as u64;
    different <= allowed
}

/// Counts pixels whose largest channel difference exceeds `tolerance`; also returns the
/// largest difference seen.
pub(crate) fn count_bad_pixels(
    expected: &RgbaImage,
    actual: &RgbaImage,
    tolerance: u8,
) -> (u64, u8) {
    let mut bad = 0;
    let mut largest = 0;
    for (e, a) in expected.pixels().zip(actual.pixels()) {
        let difference = (0..4).map(|c| e[c].abs_diff(a[c])).max().unwrap_or(0);
        largest = largest.max(difference);
        if difference > tolerance {
            bad += 1;
        }
    }
    (bad, largest)
}
