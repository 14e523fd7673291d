//! The HTML report: the files it writes and what the page says.

use crate::scene;

use scene::{Mistake, Pattern, Scene};
use scraper::{ElementRef, Html, Selector};
use viewray_compare::{
    InstructorThresholds, Outcome, Report, ReportEntry, Rules, Thresholds, compare, judge,
    load_png, write_report,
};

/// The elements of `page` that `selector` selects.
fn select<'a>(page: &'a Html, selector: &str) -> Vec<ElementRef<'a>> {
    page.select(&Selector::parse(selector).unwrap()).collect()
}

/// The text of `element`, whitespace collapsed.
fn text(element: &ElementRef<'_>) -> String {
    element
        .text()
        .collect::<String>()
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The texts of the elements under `element` that `selector` selects.
fn texts_in(element: &ElementRef<'_>, selector: &str) -> Vec<String> {
    element
        .select(&Selector::parse(selector).unwrap())
        .map(|e| text(&e))
        .collect()
}

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
    let passed = Outcome::from(judge(&reference, &correct, &thresholds));
    let failed = Outcome::from(judge(&reference, &mirrored, &thresholds));
    assert!(passed.passed() && !failed.passed());
    let missing = Outcome::Failed("missing".to_owned());
    let entries = [
        ReportEntry::new("correct.png", Some(&reference), Some(&correct), &passed),
        ReportEntry::new(
            "mirrored <x>.png",
            Some(&reference),
            Some(&mirrored),
            &failed,
        ),
        ReportEntry {
            name: "lonely.png",
            expected: Some(&reference),
            actual: None,
            outcome: &missing,
        },
    ];
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("report");
    let report = Report {
        title: "viewray compare a/ b/",
        summary: "3 images: 1 passed, 2 failed, 1 of them missing or unreadable (threshold 0.3)",
        rules: Rules::Instructor(thresholds),
        entries: &entries,
    };
    let page_path = write_report(&out, &report).unwrap();
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

    let source = std::fs::read_to_string(&page_path).unwrap();
    let page = Html::parse_document(&source);
    assert!(page.errors.is_empty(), "{:?}", page.errors);
    assert_eq!(
        texts_in(&page.root_element(), "h1"),
        ["viewray compare a/ b/"]
    );
    // The summary is the terminal's line, word for word.
    assert_eq!(
        texts_in(&page.root_element(), "p.summary"),
        [report.summary]
    );
    // The index lists the failed pairs, a missing render with them.
    assert_eq!(
        texts_in(&page.root_element(), "p.index"),
        ["FAIL mirrored <x>.png lonely.png"]
    );
    let links: Vec<&str> = select(&page, "p.index a")
        .iter()
        .map(|a| a.value().attr("href").unwrap())
        .collect();
    assert_eq!(links, ["#mirrored__x_", "#lonely"]);

    // One section per pair, in order, with the terminal's verdict word.
    let sections = select(&page, "section.entry");
    let headings: Vec<String> = sections
        .iter()
        .map(|s| texts_in(s, "h2")[0].clone())
        .collect();
    assert_eq!(
        headings,
        [
            "PASS correct.png",
            "FAIL mirrored <x>.png",
            "FAIL lonely.png"
        ]
    );
    let ids: Vec<&str> = sections.iter().map(|s| s.value().id().unwrap()).collect();
    assert_eq!(ids, ["correct", "mirrored__x_", "lonely"]);
    let classes: Vec<Vec<&str>> = sections
        .iter()
        .map(|s| s.value().classes().collect())
        .collect();
    assert_eq!(
        classes,
        [["entry", "pass"], ["entry", "fail"], ["entry", "fail"]]
    );

    // Every figure has its meaning as title text and the rule it is held to; the ones
    // that do not decide the verdict say so.
    let figure_names = |section: &ElementRef<'_>| texts_in(section, "tr th[title]");
    for section in &sections[..2] {
        assert_eq!(
            figure_names(section),
            [
                "peak FLIP",
                "camera",
                "mean FLIP",
                "pixels that differ",
                "largest difference"
            ]
        );
        for row in section.select(&Selector::parse("tr:has(th[title])").unwrap()) {
            let title = row
                .select(&Selector::parse("th").unwrap())
                .next()
                .unwrap()
                .value()
                .attr("title")
                .unwrap();
            assert!(title.len() > 40, "{title}");
            let rule = texts_in(&row, "td.rule").concat();
            let judged = row
                .value()
                .has_class("meets", scraper::CaseSensitivity::CaseSensitive)
                || row
                    .value()
                    .has_class("misses", scraper::CaseSensitivity::CaseSensitive);
            assert_eq!(rule.contains("not judged"), !judged, "{rule}");
        }
    }
    // Each judged figure is marked as meeting its rule or not, as the verdict found.
    let rows = |section: &ElementRef<'_>| -> Vec<(String, String, String)> {
        section
            .select(&Selector::parse("tr:has(th[title])").unwrap())
            .map(|row| {
                let class = row.value().classes().next().unwrap().to_owned();
                (
                    texts_in(&row, "th").concat(),
                    texts_in(&row, "td.value").concat(),
                    class,
                )
            })
            .collect()
    };
    let correct_rows = rows(&sections[0]);
    assert!(
        correct_rows.iter().all(|(_, _, class)| class != "misses"),
        "{correct_rows:?}"
    );
    let mirrored_rows = rows(&sections[1]);
    let peak_misses = failed.peak_flip().unwrap() > thresholds.max_peak_flip;
    assert_eq!(
        mirrored_rows[0],
        (
            "peak FLIP".to_owned(),
            format!("{:.3}", failed.peak_flip().unwrap()),
            if peak_misses { "misses" } else { "meets" }.to_owned()
        )
    );
    assert_eq!(
        mirrored_rows[1],
        (
            "camera".to_owned(),
            "mirrored left-right: check u = up x w".to_owned(),
            "misses".to_owned()
        )
    );
    assert_eq!(mirrored_rows[3].2, "shown");
    assert!(
        texts_in(&sections[1], "tr.why td")
            .iter()
            .any(|w| w.contains("camera mistake"))
    );
    assert_eq!(texts_in(&sections[2], "tr.error td"), ["missing"]);
    // The images, linked, with their captions.
    let images: Vec<(String, String)> = sections
        .iter()
        .flat_map(|s| {
            s.select(&Selector::parse("figure").unwrap())
                .map(|f| {
                    let img = f
                        .select(&Selector::parse("a > img").unwrap())
                        .next()
                        .unwrap();
                    (
                        img.value().attr("src").unwrap().to_owned(),
                        texts_in(&f, "figcaption").concat(),
                    )
                })
                .collect::<Vec<_>>()
        })
        .collect();
    assert_eq!(
        images[2],
        (
            "correct.diff.png".to_owned(),
            "difference (FLIP of the blurred images)".to_owned()
        )
    );
    assert_eq!(images.len(), 7);
    // The legend explains each verdict and each figure.
    assert_eq!(
        texts_in(&page.root_element(), "section.rules dl:not(.legend) dt"),
        ["PASS", "FAIL"]
    );
    assert_eq!(
        texts_in(&page.root_element(), "dl.legend dt"),
        [
            "peak FLIP",
            "mean FLIP",
            "pixels that differ",
            "largest difference",
            "camera",
            "difference"
        ]
    );

    // The same report gives the same bytes (no timestamps).
    write_report(&out, &report).unwrap();
    assert_eq!(std::fs::read_to_string(&page_path).unwrap(), source);
}

