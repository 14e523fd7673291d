//! three.js's checks: its own `Vector3.project` of world points, the import of its
//! `toJSON` after loading the export, and of cameras made in three.js.

use std::path::Path;

use anyhow::Result;
use glam::{DVec2, DVec3};
use serde_json::{Value, json};
use viewray_interop::Format;

use super::Paths;
use super::cases::Case;
use super::export::Exported;
use super::install::script;
use super::report::{Report, Worst, image_error, import_camera, size_of, vec2};

/// Exports three.js loads and checks against viewray.
///
/// # Errors
/// When the checker script cannot run or a file cannot be read.
pub(super) fn check(
    paths: &Paths,
    cases: &[Case],
    exported: &Exported,
    report: &mut Report,
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
    report.check("three.js: Vector3.project vs viewray project", &projections);
    report.check(
        "three.js: import of toJSON after loading the export",
        &round_trip,
    );
    report.check("three.js: import of cameras made in three.js", &made_worst);
    Ok(())
}
