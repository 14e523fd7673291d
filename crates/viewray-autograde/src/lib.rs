//! One student's submission graded as courses grade, inside their autograding platforms:
//! Gradescope, PrairieLearn, GitHub Classroom, or any CI that reads JUnit XML.
//!
//! What the crate owns:
//!
//! - the assignment file ([`load_assignment`]: RON, paths relative to it; its tests, each
//!   a scene and what the student hands in, a picture or answers, with points and
//!   visibility; the program to run; partial credit);
//! - running the student's own program with limits ([`sandbox`]: a time limit with the
//!   whole process group killed, output and file sizes capped, another user when viewray
//!   is root, nothing read through a symbolic link ([`files`]), and what is not prevented
//!   without a container, said);
//! - judging each test as viewray judges a student's work: a picture by its camera
//!   (viewray-judge's label maps and the catalogue of mistakes) and its appearance
//!   (viewray-compare's FLIP), behind the one function [`judge_picture`]; answers as
//!   `viewray check` judges them (viewray-judge's `Checker`);
//! - the results ([`Results`]) in each platform's own format ([`Format`]).
//!
//! Where to start reading: [`grade`] (in `grading`), then `picture` and `sandbox`.
//!
//! **Invariant:** [`grade`] never fails: whatever is broken (the assignment file, the
//! submission, the student's program), it returns [`Results`] that say why, so a results
//! file can always be written. The crate knows no command line: the command that runs it
//! and the kits that call that command are the `viewray` crate's.

mod assignment;
pub mod files;
mod formats;
mod grading;
mod picture;
mod results;
pub mod sandbox;
mod words;

pub use assignment::{
    Assignment, AssignmentError, HandIn, Judge, Run, Test, Visibility, load_assignment,
};
pub use formats::{
    Format, PRAIRIELEARN_MAX_BYTES, github_result, github_result_base64, gradescope_results,
    json_results, junit_xml, prairielearn_results,
};
pub use grading::{Options, grade, grade_assignment};
pub use picture::{
    MAX_PICTURE_BYTES, PICTURE_FORMATS, PictureError, PictureJudges, PictureVerdict, judge_picture,
    read_picture,
};
pub use results::{Results, Shown, Status, TestResult, Thumbnail, points};
