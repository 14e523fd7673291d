//! `viewray compare` as an instructor uses it: PNGs made here in a temporary folder, exit
//! codes 0 / 1 / 2, the summary table, JSON lines and the HTML report.

use std::path::Path;

use image::{Rgba, RgbaImage};
use serde_json::Value;

use crate::support;
use support::pictures::picture;
use support::{error_line, viewray};

const W: u32 = 96;
const H: u32 = 72;

fn reference() -> RgbaImage {
    picture(W, H, 4, false, 0.0)
}

fn save(image: &RgbaImage, path: &Path) {
    image.save(path).unwrap();
}

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// Two folders: `correct.png` (a one-sample render: passes), `mirrored.png` (fails,
/// diagnosed), `moved.png` (the picture 12 px right: fails, diagnosed), `small.png`
/// (another size), `notes.png` (not a PNG), `extra.png` (only in EXPECTED), and
/// `readme.txt` (only in ACTUAL).
fn folders(dir: &Path) -> (std::path::PathBuf, std::path::PathBuf) {
    let (expected, actual) = (dir.join("expected"), dir.join("actual"));
    std::fs::create_dir_all(&expected).unwrap();
    std::fs::create_dir_all(&actual).unwrap();
    for name in [
        "correct.png",
        "mirrored.png",
        "moved.png",
        "small.png",
        "notes.png",
        "extra.png",
    ] {
        save(&reference(), &expected.join(name));
    }
    save(&picture(W, H, 1, false, 0.0), &actual.join("correct.png"));
    save(&picture(W, H, 1, true, 0.0), &actual.join("mirrored.png"));
    save(&picture(W, H, 2, false, 12.0), &actual.join("moved.png"));
    save(
        &picture(W / 2, H / 2, 2, false, 0.0),
        &actual.join("small.png"),
    );
    std::fs::write(actual.join("notes.png"), "these are notes, not a picture").unwrap();
    std::fs::write(actual.join("readme.txt"), "not compared").unwrap();
    (expected, actual)
}

