//! Writing a figure as an SVG 1.1 document.
//!
//! The geometry is the PNG painter's: arrowheads and glyph outlines from the same
//! functions, ellipses as `<ellipse>` with the same rotation. Coordinates are written with
//! at most two decimals ([`SvgNumber`]), so the document is compact and deterministic.
//! The XML is written by quick-xml, which escapes every attribute value and text node.
//!
//! ```
//! use glam::Vec2;
//! use viewray_draw::{Figure, Label, svg};
//!
//! let mut figure = Figure::new(400, 100);
//! figure.push(Label::new("a < b", Vec2::new(200.0, 50.0)));
//! let document = svg::document(&figure, svg::SvgText::Paths);
//! assert!(document.contains(r#"aria-label="a &lt; b""#));
//! ```

use std::fmt::Display;

use base64::Engine as _;
use glam::Vec2;
use quick_xml::Writer;
use quick_xml::events::{BytesDecl, BytesEnd, BytesStart, BytesText, Event};
use tiny_skia::{Path, PathSegment};
use viewray_output::number::SvgNumber;
use viewray_output::{Compression, encode_png};

use crate::shape::{arrow_shape, label_outline};
use crate::text::Label;
use crate::{Anchor, Color, Figure, FontFace, Item, Rect, Sampling, Stroke};

/// The font-family list of `<text>` elements: the bundled face first, then look-alikes.
const FONT_FAMILY: &str = "'DejaVu Sans', Verdana, Arial, Helvetica, sans-serif";

/// How SVG output draws text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SvgText {
    /// Each label is a `<path>` of its glyph outlines from the bundled font, with an
    /// `aria-label` holding the text: identical to the PNG in every viewer, but the text
    /// cannot be edited as text.
    #[default]
    Paths,
    /// Each label is a `<text>` element (sub- and superscripts as `<tspan>`s) with the
    /// font-family list `'DejaVu Sans', Verdana, Arial, Helvetica, sans-serif`: editable
    /// in Inkscape or PowerPoint, but drawn with whatever font the viewer finds.
    Elements,
}

/// `figure` as a standalone SVG document, its labels drawn as `text` says.
pub fn document(figure: &Figure, text: SvgText) -> String {
    let (w, h) = (figure.width, figure.height);
    let mut svg = Svg::new();
    svg.start(
        "svg",
        Attributes::new()
            .with("xmlns", "http://www.w3.org/2000/svg")
            .with("xmlns:xlink", "http://www.w3.org/1999/xlink")
            .with("version", "1.1")
            .with("width", w)
            .with("height", h)
            .with("viewBox", format_args!("0 0 {w} {h}")),
    );
    svg.newline();
    if figure.background.a > 0 {
        svg.empty(
            "rect",
            Attributes::new()
                .with("width", w)
                .with("height", h)
                .fill(figure.background),
        );
    }
    for item in &figure.items {
        write_item(&mut svg, item, text);
    }
    svg.end("svg");
    svg.newline();
    svg.finish()
}

