//! The camera's marks in a side view: its lens and focus plane, the viewing rays traced
//! to what they hit, and an arrow toward an eye beyond the window.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, Projection};
use viewray_draw::{Color, Stroke};
use viewray_geometry::DRay;
use viewray_scene::Scene;

use super::labels::{Labels, beside, label_anchor, place_label};
use super::window::Plane;
use crate::sketch::{CameraRay, Sketch};
use crate::style;
use crate::view::{FigureView, SideView};

/// The aperture and focus distance of a camera with a lens.
pub(super) fn lens(camera: &Camera) -> Option<(f64, f64)> {
    match camera.projection() {
        Projection::ThinLens(p) => Some((p.aperture, p.focus)),
        Projection::Orthographic(o) => o.lens.map(|l| (l.aperture, l.focus)),
        _ => None,
    }
}

/// The angle (radians, counter-clockwise on the figure) of the world direction `d` from
/// the figure's up.
pub(super) fn tilt_on_figure(view: &SideView, d: DVec3) -> f32 {
    let p = view.plane_point(d);
    (-p.x).atan2(p.y) as f32
}

/// Draws the focus plane of a camera with a lens: a dashed segment across the frustum at
/// distance `focus` along `-w` (across **v** seen from the side, **u** from above);
/// returns its upper and lower ends on the figure, if it is in the view. A tilted lens's
/// plane of focus is drawn instead from its hinge line on, labelled, and returns `None`.
pub(super) fn draw_focus_plane(
    sketch: &mut Sketch,
    view: &SideView,
    camera: &Camera,
    (focus, plane): (f64, Plane),
) -> Option<(Vec2, Vec2)> {
    if let (Some(tilted), Some(focus_plane)) = (camera.tilted_focus(), camera.focus_plane()) {
        draw_tilted_focus_plane(
            sketch,
            view,
            camera,
            tilted.hinge_line.point,
            focus_plane.normal,
        );
        return None;
    }
    let frame = camera.frame();
    let centre = frame.e() - frame.w() * focus;
    let across = plane.across(frame);
    let extent = |viewport: DVec2| match plane {
        Plane::Side => viewport.y,
        Plane::Top => viewport.x,
    };
    let half = match camera.projection() {
        Projection::ThinLens(p) => extent(p.viewport) / 2.0 * focus / p.distance,
        _ => camera
            .projection()
            .viewport()
            .map_or(1.0, |v| extent(v) / 2.0),
    };
    // The segment across the frustum, a little longer, clipped to the view.
    let segment = DRay {
        origin: centre - across * half * 1.15,
        direction: across * half * 2.3,
    };
    let (t0, t1) = view.clip_ray(&segment, (0.0, 1.0))?;
    let (bottom, top) = (
        view.to_figure(segment.at(t0)),
        view.to_figure(segment.at(t1)),
    );
    sketch.line(
        top,
        bottom,
        Stroke::new(style::HIGHLIGHT, style::LINE_REGULAR).dashed(&style::DASH),
    );
    Some(if top.y < bottom.y {
        (top, bottom)
    } else {
        (bottom, top)
    })
}

/// Draws a tilted lens's plane of focus (unit normal `normal`) where it crosses the
/// view's plane, from the hinge line's point `hinge` ahead of the camera to the edge of
/// the view, with a dot at the hinge line; labelled.
fn draw_tilted_focus_plane(
    sketch: &mut Sketch,
    view: &SideView,
    camera: &Camera,
    hinge: DVec3,
    normal: DVec3,
) {
    let across = normal.cross(view.towards_viewer());
    let ahead = if across.dot(camera.frame().w()) > 0.0 {
        -across
    } else {
        across
    };
    let trace = DRay {
        origin: hinge,
        direction: ahead.normalize(),
    };
    let Some((t0, t1)) = view.clip_ray(&trace, (0.0, 1e6)) else {
        return;
    };
    let (near, far) = (view.to_figure(trace.at(t0)), view.to_figure(trace.at(t1)));
    sketch.line(
        near,
        far,
        Stroke::new(style::HIGHLIGHT, style::LINE_REGULAR).dashed(&style::DASH),
    );
    if t0 == 0.0 {
        sketch.dot(near, style::DOT_RADIUS * 0.7, style::HIGHLIGHT);
    }
    let middle = view.to_figure(trace.at(t0 + 0.6 * (t1 - t0)));
    place_label(
        sketch,
        "plane of focus (tilted lens)",
        &[
            beside(middle, 14.0, 14.0),
            beside(middle, -14.0, -14.0),
            beside(far, -12.0, 14.0),
            beside(near, 12.0, -12.0),
        ],
        style::HIGHLIGHT,
        style::SMALL_LABEL_SIZE,
    );
}

