//! viewray's automation, written in Rust so it runs wherever cargo does.
//!
//! `cargo xtask` (an alias in `.cargo/config.toml`) with no argument lists the commands.

mod figures;
mod golden;
mod icosphere;

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

use anyhow::{Context, Result, bail};

const HELP: &str = "\
usage: cargo xtask <command>

commands:
  ci                      every check CI runs: cargo fmt --check, cargo clippy (warnings
                          are errors), cargo test, then the golden check
  golden [FILTER]         render every scene in fixtures/scenes (and the default scene)
                          and every lecture figure, and compare each with
                          golden/{scenes,figures}/<name>.png; a report of the failures
                          goes to target/golden/index.html. FILTER keeps the images
                          whose `scenes/<name>` or `figures/<name>` contains it
  golden [FILTER] --bless rewrite the goldens whose pixels changed, add missing ones and
                          remove those with no scene or figure (refused when CI is set)
  figures [--out DIR]     draw every lecture figure, pictures ray traced, as <name>.png
                          and <name>.svg into DIR (default target/figures/)
  icosphere [--out DIR]   write the geometry benchmark's mesh (1,310,720 triangles) and
                          camera as icosphere.obj and icosphere.ron into DIR (default
                          target/icosphere/), to time `viewray render --stats` on them
";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("ci") => ci(),
        Some("golden") => golden::GoldenArgs::parse(&args[1..])
            .and_then(|a| golden::golden(&workspace_root(), &a)),
        Some("figures") => figures::FiguresArgs::parse(&args[1..])
            .and_then(|a| figures::figures(&workspace_root(), &a)),
        Some("icosphere") => icosphere::IcosphereArgs::parse(&args[1..])
            .and_then(|a| icosphere::icosphere(&workspace_root(), &a)),
        Some("help" | "--help" | "-h") | None => {
            print!("{HELP}");
            Ok(())
        }
        Some(other) => Err(anyhow::anyhow!("unknown command `{other}`\n\n{HELP}")),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::FAILURE
        }
    }
}

/// Runs every check CI runs, stopping at the first that fails.
fn ci() -> Result<()> {
    cargo(&["fmt", "--all", "--check"])?;
    // The benchmarks' harness and peers are behind features so `cargo test` does not build
    // them; turn them on here so the benchmarks are linted too.
    cargo(&[
        "clippy",
        "--workspace",
        "--all-targets",
        "--features",
        "viewray-geometry/bench,viewray-compare/bench",
        "--",
        "-D",
        "warnings",
    ])?;
    cargo(&["test", "--workspace"])?;
    eprintln!("$ cargo xtask golden");
    golden::golden(&workspace_root(), &golden::GoldenArgs::default())
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

/// The folder of a command whose only option is `--out DIR` (or `--out=DIR`).
pub(crate) fn parse_out(command: &str, args: &[String]) -> Result<Option<PathBuf>> {
    let mut out = None;
    let mut args = args.iter();
    while let Some(arg) = args.next() {
        let dir = match arg.as_str() {
            "--out" => match args.next() {
                Some(dir) => dir.as_str(),
                None => bail!("--out needs a folder: --out DIR"),
            },
            other => match other.strip_prefix("--out=") {
                Some(dir) => dir,
                None => bail!("unknown argument `{other}` for {command} (only --out DIR)"),
            },
        };
        if out.replace(PathBuf::from(dir)).is_some() {
            bail!("--out given twice");
        }
    }
    Ok(out)
}

/// Writes `bytes` to `path` (creating its folder) through a temporary file beside it,
/// renamed into place when complete, so `path` is never left half-written.
pub(crate) fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path.parent().context("an output lives in a folder")?;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let mut builder = tempfile::Builder::new();
    builder.prefix(".xtask-").suffix(".tmp");
    // The temporary file is private (0600) by default; the outputs are ordinary files.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        builder.permissions(std::fs::Permissions::from_mode(0o644));
    }
    let mut file = builder
        .tempfile_in(dir)
        .with_context(|| format!("cannot write {}", path.display()))?;
    std::io::Write::write_all(&mut file, bytes)
        .with_context(|| format!("cannot write {}", path.display()))?;
    file.persist(path)
        .with_context(|| format!("cannot write {}", path.display()))?;
    Ok(())
}

/// The workspace root: the parent of this crate's manifest directory.
fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives one level below the workspace root")
        .to_path_buf()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<Option<PathBuf>> {
        let args: Vec<String> = args.iter().map(|&a| a.to_owned()).collect();
        parse_out("figures", &args)
    }

    #[test]
    fn out_is_the_only_option() {
        assert_eq!(parse(&[]).unwrap(), None);
        assert_eq!(
            parse(&["--out", "a/b"]).unwrap(),
            Some(PathBuf::from("a/b"))
        );
        assert_eq!(parse(&["--out=c"]).unwrap(), Some(PathBuf::from("c")));
        let error = |args: &[&str]| parse(args).unwrap_err().to_string();
        assert_eq!(error(&["--out"]), "--out needs a folder: --out DIR");
        assert_eq!(error(&["--out", "a", "--out=b"]), "--out given twice");
        assert_eq!(
            error(&["--bless"]),
            "unknown argument `--bless` for figures (only --out DIR)"
        );
    }
}
