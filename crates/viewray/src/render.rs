//! `viewray render`: load a scene, render it, write the image atomically to a file or to
//! standard output.

use std::io::{Cursor, IsTerminal, Write};
use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{Result, anyhow, bail};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde_json::json;
use viewray_camera::{Camera, Projection};
use viewray_render::{Image, ImageFormat, RenderSettings};
use viewray_scene::{LoadOptions, LoadedScene};

use crate::output::Output;
use crate::style;
use crate::usage::usage_error;
use crate::values::{is_standard_stream, parse_samples, parse_size, parse_threads};

/// The file format of an image written to standard output, or one whose name has no
/// .png or .exr extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum OutputFormat {
    /// 8-bit sRGB PNG.
    Png,
    /// OpenEXR of linear 32-bit floats.
    Exr,
}

impl From<OutputFormat> for ImageFormat {
    fn from(format: OutputFormat) -> Self {
        match format {
            OutputFormat::Png => ImageFormat::Png,
            OutputFormat::Exr => ImageFormat::Exr,
        }
    }
}

#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    /// The scene file to render, or - to read it from standard input (mesh paths are
    /// then relative to the current folder); without it, the built-in default scene.
    pub(crate) scene: Option<PathBuf>,
    /// Where to write the image: .png (8-bit sRGB) or .exr (linear 32-bit floats), or -
    /// for standard output (PNG unless --format says otherwise).
    #[arg(short, long, value_name = "OUT.png", default_value = "viewray.png")]
    pub(crate) output: PathBuf,
    /// The image format, when the output's extension does not say (as for -o -).
    #[arg(long, value_name = "FORMAT")]
    pub(crate) format: Option<OutputFormat>,
    /// Samples per pixel, instead of the scene's (1 is the pixel centre, the lecture's
    /// ray).
    #[arg(long, value_name = "N", value_parser = parse_samples)]
    pub(crate) samples: Option<u32>,
    /// The image size as WIDTHxHEIGHT, instead of the scene's; fields of view and presets
    /// follow the new aspect ratio, an explicit viewport does not (a warning says when
    /// pixels are no longer square).
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

/// `viewray render`: renders a scene (or the default one) to a PNG or EXR.
///
/// `--threads N` bounds the whole command, the BVH builds as well as the render, so
/// that `--threads 1 --stats` times one thread throughout.
pub(crate) fn render(args: &RenderArgs) -> Result<()> {
    match args.threads {
        None => render_on_current_pool(args),
        Some(threads) => rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("viewray-{i}"))
            .build()
            .map_err(|error| anyhow!("cannot start {threads} threads: {error}"))?
            .install(|| render_on_current_pool(args)),
    }
}

/// Where the image goes: a file written atomically, or standard output.
enum Destination {
    File(Output),
    Stdout,
}

/// The image format: `--format`, else the output's extension; PNG on standard output.
fn output_format(args: &RenderArgs) -> Result<ImageFormat> {
    let asked = args.format.map(ImageFormat::from);
    if is_standard_stream(&args.output) {
        return Ok(asked.unwrap_or(ImageFormat::Png));
    }
    match (ImageFormat::from_path(&args.output), asked) {
        (Some(by_name), Some(asked)) if by_name != asked => Err(usage_error(
            "render",
            format!(
                "--format {} disagrees with the output's name {}",
                format_name(asked),
                args.output.display()
            ),
        )),
        (Some(format), _) | (None, Some(format)) => Ok(format),
        (None, None) => bail!(
            "cannot write {}: the output must be a .png or .exr file (or say --format png or \
             --format exr)",
            args.output.display()
        ),
    }
}

fn format_name(format: ImageFormat) -> &'static str {
    match format {
        ImageFormat::Png => "png",
        ImageFormat::Exr => "exr",
    }
}

