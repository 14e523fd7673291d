//! What the `viewray` binary's integration tests share: running the binary, and the check
//! every bad input must pass (exit code 2, nothing on stdout, exactly one `error:` line,
//! never a panic).

// Each test file uses a part of this module.
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

/// The `viewray` binary built for these tests, not yet run.
pub(crate) fn command() -> Command {
    Command::new(env!("CARGO_BIN_EXE_viewray"))
}

/// Runs `viewray args` in the current folder.
pub(crate) fn viewray(args: &[&str]) -> Output {
    command()
        .args(args)
        .output()
        .expect("the viewray binary runs")
}

/// Runs `viewray args` in the folder `dir`.
pub(crate) fn viewray_in(dir: &Path, args: &[&str]) -> Output {
    command()
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the viewray binary runs")
}

/// Runs `viewray args` expecting bad input; returns its one error line.
#[track_caller]
pub(crate) fn error_line(args: &[&str]) -> String {
    bad_input(args, viewray(args))
}

/// [`error_line`] with `viewray` run in the folder `dir`.
#[track_caller]
pub(crate) fn error_line_in(dir: &Path, args: &[&str]) -> String {
    bad_input(args, viewray_in(dir, args))
}

/// Checks that `out` is a bad-input failure: exit code 2, nothing on stdout, exactly one
/// line on stderr starting with `error: `, no panic. Returns that line.
#[track_caller]
fn bad_input(args: &[&str], out: Output) -> String {
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "viewray {args:?}: {stderr}");
    assert!(
        out.stdout.is_empty(),
        "viewray {args:?} printed {:?}",
        out.stdout
    );
    assert_eq!(stderr.lines().count(), 1, "not one line: {stderr}");
    assert!(stderr.starts_with("error: "), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr.trim_end().to_owned()
}
