//! Writing a figure as an SVG 1.1 document.
//!
//! The geometry is the PNG renderer's: arrowheads from the same `arrow_shape`, ellipses as
//! `<ellipse>` with the same rotation, glyphs from the same outlines. Coordinates are
//! written with at most two decimals, so the document is compact and deterministic.

use std::fmt::Write as _;

use base64::Engine as _;
use glam::Vec2;
use tiny_skia::{Path, PathSegment};
use viewray_output::{Compression, encode_png};

use crate::figure::arrow_shape;
use crate::text::Label;
use crate::{Color, Figure, Item, Rect, Sampling, Stroke, SvgText};

/// The font-family list of `<text>` elements: the bundled face first, then look-alikes.
const FONT_FAMILY: &str = "'DejaVu Sans', Verdana, Arial, Helvetica, sans-serif";

/// The figure as an SVG document.
pub(crate) fn to_svg(figure: &Figure, text: SvgText) -> String {
    let (w, h) = (figure.width, figure.height);
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    out.push_str(&format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" \
         xmlns:xlink=\"http://www.w3.org/1999/xlink\" version=\"1.1\" \
         width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n"
    ));
    if figure.background.a > 0 {
        out.push_str(&format!(
            "<rect width=\"{w}\" height=\"{h}\"{}/>\n",
            fill_attrs(figure.background)
        ));
    }
    for item in &figure.items {
        write_item(&mut out, item, text);
    }
    out.push_str("</svg>\n");
    out
}

/// Writes one display-list item as one element (an arrow as a group).
fn write_item(out: &mut String, item: &Item, text: SvgText) {
    match item {
        Item::Line { from, to, stroke } => {
            if let Some(attrs) = stroke_attrs(stroke) {
                out.push_str(&format!(
                    "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" fill=\"none\"{attrs}/>\n",
                    num(from.x),
                    num(from.y),
                    num(to.x),
                    num(to.y)
                ));
            }
        }
        Item::Polyline {
            points,
            closed,
            stroke,
        } => {
            if let Some(attrs) = stroke_attrs(stroke).filter(|_| points.len() >= 2) {
                let element = if *closed { "polygon" } else { "polyline" };
                out.push_str(&format!(
                    "<{element} points=\"{}\" fill=\"none\"{attrs}/>\n",
                    points_attr(points)
                ));
            }
        }
        Item::Arrow {
            from,
            to,
            stroke,
            ends,
        } => {
            let shape = arrow_shape(*from, *to, stroke.width, *ends);
            out.push_str("<g>\n");
            if let Some(attrs) = stroke_attrs(stroke) {
                let (a, b) = shape.shaft;
                out.push_str(&format!(
                    "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" fill=\"none\"{attrs}/>\n",
                    num(a.x),
                    num(a.y),
                    num(b.x),
                    num(b.y)
                ));
            }
            for head in &shape.heads {
                out.push_str(&format!(
                    "<polygon points=\"{}\"{}/>\n",
                    points_attr(head),
                    fill_attrs(stroke.color)
                ));
            }
            out.push_str("</g>\n");
        }
        Item::Dot {
            center,
            radius,
            color,
        } => out.push_str(&format!(
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{}/>\n",
            num(center.x),
            num(center.y),
            num(*radius),
            fill_attrs(*color)
        )),
        Item::Polygon {
            points,
            fill,
            stroke,
        } => {
            if points.len() >= 2 {
                let outline = stroke.as_ref().and_then(stroke_attrs).unwrap_or_default();
                out.push_str(&format!(
                    "<polygon points=\"{}\"{}{outline}/>\n",
                    points_attr(points),
                    fill_attrs(*fill)
                ));
            }
        }
        Item::Ellipse {
            center,
            radii,
            rotation,
            fill,
            stroke,
        } => {
            let fill = fill.map_or_else(|| " fill=\"none\"".to_owned(), fill_attrs);
            let outline = stroke.as_ref().and_then(stroke_attrs).unwrap_or_default();
            let turn = if *rotation == 0.0 {
                String::new()
            } else {
                format!(
                    " transform=\"rotate({} {} {})\"",
                    num(-rotation.to_degrees()),
                    num(center.x),
                    num(center.y)
                )
            };
            out.push_str(&format!(
                "<ellipse cx=\"{}\" cy=\"{}\" rx=\"{}\" ry=\"{}\"{turn}{fill}{outline}/>\n",
                num(center.x),
                num(center.y),
                num(radii.x),
                num(radii.y)
            ));
        }
        Item::Label(label) => match text {
            SvgText::Paths => write_label_path(out, label),
            SvgText::Elements => write_label_text(out, label),
        },
        Item::Image {
            pixels,
            rect,
            sampling,
        } => write_image(out, pixels, *rect, *sampling),
    }
}

