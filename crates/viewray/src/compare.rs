//! `viewray compare`: judge renders against reference images as an instructor would.
//!
//! Output: a table on stdout, one row per reference image in name order, each printed as
//! soon as it and those before it are judged (pairs are judged in parallel), then the
//! files judged nowhere and a summary line; with `--json`, JSON lines instead: one object
//! per pair, then one `{"summary":{..}}` object.
//!
//! Folders are paired like `diff -r` (see [`viewray_grade::pair`]): a reference image the
//! ACTUAL folder lacks, or whose counterpart cannot be read, is a failing row; a problem
//! on the EXPECTED side, a scene, or a file given directly is bad input (exit 2).

use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;

use anyhow::{Context, Result, bail};
use clap::Args;
use rayon::prelude::*;
use viewray_camera::Projection;
use viewray_compare::{
    CameraJudge, CameraKind, Expectations, InstructorThresholds, Judge, Outcome, Reference, Report,
    ReportEntry, RgbaImage, Rules, Tally, Verdict, load_image, write_report,
};
use viewray_grade::{Counterpart, ReferenceImage, in_order, load_counterpart};
use viewray_judge::SceneJudge;
use viewray_scene::{LoadOptions, Scene, SceneLoader};

/// Exit code when a render failed.
pub(crate) const EXIT_FAILED: u8 = 1;

#[derive(Args, Debug)]
pub(crate) struct CompareArgs {
    /// The reference: an image file (PNG, PPM/PGM or OpenEXR), or a folder of them.
    pub(crate) expected: PathBuf,
    /// The render(s) to judge: an image file, or a folder whose files are paired with
    /// EXPECTED's images by name (or by stem in another format: a.ppm answers a.png).
    pub(crate) actual: PathBuf,
    /// The perceptual threshold, in [0, 1]: the largest FLIP error allowed in the worst 3x3
    /// window after both images are blurred by 2 px (0: identical; 1: black against
    /// white). The default passes correct renders made with any sample pattern or count,
    /// and fails an object moved by a pixel, a missing object or a clearly wrong colour.
    /// Camera mistakes (mirrored, scaled, shifted) fail whatever the threshold.
    #[arg(long, value_name = "X", value_parser = parse_threshold,
          default_value_t = InstructorThresholds::default().max_peak_flip)]
    pub(crate) threshold: f32,
    /// Also write the images, FLIP heatmaps and an HTML page (DIR/index.html) into DIR.
    #[arg(long, value_name = "DIR")]
    pub(crate) report: Option<PathBuf>,
    /// Print JSON lines instead of a table: one object per pair, then a summary object.
    #[arg(long)]
    pub(crate) json: bool,
    /// The scene the reference was rendered from: the diagnosis then speaks the lecture's
    /// terms ("the sign of the shift is flipped", "the shift is missing", "your field of
    /// view is 1.25 times too wide"). With folders, a folder of scenes matched to the
    /// images by file stem (a.png <-> a.ron), or one scene for every image.
    #[arg(long, value_name = "SCENE")]
    pub(crate) scene: Option<PathBuf>,
    /// Which judgement decides the verdict: `camera` (the render's edges against the
    /// scene's, whatever its shading, gamma, brightness or noise; needs --scene, and is
    /// the default with it), `image` (FLIP against the reference, the default without a
    /// scene) or `both`. The other is reported, never failed.
    #[arg(long, value_name = "WHAT", value_parser = parse_judge)]
    pub(crate) judge: Option<Judge>,
}

/// Parses `--judge`: `camera`, `image` or `both`.
pub(crate) fn parse_judge(text: &str) -> Result<Judge, String> {
    [Judge::Camera, Judge::Image, Judge::Both]
        .into_iter()
        .find(|j| j.word() == text.trim())
        .ok_or_else(|| format!("`{text}` is not a judgement: give camera, image or both"))
}

/// The judgement that decides: `judge` as given, else `camera` with a scene and `image`
/// without one.
///
/// # Errors
/// `--judge camera` or `both` without a scene.
pub(crate) fn deciding(judge: Option<Judge>, scene: Option<&Path>) -> Result<Judge> {
    match (judge, scene) {
        (Some(judge), Some(_)) => Ok(judge),
        (Some(Judge::Image) | None, None) => Ok(Judge::Image),
        (Some(judge), None) => bail!(
            "--judge {} needs --scene: the camera is judged against the scene the \
             reference was rendered from",
            judge.word()
        ),
        (None, Some(_)) => Ok(Judge::Camera),
    }
}

