//! Measuring and reporting: the relative errors of a tool's rays and image points against
//! viewray's, the worst of each check, and the table of checks with its failures.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Result;
use glam::{DVec2, DVec3};
use serde_json::Value;
use viewray_camera::Camera;
use viewray_interop::Format;
use viewray_scene::{Scene, SceneLoader};

use super::TOLERANCE;

/// The largest error seen by one check, and where.
#[derive(Default)]
pub(super) struct Worst {
    error: f64,
    at: String,
    count: usize,
}

impl Worst {
    /// Counts one check of `error`, found `at`.
    pub(super) fn add(&mut self, error: f64, at: impl FnOnce() -> String) {
        self.count += 1;
        if error > self.error || error.is_nan() {
            self.error = error;
            self.at = at();
        }
    }
}

/// The table of checks, one line each, and the checks that failed.
#[derive(Default)]
pub(super) struct Report {
    table: String,
    failures: Vec<String>,
}

impl Report {
    /// Adds the line of the check `label`: it fails when nothing was checked, or the worst
    /// error is NaN or above [`TOLERANCE`].
    pub(super) fn check(&mut self, label: &str, worst: &Worst) {
        self.check_within(label, worst, TOLERANCE);
    }

    /// [`Report::check`] with a tolerance of its own (pixels, for pictures).
    pub(super) fn check_within(&mut self, label: &str, worst: &Worst, tolerance: f64) {
        let _ = writeln!(
            self.table,
            "{label:<58} {:>6} checks  max error {:.2e}  {}",
            worst.count, worst.error, worst.at
        );
        if worst.count == 0 || worst.error.is_nan() || worst.error > tolerance {
            self.failures.push(format!(
                "{label}: max error {:e} at {}",
                worst.error, worst.at
            ));
        }
    }

    /// The table, one line per check.
    pub(super) fn table(&self) -> &str {
        &self.table
    }

    /// The failed checks, one line each.
    pub(super) fn failures(&self) -> &[String] {
        &self.failures
    }
}

pub(super) fn vec3(v: &Value) -> Option<DVec3> {
    let a = v.as_array()?;
    Some(DVec3::new(
        a.first()?.as_f64()?,
        a.get(1)?.as_f64()?,
        a.get(2)?.as_f64()?,
    ))
}

pub(super) fn vec2(v: &Value) -> Option<DVec2> {
    let a = v.as_array()?;
    Some(DVec2::new(a.first()?.as_f64()?, a.get(1)?.as_f64()?))
}

/// The error of a tool's ray `(origin, direction)` against viewray's ray through the same
/// image point: directions compared as unit vectors, the origin by its distance from
/// viewray's line relative to the scene's scale.
pub(super) fn ray_error(camera: &Camera, image: DVec2, lens: DVec2, tool: &Value) -> f64 {
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

pub(super) fn image_error(expected: DVec2, tool: &Value, size: DVec2) -> f64 {
    match vec2(tool) {
        Some(p) => (p - expected).length() / size.max_element(),
        None => f64::INFINITY,
    }
}

pub(super) fn size_of(camera: &Camera) -> DVec2 {
    DVec2::new(f64::from(camera.width()), f64::from(camera.height()))
}

pub(super) fn import_camera(file: &Path, format: Format) -> Result<Camera> {
    let bytes = std::fs::read(file)?;
    let mut document =
        viewray_interop::import(&bytes, file, format).map_err(|e| anyhow::anyhow!("{e}"))?;
    // Only the camera is compared: the objects would only cost time to load.
    document.objects.clear();
    let scene = SceneLoader::text(&document.to_ron(), file)
        .load()
        .map_err(|e| anyhow::anyhow!("{e}"))?
        .scene;
    Ok(*scene.camera())
}

/// The share of pixels where Mitsuba's pixel-centre ray and viewray's disagree on
/// hitting anything, not counting pixels on a silhouette (a neighbour differs in
/// viewray's own mask): f32 against f64 ray setup may flip those.
pub(super) fn coverage_error(scene: &Scene, bits: &str) -> (f64, String) {
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
