//! 2D drawings as display lists, painted to PNG with tiny-skia and written as SVG.
//!
//! A [`Figure`] is a canvas and a list of [`Item`]s (lines, polylines, arrows, dots,
//! polygons, ellipses, [`Label`]s and embedded raster images) in figure pixels, x right
//! and y down; [`Mapping`] lets drawing code work in world units with y up. The crate
//! knows nothing of cameras, scenes or lectures: it draws what it is given.
//!
//! # Layers
//! Each module uses only those above it in this list, so the model never calls its
//! outputs:
//! - the model: [`Color`], [`Rect`], [`Mapping`]; text ([`Label`], [`FontFace`]: fonts,
//!   markup, layout, measured boxes); the display list
//!   ([`Figure`], [`Item`], [`Stroke`]);
//! - shapes: the geometry every output draws (arrowheads, ellipses, glyph outlines),
//!   computed once so the PNG and the SVG cannot disagree;
//! - outputs: [`raster`] paints a figure into RGBA pixels with tiny-skia, [`svg`] writes
//!   it as an SVG document with an XML writer;
//! - files: [`write_png`] and [`write_svg`] write one file atomically, through
//!   `viewray-output` (its PNG encoder and atomic writer, shared by every viewray crate
//!   that writes a file; the only viewray crate this one uses).
//!
//! # Text
//! Text is set with the DejaVu Sans faces bundled in the `dejavu` crate (no system font
//! is ever read, so output is the same on every machine), laid out with the font's
//! kerning and drawn from its glyph outlines with antialiasing. SVG output draws the same
//! outlines as paths by default, so a drawing looks identical everywhere;
//! [`svg::SvgText::Elements`] writes editable `<text>` instead. [`Label::vector`] sets
//! **u** in bold, [`Label::math`] sets *vw* in italics, and `v_h` writes h as a
//! subscript (see [`Label`]'s markup).
//!
//! # Why PNGs are painted here rather than rasterized from the SVG
//! The SVG could be the single output, rasterized by resvg (the same tiny-skia
//! underneath, text shaped by its own shaper from the same fonts). Measured on the
//! lecture's 14 figures, that would make rasterizing 1.5 to 2.5 times slower (the
//! pictures are PNG-encoded into the document and decoded again), bring some 30 more
//! crates into the build, and still leave the text layout here: figures place labels by
//! their measured boxes, which must come from the same layout that draws them, and
//! resvg's shaper places glyphs a fraction of a pixel away from it. Painting the
//! display list directly keeps one layout, one set of shapes and two thin painters.
//!
//! ```
//! use glam::Vec2;
//! use viewray_draw::{ArrowEnds, Color, Figure, Item, Label, Stroke, raster, svg};
//!
//! let mut figure = Figure::new(1080, 1080);
//! let e = Vec2::new(200.0, 800.0);
//! let vermillion = Color::from_hex(0xD55E00);
//! figure.push(Item::Arrow {
//!     from: e,
//!     to: Vec2::new(600.0, 800.0),
//!     stroke: Stroke::new(vermillion, 5.0),
//!     ends: ArrowEnds::End,
//! });
//! figure.push(Label::vector("u", Vec2::new(640.0, 800.0)).with_color(vermillion));
//! let pixels = raster::render(&figure);
//! assert_eq!(pixels.dimensions(), (1080, 1080));
//! assert!(svg::document(&figure, svg::SvgText::Paths).contains("<svg"));
//! ```

mod color;
mod figure;
mod mapping;
mod output;
pub mod raster;
mod rect;
mod shape;
pub mod svg;
mod text;

pub use color::Color;
pub use figure::{ArrowEnds, Figure, Item, Sampling, Stroke};
pub use mapping::Mapping;
pub use output::{write_png, write_svg};
pub use rect::Rect;
pub use text::{Anchor, Baseline, FontFace, Label, wrap_parts};
