//! Image comparison: the golden-image gates of `cargo xtask golden`, and the instructor's
//! judgement of `viewray compare`, with diff heatmaps and an HTML report.
//!
//! This crate owns deciding whether two images are "the same picture". It compares
//! decoded pixels (never PNG bytes) and knows nothing about scenes, cameras or the
//! renderer: it depends on no other viewray crate but the leaf `viewray-output` (the
//! sRGB transfer function, the PNG encoder, atomic writes). Its only I/O is [`load_png`]
//! and [`write_report`].
//!
//! Two modes share one result type, [`Comparison`]:
//!
//! - [`compare`] with [`Thresholds::GOLDEN`]: a render must match its committed reference
//!   up to last-bit floating-point noise. A per-pixel gate (channel tolerance, a tiny
//!   allowance of bad pixels) and a perceptual gate (NVIDIA's LDR-FLIP, mean and worst
//!   3 x 3 window).
//! - [`judge`] with [`InstructorThresholds`]: a student's render against the instructor's.
//!   Antialiasing and sample count are not errors (both images are blurred before FLIP);
//!   camera mistakes are, and the systematic transform between the images (mirrors, a
//!   turn, a scale about any point, a move; measured on the part both images show) names
//!   them: a [`Diagnosis`] such as `shifted -0.5 px in x and y: check the pixel-centre
//!   offset (j - 1/2, i - 1/2)` or `rotated 8 degrees counterclockwise: check the up
//!   vector`, or, when no transform explains the difference, [`Diagnosis::Unexplained`].
//!   [`judge_with`] takes the reference scene's [`Expectations`] (its principal point and
//!   lens shift, as plain numbers) and words the diagnosis in the lecture's terms: `shifted
//!   64 px up: the sign of the shift is flipped`. A [`Reference`] is a reference image
//!   prepared once (its blur, its half of FLIP, its image pyramid) to judge a class of
//!   renders against, with the same result as [`judge_with`], bit for bit.
//!
//! What became of a pair, compared or not and whose failure that is, is an [`Outcome`]
//! with its [`Verdict`]; a [`Tally`] counts many. The golden check, `viewray compare` and
//! `viewray grade` speak of pairs in these words, and their HTML pages share one skeleton
//! ([`report_page`], [`verdict_badge`]). FLIP is NVIDIA's reference code ported bit for bit
//! (module `flip`, its heatmap colours in `magma`); the transform behind a diagnosis is
//! estimated in module `estimate` (start at its `estimate_search`).
//!
//! Images follow the camera crate's pixel convention: W columns by H rows, 0-based from
//! the top-left, pixel (row, col) covering [col, col + 1) x [row, row + 1); x runs right
//! and y down, so a diagnosis's move (-0.5, -0.5) is left and up.
//!
//! ```no_run
//! use viewray_compare::{
//!     Outcome, Report, ReportEntry, Rules, Thresholds, compare, load_png, write_report,
//! };
//!
//! let expected = load_png("golden/scenes/perspective.png")?;
//! let actual = load_png("target/golden/perspective.png")?;
//! let outcome = Outcome::from(compare(&expected, &actual, &Thresholds::GOLDEN));
//! if !outcome.passed() {
//!     eprintln!("perspective: {}", outcome.note());
//! }
//! let entry = ReportEntry::new("perspective", Some(&expected), Some(&actual), &outcome);
//! let report = Report {
//!     title: "perspective against its golden image",
//!     summary: outcome.verdict().label(),
//!     rules: Rules::Golden(Thresholds::GOLDEN),
//!     entries: &[entry],
//! };
//! let page = write_report("target/golden", &report)?;
//! println!("report: {}", page.display());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod appearance;
mod camera;
mod chamfer;
mod comparison;
mod diagnosis;
mod estimate;
mod flip;
mod geometry;
mod golden;
mod instructor;
mod load;
mod magma;
mod outcome;
mod page;
mod raster;
mod report;

/// The pixel types of the API, from the `image` crate: RGBA8 images in, RGB8 heatmaps
/// out.
pub use image::{RgbImage, RgbaImage};

pub use appearance::Appearance;
pub use camera::{CameraFinding, CameraJudge, CatalogueEntry, Judge};
pub use comparison::{Comparison, Failure, Metrics, Mode};
pub use diagnosis::{CameraKind, CameraMistake, Diagnosis, Expectations, Significant};
pub use geometry::{
    AGREEMENT_MARGIN, AGREEMENT_NEEDED, CANDIDATE_MARGIN, COVERAGE_NEEDED, CameraCandidates, Fit,
    GeometryJudgement, GeometryVerdict, LabelMap, PictureEdges, STRONG_EDGE,
};
pub use golden::{Thresholds, compare};
pub use instructor::{InstructorThresholds, Reference, judge, judge_with};
pub use load::{IMAGE_EXTENSIONS, LoadError, SUPPORTED_IMAGES, load_image, load_png};
pub use outcome::{FailureKind, Outcome, Tally, Verdict};
pub use page::{report_page, verdict_badge};
pub use report::{Report, ReportEntry, Rules, unique_stem, write_report};

/// Decodes PNG bytes as [`load_png`] decodes a file's: the entry point of the PNG fuzz
/// target.
#[doc(hidden)]
pub fn fuzz_decode_png(bytes: &[u8]) -> Result<RgbaImage, String> {
    load::decode_png_bytes(bytes)
}
