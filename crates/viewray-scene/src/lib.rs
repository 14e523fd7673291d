//! viewray's scene files: the RON schema, loading and validation.
//!
//! This crate is the only one that knows RON (and, later, OBJ). It turns a scene file
//! into a [`Scene`], the runtime value the other crates use, and rejects a bad file with
//! one [`SceneError`] naming the file, line and column, what was found and what was
//! expected. The serde types mirroring the file stay private.
//!
//! The format is documented in DESIGN.md ("Scene files"); every field but `camera` has a
//! default, so a camera-only file is a valid scene:
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
//! Angles are degrees in scene files.

mod error;
mod load;
mod mesh;
mod scene;
mod schema;

use std::path::Path;

pub use error::{Position, SceneError};
pub use load::{LoadOptions, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES};
pub use scene::{Grid, Light, Material, ObjectMaterial, Scene, Shading};

impl Scene {
    /// Loads the scene file at `path`.
    ///
    /// # Errors
    /// A [`SceneError`] if the file cannot be read or is not a valid scene.
    pub fn load(path: &Path) -> Result<Scene, SceneError> {
        Self::load_with(path, LoadOptions::default())
    }

    /// Loads the scene file at `path`, with `options` overriding some of its settings.
    ///
    /// # Errors
    /// A [`SceneError`] if the file cannot be read or is not a valid scene.
    pub fn load_with(path: &Path, options: LoadOptions) -> Result<Scene, SceneError> {
        let text = std::fs::read_to_string(path).map_err(|error| {
            SceneError::at(path, None, format!("cannot read the scene file: {error}"))
        })?;
        Self::parse_with(&text, path, options)
    }

    /// Parses the scene `text`; `path` names it in error messages, and meshes are found
    /// relative to its folder.
    ///
    /// # Errors
    /// A [`SceneError`] if `text` is not a valid scene.
    pub fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
        Self::parse_with(text, path, LoadOptions::default())
    }

    /// Parses the scene `text` with `options` overriding some of its settings.
    ///
    /// # Errors
    /// A [`SceneError`] if `text` is not a valid scene.
    pub fn parse_with(text: &str, path: &Path, options: LoadOptions) -> Result<Scene, SceneError> {
        load::parse(text, path, options)
    }
}
