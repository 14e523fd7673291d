//! `viewray autograde` on the repository's example assignment (fixtures/autograde: the
//! lecture's Homework 3, five pictures and three sets of numbers, and one student's
//! answer in Python), each platform's results file read by its consumer (support's
//! `platforms`), partial credit, and a broken assignment still written in every format.

use std::path::{Path, PathBuf};
use std::process::Output;

use base64::Engine as _;
use serde_json::Value;

use crate::support;
use support::platforms::{check_gradescope, check_prairielearn, github_reporter, junit};
use support::{command, repository};

/// The example assignment.
fn homework() -> PathBuf {
    repository().join("fixtures/autograde/homework.ron")
}

/// The example student's program.
fn right_student() -> PathBuf {
    repository().join("fixtures/autograde/student/raytracer.py")
}

/// A submission folder in `dir` holding the example student's program with `from`
/// replaced by `to` (a student's mistake).
fn student_with(dir: &Path, name: &str, from: &str, to: &str) -> PathBuf {
    let source = std::fs::read_to_string(right_student()).unwrap();
    assert!(source.contains(from), "the example program has `{from}`");
    let folder = dir.join(name);
    std::fs::create_dir_all(&folder).unwrap();
    std::fs::write(folder.join("raytracer.py"), source.replace(from, to)).unwrap();
    folder
}

/// A student who forgot the lens shift: the shifted picture and rays are wrong, the
/// other cameras right.
fn no_shift_student(dir: &Path) -> PathBuf {
    student_with(dir, "no-shift", "sx, sy = self.shift", "sx, sy = 0.0, 0.0")
}

/// Runs `viewray autograde ASSIGNMENT SUBMISSION --format FORMAT -o RESULTS [more]`.
fn autograde(
    assignment: &Path,
    submission: &Path,
    format: &str,
    results: &Path,
    more: &[&str],
) -> Output {
    command()
        .arg("autograde")
        .arg(assignment)
        .arg(submission)
        .args(["--format", format, "-o"])
        .arg(results)
        .args(more)
        .output()
        .unwrap()
}

fn json(path: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// The test named `name` in a list of tests.
fn named<'a>(tests: &'a Value, name: &str) -> &'a Value {
    tests
        .as_array()
        .unwrap()
        .iter()
        .find(|t| t["name"] == name)
        .unwrap_or_else(|| panic!("no test `{name}` in {tests:#}"))
}

/// A thumbnail's data URI decoded: its width and height.
fn thumbnail_size(url: &str) -> (u32, u32) {
    let encoded = url.strip_prefix("data:image/png;base64,").unwrap();
    let png = base64::engine::general_purpose::STANDARD
        .decode(encoded)
        .unwrap();
    let image = image::load_from_memory(&png).unwrap();
    (image.width(), image.height())
}

#[test]
fn the_example_students_python_ray_tracer_gets_every_point() {
    let dir = tempfile::tempdir().unwrap();
    let submission = right_student().parent().unwrap().to_path_buf();
    let results = dir.path().join("results.json");
    let output = autograde(&homework(), &submission, "json", &results, &[]);
    assert_eq!(output.status.code(), Some(0), "{}", stdout(&output));
    let value = json(&results);
    assert_eq!(value["score"], 14.0);
    assert_eq!(value["max_score"], 14.0);
    assert_eq!(value["passed"], true);
    let tests = value["tests"].as_array().unwrap();
    let names: Vec<&str> = tests.iter().map(|t| t["name"].as_str().unwrap()).collect();
    assert_eq!(
        names,
        [
            "canonical",
            "general",
            "orthographic",
            "oblique",
            "shifted",
            "canonical rays",
            "general frame and rays",
            "shifted rays"
        ]
    );
    for test in tests {
        assert_eq!(test["status"], "passed", "{test:#}");
    }
    assert_eq!(
        named(&value["tests"], "general frame and rays")["message"],
        "all 13 answers are right"
    );
    assert!(
        stdout(&output)
            .ends_with("Homework 3: the lecture's cameras: 14 of 14 points; 8 of 8 tests passed\n"),
        "{}",
        stdout(&output)
    );
}

