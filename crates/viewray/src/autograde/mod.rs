//! `viewray autograde`: one student's submission graded on an assignment file, the
//! results written in an autograding platform's format (viewray-autograde); and
//! `viewray autograde kit`, what a platform takes to run it (module `kit`).
//!
//! Output: the results file (always, even when the assignment or the submission is
//! broken: then it says why), and on stdout one line per test as a student may see it
//! now (a test's details that wait for the due date, or are hidden, are not printed: on
//! GitHub Classroom the student reads this log). Exit code 0 when every test passed, 1
//! when some failed, 2 when nothing could be graded (the results file says why; an
//! `error:` line too) or the results file cannot be written.

mod kit;

use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Args, Subcommand, ValueEnum};
use viewray_autograde::{Format, Options, Results, Status, grade, points};

use crate::compare::EXIT_FAILED;
use crate::usage::EXIT_BAD_INPUT;

pub(crate) use kit::KitArgs;

#[derive(Args, Debug)]
#[command(
    args_conflicts_with_subcommands = true,
    subcommand_negates_reqs = true,
    override_usage = "viewray autograde [OPTIONS] --format <FORMAT> -o <RESULTS> <ASSIGNMENT>\n       \
                      \x20                 <SUBMISSION>\n       \
                      viewray autograde kit <ASSIGNMENT> --for <PLATFORM> -o <OUT>"
)]
pub(crate) struct AutogradeArgs {
    #[command(subcommand)]
    pub(crate) command: Option<AutogradeCommand>,
    /// The assignment file (RON; its paths are relative to it).
    #[arg(required = true)]
    pub(crate) assignment: Option<PathBuf>,
    /// The student's submission: a folder with the files the tests name, or the program
    /// the assignment's `run` command runs.
    #[arg(required = true)]
    pub(crate) submission: Option<PathBuf>,
    /// The results' format: the platform's own.
    #[arg(long, value_enum, required = true)]
    pub(crate) format: Option<FormatArg>,
    /// Where the results go (its folder is made if need be).
    #[arg(short = 'o', long = "output", value_name = "RESULTS", required = true)]
    pub(crate) output: Option<PathBuf>,
    /// Grade only the test of this name (repeat for several); the others are left out
    /// of the results.
    #[arg(long = "test", value_name = "NAME")]
    pub(crate) tests: Vec<String>,
    /// Run the student's program as this user (viewray must be root), who owns only the
    /// program's folders: what the Gradescope kit does with `nobody`.
    #[arg(long, value_name = "USER")]
    pub(crate) run_as: Option<String>,
}

#[derive(Subcommand, Debug)]
pub(crate) enum AutogradeCommand {
    /// Write what an autograding platform takes to run `viewray autograde`.
    ///
    /// gradescope: the autograder zip to upload (setup.sh, run_autograder, viewray
    /// itself, the assignment with its scenes and references, and a README for the
    /// instructor). github: the files to add to a GitHub Classroom assignment's template
    /// repository (the workflow, with the autograding reporter action, and .viewray/).
    Kit(KitArgs),
}

/// The formats, as typed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum FormatArg {
    /// Gradescope's results.json (/autograder/results/results.json).
    Gradescope,
    /// PrairieLearn's external grader results.json (/grade/results/results.json).
    Prairielearn,
    /// GitHub Classroom: the autograding result object in base64, for the reporter
    /// action.
    Github,
    /// JUnit XML, for any CI.
    Junit,
    /// viewray's own JSON, with everything.
    Json,
}

impl FormatArg {
    fn format(self) -> Format {
        match self {
            FormatArg::Gradescope => Format::Gradescope,
            FormatArg::Prairielearn => Format::PrairieLearn,
            FormatArg::Github => Format::Github,
            FormatArg::Junit => Format::Junit,
            FormatArg::Json => Format::Json,
        }
    }
}

/// Runs `viewray autograde` (or its `kit`); prints its own errors and returns the exit
/// code.
pub(crate) fn run(args: &AutogradeArgs) -> ExitCode {
    if let Some(AutogradeCommand::Kit(kit)) = &args.command {
        return match kit::kit(kit) {
            Ok(()) => ExitCode::SUCCESS,
            Err(error) => crate::failure(&error),
        };
    }
    let (Some(assignment), Some(submission), Some(format), Some(output)) = (
        &args.assignment,
        &args.submission,
        args.format,
        &args.output,
    ) else {
        unreachable!("clap requires them without a subcommand");
    };
    let options = Options {
        only: args.tests.clone(),
        run_as: args.run_as.clone(),
        ..Options::default()
    };
    let results = grade(assignment, submission, &options);
    if let Err(error) = write_results(&results, format.format(), output) {
        return crate::failure(&error);
    }
    if let Err(error) = print_rows(&results) {
        return crate::failure(&error);
    }
    if let Some(problem) = &results.problem {
        crate::style::error(format_args!("not graded: {problem} (the results say so)"));
        return ExitCode::from(EXIT_BAD_INPUT);
    }
    if results.all_passed() {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(EXIT_FAILED)
    }
}

/// Writes the results file atomically, making its folder first.
fn write_results(results: &Results, format: Format, output: &std::path::Path) -> Result<()> {
    if let Some(parent) = output.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("cannot make the folder of {}", output.display()))?;
    }
    viewray_output::write_atomically(output, &format.write(results))?;
    Ok(())
}

/// One line per test, as a student may see it now, then the summary.
fn print_rows(results: &Results) -> Result<()> {
    let mut out = BufWriter::new(anstream::AutoStream::auto(std::io::stdout().lock()));
    let width = results
        .tests
        .iter()
        .map(|t| t.name.chars().count())
        .max()
        .unwrap_or(4);
    for test in &results.tests {
        let (style, label) = match test.status {
            Status::Passed => (crate::style::PASS, "PASS"),
            Status::Failed => (crate::style::FAIL, "FAIL"),
        };
        let shown = test.shown();
        let score = format!("{}/{}", points(test.score), points(test.max_score));
        writeln!(
            out,
            "{}  {score:>7}  {:width$}  {}",
            crate::style::padded(style, label, 4),
            test.name,
            shown.message
        )?;
        for line in shown.output.lines() {
            writeln!(out, "      {line}")?;
        }
    }
    writeln!(out, "{}", results.summary())?;
    out.flush()?;
    Ok(())
}
