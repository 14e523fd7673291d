//! `viewray check`: a student's numbers judged answer by answer, and the wrong ones
//! explained by the lecture's catalogue of mistakes (viewray-judge).

use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use clap::Args;
use viewray_judge::{CheckOptions, Checker, Report, read_answers};

use crate::commands::CONVENTIONS;
use crate::input::load_scene_file;
use crate::values::is_standard_stream;

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct CheckArgs {
    /// The scene file the answers are about (its camera and image size), or - for
    /// standard input.
    pub(crate) scene: PathBuf,
    /// What the student's program printed: a file, or - for standard input.
    pub(crate) answers: PathBuf,
    /// The answers' pixels are 1-based, the lecture's (i, j) (viewray's JSON lines with
    /// the keys "i" and "j" say so themselves).
    #[arg(long)]
    pub(crate) one_based: bool,
    /// How close a number must be: |found - expected| <= TOLERANCE x max(1, |expected|).
    #[arg(long, value_name = "TOLERANCE", default_value = "1e-6", value_parser = parse_tolerance)]
    pub(crate) tolerance: f64,
    /// Directions must be the right ones exactly, not only up to a positive factor (by
    /// default a normalized direction is right).
    #[arg(long)]
    pub(crate) exact_direction: bool,
    /// One JSON line per answer ({"line", "kind", "right", "expected", ...}) and a last
    /// line {"summary": {"answers", "right", "wrong", "index_hint", "diagnosis",
    /// "pattern"}}.
    #[arg(long)]
    pub(crate) json: bool,
}

/// A tolerance: a positive, finite number.
fn parse_tolerance(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(t) if t.is_finite() && t > 0.0 => Ok(t),
        _ => Err(format!(
            "expected a positive number such as 1e-6, found `{text}`"
        )),
    }
}

/// Runs `viewray check`: exit code 0 when every answer is right, 1 when any is wrong, 2
/// on bad input (the scene, or an answer that cannot be read, naming its line).
pub(crate) fn run(args: &CheckArgs) -> ExitCode {
    match check(args) {
        Ok(report) if report.passed() => ExitCode::SUCCESS,
        Ok(_) => ExitCode::from(1),
        Err(error) => crate::failure(&error),
    }
}

fn check(args: &CheckArgs) -> Result<Report> {
    if is_standard_stream(&args.scene) && is_standard_stream(&args.answers) {
        bail!("the scene and the answers cannot both come from standard input");
    }
    let camera = *load_scene_file(&args.scene)?.camera();
    let options = CheckOptions {
        one_based: args.one_based,
        tolerance: args.tolerance,
        exact_direction: args.exact_direction,
    };
    // A file is read twice, once to find bad input before anything is printed (bad input
    // prints nothing but its error); standard input can only be read once.
    if !is_standard_stream(&args.answers) {
        let mut checker = Checker::new(&camera, options);
        for item in read_answers(open(&args.answers)?) {
            let (line, answer) =
                item.map_err(|e| anyhow::anyhow!("{}: {e}", shown(&args.answers)))?;
            checker
                .check(line, &answer)
                .map_err(|e| anyhow::anyhow!("{}: {e}", shown(&args.answers)))?;
        }
    }
    let input: Box<dyn BufRead> = if is_standard_stream(&args.answers) {
        Box::new(std::io::stdin().lock())
    } else {
        Box::new(open(&args.answers)?)
    };
    let mut checker = Checker::new(&camera, options);
    let mut out = BufWriter::new(std::io::stdout().lock());
    for item in read_answers(input) {
        let (line, answer) = item.map_err(|e| anyhow::anyhow!("{}: {e}", shown(&args.answers)))?;
        let judged = checker
            .check(line, &answer)
            .map_err(|e| anyhow::anyhow!("{}: {e}", shown(&args.answers)))?;
        if args.json {
            viewray_json::write_line(&mut out, &viewray_json::checked_line(&judged))?;
        } else {
            writeln!(out, "{judged}")?;
        }
    }
    let report = checker.finish();
    if args.json {
        viewray_json::write_line(&mut out, &viewray_json::check_summary_line(&report))?;
    } else {
        writeln!(out, "\n{report}")?;
    }
    out.flush()?;
    Ok(report)
}

fn open(path: &Path) -> Result<BufReader<File>> {
    let file =
        File::open(path).with_context(|| format!("{}: cannot read the answers", path.display()))?;
    Ok(BufReader::new(file))
}

/// How the answers' source is named in an error.
fn shown(path: &Path) -> String {
    if is_standard_stream(path) {
        "standard input".to_owned()
    } else {
        path.display().to_string()
    }
}
