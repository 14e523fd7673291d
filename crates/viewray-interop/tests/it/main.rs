//! viewray-interop's integration tests, built as one test binary (linked once).

// Shared by the test modules below.

mod bad_files;
mod conventions;
mod round_trip;
mod snapshots;
