//! A right camera is never accused: every fixture scene, rendered by viewray itself at its
//! own size (one sample, and the scene's own count), is judged by `viewray compare
//! --scene` against its golden render with its scene. Each must pass, and its camera must
//! be right, or (when the scene's edges are too weak to judge a camera from: smooth
//! shading, defocus blur, a few pixels) left to the image judgement: never "wrong".
//! Sample counts are not errors.
//!
//! Turned round (the one-sample render as the reference), no camera is accused either.
//!
//! The homework scenes (a few pixels each) are judged the same way, against viewray's own
//! render of them at their own sample count.

use crate::support;

use std::path::{Path, PathBuf};

use serde_json::Value;
use support::{repository, viewray};

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The `.ron` scenes of `folder`, sorted.
fn scenes(folder: &Path) -> Vec<PathBuf> {
    let mut found: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    found.sort();
    found
}

/// Renders `scene` with viewray into `out`, with `samples` samples when given (else the
/// scene's own).
fn render(scene: &Path, out: &Path, samples: Option<u32>) {
    let samples = samples.map(|n| n.to_string());
    let mut args = vec!["render", s(scene), "-o", s(out)];
    if let Some(samples) = &samples {
        args.extend(["--samples", samples.as_str()]);
    }
    let done = viewray(&args);
    assert!(
        done.status.success(),
        "{}: {}",
        scene.display(),
        String::from_utf8_lossy(&done.stderr)
    );
}

/// `viewray compare reference student --scene scenes --json`: the lines of the pairs.
fn compare(reference: &Path, student: &Path, scenes: &Path) -> Vec<Value> {
    let out = viewray(&[
        "compare",
        s(reference),
        s(student),
        "--scene",
        s(scenes),
        "--json",
    ]);
    let lines: Vec<Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|line| serde_json::from_str(line).expect("every line is JSON"))
        .collect();
    assert!(
        out.status.code() == Some(0) || out.status.code() == Some(1),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    lines
        .into_iter()
        .filter(|line| line.get("summary").is_none())
        .collect()
}

/// The pictures whose camera cannot be judged, as `what` and the image's name: their
/// reference's edges are too weak (depth shading is smooth and has no sharp object edge,
/// a large aperture blurs, a tilted lens blurs all but a band of the tabletop, sixteen
/// pixels show too little). Every other right render's camera must be found right, not
/// merely left unjudged.
const UNJUDGED: [(&str, &str); 5] = [
    ("1 sample", "shading_depth.png"),
    ("own", "shading_depth.png"),
    ("own", "thin_lens_large_aperture.png"),
    ("own", "thin_lens_tilted.png"),
    ("homework", "lit_4x4.png"),
];

/// Checks every pair of `lines` (of `what`): passed, its camera right (or unjudged where
/// [`UNJUDGED`] says), never wrong. Returns the failures and how many cameras were found
/// right, and prints each line's camera and diagnosis.
fn check(what: &str, lines: &[Value]) -> (Vec<String>, usize) {
    let mut wrong = Vec::new();
    let mut right = 0;
    for line in lines {
        let (name, camera, verdict) = (&line["name"], &line["camera"], &line["verdict"]);
        println!(
            "{what:10} {name:36} {verdict:6} camera {camera:10} {}",
            line["camera_diagnosis"]
        );
        if camera == "right" {
            right += 1;
        }
        let unjudged = UNJUDGED.iter().any(|&(w, n)| w == what && name == n);
        let want = if unjudged { "unjudged" } else { "right" };
        if verdict != "pass" || camera != want {
            wrong.push(format!("{what} {name} (camera should be {want}): {line}"));
        }
    }
    (wrong, right)
}

#[test]
fn every_fixture_rendered_by_viewray_passes_the_camera_judgement() {
    let root = repository();
    let dir = tempfile::tempdir().unwrap();
    let scene_folder = root.join("fixtures/scenes");
    let (reference, one, own) = (
        dir.path().join("reference"),
        dir.path().join("one-sample"),
        dir.path().join("own-samples"),
    );
    for folder in [&reference, &one, &own] {
        std::fs::create_dir_all(folder).unwrap();
    }
    let all = scenes(&scene_folder);
    assert!(all.len() >= 30, "{} fixture scenes", all.len());
    for scene in &all {
        let stem = scene.file_stem().unwrap().to_str().unwrap();
        let image = format!("{stem}.png");
        std::fs::copy(
            root.join("golden/scenes").join(&image),
            reference.join(&image),
        )
        .unwrap();
        render(scene, &one.join(&image), Some(1));
        render(scene, &own.join(&image), None);
    }
    let mut wrong = Vec::new();
    let mut right = 0;
    for (what, student) in [("1 sample", &one), ("own", &own)] {
        let lines = compare(&reference, student, &scene_folder);
        assert_eq!(lines.len(), all.len(), "{lines:?}");
        let (failed, judged_right) = check(what, &lines);
        wrong.extend(failed);
        right += judged_right;
    }

    // Turned round, a one-sample reference (a lens's is a pinhole's picture, sharp)
    // against the scene's own count: the verdict may fail by the image judgement (the
    // large aperture's blur is not in the reference), but no camera is accused.
    for line in compare(&one, &own, &scene_folder) {
        println!(
            "reversed   {:36} {:6} camera {}",
            line["name"], line["verdict"], line["camera"]
        );
        if line["camera"] == "wrong" {
            wrong.push(format!("reversed {}: {line}", line["name"]));
        }
    }

    // The homework scenes: viewray's render at their own sample count is the reference.
    let homework = root.join("fixtures/homework");
    let (reference, one) = (
        dir.path().join("homework-reference"),
        dir.path().join("homework-one"),
    );
    for folder in [&reference, &one] {
        std::fs::create_dir_all(folder).unwrap();
    }
    let tasks = scenes(&homework);
    for scene in &tasks {
        let image = format!("{}.png", scene.file_stem().unwrap().to_str().unwrap());
        render(scene, &reference.join(&image), None);
        render(scene, &one.join(&image), Some(1));
    }
    let lines = compare(&reference, &one, &homework);
    assert_eq!(lines.len(), tasks.len(), "{lines:?}");
    let (failed, judged_right) = check("homework", &lines);
    wrong.extend(failed);
    right += judged_right;

    let total = 2 * all.len() + tasks.len();
    println!(
        "{} of {total} right renders pass ({right} judged right by their camera)",
        total - wrong.len()
    );
    assert!(
        wrong.is_empty(),
        "{} right renders failed or were accused:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
}
