//! The part of the world a side view shows: a plane through the camera (its **v** and
//! **w**, seen from the side, or its **u** and **w**, seen from above) and a rectangle of
//! it, fitted to one camera or to every camera of an animation.

use glam::{DVec2, DVec3};
use viewray_camera::Camera;
use viewray_draw::{Color, Mapping, Rect};
use viewray_geometry::Object;
use viewray_scene::Scene;

use super::camera::lens;
use crate::side::viewport_points;
use crate::style;
use crate::view::SideView;

/// How far beyond the objects a camera's eye, image plane or focus point may lie and
/// still be fitted into the window, in sizes of the objects' bounds. An eye farther out
/// (a camera receding to infinity) is drawn as an arrow at the window's edge.
const REACH: f64 = 3.0;

/// The margin around what a window is fitted to, as a fraction of its larger side.
const MARGIN: f64 = 0.1;

/// How far past an eye along **v** and **w** a window reaches, as a fraction of what it
/// is fitted to, so that the arrows and their names stay inside.
const AXIS_ROOM: f64 = 0.1;

/// The part of the world a side view shows: a plane and a rectangle of it.
/// [`SideWindow::fit`] fits the camera's side view (the plane of its **v** and **w**,
/// world up drawn up) to one camera (`viewray diagram`, the live playground) or to every
/// camera of an animation, so that from frame to frame only the camera moves;
/// [`SideWindow::fit_top`] its top view (the plane of **u** and **w**, seen from above,
/// **u** drawn to the right and the view up the page).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SideWindow {
    /// Which plane of the camera it shows.
    pub(crate) plane: Plane,
    /// The world direction drawn to the right, a unit vector.
    pub(crate) right: DVec3,
    /// The world direction drawn up, a unit vector perpendicular to `right`.
    pub(crate) up: DVec3,
    /// The rectangle's lower left corner in plane coordinates `(p . right, p . up)`.
    pub(crate) min: DVec2,
    /// Its upper right corner.
    pub(crate) max: DVec2,
}

/// The plane of a camera a window shows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Plane {
    /// The plane of **v** and **w**, seen from **u**'s side: the rays of the image's
    /// middle column, spread over **v**.
    Side,
    /// The plane of **u** and **w**, seen from **v**'s side (from above, for a level
    /// camera): the rays of the image's middle row, spread over **u**.
    Top,
}

impl SideWindow {
    /// The window on `scene` for `cameras` (one camera, or every frame's): the plane of
    /// the first camera's **v** and **w**, seen from **u**'s side with world up (`+y`)
    /// up, and the rectangle of it holding the objects' bounds, the eyes, image planes and
    /// focus points of the cameras near them (within three times the objects' size), and
    /// the nearest stretch of each plane seen edge-on (the ground), with a margin. A
    /// camera farther out (a parallel preset's eye, ten sizes away) is left out, so the
    /// objects stay large; its eye is drawn as an arrow at the window's edge.
    pub fn fit(scene: &Scene, cameras: &[Camera]) -> SideWindow {
        SideWindow::fit_plane(scene, cameras, Plane::Side)
    }

    /// The top view's window on `scene` for `cameras`: as [`SideWindow::fit`], in the
    /// plane of the first camera's **u** and **w** seen from **v**'s side (from above,
    /// for a camera that is not rolled), **u** drawn to the right and `-w` (the view) up
    /// the page, so that left and right are the picture's.
    pub fn fit_top(scene: &Scene, cameras: &[Camera]) -> SideWindow {
        SideWindow::fit_plane(scene, cameras, Plane::Top)
    }

