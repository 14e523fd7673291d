//! The command line: clap definitions, vector parsing and one-line usage errors.

use std::ffi::OsString;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use glam::{DVec2, DVec3};
use viewray_scene::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES};

const CONVENTIONS: &str = "\
Conventions (the lecture's, made exact): an image is W columns by H rows; pixel (row, col)
is 0-based from the top-left (the lecture's 1-based (i, j) = (row + 1, col + 1), see
--one-based). The camera frame is e, u, v, w with u right, v up and w back (the camera looks
along -w): w = -view/|view|, u = up x w normalized, v = w x u. The pixel centre maps to the
image plane at u = ((j - 1/2)/W - 1/2) vw, v = -((i - 1/2)/H - 1/2) vh, and the perspective
viewing ray is origin e, direction u U + v V - d W, not normalized.

Exit codes: 0 success, 1 a comparison failed, 2 bad input or usage, other values internal
errors.";

/// Ray tracing for learning cameras: render scenes, and check camera frames, viewing rays
/// and projections number by number.
#[derive(Parser, Debug)]
#[command(name = "viewray", version, after_long_help = CONVENTIONS, after_help = CONVENTIONS)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Render a scene file to a PNG (or, with an .exr output, linear floats).
    ///
    /// For each pixel: generate viewing rays, find the closest object each meets, and
    /// determine its colour. Without SCENE, renders the built-in default scene. The image
    /// is the same, byte for byte, on any number of threads. A progress bar is shown on
    /// stderr when it is a terminal.
    Render(RenderArgs),
    /// Print the camera frame (e, u, v, w) built from eye, view (or look-at) and up.
    ///
    /// w = -view / |view|, u = (up x w) / |up x w|, v = w x u; with --look-at, view =
    /// look_at - eye. Prints one JSON line: {"e":[..],"u":[..],"v":[..],"w":[..]}.
    Frame(FrameArgs),
    /// Print the viewing ray of pixels of a scene's camera.
    ///
    /// For pixel (row, col), 0-based from the top-left, the ray goes through the pixel's
    /// centre (and the lens centre): with the lecture's i = row + 1, j = col + 1,
    /// u = ((j - 1/2)/W - 1/2) vw, v = -((i - 1/2)/H - 1/2) vh, and for a perspective camera
    /// origin = e, direction = u U + v V - d W (not normalized). Prints one JSON line per
    /// pixel: {"row":R,"col":C,"origin":[..],"direction":[..]}. Without --pixel, every
    /// pixel, row by row.
    Rays(RaysArgs),
    /// Print where points appear in a scene's camera image.
    ///
    /// x, y are continuous image coordinates: x from the left edge, y from the top, so
    /// pixel (row, col) spans [col, col + 1) x [row, row + 1) and its centre is
    /// (col + 0.5, row + 0.5). row and col name the pixel holding the point, null outside
    /// the image; all four are null where the point is not visible (behind a perspective
    /// eye). Prints one JSON line per point: {"point":[..],"x":X,"y":Y,"row":R,"col":C}.
    Project(ProjectArgs),
    /// Judge renders against reference images, as an instructor would.
    ///
    /// EXPECTED and ACTUAL are two PNG files, or two folders whose *.png files are paired
    /// by name. Antialiasing and sample count are not errors: both images are blurred by
    /// 2 px before NVIDIA's FLIP compares them, so a correct one-sample render passes.
    /// Camera mistakes are errors, and are named from the transform between the images,
    /// measured on the part both show: mirrored ("check u = up x w"), upside down,
    /// rotated ("check the up vector"), scaled ("check vw, vh or d"), shifted by half a
    /// pixel ("check the pixel-centre offset") or more ("check the shift (sx, sy)"); moves
    /// are in pixels, x right and y down. When no transform explains the difference, the
    /// diagnosis says so. With --scene, the diagnosis speaks the lecture's terms: "the
    /// sign of the shift is flipped", "the shift is missing", "your field of view is 1.25
    /// times too wide".
    ///
    /// Prints a table (NAME, VERDICT, PEAK FLIP, DIAGNOSIS) and a summary line, or with
    /// --json one JSON line per pair ({"name", "verdict": "pass" | "fail" | "error",
    /// "peak_flip", "mean_flip", "threshold", "diagnosis", "transform": {"mirrored_left_right",
    /// "upside_down", "rotation" (degrees counterclockwise), "scale", "about", "shift"},
    /// "reasons", "error"})
    /// and a last line {"summary": {"total", "passed", "failed", "errors"}}. Images of
    /// different sizes fail. A pair that cannot be compared (a file on one side only, an
    /// unreadable file, not a PNG) is reported as an error, and every other pair is still
    /// judged. Exit code 0 when every pair passes, 1 when any fails, 2 when a pair could
    /// not be compared or on bad usage.
    Compare(crate::compare::CompareArgs),
    /// Draw one of the lecture's figures to a PNG or SVG.
    ///
    /// Every figure is computed from the camera code: each 3D point is placed by a
    /// camera's projection and each ray drawn is one the camera generates. The pictures
    /// inside figures (the taxonomy's thumbnails, the distortions', the thin lens at two
    /// apertures) are rendered by the ray tracer. Writes a .png or an .svg as OUT's
    /// extension says, atomically. NAME is one of the figures listed below.
    Figure(crate::figures::FigureArgs),
    /// Draw every lecture figure into a folder, as NAME.png and NAME.svg.
    Figures(crate::figures::FiguresArgs),
}

