//! The autograding platforms' consumers of a results file, as near to the real ones as a
//! test can run: Gradescope's published results specification as a checker, PrairieLearn's
//! documented external grader schema as a checker, GitHub Classroom's autograding
//! reporter's own decoding run by Node, and JUnit XML parsed by Python's junitparser
//! (installed from PyPI into the target folder on first use).

use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::OnceLock;

use serde_json::{Map, Value};

/// Checks `results` against Gradescope's autograder results specification
/// (gradescope-autograders.readthedocs.io, "Autograder Specifications", "Output
/// format"): the keys it names and no others, each of the type it gives; `score` on the
/// top level or on every test; `status` `passed` or `failed`; formats and visibilities
/// from its lists.
pub(crate) fn check_gradescope(results: &Value) -> Result<(), String> {
    const TOP: [&str; 11] = [
        "score",
        "execution_time",
        "output",
        "output_format",
        "test_output_format",
        "test_name_format",
        "visibility",
        "stdout_visibility",
        "extra_data",
        "tests",
        "leaderboard",
    ];
    const TEST: [&str; 11] = [
        "score",
        "max_score",
        "status",
        "name",
        "name_format",
        "number",
        "output",
        "output_format",
        "tags",
        "visibility",
        "extra_data",
    ];
    const FORMATS: [&str; 5] = ["text", "simple_format", "html", "md", "ansi"];
    const VISIBILITIES: [&str; 4] = ["hidden", "after_due_date", "after_published", "visible"];
    let top = object(results, "results")?;
    keys(top, &TOP, "results")?;
    number(top, "score", "results")?;
    number(top, "execution_time", "results")?;
    string(top, "output", "results")?;
    for key in ["output_format", "test_output_format", "test_name_format"] {
        one_of(top, key, &FORMATS, "results")?;
    }
    for key in ["visibility", "stdout_visibility"] {
        one_of(top, key, &VISIBILITIES, "results")?;
    }
    let tests = match top.get("tests") {
        None => &Vec::new(),
        Some(Value::Array(tests)) => tests,
        Some(other) => return Err(format!("results: `tests` is not an array: {other}")),
    };
    if !top.contains_key("score") && tests.is_empty() {
        return Err("results: no top-level `score` and no tests".to_owned());
    }
    for (k, test) in tests.iter().enumerate() {
        let at = format!("tests[{k}]");
        let test = object(test, &at)?;
        keys(test, &TEST, &at)?;
        for key in ["score", "max_score"] {
            number(test, key, &at)?;
        }
        if !top.contains_key("score") && !test.contains_key("score") {
            return Err(format!("{at}: no `score`, and none on the top level"));
        }
        one_of(test, "status", &["passed", "failed"], &at)?;
        for key in ["name", "number", "output"] {
            string(test, key, &at)?;
        }
        for key in ["name_format", "output_format"] {
            one_of(test, key, &FORMATS, &at)?;
        }
        one_of(test, "visibility", &VISIBILITIES, &at)?;
    }
    Ok(())
}

/// Checks `results` (and its size) against PrairieLearn's external grading results
/// (PrairieLearn's docs/externalGrading.md, "Grading results"): an object under 1 MB;
/// `gradable` a boolean; when gradable, `score` a number in [0, 1]; `message` and
/// `output` strings; `images` each a data URI (`url`, optional `label`); `tests` each
/// with `name`, `points` and `max_points` (0 <= points <= max_points), `message`,
/// `output` and `images`.
pub(crate) fn check_prairielearn(results: &Value, bytes: usize) -> Result<(), String> {
    if bytes >= 1_000_000 {
        return Err(format!("results.json is {bytes} bytes: at most 1 MB"));
    }
    let top = object(results, "results")?;
    let gradable = match top.get("gradable") {
        None => true,
        Some(Value::Bool(b)) => *b,
        Some(other) => return Err(format!("results: `gradable` is not a boolean: {other}")),
    };
    if gradable {
        let score = top
            .get("score")
            .and_then(Value::as_f64)
            .ok_or("results: gradable, but `score` is not a number")?;
        if !(0.0..=1.0).contains(&score) {
            return Err(format!("results: `score` {score} is outside [0, 1]"));
        }
    }
    for key in ["message", "output"] {
        string(top, key, "results")?;
    }
    images(top, "results")?;
    if let Some(tests) = top.get("tests") {
        let tests = tests.as_array().ok_or("results: `tests` is not an array")?;
        for (k, test) in tests.iter().enumerate() {
            let at = format!("tests[{k}]");
            let test = object(test, &at)?;
            for key in ["name", "description", "message", "output"] {
                string(test, key, &at)?;
            }
            let points = number(test, "points", &at)?;
            let max = number(test, "max_points", &at)?;
            if let (Some(points), Some(max)) = (points, max)
                && !(0.0 <= points && points <= max)
            {
                return Err(format!("{at}: points {points} not in [0, {max}]"));
            }
            images(test, &at)?;
        }
    }
    Ok(())
}

