//! viewray's own results JSON: everything, for the instructor (and any program):
//! `title`, `score`, `max_score`, `passed`, `problem`, `notes`, `elapsed_s`, and each
//! test's `name`, `score`, `max_score`, `status`, `visibility`, `message`, `output`,
//! `command`, `duration_s` and `images` (`label`, `url`: a data URI).

use serde_json::{Value, json};

use crate::assignment::Visibility;
use crate::formats::{points, seconds};
use crate::results::{Results, Status};

/// The whole results as one JSON object.
pub fn json_results(results: &Results) -> Value {
    let tests: Vec<Value> = results
        .tests
        .iter()
        .map(|test| {
            json!({
                "name": test.name,
                "score": points(test.score),
                "max_score": points(test.max_score),
                "status": match test.status { Status::Passed => "passed", Status::Failed => "failed" },
                "visibility": match test.visibility {
                    Visibility::Visible => "visible",
                    Visibility::AfterDueDate => "after_due_date",
                    Visibility::Hidden => "hidden",
                },
                "message": test.message,
                "output": test.output,
                "command": test.command,
                "duration_s": seconds(test.duration),
                "images": test.images.iter().map(|i| json!({"label": i.label, "url": i.data_uri()})).collect::<Vec<_>>(),
            })
        })
        .collect();
    json!({
        "title": results.title,
        "score": points(results.score()),
        "max_score": points(results.max_score()),
        "passed": results.all_passed(),
        "problem": results.problem,
        "notes": results.notes,
        "elapsed_s": seconds(results.elapsed),
        "tests": tests,
    })
}
