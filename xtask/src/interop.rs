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
//! - three.js's `Vector3.project` of world points with viewray's;
//! - imports, by round trips through each tool: Mitsuba-written XML (`mi.parser`),
//!   Blender's glTF of the exported scene, three.js's `toJSON` of the loaded scene and of
//!   cameras made in three.js, and viewray's glTF imported by Blender.
//!
//! Errors are relative: a unit direction's difference, an origin's distance from
//! viewray's ray over the eye's distance from the origin (at least 1), an image point's
//! difference over the image's larger side. Every one must be below 1e-5.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use glam::{DVec2, DVec3};
use serde_json::{Value, json};
use viewray_camera::Camera;
use viewray_interop::Format;
use viewray_scene::Scene;

/// The pinned tools: PyPI's mitsuba and bpy (bpy 5.0 is built for CPython 3.11), npm's
/// three.
const MITSUBA: &str = "mitsuba==3.9.1";
const BPY: &str = "bpy==5.0.1";
const THREE: &str = "three@0.187.0";

/// The largest relative error accepted.
const TOLERANCE: f64 = 1e-5;

/// Where the tools and the work files live.
struct Paths {
    root: PathBuf,
    interop: PathBuf,
    python: PathBuf,
    three: PathBuf,
    work: PathBuf,
}

/// The command line of `cargo xtask interop`.
#[derive(Debug, Default, clap::Args)]
pub struct InteropArgs {
    /// Only the cases whose name contains FILTER.
    pub filter: Option<String>,
}

/// A scene exported to the tools.
struct Case {
    name: String,
    scene: Scene,
    /// Image points `(x, y)` whose rays are compared.
    pixels: Vec<DVec2>,
    /// Lens samples for the thin lens, one per pixel.
    lens: Vec<DVec2>,
    /// World points and the image points where viewray sees them.
    points: Vec<(DVec3, DVec2)>,
    /// Whether Mitsuba's coverage is compared (scenes of fixtures/scenes/).
    coverage: bool,
}

/// The largest error seen by one check, and where.
#[derive(Default)]
struct Worst {
    error: f64,
    at: String,
    count: usize,
}

impl Worst {
    fn add(&mut self, error: f64, at: impl FnOnce() -> String) {
        self.count += 1;
        if error > self.error || error.is_nan() {
            self.error = error;
            self.at = at();
        }
    }
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
    install(&paths)?;
    let installed = started.elapsed();
    if paths.work.exists() {
        std::fs::remove_dir_all(&paths.work)
            .with_context(|| format!("cannot clear {}", paths.work.display()))?;
    }
    std::fs::create_dir_all(&paths.work)?;
    let cases: Vec<Case> = cases(root)?
        .into_iter()
        .filter(|c| args.filter.as_deref().is_none_or(|f| c.name.contains(f)))
        .collect();
    eprintln!("{} cases", cases.len());

    // Export every case to every tool that can hold its camera.
    let mut exported: BTreeMap<(String, Format), PathBuf> = BTreeMap::new();
    let mut refused: Vec<String> = Vec::new();
    for case in &cases {
        for format in Format::ALL {
            let extension = match format {
                Format::Mitsuba => "xml",
                Format::Pbrt => "pbrt",
                Format::Blender => "py",
                Format::Three => "json",
                Format::Gltf => "gltf",
            };
            let file = paths.work.join(format!("{}.{extension}", case.name));
            let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("scene");
            match viewray_interop::export(&case.scene, format, name) {
                Ok(export) => {
                    std::fs::write(&file, &export.main)?;
                    for (extra, bytes) in &export.extra_files {
                        std::fs::write(paths.work.join(extra), bytes)?;
                    }
                    exported.insert((case.name.clone(), format), file);
                }
                Err(e) => refused.push(format!("{:<40} {}", case.name, e)),
            }
        }
    }

    let mut report = String::new();
    let mut failures = Vec::new();
    let mut check = |label: &str, worst: &Worst, failures: &mut Vec<String>| {
        let _ = writeln!(
            report,
            "{label:<58} {:>6} checks  max error {:.2e}  {}",
            worst.count, worst.error, worst.at
        );
        if worst.count == 0 || worst.error.is_nan() || worst.error > TOLERANCE {
            failures.push(format!(
                "{label}: max error {:e} at {}",
                worst.error, worst.at
            ));
        }
    };

