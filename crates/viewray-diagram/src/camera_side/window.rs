//! The part of the world a side view shows: a vertical plane through the camera and a
//! rectangle of it, fitted to one camera or to every camera of an animation.

use glam::{DVec2, DVec3};
use viewray_camera::Camera;
use viewray_draw::{Mapping, Rect};
use viewray_geometry::Object;
use viewray_scene::Scene;

use super::camera::lens;
use crate::side::viewport_edges;
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
                for p in aabb.corners() {
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
            let distance = |c: &Camera| (on_plane(c.frame().e()) - centre).length();
            distance(a).total_cmp(&distance(b))
        });
        if let Some(nearest) = by_distance.first() {
            if bounds.range().is_none() {
                let frame = nearest.frame();
                bounds.add(on_plane(frame.e() - frame.w() * 4.0));
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
            if shown.holds(on_plane(frame.e())) {
                for axis in [frame.v(), frame.w()] {
                    bounds.add(on_plane(frame.e() + axis * AXIS_ROOM * size));
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

/// The points of `camera` a window shows: the eye, the image plane's top and bottom
/// edges, the focus point.
fn camera_points(camera: &Camera) -> impl Iterator<Item = DVec3> {
    let frame = camera.frame();
    let edges = camera
        .projection()
        .viewport()
        .map(|_| viewport_edges(camera));
    let focus = lens(camera).map(|(_, focus)| frame.e() - frame.w() * focus);
    std::iter::once(frame.e())
        .chain(edges.into_iter().flat_map(|(top, bottom)| [top, bottom]))
        .chain(focus)
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
