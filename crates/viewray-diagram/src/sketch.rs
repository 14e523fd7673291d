//! The figure builder shared by the lecture figures: the display list, the record of the
//! camera rays drawn, and the recurring marks (titles, text blocks, dimensions, frames).

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample};
use viewray_output::number;

use crate::style;
use crate::view::FigureView;
use crate::{Diagram, DrawnRay};
use viewray_draw::{
    Anchor, ArrowEnds, Baseline, Color, Figure, FontFace, Item, Label, Rect, Stroke,
};

/// Where a slide's title sits: its left end and the top of its text.
const TITLE_AT: Vec2 = Vec2::new(56.0, 34.0);

/// The two canvases of [`style`]: the slide and the square.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Canvas {
    /// 1600 x 900.
    Slide,
    /// 1080 x 1080.
    Square,
}

/// A figure under construction, with the camera rays it draws.
pub(crate) struct Sketch {
    pub(crate) figure: Figure,
    pub(crate) rays: Vec<DrawnRay>,
}

impl Sketch {
    /// An empty slide (1600 x 900).
    pub(crate) fn slide() -> Sketch {
        Sketch::on(Canvas::Slide)
    }

    /// An empty figure on `canvas`.
    pub(crate) fn on(canvas: Canvas) -> Sketch {
        let (width, height) = match canvas {
            Canvas::Slide => style::SLIDE,
            Canvas::Square => style::SQUARE,
        };
        let figure = Figure {
            background: style::BACKGROUND,
            ..Figure::new(width, height)
        };
        Sketch {
            figure,
            rays: Vec::new(),
        }
    }

    /// An empty figure of `width x height` pixels on the figures' background.
    pub(crate) fn sized(width: u32, height: u32) -> Sketch {
        let figure = Figure {
            background: style::BACKGROUND,
            ..Figure::new(width, height)
        };
        Sketch {
            figure,
            rays: Vec::new(),
        }
    }

    /// The finished figure and its rays.
    pub(crate) fn finish(self) -> Diagram {
        Diagram {
            figure: self.figure,
            rays: self.rays,
        }
    }

    /// Appends an item.
    pub(crate) fn push(&mut self, item: impl Into<Item>) {
        self.figure.push(item);
    }

    /// The figure's title, top left, bold.
    pub(crate) fn title(&mut self, text: &str) {
        self.push(
            Label::new(text, TITLE_AT)
                .with_size(style::TITLE_SIZE)
                .with_color(style::TEXT)
                .with_face(FontFace::Bold)
                .with_anchor(Anchor::Start, Baseline::Top),
        );
    }

    /// Lines of text, left-aligned, the first baseline at `at`; returns the baseline
    /// after the last line. A line is `(markup, colour, size)`; an empty line is a gap
    /// of half a line.
    pub(crate) fn text_lines(&mut self, at: Vec2, lines: &[(&str, Color, f32)]) -> f32 {
        let mut y = at.y;
        for &(text, color, size) in lines {
            if text.is_empty() {
                y += 0.6 * size;
                continue;
            }
            self.push(
                Label::new(text, Vec2::new(at.x, y))
                    .with_size(size)
                    .with_color(color)
                    .with_anchor(Anchor::Start, Baseline::Alphabetic),
            );
            y += LINE_SPACING * size;
        }
        y
    }

    /// A label centred at `at`.
    pub(crate) fn label(&mut self, text: &str, at: Vec2, color: Color, size: f32) {
        self.push(Label::new(text, at).with_size(size).with_color(color));
    }

    /// A label anchored at `at` as `anchor` and `baseline` say.
    pub(crate) fn label_at(
        &mut self,
        text: &str,
        at: Vec2,
        (anchor, baseline): (Anchor, Baseline),
        color: Color,
        size: f32,
    ) {
        self.push(
            Label::new(text, at)
                .with_size(size)
                .with_color(color)
                .with_anchor(anchor, baseline),
        );
    }

    /// A straight line.
    pub(crate) fn line(&mut self, from: Vec2, to: Vec2, stroke: Stroke) {
        self.push(Item::Line { from, to, stroke });
    }

    /// An arrow from `from` to `to`.
    pub(crate) fn arrow(&mut self, from: Vec2, to: Vec2, stroke: Stroke) {
        self.push(Item::Arrow {
            from,
            to,
            stroke,
            ends: ArrowEnds::End,
        });
    }