/// Writes one display-list item as one element (an arrow as a group).
fn write_item(svg: &mut Svg, item: &Item, text: SvgText) {
    match item {
        Item::Line { from, to, stroke } => {
            if let Some(stroke) = stroke_attributes(stroke) {
                svg.empty("line", line_attributes(*from, *to).extend(stroke));
            }
        }
        Item::Polyline {
            points,
            closed,
            stroke,
        } => {
            if let Some(stroke) = stroke_attributes(stroke).filter(|_| points.len() >= 2) {
                let element = if *closed { "polygon" } else { "polyline" };
                svg.empty(
                    element,
                    Attributes::new()
                        .with("points", Points(points))
                        .with("fill", "none")
                        .extend(stroke),
                );
            }
        }
        Item::Arrow {
            from,
            to,
            stroke,
            ends,
        } => {
            let shape = arrow_shape(*from, *to, stroke.width, *ends);
            svg.start("g", Attributes::new());
            svg.newline();
            if let Some(attributes) = stroke_attributes(stroke) {
                let (a, b) = shape.shaft;
                svg.empty("line", line_attributes(a, b).extend(attributes));
            }
            for head in &shape.heads {
                svg.empty(
                    "polygon",
                    Attributes::new()
                        .with("points", Points(head))
                        .fill(stroke.color),
                );
            }
            svg.end("g");
            svg.newline();
        }
        Item::Dot {
            center,
            radius,
            color,
        } => svg.empty(
            "circle",
            Attributes::new()
                .with("cx", SvgNumber(center.x))
                .with("cy", SvgNumber(center.y))
                .with("r", SvgNumber(*radius))
                .fill(*color),
        ),
        Item::Polygon {
            points,
            fill,
            stroke,
        } => {
            if points.len() >= 2 {
                let outline = stroke.as_ref().and_then(stroke_attributes);
                svg.empty(
                    "polygon",
                    Attributes::new()
                        .with("points", Points(points))
                        .fill(*fill)
                        .extend(outline.unwrap_or_default()),
                );
            }
        }
        Item::Ellipse {
            center,
            radii,
            rotation,
            fill,
            stroke,
        } => {
            let mut attributes = Attributes::new()
                .with("cx", SvgNumber(center.x))
                .with("cy", SvgNumber(center.y))
                .with("rx", SvgNumber(radii.x))
                .with("ry", SvgNumber(radii.y));
            if *rotation != 0.0 {
                attributes = attributes.with("transform", Rotate(*rotation, *center));
            }
            attributes = match fill {
                Some(fill) => attributes.fill(*fill),
                None => attributes.with("fill", "none"),
            };
            let outline = stroke.as_ref().and_then(stroke_attributes);
            svg.empty("ellipse", attributes.extend(outline.unwrap_or_default()));
        }
        Item::Label(label) => match text {
            SvgText::Paths => write_label_path(svg, label),
            SvgText::Elements => write_label_text(svg, label),
        },
        Item::Image {
            pixels,
            rect,
            sampling,
        } => write_image(svg, pixels, *rect, *sampling),
    }
}

/// A label as one `<path>` of glyph outlines.
fn write_label_path(svg: &mut Svg, label: &Label) {
    if let Some(path) = label_outline(label) {
        // Control characters set no glyph; XML cannot hold most of them.
        let text: String = label.text.chars().filter(|c| !c.is_control()).collect();
        svg.empty(
            "path",
            Attributes::new()
                .with("aria-label", text)
                .with("d", PathData(&path))
                .fill(label.color),
        );
    }
}

/// A label as a `<text>` element, its scripts as `<tspan>`s shifted with `dy`.
fn write_label_text(svg: &mut Svg, label: &Label) {
    let layout = label.layout();
    if layout.spans.is_empty() {
        return;
    }
    // The text-anchor point on the label's baseline, in figure pixels.
    let (anchor_fraction, text_anchor) = match label.anchor {
        Anchor::Start => (0.0, "start"),
        Anchor::Middle => (0.5, "middle"),
        Anchor::End => (1.0, "end"),
    };
    let at = label
        .local_to_figure(&layout.extent)
        .transform_point2(Vec2::new(anchor_fraction * layout.extent.width, 0.0));
    let (font_style, font_weight) = style_and_weight(label.face);
    let mut attributes = Attributes::new()
        .with("x", SvgNumber(at.x))
        .with("y", SvgNumber(at.y))
        .with("text-anchor", text_anchor)
        .with("font-family", FONT_FAMILY)
        .with("font-size", SvgNumber(label.size))
        .with("font-style", font_style)
        .with("font-weight", font_weight);
    if label.rotation != 0.0 {
        attributes = attributes.with("transform", Rotate(label.rotation, at));
    }
    svg.start("text", attributes.fill(label.color));
    let mut shift = 0.0;
    for span in &layout.spans {
        let dy = span.shift - shift;
        shift = span.shift;
        let mut attributes = Attributes::new().with("font-size", SvgNumber(span.size));
        if dy != 0.0 {
            attributes = attributes.with("dy", SvgNumber(dy));
        }
        if span.face != label.face {
            let (style, weight) = style_and_weight(span.face);
            attributes = attributes
                .with("font-style", style)
                .with("font-weight", weight);
        }
        svg.start("tspan", attributes);
        svg.text(&span.text);
        svg.end("tspan");
    }
    svg.end("text");
    svg.newline();
}

/// The SVG `font-style` and `font-weight` of a face.
fn style_and_weight(face: FontFace) -> (&'static str, &'static str) {
    match face {
        FontFace::Regular => ("normal", "normal"),
        FontFace::Italic => ("italic", "normal"),
        FontFace::Bold => ("normal", "bold"),
        FontFace::BoldItalic => ("italic", "bold"),
    }
}

