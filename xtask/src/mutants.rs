//! `cargo xtask mutants`: mutation testing with cargo-mutants.
//!
//! cargo-mutants changes the code one small way at a time (`*` to `/`, `>` to `>=`, a
//! function body to `Ok(())`) and runs the crate's own tests against each change; a
//! change no test notices is a *survivor*: a wrong formula the tests would let through.
//! This runs it on one crate with that crate's tests only, one job at a time unless told
//! otherwise (the machine is shared), built unoptimized (the `mutation` profile), and
//! prints the survivors. A mutant that cannot change behaviour is best rewritten away
//! (the code can usually say the same thing more plainly); failing that, it would be
//! excluded with the reason in `.cargo/mutants.toml` (viewray-camera has three: fast
//! paths that make the same rays to the bit, and a half turn either way).
//!
//! cargo-mutants is installed from crates.io (`cargo install --locked`) into cargo's bin
//! folder when it is missing.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use crate::cargo;
use anyhow::{Context, Result, bail};
use clap::Args;

/// The cargo-mutants release these figures and flags were measured with.
const CARGO_MUTANTS_VERSION: &str = "27.1.0";

/// The options of `cargo xtask mutants`; `Default` gives the command line's defaults.
#[derive(Debug, Args)]
pub struct MutantsArgs {
    /// The crate to mutate; its own tests are the ones run.
    #[arg(default_value = "viewray-camera")]
    pub krate: String,
    /// Only the mutants in lines changed since the merge base with `main` (on `main`
    /// itself: since its previous commit), uncommitted changes included; nothing to do
    /// when the crate's sources did not change.
    #[arg(long)]
    pub in_diff: bool,
    /// Only the mutants in these files (a glob, relative to the workspace root, or a
    /// file name such as `projection.rs`); may be repeated.
    #[arg(long, short = 'f', value_name = "FILE")]
    pub file: Vec<String>,
    /// Only the mutants whose name (`file:line:col: replace ... in function`) matches
    /// this regular expression; may be repeated (any one matching is enough).
    #[arg(long = "re", short = 'F', value_name = "REGEX")]
    pub regex: Vec<String>,
    /// How many mutants to build and test at once (under CI, which mutates its clone in
    /// place, one).
    #[arg(long, short = 'j', default_value_t = 1)]
    pub jobs: usize,
}

impl Default for MutantsArgs {
    fn default() -> Self {
        Self {
            krate: "viewray-camera".to_owned(),
            in_diff: false,
            file: Vec::new(),
            regex: Vec::new(),
            jobs: 1,
        }
    }
}

/// What one run found, read from cargo-mutants' `mutants.out`.
#[derive(Debug, PartialEq)]
struct Outcome {
    caught: usize,
    unviable: usize,
    missed: Vec<String>,
    timeouts: Vec<String>,
}

