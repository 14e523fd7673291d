//! Where a scene comes from: a file, standard input (`-`), or the built-in default; and a
//! scene's error as the command prints it.

use std::io::IsTerminal;
use std::path::Path;

use anyhow::{Result, anyhow};
use viewray_scene::{FileKind, LoadOptions, LoadedScene, SceneError, SceneLoader};

use crate::values::is_standard_stream;

/// The scene rendered when no scene file is given. It uses only analytic shapes, so it
/// needs no other file and works from any directory.
pub(crate) const DEFAULT_SCENE: &str = include_str!("../../../fixtures/default.ron");

/// The name the default scene goes by in error messages.
pub(crate) const DEFAULT_SCENE_PATH: &str = "fixtures/default.ron";

/// The name standard input goes by in error messages. Meshes it names are found
/// relative to the current folder (the folder of a bare name).
pub(crate) const STDIN_NAME: &str = "<stdin>";

/// Loads the scene `path` names (`-`: standard input), or the default scene for `None`.
///
/// # Errors
/// The scene's error: the file, line and column, and what is wrong.
pub(crate) fn load_scene(path: Option<&Path>, options: LoadOptions) -> Result<LoadedScene> {
    let loader = match path {
        None => SceneLoader::text(DEFAULT_SCENE, Path::new(DEFAULT_SCENE_PATH)),
        Some(path) if is_standard_stream(path) => {
            let stdin = std::io::stdin();
            if stdin.is_terminal() {
                crate::style::note(
                    "reading the scene from standard input: type or paste it, then press \
                     Ctrl-D (or give a file name instead of -)",
                );
            }
            SceneLoader::reader(stdin.lock(), Path::new(STDIN_NAME))
        }
        Some(path) => SceneLoader::file(path),
    };
    loader.options(options).load().map_err(scene_error)
}

/// Loads the scene `path` names (`-`: standard input) as it is.
///
/// # Errors
/// The scene's error: the file, line and column, and what is wrong.
pub(crate) fn load_scene_file(path: &Path) -> Result<viewray_scene::Scene> {
    load_scene(Some(path), LoadOptions::default()).map(|loaded| loaded.scene)
}

/// The name a SCENE argument goes by in messages: `<stdin>` for `-`.
pub(crate) fn scene_name(path: &Path) -> String {
    if is_standard_stream(path) {
        STDIN_NAME.to_owned()
    } else {
        path.display().to_string()
    }
}

/// A scene's error as the command prints it: another tool's scene given as a scene
/// comes with the command that converts it.
pub(crate) fn scene_error(error: SceneError) -> anyhow::Error {
    match error.found() {
        Some(
            FileKind::MitsubaXml
            | FileKind::Pbrt
            | FileKind::ThreeJson
            | FileKind::Gltf
            | FileKind::Glb,
        ) => anyhow!(
            "{error}: `viewray import {} > scene.ron` turns it into one",
            error.path().display()
        ),
        _ => error.into(),
    }
}