/// An embedded image as a base64 PNG data URI.
///
/// SVG viewers disagree on `image-rendering` (librsvg, for one, always smooths), so a
/// [`Sampling::Nearest`] image is embedded enlarged by a whole factor, each pixel a
/// solid block, and looks pixelated even where the hint is ignored.
fn write_image(svg: &mut Svg, pixels: &image::RgbaImage, rect: Rect, sampling: Sampling) {
    let png = match sampling {
        Sampling::Nearest => encode_png(&enlarge_for(pixels, rect), Compression::Balanced),
        Sampling::Smooth => encode_png(pixels, Compression::Balanced),
    };
    let Ok(png) = png else {
        return;
    };
    let mut attributes = Attributes::new()
        .with("x", SvgNumber(rect.min.x))
        .with("y", SvgNumber(rect.min.y))
        .with("width", SvgNumber(rect.width()))
        .with("height", SvgNumber(rect.height()))
        .with("preserveAspectRatio", "none");
    attributes = match sampling {
        Sampling::Nearest => attributes
            .with("image-rendering", "optimizeSpeed")
            .with("style", "image-rendering:pixelated"),
        Sampling::Smooth => attributes.with("image-rendering", "optimizeQuality"),
    };
    let data = base64::engine::general_purpose::STANDARD.encode(png);
    svg.empty(
        "image",
        attributes.with("xlink:href", format_args!("data:image/png;base64,{data}")),
    );
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

/// `x1`, `y1`, `x2`, `y2` and no fill: a line element's geometry.
fn line_attributes(from: Vec2, to: Vec2) -> Attributes {
    Attributes::new()
        .with("x1", SvgNumber(from.x))
        .with("y1", SvgNumber(from.y))
        .with("x2", SvgNumber(to.x))
        .with("y2", SvgNumber(to.y))
        .with("fill", "none")
}

/// The stroke attributes, or `None` for a stroke too thin to draw.
fn stroke_attributes(stroke: &Stroke) -> Option<Attributes> {
    if !(stroke.width > 0.0 && stroke.width.is_finite()) {
        return None;
    }
    let mut attributes = Attributes::new()
        .with("stroke", Hex(stroke.color))
        .with("stroke-width", SvgNumber(stroke.width))
        .with("stroke-linejoin", "round");
    if let Some(opacity) = opacity(stroke.color) {
        attributes = attributes.with("stroke-opacity", opacity);
    }
    Some(match stroke.dash_pattern() {
        Some(pattern) => {
            let pattern: Vec<String> = pattern.iter().map(|d| SvgNumber(*d).to_string()).collect();
            attributes
                .with("stroke-linecap", "butt")
                .with("stroke-dasharray", pattern.join(" "))
        }
        None => attributes.with("stroke-linecap", "round"),
    })
}

/// The alpha as an opacity in 0..=1 with three decimals at most, or `None` when the
/// colour is opaque.
fn opacity(color: Color) -> Option<f32> {
    (color.a < 255).then(|| (f32::from(color.a) / 255.0 * 1000.0).round() / 1000.0)
}

/// An element's attributes, in the order they are written.
#[derive(Default)]
struct Attributes(Vec<(&'static str, String)>);

impl Attributes {
    fn new() -> Attributes {
        Attributes::default()
    }

    /// The attributes and `name="value"`.
    fn with(mut self, name: &'static str, value: impl Display) -> Attributes {
        self.0.push((name, value.to_string()));
        self
    }

    /// The attributes and `more`.
    fn extend(mut self, more: Attributes) -> Attributes {
        self.0.extend(more.0);
        self
    }

    /// The attributes and `fill="#rrggbb"`, and `fill-opacity` if `color` is translucent.
    fn fill(self, color: Color) -> Attributes {
        let attributes = self.with("fill", Hex(color));
        match opacity(color) {
            Some(opacity) => attributes.with("fill-opacity", opacity),
            None => attributes,
        }
    }
}

/// An SVG document being written, one element per line.
struct Svg {
    writer: Writer<Vec<u8>>,
}

impl Svg {
    /// A document holding the XML declaration.
    fn new() -> Svg {
        let mut svg = Svg {
            writer: Writer::new(Vec::new()),
        };
        svg.write(Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None)));
        svg.newline();
        svg
    }

    fn write(&mut self, event: Event<'_>) {
        self.writer
            .write_event(event)
            .expect("writing XML into memory cannot fail");
    }

    fn tag<'a>(name: &'a str, attributes: &'a Attributes) -> BytesStart<'a> {
        BytesStart::new(name).with_attributes(
            attributes
                .0
                .iter()
                .map(|(name, value)| (*name, value.as_str())),
        )
    }

    /// `<name attributes/>` and a line break.
    fn empty(&mut self, name: &str, attributes: Attributes) {
        self.write(Event::Empty(Svg::tag(name, &attributes)));
        self.newline();
    }

    /// `<name attributes>`.
    fn start(&mut self, name: &str, attributes: Attributes) {
        self.write(Event::Start(Svg::tag(name, &attributes)));
    }

    /// `</name>`.
    fn end(&mut self, name: &str) {
        self.write(Event::End(BytesEnd::new(name)));
    }

    /// Character data, escaped.
    fn text(&mut self, text: &str) {
        self.write(Event::Text(BytesText::new(text)));
    }

    /// A line break between elements (never inside `<text>`, where it would be a space).
    fn newline(&mut self) {
        self.writer.get_mut().push(b'\n');
    }

    fn finish(self) -> String {
        String::from_utf8(self.writer.into_inner()).expect("the XML writer writes UTF-8")
    }
}

/// `#rrggbb`, a colour without its alpha.
struct Hex(Color);

impl Display for Hex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Color { r, g, b, .. } = self.0;
        write!(f, "#{r:02x}{g:02x}{b:02x}")
    }
}