#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    /// The scene file to render; without it, the built-in default scene.
    pub(crate) scene: Option<PathBuf>,
    /// Where to write the image: .png (8-bit sRGB) or .exr (linear 32-bit floats).
    #[arg(short, long, value_name = "OUT.png", default_value = "viewray.png")]
    pub(crate) output: PathBuf,
    /// Samples per pixel, instead of the scene's (1 is the pixel centre, the lecture's
    /// ray).
    #[arg(long, value_name = "N", value_parser = parse_samples)]
    pub(crate) samples: Option<u32>,
    /// The image size as WIDTHxHEIGHT, instead of the scene's; fields of view given in
    /// degrees and presets follow the new aspect ratio.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    /// How many threads to load, build and render on (default: one per core).
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub(crate) threads: Option<usize>,
    /// Print one JSON line of statistics on stdout:
    /// {"triangles":N,"load_s":..,"build_s":..,"render_s":..,"rays":N}. load_s is reading
    /// and parsing the scene and its meshes; build_s is building the BVHs (timed by
    /// building them once more, since loading builds them); render_s is tracing and
    /// shading; rays counts primary, shadow and reflected rays.
    #[arg(long)]
    pub(crate) stats: bool,
}

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct FrameArgs {
    /// The eye position e.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub(crate) eye: DVec3,
    /// The view direction.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true,
          required_unless_present = "look_at", conflicts_with = "look_at")]
    pub(crate) view: Option<DVec3>,
    /// A point to look at: view = look_at - eye.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub(crate) look_at: Option<DVec3>,
    /// The up vector; it fixes the camera's roll and need not be perpendicular to view.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true,
          default_value = "0,1,0")]
    pub(crate) up: DVec3,
}

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct RaysArgs {
    /// The scene file whose camera and image size to use.
    pub(crate) scene: PathBuf,
    /// A pixel as ROW,COL (repeat the option, or list several after it). Without it,
    /// every pixel.
    #[arg(long, value_name = "ROW,COL", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub(crate) pixel: Vec<(i64, i64)>,
    /// Pixels are given and printed 1-based, as the lecture's (i, j).
    #[arg(long)]
    pub(crate) one_based: bool,
    /// The point inside each pixel as SX,SY in [0, 1); 0.5,0.5 is the centre.
    #[arg(long, value_name = "SX,SY", value_parser = parse_vec2, default_value = "0.5,0.5")]
    pub(crate) sample: DVec2,
}

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct ProjectArgs {
    /// The scene file whose camera and image size to use.
    pub(crate) scene: PathBuf,
    /// A world point as X,Y,Z (repeat the option, or list several after it).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true,
          required = true)]
    pub(crate) point: Vec<DVec3>,
    /// Print row and col 1-based, as the lecture's (i, j).
    #[arg(long)]
    pub(crate) one_based: bool,
}

