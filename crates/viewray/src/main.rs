//! The `viewray` command: render scenes, print camera frames, viewing rays and
//! projections so students can check homework numbers, compare renders, and draw the
//! lecture's figures.
//!
//! Output meant for programs (and for checking by hand) is JSON lines on stdout. Errors
//! are one line, `error: ...`, on stderr.
//!
//! Exit codes: 0 success; 1 a comparison failed; 2 bad input or usage; anything else an
//! internal error.

mod cli;
mod commands;
mod compare;
mod diagram;
mod figures;
mod json;
mod render;

use std::process::ExitCode;

use clap::Parser;

use crate::cli::{Cli, Command};

/// Exit code for bad input or usage.
const EXIT_BAD_INPUT: u8 = 2;

fn main() -> ExitCode {
    let args = cli::expand_repeated_values(std::env::args_os());
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(error) => return cli::report_usage_error(&error),
    };
    let result = match cli.command {
        Command::Render(args) => render::render(&args),
        Command::Frame(args) => commands::frame(&args),
        Command::Rays(args) => commands::rays(&args),
        Command::Project(args) => commands::project(&args),
        Command::Compare(args) => return compare::run(&args),
        Command::Figure(args) => figures::figure(&args),
        Command::Figures(args) => figures::figures(&args),
        Command::Diagram(args) => diagram::diagram(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::from(EXIT_BAD_INPUT)
        }
    }
}
