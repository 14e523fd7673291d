//! `viewray figure` and `viewray figures`: the lecture's figures as PNG and SVG files.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use viewray_diagram::{NamedFigure, UnknownFigure, all_figures, figure_by_name};
use viewray_draw::Figure;

#[derive(Args, Debug)]
#[command(after_help = figure_list())]
pub(crate) struct FigureArgs {
    /// The figure's name (the list is below).
    #[arg(value_name = "NAME")]
    pub(crate) name: String,
    /// Where to write it: a .png (1600 x 900 or 1080 x 1080 pixels) or an .svg (text as
    /// glyph outlines, looks the same everywhere). Default: NAME.png.
    #[arg(short, long, value_name = "OUT.png|OUT.svg")]
    pub(crate) output: Option<PathBuf>,
}

#[derive(Args, Debug)]
#[command(after_help = figure_list())]
pub(crate) struct FiguresArgs {
    /// The folder to write NAME.png and NAME.svg into, for every figure; created if
    /// missing, files of the same names replaced.
    #[arg(short, long, value_name = "DIR", default_value = "figures")]
    pub(crate) output: PathBuf,
}

/// The help text listing every figure with its summary, wrapped to 80 columns with
/// the summaries in a column of their own.
fn figure_list() -> String {
    let figures = all_figures();
    let width = figures.iter().map(|f| f.name.len()).max().unwrap_or(0);
    let indent = " ".repeat(2 + width + 2);
    let mut text = String::from("Figures:\n");
    for figure in &figures {
        let mut line = format!("  {:width$}  ", figure.name);
        let mut empty = true;
        for word in figure.summary.split_whitespace() {
            if !empty && line.len() + 1 + word.len() > 80 {
                text.push_str(line.trim_end());
                text.push('\n');
                line = indent.clone();
                empty = true;
            }
            if !empty {
                line.push(' ');
            }
            line.push_str(word);
            empty = false;
        }
        text.push_str(&line);
        text.push('\n');
    }
    text
}

/// The formats a figure can be written in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Format {
    Png,
    Svg,
}

impl Format {
    /// The format named by `path`'s extension (any case).
    pub(crate) fn from_path(path: &Path) -> Option<Format> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "png" => Some(Format::Png),
            "svg" => Some(Format::Svg),
            _ => None,
        }
    }
}

/// Writes `figure` to `path` in `format`, atomically (a temporary file renamed into
/// place); an error names `path`.
pub(crate) fn write(figure: &Figure, path: &Path, format: Format) -> Result<()> {
    match format {
        Format::Png => viewray_draw::write_png(figure, path)?,
        Format::Svg => viewray_draw::write_svg(figure, path)?,
    }
    Ok(())
}

/// `viewray figure`: one figure to a PNG or SVG.
pub(crate) fn figure(args: &FigureArgs) -> Result<()> {
    let named = figure_by_name(&args.name).ok_or_else(|| UnknownFigure::new(&args.name))?;
    let output = args
        .output
        .clone()
        .unwrap_or_else(|| PathBuf::from(format!("{}.png", named.name)));
    if output.is_dir() {
        bail!("cannot write {}: it is a directory", output.display());
    }
    let format = Format::from_path(&output).ok_or_else(|| {
        anyhow!(
            "cannot write {}: the output must be a .png or .svg file",
            output.display()
        )
    })?;
    let start = Instant::now();
    let figure = named.figure();
    write(&figure, &output, format)?;
    if std::io::stderr().is_terminal() {
        eprintln!(
            "wrote {}: {} x {}, in {:.2} s",
            output.display(),
            figure.width,
            figure.height,
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}

/// `viewray figures`: every figure as NAME.png and NAME.svg in a folder.
pub(crate) fn figures(args: &FiguresArgs) -> Result<()> {
    let dir = &args.output;
    if dir.exists() && !dir.is_dir() {
        bail!("cannot write into {}: it is not a directory", dir.display());
    }
    std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let interactive = std::io::stderr().is_terminal();
    let start = Instant::now();
    let figures: Vec<NamedFigure> = all_figures();
    for named in &figures {
        let figure = named.figure();
        for (extension, format) in [("png", Format::Png), ("svg", Format::Svg)] {
            write(
                &figure,
                &dir.join(format!("{}.{extension}", named.name)),
                format,
            )?;
        }
        if interactive {
            eprintln!("wrote {}.png and .svg", dir.join(named.name).display());
        }
    }
    if interactive {
        eprintln!(
            "wrote {} figures to {} in {:.2} s",
            figures.len(),
            dir.display(),
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