/// `x,y x,y ...`, a `points` attribute.
struct Points<'a>(&'a [Vec2]);

impl Display for Points<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, p) in self.0.iter().enumerate() {
            let separator = if i == 0 { "" } else { " " };
            write!(f, "{separator}{},{}", SvgNumber(p.x), SvgNumber(p.y))?;
        }
        Ok(())
    }
}

/// `rotate(-degrees cx cy)`: a turn of `radians` counter-clockwise on screen about a
/// point (SVG turns clockwise for positive angles, y being down).
struct Rotate(f32, Vec2);

impl Display for Rotate {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let Rotate(radians, about) = self;
        write!(
            f,
            "rotate({} {} {})",
            SvgNumber(-radians.to_degrees()),
            SvgNumber(about.x),
            SvgNumber(about.y)
        )
    }
}

/// Path data (`M`, `L`, `Q`, `C`, `Z`) of a tiny-skia path.
struct PathData<'a>(&'a Path);

impl Display for PathData<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for segment in self.0.segments() {
            match segment {
                PathSegment::MoveTo(p) => write!(f, "M{} {}", SvgNumber(p.x), SvgNumber(p.y))?,
                PathSegment::LineTo(p) => write!(f, "L{} {}", SvgNumber(p.x), SvgNumber(p.y))?,
                PathSegment::QuadTo(c, p) => write!(
                    f,
                    "Q{} {} {} {}",
                    SvgNumber(c.x),
                    SvgNumber(c.y),
                    SvgNumber(p.x),
                    SvgNumber(p.y)
                )?,
                PathSegment::CubicTo(c1, c2, p) => write!(
                    f,
                    "C{} {} {} {} {} {}",
                    SvgNumber(c1.x),
                    SvgNumber(c1.y),
                    SvgNumber(c2.x),
                    SvgNumber(c2.y),
                    SvgNumber(p.x),
                    SvgNumber(p.y)
                )?,
                PathSegment::Close => f.write_str("Z")?,
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colours_are_hex_and_opacity() {
        assert_eq!(Hex(Color::from_hex(0xD55E00)).to_string(), "#d55e00");
        assert_eq!(opacity(Color::WHITE), None);
        assert_eq!(opacity(Color::rgba(0, 0, 0, 51)), Some(0.2));
        assert_eq!(opacity(Color::rgba(0, 0, 0, 64)), Some(0.251));
    }

    #[test]
    fn markup_characters_are_escaped() {
        let mut figure = Figure::new(400, 100);
        figure.push(Label::new("a<b & \"c\"\n", Vec2::new(200.0, 50.0)));
        let document = document(&figure, SvgText::Paths);
        assert!(
            document.contains(r#"aria-label="a&lt;b &amp; &quot;c&quot;""#),
            "{document}"
        );
    }
}
