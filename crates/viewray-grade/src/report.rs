//! The class report: an HTML page with the class at a glance (a grid of students by
//! images, failures first, each failed cell coloured and worded by what failed: missing,
//! unreadable, wrong camera, wrong appearance, with its diagnosis written in it, so that
//! the page reads the same printed) and a page per
//! student with thumbnails of the expected image, the render and the FLIP heatmap for each
//! failure.

use std::collections::HashSet;
use std::io;
use std::path::{Path, PathBuf};

use image::{ImageBuffer, Pixel};
use maud::{Markup, html};
use viewray_compare::{FailureKind, Verdict, report_page, unique_stem, verdict_badge};
use viewray_output::{Compression, encode_png, write_atomically};

use crate::class::{Assignment, ClassSummary, StudentGrade, thumbnail};

/// What the class report shows.
pub struct ClassReport<'a> {
    /// The page's title, e.g. the command line.
    pub title: &'a str,
    /// The summary lines, as the terminal prints them (the grid shows each image's pass
    /// rate).
    pub summary: &'a [String],
    /// The rule renders were judged by, as a sentence (the threshold).
    pub rule: &'a str,
    /// The assignment.
    pub assignment: &'a Assignment,
    /// Every student's grade, in name order.
    pub grades: &'a [StudentGrade],
    /// The class's tallies.
    pub tally: &'a ClassSummary,
}

/// Writes the class report into `directory` (created if need be) and returns the path of
/// its page, `index.html`.
///
/// Beside it go `reference/IMAGE.png` (a thumbnail of each reference image),
/// `students/STUDENT.html` (a page per student) and `students/STUDENT/IMAGE.actual.png`
/// and `IMAGE.diff.png` (thumbnails of the render and its FLIP heatmap, for each failure
/// that has them; see [`crate::grade_student`]). File names are the names with characters
/// other than letters, digits, `-`, `_` and `.` replaced by `_` (and a number added when
/// two would collide). Every file is written atomically; the pages have no timestamp.
///
/// # Errors
/// Any I/O error creating a folder or writing a file; a file's error names it.
pub fn write_class_report(directory: &Path, report: &ClassReport<'_>) -> io::Result<PathBuf> {
    let students_dir = directory.join("students");
    let reference_dir = directory.join("reference");
    std::fs::create_dir_all(&students_dir)?;
    std::fs::create_dir_all(&reference_dir)?;

    let mut used = HashSet::new();
    let image_stems: Vec<String> = report
        .assignment
        .names()
        .map(|name| unique_stem(name, &mut used))
        .collect();
    for (task, stem) in report.assignment.tasks.iter().zip(&image_stems) {
        write_png(
            &reference_dir.join(format!("{stem}.png")),
            &thumbnail(task.reference.image()),
        )?;
    }

    let mut used = HashSet::new();
    let mut student_stems = Vec::with_capacity(report.grades.len());
    for grade in report.grades {
        let stem = unique_stem(&grade.name, &mut used);
        let mut pictures = Vec::new();
        for (image, image_stem) in grade.images.iter().zip(&image_stems) {
            let mut written = Written::default();
            if let Some(p) = &image.pictures {
                if p.actual.is_some() || p.heatmap.is_some() {
                    std::fs::create_dir_all(students_dir.join(&stem))?;
                }
                if let Some(actual) = &p.actual {
                    let file = format!("{stem}/{image_stem}.actual.png");
                    write_png(&students_dir.join(&file), actual)?;
                    written.actual = Some(file);
                }
                if let Some(heatmap) = &p.heatmap {
                    let file = format!("{stem}/{image_stem}.diff.png");
                    write_png(&students_dir.join(&file), heatmap)?;
                    written.heatmap = Some(file);
                }
            }
            pictures.push(written);
        }
        let page = student_page(report, grade, &image_stems, &pictures).into_string();
        write_atomically(students_dir.join(format!("{stem}.html")), page.as_bytes())?;
        student_stems.push(stem);
    }

    let page = class_page(report, &image_stems, &student_stems).into_string();
    let path = directory.join("index.html");
    write_atomically(&path, page.as_bytes())?;
    Ok(path)
}

/// The thumbnails written for one image of one student, relative to `students/`.
#[derive(Default)]
struct Written {
    actual: Option<String>,
    heatmap: Option<String>,
}

fn write_png<P>(path: &Path, image: &ImageBuffer<P, Vec<u8>>) -> io::Result<()>
where
    P: Pixel<Subpixel = u8> + image::PixelWithColorType,
{
    let png = encode_png(image, Compression::Balanced)?;
    write_atomically(path, &png)?;
    Ok(())
}

