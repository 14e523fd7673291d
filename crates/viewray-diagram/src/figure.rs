//! The display list: a [`Figure`] is a canvas size, a background and a list of [`Item`]s.

use std::io;
use std::path::Path;

use glam::Vec2;
use image::RgbaImage;

use crate::text::Label;
use crate::{Color, style};

/// An axis-aligned rectangle from `min` to `max`.
///
/// In figure space (y down) `min` is the top-left corner; in world space (y up, see
/// [`Mapping`](crate::Mapping)) it is the bottom-left one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// The corner with the smallest coordinates.
    pub min: Vec2,
    /// The corner with the largest coordinates.
    pub max: Vec2,
}

impl Rect {
    /// The rectangle spanned by two opposite corners, in either order.
    pub fn from_corners(a: Vec2, b: Vec2) -> Rect {
        Rect {
            min: a.min(b),
            max: a.max(b),
        }
    }

    /// The rectangle with top-left corner `(x, y)` (in figure space) and the given size.
    pub fn from_xywh(x: f32, y: f32, width: f32, height: f32) -> Rect {
        Rect::from_corners(Vec2::new(x, y), Vec2::new(x + width, y + height))
    }

    /// `max.x - min.x`.
    pub fn width(&self) -> f32 {
        self.max.x - self.min.x
    }

    /// `max.y - min.y`.
    pub fn height(&self) -> f32 {
        self.max.y - self.min.y
    }

    /// The centre point.
    pub fn center(&self) -> Vec2 {
        (self.min + self.max) * 0.5
    }

