//! The side view of any scene's camera: the scene's objects, the eye and its frame, the
//! image plane seen edge-on, the frustum and a few viewing rays up to what they hit.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, Projection};
use viewray_draw::{Anchor, Baseline, Color, Item, Label, Rect, Stroke};
use viewray_geometry::{DRay, Object};
use viewray_scene::Scene;

use crate::Diagram;
use crate::pictures::srgb;
use crate::side::{draw_image_plane, draw_side_frame, viewport_edges};
use crate::sketch::{Sketch, number};
use crate::style;
use crate::view::{FigureView, SideView};

/// How many viewing rays of the middle column are drawn, spread over its rows.
const RAY_COUNT: u32 = 5;

/// Meshes with more triangles than this are drawn as the outline of their bounds.
const MAX_DRAWN_TRIANGLES: usize = 4000;

/// The canvases a side view is drawn on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SideViewCanvas {
    /// A slide, 1600 x 900, with a title: for `viewray diagram`.
    #[default]
    Slide,
    /// A panel beside a render, 1000 x 600, without a title: the same labels read
    /// larger when the panel is shown at half a screen's width (the live playground).
    Panel,
}

impl SideViewCanvas {
    /// The canvas size, where the drawing goes, where the caption's baseline starts,
    /// and whether there is a title.
    fn layout(self) -> ((u32, u32), Rect, Vec2, bool) {
        match self {
            SideViewCanvas::Slide => (
                (1600, 900),
                Rect::from_corners(Vec2::new(40.0, 100.0), Vec2::new(1560.0, 800.0)),
                Vec2::new(56.0, 858.0),
                true,
            ),
            SideViewCanvas::Panel => (
                (1000, 600),
                Rect::from_corners(Vec2::new(50.0, 50.0), Vec2::new(950.0, 490.0)),
                Vec2::new(24.0, 540.0),
                false,
            ),
        }
    }
}

