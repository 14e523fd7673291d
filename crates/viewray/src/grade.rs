//! `viewray grade`: a class's renders judged against the reference images, one folder
//! per student (or a flat course-site download, `--flat`).
//!
//! Output: a table on stdout, one row per student in name order (passed of total, then
//! each failure with its diagnosis, one per line), printed as each student is graded
//! (students are graded in parallel), then the summary lines; with `--json`, JSON lines
//! instead: one object per student and image, then one `{"summary":{..}}` object.
//! `--csv` and `--report` are written once every student is graded.

use std::io::{BufWriter, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result, bail};
use clap::Args;
use rayon::prelude::*;
use viewray_compare::{InstructorThresholds, Judge};
use viewray_grade::{
    Assignment, ClassReport, ClassSummary, StudentGrade, Task, grade_class, listed,
    write_class_report, write_feedback, write_gradebook,
};

use crate::compare::{deciding, parse_judge, parse_threshold, prepare, thresholds};

#[derive(Args, Debug)]
pub(crate) struct GradeArgs {
    /// The reference images: a folder of image files (PNG, PPM/PGM or OpenEXR), the
    /// assignment.
    pub(crate) reference: PathBuf,
    /// The class: a folder holding one folder per student, each with the student's
    /// renders named as the reference images are (any supported format: a.ppm answers
    /// a.png; a student folder holding one folder alone is descended into).
    pub(crate) submissions: PathBuf,
    /// The perceptual threshold, in [0, 1], as `viewray compare` has it.
    #[arg(long, value_name = "X", value_parser = parse_threshold,
          default_value_t = InstructorThresholds::default().max_peak_flip)]
    pub(crate) threshold: f32,
    /// Write the gradebook to FILE: CSV, one line per student and image (student, image,
    /// verdict, camera, camera_diagnosis, peak_flip, appearance).
    #[arg(long, value_name = "FILE")]
    pub(crate) csv: Option<PathBuf>,
    /// Write an HTML report of the class into DIR (DIR/index.html): the class at a
    /// glance, failures first, and a page per student with each failure's images.
    #[arg(long, value_name = "DIR")]
    pub(crate) report: Option<PathBuf>,
    /// Print JSON lines instead of a table: one object per student and image, then a
    /// summary object.
    #[arg(long)]
    pub(crate) json: bool,
    /// The scenes the reference images were rendered from: a folder of scenes matched to
    /// the images by file stem (a.png <-> a.ron), or one scene for every image. The
    /// diagnoses then speak the lecture's terms.
    #[arg(long, value_name = "SCENE")]
    pub(crate) scene: Option<PathBuf>,
    /// Which judgement decides the verdict, as `viewray compare` has it: `camera` (the
    /// default with --scene), `image` (the default without) or `both`.
    #[arg(long, value_name = "WHAT", value_parser = parse_judge)]
    pub(crate) judge: Option<Judge>,
    /// SUBMISSIONS is a flat folder, as Canvas and Moodle download a class ("download all
    /// submissions"): the student is taken from each file's name
    /// (`lovelaceada_12345_67890_tower.png`, `Ada Lovelace_12345_assignsubmission_file_tower.png`).
    #[arg(long)]
    pub(crate) flat: bool,
    /// Write a text file per student into DIR (DIR/STUDENT.txt), to paste back into a
    /// course site: each failure with its diagnosis and the formula to fix.
    #[arg(long, value_name = "DIR")]
    pub(crate) feedback: Option<PathBuf>,
}

/// Runs `viewray grade`; prints its own errors and returns the exit code.
pub(crate) fn run(args: &GradeArgs) -> ExitCode {
    match grade(args) {
        Ok(summary) if summary.all_passed() => ExitCode::SUCCESS,
        Ok(_) => ExitCode::from(crate::compare::EXIT_FAILED),
        Err(error) => crate::failure(&error),
    }
}

/// The width of the STUDENT column.
fn name_width(grades: &[viewray_grade::Student]) -> usize {
    grades
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(0)
        .max(7)
}

