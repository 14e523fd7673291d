//! Blades checked against Cycles itself: a defocused point light seen through a lens with
//! blades, rendered by Cycles (through viewray's Blender export) and by viewray, must show
//! the same polygon, turned the same way, of the same size.
//!
//! Each case is one small lamp well beyond (or well before) the plane of focus, alone on
//! a black background: its picture is the aperture's polygon, scaled (and turned half a
//! turn where the lamp is nearer than the plane of focus), blurred by the lamp's own small
//! disc. viewray renders it with `Flat` shading; Cycles with the lamp's colour as pure
//! emission, through its narrowest pixel filter. Both pictures are measured alike
//! ([`Profile::of`]): the centroid of the light, the plateau intensity inside, and from
//! the centroid in every whole degree the radial extent
//!
//! ```text
//! e(theta) = (integral of the intensity along the ray from the centroid) / plateau
//! ```
//!
//! which is the distance to a straight edge however the edge is blurred. The pictures
//! agree when the centroids and every `e(theta)` (averaged over +-3 degrees, under 4
//! pixels of arc) agree within a pixel; and each picture must show `N` corners, its
//! strongest angular harmonic of `e` being the `N`-th, so that two discs cannot pass.

use std::f64::consts::TAU;
use std::fmt::Write as _;

use anyhow::{Context, Result, bail};
use glam::{DVec2, DVec3};
use serde_json::json;
use viewray_interop::Format;
use viewray_render::RenderSettings;
use viewray_scene::SceneLoader;

use super::Paths;
use super::install::script;
use super::report::{Report, Worst};

/// The image's side, pixels.
const SIZE: u32 = 112;
/// Samples per pixel, in both renderers.
const SAMPLES: u32 = 4096;
/// How far the pictures may differ, in pixels.
const TOLERANCE_PIXELS: f64 = 1.0;

/// A lamp seen through a lens with blades.
struct BokehCase {
    name: &'static str,
    blades: u32,
    /// Degrees, as a scene file writes it.
    rotation: f64,
    /// The lens radius `r` (the canonical camera: `d = 1`, a 1 x 1 viewport).
    aperture: f64,
    focus: f64,
    lamp: DVec3,
    lamp_radius: f64,
}

/// The cases: a pentagon beyond the plane of focus, a heptagon before it (turned by a
/// negative angle, which the scene wraps), a square nearly edge-on to the axes.
const CASES: [BokehCase; 3] = [
    // Blur radius r d (1/f - 1/D) = 0.8 (1/2 - 1/10) = 0.32 of the viewport: 36 px; the
    // lamp's disc 0.6 d / D = 0.06: 6.7 px (a larger lamp is more light per sample, less
    // noise; both renderers round the corners alike).
    BokehCase {
        name: "bokeh_5_blades_beyond_focus",
        blades: 5,
        rotation: 20.0,
        aperture: 0.8,
        focus: 2.0,
        lamp: DVec3::new(0.4, 0.3, -10.0),
        lamp_radius: 0.6,
    },
    // r d (1/D - 1/f) = 0.12 (1/0.4 - 1/4) = 0.27: 30 px; the disc 0.024 / 0.4 = 0.06.
    BokehCase {
        name: "bokeh_7_blades_before_focus",
        blades: 7,
        rotation: -100.0,
        aperture: 0.12,
        focus: 4.0,
        lamp: DVec3::new(-0.02, 0.01, -0.4),
        lamp_radius: 0.024,
    },
    BokehCase {
        name: "bokeh_4_blades_beyond_focus",
        blades: 4,
        rotation: 10.0,
        aperture: 0.8,
        focus: 2.0,
        lamp: DVec3::new(-0.3, -0.5, -10.0),
        lamp_radius: 0.6,
    },
];

impl BokehCase {
    /// The case as a scene file.
    fn scene_text(&self) -> String {
        let mut text = String::new();
        let _ = write!(
            text,
            "(\n    image: (width: {SIZE}, height: {SIZE}, samples: {SAMPLES}),\n    camera: (\n        \
             eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),\n        projection: ThinLens(distance: \
             1.0, viewport: (1.0, 1.0), aperture: {}, focus: {}, blades: {}, blade_rotation: {}),\n    \
             ),\n    background: (0.0, 0.0, 0.0),\n    shading: Flat,\n    materials: {{ \"lamp\": \
             (color: (1.0, 1.0, 1.0)) }},\n    objects: [Sphere(center: ({}, {}, {}), radius: {}, \
             material: \"lamp\")],\n)\n",
            self.aperture,
            self.focus,
            self.blades,
            self.rotation,
            self.lamp.x,
            self.lamp.y,
            self.lamp.z,
            self.lamp_radius,
        );
        text
    }
}

