//! JSON lines on stdout, with numbers as a student expects to read them.

use std::io::Write;

use glam::DVec3;
use serde_json::{Value, json};

/// A number for printing: `-0` becomes `0` (a student's answer never says minus zero).
pub(crate) fn number(x: f64) -> Value {
    json!(x + 0.0)
}

/// A vector as a JSON array `[x, y, z]`.
pub(crate) fn vector(v: DVec3) -> Value {
    Value::Array(v.to_array().map(number).to_vec())
}

/// Writes `value` as one line on `out`.
pub(crate) fn write_line(out: &mut impl Write, value: &Value) -> std::io::Result<()> {
    serde_json::to_writer(&mut *out, value)?;
    out.write_all(b"\n")
}