fn grade(args: &GradeArgs) -> Result<ClassSummary> {
    let (reference, submissions) = (args.reference.as_path(), args.submissions.as_path());
    if !reference.is_dir() {
        if reference.exists() {
            bail!(
                "REFERENCE `{}` is not a folder: give the folder of reference images",
                reference.display()
            );
        }
        bail!("REFERENCE `{}` does not exist", reference.display());
    }
    if !submissions.is_dir() {
        if submissions.exists() {
            bail!(
                "SUBMISSIONS `{}` is not a folder: give a folder holding one folder per student",
                submissions.display()
            );
        }
        bail!("SUBMISSIONS `{}` does not exist", submissions.display());
    }
    // A gradebook that could not be written is found out before the class is graded.
    if let Some(csv) = &args.csv {
        let folder = csv.parent().filter(|p| !p.as_os_str().is_empty());
        if csv.is_dir() || folder.is_some_and(|f| !f.is_dir()) {
            bail!(
                "cannot write the gradebook `{}`: {}",
                csv.display(),
                if csv.is_dir() {
                    "it is a folder"
                } else {
                    "its folder does not exist"
                }
            );
        }
    }
    let decides = deciding(args.judge, args.scene.as_deref())?;
    let images = viewray_grade::reference_images(reference, "REFERENCE")?;
    let class = if args.flat {
        viewray_grade::flat_submissions(submissions, "SUBMISSIONS")?
    } else {
        viewray_grade::submissions(submissions, "SUBMISSIONS")?
    };
    let thresholds = thresholds(args.threshold);
    let tasks: Vec<Task> = prepare(&images, args.scene.as_deref())?
        .into_par_iter()
        .map(|p| Task {
            reference: p.reference(thresholds, decides),
            image: p.image,
        })
        .collect();
    let assignment = Assignment { tasks };

    let names: Vec<&str> = assignment.names().collect();
    let width = name_width(&class.students);
    let mut out = BufWriter::new(anstream::AutoStream::auto(std::io::stdout().lock()));
    if !args.json {
        writeln!(out, "{:width$}  PASSED  FAILURES", "STUDENT")?;
        out.flush()?;
    }
    let grades = grade_class(
        &assignment,
        &class.students,
        args.report.is_some(),
        |grade| {
            if args.json {
                for (name, image) in names.iter().zip(&grade.images) {
                    let line = viewray_json::student_image_line(
                        &grade.name,
                        name,
                        &image.outcome,
                        args.threshold,
                    );
                    viewray_json::write_line(&mut out, &line)?;
                }
            } else {
                for line in student_rows(grade, &names, width) {
                    writeln!(out, "{line}")?;
                }
            }
            out.flush()
        },
    )?;
    let summary = ClassSummary::new(&assignment, &grades);
    let lines = summary_lines(&summary, args.threshold);
    if args.json {
        let line = viewray_json::class_summary_line(&summary, &class.other);
        viewray_json::write_line(&mut out, &line)?;
    } else {
        if !class.other.is_empty() {
            let what = if args.flat {
                "not graded, not named as a course site names submissions"
            } else {
                "not graded, not a folder in SUBMISSIONS"
            };
            writeln!(out, "{what}: {}", listed(&class.other))?;
        }
        for line in &lines {
            writeln!(out, "{line}")?;
        }
    }
    out.flush()?;
    if let Some(path) = &args.csv {
        write_gradebook(path, &assignment, &grades)
            .with_context(|| format!("cannot write the gradebook `{}`", path.display()))?;
        eprintln!("gradebook: {}", path.display());
    }
    if let Some(directory) = &args.feedback {
        write_feedback(directory, &assignment, &grades)
            .with_context(|| format!("cannot write the feedback into `{}`", directory.display()))?;
        eprintln!("feedback: {}", directory.display());
    }
    if let Some(directory) = &args.report {
        let title = format!(
            "viewray grade {} {}",
            reference.display(),
            submissions.display()
        );
        let rule = match decides {
            Judge::Image => format!(
                "a render passes when its peak FLIP is at most {} and no camera mistake shows",
                args.threshold
            ),
            Judge::Camera => "a render passes when its camera is right: its edges are the \
                              scene's, whatever its shading"
                .to_owned(),
            Judge::Both => format!(
                "a render passes when its camera is right and its peak FLIP is at most {}",
                args.threshold
            ),
        };
        // The grid shows each image's pass rate: the page's summary is the rest.
        let headline: Vec<String> = std::iter::once(lines[0].clone())
            .chain(summary.hardest_line())
            .chain(summary.diagnoses_line())
            .collect();
        let report = ClassReport {
            title: &title,
            summary: &headline,
            rule: &rule,
            assignment: &assignment,
            grades: &grades,
            tally: &summary,
        };
        let page = write_class_report(directory, &report)
            .with_context(|| format!("cannot write the report into `{}`", directory.display()))?;
        eprintln!("report: {}", page.display());
    }
    Ok(summary)
}

/// A student's rows: the name, passed of total, and the first failure (`image: note`);
/// each further failure, and the files not judged, on a line of its own under the first.
fn student_rows(grade: &StudentGrade, names: &[&str], width: usize) -> Vec<String> {
    let passed = format!("{}/{}", grade.passed(), grade.images.len());
    let style = if grade.passed_everything() {
        crate::style::PASS
    } else {
        crate::style::FAIL
    };
    let mut notes: Vec<String> = names
        .iter()
        .zip(&grade.images)
        .filter(|(_, image)| !image.outcome.passed())
        .map(|(name, image)| format!("{name}: {}", image.outcome.note()))
        .collect();
    if !grade.extra.is_empty() {
        notes.push(format!("(not judged: {})", listed(&grade.extra)));
    }
    let mut rows = Vec::with_capacity(notes.len().max(1));
    let first = format!(
        "{:width$}  {}  {}",
        grade.name,
        crate::style::padded_right(style, &passed, 6),
        notes.first().map_or("", String::as_str)
    );
    rows.push(first.trim_end().to_owned());
    for note in notes.iter().skip(1) {
        rows.push(format!("{:width$}  {:6}  {note}", "", ""));
    }
    rows
}

/// The summary lines: the headline, the pass rate of each image, the hardest images, the
/// failures counted by diagnosis.
pub(crate) fn summary_lines(summary: &ClassSummary, threshold: f32) -> Vec<String> {
    let mut lines = vec![format!("{} (threshold {threshold})", summary.headline())];
    // The pass rates, wrapped at 80 columns.
    let mut line = String::from("passed per image:");
    for (index, image) in summary.images.iter().enumerate() {
        let item = format!(
            " {} {}{}",
            image.name,
            image.percent(),
            if index + 1 < summary.images.len() {
                ","
            } else {
                ""
            }
        );
        if line.chars().count() + item.chars().count() > 80 {
            lines.push(std::mem::take(&mut line));
            line.push_str("  ");
            line.push_str(item.trim_start());
        } else {
            line.push_str(&item);
        }
    }
    lines.push(line);
    if let Some(hardest) = summary.hardest_line() {
        lines.push(hardest);
    }
    if let Some(diagnoses) = summary.diagnoses_line() {
        lines.push(diagnoses);
    }
    lines
}
