//! `cargo xtask wheel`: the `viewray` wheel for `pip install`, with maturin.
//!
//! The wheel holds the Python module (crate viewray-python, built by maturin with its
//! `python` feature) and the `viewray` command itself, as a script of the wheel's data
//! (`viewray-X.data/scripts/viewray`, which pip installs on the user's PATH). The command
//! is the real binary, not a Python entry point into the module: it starts without an
//! interpreter, keeps its own Ctrl-C handling and exit codes, and the module stays a thin
//! layer that knows nothing of the command line. maturin builds both, each with zig as
//! the linker for glibc 2.17, so the wheel is `manylinux_2_17` (manylinux2014) however
//! new the build machine's glibc is: the command first (`maturin build -b bin`, from which
//! the binary is taken), then the module, with the command in `viewray.data/scripts/`
//! beside its `pyproject.toml` for the time of the build.
//!
//! maturin, the `ziglang` package and auditwheel are installed from PyPI, pinned below,
//! into a virtual environment under the target directory (`python/tools`), once. The
//! wheel goes to `wheels/` in the target directory and is checked with `auditwheel
//! show`, which must find it consistent with manylinux_2_17 or older.
//!
//! `--test` then lints the PyO3 layer, installs the wheel into a fresh virtual
//! environment (`python/test-venv`, with pytest and Pillow) and runs
//! `crates/viewray-python/tests/` there. `--in-diff` (what CI runs) does all of this
//! only when the wheel's inputs changed since the merge base with `main` (see
//! `wheel_inputs`).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;
use serde_json::Value;

use crate::mutants::{base_commit, git};
use crate::run;

/// The build tools, from PyPI: maturin, the zig toolchain it links with, auditwheel.
const TOOLS: [&str; 3] = ["maturin==1.16.0", "ziglang==0.15.2", "auditwheel==6.8.2"];
/// What the Python tests run with, beside the wheel (which brings NumPy): pytest, and
/// Pillow to decode the command's PNGs independently of viewray.
const TEST_TOOLS: [&str; 2] = ["pytest==9.2.0", "pillow==13.0.0"];
/// The newest glibc the wheel may need: manylinux2014's.
const GLIBC_MINOR: u32 = 17;
/// The crate that is the module.
const MODULE_CRATE: &str = "crates/viewray-python";

/// The options of `cargo xtask wheel`.
#[derive(Debug, Default, Args)]
pub struct WheelArgs {
    /// Also install the wheel into a fresh virtual environment and run the module's
    /// Python tests there (and clippy on the PyO3 layer).
    #[arg(long)]
    pub test: bool,
    /// Only when the wheel's inputs (the module's crate and the crates it is built from,
    /// Cargo.toml, Cargo.lock, the fixtures or this task) changed since the merge base
    /// with `main`, uncommitted changes included; nothing to do otherwise.
    #[arg(long)]
    pub in_diff: bool,
}

/// Where the tools and the outputs live.
struct Paths {
    root: PathBuf,
    /// `python/` in the target directory: the tools and the scratch files (not `wheel/`,
    /// where cargo puts the `wheel` profile's host builds).
    work: PathBuf,
    /// The tools' virtual environment.
    tools: PathBuf,
    /// Where the wheel goes: `wheels/` in the target directory.
    wheels: PathBuf,
}

/// Builds the wheel (and with `--test`, tests it).
///
/// # Errors
/// A tool that cannot be installed, a failed build, a wheel needing a newer glibc than
/// manylinux2014's, or a failed test.
pub fn wheel(root: &Path, args: &WheelArgs) -> Result<()> {
    if args.in_diff {
        match changed_input(root)? {
            Some(why) => eprintln!("building the wheel: {why}"),
            None => {
                println!("the wheel's inputs have not changed since main: no wheel to build");
                return Ok(());
            }
        }
    }
    let target = crate::target_dir(root)?;
    let work = target.join("python");
    let paths = Paths {
        root: root.to_path_buf(),
        tools: work.join("tools"),
        wheels: target.join("wheels"),
        work,
    };
    if args.test {
        // The PyO3 layer is behind the `python` feature, which the workspace's clippy
        // leaves off (it compiles PyO3); lint it here, where it is built.
        run(
            Command::new(crate::cargo())
                .args([
                    "clippy",
                    "--package",
                    "viewray-python",
                    "--features",
                    "python",
                ])
                .args(["--all-targets", "--", "-D", "warnings"])
                .current_dir(root),
            "lint the Python module with clippy",
        )?;
    }
    let started = Instant::now();
    install_tools(&paths)?;
    let wheel = build(&paths)?;
    let seconds = started.elapsed().as_secs();
    let tag = audit(&paths, &wheel)?;
    let size = std::fs::metadata(&wheel)?.len();
    println!(
        "built {} ({:.1} MB, {tag}) in {}m {:02}s",
        wheel.display(),
        size as f64 / 1e6,
        seconds / 60,
        seconds % 60
    );
    if args.test {
        test(&paths, &wheel)?;
    }
    Ok(())
}

