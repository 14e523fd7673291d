//! Painting a figure into pixels with tiny-skia.
//!
//! ```
//! use viewray_draw::{Figure, raster};
//!
//! let figure = Figure::new(1600, 900);
//! assert_eq!(raster::render(&figure).dimensions(), (1600, 900));
//! assert_eq!(raster::render_scaled(&figure, 0.5).dimensions(), (800, 450));
//! ```

use glam::Vec2;
use image::RgbaImage;
use tiny_skia::{
    ColorU8, FillRule, FilterQuality, LineCap, LineJoin, Paint, Path, PathBuilder, Pattern, Pixmap,
    SpreadMode, StrokeDash, Transform,
};

use crate::shape::{arrow_shape, label_outline};
use crate::{Color, Figure, Item, Rect, Sampling, Stroke};

/// Paints `figure` into antialiased, straight-alpha sRGB pixels (RGBA8), one pixel per
/// figure pixel.
///
/// A figure with a zero width or height renders as an empty image.
pub fn render(figure: &Figure) -> RgbaImage {
    render_scaled(figure, 1.0)
}

/// Paints `figure` scaled by `scale`: the canvas is `round(scale * width) x round(scale *
/// height)` pixels and every item is drawn through the scale, so the picture is the same,
/// only finer or coarser.
pub fn render_scaled(figure: &Figure, scale: f32) -> RgbaImage {
    let size = |side: u32| (side as f32 * scale).round() as u32;
    let (width, height) = (size(figure.width), size(figure.height));
    let Some(mut pixmap) = Pixmap::new(width, height) else {
        return RgbaImage::new(width, height);
    };
    pixmap.fill(skia_color(figure.background));
    let transform = Transform::from_scale(scale, scale);
    for item in &figure.items {
        draw_item(&mut pixmap, item, transform);
    }
    RgbaImage::from_raw(width, height, pixmap.take_demultiplied())
        .expect("a pixmap holds width * height RGBA pixels")
}

/// Paints one display-list item through `transform` (figure space to pixels).
fn draw_item(pixmap: &mut Pixmap, item: &Item, transform: Transform) {
    let fill_path = |pixmap: &mut Pixmap, path: Option<&Path>, color: Color| {
        fill_path(pixmap, path, color, transform);
    };
    let stroke_path = |pixmap: &mut Pixmap, path: Option<&Path>, stroke: &Stroke| {
        stroke_path(pixmap, path, stroke, transform);
    };
    match item {
        Item::Line { from, to, stroke } => {
            stroke_path(pixmap, polyline_path(&[*from, *to], false).as_ref(), stroke);
        }
        Item::Polyline {
            points,
            closed,
            stroke,
        } => stroke_path(pixmap, polyline_path(points, *closed).as_ref(), stroke),
        Item::Arrow {
            from,
            to,
            stroke,
            ends,
        } => {
            let shape = arrow_shape(*from, *to, stroke.width, *ends);
            let shaft = polyline_path(&[shape.shaft.0, shape.shaft.1], false);
            stroke_path(pixmap, shaft.as_ref(), stroke);
            for head in &shape.heads {
                fill_path(pixmap, polyline_path(head, true).as_ref(), stroke.color);
            }
        }
        Item::Dot {
            center,
            radius,
            color,
        } => fill_path(
            pixmap,
            PathBuilder::from_circle(center.x, center.y, *radius).as_ref(),
            *color,
        ),
        Item::Polygon {
            points,
            fill,
            stroke,
        } => {
            let path = polyline_path(points, true);
            fill_path(pixmap, path.as_ref(), *fill);
            if let Some(stroke) = stroke {
                stroke_path(pixmap, path.as_ref(), stroke);
            }
        }
        Item::Ellipse {
            center,
            radii,
            rotation,
            fill,
            stroke,
        } => {
            let path = ellipse_path(*center, *radii, *rotation);
            if let Some(fill) = fill {
                fill_path(pixmap, path.as_ref(), *fill);
            }
            if let Some(stroke) = stroke {
                stroke_path(pixmap, path.as_ref(), stroke);
            }
        }
        Item::Label(label) => fill_path(pixmap, label_outline(label).as_ref(), label.color),
        Item::Image {
            pixels,
            rect,
            sampling,
        } => draw_image(pixmap, pixels, *rect, *sampling, transform),
    }
}

