//! The gradebook: one CSV line per student and image, for a spreadsheet.

use std::io;
use std::path::Path;

use crate::class::{Assignment, StudentGrade};

/// The gradebook's header.
pub const HEADER: [&str; 7] = [
    "student",
    "image",
    "verdict",
    "camera",
    "camera_diagnosis",
    "peak_flip",
    "appearance",
];

/// The gradebook as CSV bytes: the header, then one line per student and image in the
/// students' and the images' order: the student's name, the image's name, `pass` or
/// `fail`, the camera judgement (`right`, `wrong` or `unjudged`; empty without a scene),
/// the diagnosis of the judgement that decided (`--judge`: the camera's, the catalogue's
/// entry with the formula to fix; or the image judgement's; else why it failed:
/// `missing`, `not an image ...`; empty for a pass), the
/// peak FLIP to 4 decimals (empty when the images were not compared with FLIP) and the
/// appearance (`same`, `gamma-missing`, `brighter`, ...; empty when not judged). Fields
/// are quoted as RFC 4180 says where they need it.
///
/// # Errors
/// None in practice (the CSV goes to memory); an I/O error type for the writer's sake.
pub fn gradebook(assignment: &Assignment, grades: &[StudentGrade]) -> io::Result<Vec<u8>> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(HEADER)?;
    for grade in grades {
        for (name, image) in assignment.names().zip(&grade.images) {
            let outcome = &image.outcome;
            let peak = outcome
                .peak_flip()
                .map_or_else(String::new, |p| format!("{p:.4}"));
            let camera = outcome.camera();
            writer.write_record([
                grade.name.as_str(),
                name,
                outcome.verdict().word(),
                camera.map_or("", |c| c.word()),
                &outcome.note(),
                &peak,
                outcome.appearance().map_or("", |a| a.id()),
            ])?;
        }
    }
    writer
        .into_inner()
        .map_err(|e| io::Error::other(e.to_string()))
}

/// Writes the gradebook (see [`gradebook`]) to `path`, atomically: a reader never sees a
/// partial file, and a failed write leaves none.
///
/// # Errors
/// The file cannot be written.
pub fn write_gradebook(
    path: &Path,
    assignment: &Assignment,
    grades: &[StudentGrade],
) -> io::Result<()> {
    let bytes = gradebook(assignment, grades)?;
    viewray_output::write_atomically(path, &bytes).map_err(io::Error::other)
}
