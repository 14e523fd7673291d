//! The lecture's figures, drawn with `viewray-draw` from the camera code.
//!
//! Every 3D point of a figure is placed through a `FigureView`: a viewray [`Camera`]'s
//! [`Camera::project`] (the 3D figures look through an orthographic "figure camera", the
//! pictures through the camera they show) or a side view of the y-z plane. Every viewing
//! ray drawn is one that a camera generates ([`Camera::generate_ray`]) and is recorded
//! with the figure, so tests check the figures against the cameras number by number, and
//! a figure can never disagree with a render.
//!
//! The pictures inside figures (the taxonomy's thumbnails, the distortions' and the thin
//! lens's pictures) are rendered by `viewray-render` at the size of their slot, so they
//! land on the figure pixel for pixel; the little scenes they show are built in code as
//! `viewray-scene`'s runtime `Scene`, the same objects as the fixtures' scene files.
//!
//! The figures share one visual language (colours, line weights, label sizes, the
//! 1600 x 900 slide and 1080 x 1080 square canvases), so the camera basis looks the same
//! on every slide. Labels follow the lecture's notation: vectors in bold (**u**), scalars
//! in italics (*vw*).
//!
//! [`all_figures`] lists the figures by name for `viewray figure NAME`, `cargo xtask
//! figures` and the golden check (`golden/figures/<name>.png`); [`figure_by_name`] finds
//! one. [`side_view`] draws the side view (or the top view) of any camera over any
//! scene, in a [`SideWindow`] on a [`SideViewCanvas`], for `viewray diagram`, the live
//! playground and animations. This crate knows no file format and does no I/O: writing a figure is
//! `viewray-draw`'s.
//!
//! Where to start reading: `sketch` (the figure builder: the display list, and the record
//! of every camera ray drawn) and `view` (how a figure places world points), then one
//! module per figure (`canonical`, `image_plane`, `assumptions`, `frame`,
//! `viewing_rays`, `taxonomy`, `distortions`, `thin_lens`, `scheimpflug`), `side` (the pieces the
//! side-view figures share) and `camera_side` (the side view of any camera; its module
//! doc is the map). `pictures` and `rendered` make the pictures inside figures, `clip`
//! keeps them inside their image, and `style` is the visual language. Numbers in labels
//! are written by [`viewray_output::number::label`] (and `label_significant`).
//!
//! ```no_run
//! use viewray_diagram::figure_by_name;
//!
//! let taxonomy = figure_by_name("taxonomy").expect("a lecture figure").figure();
//! let pixels = viewray_draw::raster::render(&taxonomy);
//! assert_eq!(pixels.dimensions(), (1600, 900));
//! ```

mod assumptions;
mod camera_side;
mod canonical;
mod clip;
mod distortions;
mod frame;
mod image_plane;
mod pictures;
mod rendered;
mod scheimpflug;
mod side;
mod sketch;
mod style;
mod taxonomy;
#[cfg(test)]
mod tests;
mod thin_lens;
mod view;
mod viewing_rays;

use std::fmt;

use glam::{DVec3, Vec2};
use viewray_camera::{Camera, CameraSample};
use viewray_draw::Figure;
use viewray_scene::Scene;

use crate::assumptions::{
    assumption_basis, assumption_distance, assumption_eye, assumption_viewport,
};
pub use crate::camera_side::{SideViewCanvas, SideWindow};
use crate::canonical::{canonical_camera, canonical_camera_square};
use crate::distortions::{distortion_foreshortening, distortion_verticals};
use crate::frame::{camera_frame, camera_frame_square};
use crate::image_plane::pixel_to_image_plane;
use crate::pictures::Pictures;
use crate::rendered::RenderedPictures;
use crate::scheimpflug::scheimpflug;
use crate::taxonomy::taxonomy;
use crate::thin_lens::thin_lens;
use crate::view::FigureView;
use crate::viewing_rays::viewing_rays;

/// A figure and the viewing rays it draws.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Diagram {
    /// The figure.
    pub(crate) figure: Figure,
    /// Every viewing ray drawn, with the camera that generated it, in drawing order.
    pub(crate) rays: Vec<DrawnRay>,
}

