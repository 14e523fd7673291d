//! viewray-scene's integration tests, built as one test binary (linked once).

// Shared by the test modules below.

mod animation;
mod bad_scenes;
mod camera_text;
mod document;
mod fixtures;
mod parts;
mod projection_errors;
mod projections;
