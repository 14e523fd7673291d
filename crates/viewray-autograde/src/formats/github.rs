//! GitHub Classroom's autograding: the result object its grader actions set as their
//! `result` output (base64 of the JSON), which the autograding reporter action decodes
//! with `Buffer.from(value, "base64")` and `JSON.parse`. The fields are the command
//! grader's: `version` 1, `status` (`pass`, `fail` or `error`), `max_score`, and `tests`,
//! each `name`, `status`, `score`, `message`, `test_code`, `filename`, `line_no` (0: the
//! reporter then prints no line number) and `duration` (milliseconds). The reporter adds
//! up the tests' `score`s for the points it reports to GitHub Classroom, so partial
//! credit counts.

use base64::Engine as _;
use serde_json::{Value, json};

use crate::formats::points;
use crate::results::{Results, Status};

/// The result object.
pub fn github_result(results: &Results) -> Value {
    if let Some(problem) = &results.problem {
        return json!({
            "version": 1,
            "status": "error",
            "max_score": 0,
            "tests": [{
                "name": results.title,
                "status": "error",
                "score": 0,
                "message": problem,
                "test_code": "",
                "filename": "",
                "line_no": 0,
                "duration": results.elapsed.as_millis() as u64,
            }],
        });
    }
    let tests: Vec<Value> = results
        .tests
        .iter()
        .map(|test| {
            let shown = test.shown();
            let mut message = shown.message.to_owned();
            if !shown.output.is_empty() {
                message.push_str("\n\n");
                message.push_str(shown.output);
            }
            json!({
                "name": test.name,
                "status": match test.status { Status::Passed => "pass", Status::Failed => "fail" },
                "score": points(test.score),
                "message": message,
                "test_code": test.command,
                "filename": "",
                "line_no": 0,
                "duration": test.duration.as_millis() as u64,
            })
        })
        .collect();
    json!({
        "version": 1,
        "status": if results.all_passed() { "pass" } else { "fail" },
        "max_score": points(results.max_score()),
        "tests": tests,
    })
}

/// The result object as the grader's `result` output carries it: base64 of its JSON.
pub fn github_result_base64(results: &Results) -> String {
    let text =
        serde_json::to_string(&github_result(results)).expect("JSON values always serialize");
    base64::engine::general_purpose::STANDARD.encode(text)
}
