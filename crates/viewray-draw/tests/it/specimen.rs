//! The specimen figure (every item kind) renders, and writes PNG and SVG files.

#[path = "../../examples/specimen.rs"]
#[allow(dead_code)]
mod example;

use viewray_draw::raster::render;
use viewray_draw::{Item, write_png, write_svg};

#[test]
fn specimen_writes_png_and_svg() {
    let figure = example::specimen();
    let dir = tempfile::tempdir().expect("a temporary directory");
    let png = dir.path().join("specimen.png");
    let svg = dir.path().join("specimen.svg");
    write_png(&figure, &png).expect("PNG written");
    write_svg(&figure, &svg).expect("SVG written");

    let decoded = image::open(&png).expect("a PNG").to_rgba8();
    assert_eq!(decoded, render(&figure));
    let text = std::fs::read_to_string(&svg).expect("SVG text");
    roxmltree::Document::parse(&text).expect("well-formed SVG");

    // Only the two figures are left: the temporary files were renamed into place.
    let mut names: Vec<_> = std::fs::read_dir(dir.path())
        .expect("listing")
        .map(|entry| entry.expect("entry").file_name())
        .collect();
    names.sort();
    assert_eq!(names, ["specimen.png", "specimen.svg"]);

    // Writing again replaces the files.
    let before = std::fs::read(&png).expect("bytes");
    write_png(&figure, &png).expect("PNG rewritten");
    assert_eq!(std::fs::read(&png).expect("bytes"), before);
}

#[test]
fn specimen_labels_stay_on_the_canvas_and_apart() {
    let figure = example::specimen();
    let canvas = figure.bounds();
    let labels: Vec<_> = figure
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Label(label) => Some(label),
            _ => None,
        })
        .collect();
    assert!(labels.len() >= 8);
    for (i, a) in labels.iter().enumerate() {
        assert!(
            canvas.contains_rect(&a.bounds()),
            "{:?} leaves the canvas",
            a.text
        );
        for b in &labels[i + 1..] {
            assert!(
                !a.bounds().intersects(&b.bounds()),
                "{:?} overlaps {:?}",
                a.text,
                b.text
            );
        }
    }
}

#[test]
fn writing_into_a_missing_directory_fails_without_a_file() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join("missing").join("figure.png");
    let error = write_png(&example::specimen(), &path).expect_err("no such directory");
    assert_eq!(error.kind(), std::io::ErrorKind::NotFound);
    assert!(!path.exists());
}
