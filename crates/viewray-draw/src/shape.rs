//! The shapes every output draws: arrows as a shaft and filled heads, labels as glyph
//! outlines. Computed once here, so the PNG and the SVG of a figure cannot disagree.

use ab_glyph::{Font as _, OutlineCurve};
use glam::Vec2;
use tiny_skia::{Path, PathBuilder};

use crate::figure::ArrowEnds;
use crate::text::Label;

/// Length of an arrowhead, tip to barbs, for a shaft of width `stroke_width`.
///
/// ```text
/// length = 4 * stroke_width + 10
/// ```
/// A 3.5 px line gets a 24 px head, a 5 px one a 30 px head. The head's half-width at its
/// barbs is [`ARROWHEAD_ASPECT`] times its length.
pub(crate) fn arrowhead_length(stroke_width: f32) -> f32 {
    4.0 * stroke_width.max(0.0) + 10.0
}

/// Half-width of an arrowhead at its barbs, as a fraction of its length.
pub(crate) const ARROWHEAD_ASPECT: f32 = 0.42;

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
    let head = arrowhead_length(width).min(length * max_share);
    let half = ARROWHEAD_ASPECT * head;
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

/// The glyph outlines of `label` in figure pixels, or `None` for text without ink.
pub(crate) fn label_outline(label: &Label) -> Option<Path> {
    let layout = label.layout();
    let to_figure = label.local_to_figure(&layout.extent);
    let mut builder = PathBuilder::new();
    for glyph in &layout.glyphs {
        let Some(outline) = glyph.face.font().outline(glyph.id) else {
            continue;
        };
        // Font units have y up; label-local coordinates have y down.
        let map = |p: ab_glyph::Point| {
            let local = glyph.origin + Vec2::new(p.x, -p.y) * glyph.scale;
            to_figure.transform_point2(local)
        };
        append_outline(&mut builder, &outline.curves, map);
    }
    builder.finish()
}

/// Appends a glyph's curves to `builder`, starting a new contour wherever a curve does
/// not begin where the previous one ended.
fn append_outline(
    builder: &mut PathBuilder,
    curves: &[OutlineCurve],
    map: impl Fn(ab_glyph::Point) -> Vec2,
) {
    let mut last: Option<ab_glyph::Point> = None;
    for curve in curves {
        let (start, end) = match *curve {
            OutlineCurve::Line(a, b)
            | OutlineCurve::Quad(a, _, b)
            | OutlineCurve::Cubic(a, _, _, b) => (a, b),
        };
        if last != Some(start) {
            if last.is_some() {
                builder.close();
            }
            let p = map(start);
            builder.move_to(p.x, p.y);
        }
        match *curve {
            OutlineCurve::Line(_, b) => {
                let b = map(b);
                builder.line_to(b.x, b.y);
            }
            OutlineCurve::Quad(_, c, b) => {
                let (c, b) = (map(c), map(b));
                builder.quad_to(c.x, c.y, b.x, b.y);
            }
            OutlineCurve::Cubic(_, c1, c2, b) => {
                let (c1, c2, b) = (map(c1), map(c2), map(b));
                builder.cubic_to(c1.x, c1.y, c2.x, c2.y, b.x, b.y);
            }
        }
        last = Some(end);
    }
    if last.is_some() {
        builder.close();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrowhead_tip_is_the_end_point_and_barbs_lie_behind_it() {
        let shape = arrow_shape(Vec2::ZERO, Vec2::new(200.0, 0.0), 4.0, ArrowEnds::End);
        let [tip, b1, notch, b2] = shape.heads[0];
        assert_eq!(tip, Vec2::new(200.0, 0.0));
        let length = arrowhead_length(4.0);
        assert!((b1.x - (200.0 - length)).abs() < 1e-4);
        assert!((b1.y.abs() - ARROWHEAD_ASPECT * length).abs() < 1e-4);
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
