//! The live playground behind `viewray serve`: an HTTP server that renders one loaded
//! scene through whatever camera the page sends, draws that camera's side view, prints
//! its numbers, and serves the page that drives it.
//!
//! # What it owns
//!
//! - [`ServedScene`]: the scene file's text, its camera's text and the loaded scene
//!   with its BVHs, loaded once; every request brings a camera as the text of a scene
//!   file's `camera:` value, which is parsed alone ([`viewray_scene::parse_camera`]) and
//!   rendered through [`viewray_render::render_view`], so a new camera costs a render
//!   and nothing else.
//! - [`Server`] (`http`: hyper on a small tokio runtime, requests answered on a
//!   bounded pool of blocking threads, render slots), the
//!   endpoints (`api`: each a function from path and query to status and body), the
//!   query's parameters (`params`: each checked before anything is allocated) and the
//!   page (`page`: HTML, CSS and JavaScript by hand, compiled in).
//! - [`Limits`]: how much work one request may ask for, within viewray's own image
//!   limits (viewray-camera's `ImageLimits`, which this crate only tightens).
//!
//! # Invariant
//!
//! No request reaches the file system: the scene and its meshes were read when the
//! server started, and every answer is computed from memory with the libraries the
//! command line uses, so the page shows the command line's numbers and pictures. This
//! crate knows nothing of the command line: its answers name its own parameters.
//!
//! # Where to start reading
//!
//! `api` (the endpoints below), then `params` and `http`.
//!
//! # Endpoints (GET)
//! `camera` is URL-encoded RON (default: the served scene's); `width`, `height`,
//! `samples` and `shading` override the served scene's. `/api/render`, `/api/frame`,
//! `/api/rays`, `/api/diagram.svg` and `/api/slide.png` also take
//! `mistakes=u-sign,v-sign` (ids of the lecture's catalogue, [`viewray_camera::Mistake`]):
//! the camera a student with those mistakes wrote
//! ([`viewray_camera::Camera::with_mistakes`]; a mistake its family cannot make is a
//! `400`). The page has the catalogue compiled in: each entry's words and the families it
//! fits. `/api/render` also takes `ticket=NAME.TURN`: a render with a ticket stops the
//! renders of its name with an earlier turn, running or waiting for a slot, which are
//! answered `409` (a page's view abandons each picture as the next is asked for, and the
//! server cannot see a connection close while it renders).
//!
//! | path | reply |
//! |---|---|
//! | `/` | the page (HTML, CSS and JavaScript compiled in; the URL fragment holds its state) |
//! | `/lecture` | the lecture as live steps, each with its render, views, controls and formulas (MathML, the command line's digits); the URL fragment names the step and the camera |
//! | `/api/render?camera&width&height&samples&shading[&ticket]` | `image/png`: pixel for pixel what `viewray render` writes for the scene with that camera and settings |
//! | `/api/frame?camera` | the line of `viewray frame` |
//! | `/api/rays?camera&width&height&row&col` (or `i&j`, 1-based) | the line of `viewray rays --pixel R,C` (`--one-based --pixel I,J`) |
//! | `/api/project?camera&width&height&point=X,Y,Z` (repeatable) | the lines of `viewray project` |
//! | `/api/diagram.svg?camera&width&height[&row&col][&view=top][&canvas=WxH]` | the camera's side view ([`viewray_diagram::side_view`]), or its top view, on a canvas of that size |
//! | `/api/depth?camera&width&height` | `{"depth": D, "from": "hit"}`: how far along the view the scene lies at the picture's middle (what the centre ray hits, else the objects' middle; `null` if nothing is in front), for switching the projection kind |
//! | `/api/slide.png?camera&width&height&samples&shading[&row&col][&top=1]` | a 1920 x 1080 slide: the render at the slide's size, the side view (and the top view), the frame's and the pixel's numbers |
//! | `/api/trace?camera&width&height&shading&row&col` (or `i&j`)`[&format=text]` | the lines of `viewray trace --pixel R,C --json` for the image `/api/render` makes with one sample (with `format=text`, the trace as text) |
//! | `/api/scene` | the served scene's RON text |
//! | `/api/status` | `{"renders": {"running", "waiting", "rendered", "superseded", "busy"}}`: the renders in a slot and waiting for one now, and how many were answered, given up for a newer one with their ticket, and refused `503` since the server started |
//!
//! Bad parameters are `400` with `{"error": "..."}`, in the command line's words where
//! they are the same and in the query's where the command line would name a flag (`i=I&j=J`
//! for `--one-based`), starting with the parameter's name (`width: ...`, `camera:1:9:
//! ...`); an unknown path is `404`; a method other than GET or HEAD `405`. Sizes and
//! samples are bounded ([`Limits`]) and checked before anything is allocated, so a
//! 100000 x 100000 request is refused at once. Renders take one of a few render slots; a
//! request that finds none free within [`ServeOptions::slot_wait`] (or too many requests
//! already waiting) is `503`, so a room of laptops dragging sliders is answered or told
//! to retry, never queued without bound.

