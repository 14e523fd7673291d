//! The numbers viewray prints as JSON lines, formatted in one place so that the command
//! line (`viewray frame`, `rays`, `project`, `trace`) and the live playground print the
//! same digits for the same camera.
//!
//! # What it owns
//!
//! - The lines: [`frame_line`] `{"e":[..],"u":[..],"v":[..],"w":[..]}`, and
//!   [`camera_frame_line`], which adds `"focus_plane":{"point":[..],"normal":[..]}` for a
//!   camera with a lens and `"hinge_line":{"point":[..],"direction":[..]}` for a tilted
//!   one; [`ray_line`] `{"row":R,"col":C,"u":U,"v":V,"origin":[..],"direction":[..]}`, and
//!   [`lens_ray_line`], the same through a chosen lens point; [`project_line`]
//!   `{"point":[..],"x":X,"y":Y,"row":R,"col":C}`.
//! - A pixel's trace (viewray-render's [`PixelTrace`](viewray_render::PixelTrace)):
//!   [`trace_lines`], `{"step":..,"bounce":B,..}` per step, then
//!   `{"row":R,"col":C,"linear":[..],"srgb8":[..]}`; and [`trace_text`], the same numbers
//!   for people, each beside its formula under the lecture's pseudocode.
//! - How a number is printed: [`number`] (as Rust prints an `f64`, the shortest text that
//!   reads back to the same number, with `-0` written `0`), [`vector`], [`write_line`].
//! - How a pixel is named ([`PixelIndices`]: 0-based `row`, `col`, or the lecture's
//!   1-based `i`, `j`; the keys say which), and the sentence for a pixel outside the image
//!   ([`PixelOutside`]).
//!
//! Ray directions are not normalized: they are the lecture's formulas evaluated exactly.
//!
//! # Invariant
//!
//! This crate knows cameras, the renderer's trace and JSON, and nothing of the command
//! line, files or HTTP: no sentence of it names a flag or a query parameter (a program
//! adds its own words, as [`PixelOutside::sentence`] lets it).
//!
//! # Where to start reading
//!
//! This file holds the lines of `frame`, `rays` and `project`; `pixel` the indices and
//! their sentence; `trace` the trace's lines and text; `judgement` the lines of `compare` and
//! `grade`; `check` those of `check`.

mod check;
mod judgement;
mod pixel;
mod trace;

use std::io::Write;

use glam::{DVec2, DVec3};
use serde_json::{Map, Value, json};
use viewray_camera::{Camera, CameraSample, Frame, pixel_to_image_plane};

pub use check::{check_summary_line, checked_line};
pub use judgement::{class_summary_line, pair_line, pairs_summary_line, student_image_line};
pub use pixel::{PixelIndices, PixelOutside};
pub use trace::{number_f32, trace_lines, trace_text, vector_f32};

/// A number for printing: `-0` becomes `0` (a student's answer never says minus zero),
/// by viewray-output's one rule for it.
pub fn number(x: f64) -> Value {
    json!(viewray_output::number::without_minus_zero(x))
}

/// A vector as a JSON array `[x, y, z]`.
pub fn vector(v: DVec3) -> Value {
    Value::Array(v.to_array().map(number).to_vec())
}

/// Writes `value` as one line on `out`.
///
/// # Errors
/// The writer's error.
pub fn write_line(out: &mut impl Write, value: &Value) -> std::io::Result<()> {
    serde_json::to_writer(&mut *out, value)?;
    out.write_all(b"\n")
}

/// The line of `viewray frame`: `{"e":[..],"u":[..],"v":[..],"w":[..]}`.
pub fn frame_line(frame: &Frame) -> Value {
    json!({
        "e": vector(frame.e()),
        "u": vector(frame.u()),
        "v": vector(frame.v()),
        "w": vector(frame.w()),
    })
}

