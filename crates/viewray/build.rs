//! Sets `VIEWRAY_VERSION`, what `viewray --version` prints: the package version and, when
//! the source is a git checkout of viewray and git is installed, the commit it was built
//! from, as `0.1.0 (1a2b3c4)`. Built from a tarball, or without git, it is the package
//! version alone: this script never fails the build.
//!
//! It reruns only when the checkout's current commit changes (HEAD, the branch it points
//! to, or the packed refs), not on every build.

use std::path::{Path, PathBuf};
use std::process::Command;

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    let version = env!("CARGO_PKG_VERSION");
    let manifest_dir = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    match commit(&manifest_dir) {
        Some((commit, watched)) => {
            for path in watched {
                println!("cargo:rerun-if-changed={}", path.display());
            }
            println!("cargo:rustc-env=VIEWRAY_VERSION={version} ({commit})");
        }
        None => println!("cargo:rustc-env=VIEWRAY_VERSION={version}"),
    }
}

/// Runs `git args` in `dir`; its output, trimmed, if it succeeds.
fn git(dir: &Path, args: &[&str]) -> Option<String> {
    let output = Command::new("git")
        .args(args)
        .current_dir(dir)
        .output()
        .ok()?;
    if !output.status.success() {
        return None;
    }
    let text = String::from_utf8(output.stdout).ok()?.trim().to_owned();
    (!text.is_empty()).then_some(text)
}

/// The short commit of the checkout `dir` is in, and the files that change when the
/// commit does; `None` unless `dir` is this crate inside a checkout of viewray (not, say,
/// an unpacked tarball inside some other repository).
fn commit(dir: &Path) -> Option<(String, Vec<PathBuf>)> {
    let top = PathBuf::from(git(dir, &["rev-parse", "--show-toplevel"])?);
    let ours = top.join("crates/viewray/Cargo.toml").canonicalize().ok()?;
    if ours != dir.join("Cargo.toml").canonicalize().ok()? {
        return None;
    }
    let commit = git(dir, &["rev-parse", "--short", "HEAD"])?;
    // HEAD names the branch; the branch's file (or packed-refs) names the commit. Only
    // files that exist are watched: cargo reruns the script every time for a missing one.
    let mut watched = vec![git(dir, &["rev-parse", "--git-path", "HEAD"])?];
    if let Some(branch) = git(dir, &["symbolic-ref", "-q", "HEAD"]) {
        watched.extend(git(dir, &["rev-parse", "--git-path", &branch]));
    }
    watched.extend(git(dir, &["rev-parse", "--git-path", "packed-refs"]));
    let watched = watched
        .into_iter()
        .map(|path| dir.join(path))
        .filter(|path| path.exists())
        .collect();
    Some((commit, watched))
}
