//! Instructor mode: judge a student's render as an instructor would.

use std::cell::OnceCell;
use std::sync::{Arc, OnceLock};

use image::RgbaImage;

use crate::appearance;
use crate::camera::{CameraFinding, CameraJudge, Judge};
use crate::comparison::{Comparison, Failure, Metrics, Mode, count_bad_pixels, is_nearly_blank};
use crate::diagnosis::{CameraMistake, Diagnosis, Expectations, Significant};
use crate::estimate::{self, Estimate, ExpectedPyramid, Pyramid};
use crate::flip::{FlipReference, PEAK_WINDOW};
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
    /// Default 0.02 (2%): a fifth of the classic wrong field of view (1.1x, measured 1.099
    /// to 1.101), and above what a one-sample render's aliasing fakes on a moved picture
    /// (up to 1.2% where the far lines of a ground grid alias).
    pub max_scale_error: f64,
    /// A turn of the picture is a mistake when it exceeds this many degrees.
    ///
    /// Default 0.5: a sixth of the smallest rolled up vector of the test matrix (3
    /// degrees), a move of a pixel at the corners of a 320 x 240 picture, and twice what
    /// the sampling of a one-sample render fakes on a correct or merely moved picture (up
    /// to 0.3 degrees on the test scenes).
    pub max_rotation: f64,
    /// A transform is reported only when undoing it removes at least this fraction of the
    /// mean squared difference between the blurred images, on the part both show.
    ///
    /// Default 0.5: a camera mistake explains nearly all of the difference (0.98 and more
    /// on the test matrix, `tests/it/planted`; the half-pixel offset at one sample, 0.82),
    /// while a transform fitted to antialiasing noise or to an unrelated change (a missing
    /// object) explains little.
    pub min_explained: f64,
    /// A transform is reported only when, undone, it leaves at most this much of the
    /// contrast on the part both images show (the squared difference over the variances
    /// of both): a camera mistake leaves antialiasing noise (under 0.02 on the test
    /// scenes), an unrelated picture about 1.
    pub max_unexplained: f64,
}

impl Default for InstructorThresholds {
    fn default() -> Self {
        Self {
            max_peak_flip: 0.3,
            blur_sigma: 2.0,
            max_shift: 0.25,
            max_scale_error: 0.02,
            max_rotation: 0.5,
            min_explained: 0.5,
            max_unexplained: 0.1,
        }
    }
}

/// Judges a student's render (`actual`) against the instructor's reference (`expected`):
/// antialiasing and sample count are not errors, camera mistakes are. The diagnosis is
/// worded in pixels; [`judge_with`] words it in the lecture's terms.
///
/// 1. Both images are blurred in linear light (`blur_sigma`), which makes renders with any
///    sample pattern and count agree, then compared with FLIP: it fails when the worst
///    3 x 3 window is above `max_peak_flip` (a missing object, a wrong colour, a moved
///    edge).
/// 2. The systematic transform between the blurred images is estimated (mirrors, a turn,
///    per-axis scale, a move; see [`CameraMistake`]), on the part both images show. When
///    FLIP passed, the images already agree and only a small transform can hide in them:
///    it is refined from the identity, with no search. When FLIP failed, a search over
///    mirrors, turns of up to 30 degrees, scales from 0.68x to 1.45x and moves of up to
///    the whole picture finds it. Only the components the evidence supports are kept: each
///    is removed in turn, and kept only if that clearly raises the difference.
/// 3. The render fails when the transform is beyond `max_shift` / `max_scale_error` /
///    `max_rotation` or mirrored, and explains at least `min_explained` of the difference,
///    leaving at most `max_unexplained`. This catches what the blur hides: a half-pixel
///    move of every edge.
///
/// A failed render gets a [`Diagnosis`]: the camera mistake, with messages like
/// `mirrored left-right: check u = up x w`, or, when no transform explains the
/// difference, [`Diagnosis::Unexplained`]. A blank expected image and images of different
/// sizes fail, as in [`crate::compare`]. Never panics.
pub fn judge(
    expected: &RgbaImage,
    actual: &RgbaImage,
    thresholds: &InstructorThresholds,
) -> Comparison {
    judge_with(expected, actual, thresholds, None)
}

