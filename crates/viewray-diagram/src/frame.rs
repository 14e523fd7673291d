//! The camera frame e, u, v, w built from eye, view and up.

use glam::{DVec3, Vec2};
use viewray_camera::Frame;

use crate::Diagram;
use crate::sketch::{Canvas, Sketch, vector};
use crate::style;
use crate::view::{CameraView, FigureView};
use viewray_draw::{Color, Item, Rect, Stroke};

/// The camera's eye in the frame figure.
const EYE: DVec3 = DVec3::new(1.2, 1.3, 1.8);
/// Its view direction: ahead and 30 degrees down.
const VIEW: DVec3 = DVec3::new(-1.1, -1.25, -1.8);
/// Its up vector: the world's vertical, not perpendicular to the view.
const UP: DVec3 = DVec3::Y;

/// The camera frame (slide, 1600 x 900): **e**, **u**, **v**, **w** computed by
/// [`Frame::from_eye_view_up`] from **eye**, **view** and **up**, drawn in 3D through an
/// orthographic figure camera, with **view** and **up**, the plane they span (which holds
/// **v** and **w**), and the right angles between **u**, **v** and **w**.
///
/// ```text
/// e = eye,  w = -view / |view|,  u = (up x w) / |up x w|,  v = w x u
/// ```
pub(crate) fn camera_frame() -> Diagram {
    camera_frame_on(Canvas::Slide)
}

/// [`camera_frame`] on the square canvas (1080 x 1080): the 3D view on top, the recipe
/// and the numbers below.
pub(crate) fn camera_frame_square() -> Diagram {
    camera_frame_on(Canvas::Square)
}