    /// Whether `p` lies inside or on the boundary.
    pub fn contains(&self, p: Vec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// Whether `other` lies entirely inside (or on the boundary of) this rectangle.
    pub fn contains_rect(&self, other: &Rect) -> bool {
        self.contains(other.min) && self.contains(other.max)
    }

    /// Whether the two rectangles overlap in an area (touching edges do not count).
    pub fn intersects(&self, other: &Rect) -> bool {
        self.min.cmplt(other.max).all() && other.min.cmplt(self.max).all()
    }

    /// The smallest rectangle holding both.
    pub fn union(&self, other: &Rect) -> Rect {
        Rect {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The rectangle grown by `margin` on every side (shrunk for a negative margin).
    pub fn expand(&self, margin: f32) -> Rect {
        Rect {
            min: self.min - Vec2::splat(margin),
            max: self.max + Vec2::splat(margin),
        }
    }
}

/// How a line is drawn: colour, width in pixels and an optional dash pattern.
///
/// Solid lines have round caps and joins. Dashed lines have butt caps, so the dashes are
/// exactly as long as the pattern says.
#[derive(Clone, Debug, PartialEq)]
pub struct Stroke {
    /// The line colour (its alpha makes the line translucent).
    pub color: Color,
    /// The line width in pixels.
    pub width: f32,
    /// Alternating on and off lengths in pixels; empty for a solid line. A pattern with an
    /// odd count or a non-positive total is drawn solid.
    pub dash: Vec<f32>,
}

impl Stroke {
    /// A solid line.
    pub fn new(color: Color, width: f32) -> Stroke {
        Stroke {
            color,
            width,
            dash: Vec::new(),
        }
    }

    /// The same line, dashed with `pattern` (on, off, on, off, ... in pixels).
    pub fn dashed(self, pattern: &[f32]) -> Stroke {
        Stroke {
            dash: pattern.to_vec(),
            ..self
        }
    }

    /// The dash pattern if it is one that can be drawn.
    pub(crate) fn dash_pattern(&self) -> Option<&[f32]> {
        let valid = self.dash.len() >= 2
            && self.dash.len().is_multiple_of(2)
            && self.dash.iter().all(|d| d.is_finite() && *d >= 0.0)
            && self.dash.iter().sum::<f32>() > 0.0;
        valid.then_some(self.dash.as_slice())
    }
}

/// Which ends of an [`Item::Arrow`] carry a head.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ArrowEnds {
    /// One head, at `to`.
    #[default]
    End,
    /// Heads at both ends: a dimension arrow such as the span of *vw*.
    Both,
}

/// How an embedded raster image is resampled to its rectangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Sampling {
    /// Every image pixel becomes a sharp-edged block: right for showing pixels as pixels.
    #[default]
    Nearest,
    /// Bilinear filtering: right for photographs and renders shown as pictures.
    Smooth,
}

/// One thing drawn on a figure. Coordinates are figure pixels, x right and y down.
///
/// Items are drawn in list order, later ones on top.
#[derive(Clone, Debug, PartialEq)]
pub enum Item {
    /// A straight line segment.
    Line {
        /// Start point.
        from: Vec2,
        /// End point.
        to: Vec2,
        /// How the line is drawn.
        stroke: Stroke,
    },
    /// A chain of line segments through `points`; `closed` joins the last to the first.
    Polyline {
        /// The vertices, in order.
        points: Vec<Vec2>,
        /// Whether the last point connects back to the first.
        closed: bool,
        /// How the line is drawn.
        stroke: Stroke,
    },
    /// A line with a filled arrowhead at `to` (and at `from` for [`ArrowEnds::Both`]).
    ///
    /// The head is [`style::arrowhead_length`] long for the stroke's width and its tip is
    /// exactly at the end point; a head longer than half the arrow shrinks to fit. Dash
    /// patterns apply to the shaft only.
    Arrow {
        /// The tail (or the first tip, for two heads).
        from: Vec2,
        /// The tip.
        to: Vec2,
        /// The shaft's stroke; the heads are filled with its colour.
        stroke: Stroke,
        /// Which ends have heads.
        ends: ArrowEnds,
    },
    /// A filled disc marking a point, such as the eye **e** or a pixel centre.
    Dot {
        /// The marked point.
        center: Vec2,
        /// Radius in pixels.
        radius: f32,
        /// Fill colour.
        color: Color,
    },
    /// A filled polygon (non-zero winding rule), optionally outlined.
    Polygon {
        /// The vertices, in order; the polygon is closed automatically.
        points: Vec<Vec2>,
        /// Fill colour.
        fill: Color,
        /// Outline, if any.
        stroke: Option<Stroke>,
    },
    /// An ellipse (a circle when both radii are equal), filled and/or outlined.
    Ellipse {
        /// The centre.
        center: Vec2,
        /// Semi-axis lengths along the ellipse's own x and y axes, in pixels.
        radii: Vec2,
        /// Rotation of the ellipse's x axis, radians, counter-clockwise on screen.
        rotation: f32,
        /// Fill colour, if any.
        fill: Option<Color>,
        /// Outline, if any.
        stroke: Option<Stroke>,
    },
    /// A text label; see [`Label`].
    Label(Label),
    /// An RGBA8 raster image stretched over `rect`, e.g. a low-resolution render shown
    /// beside the camera that made it.
    Image {
        /// The pixels (straight alpha, sRGB).
        pixels: RgbaImage,
        /// Where the image goes on the figure.
        rect: Rect,
        /// How its pixels are resampled.
        sampling: Sampling,
    },
}

impl From<Label> for Item {
    fn from(label: Label) -> Item {
        Item::Label(label)
    }
}

/// A figure: a canvas of `width` x `height` pixels, a background and a display list.
///
/// Build it by pushing [`Item`]s, then render it to PNG ([`Figure::render`],
/// [`Figure::write_png`]) or write it as SVG ([`Figure::to_svg`], [`Figure::write_svg`]).
/// Both outputs draw the same geometry: glyph outlines, arrowheads and ellipses are
/// computed once, here, and only painted differently.
#[derive(Clone, Debug, PartialEq)]
pub struct Figure {
    /// Canvas width in pixels.
    pub width: u32,
    /// Canvas height in pixels.
    pub height: u32,
    /// Colour under all items.
    pub background: Color,
    /// The display list, drawn first to last.
    pub items: Vec<Item>,
}

impl Figure {
    /// An empty figure of `width` x `height` pixels on the [`style::BACKGROUND`].
    pub fn new(width: u32, height: u32) -> Figure {
        Figure {
            width,
            height,
            background: style::BACKGROUND,
            items: Vec::new(),
        }
    }

