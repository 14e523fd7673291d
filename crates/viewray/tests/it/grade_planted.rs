//! viewray-compare's matrix of planted camera mistakes, run through `viewray grade`: a
//! class made from the matrix (one student per planted case, who hands in the case's
//! render and correct renders of the other images), graded with and without the
//! reference scenes; the gradebook must name every case's mistake as the matrix says.

use std::collections::BTreeMap;
use std::path::Path;

use crate::support;
use support::viewray;

use crate::planted;

use planted::Case;

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The reference image a case is judged against, e.g. `boxes_192x144.png`.
fn image_name(case: &Case) -> String {
    format!("{}_{}x{}.png", case.base.name(), case.size.0, case.size.1)
}

/// The gradebook's lines by (student, image): verdict and diagnosis.
fn gradebook(path: &Path) -> BTreeMap<(String, String), (String, String)> {
    let mut reader = csv::Reader::from_path(path).unwrap();
    reader
        .records()
        .map(|record| {
            let r = record.unwrap();
            (
                (r[0].to_owned(), r[1].to_owned()),
                (r[2].to_owned(), r[4].to_owned()),
            )
        })
        .collect()
}

#[test]
fn every_planted_mistake_is_named_in_the_gradebook() {
    let cases = planted::cases();
    let dir = tempfile::tempdir().unwrap();
    let (reference, scenes, submissions) = (
        dir.path().join("reference"),
        dir.path().join("scenes"),
        dir.path().join("submissions"),
    );
    for folder in [&reference, &scenes, &submissions] {
        std::fs::create_dir_all(folder).unwrap();
    }
    // The assignment: one reference image per base scene and size, with its scene.
    let mut images = BTreeMap::new();
    for case in &cases {
        let name = image_name(case);
        if let std::collections::btree_map::Entry::Vacant(entry) = images.entry(name) {
            let path = reference.join(entry.key());
            case.render_reference().save(&path).unwrap();
            let stem = entry.key().trim_end_matches(".png");
            std::fs::write(scenes.join(format!("{stem}.ron")), case.reference_scene()).unwrap();
            entry.insert(path);
        }
    }
    // A student per case: its render, and a copy of the reference for every other image.
    for case in &cases {
        let folder = submissions.join(&case.name);
        std::fs::create_dir_all(&folder).unwrap();
        for (name, path) in &images {
            if *name == image_name(case) {
                case.render_student().save(folder.join(name)).unwrap();
            } else {
                std::fs::copy(path, folder.join(name)).unwrap();
            }
        }
    }

    let mut wrong = Vec::new();
    for with_scene in [true, false] {
        let csv = dir.path().join(format!("gradebook-{with_scene}.csv"));
        let mut args = vec!["grade", s(&reference), s(&submissions), "--csv", s(&csv)];
        if with_scene {
            // The image judgement, worded with the scenes (the camera judgement, the
            // default with scenes, is held to the catalogue by judge_matrix.rs).
            args.extend(["--scene", s(&scenes), "--judge", "image"]);
        }
        let out = viewray(&args);
        assert_eq!(
            out.status.code(),
            Some(1),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let stdout = String::from_utf8(out.stdout).unwrap();
        let book = gradebook(&csv);
        assert_eq!(book.len(), cases.len() * images.len());
        for case in &cases {
            for name in images.keys() {
                let (verdict, diagnosis) = &book[&(case.name.clone(), name.clone())];
                let planted_here = *name == image_name(case);
                let (passes, want) = if planted_here {
                    let want = if with_scene {
                        &case.with_scene
                    } else {
                        &case.without_scene
                    };
                    (case.passes, want.as_str())
                } else {
                    (true, "")
                };
                let verdict_ok = verdict == if passes { "pass" } else { "fail" };
                if !verdict_ok || !planted::same_message(diagnosis, want) {
                    wrong.push(format!(
                        "{} {name} ({}): {verdict} {diagnosis:?}, want {want:?}",
                        case.name,
                        if with_scene {
                            "with the scenes"
                        } else {
                            "in pixels"
                        }
                    ));
                }
            }
            // The student's row names the planted failure.
            if !case.passes {
                let row = stdout
                    .lines()
                    .find(|l| l.starts_with(&format!("{} ", case.name)))
                    .unwrap_or_else(|| panic!("no row for {}:\n{stdout}", case.name));
                assert!(row.contains(&format!("{}: ", image_name(case))), "{row}");
            }
        }
        let failing = cases.iter().filter(|c| !c.passes).count();
        assert!(
            stdout.contains(&format!(
                "{} students, {} images each: {} passed everything, {failing} failed some",
                cases.len(),
                images.len(),
                cases.len() - failing
            )),
            "{stdout}"
        );
    }
    assert!(
        wrong.is_empty(),
        "{} wrong:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
}
