//! `cargo xtask interop`: viewray's exports and imports checked against the real tools.
//!
//! Installs Mitsuba 3 and Blender's `bpy` from PyPI into a virtual environment under
//! `target/interop/venv` and three.js from npm into `target/interop/node_modules` (once;
//! the versions are pinned below), exports every fixture scene and a set of camera cases
//! to each tool, and compares:
//!
//! - Mitsuba's own rays (`sensor.sample_ray`, with lens samples for the thin lens) with
//!   viewray's at many image points, and Mitsuba's own coverage (`scene.ray_intersect` of
//!   its pixel-centre rays) with viewray's (its tracer on the same rays);
//! - Blender's own projection (`world_to_camera_view`) of world points with viewray's,
//!   and for the panoramas Cycles' own rays (a render of the ray direction);
//! - Cycles' picture of a defocused point light through a lens with blades with
//!   viewray's: the same polygon, orientation and size within a pixel (`bokeh.rs`);
//! - three.js's `Vector3.project` of world points with viewray's;
//! - imports, by round trips through each tool: Mitsuba-written XML (`mi.parser`),
//!   Blender's glTF of the exported scene, three.js's `toJSON` of the loaded scene and of
//!   cameras made in three.js, and viewray's glTF imported by Blender.
//!
//! Errors are relative: a unit direction's difference, an origin's distance from
//! viewray's ray over the eye's distance from the origin (at least 1), an image point's
//! difference over the image's larger side. Every one must be below 1e-5; the bokeh
//! pictures, Monte Carlo renders both, within a pixel.
//!
//! The parts: `install.rs` installs the tools and runs their checker scripts, `cases.rs`
//! makes the cases, `export.rs` writes them for every tool, `report.rs` measures the
//! errors and keeps the table; `mitsuba.rs`, `blender.rs`, `three.rs` and `pbrt.rs` hold
//! each tool's checks, `bokeh.rs` the pictures of a lens with blades.

mod blender;
mod bokeh;
mod cases;
mod export;
mod install;
mod mitsuba;
mod pbrt;
mod report;
mod three;

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, bail};

use self::report::Report;

/// The pinned tools: PyPI's mitsuba and bpy (bpy 5.0 is built for CPython 3.11), npm's
/// three.
const MITSUBA: &str = "mitsuba==3.9.1";
const BPY: &str = "bpy==5.0.1";
const THREE: &str = "three@0.187.0";

/// The largest relative error accepted.
const TOLERANCE: f64 = 1e-5;

/// Where the tools and the work files live.
struct Paths {
    /// The repository.
    root: PathBuf,
    /// `target/interop`.
    interop: PathBuf,
    /// The virtual environment's Python, with Mitsuba and bpy.
    python: PathBuf,
    /// three.js's module file.
    three: PathBuf,
    /// Where the exports, jobs and results go (cleared on each run).
    work: PathBuf,
}

/// The command line of `cargo xtask interop`.
#[derive(Debug, Default, clap::Args)]
pub struct InteropArgs {
    /// Only the cases whose name contains FILTER.
    pub filter: Option<String>,
}

/// Installs the tools (once), exports every case to them and compares their numbers
/// with viewray's; prints a table of the largest errors and the refused exports.
///
/// # Errors
/// When a tool cannot be installed or run, or any error is above 1e-5.
pub fn interop(root: &Path, args: &InteropArgs) -> Result<()> {
    let started = Instant::now();
    let interop = crate::target_dir(root)?.join("interop");
    let paths = Paths {
        root: root.to_path_buf(),
        python: interop.join("venv/bin/python"),
        three: interop.join("node_modules/three/build/three.module.js"),
        work: interop.join("work"),
        interop,
    };
    install::install(&paths)?;
    let installed = started.elapsed();
    if paths.work.exists() {
        std::fs::remove_dir_all(&paths.work)
            .with_context(|| format!("cannot clear {}", paths.work.display()))?;
    }
    std::fs::create_dir_all(&paths.work)?;
    let cases: Vec<cases::Case> = cases::cases(root)?
        .into_iter()
        .filter(|c| args.filter.as_deref().is_none_or(|f| c.name.contains(f)))
        .collect();
    eprintln!("{} cases", cases.len());

    // Export every case to every tool that can hold its camera.
    let (exported, refused) = export::export_all(&paths, &cases)?;

    let mut report = Report::default();
    let (mut mitsuba_time, mut blender_time, mut three_time) = Default::default();
    // A filter may select no camera case (only the bokeh pictures): then there is
    // nothing for these checks to count.
    if !cases.is_empty() {
        let timer = Instant::now();
        mitsuba::check(&paths, &cases, &exported, &mut report)?;
        mitsuba_time = timer.elapsed();
        let timer = Instant::now();
        blender::check(&paths, &cases, &exported, &mut report)?;
        blender_time = timer.elapsed();
        let timer = Instant::now();
        three::check(&paths, &cases, &exported, &mut report)?;
        three_time = timer.elapsed();
        pbrt::check(&cases, &exported, &mut report)?;
    }
    let timer = Instant::now();
    bokeh::check(&paths, args.filter.as_deref(), &mut report)?;
    blender_time += timer.elapsed();

    println!("{}", report.table());
    println!("cameras the tools cannot express (export refused):");
    for line in &refused {
        println!("  {line}");
    }
    println!(
        "time: install {:.1} s, Mitsuba {:.1} s, Blender {:.1} s, three.js {:.1} s, total {:.1} s",
        installed.as_secs_f64(),
        mitsuba_time.as_secs_f64(),
        blender_time.as_secs_f64(),
        three_time.as_secs_f64(),
        started.elapsed().as_secs_f64()
    );
    let failures = report.failures();
    if !failures.is_empty() {
        bail!(
            "{} interop checks failed:\n{}",
            failures.len(),
            failures.join("\n")
        );
    }
    Ok(())
}