/// Runs cargo-mutants on `args.krate` and fails when a mutant survives or times out.
///
/// # Errors
/// cargo-mutants cannot be installed or run, the unmutated tests fail, or a mutant
/// survives.
pub fn mutants(root: &Path, args: &MutantsArgs) -> Result<()> {
    let source = root.join("crates").join(&args.krate);
    if !source.join("Cargo.toml").is_file() {
        bail!("no crate {} under crates/", args.krate);
    }
    let out = crate::target_dir(root)?.join("mutants").join(&args.krate);
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;

    let mut command = Command::new(cargo());
    command.current_dir(root).args([
        "mutants",
        "--package",
        &args.krate,
        "--test-package",
        &args.krate,
        // The auto-set timeout is a few times the unmutated tests' time; on a busy shared
        // machine that is too tight, and a slow test is not a survivor. The crates' tests
        // take 2-5 s unoptimized; a mutant that loops forever costs a job this long.
        "--minimum-test-timeout",
        "30",
        "--no-shuffle",
        // Each mutant is a rebuild of the crate: the `mutation` profile builds it
        // unoptimized (2-3 s per mutant instead of ~15 s at the test profile's
        // opt-level 3); the tests are the same, a little slower.
        "--profile",
        "mutation",
    ]);
    command.arg("--output").arg(&out);
    if std::env::var_os("CI").is_some() {
        // CI's clone is thrown away afterwards and `cargo test` has just built it: mutate
        // it in place and reuse that build rather than copy the tree and build it afresh.
        // (Not on a developer's checkout, whose files must not change under their editor.)
        // In place there is one tree, so one mutant at a time: cargo-mutants refuses
        // `--jobs` beside `--in-place`.
        command.arg("--in-place");
    } else {
        command.args(["--jobs", &args.jobs.to_string()]);
    }
    for file in &args.file {
        command.args(["--file", file]);
    }
    for regex in &args.regex {
        command.args(["--re", regex]);
    }
    if args.in_diff {
        let Some(diff) = diff_since_base(root, &args.krate)? else {
            return Ok(());
        };
        let path = out.join("in.diff");
        std::fs::write(&path, diff).with_context(|| format!("cannot write {}", path.display()))?;
        command.arg("--in-diff").arg(&path);
    }

    ensure_cargo_mutants()?;
    eprintln!(
        "$ cargo {}",
        command
            .get_args()
            .map(|a| a.to_string_lossy().into_owned())
            .collect::<Vec<_>>()
            .join(" ")
    );
    // A run that finds no mutants (an `--in-diff` touching only comments) writes no
    // results: remove the last run's so they are not read as this one's.
    let results = out.join("mutants.out");
    if results.exists() {
        std::fs::remove_dir_all(&results)
            .with_context(|| format!("cannot remove {}", results.display()))?;
    }
    let start = Instant::now();
    let status = command.status().context("cannot run cargo mutants")?;
    let seconds = start.elapsed().as_secs();
    // 0: every mutant caught; 2: some survived; 3: some timed out. Anything else (the
    // unmutated tests failed, bad usage) is no result at all.
    if !matches!(status.code(), Some(0 | 2 | 3)) {
        bail!("cargo mutants failed ({status})");
    }
    if status.success() && !results.join("outcomes.json").exists() {
        println!("{}: no mutants to test", args.krate);
        return Ok(());
    }
    let outcome = read_outcome(&results)?;
    println!("{}", summary(&args.krate, &outcome, seconds));
    let survivors = outcome.missed.len() + outcome.timeouts.len();
    if survivors > 0 {
        bail!(
            "{survivors} mutant(s) of {} survived: a test should fail for each, or, if it \
             cannot change behaviour, exclude it in .cargo/mutants.toml and say why",
            args.krate
        );
    }
    Ok(())
}

/// The diff of `crates/<krate>/src` since the base this branch is compared with, or
/// `None` (having said so) when those sources did not change.
fn diff_since_base(root: &Path, krate: &str) -> Result<Option<String>> {
    let Some(base) = base_commit(root)? else {
        println!("no commit to compare with (a clone of one commit?): no mutants to test");
        return Ok(None);
    };
    let sources = format!("crates/{krate}/src");
    let diff = git(root, &["diff", &base, "--", &sources])?;
    if diff.trim().is_empty() {
        println!(
            "{sources} has not changed since {}: no mutants to test",
            &base[..12]
        );
        return Ok(None);
    }
    eprintln!(
        "testing the mutants in lines of {sources} changed since {}",
        &base[..12]
    );
    Ok(Some(diff))
}

/// The commit a change is measured from: the merge base with `main` (or `origin/main`),
/// or, where that is the current commit itself (CI's clone of `main`), its first parent:
/// the `main` before the change landed. `None` where there is none to be had: a clone of
/// that one commit alone.
pub(crate) fn base_commit(root: &Path) -> Result<Option<String>> {
    let head = git(root, &["rev-parse", "HEAD"])?.trim().to_owned();
    let merge_base = ["main", "origin/main"]
        .into_iter()
        .find_map(|main| git(root, &["merge-base", "HEAD", main]).ok())
        .map(|base| base.trim().to_owned());
    Ok(match merge_base {
        Some(base) if base != head => Some(base),
        _ => git(root, &["rev-parse", "--verify", "--quiet", "HEAD^1"])
            .ok()
            .map(|parent| parent.trim().to_owned()),
    })
}