#[test]
fn a_golden_report_holds_each_figure_against_the_golden_gates() {
    let (w, h) = (64, 48);
    let reference = Scene::default().render(w, h, Mistake::NONE, Pattern::Grid(4));
    let moved = Scene::default().render(
        w,
        h,
        Mistake {
            shift: (1.0, 0.0),
            ..Mistake::NONE
        },
        Pattern::Grid(4),
    );
    let outcome = Outcome::from(compare(&reference, &moved, &Thresholds::GOLDEN));
    assert!(!outcome.passed());
    let entries = [ReportEntry::new(
        "scenes/moved",
        Some(&reference),
        Some(&moved),
        &outcome,
    )];
    let dir = tempfile::tempdir().unwrap();
    let report = Report {
        title: "viewray golden images: the failures",
        summary: "1 of 46 golden images differ and 0 goldens have no scene",
        rules: Rules::Golden(Thresholds::GOLDEN),
        entries: &entries,
    };
    let page = write_report(dir.path(), &report).unwrap();
    let page = Html::parse_document(&std::fs::read_to_string(page).unwrap());
    assert_eq!(
        texts_in(&page.root_element(), "p.summary"),
        [report.summary]
    );
    let section = &select(&page, "section.entry")[0];
    assert_eq!(texts_in(section, "h2"), ["FAIL scenes/moved"]);
    assert_eq!(
        texts_in(section, "tr th[title]"),
        [
            "pixels that differ",
            "mean FLIP",
            "peak FLIP",
            "largest difference"
        ]
    );
    assert!(texts_in(section, "tr.misses th").contains(&"pixels that differ".to_owned()));
    let allowed = Thresholds::GOLDEN.max_bad_pixels(u64::from(w * h));
    assert_eq!(
        texts_in(section, "tr:has(th[title]) td.rule")[0],
        format!("by more than 2/255; passes at most {allowed}")
    );
    assert!(
        texts_in(&page.root_element(), "section.rules p")
            .concat()
            .starts_with("Golden check: an image passes when at most 0.05% of its pixels")
    );
}
