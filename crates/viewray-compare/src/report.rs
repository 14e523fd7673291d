//! The HTML report: per pair, expected / actual / heatmap side by side, the verdict the
//! terminal printed, and every figure with what it means and the rule it was held to.
//!
//! The page is a maud template (which escapes every string it is given); it has no
//! timestamp, so the same report gives the same bytes.

use std::collections::HashSet;
use std::io;
use std::path::{Path, PathBuf};

use image::RgbaImage;
use maud::{Markup, html};
use viewray_output::{Compression, encode_png, write_atomically};

use crate::comparison::{Comparison, Metrics};
use crate::golden::Thresholds;
use crate::instructor::InstructorThresholds;
use crate::outcome::{Outcome, Verdict};
use crate::page::{report_page, verdict_badge};

/// A report: what it is about, what the terminal said, the rules, and the pairs.
#[derive(Clone, Copy, Debug)]
pub struct Report<'a> {
    /// The page's heading, e.g. `viewray compare reference/ submissions/alice/`.
    pub title: &'a str,
    /// The summary line the terminal printed, shown as is, so that the page and the
    /// terminal say the same thing.
    pub summary: &'a str,
    /// The rules the pairs were judged by: the page states them, and holds each figure
    /// against its threshold.
    pub rules: Rules,
    /// The pairs, in the order the terminal listed them.
    pub entries: &'a [ReportEntry<'a>],
}

/// The rules a report's pairs were judged by.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rules {
    /// [`crate::compare`] with these thresholds: the golden check.
    Golden(Thresholds),
    /// [`crate::judge`] with these thresholds: `viewray compare`.
    Instructor(InstructorThresholds),
}

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
    pub outcome: &'a Outcome,
}

impl<'a> ReportEntry<'a> {
    /// An entry for the pair `name`, with whichever images were read.
    pub fn new(
        name: &'a str,
        expected: Option<&'a RgbaImage>,
        actual: Option<&'a RgbaImage>,
        outcome: &'a Outcome,
    ) -> Self {
        Self {
            name,
            expected,
            actual,
            outcome,
        }
    }

    /// The pair's verdict.
    fn verdict(&self) -> Verdict {
        self.outcome.verdict()
    }
}

/// Writes the HTML report into `directory` (created if missing) and returns the path of
/// its page, `directory/index.html`.
///
/// Beside the page, for each entry, go `NAME.expected.png`, `NAME.actual.png` and
/// `NAME.diff.png` (the FLIP heatmap), for the images the entry has; NAME is the entry's
/// name without a `.png` extension, with characters other than letters, digits, `-`, `_`
/// and `.` replaced by `_` (and a number added when two entries would collide). Every
/// file is written atomically (viewray-output), so a reader never sees a partial file.
/// The page has no timestamp: the same report gives the same bytes.
///
/// # Errors
/// Any I/O error creating the directory or writing a file; a file's error names it.
pub fn write_report(directory: impl AsRef<Path>, report: &Report<'_>) -> io::Result<PathBuf> {
    let directory = directory.as_ref();
    std::fs::create_dir_all(directory)?;
    let mut used = HashSet::new();
    let mut sections = Vec::new();
    for entry in report.entries {
        let stem = unique_stem(entry.name, &mut used);
        let mut images = Vec::new();
        let mut add = |role: Role, file: String, pixels: Vec<u8>, width: u32| {
            write_atomically(directory.join(&file), &pixels)?;
            images.push(Picture { role, file, width });
            io::Result::Ok(())
        };
        if let Some(expected) = entry.expected {
            let png = encode_png(expected, Compression::Balanced)?;
            add(
                Role::Expected,
                format!("{stem}.expected.png"),
                png,
                expected.width(),
            )?;
        }
        if let Some(actual) = entry.actual {
            let png = encode_png(actual, Compression::Balanced)?;
            add(
                Role::Actual,
                format!("{stem}.actual.png"),
                png,
                actual.width(),
            )?;
        }
        if let Some(comparison) = entry.outcome.comparison()
            && let Some(heatmap) = comparison.heatmap()
        {
            let png = encode_png(&heatmap, Compression::Balanced)?;
            add(
                Role::Difference,
                format!("{stem}.diff.png"),
                png,
                heatmap.width(),
            )?;
        }
        sections.push(Section {
            entry,
            stem,
            images,
        });
    }
    let page = page(report, &sections).into_string();
    let path = directory.join("index.html");
    write_atomically(&path, page.as_bytes())?;
    Ok(path)
}

/// One entry with the files written for it.
struct Section<'a> {
    entry: &'a ReportEntry<'a>,
    stem: String,
    images: Vec<Picture>,
}

