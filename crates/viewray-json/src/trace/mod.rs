//! A pixel's trace printed: as JSON lines ([`trace_lines`], here), one object per step of
//! the trace, then the pixel's value; and as text for people ([`trace_text`], module
//! `text`, with `ray` for the viewing ray's numbers and `lighting` for a Lit surface's
//! terms).
//!
//! ```text
//! {"step":"viewing-ray","bounce":0,"row":R,"col":C,"x":X,"y":Y,"u":U,"v":V,"origin":[..],"direction":[..]}
//! {"step":"test","bounce":0,"object":K,"shape":"Sphere","t":T}           (t null: a miss)
//! {"step":"closest","bounce":0,"object":K,"shape":..,"primitive":P,"material":M,"t":T,"point":[..],"normal":[..],"shading_normal":[..]}
//! {"step":"background","bounce":B,"color":[..]}
//! {"step":"flat"|"normals"|"depth"|"surface"|"headlight"|"ambient"|"light"|"reflect"|"mix",..}
//! {"row":R,"col":C,"linear":[r,g,b],"srgb8":[r,g,b]}
//! ```
//!
//! `u`, `v` are the planar families' image-plane point; the equirectangular camera
//! gives `longitude`, `latitude` instead, the fisheye `a`, `b`, `r`, `theta`. With
//! 1-based indices the pixel's keys are `i`, `j` (see [`PixelIndices`]). `linear` is the
//! value the image holds (for Normals and Depth, the data) and `srgb8` the 8-bit value
//! its PNG stores. The renderer's numbers are `f32`: each is printed as the shortest
//! decimal that reads back as the same `f32`.

use glam::{DVec2, Vec3};
use serde_json::{Map, Value, json};
use viewray_camera::{CameraSample, Projection, equirectangular_angles, pixel_to_image_plane};
use viewray_render::{
    BlinnPhong, ClosestHit, GridLines, LightSource, LightTerms, LitSurface, PixelTrace, Step,
    StepKind,
};

use crate::{PixelIndices, number, vector};

mod lighting;
mod ray;
mod text;

pub use text::trace_text;

/// An `f32` for printing: the shortest decimal that reads back as the same `f32`
/// (`0.15`, not the `0.15000000596046448` of its `f64`), `-0` written `0`; infinities
/// and NaN are `null`.
pub fn number_f32(x: f32) -> Value {
    let shortest: f64 = viewray_output::number::round_trip_f32(x)
        .parse()
        .unwrap_or(f64::NAN);
    number(shortest)
}

/// A vector of `f32`s as a JSON array (see [`number_f32`]).
pub fn vector_f32(v: Vec3) -> Value {
    Value::Array(v.to_array().map(number_f32).to_vec())
}

/// The lines of `viewray trace` for the trace `trace` of a pixel of `camera`'s image: one
/// per step, then `{"row":R,"col":C,"linear":[..],"srgb8":[..]}` (`i`, `j` for 1-based
/// `indices`).
pub fn trace_lines(
    camera: &viewray_camera::Camera,
    trace: &PixelTrace,
    indices: PixelIndices,
) -> Vec<Value> {
    let [row_key, col_key] = indices.keys();
    let base = u64::from(indices.base());
    let pixel = |line: &mut Map<String, Value>| {
        line.insert(row_key.into(), json!(u64::from(trace.row) + base));
        line.insert(col_key.into(), json!(u64::from(trace.col) + base));
    };
    let mut lines: Vec<Value> = trace
        .steps
        .iter()
        .map(|step| {
            let mut line = Map::new();
            line.insert("step".into(), json!(step_name(&step.kind)));
            line.insert("bounce".into(), json!(step.bounce));
            if let StepKind::ViewingRay { .. } = step.kind {
                pixel(&mut line);
                image_point(camera, (trace.row, trace.col), &mut line);
            }
            step_fields(step, &mut line);
            Value::Object(line)
        })
        .collect();
    let mut last = Map::new();
    pixel(&mut last);
    last.insert("linear".into(), vector_f32(trace.value));
    last.insert("srgb8".into(), json!(trace.rgb8));
    lines.push(Value::Object(last));
    lines
}

/// The name of a step in its line's `"step"`.
fn step_name(kind: &StepKind) -> &'static str {
    match kind {
        StepKind::ViewingRay { .. } => "viewing-ray",
        StepKind::Test { .. } => "test",
        StepKind::Closest(_) => "closest",
        StepKind::Background { .. } => "background",
        StepKind::Flat { .. } => "flat",
        StepKind::Normals { .. } => "normals",
        StepKind::Depth(_) => "depth",
        StepKind::Surface(_) => "surface",
        StepKind::Headlight(_) => "headlight",
        StepKind::Ambient { .. } => "ambient",
        StepKind::Light(_) => "light",
        StepKind::Reflect { .. } => "reflect",
        StepKind::Mix { .. } => "mix",
    }
}

