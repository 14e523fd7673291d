//! Labels that find a free place: the eye's frame (e and its axes), the image plane, and
//! the placement rule every side-view label follows, which keeps a label off the other
//! labels and, where it can, off the rays, arrows and objects drawn before it.

use glam::Vec2;
use viewray_camera::{Camera, Frame, Projection};
use viewray_draw::{Anchor, Baseline, Color, Item, Label, Rect, Stroke};
use viewray_output::number;

use super::window::Plane;
use crate::sketch::Sketch;
use crate::style;
use crate::view::SideView;

/// How far apart two labels stay, in pixels.
const LABEL_GAP: f32 = 6.0;

/// A label to place once everything else is drawn: its text, the places it may go (in
/// order of preference), its colour and size.
pub(super) struct Pending {
    text: String,
    candidates: Vec<(Vec2, (Anchor, Baseline))>,
    color: Color,
    size: f32,
    /// The point it names, joined to it by a thin line when it lands far from it.
    names: Option<Vec2>,
}

/// How far from the point it names a label may land before a line joins them, pixels.
const LEADER_AFTER: f32 = 36.0;

/// The labels of a side view, placed after the drawing so that each can keep off it.
#[derive(Default)]
pub(super) struct Labels {
    pending: Vec<Pending>,
}

impl Labels {
    /// Adds a label to place later.
    pub(super) fn add(
        &mut self,
        text: impl Into<String>,
        candidates: Vec<(Vec2, (Anchor, Baseline))>,
        color: Color,
        size: f32,
    ) {
        self.pending.push(Pending {
            text: text.into(),
            candidates,
            color,
            size,
            names: None,
        });
    }

    /// Adds a label naming the point `names`, to place later; a thin line joins them if
    /// it lands far from it.
    pub(super) fn add_naming(
        &mut self,
        text: impl Into<String>,
        candidates: Vec<(Vec2, (Anchor, Baseline))>,
        (color, size): (Color, f32),
        names: Vec2,
    ) {
        self.add(text, candidates, color, size);
        if let Some(last) = self.pending.last_mut() {
            last.names = Some(names);
        }
    }

    /// Places every label, in the order they were added.
    pub(super) fn place(self, sketch: &mut Sketch) {
        for pending in self.pending {
            let Some(label) = choose_label(
                sketch,
                &pending.text,
                &pending.candidates,
                pending.color,
                pending.size,
            ) else {
                continue;
            };
            if let Some(point) = pending.names {
                let bounds = label.bounds();
                let nearest = point.clamp(bounds.min, bounds.max);
                if nearest.distance(point) > LEADER_AFTER {
                    // From just off the point to the label's nearest edge.
                    let along = (nearest - point).normalize_or_zero();
                    sketch.line(
                        point + along * 10.0,
                        nearest,
                        Stroke::new(pending.color, style::LINE_THIN / 2.0),
                    );
                }
            }
            push_label(sketch, label);
        }
    }
}

/// Names e, the two axes drawn at the eye and the one out of the page, each where it
/// overlaps no other label and, where it can, nothing drawn: the arrows' names past their
/// tips, e and the out-of-page axis beside the eye (behind it first, where no ray goes).
pub(super) fn frame_labels(
    labels: &mut Labels,
    view: &SideView,
    frame: &Frame,
    plane: Plane,
    length: f64,
) {
    let e = view.to_figure(frame.e());
    // Behind the eye: along w on the figure.
    let back = (view.to_figure(frame.e() + frame.w()) - e).normalize_or_zero();
    let around = |at: Vec2, gap: f32| {
        let mut places: Vec<(Vec2, (Anchor, Baseline))> = Vec::new();
        // The eight directions, those pointing behind the eye first.
        let mut directions: Vec<Vec2> = (0..8)
            .map(|k| Vec2::from_angle(k as f32 * std::f32::consts::FRAC_PI_4 + 0.3))
            .collect();
        directions.sort_by(|a, b| b.dot(back).total_cmp(&a.dot(back)));
        for scale in [1.0, 1.6, 2.4] {
            for d in &directions {
                places.push(beside(at, d.x * gap * scale, d.y * gap * scale));
            }
        }
        places
    };
    for (axis, color, name) in plane.arrows(frame) {
        let tip = view.to_figure(frame.e() + axis * length);
        let out = (tip - e).normalize_or_zero();
        let mut candidates = vec![(tip + out * 26.0, (Anchor::Middle, Baseline::Middle))];
        candidates.extend(around(tip, 16.0));
        labels.add(name, candidates, color, style::LABEL_SIZE);
    }
    labels.add("*e*", around(e, 24.0), style::EYE, style::LABEL_SIZE);
    let (_, color, name) = plane.out_axis(frame);
    labels.add(name, around(e, 30.0), color, style::LABEL_SIZE);
}