/// [`judge`], with the reference scene's [`Expectations`] when they are known: the
/// diagnosis then speaks the lecture's terms ("the sign of the shift is flipped", "your
/// field of view is 1.25 times too wide"), a scale or turn about the principal point is
/// no move, and the moves the scene's shift predicts are tried even when little of the
/// picture is left in common. The verdict is the same as without them.
///
/// To judge many renders against one reference, prepare it once with [`Reference::new`]:
/// the same judgement, without redoing the reference's half of the work.
pub fn judge_with(
    expected: &RgbaImage,
    actual: &RgbaImage,
    thresholds: &InstructorThresholds,
    expectations: Option<&Expectations>,
) -> Comparison {
    Reference::new(expected.clone(), *thresholds, expectations.copied()).judge(actual)
}

/// A reference image prepared for judging renders against it: everything [`judge_with`]
/// computes from the reference alone (its blur, its half of FLIP, its image pyramid),
/// computed once. A class of students judged against one reference shares it, across
/// threads too.
///
/// [`Reference::judge`] gives exactly what [`judge_with`] gives for the same images,
/// thresholds and expectations, bit for bit. With a [`CameraJudge`]
/// ([`Reference::with_camera`]) it judges the picture's camera too, and the [`Judge`]
/// says which judgement decides.
#[derive(Clone, Debug)]
pub struct Reference {
    expected: RgbaImage,
    thresholds: InstructorThresholds,
    expectations: Option<Expectations>,
    /// Whether the image is (nearly) one flat colour.
    uniform: bool,
    /// In linear light, before and after the blur, and the blurred image sRGB-encoded.
    linear: FloatImage,
    blurred_linear: FloatImage,
    blurred: FloatImage,
    flip: FlipReference,
    pyramid: ExpectedPyramid,
    /// The scene's judge of a picture's camera, when the scene is known.
    camera: Option<Arc<dyn CameraJudge>>,
    /// Which judgement decides.
    decides: Judge,
    /// Where appearance is measured without a camera judge: the reference's flat parts,
    /// found the first time they are needed.
    flat: OnceLock<Vec<bool>>,
}

impl Reference {
    /// Prepares `expected` for judging renders against it with `thresholds`, and the
    /// reference scene's `expectations` when they are known (see [`judge_with`]).
    pub fn new(
        expected: RgbaImage,
        thresholds: InstructorThresholds,
        expectations: Option<Expectations>,
    ) -> Self {
        let pixel_count = u64::from(expected.width()) * u64::from(expected.height());
        let golden = Thresholds::GOLDEN;
        let uniform = is_nearly_blank(
            &expected,
            golden.channel_tolerance,
            golden.max_bad_pixels(pixel_count),
        );
        let linear = FloatImage::linear_from_rgba8(&expected);
        let blurred_linear = linear.gaussian_blur(thresholds.blur_sigma);
        let blurred = blurred_linear.encoded_as_srgb();
        let flip = FlipReference::new(&blurred.to_rgb8_bytes(), blurred.width, blurred.height);
        let pyramid = ExpectedPyramid::new(&blurred);
        Self {
            expected,
            thresholds,
            expectations,
            uniform,
            linear,
            blurred_linear,
            blurred,
            flip,
            pyramid,
            camera: None,
            decides: Judge::Image,
            flat: OnceLock::new(),
        }
    }

    /// This reference with the scene's `camera` judge, and `decides` saying which
    /// judgement decides a render's verdict ([`Judge::Image`] still judges and reports
    /// the camera).
    #[must_use]
    pub fn with_camera(self, camera: Arc<dyn CameraJudge>, decides: Judge) -> Self {
        Self {
            camera: Some(camera),
            decides,
            ..self
        }
    }

