//! Labels that find a free place: the eye's frame (e, u, v, w), the image plane, and
//! the placement rule every side-view label follows.

use glam::Vec2;
use viewray_camera::{Camera, Frame, Projection};
use viewray_draw::{Anchor, Baseline, Color, Item, Label};
use viewray_output::number;

use crate::sketch::Sketch;
use crate::style;
use crate::view::SideView;

/// Names e, v, w and u at the eye, each where it overlaps no other label: v and w past
/// their arrows' tips, u (out of the page) and e beside the eye.
pub(super) fn draw_frame_labels(sketch: &mut Sketch, view: &SideView, frame: &Frame, length: f64) {
    let e = view.to_figure(frame.e());
    let around = |at: Vec2, gap: f32| {
        [
            beside(at, -gap, gap),
            beside(at, gap, gap),
            beside(at, -gap, -gap),
            beside(at, gap, -gap),
            beside(at, 0.0, 1.6 * gap),
            beside(at, 0.0, -1.6 * gap),
            beside(at, -1.6 * gap, 0.0),
            beside(at, 1.6 * gap, 0.0),
        ]
    };
    for (axis, color, name) in [
        (frame.v(), style::V_AXIS, "*v*"),
        (frame.w(), style::W_AXIS, "*w*"),
    ] {
        let tip = view.to_figure(frame.e() + axis * length);
        let out = (tip - e).normalize_or_zero();
        let mut candidates = vec![(tip + out * 26.0, (Anchor::Middle, Baseline::Middle))];
        candidates.extend(around(tip, 16.0));
        place_label(sketch, name, &candidates, color, style::LABEL_SIZE);
    }
    place_label(
        sketch,
        "*e*",
        &around(e, 22.0),
        style::EYE,
        style::LABEL_SIZE,
    );
    place_label(
        sketch,
        "*u*",
        &around(e, 30.0),
        style::U_AXIS,
        style::LABEL_SIZE,
    );
}

/// Names the image plane drawn from `top` to `bottom` (figure pixels) beside one of its
/// ends, or farther out around its middle where the eye's labels crowd it.
pub(super) fn draw_image_plane_label(
    sketch: &mut Sketch,
    camera: &Camera,
    top: Vec2,
    bottom: Vec2,
) {
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
    for distance in [70.0, 120.0, 170.0, 220.0] {
        candidates.extend([
            beside(middle, 0.0, distance),
            beside(middle, distance, 0.0),
            beside(middle, 0.0, -distance),
            beside(middle, -distance, 0.0),
        ]);
    }
    place_label(
        sketch,
        &label,
        &candidates,
        style::IMAGE_PLANE,
        style::SMALL_LABEL_SIZE,
    );
}

/// Adds the label `text` at the first of `candidates` where it stays on the canvas and
/// overlaps no label already there (at the first candidate if none is free).
pub(super) fn place_label(
    sketch: &mut Sketch,
    text: &str,
    candidates: &[(Vec2, (Anchor, Baseline))],
    color: Color,
    size: f32,
) {
    let make = |&(at, (anchor, baseline)): &(Vec2, (Anchor, Baseline))| {
        Label::new(text, at)
            .with_size(size)
            .with_color(color)
            .with_anchor(anchor, baseline)
    };
    let canvas = sketch.figure.bounds();
    let free = |label: &Label| {
        let bounds = label.bounds();
        canvas.contains_rect(&bounds)
            && !sketch.figure.items.iter().any(|item| match item {
                Item::Label(other) => other.bounds().intersects(&bounds),
                _ => false,
            })
    };
    // The first free place; else the first on the canvas; else the first, moved onto it.
    let chosen = candidates
        .iter()
        .map(make)
        .find(|label| free(label))
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
        });
    if let Some(label) = chosen {
        // A light backing keeps the label legible over rays and objects.
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