/// An image written beside the page.
struct Picture {
    role: Role,
    file: String,
    width: u32,
}

#[derive(Clone, Copy)]
enum Role {
    Expected,
    Actual,
    Difference,
}

/// A file-name stem for the image `name` in a report folder: `name` without `.png`, every
/// character but ASCII letters, digits, `-`, `_` and `.` made `_`, never hidden, and
/// distinct from the stems already `used` whatever the case of their letters (a report
/// folder may sit on a file system that ignores it): `-2`, `-3`, ... added when needed.
pub fn unique_stem(name: &str, used: &mut HashSet<String>) -> String {
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
    while !used.insert(candidate.to_ascii_lowercase()) {
        candidate = format!("{stem}-{n}");
        n += 1;
    }
    candidate
}

/// What each figure means: the legend's text and each figure's title (hover) text.
mod meaning {
    pub(super) const PEAK_FLIP: &str = "FLIP (NVIDIA's perceptual difference: 0 identical, \
        1 black against white) averaged over the worst 3 x 3-pixel window: how bad the worst \
        small region looks, while a lone stray pixel counts for a ninth.";
    pub(super) const MEAN_FLIP: &str =
        "FLIP averaged over the whole image: a change spread thin over every pixel.";
    pub(super) const DIFFERING_PIXELS: &str = "Pixels where some channel (R, G, B or A) \
        differs by more than the channel tolerance, counted on the images as stored.";
    pub(super) const LARGEST_DIFFERENCE: &str =
        "The largest difference of any channel of any pixel, in 8-bit codes.";
    pub(super) const CAMERA: &str = "The systematic transform between the two pictures \
        (a move, a scale about the centre, a mirror), estimated from the blurred images: a \
        camera mistake moves the whole picture, where sampling noise does not.";
    pub(super) const HEATMAP: &str = "The FLIP error of each pixel, from black (none) to \
        pale yellow (the largest).";
}

/// The whole page.
fn page(report: &Report<'_>, sections: &[Section<'_>]) -> Markup {
    let listed = |verdict: Verdict| -> Vec<&Section<'_>> {
        sections
            .iter()
            .filter(|s| s.entry.verdict() == verdict)
            .collect()
    };
    let body = html! {
        h1 { (report.title) }
        p.summary { (report.summary) }
        @for verdict in [Verdict::Fail, Verdict::Error] {
            @let names = listed(verdict);
            @if !names.is_empty() {
                p.index {
                    (verdict_badge(verdict))
                    @for section in names {
                        " " a href={ "#" (section.stem) } { (section.entry.name) }
                    }
                }
            }
        }
        (rules(report.rules))
        @for section in sections {
            (entry_section(section, report.rules))
        }
    };
    report_page(report.title, STYLE, body)
}

/// How the pairs were judged: the verdicts, the rule, and what each figure means.
fn rules(rules: Rules) -> Markup {
    html! {
        section.rules {
            h2 { "How to read this page" }
            dl {
                dt { (verdict_badge(Verdict::Pass)) }
                dd { (match rules {
                    Rules::Instructor(_) => "The render shows the reference's picture: \
                        antialiasing and the sample count are not errors.",
                    Rules::Golden(_) => "The image matches its golden image up to \
                        last-bit floating-point noise.",
                }) }
                dt { (verdict_badge(Verdict::Fail)) }
                dd { (match rules {
                    Rules::Instructor(_) => "Judged different, or the render is missing, \
                        unreadable or not a PNG: the reasons are under the image.",
                    Rules::Golden(_) => "Compared, and judged different: the reasons are \
                        under the image.",
                }) }
                @if let Rules::Golden(_) = rules {
                    dt { (verdict_badge(Verdict::Error)) }
                    dd { "Not compared: no golden image yet, an unreadable one, or an image \
                        that could not be made." }
                }
            }
            p { (rule_sentence(rules)) }
            dl.legend {
                dt { "peak FLIP" } dd { (meaning::PEAK_FLIP) }
                dt { "mean FLIP" } dd { (meaning::MEAN_FLIP) }
                dt { "pixels that differ" }
                dd { (meaning::DIFFERING_PIXELS) " The tolerance: " (channel_tolerance(rules)) " of 255." }
                dt { "largest difference" } dd { (meaning::LARGEST_DIFFERENCE) }
                @if let Rules::Instructor(_) = rules {
                    dt { "camera" } dd { (meaning::CAMERA) }
                }
                dt { "difference" }
                dd { span.ramp {} " " (meaning::HEATMAP) }
            }
        }
    }
}

