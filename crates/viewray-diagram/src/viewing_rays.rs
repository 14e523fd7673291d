//! The four planar families side by side: which rays each generates.

use std::f64::consts::FRAC_PI_2;

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, Frame, Oblique, Orthographic, Perspective, Projection};

use crate::Diagram;
use crate::side::{draw_column_rays, draw_frustum_edges, draw_image_plane, draw_side_frame};
use crate::sketch::Sketch;
use crate::style;
use crate::view::SideView;
use viewray_draw::{Anchor, Baseline, Rect, Stroke};

/// The image of every camera of the figure: `W x H` pixels.
const SIZE: (u32, u32) = (5, 5);
/// The common viewport `(vw, vh)`.
const VIEWPORT: DVec2 = DVec2::new(1.2, 1.2);
/// The depth (along `-z`) of the image plane of all four cameras.
const PLANE_DEPTH: f64 = 1.0;
/// How far (along `-z`) the rays are drawn.
const FAR_DEPTH: f64 = 2.05;

/// One panel: a camera, its name and property, and its rule.
struct Panel {
    camera: Camera,
    title: &'static str,
    property: &'static str,
    rule: [&'static str; 4],
    /// The camera's parameters, if the rule names any.
    parameters: &'static str,
}

/// The four cameras, all with the same viewport at the same place: perspective,
/// orthographic, oblique and shifted perspective.
fn panels() -> [Panel; 4] {
    let canonical = Frame::CANONICAL;
    let on_plane = Frame::CANONICAL
        .with_eye(DVec3::new(0.0, 0.0, -PLANE_DEPTH))
        .expect("a finite eye");
    let camera = |frame: Frame, projection: Projection| {
        Camera::new(frame, projection, SIZE.0, SIZE.1).expect("a valid camera")
    };
    let perspective = Perspective {
        distance: PLANE_DEPTH,
        viewport: VIEWPORT,
        shift: DVec2::ZERO,
    };
    [
        Panel {
            camera: camera(canonical, Projection::Perspective(perspective)),
            title: "Perspective",
            property: "converge at *e*",
            rule: ["origin *e*", "direction", "$u$ *u* + $v$ *v* − $d$ *w*", ""],
            parameters: "",
        },
        Panel {
            camera: camera(
                on_plane,
                Projection::Orthographic(Orthographic {
                    viewport: VIEWPORT,
                    lens: None,
                }),
            ),
            title: "Orthographic",
            property: "parallel, perpendicular",
            rule: ["origin *e* + $u$ *u* + $v$ *v*", "direction", "−*w*", ""],
            parameters: "",
        },
        Panel {
            camera: camera(
                on_plane,
                Projection::Oblique(Oblique {
                    viewport: VIEWPORT,
                    ratio: 0.5,
                    angle: FRAC_PI_2,
                }),
            ),
            title: "Oblique parallel",
            property: "parallel, slanted",
            rule: [
                "origin *e* + $u$ *u* + $v$ *v*",
                "direction",
                "−*w* − $L$ cos $φ$ *u*",
                "      − $L$ sin $φ$ *v*",
            ],
            parameters: "$L$ = ½,  $φ$ = 90°",
        },
        Panel {
            camera: camera(
                canonical,
                Projection::Perspective(Perspective {
                    shift: DVec2::new(0.0, 0.45),
                    ..perspective
                }),
            ),
            title: "Shifted perspective",
            property: "asymmetric frustum",
            rule: [
                "origin *e*",
                "direction",
                "$u$ *u* + ($v + s_y$) *v*",
                "      − $d$ *w*",
            ],
            parameters: "$s_y$ = 0.45",
        },
    ]
}

/// The viewing rays of the four planar families (slide, 1600 x 900), side by side, each
/// a side view of one column of a 5 x 5 image with the same viewport at the same place:
/// perspective (converging at **e**), orthographic (parallel and perpendicular to the
/// image plane), oblique parallel (parallel and slanted) and shifted perspective (an
/// asymmetric frustum whose optical axis misses the window's centre).
pub(crate) fn viewing_rays() -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("Viewing rays: one rule per projection");
    let width = 372.0;
    for (k, panel) in panels().iter().enumerate() {
        let cell = Rect::from_xywh(40.0 + k as f32 * (width + 10.0), 115.0, width, 770.0);
        draw_panel(&mut sketch, panel, cell);
    }
    sketch.finish()
}

