//! The scene crate's one error type: what went wrong, and where in which file.

use std::fmt;
use std::path::{Path, PathBuf};

use crate::FileKind;

/// A scene file that could not be loaded: the file, the position when known, and a
/// sentence saying what was found and what was expected.
///
/// Displays as `path:line:column: message`, the form compilers use, so editors and
/// terminals can jump to the spot.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SceneError {
    path: PathBuf,
    position: Option<Position>,
    message: String,
    /// The kind of file found instead of a scene file, when it is one viewray knows.
    found: Option<FileKind>,
}

/// A 1-based line and column in a scene file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub struct Position {
    /// The line, from 1.
    pub line: usize,
    /// The column in characters, from 1.
    pub column: usize,
}

impl SceneError {
    /// An error at `position` of the file `path`.
    pub(crate) fn at(path: &Path, position: Option<Position>, message: impl Into<String>) -> Self {
        Self {
            path: path.to_path_buf(),
            position,
            message: one_line(&message.into()),
            found: None,
        }
    }

    /// The file `path` is of another `kind` than a scene file: an error saying what it is
    /// and where it goes instead.
    pub(crate) fn not_a_scene(path: &Path, kind: FileKind, message: String) -> Self {
        Self {
            found: Some(kind),
            ..Self::at(path, None, message)
        }
    }

    /// The file the error is about.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Where in the file, when known.
    pub fn position(&self) -> Option<Position> {
        self.position
    }

    /// What went wrong, without the location.
    pub fn message(&self) -> &str {
        &self.message
    }

    /// The kind of file that was found where a scene file was expected, when it is
    /// another kind viewray knows ([`FileKind::recognise`]): a program can add how to
    /// turn it into a scene.
    pub fn found(&self) -> Option<FileKind> {
        self.found
    }
}

impl fmt::Display for SceneError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write_file_error(f, &self.path, self.position, &self.message)
    }
}

impl std::error::Error for SceneError {}

/// How viewray words an error about a file it reads (a scene, or another tool's file):
/// `path:line:column: message`, the position when there is one, with the path's control
/// characters escaped so that the error stays on one line.
///
/// # Errors
/// The formatter's.
pub fn write_file_error(
    f: &mut fmt::Formatter<'_>,
    path: &std::path::Path,
    position: Option<Position>,
    message: &str,
) -> fmt::Result {
    write!(f, "{}", one_line(&path.display().to_string()))?;
    if let Some(Position { line, column }) = position {
        write!(f, ":{line}:{column}")?;
    }
    write!(f, ": {message}")
}

/// `text` with control characters (a newline in a file name or a quoted string) escaped,
/// so an error stays on one line whatever the input held.
pub fn one_line(text: &str) -> String {
    text.chars()
        .flat_map(|c| {
            let escaped: Vec<char> = if c.is_control() {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            escaped
        })
        .collect()
}
