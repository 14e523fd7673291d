//! Writing a figure to a file: PNG or SVG, atomically.

use std::io::{self, Write as _};
use std::path::Path;

use crate::svg::SvgText;
use crate::{Figure, raster, svg};

/// Paints `figure` ([`raster::render`]) and writes it to `path` as a PNG with no
/// timestamp or other metadata, so the same figure always gives the same bytes.
///
/// The file is written atomically: a temporary file in the same directory, renamed over
/// `path` when complete, so a failed run leaves no partial file.
///
/// # Errors
/// Any I/O error, or one of kind `InvalidInput` for a figure with a zero width or height
/// (PNG cannot hold it).
pub fn write_png(figure: &Figure, path: impl AsRef<Path>) -> io::Result<()> {
    let bytes = crate::png::encode_png(&raster::render(figure))?;
    write_atomically(path.as_ref(), &bytes)
}

/// Writes `figure` to `path` as an SVG document with text as glyph outlines
/// ([`svg::document`] with [`SvgText::Paths`]), atomically as [`write_png`] does.
///
/// # Errors
/// Any I/O error.
pub fn write_svg(figure: &Figure, path: impl AsRef<Path>) -> io::Result<()> {
    let document = svg::document(figure, SvgText::Paths);
    write_atomically(path.as_ref(), document.as_bytes())
}

/// Writes `bytes` to `path` through a temporary file in the same directory that is
/// renamed over `path` once complete: readers see the old file or the new one, never a
/// partial one, and a failure leaves no stray file behind.
fn write_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    let directory = match path.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent,
        _ => Path::new("."),
    };
    let mut builder = tempfile::Builder::new();
    builder.prefix(".viewray-figure-").suffix(".tmp");
    // The temporary file is private (0600) by default; a figure is an ordinary file.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut file = builder.tempfile_in(directory)?;
    file.write_all(bytes)?;
    file.as_file().sync_all()?;
    file.persist(path).map_err(|e| e.error)?;
    Ok(())
}
