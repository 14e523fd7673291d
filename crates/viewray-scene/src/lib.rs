//! viewray's scene files: the RON format, read into the runtime [`Scene`] the other
//! crates render and draw, with every error placed at its file, line and column.
//!
//! # What it owns
//!
//! - The scene format: the serde types mirroring the file (private: `schema`), their
//!   translation into viewray-camera's cameras (`camera`) and into the renderer's values
//!   (`values`), the `animation:` section and the mixing of its keys (`animation`,
//!   `mix`), OBJ meshes with their MTL materials (`mesh`, on tobj), and RON's errors
//!   reworded in the format's terms (`ron_text`).
//! - [`SceneLoader`], the one way in: a file, a reader or text, with [`LoadOptions`],
//!   giving a [`LoadedScene`]; and [`parse_camera`], a `camera:` value on its own.
//! - [`FileKind`], the recogniser of every kind of file viewray reads or writes (scenes,
//!   meshes, other tools' scenes, images), so that a wrong file is named for what it is.
//! - [`SceneDocument`], which writes a scene file from plain values, for code that makes
//!   scenes (the importers of other tools' scenes).
//!
//! # Invariant
//!
//! No other crate knows RON or OBJ, and the serde types never leave this one. A [`Scene`]
//! that exists is consistent ([`Scene::new`] checks its parts), and a bad file is one
//! [`SceneError`] on one line, naming the file, the line and column where it can, what was
//! found and what was expected; it never panics.
//!
//! # Where to start reading
//!
//! `loader` (the entry), then `load` (the file in steps: image, camera, materials, lights,
//! objects) and `schema` (what a file may say). The format is documented for users in the
//! repository's `docs/scene-format.md`; every field but `camera` has a default, so a
//! camera-only file is a valid scene:
//!
//! ```ron
//! (
//!     image: (width: 320, height: 240, samples: 4),
//!     camera: (
//!         eye: (0.0, 1.0, 5.0),
//!         look_at: (0.0, 0.0, 0.0),   // or view: (x, y, z)
//!         up: (0.0, 1.0, 0.0),
//!         projection: Perspective(distance: 1.0, viewport: (1.0, 0.75)),
//!     ),
//! )
//! ```
//!
//! or with a taxonomy preset: `camera: Isometric(target: (0.0, 0.0, 0.0), size: 4.0)`.
//! Angles are degrees in scene files. The image's size and samples obey viewray's
//! limits, which viewray-camera's `ImageLimits` holds.

mod animation;
mod camera;
mod document;
mod error;
mod file_kind;
mod load;
mod loader;
mod mesh;
mod mix;
mod obj;
mod ron_text;
mod scene;
mod schema;
mod values;

use std::path::Path;

pub use animation::{Animation, Ease, Key, MAX_FPS, MAX_FRAMES};
pub use camera::{CameraSpec, camera_text, parse_camera};
pub use document::{
    Aperture, CameraDocument, ObjectDocument, PerspectiveSize, ProjectionDocument, SceneDocument,
};
pub use error::{Position, SceneError, one_line, write_file_error};
pub use file_kind::FileKind;
pub use loader::{
    LoadOptions, LoadTimes, LoadedScene, MAX_SCENE_BYTES, SceneLoader, read_scene_file,
    read_scene_text,
};
pub use obj::obj_text;
pub use scene::{Grid, InvalidScene, Light, Material, ObjectMaterial, Scene, SceneParts, Shading};
/// viewray's image limits, which scene files obey: re-exported from the camera crate, where
/// the rule is written.
pub use viewray_camera::{MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES};

/// Parses OBJ text as a scene's mesh would be, ignoring MTL libraries: the entry point of
/// the OBJ fuzz target. Returns the number of triangles kept, or the error message.
#[doc(hidden)]
pub fn fuzz_parse_obj(bytes: &[u8]) -> Result<usize, String> {
    let mut materials = Vec::new();
    let no_mtl = |_: &Path| Err(tobj::LoadError::OpenFileFailed);
    let mut build_time = std::time::Duration::ZERO;
    mesh::parse_obj(bytes, no_mtl, &mut materials, &mut build_time).map(|m| m.mesh.triangle_count())
}