/// The channel difference, in 8-bit codes, beyond which a pixel counts as differing.
fn channel_tolerance(rules: Rules) -> u8 {
    match rules {
        Rules::Golden(t) => t.channel_tolerance,
        Rules::Instructor(_) => Thresholds::GOLDEN.channel_tolerance,
    }
}

/// The rule a pair must meet to pass, in one sentence.
fn rule_sentence(rules: Rules) -> String {
    match rules {
        Rules::Instructor(t) => format!(
            "Judged as an instructor would: both images are blurred by {} px in linear \
             light, so that sampling noise cancels, and compared with FLIP. A pair passes \
             when the peak FLIP of the blurred images is at most {} and the picture is not \
             moved by more than {} px, scaled by more than {}% or mirrored (a camera \
             mistake). The other figures are shown to explain, not judged.",
            t.blur_sigma,
            t.max_peak_flip,
            t.max_shift,
            t.max_scale_error * 100.0
        ),
        Rules::Golden(t) => format!(
            "Golden check: an image passes when at most {}% of its pixels (and at least {}) \
             differ by more than {}/255 in a channel, its mean FLIP is at most {} and its \
             peak FLIP at most {}.",
            t.bad_pixel_fraction * 100.0,
            t.min_allowed_bad_pixels,
            t.channel_tolerance,
            t.max_mean_flip,
            t.max_peak_flip
        ),
    }
}

/// One figure's row: its name (with its meaning as title text), its value, and the rule
/// it is held to with whether it meets it (`None`: shown, not judged).
struct Figure {
    name: &'static str,
    meaning: &'static str,
    value: String,
    rule: String,
    meets: Option<bool>,
}

/// The figures of a comparison, in the order they matter under `rules`.
fn figures(metrics: &Metrics, comparison: &Comparison, rules: Rules) -> Vec<Figure> {
    let percent = 100.0 * metrics.bad_pixels as f64 / metrics.pixel_count.max(1) as f64;
    let differing = format!(
        "{} of {} ({percent:.1}%)",
        metrics.bad_pixels, metrics.pixel_count
    );
    let largest = format!("{} of 255", metrics.max_channel_difference);
    let not_judged = |why: &str| why.to_owned();
    match rules {
        Rules::Instructor(t) => vec![
            Figure {
                name: "peak FLIP",
                meaning: meaning::PEAK_FLIP,
                value: format!("{:.3}", metrics.peak_flip),
                rule: format!(
                    "blurred by {} px; passes at most {}",
                    t.blur_sigma, t.max_peak_flip
                ),
                meets: Some(metrics.peak_flip <= t.max_peak_flip),
            },
            Figure {
                name: "camera",
                meaning: meaning::CAMERA,
                value: match comparison.diagnosis {
                    Some(d) => d.messages().join("; "),
                    None => "no move, scale or mirror found".to_owned(),
                },
                rule: format!(
                    "a move over {} px, a scale over {}% or a mirror fails",
                    t.max_shift,
                    t.max_scale_error * 100.0
                ),
                meets: Some(comparison.diagnosis.is_none()),
            },
            Figure {
                name: "mean FLIP",
                meaning: meaning::MEAN_FLIP,
                value: format!("{:.4}", metrics.mean_flip),
                rule: not_judged("of the blurred images; not judged"),
                meets: None,
            },
            Figure {
                name: "pixels that differ",
                meaning: meaning::DIFFERING_PIXELS,
                value: differing,
                rule: format!(
                    "by more than {}/255; not judged: sampling alone changes edge pixels",
                    channel_tolerance(rules)
                ),
                meets: None,
            },
            Figure {
                name: "largest difference",
                meaning: meaning::LARGEST_DIFFERENCE,
                value: largest,
                rule: not_judged("not judged"),
                meets: None,
            },
        ],
        Rules::Golden(t) => {
            let allowed = t.max_bad_pixels(metrics.pixel_count);
            vec![
                Figure {
                    name: "pixels that differ",
                    meaning: meaning::DIFFERING_PIXELS,
                    value: differing,
                    rule: format!(
                        "by more than {}/255; passes at most {allowed}",
                        t.channel_tolerance
                    ),
                    meets: Some(metrics.bad_pixels <= allowed),
                },
                Figure {
                    name: "mean FLIP",
                    meaning: meaning::MEAN_FLIP,
                    value: format!("{:.4}", metrics.mean_flip),
                    rule: format!("passes at most {}", t.max_mean_flip),
                    meets: Some(metrics.mean_flip <= t.max_mean_flip),
                },
                Figure {
                    name: "peak FLIP",
                    meaning: meaning::PEAK_FLIP,
                    value: format!("{:.4}", metrics.peak_flip),
                    rule: format!("passes at most {}", t.max_peak_flip),
                    meets: Some(metrics.peak_flip <= t.max_peak_flip),
                },
                Figure {
                    name: "largest difference",
                    meaning: meaning::LARGEST_DIFFERENCE,
                    value: largest,
                    rule: not_judged("not judged"),
                    meets: None,
                },
            ]
        }
    }
}