/// Parses `--threshold`: a FLIP error in [0, 1].
pub(crate) fn parse_threshold(text: &str) -> Result<f32, String> {
    let value: f32 = text
        .trim()
        .parse()
        .map_err(|_| format!("`{text}` is not a number"))?;
    if !(0.0..=1.0).contains(&value) {
        return Err(format!(
            "{text} is outside [0, 1]: FLIP errors run from 0 (identical) to 1"
        ));
    }
    Ok(value)
}

/// The thresholds of `--threshold`.
pub(crate) fn thresholds(threshold: f32) -> InstructorThresholds {
    InstructorThresholds {
        max_peak_flip: threshold,
        ..InstructorThresholds::default()
    }
}

/// A reference image with what judging against it needs.
pub(crate) struct Prepared {
    pub(crate) image: ReferenceImage,
    pub(crate) pixels: RgbaImage,
    pub(crate) expectations: Option<Expectations>,
    /// The scene's camera judge, when a scene was given.
    pub(crate) camera: Option<Arc<dyn CameraJudge>>,
}

impl Prepared {
    /// The reference, prepared to judge renders with `thresholds`, its camera judged when
    /// its scene is known, `decides` deciding the verdicts.
    pub(crate) fn reference(&self, thresholds: InstructorThresholds, decides: Judge) -> Reference {
        let reference = Reference::new(self.pixels.clone(), thresholds, self.expectations);
        match &self.camera {
            Some(camera) => reference.with_camera(Arc::clone(camera), decides),
            None => reference,
        }
    }
}

/// Loads the reference images (in parallel), their scenes' expectations and, with a
/// scene, its camera judge (the scene labelled through its camera and the catalogue's
/// mistaken ones, once per reference image).
///
/// # Errors
/// Bad input: a reference image that cannot be read or is not an image viewray reads; a
/// scene that does not exist or is not a valid scene file; a folder of scenes without the
/// scene of some reference image.
pub(crate) fn prepare(images: &[ReferenceImage], scene: Option<&Path>) -> Result<Vec<Prepared>> {
    let scenes = match scene {
        Some(scene) => scene_files(images, scene)?,
        None => vec![None; images.len()],
    };
    images
        .par_iter()
        .zip(&scenes)
        .map(|(image, scene)| {
            let pixels = load_image(&image.path)?;
            let (expectations, camera) = match scene {
                Some(path) => {
                    let scene = load_scene(path, pixels.width(), pixels.height())?;
                    let expectations = expectations(&scene);
                    let judge: Arc<dyn CameraJudge> = Arc::new(SceneJudge::new(scene, &pixels));
                    (expectations, Some(judge))
                }
                None => (None, None),
            };
            Ok(Prepared {
                image: image.clone(),
                pixels,
                expectations,
                camera,
            })
        })
        .collect()
}

/// Each reference image's scene: `scene` itself when it is a file, else the file of
/// `scene` (a folder) with the image's stem and the extension `.ron`.
///
/// # Errors
/// A scene that does not exist; a folder without the scene of some reference image.
fn scene_files(images: &[ReferenceImage], scene: &Path) -> Result<Vec<Option<PathBuf>>> {
    if !scene.exists() {
        bail!("SCENE `{}` does not exist", scene.display());
    }
    images
        .iter()
        .map(|image| {
            if !scene.is_dir() {
                return Ok(Some(scene.to_owned()));
            }
            let stem = Path::new(&image.name)
                .file_stem()
                .map_or_else(|| image.name.clone(), |s| s.to_string_lossy().into_owned());
            let path = scene.join(format!("{stem}.ron"));
            if !path.is_file() {
                bail!(
                    "no scene for {} in `{}` (looked for `{}`)",
                    image.name,
                    scene.display(),
                    path.display()
                );
            }
            Ok(Some(path))
        })
        .collect()
}

/// The scene at `path`, loaded for a reference of `width` x `height` (so that fields of
/// view in degrees follow its aspect ratio).
fn load_scene(path: &Path, width: u32, height: u32) -> Result<Scene> {
    let options = LoadOptions {
        size: Some((width, height)),
        samples: None,
    };
    Ok(SceneLoader::file(path).options(options).load()?.scene)
}