fn camera_frame_on(canvas: Canvas) -> Diagram {
    let frame = Frame::from_eye_view_up(EYE, VIEW, UP).expect("a valid frame");
    let mut sketch = Sketch::on(canvas);
    sketch.title(match canvas {
        Canvas::Slide => "The camera frame from *eye*, *view* and *up*",
        Canvas::Square => "The camera frame",
    });

    let view_tip = EYE + VIEW.normalize() * 1.6;
    let up_tip = EYE + UP * 1.25;
    // The plane of up and view around the eye: it holds v and w.
    let span = [
        EYE + UP * 1.5 + VIEW.normalize() * 1.9,
        EYE + UP * 1.5 - VIEW.normalize() * 1.0,
        EYE - UP * 0.5 - VIEW.normalize() * 1.0,
        EYE - UP * 0.5 + VIEW.normalize() * 1.9,
    ];
    let mut fit = span.to_vec();
    fit.extend([
        EYE + frame.u() * 1.2,
        EYE - frame.u() * 0.3,
        view_tip,
        up_tip,
    ]);
    let towards = 0.6 * frame.u() + 0.4 * frame.v() + 1.0 * frame.w();
    let view = CameraView::fit_orthographic(
        towards,
        DVec3::Y,
        &fit,
        match canvas {
            Canvas::Slide => Rect::from_xywh(40.0, 110.0, 900.0, 770.0),
            Canvas::Square => Rect::from_xywh(40.0, 100.0, 1000.0, 580.0),
        },
        70.0,
    );
    let fv = FigureView::Camera(view);
    let at = |p: DVec3| view.to_figure(p).expect("in view");
    let e = at(EYE);

    sketch.push(Item::Polygon {
        points: span.iter().map(|&p| at(p)).collect(),
        fill: style::GRID.with_alpha(0.25),
        stroke: Some(Stroke::new(style::GRID, style::LINE_THIN)),
    });
    // Inside the plane's lower left corner on the slide; under it on the square, where
    // the plane is small and u crosses that corner.
    let (plane_label_at, plane_label_baseline) = match canvas {
        Canvas::Slide => (
            at(span[2]) + Vec2::new(12.0, -10.0),
            viewray_draw::Baseline::Bottom,
        ),
        Canvas::Square => (
            at(span[2]) + Vec2::new(-30.0, 12.0),
            viewray_draw::Baseline::Top,
        ),
    };
    sketch.label_at(
        "plane of *up* and *view*",
        plane_label_at,
        (viewray_draw::Anchor::Start, plane_label_baseline),
        style::ANNOTATION,
        style::SMALL_LABEL_SIZE,
    );

    // view and up, the given vectors, in grey.
    let given = Stroke::new(style::ANNOTATION, style::LINE_REGULAR);
    sketch.arrow(e, at(view_tip), given.clone());
    sketch.arrow(e, at(up_tip), given);
    let offset = |tip: Vec2, by: f32| {
        let out = (tip - e).normalize_or_zero();
        tip + out * by
    };
    sketch.label(
        "*view*",
        offset(at(view_tip), 46.0),
        style::ANNOTATION,
        style::LABEL_SIZE,
    );
    sketch.label(
        "*up*",
        offset(at(up_tip), 30.0),
        style::ANNOTATION,
        style::LABEL_SIZE,
    );

    // Right angles, then the basis.
    // The three right angles, each mark a different size so that they read as three
    // marks rather than one small cube.
    for (a, b, size) in [
        (frame.v(), frame.w(), 0.22),
        (frame.w(), frame.u(), 0.16),
        (frame.u(), frame.v(), 0.11),
    ] {
        sketch.right_angle(&fv, EYE, (a, b), size, style::TEXT);
    }
    for (axis, color, name, by) in [
        (frame.u(), style::U_AXIS, "*u*", 28.0),
        (frame.v(), style::V_AXIS, "*v*", 28.0),
        (frame.w(), style::W_AXIS, "*w*", 28.0),
    ] {
        let tip = at(EYE + axis);
        sketch.arrow(e, tip, Stroke::new(color, style::LINE_THICK));
        sketch.label(name, offset(tip, by), color, style::LABEL_SIZE);
    }
    sketch.dot(e, style::DOT_RADIUS, style::EYE);
    sketch.label_at(
        "*e*",
        e + Vec2::new(-18.0, 14.0),
        (viewray_draw::Anchor::End, viewray_draw::Baseline::Top),
        style::EYE,
        style::LABEL_SIZE,
    );

    // The recipe, and this frame's numbers.
    let (l, s) = (style::LABEL_SIZE, style::SMALL_LABEL_SIZE);
    let given_line = format!("*eye* = {}", vector(EYE));
    let view_line = format!("*view* = {}", vector(VIEW));
    let up_line = format!("*up* = {}", vector(UP));
    let u_line = format!("*u* = {}", vector(frame.u()));
    let v_line = format!("*v* = {}", vector(frame.v()));
    let w_line = format!("*w* = {}", vector(frame.w()));
    let recipe = |size: f32| {
        [
            ("1.  *e* = *eye*", style::EYE, size),
            ("2.  *w* = −*view* / |*view*|", style::W_AXIS, size),
            ("3.  *u* = *up* × *w* / |*up* × *w*|", style::U_AXIS, size),
            ("4.  *v* = *w* × *u*", style::V_AXIS, size),
        ]
    };
    let numbers = [
        (given_line.as_str(), style::ANNOTATION, s),
        (&view_line, style::ANNOTATION, s),
        (&up_line, style::ANNOTATION, s),
        (&u_line, style::U_AXIS, s),
        (&v_line, style::V_AXIS, s),
        (&w_line, style::W_AXIS, s),
    ];
    if canvas == Canvas::Square {
        sketch.text_lines(Vec2::new(50.0, 760.0), &recipe(style::CAPTION_SIZE));
        sketch.text_lines(Vec2::new(620.0, 750.0), &numbers);
        return sketch.finish();
    }
    let blank = ("", style::TEXT, l);
    let notes = [
        (
            "*up* need not be perpendicular to *view*:",
            style::ANNOTATION,
            s,
        ),
        (
            "*v* is *up* made perpendicular to *w*",
            style::ANNOTATION,
            s,
        ),
    ];
    let lines: Vec<(&str, Color, f32)> = recipe(l)
        .into_iter()
        .chain([blank])
        .chain(numbers)
        .chain([blank])
        .chain(notes)
        .collect();
    sketch.text_lines(Vec2::new(960.0, 190.0), &lines);
    sketch.finish()
}
