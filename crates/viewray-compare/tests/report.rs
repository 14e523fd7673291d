//! The HTML report: the files it writes and what the page says.

mod scene;

use scene::{Mistake, Pattern, Scene};
use viewray_compare::{InstructorThresholds, ReportEntry, judge, load_png, write_report};

#[test]
fn the_report_shows_each_pair_with_its_figures_verdict_and_diagnosis() {
    let (w, h) = (64, 48);
    let reference = Scene::default().render(w, h, Mistake::NONE, Pattern::Grid(4));
    let correct = Scene::default().render(w, h, Mistake::NONE, Pattern::Center);
    let mirrored = Scene::default().render(
        w,
        h,
        Mistake {
            mirror_x: true,
            ..Mistake::NONE
        },
        Pattern::Center,
    );
    let thresholds = InstructorThresholds::default();
    let passed = judge(&reference, &correct, &thresholds);
    let failed = judge(&reference, &mirrored, &thresholds);
    assert!(passed.passed() && !failed.passed());
    let entries = [
        ReportEntry::compared("correct.png", &reference, &correct, &passed),
        ReportEntry::compared("mirrored <x>.png", &reference, &mirrored, &failed),
        ReportEntry::error(
            "lonely.png",
            "lonely.png: only in EXPECTED",
            Some(&reference),
            None,
        ),
    ];
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let page_path = write_report(&out, &entries).unwrap();
    assert_eq!(page_path, out.join("index.html"));

    let mut files: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    files.sort();
    assert_eq!(
        files,
        [
            "correct.actual.png",
            "correct.diff.png",
            "correct.expected.png",
            "index.html",
            "lonely.expected.png",
            "mirrored__x_.actual.png",
            "mirrored__x_.diff.png",
            "mirrored__x_.expected.png",
        ]
    );
    assert_eq!(load_png(out.join("correct.actual.png")).unwrap(), correct);
    assert_eq!(
        load_png(out.join("mirrored__x_.diff.png"))
            .unwrap()
            .dimensions(),
        (w, h)
    );

    let page = std::fs::read_to_string(&page_path).unwrap();
    assert!(
        page.contains("1 passed, 1 failed, 1 could not be compared, of 3."),
        "{page}"
    );
    assert!(page.contains("mirrored &lt;x&gt;.png"));
    assert!(page.contains("mirrored left-right: check u = up x w"));
    assert!(page.contains("lonely.png: only in EXPECTED"));
    assert!(page.contains("<img src=\"correct.diff.png\""));
    for section in ["correct", "mirrored__x_", "lonely"] {
        assert!(
            page.contains(&format!("<section id=\"{section}\"")),
            "{section}"
        );
    }

    // The same entries give the same bytes (no timestamps).
    write_report(&out, &entries).unwrap();
    assert_eq!(std::fs::read_to_string(&page_path).unwrap(), page);
}