/// What a scene says camera mistakes look like: the principal point, the lens shift and
/// the kind of projection. `None` for a panoramic camera, whose mistakes are not
/// transforms of the picture.
fn expectations(scene: &Scene) -> Option<Expectations> {
    let projection = scene.camera().projection();
    let principal = projection.principal_point()?;
    let shift = match projection {
        Projection::Perspective(p) => p.shift,
        Projection::ThinLens(p) => p.shift,
        _ => glam::DVec2::ZERO,
    };
    Some(Expectations {
        principal_point: (principal.x, principal.y),
        shift: (shift.x, shift.y),
        camera: if projection.is_parallel() {
            CameraKind::Parallel
        } else {
            CameraKind::Perspective
        },
    })
}

/// One pair to judge: the reference and what the ACTUAL side holds for it.
struct Pair {
    reference: Prepared,
    counterpart: Counterpart,
}

/// What became of one pair.
struct Judged {
    name: String,
    expected: Option<RgbaImage>,
    actual: Option<RgbaImage>,
    outcome: Outcome,
}

/// 1 when a pair failed, else 0.
fn exit_code(tally: Tally) -> ExitCode {
    if tally.failed > 0 {
        ExitCode::from(EXIT_FAILED)
    } else {
        ExitCode::SUCCESS
    }
}

/// Runs `viewray compare`; prints its own errors and returns the exit code.
pub(crate) fn run(args: &CompareArgs) -> ExitCode {
    let decides = match deciding(args.judge, args.scene.as_deref()) {
        Ok(decides) => decides,
        Err(error) => return crate::failure(&error),
    };
    let planned = plan(args);
    let (pairs, extra) = match planned {
        Ok(planned) => planned,
        Err(error) => return crate::failure(&error),
    };
    match judge_all(args, decides, pairs, &extra) {
        Ok(tally) => exit_code(tally),
        Err(error) => crate::failure(&error),
    }
}

/// The pairs to judge and the ACTUAL folder's files that no reference image has: two
/// files, or a folder's reference images with what the other folder holds for each.
///
/// # Errors
/// Bad usage or input: a path that does not exist, a file against a folder, a folder that
/// cannot be read, an EXPECTED folder without PNG files, a reference image or a file given
/// directly that cannot be read, a bad scene.
fn plan(args: &CompareArgs) -> Result<(Vec<Pair>, Vec<String>)> {
    let (expected, actual) = (args.expected.as_path(), args.actual.as_path());
    for (role, path) in [("EXPECTED", expected), ("ACTUAL", actual)] {
        if !path.exists() {
            bail!("{role} `{}` does not exist", path.display());
        }
    }
    let scene = args.scene.as_deref();
    match (expected.is_dir(), actual.is_dir()) {
        (false, false) => {
            // Files given directly: either unreadable is bad input.
            load_image(actual)?;
            let mut reference = ReferenceImage::file(expected);
            reference.name = actual.file_name().map_or_else(
                || actual.display().to_string(),
                |n| n.to_string_lossy().into_owned(),
            );
            let references = prepare(&[reference], scene)?;
            let pairs = references
                .into_iter()
                .map(|reference| Pair {
                    reference,
                    counterpart: Counterpart::File(actual.to_owned()),
                })
                .collect();
            Ok((pairs, Vec::new()))
        }
        (true, true) => {
            let images = viewray_grade::reference_images(expected, "EXPECTED")?;
            let pairing = viewray_grade::pair(actual, &images)
                .with_context(|| format!("cannot read ACTUAL `{}`", actual.display()))?;
            let references = prepare(&images, scene)?;
            let pairs = references
                .into_iter()
                .zip(pairing.counterparts)
                .map(|(reference, counterpart)| Pair {
                    reference,
                    counterpart,
                })
                .collect();
            Ok((pairs, pairing.extra))
        }
        (true, false) => bail!(
            "EXPECTED `{}` is a folder but ACTUAL `{}` is a file: give two PNG files or two folders",
            expected.display(),
            actual.display()
        ),
        (false, true) => bail!(
            "EXPECTED `{}` is a file but ACTUAL `{}` is a folder: give two PNG files or two folders",
            expected.display(),
            actual.display()
        ),
    }
}