/// Draws the centre ray of `pixel` from its origin to the first thing it hits in the
/// scene (or to the edge of the view), recording it; marks the hit with a dot and
/// returns where it is drawn, if the ray hits something inside the view.
pub(super) fn draw_traced_ray(
    sketch: &mut Sketch,
    view: &SideView,
    scene: &Scene,
    camera: &Camera,
    (row, col): (u32, u32),
    stroke: &Stroke,
    dot: Color,
) -> Option<Vec2> {
    let ray: DRay = camera.generate_ray(row, col, CameraSample::CENTER)?;
    let hit = scene
        .world()
        .closest_hit(&ray.as_ray(), f32::MIN_POSITIVE..f32::INFINITY)
        .map(|hit| f64::from(hit.t));
    let (t0, t1) = view.clip_ray(&ray, (0.0, hit.unwrap_or(f64::INFINITY)))?;
    if !t1.is_finite() {
        return None;
    }
    let drawn = sketch.camera_ray(
        &FigureView::Side(*view),
        CameraRay {
            camera,
            pixel: (row, col),
            sample: CameraSample::CENTER,
            t: (t0, t1),
        },
        stroke.clone(),
        false,
    );
    let hit_inside = hit.is_some_and(|t| t <= t1);
    if hit_inside {
        sketch.dot(drawn.to_px, style::DOT_RADIUS, dot);
        Some(drawn.to_px)
    } else {
        None
    }
}

/// Draws an arrow at the edge of the view pointing at the eye `e`, which lies beyond it,
/// from `from` (the middle of the objects, or of the view when there are none), and asks
/// for its label: how far the eye is from `from`, in world units.
pub(super) fn draw_eye_beyond(
    sketch: &mut Sketch,
    labels: &mut Labels,
    view: &SideView,
    e: DVec3,
    from: Option<DVec3>,
) {
    let (min, max) = (view.bounds.min.as_dvec2(), view.bounds.max.as_dvec2());
    let view_centre = (min + max) / 2.0;
    let eye = view.plane_point(e);
    let (centre, distance) = match from {
        Some(from) => (view.plane_point(from).clamp(min, max), (e - from).length()),
        None => (view_centre, (eye - view_centre).length()),
    };
    let Some(towards) = (eye - centre).try_normalize() else {
        return;
    };
    // Where the line from the centre to the eye leaves the view.
    let room = (towards.signum() * (max - min) / 2.0 + view_centre - centre) / towards;
    let reach = DVec2::new(
        if towards.x == 0.0 {
            f64::INFINITY
        } else {
            room.x
        },
        if towards.y == 0.0 {
            f64::INFINITY
        } else {
            room.y
        },
    )
    .min_element();
    let to_canvas = |p: DVec2| view.mapping.to_canvas(p.as_vec2());
    let tip = to_canvas(centre + towards * reach * 0.96);
    let tail = to_canvas(centre + towards * reach * 0.72);
    sketch.arrow(tail, tip, Stroke::new(style::EYE, style::LINE_REGULAR));
    let text = format!("*e*, {:.0} away", distance);
    let along = (tip - tail).normalize_or_zero();
    let side = along.perp() * 18.0;
    labels.add(
        text,
        vec![
            (tail - along * 14.0, label_anchor(-along)),
            (tail + side, label_anchor(side)),
            (tail - side, label_anchor(-side)),
            (tip + side, label_anchor(side)),
            (tip - side, label_anchor(-side)),
        ],
        style::EYE,
        style::SMALL_LABEL_SIZE,
    );
}
