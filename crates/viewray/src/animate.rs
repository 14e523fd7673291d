//! `viewray animate`: a scene file's animation or a built-in demo, rendered frame by frame
//! into a looping GIF, an animated PNG or a folder of numbered PNGs, atomically.

use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use serde_json::json;
use viewray_animation::{
    Movie, MovieSettings, all_demos, demo_by_name, write_apng, write_frames, write_gif,
};
use viewray_output::{Compression, MAX_GIF_SIDE};
use viewray_render::RenderSettings;
use viewray_scene::{LoadOptions, LoadedScene};

use crate::output::Output;
use crate::render::{available_memory, gib, progress_bar, seconds, stretched_pixels};
use crate::style;
use crate::values::{
    is_standard_stream, parse_fps, parse_frames, parse_samples, parse_size, parse_threads,
};

#[derive(Args, Debug)]
pub(crate) struct AnimateArgs {
    /// The scene file to animate (it needs an `animation:` section), or - to read it from
    /// standard input.
    #[arg(value_name = "SCENE", conflicts_with_all = ["demo", "list"],
          required_unless_present_any = ["demo", "list"])]
    pub(crate) scene: Option<PathBuf>,
    /// Where to write: OUT.gif (looping GIF), OUT.png (animated PNG) or DIR/ (numbered
    /// PNG frames, DIR/frame_0000.png, ...).
    #[arg(short, long, value_name = "OUT", default_value = "viewray.gif")]
    pub(crate) output: PathBuf,
    /// Animate one of the lecture's demonstrations on its built-in scene.
    #[arg(long, value_name = "NAME", conflicts_with = "list",
          value_parser = clap::builder::PossibleValuesParser::new(viewray_animation::demo_names()))]
    pub(crate) demo: Option<String>,
    /// List the demonstrations, one line each, and exit.
    #[arg(long)]
    pub(crate) list: bool,
    /// How many frames, instead of the animation's (1 to 10000).
    #[arg(long, value_name = "N", value_parser = parse_frames)]
    pub(crate) frames: Option<u32>,
    /// Frames per second, instead of the animation's (1 to 100; a GIF plays at most 50).
    #[arg(long, value_name = "N", value_parser = parse_fps)]
    pub(crate) fps: Option<u32>,
    /// The size of each picture as WIDTHxHEIGHT, instead of the scene's; fields of view
    /// and presets follow the new aspect ratio, as for `render`.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    /// Samples per pixel, instead of the scene's.
    #[arg(long, value_name = "N", value_parser = parse_samples)]
    pub(crate) samples: Option<u32>,
    /// Put the side view of each frame's camera beside its picture.
    #[arg(long)]
    pub(crate) with_diagram: bool,
    /// How many threads to render on (default: one per core).
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub(crate) threads: Option<usize>,
    /// Print one JSON line of statistics on stdout:
    /// {"frames":N,"width":W,"height":H,"render_s":..,"encode_s":..}. render_s is
    /// rendering and laying out the frames; encode_s is choosing the palette, encoding
    /// and writing them (a frame is encoded while the next one renders, so the two can
    /// add up to more than the time taken).
    #[arg(long)]
    pub(crate) stats: bool,
}

/// `viewray animate`.
pub(crate) fn animate(args: &AnimateArgs) -> Result<()> {
    if args.list {
        return list();
    }
    match args.threads {
        None => animate_on_current_pool(args),
        Some(threads) => rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(|i| format!("viewray-{i}"))
            .build()
            .map_err(|error| anyhow!("cannot start {threads} threads: {error}"))?
            .install(|| animate_on_current_pool(args)),
    }
}

/// `--list`: each demo's name and what it shows, one line each.
fn list() -> Result<()> {
    let demos = all_demos();
    let width = demos.iter().map(|d| d.name.len()).max().unwrap_or(0);
    let mut out = std::io::stdout().lock();
    for demo in demos {
        writeln!(out, "{:width$}  {}", demo.name, demo.summary)?;
    }
    out.flush()?;
    Ok(())
}

/// What the output's name asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Format {
    Gif,
    Apng,
    Folder,
}

fn output_format(path: &Path) -> Result<Format> {
    if is_standard_stream(path) {
        bail!(
            "cannot write an animation to standard output: give a .gif, a .png or a folder \
             ending in /"
        );
    }
    let text = path.to_string_lossy();
    if text.ends_with('/') || text.ends_with(std::path::MAIN_SEPARATOR) || path.is_dir() {
        return Ok(Format::Folder);
    }
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
    {
        Some(e) if e == "gif" => Ok(Format::Gif),
        Some(e) if e == "png" => Ok(Format::Apng),
        _ => bail!(
            "cannot write {}: the output must be a .gif (a looping GIF), a .png (an animated \
             PNG) or a folder ending in / (numbered PNG frames)",
            path.display()
        ),
    }
}

