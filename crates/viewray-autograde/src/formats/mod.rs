//! The results in each platform's own format, one module per platform, each a pure
//! function of [`Results`] to the file's bytes.
//!
//! Every platform's fields are written as its documentation gives them (each module
//! says where); a test that is not [`crate::Visibility::Visible`] keeps its details for
//! Gradescope (which hides them itself until its time) and for viewray's own JSON (the
//! instructor's), and shows only when they will be shown elsewhere.

mod github;
mod gradescope;
mod json;
mod junit;
mod prairielearn;

pub use github::{github_result, github_result_base64};
pub use gradescope::gradescope_results;
pub use json::json_results;
pub use junit::junit_xml;
pub use prairielearn::{PRAIRIELEARN_MAX_BYTES, prairielearn_results};

use crate::results::Results;

/// A results format.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Format {
    /// Gradescope's `results.json`.
    Gradescope,
    /// PrairieLearn's external grader `results.json`.
    PrairieLearn,
    /// GitHub Classroom: the autograding grader's result object, base64 for the reporter.
    Github,
    /// JUnit XML.
    Junit,
    /// viewray's own JSON: everything, for the instructor.
    Json,
}

impl Format {
    /// Every format, in the order the command lists them.
    pub const ALL: [Format; 5] = [
        Format::Gradescope,
        Format::PrairieLearn,
        Format::Github,
        Format::Junit,
        Format::Json,
    ];

    /// The format's name on the command line: `gradescope`, `prairielearn`, `github`,
    /// `junit`, `json`.
    pub fn name(self) -> &'static str {
        match self {
            Format::Gradescope => "gradescope",
            Format::PrairieLearn => "prairielearn",
            Format::Github => "github",
            Format::Junit => "junit",
            Format::Json => "json",
        }
    }

    /// The results file's bytes.
    pub fn write(self, results: &Results) -> Vec<u8> {
        let json = |value: serde_json::Value| {
            let mut bytes =
                serde_json::to_vec_pretty(&value).expect("JSON values always serialize");
            bytes.push(b'\n');
            bytes
        };
        match self {
            Format::Gradescope => json(gradescope_results(results)),
            Format::PrairieLearn => json(prairielearn_results(results)),
            Format::Github => format!("{}\n", github_result_base64(results)).into_bytes(),
            Format::Junit => junit_xml(results).into_bytes(),
            Format::Json => json(json_results(results)),
        }
    }
}

/// Seconds as JSON numbers are written: to the millisecond.
pub(crate) fn seconds(duration: std::time::Duration) -> f64 {
    (duration.as_secs_f64() * 1000.0).round() / 1000.0
}

/// Points as a JSON number: to the millionth (no 0.30000000000000004), and never `-0`
/// (the sum of no tests is -0.0 in floating point).
pub(crate) fn points(value: f64) -> f64 {
    (value * 1e6).round() / 1e6 + 0.0
}