/// Installs the pinned build tools into their virtual environment unless its stamp says
/// they are there.
fn install_tools(paths: &Paths) -> Result<()> {
    let stamp = paths.tools.join("installed.txt");
    let wanted = format!("{}\n", TOOLS.join(" "));
    if std::fs::read_to_string(&stamp).is_ok_and(|s| s == wanted) {
        return Ok(());
    }
    std::fs::create_dir_all(&paths.work)?;
    make_venv(&paths.tools)?;
    pip_install(&paths.tools, &TOOLS)?;
    std::fs::write(&stamp, wanted)?;
    Ok(())
}

/// A new virtual environment at `dir`, made by `$VIEWRAY_PYTHON` (default `python3`).
fn make_venv(dir: &Path) -> Result<()> {
    let python = std::env::var("VIEWRAY_PYTHON").unwrap_or_else(|_| "python3".to_owned());
    run(
        Command::new(&python)
            .args(["-m", "venv", "--clear"])
            .arg(dir),
        "create a Python virtual environment (Python 3.9 or newer: set VIEWRAY_PYTHON)",
    )
}

fn pip_install(venv: &Path, packages: &[&str]) -> Result<()> {
    run(
        Command::new(venv.join("bin/python"))
            .args(["-m", "pip", "install", "--quiet", "--progress-bar", "off"])
            .args(packages),
        &format!("install {} from PyPI", packages.join(", ")),
    )
}

/// Builds the command, then the wheel with the command in it; returns the wheel's path.
fn build(paths: &Paths) -> Result<PathBuf> {
    let python = paths.tools.join("bin/python");
    // maturin runs zig as `python -m ziglang` with the Python it finds first.
    let path = prepend_path(&paths.tools.join("bin"))?;

    let cli_wheels = paths.work.join("cli");
    remove_dir(&cli_wheels)?;
    run(
        Command::new(&python)
            .args([
                "-m",
                "maturin",
                "build",
                "--bindings",
                "bin",
                "--zig",
                "--strip",
            ])
            .args(["--compatibility", "manylinux2014", "--profile", "wheel"])
            .arg("--manifest-path")
            .arg(paths.root.join("crates/viewray/Cargo.toml"))
            .arg("--out")
            .arg(&cli_wheels)
            .env("PATH", &path)
            .current_dir(&paths.root),
        "build the viewray command with maturin",
    )?;
    let cli_wheel = only_wheel(&cli_wheels, "viewray-")?;

    let staged = Staged::command(paths, &cli_wheel)?;
    std::fs::create_dir_all(&paths.wheels)?;
    for old in wheels_in(&paths.wheels, "viewray-")? {
        std::fs::remove_file(&old).with_context(|| format!("cannot remove {}", old.display()))?;
    }
    run(
        Command::new(&python)
            .args(["-m", "maturin", "build", "--zig"])
            .arg("--manifest-path")
            .arg(paths.root.join(MODULE_CRATE).join("Cargo.toml"))
            .arg("--out")
            .arg(&paths.wheels)
            .env("PATH", &path)
            .current_dir(&paths.root),
        "build the viewray wheel with maturin",
    )?;
    drop(staged);
    remove_dir(&cli_wheels)?;
    only_wheel(&paths.wheels, "viewray-")
}

/// The command, put where maturin takes a wheel's scripts from for the time of the
/// module's build (`viewray.data/scripts/viewray` beside its `pyproject.toml`), and
/// removed again when dropped, whether the build worked or not.
struct Staged {
    data: PathBuf,
}

impl Staged {
    fn command(paths: &Paths, cli_wheel: &Path) -> Result<Staged> {
        let data = paths.root.join(MODULE_CRATE).join("viewray.data");
        remove_dir(&data)?;
        let scripts = data.join("scripts");
        std::fs::create_dir_all(&scripts)?;
        let staged = Staged { data };
        let binary = scripts.join("viewray");
        // The wheel is a zip file; Python (the tools' own) reads it.
        run(
            Command::new(paths.tools.join("bin/python"))
                .args([
                    "-c",
                    "import sys, zipfile\n\
                     wheel = zipfile.ZipFile(sys.argv[1])\n\
                     (name,) = [n for n in wheel.namelist() if n.endswith('.data/scripts/viewray')]\n\
                     open(sys.argv[2], 'wb').write(wheel.read(name))",
                ])
                .arg(cli_wheel)
                .arg(&binary),
            "take the viewray command out of its wheel",
        )?;
        set_executable(&binary)?;
        Ok(staged)
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        // Best effort: a folder left behind is ignored by git and replaced next time.
        let _ = std::fs::remove_dir_all(&self.data);
    }
}