/// Installs the pinned cargo-mutants with `cargo install --locked` unless some version
/// of it is installed.
fn ensure_cargo_mutants() -> Result<()> {
    let installed = Command::new(cargo())
        .args(["mutants", "--version"])
        .output()
        .is_ok_and(|output| output.status.success());
    if installed {
        return Ok(());
    }
    eprintln!("$ cargo install --locked cargo-mutants --version {CARGO_MUTANTS_VERSION}");
    let status = Command::new(cargo())
        .args(["install", "--locked", "cargo-mutants", "--version"])
        .arg(CARGO_MUTANTS_VERSION)
        .status()
        .context("cannot run cargo install")?;
    if !status.success() {
        bail!("cannot install cargo-mutants ({status})");
    }
    Ok(())
}

/// Reads what cargo-mutants wrote in `dir` (its `mutants.out`).
fn read_outcome(dir: &Path) -> Result<Outcome> {
    let lines = |name: &str| -> Result<Vec<String>> {
        let path: PathBuf = dir.join(name);
        let text = std::fs::read_to_string(&path)
            .with_context(|| format!("cannot read {}", path.display()))?;
        Ok(text.lines().map(str::to_owned).collect())
    };
    Ok(Outcome {
        caught: lines("caught.txt")?.len(),
        unviable: lines("unviable.txt")?.len(),
        missed: lines("missed.txt")?,
        timeouts: lines("timeout.txt")?,
    })
}

/// The figures of a run and its survivors, one a line.
fn summary(krate: &str, outcome: &Outcome, seconds: u64) -> String {
    let tested = outcome.caught + outcome.unviable + outcome.missed.len() + outcome.timeouts.len();
    let viable = tested - outcome.unviable;
    let mut text = format!(
        "{krate}: {tested} mutants, {} caught, {} unviable, {} survived, {} timeouts \
         ({} of {viable} viable caught) in {}m {:02}s",
        outcome.caught,
        outcome.unviable,
        outcome.missed.len(),
        outcome.timeouts.len(),
        percent(outcome.caught, viable),
        seconds / 60,
        seconds % 60,
    );
    for line in &outcome.missed {
        text += &format!("\nsurvived: {line}");
    }
    for line in &outcome.timeouts {
        text += &format!("\ntimeout:  {line}");
    }
    text
}

fn percent(part: usize, whole: usize) -> String {
    (part * 100)
        .checked_div(whole)
        .map_or_else(|| "all".to_owned(), |p| format!("{p}%"))
}

