//! viewray-compare's integration tests, built as one test binary (linked once, the shared
//! scenes and planted cases compiled once).

// Shared by the test modules below.
mod planted;
mod scene;

mod golden;
mod instructor;
mod matrix;
mod real_renders;
mod report;
