//! Other tools' cameras and scenes: a viewray [`Scene`] written for Mitsuba 3, pbrt-v4,
//! Blender, three.js and glTF 2.0, and their files read back as a viewray
//! [`SceneDocument`].
//!
//! Each format is one module, a pair of pure functions between its text and viewray's
//! scene, with its conventions written once at its top (axes, handedness, units, what a
//! field of view spans, shift units, orthographic scale). This crate knows nothing of
//! the command line and does no I/O: it turns values into bytes and bytes into values;
//! the caller reads and writes the files.
//!
//! The camera is carried exactly, to the last digit the target's conventions allow. A
//! camera the target cannot express (an oblique projection in Mitsuba 3, pbrt or glTF, a
//! shift in glTF, a panorama where the target has none) is an [`ExportError`] that names
//! what the target lacks: never a silently different camera. The scene around it comes
//! along as well as the target allows: spheres, boxes, triangles and meshes, diffuse
//! colours, lights (what cannot be carried is named in a comment of the output, or
//! skipped with a comment on import).
//!
//! The conventions of every tool are in `docs/cameras-in-other-tools.md`, each backed by
//! a test.
//!
//! # Where to start reading
//!
//! [`export`] and [`import`] below pick the format. Each format's `mod.rs` states its
//! conventions and re-exports its pair; `export.rs` and `import.rs` are the two
//! directions (Blender, export only, is one file). What every exporter shares is in
//! `common.rs`: the scene as shapes in world space (`Parts`), its lights and materials
//! in the tools' terms (`Parts::lights`, `Parts::materials`, with the one rule for units
//! of light), box, plane and sphere meshes, the camera frame as a matrix. Meshes that
//! Mitsuba loads from files are written by `viewray_scene::obj_text`, colours encoded by
//! `viewray_output`'s sRGB transfer.

pub mod blender;
mod common;
pub mod gltf;
pub mod mitsuba;
pub mod pbrt;
pub mod three;

use std::fmt;
use std::path::{Path, PathBuf};

use viewray_scene::{FileKind, Scene, SceneDocument};

/// A tool viewray exchanges scenes with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Format {
    /// Mitsuba 3 XML (`mitsuba.load_file`).
    Mitsuba,
    /// A pbrt-v4 scene file.
    Pbrt,
    /// A Blender Python script (`blender -b -P OUT.py`, or `python OUT.py` with `bpy`);
    /// export only.
    Blender,
    /// A three.js JSON object (`THREE.ObjectLoader().parse`, `object.toJSON()`).
    Three,
    /// glTF 2.0, as `.gltf` (JSON, buffers embedded) or `.glb` (binary).
    Gltf,
}

impl Format {
    /// Every format, in the order the command line lists them.
    pub const ALL: [Format; 5] = [
        Format::Mitsuba,
        Format::Pbrt,
        Format::Blender,
        Format::Three,
        Format::Gltf,
    ];

    /// The name on the command line: `mitsuba`, `pbrt`, `blender`, `three`, `gltf`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Mitsuba => "mitsuba",
            Format::Pbrt => "pbrt",
            Format::Blender => "blender",
            Format::Three => "three",
            Format::Gltf => "gltf",
        }
    }

    /// The tool's name for people: "Mitsuba 3", "pbrt-v4", "Blender", "three.js",
    /// "glTF".
    pub fn tool(self) -> &'static str {
        match self {
            Format::Mitsuba => "Mitsuba 3",
            Format::Pbrt => "pbrt-v4",
            Format::Blender => "Blender",
            Format::Three => "three.js",
            Format::Gltf => "glTF",
        }
    }

    /// The format named `name` on the command line.
    pub fn from_name(name: &str) -> Option<Format> {
        Format::ALL.into_iter().find(|f| f.name() == name)
    }

    /// The format of a file to import, as viewray-scene's recogniser tells its kind from
    /// its first bytes and its name ([`FileKind::recognise`]); `None` for a file that is
    /// no tool's scene (a viewray scene, a mesh, an image) or of a kind viewray does not
    /// know.
    pub fn detect(path: &Path, bytes: &[u8]) -> Option<Format> {
        match FileKind::recognise(path, bytes)? {
            FileKind::MitsubaXml => Some(Format::Mitsuba),
            FileKind::Pbrt => Some(Format::Pbrt),
            FileKind::BlenderScript => Some(Format::Blender),
            FileKind::ThreeJson => Some(Format::Three),
            FileKind::Gltf | FileKind::Glb => Some(Format::Gltf),
            FileKind::Scene
            | FileKind::ObjMesh
            | FileKind::ObjMaterials
            | FileKind::Png
            | FileKind::Ppm
            | FileKind::Exr => None,
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.tool())
    }
}

