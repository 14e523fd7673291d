//! Numbers as text: every way viewray writes a number, each rule written once.
//!
//! There are three rules because there are three kinds of reader, and none of them ever
//! sees minus zero (`-0.0001` rounds to `0`, not `-0`; a computed `-0.0` is `0`):
//!
//! | rule | reader | text |
//! |---|---|---|
//! | [`label`], [`label_significant`] | people: figure labels and captions | at most three decimals (or three significant digits), no trailing zeros, a true minus sign `−` |
//! | [`SvgNumber`] | an SVG reader: coordinates in figure pixels | at most two decimals, no trailing zeros, the ASCII `-` of SVG's number syntax |
//! | [`round_trip`], [`round_trip_f32`], [`without_minus_zero`] | programs that read the value back: other tools' scene files, JSON | the shortest text that reads back as the same float |
//!
//! They differ where their readers do. A label rounds to what a person compares (a
//! thousandth of the lecture's units) and is typeset, so its minus is U+2212. An SVG
//! coordinate needs no more than a hundredth of a pixel, and its text is the shortest that
//! reads back as the rounded `f32` the drawing holds. A value another program computes
//! with must come back bit for bit, so nothing is rounded at all.

use std::fmt::{self, Display};

/// The minus sign of typeset text (U+2212), wider than a hyphen.
const MINUS: char = '\u{2212}';

/// `x` for a label people read: at most three decimals (rounded half away from zero),
/// no trailing zeros, a true minus sign, never minus zero.
///
/// ```
/// use viewray_output::number::label;
///
/// assert_eq!(label(0.199_999_999), "0.2");
/// assert_eq!(label(-1.0), "\u{2212}1");
/// assert_eq!(label(-0.0001), "0");
/// ```
pub fn label(x: f64) -> String {
    fixed((x * 1000.0).round() / 1000.0, 3)
}

/// `x` for a label, as [`label`] writes it, but to three significant digits below 0.1,
/// so that a small value keeps its digits: a viewport of 0.0009 reads 0.0009, not 0.001.
///
/// ```
/// use viewray_output::number::label_significant;
///
/// assert_eq!(label_significant(1.994_3), "1.994");
/// assert_eq!(label_significant(0.000_123_45), "0.000123");
/// ```
pub fn label_significant(x: f64) -> String {
    if x == 0.0 || !x.is_finite() || x.abs() >= 0.1 {
        return label(x);
    }
    // Three significant digits: 0.0123 has two zeros after the point.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let decimals = (2.0 - x.abs().log10().floor()).clamp(3.0, 15.0) as usize;
    fixed(x, decimals)
}

/// `|x|` to `decimals` decimals (Rust's rounding of the exact value), trailing zeros and
/// point dropped, after a true minus sign where `x` is negative and the text is not `0`.
fn fixed(x: f64, decimals: usize) -> String {
    let text = format!("{:.*}", decimals, x.abs());
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if x < 0.0 && text != "0" {
        format!("{MINUS}{text}")
    } else {
        text.to_owned()
    }
}

/// A number in an SVG attribute (a coordinate or a length in figure pixels, an angle in
/// degrees): rounded to two decimals (half away from zero), then the
/// shortest text that reads back as that `f32`, so no trailing zeros; `-` for negatives,
/// never minus zero.
///
/// ```
/// use viewray_output::number::SvgNumber;
///
/// assert_eq!(SvgNumber(1599.999).to_string(), "1600");
/// assert_eq!(SvgNumber(-0.25).to_string(), "-0.25");
/// assert_eq!(SvgNumber(-0.001).to_string(), "0");
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SvgNumber(pub f32);

impl Display for SvgNumber {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let rounded = (self.0 * 100.0).round() / 100.0;
        if rounded == 0.0 {
            f.write_str("0")
        } else {
            write!(f, "{rounded}")
        }
    }
}

/// `x` with minus zero made zero, every other value as it is (`x + 0.0`): for a writer
/// that formats the float itself, as JSON's does.
pub fn without_minus_zero(x: f64) -> f64 {
    x + 0.0
}