    /// An empty figure on the slide canvas, [`style::SLIDE`] (1600 x 900).
    pub fn slide() -> Figure {
        Figure::new(style::SLIDE.0, style::SLIDE.1)
    }

    /// An empty figure on the square canvas, [`style::SQUARE`] (1080 x 1080).
    pub fn square() -> Figure {
        Figure::new(style::SQUARE.0, style::SQUARE.1)
    }

    /// The whole canvas as a rectangle in figure space.
    pub fn bounds(&self) -> Rect {
        Rect::from_xywh(0.0, 0.0, self.width as f32, self.height as f32)
    }

    /// Appends an item (drawn on top of everything before it).
    pub fn push(&mut self, item: impl Into<Item>) -> &mut Figure {
        self.items.push(item.into());
        self
    }

    /// Renders the figure with tiny-skia: antialiased, straight-alpha sRGB pixels.
    ///
    /// A figure with a zero width or height renders as an empty image.
    pub fn render(&self) -> RgbaImage {
        crate::raster::render(self)
    }

    /// Renders the figure scaled by `scale`: a `round(scale * width) x round(scale *
    /// height)` image of the same drawing (the golden check keeps figures at half size).
    pub fn render_scaled(&self, scale: f32) -> RgbaImage {
        crate::raster::render_scaled(self, scale)
    }

    /// Renders the figure and encodes it as PNG bytes, with no timestamp or other
    /// metadata, so the same figure always gives the same bytes.
    ///
    /// # Errors
    /// An error of kind `InvalidInput` when the figure has a zero width or height.
    pub fn encode_png(&self) -> io::Result<Vec<u8>> {
        viewray_output::encode_png(&self.render(), viewray_output::Compression::Balanced)
    }

    /// The figure as a standalone SVG document, text drawn as glyph outlines
    /// ([`SvgText::Paths`]), so it looks the same in every viewer.
    pub fn to_svg(&self) -> String {
        crate::svg::to_svg(self, SvgText::Paths)
    }

    /// The figure as a standalone SVG document, text drawn as `text` chooses.
    pub fn to_svg_with(&self, text: SvgText) -> String {
        crate::svg::to_svg(self, text)
    }

    /// Writes [`Figure::encode_png`] to `path` atomically: a temporary file in the same
    /// directory, renamed over `path` when complete, so a failed run leaves no partial file.
    ///
    /// # Errors
    /// Any I/O error, or `InvalidInput` for a figure with a zero width or height.
    pub fn write_png(&self, path: impl AsRef<Path>) -> io::Result<()> {
        let bytes = self.encode_png()?;
        Ok(viewray_output::write_atomically(path, &bytes)?)
    }

    /// Writes [`Figure::to_svg`] to `path` atomically, as [`Figure::write_png`] does.
    ///
    /// # Errors
    /// Any I/O error.
    pub fn write_svg(&self, path: impl AsRef<Path>) -> io::Result<()> {
        Ok(viewray_output::write_atomically(
            path,
            self.to_svg().as_bytes(),
        )?)
    }
}

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

/// The shapes an arrow is drawn with: one shaft and a filled polygon per head.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct ArrowShape {
    /// The shaft runs from the tail's notch to the tip's notch, so its caps hide inside
    /// the heads.
    pub shaft: (Vec2, Vec2),
    /// Each head as tip, barb, notch, barb.
    pub heads: Vec<[Vec2; 4]>,
}

