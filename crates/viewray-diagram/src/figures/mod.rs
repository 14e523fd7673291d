//! The lecture's figures, each computed from the camera code.
//!
//! Every 3D point of a figure is placed through a [`FigureView`]: a viewray
//! [`Camera`]'s [`Camera::project`] (the 3D figures look through an orthographic "figure
//! camera", the pictures through the camera they show) or a [`SideView`] of the y-z
//! plane. Every viewing ray drawn is one that a camera generates
//! ([`Camera::generate_ray`]) and is recorded in [`Diagram::rays`], so tests check the
//! figures against the cameras number by number, and a figure can never disagree with a
//! render.
//!
//! The pictures inside figures (the taxonomy's thumbnails, the distortions' and the thin
//! lens's pictures) are rendered by the ray tracer through [`RenderedPictures`], at the
//! size of their slot, so they land on the figure pixel for pixel.
//!
//! [`all_figures`] lists them by name for `viewray figure NAME` and `cargo xtask
//! figures`; [`figure_by_name`] finds one. `cargo xtask golden` compares
//! [`render_all`] with `golden/figures/`:
//!
//! ```no_run
//! use viewray_diagram::figures::{RenderedPictures, all_figures, render_all};
//!
//! // Every figure, rasterized with rendered pictures: (name, RGBA pixels).
//! let images = render_all();
//! // The same, one figure at a time.
//! for named in all_figures() {
//!     let pixels = named.draw(&RenderedPictures::default()).figure.render();
//!     assert_eq!(pixels, named.figure().render());
//! }
//! # let _ = images;
//! ```

mod assumptions;
mod canonical;
mod clip;
mod distortions;
mod frame;
mod image_plane;
mod pictures;
mod rendered;
mod side;
mod sketch;
mod taxonomy;
mod thin_lens;
mod view;
mod viewing_rays;

use std::fmt;

use glam::{DVec3, Vec2};
use image::RgbaImage;
use viewray_camera::{Camera, CameraSample};

use crate::Figure;

pub use assumptions::{assumption_basis, assumption_distance, assumption_eye, assumption_viewport};
pub use canonical::{canonical_camera, canonical_camera_square};
pub use distortions::{distortion_foreshortening, distortion_verticals};
pub use frame::{camera_frame, camera_frame_square};
pub use image_plane::pixel_to_image_plane;
pub use pictures::{
    AXIS_COLOURS, GROUND, Paint, PictureRequest, PictureScene, Pictures, SKY, SceneObject, Shape,
    Wireframes,
};
pub use rendered::{EARTH_DEPTH, RenderedPictures, picture_lights, picture_scene};
pub use taxonomy::{THUMBNAIL_IMAGE, taxonomy, taxonomy_camera};
pub use thin_lens::{
    CONE_PIXEL, FOCUS, LENS_POINTS, PICTURE_APERTURES, thin_lens, thin_lens_camera,
};
pub use view::{CameraView, FigureView, SideView};
pub use viewing_rays::viewing_rays;

/// A figure and the viewing rays it draws.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagram {
    /// The figure.
    pub figure: Figure,
    /// Every viewing ray drawn, with the camera that generated it, in drawing order.
    pub rays: Vec<DrawnRay>,
}

/// A viewing ray drawn on a figure: which camera generated it for which pixel and
/// sample, the world segment drawn, and where it was drawn.
///
/// ```text
/// from = ray.at(t.0),  to = ray.at(t.1),  ray = camera.generate_ray(row, col, sample)
/// from_px = view.to_figure(from),  to_px = view.to_figure(to)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DrawnRay {
    /// How the figure places world points.
    pub view: FigureView,
    /// The camera that generated the ray.
    pub camera: Camera,
    /// The pixel's row (0-based, from the top).
    pub row: u32,
    /// The pixel's column (0-based, from the left).
    pub col: u32,
    /// The film and lens sample.
    pub sample: CameraSample,
    /// The ray parameters of the drawn segment's ends.
    pub t: (f64, f64),
    /// The world point at `t.0`.
    pub from: DVec3,
    /// The world point at `t.1`.
    pub to: DVec3,
    /// Where `from` is drawn (figure pixels).
    pub from_px: Vec2,
    /// Where `to` is drawn (figure pixels).
    pub to_px: Vec2,
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
    pub fn draw(&self, pictures: &dyn Pictures) -> Diagram {
        (self.draw)(pictures)
    }

    /// The figure as the lecture shows it: its pictures rendered by the ray tracer
    /// ([`RenderedPictures::default`]).
    pub fn figure(&self) -> Figure {
        self.draw(&RenderedPictures::default()).figure
    }

    /// The figure with every picture drawn as projected polygons ([`Wireframes`]):
    /// nothing is ray traced, so it is quick, for tests and previews.
    pub fn wireframe(&self) -> Figure {
        self.draw(&Wireframes).figure
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
    ]
}

/// Every figure as the lecture shows it (pictures rendered, [`NamedFigure::figure`]),
/// rasterized: `(name, pixels)` in the lecture's order, the images that
/// `golden/figures/<name>.png` holds.
///
/// Deterministic: the same pixels on every run and every number of threads.
pub fn render_all() -> Vec<(String, RgbaImage)> {
    all_figures()
        .iter()
        .map(|named| (named.name.to_owned(), named.figure().render()))
        .collect()
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