/// The continuous image point of the pixel's centre and the numbers the camera makes of
/// it: `x`, `y`, then `u`, `v` (planar families), `longitude`, `latitude`
/// (equirectangular) or `a`, `b`, `r`, `theta` (fisheye).
fn image_point(
    camera: &viewray_camera::Camera,
    (row, col): (u32, u32),
    line: &mut Map<String, Value>,
) {
    let p_film = CameraSample::CENTER.p_film;
    let image = DVec2::new(f64::from(col), f64::from(row)) + p_film;
    let size = DVec2::new(f64::from(camera.width()), f64::from(camera.height()));
    line.insert("x".into(), number(image.x));
    line.insert("y".into(), number(image.y));
    let mut put = |key: &str, value: f64| {
        line.insert(key.into(), number(value));
    };
    match camera.projection() {
        Projection::Equirectangular => {
            let (longitude, latitude) = equirectangular_angles(image, size);
            put("longitude", longitude);
            put("latitude", latitude);
        }
        Projection::Fisheye(fisheye) => {
            let point = fisheye.image_point(image, size);
            put("a", point.a);
            put("b", point.b);
            put("r", point.r);
            put("theta", point.theta);
        }
        projection => {
            let viewport = projection.viewport().unwrap_or(DVec2::ONE);
            let size = (camera.width(), camera.height());
            let uv = pixel_to_image_plane(row, col, p_film, size, viewport);
            put("u", uv.x);
            put("v", uv.y);
        }
    }
}

/// The fields of `step` after its name and bounce.
fn step_fields(step: &Step, line: &mut Map<String, Value>) {
    let mut put = |key: &str, value: Value| {
        line.insert(key.into(), value);
    };
    match &step.kind {
        StepKind::ViewingRay { ray } => {
            put("origin", ray.map_or(Value::Null, |r| vector(r.origin)));
            put(
                "direction",
                ray.map_or(Value::Null, |r| vector(r.direction)),
            );
        }
        StepKind::Test { object, shape, t } => {
            put("object", json!(object));
            put("shape", json!(shape.name()));
            put("t", t.map_or(Value::Null, number_f32));
        }
        StepKind::Closest(hit) => closest(hit, &mut put),
        StepKind::Background { color } => put("color", vector_f32(*color)),
        StepKind::Flat {
            material,
            color,
            grid,
        } => {
            put("material", json!(material));
            put("color", vector_f32(*color));
            put("grid", grid.as_ref().map_or(Value::Null, grid_lines));
        }
        StepKind::Normals { normal, value } => {
            put("normal", vector_f32(*normal));
            put("value", vector_f32(*value));
        }
        StepKind::Depth(depth) => {
            put("panoramic", json!(depth.panoramic));
            put("z", number_f32(depth.z));
            put("near", number_f32(depth.near));
            put("far", number_f32(depth.far));
            put("s", depth.s.map_or(Value::Null, number_f32));
            put("value", number_f32(depth.value));
        }
        StepKind::Surface(surface) => lit_surface(surface, &mut put),
        StepKind::Headlight(headlight) => {
            put("ambient", number_f32(headlight.ambient));
            put("blinn_phong", blinn_phong(&headlight.lit));
            put("term", vector_f32(headlight.term));
            put("color", vector_f32(headlight.color));
        }
        StepKind::Ambient {
            light,
            intensity,
            term,
            color,
        } => {
            put("light", json!(light));
            put("intensity", vector_f32(*intensity));
            put("term", vector_f32(*term));
            put("color", vector_f32(*color));
        }
        StepKind::Light(terms) => light(terms, &mut put),
        StepKind::Reflect { mirror, ray } => {
            put("mirror", number_f32(*mirror));
            put("origin", ray.map_or(Value::Null, |r| vector_f32(r.origin)));
            put(
                "direction",
                ray.map_or(Value::Null, |r| vector_f32(r.direction)),
            );
        }
        StepKind::Mix {
            mirror,
            local,
            reflected,
            color,
        } => {
            put("mirror", number_f32(*mirror));
            put("local", vector_f32(*local));
            put("reflected", vector_f32(*reflected));
            put("color", vector_f32(*color));
        }
    }
}

