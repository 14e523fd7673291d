//! viewray-camera's integration tests, built as one test binary (linked once).

// Shared by the test modules below.

mod boundaries;
mod errors;
mod frames;
mod image_limits;
mod iris;
mod lens;
mod mistakes;
mod presets;
mod project;
mod rays;
mod tilt;
