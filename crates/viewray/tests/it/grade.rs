//! `viewray grade` as an instructor uses it: a class made here in a temporary folder
//! (a reference folder, one folder per student), exit codes 0 / 1 / 2, the rows, the
//! gradebook, JSON lines and the HTML report.

use std::path::{Path, PathBuf};

use scraper::{Html, Selector};
use serde_json::Value;

use crate::support;
use support::pictures::picture;
use support::{error_line, viewray};

const W: u32 = 96;
const H: u32 = 72;

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// A class: reference/ with `disc.png` and `moved.png` (the same picture), and
///
/// - `alice`: both right (one-sample renders): passes;
/// - `bob`: `disc.png` mirrored, `moved.png` missing, and a `notes.txt`;
/// - `carol`: `disc.png` not a PNG, `Moved.png` for `moved.png`;
/// - `dave`: `moved.png` 12 px right, `disc.png` right;
/// - `erin`: an empty folder;
///
/// and a file `grades.xlsx` beside the students.
fn class(dir: &Path) -> (PathBuf, PathBuf) {
    let (reference, submissions) = (dir.join("reference"), dir.join("submissions"));
    std::fs::create_dir_all(&reference).unwrap();
    let reference_picture = picture(W, H, 4, false, 0.0);
    for name in ["disc.png", "moved.png"] {
        reference_picture.save(reference.join(name)).unwrap();
    }
    let student = |name: &str| {
        let folder = submissions.join(name);
        std::fs::create_dir_all(&folder).unwrap();
        folder
    };
    let correct = picture(W, H, 1, false, 0.0);
    let alice = student("alice");
    correct.save(alice.join("disc.png")).unwrap();
    correct.save(alice.join("moved.png")).unwrap();
    let bob = student("bob");
    picture(W, H, 2, true, 0.0)
        .save(bob.join("disc.png"))
        .unwrap();
    std::fs::write(bob.join("notes.txt"), "my notes").unwrap();
    let carol = student("carol");
    std::fs::write(carol.join("disc.png"), "not a picture").unwrap();
    correct.save(carol.join("Moved.png")).unwrap();
    let dave = student("dave");
    correct.save(dave.join("disc.png")).unwrap();
    picture(W, H, 2, false, 12.0)
        .save(dave.join("moved.png"))
        .unwrap();
    student("erin");
    std::fs::write(submissions.join("grades.xlsx"), "a spreadsheet").unwrap();
    (reference, submissions)
}

#[test]
fn a_class_gets_a_row_per_student_a_summary_and_a_gradebook() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, submissions) = class(dir.path());
    let csv = dir.path().join("gradebook.csv");
    let out = viewray(&["grade", s(&reference), s(&submissions), "--csv", s(&csv)]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    let expected = [
        "STUDENT  PASSED  FAILURES",
        "alice       2/2",
        "bob         0/2  disc.png: mirrored left-right: check u = up x w",
        "                 moved.png: missing",
        "                 (not judged: notes.txt)",
        "carol       0/2  disc.png: not an image viewray reads (PNG, PPM/PGM (P2, P3, P5, P6) or OpenEXR)",
        "                 moved.png: missing (found `Moved.png`: names must match exactly, \
         case included)",
        "                 (not judged: Moved.png)",
        "dave        1/2  moved.png: shifted 12 px right: check the shift (sx, sy)",
        "erin        0/2  disc.png: missing",
        "                 moved.png: missing",
        "not graded, not a folder in SUBMISSIONS: grades.xlsx",
        "5 students, 2 images each: 1 passed everything, 4 failed some (threshold 0.3)",
        "passed per image: disc.png 40%, moved.png 20%",
        "hardest image: moved.png, passed by 1 of 5 (20%)",
        "failures: 4 missing, 1 mirrored left-right, 1 moved 12 px right, 1 unreadable",
    ];
    assert_eq!(stdout.lines().collect::<Vec<_>>(), expected, "{stdout}");
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr, format!("gradebook: {}\n", csv.display()));

    // The gradebook: a line per student and image.
    let mut reader = csv::Reader::from_path(&csv).unwrap();
    assert_eq!(
        reader.headers().unwrap(),
        vec![
            "student",
            "image",
            "verdict",
            "camera",
            "camera_diagnosis",
            "peak_flip",
            "appearance"
        ]
    );
    let rows: Vec<Vec<String>> = reader
        .records()
        .map(|r| r.unwrap().iter().map(str::to_owned).collect())
        .collect();
    assert_eq!(rows.len(), 10);
    let row = |student: &str, image: &str| {
        rows.iter()
            .find(|r| r[0] == student && r[1] == image)
            .unwrap()
            .clone()
    };
    assert_eq!(row("alice", "disc.png")[2..4].len(), 2);
    assert_eq!(row("alice", "disc.png")[2], "pass");
    assert_eq!(row("alice", "disc.png")[4], "");
    let peak: f32 = row("alice", "moved.png")[5].parse().unwrap();
    assert!(peak <= 0.3, "{peak}");
    let mirrored = row("bob", "disc.png");
    assert_eq!(mirrored[2], "fail");
    assert!(mirrored[5].parse::<f32>().unwrap() > 0.3);
    // No scene: the camera is not judged, the appearance is (not for a moved picture).
    assert_eq!((mirrored[3].as_str(), mirrored[6].as_str()), ("", ""));
    assert_eq!(row("alice", "disc.png")[6], "same");
    assert_eq!(mirrored[4], "mirrored left-right: check u = up x w");
    assert_eq!(
        row("bob", "moved.png")[2..],
        ["fail", "", "missing", "", ""]
    );
    assert_eq!(
        row("carol", "disc.png")[4],
        "not an image viewray reads (PNG, PPM/PGM (P2, P3, P5, P6) or OpenEXR)"
    );
    assert_eq!(
        row("dave", "moved.png")[4],
        "shifted 12 px right: check the shift (sx, sy)"
    );
}