fn closest(hit: &ClosestHit, put: &mut impl FnMut(&str, Value)) {
    put("object", json!(hit.object));
    put("shape", json!(hit.shape.name()));
    put("primitive", json!(hit.primitive));
    put("material", json!(hit.material));
    put("t", number_f32(hit.t));
    put("point", vector_f32(hit.point));
    put("normal", vector_f32(hit.normal));
    put("shading_normal", vector_f32(hit.shading_normal));
}

fn lit_surface(surface: &LitSurface, put: &mut impl FnMut(&str, Value)) {
    put("material", json!(surface.material));
    put("color", vector_f32(surface.color));
    put(
        "grid",
        surface.grid.as_ref().map_or(Value::Null, grid_lines),
    );
    put("specular", vector_f32(surface.specular));
    put("shininess", number_f32(surface.shininess));
    put("mirror", number_f32(surface.mirror));
    put("view", vector_f32(surface.view));
    put("origin", vector_f32(surface.origin));
}

/// `{"axes":["x","z"],"footprint":[..],"coverage":[..],"total":..,"line_color":[..],
/// "base":[..],"color":[..]}`.
fn grid_lines(grid: &GridLines) -> Value {
    let axis = |a: usize| ["x", "y", "z"].get(a).copied().unwrap_or("?");
    json!({
        "axes": grid.axes.map(axis),
        "footprint": grid.footprint.map(number_f32),
        "coverage": grid.coverage.map(number_f32),
        "total": number_f32(grid.total),
        "line_color": vector_f32(grid.line_color),
        "base": vector_f32(grid.base),
        "color": vector_f32(grid.color),
    })
}

/// `{"n_dot_l":..,"diffuse":[..],"specular":{"h":[..],"n_dot_h":..,"power":..,"term":[..]}
/// (or null),"sum":[..]}`.
fn blinn_phong(terms: &BlinnPhong) -> Value {
    let specular = terms.specular.map_or(Value::Null, |s| {
        json!({
            "h": vector_f32(s.h),
            "n_dot_h": number_f32(s.n_dot_h),
            "power": number_f32(s.power),
            "term": vector_f32(s.term),
        })
    });
    json!({
        "n_dot_l": number_f32(terms.n_dot_l),
        "diffuse": vector_f32(terms.diffuse),
        "specular": specular,
        "sum": vector_f32(terms.sum),
    })
}

