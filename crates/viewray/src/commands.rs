//! The subcommands that print numbers and texts: frame, rays, project, scene,
//! completions and man.

use std::io::{BufWriter, IsTerminal, Write};

use anyhow::{Context, Result, bail};
use clap::CommandFactory;
use glam::DVec2;
use serde_json::{Map, Value, json};
use viewray_camera::{Camera, CameraSample, Frame, pixel_to_image_plane};

use crate::cli::{Cli, CompletionsArgs, FrameArgs, ManArgs, ProjectArgs, RaysArgs, SceneArgs};
use crate::input::{DEFAULT_SCENE, load_scene_file};
use crate::{json, style};

/// `viewray frame`: the camera frame of a scene, or from eye, view (or look-at) and up.
pub(crate) fn frame(args: &FrameArgs) -> Result<()> {
    let frame = match &args.scene {
        Some(scene) => *load_scene_file(scene)?.camera().frame(),
        None => frame_from_options(args)?,
    };
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

/// The frame of `--eye` with `--view` or `--look-at`, and `--up`.
fn frame_from_options(args: &FrameArgs) -> Result<Frame> {
    let usage = |message: &str| crate::cli::usage_error("frame", message);
    let Some(eye) = args.eye else {
        return Err(usage(
            "give the camera as a SCENE file, or as --eye X,Y,Z with --view X,Y,Z or \
             --look-at X,Y,Z",
        ));
    };
    let up = args.up.unwrap_or(glam::DVec3::Y);
    match (args.view, args.look_at) {
        (Some(view), _) => Frame::from_eye_view_up(eye, view, up),
        (None, Some(look_at)) => Frame::from_eye_look_at_up(eye, look_at, up),
        (None, None) => {
            return Err(usage(
                "--eye needs a direction to look in: --view X,Y,Z (a direction) or \
                 --look-at X,Y,Z (a point to look at)",
            ));
        }
    }
    .context("cannot build the camera frame")
}

/// The JSON keys of a pixel's two indices: the library's `row`, `col`, or the lecture's
/// 1-based `i`, `j`.
fn pixel_keys(one_based: bool) -> [&'static str; 2] {
    if one_based {
        ["i", "j"]
    } else {
        ["row", "col"]
    }
}

/// Says on a terminal which pixel convention the numbers follow (JSON lines on stdout
/// carry it in their keys).
fn note_pixel_convention(one_based: bool) {
    if !std::io::stderr().is_terminal() {
        return;
    }
    if one_based {
        style::note(
            "pixels are the lecture's 1-based (i, j): i counts rows from the top, j columns \
             from the left",
        );
    } else {
        style::note(
            "pixels are 0-based (row, col) from the top-left; --one-based takes and prints \
             the lecture's (i, j) = (row + 1, col + 1)",
        );
    }
}

/// The 0-based index of the 0- or 1-based `index` (`base` 0 or 1), if it is inside
/// `0..size`.
fn zero_based(index: i64, base: i64, size: u32) -> Option<u32> {
    index
        .checked_sub(base)
        .and_then(|i| u32::try_from(i).ok())
        .filter(|&i| i < size)
}

/// `viewray rays`: the viewing rays of pixels, with their image-plane points.
pub(crate) fn rays(args: &RaysArgs) -> Result<()> {
    let camera = *load_scene_file(&args.scene)?.camera();
    let (width, height) = (camera.width(), camera.height());
    let base = i64::from(args.one_based);
    // Check every pixel before printing any, so that bad input prints nothing.
    let pixels = args
        .pixel
        .iter()
        .map(
            |&(row, col)| match (zero_based(row, base, height), zero_based(col, base, width)) {
                (Some(r), Some(c)) => Ok((r, c)),
                _ => {
                    let [first, last_row, last_col] = if args.one_based {
                        [1, u64::from(height), u64::from(width)]
                    } else {
                        [0, u64::from(height) - 1, u64::from(width) - 1]
                    };
                    let [row_key, col_key] = pixel_keys(args.one_based);
                    bail!(
                        "pixel {row},{col} is outside the {width} x {height} image: {row_key} \
                         runs {first}..={last_row} and {col_key} {first}..={last_col}{}",
                        if args.one_based {
                            " (1-based, the lecture's i, j)"
                        } else {
                            " (0-based; --one-based for the lecture's i, j)"
                        }
                    )
                }
            },
        )
        .collect::<Result<Vec<(u32, u32)>>>()?;
    note_pixel_convention(args.one_based);
    let printer = RayPrinter {
        camera: &camera,
        sample: CameraSample {
            p_film: args.sample,
            ..CameraSample::CENTER
        },
        keys: pixel_keys(args.one_based),
        base: u64::from(args.one_based),
    };
    let mut out = BufWriter::new(std::io::stdout().lock());
    if pixels.is_empty() {
        // Every pixel, each printed as it is computed: constant memory, and the first
        // lines appear at once however large the image.
        for row in 0..height {
            for col in 0..width {
                printer.write(&mut out, row, col)?;
            }
        }
    } else {
        for (row, col) in pixels {
            printer.write(&mut out, row, col)?;
        }
    }
    out.flush()?;
    Ok(())
}

/// Prints the JSON line of a pixel's viewing ray.
struct RayPrinter<'a> {
    camera: &'a Camera,
    sample: CameraSample,
    /// The keys of the two indices.
    keys: [&'static str; 2],
    /// What to add to a 0-based index to print it: 0, or 1 for the lecture's i, j.
    base: u64,
}

impl RayPrinter<'_> {
    fn write(&self, out: &mut impl Write, row: u32, col: u32) -> std::io::Result<()> {
        let camera = self.camera;
        let ray = camera.generate_ray(row, col, self.sample);
        // The image-plane point, for the planar families; the panoramic ones have none.
        let uv = camera.projection().viewport().map(|viewport| {
            pixel_to_image_plane(
                row,
                col,
                self.sample.p_film,
                (camera.width(), camera.height()),
                viewport,
            )
        });
        let mut line = Map::new();
        line.insert(self.keys[0].into(), json!(u64::from(row) + self.base));
        line.insert(self.keys[1].into(), json!(u64::from(col) + self.base));
        line.insert("u".into(), uv.map_or(Value::Null, |uv| json::number(uv.x)));
        line.insert("v".into(), uv.map_or(Value::Null, |uv| json::number(uv.y)));
        line.insert(
            "origin".into(),
            ray.map_or(Value::Null, |r| json::vector(r.origin)),
        );
        line.insert(
            "direction".into(),
            ray.map_or(Value::Null, |r| json::vector(r.direction)),
        );
        json::write_line(out, &Value::Object(line))
    }
}