#[test]
fn a_flipped_v_is_named_with_the_formula_line_to_fix() {
    let dir = tempfile::tempdir().unwrap();
    let submission = student_with(
        dir.path(),
        "v-sign",
        "v = (0.5 - (row + 0.5) / self.height) * self.vh",
        "v = ((row + 0.5) / self.height - 0.5) * self.vh",
    );
    let results = dir.path().join("results.json");
    let only = ["--test", "oblique", "--test", "canonical rays"];
    let output = autograde(&homework(), &submission, "json", &results, &only);
    assert_eq!(output.status.code(), Some(1), "{}", stdout(&output));
    let value = json(&results);
    assert_eq!(value["score"], 0.0);
    assert_eq!(value["max_score"], 3.0);
    let picture = named(&value["tests"], "oblique");
    assert_eq!(
        picture["message"],
        "the camera is wrong: v-sign (v without its minus sign)"
    );
    let fix = "the lecture says: v = -((i - 1/2)/H - 1/2) vh";
    assert!(
        picture["output"].as_str().unwrap().contains(fix),
        "{picture:#}"
    );
    let numbers = named(&value["tests"], "canonical rays");
    assert_eq!(
        numbers["message"],
        "4 of 5 answers are wrong: the catalogue explains them: v-sign"
    );
    assert!(numbers["output"].as_str().unwrap().contains(fix));
    // The student reads the same on the terminal (GitHub Classroom's log).
    assert!(stdout(&output).contains(fix));
}

#[test]
fn gradescope_reads_points_status_diagnosis_and_thumbnails() {
    let dir = tempfile::tempdir().unwrap();
    let submission = no_shift_student(dir.path());
    let results = dir.path().join("results/results.json");
    let output = autograde(&homework(), &submission, "gradescope", &results, &[]);
    assert_eq!(output.status.code(), Some(1), "{}", stdout(&output));
    let value = json(&results);
    check_gradescope(&value).unwrap();
    assert_eq!(value["score"], 11.0);
    let tests = &value["tests"];
    let shifted = named(tests, "shifted");
    assert_eq!(
        (&shifted["score"], &shifted["max_score"], &shifted["status"]),
        (&0.0.into(), &2.0.into(), &"failed".into())
    );
    assert_eq!(shifted["output_format"], "html");
    let html = shifted["output"].as_str().unwrap();
    assert!(html.contains("the camera is wrong"), "{html}");
    // Expected, yours and the difference, each a small PNG of the 96 x 72 picture.
    for label in ["expected", "yours", "difference"] {
        let at = html
            .find(&format!("alt=\"{label}\" src=\""))
            .unwrap_or_else(|| panic!("no {label} thumbnail in {html}"));
        let url = html[at..].split('"').nth(3).unwrap();
        assert_eq!(thumbnail_size(url), (96, 72));
    }
    let general = named(tests, "general");
    assert_eq!(
        (&general["score"], &general["status"]),
        (&2.0.into(), &"passed".into())
    );
    // Gradescope hides a test until its due date itself: its details stay.
    let later = named(tests, "shifted rays");
    assert_eq!(later["visibility"], "after_due_date");
    assert_eq!(later["status"], "failed");
    assert_eq!(later["output_format"], "text");
}

#[test]
fn prairielearn_reads_a_score_in_0_1_with_images() {
    let dir = tempfile::tempdir().unwrap();
    let submission = no_shift_student(dir.path());
    let results = dir.path().join("results.json");
    let output = autograde(&homework(), &submission, "prairielearn", &results, &[]);
    assert_eq!(output.status.code(), Some(1));
    let bytes = std::fs::read(&results).unwrap();
    let value: Value = serde_json::from_slice(&bytes).unwrap();
    check_prairielearn(&value, bytes.len()).unwrap();
    assert_eq!(value["gradable"], true);
    // 11 of 14 points, to the millionth.
    assert!((value["score"].as_f64().unwrap() - 11.0 / 14.0).abs() < 1e-6);
    let shifted = named(&value["tests"], "shifted");
    assert_eq!(
        (&shifted["points"], &shifted["max_points"]),
        (&0.0.into(), &2.0.into())
    );
    let labels: Vec<&str> = shifted["images"]
        .as_array()
        .unwrap()
        .iter()
        .map(|i| i["label"].as_str().unwrap())
        .collect();
    assert_eq!(labels, ["expected", "yours", "difference"]);
    // PrairieLearn cannot hide a test until later: its details wait.
    let later = named(&value["tests"], "shifted rays");
    assert_eq!(
        later["message"],
        "the details of this test are shown after the due date"
    );
    assert_eq!(later["images"], Value::Array(Vec::new()));
}