    /// A dot.
    pub(crate) fn dot(&mut self, center: Vec2, radius: f32, color: Color) {
        self.push(Item::Dot {
            center,
            radius,
            color,
        });
    }

    /// The image plane's u and v axes through `origin`, the centre of a viewport drawn
    /// from `top_left` to `bottom_right`: u from the left edge to 70 px past the right one,
    /// v from the bottom edge to `v_overshoot` px above the top one, each named at its
    /// head, `label_gap` px clear of the arrow.
    pub(crate) fn uv_axes(
        &mut self,
        origin: Vec2,
        (top_left, bottom_right): (Vec2, Vec2),
        v_overshoot: f32,
        label_gap: f32,
    ) {
        let u_end = Vec2::new(bottom_right.x + 70.0, origin.y);
        let v_end = Vec2::new(origin.x, top_left.y - v_overshoot);
        self.arrow(
            Vec2::new(top_left.x, origin.y),
            u_end,
            Stroke::new(style::U_AXIS, style::LINE_REGULAR),
        );
        self.arrow(
            Vec2::new(origin.x, bottom_right.y),
            v_end,
            Stroke::new(style::V_AXIS, style::LINE_REGULAR),
        );
        self.label_at(
            "$u$",
            u_end + Vec2::new(-4.0, -label_gap),
            (Anchor::End, Baseline::Bottom),
            style::U_AXIS,
            style::LABEL_SIZE,
        );
        self.label_at(
            "$v$",
            v_end + Vec2::new(label_gap + 2.0, 0.0),
            (Anchor::Start, Baseline::Top),
            style::V_AXIS,
            style::LABEL_SIZE,
        );
    }

    /// A dimension: a thin two-headed arrow from `from` to `to` with short extension
    /// ticks at both ends, perpendicular to it.
    pub(crate) fn dimension(&mut self, from: Vec2, to: Vec2) {
        let stroke = Stroke::new(style::ANNOTATION, style::LINE_THIN);
        self.push(Item::Arrow {
            from,
            to,
            stroke: stroke.clone(),
            ends: ArrowEnds::Both,
        });
        if let Some(n) = (to - from).try_normalize() {
            let n = n.perp() * 10.0;
            self.line(from - n, from + n, stroke.clone());
            self.line(to - n, to + n, stroke);
        }
    }

    /// Draws `ray` through `view` (an arrowhead at its end when `head`), and records it
    /// in [`Sketch::rays`].
    pub(crate) fn camera_ray(
        &mut self,
        view: &FigureView,
        ray: CameraRay<'_>,
        stroke: Stroke,
        head: bool,
    ) -> DrawnRay {
        let CameraRay {
            camera,
            pixel: (row, col),
            sample,
            t,
        } = ray;
        let ray = camera
            .generate_ray(row, col, sample)
            .expect("the figures' cameras have a ray for every pixel");
        let (from, to) = (ray.at(t.0), ray.at(t.1));
        let from_px = view.to_figure(from).expect("a drawn ray is in view");
        let to_px = view.to_figure(to).expect("a drawn ray is in view");
        if head {
            self.arrow(from_px, to_px, stroke);
        } else {
            self.line(from_px, to_px, stroke);
        }
        let drawn = DrawnRay {
            view: *view,
            camera: *camera,
            row,
            col,
            sample,
            t,
            from,
            to,
            from_px,
            to_px,
        };
        self.rays.push(drawn);
        drawn
    }

    /// The centre ray of pixel `pixel` from the eye to the image plane (`t` from 0 to 1),
    /// ending in a small dot at the pixel centre: the highlight colour for the figure's
    /// example pixel, the ray colour for the others.
    pub(crate) fn ray_to_pixel_centre(
        &mut self,
        view: &FigureView,
        camera: &Camera,
        pixel: (u32, u32),
        stroke: Stroke,
        example: bool,
    ) {
        let ray = CameraRay {
            camera,
            pixel,
            sample: CameraSample::CENTER,
            t: (0.0, 1.0),
        };
        let drawn = self.camera_ray(view, ray, stroke, false);
        let color = if example {
            style::HIGHLIGHT
        } else {
            style::RAY
        };
        self.dot(drawn.to_px, style::DOT_RADIUS * 0.7, color);
    }

