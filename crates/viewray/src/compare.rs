//! `viewray compare`: judge renders against reference images as an instructor would.
//!
//! Output: a table on stdout, one row per pair as it is judged, then a summary line; with
//! `--json`, JSON lines instead: one object per pair, then one `{"summary":{..}}` object.

use std::collections::{BTreeSet, HashMap};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use clap::Args;
use serde_json::{Value, json};
use viewray_camera::Projection;
use viewray_compare::{
    CameraKind, Comparison, Diagnosis, Expectations, InstructorThresholds, Report, ReportEntry,
    RgbaImage, Rules, Verdict, judge_with, load_png, write_report,
};
use viewray_scene::{LoadOptions, Scene};

use crate::EXIT_BAD_INPUT;

/// Exit code when a comparison failed.
const EXIT_FAILED: u8 = 1;

#[derive(Args, Debug)]
pub(crate) struct CompareArgs {
    /// The reference: a PNG file, or a folder of PNG files.
    pub(crate) expected: PathBuf,
    /// The render(s) to judge: a PNG file, or a folder whose *.png files are paired with
    /// EXPECTED's by file name.
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
}

fn parse_threshold(text: &str) -> Result<f32, String> {
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

/// One pair to judge: a name and the two files (`None` when one side lacks it), and the
/// reference's scene file when `--scene` names one.
struct Pair {
    name: String,
    expected: Option<PathBuf>,
    actual: Option<PathBuf>,
    scene: Option<PathBuf>,
}

/// What became of one pair.
struct Judged {
    name: String,
    expected: Option<RgbaImage>,
    actual: Option<RgbaImage>,
    outcome: Result<Comparison, String>,
}

/// How the pairs fared: `passed + failed + errors` is the number of pairs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct Tally {
    passed: usize,
    /// Compared, and judged different.
    failed: usize,
    /// Not compared: a side missing, unreadable or not a PNG.
    errors: usize,
}

impl Tally {
    fn of(results: &[Judged]) -> Self {
        let mut tally = Self::default();
        for judged in results {
            match &judged.outcome {
                Ok(c) if c.passed() => tally.passed += 1,
                Ok(_) => tally.failed += 1,
                Err(_) => tally.errors += 1,
            }
        }
        tally
    }

    /// 2 when a pair could not be compared (bad input), else 1 when one failed, else 0.
    fn exit_code(self) -> ExitCode {
        if self.errors > 0 {
            ExitCode::from(EXIT_BAD_INPUT)
        } else if self.failed > 0 {
            ExitCode::from(EXIT_FAILED)
        } else {
            ExitCode::SUCCESS
        }
    }

    /// The summary line, e.g. `6 images: 1 passed, 3 failed, 2 could not be compared`.
    fn summary(self) -> String {
        let total = self.passed + self.failed + self.errors;
        let noun = if total == 1 { "image" } else { "images" };
        let mut line = format!(
            "{total} {noun}: {} passed, {} failed",
            self.passed, self.failed
        );
        if self.errors > 0 {
            line.push_str(&format!(", {} could not be compared", self.errors));
        }
        line
    }
}

/// Runs `viewray compare`; prints its own errors and returns the exit code.
pub(crate) fn run(args: &CompareArgs) -> ExitCode {
    let pairs = pairs(&args.expected, &args.actual).and_then(|mut pairs| {
        if let Some(scene) = &args.scene {
            assign_scenes(&mut pairs, scene)?;
        }
        Ok(pairs)
    });
    let pairs = match pairs {
        Ok(pairs) => pairs,
        Err(error) => return crate::failure(&error),
    };
    match judge_all(args, &pairs) {
        Ok(tally) => tally.exit_code(),
        Err(error) => crate::failure(&error),
    }
}