    fn fit_plane(scene: &Scene, cameras: &[Camera], plane: Plane) -> SideWindow {
        let (right, up) = cameras
            .first()
            .map_or((DVec3::NEG_Z, DVec3::Y), |camera| match plane {
                Plane::Side => side_plane(camera),
                Plane::Top => top_plane(camera),
            });
        let on_plane = |p: DVec3| DVec2::new(p.dot(right), p.dot(up));
        let objects = scene.world().objects();
        let mut bounds = Bounds::default();
        for object in objects {
            if let Some(aabb) = object.bounds() {
                for p in aabb.corners() {
                    bounds.add(on_plane(p.as_dvec3()));
                }
            }
        }
        // The cameras near the objects (within three times their size), nearest first;
        // with no objects, the nearest camera and some way in front of it.
        let centre = bounds
            .range()
            .map_or(DVec2::ZERO, |(min, max)| (min + max) / 2.0);
        let mut by_distance: Vec<&Camera> = cameras.iter().collect();
        by_distance.sort_by(|a, b| {
            let distance = |c: &Camera| (on_plane(c.frame().e()) - centre).length();
            distance(a).total_cmp(&distance(b))
        });
        if let Some(nearest) = by_distance.first() {
            let frame = nearest.frame();
            let within_reach = match bounds.range() {
                None => {
                    bounds.add(on_plane(frame.e() - frame.w() * 4.0));
                    true
                }
                Some((min, max)) => Bounds::reach(min, max).holds(on_plane(frame.e())),
            };
            if within_reach {
                camera_points(nearest, plane).for_each(|p| bounds.add(on_plane(p)));
            } else if let Some(centre) = objects_centre(scene) {
                // A far camera: the stretch of its frustum that passes the objects.
                let near = bounds.range().map(|(min, max)| Bounds::reach(min, max));
                frustum_near(nearest, plane, centre)
                    .map(on_plane)
                    .filter(|&p| near.is_some_and(|near| near.holds(p)))
                    .for_each(|p| bounds.add(p));
            }
        }
        let Some((min, max)) = bounds.range() else {
            return SideWindow::around(
                plane,
                right,
                up,
                DVec2::new(-1.0, 0.0),
                DVec2::new(1.0, 1.0),
            );
        };
        let near = Bounds::reach(min, max);
        for camera in &by_distance {
            camera_points(camera, plane)
                .map(on_plane)
                .filter(|&p| near.holds(p))
                .for_each(|p| bounds.add(p));
        }
        // The ground and walls seen edge-on: their nearest stretch.
        let towards_viewer = right.cross(up);
        let centre = (bounds.min + bounds.max) / 2.0;
        for object in objects {
            if let Object::Plane(wall) = object {
                let normal = wall.normal.as_dvec3();
                let n = on_plane(normal);
                if normal.dot(towards_viewer).abs() > 1e-9 * normal.length()
                    || n.length_squared() == 0.0
                {
                    continue;
                }
                let c = wall.point.as_dvec3().dot(normal);
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
            if shown.holds(on_plane(frame.e())) {
                for axis in [plane.across(frame), frame.w()] {
                    bounds.add(on_plane(frame.e() + axis * AXIS_ROOM * size));
                }
            }
        }
        SideWindow::around(plane, right, up, bounds.min, bounds.max)
    }

    /// The window from `min` to `max` with a margin.
    fn around(plane: Plane, right: DVec3, up: DVec3, min: DVec2, max: DVec2) -> SideWindow {
        let margin = MARGIN * (max - min).max_element().max(1e-3);
        SideWindow {
            plane,
            right,
            up,
            min: min - margin,
            max: max + margin,
        }
    }

    /// The side view showing this window inside `drawing` (figure pixels), centred at
    /// one scale; what it shows and clips to is all of `drawing`, which may hold more of
    /// the plane than the window on two sides.
    pub(super) fn view(&self, drawing: Rect) -> SideView {
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

    /// The rectangle from `min` to `max` grown by [`REACH`] times its larger side all
    /// round: where a camera is near enough to be shown.
    fn reach(min: DVec2, max: DVec2) -> Bounds {
        let size = (max - min).max_element().max(1e-3);
        Bounds {
            min: min - REACH * size,
            max: max + REACH * size,
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

/// The points of `camera` a window on `plane` shows: the eye, the image plane's edges
/// across it (top and bottom seen from the side, left and right from above), the focus
/// point.
fn camera_points(camera: &Camera, plane: Plane) -> impl Iterator<Item = DVec3> {
    let frame = camera.frame();
    let edges = camera
        .projection()
        .viewport()
        .map(|_| plane.viewport_edges(camera));
    let focus = lens(camera).map(|(_, focus)| frame.e() - frame.w() * focus);
    std::iter::once(frame.e())
        .chain(edges.into_iter().flat_map(|(top, bottom)| [top, bottom]))
        .chain(focus)
}

impl Plane {
    /// The two image points (pixel units) whose rays bound the frustum in this plane:
    /// the middle column's top and bottom edges seen from the side, the middle row's left
    /// and right edges from above.
    pub(crate) fn image_edges(self, camera: &Camera) -> [DVec2; 2] {
        let (w, h) = (f64::from(camera.width()), f64::from(camera.height()));
        match self {
            Plane::Side => [DVec2::new(w / 2.0, 0.0), DVec2::new(w / 2.0, h)],
            Plane::Top => [DVec2::new(0.0, h / 2.0), DVec2::new(w, h / 2.0)],
        }
    }

    /// Where the image plane of a planar camera meets this plane: its two ends.
    pub(crate) fn viewport_edges(self, camera: &Camera) -> (DVec3, DVec3) {
        viewport_points(camera, self.image_edges(camera))
    }

    /// The pixels whose viewing rays the view draws: `count` of the middle column seen
    /// from the side, of the middle row from above, spread evenly.
    pub(crate) fn pixels(self, camera: &Camera, count: u32) -> Vec<(u32, u32)> {
        let spread = |k: u32, n: u32| {
            let centre = (f64::from(k) + 0.5) / f64::from(count) * f64::from(n);
            // Whole pixels inside the image.
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let index = centre.floor() as u32;
            index.min(n - 1)
        };
        (0..count)
            .map(|k| match self {
                Plane::Side => (spread(k, camera.height()), camera.width() / 2),
                Plane::Top => (camera.height() / 2, spread(k, camera.width())),
            })
            .collect()
    }

    /// The camera's axes drawn as arrows at the eye, with their colours and names: the
    /// one across the plane, then **w**.
    pub(crate) fn arrows(self, frame: &viewray_camera::Frame) -> [(DVec3, Color, &'static str); 2] {
        let across = match self {
            Plane::Side => (frame.v(), style::V_AXIS, "*v*"),
            Plane::Top => (frame.u(), style::U_AXIS, "*u*"),
        };
        [across, (frame.w(), style::W_AXIS, "*w*")]
    }

    /// The axis out of the page, its colour and name.
    pub(crate) fn out_axis(self, frame: &viewray_camera::Frame) -> (DVec3, Color, &'static str) {
        match self {
            Plane::Side => (frame.u(), style::U_AXIS, "*u*"),
            Plane::Top => (frame.v(), style::V_AXIS, "*v*"),
        }
    }

    /// The camera axis the plane spreads the rays over: **v** seen from the side, **u**
    /// from above.
    pub(crate) fn across(self, frame: &viewray_camera::Frame) -> DVec3 {
        match self {
            Plane::Side => frame.v(),
            Plane::Top => frame.u(),
        }
    }
}

/// Where the rays through the edges of `camera`'s image across `plane` pass nearest
/// `centre` (for a camera whose eye is too far to show, the part of its frustum among the
/// objects).
fn frustum_near(camera: &Camera, plane: Plane, centre: DVec3) -> impl Iterator<Item = DVec3> {
    plane
        .image_edges(camera)
        .into_iter()
        .filter_map(move |image| {
            let ray = camera.generate_ray_through(image, DVec2::splat(0.5))?;
            let t = (centre - ray.origin).dot(ray.direction) / ray.direction.length_squared();
            Some(ray.at(t.max(0.0)))
        })
}

/// The centre of the bounds of the scene's bounded objects (everything but planes), if
/// it has any: where a far eye's distance is measured from.
pub(super) fn objects_centre(scene: &Scene) -> Option<DVec3> {
    let mut bounds = Option::<(DVec3, DVec3)>::None;
    for object in scene.world().objects() {
        if let Some(aabb) = object.bounds() {
            let (min, max) = (aabb.min.as_dvec3(), aabb.max.as_dvec3());
            if !(min.is_finite() && max.is_finite()) {
                continue;
            }
            bounds = Some(bounds.map_or((min, max), |(a, b)| (a.min(min), b.max(max))));
        }
    }
    bounds.map(|(min, max)| (min + max) / 2.0)
}

/// The top view's axes `(right, up)`: **u** to the right and `-w` (the view) up, seen
/// from **v**'s side.
fn top_plane(camera: &Camera) -> (DVec3, DVec3) {
    let frame = camera.frame();
    (frame.u(), -frame.w())
}

/// The side view's axes `(right, up)`: the plane of the camera's **v** and **w** (which
/// holds the viewing rays of the image's middle column), seen from **u**'s side, with up
/// the world's `+y` projected onto it (**v** for a camera looking straight along `y`).
/// A camera that is not rolled has a horizontal **u**, so up is `+y` itself.
fn side_plane(camera: &Camera) -> (DVec3, DVec3) {
    let frame = camera.frame();
    let world_up = DVec3::Y - DVec3::Y.dot(frame.u()) * frame.u();
    let up = if world_up.length() > 1e-6 {
        world_up.normalize()
    } else {
        frame.v()
    };
    (up.cross(frame.u()), up)
}