/// A viewing ray drawn on a figure: which camera generated it for which pixel and
/// sample, the world segment drawn, and where it was drawn.
///
/// ```text
/// from = ray.at(t.0),  to = ray.at(t.1),  ray = camera.generate_ray(row, col, sample)
/// from_px = view.to_figure(from),  to_px = view.to_figure(to)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DrawnRay {
    /// How the figure places world points.
    pub(crate) view: FigureView,
    /// The camera that generated the ray.
    pub(crate) camera: Camera,
    /// The pixel's row (0-based, from the top).
    pub(crate) row: u32,
    /// The pixel's column (0-based, from the left).
    pub(crate) col: u32,
    /// The film and lens sample.
    pub(crate) sample: CameraSample,
    /// The ray parameters of the drawn segment's ends.
    pub(crate) t: (f64, f64),
    /// The world point at `t.0`.
    pub(crate) from: DVec3,
    /// The world point at `t.1`.
    pub(crate) to: DVec3,
    /// Where `from` is drawn (figure pixels).
    pub(crate) from_px: Vec2,
    /// Where `to` is drawn (figure pixels).
    pub(crate) to_px: Vec2,
}

/// A lecture figure with its name, as `viewray figure NAME` and `cargo xtask figures`
/// list them.
#[derive(Clone, Copy)]
pub struct NamedFigure {
    /// The name, snake_case: also the file stem of `golden/figures/<name>.png`.
    pub name: &'static str,
    /// One line saying what the figure shows.
    pub summary: &'static str,
    draw: fn(&dyn Pictures) -> Diagram,
}

impl NamedFigure {
    /// Draws the figure, taking its pictures (if it has any) from `pictures`.
    pub(crate) fn draw(&self, pictures: &dyn Pictures) -> Diagram {
        (self.draw)(pictures)
    }

    /// The figure as the lecture shows it: its pictures rendered by the ray tracer.
    pub fn figure(&self) -> Figure {
        self.draw(&RenderedPictures::default()).figure
    }

    /// The figure with every picture drawn as flat-shaded polygons projected with the
    /// picture's camera: nothing is ray traced, so it is quick, for previews and tests.
    pub fn wireframe(&self) -> Figure {
        self.draw(&pictures::Wireframes).figure
    }
}

impl fmt::Debug for NamedFigure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("NamedFigure")
            .field("name", &self.name)
            .field("summary", &self.summary)
            .finish_non_exhaustive()
    }
}

/// Every lecture figure, in the lecture's order.
pub fn all_figures() -> Vec<NamedFigure> {
    vec![
        NamedFigure {
            name: "canonical_camera",
            summary: "The canonical camera: eye at the origin, -z, d = 1, rays through the pixel centres",
            draw: |_| canonical_camera(),
        },
        NamedFigure {
            name: "canonical_camera_square",
            summary: "The canonical camera on the square canvas",
            draw: |_| canonical_camera_square(),
        },
        NamedFigure {
            name: "pixel_to_image_plane",
            summary: "Pixel indices (row, col) and (i, j) to the image-plane point (u, v)",
            draw: |_| pixel_to_image_plane(),
        },
        NamedFigure {
            name: "assumption_distance",
            summary: "Breaking the assumptions, 1: d != 1 narrows the view",
            draw: |_| assumption_distance(),
        },
        NamedFigure {
            name: "assumption_viewport",
            summary: "Breaking the assumptions, 2: vw != vh != 1 scales u and v",
            draw: |_| assumption_viewport(),
        },
        NamedFigure {
            name: "assumption_eye",
            summary: "Breaking the assumptions, 3: the eye moved to e, rays start there",
            draw: |_| assumption_eye(),
        },
        NamedFigure {
            name: "assumption_basis",
            summary: "Breaking the assumptions, 4: a general basis, direction u u + v v - d w",
            draw: |_| assumption_basis(),
        },
        NamedFigure {
            name: "camera_frame",
            summary: "The camera frame e, u, v, w from eye, view and up, in 3D",
            draw: |_| camera_frame(),
        },
        NamedFigure {
            name: "camera_frame_square",
            summary: "The camera frame on the square canvas",
            draw: |_| camera_frame_square(),
        },
        NamedFigure {
            name: "viewing_rays",
            summary: "Perspective, orthographic, oblique and shifted perspective rays, side by side",
            draw: |_| viewing_rays(),
        },
        NamedFigure {
            name: "taxonomy",
            summary: "The classical projection taxonomy as a tree, a picture of the cube per preset",
            draw: taxonomy,
        },
        NamedFigure {
            name: "distortion_foreshortening",
            summary: "Foreshortening: equal posts at growing depth, image size inversely related to depth",
            draw: distortion_foreshortening,
        },
        NamedFigure {
            name: "distortion_verticals",
            summary: "A tilted camera makes verticals converge, a shifted lens keeps them parallel",
            draw: distortion_verticals,
        },
        NamedFigure {
            name: "thin_lens",
            summary: "Thin lens: one pixel's cone of rays meets at the focus plane; pictures at two apertures",
            draw: thin_lens,
        },
        NamedFigure {
            name: "scheimpflug",
            summary: "A tilted lens: sensor, lens and plane of focus meet in the Scheimpflug line; the hinge line",
            draw: |_| scheimpflug(),
        },
    ]
}

