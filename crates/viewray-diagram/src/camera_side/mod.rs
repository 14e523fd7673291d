//! The side view of any camera over a scene: the scene's objects, the eye and its frame,
//! the image plane seen edge-on, the frustum and a few viewing rays up to what they hit,
//! in a window on the world that is fitted to one camera or fixed for an animation.
//!
//! [`side_view`] draws it, step by step, from its parts:
//!
//! - [`window`]: the [`SideWindow`], the plane (the side's **v** and **w**, or the top's
//!   **u** and **w**) and rectangle of the world shown;
//! - [`canvas`]: the [`SideViewCanvas`] (slide, panel, beside a picture) and its layout;
//! - [`objects`]: the scene's objects projected onto the plane;
//! - [`camera`]: the camera's marks (lens, focus plane, traced rays, a far eye's arrow);
//! - [`labels`]: the frame's and the image plane's names, placed last, each where it
//!   covers no other label and, where it can, nothing drawn;
//! - [`caption`]: the projection and its parameters in the lecture's notation.

mod camera;
mod canvas;
mod caption;
mod labels;
mod objects;
mod window;

use glam::{DVec2, Vec2};
use viewray_camera::Camera;
use viewray_draw::{Item, Stroke};
use viewray_scene::Scene;

use self::camera::{draw_eye_beyond, draw_focus_plane, draw_traced_ray, lens, tilt_on_figure};
pub use self::canvas::SideViewCanvas;
use self::caption::Caption;
use self::labels::{Labels, beside, focus_plane_label, frame_labels, image_plane_label};
use self::objects::draw_objects;
pub use self::window::SideWindow;
use self::window::{Plane, objects_centre};
use crate::Diagram;
use crate::side::draw_out_of_page;
use crate::sketch::{CameraRay, Sketch};
use crate::style;
use crate::view::FigureView;

/// How many viewing rays of the middle column (or row) are drawn, spread over it.
const RAY_COUNT: u32 = 5;