    let timer = Instant::now();
    mitsuba(&paths, &cases, &exported, &mut check, &mut failures)?;
    let mitsuba_time = timer.elapsed();
    let timer = Instant::now();
    blender(&paths, &cases, &exported, &mut check, &mut failures)?;
    let blender_time = timer.elapsed();
    let timer = Instant::now();
    three(&paths, &cases, &exported, &mut check, &mut failures)?;
    let three_time = timer.elapsed();
    pbrt(&cases, &exported, &mut check, &mut failures)?;

    println!("{report}");
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
    if !failures.is_empty() {
        bail!(
            "{} interop checks failed:\n{}",
            failures.len(),
            failures.join("\n")
        );
    }
    Ok(())
}

/// Installs the pinned tools under target/interop unless the stamp says they are there.
fn install(paths: &Paths) -> Result<()> {
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

fn run(command: &mut Command, what: &str) -> Result<()> {
    eprintln!("$ {command:?}");
    let status = command
        .status()
        .with_context(|| format!("could not {what}"))?;
    if !status.success() {
        bail!("could not {what} ({status})");
    }
    Ok(())
}

/// Runs a checker script on a job and reads its result.
fn script(paths: &Paths, program: &Path, args: &[&Path], name: &str, job: &Value) -> Result<Value> {
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

fn vec3(v: &Value) -> Option<DVec3> {
    let a = v.as_array()?;
    Some(DVec3::new(
        a.first()?.as_f64()?,
        a.get(1)?.as_f64()?,
        a.get(2)?.as_f64()?,
    ))
}

fn vec2(v: &Value) -> Option<DVec2> {
    let a = v.as_array()?;
    Some(DVec2::new(a.first()?.as_f64()?, a.get(1)?.as_f64()?))
}

/// The error of a tool's ray `(origin, direction)` against viewray's ray through the same
/// image point: directions compared as unit vectors, the origin by its distance from
/// viewray's line relative to the scene's scale.
fn ray_error(camera: &Camera, image: DVec2, lens: DVec2, tool: &Value) -> f64 {
    let Some(ours) = camera.generate_ray_through(image, lens) else {
        return f64::INFINITY;
    };
    let (Some(origin), Some(direction)) = (vec3(&tool[0]), vec3(&tool[1])) else {
        return f64::INFINITY;
    };
    let d = ours.direction.normalize();
    let direction_error = (direction.normalize() - d).length();
    let offset = origin - ours.origin;
    let off_line = (offset - offset.dot(d) * d).length();
    let scale = ours.origin.length().max(1.0);
    direction_error.max(off_line / scale)
}

fn image_error(expected: DVec2, tool: &Value, size: DVec2) -> f64 {
    match vec2(tool) {
        Some(p) => (p - expected).length() / size.max_element(),
        None => f64::INFINITY,
    }
}

fn size_of(camera: &Camera) -> DVec2 {
    DVec2::new(f64::from(camera.width()), f64::from(camera.height()))
}

fn import_camera(file: &Path, format: Format) -> Result<Camera> {
    let bytes = std::fs::read(file)?;
    let mut document =
        viewray_interop::import(&bytes, file, format).map_err(|e| anyhow::anyhow!("{e}"))?;
    // Only the camera is compared: the objects would only cost time to load.
    document.objects.clear();
    let scene = viewray_scene::SceneLoader::text(&document.to_ron(), file)
        .load()
        .map_err(|e| anyhow::anyhow!("{e}"))?
        .scene;
    Ok(*scene.camera())
}

type Check<'a> = dyn FnMut(&str, &Worst, &mut Vec<String>) + 'a;

fn mitsuba(
    paths: &Paths,
    cases: &[Case],
    exported: &BTreeMap<(String, Format), PathBuf>,
    check: &mut Check<'_>,
    failures: &mut Vec<String>,
) -> Result<()> {
    let mut job_cases = Vec::new();
    for case in cases {
        let Some(file) = exported.get(&(case.name.clone(), Format::Mitsuba)) else {
            continue;
        };
        let camera = case.scene.camera();
        let lens = matches!(camera.projection(), viewray_camera::Projection::ThinLens(_));
        job_cases.push(json!({
            "name": case.name, "file": file,
            "pixels": case.pixels.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
            "lens": lens.then(|| case.lens.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>()),
            "coverage": case.coverage.then(|| [camera.width(), camera.height()]),
        }));
    }
    // Scenes Mitsuba itself writes, for the importer.
    let pixels: Vec<[f64; 2]> = grid(DVec2::new(40.0, 30.0))
        .iter()
        .map(|p| [p.x, p.y])
        .collect();
    let look_at = json!([[1.0, 2.0, 3.0], [0.0, 0.5, 0.0], [0.0, 1.0, 0.0]]);
    let film = json!({ "type": "hdrfilm", "width": 40, "height": 30 });
    let portrait = json!({ "type": "hdrfilm", "width": 30, "height": 40 });
    let written_cases = [
        (
            "fov_x",
            json!({ "type": "perspective", "fov": 50, "fov_axis": "x", "film": film }),
        ),
        (
            "fov_y",
            json!({ "type": "perspective", "fov": 40, "fov_axis": "y", "film": film }),
        ),
        (
            "fov_diagonal",
            json!({ "type": "perspective", "fov": 60, "fov_axis": "diagonal", "film": film }),
        ),
        (
            "fov_smaller_portrait",
            json!({ "type": "perspective", "fov": 45, "fov_axis": "smaller", "film": portrait }),
        ),
        (
            "fov_larger_portrait",
            json!({ "type": "perspective", "fov": 55, "fov_axis": "larger", "film": portrait }),
        ),
        (
            "focal_length_35mm",
            json!({ "type": "perspective", "focal_length": "35mm", "film": film }),
        ),
        (
            "principal_point",
            json!({ "type": "perspective", "fov": 45, "principal_point_offset_x": 0.1, "principal_point_offset_y": -0.2, "film": film }),
        ),
        (
            "thinlens",
            json!({ "type": "thinlens", "fov": 45, "aperture_radius": 0.1, "focus_distance": 4.0, "film": film }),
        ),
        (
            "orthographic_scaled",
            json!({ "type": "orthographic", "scale": [2.0, 1.5, 1.0], "film": film }),
        ),
    ];
    let written: Vec<Value> = written_cases
        .iter()
        .map(|(name, sensor)| {
            let mut sensor = sensor.clone();
            sensor["look_at"] = look_at.clone();
            let film_size = if sensor["film"]["width"] == 30 {
                DVec2::new(30.0, 40.0)
            } else {
                DVec2::new(40.0, 30.0)
            };
            json!({
                "name": name, "out": paths.work.join(format!("mitsuba-written-{name}.xml")),
                "dict": { "type": "scene", "sensor": sensor },
                "pixels": grid(film_size).iter().map(|p| [p.x, p.y]).collect::<Vec<_>>(),
            })
        })
        .collect();
    let _ = pixels;
    let result = script(
        paths,
        &paths.python,
        &[&paths.root.join("xtask/interop/mitsuba_check.py")],
        "mitsuba",
        &json!({ "cases": job_cases, "written": written }),
    )?;

    let (mut rays, mut lens_rays, mut coverage, mut round_trip) = (
        Worst::default(),
        Worst::default(),
        Worst::default(),
        Worst::default(),
    );
    for case in cases {
        let Some(entry) = result["cases"].get(&case.name) else {
            continue;
        };
        let camera = case.scene.camera();
        let imported = import_camera(
            &exported[&(case.name.clone(), Format::Mitsuba)],
            Format::Mitsuba,
        )?;
        for (i, &p) in case.pixels.iter().enumerate() {
            let tool = &entry["rays"][i];
            rays.add(ray_error(camera, p, DVec2::splat(0.5), tool), || {
                format!("{} pixel {p}", case.name)
            });
            round_trip.add(ray_error(&imported, p, DVec2::splat(0.5), tool), || {
                format!("{} pixel {p}", case.name)
            });
            if let Some(lens) = entry.get("lens_rays") {
                lens_rays.add(ray_error(camera, p, case.lens[i], &lens[i]), || {
                    format!("{} pixel {p} lens {}", case.name, case.lens[i])
                });
            }
        }
        if let Some(bits) = entry.get("coverage").and_then(Value::as_str) {
            let (error, at) = coverage_error(&case.scene, bits);
            coverage.add(error, || format!("{} {at}", case.name));
        }
    }
    check(
        "Mitsuba: sensor.sample_ray vs viewray rays",
        &rays,
        failures,
    );
    check(
        "Mitsuba: thin-lens rays through lens samples",
        &lens_rays,
        failures,
    );
    check(
        "Mitsuba: import of the export vs Mitsuba's rays",
        &round_trip,
        failures,
    );
    let mut written_worst = Worst::default();
    for (name, _) in &written_cases {
        let file = paths.work.join(format!("mitsuba-written-{name}.xml"));
        let camera = import_camera(&file, Format::Mitsuba)?;
        let size = size_of(&camera);
        for (i, p) in grid(size).iter().enumerate() {
            let tool = &result["written"][name]["rays"][i];
            written_worst.add(ray_error(&camera, *p, DVec2::splat(0.5), tool), || {
                format!("{name} pixel {p}")
            });
        }
    }
    check(
        "Mitsuba: import of Mitsuba-written XML vs its rays",
        &written_worst,
        failures,
    );
    // Coverage: the share of pixels whose hit or miss differs, away from silhouettes.
    let _ = writeln!(String::new());
    check(
        "Mitsuba: coverage (ray_intersect) vs viewray's tracer",
        &coverage,
        failures,
    );
    Ok(())
}

/// The share of pixels where Mitsuba's pixel-centre ray and viewray's disagree on
/// hitting anything, not counting pixels on a silhouette (a neighbour differs in
/// viewray's own mask): f32 against f64 ray setup may flip those.
fn coverage_error(scene: &Scene, bits: &str) -> (f64, String) {
    let camera = scene.camera();
    let (w, h) = (camera.width() as usize, camera.height() as usize);
    let ours: Vec<bool> = (0..h)
        .flat_map(|row| (0..w).map(move |col| (row, col)))
        .map(|(row, col)| {
            camera
                .generate_ray(row as u32, col as u32, viewray_camera::CameraSample::CENTER)
                .is_some_and(|ray| {
                    scene
                        .world()
                        .closest_hit(&ray.as_ray(), 0.0..f32::INFINITY)
                        .is_some()
                })
        })
        .collect();
    let theirs: Vec<bool> = bits.bytes().map(|b| b == b'1').collect();
    if theirs.len() != ours.len() {
        return (f64::INFINITY, "sizes differ".to_owned());
    }
    let mut differ = 0;
    let mut first = String::new();
    for row in 0..h {
        for col in 0..w {
            let i = row * w + col;
            if ours[i] == theirs[i] {
                continue;
            }
            let silhouette = [(-1i64, 0i64), (1, 0), (0, -1), (0, 1)]
                .iter()
                .any(|(dr, dc)| {
                    let (r, c) = (row as i64 + dr, col as i64 + dc);
                    r >= 0
                        && c >= 0
                        && (r as usize) < h
                        && (c as usize) < w
                        && ours[r as usize * w + c as usize] != ours[i]
                });
            if !silhouette {
                differ += 1;
                if first.is_empty() {
                    first = format!("pixel ({row}, {col})");
                }
            }
        }
    }
    (f64::from(differ) / (w * h) as f64, first)
}

fn blender(
    paths: &Paths,
    cases: &[Case],
    exported: &BTreeMap<(String, Format), PathBuf>,
    check: &mut Check<'_>,
    failures: &mut Vec<String>,
) -> Result<()> {
    let mut job = Vec::new();
    for case in cases {
        let points: Vec<[f64; 3]> = case.points.iter().map(|(p, _)| p.to_array()).collect();
        let camera = case.scene.camera();
        if let Some(script) = exported.get(&(case.name.clone(), Format::Blender)) {
            let panorama = camera.projection().viewport().is_none();
            // Blender's glTF can hold only what glTF can: round trips of those cameras.
            let gltf_can = exported.contains_key(&(case.name.clone(), Format::Gltf));
            let glb = paths.work.join(format!("{}-blender.glb", case.name));
            job.push(json!({
                "name": format!("{}/script", case.name), "script": script,
                "size": [camera.width(), camera.height()],
                "points": if panorama { Vec::new() } else { points.clone() },
                "render": panorama,
                "render_path": paths.work.join(format!("{}-cycles.exr", case.name)),
                "export_glb": (!panorama && gltf_can).then_some(glb),
            }));
        }
        if let Some(gltf) = exported.get(&(case.name.clone(), Format::Gltf)) {
            // glTF's aspectRatio against the image's: Blender renders that with non-square
            // pixels.
            let viewport = camera.projection().viewport().unwrap_or(DVec2::ONE);
            let (x, y) = (
                viewport.x / f64::from(camera.width()),
                viewport.y / f64::from(camera.height()),
            );
            let pixel_aspect = if x >= y { [x / y, 1.0] } else { [1.0, y / x] };
            job.push(json!({
                "name": format!("{}/gltf", case.name), "gltf": gltf,
                "size": [camera.width(), camera.height()], "pixel_aspect": pixel_aspect,
                "points": points,
            }));
        }
    }
    let result = script(
        paths,
        &paths.python,
        &[&paths.root.join("xtask/interop/blender_check.py")],
        "blender",
        &json!({ "cases": job }),
    )?;
    let (mut projections, mut gltf, mut cycles, mut round_trip) = (
        Worst::default(),
        Worst::default(),
        Worst::default(),
        Worst::default(),
    );
    for case in cases {
        let camera = case.scene.camera();
        let size = size_of(camera);
        if let Some(entry) = result.get(format!("{}/script", case.name)) {
            for (i, (p, image)) in case.points.iter().enumerate() {
                if let Some(tool) = entry["points"].get(i) {
                    projections.add(image_error(*image, tool, size), || {
                        format!("{} point {p}", case.name)
                    });
                }
            }
            if let Some(directions) = entry.get("directions").and_then(Value::as_array) {
                // Cycles' ray direction in each pixel, placed by viewray's projection: it
                // must land in that pixel's centre (Cycles' narrowest pixel filter moves
                // a sample by at most 0.005 px).
                let (w, h) = (camera.width(), camera.height());
                for row in 0..h {
                    for col in 0..w {
                        let Some(d) = directions.get((row * w + col) as usize).and_then(vec3)
                        else {
                            continue;
                        };
                        let centre = DVec2::new(f64::from(col) + 0.5, f64::from(row) + 0.5);
                        if camera
                            .generate_ray_through(centre, DVec2::splat(0.5))
                            .is_none()
                        {
                            continue;
                        }
                        let seen = camera
                            .project(camera.frame().e + d)
                            .map_or(Value::Null, |q| json!([q.x, q.y]));
                        cycles.add(image_error(centre, &seen, size), || {
                            format!("{} pixel ({row}, {col})", case.name)
                        });
                    }
                }
            }
            let glb = paths.work.join(format!("{}-blender.glb", case.name));
            if glb.exists() {
                let imported = import_camera(&glb, Format::Gltf)?;
                for &p in &case.pixels {
                    let Some(ray) = imported
                        .generate_ray_through(p * size_of(&imported) / size, DVec2::splat(0.5))
                    else {
                        continue;
                    };
                    let tool = json!([ray.origin.to_array(), ray.direction.to_array()]);
                    round_trip.add(ray_error(camera, p, DVec2::splat(0.5), &tool), || {
                        format!("{} pixel {p}", case.name)
                    });
                }
            }
        }
        if let Some(entry) = result.get(format!("{}/gltf", case.name)) {
            for (i, (p, image)) in case.points.iter().enumerate() {
                if let Some(tool) = entry["points"].get(i) {
                    gltf.add(image_error(*image, tool, size), || {
                        format!("{} point {p}", case.name)
                    });
                }
            }
        }
    }
    check(
        "Blender: world_to_camera_view vs viewray project",
        &projections,
        failures,
    );
    check(
        "Blender: Cycles ray directions (panoramas) vs viewray",
        &cycles,
        failures,
    );
    check(
        "Blender: viewray glTF imported by Blender, projections",
        &gltf,
        failures,
    );
    check(
        "Blender: Blender's glTF of the export, imported, rays",
        &round_trip,
        failures,
    );
    Ok(())
}

fn three(
    paths: &Paths,
    cases: &[Case],
    exported: &BTreeMap<(String, Format), PathBuf>,
    check: &mut Check<'_>,
    failures: &mut Vec<String>,
) -> Result<()> {
    let mut job = Vec::new();
    for case in cases {
        let Some(file) = exported.get(&(case.name.clone(), Format::Three)) else {
            continue;
        };
        job.push(json!({
            "name": case.name, "file": file,
            "points": case.points.iter().map(|(p, _)| p.to_array()).collect::<Vec<_>>(),
            "roundtrip": paths.work.join(format!("{}-three-roundtrip.json", case.name)),
        }));
    }
    let points: Vec<DVec3> = vec![
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(-1.0, 0.5, 2.0),
        DVec3::new(0.3, -0.7, -1.5),
        DVec3::new(2.0, 0.1, -0.4),
    ];
    let made_cameras = [
        (
            "perspective_view_offset",
            json!({ "type": "perspective", "fov": 40, "aspect": 1.5, "view": [600, 400, 30, -20, 600, 400], "position": [3, 2, 5], "up": [0, 1, 0], "target": [0, 0, 0] }),
        ),
        (
            "perspective_zoom_film_offset",
            json!({ "type": "perspective", "fov": 55, "aspect": 0.75, "zoom": 1.3, "filmOffset": 3, "view": [300, 400, 0, 0, 300, 400], "position": [-2, 1, 4], "up": [0, 1, 0], "target": [0.5, 0, 0], "inScene": true }),
        ),
        (
            "perspective_no_view",
            json!({ "type": "perspective", "fov": 50, "aspect": 1.25, "position": [1, 3, 4], "up": [0, 1, 0], "target": [0, 0, 0] }),
        ),
        (
            "orthographic_zoom",
            json!({ "type": "orthographic", "left": -2, "right": 3, "top": 1.5, "bottom": -1, "near": 0.5, "zoom": 2, "view": [500, 250, 0, 0, 500, 250], "position": [2, 2, 6], "up": [0, 1, 0], "target": [0, 0, 0] }),
        ),
    ];
    let made: Vec<Value> = made_cameras
        .iter()
        .map(|(name, camera)| {
            json!({
                "name": name, "camera": camera,
                "out": paths.work.join(format!("three-made-{name}.json")),
                "points": points.iter().map(|p| p.to_array()).collect::<Vec<_>>(),
            })
        })
        .collect();
    let result = script(
        paths,
        Path::new("node"),
        &[
            &paths.root.join("xtask/interop/three_check.mjs"),
            &paths.three,
        ],
        "three",
        &json!({ "cases": job, "made": made }),
    )?;
    let (mut projections, mut round_trip, mut made_worst) =
        (Worst::default(), Worst::default(), Worst::default());
    for case in cases {
        let Some(entry) = result["cases"].get(&case.name) else {
            continue;
        };
        let size = size_of(case.scene.camera());
        let imported = import_camera(
            &paths
                .work
                .join(format!("{}-three-roundtrip.json", case.name)),
            Format::Three,
        )?;
        for (i, (p, image)) in case.points.iter().enumerate() {
            projections.add(image_error(*image, &entry["points"][i], size), || {
                format!("{} point {p}", case.name)
            });
            let ours = imported
                .project(*p)
                .map_or(Value::Null, |q| json!([q.x, q.y]));
            round_trip.add(image_error(*image, &ours, size), || {
                format!("{} point {p}", case.name)
            });
        }
    }
    for (name, _) in &made_cameras {
        let camera = import_camera(
            &paths.work.join(format!("three-made-{name}.json")),
            Format::Three,
        )?;
        let entry = &result["made"][name];
        let size = vec2(&entry["size"]).unwrap_or(DVec2::ONE);
        for (i, p) in points.iter().enumerate() {
            let tool = &entry["points"][i];
            let Some(theirs) = vec2(tool) else { continue };
            // The imported image may be a different size (a camera with no view gets
            // 480 rows): compare in units of the image.
            let ours = camera.project(*p).map(|q| q / size_of(&camera) * size);
            let ours = ours.map_or(Value::Null, |q| json!([q.x, q.y]));
            made_worst.add(image_error(theirs, &ours, size), || {
                format!("{name} point {p}")
            });
        }
    }
    check(
        "three.js: Vector3.project vs viewray project",
        &projections,
        failures,
    );
    check(
        "three.js: import of toJSON after loading the export",
        &round_trip,
        failures,
    );
    check(
        "three.js: import of cameras made in three.js",
        &made_worst,
        failures,
    );
    Ok(())
}

/// pbrt-v4 is not on any registry viewray may use: its files are checked by reading them
/// back (the hand-worked conventions are unit tests of viewray-interop).
fn pbrt(
    cases: &[Case],
    exported: &BTreeMap<(String, Format), PathBuf>,
    check: &mut Check<'_>,
    failures: &mut Vec<String>,
) -> Result<()> {
    let mut worst = Worst::default();
    for case in cases {
        let Some(file) = exported.get(&(case.name.clone(), Format::Pbrt)) else {
            continue;
        };
        let imported = import_camera(file, Format::Pbrt)?;
        for &p in &case.pixels {
            let Some(ray) = imported.generate_ray_through(p, DVec2::splat(0.5)) else {
                continue;
            };
            let tool = json!([ray.origin.to_array(), ray.direction.to_array()]);
            worst.add(
                ray_error(case.scene.camera(), p, DVec2::splat(0.5), &tool),
                || format!("{} pixel {p}", case.name),
            );
        }
    }
    check(
        "pbrt-v4 (no registry package): export read back, rays",
        &worst,
        failures,
    );
    Ok(())
}

/// Image points spread over an image of `size`: a 9 x 7 grid from corner to corner and the
/// pixel centres of the corners.
fn grid(size: DVec2) -> Vec<DVec2> {
    let mut out = Vec::new();
    for j in 0..7 {
        for i in 0..9 {
            out.push(DVec2::new(f64::from(i) / 8.0, f64::from(j) / 6.0) * size);
        }
    }
    out.extend([
        DVec2::new(0.5, 0.5),
        DVec2::new(size.x - 0.5, 0.5),
        DVec2::new(0.5, size.y - 0.5),
        DVec2::new(size.x - 0.5, size.y - 0.5),
    ]);
    out
}

/// The fixture scenes and camera cases for the conventions no fixture covers.
fn cases(root: &Path) -> Result<Vec<Case>> {
    let mut scenes: Vec<(String, Scene, bool)> = Vec::new();
    let mut files: Vec<PathBuf> = std::fs::read_dir(root.join("fixtures/scenes"))?
        .map(|e| e.map(|e| e.path()))
        .collect::<Result<_, _>>()?;
    files.sort();
    for file in files
        .iter()
        .filter(|f| f.extension().is_some_and(|e| e == "ron"))
    {
        let name = file
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("scene")
            .to_owned();
        let scene = viewray_scene::SceneLoader::file(file)
            .load()
            .map_err(|e| anyhow::anyhow!("{e}"))?
            .scene;
        scenes.push((name, scene, true));
    }
    let world = format!(
        "background: (0.5, 0.6, 0.8),
         materials: {{ \"red\": (color: (0.8, 0.1, 0.1)), \"grey\": (color: (0.6, 0.6, 0.6)) }},
         lights: [Point(position: (3.0, 5.0, 4.0), intensity: (20.0, 20.0, 20.0)), Ambient(intensity: (0.1, 0.1, 0.1))],
         objects: [
             Plane(point: (0.0, -1.0, 0.0), normal: (0.0, 1.0, 0.0), material: \"grey\"),
             Sphere(center: (0.0, 0.0, 0.0), radius: 1.0, material: \"red\"),
             Box(min: (1.5, -1.0, -1.0), max: (2.5, 0.5, 0.0)),
             Triangle(a: (-2.5, -1.0, 0.5), b: (-1.5, -1.0, 0.5), c: (-2.0, 0.5, 0.5)),
             Mesh(path: \"{}\", transform: (translate: (-1.0, -0.5, -2.0), rotate: (0.0, 30.0, 0.0), scale: 0.5)),
         ]",
        root.join("fixtures/meshes/cube.obj").display()
    );
    let cameras = [
        ("fov_x", 64, 48, "Perspective(fov_x: 50.0)"),
        (
            "fov_diagonal_portrait",
            48,
            64,
            "Perspective(fov_diagonal: 60.0)",
        ),
        ("fov_smaller", 64, 40, "Perspective(fov_smaller: 35.0)"),
        (
            "physical_vertical",
            64,
            36,
            "Perspective(focal_length: 35.0, sensor: (36.0, 24.0), fit: Vertical)",
        ),
        (
            "physical_auto_portrait",
            36,
            64,
            "Perspective(focal_length: 50.0)",
        ),
        (
            "shift",
            64,
            48,
            "Perspective(fov_y: 40.0, shift: (0.1, -0.25))",
        ),
        (
            "non_square_pixels",
            64,
            48,
            "Perspective(distance: 1.0, viewport: (2.0, 1.0))",
        ),
        (
            "non_square_pixels_shift",
            40,
            60,
            "Perspective(distance: 2.0, viewport: (1.0, 3.0), shift: (0.3, 0.2))",
        ),
        (
            "thin_lens_f_number",
            64,
            48,
            "ThinLens(focal_length: 50.0, f_number: 2.8, focus: 6.0)",
        ),
        (
            "thin_lens_shift",
            64,
            48,
            "ThinLens(fov_y: 40.0, shift: (0.05, 0.1), aperture: 0.1, focus: 6.0)",
        ),
        ("orthographic", 64, 48, "Orthographic(height: 6.0)"),
        (
            "orthographic_non_square",
            64,
            48,
            "Orthographic(viewport: (8.0, 3.0))",
        ),
        (
            "orthographic_lens",
            64,
            48,
            "Orthographic(viewport: (8.0, 6.0), aperture: 0.2, focus: 5.0)",
        ),
        (
            "oblique",
            64,
            48,
            "Oblique(height: 6.0, ratio: 0.5, angle: 30.0)",
        ),
        ("equirectangular", 64, 32, "Equirectangular"),
        ("fisheye_square", 48, 48, "Fisheye(fov: 200.0)"),
        ("fisheye_wide", 64, 48, "Fisheye(fov: 180.0)"),
    ];
    for (name, width, height, projection) in cameras {
        let text = format!(
            "(image: (width: {width}, height: {height}, samples: 4),
              camera: (eye: (1.5, 1.2, 6.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), projection: {projection}),
              {world})"
        );
        let scene = viewray_scene::SceneLoader::text(&text, &root.join(format!("{name}.ron")))
            .load()
            .map(|loaded| loaded.scene)
            .map_err(|e| anyhow::anyhow!("{name}: {e}"))?;
        scenes.push((format!("camera_{name}"), scene, true));
    }
    Ok(scenes
        .into_iter()
        .map(|(name, scene, coverage)| {
            let camera = scene.camera();
            let size = size_of(camera);
            let pixels = grid(size);
            let lens: Vec<DVec2> = (0..pixels.len())
                .map(|i| {
                    let t = i as f64 * 0.618_033_988_749_895;
                    DVec2::new(t.fract(), (t * 1.7).fract().mul_add(0.98, 0.01))
                })
                .collect();
            let mut points = Vec::new();
            for &p in &pixels {
                let Some(ray) = camera.generate_ray_through(p, DVec2::splat(0.5)) else {
                    continue;
                };
                // Points 1, 3 and 10 units along the ray: far enough from the eye that
                // single-precision tools resolve them.
                for distance in [1.0, 3.0, 10.0] {
                    let world = ray.at(distance / ray.direction.length());
                    if let Some(image) = camera.project(world) {
                        points.push((world, image));
                    }
                }
            }
            Case {
                name,
                scene,
                pixels,
                lens,
                points,
                coverage,
            }
        })
        .collect())
}