/// The side view of `camera` over `scene`: the lecture's side-view figures for any camera
/// and any scene. The scene's objects are seen from the side (`window`'s plane, world up
/// kept up: for a window fitted to this camera, the plane of its **v** and **w**), with
/// the eye **e** and its **v** and **w**, the image plane edge-on, the frustum's edges,
/// and the viewing rays of five pixels of the middle column, each drawn up to the first
/// object it hits (traced in `scene`'s world); for a thin lens, the lens and the focus
/// plane. A caption names the projection and its parameters. Labels are placed last,
/// each where it covers no other label and, where it can, no ray or object.
///
/// `window` is [`SideWindow::fit`] to this camera alone (`viewray diagram`, the live
/// playground) or to every camera of an animation, so that only the camera moves from
/// frame to frame; an eye beyond the window (farther than three times the objects' size)
/// is drawn as an arrow at its edge, labelled with its distance from the middle of the
/// objects. A window made by [`SideWindow::fit_top`] draws the top view instead: the
/// plane of **u** and **w** seen from **v**'s side, **u** to the right and the view up
/// the page, with the rays of the image's middle row. `canvas`
/// says where the figure goes ([`SideViewCanvas`]). `camera` need not be the scene's own
/// (a live viewer draws the camera being edited); `pixel`, a 0-based (row, col) of its
/// image, adds that pixel's viewing ray, highlighted and labelled with the lecture's
/// (i, j). Every ray drawn is one `camera` generates.
///
/// ```
/// use viewray_diagram::{SideViewCanvas, SideWindow, side_view};
/// # let scene = viewray_scene::SceneLoader::text(
/// #     "(camera: (eye: (0.0, 1.0, 5.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), \
/// #      projection: Perspective(fov_y: 40.0)))",
/// #     std::path::Path::new("scene.ron"),
/// # ).load().unwrap().scene;
/// let camera = scene.camera();
/// let window = SideWindow::fit(&scene, std::slice::from_ref(camera));
/// let figure = side_view(&scene, camera, &window, SideViewCanvas::Slide, Some((10, 20)));
/// assert_eq!((figure.width, figure.height), SideViewCanvas::Slide.size());
/// ```
pub fn side_view(
    scene: &Scene,
    camera: &Camera,
    window: &SideWindow,
    canvas: SideViewCanvas,
    pixel: Option<(u32, u32)>,
) -> Figure {
    camera_side::side_view(scene, camera, window, canvas, pixel).figure
}

/// The figure called `name`, if there is one; see [`figure_names`] for the names and
/// [`UnknownFigure`] for the error to report otherwise.
pub fn figure_by_name(name: &str) -> Option<NamedFigure> {
    all_figures().into_iter().find(|figure| figure.name == name)
}

/// The names of all figures, in the lecture's order.
pub fn figure_names() -> Vec<&'static str> {
    all_figures().iter().map(|figure| figure.name).collect()
}

/// The error for a figure name that [`figure_by_name`] does not know; its message lists
/// the valid names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct UnknownFigure {
    /// The name asked for.
    pub name: String,
}

impl UnknownFigure {
    /// The error for `name`.
    pub fn new(name: impl Into<String>) -> UnknownFigure {
        UnknownFigure { name: name.into() }
    }
}

impl fmt::Display for UnknownFigure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "unknown figure `{}`; the figures are: {}",
            self.name,
            figure_names().join(", ")
        )
    }
}

impl std::error::Error for UnknownFigure {}