/// The pairs to judge: two files, or the union of two folders' *.png names.
///
/// # Errors
/// Bad usage: a path that does not exist, a file against a folder, an unreadable folder,
/// two folders without a single PNG.
fn pairs(expected: &Path, actual: &Path) -> Result<Vec<Pair>> {
    for (role, path) in [("EXPECTED", expected), ("ACTUAL", actual)] {
        if !path.exists() {
            bail!("{role} `{}` does not exist", path.display());
        }
    }
    match (expected.is_dir(), actual.is_dir()) {
        (false, false) => {
            let name = actual.file_name().map_or_else(
                || actual.display().to_string(),
                |n| n.to_string_lossy().into_owned(),
            );
            Ok(vec![Pair {
                name,
                expected: Some(expected.to_owned()),
                actual: Some(actual.to_owned()),
                scene: None,
            }])
        }
        (true, true) => {
            let expected_names = png_names(expected)?;
            let actual_names = png_names(actual)?;
            if expected_names.is_empty() && actual_names.is_empty() {
                bail!(
                    "no *.png files in `{}` or `{}`",
                    expected.display(),
                    actual.display()
                );
            }
            Ok(expected_names
                .union(&actual_names)
                .map(|name| Pair {
                    name: name.clone(),
                    expected: expected_names.contains(name).then(|| expected.join(name)),
                    actual: actual_names.contains(name).then(|| actual.join(name)),
                    scene: None,
                })
                .collect())
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

/// Gives each pair with a reference image its scene: `scene` itself when it is a file,
/// else the file of `scene` (a folder) with the image's stem and the extension `.ron`.
/// Every scene is loaded once here, so that a bad one is bad input before anything is
/// judged.
///
/// # Errors
/// A scene that does not exist or is not a valid scene file; a folder without the scene
/// of some reference image.
fn assign_scenes(pairs: &mut [Pair], scene: &Path) -> Result<()> {
    if !scene.exists() {
        bail!("SCENE `{}` does not exist", scene.display());
    }
    let mut checked = BTreeSet::new();
    for pair in pairs.iter_mut().filter(|p| p.expected.is_some()) {
        let path = if scene.is_dir() {
            let stem = Path::new(&pair.name)
                .file_stem()
                .map_or_else(|| pair.name.clone(), |s| s.to_string_lossy().into_owned());
            let path = scene.join(format!("{stem}.ron"));
            if !path.is_file() {
                bail!(
                    "no scene for {} in `{}` (looked for `{}`)",
                    pair.name,
                    scene.display(),
                    path.display()
                );
            }
            path
        } else {
            scene.to_owned()
        };
        if checked.insert(path.clone()) {
            Scene::load(&path)?;
        }
        pair.scene = Some(path);
    }
    Ok(())
}

/// What a scene says camera mistakes look like, for a reference of `width` x `height`
/// (the scene is loaded at that size, so that fields of view in degrees follow its
/// aspect ratio): the principal point, the lens shift and the kind of projection.
/// `None` for a panoramic camera, whose mistakes are not transforms of the picture.
fn expectations(path: &Path, width: u32, height: u32) -> Result<Option<Expectations>> {
    let options = LoadOptions {
        size: Some((width, height)),
        samples: None,
    };
    let scene = Scene::load_with(path, options)?;
    // The principal point, where u + sx = 0 and v + sy = 0: x = W (1/2 - sx/vw),
    // y = H (1/2 + sy/vh).
    let perspective = |viewport: glam::DVec2, shift: glam::DVec2| Expectations {
        principal_point: (0.5 - shift.x / viewport.x, 0.5 + shift.y / viewport.y),
        shift: (shift.x, shift.y),
        camera: CameraKind::Perspective,
    };
    Ok(match scene.camera().projection() {
        Projection::Perspective(p) => Some(perspective(p.viewport, p.shift)),
        Projection::ThinLens(p) => Some(perspective(p.viewport, p.shift)),
        Projection::Orthographic(_) | Projection::Oblique(_) => Some(Expectations {
            principal_point: (0.5, 0.5),
            shift: (0.0, 0.0),
            camera: CameraKind::Parallel,
        }),
        Projection::Equirectangular | Projection::Fisheye(_) => None,
    })
}

/// The names of the files in `folder` ending in `.png` (any case), sorted.
fn png_names(folder: &Path) -> Result<BTreeSet<String>> {
    let mut names = BTreeSet::new();
    let entries = std::fs::read_dir(folder)
        .with_context(|| format!("cannot read the folder `{}`", folder.display()))?;
    for entry in entries {
        let entry =
            entry.with_context(|| format!("cannot read the folder `{}`", folder.display()))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let is_png = Path::new(&name)
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("png"));
        if is_png && !entry.path().is_dir() {
            names.insert(name);
        }
    }
    Ok(names)
}

/// Judges every pair, printing a row (or a JSON line) as each is done, then the summary
/// and, with `--report`, the report. Returns how the pairs fared.
fn judge_all(args: &CompareArgs, pairs: &[Pair]) -> Result<Tally> {
    let thresholds = InstructorThresholds {
        max_peak_flip: args.threshold,
        ..InstructorThresholds::default()
    };
    let name_width = pairs
        .iter()
        .map(|p| p.name.chars().count())
        .max()
        .unwrap_or(0)
        .max(4);
    // The table's verdicts are coloured on a terminal (see `style`); JSON never is.
    let mut out = BufWriter::new(anstream::AutoStream::auto(std::io::stdout().lock()));
    if !args.json {
        writeln!(out, "{:name_width$}  VERDICT  PEAK FLIP  DIAGNOSIS", "NAME")?;
        out.flush()?;
    }
    let mut results = Vec::new();
    let mut scenes = HashMap::new();
    for pair in pairs {
        let judged = judge_pair(pair, &thresholds, &mut scenes);
        if args.json {
            viewray_json::write_line(&mut out, &json_line(&judged, args.threshold))?;
        } else {
            writeln!(out, "{}", table_row(&judged, name_width))?;
        }
        out.flush()?;
        // Keep the images only for the report.
        results.push(if args.report.is_some() {
            judged
        } else {
            Judged {
                expected: None,
                actual: None,
                ..judged
            }
        });
    }
    let tally = Tally::of(&results);
    let summary_line = format!("{} (threshold {})", tally.summary(), args.threshold);
    if args.json {
        let summary = json!({"summary": {
            "total": results.len(),
            "passed": tally.passed,
            "failed": tally.failed,
            "errors": tally.errors,
        }});
        viewray_json::write_line(&mut out, &summary)?;
    } else {
        writeln!(out, "{summary_line}")?;
    }
    out.flush()?;
    if let Some(directory) = &args.report {
        let entries: Vec<ReportEntry<'_>> = results
            .iter()
            .map(|r| match &r.outcome {
                Ok(comparison) => ReportEntry {
                    name: &r.name,
                    expected: r.expected.as_ref(),
                    actual: r.actual.as_ref(),
                    outcome: viewray_compare::Outcome::Compared(comparison),
                },
                Err(message) => {
                    ReportEntry::error(&r.name, message, r.expected.as_ref(), r.actual.as_ref())
                }
            })
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

/// The expectations of the scenes already loaded, by scene file and image size.
type Scenes = HashMap<(PathBuf, (u32, u32)), Option<Expectations>>;

/// Loads and judges one pair; a missing side or an unreadable file is the pair's error.
fn judge_pair(pair: &Pair, thresholds: &InstructorThresholds, scenes: &mut Scenes) -> Judged {
    let mut errors = Vec::new();
    let mut load = |path: &Option<PathBuf>| match path.as_ref().map(load_png).transpose() {
        Ok(image) => image,
        Err(error) => {
            errors.push(error.to_string());
            None
        }
    };
    let expected = load(&pair.expected);
    let actual = load(&pair.actual);
    let outcome = match (&expected, &actual) {
        _ if !errors.is_empty() => Err(errors.join("; ")),
        (Some(e), Some(a)) => match &pair.scene {
            None => Ok(judge_with(e, a, thresholds, None)),
            Some(path) => {
                let key = (path.clone(), e.dimensions());
                let known = match scenes.get(&key) {
                    Some(known) => Ok(*known),
                    None => expectations(path, e.width(), e.height())
                        .inspect(|known| {
                            scenes.insert(key, *known);
                        })
                        .map_err(|error| format!("{error:#}")),
                };
                known.map(|known| judge_with(e, a, thresholds, known.as_ref()))
            }
        },
        (Some(_), None) => Err(format!("only in EXPECTED: ACTUAL has no {}", pair.name)),
        (None, _) => Err(format!("only in ACTUAL: EXPECTED has no {}", pair.name)),
    };
    Judged {
        name: pair.name.clone(),
        expected,
        actual,
        outcome,
    }
}

/// The verdict, as the report states it too: `error` for a pair that could not be
/// compared.
fn verdict(judged: &Judged) -> Verdict {
    match &judged.outcome {
        Ok(c) if c.passed() => Verdict::Pass,
        Ok(_) => Verdict::Fail,
        Err(_) => Verdict::Error,
    }
}

/// The last column: the diagnosis, else why it failed, else nothing.
fn note(judged: &Judged) -> String {
    match &judged.outcome {
        Ok(c) => match c.diagnosis {
            Some(d) => d.to_string(),
            None => c.reasons(),
        },
        Err(message) => message.clone(),
    }
}

fn table_row(judged: &Judged, name_width: usize) -> String {
    let peak = match &judged.outcome {
        Ok(Comparison {
            metrics: Some(m), ..
        }) => format!("{:.3}", m.peak_flip),
        _ => "-".to_owned(),
    };
    let style = match verdict(judged) {
        Verdict::Pass => crate::style::PASS,
        Verdict::Fail => crate::style::FAIL,
        Verdict::Error => crate::style::BROKEN,
    };
    let row = format!(
        "{:name_width$}  {}  {peak:9}  {}",
        judged.name,
        crate::style::padded(style, verdict(judged).label(), 7),
        note(judged)
    );
    row.trim_end().to_owned()
}

/// A FLIP figure for JSON, rounded to 4 decimals.
fn figure(value: f32) -> Value {
    json!((f64::from(value) * 1e4).round() / 1e4)
}

fn json_line(judged: &Judged, threshold: f32) -> Value {
    let (metrics, diagnosis, reasons) = match &judged.outcome {
        Ok(c) => (
            c.metrics,
            c.diagnosis,
            c.failures.iter().map(ToString::to_string).collect(),
        ),
        Err(_) => (None, None, Vec::new()),
    };
    json!({
        "name": judged.name,
        "verdict": verdict(judged).word(),
        "peak_flip": metrics.map_or(Value::Null, |m| figure(m.peak_flip)),
        "mean_flip": metrics.map_or(Value::Null, |m| figure(m.mean_flip)),
        "threshold": figure(threshold),
        "diagnosis": diagnosis.map_or(Value::Null, |d| json!(d.messages())),
        "transform": diagnosis.as_ref().and_then(Diagnosis::camera_mistake).map_or(Value::Null, |m| json!({
            "mirrored_left_right": m.mirrored_left_right,
            "upside_down": m.upside_down,
            "rotation": figure(m.rotation as f32),
            "scale": [figure(m.scale.0 as f32), figure(m.scale.1 as f32)],
            "about": [figure(m.about.0 as f32), figure(m.about.1 as f32)],
            "shift": [figure(m.shift.0 as f32), figure(m.shift.1 as f32)],
        })),
        "reasons": reasons,
        "error": match &judged.outcome {
            Err(message) => json!(message),
            Ok(_) => Value::Null,
        },
    })
}
