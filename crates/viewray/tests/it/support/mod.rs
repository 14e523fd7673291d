//! What the `viewray` binary's integration tests share: running the binary, and the check
//! every bad input must pass (exit code 2, nothing on stdout, exactly one `error:` line,
//! never a panic).

// Each test file uses a part of this module.
#![allow(dead_code)]

use std::path::Path;
use std::process::{Command, Output};

/// The `viewray` binary built for these tests, not yet run: help wrapped at 80 columns
/// whatever the terminal, and colour left to the tests that ask for it.
pub(crate) fn command() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_viewray"));
    command
        .env("COLUMNS", "80")
        .env_remove("CLICOLOR_FORCE")
        .env_remove("NO_COLOR");
    command
}

/// The repository's root, where the tests run commands that name fixtures, so that
/// messages show paths like `fixtures/homework/canonical_2x2.ron`.
pub(crate) fn repository() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../..")
        .canonicalize()
        .expect("the repository root exists")
}

/// Runs `viewray args` with `input` on its standard input.
pub(crate) fn viewray_with_input(dir: &Path, args: &[&str], input: &[u8]) -> Output {
    use std::io::Write as _;
    let mut child = command()
        .args(args)
        .current_dir(dir)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("the viewray binary runs");
    let mut stdin = child.stdin.take().unwrap();
    // Written from another thread while this one reads the output, so that a command
    // printing as it reads cannot fill its output pipe and wait for us forever. The
    // command may stop reading early (bad input): a closed pipe is no failure here.
    std::thread::scope(|scope| {
        scope.spawn(move || {
            let _ = stdin.write_all(input);
        });
        child.wait_with_output().expect("the viewray binary runs")
    })
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

pub(crate) mod http;
pub(crate) mod pictures;
pub(crate) mod platforms;
pub(crate) mod student;