    /// A right-angle mark at `corner` between the world directions `a` and `b`: a small
    /// square of side `size` (world units), drawn through `view`.
    pub(crate) fn right_angle(
        &mut self,
        view: &FigureView,
        corner: DVec3,
        (a, b): (DVec3, DVec3),
        size: f64,
        color: Color,
    ) {
        let (a, b) = (a.normalize() * size, b.normalize() * size);
        let points: Vec<Vec2> = [corner + a, corner + a + b, corner + b]
            .iter()
            .filter_map(|&p| view.to_figure(p))
            .collect();
        self.push(Item::Polyline {
            points,
            closed: false,
            stroke: Stroke::new(color, style::LINE_THIN),
        });
    }

    /// The outline of `rect` (figure pixels).
    pub(crate) fn frame(&mut self, rect: Rect, stroke: Stroke) {
        self.push(Item::Polyline {
            points: rect_corners(rect).to_vec(),
            closed: true,
            stroke,
        });
    }
}

/// A stretch of a viewing ray for [`Sketch::camera_ray`] to draw: the ray `camera`
/// generates for `pixel` (row, col) through `sample`, from `t.0` to `t.1`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct CameraRay<'c> {
    pub(crate) camera: &'c Camera,
    pub(crate) pixel: (u32, u32),
    pub(crate) sample: CameraSample,
    pub(crate) t: (f64, f64),
}

impl<'c> CameraRay<'c> {
    /// The ray through the continuous image point `image` and the lens sample `p_lens`:
    /// the ray of the pixel that holds the point, at the point's offset inside it.
    pub(crate) fn through(
        camera: &'c Camera,
        image: DVec2,
        p_lens: DVec2,
        t: (f64, f64),
    ) -> CameraRay<'c> {
        let (row, col, p_film) = pixel_and_offset(camera, image);
        CameraRay {
            camera,
            pixel: (row, col),
            sample: CameraSample { p_film, p_lens },
            t,
        }
    }
}

/// Baseline-to-baseline distance of [`Sketch::text_lines`], in font sizes.
pub(crate) const LINE_SPACING: f32 = 1.5;

/// The four corners of `rect`, clockwise on screen from the top left.
pub(crate) fn rect_corners(rect: Rect) -> [Vec2; 4] {
    [
        rect.min,
        Vec2::new(rect.max.x, rect.min.y),
        rect.max,
        Vec2::new(rect.min.x, rect.max.y),
    ]
}

/// The pixel `(row, col)` holding the continuous image point `image` and the offset of
/// the point inside it; a point on the image's right or bottom edge belongs to the last
/// column or row, at offset 1.
pub(crate) fn pixel_and_offset(camera: &Camera, image: DVec2) -> (u32, u32, DVec2) {
    let last = DVec2::new(
        f64::from(camera.width() - 1),
        f64::from(camera.height() - 1),
    );
    let cell = image.floor().clamp(DVec2::ZERO, last);
    // The cell is a whole number in [0, W - 1] x [0, H - 1].
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let (row, col) = (cell.y as u32, cell.x as u32);
    (row, col, image - cell)
}

/// `(x, y, z)` for a label, each coordinate a [`number::label`].
pub(crate) fn vector(v: DVec3) -> String {
    format!(
        "({}, {}, {})",
        number::label(v.x),
        number::label(v.y),
        number::label(v.z)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vectors_are_three_label_numbers() {
        assert_eq!(
            vector(DVec3::new(0.2, -0.2, -1.0)),
            "(0.2, \u{2212}0.2, \u{2212}1)"
        );
        assert_eq!(vector(DVec3::new(1.23456, -0.0001, 0.0)), "(1.235, 0, 0)");
    }

    #[test]
    fn image_points_belong_to_their_pixel() {
        let camera = Camera::canonical(4, 3).expect("valid");
        assert_eq!(
            pixel_and_offset(&camera, DVec2::new(2.5, 1.25)),
            (1, 2, DVec2::new(0.5, 0.25))
        );
        assert_eq!(
            pixel_and_offset(&camera, DVec2::new(4.0, 3.0)),
            (2, 3, DVec2::new(1.0, 1.0))
        );
    }
}