mod api;
mod depth;
mod http;
mod page;
mod params;
mod slide;

use std::path::Path;

use viewray_camera::ImageLimits;
use viewray_scene::{Scene, SceneError, SceneLoader};

pub use crate::http::{ServeOptions, Server, Stopper};

/// How much work one request may ask for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Limits {
    /// The largest side of a rendered image, in pixels.
    pub max_side: u32,
    /// The most pixels of a rendered image.
    pub max_pixels: u64,
    /// The most samples per pixel of a render.
    pub max_samples: u32,
    /// The most samples of one render in all: pixels x samples per pixel.
    pub max_frame_samples: u64,
    /// The longest camera text, in bytes.
    pub max_camera_bytes: usize,
    /// The most points of one `/api/project` request.
    pub max_points: usize,
}

impl Default for Limits {
    /// Up to 4096 pixels a side and 4 Mpixels (2048 x 2048), 1024 samples per pixel and
    /// 2^26 samples a frame (1920 x 1080 at 32): a few seconds of work at most, and a few
    /// hundred megabytes.
    fn default() -> Self {
        Self {
            max_side: 4096,
            max_pixels: 1 << 22,
            max_samples: 1024,
            max_frame_samples: 1 << 26,
            max_camera_bytes: 16 << 10,
            max_points: 256,
        }
    }
}

impl Limits {
    /// The limits on a rendered image's size and samples, as viewray's image limits
    /// (tightened to them when these are looser).
    pub fn image(&self) -> ImageLimits {
        ImageLimits {
            max_side: self.max_side,
            max_pixels: self.max_pixels,
            max_samples: self.max_samples,
        }
        .within_viewray()
    }
}

/// The scene a server serves, loaded once: its text, its camera's text, the runtime
/// scene with its BVHs, and the page.
#[derive(Debug)]
pub struct ServedScene {
    /// What the page calls the scene (its file name, or "the default scene").
    name: String,
    /// The scene file's text.
    text: String,
    /// The text of its `camera:` value: the camera a request without one uses, and the
    /// page's starting state.
    camera_text: String,
    /// The loaded scene.
    scene: Scene,
    /// The page, with the scene's starting state in it.
    page: String,
    /// The lecture, with the scene's camera in it.
    lecture: String,
}

impl ServedScene {
    /// Loads the scene file `text` (read from `path`: meshes are found beside it), to be
    /// called `name` on the page.
    ///
    /// # Errors
    /// The scene's error, naming `path`, line and column.
    pub fn parse(name: &str, text: String, path: &Path) -> Result<ServedScene, SceneError> {
        let scene = SceneLoader::text(&text, path).load()?.scene;
        let camera_text = viewray_scene::camera_text(&text, path)?.to_owned();
        let page = page::page(name, &camera_text, &scene);
        let lecture = page::lecture(name, &camera_text);
        Ok(ServedScene {
            name: name.to_owned(),
            text,
            camera_text,
            scene,
            page,
            lecture,
        })
    }

    /// What the page calls the scene.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The loaded scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The text of the scene file's `camera:` value.
    pub fn camera_text(&self) -> &str {
        &self.camera_text
    }
}
