//! Side views of cameras: the eye and its frame, the image plane seen edge-on, and the
//! viewing rays of one column of pixels, all in the y-z plane.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, Frame, Projection};

use crate::DrawnRay;
use crate::sketch::{CameraRay, Sketch};
use crate::style;
use crate::view::{FigureView, SideView};
use viewray_draw::{Color, Item, Stroke};

/// The top and bottom edges of a planar camera's viewport, in the middle column, as
/// world points: where the rays through the image's top and bottom edges (through the
/// lens centre) meet the image plane. A perspective ray's direction has the component
/// `-d w`, so it reaches the plane at `t = 1`; a thin lens's ray has `-f w`, reaching it
/// at `t = d / f`; a parallel camera's rays start on the plane.
pub(crate) fn viewport_edges(camera: &Camera) -> (DVec3, DVec3) {
    let w = f64::from(camera.width());
    let h = f64::from(camera.height());
    viewport_points(camera, [DVec2::new(w / 2.0, 0.0), DVec2::new(w / 2.0, h)])
}

/// The points of a planar camera's viewport seen at the image points `image` (pixel
/// units, through the lens centre), as [`viewport_edges`] finds them.
pub(crate) fn viewport_points(camera: &Camera, image: [DVec2; 2]) -> (DVec3, DVec3) {
    let distance = match camera.projection() {
        Projection::Perspective(p) => Some(p.distance),
        Projection::ThinLens(p) => Some(p.distance),
        _ => None,
    };
    let at_plane = |point: DVec2| {
        let ray = camera
            .generate_ray_through(point, DVec2::splat(0.5))
            .expect("a planar camera has a ray at every image point");
        match distance {
            Some(d) => ray.at(d / -ray.direction.dot(camera.frame().w())),
            None => ray.origin,
        }
    };
    (at_plane(image[0]), at_plane(image[1]))
}

/// Draws the image plane seen edge-on: a thick segment over the viewport and, when
/// `extend` is positive, a thin continuation of that many world units past both ends.
pub(crate) fn draw_image_plane(
    sketch: &mut Sketch,
    view: &SideView,
    camera: &Camera,
    color: Color,
    extend: f64,
) -> (Vec2, Vec2) {
    let (top, bottom) = viewport_edges(camera);
    let (top_px, bottom_px) = (view.to_figure(top), view.to_figure(bottom));
    if extend > 0.0 {
        let along = (top - bottom).normalize() * extend;
        sketch.line(
            view.to_figure(top + along),
            view.to_figure(bottom - along),
            Stroke::new(color.with_alpha(0.5), style::LINE_THIN),
        );
    }
    sketch.line(top_px, bottom_px, Stroke::new(color, style::LINE_THICK));
    (top_px, bottom_px)
}

/// Draws the viewing rays of every pixel of column `col` (pixel centres, lens centre)
/// from `t.0` to `t.1`, recording them; returns them top row first.
pub(crate) fn draw_column_rays(
    sketch: &mut Sketch,
    view: &SideView,
    camera: &Camera,
    col: u32,
    t: (f64, f64),
    stroke: &Stroke,
) -> Vec<DrawnRay> {
    let fv = FigureView::Side(*view);
    (0..camera.height())
        .filter_map(|row| {
            let ray = camera.generate_ray(row, col, CameraSample::CENTER)?;
            let clipped = view.clip_ray(&ray, t)?;
            Some(sketch.camera_ray(
                &fv,
                CameraRay {
                    camera,
                    pixel: (row, col),
                    sample: CameraSample::CENTER,
                    t: clipped,
                },
                stroke.clone(),
                true,
            ))
        })
        .collect()
}

/// Draws the camera frame at the eye in a side view: **v** and **w** as arrows of
/// `length` world units, **u** (perpendicular to the page) as a circled dot when it
/// points at the viewer, a circled cross when away; labels them when `labels`.
pub(crate) fn draw_side_frame(
    sketch: &mut Sketch,
    view: &SideView,
    frame: &Frame,
    length: f64,
    labels: bool,
) {
    let e = view.to_figure(frame.e());
    for (axis, color, name) in [
        (frame.v(), style::V_AXIS, "*v*"),
        (frame.w(), style::W_AXIS, "*w*"),
    ] {
        let tip = view.to_figure(frame.e() + axis * length);
        sketch.arrow(e, tip, Stroke::new(color, style::LINE_THICK));
        if labels {
            let out = (tip - e).normalize_or_zero();
            sketch.label(
                name,
                tip + out * 26.0 + out.perp() * 0.0,
                color,
                style::LABEL_SIZE,
            );
        }
    }
    // u is out of the page when it points towards the viewer of the side view (along x
    // in the lecture's figures, seen from +x). Its label goes in the quadrant between v
    // (up) and w, on the side away from -w.
    if labels {
        let away = view.to_figure(frame.e() + frame.w()) - e;
        let side = if away.x <= 0.0 { -1.0 } else { 1.0 };
        sketch.label(
            "*u*",
            e + Vec2::new(side * 30.0, -32.0),
            style::U_AXIS,
            style::LABEL_SIZE,
        );
    }
    draw_out_of_page(
        sketch,
        e,
        frame.u().dot(view.towards_viewer()) > 0.0,
        style::U_AXIS,
    );
}

/// Draws the mark at the eye `e` of the axis perpendicular to the page: a circled dot
/// when it points at the viewer (`towards_viewer`), a circled cross when away.
pub(crate) fn draw_out_of_page(sketch: &mut Sketch, e: Vec2, towards_viewer: bool, color: Color) {
    sketch.push(Item::Ellipse {
        center: e,
        radii: Vec2::splat(15.0),
        rotation: 0.0,
        fill: Some(style::BACKGROUND),
        stroke: Some(Stroke::new(color, style::LINE_REGULAR)),
    });
    if towards_viewer {
        sketch.dot(e, 5.0, color);
    } else {
        let d = 7.0;
        let stroke = Stroke::new(color, style::LINE_REGULAR);
        sketch.line(e + Vec2::new(-d, -d), e + Vec2::new(d, d), stroke.clone());
        sketch.line(e + Vec2::new(-d, d), e + Vec2::new(d, -d), stroke);
    }
}

/// Draws the two rays through the top and bottom edges of the image (middle column),
/// the frustum's outline in a side view, from `t.0` to `t.1`, recording them.
pub(crate) fn draw_frustum_edges(
    sketch: &mut Sketch,
    view: &SideView,
    camera: &Camera,
    t: (f64, f64),
    stroke: &Stroke,
) -> Vec<DrawnRay> {
    let fv = FigureView::Side(*view);
    let x = f64::from(camera.width()) / 2.0;
    let h = f64::from(camera.height());
    [0.0, h]
        .into_iter()
        .filter_map(|y| {
            let image = DVec2::new(x, y);
            let ray = camera.generate_ray_through(image, DVec2::splat(0.5))?;
            let clipped = view.clip_ray(&ray, t)?;
            Some(sketch.camera_ray(
                &fv,
                CameraRay::through(camera, image, DVec2::splat(0.5), clipped),
                stroke.clone(),
                false,
            ))
        })
        .collect()
}
