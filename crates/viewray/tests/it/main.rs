//! The `viewray` binary's integration tests, one module per command or concern, built as
//! one test binary: linked once, and the shared support (the student ray tracer, the
//! planted cases) compiled once. `cargo test -p viewray --test it -- judge_matrix` runs one
//! module.

// Shared by the test modules below.
mod support;
// The planted mistakes of viewray-compare's test matrix, rendered here by viewray.
#[path = "../../../viewray-compare/tests/it/planted/mod.rs"]
mod planted;

mod animate;
mod autograde;
mod autograde_kit;
mod bad_inputs;
mod check_matrix;
mod cli;
mod compare;
mod compare_scene;
mod diagram;
mod figures;
mod grade;
mod grade_planted;
mod homework_docs;
mod interop;
mod judge_fixtures;
mod judge_matrix;
mod render;
mod serve;
mod student_tracer;
mod trace;
mod wrong_files;
