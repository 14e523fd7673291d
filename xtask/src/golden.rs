//! `cargo xtask golden`: every projection family rendered and compared with its committed
//! golden image.
//!
//! Each scene `fixtures/scenes/<name>.ron` (and `viewray render`'s built-in
//! `fixtures/default.ron`, as `default`) is rendered in-process and compared with
//! `golden/scenes/<name>.png`, each lecture figure with `golden/figures/<name>.png`, and
//! the first, middle and last frames of each built-in animation with
//! `golden/animations/<demo>_{first,middle,last}.png`, and each entry of the lecture's
//! catalogue of mistakes (viewray-camera's `Mistake`, but the one whose picture is one
//! colour) rendered through the mistaken camera of its family's scene with
//! `golden/mistakes/<id>.png` (the pictures of
//! docs/mistakes.md, beside the right ones, `golden/mistakes/right-<family>.png`),
//! by decoded pixels, never by PNG bytes, through
//! viewray-compare's golden gates ([`Thresholds::GOLDEN`]): a per-pixel gate that absorbs
//! last-bit floating-point differences between machines, and a perceptual (FLIP) gate that
//! catches a one-pixel edge shift or a colour change a person would notice. A missing
//! golden, a golden without a scene, and a blank golden each fail.
//!
//! On failure `target/golden/index.html` shows expected, actual and a FLIP heatmap for each
//! failing image, and the console prints the command that accepts the new images.
//! `--bless` rewrites exactly the goldens whose pixels changed, adds missing ones and
//! removes orphans; it refuses to run under CI.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use viewray_camera::{Mistake, Mistakes};
use viewray_compare::{Comparison, Outcome, Report, ReportEntry, RgbaImage, Rules, Thresholds};
use viewray_output::Compression;
use viewray_render::RenderSettings;
use viewray_scene::LoadOptions;

/// The command line of `cargo xtask golden`.
#[derive(Debug, Default, clap::Args)]
pub struct GoldenArgs {
    /// Only the images whose `scenes/<name>`, `figures/<name>` or `animations/<name>`
    /// contains FILTER.
    pub filter: Option<String>,
    /// Rewrite the goldens whose pixels changed, add missing ones and remove those with
    /// no scene or figure (refused when CI is set).
    #[arg(long)]
    pub bless: bool,
}

impl GoldenArgs {
    fn selects(&self, id: &str) -> bool {
        self.filter.as_deref().is_none_or(|f| id.contains(f))
    }
}

/// One image the check covers: where its golden lives and how to make the actual one.
pub struct Case {
    id: String,
    golden: PathBuf,
    source: Source,
}

impl Case {
    /// `scenes/<name>` or `figures/<name>`: the report's, the console's and the filters'
    /// name for it.
    pub fn id(&self) -> &str {
        &self.id
    }

    /// Makes the image and compares it with its golden.
    pub fn check(&self) -> Verdict {
        check(self)
    }
}