/// The students in the grid's order: the most failures first, then by name.
fn failures_first(grades: &[StudentGrade]) -> Vec<usize> {
    let mut order: Vec<usize> = (0..grades.len()).collect();
    order.sort_by_key(|&i| (grades[i].passed(), i));
    order
}

/// A cell's CSS classes: its verdict, and for a failure what failed.
fn cell_class(verdict: Verdict, kind: Option<FailureKind>) -> String {
    match kind {
        Some(kind) => format!("cell {} {}", verdict.word(), kind.class()),
        None => format!("cell {}", verdict.word()),
    }
}

/// The mark of a failed cell: `?` missing, `!` unreadable, `✗` wrong camera, `~` wrong
/// appearance.
fn failure_mark(kind: Option<FailureKind>) -> &'static str {
    match kind {
        Some(FailureKind::Missing) => "?",
        Some(FailureKind::Unreadable) => "!",
        Some(FailureKind::Appearance) => "~",
        Some(FailureKind::Camera) | None => "✗",
    }
}

/// The page of the whole class.
fn class_page(
    report: &ClassReport<'_>,
    image_stems: &[String],
    student_stems: &[String],
) -> Markup {
    let names: Vec<&str> = report.assignment.names().collect();
    let hardest: Vec<&str> = report
        .tally
        .hardest()
        .iter()
        .map(|h| h.name.as_str())
        .collect();
    let body = html! {
        h1 { (report.title) }
        @for line in report.summary {
            p.summary { (line) }
        }
        p.legend {
            span.cell.pass { "✓" } " passed  "
            span."cell fail camera" { "✗" } " wrong camera  "
            span."cell fail appearance" { "~" } " wrong appearance  "
            span."cell fail missing" { "?" } " missing  "
            span."cell fail unreadable" { "!" } " unreadable  · each failure's diagnosis \
                in its cell (the whole on hover and on the student's page)  · " (report.rule)
        }
        table.grid {
            thead {
                tr {
                    th.student { "student" }
                    th.count { "passed" }
                    @for (name, stem) in names.iter().zip(image_stems) {
                        th.image title=(name) {
                            a href={ "reference/" (stem) ".png" } {
                                span.label { (stem) }
                            }
                        }
                    }
                }
                tr.rates {
                    th.student { "passed by" }
                    td.count {}
                    @for tally in &report.tally.images {
                        td class={ "rate" @if hardest.contains(&tally.name.as_str()) { " hardest" } }
                            title={ (tally.name) ": passed by " (tally.passed) " of " (tally.total) } {
                            (tally.percent())
                        }
                    }
                }
            }
            tbody {
                @for index in failures_first(report.grades) {
                    @let grade = &report.grades[index];
                    @let page = format!("students/{}.html", student_stems[index]);
                    @let all = grade.passed_everything();
                    tr class=(if all { "pass" } else { "fail" }) {
                        th.student { a href=(page) { (grade.name) } }
                        td.count { (grade.passed()) "/" (grade.images.len()) }
                        @for ((image, name), stem) in grade.images.iter().zip(&names).zip(image_stems) {
                            @let verdict = image.outcome.verdict();
                            @let note = image.outcome.note();
                            @let hover = if note.is_empty() {
                                format!("{name}: {}", verdict.label())
                            } else {
                                format!("{name}: {}: {note}", verdict.label())
                            };
                            @let kind = image.outcome.failure_kind();
                            td class=(cell_class(verdict, kind)) title=(hover) {
                                @if verdict == Verdict::Pass {
                                    "✓"
                                } @else {
                                    a href={ (page) "#" (stem) } {
                                        span.mark { (failure_mark(kind)) }
                                        " "
                                        span.what { (kind.map_or("failed", FailureKind::word)) }
                                        @if let Some(key) = image.outcome.summary_key().filter(|k| Some(k.as_str()) != kind.map(FailureKind::word)) {
                                            ": " span.why { (key) }
                                        }
                                    }
                                }
                            }
                        }
                    }
                }
            }
        }
    };
    report_page(report.title, STYLE, body)
}

