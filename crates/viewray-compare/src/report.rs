//! The HTML report: per image, expected / actual / heatmap side by side with the figures
//! and the verdict.

use std::collections::HashSet;
use std::fmt::Write as _;
use std::io;
use std::path::{Path, PathBuf};

use image::RgbaImage;
use viewray_output::{Compression, encode_png, write_atomically};

use crate::comparison::Comparison;

/// One image's row in a report.
#[derive(Clone, Copy, Debug)]
pub struct ReportEntry<'a> {
    /// The name shown, e.g. a scene or a file name; the written PNGs are named after it.
    pub name: &'a str,
    /// The expected image, if it could be read.
    pub expected: Option<&'a RgbaImage>,
    /// The actual image, if it could be read.
    pub actual: Option<&'a RgbaImage>,
    /// What became of the pair.
    pub outcome: Outcome<'a>,
}

/// What became of one pair of images.
#[derive(Clone, Copy, Debug)]
pub enum Outcome<'a> {
    /// The images were compared.
    Compared(&'a Comparison),
    /// They could not be compared (a missing file, a PNG that does not decode): the
    /// message says why. Counts as a failure.
    Error(&'a str),
}

impl<'a> ReportEntry<'a> {
    /// An entry for a pair that was compared.
    pub fn compared(
        name: &'a str,
        expected: &'a RgbaImage,
        actual: &'a RgbaImage,
        comparison: &'a Comparison,
    ) -> Self {
        Self {
            name,
            expected: Some(expected),
            actual: Some(actual),
            outcome: Outcome::Compared(comparison),
        }
    }

    /// An entry for a pair that could not be compared, with whichever images were read.
    pub fn error(
        name: &'a str,
        message: &'a str,
        expected: Option<&'a RgbaImage>,
        actual: Option<&'a RgbaImage>,
    ) -> Self {
        Self {
            name,
            expected,
            actual,
            outcome: Outcome::Error(message),
        }
    }

    /// Whether this entry passed (an error never does).
    pub fn passed(&self) -> bool {
        matches!(self.outcome, Outcome::Compared(c) if c.passed())
    }
}

/// Writes an HTML report of `entries` into `directory` (created if missing) and returns
/// the path of its page, `directory/index.html`.
///
/// Beside the page, for each entry, go `NAME.expected.png`, `NAME.actual.png` and
/// `NAME.diff.png` (the FLIP heatmap), for the images the entry has; NAME is the entry's
/// name without a `.png` extension, with characters other than letters, digits, `-`, `_`
/// and `.` replaced by `_` (and a number added when two entries would collide). Every
/// file is written atomically (a temporary file renamed into place), so a reader never
/// sees a partial file. The page has no timestamp: the same entries give the same bytes.
///
/// # Errors
/// Any I/O error creating the directory or writing a file.
pub fn write_report(
    directory: impl AsRef<Path>,
    entries: &[ReportEntry<'_>],
) -> io::Result<PathBuf> {
    let directory = directory.as_ref();
    std::fs::create_dir_all(directory)?;
    let mut used = HashSet::new();
    let mut sections = String::new();
    for entry in entries {
        let stem = unique_stem(entry.name, &mut used);
        let mut images = Vec::new();
        if let Some(expected) = entry.expected {
            let file = format!("{stem}.expected.png");
            write_atomically(
                directory.join(&file),
                &encode_png(expected, Compression::Balanced)?,
            )?;
            images.push(("expected", file, expected.width()));
        }
        if let Some(actual) = entry.actual {
            let file = format!("{stem}.actual.png");
            write_atomically(
                directory.join(&file),
                &encode_png(actual, Compression::Balanced)?,
            )?;
            images.push(("actual", file, actual.width()));
        }
        if let Outcome::Compared(Comparison {
            heatmap: Some(heatmap),
            ..
        }) = entry.outcome
        {
            let file = format!("{stem}.diff.png");
            write_atomically(
                directory.join(&file),
                &encode_png(heatmap, Compression::Balanced)?,
            )?;
            images.push(("difference (FLIP)", file, heatmap.width()));
        }
        section(&mut sections, entry, &stem, &images);
    }
    let page = page(entries, &sections);
    let path = directory.join("index.html");
    write_atomically(&path, page.as_bytes())?;
    Ok(path)
}

/// A file-name stem for `name`, distinct from those already `used`.
fn unique_stem(name: &str, used: &mut HashSet<String>) -> String {
    let base = name.strip_suffix(".png").unwrap_or(name);
    let mut stem: String = base
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect();
    if stem.is_empty() || stem.starts_with('.') {
        stem.insert(0, '_');
    }
    let mut candidate = stem.clone();
    let mut n = 2;
    while !used.insert(candidate.clone()) {
        candidate = format!("{stem}-{n}");
        n += 1;
    }
    candidate
}

/// Escapes text for HTML.
fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            c => out.push(c),
        }
    }
    out
}