/// A label as one `<path>` of glyph outlines.
fn write_label_path(out: &mut String, label: &Label) {
    if let Some(path) = label.outline_path() {
        out.push_str(&format!(
            "<path aria-label=\"{}\" d=\"{}\"{}/>\n",
            escape(&label.text),
            path_data(&path),
            fill_attrs(label.color)
        ));
    }
}

/// A label as a `<text>` element, its scripts as `<tspan>`s shifted with `dy`.
fn write_label_text(out: &mut String, label: &Label) {
    let layout = label.layout();
    if layout.spans.is_empty() {
        return;
    }
    // The text-anchor point on the label's baseline, in figure pixels.
    let anchor_fraction = match label.anchor {
        crate::Anchor::Start => 0.0,
        crate::Anchor::Middle => 0.5,
        crate::Anchor::End => 1.0,
    };
    let at = label
        .local_to_figure(&layout.extent)
        .transform_point2(Vec2::new(anchor_fraction * layout.extent.width, 0.0));
    let text_anchor = match label.anchor {
        crate::Anchor::Start => "start",
        crate::Anchor::Middle => "middle",
        crate::Anchor::End => "end",
    };
    let (font_style, font_weight) = label.face.svg_style_weight();
    let turn = if label.rotation == 0.0 {
        String::new()
    } else {
        format!(
            " transform=\"rotate({} {} {})\"",
            num(-label.rotation.to_degrees()),
            num(at.x),
            num(at.y)
        )
    };
    let _ = write!(
        out,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"{text_anchor}\" font-family=\"{FONT_FAMILY}\" \
         font-size=\"{}\" font-style=\"{font_style}\" font-weight=\"{font_weight}\"{turn}{}>",
        num(at.x),
        num(at.y),
        num(label.size),
        fill_attrs(label.color)
    );
    let mut shift = 0.0;
    for span in &layout.spans {
        let dy = span.shift - shift;
        shift = span.shift;
        let dy = if dy == 0.0 {
            String::new()
        } else {
            format!(" dy=\"{}\"", num(dy))
        };
        let face = if span.face == label.face {
            String::new()
        } else {
            let (style, weight) = span.face.svg_style_weight();
            format!(" font-style=\"{style}\" font-weight=\"{weight}\"")
        };
        let _ = write!(
            out,
            "<tspan font-size=\"{}\"{dy}{face}>{}</tspan>",
            num(span.size),
            escape(&span.text)
        );
    }
    out.push_str("</text>\n");
}

/// An embedded image as a base64 PNG data URI.
///
/// SVG viewers disagree on `image-rendering` (librsvg, for one, always smooths), so a
/// [`Sampling::Nearest`] image is embedded enlarged by a whole factor, each pixel a
/// solid block, and looks pixelated even where the hint is ignored.
fn write_image(out: &mut String, pixels: &image::RgbaImage, rect: Rect, sampling: Sampling) {
    let png = match sampling {
        Sampling::Nearest => encode_png(&enlarge_for(pixels, rect), Compression::Balanced),
        Sampling::Smooth => encode_png(pixels, Compression::Balanced),
    };
    let Ok(png) = png else {
        return;
    };
    let rendering = match sampling {
        Sampling::Nearest => {
            " image-rendering=\"optimizeSpeed\" style=\"image-rendering:pixelated\""
        }
        Sampling::Smooth => " image-rendering=\"optimizeQuality\"",
    };
    out.push_str(&format!(
        "<image x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" preserveAspectRatio=\"none\"{rendering} \
         xlink:href=\"data:image/png;base64,{}\"/>\n",
        num(rect.min.x),
        num(rect.min.y),
        num(rect.width()),
        num(rect.height()),
        base64::engine::general_purpose::STANDARD.encode(png)
    ));
}