/// Renders every case selected by `filter` in viewray and in Cycles and compares their
/// pictures; adds the checks' lines to `report`. Nothing to do when no case is selected.
///
/// # Errors
/// When a scene cannot be built, exported or rendered, or Blender cannot run.
pub(super) fn check(paths: &Paths, filter: Option<&str>, report: &mut Report) -> Result<()> {
    let cases: Vec<&BokehCase> = CASES
        .iter()
        .filter(|c| filter.is_none_or(|f| c.name.contains(f)))
        .collect();
    if cases.is_empty() {
        return Ok(());
    }
    let mut jobs = Vec::new();
    let mut ours = Vec::new();
    for case in &cases {
        let file = paths.work.join(format!("{}.ron", case.name));
        let scene = SceneLoader::text(&case.scene_text(), &file)
            .load()
            .with_context(|| format!("the case {}", case.name))?
            .scene;
        let script = paths.work.join(format!("{}.py", case.name));
        let export = viewray_interop::export(&scene, Format::Blender, "scene.py")
            .map_err(|e| anyhow::anyhow!("{}: {e}", case.name))?;
        std::fs::write(&script, &export.main)?;
        jobs.push(json!({
            "name": case.name, "script": script, "points": [],
            "bokeh": {
                "samples": SAMPLES,
                "path": paths.work.join(format!("{}-cycles.exr", case.name)),
            },
        }));
        let rendered = viewray_render::render(&scene, &RenderSettings::default(), |_, _| {})
            .map_err(|e| anyhow::anyhow!("{}: {e}", case.name))?;
        let intensity: Vec<f64> = rendered
            .image
            .pixels()
            .iter()
            .map(|p| f64::from(p.x + p.y + p.z) / 3.0)
            .collect();
        ours.push(intensity);
    }
    let result = script(
        paths,
        &paths.python,
        &[&paths.root.join("xtask/interop/blender_check.py")],
        "blender-bokeh",
        &json!({ "cases": jobs }),
    )?;
    let (mut centres, mut extents, mut corners) =
        (Worst::default(), Worst::default(), Worst::default());
    for (case, ours) in cases.iter().zip(&ours) {
        let theirs: Vec<f64> = result[case.name]["intensity"]
            .as_array()
            .with_context(|| format!("Cycles gave no picture for {}", case.name))?
            .iter()
            .map(|v| v.as_f64().unwrap_or(f64::NAN))
            .collect();
        let side = SIZE as usize;
        let (Some(a), Some(b)) = (Profile::of(ours, side), Profile::of(&theirs, side)) else {
            bail!("{}: a picture holds no light", case.name);
        };
        centres.add(a.centroid.distance(b.centroid), || {
            format!(
                "{}: centroid {} vs Cycles {}",
                case.name, a.centroid, b.centroid
            )
        });
        let (worst, at) = a.largest_difference(&b);
        extents.add(worst, || format!("{}: {at} degrees", case.name));
        for (who, profile) in [("viewray", &a), ("Cycles", &b)] {
            let seen = profile.strongest_harmonic();
            // 0 when the N-th harmonic is the strongest, else a failing count.
            let wrong = if seen == case.blades { 0.0 } else { 10.0 };
            corners.add(wrong, || {
                format!(
                    "{}: {who} shows {seen} corners, not {}",
                    case.name, case.blades
                )
            });
        }
    }
    report.check_within(
        "Blender: Cycles bokeh centre vs viewray (px)",
        &centres,
        TOLERANCE_PIXELS,
    );
    report.check_within(
        "Blender: Cycles bokeh extent, every degree (px)",
        &extents,
        TOLERANCE_PIXELS,
    );
    report.check_within(
        "Blender: bokeh corners, the blades' count",
        &corners,
        TOLERANCE_PIXELS,
    );
    Ok(())
}