/// What GitHub Classroom's autograding reporter makes of the grader steps' results: the
/// `runners` and each step's `result` output (base64), decoded by Node exactly as the
/// reporter's `src/main.js` decodes them (`Buffer.from(value, "base64")`, `JSON.parse`),
/// its `runners` pattern checked, and the points added up as its
/// `src/notify-classroom.js` adds them up for GitHub Classroom.
#[derive(Debug)]
pub(crate) struct Reported {
    /// The points reported to GitHub Classroom.
    pub(crate) total_points: f64,
    /// The points there were.
    pub(crate) max_points: f64,
    /// The reporter's `setFailed` message, if it fails the step.
    pub(crate) failed: Option<String>,
    /// Each runner's decoded result object.
    pub(crate) results: Vec<Value>,
}

/// Runs the reporter's decoding on `(step id, base64 result)` pairs.
pub(crate) fn github_reporter(steps: &[(&str, &str)]) -> Reported {
    const REPORTER: &str = r#"
const runners = process.argv[1];
if (!/^([a-zA-Z0-9]+,)*[a-zA-Z0-9]+$/.test(runners)) {
  throw new Error("The runners input must be a comma-separated list of strings.");
}
const runnerResults = runners.split(",").map((runner) => {
  const encodedResults = process.env[`${runner.trim().toUpperCase()}_RESULTS`];
  const json = Buffer.from(encodedResults, "base64").toString("utf-8");
  return { runner, results: JSON.parse(json) };
});
const { totalPoints, maxPoints } = runnerResults.reduce(
  (acc, { results }) => {
    if (!results.max_score) return acc;
    acc.maxPoints += results.max_score;
    results.tests.forEach(({ score }) => {
      acc.totalPoints += score;
    });
    return acc;
  },
  { totalPoints: 0, maxPoints: 0 }
);
let failed = null;
if (runnerResults.some((r) => r.results.status === "fail")) {
  failed = "Some tests failed.";
} else if (runnerResults.some((r) => r.results.status === "error")) {
  failed = "Some tests errored.";
}
console.log(JSON.stringify({ totalPoints, maxPoints, failed, results: runnerResults.map((r) => r.results) }));
"#;
    let runners: Vec<&str> = steps.iter().map(|(id, _)| *id).collect();
    let mut command = Command::new("node");
    command.arg("-e").arg(REPORTER).arg(runners.join(","));
    for (id, encoded) in steps {
        command.env(format!("{}_RESULTS", id.to_uppercase()), encoded);
    }
    let output = command
        .output()
        .expect("Node runs (GitHub's autograding reporter is a Node action)");
    assert!(
        output.status.success(),
        "the reporter's decoding failed: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    let value: Value = serde_json::from_slice(&output.stdout).unwrap();
    Reported {
        total_points: value["totalPoints"].as_f64().unwrap(),
        max_points: value["maxPoints"].as_f64().unwrap(),
        failed: value["failed"].as_str().map(str::to_owned),
        results: value["results"].as_array().unwrap().clone(),
    }
}

/// The junitparser release the JUnit XML is read with.
const JUNITPARSER: &str = "junitparser==3.2.0";

/// A folder with junitparser in it, installed by pip from PyPI on first use into the
/// target folder (kept there for the next run).
fn junitparser() -> &'static Path {
    static FOLDER: OnceLock<PathBuf> = OnceLock::new();
    FOLDER.get_or_init(|| {
        let folder = Path::new(env!("CARGO_TARGET_TMPDIR")).join("junitparser-3.2.0");
        if folder.join("junitparser").is_dir() {
            return folder;
        }
        // Installed beside and renamed, so that an interrupted install is never used.
        let partial = folder.with_extension(format!("partial-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&partial);
        let status = Command::new("python3")
            .args(["-m", "pip", "install", "--quiet", "--no-deps", "--target"])
            .arg(&partial)
            .arg(JUNITPARSER)
            .status()
            .expect("python3 runs (pip installs junitparser from PyPI)");
        assert!(status.success(), "pip could not install {JUNITPARSER}");
        if std::fs::rename(&partial, &folder).is_err() {
            // Another test run installed it first.
            let _ = std::fs::remove_dir_all(&partial);
        }
        folder
    })
}

/// The JUnit XML file at `path` as junitparser reads it: `{suites: [{name, tests,
/// failures, errors, time, properties: {..}, cases: [{name, classname, time, results:
/// [{kind, message, type, text}], system_out}]}]}`.
pub(crate) fn junit(path: &Path) -> Value {
    const READ: &str = r#"
import json, sys
from junitparser import JUnitXml, TestSuite
xml = JUnitXml.fromfile(sys.argv[1])
suites = [xml] if isinstance(xml, TestSuite) else list(xml)
out = {"suites": []}
for suite in suites:
    cases = []
    for case in suite:
        cases.append({
            "name": case.name,
            "classname": case.classname,
            "time": case.time,
            "results": [
                {"kind": type(r).__name__, "message": r.message, "type": r.type, "text": r.text}
                for r in case.result
            ],
            "system_out": case.system_out,
        })
    out["suites"].append({
        "name": suite.name,
        "tests": suite.tests,
        "failures": suite.failures,
        "errors": suite.errors,
        "time": suite.time,
        "properties": {p.name: p.value for p in suite.properties()},
        "cases": cases,
    })
print(json.dumps(out))
"#;
    let output = Command::new("python3")
        .arg("-c")
        .arg(READ)
        .arg(path)
        .env("PYTHONPATH", junitparser())
        .output()
        .expect("python3 runs");
    assert!(
        output.status.success(),
        "junitparser could not read {}: {}",
        path.display(),
        String::from_utf8_lossy(&output.stderr)
    );
    serde_json::from_slice(&output.stdout).unwrap()
}

fn object<'a>(value: &'a Value, at: &str) -> Result<&'a Map<String, Value>, String> {
    value
        .as_object()
        .ok_or_else(|| format!("{at}: not an object: {value}"))
}

