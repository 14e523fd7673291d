//! viewray's automation, written in Rust so it runs wherever cargo does: the golden check,
//! the lecture figures, the benchmark's icosphere scene, the interop check against the
//! real tools, the live playground driven in headless Chromium, and mutation testing.
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
pub mod mutants;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

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
