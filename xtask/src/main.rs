//! `cargo xtask`: viewray's automation (see the library's docs). With no argument it lists
//! its commands.

use std::process::{Command, ExitCode};

use anyhow::{Context, Result, bail};
use clap::{CommandFactory as _, Parser, Subcommand};
use xtask::{
    browser, figures, golden, icosphere, interop, mistakes, mutants, wheel, workspace_root,
};

/// viewray's automation.
#[derive(Debug, Parser)]
#[command(name = "cargo xtask", bin_name = "cargo xtask")]
struct Cli {
    #[command(subcommand)]
    command: Option<Task>,
}

#[derive(Debug, Subcommand)]
enum Task {
    /// Every check CI runs: cargo fmt --check, cargo clippy (warnings are errors), cargo
    /// test (the golden check included, as the `golden` test target), the camera crate's
    /// mutants in lines changed since main (`mutants --in-diff`), the wheel and its
    /// Python tests when what it is built from changed since main (`wheel --test
    /// --in-diff`), the live playground in headless Chromium (`browser`), then the
    /// interop check against the real tools.
    Ci,
    /// Render every scene in fixtures/scenes (and the default scene), every lecture
    /// figure, the first, middle and last frames of every built-in animation and the
    /// picture of every entry of the lecture's catalogue of mistakes, and compare each
    /// with golden/{scenes,figures,animations,mistakes}/<name>.png; a report of the
    /// failures goes to golden/index.html in the target directory.
    Golden(golden::GoldenArgs),
    /// Draw every lecture figure, pictures ray traced, as <name>.png and <name>.svg, and
    /// every built-in animation as animations/<demo>.gif.
    Figures(figures::FiguresArgs),
    /// Write docs/mistakes.md, the students' page of the lecture's mistakes, from the
    /// catalogue (each entry's formula, its picture in golden/mistakes, the line to fix).
    Mistakes(mistakes::MistakesArgs),
    /// Write the geometry benchmark's mesh (1,310,720 triangles) and camera as
    /// icosphere.obj and icosphere.ron, to time `viewray render --stats` on them.
    Icosphere(icosphere::IcosphereArgs),
    /// Install Mitsuba 3 and bpy (PyPI) and three.js (npm) under the target directory (interop/), export
    /// every fixture scene and camera case to each tool, and check the tools' own rays
    /// and projections against viewray's, and each importer by round trips (1e-5
    /// relative).
    Interop(interop::InteropArgs),
    /// Drive the live playground (`viewray serve`) in headless Chromium: it loads with no
    /// console errors, renders, follows a slider, survives a reload, and shows a clicked
    /// pixel's ray as `viewray rays` prints it; screenshots in browser/ in the target directory. Installs
    /// Debian's chromium and playwright-core (into the target directory) when missing.
    Browser(browser::BrowserArgs),
    /// Mutation testing: run cargo-mutants on one crate (viewray-camera by default) with
    /// that crate's own tests, one job at a time, and print the mutants no test caught.
    /// Installs cargo-mutants from crates.io when missing. Output in mutants/ in the target directory.
    Mutants(mutants::MutantsArgs),
    /// Build the wheel for `pip install viewray` (the Python module and the `viewray`
    /// command, manylinux2014) with maturin into wheels/ in the target directory, and
    /// check it with auditwheel; --test installs it into a fresh virtual environment
    /// and runs the module's Python tests. Installs maturin, ziglang and auditwheel from
    /// PyPI into the target directory (python/tools).
    Wheel(wheel::WheelArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let root = workspace_root();
    let result = match cli.command {
        None => {
            // No command: list them, as `cargo xtask help` does.
            Cli::command().print_help().context("cannot print the help")
        }
        Some(Task::Ci) => ci(),
        Some(Task::Golden(args)) => golden::golden(&root, &args),
        Some(Task::Figures(args)) => figures::figures(&root, &args),
        Some(Task::Mistakes(args)) => mistakes::mistakes(&root, &args),
        Some(Task::Icosphere(args)) => icosphere::icosphere(&root, &args),
        Some(Task::Interop(args)) => interop::interop(&root, &args),
        Some(Task::Browser(args)) => browser::browser(&root, &args),
        Some(Task::Mutants(args)) => mutants::mutants(&root, &args),
        Some(Task::Wheel(args)) => wheel::wheel(&root, &args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

/// Runs every check CI runs, stopping at the first that fails. `cargo test` runs the
/// golden check too (the `golden` test target), so it is not run a second time.
fn ci() -> Result<()> {
    let mut steps = Steps::default();
    steps.run("fmt", || cargo(&["fmt", "--all", "--check"]))?;
    // The benchmarks' harness and peers are behind features so `cargo test` does not build
    // them; turn them on here so the benchmarks are linted too.
    steps.run("clippy", || {
        cargo(&[
            "clippy",
            "--workspace",
            "--all-targets",
            "--features",
            "viewray-geometry/bench,viewray-compare/bench",
            "--",
            "-D",
            "warnings",
        ])
    })?;
    steps.run("test", || cargo(&["test", "--workspace"]))?;
    // The whole camera crate (484 mutants) took 30 minutes at one job on two shared
    // cores, far too long for CI; the mutants in the lines a change touches take a minute
    // or two (12 mutants in 73 s, baseline build included), and none is nothing to do.
    steps.run("mutants", || {
        eprintln!("$ cargo xtask mutants viewray-camera --in-diff");
        mutants::mutants(
            &workspace_root(),
            &mutants::MutantsArgs {
                krate: "viewray-camera".to_owned(),
                in_diff: true,
                ..mutants::MutantsArgs::default()
            },
        )
    })?;
    // The wheel takes minutes to build from nothing (two release builds linked by zig:
    // 12 minutes on two shared cores, 7 of processor time), as CI's fresh target
    // directory always does, so CI builds and tests it only when what it is built from
    // changed (the module's crates, Cargo.toml, Cargo.lock, the fixtures).
    steps.run("wheel", || {
        eprintln!("$ cargo xtask wheel --test --in-diff");
        wheel::wheel(
            &workspace_root(),
            &wheel::WheelArgs {
                test: true,
                in_diff: true,
            },
        )
    })?;
    steps.run("browser", || {
        eprintln!("$ cargo xtask browser");
        browser::browser(&workspace_root(), &browser::BrowserArgs { out: None })
    })?;
    // The real tools: about a minute to install them the first time (PyPI and npm), half
    // a minute to check every export and import against them.
    steps.run("interop", || {
        eprintln!("$ cargo xtask interop");
        interop::interop(&workspace_root(), &interop::InteropArgs::default())
    })?;
    steps.report();
    Ok(())
}

/// The wall-clock time of each of `ci`'s steps, printed at the end (and after a failed
/// step, with the steps before it) so that what CI spends its time on is in every log.
#[derive(Default)]
struct Steps {
    done: Vec<(&'static str, std::time::Duration)>,
}

impl Steps {
    /// Runs the step `name` and records how long it took, failed or not.
    fn run(&mut self, name: &'static str, step: impl FnOnce() -> Result<()>) -> Result<()> {
        let start = std::time::Instant::now();
        let result = step();
        self.done.push((name, start.elapsed()));
        if result.is_err() {
            self.report();
        }
        result
    }

    /// Prints one line: each step's seconds and the total.
    fn report(&self) {
        let total: std::time::Duration = self.done.iter().map(|(_, time)| *time).sum();
        let steps: Vec<String> = self
            .done
            .iter()
            .map(|(name, time)| format!("{name} {:.0} s", time.as_secs_f64()))
            .collect();
        eprintln!(
            "ci: {} (total {:.0} s)",
            steps.join(", "),
            total.as_secs_f64()
        );
    }
}

/// Runs `cargo` with `args` in the workspace root and fails unless it succeeds.
fn cargo(args: &[&str]) -> Result<()> {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned());
    eprintln!("$ cargo {}", args.join(" "));
    let status = Command::new(&cargo)
        .args(args)
        .current_dir(workspace_root())
        .status()
        .with_context(|| format!("could not run `{cargo}`"))?;
    if !status.success() {
        bail!("`cargo {}` failed ({status})", args.join(" "));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::*;

    fn parse(args: &[&str]) -> Result<Cli, clap::Error> {
        Cli::try_parse_from(std::iter::once("cargo xtask").chain(args.iter().copied()))
    }

    #[test]
    fn the_command_line_is_consistent() {
        Cli::command().debug_assert();
    }

    #[test]
    fn no_argument_lists_every_command() {
        assert!(parse(&[]).unwrap().command.is_none());
        let help = Cli::command().render_help().to_string();
        assert!(help.contains("Usage: cargo xtask [COMMAND]"), "{help}");
        for command in [
            "ci",
            "golden",
            "figures",
            "icosphere",
            "interop",
            "browser",
            "mutants",
            "wheel",
        ] {
            assert!(
                help.contains(&format!("\n  {command} ")),
                "{command}: {help}"
            );
        }
    }

    #[test]
    fn each_command_takes_its_own_options() {
        let Some(Task::Golden(golden)) = parse(&["golden", "oblique", "--bless"]).unwrap().command
        else {
            panic!("golden");
        };
        assert_eq!(golden.filter.as_deref(), Some("oblique"));
        assert!(golden.bless);
        let Some(Task::Figures(figures)) = parse(&["figures", "--out=a/b"]).unwrap().command else {
            panic!("figures");
        };
        assert_eq!(figures.out, Some(PathBuf::from("a/b")));
        let Some(Task::Icosphere(icosphere)) = parse(&["icosphere"]).unwrap().command else {
            panic!("icosphere");
        };
        assert_eq!(icosphere.out, None);
        let Some(Task::Wheel(w)) = parse(&["wheel", "--test", "--in-diff"]).unwrap().command else {
            panic!("wheel");
        };
        assert!(w.test && w.in_diff);
        let Some(Task::Wheel(w)) = parse(&["wheel"]).unwrap().command else {
            panic!("wheel");
        };
        assert!(!w.test && !w.in_diff);
        let Some(Task::Mutants(m)) = parse(&["mutants"]).unwrap().command else {
            panic!("mutants");
        };
        assert_eq!(
            (
                m.krate.as_str(),
                m.in_diff,
                m.jobs,
                m.file.len(),
                m.regex.len()
            ),
            ("viewray-camera", false, 1, 0, 0)
        );
        let Some(Task::Mutants(m)) = parse(&[
            "mutants",
            "viewray-geometry",
            "--in-diff",
            "-j",
            "2",
            "-f",
            "aabb.rs",
            "--file=bvh.rs",
            "-F",
            "slab",
            "--re=Bvh::any",
        ])
        .unwrap()
        .command
        else {
            panic!("mutants");
        };
        assert_eq!(m.krate, "viewray-geometry");
        assert!(m.in_diff);
        assert_eq!(m.jobs, 2);
        assert_eq!(m.file, ["aabb.rs", "bvh.rs"]);
        assert_eq!(m.regex, ["slab", "Bvh::any"]);
        for bad in [
            &["mutants", "a", "b"][..],
            &["figures", "--bless"][..],
            &["figures", "--out"],
            &["golden", "a", "b"],
            &["ci", "--out", "x"],
            &["frobnicate"],
        ] {
            let error = parse(bad).unwrap_err();
            assert_eq!(error.exit_code(), 2, "{bad:?}");
        }
    }
}