/// What an export writes: the main file, and the files it refers to (Mitsuba 3 loads
/// meshes from files of their own), named relative to the main file's folder.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Export {
    /// The main file's bytes.
    pub main: Vec<u8>,
    /// `(file name, bytes)` of every file the main file refers to, beside it.
    pub extra_files: Vec<(String, Vec<u8>)>,
}

/// A scene another tool cannot hold as it is: names what the target lacks.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{target} {lacks}")]
pub struct ExportError {
    target: &'static str,
    lacks: String,
}

impl ExportError {
    pub(crate) fn new(format: Format, lacks: impl Into<String>) -> Self {
        Self {
            target: format.tool(),
            lacks: lacks.into(),
        }
    }

    /// The tool that cannot hold the scene, e.g. "Mitsuba 3".
    pub fn target(&self) -> &str {
        self.target
    }

    /// What the target lacks, e.g. "has no oblique camera (...)".
    pub fn lacks(&self) -> &str {
        &self.lacks
    }
}

/// A foreign file that could not be read: the file, the line and column where the format
/// has lines, and what was expected.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ImportError {
    path: PathBuf,
    position: Option<(usize, usize)>,
    message: String,
}

impl ImportError {
    pub(crate) fn new(
        path: &Path,
        position: Option<(usize, usize)>,
        message: impl Into<String>,
    ) -> Self {
        Self {
            path: path.to_path_buf(),
            position,
            message: viewray_scene::one_line(&message.into()),
        }
    }

    /// The file.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The 1-based line and column, where the format has lines.
    pub fn position(&self) -> Option<(usize, usize)> {
        self.position
    }

    /// What went wrong, without the location.
    pub fn message(&self) -> &str {
        &self.message
    }
}

impl fmt::Display for ImportError {
    /// Worded as a scene's errors are (viewray-scene's one rule for errors about files).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let position = self
            .position
            .map(|(line, column)| viewray_scene::Position { line, column });
        viewray_scene::write_file_error(f, &self.path, position, &self.message)
    }
}

impl std::error::Error for ImportError {}

/// Writes `scene` for `format`. `file_name` is the main output's file name (e.g.
/// `scene.xml`): the files it refers to are named after it.
///
/// # Errors
/// An [`ExportError`] naming what the target cannot express (the camera's projection,
/// a shift, non-square pixels, a panorama).
pub fn export(scene: &Scene, format: Format, file_name: &str) -> Result<Export, ExportError> {
    let stem = Path::new(file_name)
        .file_stem()
        .and_then(|s| s.to_str())
        .filter(|s| !s.is_empty())
        .unwrap_or("scene");
    match format {
        Format::Mitsuba => mitsuba::export(scene, stem),
        Format::Pbrt => pbrt::export(scene).map(Export::single),
        Format::Blender => blender::export(scene).map(Export::single),
        Format::Three => three::export(scene).map(Export::single),
        Format::Gltf => {
            let binary = Path::new(file_name)
                .extension()
                .is_some_and(|e| e.eq_ignore_ascii_case("glb"));
            gltf::export(scene, binary).map(Export::single)
        }
    }
}

impl Export {
    fn single(main: Vec<u8>) -> Self {
        Self {
            main,
            extra_files: Vec::new(),
        }
    }
}

/// Reads the camera (and the scene, where the format has one) of a `format` file whose
/// contents are `bytes`. `path` names it in errors and is where relative mesh files are
/// found (Mitsuba's `obj` shapes become `Mesh` objects with absolute paths).
///
/// # Errors
/// An [`ImportError`] naming the file (and line where the format has lines) and what was
/// expected.
pub fn import(bytes: &[u8], path: &Path, format: Format) -> Result<SceneDocument, ImportError> {
    match format {
        Format::Mitsuba => mitsuba::import(text(bytes, path)?, path),
        Format::Pbrt => pbrt::import(text(bytes, path)?, path),
        Format::Three => three::import(text(bytes, path)?, path),
        Format::Gltf => gltf::import(bytes, path),
        Format::Blender => Err(ImportError::new(
            path,
            None,
            "a Blender script cannot be imported: export the scene from Blender as glTF \
             (File > Export > glTF 2.0) and import that",
        )),
    }
}

fn text<'a>(bytes: &'a [u8], path: &Path) -> Result<&'a str, ImportError> {
    let text = std::str::from_utf8(bytes)
        .map_err(|_| ImportError::new(path, None, "is not a text file (not UTF-8)"))?;
    Ok(text.strip_prefix('\u{feff}').unwrap_or(text))
}