/// The line of `viewray frame SCENE`: [`frame_line`] of the camera's frame and, for a
/// camera with a lens, its plane of sharp focus (its point nearest the lens centre and
/// its unit normal toward the lens: `e - f w` and `w` untilted) and, for a tilted or
/// swung thin lens, its hinge line (the point nearest the lens centre, the unit
/// direction `w x n`):
///
/// ```text
/// {"e":[..],"u":[..],"v":[..],"w":[..],
///  "focus_plane":{"point":[..],"normal":[..]},"hinge_line":{"point":[..],"direction":[..]}}
/// ```
pub fn camera_frame_line(camera: &Camera) -> Value {
    let mut line = frame_line(camera.frame());
    let Value::Object(map) = &mut line else {
        unreachable!("frame_line is an object")
    };
    if let Some(plane) = camera.focus_plane() {
        map.insert(
            "focus_plane".into(),
            json!({ "point": vector(plane.point), "normal": vector(plane.normal) }),
        );
    }
    if let Some(tilted) = camera.tilted_focus() {
        let hinge = tilted.hinge_line;
        map.insert(
            "hinge_line".into(),
            json!({ "point": vector(hinge.point), "direction": vector(hinge.direction) }),
        );
    }
    line
}

/// The line of `viewray rays` for pixel (`row`, `col`) (0-based) and the film and lens
/// point `sample`: `{"row":R,"col":C,"u":U,"v":V,"origin":[..],"direction":[..]}`, the
/// indices named as `indices` says. `u`, `v` are the image-plane point
/// ([`pixel_to_image_plane`]), null for the panoramic cameras, which have no image plane;
/// `origin` and `direction` are null where the camera has no ray (outside a fisheye's
/// circle).
pub fn ray_line(
    camera: &Camera,
    (row, col): (u32, u32),
    sample: CameraSample,
    indices: PixelIndices,
) -> Value {
    let ray = camera.generate_ray(row, col, sample);
    let ray = ray.map(|r| (r.origin, r.direction));
    pixel_ray_line(camera, (row, col), sample.p_film, ray, indices)
}

/// The line of `viewray rays` through a chosen lens point: as [`ray_line`], the ray through the film
/// point `p_film` of pixel (`row`, `col`) and the lens point `lens` given in unit-disk
/// coordinates (the ray starts at `e + r (LX U + LY V)`; see
/// [`Camera::generate_ray_at_lens`]).
pub fn lens_ray_line(
    camera: &Camera,
    (row, col): (u32, u32),
    p_film: DVec2,
    lens: DVec2,
    indices: PixelIndices,
) -> Value {
    let image = DVec2::new(f64::from(col), f64::from(row)) + p_film;
    let ray = camera.generate_ray_at_lens(image, lens);
    let ray = ray.map(|r| (r.origin, r.direction));
    pixel_ray_line(camera, (row, col), p_film, ray, indices)
}

/// The keys and numbers of a `viewray rays` line for `ray` (origin, direction), the ray
/// of pixel (`row`, `col`) through its film point `p_film`.
fn pixel_ray_line(
    camera: &Camera,
    (row, col): (u32, u32),
    p_film: DVec2,
    ray: Option<(DVec3, DVec3)>,
    indices: PixelIndices,
) -> Value {
    // The image-plane point, for the planar families; the panoramic ones have none. A
    // camera with the catalogue's mistakes prints its own, mistaken, point.
    let uv = if camera.mistakes().is_empty() {
        camera.projection().viewport().map(|viewport| {
            pixel_to_image_plane(
                row,
                col,
                p_film,
                (camera.width(), camera.height()),
                viewport,
            )
        })
    } else {
        camera.image_plane_point(row, col, p_film)
    };
    let [row_key, col_key] = indices.keys();
    let base = u64::from(indices.base());
    let mut line = Map::new();
    line.insert(row_key.into(), json!(u64::from(row) + base));
    line.insert(col_key.into(), json!(u64::from(col) + base));
    line.insert("u".into(), uv.map_or(Value::Null, |uv| number(uv.x)));
    line.insert("v".into(), uv.map_or(Value::Null, |uv| number(uv.y)));
    line.insert(
        "origin".into(),
        ray.map_or(Value::Null, |(origin, _)| vector(origin)),
    );
    line.insert(
        "direction".into(),
        ray.map_or(Value::Null, |(_, direction)| vector(direction)),
    );
    Value::Object(line)
}

