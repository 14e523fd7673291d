//! `cargo xtask browser`: the live playground driven in headless Chromium.
//!
//! Installs what the test needs when it is missing (Debian's `chromium`, Node.js and
//! npm through apt-get; playwright-core, pinned by `xtask/browser/package-lock.json`,
//! into `target/browser/node_modules`, no browser download), builds `viewray`, starts
//! `viewray serve --port 0`, and runs `xtask/browser/playground.mjs` against it.
//! Screenshots go to `target/browser/`.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};

use anyhow::{Context, Result, bail};
use clap::Args;

use crate::run;

/// The Chromium the test drives: Debian's.
const CHROMIUM: &str = "/usr/bin/chromium";

/// The options of `cargo xtask browser`.
#[derive(Debug, Args)]
pub struct BrowserArgs {
    /// Where the screenshots go (default: target/browser).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// Runs the browser test; fails when any of its checks fails.
///
/// # Errors
/// A missing tool that cannot be installed, a build that fails, or a failed check.
pub fn browser(root: &Path, args: &BrowserArgs) -> Result<()> {
    let work = crate::target_dir(root)?.join("browser");
    let out = args.out.clone().unwrap_or_else(|| work.clone());
    std::fs::create_dir_all(&work).with_context(|| format!("cannot create {}", work.display()))?;

    ensure_system_packages()?;
    ensure_playwright(root, &work)?;

    let viewray = crate::build_executable(root, &["--package", "viewray"])?;
    let mut server = Server::start(&viewray)?;
    // Run from beside node_modules: an ES module finds its imports from where it is.
    let script = work.join("playground.mjs");
    std::fs::copy(root.join("xtask/browser/playground.mjs"), &script)
        .context("cannot copy the browser test script")?;
    eprintln!("$ node {} {}", script.display(), server.url);
    let status = Command::new("node")
        .arg(&script)
        .arg(&server.url)
        .arg(&viewray)
        .arg(&out)
        .env("CHROMIUM", CHROMIUM)
        .current_dir(&work)
        .status()
        .context("cannot run node")?;
    server.stop();
    if !status.success() {
        bail!(
            "the browser test failed ({status}); see {}",
            out.join("failure.png").display()
        );
    }
    Ok(())
}

/// Installs Chromium and Node.js with apt-get when they are missing.
fn ensure_system_packages() -> Result<()> {
    let mut missing = Vec::new();
    if !Path::new(CHROMIUM).exists() {
        missing.push("chromium");
    }
    if Command::new("node").arg("--version").output().is_err() {
        missing.extend(["nodejs", "npm"]);
    } else if Command::new("npm").arg("--version").output().is_err() {
        missing.push("npm");
    }
    if missing.is_empty() {
        return Ok(());
    }
    eprintln!("installing {} with apt-get", missing.join(", "));
    let what = "install the browser test's tools (run as root, or install them)";
    run(Command::new("apt-get").arg("update"), what)?;
    run(
        Command::new("apt-get")
            .args(["install", "-y", "--no-install-recommends"])
            .args(&missing)
            .env("DEBIAN_FRONTEND", "noninteractive"),
        what,
    )
}

/// Installs playwright-core into `work/node_modules` from the committed lock file,
/// unless that version is there already.
fn ensure_playwright(root: &Path, work: &Path) -> Result<()> {
    let source = root.join("xtask/browser");
    let lock = std::fs::read_to_string(source.join("package-lock.json"))
        .context("cannot read xtask/browser/package-lock.json")?;
    let installed = std::fs::read_to_string(work.join("node_modules/.package-lock.json"));
    let wanted = pinned_version(&lock);
    if let (Ok(installed), Some(wanted)) = (installed, wanted.as_deref())
        && pinned_version(&installed).as_deref() == Some(wanted)
    {
        return Ok(());
    }
    for file in ["package.json", "package-lock.json"] {
        std::fs::copy(source.join(file), work.join(file))
            .with_context(|| format!("cannot copy {file} into {}", work.display()))?;
    }
    run(
        Command::new("npm")
            .args(["ci", "--no-audit", "--no-fund", "--loglevel=error"])
            .current_dir(work),
        "install playwright-core from npm",
    )
}

/// The version of playwright-core a package lock file pins.
fn pinned_version(lock: &str) -> Option<String> {
    let at = lock.find("\"node_modules/playwright-core\"")?;
    let rest = &lock[at..];
    let version = rest.find("\"version\"")?;
    let value = rest[version + "\"version\"".len()..].trim_start_matches([' ', ':']);
    let value = value.strip_prefix('"')?;
    Some(value[..value.find('"')?].to_owned())
}

/// `viewray serve --port 0`, running.
struct Server {
    child: Child,
    url: String,
}

impl Server {
    fn start(viewray: &Path) -> Result<Server> {
        let mut child = Command::new(viewray)
            .args(["serve", "--port", "0"])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .spawn()
            .with_context(|| format!("cannot run {}", viewray.display()))?;
        let stdout = child.stdout.take().context("the server's output")?;
        let mut url = String::new();
        BufReader::new(stdout)
            .read_line(&mut url)
            .context("cannot read the server's URL")?;
        let url = url.trim().to_owned();
        if !url.starts_with("http://") {
            let _ = child.kill();
            bail!("viewray serve printed {url:?} instead of its URL");
        }
        Ok(Server { child, url })
    }

    fn stop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.stop();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_pinned_playwright_is_read_from_the_lock_file() {
        let lock = r#"{"packages": {"": {}, "node_modules/playwright-core": {
            "version": "1.65.1", "resolved": "x"}}}"#;
        assert_eq!(pinned_version(lock).as_deref(), Some("1.65.1"));
        assert_eq!(pinned_version("{}"), None);
        let committed = include_str!("../browser/package-lock.json");
        let package = include_str!("../browser/package.json");
        let pinned = pinned_version(committed).expect("the lock pins playwright-core");
        assert!(package.contains(&format!("\"playwright-core\": \"{pinned}\"")));
    }
}