/// Names the image plane drawn from `top` to `bottom` (figure pixels) beside one of its
/// ends (outside the frustum first), or farther out around it where those are taken.
pub(super) fn image_plane_label(labels: &mut Labels, camera: &Camera, top: Vec2, bottom: Vec2) {
    let label = match camera.projection() {
        Projection::Perspective(p) => format!(
            "image plane, $d$ = {}",
            number::label_significant(p.distance)
        ),
        Projection::ThinLens(p) => format!(
            "image plane, $d$ = {}",
            number::label_significant(p.distance)
        ),
        _ => "image plane".to_owned(),
    };
    let (lower, upper) = if top.y > bottom.y {
        (top, bottom)
    } else {
        (bottom, top)
    };
    let mut candidates = vec![
        beside(lower, 12.0, 10.0),
        beside(lower, -12.0, 10.0),
        beside(upper, 12.0, -10.0),
        beside(upper, -12.0, -10.0),
    ];
    let middle = (lower + upper) / 2.0;
    for distance in [40.0, 70.0, 120.0, 170.0, 220.0] {
        candidates.extend([
            beside(lower, 0.0, distance),
            beside(upper, 0.0, -distance),
            beside(lower, -distance, distance * 0.5),
            beside(upper, -distance, -distance * 0.5),
            beside(middle, 0.0, distance),
            beside(middle, distance, 0.0),
            beside(middle, 0.0, -distance),
            beside(middle, -distance, 0.0),
        ]);
    }
    labels.add_naming(
        label,
        candidates,
        (style::IMAGE_PLANE, style::SMALL_LABEL_SIZE),
        middle,
    );
}

/// Names the focus plane drawn from `upper` to `lower` (figure pixels) beyond one of its
/// ends, or beside it.
pub(super) fn focus_plane_label(labels: &mut Labels, focus: f64, upper: Vec2, lower: Vec2) {
    labels.add(
        format!("focus plane, $f$ = {}", number::label_significant(focus)),
        vec![
            beside(upper, 0.0, -10.0),
            beside(lower, 0.0, 10.0),
            beside(upper, 12.0, 12.0),
            beside(lower, 12.0, -12.0),
            beside(upper, -12.0, 12.0),
            beside(lower, -12.0, -12.0),
            beside((upper + lower) / 2.0, 14.0, 0.0),
            beside((upper + lower) / 2.0, -14.0, 0.0),
        ],
        style::HIGHLIGHT,
        style::SMALL_LABEL_SIZE,
    );
}

/// What a label's box would cover: nothing at all (0), or some of the rays, arrows, dots
/// and objects drawn (the number of them it meets).
fn covered(items: &[Item], bounds: &Rect) -> usize {
    let meets_segment = |a: Vec2, b: Vec2| segment_meets(bounds, a, b);
    items
        .iter()
        .filter(|item| match item {
            Item::Line { from, to, .. } | Item::Arrow { from, to, .. } => meets_segment(*from, *to),
            Item::Polyline { points, closed, .. } => {
                let n = points.len();
                let edges = if *closed { n } else { n.saturating_sub(1) };
                (0..edges).any(|k| meets_segment(points[k], points[(k + 1) % n]))
            }
            Item::Dot { center, radius, .. } => {
                bounds.intersects(&Rect::from_corners(*center - *radius, *center + *radius))
            }
            Item::Ellipse { center, radii, .. } => {
                let r = Vec2::splat(radii.max_element());
                bounds.intersects(&Rect::from_corners(*center - r, *center + r))
            }
            // Objects are outlined; a plane's fill and a label's backing are not.
            Item::Polygon {
                points,
                stroke: Some(_),
                ..
            } => polygon_meets(bounds, points),
            _ => false,
        })
        .count()
}

/// Whether the segment from `a` to `b` crosses the rectangle `rect`.
fn segment_meets(rect: &Rect, a: Vec2, b: Vec2) -> bool {
    // Clip the segment's parameter to the rectangle's two slabs (Liang-Barsky).
    let d = b - a;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for (start, slope, low, high) in [
        (a.x, d.x, rect.min.x, rect.max.x),
        (a.y, d.y, rect.min.y, rect.max.y),
    ] {
        if slope == 0.0 {
            if start < low || start > high {
                return false;
            }
            continue;
        }
        let (p, q) = ((low - start) / slope, (high - start) / slope);
        t0 = t0.max(p.min(q));
        t1 = t1.min(p.max(q));
    }
    t0 <= t1
}

