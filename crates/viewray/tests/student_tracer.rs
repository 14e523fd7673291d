//! The student's ray tracer the CLI's tests judge viewray by (`tests/support/student`):
//! its numbers against values worked by hand from the lecture and the catalogue of
//! mistakes, its scene files against viewray itself, and its pictures and printouts.

mod support;

// The student tracer's own tests live beside it; only this test binary compiles them.
#[path = "support/student/tests/mod.rs"]
mod student;