/// One panel inside `cell`: title and property on top, the side view, the rule below.
fn draw_panel(sketch: &mut Sketch, panel: &Panel, cell: Rect) {
    let camera = &panel.camera;
    let parallel = camera.projection().is_parallel();
    sketch.frame(cell, Stroke::new(style::GRID, 1.5));
    let centre_x = cell.center().x;
    sketch.label_at(
        panel.title,
        Vec2::new(centre_x, cell.min.y + 16.0),
        (Anchor::Middle, Baseline::Top),
        style::TEXT,
        style::CAPTION_SIZE,
    );
    sketch.label_at(
        panel.property,
        Vec2::new(centre_x, cell.min.y + 66.0),
        (Anchor::Middle, Baseline::Top),
        style::RAY,
        style::SMALL_LABEL_SIZE,
    );

    // Every panel shows the same stretch of the y-z plane at the same scale, so the
    // image planes line up across the slide.
    let region = Rect::from_xywh(
        cell.min.x + 8.0,
        cell.min.y + 100.0,
        cell.width() - 16.0,
        430.0,
    );
    let view = SideView::fit((-0.45, 2.15), (-1.05, 2.2), region);

    // The frustum's edges and the rays, the plane, then the frame at the eye.
    let t_far = if parallel {
        FAR_DEPTH - PLANE_DEPTH
    } else {
        FAR_DEPTH / PLANE_DEPTH
    };
    if !parallel {
        let edges = Stroke::new(style::RAY, style::LINE_THIN).dashed(&[8.0, 6.0]);
        draw_frustum_edges(sketch, &view, camera, (0.0, t_far), &edges);
    }
    let stroke = Stroke::new(style::RAY, style::LINE_REGULAR);
    draw_column_rays(sketch, &view, camera, SIZE.0 / 2, (0.0, t_far), &stroke);
    if let Projection::Perspective(p) = camera.projection()
        && p.shift != DVec2::ZERO
    {
        // The unshifted window and the optical axis, for comparison.
        let axis = Stroke::new(style::ANNOTATION, style::LINE_THIN).dashed(&style::DASH);
        let e = camera.frame().e();
        sketch.line(
            view.to_figure(e),
            view.to_figure(e - camera.frame().w() * FAR_DEPTH),
            axis.clone(),
        );
        let half = VIEWPORT.y / 2.0;
        sketch.line(
            view.to_figure(DVec3::new(0.0, -half, -PLANE_DEPTH)),
            view.to_figure(DVec3::new(0.0, half, -PLANE_DEPTH)),
            axis,
        );
    }
    draw_image_plane(sketch, &view, camera, style::IMAGE_PLANE, 0.0);
    draw_side_frame(sketch, &view, camera.frame(), 0.35, false);
    let e = view.to_figure(camera.frame().e());
    sketch.label_at(
        "*e*",
        e + Vec2::new(-14.0, 14.0),
        (Anchor::End, Baseline::Top),
        style::EYE,
        style::LABEL_SIZE,
    );

    let mut lines: Vec<(&str, viewray_draw::Color, f32)> = panel
        .rule
        .iter()
        .filter(|text| !text.is_empty())
        .enumerate()
        .map(|(k, text)| {
            let color = if k == 1 {
                style::ANNOTATION
            } else {
                style::TEXT
            };
            (*text, color, style::SMALL_LABEL_SIZE)
        })
        .collect();
    if !panel.parameters.is_empty() {
        lines.push((panel.parameters, style::ANNOTATION, style::SMALL_LABEL_SIZE));
    }
    sketch.text_lines(Vec2::new(cell.min.x + 20.0, cell.min.y + 565.0), &lines);
}