/// The side view of `camera` over `scene` in `window`, on `canvas`: the plane of the
/// window seen face-on (for a window fitted to this camera, the plane of its **v** and
/// **w**, so **u** points at the viewer; world up is up, so a tilted camera looks tilted
/// and a shifted one level; for a top view, the plane of **u** and **w** seen from **v**'s
/// side). It shows the scene's objects projected onto that plane (spheres as circles,
/// boxes and meshes as their outlines, planes seen edge-on as lines), the eye **e** with
/// the two axes in the plane (an arrow at the edge when the eye lies beyond the window),
/// the image plane edge-on, the frustum's edges, a thin lens's lens and focus plane, and
/// the viewing rays of five pixels of the middle column (row, from above), each drawn to
/// the first thing it hits, traced in the scene; a caption names the projection and its
/// parameters. `pixel` (row, col), when given, adds that pixel's ray, highlighted. The
/// labels are placed last, each where it covers no other and, where it can, nothing
/// drawn.
pub(crate) fn side_view(
    scene: &Scene,
    camera: &Camera,
    window: &SideWindow,
    canvas: SideViewCanvas,
    pixel: Option<(u32, u32)>,
) -> Diagram {
    let plane = window.plane;
    let caption = Caption::new(camera, canvas);
    let layout = canvas.layout(caption.len());
    let (width, height) = canvas.size();
    let mut sketch = Sketch::sized(width, height);
    if layout.title {
        sketch.title(match plane {
            Plane::Side => "Side view of the camera",
            Plane::Top => "Top view of the camera",
        });
    }
    let view = window.view(layout.drawing);
    draw_objects(&mut sketch, &view, scene);
    // The caption over the drawing goes on top of the objects, before anything is placed
    // around it.
    caption.draw(&mut sketch, canvas, layout.caption_at);
    let figure_view = FigureView::Side(view);
    let mut labels = Labels::default();

    // The frustum's edges in the plane, for the planar projections.
    let frame = *camera.frame();
    let planar = camera.projection().viewport().is_some();
    if planar {
        let stroke = Stroke::new(style::RAY, style::LINE_THIN).dashed(&style::DASH);
        for image in plane.image_edges(camera) {
            if let Some(ray) = camera.generate_ray_through(image, DVec2::splat(0.5))
                && let Some(t) = view.clip_ray(&ray, (0.0, f64::INFINITY))
                && t.1.is_finite()
            {
                sketch.camera_ray(
                    &figure_view,
                    CameraRay::through(camera, image, DVec2::splat(0.5), t),
                    stroke.clone(),
                    false,
                );
            }
        }
    }

    // The thin lens's focus plane and lens.
    let eye_in_view = view.bounds.contains(view.plane_point(frame.e()).as_vec2());
    let mut focus_ends = None;
    if let Some((aperture, focus)) = lens(camera) {
        focus_ends = draw_focus_plane(&mut sketch, &view, camera, (focus, plane))
            .map(|(upper, lower)| (focus, upper, lower));
        if eye_in_view {
            let half = view.length(aperture).max(2.0);
            sketch.push(Item::Ellipse {
                center: view.to_figure(frame.e()),
                radii: Vec2::new((half * 0.18).max(3.0), half),
                rotation: -tilt_on_figure(&view, plane.across(&frame)),
                fill: Some(style::IMAGE_PLANE_FILL),
                stroke: Some(Stroke::new(style::OBJECT, style::LINE_THIN)),
            });
        }
    }

    // A few viewing rays of the middle column (row), each to what it hits.
    let ray_stroke = Stroke::new(style::RAY, style::LINE_REGULAR);
    for pixel in plane.pixels(camera, RAY_COUNT) {
        draw_traced_ray(
            &mut sketch,
            &view,
            scene,
            camera,
            pixel,
            &ray_stroke,
            style::RAY,
        );
    }
    let pixel_hit = pixel.and_then(|pixel| {
        let stroke = Stroke::new(style::HIGHLIGHT, style::LINE_THICK);
        draw_traced_ray(
            &mut sketch,
            &view,
            scene,
            camera,
            pixel,
            &stroke,
            style::HIGHLIGHT,
        )
        .map(|hit| (pixel, hit))
    });

    // The image plane, the frame at the eye, the eye (or an arrow towards it).
    let mut plane_ends = None;
    if planar && eye_in_view {
        let (top, bottom) = plane.viewport_edges(camera);
        let (top, bottom) = (view.plane_point(top), view.plane_point(bottom));
        if view.bounds.contains(top.as_vec2()) && view.bounds.contains(bottom.as_vec2()) {
            let (top, bottom) = (
                view.mapping.to_canvas(top.as_vec2()),
                view.mapping.to_canvas(bottom.as_vec2()),
            );
            sketch.line(
                top,
                bottom,
                Stroke::new(style::IMAGE_PLANE, style::LINE_THICK),
            );
            plane_ends = Some((top, bottom));
        }
    }
    if eye_in_view {
        let axis_length = 0.09 * (window.max - window.min).max_element();
        let e = view.to_figure(frame.e());
        for (axis, color, _) in plane.arrows(&frame) {
            let tip = view.to_figure(frame.e() + axis * axis_length);
            sketch.arrow(e, tip, Stroke::new(color, style::LINE_THICK));
        }
        let (out, color, _) = plane.out_axis(&frame);
        draw_out_of_page(&mut sketch, e, out.dot(view.towards_viewer()) > 0.0, color);
        frame_labels(&mut labels, &view, &frame, plane, axis_length);
    } else {
        draw_eye_beyond(
            &mut sketch,
            &mut labels,
            &view,
            frame.e(),
            objects_centre(scene),
        );
    }

    if let Some((top, bottom)) = plane_ends {
        image_plane_label(&mut labels, camera, top, bottom);
    }
    if let Some((focus, upper, lower)) = focus_ends {
        focus_plane_label(&mut labels, focus, upper, lower);
    }
    if let Some((pixel, hit)) = pixel_hit {
        let text = format!("$i$ = {}, $j$ = {}", pixel.0 + 1, pixel.1 + 1);
        let mut candidates = Vec::new();
        for gap in [14.0, 40.0, 80.0, 130.0] {
            candidates.extend([
                beside(hit, gap, -gap),
                beside(hit, -gap, -gap),
                beside(hit, gap, gap),
                beside(hit, -gap, gap),
                beside(hit, 0.0, -2.5 * gap),
                beside(hit, 0.0, 2.5 * gap),
            ]);
        }
        labels.add_naming(
            text,
            candidates,
            (style::HIGHLIGHT, style::SMALL_LABEL_SIZE),
            hit,
        );
    }
    labels.place(&mut sketch);
    sketch.finish()
}
