//! Grading a class of renders: what `viewray grade` and the folder form of `viewray
//! compare` do, without the command line.
//!
//! This crate owns pairing folders and grading a class on viewray-compare's judgement:
//!
//! - [`reference_images`] and [`pair`]: a folder of reference images paired with a folder
//!   of renders as `diff -r` pairs two trees, by file name (or by stem in another image
//!   format: `a.ppm` answers `a.png`; a folder holding one folder alone is descended
//!   into). What the render's side lacks or cannot read is the render's failure
//!   ([`Counterpart`], [`viewray_compare::Outcome::Failed`]); what it has besides is
//!   listed; the reference side's problems are bad input ([`FolderError`]).
//! - [`submissions`], [`flat_submissions`], [`grade_class`]: one folder per student, or a
//!   flat Canvas or Moodle download (the student taken from each file's name), each
//!   judged against the [`Assignment`]'s references (prepared once:
//!   [`viewray_compare::Reference`], with the scene's camera judge when there is one),
//!   students in parallel (rayon), results handed on in the students' order.
//! - [`ClassSummary`]: students fully passing, per-image pass rates ([`percent`]: rounded,
//!   never to all or none), the hardest images (ties named), the failures counted by
//!   diagnosis.
//! - [`write_gradebook`]: the CSV gradebook (student, image, verdict, camera,
//!   camera_diagnosis, peak FLIP, appearance); [`write_class_report`]: the HTML class
//!   report (maud), the class at a glance (each failure worded in its cell) and a page per
//!   student with thumbnails of each failure; [`write_feedback`]: a text file per student.
//!
//! It reads the folders and images it is given, and writes only the gradebook, the
//! report and the feedback, atomically; it knows nothing of scenes or of the command line
//! (a reference's scene reaches it inside its `Reference`: compare's `Expectations` and
//! `CameraJudge`).

mod class;
mod feedback;
mod flat;
mod folders;
mod gradebook;
mod judging;
mod report;

pub use class::{
    Assignment, ClassSummary, ImageGrade, ImageTally, Pictures, StudentGrade, THUMBNAIL, Task,
    grade_class, grade_student, percent, thumbnail,
};
pub use feedback::{feedback, write_feedback};
pub use folders::{
    Counterpart, FolderError, HandedIn, Pairing, ReferenceImage, Student, Submissions,
    flat_submissions, is_image_name, listed, pair, reference_images, submissions,
};
pub use gradebook::{HEADER, gradebook, write_gradebook};
pub use judging::{in_order, judge_counterpart, load_counterpart, unreadable};
pub use report::{ClassReport, write_class_report};
