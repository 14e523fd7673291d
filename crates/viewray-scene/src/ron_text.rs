//! The RON dialect of scene files, and RON's errors in the scene format's words.
//!
//! A scene file is read in steps (the whole file, then each value kept as raw text), so
//! every slice is parsed with its [`Origin`] in the file, and [`parse`] turns a RON error
//! in the slice into a [`SceneError`] at the file's line and column, worded as a sentence
//! that says what was found and what was expected ([`ron_error`]).

use std::path::Path;

use ron::error::{Error as RonError, SpannedError};
use serde::Deserialize;

use crate::{Position, SceneError};

/// RON as scene files use it: optional fields are written bare, `look_at: (0, 0, 0)`
/// rather than `look_at: Some((0, 0, 0))`.
fn ron_options() -> ron::Options {
    ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
}

/// Parses `text`, a slice of the scene file `path` starting at `origin`, as a `T`, its
/// errors placed in the file.
pub(crate) fn parse<'a, T: Deserialize<'a>>(
    text: &'a str,
    origin: Origin,
    path: &Path,
) -> Result<T, SceneError> {
    ron_options()
        .from_str(text)
        .map_err(|e| ron_error(path, text, origin, &e))
}

/// Where a piece of text starts inside the scene file, so positions in it can be turned
/// into positions in the file.
#[derive(Clone, Copy)]
pub(crate) struct Origin {
    line: usize,
    column: usize,
}

impl Origin {
    /// The start of the file.
    pub(crate) const FILE: Origin = Origin { line: 1, column: 1 };

    /// The file position of `position` (1-based, relative to this origin).
    fn offset(self, line: usize, column: usize) -> Position {
        if line <= 1 {
            Position {
                line: self.line,
                column: self.column + column.saturating_sub(1),
            }
        } else {
            Position {
                line: self.line + line - 1,
                column,
            }
        }
    }

    /// Where this origin is, as a file position.
    pub(crate) fn position(self) -> Position {
        Position {
            line: self.line,
            column: self.column,
        }
    }
}

/// Where each line of a file starts, so that the position of any slice of it is found
/// in `O(log lines)`: a scene of many objects looks up one position per object, and
/// counting lines from the start for each made loading quadratic.
pub(crate) struct LineIndex<'a> {
    text: &'a str,
    /// The byte offset of each line's first character; the first line starts at 0.
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    /// The index of `text`'s lines.
    pub(crate) fn new(text: &'a str) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(newline, _)| newline + 1))
            .collect();
        Self { text, starts }
    }

    /// Where `part`, a slice of the indexed text, starts: its 1-based line, and its
    /// column counted in characters.
    pub(crate) fn origin_of(&self, part: &str) -> Origin {
        let offset = (part.as_ptr() as usize)
            .saturating_sub(self.text.as_ptr() as usize)
            .min(self.text.len());
        // The number of lines starting at or before `offset` is `offset`'s line.
        let line = self.starts.partition_point(|&start| start <= offset);
        let line_start = self.starts[line - 1];
        let column = self
            .text
            .get(line_start..offset)
            .map_or(0, |before| before.chars().count());
        Origin {
            line,
            column: column + 1,
        }
    }
}

/// A RON error in `text` (which starts at `origin` in the file) as a [`SceneError`], its
/// position moved from `origin`-relative to the file and its message in the scene
/// format's words.
fn ron_error(path: &Path, text: &str, origin: Origin, error: &SpannedError) -> SceneError {
    let start = error.span.start;
    if let Some((line, column, message)) = number_error(text, error) {
        return SceneError::at(path, Some(origin.offset(line, column)), message);
    }
    let position = origin.offset(start.line, start.col);
    SceneError::at(path, Some(position), describe(&error.code))
}

/// What to say about an empty scene file, or one that holds only comments (after its
/// name, as "is not a text file" is).
pub(crate) fn empty_file_message(text: &str) -> String {
    let what = if text.trim().is_empty() {
        "is empty"
    } else {
        "holds only comments"
    };
    format!(
        "{what}: a scene is one value in parentheses, at least \
         `(camera: Front(target: (0.0, 0.0, 0.0), size: 2.0))`"
    )
}

/// The mistakes with whole numbers that RON words in its own terms: something else
/// where a whole number is expected (`width: "wide"`), a decimal point (`width: 8.0`,
/// which RON reads as `8` followed by a stray `.0`), and a negative or huge whole number
/// (`width: -8`). Returns the 1-based
/// line and column of the number in `text` and the message.
fn number_error(text: &str, error: &SpannedError) -> Option<(usize, usize, String)> {
    let at = byte_offset(text, error.span.start.line, error.span.start.col)?;
    if error.code == RonError::ExpectedInteger {
        let name = field_before(&text[..at])?;
        let (line, column) = (error.span.start.line, error.span.start.col);
        return Some((line, column, format!("`{name}` must be a whole number")));
    }
    let (start, token) = number_around(text, at)?;
    let field = field_before(&text[..start]);
    let message = match error.code {
        // `8.0`: the parser stops at the `.`, right after the digits of a whole number.
        RonError::ExpectedComma
            if text[..at].ends_with(|c: char| c.is_ascii_digit())
                && token.contains(['.', 'e', 'E'])
                && token.parse::<f64>().is_ok() =>
        {
            match field {
                Some(name) => format!("`{name}` must be a whole number, found `{token}`"),
                None => format!("expected a whole number, found `{token}`"),
            }
        }
        RonError::IntegerOutOfBounds if token.starts_with('-') => match field {
            Some(name) => format!("`{name}` must be a positive whole number, found `{token}`"),
            None => format!("expected a positive whole number, found `{token}`"),
        },
        RonError::IntegerOutOfBounds => match field {
            Some(name) => format!("`{name}` is out of range: `{token}` is too large"),
            None => format!("`{token}` is too large"),
        },
        _ => return None,
    };
    let before = &text[..start];
    let line = 1 + before.matches('\n').count();
    let column = 1 + before
        .rsplit_once('\n')
        .map_or(before, |(_, last)| last)
        .chars()
        .count();
    Some((line, column, message))
}

