//! viewray's scene files: the RON schema, loading and validation.
//!
//! This crate is the only one that knows RON (and, later, OBJ). It turns a scene file
//! into a [`Scene`], the runtime value the other crates use, and rejects a bad file with
//! one [`SceneError`] naming the file, line and column, what was found and what was
//! expected. The serde types mirroring the file stay private.
//!
//! The format is documented for users in the repository's `docs/scene-format.md`; every
//! field but `camera` has a default, so a camera-only file is a valid scene:
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
//! [`SceneDocument`] writes a scene file from plain values, for code that makes scenes.
//! Angles are degrees in scene files.

mod animation;
mod camera;
mod document;
mod error;
mod load;
mod mesh;
mod mix;
mod ron_text;
mod scene;
mod schema;
mod values;

use std::io::Read;
use std::path::Path;
use std::time::{Duration, Instant};

pub use animation::{Animation, Ease, Key, MAX_FPS, MAX_FRAMES};
pub use camera::{CameraSpec, camera_text, parse_camera};
pub use document::{
    Aperture, CameraDocument, ObjectDocument, PerspectiveSize, ProjectionDocument, SceneDocument,
};
pub use error::{Position, SceneError};
pub use load::LoadOptions;
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

/// How long loading a scene took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadTimes {
    /// Everything: reading, parsing, loading meshes, building BVHs.
    pub total: Duration,
    /// The part spent building BVHs (each distinct mesh's and the world's).
    pub build: Duration,
}

/// The largest scene file viewray reads: 16 MiB (scenes describe geometry in meshes).
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// Reads the text of the scene file at `path` as loading it would, without parsing it:
/// for a program that keeps the text beside the loaded scene (the live playground
/// serves it).
///
/// # Errors
/// A [`SceneError`] naming `path` for a missing file, a directory, a file that is not
/// UTF-8 text, or one larger than [`MAX_SCENE_BYTES`].
pub fn read_scene_file(path: &Path) -> Result<String, SceneError> {
    let error = |message: String| SceneError::at(path, None, message);
    let file = std::fs::File::open(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => error("no such scene file".to_owned()),
        _ => error(format!("cannot read the scene file: {e}")),
    })?;
    let metadata = file
        .metadata()
        .map_err(|e| error(format!("cannot read the scene file: {e}")))?;
    if metadata.is_dir() {
        return Err(error("is a directory, not a scene file".to_owned()));
    }
    read_scene_text(file, path)
}

/// Reads scene text from `reader` (standard input, say) as [`read_scene_file`] reads a
/// file, refusing text that is not UTF-8 or too large to be a scene; `path` names it in
/// errors.
///
/// # Errors
/// A [`SceneError`] naming `path`.
pub fn read_scene_text(reader: impl Read, path: &Path) -> Result<String, SceneError> {
    let error = |message: String| SceneError::at(path, None, message);
    let mut text = String::new();
    let read = reader
        .take(MAX_SCENE_BYTES + 1)
        .read_to_string(&mut text)
        .map_err(|e| match e.kind() {
            std::io::ErrorKind::InvalidData => error("is not a text file (not UTF-8)".to_owned()),
            _ => error(format!("cannot read the scene: {e}")),
        })?;
    if read as u64 > MAX_SCENE_BYTES {
        return Err(error(format!(
            "is larger than {} MiB: too large for a scene file",
            MAX_SCENE_BYTES >> 20
        )));
    }
    Ok(text)
}

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
        Self::load_timed(path, options).map(|(scene, _)| scene)
    }

    /// Loads the scene file at `path` like [`Scene::load_with`], and says how long the
    /// loading took and how much of that was building BVHs.
    ///
    /// # Errors
    /// A [`SceneError`] if the file cannot be read or is not a valid scene.
    pub fn load_timed(path: &Path, options: LoadOptions) -> Result<(Scene, LoadTimes), SceneError> {
        let started = Instant::now();
        let text = read_scene_file(path)?;
        let (scene, _animation, build) = load::parse(&text, path, options)?;
        Ok((
            scene,
            LoadTimes {
                total: started.elapsed(),
                build,
            },
        ))
    }

    /// Reads a scene from `reader` (standard input, say) like [`Scene::load_timed`];
    /// `path` names it in error messages, and meshes are found relative to its folder:
    /// the current folder for a bare name such as `<stdin>`.
    ///
    /// # Errors
    /// A [`SceneError`] if the text cannot be read or is not a valid scene.
    pub fn read_timed(
        reader: impl Read,
        path: &Path,
        options: LoadOptions,
    ) -> Result<(Scene, LoadTimes), SceneError> {
        let started = Instant::now();
        let text = read_scene_text(reader, path)?;
        let (scene, _animation, build) = load::parse(&text, path, options)?;
        Ok((
            scene,
            LoadTimes {
                total: started.elapsed(),
                build,
            },
        ))
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
        Self::parse_timed(text, path, options).map(|(scene, _)| scene)
    }

    /// Loads the scene file at `path` like [`Scene::load_with`], with its `animation:`
    /// section when it has one (checked either way: a scene with a bad animation does not
    /// load).
    ///
    /// # Errors
    /// A [`SceneError`] if the file cannot be read or is not a valid scene.
    pub fn load_animated(
        path: &Path,
        options: LoadOptions,
    ) -> Result<(Scene, Option<Animation>), SceneError> {
        let text = read_scene_file(path)?;
        Self::parse_animated(&text, path, options)
    }

    /// Reads a scene from `reader` like [`Scene::read_timed`], with its animation.
    ///
    /// # Errors
    /// A [`SceneError`] if the text cannot be read or is not a valid scene.
    pub fn read_animated(
        reader: impl Read,
        path: &Path,
        options: LoadOptions,
    ) -> Result<(Scene, Option<Animation>), SceneError> {
        let text = read_scene_text(reader, path)?;
        Self::parse_animated(&text, path, options)
    }

    /// Parses the scene `text` like [`Scene::parse_with`], with its animation.
    ///
    /// # Errors
    /// A [`SceneError`] if `text` is not a valid scene.
    pub fn parse_animated(
        text: &str,
        path: &Path,
        options: LoadOptions,
    ) -> Result<(Scene, Option<Animation>), SceneError> {
        let (scene, animation, _) = load::parse(text, path, options)?;
        Ok((scene, animation))
    }

    /// Parses the scene `text` like [`Scene::parse_with`], and says how long it took and
    /// how much of that was building BVHs.
    ///
    /// # Errors
    /// A [`SceneError`] if `text` is not a valid scene.
    pub fn parse_timed(
        text: &str,
        path: &Path,
        options: LoadOptions,
    ) -> Result<(Scene, LoadTimes), SceneError> {
        let started = Instant::now();
        let (scene, _animation, build) = load::parse(text, path, options)?;
        Ok((
            scene,
            LoadTimes {
                total: started.elapsed(),
                build,
            },
        ))
    }
}