    /// Which judgement decides a render's verdict.
    pub fn decides(&self) -> Judge {
        self.decides
    }

    /// Whether renders' cameras are judged (a scene's judge was given).
    pub fn judges_cameras(&self) -> bool {
        self.camera.is_some()
    }

    /// The reference image.
    pub fn image(&self) -> &RgbaImage {
        &self.expected
    }

    /// The thresholds renders are judged by.
    pub fn thresholds(&self) -> &InstructorThresholds {
        &self.thresholds
    }

    /// The reference scene's expectations, when they are known.
    pub fn expectations(&self) -> Option<&Expectations> {
        self.expectations.as_ref()
    }

    /// Judges a student's render (`actual`) against this reference, as [`judge_with`]
    /// does, and its camera when a camera judge was given. Never panics.
    pub fn judge(&self, actual: &RgbaImage) -> Comparison {
        let expected = &self.expected;
        let thresholds = &self.thresholds;
        if expected.dimensions() != actual.dimensions() {
            let mut comparison = Comparison::size_mismatch(Mode::Instructor, expected, actual);
            comparison.judge = self.decides;
            comparison.camera = self.camera.as_ref().map(|_| CameraFinding::WrongSize {
                found: actual.dimensions(),
                expected: expected.dimensions(),
            });
            return comparison;
        }
        let mut failures = Vec::new();
        let pixel_count = u64::from(expected.width()) * u64::from(expected.height());
        if self.uniform {
            failures.push(Failure::UniformExpected);
        }
        let golden = Thresholds::GOLDEN;
        let (bad_pixels, max_channel_difference) =
            count_bad_pixels(expected, actual, golden.channel_tolerance);

        // Blur in linear light, where a pixel's samples are averaged, then encode for FLIP.
        let actual_linear = FloatImage::linear_from_rgba8(actual);
        let actual_blurred_linear = actual_linear.gaussian_blur(thresholds.blur_sigma);
        let actual_blurred =
            actual_blurred_linear.encoded_as_srgb_reusing(&self.blurred_linear, &self.blurred);
        let map = self.flip.compare(&actual_blurred.to_rgb8_bytes());
        let (mean_flip, peak_flip) = (map.mean(), map.peak(PEAK_WINDOW));
        let flip_failed = peak_flip > thresholds.max_peak_flip;
        if flip_failed {
            failures.push(Failure::PeakFlip {
                peak: peak_flip,
                threshold: thresholds.max_peak_flip,
            });
        }

        // The transform between the pictures, as the image judgement measures it: at once
        // when the image judgement decides (or is the only one); else only when the camera
        // judge asks, to say what it measured.
        let transform = |search: bool| {
            let mut mistake = find_mistake(
                &self.blurred,
                &self.pyramid,
                &actual_blurred,
                search,
                thresholds,
                self.expectations.as_ref(),
            );
            if mistake.is_none()
                && search
                && let Some(expectations) = &self.expectations
            {
                mistake = find_predicted_move(&self.linear, &actual_linear, expectations);
            }
            mistake
        };
        let measured: OnceCell<Option<CameraMistake>> = OnceCell::new();
        if self.decides.image_decides() || self.camera.is_none() {
            let _ = measured.set(transform(flip_failed));
        }
        let camera = self
            .camera
            .as_ref()
            .map(|judge| judge.judge(actual, &|| *measured.get_or_init(|| transform(true))));
        // A camera that cannot be judged leaves the verdict to the image judgement.
        let unjudged = camera.as_ref().is_some_and(|c| !c.judged());
        if unjudged {
            let _ = measured.get_or_init(|| transform(flip_failed));
        }
        let mistake = measured.get().copied().flatten();
        let image_judged = self.decides.image_decides() || self.camera.is_none() || unjudged;
        let diagnosis = match mistake {
            Some(mistake) => {
                if image_judged {
                    failures.push(Failure::CameraMistake);
                }
                Some(Diagnosis::Camera(mistake))
            }
            None if flip_failed && image_judged => Some(Diagnosis::Unexplained {
                whole_view: differs_everywhere(&self.blurred, &actual_blurred),
            }),
            None => None,
        };

        // Appearance, where the camera is right (or, without a scene, where no transform
        // explains the difference).
        let camera_right = match &camera {
            Some(finding) if finding.judged() => finding.passed(),
            _ => mistake.is_none(),
        };
        let appearance = camera_right.then(|| {
            let interior = match &self.camera {
                Some(judge) => judge.interior(),
                None => self
                    .flat
                    .get_or_init(|| appearance::flat_parts(&self.linear)),
            };
            appearance::classify(
                &appearance::Pictures {
                    expected: &self.linear,
                    actual: &actual_linear,
                    expected_blurred: &self.blurred_linear,
                    actual_blurred: &actual_blurred_linear,
                    interior,
                },
                flip_failed,
            )
        });

        let failures = decide(self.decides, failures, camera.as_ref());
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
            camera,
            appearance,
            judge: self.decides,
            error_map: Some(map),
        }
    }
}

