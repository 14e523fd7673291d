//! The side view of any camera over a scene: the scene's objects, the eye and its frame,
//! the image plane seen edge-on, the frustum and a few viewing rays up to what they hit,
//! in a window on the world that is fitted to one camera or fixed for an animation.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, Projection};
use viewray_draw::{Anchor, Baseline, Color, Item, Label, Mapping, Rect, Stroke};
use viewray_geometry::{Aabb, DRay, Object};
use viewray_output::number;
use viewray_scene::Scene;

use crate::Diagram;
use crate::pictures::srgb;
use crate::side::{draw_image_plane, draw_side_frame, viewport_edges};
use crate::sketch::{LINE_SPACING, Sketch};
use crate::style;
use crate::view::{FigureView, SideView};

/// How many viewing rays of the middle column are drawn, spread over its rows.
const RAY_COUNT: u32 = 5;

/// Meshes with more triangles than this are drawn as the outline of their bounds.
const MAX_DRAWN_TRIANGLES: usize = 4000;

/// How far beyond the objects a camera's eye, image plane or focus point may lie and
/// still be fitted into the window, in sizes of the objects' bounds. An eye farther out
/// (a camera receding to infinity) is drawn as an arrow at the window's edge.
const REACH: f64 = 3.0;

/// The margin around what a window is fitted to, as a fraction of its larger side.
const MARGIN: f64 = 0.1;

/// How far past an eye along **v** and **w** a window reaches, as a fraction of what it
/// is fitted to, so that the arrows and their names stay inside.
const AXIS_ROOM: f64 = 0.1;

/// The part of the world a side view shows: a vertical plane (world up drawn up) and a
/// rectangle of it. [`SideWindow::fit`] fits it to one camera (`viewray diagram`, the
/// live playground) or to every camera of an animation, so that from frame to frame only
/// the camera moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SideWindow {
    /// The world direction drawn to the right, a unit vector.
    pub(crate) right: DVec3,
    /// The world direction drawn up, a unit vector perpendicular to `right`.
    pub(crate) up: DVec3,
    /// The rectangle's lower left corner in plane coordinates `(p . right, p . up)`.
    pub(crate) min: DVec2,
    /// Its upper right corner.
    pub(crate) max: DVec2,
}

impl SideWindow {
    /// The window on `scene` for `cameras` (one camera, or every frame's): the plane of
    /// the first camera's **v** and **w**, seen from **u**'s side with world up (`+y`)
    /// up, and the rectangle of it holding the objects' bounds, the eyes, image planes and
    /// focus points of the cameras near them (within three times the objects' size), and
    /// the nearest stretch of each plane seen edge-on (the ground), with a margin.
    pub fn fit(scene: &Scene, cameras: &[Camera]) -> SideWindow {
        let (right, up) = cameras.first().map_or((DVec3::NEG_Z, DVec3::Y), side_plane);
        let on_plane = |p: DVec3| DVec2::new(p.dot(right), p.dot(up));
        let objects = scene.world().objects();
        let mut bounds = Bounds::default();
        for object in objects {
            if let Some(aabb) = object.bounds() {
                for p in box_corners(aabb) {
                    bounds.add(on_plane(p.as_dvec3()));
                }
            }
        }
        // The camera nearest the objects always, with some way in front of it when there
        // are none; then the others near both.
        let centre = bounds
            .range()
            .map_or(DVec2::ZERO, |(min, max)| (min + max) / 2.0);
        let mut by_distance: Vec<&Camera> = cameras.iter().collect();
        by_distance.sort_by(|a, b| {
            let distance = |c: &Camera| (on_plane(c.frame().e) - centre).length();
            distance(a).total_cmp(&distance(b))
        });
        if let Some(nearest) = by_distance.first() {
            if bounds.range().is_none() {
                let frame = nearest.frame();
                bounds.add(on_plane(frame.e - frame.w * 4.0));
            }
            camera_points(nearest).for_each(|p| bounds.add(on_plane(p)));
        }
        let Some((min, max)) = bounds.range() else {
            return SideWindow::around(right, up, DVec2::new(-1.0, 0.0), DVec2::new(1.0, 1.0));
        };
        let size = (max - min).max_element().max(1e-3);
        let near = Bounds {
            min: min - REACH * size,
            max: max + REACH * size,
        };
        for camera in by_distance.iter().skip(1) {
            camera_points(camera)
                .map(on_plane)
                .filter(|&p| near.holds(p))
                .for_each(|p| bounds.add(p));
        }
        // The ground and walls seen edge-on: their nearest stretch.
        let towards_viewer = right.cross(up);
        let centre = (bounds.min + bounds.max) / 2.0;
        for object in objects {
            if let Object::Plane(plane) = object {
                let normal = plane.normal.as_dvec3();
                let n = on_plane(normal);
                if normal.dot(towards_viewer).abs() > 1e-9 * normal.length()
                    || n.length_squared() == 0.0
                {
                    continue;
                }
                let c = plane.point.as_dvec3().dot(normal);
                let nearest = centre - n * ((n.dot(centre) - c) / n.length_squared());
                if near.holds(nearest) {
                    bounds.add(nearest);
                }
            }
        }
        // Room for v and w and their names at every eye shown.
        let size = (bounds.max - bounds.min).max_element().max(1e-3);
        let shown = bounds;
        for camera in cameras {
            let frame = camera.frame();
            if shown.holds(on_plane(frame.e)) {
                for axis in [frame.v, frame.w] {
                    bounds.add(on_plane(frame.e + axis * AXIS_ROOM * size));
                }
            }
        }
        SideWindow::around(right, up, bounds.min, bounds.max)
    }