/// A picture of a blurred light, measured: where it is, how bright inside, how far it
/// reaches in each direction.
#[derive(Debug)]
struct Profile {
    /// The light's centroid, continuous image coordinates.
    centroid: DVec2,
    /// `e(theta)` for theta = 0, 1, ... 359 degrees (x right, y down), pixels.
    extent: Vec<f64>,
}

impl Profile {
    /// Measures the picture `intensity` (`side x side`, rows from the top); `None` when it
    /// holds no light.
    fn of(intensity: &[f64], side: usize) -> Option<Profile> {
        let at = |x: usize, y: usize| intensity[y * side + x].max(0.0);
        let total: f64 = intensity.iter().map(|v| v.max(0.0)).sum();
        // No light (or a NaN in the picture): nothing to measure.
        if total.is_nan() || total <= 0.0 {
            return None;
        }
        let mut centroid = DVec2::ZERO;
        for y in 0..side {
            for x in 0..side {
                centroid += at(x, y) * DVec2::new(x as f64 + 0.5, y as f64 + 0.5);
            }
        }
        centroid /= total;
        // The plateau p: the total light over the area above p / 2 (a flat-topped picture
        // blurred evenly at its edges holds p times its area), from the 90th percentile.
        let mut lit: Vec<f64> = intensity.iter().copied().filter(|v| *v > 0.0).collect();
        lit.sort_by(f64::total_cmp);
        let mut plateau = lit[lit.len() * 9 / 10];
        for _ in 0..4 {
            let area = intensity.iter().filter(|v| **v > plateau / 2.0).count();
            if area == 0 {
                return None;
            }
            plateau = total / area as f64;
        }
        // Bilinear samples along each ray, a quarter pixel apart, to the image's edge.
        let sample = |p: DVec2| {
            let q = p - DVec2::splat(0.5);
            let (x0, y0) = (q.x.floor(), q.y.floor());
            let (fx, fy) = (q.x - x0, q.y - y0);
            let get = |x: f64, y: f64| {
                if x < 0.0 || y < 0.0 || x >= side as f64 || y >= side as f64 {
                    0.0
                } else {
                    at(x as usize, y as usize)
                }
            };
            (1.0 - fy) * ((1.0 - fx) * get(x0, y0) + fx * get(x0 + 1.0, y0))
                + fy * ((1.0 - fx) * get(x0, y0 + 1.0) + fx * get(x0 + 1.0, y0 + 1.0))
        };
        let step = 0.25;
        let reach = side as f64 * 1.5;
        let extent = (0..360)
            .map(|degree| {
                let (sin, cos) = f64::from(degree).to_radians().sin_cos();
                let direction = DVec2::new(cos, sin);
                let steps = (reach / step) as usize;
                (0..steps)
                    .map(|k| sample(centroid + direction * ((k as f64 + 0.5) * step)))
                    .sum::<f64>()
                    * step
                    / plateau
            })
            .collect();
        Some(Profile { centroid, extent })
    }

    /// `e` averaged over the 7 whole degrees around `degree` (at 36 px, less than 4 px
    /// of arc: the Monte Carlo noise of both pictures averages out, a corner does not).
    fn smoothed(&self, degree: usize) -> f64 {
        (0..7)
            .map(|k| self.extent[(degree + 360 + k - 3) % 360])
            .sum::<f64>()
            / 7.0
    }

    /// The largest difference of the smoothed extents, and the degree where it is.
    fn largest_difference(&self, other: &Profile) -> (f64, usize) {
        (0..360)
            .map(|degree| {
                (
                    (self.smoothed(degree) - other.smoothed(degree)).abs(),
                    degree,
                )
            })
            .fold((0.0, 0), |worst, d| if d.0 > worst.0 { d } else { worst })
    }