#[test]
fn a_class_that_passes_everything_exits_0() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, submissions) = class(dir.path());
    for student in ["bob", "carol", "dave", "erin"] {
        std::fs::remove_dir_all(submissions.join(student)).unwrap();
    }
    let out = viewray(&["grade", s(&reference), s(&submissions)]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("1 student, 2 images each: 1 passed everything, 0 failed some"),
        "{stdout}"
    );
    assert!(!stdout.contains("hardest"), "{stdout}");
}

#[test]
fn json_lines_are_compares_with_the_student() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, submissions) = class(dir.path());
    let out = viewray(&["grade", s(&reference), s(&submissions), "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let lines: Vec<Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).expect("every line is JSON"))
        .collect();
    assert_eq!(lines.len(), 11);
    assert_eq!(lines[0]["student"], "alice");
    assert_eq!(lines[0]["name"], "disc.png");
    assert_eq!(lines[0]["verdict"], "pass");
    let bob = &lines[2];
    assert_eq!(
        (&bob["student"], &bob["name"]),
        (&"bob".into(), &"disc.png".into())
    );
    assert_eq!(bob["transform"]["mirrored_left_right"], true);
    assert_eq!(lines[3]["reasons"], serde_json::json!(["missing"]));
    assert_eq!(
        lines[10]["summary"],
        serde_json::json!({
            "students": 5, "images": 2, "passed_everything": 1,
            "per_image": [{"name": "disc.png", "passed": 2, "total": 5},
                          {"name": "moved.png", "passed": 1, "total": 5}],
            "hardest": ["moved.png"],
            "failures": {"missing": 4, "mirrored left-right": 1, "moved 12 px right": 1,
                         "unreadable": 1},
            "not_graded": ["grades.xlsx"]})
    );
}

/// The elements of `page` that `selector` selects, as their trimmed text.
fn texts(page: &Html, selector: &str) -> Vec<String> {
    page.select(&Selector::parse(selector).unwrap())
        .map(|e| e.text().collect::<String>().trim().to_owned())
        .collect()
}

fn attributes(page: &Html, selector: &str, attribute: &str) -> Vec<String> {
    page.select(&Selector::parse(selector).unwrap())
        .map(|e| e.value().attr(attribute).unwrap_or_default().to_owned())
        .collect()
}

#[test]
fn the_report_shows_the_class_failures_first_and_a_page_per_student() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, submissions) = class(dir.path());
    let report = dir.path().join("report");
    let out = viewray(&[
        "grade",
        s(&reference),
        s(&submissions),
        "--report",
        s(&report),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stdout = String::from_utf8(out.stdout).unwrap();
    let page = Html::parse_document(&std::fs::read_to_string(report.join("index.html")).unwrap());

    // The summary as the terminal prints it, the pass rates aside (the grid has them).
    let lines: Vec<&str> = stdout.lines().collect();
    let n = lines.len();
    assert!(lines[n - 3].starts_with("passed per image:"));
    assert_eq!(
        texts(&page, "p.summary"),
        [lines[n - 4], lines[n - 2], lines[n - 1]]
    );
    // The grid: the images as columns, the students as rows, the most failures first.
    assert_eq!(
        texts(&page, "table.grid thead tr:first-child th.image"),
        ["disc", "moved"]
    );
    assert_eq!(
        texts(&page, "table.grid tbody th.student"),
        ["bob", "carol", "erin", "dave", "alice"]
    );
    assert_eq!(
        texts(&page, "table.grid tbody td.count"),
        ["0/2", "0/2", "0/2", "1/2", "2/2"]
    );
    let cells = attributes(&page, "table.grid tbody td.cell", "class");
    assert_eq!(
        cells,
        [
            "cell fail camera",
            "cell fail missing",
            "cell fail unreadable",
            "cell fail missing",
            "cell fail missing",
            "cell fail missing",
            "cell pass",
            "cell fail camera",
            "cell pass",
            "cell pass"
        ]
    );
    // Each failure is worded in its cell, to read the page printed: what failed and why.
    assert_eq!(
        texts(&page, "table.grid tbody td.cell")[..3],
        [
            "✗ wrong camera: mirrored left-right",
            "? missing",
            "! unreadable"
        ]
    );
    // The diagnosis on hover; a failure links to its place on the student's page.
    let hovers = attributes(&page, "table.grid tbody td.cell", "title");
    assert_eq!(
        hovers[0],
        "disc.png: FAIL: mirrored left-right: check u = up x w"
    );
    assert_eq!(hovers[1], "moved.png: FAIL: missing");
    assert_eq!(hovers[9], "moved.png: PASS");
    let links = attributes(&page, "table.grid tbody td.cell a", "href");
    assert_eq!(links[0], "students/bob.html#disc");
    assert_eq!(
        attributes(&page, "table.grid tbody th.student a", "href")[4],
        "students/alice.html"
    );
    assert_eq!(
        texts(&page, "table.grid thead tr.rates td.rate"),
        ["40%", "20%"]
    );
    assert_eq!(
        attributes(&page, "table.grid thead tr.rates td.rate", "class"),
        ["rate", "rate hardest"]
    );

    // Bob's page: each failure with its diagnosis and thumbnails that exist.
    let students = report.join("students");
    let bob = Html::parse_document(&std::fs::read_to_string(students.join("bob.html")).unwrap());
    assert_eq!(texts(&bob, "h1"), ["bob"]);
    assert_eq!(
        texts(&bob, "section.failure h2"),
        ["FAIL disc.png", "FAIL moved.png"]
    );
    assert_eq!(attributes(&bob, "section.failure", "id"), ["disc", "moved"]);
    assert_eq!(
        texts(&bob, "section.failure p.diagnosis"),
        ["mirrored left-right: check u = up x w", "missing"]
    );
    assert_eq!(
        texts(&bob, "section#disc figcaption"),
        ["expected", "actual", "FLIP heatmap"]
    );
    // A missing render has its expected image alone.
    assert_eq!(texts(&bob, "section#moved figcaption"), ["expected"]);
    for src in attributes(&bob, "section.failure img", "src") {
        let file = students.join(&src);
        let thumbnail = image::open(&file).unwrap_or_else(|e| panic!("{src}: {e}"));
        assert_eq!((thumbnail.width(), thumbnail.height()), (W, H));
    }
    assert_eq!(
        texts(&bob, "p.extra"),
        ["not judged, only in the student's folder: notes.txt"]
    );
    // Alice passed: no failure section, her images listed as passed.
    let alice =
        Html::parse_document(&std::fs::read_to_string(students.join("alice.html")).unwrap());
    assert!(texts(&alice, "section.failure").is_empty());
    assert_eq!(texts(&alice, "p.passed"), ["PASS disc.png, moved.png"]);
}

#[test]
fn large_renders_are_shrunk_to_thumbnails() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, submissions) = (dir.path().join("reference"), dir.path().join("class"));
    std::fs::create_dir_all(&reference).unwrap();
    std::fs::create_dir_all(submissions.join("ann")).unwrap();
    picture(480, 360, 2, false, 0.0)
        .save(reference.join("big.png"))
        .unwrap();
    picture(480, 360, 1, true, 0.0)
        .save(submissions.join("ann").join("big.png"))
        .unwrap();
    let report = dir.path().join("report");
    let out = viewray(&[
        "grade",
        s(&reference),
        s(&submissions),
        "--report",
        s(&report),
    ]);
    assert_eq!(out.status.code(), Some(1));
    for file in [
        "reference/big.png",
        "students/ann/big.actual.png",
        "students/ann/big.diff.png",
    ] {
        let thumbnail = image::open(report.join(file)).unwrap();
        assert_eq!(
            (thumbnail.width(), thumbnail.height()),
            (240, 180),
            "{file}"
        );
    }
}

