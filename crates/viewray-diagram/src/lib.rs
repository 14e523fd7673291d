//! Lecture figures as display lists, rendered to PNG with tiny-skia and written as SVG.
//!
//! This crate owns the 2D drawing layer of viewray's figures: a [`Figure`] is a canvas and
//! a list of [`Item`]s (lines, polylines, arrows, dots, polygons, ellipses, [`Label`]s and
//! embedded raster images) in figure pixels, x right and y down. [`Mapping`] lets figure
//! code draw in world units with y up. [`style`] fixes the visual language (colours, line
//! weights, label sizes, the 1600 x 900 slide and 1080 x 1080 square canvases) so every
//! lecture figure matches.
//!
//! [`figures`] draws the lecture's figures on this layer, every 3D point placed with a
//! `viewray-camera` camera's `project` and every ray one its `generate_ray` makes; its
//! registry ([`figures::all_figures`], [`figures::figure_by_name`]) is what `viewray
//! figure(s)` and `cargo xtask figures` list. Pictures inside figures come from a
//! [`figures::Pictures`] source: [`figures::RenderedPictures`] builds each picture's
//! scene in code and renders it with `viewray-render` (the default, what
//! [`figures::NamedFigure::figure`] draws), [`figures::Wireframes`] draws projected
//! polygons instead, without ray tracing.
//!
//! It knows nothing about scene files (it builds `viewray-scene`'s runtime `Scene`
//! directly), and it does no I/O except [`Figure::write_png`] and [`Figure::write_svg`],
//! which write one file atomically.
//!
//! Text is set with the DejaVu Sans faces bundled in the `dejavu` crate (nothing to
//! install), laid out with the font's kerning and rasterized from its glyph outlines with
//! antialiasing. SVG output draws the same outlines as paths by default, so a slide looks
//! identical everywhere; [`SvgText::Elements`] writes editable `<text>` instead. Labels
//! follow the lecture's notation: [`Label::vector`] sets **u** in bold, [`Label::math`]
//! sets *vw* in italics, and `v_h` writes h as a subscript.
//!
//! ```
//! use glam::Vec2;
//! use viewray_diagram::{style, ArrowEnds, Figure, Item, Label, Stroke};
//!
//! let mut figure = Figure::square();
//! let e = Vec2::new(200.0, 800.0);
//! figure.push(Item::Arrow {
//!     from: e,
//!     to: Vec2::new(600.0, 800.0),
//!     stroke: Stroke::new(style::U_AXIS, style::LINE_THICK),
//!     ends: ArrowEnds::End,
//! });
//! figure.push(Label::vector("u", Vec2::new(640.0, 800.0)).with_color(style::U_AXIS));
//! let pixels = figure.render();
//! assert_eq!(pixels.dimensions(), (1080, 1080));
//! assert!(figure.to_svg().contains("<svg"));
//! ```

mod color;
mod figure;
pub mod figures;
mod mapping;
mod raster;
pub mod style;
mod svg;
mod text;

pub use color::Color;
pub use figure::{ArrowEnds, Figure, Item, Rect, Sampling, Stroke, SvgText};
pub use mapping::Mapping;
pub use text::{Anchor, Baseline, FontFace, Label, TextExtent, measure_text};