/// `pixels` enlarged by the whole factor that makes them at least as large as `rect`
/// (at most 64, and at most 4096 pixels a side), every pixel repeated as a block.
fn enlarge_for(pixels: &image::RgbaImage, rect: Rect) -> image::RgbaImage {
    const MAX_SIDE: u32 = 4096;
    let (w, h) = pixels.dimensions();
    if w == 0 || h == 0 {
        return pixels.clone();
    }
    let wanted = (rect.width() / w as f32)
        .max(rect.height() / h as f32)
        .ceil();
    let wanted = if wanted.is_finite() {
        wanted.clamp(1.0, 64.0) as u32
    } else {
        1
    };
    let factor = wanted.min(MAX_SIDE / w.max(h)).max(1);
    if factor == 1 {
        return pixels.clone();
    }
    image::RgbaImage::from_fn(w * factor, h * factor, |x, y| {
        *pixels.get_pixel(x / factor, y / factor)
    })
}

/// ` fill="#rrggbb"` and, if translucent, ` fill-opacity="a"`.
fn fill_attrs(color: Color) -> String {
    let mut attrs = format!(" fill=\"{}\"", color.svg_hex());
    if let Some(opacity) = color.svg_opacity() {
        let _ = write!(attrs, " fill-opacity=\"{}\"", opacity_num(opacity));
    }
    attrs
}

/// The stroke attributes, or `None` for a stroke too thin to draw.
fn stroke_attrs(stroke: &Stroke) -> Option<String> {
    if !(stroke.width > 0.0 && stroke.width.is_finite()) {
        return None;
    }
    let mut attrs = format!(
        " stroke=\"{}\" stroke-width=\"{}\" stroke-linejoin=\"round\"",
        stroke.color.svg_hex(),
        num(stroke.width)
    );
    if let Some(opacity) = stroke.color.svg_opacity() {
        let _ = write!(attrs, " stroke-opacity=\"{}\"", opacity_num(opacity));
    }
    match stroke.dash_pattern() {
        Some(pattern) => {
            let pattern: Vec<String> = pattern.iter().map(|d| num(*d)).collect();
            let _ = write!(
                attrs,
                " stroke-linecap=\"butt\" stroke-dasharray=\"{}\"",
                pattern.join(" ")
            );
        }
        None => attrs.push_str(" stroke-linecap=\"round\""),
    }
    Some(attrs)
}

/// `x,y x,y ...` for `points` attributes.
fn points_attr(points: &[Vec2]) -> String {
    let points: Vec<String> = points
        .iter()
        .map(|p| format!("{},{}", num(p.x), num(p.y)))
        .collect();
    points.join(" ")
}

/// Path data (`M`, `L`, `Q`, `C`, `Z`) for a tiny-skia path.
fn path_data(path: &Path) -> String {
    let mut d = String::new();
    for segment in path.segments() {
        let _ = match segment {
            PathSegment::MoveTo(p) => write!(d, "M{} {}", num(p.x), num(p.y)),
            PathSegment::LineTo(p) => write!(d, "L{} {}", num(p.x), num(p.y)),
            PathSegment::QuadTo(c, p) => {
                write!(d, "Q{} {} {} {}", num(c.x), num(c.y), num(p.x), num(p.y))
            }
            PathSegment::CubicTo(c1, c2, p) => write!(
                d,
                "C{} {} {} {} {} {}",
                num(c1.x),
                num(c1.y),
                num(c2.x),
                num(c2.y),
                num(p.x),
                num(p.y)
            ),
            PathSegment::Close => write!(d, "Z"),
        };
    }
    d
}

/// A coordinate with at most two decimals and no trailing zeros (`12.5`, `3`, `-0.25`).
fn num(x: f32) -> String {
    let rounded = (x * 100.0).round() / 100.0;
    if rounded == 0.0 {
        "0".to_owned()
    } else {
        format!("{rounded}")
    }
}

/// An opacity with three decimals at most.
fn opacity_num(x: f32) -> String {
    let rounded = (x * 1000.0).round() / 1000.0;
    format!("{rounded}")
}

/// Escapes text for XML attribute values and character data.
fn escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            '\'' => escaped.push_str("&apos;"),
            c if c.is_control() => {}
            c => escaped.push(c),
        }
    }
    escaped
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_short() {
        let cases = [
            (3.0, "3"),
            (12.5, "12.5"),
            (-0.25, "-0.25"),
            (1.23456, "1.23"),
            (-0.001, "0"),
            (1599.999, "1600"),
        ];
        for (x, expected) in cases {
            assert_eq!(num(x), expected, "num({x})");
        }
    }

    #[test]
    fn escapes_markup_characters() {
        assert_eq!(escape("a<b & \"c\"\n"), "a&lt;b &amp; &quot;c&quot;");
    }
}
