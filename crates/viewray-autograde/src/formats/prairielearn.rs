//! PrairieLearn's external grader `results.json`, as its external grading documentation
//! gives it: `gradable`, `score` in [0, 1], `message`, `output`, `images` (each `label`
//! and `url`, a data URI) and `tests` (each `name`, `points`, `max_points`, `message`,
//! `output`, `images`). The file must stay under 1 MB: thumbnails are left out, last test
//! first, until it does. A submission that could not be graded at all (a broken
//! assignment) is `"gradable": false`, which costs the student no attempt.

use serde_json::{Value, json};

use crate::formats::points;
use crate::results::{Results, Status};

/// The most bytes PrairieLearn takes in a results file.
pub const PRAIRIELEARN_MAX_BYTES: usize = 1_000_000;

/// The `results.json` PrairieLearn reads from `/grade/results/`.
pub fn prairielearn_results(results: &Results) -> Value {
    if let Some(problem) = &results.problem {
        return json!({
            "gradable": false,
            "score": 0.0,
            "message": problem,
            "output": results.summary(),
            "images": [],
            "tests": [],
        });
    }
    let max = results.max_score();
    let score = if max > 0.0 {
        (results.score() / max).clamp(0.0, 1.0)
    } else if results.all_passed() {
        1.0
    } else {
        0.0
    };
    let mut images_kept = results.tests.len();
    loop {
        let tests: Vec<Value> = results
            .tests
            .iter()
            .enumerate()
            .map(|(k, test)| {
                let shown = test.shown();
                let images: Vec<Value> = if k < images_kept {
                    shown
                        .images
                        .iter()
                        .map(|i| json!({"label": i.label, "url": i.data_uri()}))
                        .collect()
                } else {
                    Vec::new()
                };
                let mut message = shown.message.to_owned();
                if test.status == Status::Passed && test.visibility != crate::Visibility::Visible {
                    message = format!("passed; {message}");
                }
                json!({
                    "name": test.name,
                    "points": points(test.score),
                    "max_points": points(test.max_score),
                    "message": message,
                    "output": shown.output,
                    "images": images,
                })
            })
            .collect();
        let mut output = results.summary();
        if images_kept < results.tests.len() {
            output.push_str("\n(some pictures are left out: the results must stay under 1 MB)");
        }
        let value = json!({
            "gradable": true,
            "score": points(score),
            "message": results.summary().lines().next().unwrap_or_default(),
            "output": output,
            "images": [],
            "tests": tests,
        });
        let size = serde_json::to_vec_pretty(&value).map_or(usize::MAX, |b| b.len());
        if size < PRAIRIELEARN_MAX_BYTES || images_kept == 0 {
            return value;
        }
        images_kept -= 1;
    }
}