/// One entry's section: verdict and name, figures, images side by side.
fn entry_section(section: &Section<'_>, rules: Rules) -> Markup {
    let entry = section.entry;
    let verdict = entry.verdict();
    html! {
        section id=(section.stem) class={ "entry " (verdict.word()) } {
            h2 {
                (verdict_badge(verdict))
                " " (entry.name)
            }
            table.figures {
                @match entry.outcome {
                    Outcome::Error(message) | Outcome::Failed(message) => {
                        tr.error { th { "not compared" } td colspan="2" { (message) } }
                    }
                    Outcome::Compared(comparison) => {
                        @if let Some(metrics) = &comparison.metrics {
                            @for figure in figures(metrics, comparison, rules) {
                                tr class=(match figure.meets {
                                    Some(true) => "meets",
                                    Some(false) => "misses",
                                    None => "shown",
                                }) {
                                    th title=(figure.meaning) { (figure.name) }
                                    td.value { (figure.value) }
                                    td.rule { (figure.rule) }
                                }
                            }
                        }
                        @for failure in &comparison.failures {
                            tr.why { th { "why it failed" } td colspan="2" { (failure.to_string()) } }
                        }
                    }
                }
            }
            div.images {
                @for picture in &section.images {
                    (figure_html(picture, rules))
                }
            }
        }
    }
}

/// An image beside its caption; small renders are shown enlarged, pixel for pixel.
fn figure_html(picture: &Picture, rules: Rules) -> Markup {
    let caption = match (picture.role, rules) {
        (Role::Expected, _) => "expected",
        (Role::Actual, _) => "actual",
        (Role::Difference, Rules::Instructor(_)) => "difference (FLIP of the blurred images)",
        (Role::Difference, Rules::Golden(_)) => "difference (FLIP)",
    };
    let width = picture.width;
    let shown = (width * (480 / width.max(1)).clamp(1, 4)).min(480);
    html! {
        figure {
            a href=(picture.file) {
                img src=(picture.file) alt=(caption) style={ "width: " (shown) "px" };
            }
            figcaption { (caption) }
        }
    }
}

/// The report's own style, after the common one ([`report_page`]).
const STYLE: &str = "
body { margin: 2em; max-width: 90em; }
h1 { font-size: 1.5em; }
h2 { font-size: 1.15em; margin: 0 0 0.5em; }
.summary { font-size: 1.1em; }
section { padding: 1em; }
section.entry { border-left: 6px solid #2a2; }
section.entry.fail { border-left-color: #c22; }
section.entry.error { border-left-color: #888; }
.rules dl { display: grid; grid-template-columns: max-content auto; gap: 0.3em 1em; margin: 0.5em 0; }
.rules dt { font-weight: bold; }
.rules dd { margin: 0; }
.figures th { white-space: nowrap; text-align: left; padding-right: 1em; font-weight: normal; color: #555; vertical-align: top; cursor: help; }
.figures td { padding-right: 1.5em; vertical-align: top; }
.figures td.rule { color: #666; }
.figures tr.misses td.value { color: #c22; font-weight: bold; }
.figures tr.meets td.value { color: #185; }
.figures tr.why td, .figures tr.error td { font-weight: bold; }
.images { gap: 1em; margin-top: 0.8em; }
figure img { image-rendering: pixelated; }
figcaption { font-size: 0.9em; }
.ramp { display: inline-block; width: 8em; height: 0.8em; vertical-align: middle;
  background: linear-gradient(to right, #000004, #3b0f70, #8c2981, #de4968, #fe9f6d, #fcfdbf); }
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stems_are_safe_file_names_and_never_collide_even_in_case() {
        let mut used = HashSet::new();
        assert_eq!(unique_stem("perspective.png", &mut used), "perspective");
        assert_eq!(unique_stem("perspective", &mut used), "perspective-2");
        assert_eq!(unique_stem("Perspective.png", &mut used), "Perspective-3");
        assert_eq!(unique_stem("a b/c<d>.png", &mut used), "a_b_c_d_");
        assert_eq!(unique_stem("../x", &mut used), "_.._x");
        assert_eq!(unique_stem("", &mut used), "_");
    }
}
