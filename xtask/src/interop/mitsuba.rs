//! Mitsuba 3's checks: its own rays (`sensor.sample_ray`, with lens samples for the thin
//! lens) and coverage (`scene.ray_intersect`) against viewray's, and the import of the
//! export and of XML Mitsuba itself writes.

use anyhow::Result;
use glam::DVec2;
use serde_json::{Value, json};
use viewray_interop::Format;

use super::Paths;
use super::cases::{Case, grid};
use super::export::Exported;
use super::install::script;
use super::report::{Report, Worst, coverage_error, import_camera, ray_error, size_of};

/// Exports Mitsuba 3 loads and checks against viewray.
///
/// # Errors
/// When the checker script cannot run or a file cannot be read.
pub(super) fn check(
    paths: &Paths,
    cases: &[Case],
    exported: &Exported,
    report: &mut Report,
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
    report.check("Mitsuba: sensor.sample_ray vs viewray rays", &rays);
    report.check("Mitsuba: thin-lens rays through lens samples", &lens_rays);
    report.check(
        "Mitsuba: import of the export vs Mitsuba's rays",
        &round_trip,
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
    report.check(
        "Mitsuba: import of Mitsuba-written XML vs its rays",
        &written_worst,
    );
    // Coverage: the share of pixels whose hit or miss differs, away from silhouettes.
    report.check(
        "Mitsuba: coverage (ray_intersect) vs viewray's tracer",
        &coverage,
    );
    Ok(())
}