#[test]
fn two_matching_files_pass_with_exit_code_0() {
    let dir = tempfile::tempdir().unwrap();
    let (expected, actual) = (dir.path().join("ref.png"), dir.path().join("student.png"));
    save(&reference(), &expected);
    save(&picture(W, H, 1, false, 0.0), &actual);
    let out = viewray(&["compare", s(&expected), s(&actual)]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(lines.len(), 3, "{stdout}");
    assert!(lines[0].starts_with("NAME") && lines[0].contains("VERDICT"));
    assert!(lines[1].starts_with("student.png  PASS"), "{stdout}");
    assert_eq!(lines[2], "1 image: 1 passed, 0 failed (threshold 0.3)");
    assert!(out.stderr.is_empty());
}

#[test]
fn folders_are_paired_like_diff_r_and_every_problem_is_a_row() {
    let dir = tempfile::tempdir().unwrap();
    let (expected, actual) = folders(dir.path());
    let out = viewray(&["compare", s(&expected), s(&actual)]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    // A missing or unreadable render is the student's failure: exit code 1, every pair
    // still judged.
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(out.stderr.is_empty());
    let row = |name: &str| {
        stdout
            .lines()
            .find(|l| l.starts_with(name))
            .unwrap_or_else(|| panic!("no row for {name}: {stdout}"))
            .to_owned()
    };
    assert!(row("correct.png").contains("PASS"));
    assert!(row("mirrored.png").contains("FAIL"));
    assert!(row("mirrored.png").ends_with("mirrored left-right: check u = up x w"));
    assert!(row("moved.png").ends_with("shifted 12 px right: check the shift (sx, sy)"));
    assert!(row("small.png").ends_with("sizes differ: expected 96x72, actual 48x36"));
    assert_eq!(
        row("notes.png"),
        "notes.png     FAIL     -          not an image viewray reads (PNG, PPM/PGM (P2, P3, P5, P6) or OpenEXR)"
    );
    assert_eq!(
        row("extra.png"),
        "extra.png     FAIL     -          missing"
    );
    assert!(
        stdout.contains("\nnot judged, only in ACTUAL: readme.txt\n"),
        "{stdout}"
    );
    assert!(
        stdout.ends_with(
            "6 images: 1 passed, 5 failed, 2 of them missing or unreadable (threshold 0.3)\n"
        ),
        "{stdout}"
    );
}

#[test]
fn a_render_folder_with_a_link_out_of_it_or_nothing_in_it_fails_each_image() {
    let dir = tempfile::tempdir().unwrap();
    let (expected, actual) = folders(dir.path());
    // A student's "render" that is a link to the reference itself.
    std::fs::remove_file(actual.join("correct.png")).unwrap();
    std::os::unix::fs::symlink(expected.join("correct.png"), actual.join("correct.png")).unwrap();
    let out = viewray(&["compare", s(&expected), s(&actual)]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    let row = stdout
        .lines()
        .find(|l| l.starts_with("correct.png"))
        .unwrap();
    assert!(
        row.contains("FAIL") && row.contains("not read: a symbolic link out of the folder"),
        "{row}"
    );
    // An empty render folder: every image missing.
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    let out = viewray(&["compare", s(&expected), s(&empty)]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert_eq!(stdout.matches("  missing").count(), 6, "{stdout}");
    assert!(stdout.ends_with(
        "6 images: 0 passed, 6 failed, 6 of them missing or unreadable (threshold 0.3)\n"
    ));
}

#[test]
fn a_problem_on_the_reference_side_or_a_file_given_directly_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let (expected, actual) = folders(dir.path());
    // A reference image that is not a PNG: nothing is judged.
    std::fs::write(expected.join("broken.png"), "not a picture").unwrap();
    let line = error_line(&["compare", s(&expected), s(&actual)]);
    assert!(
        line.contains("broken.png") && line.contains("not an image viewray reads"),
        "{line}"
    );
    // Files given directly: either one unreadable is bad input.
    let good = expected.join("correct.png");
    let notes = actual.join("notes.png");
    for args in [[s(&good), s(&notes)], [s(&notes), s(&good)]] {
        let line = error_line(&["compare", args[0], args[1]]);
        assert!(
            line.contains("notes.png: not an image viewray reads"),
            "{line}"
        );
    }
}

#[test]
fn folders_whose_pairs_all_compare_exit_1_when_one_fails() {
    let dir = tempfile::tempdir().unwrap();
    let (expected, actual) = folders(dir.path());
    for name in ["notes.png", "extra.png"] {
        std::fs::remove_file(expected.join(name)).unwrap();
        let _ = std::fs::remove_file(actual.join(name));
    }
    let out = viewray(&["compare", s(&expected), s(&actual)]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    assert!(stdout.ends_with("4 images: 1 passed, 3 failed (threshold 0.3)\n"));
    // Without the failing pairs, all pass.
    for name in ["mirrored.png", "moved.png", "small.png"] {
        std::fs::remove_file(expected.join(name)).unwrap();
        std::fs::remove_file(actual.join(name)).unwrap();
    }
    assert_eq!(
        viewray(&["compare", s(&expected), s(&actual)])
            .status
            .code(),
        Some(0)
    );
}

#[test]
fn json_lines_parse_and_end_with_a_summary() {
    let dir = tempfile::tempdir().unwrap();
    let (expected, actual) = folders(dir.path());
    let out = viewray(&["compare", s(&expected), s(&actual), "--json"]);
    assert_eq!(out.status.code(), Some(1));
    let lines: Vec<Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).expect("every line is JSON"))
        .collect();
    assert_eq!(lines.len(), 7);
    let by_name = |name: &str| lines.iter().find(|l| l["name"] == name).unwrap();
    assert_eq!(by_name("correct.png")["verdict"], "pass");
    assert!(by_name("correct.png")["peak_flip"].as_f64().unwrap() < 0.3);
    let mirrored = by_name("mirrored.png");
    assert_eq!(mirrored["verdict"], "fail");
    assert_eq!(
        mirrored["diagnosis"][0],
        "mirrored left-right: check u = up x w"
    );
    assert_eq!(mirrored["transform"]["mirrored_left_right"], true);
    let moved = by_name("moved.png");
    let shift_x = moved["transform"]["shift"][0].as_f64().unwrap();
    assert!((shift_x - 12.0).abs() < 0.3, "{moved}");
    assert_eq!(by_name("notes.png")["verdict"], "fail");
    assert_eq!(by_name("notes.png")["peak_flip"], Value::Null);
    assert_eq!(by_name("extra.png")["verdict"], "fail");
    assert_eq!(
        by_name("extra.png")["reasons"],
        serde_json::json!(["missing"])
    );
    assert_eq!(
        lines[6]["summary"],
        serde_json::json!({"total": 6, "passed": 1, "failed": 5,
                           "missing_or_unreadable": 2, "extra": ["readme.txt"]})
    );
}

#[test]
fn report_writes_a_page_and_heatmaps() {
    let dir = tempfile::tempdir().unwrap();
    let (expected, actual) = folders(dir.path());
    let report = dir.path().join("report");
    let out = viewray(&["compare", s(&expected), s(&actual), "--report", s(&report)]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert!(
        stderr.contains("report: ") && stderr.contains("index.html"),
        "{stderr}"
    );
    let page = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(page.contains("mirrored left-right: check u = up x w"));
    // The page says what the terminal says: the same summary line, the same verdict
    // for each pair, in the same order.
    let html = scraper::Html::parse_document(&page);
    let select = |selector: &str| -> Vec<String> {
        html.select(&scraper::Selector::parse(selector).unwrap())
            .map(|e| {
                e.text()
                    .collect::<String>()
                    .split_whitespace()
                    .collect::<Vec<_>>()
                    .join(" ")
            })
            .collect()
    };
    let stdout = String::from_utf8(out.stdout).unwrap();
    let lines: Vec<&str> = stdout.lines().collect();
    assert_eq!(select("p.summary"), [*lines.last().unwrap()]);
    // The rows: between the heading and the line of files judged nowhere.
    let terminal: Vec<String> = lines[1..lines.len() - 2]
        .iter()
        .map(|row| {
            let words: Vec<&str> = row.split_whitespace().collect();
            format!("{} {}", words[1], words[0])
        })
        .collect();
    assert_eq!(select("section.entry h2"), terminal);
    assert!(
        terminal.contains(&"FAIL extra.png".to_owned()),
        "{terminal:?}"
    );
    assert!(select("section.entry.fail tr.error td").contains(&"missing".to_owned()));
    for name in ["correct", "mirrored", "moved"] {
        let heatmap = image::open(report.join(format!("{name}.diff.png"))).unwrap();
        assert_eq!((heatmap.width(), heatmap.height()), (W, H));
        assert!(page.contains(&format!("src=\"{name}.diff.png\"")));
    }
}

#[test]
fn the_threshold_decides_a_small_difference() {
    let dir = tempfile::tempdir().unwrap();
    let (expected, actual) = (dir.path().join("a.png"), dir.path().join("b.png"));
    save(&reference(), &expected);
    // The yellow bar recoloured: not a camera mistake, a visible difference.
    let mut recoloured = reference();
    for pixel in recoloured.pixels_mut() {
        if pixel[0] > 200 && pixel[1] > 180 && pixel[2] < 120 {
            *pixel = Rgba([120, 200, 255, 255]);
        }
    }
    save(&recoloured, &actual);
    assert_eq!(
        viewray(&["compare", s(&expected), s(&actual)])
            .status
            .code(),
        Some(1)
    );
    let out = viewray(&["compare", s(&expected), s(&actual), "--threshold", "1"]);
    assert_eq!(out.status.code(), Some(0));
}

#[test]
fn bad_usage_is_one_line_and_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("a.png");
    save(&reference(), &file);
    let missing = dir.path().join("missing");
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    assert!(error_line(&["compare", s(&missing), s(&file)]).contains("EXPECTED"));
    assert!(error_line(&["compare", s(&file), s(&missing)]).contains("does not exist"));
    assert!(
        error_line(&["compare", s(&file), s(dir.path())])
            .contains("give two PNG files or two folders")
    );
    assert!(
        error_line(&["compare", s(&empty), s(&empty)])
            .contains("holds no image (*.png, *.ppm, *.pgm or *.exr file)")
    );
    assert!(error_line(&["compare", s(&file), s(&file), "--threshold", "1.5"]).contains("[0, 1]"));
    assert!(error_line(&["compare", s(&file)]).contains("ACTUAL"));
}