/// `viewray project`: where points appear in the image.
pub(crate) fn project(args: &ProjectArgs) -> Result<()> {
    let camera = *load_scene_file(&args.scene)?.camera();
    note_pixel_convention(args.one_based);
    let [row_key, col_key] = pixel_keys(args.one_based);
    let base = u64::from(args.one_based);
    let mut out = BufWriter::new(std::io::stdout().lock());
    for &point in &args.point {
        let image: Option<DVec2> = camera.project(point);
        let pixel = image.and_then(|xy| camera.pixel_at(xy));
        let mut line = Map::new();
        line.insert("point".into(), json::vector(point));
        line.insert(
            "x".into(),
            image.map_or(Value::Null, |xy| json::number(xy.x)),
        );
        line.insert(
            "y".into(),
            image.map_or(Value::Null, |xy| json::number(xy.y)),
        );
        line.insert(
            row_key.into(),
            pixel.map_or(Value::Null, |(row, _)| json!(u64::from(row) + base)),
        );
        line.insert(
            col_key.into(),
            pixel.map_or(Value::Null, |(_, col)| json!(u64::from(col) + base)),
        );
        json::write_line(&mut out, &Value::Object(line))?;
    }
    out.flush()?;
    Ok(())
}

/// `viewray scene --default`: the built-in default scene's text.
pub(crate) fn scene(args: &SceneArgs) -> Result<()> {
    debug_assert!(args.default, "clap requires --default");
    let mut out = std::io::stdout().lock();
    out.write_all(DEFAULT_SCENE.as_bytes())?;
    out.flush()?;
    Ok(())
}

/// `viewray completions SHELL`: the shell's completion script.
pub(crate) fn completions(args: &CompletionsArgs) -> Result<()> {
    // Into memory first: clap_complete panics when its writer fails (as a closed pipe
    // makes it), and a write error here is reported like any other.
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut Cli::command(), "viewray", &mut script);
    let mut out = std::io::stdout().lock();
    out.write_all(&script)?;
    out.flush()?;
    Ok(())
}

/// `viewray man [COMMAND]`: a man page, in roff.
pub(crate) fn man(args: &ManArgs) -> Result<()> {
    let mut command = Cli::command();
    // Building names the subcommands `viewray-NAME`, as their pages are called.
    command.build();
    let page = match &args.command {
        None => command,
        Some(name) => match command.find_subcommand(name) {
            Some(subcommand) => subcommand.clone(),
            None => {
                let names: Vec<&str> = command
                    .get_subcommands()
                    .map(clap::Command::get_name)
                    .filter(|n| *n != "help")
                    .collect();
                return Err(crate::cli::usage_error(
                    "man",
                    format!("no command `{name}`: one of {}", names.join(", ")),
                ));
            }
        },
    };
    let mut out = BufWriter::new(std::io::stdout().lock());
    clap_mangen::Man::new(page)
        .source(format!("viewray {}", crate::cli::VERSION))
        .manual("viewray manual")
        .render(&mut out)?;
    out.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_convert_without_overflow() {
        assert_eq!(zero_based(0, 0, 2), Some(0));
        assert_eq!(zero_based(1, 1, 2), Some(0));
        assert_eq!(zero_based(2, 1, 2), Some(1));
        assert_eq!(zero_based(2, 0, 2), None);
        assert_eq!(zero_based(0, 1, 2), None);
        assert_eq!(zero_based(i64::MIN, 1, 2), None);
        assert_eq!(zero_based(i64::MAX, 0, u32::MAX), None);
        assert_eq!(zero_based(-1, 0, 2), None);
    }
}