/// Parses `text` as comma-separated finite numbers, exactly `N` of them.
fn parse_numbers<const N: usize>(text: &str, example: &str) -> Result<[f64; N], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let wrong = || format!("expected {N} numbers separated by commas, like {example}");
    if parts.len() != N {
        return Err(wrong());
    }
    let mut numbers = [0.0; N];
    for (number, part) in numbers.iter_mut().zip(parts) {
        *number = part.parse::<f64>().map_err(|_| wrong())?;
        if !number.is_finite() {
            return Err(format!("`{part}` is not a finite number"));
        }
    }
    Ok(numbers)
}

fn parse_vec3(text: &str) -> Result<DVec3, String> {
    parse_numbers::<3>(text, "0,1.5,-2").map(DVec3::from)
}

fn parse_vec2(text: &str) -> Result<DVec2, String> {
    parse_numbers::<2>(text, "0.5,0.5").map(DVec2::from)
}

fn parse_pixel(text: &str) -> Result<(i64, i64), String> {
    let wrong = || "expected a pixel as two whole numbers ROW,COL, like 2,3".to_owned();
    let (row, col) = text.split_once(',').ok_or_else(wrong)?;
    let row = row.trim().parse().map_err(|_| wrong())?;
    let col = col.trim().parse().map_err(|_| wrong())?;
    Ok((row, col))
}

/// Parses an image size `WIDTHxHEIGHT` within the renderer's limits.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let wrong = || "expected the size as WIDTHxHEIGHT in pixels, like 640x480".to_owned();
    let (width, height) = text.split_once(['x', 'X']).ok_or_else(wrong)?;
    let width: u64 = width.trim().parse().map_err(|_| wrong())?;
    let height: u64 = height.trim().parse().map_err(|_| wrong())?;
    if width == 0 || height == 0 {
        return Err(format!(
            "the image must be at least 1 x 1 pixels, found {width} x {height}"
        ));
    }
    let side = u64::from(MAX_IMAGE_SIDE);
    if width > side || height > side {
        return Err(format!(
            "{width} x {height} is too large: each side can be at most {side} pixels"
        ));
    }
    if width * height > MAX_IMAGE_PIXELS {
        return Err(format!(
            "{width} x {height} is too large: at most {MAX_IMAGE_PIXELS} pixels (2^28)"
        ));
    }
    // Both sides are at most MAX_IMAGE_SIDE, so they fit.
    Ok((width as u32, height as u32))
}

/// Parses a number of samples per pixel, 1 to [`MAX_SAMPLES`].
fn parse_samples(text: &str) -> Result<u32, String> {
    let wrong = || format!("expected a whole number of samples from 1 to {MAX_SAMPLES}");
    let samples: u64 = text.trim().parse().map_err(|_| wrong())?;
    match u32::try_from(samples) {
        Ok(samples) if (1..=MAX_SAMPLES).contains(&samples) => Ok(samples),
        _ => Err(wrong()),
    }
}

/// The most render threads `--threads` accepts.
const MAX_THREADS: usize = 1024;

/// Parses a number of threads, 1 to [`MAX_THREADS`].
fn parse_threads(text: &str) -> Result<usize, String> {
    let wrong = || format!("expected a whole number of threads from 1 to {MAX_THREADS}");
    let threads: usize = text.trim().parse().map_err(|_| wrong())?;
    if (1..=MAX_THREADS).contains(&threads) {
        Ok(threads)
    } else {
        Err(wrong())
    }
}