fn light(terms: &LightTerms, put: &mut impl FnMut(&str, Value)) {
    put("light", json!(terms.light));
    match terms.source {
        LightSource::Point(position) => {
            put("kind", json!("point"));
            put("position", vector_f32(position));
        }
        LightSource::Directional(direction) => {
            put("kind", json!("directional"));
            put("direction", vector_f32(direction));
        }
    }
    put("intensity", vector_f32(terms.intensity));
    put("l", vector_f32(terms.l));
    put("distance_squared", number_f32(terms.distance_squared));
    let shadow = terms.shadow.map_or(Value::Null, |shadow| {
        let blocker = shadow.blocker.map_or(Value::Null, |(object, shape, t)| {
            json!({"object": object, "shape": shape.name(), "t": number_f32(t)})
        });
        json!({
            "origin": vector_f32(shadow.ray.origin),
            "direction": vector_f32(shadow.ray.direction),
            "t_min": number_f32(shadow.t_min),
            "t_max": number_f32(shadow.t_max),
            "blocked": shadow.blocked,
            "blocker": blocker,
        })
    });
    put("shadow_ray", shadow);
    let lit = terms.lit.map_or(Value::Null, |lit| {
        json!({
            "scale": vector_f32(lit.scale),
            "blinn_phong": blinn_phong(&lit.blinn_phong),
            "term": vector_f32(lit.term),
        })
    });
    put("lit", lit);
    put("color", vector_f32(terms.color));
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use viewray_render::{RenderSettings, View, trace_pixel};
    use viewray_scene::SceneLoader;

    use super::*;

    #[test]
    fn renderer_numbers_print_as_their_shortest_f32_text() {
        assert_eq!(number_f32(0.15).to_string(), "0.15");
        assert_eq!(number_f32(-0.0).to_string(), "0.0");
        assert_eq!(number_f32(1.0 / 3.0).to_string(), "0.33333334");
        assert_eq!(number_f32(f32::INFINITY), Value::Null);
        assert_eq!(
            vector_f32(Vec3::new(0.1, -2.5, 3e-8)).to_string(),
            "[0.1,-2.5,3e-8]"
        );
    }

    /// The keys of a line, in order.
    fn keys(line: &Value) -> Vec<&str> {
        line.as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect()
    }

    #[test]
    fn a_trace_is_its_steps_then_the_pixel() {
        // The canonical camera, 3 x 3 pixels: the centre pixel looks at a sphere lit by a
        // point light; the corner sees the background.
        let scene = SceneLoader::text(
            "(image: (width: 3, height: 3), shading: Lit,
              camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                       projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))),
              background: (0.25, 0.5, 1.0),
              materials: { \"red\": (color: (0.8, 0.1, 0.1)) },
              lights: [Point(position: (0.0, 2.0, 0.0), intensity: (4.0, 4.0, 4.0))],
              objects: [Sphere(center: (0.0, 0.0, -3.0), radius: 0.5, material: \"red\")])",
            Path::new("sphere.ron"),
        )
        .load()
        .unwrap()
        .scene;
        let view = View::of(&scene);
        let trace = trace_pixel(&scene, &view, &RenderSettings::default(), 1, 1).unwrap();
        let lines = trace_lines(scene.camera(), &trace, PixelIndices::ZeroBased);
        let steps: Vec<&str> = lines.iter().filter_map(|l| l["step"].as_str()).collect();
        assert_eq!(
            steps,
            ["viewing-ray", "test", "closest", "surface", "light"]
        );
        assert_eq!(
            keys(&lines[0]),
            [
                "step",
                "bounce",
                "row",
                "col",
                "x",
                "y",
                "u",
                "v",
                "origin",
                "direction"
            ]
        );
        // u = ((j - 1/2)/W - 1/2) vw = 0 for the centre column.
        assert_eq!(lines[0]["u"], json!(0.0));
        assert_eq!(lines[0]["direction"], json!([0.0, 0.0, -1.0]));
        assert_eq!(lines[1]["t"], json!(2.5));
        assert_eq!(lines[2]["point"], json!([0.0, 0.0, -2.5]));
        let last = lines.last().unwrap();
        assert_eq!(keys(last), ["row", "col", "linear", "srgb8"]);
        assert_eq!(last["srgb8"], json!(trace.rgb8));
        assert_eq!(last["linear"], vector_f32(trace.value));

        // The corner, 1-based: no hit, the background.
        let trace = trace_pixel(&scene, &view, &RenderSettings::default(), 0, 0).unwrap();
        let lines = trace_lines(scene.camera(), &trace, PixelIndices::OneBased);
        assert_eq!(lines[0]["i"], json!(1));
        assert_eq!(lines[2]["step"], "background");
        assert_eq!(lines[2]["color"], json!([0.25, 0.5, 1.0]));
        assert_eq!(keys(lines.last().unwrap()), ["i", "j", "linear", "srgb8"]);
    }

    #[test]
    fn a_tilted_lens_s_trace_names_the_plane_of_focus_its_ray_meets() {
        // A 90 mm lens focused at 5 m and tilted 3 degrees: the top middle pixel's
        // centre ray c = (0, 0.006, -0.09) meets m.P = F, m = (0, -sin 3, 1 - 0.09/5 -
        // cos 3), at t = F / m.c = 76.10, the point (0, 0.4566, -6.849).
        let scene = SceneLoader::text(
            "(image: (width: 3, height: 2), shading: Flat,
              camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                       projection: ThinLens(focal_length: 90.0, sensor: (36.0, 24.0),
                                            f_number: 4.0, focus: 5.0, lens_tilt: 3.0)))",
            Path::new("tilted.ron"),
        )
        .load()
        .unwrap()
        .scene;
        let view = View::of(&scene);
        let trace = trace_pixel(&scene, &view, &RenderSettings::default(), 0, 1).unwrap();
        let text = trace_text(scene.camera(), scene.shading(), &trace, "");
        let (sin, cos) = 3f64.to_radians().sin_cos();
        let m_y = -sin;
        let m_z = 1.0 - 0.09 / 5.0 - cos;
        let t = 0.09 / (m_y * 0.006 + m_z * -0.09);
        assert!((t - 76.10).abs() < 0.01, "{t}");
        assert!(
            text.contains(&format!(
                "tilt 3 degrees, swing 0 degrees: plane of focus m.P = F, F = d = 0.09, m = n + \
                 (1 - F/f) W = (0, {}, {})",
                text::m(m_y),
                text::m(m_z)
            )),
            "{text}"
        );
        assert!(
            text.contains(&format!(
                "direction = (F / m.c) c where m.c > 0, else c;  c = (u + sx) U + (v + sy) V - d \
                 W = (0, {}, {})",
                text::m(t * 0.006),
                text::m(t * -0.09)
            )),
            "{text}"
        );
        assert!(!text.contains("(f/d)"), "{text}");
    }
}