/// The failures that decide a verdict: the image judgement's (`image`), the camera's, or
/// both, as `decides` says. Without a camera judgement (or one that could not judge),
/// the image's.
fn decide(decides: Judge, image: Vec<Failure>, camera: Option<&CameraFinding>) -> Vec<Failure> {
    let Some(camera) = camera.filter(|c| c.judged()) else {
        return image;
    };
    let wrong = (!camera.passed()).then(|| Failure::WrongCamera {
        diagnosis: camera.diagnosis(),
    });
    match decides {
        Judge::Image => image,
        Judge::Camera => wrong.into_iter().collect(),
        Judge::Both => wrong.into_iter().chain(image).collect(),
    }
}

/// Below this mean squared difference (an RMS of a tenth of an 8-bit code) two images
/// are the same: there is nothing to explain.
const NOISE_FLOOR: f64 = (0.1 / 255.0) * (0.1 / 255.0);

/// Estimates the transform between the blurred images and keeps it if it is a camera
/// mistake: the search only when FLIP failed (a pass can hide only a small transform).
fn find_mistake(
    expected: &FloatImage,
    expected_pyramid: &ExpectedPyramid,
    actual: &FloatImage,
    flip_failed: bool,
    thresholds: &InstructorThresholds,
    expectations: Option<&Expectations>,
) -> Option<CameraMistake> {
    if expected.width < 16 || expected.height < 16 {
        return None;
    }
    let identical = expected
        .pixels
        .iter()
        .zip(&actual.pixels)
        .all(|(e, a)| (0..3).all(|c| (e[c] - a[c]).abs() < 1e-4));
    if identical {
        return None;
    }
    // A pass is refined on the two finest levels alone.
    let max_levels = if flip_failed { usize::MAX } else { 2 };
    let pyramid = Pyramid::new(expected_pyramid, actual, thresholds.blur_sigma, max_levels);
    let size = (expected.width as u32, expected.height as u32);
    let centre = pyramid.centre();
    let mut anchors = vec![centre];
    let mut extra = Vec::new();
    if let Some(e) = expectations {
        let (px, py) = e.principal_point_pixels(size.0, size.1);
        if (px - centre[0]).abs() > 0.25 || (py - centre[1]).abs() > 0.25 {
            anchors.push([px, py]);
        }
        let (mx, my) = e.missing_shift_move(size.0, size.1);
        for k in [1.0, 2.0] {
            let mut model = estimate::Model::identity(centre);
            model.shift = [k * mx, k * my];
            extra.push(model);
        }
    }
    let tolerances = estimate::Tolerances {
        shift: thresholds.max_shift,
        scale: thresholds.max_scale_error,
        rotation: thresholds.max_rotation.to_radians(),
    };
    let estimate = if flip_failed {
        estimate::estimate_search(&pyramid, &anchors, &extra, &tolerances)
    } else {
        estimate::estimate_local(&pyramid, &anchors, &tolerances)
    };
    diagnose(&estimate, &pyramid, size, thresholds, expectations)
}