    /// Which angular harmonic of `e`, from the 3rd to the 12th, is the strongest: the
    /// number of the polygon's corners.
    fn strongest_harmonic(&self) -> u32 {
        let amplitude = |n: u32| {
            let (mut c, mut s) = (0.0, 0.0);
            for (degree, e) in self.extent.iter().enumerate() {
                let angle = f64::from(n) * TAU * degree as f64 / 360.0;
                c += e * angle.cos();
                s += e * angle.sin();
            }
            c.hypot(s)
        };
        (3..=12)
            .max_by(|a, b| amplitude(*a).total_cmp(&amplitude(*b)))
            .unwrap_or(0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A polygon of `corners` corners on a circle of `radius` pixels about `centre`, turned
    /// by `turn`, drawn with 8 x 8 samples a pixel at intensity 3.
    fn polygon_picture(
        side: usize,
        centre: DVec2,
        radius: f64,
        corners: u32,
        turn: f64,
    ) -> Vec<f64> {
        let n = f64::from(corners);
        let apothem = radius * (std::f64::consts::PI / n).cos();
        let inside = |p: DVec2| {
            (0..corners).all(|k| {
                let (sin, cos) = (turn + TAU * f64::from(k) / n).sin_cos();
                (p - centre).dot(DVec2::new(cos, sin)) <= apothem
            })
        };
        let mut out = vec![0.0; side * side];
        for y in 0..side {
            for x in 0..side {
                let mut hits = 0;
                for j in 0..8 {
                    for i in 0..8 {
                        let p = DVec2::new(
                            x as f64 + (f64::from(i) + 0.5) / 8.0,
                            y as f64 + (f64::from(j) + 0.5) / 8.0,
                        );
                        hits += u32::from(inside(p));
                    }
                }
                out[y * side + x] = 3.0 * f64::from(hits) / 64.0;
            }
        }
        out
    }

    #[test]
    fn a_polygon_s_extent_is_its_distance_to_the_edge_in_each_direction() {
        let centre = DVec2::new(50.3, 47.8);
        let picture = polygon_picture(100, centre, 30.0, 5, 0.4);
        let profile = Profile::of(&picture, 100).unwrap();
        assert!(
            profile.centroid.distance(centre) < 0.05,
            "{}",
            profile.centroid
        );
        // The edge's middle at angle 0.4 rad (22.9 degrees): the apothem 30 cos 36 =
        // 24.27; a corner at 0.4 + 36 degrees: 30.
        let apothem = 30.0 * 36f64.to_radians().cos();
        assert!(
            (profile.extent[23] - apothem).abs() < 0.2,
            "{}",
            profile.extent[23]
        );
        let corner = (0.4f64.to_degrees() + 36.0).round() as usize;
        assert!(profile.extent[corner] > 29.0, "{}", profile.extent[corner]);
        assert_eq!(profile.strongest_harmonic(), 5);
        // The same polygon matches itself; turned by half a wedge it does not.
        let (same, _) = profile.largest_difference(&Profile::of(&picture, 100).unwrap());
        assert_eq!(same, 0.0);
        let turned = polygon_picture(100, centre, 30.0, 5, 0.4 + 36f64.to_radians());
        let (differ, _) = profile.largest_difference(&Profile::of(&turned, 100).unwrap());
        assert!(differ > 4.0, "{differ}");
        // Larger by a pixel: a pixel apart everywhere.
        let larger = polygon_picture(100, centre, 31.0, 5, 0.4);
        let (apart, _) = profile.largest_difference(&Profile::of(&larger, 100).unwrap());
        assert!((0.7..1.1).contains(&apart), "{apart}");
        // Seven corners and four are told apart from five.
        let seven = Profile::of(&polygon_picture(100, centre, 30.0, 7, 1.0), 100).unwrap();
        assert_eq!(seven.strongest_harmonic(), 7);
        let four = Profile::of(&polygon_picture(100, centre, 30.0, 4, 1.0), 100).unwrap();
        assert_eq!(four.strongest_harmonic(), 4);
        assert!(Profile::of(&vec![0.0; 100], 10).is_none());
    }

    #[test]
    fn every_case_is_a_valid_scene_that_blender_takes() {
        for case in &CASES {
            let text = case.scene_text();
            let scene = SceneLoader::text(&text, std::path::Path::new("case.ron"))
                .load()
                .unwrap_or_else(|e| panic!("{}: {e}", case.name))
                .scene;
            let script = viewray_interop::export(&scene, Format::Blender, "scene.py").unwrap();
            let text = String::from_utf8(script.main).unwrap();
            assert!(text.contains(&format!("cam.dof.aperture_blades = {}\n", case.blades)));
        }
    }
}
