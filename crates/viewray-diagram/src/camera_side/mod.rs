//! The side view of any camera over a scene: the scene's objects, the eye and its frame,
//! the image plane seen edge-on, the frustum and a few viewing rays up to what they hit,
//! in a window on the world that is fitted to one camera or fixed for an animation.
//!
//! [`side_view`] draws it, step by step, from its parts:
//!
//! - [`window`]: the [`SideWindow`], the plane and rectangle of the world shown;
//! - [`canvas`]: the [`SideViewCanvas`] (slide, panel, beside a picture) and its layout;
//! - [`objects`]: the scene's objects projected onto the plane;
//! - [`camera`]: the camera's marks (lens, focus plane, traced rays, a far eye's arrow);
//! - [`labels`]: the frame's and the image plane's names, each placed where it is free;
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
use self::caption::draw_caption;
use self::labels::{beside, draw_frame_labels, draw_image_plane_label, place_label};
use self::objects::draw_objects;
pub use self::window::SideWindow;
use crate::Diagram;
use crate::side::{draw_image_plane, draw_side_frame, viewport_edges};
use crate::sketch::{CameraRay, Sketch};
use crate::style;
use crate::view::FigureView;

/// How many viewing rays of the middle column are drawn, spread over its rows.
const RAY_COUNT: u32 = 5;

/// The side view of `camera` over `scene` in `window`, on `canvas`: the plane of the
/// window seen face-on (for a window fitted to this camera, the plane of its **v** and
/// **w**, so **u** points at the viewer; world up is up, so a tilted camera looks tilted
/// and a shifted one level). It shows the scene's objects projected onto that plane
/// (spheres as circles, boxes and meshes as their outlines, planes seen edge-on as
/// lines), the eye **e** with **v** and **w** (an arrow at the edge when the eye lies
/// beyond the window), the image plane edge-on, the frustum's top and bottom edges, a
/// thin lens's lens and focus plane, and the viewing rays of five pixels of the middle
/// column, each drawn to the first thing it hits, traced in the scene; a caption names
/// the projection and its parameters. `pixel` (row, col), when given, adds that pixel's
/// ray, highlighted.
pub(crate) fn side_view(
    scene: &Scene,
    camera: &Camera,
    window: &SideWindow,
    canvas: SideViewCanvas,
    pixel: Option<(u32, u32)>,
) -> Diagram {
    let layout = canvas.layout();
    let (width, height) = canvas.size();
    let mut sketch = Sketch::sized(width, height);
    if layout.title {
        sketch.title("Side view of the camera");
    }
    let view = window.view(layout.drawing);
    draw_objects(&mut sketch, &view, scene);
    // The caption over the drawing goes on top of the objects, before anything is placed
    // around it.
    draw_caption(&mut sketch, camera, canvas, layout.caption_at);
    let figure_view = FigureView::Side(view);

    // The frustum's top and bottom edges, for the planar projections.
    let frame = *camera.frame();
    let planar = camera.projection().viewport().is_some();
    if planar {
        let x = f64::from(camera.width()) / 2.0;
        let stroke = Stroke::new(style::RAY, style::LINE_THIN).dashed(&style::DASH);
        for y in [0.0, f64::from(camera.height())] {
            let image = DVec2::new(x, y);
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
    if let Some((aperture, focus)) = lens(camera) {
        draw_focus_plane(&mut sketch, &view, camera, focus);
        if eye_in_view {
            let half = view.length(aperture).max(2.0);
            sketch.push(Item::Ellipse {
                center: view.to_figure(frame.e()),
                radii: Vec2::new((half * 0.18).max(3.0), half),
                rotation: -tilt_on_figure(&view, frame.v()),
                fill: Some(style::IMAGE_PLANE_FILL),
                stroke: Some(Stroke::new(style::OBJECT, style::LINE_THIN)),
            });
        }
    }

    // A few viewing rays of the middle column, each to what it hits.
    let col = camera.width() / 2;
    let rows = (0..RAY_COUNT).map(|k| {
        let centre = (f64::from(k) + 0.5) / f64::from(RAY_COUNT) * f64::from(camera.height());
        // Rows are whole pixels inside the image.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let row = centre.floor() as u32;
        row.min(camera.height() - 1)
    });
    let ray_stroke = Stroke::new(style::RAY, style::LINE_REGULAR);
    for row in rows {
        draw_traced_ray(
            &mut sketch,
            &view,
            scene,
            camera,
            (row, col),
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

    // The image plane, the frame at the eye, the eye (or an arrow towards it); the
    // plane's label where it overlaps no other.
    let plane_ends = if planar && eye_in_view {
        let (top, bottom) = viewport_edges(camera);
        let (top, bottom) = (view.plane_point(top), view.plane_point(bottom));
        (view.bounds.contains(top.as_vec2()) && view.bounds.contains(bottom.as_vec2()))
            .then(|| draw_image_plane(&mut sketch, &view, camera, style::IMAGE_PLANE, 0.0))
    } else {
        None
    };
    if eye_in_view {
        let axis_length = 0.09 * (window.max - window.min).max_element();
        draw_side_frame(&mut sketch, &view, &frame, axis_length, false);
        draw_frame_labels(&mut sketch, &view, &frame, axis_length);
    } else {
        draw_eye_beyond(&mut sketch, &view, frame.e());
    }
    if let Some((top, bottom)) = plane_ends {
        draw_image_plane_label(&mut sketch, camera, top, bottom);
    }

    if let Some((pixel, hit)) = pixel_hit {
        let text = format!("$i$ = {}, $j$ = {}", pixel.0 + 1, pixel.1 + 1);
        let candidates = [
            beside(hit, 14.0, -14.0),
            beside(hit, -14.0, -14.0),
            beside(hit, 14.0, 14.0),
            beside(hit, -14.0, 14.0),
            beside(hit, 0.0, -50.0),
            beside(hit, 0.0, 50.0),
        ];
        place_label(
            &mut sketch,
            &text,
            &candidates,
            style::HIGHLIGHT,
            style::SMALL_LABEL_SIZE,
        );
    }
    sketch.finish()
}
