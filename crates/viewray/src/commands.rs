//! The subcommands.

use std::io::{BufWriter, Write};

use anyhow::{Context, Result, bail};
use glam::DVec2;
use serde_json::{Value, json};
use viewray_camera::{Camera, CameraSample, Frame};
use viewray_scene::Scene;

use crate::cli::{FrameArgs, ProjectArgs, RaysArgs};
use crate::json;

/// `viewray frame`: the camera frame from eye, view (or look-at) and up.
pub(crate) fn frame(args: &FrameArgs) -> Result<()> {
    let frame = match (args.view, args.look_at) {
        (Some(view), _) => Frame::from_eye_view_up(args.eye, view, args.up),
        (None, Some(look_at)) => Frame::from_eye_look_at_up(args.eye, look_at, args.up),
        (None, None) => bail!("give --view or --look-at"),
    }
    .context("cannot build the camera frame")?;
    let line = json!({
        "e": json::vector(frame.e),
        "u": json::vector(frame.u),
        "v": json::vector(frame.v),
        "w": json::vector(frame.w),
    });
    let mut out = std::io::stdout().lock();
    json::write_line(&mut out, &line)?;
    Ok(())
}

fn load_camera(path: &std::path::Path) -> Result<Camera> {
    Ok(*Scene::load(path)?.camera())
}

/// `viewray rays`: the viewing rays of pixels.
pub(crate) fn rays(args: &RaysArgs) -> Result<()> {
    let camera = load_camera(&args.scene)?;
    let (width, height) = (camera.width(), camera.height());
    if !(0.0..1.0).contains(&args.sample.x) || !(0.0..1.0).contains(&args.sample.y) {
        bail!(
            "--sample {},{} lies outside the pixel: each offset must be in [0, 1)",
            args.sample.x,
            args.sample.y
        );
    }
    let base = i64::from(args.one_based);
    let pixels: Vec<(u32, u32)> = if args.pixel.is_empty() {
        (0..height)
            .flat_map(|row| (0..width).map(move |col| (row, col)))
            .collect()
    } else {
        args.pixel
            .iter()
            .map(|&(row, col)| {
                let inside =
                    |index: i64, size: u32| u32::try_from(index - base).ok().filter(|&i| i < size);
                match (inside(row, height), inside(col, width)) {
                    (Some(r), Some(c)) => Ok((r, c)),
                    _ => {
                        let (first, last_row, last_col) = if args.one_based {
                            (1, i64::from(height), i64::from(width))
                        } else {
                            (0, i64::from(height) - 1, i64::from(width) - 1)
                        };
                        bail!(
                            "pixel {row},{col} is outside the {width} x {height} image: rows \
                             run {first}..={last_row} and columns {first}..={last_col}{}",
                            if args.one_based {
                                " (1-based)"
                            } else {
                                " (0-based; --one-based for the lecture's i, j)"
                            }
                        )
                    }
                }
            })
            .collect::<Result<_>>()?
    };
    let sample = CameraSample {
        p_film: args.sample,
        ..CameraSample::CENTER
    };
    let mut out = BufWriter::new(std::io::stdout().lock());
    for (row, col) in pixels {
        let ray = camera.generate_ray(row, col, sample);
        let line = json!({
            "row": i64::from(row) + base,
            "col": i64::from(col) + base,
            "origin": ray.map_or(Value::Null, |r| json::vector(r.origin)),
            "direction": ray.map_or(Value::Null, |r| json::vector(r.direction)),
        });
        json::write_line(&mut out, &line)?;
    }
    out.flush()?;
    Ok(())
}

/// `viewray project`: where points appear in the image.
pub(crate) fn project(args: &ProjectArgs) -> Result<()> {
    let camera = load_camera(&args.scene)?;
    let base = i64::from(args.one_based);
    let mut out = BufWriter::new(std::io::stdout().lock());
    for &point in &args.point {
        let image: Option<DVec2> = camera.project(point);
        let pixel = image.and_then(|xy| camera.pixel_at(xy));
        let line = json!({
            "point": json::vector(point),
            "x": image.map_or(Value::Null, |xy| json::number(xy.x)),
            "y": image.map_or(Value::Null, |xy| json::number(xy.y)),
            "row": pixel.map_or(Value::Null, |(row, _)| json!(i64::from(row) + base)),
            "col": pixel.map_or(Value::Null, |(_, col)| json!(i64::from(col) + base)),
        });
        json::write_line(&mut out, &line)?;
    }
    out.flush()?;
    Ok(())
}