/// Judges every pair, printing a row (or a JSON line) as each is done, then the extra
/// files, the summary and, with `--report`, the report. Returns how the pairs fared.
fn judge_all(
    args: &CompareArgs,
    decides: Judge,
    pairs: Vec<Pair>,
    extra: &[String],
) -> Result<Tally> {
    let thresholds = thresholds(args.threshold);
    let name_width = pairs
        .iter()
        .map(|p| p.reference.image.name.chars().count())
        .max()
        .unwrap_or(0)
        .max(4);
    // The table's verdicts are coloured on a terminal (see `style`); JSON never is.
    let mut out = BufWriter::new(anstream::AutoStream::auto(std::io::stdout().lock()));
    let cameras = args.scene.is_some();
    if !args.json {
        writeln!(out, "{}", table_header(name_width, cameras))?;
        out.flush()?;
    }
    let keep_images = args.report.is_some();
    let mut results = Vec::new();
    let mut tally = Tally::default();
    in_order(
        &pairs,
        |pair| judge_pair(pair, thresholds, decides, keep_images),
        |judged| {
            tally.add(&judged.outcome);
            if args.json {
                let line = viewray_json::pair_line(&judged.name, &judged.outcome, args.threshold);
                viewray_json::write_line(&mut out, &line)?;
            } else {
                writeln!(
                    out,
                    "{}",
                    table_row(&judged.name, &judged.outcome, name_width, cameras)
                )?;
            }
            out.flush()?;
            results.push(judged);
            anyhow::Ok(())
        },
    )?;
    let summary_line = format!("{} (threshold {})", tally.summary(), args.threshold);
    if args.json {
        viewray_json::write_line(&mut out, &viewray_json::pairs_summary_line(&tally, extra))?;
    } else {
        if !extra.is_empty() {
            writeln!(
                out,
                "not judged, only in ACTUAL: {}",
                viewray_grade::listed(extra)
            )?;
        }
        writeln!(out, "{summary_line}")?;
    }
    out.flush()?;
    if let Some(directory) = &args.report {
        let entries: Vec<ReportEntry<'_>> = results
            .iter()
            .map(|r| ReportEntry::new(&r.name, r.expected.as_ref(), r.actual.as_ref(), &r.outcome))
            .collect();
        let title = format!(
            "viewray compare {} {}",
            args.expected.display(),
            args.actual.display()
        );
        let report = Report {
            title: &title,
            summary: &summary_line,
            rules: Rules::Instructor(thresholds),
            entries: &entries,
        };
        let page = write_report(directory, &report)
            .with_context(|| format!("cannot write the report into `{}`", directory.display()))?;
        eprintln!("report: {}", page.display());
    }
    Ok(tally)
}

/// Loads and judges one pair; a missing or unreadable render is the pair's failure.
fn judge_pair(
    pair: &Pair,
    thresholds: InstructorThresholds,
    decides: Judge,
    keep_images: bool,
) -> Judged {
    let reference = &pair.reference;
    let name = reference.image.name.clone();
    let (actual, outcome) = match load_counterpart(&pair.counterpart, &name) {
        Ok(actual) => {
            let comparison = reference.reference(thresholds, decides).judge(&actual);
            (Some(actual), Outcome::from(comparison))
        }
        Err(message) => (None, Outcome::Failed(message)),
    };
    Judged {
        name,
        expected: keep_images.then(|| reference.pixels.clone()),
        actual: actual.filter(|_| keep_images),
        outcome: if keep_images {
            outcome
        } else {
            outcome.without_error_map()
        },
    }
}

/// The table's header: with cameras judged (a scene given), the camera's and the
/// appearance's columns too.
fn table_header(name_width: usize, cameras: bool) -> String {
    if cameras {
        format!(
            "{:name_width$}  VERDICT  CAMERA    PEAK FLIP  APPEARANCE     DIAGNOSIS",
            "NAME"
        )
    } else {
        format!("{:name_width$}  VERDICT  PEAK FLIP  DIAGNOSIS", "NAME")
    }
}

/// A row of the table: name, verdict, (with `cameras`: the camera, `right`, `wrong` or
/// `unjudged`,) peak FLIP, (the appearance,) and the note.
pub(crate) fn table_row(name: &str, outcome: &Outcome, name_width: usize, cameras: bool) -> String {
    let peak = outcome
        .peak_flip()
        .map_or_else(|| "-".to_owned(), |p| format!("{p:.3}"));
    let verdict = outcome.verdict();
    let style = match verdict {
        Verdict::Pass => crate::style::PASS,
        Verdict::Fail | Verdict::Error => crate::style::FAIL,
    };
    let verdict = crate::style::padded(style, verdict.label(), 7);
    let row = if cameras {
        let camera = outcome.camera().map_or("-", |c| c.word());
        let appearance = outcome.appearance().map_or("-", |a| a.id());
        format!(
            "{name:name_width$}  {verdict}  {camera:8}  {peak:9}  {appearance:13}  {}",
            outcome.note()
        )
    } else {
        format!(
            "{name:name_width$}  {verdict}  {peak:9}  {}",
            outcome.note()
        )
    };
    row.trim_end().to_owned()
}
