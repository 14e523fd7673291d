//! What viewray writes, written one way: colour encodings, numbers as text, PNG files,
//! animations and atomic file writes, shared by every crate that produces an image, a
//! text or a file.
//!
//! This crate is a leaf: it depends on no other viewray crate, so the renderer, the
//! figures, the image comparison (which knows no other viewray crate) and the automation
//! can all use it. It owns five things:
//!
//! - [`color`]: the sRGB transfer function, once, and the types that say which encoding a
//!   colour is in: [`LinearRgb`] (linear light, as scene files, the renderer and EXR hold
//!   it) and [`Srgb8`] (8-bit sRGB, as PNG files and figures store it).
//! - [`number`]: numbers as text, one rule per kind of reader (labels people read, SVG
//!   coordinates, values other programs read back), none of them ever writing minus zero.
//! - [`png`]: the one PNG encoder. Fixed settings and no ancillary chunks (no time, no
//!   text, no gamma): the same pixels always give the same bytes.
//! - [`animation`]: looping GIF and animated PNG, written frame by frame, with the same
//!   promise: the same frames always give the same bytes.
//! - [`file`](mod@file): every file viewray writes goes through [`write_atomically`] or
//!   [`AtomicFile`]: written to a temporary file beside the target, flushed to disk, and
//!   renamed over the target only when complete, so a reader sees the old file or the new
//!   one, never a part; a failure leaves the target as it was and no stray file behind.
//!   Errors name the path the caller gave, never the temporary file.
//!
//! ```
//! use viewray_output::{Compression, LinearRgb, Srgb8, encode_png};
//!
//! // Linear 0.5 is stored as sRGB code 188, not 128.
//! assert_eq!(LinearRgb([0.5, 0.0, 1.0]).to_srgb8(), Srgb8([188, 0, 255]));
//! let pixels = image::RgbImage::from_pixel(2, 1, image::Rgb([188, 0, 255]));
//! let png = encode_png(&pixels, Compression::Balanced)?;
//! assert_eq!(png, encode_png(&pixels, Compression::Balanced)?);
//! # Ok::<(), std::io::Error>(())
//! ```

pub mod animation;
pub mod color;
pub mod file;
pub mod number;
pub mod png;

pub use animation::{ApngWriter, GifPalette, GifWriter, MAX_GIF_SIDE};
pub use color::{LinearRgb, Srgb8, linear_to_srgb, linear_to_srgb8, srgb_to_linear, unit_to_u8};
pub use file::{AtomicFile, WriteError, write_atomically};
pub use png::{Compression, encode_png, write_png};