fn render_on_current_pool(args: &RenderArgs) -> Result<()> {
    let to_stdout = is_standard_stream(&args.output);
    if !to_stdout && args.output.is_dir() {
        bail!("cannot write {}: it is a directory", args.output.display());
    }
    let format = output_format(args)?;
    if to_stdout && args.stats {
        return Err(usage_error(
            "render",
            "--stats prints on standard output, which -o - takes for the image: write the \
             image to a file to see the statistics",
        ));
    }
    let destination = if to_stdout {
        if std::io::stdout().is_terminal() {
            bail!(
                "standard output is a terminal, not a place for a binary image: redirect it \
                 (`-o - > picture.png`) or pipe it into a program"
            );
        }
        Destination::Stdout
    } else {
        // Open the output's temporary file first, so that an unwritable path fails before
        // a long render rather than after it (Ctrl-C deletes it from then on).
        Destination::File(Output::file(&args.output)?)
    };

    // Load the scene (this builds its BVHs too).
    let options = LoadOptions {
        size: args.size,
        samples: args.samples,
    };
    let LoadedScene {
        scene,
        times: load_times,
        ..
    } = crate::input::load_scene(args.scene.as_deref(), options)?;
    if let Some(size) = args.size
        && let Some(warning) = stretched_pixels(scene.camera(), size)
    {
        style::warning(warning);
    }
    check_memory(scene.camera().width(), scene.camera().height(), format)?;

    // Render, with a progress bar on a terminal.
    let interactive = std::io::stderr().is_terminal();
    let bar = progress_bar(interactive);
    // The caller runs this on a pool of `--threads` threads.
    let settings = RenderSettings::default();
    let start = Instant::now();
    let rendered = viewray_render::render(&scene, &settings, |done, total| {
        bar.set_length(total);
        bar.set_position(done);
    })?;
    let render_time = start.elapsed();
    bar.finish_and_clear();

    let written_to = match destination {
        // Write the image beside the output and move it into place.
        Destination::File(output) => {
            output.write_and_commit(|out| rendered.image.write(out, format).map_err(Into::into))?;
            args.output.display().to_string()
        }
        Destination::Stdout => {
            write_to_stdout(&rendered.image, format)?;
            "standard output".to_owned()
        }
    };

    if interactive {
        eprintln!(
            "wrote {written_to}: {} x {}, {} samples per pixel, rendered in {:.2} s",
            rendered.image.width(),
            rendered.image.height(),
            scene.samples(),
            render_time.as_secs_f64()
        );
    }
    if args.stats {
        let line = json!({
            "triangles": scene.world().triangle_count(),
            "load_s": seconds(load_times.total.saturating_sub(load_times.build)),
            "build_s": seconds(load_times.build),
            "render_s": seconds(render_time),
            "rays": rendered.stats.rays,
        });
        let mut out = std::io::stdout().lock();
        viewray_json::write_line(&mut out, &line)?;
        out.flush()?;
    }
    Ok(())
}

/// Encodes the image in memory (EXR needs to seek), then writes it to standard output.
fn write_to_stdout(image: &Image, format: ImageFormat) -> Result<()> {
    let mut encoded = Cursor::new(Vec::new());
    image.write(&mut encoded, format)?;
    let mut out = std::io::stdout().lock();
    out.write_all(encoded.get_ref())?;
    out.flush()?;
    Ok(())
}

