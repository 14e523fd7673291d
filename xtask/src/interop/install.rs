//! The tools: installed once under `target/interop` at the pinned versions, and their
//! checker scripts run on a job file.

use std::path::Path;
use std::process::Command;

use anyhow::{Context, Result, bail};
use serde_json::Value;

use crate::run;

use super::{BPY, MITSUBA, Paths, THREE};

/// Installs the pinned tools under target/interop unless the stamp says they are there.
pub(super) fn install(paths: &Paths) -> Result<()> {
    let stamp = paths.interop.join("installed.txt");
    let wanted = format!("{MITSUBA} {BPY} {THREE}\n");
    if std::fs::read_to_string(&stamp).is_ok_and(|s| s == wanted)
        && paths.python.exists()
        && paths.three.exists()
    {
        return Ok(());
    }
    std::fs::create_dir_all(&paths.interop)?;
    let python = std::env::var("VIEWRAY_PYTHON").unwrap_or_else(|_| "python3.11".to_owned());
    if !paths.python.exists() {
        run(
            Command::new(&python)
                .args(["-m", "venv"])
                .arg(paths.interop.join("venv")),
            "create the Python environment (bpy needs CPython 3.11: set VIEWRAY_PYTHON)",
        )?;
    }
    run(
        Command::new(&paths.python).args([
            "-m",
            "pip",
            "install",
            "--quiet",
            "--progress-bar",
            "off",
            MITSUBA,
            BPY,
        ]),
        "install Mitsuba 3 and bpy from PyPI",
    )?;
    run(
        Command::new("npm")
            .args(["install", "--silent", "--no-audit", "--no-fund", "--prefix"])
            .arg(&paths.interop)
            .arg(THREE),
        "install three.js from npm",
    )?;
    std::fs::write(&stamp, wanted)?;
    Ok(())
}

/// Runs a checker script on a job and reads its result.
pub(super) fn script(
    paths: &Paths,
    program: &Path,
    args: &[&Path],
    name: &str,
    job: &Value,
) -> Result<Value> {
    let job_file = paths.work.join(format!("{name}-job.json"));
    let result_file = paths.work.join(format!("{name}-result.json"));
    std::fs::write(&job_file, serde_json::to_vec_pretty(job)?)?;
    let log = paths.work.join(format!("{name}.log"));
    let mut command = Command::new(program);
    command
        .args(args)
        .arg(&job_file)
        .arg(&result_file)
        .current_dir(&paths.work)
        .stdout(std::fs::File::create(&log)?)
        .stderr(std::fs::File::create(
            paths.work.join(format!("{name}.err")),
        )?);
    let status = command
        .status()
        .with_context(|| format!("could not run {name}"))?;
    if !status.success() {
        let err =
            std::fs::read_to_string(paths.work.join(format!("{name}.err"))).unwrap_or_default();
        let tail: Vec<&str> = err.lines().rev().take(15).collect();
        bail!(
            "{name} failed ({status}):\n{}",
            tail.into_iter().rev().collect::<Vec<_>>().join("\n")
        );
    }
    Ok(serde_json::from_slice(&std::fs::read(&result_file)?)?)
}