/// Whether `rect` meets the polygon `points`: an edge crosses it, or it lies inside.
fn polygon_meets(rect: &Rect, points: &[Vec2]) -> bool {
    let n = points.len();
    if n == 0 {
        return false;
    }
    if (0..n).any(|k| segment_meets(rect, points[k], points[(k + 1) % n])) {
        return true;
    }
    // The rectangle's centre inside the polygon (even-odd rule).
    let c = rect.center();
    let mut inside = false;
    for k in 0..n {
        let (a, b) = (points[k], points[(k + 1) % n]);
        if (a.y > c.y) != (b.y > c.y) && c.x < a.x + (c.y - a.y) / (b.y - a.y) * (b.x - a.x) {
            inside = !inside;
        }
    }
    inside
}

/// Adds the label `text` at the first of `candidates` where it stays on the canvas,
/// keeps [`LABEL_GAP`] from every label already there and covers nothing drawn; else at
/// the candidate of those apart from the labels that covers the fewest things; else at
/// the first on the canvas; else at the first, moved onto it.
pub(super) fn place_label(
    sketch: &mut Sketch,
    text: &str,
    candidates: &[(Vec2, (Anchor, Baseline))],
    color: Color,
    size: f32,
) {
    if let Some(label) = choose_label(sketch, text, candidates, color, size) {
        push_label(sketch, label);
    }
}

/// The label [`place_label`] would add.
fn choose_label(
    sketch: &Sketch,
    text: &str,
    candidates: &[(Vec2, (Anchor, Baseline))],
    color: Color,
    size: f32,
) -> Option<Label> {
    let make = |&(at, (anchor, baseline)): &(Vec2, (Anchor, Baseline))| {
        Label::new(text, at)
            .with_size(size)
            .with_color(color)
            .with_anchor(anchor, baseline)
    };
    let canvas = sketch.figure.bounds();
    let items = &sketch.figure.items;
    let apart = |label: &Label| {
        let bounds = label.bounds();
        canvas.contains_rect(&bounds)
            && !items.iter().any(|item| match item {
                Item::Label(other) => other.bounds().expand(LABEL_GAP).intersects(&bounds),
                _ => false,
            })
    };
    candidates
        .iter()
        .map(make)
        .filter(|label| apart(label))
        .map(|label| (covered(items, &label.bounds()), label))
        // The first that covers nothing, else the one covering least (the first of ties).
        .reduce(|best, next| if next.0 < best.0 { next } else { best })
        .map(|(_, label)| label)
        .or_else(|| {
            candidates
                .iter()
                .map(make)
                .find(|label| canvas.contains_rect(&label.bounds()))
        })
        .or_else(|| {
            candidates.first().map(|first| {
                let label = make(first);
                let bounds = label.bounds();
                let shift = Vec2::new(
                    (canvas.min.x - bounds.min.x).max(0.0) + (canvas.max.x - bounds.max.x).min(0.0),
                    (canvas.min.y - bounds.min.y).max(0.0) + (canvas.max.y - bounds.max.y).min(0.0),
                );
                make(&(first.0 + shift, first.1))
            })
        })
}

/// Adds `label` on a light backing that keeps it legible over rays and objects.
fn push_label(sketch: &mut Sketch, label: Label) {
    let backing = label.bounds().expand(4.0);
    sketch.push(Item::Polygon {
        points: vec![
            backing.min,
            Vec2::new(backing.max.x, backing.min.y),
            backing.max,
            Vec2::new(backing.min.x, backing.max.y),
        ],
        fill: style::BACKGROUND.with_alpha(0.85),
        stroke: None,
    });
    sketch.push(label);
}

/// A place for a label `(dx, dy)` pixels from the point `at` it names, anchored so that
/// it grows away from it.
pub(super) fn beside(at: Vec2, dx: f32, dy: f32) -> (Vec2, (Anchor, Baseline)) {
    let d = Vec2::new(dx, dy);
    (at + d, label_anchor(d))
}

/// The anchor of a label placed in direction `d` from what it names, so that it grows
/// away from it.
pub(super) fn label_anchor(d: Vec2) -> (Anchor, Baseline) {
    let anchor = if d.x > 0.5 * d.length() {
        Anchor::Start
    } else if d.x < -0.5 * d.length() {
        Anchor::End
    } else {
        Anchor::Middle
    };
    let baseline = if d.y > 0.5 * d.length() {
        Baseline::Top
    } else if d.y < -0.5 * d.length() {
        Baseline::Bottom
    } else {
        Baseline::Middle
    };
    (anchor, baseline)
}
