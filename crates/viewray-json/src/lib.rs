//! The JSON lines of `viewray frame`, `viewray rays`, `viewray project` and `viewray
//! trace`: the numbers a student checks a homework answer against, formatted in one
//! place so that the command line and the live playground (`viewray serve`) print the
//! same digits.
//!
//! Numbers are printed as Rust prints an `f64` (the shortest text that reads back to the
//! same number), with `-0` written `0`. Ray directions are not normalized: they are the
//! lecture's formulas evaluated exactly. Pixels are named by 0-based `row`, `col`, or by
//! the lecture's 1-based `i`, `j` ([`PixelIndices`]); the keys say which.
//!
//! ```text
//! frame:    {"e":[..],"u":[..],"v":[..],"w":[..]}
//! rays:     {"row":R,"col":C,"u":U,"v":V,"origin":[..],"direction":[..]}
//! project:  {"point":[..],"x":X,"y":Y,"row":R,"col":C}
//! trace:    {"step":..,"bounce":B,..} per step, then {"row":R,"col":C,"linear":[..],"srgb8":[..]}
//! ```
//!
//! The trace's lines ([`trace_lines`], module `trace`) format viewray-render's
//! [`PixelTrace`](viewray_render::PixelTrace), which is why this crate depends on the
//! renderer's types.
//!
//! This crate knows cameras, the renderer's trace and JSON, and nothing of the command
//! line, files or HTTP.

mod trace;

use std::io::Write;

use glam::{DVec2, DVec3};
use serde_json::{Map, Value, json};
use viewray_camera::{Camera, CameraSample, Frame, pixel_to_image_plane};

pub use crate::trace::{number_f32, trace_lines, vector_f32};

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

/// How a line names a pixel: 0-based `row`, `col` from the top-left, or the lecture's
/// 1-based `i = row + 1`, `j = col + 1`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelIndices {
    /// `row`, `col`, from 0.
    #[default]
    ZeroBased,
    /// `i`, `j`, from 1.
    OneBased,
}

impl PixelIndices {
    /// [`PixelIndices::OneBased`] when `one_based`.
    pub fn one_based_if(one_based: bool) -> PixelIndices {
        if one_based {
            PixelIndices::OneBased
        } else {
            PixelIndices::ZeroBased
        }
    }

    /// The JSON keys of the two indices: `["row", "col"]` or `["i", "j"]`.
    pub fn keys(self) -> [&'static str; 2] {
        match self {
            PixelIndices::ZeroBased => ["row", "col"],
            PixelIndices::OneBased => ["i", "j"],
        }
    }

    /// What is added to a 0-based index to print it: 0 or 1.
    pub fn base(self) -> u32 {
        match self {
            PixelIndices::ZeroBased => 0,
            PixelIndices::OneBased => 1,
        }
    }

    /// The 0-based `(row, col)` of the pixel given as `(first, second)` in these
    /// indices, if it lies in a `width x height` image.
    ///
    /// # Errors
    /// A sentence naming the image and the valid ranges, for a pixel outside it:
    /// `pixel 3,9 is outside the 4 x 3 image: row runs 0..=2 and col 0..=3 (0-based;
    /// --one-based for the lecture's i, j)`.
    pub fn pixel(
        self,
        (first, second): (i64, i64),
        width: u32,
        height: u32,
    ) -> Result<(u32, u32), String> {
        let base = i64::from(self.base());
        let zero_based = |index: i64, size: u32| {
            index
                .checked_sub(base)
                .and_then(|i| u32::try_from(i).ok())
                .filter(|&i| i < size)
        };
        match (zero_based(first, height), zero_based(second, width)) {
            (Some(row), Some(col)) => Ok((row, col)),
            _ => {
                let first_index = u64::from(self.base());
                let last_row = u64::from(height) + first_index - 1;
                let last_col = u64::from(width) + first_index - 1;
                let [row_key, col_key] = self.keys();
                Err(format!(
                    "pixel {first},{second} is outside the {width} x {height} image: {row_key} \
                     runs {first_index}..={last_row} and {col_key} {first_index}..={last_col}{}",
                    match self {
                        PixelIndices::OneBased => " (1-based, the lecture's i, j)",
                        PixelIndices::ZeroBased => " (0-based; --one-based for the lecture's i, j)",
                    }
                ))
            }
        }
    }
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
    // The image-plane point, for the planar families; the panoramic ones have none.
    let uv = camera.projection().viewport().map(|viewport| {
        pixel_to_image_plane(
            row,
            col,
            sample.p_film,
            (camera.width(), camera.height()),
            viewport,
        )
    });
    let [row_key, col_key] = indices.keys();
    let base = u64::from(indices.base());
    let mut line = Map::new();
    line.insert(row_key.into(), json!(u64::from(row) + base));
    line.insert(col_key.into(), json!(u64::from(col) + base));
    line.insert("u".into(), uv.map_or(Value::Null, |uv| number(uv.x)));
    line.insert("v".into(), uv.map_or(Value::Null, |uv| number(uv.y)));
    line.insert(
        "origin".into(),
        ray.map_or(Value::Null, |r| vector(r.origin)),
    );
    line.insert(
        "direction".into(),
        ray.map_or(Value::Null, |r| vector(r.direction)),
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

    #[test]
    fn pixels_outside_the_image_are_named_with_the_valid_ranges() {
        let zero = PixelIndices::ZeroBased;
        let one = PixelIndices::OneBased;
        assert_eq!(zero.pixel((2, 3), 4, 3), Ok((2, 3)));
        assert_eq!(one.pixel((3, 4), 4, 3), Ok((2, 3)));
        assert_eq!(
            zero.pixel((3, 0), 4, 3),
            Err(
                "pixel 3,0 is outside the 4 x 3 image: row runs 0..=2 and col 0..=3 \
                 (0-based; --one-based for the lecture's i, j)"
                    .to_owned()
            )
        );
        assert_eq!(
            one.pixel((0, 1), 4, 3),
            Err(
                "pixel 0,1 is outside the 4 x 3 image: i runs 1..=3 and j 1..=4 \
                 (1-based, the lecture's i, j)"
                    .to_owned()
            )
        );
        assert!(zero.pixel((i64::MIN, 0), 4, 3).is_err());
        assert!(one.pixel((i64::MIN, 1), 4, 3).is_err());
        assert!(zero.pixel((0, i64::MAX), 4, 3).is_err());
        assert!(zero.pixel((i64::MAX, 0), u32::MAX, u32::MAX).is_err());
        assert!(zero.pixel((-1, 0), 4, 3).is_err());
        assert_eq!(
            zero.pixel((i64::from(u32::MAX) - 1, 0), 1, u32::MAX),
            Ok((u32::MAX - 1, 0))
        );
    }
}
