//! viewray's automation, written in Rust so it runs wherever cargo does: the golden check,
//! the lecture figures, the benchmark's icosphere scene, the interop check against the
//! real tools, the live playground driven in headless Chromium, mutation testing, and
//! the wheel for `pip install viewray`.
//!
//! `main.rs` is the `cargo xtask` command (an alias in `.cargo/config.toml`); the golden
//! check is also the `golden` test target (`tests/golden.rs`), so plain `cargo test` runs
//! it and `cargo test -p xtask --test golden -- oblique` runs the images whose name
//! contains `oblique`.

pub mod browser;
pub mod figures;
pub mod golden;
pub mod icosphere;
pub mod interop;
pub mod mistakes;
pub mod mutants;
pub mod wheel;

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use anyhow::{Context, Result, bail};

/// Writes `bytes` to `path` atomically (viewray-output's writer), creating its folder.
///
/// # Errors
/// When the folder cannot be created or the file cannot be written; the error names the
/// path.
pub fn write_atomically(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = path.parent().context("an output lives in a folder")?;
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    viewray_output::write_atomically(path, bytes)?;
    Ok(())
}

/// The workspace root: the parent of this crate's manifest directory.
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("xtask lives one level below the workspace root")
        .to_path_buf()
}

/// The cargo this xtask was started by (`$CARGO`), or the one on the path.
pub fn cargo() -> String {
    std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_owned())
}

/// Runs `command`, echoing it as a shell would show it, and fails unless it succeeds;
/// the error says `what` it was for and the command.
///
/// # Errors
/// When the command cannot start or exits unsuccessfully.
pub fn run(command: &mut Command, what: &str) -> Result<()> {
    let shown = std::iter::once(command.get_program())
        .chain(command.get_args())
        .map(|a| a.to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join(" ");
    eprintln!("$ {shown}");
    let status = command
        .status()
        .with_context(|| format!("could not {what}: cannot run `{shown}`"))?;
    if !status.success() {
        bail!("could not {what}: `{shown}` failed ({status})");
    }
    Ok(())
}

/// Where cargo puts the workspace's build outputs: `cargo metadata`'s
/// `target_directory`, which honours `CARGO_TARGET_DIR` and `build.target-dir`. Every
/// xtask writes its own outputs (reports, installed tools, screenshots) under it and
/// finds the binaries it builds there, never under a hard-coded `target/`. Asked once per
/// process.
///
/// # Errors
/// When `cargo metadata` cannot run or does not say.
pub fn target_dir(root: &Path) -> Result<PathBuf> {
    static TARGET: OnceLock<PathBuf> = OnceLock::new();
    if let Some(dir) = TARGET.get() {
        return Ok(dir.clone());
    }
    let mut command = Command::new(cargo());
    command.current_dir(root);
    let dir = metadata_target_dir(&mut command)?;
    Ok(TARGET.get_or_init(|| dir).clone())
}

/// `target_directory` from `command` (a cargo to run, with its environment and working
/// directory set) given `metadata --format-version 1 --no-deps`.
fn metadata_target_dir(command: &mut Command) -> Result<PathBuf> {
    command.args(["metadata", "--format-version", "1", "--no-deps"]);
    let output = command.output().context("cannot run `cargo metadata`")?;
    if !output.status.success() {
        bail!(
            "`cargo metadata` failed ({}): {}",
            output.status,
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    let metadata: serde_json::Value =
        serde_json::from_slice(&output.stdout).context("`cargo metadata` printed no JSON")?;
    metadata["target_directory"]
        .as_str()
        .map(PathBuf::from)
        .context("`cargo metadata` names no target_directory")
}

/// Builds `args` (`cargo build` arguments naming one binary, such as `["--package",
/// "viewray"]`) and returns the path of the executable cargo made, read from cargo's own
/// JSON messages: right whatever the target directory, profile or target triple.
///
/// # Errors
/// When the build fails or makes no executable.
pub fn build_executable(root: &Path, args: &[&str]) -> Result<PathBuf> {
    let shown = format!("cargo build {}", args.join(" "));
    eprintln!("$ {shown}");
    let output = Command::new(cargo())
        .arg("build")
        .args(args)
        .arg("--message-format=json-render-diagnostics")
        .current_dir(root)
        .stderr(std::process::Stdio::inherit())
        .output()
        .with_context(|| format!("cannot run `{shown}`"))?;
    if !output.status.success() {
        bail!("`{shown}` failed ({})", output.status);
    }
    executable_from_messages(&output.stdout)
        .with_context(|| format!("`{shown}` made no executable"))
}

/// The last executable named by cargo's `compiler-artifact` JSON messages in `stdout`.
fn executable_from_messages(stdout: &[u8]) -> Option<PathBuf> {
    String::from_utf8_lossy(stdout)
        .lines()
        .filter_map(|line| serde_json::from_str::<serde_json::Value>(line).ok())
        .filter(|message| message["reason"] == "compiler-artifact")
        .filter_map(|message| message["executable"].as_str().map(PathBuf::from))
        .next_back()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `target_dir` asks cargo, so it follows what cargo follows: `CARGO_TARGET_DIR`
    /// and `build.target-dir`, not a `target/` beside the sources.
    #[test]
    fn the_target_dir_is_where_cargo_puts_it() {
        let root = workspace_root();
        let elsewhere = tempfile::tempdir().unwrap();
        let mut command = Command::new(cargo());
        command
            .current_dir(&root)
            .env("CARGO_TARGET_DIR", elsewhere.path());
        assert_eq!(metadata_target_dir(&mut command).unwrap(), elsewhere.path());

        let configured = elsewhere.path().join("configured");
        let mut command = Command::new(cargo());
        command
            .current_dir(&root)
            .env_remove("CARGO_TARGET_DIR")
            .arg("--config")
            .arg(format!(
                "build.target-dir={:?}",
                configured.to_str().unwrap()
            ));
        assert_eq!(metadata_target_dir(&mut command).unwrap(), configured);
    }

    #[test]
    fn the_executable_is_read_from_cargos_messages() {
        let messages = concat!(
            r#"{"reason":"compiler-artifact","package_id":"a","executable":null}"#,
            "\n",
            "not json\n",
            r#"{"reason":"compiler-artifact","package_id":"viewray","executable":"/t/debug/viewray"}"#,
            "\n",
            r#"{"reason":"build-finished","success":true}"#,
            "\n",
        );
        assert_eq!(
            executable_from_messages(messages.as_bytes()),
            Some(PathBuf::from("/t/debug/viewray"))
        );
        assert_eq!(executable_from_messages(b"{}"), None);
    }
}
