//! Writing a figure to a file: PNG or SVG, atomically.

use std::io;
use std::path::Path;

use viewray_output::{Compression, encode_png, write_atomically};

use crate::svg::SvgText;
use crate::{Figure, raster, svg};

/// Paints `figure` ([`raster::render`]) and writes it to `path` as a PNG with no
/// timestamp or other metadata, so the same figure always gives the same bytes.
///
/// The file is written atomically (`viewray_output::write_atomically`): a temporary file
/// in the same directory, renamed over `path` when complete, so a failed run leaves no
/// partial file.
///
/// # Errors
/// An I/O error whose message names `path`, or one of kind `InvalidInput` for a figure
/// with a zero width or height (PNG cannot hold it).
pub fn write_png(figure: &Figure, path: impl AsRef<Path>) -> io::Result<()> {
    let bytes = encode_png(&raster::render(figure), Compression::Balanced)?;
    Ok(write_atomically(path, &bytes)?)
}

/// Writes `figure` to `path` as an SVG document with text as glyph outlines
/// ([`svg::document`] with [`SvgText::Paths`]), atomically as [`write_png`] does.
///
/// # Errors
/// An I/O error whose message names `path`.
pub fn write_svg(figure: &Figure, path: impl AsRef<Path>) -> io::Result<()> {
    let document = svg::document(figure, SvgText::Paths);
    Ok(write_atomically(path, document.as_bytes())?)
}