#[test]
fn github_classrooms_reporter_decodes_each_step_and_adds_up_the_points() {
    let dir = tempfile::tempdir().unwrap();
    let submission = no_shift_student(dir.path());
    // As the kit's workflow runs it: one step per test.
    let mut steps = Vec::new();
    for (k, name) in ["canonical", "shifted", "general frame and rays"]
        .iter()
        .enumerate()
    {
        let results = dir.path().join(format!("test{}.b64", k + 1));
        let output = autograde(
            &homework(),
            &submission,
            "github",
            &results,
            &["--test", name],
        );
        assert!(output.status.code() == Some(0) || output.status.code() == Some(1));
        let encoded = std::fs::read_to_string(&results).unwrap();
        steps.push((format!("test{}", k + 1), encoded.trim().to_owned()));
    }
    let pairs: Vec<(&str, &str)> = steps
        .iter()
        .map(|(a, b)| (a.as_str(), b.as_str()))
        .collect();
    let reported = github_reporter(&pairs);
    assert_eq!(reported.total_points, 4.0);
    assert_eq!(reported.max_points, 6.0);
    assert_eq!(reported.failed.as_deref(), Some("Some tests failed."));
    let shifted = &reported.results[1];
    assert_eq!(shifted["version"], 1);
    assert_eq!(shifted["status"], "fail");
    let test = &shifted["tests"][0];
    assert_eq!(test["name"], "shifted");
    assert_eq!(test["status"], "fail");
    assert!(
        test["message"]
            .as_str()
            .unwrap()
            .starts_with("the camera is wrong"),
        "{test:#}"
    );
    assert_eq!(test["line_no"], 0);
    assert_eq!(reported.results[0]["status"], "pass");
}

#[test]
fn junitparser_reads_failures_with_their_diagnosis() {
    let dir = tempfile::tempdir().unwrap();
    let submission = no_shift_student(dir.path());
    let results = dir.path().join("junit.xml");
    let output = autograde(&homework(), &submission, "junit", &results, &[]);
    assert_eq!(output.status.code(), Some(1));
    let read = junit(&results);
    let suite = &read["suites"][0];
    assert_eq!(suite["name"], "Homework 3: the lecture's cameras");
    assert_eq!(
        (&suite["tests"], &suite["failures"], &suite["errors"]),
        (&8.into(), &2.into(), &0.into())
    );
    assert_eq!(suite["properties"]["score"], "11");
    assert_eq!(suite["properties"]["max_score"], "14");
    let shifted = named(&suite["cases"], "shifted");
    let failure = &shifted["results"][0];
    assert_eq!(failure["kind"], "Failure");
    assert!(
        failure["message"]
            .as_str()
            .unwrap()
            .starts_with("the camera is wrong")
    );
    assert!(
        failure["text"]
            .as_str()
            .unwrap()
            .contains("the lecture says"),
        "{failure:#}"
    );
    let general = named(&suite["cases"], "general");
    assert_eq!(general["results"], Value::Array(Vec::new()));
    assert!(
        general["system_out"]
            .as_str()
            .unwrap()
            .starts_with("points: 2 of 2")
    );
}

#[test]
fn partial_credit_when_the_camera_is_right_and_the_appearance_is_not() {
    // The example student shades flat colours: with `judge: Both` the camera earns the
    // half the assignment grants.
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("assignment");
    std::fs::create_dir_all(&folder).unwrap();
    let text = std::fs::read_to_string(homework())
        .unwrap()
        .replace("judge: Camera", "judge: Both")
        .replace(
            "image: \"canonical.png\", points: 2.0)",
            "image: \"canonical.png\", points: 2.0, partial: Some(0.5))",
        );
    let assignment = folder.join("homework.ron");
    std::fs::write(&assignment, text).unwrap();
    copy_folder(
        &repository().join("fixtures/autograde/scenes"),
        &folder.join("scenes"),
    );
    let submission = right_student().parent().unwrap().to_path_buf();
    let results = dir.path().join("results.json");
    let output = autograde(
        &assignment,
        &submission,
        "gradescope",
        &results,
        &["--test", "canonical"],
    );
    assert_eq!(output.status.code(), Some(1), "{}", stdout(&output));
    let value = json(&results);
    check_gradescope(&value).unwrap();
    let test = named(&value["tests"], "canonical");
    assert_eq!(
        (&test["score"], &test["status"]),
        (&1.0.into(), &"failed".into())
    );
    assert!(
        test["output"].as_str().unwrap().contains(
            "the camera is right, but the picture does not look like the reference: 1 of 2 points"
        ),
        "{test:#}"
    );
}