    /// The window from `min` to `max` with a margin.
    fn around(right: DVec3, up: DVec3, min: DVec2, max: DVec2) -> SideWindow {
        let margin = MARGIN * (max - min).max_element().max(1e-3);
        SideWindow {
            right,
            up,
            min: min - margin,
            max: max + margin,
        }
    }

    /// The side view showing this window inside `drawing` (figure pixels), centred at
    /// one scale; what it shows and clips to is all of `drawing`, which may hold more of
    /// the plane than the window on two sides.
    fn view(&self, drawing: Rect) -> SideView {
        let window = Rect::from_corners(self.min.as_vec2(), self.max.as_vec2());
        let mapping = Mapping::fit(window, drawing).expect("a window and a drawing with area");
        SideView {
            mapping,
            bounds: Rect::from_corners(
                mapping.to_world(drawing.min),
                mapping.to_world(drawing.max),
            ),
            right: self.right,
            up: self.up,
        }
    }
}

/// A growing rectangle of plane points.
#[derive(Clone, Copy)]
struct Bounds {
    min: DVec2,
    max: DVec2,
}

impl Default for Bounds {
    fn default() -> Bounds {
        Bounds {
            min: DVec2::INFINITY,
            max: DVec2::NEG_INFINITY,
        }
    }
}

impl Bounds {
    fn add(&mut self, p: DVec2) {
        if p.is_finite() {
            self.min = self.min.min(p);
            self.max = self.max.max(p);
        }
    }

    fn holds(&self, p: DVec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// The corners, once a point has been added.
    fn range(&self) -> Option<(DVec2, DVec2)> {
        self.min
            .cmple(self.max)
            .all()
            .then_some((self.min, self.max))
    }
}

/// The canvases a side view is drawn on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SideViewCanvas {
    /// A slide, 1600 x 900, with a title: for `viewray diagram`.
    #[default]
    Slide,
    /// A panel beside a render, 1000 x 600, without a title: the same labels read
    /// larger when the panel is shown at half a screen's width (the live playground).
    Panel,
    /// A 16:9 panel beside an animation's picture, 1280 x 720, without a title, the
    /// drawing filling it: painted at the picture's height
    /// ([`render_scaled`](viewray_draw::raster::render_scaled)), every line and label
    /// shrinks with it.
    Beside,
}

/// Where a canvas puts things.
struct Layout {
    /// Where the drawing goes (all of the canvas but the title and caption, if apart).
    drawing: Rect,
    /// Where the caption's first baseline starts.
    caption_at: Vec2,
    /// Whether there is a title.
    title: bool,
}

impl SideViewCanvas {
    /// The canvas size in pixels.
    pub fn size(self) -> (u32, u32) {
        match self {
            SideViewCanvas::Slide => style::SLIDE,
            SideViewCanvas::Panel => (1000, 600),
            SideViewCanvas::Beside => (1280, 720),
        }
    }