fn animate_on_current_pool(args: &AnimateArgs) -> Result<()> {
    let format = output_format(&args.output)?;
    let options = LoadOptions {
        size: args.size,
        samples: args.samples,
    };
    let settings = MovieSettings {
        frames: args.frames,
        fps: args.fps,
        with_diagram: args.with_diagram,
    };
    let movie = match (&args.demo, &args.scene) {
        (Some(name), _) => Movie::from_demo(&demo_by_name(name)?, options, settings)?,
        (None, Some(path)) => {
            let LoadedScene {
                scene, animation, ..
            } = crate::input::load_scene(Some(path), options)?;
            let animation = animation.ok_or_else(|| {
                anyhow!(
                    "{}: the scene has no `animation:` section: add one (keys of cameras \
                     at times in [0, 1], as docs/scene-format.md describes) or animate a \
                     built-in demo (`viewray animate --list`)",
                    crate::input::scene_name(path)
                )
            })?;
            if let Some(size) = args.size
                && let Some(warning) = stretched_pixels(scene.camera(), size)
            {
                style::warning(warning);
            }
            Movie::from_animation(scene, &animation, settings)?
        }
        (None, None) => bail!("give a SCENE with an animation, or --demo NAME"),
    };
    let (width, height) = movie.frame_size();
    if format == Format::Gif && (width > MAX_GIF_SIDE || height > MAX_GIF_SIDE) {
        bail!(
            "a GIF is at most {MAX_GIF_SIDE} pixels a side, but the frames are {width} x \
             {height}: write an animated PNG (.png) or a folder instead"
        );
    }
    check_memory(width, height, available_memory())?;

    // Open the output first, so that an unwritable path fails before a long render
    // (Ctrl-C deletes it from then on).
    let output = match format {
        Format::Folder => Output::folder(&args.output)?,
        Format::Gif | Format::Apng => {
            if args.output.is_dir() {
                bail!("cannot write {}: it is a directory", args.output.display());
            }
            Output::file(&args.output)?
        }
    };
    let interactive = std::io::stderr().is_terminal();
    let bar = progress_bar(interactive);
    if let Ok(style) = indicatif::ProgressStyle::with_template(
        "animating {wide_bar} frame {pos}/{len} {elapsed} (eta {eta})",
    ) {
        bar.set_style(style);
    }
    bar.set_length(u64::from(movie.frames()));
    let settings = RenderSettings::default();
    let on_frame = || bar.inc(1);
    let cannot = || format!("cannot write {}", args.output.display());
    let timings = match format {
        Format::Gif => {
            let out = BufWriter::new(output.writer());
            let (_, timings) = write_gif(&movie, out, &settings, on_frame).with_context(cannot)?;
            timings
        }
        Format::Apng => {
            let out = BufWriter::new(output.writer());
            write_apng(&movie, out, &settings, on_frame).with_context(cannot)?
        }
        Format::Folder => {
            let folder = output.temporary_folder()?;
            write_frames(&movie, &settings, on_frame, |k, frame| {
                let png = viewray_output::encode_png(frame, Compression::Balanced)?;
                viewray_output::write_atomically(folder.join(frame_name(k)), &png)?;
                Ok(())
            })
            .with_context(cannot)?
        }
    };
    let started = Instant::now();
    output.commit(is_frame_name)?;
    let (render_time, encode_time) = (timings.render, timings.encode + started.elapsed());
    bar.finish_and_clear();

    if interactive {
        eprintln!(
            "wrote {}: {} frames, {width} x {height}, {} fps; rendered in {:.1} s, encoded in \
             {:.1} s",
            args.output.display(),
            movie.frames(),
            movie.fps(),
            render_time.as_secs_f64(),
            encode_time.as_secs_f64()
        );
    }
    if args.stats {
        let line = json!({
            "frames": movie.frames(),
            "width": width,
            "height": height,
            "render_s": seconds(render_time),
            "encode_s": seconds(encode_time),
        });
        let mut out = std::io::stdout().lock();
        viewray_json::write_line(&mut out, &line)?;
        out.flush()?;
    }
    Ok(())
}

/// The file name of frame `k` in a folder: `frame_0000.png`.
fn frame_name(k: u32) -> String {
    format!("frame_{k:04}.png")
}

/// Whether `name` is a frame's file name (`frame_` and four or more digits, `.png`).
fn is_frame_name(name: &str) -> bool {
    name.strip_prefix("frame_")
        .and_then(|rest| rest.strip_suffix(".png"))
        .is_some_and(|digits| digits.len() >= 4 && digits.bytes().all(|b| b.is_ascii_digit()))
}

/// Refuses frames whose buffers would not fit in the memory the machine has free: a
/// frame is held as floats (12 bytes a pixel) while it renders and laid out in 8-bit RGBA
/// twice (the pictures and the frame); a GIF keeps three frames for its palette and
/// gives NeuQuant their pixels (4 bytes each): some 48 bytes a pixel in all.
fn check_memory(width: u32, height: u32, available: Option<u64>) -> Result<()> {
    let needed = u64::from(width) * u64::from(height) * 48;
    if let Some(available) = available
        && needed > available
    {
        bail!(
            "frames of {width} x {height} need about {:.1} GiB of memory, but only {:.1} GiB \
             is free",
            gib(needed),
            gib(available)
        );
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_are_told_apart_by_their_names() {
        assert_eq!(output_format(Path::new("a.gif")).unwrap(), Format::Gif);
        assert_eq!(output_format(Path::new("a.GIF")).unwrap(), Format::Gif);
        assert_eq!(output_format(Path::new("a.png")).unwrap(), Format::Apng);
        assert_eq!(output_format(Path::new("frames/")).unwrap(), Format::Folder);
        assert!(output_format(Path::new("a.mp4")).is_err());
        assert!(output_format(Path::new("-")).is_err());
    }

    #[test]
    fn frame_files_are_numbered_from_zero_in_four_digits() {
        assert_eq!(frame_name(0), "frame_0000.png");
        assert_eq!(frame_name(9999), "frame_9999.png");
        assert!(is_frame_name("frame_0042.png"));
        assert!(!is_frame_name("frame_42.png"));
        assert!(!is_frame_name("notes.txt"));
    }

    #[test]
    fn frames_larger_than_free_memory_are_refused() {
        let error = check_memory(4096, 4096, Some(1 << 29))
            .unwrap_err()
            .to_string();
        assert_eq!(
            error,
            "frames of 4096 x 4096 need about 0.8 GiB of memory, but only 0.5 GiB is free"
        );
        assert!(check_memory(4096, 4096, Some(1 << 30)).is_ok());
        assert!(check_memory(4096, 4096, None).is_ok());
    }
}