fn copy_folder(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
    }
}

#[test]
fn a_broken_assignment_still_writes_valid_results_in_every_format() {
    let dir = tempfile::tempdir().unwrap();
    let assignment = dir.path().join("broken.ron");
    std::fs::write(
        &assignment,
        "(title: \"Broken\", tests: [(name: \"a\", scene: )])",
    )
    .unwrap();
    let submission = dir.path().join("submission");
    std::fs::create_dir(&submission).unwrap();
    let reason = "the assignment file is broken";
    for format in ["gradescope", "prairielearn", "github", "junit", "json"] {
        let results = dir.path().join(format!("results.{format}"));
        let output = autograde(&assignment, &submission, format, &results, &[]);
        assert_eq!(output.status.code(), Some(2), "{format}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.starts_with("error: not graded: "), "{stderr}");
        assert!(stderr.contains("broken.ron:1:"), "{stderr}");
        let bytes = std::fs::read(&results).unwrap();
        match format {
            "gradescope" => {
                let value: Value = serde_json::from_slice(&bytes).unwrap();
                check_gradescope(&value).unwrap();
                assert_eq!(value["score"], 0.0);
                assert!(value["output"].as_str().unwrap().contains(reason));
            }
            "prairielearn" => {
                let value: Value = serde_json::from_slice(&bytes).unwrap();
                check_prairielearn(&value, bytes.len()).unwrap();
                assert_eq!(value["gradable"], false);
                assert!(value["message"].as_str().unwrap().contains(reason));
            }
            "github" => {
                let encoded = String::from_utf8(bytes).unwrap();
                let reported = github_reporter(&[("test1", encoded.trim())]);
                assert_eq!(reported.failed.as_deref(), Some("Some tests errored."));
                let message = reported.results[0]["tests"][0]["message"].as_str().unwrap();
                assert!(message.contains(reason), "{message}");
            }
            "junit" => {
                let read = junit(&results);
                let case = &read["suites"][0]["cases"][0];
                assert_eq!(case["results"][0]["kind"], "Error");
                assert!(
                    case["results"][0]["message"]
                        .as_str()
                        .unwrap()
                        .contains(reason)
                );
            }
            _ => {
                let value: Value = serde_json::from_slice(&bytes).unwrap();
                assert_eq!(value["passed"], false);
                assert!(value["problem"].as_str().unwrap().contains(reason));
            }
        }
    }
}

#[test]
fn a_missing_submission_is_not_graded_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let results = dir.path().join("results.json");
    let output = autograde(
        &homework(),
        &dir.path().join("nowhere"),
        "gradescope",
        &results,
        &[],
    );
    assert_eq!(output.status.code(), Some(2));
    let value = json(&results);
    check_gradescope(&value).unwrap();
    assert!(
        value["output"].as_str().unwrap().contains("nowhere"),
        "{value:#}"
    );
}

/// The README's example (a student who left out the shift, in `alice/`) prints every
/// line the README shows under it, so the README cannot drift from the program.
#[test]
fn the_readme_example_prints_what_the_readme_shows() {
    let readme = std::fs::read_to_string(repository().join("README.md")).unwrap();
    let command = "$ viewray autograde fixtures/autograde/homework.ron alice/ --format gradescope -o results/results.json\n";
    let at = readme.find(command).expect("the README shows the example") + command.len();
    let shown = readme[at..].split("```").next().unwrap();
    let dir = tempfile::tempdir().unwrap();
    let alice = no_shift_student(dir.path());
    let results = dir.path().join("results/results.json");
    let output = autograde(&homework(), &alice, "gradescope", &results, &[]);
    assert_eq!(output.status.code(), Some(1));
    let printed = stdout(&output);
    let lines: Vec<&str> = printed.lines().collect();
    let mut checked = 0;
    for line in shown.lines().filter(|l| *l != "...") {
        assert!(
            lines.contains(&line),
            "the README shows {line:?}; printed:\n{printed}"
        );
        checked += 1;
    }
    assert!(checked >= 15, "{checked}");
}
