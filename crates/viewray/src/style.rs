//! Colour on a terminal: the `error:` and `warning:` prefixes and compare's verdicts.
//!
//! Everything styled goes through anstream, which drops the colour when the stream is not
//! a terminal or when `NO_COLOR` is set (and keeps it when `CLICOLOR_FORCE` is set), so
//! piped output and files are plain text.

use std::fmt::Display;

use anstyle::{AnsiColor, Style};

/// `error:`.
const ERROR: Style = AnsiColor::Red.on_default().bold();
/// `warning:`.
const WARNING: Style = AnsiColor::Yellow.on_default().bold();
/// `note:`.
const NOTE: Style = AnsiColor::Cyan.on_default().bold();
/// A passing verdict.
pub(crate) const PASS: Style = AnsiColor::Green.on_default().bold();
/// A failing verdict.
pub(crate) const FAIL: Style = AnsiColor::Red.on_default().bold();

/// Prints `error: message` on stderr.
pub(crate) fn error(message: impl Display) {
    anstream::eprintln!("{ERROR}error:{ERROR:#} {message}");
}

/// Prints `warning: message` on stderr.
pub(crate) fn warning(message: impl Display) {
    anstream::eprintln!("{WARNING}warning:{WARNING:#} {message}");
}

/// Prints `note: message` on stderr.
pub(crate) fn note(message: impl Display) {
    anstream::eprintln!("{NOTE}note:{NOTE:#} {message}");
}

/// `text` padded to `width` characters, in `style` (the padding outside the colour, so
/// columns line up whether or not the colour is shown).
pub(crate) fn padded(style: Style, text: &str, width: usize) -> String {
    let padding = " ".repeat(width.saturating_sub(text.chars().count()));
    format!("{style}{text}{style:#}{padding}")
}

/// `text` right-aligned in `width` characters, in `style` (the padding outside the
/// colour).
pub(crate) fn padded_right(style: Style, text: &str, width: usize) -> String {
    let padding = " ".repeat(width.saturating_sub(text.chars().count()));
    format!("{padding}{style}{text}{style:#}")
}
