//! The subcommands that print numbers and texts: frame, rays, project (the homework
//! numbers, with the conventions they follow) and scene.

use std::io::{BufWriter, IsTerminal, Write};
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use glam::{DVec2, DVec3};
use viewray_camera::{Camera, CameraSample, Frame};
use viewray_json::{PixelIndices, lens_ray_line, project_line, ray_line};

use crate::input::{DEFAULT_SCENE, load_scene_file};
use crate::style;
use crate::values::{parse_lens_point, parse_offset, parse_pixel, parse_vec3};

/// The conventions, after the help of the commands that print numbers. Each line fits
/// in 80 columns, so that clap does not rewrap it.
pub(crate) const CONVENTIONS: &str = "\
Conventions (the lecture's, made exact; docs/cameras.md in the source explains
them with worked examples):

Pixels: an image is W columns by H rows. Pixels are 0-based (row, col) from
the top-left by default; --one-based takes and prints the lecture's 1-based
(i, j) = (row + 1, col + 1), and the JSON keys say which: row/col or i/j.

Frame: e = eye, w = -view/|view|, u = (up x w)/|up x w|, v = w x u; u points
right, v up, w back (the camera looks along -w).

Image plane, at a pixel's centre:

    u = ((j - 1/2)/W - 1/2) vw,   v = -((i - 1/2)/H - 1/2) vh

Perspective ray: origin e, direction u U + v V - d W, with U, V, W the frame's
vectors; directions are not normalized.

Exit codes: 0 success, 1 a comparison failed, 2 bad input or usage, other
values internal errors.";

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct FrameArgs {
    /// A scene file (or - for standard input) whose camera's frame to print, instead of
    /// --eye, --view or --look-at, and --up.
    #[arg(value_name = "SCENE", conflicts_with_all = ["eye", "view", "look_at", "up"])]
    pub(crate) scene: Option<PathBuf>,
    /// The eye position e.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub(crate) eye: Option<DVec3>,
    /// The view direction (or give --look-at).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true,
          conflicts_with = "look_at")]
    pub(crate) view: Option<DVec3>,
    /// A point to look at: view = look_at - eye.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub(crate) look_at: Option<DVec3>,
    /// The up vector; it fixes the camera's roll and need not be perpendicular to view
    /// [default: 0,1,0].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub(crate) up: Option<DVec3>,
}

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct RaysArgs {
    /// The scene file whose camera and image size to use, or - for standard input.
    pub(crate) scene: PathBuf,
    /// A pixel as ROW,COL, 0-based (or I,J with --one-based); repeat the option, or list
    /// several after it. Without it, every pixel.
    #[arg(long, value_name = "ROW,COL", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub(crate) pixel: Vec<(i64, i64)>,
    /// Pixels are given and printed 1-based, as the lecture's (i, j), with the JSON keys
    /// "i" and "j" instead of "row" and "col".
    #[arg(long)]
    pub(crate) one_based: bool,
    /// The point inside each pixel as OX,OY, each in [0, 1) from the pixel's top-left
    /// corner; 0.5,0.5 is the centre, the lecture's ray.
    #[arg(long, value_name = "OX,OY", value_parser = parse_offset, default_value = "0.5,0.5")]
    pub(crate) sample: DVec2,
    /// The point on the lens as LX,LY in unit-disk coordinates (the ray starts at
    /// e + r (LX U + LY V)), instead of the lens centre; for a camera with a lens, the
    /// point on its aperture (the unit disk, or the polygon of its blades).
    #[arg(long, value_name = "LX,LY", value_parser = parse_lens_point, allow_hyphen_values = true)]
    pub(crate) lens: Option<DVec2>,
}

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct ProjectArgs {
    /// The scene file whose camera and image size to use, or - for standard input.
    pub(crate) scene: PathBuf,
    /// A world point as X,Y,Z (repeat the option, or list several after it).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true,
          required = true)]
    pub(crate) point: Vec<DVec3>,
    /// Print the pixel 1-based, as the lecture's (i, j), with the JSON keys "i" and "j"
    /// instead of "row" and "col" (x and y do not change).
    #[arg(long)]
    pub(crate) one_based: bool,
}

#[derive(Args, Debug)]
pub(crate) struct SceneArgs {
    /// Print the built-in default scene, the one `viewray render` renders without a
    /// SCENE.
    #[arg(long, required = true)]
    pub(crate) default: bool,
}

/// `viewray frame`: the camera frame of a scene, or from eye, view (or look-at) and up.
pub(crate) fn frame(args: &FrameArgs) -> Result<()> {
    let line = match &args.scene {
        // A scene's camera adds its plane of focus (and hinge line) where it has a lens.
        Some(scene) => viewray_json::camera_frame_line(load_scene_file(scene)?.camera()),
        None => viewray_json::frame_line(&frame_from_options(args)?),
    };
    let mut out = std::io::stdout().lock();
    viewray_json::write_line(&mut out, &line)?;
    Ok(())
}

/// The frame of `--eye` with `--view` or `--look-at`, and `--up`.
fn frame_from_options(args: &FrameArgs) -> Result<Frame> {
    let usage = |message: &str| crate::usage::usage_error("frame", message);
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
                .map_err(|outside| anyhow::anyhow!(outside.sentence(Some("--one-based"))))
        })
        .collect::<Result<Vec<(u32, u32)>>>()?;
    if let Some(lens) = args.lens {
        check_lens_point(&camera, lens)?;
    }
    note_pixel_convention(args.one_based);
    let sample = CameraSample {
        p_film: args.sample,
        ..CameraSample::CENTER
    };
    let write = |out: &mut BufWriter<_>, row, col| {
        let line = match args.lens {
            Some(lens) => lens_ray_line(&camera, (row, col), args.sample, lens, indices),
            None => ray_line(&camera, (row, col), sample, indices),
        };
        viewray_json::write_line(out, &line)
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

/// `--lens LX,LY` needs a camera with a lens, and a point on its aperture: the unit disk,
/// or the polygon of its blades.
fn check_lens_point(camera: &Camera, lens: DVec2) -> Result<()> {
    let Some(iris) = camera.projection().iris() else {
        bail!(
            "--lens picks a point on the lens, but this {} camera has none: give a ThinLens \
             (or an Orthographic camera with an aperture)",
            camera.projection().family_name()
        );
    };
    if iris.contains(lens) {
        return Ok(());
    }
    if iris.is_round() {
        bail!(
            "--lens {},{} lies outside the lens: LX, LY are unit-disk coordinates, \
             LX^2 + LY^2 <= 1",
            lens.x,
            lens.y
        );
    }
    bail!(
        "--lens {},{} lies outside the aperture: its {} blades make a polygon inside the \
         unit disk, corners on the circle at {} degrees and every 360/{} after",
        lens.x,
        lens.y,
        iris.blades,
        viewray_output::number::label(
            (iris.rotation + std::f64::consts::PI / f64::from(iris.blades)).to_degrees()
        ),
        iris.blades
    )
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