/// The line of `viewray project` for the world point `point`:
/// `{"point":[..],"x":X,"y":Y,"row":R,"col":C}`. `x`, `y` are continuous image
/// coordinates, null where the camera does not see the point (behind a perspective
/// eye); the pixel holding it is null outside the image.
pub fn project_line(camera: &Camera, point: DVec3, indices: PixelIndices) -> Value {
    let image: Option<DVec2> = camera.project(point);
    let pixel = image.and_then(|xy| camera.pixel_at(xy));
    let [row_key, col_key] = indices.keys();
    let base = u64::from(indices.base());
    let mut line = Map::new();
    line.insert("point".into(), vector(point));
    line.insert("x".into(), image.map_or(Value::Null, |xy| number(xy.x)));
    line.insert("y".into(), image.map_or(Value::Null, |xy| number(xy.y)));
    line.insert(
        row_key.into(),
        pixel.map_or(Value::Null, |(row, _)| json!(u64::from(row) + base)),
    );
    line.insert(
        col_key.into(),
        pixel.map_or(Value::Null, |(_, col)| json!(u64::from(col) + base)),
    );
    Value::Object(line)
}

#[cfg(test)]
mod tests {
    use super::*;
    use viewray_camera::{Perspective, Projection};

    /// The lecture's canonical camera: e at the origin, d = 1, vw = vh = 1, 2 x 2 pixels.
    fn canonical() -> Camera {
        let projection = Projection::Perspective(Perspective {
            distance: 1.0,
            viewport: DVec2::ONE,
            shift: DVec2::ZERO,
        });
        Camera::new(Frame::CANONICAL, projection, 2, 2).unwrap()
    }

    #[test]
    fn lines_print_the_lecture_numbers_with_their_keys() {
        let camera = canonical();
        // u = ((j - 1/2)/W - 1/2) vw = -0.25 for j = 1; v = 0.25 for i = 1.
        assert_eq!(
            ray_line(
                &camera,
                (0, 0),
                CameraSample::CENTER,
                PixelIndices::OneBased
            )
            .to_string(),
            r#"{"i":1,"j":1,"u":-0.25,"v":0.25,"origin":[0.0,0.0,0.0],"direction":[-0.25,0.25,-1.0]}"#
        );
        assert_eq!(
            ray_line(
                &camera,
                (1, 1),
                CameraSample::CENTER,
                PixelIndices::ZeroBased
            )
            .to_string(),
            r#"{"row":1,"col":1,"u":0.25,"v":-0.25,"origin":[0.0,0.0,0.0],"direction":[0.25,-0.25,-1.0]}"#
        );
        assert_eq!(
            project_line(
                &camera,
                DVec3::new(0.25, 0.25, -1.0),
                PixelIndices::ZeroBased
            )
            .to_string(),
            r#"{"point":[0.25,0.25,-1.0],"x":1.5,"y":0.5,"row":0,"col":1}"#
        );
        // Behind the eye: nothing to see.
        assert_eq!(
            project_line(&camera, DVec3::new(0.0, 0.0, 1.0), PixelIndices::OneBased).to_string(),
            r#"{"point":[0.0,0.0,1.0],"x":null,"y":null,"i":null,"j":null}"#
        );
        assert_eq!(
            frame_line(&Frame::CANONICAL).to_string(),
            r#"{"e":[0.0,0.0,0.0],"u":[1.0,0.0,0.0],"v":[0.0,1.0,0.0],"w":[0.0,0.0,1.0]}"#
        );
        assert_eq!(
            vector(DVec3::new(-0.0, 1.5, -2.0)).to_string(),
            "[0.0,1.5,-2.0]"
        );
    }