/// The shortest text that reads back as the same `f64` (Rust's `{:?}`: `1.0`, `0.1`,
/// `1e-7`), minus zero written `0.0`: for files other programs compute with.
///
/// ```
/// use viewray_output::number::round_trip;
///
/// assert_eq!(round_trip(0.1), "0.1");
/// assert_eq!(round_trip(-0.0), "0.0");
/// ```
pub fn round_trip(x: f64) -> String {
    format!("{:?}", without_minus_zero(x))
}

/// The shortest text that reads back as the same `f32`, minus zero written `0.0` (see
/// [`round_trip`]).
pub fn round_trip_f32(x: f32) -> String {
    format!("{:?}", x + 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every rule's text for `x`, as a table row: `[label, label_significant, svg, round_trip]`.
    #[track_caller]
    fn check(x: f64, expected: [&str; 4]) {
        // The SVG rule works on the drawing's `f32`.
        #[allow(clippy::cast_possible_truncation)]
        let svg = SvgNumber(x as f32).to_string();
        let got = [label(x), label_significant(x), svg, round_trip(x)];
        assert_eq!(got, expected.map(str::to_owned), "{x:e}");
    }

    #[test]
    fn each_rule_writes_its_readers_digits() {
        check(0.2, ["0.2", "0.2", "0.2", "0.2"]);
        check(0.199_999_999, ["0.2", "0.2", "0.2", "0.199999999"]);
        check(-1.0, ["\u{2212}1", "\u{2212}1", "-1", "-1.0"]);
        check(3.0, ["3", "3", "3", "3.0"]);
        check(12.5, ["12.5", "12.5", "12.5", "12.5"]);
        check(-0.25, ["\u{2212}0.25", "\u{2212}0.25", "-0.25", "-0.25"]);
        check(1.23456, ["1.235", "1.235", "1.23", "1.23456"]);
        check(1.994_3, ["1.994", "1.994", "1.99", "1.9943"]);
        check(1599.999, ["1599.999", "1599.999", "1600", "1599.999"]);
        check(0.45, ["0.45", "0.45", "0.45", "0.45"]);
        check(0.1, ["0.1", "0.1", "0.1", "0.1"]);
        // Below 0.1 only the significant-digit label keeps digits a label would round.
        check(0.05, ["0.05", "0.05", "0.05", "0.05"]);
        check(0.001_6, ["0.002", "0.0016", "0", "0.0016"]);
        check(0.000_9, ["0.001", "0.0009", "0", "0.0009"]);
        check(0.000_123_45, ["0", "0.000123", "0", "0.00012345"]);
        check(
            -0.012_34,
            ["\u{2212}0.012", "\u{2212}0.0123", "-0.01", "-0.01234"],
        );
        check(1e-7, ["0", "0.0000001", "0", "1e-7"]);
        // Half-way cases round away from zero in the labels and the SVG rule.
        check(0.0625, ["0.063", "0.0625", "0.06", "0.0625"]);
        check(0.125, ["0.125", "0.125", "0.13", "0.125"]);
    }

    #[test]
    fn no_rule_writes_minus_zero() {
        check(0.0, ["0", "0", "0", "0.0"]);
        check(-0.0, ["0", "0", "0", "0.0"]);
        check(-0.0001, ["0", "\u{2212}0.0001", "0", "-0.0001"]);
        check(-0.001, ["\u{2212}0.001", "\u{2212}0.001", "0", "-0.001"]);
        check(-0.004, ["\u{2212}0.004", "\u{2212}0.004", "0", "-0.004"]);
        // Too small for even fifteen decimals: zero, without a sign.
        check(-1e-20, ["0", "0", "0", "-1e-20"]);
        assert_eq!(round_trip_f32(-0.0), "0.0");
        assert_eq!(round_trip_f32(-0.1), "-0.1");
        assert_eq!(without_minus_zero(-0.0).to_bits(), 0.0_f64.to_bits());
        assert_eq!(without_minus_zero(-2.5), -2.5);
    }

    #[test]
    fn infinities_and_nan_are_named() {
        check(f64::INFINITY, ["inf", "inf", "inf", "inf"]);
        check(
            f64::NEG_INFINITY,
            ["\u{2212}inf", "\u{2212}inf", "-inf", "-inf"],
        );
        check(f64::NAN, ["NaN", "NaN", "NaN", "NaN"]);
    }
}