enum Source {
    /// A scene file, rendered with these overrides.
    Scene(PathBuf, LoadOptions),
    /// A lecture figure by name, drawn at [`FIGURE_SCALE`].
    Figure(&'static str),
    /// A frame of a built-in animation, as [`ANIMATION_FRAMES`] renders it.
    Animation(&'static str, u32),
    /// A scene file's picture (at [`MISTAKE_SIZE`]) through its camera with one entry of
    /// the lecture's catalogue of mistakes, or through the right camera.
    Mistake(PathBuf, Option<Mistake>),
}

/// The pictures of the lecture's mistakes (docs/mistakes.md) are small: enough to see
/// what each does to the picture.
const MISTAKE_SIZE: (u32, u32) = (160, 120);

/// The scene each entry of the catalogue is shown on: its camera's family (a general
/// perspective camera with d != 1 and a shift, an orthographic one, an oblique one; the
/// first and the last in `fixtures/mistakes/`).
fn mistake_scene(mistake: Option<Mistake>) -> &'static str {
    match mistake {
        Some(Mistake::OrthoOriginFixed | Mistake::OrthoAsPerspective) => {
            "fixtures/scenes/orthographic.ron"
        }
        Some(Mistake::ObliqueSign | Mistake::ObliqueAsOrtho) => "fixtures/mistakes/oblique.ron",
        _ => "fixtures/mistakes/perspective.ron",
    }
}

/// The right pictures the mistakes' pictures are shown beside, with their golden names.
const RIGHT_PICTURES: [(&str, Option<Mistake>); 3] = [
    ("right-perspective", None),
    ("right-orthographic", Some(Mistake::OrthoOriginFixed)),
    ("right-oblique", Some(Mistake::ObliqueSign)),
];

/// Animations are checked by their first, middle and last frames of the demo's own
/// count, each picture at 320 x 180 with its side view beside it (so the diagram is
/// checked too), at the demo's own samples per pixel.
const ANIMATION_SIZE: (u32, u32) = (320, 180);

/// Which frames of an animation of `frames` the check covers, with their names.
fn animation_frames(frames: u32) -> [(&'static str, u32); 3] {
    [("first", 0), ("middle", frames / 2), ("last", frames - 1)]
}

/// The movie whose frames the golden check compares.
fn animation_movie(demo: &str) -> Result<viewray_animation::Movie> {
    let demo = viewray_animation::demo_by_name(demo)?;
    let options = LoadOptions {
        size: Some(ANIMATION_SIZE),
        samples: None,
    };
    let settings = viewray_animation::MovieSettings {
        with_diagram: true,
        ..viewray_animation::MovieSettings::default()
    };
    Ok(viewray_animation::Movie::from_demo(
        &demo, options, settings,
    )?)
}

/// Figures are checked at half their slide size: every item and label is still drawn
/// (a moved label or line still shows), and the goldens stay tens of KiB.
const FIGURE_SCALE: f32 = 0.5;

/// `viewray render`'s built-in scene; its golden is rendered at half its 640 x 480 so the
/// committed PNG stays small.
const DEFAULT_SCENE: &str = "fixtures/default.ron";

/// An image a case made, in the form its golden PNG stores and the form it is encoded
/// from.
pub struct Made {
    pixels: RgbaImage,
    output: Output,
}

enum Output {
    Render(viewray_render::Image),
    Figure(RgbaImage),
}

impl Output {
    /// The PNG file, by viewray's one encoder: a scene as `viewray render` writes it, a
    /// figure as opaque RGB compressed hard, to keep goldens small.
    fn png(&self) -> Result<Vec<u8>> {
        let mut png = Vec::new();
        match self {
            Output::Render(image) => image.write_png(&mut png)?,
            Output::Figure(pixels) => {
                let rgb = image::DynamicImage::ImageRgba8(pixels.clone()).to_rgb8();
                viewray_output::write_png(&mut png, &rgb, Compression::Smallest)?;
            }
        }
        Ok(png)
    }
}

/// What became of one case.
pub enum Verdict {
    /// Pixel for pixel the golden.
    Same,
    /// Within the tolerances, but not identical.
    Passed(Made, Comparison),
    /// Beyond the tolerances, or nothing to compare (no golden yet, an image that could
    /// not be made).
    Failed {
        /// The image made, if it could be.
        made: Option<Made>,
        /// The golden, if it could be read.
        expected: Option<RgbaImage>,
        /// The comparison, if there were two images to compare.
        comparison: Option<Comparison>,
        /// Why it failed, in one line.
        reason: String,
    },
}

/// Runs the golden check (or, with `--bless`, updates the goldens).
///
/// # Errors
/// When an image differs from its golden (after writing the report), a golden has no
/// scene, the filter selects nothing, or a file cannot be read or written.
pub fn golden(root: &Path, args: &GoldenArgs) -> Result<()> {
    if args.bless && std::env::var_os("CI").is_some_and(|v| !v.is_empty() && v != "false") {
        bail!("--bless refuses to run under CI: goldens are blessed on purpose, by a person");
    }
    let (cases, orphans) = cases(root, args)?;
    if cases.is_empty() && orphans.is_empty() {
        bail!(
            "no golden case matches `{}`",
            args.filter.as_deref().unwrap_or_default()
        );
    }
    let started = Instant::now();
    let mut failures: Vec<(String, Verdict)> = Vec::new();
    let mut blessed = 0;
    for case in &cases {
        let case_started = Instant::now();
        let verdict = check(case);
        let ms = case_started.elapsed().as_millis();
        match &verdict {
            Verdict::Same => eprintln!("  ok    {:<40} identical {ms:>6} ms", case.id),
            Verdict::Passed(_, c) => {
                eprintln!("  ok    {:<40} {} {ms:>6} ms", case.id, figures(c));
            }
            // As the report says: ERROR when there was nothing to compare.
            Verdict::Failed {
                reason,
                comparison: None,
                ..
            } => eprintln!("  ERROR {:<40} {reason}", case.id),
            Verdict::Failed { reason, .. } => eprintln!("  FAIL  {:<40} {reason}", case.id),
        }
        match verdict {
            Verdict::Same => {}
            Verdict::Passed(made, _)
            | Verdict::Failed {
                made: Some(made), ..
            } if args.bless => {
                write_golden(root, &case.golden, &made.output)?;
                blessed += 1;
            }
            Verdict::Failed {
                made: None, reason, ..
            } if args.bless => {
                bail!(
                    "{}: cannot bless, the image could not be made: {reason}",
                    case.id
                );
            }
            Verdict::Passed(..) => {}
            failed @ Verdict::Failed { .. } => failures.push((case.id.clone(), failed)),
        }
    }
    for orphan in &orphans {
        if args.bless {
            std::fs::remove_file(orphan)
                .with_context(|| format!("cannot remove {}", orphan.display()))?;
            eprintln!("  removed {} (no scene renders it)", relative(root, orphan));
            blessed += 1;
        } else {
            eprintln!("  FAIL  {}: a golden with no scene", relative(root, orphan));
        }
    }
    let total = cases.len();
    let elapsed = started.elapsed().as_secs_f64();
    if args.bless {
        eprintln!(
            "golden: {total} images checked in {elapsed:.1} s, {blessed} goldens written or removed"
        );
        return Ok(());
    }
    if failures.is_empty() && orphans.is_empty() {
        eprintln!("golden: all {total} images match their goldens ({elapsed:.1} s)");
        return Ok(());
    }
    let summary = failure_summary(failures.len(), orphans.len(), total);
    let report = write_failure_report(root, &failures, &summary)?;
    let filter = args
        .filter
        .as_deref()
        .map(|f| format!(" {f}"))
        .unwrap_or_default();
    bail!(
        "{summary} ({elapsed:.1} s)\n  report: {}\n  if the change is intended, look at each \
         image, then run: cargo xtask golden{filter} --bless",
        relative(root, &report),
    )
}

/// The line that sums up a failed check, on the console and atop the report.
pub fn failure_summary(failed: usize, orphans: usize, total: usize) -> String {
    format!("{failed} of {total} golden images differ and {orphans} goldens have no scene")
}

/// The cases the filter selects, and the goldens that no case produces (orphans).
///
/// # Errors
/// When a folder of scenes or goldens cannot be listed.
pub fn cases(root: &Path, args: &GoldenArgs) -> Result<(Vec<Case>, Vec<PathBuf>)> {
    let mut cases = vec![Case {
        id: "scenes/default".to_owned(),
        golden: root.join("golden/scenes/default.png"),
        source: Source::Scene(
            root.join(DEFAULT_SCENE),
            LoadOptions {
                size: Some((320, 240)),
                samples: None,
            },
        ),
    }];
    for scene in files_with_extension(&root.join("fixtures/scenes"), "ron")? {
        let name = stem(&scene);
        cases.push(Case {
            id: format!("scenes/{name}"),
            golden: root.join("golden/scenes").join(format!("{name}.png")),
            source: Source::Scene(scene, LoadOptions::default()),
        });
    }
    for figure in viewray_diagram::all_figures() {
        cases.push(Case {
            id: format!("figures/{}", figure.name),
            golden: root
                .join("golden/figures")
                .join(format!("{}.png", figure.name)),
            source: Source::Figure(figure.name),
        });
    }
    for demo in viewray_animation::all_demos() {
        for (which, frame) in animation_frames(demo.frames) {
            let name = format!("{}_{which}", demo.name);
            cases.push(Case {
                id: format!("animations/{name}"),
                golden: root.join("golden/animations").join(format!("{name}.png")),
                source: Source::Animation(demo.name, frame),
            });
        }
    }
    // `ortho-origin-fixed` makes a picture of one colour, which no golden may be.
    for mistake in Mistake::ALL
        .into_iter()
        .filter(|&m| m != Mistake::OrthoOriginFixed)
    {
        let id = mistake.id();
        cases.push(Case {
            id: format!("mistakes/{id}"),
            golden: root.join("golden/mistakes").join(format!("{id}.png")),
            source: Source::Mistake(root.join(mistake_scene(Some(mistake))), Some(mistake)),
        });
    }
    for (name, family) in RIGHT_PICTURES {
        cases.push(Case {
            id: format!("mistakes/{name}"),
            golden: root.join("golden/mistakes").join(format!("{name}.png")),
            source: Source::Mistake(root.join(mistake_scene(family)), None),
        });
    }
    let produced: Vec<&Path> = cases.iter().map(|c| c.golden.as_path()).collect();
    let mut orphans = Vec::new();
    for kind in ["scenes", "figures", "animations", "mistakes"] {
        let dir = root.join("golden").join(kind);
        if !dir.exists() {
            continue;
        }
        for golden in files_with_extension(&dir, "png")? {
            if !produced.contains(&golden.as_path()) {
                orphans.push(golden);
            }
        }
    }
    cases.retain(|c| args.selects(&c.id));
    orphans.retain(|o| args.selects(&relative(root, o).replace("golden/", "")));
    Ok((cases, orphans))
}

/// Makes the case's image and compares it with its golden.
fn check(case: &Case) -> Verdict {
    let made = match make(case) {
        Ok(made) => made,
        Err(error) => {
            return Verdict::Failed {
                made: None,
                expected: None,
                comparison: None,
                reason: format!("{error:#}"),
            };
        }
    };
    let expected = if case.golden.exists() {
        viewray_compare::load_png(&case.golden).map_err(|e| e.to_string())
    } else {
        Err("no golden image yet".to_owned())
    };
    let expected = match expected {
        Ok(expected) => expected,
        Err(reason) => {
            return Verdict::Failed {
                made: Some(made),
                expected: None,
                comparison: None,
                reason,
            };
        }
    };
    if expected == made.pixels {
        return Verdict::Same;
    }
    let comparison = viewray_compare::compare(&expected, &made.pixels, &Thresholds::GOLDEN);
    if comparison.passed() {
        Verdict::Passed(made, comparison)
    } else {
        Verdict::Failed {
            reason: comparison.reasons(),
            made: Some(made),
            expected: Some(expected),
            comparison: Some(comparison),
        }
    }
}

/// The image a case produces.
fn make(case: &Case) -> Result<Made> {
    match &case.source {
        Source::Scene(path, options) => {
            let scene = viewray_scene::SceneLoader::file(path)
                .options(*options)
                .load()?
                .scene;
            let rendered = viewray_render::render(&scene, &RenderSettings::default(), |_, _| {})?;
            let image = rendered.image;
            Ok(Made {
                pixels: image::DynamicImage::ImageRgb8(image.to_rgb_image()).to_rgba8(),
                output: Output::Render(image),
            })
        }
        Source::Mistake(path, mistake) => {
            let options = LoadOptions {
                size: Some(MISTAKE_SIZE),
                samples: None,
            };
            let scene = viewray_scene::SceneLoader::file(path)
                .options(options)
                .load()?
                .scene;
            let camera = match mistake {
                Some(mistake) => scene.camera().with_mistakes(Mistakes::one(*mistake))?,
                None => *scene.camera(),
            };
            let view = viewray_render::View {
                camera,
                ..viewray_render::View::of(&scene)
            };
            let rendered =
                viewray_render::render_view(&scene, &view, &RenderSettings::default(), |_, _| {})?;
            let image = rendered.image;
            Ok(Made {
                pixels: image::DynamicImage::ImageRgb8(image.to_rgb_image()).to_rgba8(),
                output: Output::Render(image),
            })
        }
        Source::Figure(name) => {
            let figure = viewray_diagram::figure_by_name(name)
                .with_context(|| format!("no figure named {name}"))?;
            let pixels = viewray_draw::raster::render_scaled(&figure.figure(), FIGURE_SCALE);
            Ok(Made {
                pixels: pixels.clone(),
                output: Output::Figure(pixels),
            })
        }
        Source::Animation(demo, frame) => {
            let movie = animation_movie(demo)?;
            let rgb = movie.render_frame(*frame, &RenderSettings::default())?;
            let pixels = image::DynamicImage::ImageRgb8(rgb).to_rgba8();
            Ok(Made {
                pixels: pixels.clone(),
                output: Output::Figure(pixels),
            })
        }
    }
}

/// Writes `golden` from `output`, through a temporary file renamed into place.
fn write_golden(root: &Path, golden: &Path, output: &Output) -> Result<()> {
    let png = output.png()?;
    crate::write_atomically(golden, &png)?;
    eprintln!(
        "        wrote {} ({} KiB)",
        relative(root, golden),
        png.len() / 1024
    );
    Ok(())
}

/// Writes the failures' report to `target/golden/index.html` (clearing the last one),
/// headed by the same `summary` the console prints; returns the page's path.
///
/// # Errors
/// When the report cannot be written.
pub fn write_failure_report(
    root: &Path,
    failures: &[(String, Verdict)],
    summary: &str,
) -> Result<PathBuf> {
    // Each failure's images and outcome, then the entries that show them.
    let shown: Vec<(&str, Option<&RgbaImage>, Option<&RgbaImage>, Outcome)> = failures
        .iter()
        .filter_map(|(id, verdict)| match verdict {
            Verdict::Failed {
                made,
                expected,
                comparison: Some(comparison),
                ..
            } => Some((
                id.as_str(),
                Some(expected.as_ref()?),
                Some(&made.as_ref()?.pixels),
                Outcome::from(comparison.clone()),
            )),
            Verdict::Failed {
                made,
                expected,
                reason,
                ..
            } => Some((
                id.as_str(),
                expected.as_ref(),
                made.as_ref().map(|m| &m.pixels),
                Outcome::Error(reason.clone()),
            )),
            _ => None,
        })
        .collect();
    let entries: Vec<ReportEntry<'_>> = shown
        .iter()
        .map(|(id, expected, made, outcome)| ReportEntry::new(id, *expected, *made, outcome))
        .collect();
    let dir = crate::target_dir(root)?.join("golden");
    // A report shows this run only: clear the images a previous run left.
    if dir.exists() {
        std::fs::remove_dir_all(&dir)
            .with_context(|| format!("cannot clear the old report in {}", dir.display()))?;
    }
    let report = Report {
        title: "viewray golden images: the failures",
        summary,
        rules: Rules::Golden(Thresholds::GOLDEN),
        entries: &entries,
    };
    viewray_compare::write_report(&dir, &report)
        .with_context(|| format!("cannot write the report in {}", dir.display()))
}

fn figures(c: &Comparison) -> String {
    match &c.metrics {
        Some(m) => format!(
            "mean FLIP {:.4}, peak {:.4}, {} px over tolerance",
            m.mean_flip, m.peak_flip, m.bad_pixels
        ),
        None => String::new(),
    }
}

fn files_with_extension(dir: &Path, extension: &str) -> Result<Vec<PathBuf>> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .with_context(|| format!("cannot list {}", dir.display()))?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| path.extension().is_some_and(|e| e == extension))
        .collect();
    files.sort();
    Ok(files)
}

fn stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// `path` relative to `root`, for messages.
pub fn relative(root: &Path, path: &Path) -> String {
    path.strip_prefix(root)
        .unwrap_or(path)
        .display()
        .to_string()
}
