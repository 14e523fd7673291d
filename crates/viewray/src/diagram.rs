//! `viewray diagram`: the side view of a scene's camera, as a PNG or SVG.

use std::io::IsTerminal;
use std::path::PathBuf;

use crate::figures::{Format, write};
use crate::input::load_scene_file;
use anyhow::{Result, anyhow, bail};
use clap::Args;
use viewray_diagram::{SideViewCanvas, SideWindow, side_view};

#[derive(Args, Debug)]
pub(crate) struct DiagramArgs {
    /// The scene file whose camera to draw (`-`: standard input).
    pub(crate) scene: PathBuf,
    /// Where to write it: a .png (1600 x 900 pixels) or an .svg (text as glyph outlines).
    #[arg(short, long, value_name = "OUT.png|OUT.svg")]
    pub(crate) output: PathBuf,
    /// Also draw the viewing ray of this pixel, ROW,COL (0-based from the top-left),
    /// highlighted.
    #[arg(long, value_name = "ROW,COL", value_parser = crate::values::parse_pixel, allow_hyphen_values = true)]
    pub(crate) pixel: Option<(i64, i64)>,
    /// The pixel is given 1-based, as the lecture's (i, j).
    #[arg(long)]
    pub(crate) one_based: bool,
}

/// `viewray diagram`: the side view of the scene's camera (frustum, image plane, a few
/// rays over the scene) to a PNG or SVG, written atomically.
pub(crate) fn diagram(args: &DiagramArgs) -> Result<()> {
    let output = &args.output;
    if output.is_dir() {
        bail!("cannot write {}: it is a directory", output.display());
    }
    let format = Format::from_path(output).ok_or_else(|| {
        anyhow!(
            "cannot write {}: the output must be a .png or .svg file",
            output.display()
        )
    })?;
    let scene = load_scene_file(&args.scene)?;
    let camera = *scene.camera();
    let pixel = match args.pixel {
        None => None,
        Some((row, col)) => {
            let base = i64::from(args.one_based);
            let inside = |index: i64, size: u32| {
                index
                    .checked_sub(base)
                    .and_then(|i| u32::try_from(i).ok())
                    .filter(|&i| i < size)
            };
            let (width, height) = (camera.width(), camera.height());
            match (inside(row, height), inside(col, width)) {
                (Some(r), Some(c)) => Some((r, c)),
                _ => bail!(
                    "pixel {row},{col} is outside the {width} x {height} image: rows run \
                     {base}..={} and columns {base}..={}",
                    i64::from(height) - 1 + base,
                    i64::from(width) - 1 + base
                ),
            }
        }
    };
    let window = SideWindow::fit(&scene, &[camera]);
    let figure = side_view(&scene, &camera, &window, SideViewCanvas::Slide, pixel);
    write(&figure, output, format)?;
    if std::io::stderr().is_terminal() {
        eprintln!(
            "wrote {}: the side view of {}'s camera",
            output.display(),
            args.scene.display()
        );
    }
    Ok(())
}