/// The side view of `camera` looking at `scene` (slide, 1600 x 900): the vertical plane
/// through the camera's **v** and **w** seen from its right, so **u** points at the
/// viewer; world up (`+y`) is up, so a tilted camera looks tilted and a shifted one
/// level. It shows the scene's objects projected onto that plane (spheres as circles,
/// boxes and meshes as their outlines, planes seen edge-on as lines), the eye **e** with
/// **v** and **w**, the image plane edge-on, the frustum's top and bottom edges, and
/// the viewing rays of five pixels of the middle column, each drawn to the first thing
/// it hits, traced in the scene. `pixel` (row, col), when given, adds that pixel's ray,
/// highlighted.
pub(crate) fn camera_side_view(
    scene: &Scene,
    camera: &Camera,
    pixel: Option<(u32, u32)>,
    canvas: SideViewCanvas,
) -> Diagram {
    let ((width, height), drawing, caption_at, title) = canvas.layout();
    let mut sketch = Sketch::sized(width, height);
    if title {
        sketch.title("Side view of the camera");
    }
    // The caption: one line on a slide, two on a panel.
    let (parameters, more) = caption(camera);
    match canvas {
        SideViewCanvas::Slide => sketch.text_lines(
            caption_at,
            &[(
                &format!("{parameters};  {more}"),
                style::TEXT,
                style::SMALL_LABEL_SIZE,
            )],
        ),
        SideViewCanvas::Panel => sketch.text_lines(
            caption_at,
            &[
                (&parameters, style::TEXT, style::SMALL_LABEL_SIZE),
                (&more, style::TEXT, style::SMALL_LABEL_SIZE),
            ],
        ),
    };
    let (right, up) = side_plane(camera);
    let view = fit_view(scene, camera, right, up, drawing);
    let figure_view = FigureView::Side(view);

    draw_objects(&mut sketch, &view, scene);

    // The frustum's top and bottom edges, for the planar projections.
    let frame = *camera.frame();
    let extent = f64::from(view.bounds.width().max(view.bounds.height()));
    if camera.projection().viewport().is_some() {
        let x = f64::from(camera.width()) / 2.0;
        let stroke = Stroke::new(style::RAY, style::LINE_THIN).dashed(&style::DASH);
        for y in [0.0, f64::from(camera.height())] {
            let image = DVec2::new(x, y);
            if let Some(ray) = camera.generate_ray_through(image, DVec2::splat(0.5))
                && let Some(t) = view.clip_ray(&ray, (0.0, f64::INFINITY))
                && t.1.is_finite()
            {
                sketch.camera_ray_through(
                    &figure_view,
                    camera,
                    image,
                    DVec2::splat(0.5),
                    t,
                    stroke.clone(),
                    false,
                );
            }
        }
    }

    // The thin lens's focus plane and lens.
    let lens = match camera.projection() {
        Projection::ThinLens(p) => Some((p.aperture, p.focus)),
        Projection::Orthographic(o) => o.lens.map(|l| (l.aperture, l.focus)),
        _ => None,
    };
    if let Some((aperture, focus)) = lens {
        draw_focus_plane(&mut sketch, &view, camera, focus);
        let e = view.to_figure(frame.e);
        let half = view.length(aperture).max(2.0);
        sketch.push(Item::Ellipse {
            center: e,
            radii: Vec2::new((half * 0.18).max(3.0), half),
            rotation: -tilt_on_figure(&view, frame.v),
            fill: Some(style::IMAGE_PLANE_FILL),
            stroke: Some(Stroke::new(style::OBJECT, style::LINE_THIN)),
        });
    }

    // A few viewing rays of the middle column, each to what it hits.
    let col = camera.width() / 2;
    let height = camera.height();
    let rows: Vec<u32> = (0..RAY_COUNT)
        .map(|k| {
            let centre = (f64::from(k) + 0.5) / f64::from(RAY_COUNT) * f64::from(height);
            // Rows are whole pixels inside the image.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let row = centre.floor() as u32;
            row.min(height - 1)
        })
        .collect();
    let ray_stroke = Stroke::new(style::RAY, style::LINE_REGULAR);
    for &row in &rows {
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

    // The image plane, the frame at the eye, the eye; the plane's label where it
    // overlaps no other.
    let plane_ends = camera
        .projection()
        .viewport()
        .map(|_| draw_image_plane(&mut sketch, &view, camera, style::IMAGE_PLANE, 0.0));
    let axis_length = 0.09 * extent;
    draw_side_frame(&mut sketch, &view, &frame, axis_length, false);
    draw_frame_labels(&mut sketch, &view, &frame, axis_length);
    if let Some((top, bottom)) = plane_ends {
        let label = match camera.projection() {
            Projection::Perspective(p) => format!("image plane, $d$ = {}", number(p.distance)),
            Projection::ThinLens(p) => format!("image plane, $d$ = {}", number(p.distance)),
            _ => "image plane".to_owned(),
        };
        let (lower, upper) = if top.y > bottom.y {
            (top, bottom)
        } else {
            (bottom, top)
        };
        let mut candidates = vec![
            (
                lower + Vec2::new(12.0, 10.0),
                (Anchor::Start, Baseline::Top),
            ),
            (lower + Vec2::new(-12.0, 10.0), (Anchor::End, Baseline::Top)),
            (
                upper + Vec2::new(12.0, -10.0),
                (Anchor::Start, Baseline::Bottom),
            ),
            (
                upper + Vec2::new(-12.0, -10.0),
                (Anchor::End, Baseline::Bottom),
            ),
        ];
        // Farther out, around the plane's middle, if the eye's labels crowd it.
        let middle = (lower + upper) / 2.0;
        for distance in [70.0, 120.0, 170.0, 220.0] {
            candidates.extend([
                (
                    middle + Vec2::new(0.0, distance),
                    (Anchor::Middle, Baseline::Top),
                ),
                (
                    middle + Vec2::new(distance, 0.0),
                    (Anchor::Start, Baseline::Middle),
                ),
                (
                    middle + Vec2::new(0.0, -distance),
                    (Anchor::Middle, Baseline::Bottom),
                ),
                (
                    middle + Vec2::new(-distance, 0.0),
                    (Anchor::End, Baseline::Middle),
                ),
            ]);
        }
        place_label(
            &mut sketch,
            &label,
            &candidates,
            style::IMAGE_PLANE,
            style::SMALL_LABEL_SIZE,
        );
    }

    if let Some((pixel, hit)) = pixel_hit {
        let text = format!("$i$ = {}, $j$ = {}", pixel.0 + 1, pixel.1 + 1);
        let candidates = [
            (
                hit + Vec2::new(14.0, -14.0),
                (Anchor::Start, Baseline::Bottom),
            ),
            (
                hit + Vec2::new(-14.0, -14.0),
                (Anchor::End, Baseline::Bottom),
            ),
            (hit + Vec2::new(14.0, 14.0), (Anchor::Start, Baseline::Top)),
            (hit + Vec2::new(-14.0, 14.0), (Anchor::End, Baseline::Top)),
            (
                hit + Vec2::new(0.0, -50.0),
                (Anchor::Middle, Baseline::Bottom),
            ),
            (hit + Vec2::new(0.0, 50.0), (Anchor::Middle, Baseline::Top)),
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

/// Names e, v, w and u at the eye, each where it overlaps no other label: v and w past
/// their arrows' tips, u (out of the page) and e beside the eye.
fn draw_frame_labels(
    sketch: &mut Sketch,
    view: &SideView,
    frame: &viewray_camera::Frame,
    length: f64,
) {
    let e = view.to_figure(frame.e);
    let around = |at: Vec2, gap: f32| {
        [
            (at + Vec2::new(-gap, gap), (Anchor::End, Baseline::Top)),
            (at + Vec2::new(gap, gap), (Anchor::Start, Baseline::Top)),
            (at + Vec2::new(-gap, -gap), (Anchor::End, Baseline::Bottom)),
            (at + Vec2::new(gap, -gap), (Anchor::Start, Baseline::Bottom)),
            (
                at + Vec2::new(0.0, 1.6 * gap),
                (Anchor::Middle, Baseline::Top),
            ),
            (
                at + Vec2::new(0.0, -1.6 * gap),
                (Anchor::Middle, Baseline::Bottom),
            ),
            (
                at + Vec2::new(-1.6 * gap, 0.0),
                (Anchor::End, Baseline::Middle),
            ),
            (
                at + Vec2::new(1.6 * gap, 0.0),
                (Anchor::Start, Baseline::Middle),
            ),
        ]
    };
    for (axis, color, name) in [
        (frame.v, style::V_AXIS, "*v*"),
        (frame.w, style::W_AXIS, "*w*"),
    ] {
        let tip = view.to_figure(frame.e + axis * length);
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

/// The side view's axes `(right, up)`: the plane of the camera's **v** and **w** (which
/// holds the viewing rays of the image's middle column), seen from **u**'s side, with up
/// the world's `+y` projected onto it (**v** for a camera looking straight along `y`).
/// A camera that is not rolled has a horizontal **u**, so up is `+y` itself.
fn side_plane(camera: &Camera) -> (DVec3, DVec3) {
    let frame = camera.frame();
    let world_up = DVec3::Y - DVec3::Y.dot(frame.u) * frame.u;
    let up = if world_up.length() > 1e-6 {
        world_up.normalize()
    } else {
        frame.v
    };
    (up.cross(frame.u), up)
}

/// The angle (radians, counter-clockwise on the figure) of the world direction `d` from
/// the figure's up.
fn tilt_on_figure(view: &SideView, d: DVec3) -> f32 {
    let p = view.plane_point(d);
    (-p.x).atan2(p.y) as f32
}

/// A side view fitted to the eye, the image plane, the focus point and the bounded
/// objects of the scene, with a margin.
fn fit_view(scene: &Scene, camera: &Camera, right: DVec3, up: DVec3, drawing: Rect) -> SideView {
    let frame = camera.frame();
    let mut points = vec![frame.e];
    if camera.projection().viewport().is_some() {
        let (top, bottom) = viewport_edges(camera);
        points.extend([top, bottom]);
    }
    if let Projection::ThinLens(p) = camera.projection() {
        points.push(frame.e - frame.w * p.focus);
    }
    let bounds = scene.world().bounds();
    if bounds.min.is_finite() && bounds.max.is_finite() && bounds.min.cmple(bounds.max).all() {
        for corner in 0..8 {
            let pick =
                |bit: u32, lo: f32, hi: f32| f64::from(if corner & bit == 0 { lo } else { hi });
            points.push(DVec3::new(
                pick(1, bounds.min.x, bounds.max.x),
                pick(2, bounds.min.y, bounds.max.y),
                pick(4, bounds.min.z, bounds.max.z),
            ));
        }
    } else {
        // Nothing bounded: show some way in front of the camera.
        points.push(frame.e - frame.w * 4.0);
    }
    let plane: Vec<DVec2> = points
        .iter()
        .map(|&p| DVec2::new(p.dot(right), p.dot(up)))
        .collect();
    let min = plane.iter().fold(DVec2::INFINITY, |a, &b| a.min(b));
    let max = plane.iter().fold(DVec2::NEG_INFINITY, |a, &b| a.max(b));
    let size = (max - min).max_element().max(1e-3);
    let margin = 0.12 * size;
    SideView::fit_plane(
        right,
        up,
        (min.x - margin, max.x + margin),
        (min.y - margin, max.y + margin),
        drawing,
    )
}

/// The colour of object `object` of the scene: its material's (the first face's for a
/// mesh with per-face materials), as the renderer stores it.
fn object_color(scene: &Scene, object: usize) -> Color {
    // Object indices come from the scene's own world, which holds fewer than 2^32.
    #[allow(clippy::cast_possible_truncation)]
    let material = scene.material_of(object as u32, 0);
    srgb(material.color.as_dvec3())
}

/// Draws the scene's objects projected onto the side view, farthest from the viewer
/// first.
fn draw_objects(sketch: &mut Sketch, view: &SideView, scene: &Scene) {
    let outline = Stroke::new(style::OBJECT, style::LINE_THIN);
    let towards_viewer = view.towards_viewer();
    let objects = scene.world().objects();
    // Planes first (they are the ground and walls), then the rest by depth.
    for (index, object) in objects.iter().enumerate() {
        if let Object::Plane(plane) = object {
            draw_plane(
                sketch,
                view,
                plane.point.as_dvec3(),
                plane.normal.as_dvec3(),
                object_color(scene, index),
            );
        }
    }
    let mut order: Vec<(f64, usize)> = objects
        .iter()
        .enumerate()
        .filter_map(|(index, object)| {
            let bounds = object.bounds()?;
            Some((
                ((bounds.min + bounds.max) / 2.0)
                    .as_dvec3()
                    .dot(towards_viewer),
                index,
            ))
        })
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, index) in order {
        let fill = object_color(scene, index).with_alpha(0.85);
        let to_figure = |p: glam::Vec3| view.to_figure(p.as_dvec3());
        match &objects[index] {
            Object::Sphere(sphere) => sketch.push(Item::Ellipse {
                center: to_figure(sphere.center),
                radii: Vec2::splat(view.length(f64::from(sphere.radius))),
                rotation: 0.0,
                fill: Some(fill),
                stroke: Some(outline.clone()),
            }),
            Object::Triangle(triangle) => sketch.push(Item::Polygon {
                points: [triangle.a, triangle.b, triangle.c].map(to_figure).to_vec(),
                fill,
                stroke: Some(outline.clone()),
            }),
            Object::Box(aabb) => sketch.push(Item::Polygon {
                points: convex_hull(&box_corners(aabb.min, aabb.max).map(to_figure)),
                fill,
                stroke: Some(outline.clone()),
            }),
            Object::Instance(instance) => {
                let data = instance.mesh().data();
                let transform = instance.world_from_object();
                if data.triangles.len() > MAX_DRAWN_TRIANGLES {
                    let bounds = instance.bounds();
                    sketch.push(Item::Polygon {
                        points: convex_hull(&box_corners(bounds.min, bounds.max).map(to_figure)),
                        fill,
                        stroke: Some(outline.clone()),
                    });
                } else {
                    for triangle in &data.triangles {
                        let points = triangle.map(|i| {
                            to_figure(transform.transform_point3(data.positions[i as usize]))
                        });
                        sketch.push(Item::Polygon {
                            points: points.to_vec(),
                            fill,
                            stroke: Some(Stroke::new(fill.with_alpha(1.0), 1.0)),
                        });
                    }
                }
            }
            Object::Plane(_) => {}
        }
    }
}

/// The eight corners of the box from `min` to `max`.
fn box_corners(min: glam::Vec3, max: glam::Vec3) -> [glam::Vec3; 8] {
    std::array::from_fn(|corner| {
        glam::Vec3::new(
            if corner & 1 == 0 { min.x } else { max.x },
            if corner & 2 == 0 { min.y } else { max.y },
            if corner & 4 == 0 { min.z } else { max.z },
        )
    })
}

/// The convex hull of `points` (Andrew's monotone chain), counter-clockwise.
fn convex_hull(points: &[Vec2]) -> Vec<Vec2> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<Vec2> = Vec::with_capacity(sorted.len() * 2);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Vec2>> = if pass == 0 {
            Box::new(sorted.iter())
        } else {
            Box::new(sorted.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

/// Draws an infinite plane seen edge-on: the line where it cuts the view, and a light
/// fill on its back side. A plane not perpendicular to the figure covers all of it and
/// is not drawn.
fn draw_plane(sketch: &mut Sketch, view: &SideView, point: DVec3, normal: DVec3, color: Color) {
    let n = view.plane_point(normal);
    if normal.dot(view.towards_viewer()).abs() > 1e-9 * normal.length() || n.length() == 0.0 {
        return;
    }
    let c = point.dot(normal);
    // The view's corners, and the part of the rectangle behind the plane (n . p <= c).
    let (lo, hi) = (view.bounds.min.as_dvec2(), view.bounds.max.as_dvec2());
    let corners = [
        DVec2::new(lo.x, lo.y),
        DVec2::new(hi.x, lo.y),
        DVec2::new(hi.x, hi.y),
        DVec2::new(lo.x, hi.y),
    ];
    let side = |p: DVec2| n.dot(p) - c;
    let mut behind = Vec::new();
    let mut line = Vec::new();
    for k in 0..4 {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        let (sa, sb) = (side(a), side(b));
        if sa <= 0.0 {
            behind.push(a);
        }
        if (sa < 0.0) != (sb < 0.0) {
            let crossing = a + (b - a) * (sa / (sa - sb));
            behind.push(crossing);
            line.push(crossing);
        }
    }
    let to_canvas = |p: DVec2| view.mapping.to_canvas(p.as_vec2());
    if behind.len() >= 3 {
        sketch.push(Item::Polygon {
            points: behind.into_iter().map(to_canvas).collect(),
            fill: color.with_alpha(0.35),
            stroke: None,
        });
    }
    if let [a, b] = line[..] {
        sketch.line(
            to_canvas(a),
            to_canvas(b),
            Stroke::new(style::OBJECT, style::LINE_REGULAR),
        );
    }
}

/// Draws the focus plane of a camera with a lens: a dashed segment across the frustum at
/// distance `focus` along `-w`, labelled.
fn draw_focus_plane(sketch: &mut Sketch, view: &SideView, camera: &Camera, focus: f64) {
    let frame = camera.frame();
    let centre = frame.e - frame.w * focus;
    let half = match camera.projection() {
        Projection::ThinLens(p) => p.viewport.y / 2.0 * focus / p.distance,
        _ => camera.projection().viewport().map_or(1.0, |v| v.y / 2.0),
    };
    // The segment across the frustum, a little longer, clipped to the view.
    let across = DRay {
        origin: centre - frame.v * half * 1.15,
        direction: frame.v * half * 2.3,
    };
    let Some((t0, t1)) = view.clip_ray(&across, (0.0, 1.0)) else {
        return;
    };
    let (bottom, top) = (view.to_figure(across.at(t0)), view.to_figure(across.at(t1)));
    sketch.line(
        top,
        bottom,
        Stroke::new(style::HIGHLIGHT, style::LINE_REGULAR).dashed(&style::DASH),
    );
    let (upper, lower) = if top.y < bottom.y {
        (top, bottom)
    } else {
        (bottom, top)
    };
    place_label(
        sketch,
        &format!("focus plane, $f$ = {}", number(focus)),
        &[
            (
                upper + Vec2::new(0.0, -10.0),
                (Anchor::Middle, Baseline::Bottom),
            ),
            (
                lower + Vec2::new(0.0, 10.0),
                (Anchor::Middle, Baseline::Top),
            ),
            (upper + Vec2::new(12.0, 0.0), (Anchor::Start, Baseline::Top)),
            (
                lower + Vec2::new(12.0, 0.0),
                (Anchor::Start, Baseline::Bottom),
            ),
            (upper + Vec2::new(-12.0, 0.0), (Anchor::End, Baseline::Top)),
        ],
        style::HIGHLIGHT,
        style::SMALL_LABEL_SIZE,
    );
}

/// Draws the centre ray of `pixel` from its origin to the first thing it hits in the
/// scene (or to the edge of the view), recording it; marks the hit with a dot and
/// returns where it is drawn, if the ray hits something inside the view.
fn draw_traced_ray(
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
        camera,
        (row, col),
        CameraSample::CENTER,
        (t0, t1),
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

/// Adds the label `text` at the first of `candidates` where it stays on the canvas and
/// overlaps no label already there (at the first candidate if none is free).
fn place_label(
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

/// One line naming the projection and its parameters in the lecture's notation.
fn caption(camera: &Camera) -> (String, String) {
    let size = format!("image {} × {}", camera.width(), camera.height());
    let viewport = |v: DVec2| format!("$vw$ × $vh$ = {} × {}", number(v.x), number(v.y));
    let shift = |s: DVec2| {
        if s == DVec2::ZERO {
            String::new()
        } else {
            format!(",  shift ({}, {})", number(s.x), number(s.y))
        }
    };
    let lens = |aperture: f64, focus: f64| {
        format!(
            "aperture $r$ = {},  focus $f$ = {};  ",
            number(aperture),
            number(focus)
        )
    };
    let (parameters, more) = match camera.projection() {
        Projection::Perspective(p) => (
            format!(
                "perspective:  $d$ = {},  {}{}",
                number(p.distance),
                viewport(p.viewport),
                shift(p.shift)
            ),
            String::new(),
        ),
        Projection::ThinLens(p) => (
            format!(
                "thin lens:  $d$ = {},  {}{}",
                number(p.distance),
                viewport(p.viewport),
                shift(p.shift)
            ),
            lens(p.aperture, p.focus),
        ),
        Projection::Orthographic(o) => (
            format!("orthographic:  {}", viewport(o.viewport)),
            o.lens.map_or(String::new(), |l| lens(l.aperture, l.focus)),
        ),
        Projection::Oblique(o) => (
            format!(
                "oblique:  {},  $L$ = {},  $φ$ = {}°",
                viewport(o.viewport),
                number(o.ratio),
                number(o.angle.to_degrees())
            ),
            String::new(),
        ),
        Projection::Equirectangular => ("equirectangular: 360° × 180°".to_owned(), String::new()),
        Projection::Fisheye(f) => (
            format!("fisheye: field of view {}°", number(f.fov.to_degrees())),
            String::new(),
        ),
    };
    (parameters, format!("{more}{size}"))
}