/// Runs git in `root` and returns its standard output.
pub(crate) fn git(root: &Path, args: &[&str]) -> Result<String> {
    let output = Command::new("git")
        .args(args)
        .current_dir(root)
        .output()
        .context("cannot run git")?;
    if !output.status.success() {
        bail!(
            "`git {}` failed: {}",
            args.join(" "),
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    String::from_utf8(output.stdout).context("git printed something that is not UTF-8")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_options_are_the_command_lines() {
        let args = MutantsArgs::default();
        assert_eq!(
            (
                args.krate.as_str(),
                args.in_diff,
                args.jobs,
                args.file.len(),
                args.regex.len()
            ),
            ("viewray-camera", false, 1, 0, 0)
        );
    }

    #[test]
    fn the_summary_gives_the_figures_and_names_every_survivor() {
        let outcome = Outcome {
            caught: 95,
            unviable: 10,
            missed: vec!["src/a.rs:1:2: replace > with >= in f".to_owned()],
            timeouts: vec!["src/b.rs:3:4: replace + with - in g".to_owned()],
        };
        assert_eq!(
            summary("viewray-camera", &outcome, 754),
            "viewray-camera: 107 mutants, 95 caught, 10 unviable, 1 survived, 1 timeouts \
             (97% of 97 viable caught) in 12m 34s\n\
             survived: src/a.rs:1:2: replace > with >= in f\n\
             timeout:  src/b.rs:3:4: replace + with - in g"
        );
        let none = Outcome {
            caught: 0,
            unviable: 0,
            missed: Vec::new(),
            timeouts: Vec::new(),
        };
        assert!(summary("x", &none, 5).contains("(all of 0 viable caught) in 0m 05s"));
    }

    #[test]
    fn the_outcome_is_read_from_the_files_cargo_mutants_writes() {
        let dir = tempfile::tempdir().unwrap();
        let write = |name: &str, text: &str| std::fs::write(dir.path().join(name), text).unwrap();
        write("caught.txt", "a\nb\nc\n");
        write("unviable.txt", "");
        write("missed.txt", "src/x.rs:1:1: replace f -> bool with true\n");
        write("timeout.txt", "");
        assert_eq!(
            read_outcome(dir.path()).unwrap(),
            Outcome {
                caught: 3,
                unviable: 0,
                missed: vec!["src/x.rs:1:1: replace f -> bool with true".to_owned()],
                timeouts: Vec::new(),
            }
        );
        std::fs::remove_file(dir.path().join("timeout.txt")).unwrap();
        let error = read_outcome(dir.path()).unwrap_err().to_string();
        assert!(error.contains("timeout.txt"), "{error}");
    }

    #[test]
    fn the_base_is_the_merge_base_or_on_main_the_previous_commit() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        let run = |args: &[&str]| {
            let output = Command::new("git")
                .args(args)
                .current_dir(root)
                .env("GIT_AUTHOR_NAME", "t")
                .env("GIT_AUTHOR_EMAIL", "t@example.com")
                .env("GIT_COMMITTER_NAME", "t")
                .env("GIT_COMMITTER_EMAIL", "t@example.com")
                .output()
                .unwrap();
            assert!(output.status.success(), "git {args:?}: {output:?}");
            String::from_utf8(output.stdout).unwrap().trim().to_owned()
        };
        let commit = |file: &str, text: &str| {
            let path = root.join(file);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(path, text).unwrap();
            run(&["add", "."]);
            run(&["commit", "-q", "-m", file]);
            run(&["rev-parse", "HEAD"])
        };
        run(&["init", "-q", "-b", "main"]);
        let first = commit("crates/c/src/lib.rs", "fn a() {}\n");
        // One commit alone (what a clone of depth 1 has): nothing to compare with.
        assert_eq!(base_commit(root).unwrap(), None);
        assert_eq!(diff_since_base(root, "c").unwrap(), None);
        let second = commit("README.md", "readme\n");
        // On main: the previous commit; and a README change leaves the crate alone.
        assert_eq!(base_commit(root).unwrap(), Some(first));
        assert_eq!(diff_since_base(root, "c").unwrap(), None);
        // On a branch: the merge base, whatever main did since.
        run(&["checkout", "-q", "-b", "topic"]);
        commit("crates/c/src/lib.rs", "fn a() { b() }\n");
        run(&["checkout", "-q", "main"]);
        commit("other.txt", "x\n");
        run(&["checkout", "-q", "topic"]);
        assert_eq!(base_commit(root).unwrap(), Some(second));
        let diff = diff_since_base(root, "c").unwrap().unwrap();
        assert!(diff.contains("+fn a() { b() }"), "{diff}");
        // Uncommitted changes count too.
        std::fs::write(root.join("crates/c/src/lib.rs"), "fn a() { c() }\n").unwrap();
        let diff = diff_since_base(root, "c").unwrap().unwrap();
        assert!(diff.contains("+fn a() { c() }"), "{diff}");
    }
}
