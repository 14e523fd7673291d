//! The subcommands that print numbers and texts: frame, rays, project, scene,
//! completions and man.

use std::io::{BufWriter, IsTerminal, Write};

use anyhow::{Context, Result};
use clap::CommandFactory;
use viewray_camera::{CameraSample, Frame};
use viewray_json::{PixelIndices, project_line, ray_line};

use crate::cli::{Cli, CompletionsArgs, FrameArgs, ManArgs, ProjectArgs, RaysArgs, SceneArgs};
use crate::input::{DEFAULT_SCENE, load_scene_file};
use crate::style;

/// `viewray frame`: the camera frame of a scene, or from eye, view (or look-at) and up.
pub(crate) fn frame(args: &FrameArgs) -> Result<()> {
    let frame = match &args.scene {
        Some(scene) => *load_scene_file(scene)?.camera().frame(),
        None => frame_from_options(args)?,
    };
    let mut out = std::io::stdout().lock();
    viewray_json::write_line(&mut out, &viewray_json::frame_line(&frame))?;
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

/// Says on a terminal which pixel convention the numbers follow (JSON lines on stdout
/// carry it in their keys).
pub(crate) fn note_pixel_convention(one_based: bool) {
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

/// `viewray rays`: the viewing rays of pixels, with their image-plane points.
pub(crate) fn rays(args: &RaysArgs) -> Result<()> {
    let camera = *load_scene_file(&args.scene)?.camera();
    let (width, height) = (camera.width(), camera.height());
    let indices = PixelIndices::one_based_if(args.one_based);
    // Check every pixel before printing any, so that bad input prints nothing.
    let pixels = args
        .pixel
        .iter()
        .map(|&pixel| {
            indices
                .pixel(pixel, width, height)
                .map_err(anyhow::Error::msg)
        })
        .collect::<Result<Vec<(u32, u32)>>>()?;
    note_pixel_convention(args.one_based);
    let sample = CameraSample {
        p_film: args.sample,
        ..CameraSample::CENTER
    };
    let write = |out: &mut BufWriter<_>, row, col| {
        viewray_json::write_line(out, &ray_line(&camera, (row, col), sample, indices))
    };
    let mut out = BufWriter::new(std::io::stdout().lock());
    if pixels.is_empty() {
        // Every pixel, each printed as it is computed: constant memory, and the first
        // lines appear at once however large the image.
        for row in 0..height {
            for col in 0..width {
                write(&mut out, row, col)?;
            }
        }
    } else {
        for (row, col) in pixels {
            write(&mut out, row, col)?;
        }
    }
    out.flush()?;
    Ok(())
}

/// `viewray project`: where points appear in the image.
pub(crate) fn project(args: &ProjectArgs) -> Result<()> {
    let camera = *load_scene_file(&args.scene)?.camera();
    note_pixel_convention(args.one_based);
    let indices = PixelIndices::one_based_if(args.one_based);
    let mut out = BufWriter::new(std::io::stdout().lock());
    for &point in &args.point {
        viewray_json::write_line(&mut out, &project_line(&camera, point, indices))?;
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