    fn layout(self) -> Layout {
        match self {
            SideViewCanvas::Slide => Layout {
                drawing: Rect::from_corners(Vec2::new(40.0, 100.0), Vec2::new(1560.0, 800.0)),
                caption_at: Vec2::new(56.0, 858.0),
                title: true,
            },
            SideViewCanvas::Panel => Layout {
                drawing: Rect::from_corners(Vec2::new(50.0, 50.0), Vec2::new(950.0, 490.0)),
                caption_at: Vec2::new(24.0, 540.0),
                title: false,
            },
            SideViewCanvas::Beside => Layout {
                drawing: Rect::from_xywh(0.0, 0.0, 1280.0, 720.0),
                caption_at: Vec2::new(20.0, 700.0),
                title: false,
            },
        }
    }
}

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
    let eye_in_view = view.bounds.contains(view.plane_point(frame.e).as_vec2());
    if let Some((aperture, focus)) = lens(camera) {
        draw_focus_plane(&mut sketch, &view, camera, focus);
        if eye_in_view {
            let half = view.length(aperture).max(2.0);
            sketch.push(Item::Ellipse {
                center: view.to_figure(frame.e),
                radii: Vec2::new((half * 0.18).max(3.0), half),
                rotation: -tilt_on_figure(&view, frame.v),
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
        draw_eye_beyond(&mut sketch, &view, frame.e);
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

/// The caption naming the projection and its parameters: one line on a slide, two on a
/// panel; beside an animation's picture, over the drawing on a light backing, the lens
/// on a line of its own and no image size (the picture shows it).
fn draw_caption(sketch: &mut Sketch, camera: &Camera, canvas: SideViewCanvas, at: Vec2) {
    let (parameters, lens, size) = caption(camera);
    let more = if lens.is_empty() {
        size
    } else {
        format!("{lens};  {size}")
    };
    match canvas {
        SideViewCanvas::Slide => sketch.text_lines(
            at,
            &[(
                &format!("{parameters};  {more}"),
                style::TEXT,
                style::SMALL_LABEL_SIZE,
            )],
        ),
        SideViewCanvas::Panel => sketch.text_lines(
            at,
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

/// Names the image plane drawn from `top` to `bottom` (figure pixels) beside one of its
/// ends, or farther out around its middle where the eye's labels crowd it.
fn draw_image_plane_label(sketch: &mut Sketch, camera: &Camera, top: Vec2, bottom: Vec2) {
    let label = match camera.projection() {
        Projection::Perspective(p) => format!(
            "image plane, $d$ = {}",
            number::label_significant(p.distance)
        ),
        Projection::ThinLens(p) => format!(
            "image plane, $d$ = {}",
            number::label_significant(p.distance)
        ),
        _ => "image plane".to_owned(),
    };
    let (lower, upper) = if top.y > bottom.y {
        (top, bottom)
    } else {
        (bottom, top)
    };
    let mut candidates = vec![
        beside(lower, 12.0, 10.0),
        beside(lower, -12.0, 10.0),
        beside(upper, 12.0, -10.0),
        beside(upper, -12.0, -10.0),
    ];
    let middle = (lower + upper) / 2.0;
    for distance in [70.0, 120.0, 170.0, 220.0] {
        candidates.extend([
            beside(middle, 0.0, distance),
            beside(middle, distance, 0.0),
            beside(middle, 0.0, -distance),
            beside(middle, -distance, 0.0),
        ]);
    }
    place_label(
        sketch,
        &label,
        &candidates,
        style::IMAGE_PLANE,
        style::SMALL_LABEL_SIZE,
    );
}

/// Draws an arrow at the edge of the view pointing at the eye `e`, which lies beyond it,
/// labelled with how far away the eye is (world units from the view's centre).
fn draw_eye_beyond(sketch: &mut Sketch, view: &SideView, e: DVec3) {
    let (min, max) = (view.bounds.min.as_dvec2(), view.bounds.max.as_dvec2());
    let centre = (min + max) / 2.0;
    let eye = view.plane_point(e);
    let Some(towards) = (eye - centre).try_normalize() else {
        return;
    };
    // Where the line from the centre to the eye leaves the view.
    let reach = ((max - min) / 2.0 / towards.abs()).min_element();
    let to_canvas = |p: DVec2| view.mapping.to_canvas(p.as_vec2());
    let tip = to_canvas(centre + towards * reach * 0.96);
    let tail = to_canvas(centre + towards * reach * 0.72);
    sketch.arrow(tail, tip, Stroke::new(style::EYE, style::LINE_REGULAR));
    let text = format!("*e*, {:.0} away", (eye - centre).length());
    let along = (tip - tail).normalize_or_zero();
    let side = along.perp() * 18.0;
    place_label(
        sketch,
        &text,
        &[
            (tail - along * 14.0, label_anchor(-along)),
            (tail + side, label_anchor(side)),
            (tail - side, label_anchor(-side)),
        ],
        style::EYE,
        style::SMALL_LABEL_SIZE,
    );
}

/// A place for a label `(dx, dy)` pixels from the point `at` it names, anchored so that
/// it grows away from it.
fn beside(at: Vec2, dx: f32, dy: f32) -> (Vec2, (Anchor, Baseline)) {
    let d = Vec2::new(dx, dy);
    (at + d, label_anchor(d))
}

/// The anchor of a label placed in direction `d` from what it names, so that it grows
/// away from it.
fn label_anchor(d: Vec2) -> (Anchor, Baseline) {
    let anchor = if d.x > 0.5 * d.length() {
        Anchor::Start
    } else if d.x < -0.5 * d.length() {
        Anchor::End
    } else {
        Anchor::Middle
    };
    let baseline = if d.y > 0.5 * d.length() {
        Baseline::Top
    } else if d.y < -0.5 * d.length() {
        Baseline::Bottom
    } else {
        Baseline::Middle
    };
    (anchor, baseline)
}

/// The points of `camera` a window shows: the eye, the image plane's top and bottom
/// edges, the focus point.
fn camera_points(camera: &Camera) -> impl Iterator<Item = DVec3> {
    let frame = camera.frame();
    let edges = camera
        .projection()
        .viewport()
        .map(|_| viewport_edges(camera));
    let focus = lens(camera).map(|(_, focus)| frame.e - frame.w * focus);
    std::iter::once(frame.e)
        .chain(edges.into_iter().flat_map(|(top, bottom)| [top, bottom]))
        .chain(focus)
}

/// The aperture and focus distance of a camera with a lens.
fn lens(camera: &Camera) -> Option<(f64, f64)> {
    match camera.projection() {
        Projection::ThinLens(p) => Some((p.aperture, p.focus)),
        Projection::Orthographic(o) => o.lens.map(|l| (l.aperture, l.focus)),
        _ => None,
    }
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
            beside(at, -gap, gap),
            beside(at, gap, gap),
            beside(at, -gap, -gap),
            beside(at, gap, -gap),
            beside(at, 0.0, 1.6 * gap),
            beside(at, 0.0, -1.6 * gap),
            beside(at, -1.6 * gap, 0.0),
            beside(at, 1.6 * gap, 0.0),
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
                points: convex_hull(&box_corners(*aabb).map(to_figure)),
                fill,
                stroke: Some(outline.clone()),
            }),
            Object::Instance(instance) => {
                let data = instance.mesh().data();
                let transform = instance.world_from_object();
                if data.triangles.len() > MAX_DRAWN_TRIANGLES {
                    sketch.push(Item::Polygon {
                        points: convex_hull(&box_corners(instance.bounds()).map(to_figure)),
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

/// The eight corners of `aabb`.
fn box_corners(aabb: Aabb) -> [glam::Vec3; 8] {
    let (min, max) = (aabb.min, aabb.max);
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
        &format!("focus plane, $f$ = {}", number::label_significant(focus)),
        &[
            beside(upper, 0.0, -10.0),
            beside(lower, 0.0, 10.0),
            beside(upper, 12.0, 12.0),
            beside(lower, 12.0, -12.0),
            beside(upper, -12.0, 12.0),
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
        Projection::ThinLens(p) => (
            format!(
                "thin lens:  $d$ = {},  {}{}",
                number::label_significant(p.distance),
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