/// The path through `points`, closed or open; `None` for fewer than two points.
fn polyline_path(points: &[Vec2], closed: bool) -> Option<Path> {
    let (first, rest) = points.split_first()?;
    let mut builder = PathBuilder::new();
    builder.move_to(first.x, first.y);
    for p in rest {
        builder.line_to(p.x, p.y);
    }
    if closed {
        builder.close();
    }
    builder.finish()
}

/// An ellipse with semi-axes `radii`, its x axis turned `rotation` radians
/// counter-clockwise on screen.
fn ellipse_path(center: Vec2, radii: Vec2, rotation: f32) -> Option<Path> {
    let oval = tiny_skia::Rect::from_ltrb(
        center.x - radii.x,
        center.y - radii.y,
        center.x + radii.x,
        center.y + radii.y,
    )?;
    // tiny-skia turns clockwise on screen for positive degrees.
    let turn = Transform::from_rotate_at(-rotation.to_degrees(), center.x, center.y);
    PathBuilder::from_oval(oval)?.transform(turn)
}

/// The same colour as tiny-skia's colour type.
fn skia_color(color: Color) -> tiny_skia::Color {
    tiny_skia::Color::from_rgba8(color.r, color.g, color.b, color.a)
}

/// An antialiased solid paint.
fn solid(color: Color) -> Paint<'static> {
    let mut paint = Paint {
        anti_alias: true,
        ..Paint::default()
    };
    paint.set_color(skia_color(color));
    paint
}

/// Fills `path` (non-zero winding) with `color`.
fn fill_path(pixmap: &mut Pixmap, path: Option<&Path>, color: Color, transform: Transform) {
    if let Some(path) = path {
        pixmap.fill_path(path, &solid(color), FillRule::Winding, transform, None);
    }
}

/// Strokes `path` as `stroke` says: round caps and joins, butt caps when dashed.
fn stroke_path(pixmap: &mut Pixmap, path: Option<&Path>, stroke: &Stroke, transform: Transform) {
    let Some(path) = path else {
        return;
    };
    if !(stroke.width > 0.0 && stroke.width.is_finite()) {
        return;
    }
    let dash = stroke
        .dash_pattern()
        .and_then(|pattern| StrokeDash::new(pattern.to_vec(), 0.0));
    let line_cap = if dash.is_some() {
        LineCap::Butt
    } else {
        LineCap::Round
    };
    let skia_stroke = tiny_skia::Stroke {
        width: stroke.width,
        line_cap,
        line_join: LineJoin::Round,
        dash,
        ..tiny_skia::Stroke::default()
    };
    pixmap.stroke_path(path, &solid(stroke.color), &skia_stroke, transform, None);
}

/// Stretches `pixels` over `rect`.
fn draw_image(
    pixmap: &mut Pixmap,
    pixels: &RgbaImage,
    rect: Rect,
    sampling: Sampling,
    transform: Transform,
) {
    let Some(mut source) = Pixmap::new(pixels.width(), pixels.height()) else {
        return;
    };
    for (dst, src) in source.pixels_mut().iter_mut().zip(pixels.pixels()) {
        let [r, g, b, a] = src.0;
        *dst = ColorU8::from_rgba(r, g, b, a).premultiply();
    }
    let Some(target) = tiny_skia::Rect::from_ltrb(rect.min.x, rect.min.y, rect.max.x, rect.max.y)
    else {
        return;
    };
    let quality = match sampling {
        Sampling::Nearest => FilterQuality::Nearest,
        Sampling::Smooth => FilterQuality::Bilinear,
    };
    let image_to_figure = Transform::from_row(
        rect.width() / pixels.width() as f32,
        0.0,
        0.0,
        rect.height() / pixels.height() as f32,
        rect.min.x,
        rect.min.y,
    );
    let paint = Paint {
        shader: Pattern::new(
            source.as_ref(),
            SpreadMode::Pad,
            quality,
            1.0,
            image_to_figure,
        ),
        anti_alias: true,
        ..Paint::default()
    };
    pixmap.fill_rect(target, &paint, transform, None);
}