/// The warning for `--size` making the pixels of an explicit viewport non-square (a
/// field of view or a preset follows the new aspect ratio; a viewport stays as written,
/// and the picture is stretched). `None` when the pixels are square.
pub(crate) fn stretched_pixels(camera: &Camera, (width, height): (u32, u32)) -> Option<String> {
    let viewport = camera.projection().viewport()?;
    let image_aspect = f64::from(width) / f64::from(height);
    let viewport_aspect = viewport.x / viewport.y;
    if (image_aspect / viewport_aspect - 1.0).abs() <= 1e-3 {
        return None;
    }
    // The size nearest the one asked for with the viewport's aspect ratio: the same
    // width, or where that does not fit, the same height.
    let same_width = (f64::from(width) / viewport_aspect).round();
    let same_height = (f64::from(height) * viewport_aspect).round();
    let side = f64::from(viewray_camera::MAX_IMAGE_SIDE);
    let square = if (1.0..=side).contains(&same_width) {
        Some(format!("{width}x{same_width}"))
    } else if (1.0..=side).contains(&same_height) {
        Some(format!("{same_height}x{height}"))
    } else {
        None
    };
    let instead = match camera.projection() {
        Projection::Perspective(_) | Projection::ThinLens(_) => {
            "a field of view (`fov_y` or `fov_x`) instead of `viewport`"
        }
        _ => "`height` instead of `viewport`",
    };
    let keep = match square {
        Some(size) => format!("use --size {size} (the viewport's aspect ratio), or give {instead}"),
        None => format!("give {instead}"),
    };
    Some(format!(
        "--size {width}x{height} stretches the picture: the scene's viewport is {} x {} \
         (aspect {viewport_aspect:.3}) but the image is {width} x {height} (aspect \
         {image_aspect:.3}), so pixels are no longer square; to keep them square, {keep}",
        viewport.x, viewport.y
    ))
}

/// A duration in seconds, to the microsecond.
pub(crate) fn seconds(duration: Duration) -> f64 {
    (duration.as_secs_f64() * 1e6).round() / 1e6
}

/// A progress bar on stderr, or a hidden one when stderr is not a terminal.
pub(crate) fn progress_bar(interactive: bool) -> ProgressBar {
    if !interactive {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("rendering {wide_bar} {percent:>3}% {elapsed} (eta {eta})")
    {
        bar.set_style(style);
    }
    bar
}

/// Refuses an image whose buffers would not fit in the memory the machine has free,
/// before any of them is allocated.
///
/// A render holds the image as linear floats (12 bytes a pixel) and encodes it to 8-bit
/// (3 bytes) or float (12 bytes) output, plus the encoder's own buffers; twice the
/// encoded size covers those.
fn check_memory(width: u32, height: u32, format: ImageFormat) -> Result<()> {
    check_memory_against(width, height, format, available_memory())
}

fn check_memory_against(
    width: u32,
    height: u32,
    format: ImageFormat,
    available: Option<u64>,
) -> Result<()> {
    let pixels = u64::from(width) * u64::from(height);
    let encoded = match format {
        ImageFormat::Png => 3,
        ImageFormat::Exr => 12,
    };
    let needed = pixels * (12 + 2 * encoded);
    if let Some(available) = available
        && needed > available
    {
        bail!(
            "a {width} x {height} image needs about {:.1} GiB of memory, but only {:.1} GiB is free",
            gib(needed),
            gib(available)
        );
    }
    Ok(())
}

pub(crate) fn gib(bytes: u64) -> f64 {
    bytes as f64 / f64::from(1u32 << 30)
}

/// The memory the system can give this process without swapping (Linux's
/// `MemAvailable`); `None` where the system does not say.
pub(crate) fn available_memory() -> Option<u64> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = meminfo.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_larger_than_free_memory_is_refused_before_rendering() {
        let gib = 1 << 30;
        // 16384 x 16384 PNG: 2^28 pixels at 18 bytes, 4.5 GiB.
        let error = check_memory_against(16384, 16384, ImageFormat::Png, Some(4 * gib))
            .unwrap_err()
            .to_string();
        assert_eq!(
            error,
            "a 16384 x 16384 image needs about 4.5 GiB of memory, but only 4.0 GiB is free"
        );
        assert!(check_memory_against(16384, 16384, ImageFormat::Png, Some(5 * gib)).is_ok());
        assert!(check_memory_against(16384, 16384, ImageFormat::Exr, Some(5 * gib)).is_err());
        // Where the system does not say, the render goes ahead.
        assert!(check_memory_against(16384, 16384, ImageFormat::Exr, None).is_ok());
    }
}
