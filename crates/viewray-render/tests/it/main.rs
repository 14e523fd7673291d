//! viewray-render's integration tests, built as one test binary (linked once).

// Shared by the test modules below.

mod render;
mod trace;