/// Computes the shaft and heads of an arrow from `from` to `to` of line width `width`.
///
/// ```text
/// L = min(arrowhead_length(width), |to - from| / 2)   (one head; |to - from| / 2.5 for two)
/// barbs = tip - L t +- ARROWHEAD_ASPECT L n,  notch = tip - 0.75 L t
/// ```
/// with `t` the unit direction and `n` its normal. A zero-length arrow has no heads.
pub(crate) fn arrow_shape(from: Vec2, to: Vec2, width: f32, ends: ArrowEnds) -> ArrowShape {
    let length = from.distance(to);
    let Some(t) = (to - from).try_normalize() else {
        return ArrowShape {
            shaft: (from, to),
            heads: Vec::new(),
        };
    };
    let max_share = match ends {
        ArrowEnds::End => 0.5,
        ArrowEnds::Both => 0.4,
    };
    let head = style::arrowhead_length(width).min(length * max_share);
    let half = style::ARROWHEAD_ASPECT * head;
    let n = t.perp();
    let head_at = |tip: Vec2, dir: Vec2| -> [Vec2; 4] {
        let base = tip - dir * head;
        [
            tip,
            base + n * half,
            tip - dir * (0.75 * head),
            base - n * half,
        ]
    };
    let mut heads = vec![head_at(to, t)];
    let mut shaft = (from, heads[0][2]);
    if ends == ArrowEnds::Both {
        let tail = head_at(from, -t);
        shaft.0 = tail[2];
        heads.push(tail);
    }
    ArrowShape { shaft, heads }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rect_relations() {
        let r = Rect::from_xywh(10.0, 20.0, 100.0, 50.0);
        assert_eq!(r.center(), Vec2::new(60.0, 45.0));
        assert!(r.contains(Vec2::new(10.0, 70.0)));
        assert!(!r.contains(Vec2::new(9.9, 30.0)));
        let touching = Rect::from_xywh(110.0, 20.0, 5.0, 5.0);
        assert!(!r.intersects(&touching));
        assert!(r.intersects(&touching.expand(1.0)));
        assert!(r.contains_rect(&Rect::from_xywh(20.0, 30.0, 10.0, 10.0)));
        assert_eq!(Rect::from_corners(r.max, r.min), r);
    }

    #[test]
    fn dash_patterns_that_cannot_be_drawn_are_solid() {
        let s = Stroke::new(Color::BLACK, 2.0);
        assert_eq!(s.dash_pattern(), None);
        assert_eq!(
            s.clone().dashed(&[4.0, 2.0]).dash_pattern(),
            Some(&[4.0, 2.0][..])
        );
        assert_eq!(s.clone().dashed(&[4.0]).dash_pattern(), None);
        assert_eq!(s.clone().dashed(&[0.0, 0.0]).dash_pattern(), None);
        assert_eq!(s.dashed(&[4.0, -1.0]).dash_pattern(), None);
    }

    #[test]
    fn arrowhead_tip_is_the_end_point_and_barbs_lie_behind_it() {
        let shape = arrow_shape(Vec2::ZERO, Vec2::new(200.0, 0.0), 4.0, ArrowEnds::End);
        let [tip, b1, notch, b2] = shape.heads[0];
        assert_eq!(tip, Vec2::new(200.0, 0.0));
        let length = style::arrowhead_length(4.0);
        assert!((b1.x - (200.0 - length)).abs() < 1e-4);
        assert!((b1.y.abs() - style::ARROWHEAD_ASPECT * length).abs() < 1e-4);
        assert_eq!(b1.x, b2.x);
        assert_eq!(b1.y, -b2.y);
        assert!(notch.x > b1.x && notch.x < tip.x);
        assert_eq!(shape.shaft, (Vec2::ZERO, notch));
    }

    #[test]
    fn short_arrows_shrink_their_heads_and_two_heads_face_outwards() {
        let shape = arrow_shape(Vec2::ZERO, Vec2::new(0.0, 20.0), 4.0, ArrowEnds::Both);
        assert_eq!(shape.heads.len(), 2);
        let (end, start) = (shape.heads[0], shape.heads[1]);
        assert_eq!(end[0], Vec2::new(0.0, 20.0));
        assert_eq!(start[0], Vec2::ZERO);
        assert!((end[0].y - end[1].y - 8.0).abs() < 1e-4);
        assert!(start[1].y > 0.0 && end[1].y < 20.0);
        assert!(shape.shaft.0.y > 0.0 && shape.shaft.1.y < 20.0);
    }

    #[test]
    fn zero_length_arrow_has_no_heads() {
        let p = Vec2::new(5.0, 5.0);
        assert!(arrow_shape(p, p, 3.0, ArrowEnds::End).heads.is_empty());
    }
}