/// The camera mistake an estimate supports: `None` when the transform is within the
/// tolerances of the identity or explains too little of the difference.
fn diagnose(
    estimate: &Estimate,
    pyramid: &Pyramid,
    size: (u32, u32),
    thresholds: &InstructorThresholds,
    expectations: Option<&Expectations>,
) -> Option<CameraMistake> {
    let model = estimate.model;
    let kept = estimate.kept;
    let [sx, sy] = model.scale();
    let rotation = -model.rotation.to_degrees();
    let scaled = kept.scale || kept.aspect;
    let mut significant = Significant {
        rotation: kept.rotation && rotation.abs() > thresholds.max_rotation,
        scale_x: scaled && (sx - 1.0).abs() > thresholds.max_scale_error,
        scale_y: scaled && (sy - 1.0).abs() > thresholds.max_scale_error,
        ..Significant::default()
    };
    let mirrored = model.mirror[0] || model.mirror[1];
    let linear = mirrored || significant.rotation || significant.scale_x || significant.scale_y;
    let centre = pyramid.centre();
    // Write the transform about the point that names it best.
    let (about, shift) = if !linear {
        (centre, model.about_point(centre).shift)
    } else if !kept.shift {
        (model.about, [0.0; 2])
    } else if let Some(e) = expectations {
        let (px, py) = e.principal_point_pixels(size.0, size.1);
        ([px, py], model.about_point([px, py]).shift)
    } else {
        let (w, h) = (f64::from(size.0), f64::from(size.1));
        match model.fixed_point() {
            Some(p)
                if (-0.5 * w..=1.5 * w).contains(&p[0]) && (-0.5 * h..=1.5 * h).contains(&p[1]) =>
            {
                significant.about = true;
                (p, [0.0; 2])
            }
            _ => (centre, model.about_point(centre).shift),
        }
    };
    significant.shift_x = shift[0].abs() > thresholds.max_shift;
    significant.shift_y = shift[1].abs() > thresholds.max_shift;
    let mistaken = linear || significant.shift_x || significant.shift_y;
    if !mistaken || estimate.identity_mean < NOISE_FLOOR {
        return None;
    }
    let explained = 1.0 - estimate.fit.mean() / estimate.identity_mean;
    let believable = explained >= thresholds.min_explained
        && estimate.normalized <= thresholds.max_unexplained
        && estimate.fit.overlap() >= estimate::MIN_OVERLAP
        && estimate::textured(estimate.texture)
        && !estimate.ambiguous;
    believable.then_some(CameraMistake {
        mirrored_left_right: model.mirror[0],
        upside_down: model.mirror[1],
        rotation,
        scale: (sx, sy),
        about: (about[0], about[1]),
        shift: (shift[0], shift[1]),
        significant,
        explained,
        overlap: estimate.fit.overlap(),
        size,
        expectations: expectations.copied(),
    })
}

/// The move the scene's shift predicts (left out, or with its sign flipped), checked on
/// the sharp images when the search found nothing: it moves the picture so far that the
/// blurred images keep nothing in common away from their borders.
fn find_predicted_move(
    expected: &FloatImage,
    actual: &FloatImage,
    expectations: &Expectations,
) -> Option<CameraMistake> {
    let size = (expected.width as u32, expected.height as u32);
    let (mx, my) = expectations.missing_shift_move(size.0, size.1);
    if mx.abs() < 0.5 && my.abs() < 0.5 {
        return None;
    }
    [2.0, 1.0].into_iter().find_map(|k| {
        let (shift, overlap, explained) =
            estimate::verify_move(expected, actual, [k * mx, k * my])?;
        Some(CameraMistake {
            mirrored_left_right: false,
            upside_down: false,
            rotation: 0.0,
            scale: (1.0, 1.0),
            about: (f64::from(size.0) / 2.0, f64::from(size.1) / 2.0),
            shift: (shift[0], shift[1]),
            significant: Significant {
                shift_x: shift[0].abs() > 0.25,
                shift_y: shift[1].abs() > 0.25,
                ..Significant::default()
            },
            explained,
            overlap,
            size,
            expectations: Some(*expectations),
        })
    })
}