/// The page of one student.
fn student_page(
    report: &ClassReport<'_>,
    grade: &StudentGrade,
    image_stems: &[String],
    pictures: &[Written],
) -> Markup {
    let names: Vec<&str> = report.assignment.names().collect();
    let passed: Vec<&str> = names
        .iter()
        .zip(&grade.images)
        .filter(|(_, i)| i.outcome.passed())
        .map(|(n, _)| *n)
        .collect();
    let body = html! {
        p.back { a href="../index.html" { "← the class" } }
        h1 { (grade.name) }
        p.summary { (grade.passed()) " of " (grade.images.len()) " images passed" }
        @for (((image, name), stem), written) in grade.images.iter().zip(&names).zip(image_stems).zip(pictures) {
            @if !image.outcome.passed() {
                section.failure id=(stem) {
                    h2 { (verdict_badge(Verdict::Fail)) " " (name) }
                    p.diagnosis { (image.outcome.note()) }
                    @if let Some(appearance) = image.outcome.appearance().filter(|a| a.id() != "same") {
                        p.appearance { "appearance: " (appearance.id()) ": " (appearance.sentence()) }
                    }
                    @if let Some(peak) = image.outcome.peak_flip() {
                        p.figures { "peak FLIP " (format!("{peak:.3}")) }
                    }
                    div.images {
                        figure.expected {
                            img src={ "../reference/" (stem) ".png" } alt={ "expected " (name) };
                            figcaption { "expected" }
                        }
                        @if let Some(file) = &written.actual {
                            figure.actual {
                                img src=(file) alt={ "actual " (name) };
                                figcaption { "actual" }
                            }
                        }
                        @if let Some(file) = &written.heatmap {
                            figure.difference {
                                img src=(file) alt={ "FLIP heatmap of " (name) };
                                figcaption { "FLIP heatmap" }
                            }
                        }
                    }
                }
            }
        }
        @if !passed.is_empty() {
            p.passed { (verdict_badge(Verdict::Pass)) " " (passed.join(", ")) }
        }
        @if !grade.extra.is_empty() {
            p.extra { "not judged, only in the student's folder: " (crate::folders::listed(&grade.extra)) }
        }
    };
    let title = format!("{} - {}", grade.name, report.title);
    report_page(&title, STYLE, body)
}

/// The pages' own style, after the common one ([`report_page`]).
const STYLE: &str = "
body { margin: 1.5em 2em; }
h1 { font-size: 1.4em; margin: 0.3em 0; }
h2 { font-size: 1.1em; margin: 0 0 0.4em; }
.summary { margin: 0.2em 0; }
.legend { color: #555; margin: 0.8em 0; white-space: pre-wrap; }
a { color: inherit; }
table.grid { border-collapse: collapse; font-size: 0.9em; }
.grid th, .grid td { padding: 0 0.35em; height: 1.5em; }
.grid th.student { text-align: left; font-weight: normal; white-space: nowrap; padding-right: 0.8em; }
.grid td.count { text-align: right; color: #555; padding-right: 0.8em; font-variant-numeric: tabular-nums; }
.grid thead th.image { vertical-align: bottom; padding: 0 0.1em 0.3em; }
.grid thead th.image .label { writing-mode: vertical-rl; transform: rotate(180deg); white-space: nowrap; font-weight: normal; }
.grid thead a { text-decoration: none; }
.cell, .grid td.rate { width: 2.6em; min-width: 2.6em; box-sizing: border-box; }
.cell { display: table-cell; text-align: center; color: #fff; border: 1px solid #fafafa; }
span.cell { display: inline-block; height: 1.3em; line-height: 1.3em; }
.cell a { text-decoration: none; display: block; }
.cell.pass { background: #3a3; }
.cell.fail { background: #c22; font-size: 0.75em; line-height: 1.15; width: auto; min-width: 6em; max-width: 11em; padding: 0.15em 0.3em; text-align: left; }
.cell.fail .mark { font-weight: bold; }
.cell.fail .what { font-weight: bold; }
.cell.fail .why { display: block; font-weight: normal; }
span.cell.fail { min-width: 0; font-size: 1em; text-align: center; }
.cell.fail.appearance { background: #e69f00; color: #000; }
.cell.fail.missing { background: #fff; color: #333; border: 1px dashed #777; }
.cell.fail.unreadable { background: #777; }
@media print {
  .cell { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
}
.grid tbody tr:hover th, .grid tbody tr:hover td.count { background: #e8e8e8; }
.grid tr.fail + tr.pass th, .grid tr.fail + tr.pass td { border-top: 2px solid #999; }
.grid tr.rates td, .grid tr.rates th { border-bottom: 1px solid #ccc; color: #555; font-size: 0.85em; text-align: center; font-weight: normal; }
.grid tr.rates th.student { text-align: left; }
.grid thead th { font-weight: normal; color: #555; }
.grid td.rate.hardest { color: #c22; font-weight: bold; }
section { border-left: 6px solid #c22; padding: 0.8em 1em; }
.diagnosis { font-weight: bold; margin: 0.3em 0; }
.figures { color: #555; margin: 0.3em 0; }
.images { gap: 0.8em; margin-top: 0.5em; }
figure img { max-width: 240px; max-height: 180px; }
figcaption { font-size: 0.85em; }
";
