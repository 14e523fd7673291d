//! The display list: a [`Figure`] is a canvas size, a background and a list of [`Item`]s.

use glam::Vec2;
use image::RgbaImage;

use crate::color::Color;
use crate::rect::Rect;
use crate::text::Label;

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
    /// The head's tip is exactly at the end point. Its length and its half-width at the
    /// barbs grow with the stroke's width:
    ///
    /// ```text
    /// length = 4 width + 10,  half-width = 0.42 length
    /// ```
    /// so a 3.5 px line gets a 24 px head, a 5 px one a 30 px head. A head longer than
    /// half the arrow (0.4 of it, with two heads) shrinks to fit. Dash patterns apply to
    /// the shaft only.
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
    /// A filled disc marking a point, such as an eye or a pixel centre.
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
/// Build it by pushing [`Item`]s, then paint it ([`raster::render`](crate::raster::render),
/// [`write_png`](crate::write_png)) or write it as SVG
/// ([`svg::document`](crate::svg::document), [`write_svg`](crate::write_svg)). Both
/// outputs draw the same geometry: glyph outlines, arrowheads and ellipses are computed
/// once and only painted differently.
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
    /// An empty figure of `width` x `height` pixels on a white background.
    pub fn new(width: u32, height: u32) -> Figure {
        Figure {
            width,
            height,
            background: Color::WHITE,
            items: Vec::new(),
        }
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
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