/// Whether the blurred images differ over most of the picture (a different view), not
/// in a part of it (an object or a colour).
fn differs_everywhere(expected: &FloatImage, actual: &FloatImage) -> bool {
    let differing = expected
        .pixels
        .iter()
        .zip(&actual.pixels)
        .filter(|(e, a)| (0..3).any(|c| (e[c] - a[c]).abs() > 0.05))
        .count();
    differing as f64 > 0.5 * expected.pixels.len() as f64
}

#[cfg(test)]
mod tests {
    use image::Rgba;

    use super::*;

    /// A camera judge that always finds `finding`.
    #[derive(Debug)]
    struct Always {
        finding: CameraFinding,
        interior: Vec<bool>,
    }

    impl CameraJudge for Always {
        fn size(&self) -> (u32, u32) {
            (32, 24)
        }

        fn judge(
            &self,
            _picture: &RgbaImage,
            _measure: &dyn Fn() -> Option<CameraMistake>,
        ) -> CameraFinding {
            self.finding.clone()
        }

        fn interior(&self) -> &[bool] {
            &self.interior
        }
    }

    /// A grey picture with a coloured square at `x0`.
    fn picture(x0: u32, colour: [u8; 3]) -> RgbaImage {
        RgbaImage::from_fn(32, 24, |x, y| {
            if (x0..x0 + 8).contains(&x) && (8..16).contains(&y) {
                Rgba([colour[0], colour[1], colour[2], 255])
            } else {
                Rgba([90, 90, 90, 255])
            }
        })
    }

    fn reference(finding: CameraFinding) -> Reference {
        let judge = Always {
            finding,
            interior: vec![true; 32 * 24],
        };
        Reference::new(
            picture(10, [220, 40, 40]),
            InstructorThresholds::default(),
            None,
        )
        .with_camera(Arc::new(judge), Judge::Camera)
    }

    #[test]
    fn a_camera_not_judged_leaves_the_verdict_to_the_image() {
        let reference = reference(CameraFinding::Unjudged);
        // The same picture passes; its camera is unjudged, not wrong.
        let same = reference.judge(&picture(10, [220, 40, 40]));
        assert!(same.passed(), "{:?}", same.failures);
        assert_eq!(
            same.camera.as_ref().map(CameraFinding::word),
            Some("unjudged")
        );
        assert!(same.note().contains("cannot be judged"), "{}", same.note());
        // Another colour fails by the image judgement, and no camera mistake is named.
        let other = reference.judge(&picture(10, [40, 40, 220]));
        assert!(!other.passed());
        assert!(
            other
                .failures
                .iter()
                .all(|f| !matches!(f, Failure::WrongCamera { .. })),
            "{:?}",
            other.failures
        );
        assert!(
            other.note().contains("cannot be judged"),
            "{}",
            other.note()
        );
    }

    #[test]
    fn a_camera_judged_decides_alone() {
        // A right camera passes whatever the colours; a wrong one fails the same picture.
        let right = reference(CameraFinding::Right { agreement: 1.0 });
        assert!(right.judge(&picture(10, [40, 40, 220])).passed());
        let wrong = reference(CameraFinding::Unexplained {
            measured: None,
            right: 0.5,
        });
        let judged = wrong.judge(&picture(10, [220, 40, 40]));
        assert!(matches!(
            judged.failures.as_slice(),
            [Failure::WrongCamera { .. }]
        ));
    }
}
