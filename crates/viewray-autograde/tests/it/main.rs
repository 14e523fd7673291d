//! viewray-autograde's integration tests, built as one test binary (linked once).

// Shared by the test modules below.

mod assignment;
mod untrusted;