#[test]
fn bad_usage_is_one_line_exit_code_2_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, submissions) = class(dir.path());
    let csv = dir.path().join("out.csv");
    let report = dir.path().join("out-report");
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let file = reference.join("disc.png");
    let missing = dir.path().join("nowhere");
    let cases: [(&Path, &Path, &str); 5] = [
        (&missing, &submissions, "REFERENCE `"),
        (
            &empty,
            &submissions,
            "holds no image (*.png, *.ppm, *.pgm or *.exr file)",
        ),
        (&file, &submissions, "is not a folder"),
        (&reference, &file, "SUBMISSIONS"),
        (
            &reference,
            &empty,
            "holds no folder: it must hold one folder per student",
        ),
    ];
    for (reference, submissions, says) in cases {
        let line = error_line(&[
            "grade",
            s(reference),
            s(submissions),
            "--csv",
            s(&csv),
            "--report",
            s(&report),
        ]);
        assert!(line.contains(says), "{line}");
    }
    assert!(!csv.exists() && !report.exists());
    // A gradebook whose folder does not exist is found out before grading.
    let nowhere = dir.path().join("no-such-folder").join("book.csv");
    let line = error_line(&[
        "grade",
        s(&reference),
        s(&submissions),
        "--csv",
        s(&nowhere),
    ]);
    assert!(line.contains("its folder does not exist"), "{line}");
    // A reference image that is not a PNG is bad input too.
    std::fs::write(reference.join("broken.png"), "not a picture").unwrap();
    let line = error_line(&["grade", s(&reference), s(&submissions)]);
    assert!(
        line.contains("broken.png") && line.contains("not an image viewray reads"),
        "{line}"
    );
}

