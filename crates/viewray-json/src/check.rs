//! The JSON lines of `viewray check`: one per answer judged, and a last one that sums up
//! and names the catalogue's diagnosis.

use serde_json::{Map, Value, json};
use viewray_judge::{Answer, Expected, IndexHint, Judged, Report};

use crate::{number, vector};

/// The line of one judged answer: `{"line", "kind", "right"}`, the answer's pixel or point,
/// and what the right camera gives (`"expected"`): a frame's `e`, `u`, `v`, `w`; a ray's
/// 0-based `row`, `col`, `u`, `v`, `origin`, `direction`; a point's `x`, `y` (null where
/// it is not seen).
pub fn checked_line(judged: &Judged) -> Value {
    let mut line = Map::new();
    line.insert("line".into(), json!(judged.line));
    line.insert("kind".into(), json!(judged.found.kind()));
    match judged.found {
        Answer::Ray { row, col, .. } => {
            line.insert("pixel".into(), json!([row, col]));
        }
        Answer::Project { point, .. } => {
            line.insert("point".into(), vector(point));
        }
        Answer::Frame { .. } => {}
    }
    line.insert("right".into(), json!(judged.right));
    let expected = match judged.expected {
        Expected::Frame([e, u, v, w]) => json!({
            "e": vector(e), "u": vector(u), "v": vector(v), "w": vector(w),
        }),
        Expected::Ray { pixel, uv, ray } => json!({
            "row": pixel.0,
            "col": pixel.1,
            "u": uv.map(|uv| number(uv.x)),
            "v": uv.map(|uv| number(uv.y)),
            "origin": ray.map(|(o, _)| vector(o)),
            "direction": ray.map(|(_, d)| vector(d)),
        }),
        Expected::Project(xy) => json!({
            "x": xy.map(|xy| number(xy.x)),
            "y": xy.map(|xy| number(xy.y)),
        }),
    };
    line.insert("expected".into(), expected);
    Value::Object(line)
}

/// The last line: `{"summary": {"answers", "right", "wrong", "index_hint" ("one-based",
/// "zero-based" or null), "diagnosis" (the alternative sets of catalogue ids, or null),
/// "pattern" (what the wrong answers share, or null)}}`.
pub fn check_summary_line(report: &Report) -> Value {
    let diagnosis = report.diagnosis.as_ref().map(|d| {
        d.alternatives
            .iter()
            .map(|set| set.iter().map(|m| m.id()).collect::<Vec<_>>())
            .collect::<Vec<_>>()
    });
    json!({ "summary": {
        "answers": report.answers,
        "right": report.right,
        "wrong": report.wrong,
        "index_hint": report.index_hint.map(|hint| match hint {
            IndexHint::OneBased => "one-based",
            IndexHint::ZeroBased => "zero-based",
        }),
        "diagnosis": diagnosis,
        "pattern": report.pattern,
    }})
}