/// Options that take one value each time and may be followed by several:
/// `--point 1,2,3 -4,5,6` means `--point 1,2,3 --point -4,5,6`.
const REPEATABLE: [&str; 2] = ["--point", "--pixel"];

/// Rewrites `--point A B` as `--point A --point B`, so that several values may follow one
/// option while values starting with `-` (negative coordinates) are still values.
pub(crate) fn expand_repeated_values(args: impl IntoIterator<Item = OsString>) -> Vec<OsString> {
    let mut out = Vec::new();
    let mut repeating: Option<OsString> = None;
    let mut just_saw_option = false;
    for arg in args {
        let text = arg.to_str().unwrap_or_default();
        let looks_like_value = !text.is_empty()
            && text.contains(',')
            && text
                .chars()
                .all(|c| c.is_ascii_digit() || ".,-+eE ".contains(c));
        if REPEATABLE.contains(&text) {
            repeating = Some(arg.clone());
            just_saw_option = true;
            out.push(arg);
            continue;
        }
        if let Some(option) = &repeating {
            if looks_like_value {
                if !just_saw_option {
                    out.push(option.clone());
                }
                just_saw_option = false;
                out.push(arg);
                continue;
            }
            repeating = None;
        }
        just_saw_option = false;
        out.push(arg);
    }
    out
}

/// Prints a clap error: help and version as clap formats them, usage errors as one line
/// `error: ...`, exit code 2.
pub(crate) fn report_usage_error(error: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(
        error.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        let _ = error.print();
        return if error.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
            ExitCode::from(crate::EXIT_BAD_INPUT)
        } else {
            ExitCode::SUCCESS
        };
    }
    let text = error.render().to_string();
    let line: Vec<&str> = text
        .lines()
        .map(str::trim)
        .take_while(|line| !line.starts_with("Usage:") && !line.starts_with("For more information"))
        .filter(|line| !line.is_empty())
        .collect();
    let line = line.join(" ");
    let line = line.strip_prefix("error: ").unwrap_or(&line);
    eprintln!("error: {line} (see `viewray --help`)");
    ExitCode::from(crate::EXIT_BAD_INPUT)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn expand(args: &[&str]) -> Vec<String> {
        expand_repeated_values(args.iter().map(OsString::from))
            .into_iter()
            .map(|a| a.into_string().unwrap())
            .collect()
    }

    #[test]
    fn several_values_after_one_option_become_repeated_options() {
        assert_eq!(
            expand(&[
                "viewray",
                "project",
                "s.ron",
                "--point",
                "1,2,3",
                "-4,5,6",
                "--one-based"
            ]),
            [
                "viewray",
                "project",
                "s.ron",
                "--point",
                "1,2,3",
                "--point",
                "-4,5,6",
                "--one-based"
            ]
        );
        assert_eq!(
            expand(&["viewray", "rays", "--pixel", "0,0", "s.ron"]),
            ["viewray", "rays", "--pixel", "0,0", "s.ron"]
        );
    }

    #[test]
    fn sizes_samples_and_threads_are_checked() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("16384X16384"), Ok((16384, 16384)));
        for bad in [
            "0x10",
            "10x0",
            "100000x10",
            "16384x16385",
            "640",
            "640x",
            "axb",
            "-1x5",
        ] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_samples("16"), Ok(16));
        for bad in ["0", "-1", "65537", "99999999999", "x"] {
            assert!(parse_samples(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_threads("2"), Ok(2));
        assert!(parse_threads("0").is_err());
    }

    #[test]
    fn vectors_parse_with_negative_numbers_and_spaces() {
        assert_eq!(parse_vec3("-1, 0,5.5"), Ok(DVec3::new(-1.0, 0.0, 5.5)));
        assert!(parse_vec3("1,2").is_err());
        assert!(parse_vec3("1,2,x").is_err());
        assert!(parse_vec3("1,2,inf").is_err());
        assert_eq!(parse_pixel("2, 3"), Ok((2, 3)));
        assert!(parse_pixel("2.5,3").is_err());
    }
}
