//! Gradescope's `results.json`, as its autograder specifications give it: top level
//! `score`, `execution_time` (seconds), `output`, `output_format`, `tests`; each test
//! `name`, `score`, `max_score`, `status` (`passed` or `failed`), `output`,
//! `output_format` (`text`, or `html` with the thumbnails), `visibility` (`visible`,
//! `after_due_date`, `hidden`: Gradescope itself hides a test until then).

use maud::html;
use serde_json::{Value, json};

use crate::assignment::Visibility;
use crate::formats::{points, seconds};
use crate::results::{Results, Status, TestResult};

/// The `results.json` Gradescope reads from `/autograder/results/`.
pub fn gradescope_results(results: &Results) -> Value {
    let tests: Vec<Value> = results.tests.iter().map(test).collect();
    json!({
        "score": points(results.score()),
        "execution_time": seconds(results.elapsed).ceil(),
        "output": results.summary(),
        "output_format": "text",
        "tests": tests,
    })
}

fn test(test: &TestResult) -> Value {
    let (output, format) = if test.images.is_empty() {
        let mut text = test.message.clone();
        if !test.output.is_empty() {
            text.push_str("\n\n");
            text.push_str(&test.output);
        }
        (text, "text")
    } else {
        let page = html! {
            p { strong { (test.message) } }
            @if !test.output.is_empty() { pre { (test.output) } }
            p {
                @for image in &test.images {
                    figure style="display:inline-block;margin:0 1em 0 0" {
                        img alt=(image.label) src=(image.data_uri());
                        figcaption { (image.label) }
                    }
                }
            }
        };
        (page.into_string(), "html")
    };
    json!({
        "name": test.name,
        "score": points(test.score),
        "max_score": points(test.max_score),
        "status": match test.status { Status::Passed => "passed", Status::Failed => "failed" },
        "output": output,
        "output_format": format,
        "visibility": match test.visibility {
            Visibility::Visible => "visible",
            Visibility::AfterDueDate => "after_due_date",
            Visibility::Hidden => "hidden",
        },
    })
}