#[test]
fn a_flat_download_is_graded_by_the_names_course_sites_give_with_feedback_per_student() {
    let dir = tempfile::tempdir().unwrap();
    let (reference, submissions) = class(dir.path());
    let flat = dir.path().join("flat");
    std::fs::create_dir(&flat).unwrap();
    // Canvas names alice's files (a late resubmission among them), Moodle bob's.
    for (from, to) in [
        ("alice/disc.png", "alicesmith_12_34_disc.png"),
        ("alice/moved.png", "alicesmith_late_12_35_moved-1.png"),
        ("bob/disc.png", "Bob Jones_7_assignsubmission_file_disc.png"),
    ] {
        std::fs::copy(submissions.join(from), flat.join(to)).unwrap();
    }
    std::fs::write(flat.join("index.html"), "the course site's page").unwrap();
    let feedback = dir.path().join("feedback");
    let out = viewray(&[
        "grade",
        s(&reference),
        s(&flat),
        "--flat",
        "--feedback",
        s(&feedback),
    ]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(
        lines[..4],
        [
            "STUDENT     PASSED  FAILURES",
            "Bob Jones      0/2  disc.png: mirrored left-right: check u = up x w",
            "                    moved.png: missing",
            "alicesmith     2/2",
        ],
        "{stdout}"
    );
    assert_eq!(
        lines[4],
        "not graded, not named as a course site names submissions: index.html"
    );
    let bob = std::fs::read_to_string(feedback.join("Bob_Jones.txt")).unwrap();
    assert_eq!(
        bob,
        "Bob Jones: 0 of 2 images passed\n\
         \n\
         disc.png: wrong camera\n  mirrored left-right: check u = up x w\n\
         \n\
         moved.png: missing\n"
    );
    let alice = std::fs::read_to_string(feedback.join("alicesmith.txt")).unwrap();
    assert_eq!(
        alice,
        "alicesmith: 2 of 2 images passed\n\npassed: disc.png, moved.png\n"
    );
    // Folders given as a flat class: bad usage, with a hint.
    let line = support::error_line(&["grade", s(&reference), s(&submissions), "--flat"]);
    assert!(line.contains("leave out --flat"), "{line}");
}