/// Appends one entry's section: title and verdict, figures, images side by side.
fn section(out: &mut String, entry: &ReportEntry<'_>, stem: &str, images: &[(&str, String, u32)]) {
    let (verdict, class) = if entry.passed() {
        ("PASS", "pass")
    } else {
        ("FAIL", "fail")
    };
    let _ = writeln!(
        out,
        "<section id=\"{}\" class=\"{class}\">\n<h2><span class=\"verdict\">{verdict}</span> {}</h2>",
        escape(stem),
        escape(entry.name)
    );
    out.push_str("<table class=\"figures\">\n");
    match entry.outcome {
        Outcome::Error(message) => {
            let _ = writeln!(out, "<tr><th>error</th><td>{}</td></tr>", escape(message));
        }
        Outcome::Compared(comparison) => {
            let _ = writeln!(
                out,
                "<tr><th>mode</th><td>{}</td></tr>",
                comparison.mode.name()
            );
            if let Some(m) = comparison.metrics {
                let _ = writeln!(
                    out,
                    "<tr><th>mean FLIP</th><td>{:.4}</td></tr>\n\
                     <tr><th>peak FLIP (3&times;3)</th><td>{:.4}</td></tr>\n\
                     <tr><th>bad pixels</th><td>{} of {} (largest channel difference {}/255)</td></tr>",
                    m.mean_flip, m.peak_flip, m.bad_pixels, m.pixel_count, m.max_channel_difference
                );
            }
            if let Some(diagnosis) = comparison.diagnosis {
                for message in diagnosis.messages() {
                    let _ = writeln!(
                        out,
                        "<tr><th>diagnosis</th><td class=\"diagnosis\">{}</td></tr>",
                        escape(&message)
                    );
                }
            }
            for failure in &comparison.failures {
                let _ = writeln!(
                    out,
                    "<tr><th>failed</th><td>{}</td></tr>",
                    escape(&failure.to_string())
                );
            }
        }
    }
    out.push_str("</table>\n<div class=\"images\">\n");
    for &(caption, ref file, width) in images {
        // Small renders are shown enlarged, pixel for pixel; large ones fit the column.
        let shown = (width * (480 / width.max(1)).clamp(1, 4)).min(480);
        let _ = writeln!(
            out,
            "<figure><a href=\"{file}\"><img src=\"{file}\" alt=\"{caption}\" style=\"width: {shown}px\"></a><figcaption>{caption}</figcaption></figure>",
            file = escape(file),
        );
    }
    out.push_str("</div>\n</section>\n");
}

/// The whole page around the sections.
fn page(entries: &[ReportEntry<'_>], sections: &str) -> String {
    let failed: Vec<&ReportEntry<'_>> = entries.iter().filter(|e| !e.passed()).collect();
    let mut out = String::new();
    out.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>viewray image comparison</title>\n<style>\n",
    );
    out.push_str(STYLE);
    out.push_str("</style>\n</head>\n<body>\n<h1>viewray image comparison</h1>\n");
    let errors = entries
        .iter()
        .filter(|e| matches!(e.outcome, Outcome::Error(_)))
        .count();
    let not_compared = if errors > 0 {
        format!(", {errors} could not be compared")
    } else {
        String::new()
    };
    let _ = writeln!(
        out,
        "<p class=\"summary\">{} passed, {} failed{not_compared}, of {}.</p>",
        entries.len() - failed.len(),
        failed.len() - errors,
        entries.len()
    );
    if !failed.is_empty() {
        out.push_str("<p>Failed:");
        let mut used = HashSet::new();
        for entry in entries {
            let stem = unique_stem(entry.name, &mut used);
            if !entry.passed() {
                let _ = write!(
                    out,
                    " <a href=\"#{}\">{}</a>",
                    escape(&stem),
                    escape(entry.name)
                );
            }
        }
        out.push_str("</p>\n");
    }
    out.push_str(
        "<p class=\"legend\">Difference: FLIP error per pixel, <span class=\"ramp\"></span> \
         from black (none) to pale yellow (largest).</p>\n",
    );
    out.push_str(sections);
    out.push_str("</body>\n</html>\n");
    out
}

const STYLE: &str = "\
body { font-family: system-ui, sans-serif; margin: 2em; color: #222; background: #fafafa; }
h1 { font-size: 1.5em; }
h2 { font-size: 1.15em; margin: 0 0 0.5em; }
section { background: #fff; border: 1px solid #ddd; border-left: 6px solid #2a2; padding: 1em; margin: 1em 0; }
section.fail { border-left-color: #c22; }
.verdict { display: inline-block; padding: 0 0.4em; border-radius: 3px; color: #fff; background: #2a2; }
section.fail .verdict { background: #c22; }
.figures th { text-align: left; padding-right: 1em; font-weight: normal; color: #666; vertical-align: top; }
.diagnosis { font-weight: bold; }
.images { display: flex; flex-wrap: wrap; gap: 1em; margin-top: 0.8em; }
figure { margin: 0; }
figure img { image-rendering: pixelated; border: 1px solid #ccc; display: block; }
figcaption { color: #666; font-size: 0.9em; text-align: center; }
.ramp { display: inline-block; width: 8em; height: 0.8em; vertical-align: middle;
  background: linear-gradient(to right, #000004, #3b0f70, #8c2981, #de4968, #fe9f6d, #fcfdbf); }
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stems_are_safe_file_names_and_never_collide() {
        let mut used = HashSet::new();
        assert_eq!(unique_stem("perspective.png", &mut used), "perspective");
        assert_eq!(unique_stem("perspective", &mut used), "perspective-2");
        assert_eq!(unique_stem("a b/c<d>.png", &mut used), "a_b_c_d_");
        assert_eq!(unique_stem("../x", &mut used), "_.._x");
        assert_eq!(unique_stem("", &mut used), "_");
    }

    #[test]
    fn html_special_characters_are_escaped() {
        assert_eq!(
            escape("<a href=\"x\">&'"),
            "&lt;a href=&quot;x&quot;&gt;&amp;&#39;"
        );
    }
}
