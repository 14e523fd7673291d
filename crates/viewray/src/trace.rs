//! `viewray trace`: one pixel's trace, the lecture's pseudocode with every number, as
//! indented text for a student or as JSON lines.
//!
//! The numbers are viewray-render's (`trace_pixel`, the renderer's own code) and the
//! camera's; the text and the JSON lines are viewray-json's (`trace_text`,
//! `trace_lines`), as the playground shows them.

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use viewray_json::PixelIndices;
use viewray_render::{RenderSettings, View, trace_pixel};

use crate::commands::CONVENTIONS;
use crate::values::parse_pixel;

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct TraceArgs {
    /// The scene file to trace, or - for standard input.
    pub(crate) scene: PathBuf,
    /// The pixel as ROW,COL, 0-based (or I,J with --one-based).
    #[arg(long, value_name = "ROW,COL", value_parser = parse_pixel, allow_hyphen_values = true,
          required = true)]
    pub(crate) pixel: (i64, i64),
    /// The pixel is given and printed 1-based, as the lecture's (i, j), with the JSON
    /// keys "i" and "j" instead of "row" and "col".
    #[arg(long)]
    pub(crate) one_based: bool,
    /// Print one JSON line per step instead of the text.
    #[arg(long)]
    pub(crate) json: bool,
}

/// `viewray trace`: the trace of one pixel of the scene's one-sample render.
pub(crate) fn trace(args: &TraceArgs) -> Result<()> {
    // As the scene file says; the trace is of the image with one sample per pixel
    // whatever the file's samples (`trace_pixel` takes one).
    let scene = crate::input::load_scene_file(&args.scene)?;
    let camera = *scene.camera();
    let indices = PixelIndices::one_based_if(args.one_based);
    let (row, col) = indices
        .pixel(args.pixel, camera.width(), camera.height())
        .map_err(|outside| anyhow::anyhow!(outside.sentence(Some("--one-based"))))?;
    crate::commands::note_pixel_convention(args.one_based);
    let view = View::of(&scene);
    // Checked just above: the pixel is in the image.
    let trace = trace_pixel(&scene, &view, &RenderSettings::default(), row, col)?;
    let mut out = BufWriter::new(std::io::stdout().lock());
    if args.json {
        for line in viewray_json::trace_lines(&camera, &trace, indices) {
            viewray_json::write_line(&mut out, &line)?;
        }
    } else {
        let text = viewray_json::trace_text(
            &camera,
            view.shading,
            &trace,
            "`viewray render --samples 1`",
        );
        out.write_all(text.as_bytes())?;
    }
    out.flush()?;
    Ok(())
}
