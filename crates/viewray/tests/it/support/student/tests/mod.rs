//! The student tracer's own tests (compiled only by `tests/student_tracer.rs`).

mod answers;
mod camera;
mod mistakes;
mod pictures;
mod viewray;

use crate::support::student::Vec3;

/// Checks that `actual` is `expected` to 1e-12 in every coordinate.
#[track_caller]
fn assert_vec(actual: Vec3, expected: Vec3, what: &str) {
    let close = (actual - expected)
        .to_array()
        .iter()
        .all(|d| d.abs() <= 1e-12);
    assert!(close, "{what}: {actual:?}, expected {expected:?}");
}

/// `(x, y, z)`, shorter.
fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(x, y, z)
}
