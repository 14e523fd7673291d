//! The `viewray` command: render scenes, print camera frames, viewing rays, projections
//! and one pixel's trace so students can check homework numbers, compare renders, and
//! draw the lecture's figures.
//!
//! # What it owns
//!
//! The command line and the terminal: `cli` (the command tree, assembled from each
//! command's arguments; `completions` and `man`), one module per command or family of
//! commands (`render`, `animate`, `commands` for frame/rays/project/scene, `compare`,
//! `check`, `trace`, `grade`, `autograde` (with its platform kits), `figures`, `diagram`,
//! `serve`, `interop` for export/import), and what they share below them: `values`
//! (parsers of what is typed), `usage` (argument rewriting and the usage-error line),
//! `input` (where a scene comes from, and a scene's error as printed), `output` (atomic
//! files and folders, Ctrl-C), `style` (colours). Module dependencies point one way, from
//! `cli` down.
//!
//! # Invariant
//!
//! The libraries know nothing of the command line: every flag, exit code, progress bar
//! and hint that names a command is here. Output meant for programs (and for checking by
//! hand) is JSON lines on stdout. Errors are one line, `error: ...`, on stderr, and bad
//! input never leaves a partial output file. The conventions the numbers follow (pixel
//! indices, the camera frame, each family's ray, `project`'s coordinates) are written
//! for users in the repository's `docs/cameras.md`, the scene format in
//! `docs/scene-format.md`.
//!
//! Exit codes: 0 success; 1 a comparison failed; 2 bad input or usage; anything else an
//! internal error. A closed standard output (`viewray rays scene.ron | head`) ends the
//! command quietly with 0.
//!
//! # Where to start reading
//!
//! `main` below (how a command line becomes a command), `cli`, then the command's own
//! module.

mod animate;
mod autograde;
mod check;
mod cli;
mod commands;
mod compare;
mod diagram;
mod figures;
mod grade;
mod input;
mod interop;
mod output;
mod render;
mod serve;
mod style;
mod trace;
mod usage;
mod values;

use std::process::ExitCode;

use clap::Parser;

use crate::cli::{Cli, Command};
use crate::usage::EXIT_BAD_INPUT;

/// mimalloc rather than the system allocator: the renderer, compare and grade allocate
/// and free image-sized buffers per image, which glibc hands back to the kernel each
/// time (grading 200 x 10 images of 320 x 240 spent 9 s of its 40 s of CPU in page
/// faults); mimalloc keeps them for the next image.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    let args: Vec<_> = std::env::args_os().collect();
    let command = cli::subcommand_in(&args);
    if let Some(message) = usage::spaced_number_list(&args) {
        let help = usage::see_help(command.as_deref());
        style::error(format_args!("{message} {help}"));
        return ExitCode::from(EXIT_BAD_INPUT);
    }
    let expanded = usage::expand_repeated_values(args.iter().cloned());
    let cli = match Cli::try_parse_from(&expanded) {
        Ok(cli) => cli,
        Err(error) => return usage::report_usage_error(&error, command.as_deref()),
    };
    let result = match cli.command {
        Command::Render(args) => render::render(&args),
        Command::Animate(args) => animate::animate(&args),
        Command::Frame(args) => commands::frame(&args),
        Command::Rays(args) => commands::rays(&args),
        Command::Project(args) => commands::project(&args),
        Command::Trace(args) => trace::trace(&args),
        Command::Check(args) => return check::run(&args),
        Command::Compare(args) => return compare::run(&args),
        Command::Grade(args) => return grade::run(&args),
        Command::Autograde(args) => return autograde::run(&args),
        Command::Figure(args) => figures::figure(&args),
        Command::Figures(args) => figures::figures(&args),
        Command::Export(args) => interop::export(&args),
        Command::Import(args) => interop::import(&args),
        Command::Diagram(args) => diagram::diagram(&args),
        Command::Serve(args) => serve::serve(&args),
        Command::Scene(args) => commands::scene(&args),
        Command::Completions(args) => cli::completions(&args),
        Command::Man(args) => cli::man(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => failure(&error),
    }
}

/// Reports `error` as one `error:` line and returns exit code 2; a closed standard output
/// (the reader of a pipe went away, as `head` does) is not an error: exit code 0, quietly.
pub(crate) fn failure(error: &anyhow::Error) -> ExitCode {
    if is_broken_pipe(error) {
        return ExitCode::SUCCESS;
    }
    style::error(format_args!("{error:#}"));
    ExitCode::from(EXIT_BAD_INPUT)
}

/// Whether `error` comes from writing to a pipe whose reader has gone.
fn is_broken_pipe(error: &anyhow::Error) -> bool {
    error.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}
