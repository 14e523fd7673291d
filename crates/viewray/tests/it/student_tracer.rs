//! The student's ray tracer the CLI's tests judge viewray by (`tests/it/support/student`):
//! its numbers against values worked by hand from the lecture and the catalogue of
//! mistakes, its scene files against viewray itself, and its pictures and printouts.

// The student tracer's own tests live beside it; only this module compiles them.
#[path = "support/student/tests/mod.rs"]
mod student;
