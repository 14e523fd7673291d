//! The one way to load a scene: [`SceneLoader`] says where the text comes from (a file, a
//! reader such as standard input, or text in hand) and which settings to override, and
//! [`SceneLoader::load`] gives the scene, its animation and how long loading took.
//!
//! A file or a reader is read whole (at most [`MAX_SCENE_BYTES`]) and recognised
//! ([`FileKind::recognise`]) before it is parsed, so that an OBJ mesh, an image or another
//! tool's scene given as a scene is named for what it is.

use std::io::Read;
use std::path::Path;
use std::time::{Duration, Instant};

use crate::{Animation, FileKind, Scene, SceneError};

/// The largest scene file viewray reads: 16 MiB (scenes describe geometry in meshes).
pub const MAX_SCENE_BYTES: u64 = 16 << 20;

/// Settings that override the scene file's, applied before the camera is built (so a
/// field of view or a preset follows the new aspect ratio).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Render at `(width, height)` instead of the file's image size.
    pub size: Option<(u32, u32)>,
    /// Take this many samples per pixel instead of the file's.
    pub samples: Option<u32>,
}

/// How long loading a scene took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadTimes {
    /// Everything: reading, parsing, loading meshes, building BVHs.
    pub total: Duration,
    /// The part spent building BVHs (each distinct mesh's and the world's).
    pub build: Duration,
}

/// A scene to load: where its text comes from, and the settings to override.
///
/// ```no_run
/// # use std::path::Path;
/// # use viewray_scene::{LoadOptions, SceneLoader};
/// let loaded = SceneLoader::file(Path::new("scene.ron"))
///     .options(LoadOptions { size: Some((640, 480)), samples: None })
///     .load()?;
/// println!("{} samples, loaded in {:?}", loaded.scene.samples(), loaded.times.total);
/// # Ok::<(), viewray_scene::SceneError>(())
/// ```
pub struct SceneLoader<'a> {
    source: Source<'a>,
    options: LoadOptions,
}

/// Where a scene's text comes from.
enum Source<'a> {
    File(&'a Path),
    Reader(Box<dyn Read + 'a>, &'a Path),
    Text(&'a str, &'a Path),
}

/// A loaded scene file: the scene, its `animation:` section when it has one (checked
/// either way: a scene with a bad animation does not load), and how long loading took.
#[derive(Debug)]
pub struct LoadedScene {
    /// The scene.
    pub scene: Scene,
    /// The animation, when the file has an `animation:` section.
    pub animation: Option<Animation>,
    /// How long reading, parsing and building took.
    pub times: LoadTimes,
}

impl<'a> SceneLoader<'a> {
    /// The scene file at `path`; its meshes are found relative to its folder.
    pub fn file(path: &'a Path) -> Self {
        Self::from_source(Source::File(path))
    }

    /// The scene read from `reader` (standard input, say); `name` names it in error
    /// messages, and meshes are found relative to its folder: the current folder for a
    /// bare name such as `<stdin>`.
    pub fn reader(reader: impl Read + 'a, name: &'a Path) -> Self {
        Self::from_source(Source::Reader(Box::new(reader), name))
    }

    /// The scene `text`, already in hand; `path` names it in error messages, and meshes
    /// are found relative to its folder.
    pub fn text(text: &'a str, path: &'a Path) -> Self {
        Self::from_source(Source::Text(text, path))
    }

    fn from_source(source: Source<'a>) -> Self {
        Self {
            source,
            options: LoadOptions::default(),
        }
    }

    /// Overrides the file's image size or samples with `options`.
    #[must_use]
    pub fn options(self, options: LoadOptions) -> Self {
        Self { options, ..self }
    }

    /// Reads, parses and checks the scene, and builds its BVHs.
    ///
    /// # Errors
    /// A [`SceneError`] naming the file (and the line and column where it can) if the
    /// text cannot be read or is not a valid scene.
    pub fn load(self) -> Result<LoadedScene, SceneError> {
        let started = Instant::now();
        let (scene, animation, build) = match self.source {
            Source::File(path) => crate::load::parse(&read_scene_file(path)?, path, self.options)?,
            Source::Reader(reader, name) => {
                crate::load::parse(&read_scene_text(reader, name)?, name, self.options)?
            }
            Source::Text(text, path) => crate::load::parse(text, path, self.options)?,
        };
        Ok(LoadedScene {
            scene,
            animation,
            times: LoadTimes {
                total: started.elapsed(),
                build,
            },
        })
    }
}

/// Reads the text of the scene file at `path` as loading it would, without parsing it:
/// for a program that keeps the text beside the loaded scene (the live playground
/// serves it).
///
/// # Errors
/// A [`SceneError`] naming `path` for a missing file, a directory, a file of another kind
/// ([`SceneError::found`]), a file that is not UTF-8 text, or one larger than
/// [`MAX_SCENE_BYTES`].
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
/// file, refusing a file of another kind, text that is not UTF-8 or too large to be a
/// scene; `path` names it in errors.
///
/// # Errors
/// A [`SceneError`] naming `path`.
pub fn read_scene_text(reader: impl Read, path: &Path) -> Result<String, SceneError> {
    let error = |message: String| SceneError::at(path, None, message);
    let not_text = || error("is not a text file (not UTF-8)".to_owned());
    let mut bytes = Vec::new();
    reader
        .take(MAX_SCENE_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| match e.kind() {
            std::io::ErrorKind::InvalidData => not_text(),
            _ => error(format!("cannot read the scene: {e}")),
        })?;
    if let Some(kind) = FileKind::recognise(path, &bytes)
        && let Some(message) = kind.not_a_scene()
    {
        return Err(SceneError::not_a_scene(path, kind, message));
    }
    let read = bytes.len();
    let text = String::from_utf8(bytes).map_err(|_| not_text())?;
    if read as u64 > MAX_SCENE_BYTES {
        return Err(error(format!(
            "is larger than {} MiB: too large for a scene file",
            MAX_SCENE_BYTES >> 20
        )));
    }
    Ok(text)
}
