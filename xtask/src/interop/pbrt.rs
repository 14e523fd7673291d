//! pbrt-v4's check: the export read back by viewray's importer.

use anyhow::Result;
use glam::DVec2;
use serde_json::json;
use viewray_interop::Format;

use super::cases::Case;
use super::export::Exported;
use super::report::{Report, Worst, import_camera, ray_error};

/// pbrt-v4 is not on any registry viewray may use: its files are checked by reading them
/// back (the hand-worked conventions are unit tests of viewray-interop).
pub(super) fn check(cases: &[Case], exported: &Exported, report: &mut Report) -> Result<()> {
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
    report.check(
        "pbrt-v4 (no registry package): export read back, rays",
        &worst,
    );
    Ok(())
}