/// The byte offset in `text` of the 1-based `line` and character `column`.
fn byte_offset(text: &str, line: usize, column: usize) -> Option<usize> {
    let line_start = if line <= 1 {
        0
    } else {
        text.match_indices('\n').nth(line - 2).map(|(i, _)| i + 1)?
    };
    let rest = &text[line_start..];
    let within = rest
        .char_indices()
        .map(|(i, _)| i)
        .chain(std::iter::once(rest.len()))
        .nth(column.checked_sub(1)?)?;
    Some(line_start + within)
}

/// The number written around byte `at` of `text`: its start and its text.
fn number_around(text: &str, at: usize) -> Option<(usize, &str)> {
    let is_number_char = |c: char| c.is_ascii_alphanumeric() || "+-._".contains(c);
    let start = text[..at]
        .char_indices()
        .rev()
        .take_while(|&(_, c)| is_number_char(c))
        .last()
        .map_or(at, |(i, _)| i);
    let end = text[at..]
        .char_indices()
        .find(|&(_, c)| !is_number_char(c))
        .map_or(text.len(), |(i, _)| at + i);
    let token = &text[start..end];
    token
        .trim_start_matches(['+', '-'])
        .starts_with(|c: char| c.is_ascii_digit())
        .then_some((start, token))
}

/// The name of the field whose value starts right after `before` (`width` in
/// `(width: `), if the value is a field's.
fn field_before(before: &str) -> Option<&str> {
    let before = before.trim_end().strip_suffix(':')?.trim_end();
    let name_start = before
        .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .map_or(0, |i| i + 1);
    let name = &before[name_start..];
    (!name.is_empty()).then_some(name)
}

/// The name a scene file's author knows a RON struct or enum by.
fn user_name(outer: Option<&String>) -> String {
    match outer.map(String::as_str) {
        None | Some("scene") => "the scene".to_owned(),
        Some(name) => format!("`{name}`"),
    }
}

/// `a`, `b` or `c`, each in backquotes; `nothing` for none.
pub(crate) fn list(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    match quoted.as_slice() {
        [] => "nothing".to_owned(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// A sentence for a RON error, saying what was found and what was expected.
fn describe(code: &RonError) -> String {
    match code {
        RonError::NoSuchEnumVariant {
            expected,
            found,
            outer,
        } => format!(
            "unknown {} `{found}`, expected one of {}",
            match outer.as_deref() {
                Some(name) => name.to_owned(),
                None => "variant".to_owned(),
            },
            list(expected)
        ),
        RonError::NoSuchStructField {
            expected,
            found,
            outer,
        } => format!(
            "unknown field `{found}` in {}, expected {}",
            user_name(outer.as_ref()),
            list(expected)
        ),
        RonError::MissingStructField { field, outer } => {
            format!("missing field `{field}` in {}", user_name(outer.as_ref()))
        }
        RonError::DuplicateStructField { field, outer } => {
            format!(
                "field `{field}` appears twice in {}",
                user_name(outer.as_ref())
            )
        }
        RonError::ExpectedDifferentLength { expected, found } => {
            format!("expected {expected}, found {found} elements")
        }
        RonError::Eof => "unexpected end of file".to_owned(),
        RonError::ExpectedInteger => "expected a whole number".to_owned(),
        RonError::ExpectedFloat => "expected a number".to_owned(),
        RonError::ExpectedNamedStructLike("scene") => {
            "expected `(`: a scene file is one value in parentheses, \
             `(camera: .., objects: [..])`"
                .to_owned()
        }
        RonError::ExceededRecursionLimit => {
            "values are nested too deeply (more than 128 levels)".to_owned()
        }
        other => {
            // RON's own wording, as a sentence fragment like the others.
            let text = other.to_string();
            let mut chars = text.chars();
            match chars.next() {
                Some(first) => first.to_lowercase().chain(chars).collect(),
                None => text,
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_index_finds_lines_and_columns_in_characters() {
        let text = "(\n  a: 1,\n  é: (2, 3),\n\nz)";
        let index = LineIndex::new(text);
        let at = |needle: &str| {
            let start = text.find(needle).unwrap();
            let origin = index.origin_of(&text[start..]);
            (origin.line, origin.column)
        };
        assert_eq!(at("("), (1, 1));
        assert_eq!(at("a:"), (2, 3));
        // `é` is two bytes but one column: `(2` starts at column 6, not 7.
        assert_eq!(at("(2"), (3, 6));
        assert_eq!(at("3)"), (3, 10));
        assert_eq!(at("z)"), (5, 1));
        assert_eq!(at("\n\nz"), (3, 13));
    }
}
