//! Blender's checks: its own projection (`world_to_camera_view`) of world points, Cycles'
//! rays for the panoramas, viewray's glTF imported by Blender, and Blender's glTF of the
//! export imported back.

use anyhow::Result;
use glam::DVec2;
use serde_json::{Value, json};
use viewray_interop::Format;

use super::Paths;
use super::cases::Case;
use super::export::Exported;
use super::install::script;
use super::report::{Report, Worst, image_error, import_camera, ray_error, size_of, vec3};

/// Exports Blender runs and checks against viewray.
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
                            .project(camera.frame().e() + d)
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
    report.check(
        "Blender: world_to_camera_view vs viewray project",
        &projections,
    );
    report.check(
        "Blender: Cycles ray directions (panoramas) vs viewray",
        &cycles,
    );
    report.check(
        "Blender: viewray glTF imported by Blender, projections",
        &gltf,
    );
    report.check(
        "Blender: Blender's glTF of the export, imported, rays",
        &round_trip,
    );
    Ok(())
}
