//! The caption of a side view: the projection and its parameters in the lecture's
//! notation, the lens, the image size.

use glam::{DVec2, Vec2};
use viewray_camera::{Camera, Projection};
use viewray_draw::{Anchor, Baseline};
use viewray_output::number;

use super::canvas::SideViewCanvas;
use super::labels::place_label;
use crate::sketch::{LINE_SPACING, Sketch};
use crate::style;

/// The caption naming the projection and its parameters: one line on a slide, two on a
/// panel; beside an animation's picture, over the drawing on a light backing, the lens
/// on a line of its own and no image size (the picture shows it).
pub(super) fn draw_caption(sketch: &mut Sketch, camera: &Camera, canvas: SideViewCanvas, at: Vec2) {
    let (parameters, lens, size) = caption(camera);
    let more = if lens.is_empty() {
        size
    } else {
        format!("{lens};  {size}")
    };
    // A slide's one line holds about 90 characters; a longer caption (a shifted or
    // tilted lens) takes two, as on a panel.
    let one_line = format!("{parameters};  {more}");
    let slide_fits = one_line.chars().count() <= 90;
    match canvas {
        SideViewCanvas::Slide if slide_fits => {
            sketch.text_lines(at, &[(&one_line, style::TEXT, style::SMALL_LABEL_SIZE)])
        }
        SideViewCanvas::Slide | SideViewCanvas::Panel => sketch.text_lines(
            // On a slide the second line takes the first's place, the first goes above.
            if canvas == SideViewCanvas::Slide {
                at - Vec2::new(0.0, LINE_SPACING * style::SMALL_LABEL_SIZE)
            } else {
                at
            },
            &[
                (&parameters, style::TEXT, style::SMALL_LABEL_SIZE),
                (&more, style::TEXT, style::SMALL_LABEL_SIZE),
            ],
        ),
        SideViewCanvas::Beside => {
            let lines = [lens, parameters];
            let mut baseline = at.y;
            for line in lines.iter().filter(|line| !line.is_empty()) {
                place_label(
                    sketch,
                    line,
                    &[(
                        Vec2::new(at.x, baseline),
                        (Anchor::Start, Baseline::Alphabetic),
                    )],
                    style::TEXT,
                    style::SMALL_LABEL_SIZE,
                );
                baseline -= LINE_SPACING * style::SMALL_LABEL_SIZE;
            }
            baseline
        }
    };
}

/// The caption's parts: the projection and its parameters in the lecture's notation, the
/// lens (empty without one), and the image size.
fn caption(camera: &Camera) -> (String, String, String) {
    let size = format!("image {} × {}", camera.width(), camera.height());
    let viewport = |v: DVec2| {
        format!(
            "$vw$ × $vh$ = {} × {}",
            number::label_significant(v.x),
            number::label_significant(v.y)
        )
    };
    let shift = |s: DVec2| {
        if s == DVec2::ZERO {
            String::new()
        } else {
            format!(
                ",  shift ({}, {})",
                number::label_significant(s.x),
                number::label_significant(s.y)
            )
        }
    };
    let lens = |aperture: f64, focus: f64| {
        format!(
            "aperture $r$ = {},  focus $f$ = {}",
            number::label_significant(aperture),
            number::label_significant(focus)
        )
    };
    let (parameters, lens) = match camera.projection() {
        Projection::Perspective(p) => (
            format!(
                "perspective:  $d$ = {},  {}{}",
                number::label_significant(p.distance),
                viewport(p.viewport),
                shift(p.shift)
            ),
            String::new(),
        ),
        Projection::ThinLens(p) => {
            let mut lens = lens(p.aperture, p.focus);
            if p.tilt != 0.0 {
                lens += &format!(",  tilt {}°", number::label(p.tilt.to_degrees()));
            }
            if p.swing != 0.0 {
                lens += &format!(",  swing {}°", number::label(p.swing.to_degrees()));
            }
            if !p.iris.is_round() {
                lens += &format!(",  {} blades", p.iris.blades);
            }
            (
                format!(
                    "thin lens:  $d$ = {},  {}{}",
                    number::label_significant(p.distance),
                    viewport(p.viewport),
                    shift(p.shift)
                ),
                lens,
            )
        }
        Projection::Orthographic(o) => (
            format!("orthographic:  {}", viewport(o.viewport)),
            o.lens.map_or(String::new(), |l| lens(l.aperture, l.focus)),
        ),
        Projection::Oblique(o) => (
            format!(
                "oblique:  {},  $L$ = {},  $φ$ = {}°",
                viewport(o.viewport),
                number::label_significant(o.ratio),
                number::label(o.angle.to_degrees())
            ),
            String::new(),
        ),
        Projection::Equirectangular => ("equirectangular: 360° × 180°".to_owned(), String::new()),
        Projection::Fisheye(f) => (
            format!(
                "fisheye: field of view {}°",
                number::label(f.fov.to_degrees())
            ),
            String::new(),
        ),
    };
    (parameters, lens, size)
}