    /// A thin lens over the canonical camera's pinhole, 2 x 2 pixels, `r = 0.5`,
    /// `f = 4`, tilted by `tilt` degrees.
    fn thin_lens(tilt: f64) -> Camera {
        let lens = viewray_camera::ThinLens {
            tilt: tilt.to_radians(),
            ..viewray_camera::ThinLens::new(Perspective::CANONICAL, 0.5, 4.0)
        };
        Camera::new(Frame::CANONICAL, Projection::ThinLens(lens), 2, 2).unwrap()
    }

    #[test]
    fn a_lens_adds_its_plane_of_focus_and_a_tilt_its_hinge_line() {
        // Untilted: the plane z = -f, normal w; no hinge line.
        assert_eq!(
            camera_frame_line(&thin_lens(0.0)).to_string(),
            r#"{"e":[0.0,0.0,0.0],"u":[1.0,0.0,0.0],"v":[0.0,1.0,0.0],"w":[0.0,0.0,1.0],"focus_plane":{"point":[0.0,0.0,-4.0],"normal":[0.0,0.0,1.0]}}"#
        );
        // Tilted 30 degrees with F = d = 1: the hinge line F / sin 30 = 2 below the lens,
        // along u.
        let tilted = camera_frame_line(&thin_lens(30.0));
        let hinge = &tilted["hinge_line"];
        let close = |value: &Value, expected: [f64; 3]| {
            let got: Vec<f64> = value
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect();
            for (g, e) in got.iter().zip(expected) {
                assert!((g - e).abs() < 1e-12, "{got:?} != {expected:?}");
            }
        };
        close(&hinge["point"], [0.0, -2.0, 0.0]);
        close(&hinge["direction"], [1.0, 0.0, 0.0]);
        let keys: Vec<&String> = tilted.as_object().unwrap().keys().collect();
        assert_eq!(keys, ["e", "u", "v", "w", "focus_plane", "hinge_line"]);
        // The plane of focus of the tilted lens holds the hinge line.
        let plane = &tilted["focus_plane"];
        let normal: Vec<f64> = plane["normal"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let point: Vec<f64> = plane["point"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let off = normal[1] * (-2.0 - point[1]) + normal[2] * (0.0 - point[2]);
        assert!(off.abs() < 1e-12, "{off}");
        // A camera without a lens prints its frame alone.
        assert_eq!(
            camera_frame_line(&canonical()),
            frame_line(&Frame::CANONICAL)
        );
    }

    #[test]
    fn a_lens_ray_starts_at_the_chosen_lens_point() {
        // Pixel (0, 1) is (u, v) = (0.25, 0.25); its focus point is 4 (0.25, 0.25, -1);
        // from the lens point r (1, 0) = (0.5, 0, 0) the direction is (0.5, 1, -4).
        assert_eq!(
            lens_ray_line(
                &thin_lens(0.0),
                (0, 1),
                DVec2::splat(0.5),
                DVec2::new(1.0, 0.0),
                PixelIndices::ZeroBased
            )
            .to_string(),
            r#"{"row":0,"col":1,"u":0.25,"v":0.25,"origin":[0.5,0.0,0.0],"direction":[0.5,1.0,-4.0]}"#
        );
        // The lens centre is the line of `ray_line` through the centre sample.
        assert_eq!(
            lens_ray_line(
                &thin_lens(0.0),
                (1, 0),
                DVec2::splat(0.5),
                DVec2::ZERO,
                PixelIndices::OneBased
            ),
            ray_line(
                &thin_lens(0.0),
                (1, 0),
                CameraSample::CENTER,
                PixelIndices::OneBased
            )
        );
    }
}