#[cfg(unix)]
fn set_executable(path: &Path) -> Result<()> {
    use std::os::unix::fs::PermissionsExt;
    std::fs::set_permissions(path, std::fs::Permissions::from_mode(0o755))
        .with_context(|| format!("cannot make {} executable", path.display()))
}

#[cfg(not(unix))]
fn set_executable(_: &Path) -> Result<()> {
    Ok(())
}

/// Runs `auditwheel show` on the wheel and returns the platform tag it finds the wheel
/// consistent with.
///
/// # Errors
/// When auditwheel cannot run, or the tag needs a glibc newer than manylinux2014's.
fn audit(paths: &Paths, wheel: &Path) -> Result<String> {
    let output = Command::new(paths.tools.join("bin/python"))
        .args(["-m", "auditwheel", "show"])
        .arg(wheel)
        .output()
        .context("cannot run auditwheel")?;
    let text = String::from_utf8_lossy(&output.stdout);
    if !output.status.success() {
        bail!(
            "auditwheel show failed ({}): {}{}",
            output.status,
            text.trim(),
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    let tag = consistent_tag(&text)
        .with_context(|| format!("auditwheel show names no platform tag:\n{text}"))?;
    match glibc_minor(&tag) {
        Some(minor) if minor <= GLIBC_MINOR => Ok(tag),
        _ => bail!("the wheel is {tag}, newer than manylinux_2_{GLIBC_MINOR}:\n{text}"),
    }
}

/// The tag in auditwheel's `... is consistent with the following platform tag:
/// "manylinux_2_17_x86_64".`, a sentence it wraps at any space.
fn consistent_tag(text: &str) -> Option<String> {
    let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
    let after = &text[text.find("consistent with the following platform tag")?..];
    let start = after.find('"')? + 1;
    let end = start + after[start..].find('"')?;
    Some(after[start..end].to_owned())
}

/// The glibc minor version a manylinux tag needs: 17 for `manylinux_2_17_x86_64` and
/// its old name `manylinux2014_x86_64`.
fn glibc_minor(tag: &str) -> Option<u32> {
    let legacy = [
        ("manylinux1_", 5),
        ("manylinux2010_", 12),
        ("manylinux2014_", 17),
    ];
    if let Some((_, minor)) = legacy.iter().find(|(name, _)| tag.starts_with(name)) {
        return Some(*minor);
    }
    tag.strip_prefix("manylinux_2_")?
        .split('_')
        .next()?
        .parse()
        .ok()
}

/// Installs the wheel into a fresh virtual environment and runs the Python tests there;
/// the environment is removed when they pass.
fn test(paths: &Paths, wheel: &Path) -> Result<()> {
    let venv = paths.work.join("test-venv");
    make_venv(&venv)?;
    let wheel_text = wheel.to_str().context("the wheel's path is not UTF-8")?;
    let mut packages = vec![wheel_text];
    packages.extend(TEST_TOOLS);
    pip_install(&venv, &packages)?;
    let tests = paths.root.join(MODULE_CRATE).join("tests");
    // From an empty folder, so that nothing but the installed wheel can be imported.
    let scratch = paths.work.join("test-run");
    remove_dir(&scratch)?;
    std::fs::create_dir_all(&scratch)?;
    run(
        Command::new(venv.join("bin/python"))
            .args(["-m", "pytest", "-q", "-p", "no:cacheprovider"])
            .arg(&tests)
            .env("PATH", prepend_path(&venv.join("bin"))?)
            .current_dir(&scratch),
        "pass the Python tests of the installed wheel",
    )?;
    remove_dir(&scratch)?;
    remove_dir(&venv)
}

/// Why the wheel must be built: the first changed file among its inputs since the
/// merge base with `main`; `None` when none changed. Without a commit to compare with
/// (a clone of one commit), it is built.
fn changed_input(root: &Path) -> Result<Option<String>> {
    let Some(base) = base_commit(root)? else {
        return Ok(Some("no commit to compare with".to_owned()));
    };
    let metadata = cargo_metadata(root)?;
    let inputs = wheel_inputs(&metadata, root)?;
    let diff = git(root, &["diff", "--name-only", &base])?;
    Ok(diff
        .lines()
        .find(|file| inputs.iter().any(|input| is_within(file, input)))
        .map(|file| format!("{file} changed since {}", &base[..12])))
}

/// What the wheel is built and tested from, as paths relative to the workspace root:
/// the module's crate and every workspace crate it depends on (its normal and build
/// dependencies, through any depth), the workspace's `Cargo.toml` and `Cargo.lock`
/// (versions, profiles, and every dependency the command links), the fixtures its tests
/// read, and this task. Changes to the command's own crates alone do not rebuild it:
/// their tests are the command's.
fn wheel_inputs(metadata: &Value, root: &Path) -> Result<Vec<String>> {
    let mut inputs: Vec<String> = ["Cargo.toml", "Cargo.lock", "fixtures", "xtask/src/wheel.rs"]
        .map(str::to_owned)
        .to_vec();
    let packages = metadata["packages"]
        .as_array()
        .context("`cargo metadata` lists no packages")?;
    let dir_of = |name: &str| -> Option<PathBuf> {
        let package = packages.iter().find(|p| p["name"] == name)?;
        Some(
            Path::new(package["manifest_path"].as_str()?)
                .parent()?
                .to_path_buf(),
        )
    };
    let mut todo = vec!["viewray-python".to_owned()];
    let mut seen: Vec<String> = Vec::new();
    while let Some(name) = todo.pop() {
        if seen.contains(&name) {
            continue;
        }
        let dir = dir_of(&name).with_context(|| format!("no package {name} in the workspace"))?;
        let relative = dir.strip_prefix(root).unwrap_or(&dir);
        inputs.push(relative.to_string_lossy().into_owned());
        let package = packages.iter().find(|p| p["name"] == name.as_str());
        for dependency in package
            .and_then(|p| p["dependencies"].as_array())
            .into_iter()
            .flatten()
        {
            let path_dependency = dependency["path"].is_string();
            let for_tests = dependency["kind"] == "dev";
            if path_dependency
                && !for_tests
                && let Some(dependency) = dependency["name"].as_str()
            {
                todo.push(dependency.to_owned());
            }
        }
        seen.push(name);
    }
    Ok(inputs)
}

/// Whether the file `file` (relative, `/`-separated) is `input` or lies under it.
fn is_within(file: &str, input: &str) -> bool {
    file == input
        || file
            .strip_prefix(input)
            .is_some_and(|rest| rest.starts_with('/'))
}

/// `cargo metadata --no-deps`: the workspace's packages with their dependencies.
fn cargo_metadata(root: &Path) -> Result<Value> {
    let output = Command::new(crate::cargo())
        .args(["metadata", "--format-version", "1", "--no-deps"])
        .current_dir(root)
        .output()
        .context("cannot run `cargo metadata`")?;
    if !output.status.success() {
        bail!(
            "`cargo metadata` failed: {}",
            String::from_utf8_lossy(&output.stderr).trim()
        );
    }
    serde_json::from_slice(&output.stdout).context("`cargo metadata` printed no JSON")
}

/// `PATH` with `dir` first.
fn prepend_path(dir: &Path) -> Result<std::ffi::OsString> {
    let rest = std::env::var_os("PATH").unwrap_or_default();
    std::env::join_paths(std::iter::once(dir.to_path_buf()).chain(std::env::split_paths(&rest)))
        .context("a folder on PATH holds the path separator")
}

/// The wheels in `dir` whose file name starts with `prefix`.
fn wheels_in(dir: &Path, prefix: &str) -> Result<Vec<PathBuf>> {
    if !dir.exists() {
        return Ok(Vec::new());
    }
    let mut wheels = Vec::new();
    for entry in std::fs::read_dir(dir).with_context(|| format!("cannot read {}", dir.display()))? {
        let path = entry?.path();
        let name = path
            .file_name()
            .and_then(|n| n.to_str())
            .unwrap_or_default();
        if name.starts_with(prefix) && name.ends_with(".whl") {
            wheels.push(path);
        }
    }
    Ok(wheels)
}

/// The one wheel in `dir` whose name starts with `prefix`.
fn only_wheel(dir: &Path, prefix: &str) -> Result<PathBuf> {
    match wheels_in(dir, prefix)?.as_slice() {
        [wheel] => Ok(wheel.clone()),
        found => bail!(
            "expected one {prefix}*.whl in {}, found {}",
            dir.display(),
            found.len()
        ),
    }
}

fn remove_dir(dir: &Path) -> Result<()> {
    if dir.exists() {
        std::fs::remove_dir_all(dir).with_context(|| format!("cannot remove {}", dir.display()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tag_is_read_from_auditwheels_words() {
        // As auditwheel 6.8 prints it.
        let text = "\nviewray-0.1.0-cp39-abi3-manylinux_2_17_x86_64.whl\nis consistent with \
                    the following\nplatform tag: \"manylinux_2_17_x86_64\".\n\nThe wheel \
                    references external versioned symbols in these\nsystem-provided shared \
                    libraries: libc.so.6 with versions\n{'GLIBC_2.17'}\n\nThis constrains \
                    the platform tag to \"manylinux_2_17_x86_64\".";
        assert_eq!(
            consistent_tag(text).as_deref(),
            Some("manylinux_2_17_x86_64")
        );
        assert_eq!(consistent_tag("no tag here"), None);
        assert_eq!(glibc_minor("manylinux_2_17_x86_64"), Some(17));
        assert_eq!(glibc_minor("manylinux_2_5_x86_64"), Some(5));
        assert_eq!(glibc_minor("manylinux_2_28_x86_64"), Some(28));
        assert_eq!(glibc_minor("manylinux2014_x86_64"), Some(17));
        assert_eq!(glibc_minor("manylinux1_x86_64"), Some(5));
        assert_eq!(glibc_minor("linux_x86_64"), None);
    }

    #[test]
    fn the_inputs_are_the_modules_crates_by_path_not_by_test_dependencies() {
        let root = Path::new("/w");
        let metadata = serde_json::json!({"packages": [
            {"name": "viewray-python", "manifest_path": "/w/crates/viewray-python/Cargo.toml",
             "dependencies": [
                {"name": "viewray-render", "path": "/w/crates/viewray-render", "kind": null},
                {"name": "pyo3", "kind": null},
                {"name": "viewray-tests", "path": "/w/crates/viewray-tests", "kind": "dev"}]},
            {"name": "viewray-render", "manifest_path": "/w/crates/viewray-render/Cargo.toml",
             "dependencies": [
                {"name": "viewray-camera", "path": "/w/crates/viewray-camera", "kind": null},
                {"name": "viewray-scene", "path": "/w/crates/viewray-scene", "kind": "build"}]},
            {"name": "viewray-camera", "manifest_path": "/w/crates/viewray-camera/Cargo.toml",
             "dependencies": []},
            {"name": "viewray-scene", "manifest_path": "/w/crates/viewray-scene/Cargo.toml",
             "dependencies": [
                {"name": "viewray-camera", "path": "/w/crates/viewray-camera", "kind": null}]},
            {"name": "viewray-tests", "manifest_path": "/w/crates/viewray-tests/Cargo.toml",
             "dependencies": []},
            {"name": "viewray", "manifest_path": "/w/crates/viewray/Cargo.toml",
             "dependencies": []}
        ]});
        let mut inputs = wheel_inputs(&metadata, root).unwrap();
        inputs.sort();
        assert_eq!(
            inputs,
            [
                "Cargo.lock",
                "Cargo.toml",
                "crates/viewray-camera",
                "crates/viewray-python",
                "crates/viewray-render",
                "crates/viewray-scene",
                "fixtures",
                "xtask/src/wheel.rs"
            ]
        );
        assert!(is_within(
            "crates/viewray-render/src/lib.rs",
            "crates/viewray-render"
        ));
        assert!(is_within("Cargo.lock", "Cargo.lock"));
        assert!(!is_within(
            "crates/viewray-renderer/src/lib.rs",
            "crates/viewray-render"
        ));
        assert!(!is_within(
            "crates/viewray/src/main.rs",
            "crates/viewray-python"
        ));
    }

    #[test]
    fn this_workspaces_wheel_inputs_are_the_modules_crates_not_the_commands() {
        let root = crate::workspace_root();
        let inputs = wheel_inputs(&cargo_metadata(&root).unwrap(), &root).unwrap();
        for input in [
            "crates/viewray-python",
            "crates/viewray-scene",
            "crates/viewray-camera",
            "crates/viewray-render",
            "crates/viewray-geometry",
            "crates/viewray-output",
        ] {
            assert!(inputs.iter().any(|i| i == input), "{input}: {inputs:?}");
        }
        for not_input in ["crates/viewray", "crates/viewray-serve", "xtask"] {
            assert!(
                !inputs.iter().any(|i| i == not_input),
                "{not_input}: {inputs:?}"
            );
        }
    }
}