fn keys(object: &Map<String, Value>, allowed: &[&str], at: &str) -> Result<(), String> {
    match object.keys().find(|k| !allowed.contains(&k.as_str())) {
        Some(key) => Err(format!("{at}: `{key}` is not in the specification")),
        None => Ok(()),
    }
}

fn number(object: &Map<String, Value>, key: &str, at: &str) -> Result<Option<f64>, String> {
    match object.get(key) {
        None => Ok(None),
        Some(Value::Number(n)) => Ok(n.as_f64()),
        Some(other) => Err(format!("{at}: `{key}` is not a number: {other}")),
    }
}

fn string(object: &Map<String, Value>, key: &str, at: &str) -> Result<(), String> {
    match object.get(key) {
        None | Some(Value::String(_)) => Ok(()),
        Some(other) => Err(format!("{at}: `{key}` is not a string: {other}")),
    }
}

fn one_of(object: &Map<String, Value>, key: &str, values: &[&str], at: &str) -> Result<(), String> {
    match object.get(key) {
        None => Ok(()),
        Some(Value::String(s)) if values.contains(&s.as_str()) => Ok(()),
        Some(other) => Err(format!("{at}: `{key}` is {other}, not one of {values:?}")),
    }
}

fn images(object: &Map<String, Value>, at: &str) -> Result<(), String> {
    let Some(images) = object.get("images") else {
        return Ok(());
    };
    let images = images
        .as_array()
        .ok_or_else(|| format!("{at}: `images` is not an array"))?;
    for image in images {
        let url = match image {
            Value::String(url) => url.as_str(),
            Value::Object(o) => {
                string(o, "label", at)?;
                o.get("url")
                    .and_then(Value::as_str)
                    .ok_or_else(|| format!("{at}: an image without a `url`"))?
            }
            other => return Err(format!("{at}: an image is {other}")),
        };
        if !url.starts_with("data:image/") || !url.contains(";base64,") {
            return Err(format!(
                "{at}: an image's url is not a base64 data URI: {}",
                &url[..url.len().min(40)]
            ));
        }
    }
    Ok(())
}
