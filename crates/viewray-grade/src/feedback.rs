//! Feedback for each student, as text to paste back into a course site: what passed, and
//! each failure with its diagnosis (the catalogue's entry and the formula to fix) and how
//! the picture looks.

use std::collections::HashSet;
use std::io;
use std::path::{Path, PathBuf};

use viewray_compare::{Appearance, unique_stem};

use crate::class::{Assignment, StudentGrade};

/// The feedback text of one student: a line saying how many images passed, then a
/// paragraph per failed image (its name and what failed, its diagnosis, its appearance
/// when it looks different), then the images that passed and the files not judged.
pub fn feedback(assignment: &Assignment, grade: &StudentGrade) -> String {
    let names: Vec<&str> = assignment.names().collect();
    let mut text = format!(
        "{}: {} of {} images passed\n",
        grade.name,
        grade.passed(),
        grade.images.len()
    );
    let mut passed = Vec::new();
    for (name, image) in names.iter().zip(&grade.images) {
        let outcome = &image.outcome;
        let Some(kind) = outcome.failure_kind() else {
            passed.push(*name);
            continue;
        };
        text.push_str(&format!("\n{name}: {}\n", kind.word()));
        let note = outcome.note();
        if !note.is_empty() && note != kind.word() {
            text.push_str(&format!("  {note}\n"));
        }
        if let Some(appearance) = outcome.appearance().filter(|a| *a != Appearance::Same) {
            text.push_str(&format!(
                "  appearance ({}): {}\n",
                appearance.id(),
                appearance.sentence()
            ));
        }
    }
    if !passed.is_empty() {
        text.push_str(&format!("\npassed: {}\n", passed.join(", ")));
    }
    if !grade.extra.is_empty() {
        text.push_str(&format!(
            "not judged (no reference image of that name): {}\n",
            crate::folders::listed(&grade.extra)
        ));
    }
    text
}

/// Writes each student's [`feedback`] into `directory` (created if need be), as
/// `STUDENT.txt` (the name with characters other than letters, digits, `-`, `_` and `.`
/// replaced by `_`, a number added when two would collide), each atomically; returns the
/// files written, in the students' order.
///
/// # Errors
/// The folder cannot be made or a file cannot be written.
pub fn write_feedback(
    directory: &Path,
    assignment: &Assignment,
    grades: &[StudentGrade],
) -> io::Result<Vec<PathBuf>> {
    std::fs::create_dir_all(directory)?;
    let mut used = HashSet::new();
    grades
        .iter()
        .map(|grade| {
            let path = directory.join(format!("{}.txt", unique_stem(&grade.name, &mut used)));
            viewray_output::write_atomically(&path, feedback(assignment, grade).as_bytes())
                .map_err(io::Error::other)?;
            Ok(path)
        })
        .collect()
}
