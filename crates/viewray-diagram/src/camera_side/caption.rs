//! The caption of a side view: the projection and its parameters in the lecture's
//! notation, the lens, the image size, wrapped to the canvas's width.

use glam::{DVec2, Vec2};
use viewray_camera::{Camera, Projection};
use viewray_draw::{Anchor, Baseline, Label, wrap_parts};
use viewray_output::number;

use super::canvas::SideViewCanvas;
use super::labels::place_label;
use crate::sketch::{LINE_SPACING, Sketch};
use crate::style;

/// A caption's text, in lines, before it is drawn.
pub(super) struct Caption {
    lines: Vec<String>,
}

impl Caption {
    /// The caption of `camera` on `canvas`, each line at most the canvas's width less its
    /// margins: one line on a slide, the projection and then the lens and size on a panel
    /// or a square,
    /// the projection over the lens beside an animation's picture. A line too long
    /// breaks between its parts (after a `,` or `;`), never inside a number.
    pub(super) fn new(camera: &Camera, canvas: SideViewCanvas) -> Caption {
        let parts = CaptionParts::of(camera);
        let mut more: Paragraph = parts.lens.iter().map(|p| (p.clone(), ",  ")).collect();
        more.push((parts.size.clone(), ";  "));
        let parameters: Paragraph = parts
            .parameters
            .iter()
            .map(|p| (p.clone(), ",  "))
            .collect();
        let paragraphs: Vec<Paragraph> = match canvas {
            SideViewCanvas::Slide => {
                let mut all = parameters;
                let mut rest = more;
                if let Some(first) = rest.first_mut() {
                    first.1 = ";  ";
                }
                all.extend(rest);
                vec![all]
            }
            SideViewCanvas::Panel | SideViewCanvas::Square | SideViewCanvas::Fitted { .. } => {
                vec![parameters, more]
            }
            SideViewCanvas::Beside => {
                let lens: Paragraph = parts.lens.iter().map(|p| (p.clone(), ",  ")).collect();
                vec![parameters, lens]
            }
        };
        let width = canvas.size().0 as f32 - 2.0 * canvas.caption_left();
        let lines = paragraphs
            .iter()
            .filter(|paragraph| !paragraph.is_empty())
            .flat_map(|paragraph| wrap(paragraph, width))
            .collect();
        Caption { lines }
    }

    /// How many lines it takes.
    pub(super) fn len(&self) -> usize {
        self.lines.len()
    }

    /// Draws it with its first baseline at `at`: in lines downwards on a slide or a panel;
    /// beside an animation's picture, upwards from `at` over the drawing, each line on a
    /// light backing where it overlaps no other label.
    pub(super) fn draw(&self, sketch: &mut Sketch, canvas: SideViewCanvas, at: Vec2) {
        let step = LINE_SPACING * style::SMALL_LABEL_SIZE;
        match canvas {
            SideViewCanvas::Slide
            | SideViewCanvas::Panel
            | SideViewCanvas::Square
            | SideViewCanvas::Fitted { .. } => {
                let lines: Vec<(&str, _, f32)> = self
                    .lines
                    .iter()
                    .map(|line| (line.as_str(), style::TEXT, style::SMALL_LABEL_SIZE))
                    .collect();
                sketch.text_lines(at, &lines);
            }
            SideViewCanvas::Beside => {
                // The lines were listed top first; the bottom one goes at `at`.
                for (k, line) in self.lines.iter().rev().enumerate() {
                    let baseline = at.y - k as f32 * step;
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
                }
            }
        }
    }
}

/// A paragraph of a caption: its parts, each with the separator written before it when it
/// follows another on the same line.
type Paragraph = Vec<(String, &'static str)>;

/// `paragraph` in lines of at most `width` pixels at the caption's size: as many parts
/// on a line as fit (a part wider than `width` alone on its line).
fn wrap(paragraph: &Paragraph, width: f32) -> Vec<String> {
    let fits = |text: &str| {
        Label::new(text, Vec2::ZERO)
            .with_size(style::SMALL_LABEL_SIZE)
            .bounds()
            .width()
            <= width
    };
    wrap_parts(
        paragraph
            .iter()
            .map(|(part, separator)| (part.as_str(), *separator)),
        fits,
    )
}

/// The caption's parts: the projection and its parameters in the lecture's notation, the
/// lens (none without one), and the image size.
struct CaptionParts {
    parameters: Vec<String>,
    lens: Vec<String>,
    size: String,
}

impl CaptionParts {
    fn of(camera: &Camera) -> CaptionParts {
        let size = format!("image {} × {}", camera.width(), camera.height());
        let viewport = |v: DVec2| {
            format!(
                "$vw$ × $vh$ = {} × {}",
                number::label_significant(v.x),
                number::label_significant(v.y)
            )
        };
        let shift = |s: DVec2| {
            (s != DVec2::ZERO).then(|| {
                format!(
                    "shift ({}, {})",
                    number::label_significant(s.x),
                    number::label_significant(s.y)
                )
            })
        };
        let lens = |aperture: f64, focus: f64| {
            vec![
                format!("aperture $r$ = {}", number::label_significant(aperture)),
                format!("focus $f$ = {}", number::label_significant(focus)),
            ]
        };
        let perspective = |name: &str, distance: f64, v: DVec2, s: DVec2| {
            let mut parts = vec![
                format!("{name}:  $d$ = {}", number::label_significant(distance)),
                viewport(v),
            ];
            parts.extend(shift(s));
            parts
        };
        let (parameters, lens) = match camera.projection() {
            Projection::Perspective(p) => (
                perspective("perspective", p.distance, p.viewport, p.shift),
                Vec::new(),
            ),
            Projection::ThinLens(p) => {
                let mut parts = lens(p.aperture, p.focus);
                if p.tilt != 0.0 {
                    parts.push(format!("tilt {}°", number::label(p.tilt.to_degrees())));
                }
                if p.swing != 0.0 {
                    parts.push(format!("swing {}°", number::label(p.swing.to_degrees())));
                }
                if !p.iris.is_round() {
                    parts.push(format!("{} blades", p.iris.blades));
                }
                (
                    perspective("thin lens", p.distance, p.viewport, p.shift),
                    parts,
                )
            }
            Projection::Orthographic(o) => (
                vec![format!("orthographic:  {}", viewport(o.viewport))],
                o.lens.map_or(Vec::new(), |l| lens(l.aperture, l.focus)),
            ),
            Projection::Oblique(o) => (
                vec![
                    format!("oblique:  {}", viewport(o.viewport)),
                    format!("$L$ = {}", number::label_significant(o.ratio)),
                    format!("$φ$ = {}°", number::label(o.angle.to_degrees())),
                ],
                Vec::new(),
            ),
            Projection::Equirectangular => {
                (vec!["equirectangular: 360° × 180°".to_owned()], Vec::new())
            }
            Projection::Fisheye(f) => (
                vec![format!(
                    "fisheye: field of view {}°",
                    number::label(f.fov.to_degrees())
                )],
                Vec::new(),
            ),
        };
        CaptionParts {
            parameters,
            lens,
            size,
        }
    }
}
