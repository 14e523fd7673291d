//! `viewray figure` and `viewray figures` as a lecturer runs them: image files appear,
//! or one error line and no file at all.

use std::path::Path;

use tempfile::TempDir;
use viewray_diagram::{figure_by_name, figure_names};

use crate::support;
use support::{error_line_in as error_line, viewray_in};

#[track_caller]
fn run_ok(dir: &Path, args: &[&str]) {
    let out = viewray_in(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "viewray {args:?} failed: {stderr}");
    // Not a terminal: no chatter.
    assert!(out.stderr.is_empty(), "stderr: {stderr}");
    assert!(out.stdout.is_empty(), "stdout: {:?}", out.stdout);
}

/// The names of the files in `dir`, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    names
}

/// Parses an SVG document and returns its root's width and height attributes.
#[track_caller]
fn svg_size(path: &Path) -> (String, String) {
    let text = std::fs::read_to_string(path).unwrap();
    let doc =
        roxmltree::Document::parse(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    let attribute = |name| root.attribute(name).unwrap_or_default().to_owned();
    (attribute("width"), attribute("height"))
}

#[test]
fn a_figure_writes_a_png_of_the_lecture_canvas() {
    let dir = TempDir::new().unwrap();
    run_ok(
        dir.path(),
        &["figure", "canonical_camera", "-o", "canonical.png"],
    );
    let image = image::open(dir.path().join("canonical.png")).unwrap();
    assert_eq!((image.width(), image.height()), (1600, 900));
    // The temporary file is gone.
    assert_eq!(files(dir.path()), ["canonical.png"]);

    // Without -o, NAME.png in the current folder; the square canvas is 1080 x 1080.
    run_ok(dir.path(), &["figure", "camera_frame_square"]);
    let image = image::open(dir.path().join("camera_frame_square.png")).unwrap();
    assert_eq!((image.width(), image.height()), (1080, 1080));
}

#[test]
fn a_figure_writes_an_svg_that_parses() {
    let dir = TempDir::new().unwrap();
    run_ok(dir.path(), &["figure", "viewing_rays", "-o", "rays.SVG"]);
    let (width, height) = svg_size(&dir.path().join("rays.SVG"));
    assert_eq!((width.as_str(), height.as_str()), ("1600", "900"));
    assert_eq!(files(dir.path()), ["rays.SVG"]);
}

#[test]
fn an_unknown_figure_is_one_error_line_listing_the_names() {
    let dir = TempDir::new().unwrap();
    let line = error_line(dir.path(), &["figure", "no_such_figure", "-o", "x.png"]);
    assert!(line.contains("unknown figure `no_such_figure`"), "{line}");
    for name in figure_names() {
        assert!(line.contains(name), "{line} lacks {name}");
    }
    assert!(
        files(dir.path()).is_empty(),
        "wrote {:?}",
        files(dir.path())
    );
}

#[test]
fn bad_outputs_are_one_error_line_and_no_file() {
    let dir = TempDir::new().unwrap();
    let line = error_line(dir.path(), &["figure", "taxonomy", "-o", "taxonomy.jpg"]);
    assert!(line.contains("must be a .png or .svg file"), "{line}");
    std::fs::create_dir(dir.path().join("folder.png")).unwrap();
    let line = error_line(dir.path(), &["figure", "taxonomy", "-o", "folder.png"]);
    assert!(line.contains("is a directory"), "{line}");
    let line = error_line(
        dir.path(),
        &["figure", "canonical_camera", "-o", "missing/c.png"],
    );
    assert!(line.contains("cannot write missing/c.png"), "{line}");
    std::fs::write(dir.path().join("file"), "not a folder").unwrap();
    let line = error_line(dir.path(), &["figures", "-o", "file"]);
    assert!(line.contains("not a directory"), "{line}");
    assert_eq!(files(dir.path()), ["file", "folder.png"]);
}

#[test]
fn figures_writes_every_figure_as_png_and_svg() {
    let dir = TempDir::new().unwrap();
    run_ok(dir.path(), &["figures", "-o", "lecture/figures"]);
    let out = dir.path().join("lecture/figures");
    let mut expected: Vec<String> = figure_names()
        .iter()
        .flat_map(|name| [format!("{name}.png"), format!("{name}.svg")])
        .collect();
    expected.sort();
    assert_eq!(files(&out), expected);
    for name in figure_names() {
        let image = image::open(out.join(format!("{name}.png")))
            .unwrap()
            .to_rgba8();
        let size = image.dimensions();
        assert!(
            size == (1600, 900) || size == (1080, 1080),
            "{name}: {size:?}"
        );
        let (width, height) = svg_size(&out.join(format!("{name}.svg")));
        assert_eq!((width, height), (size.0.to_string(), size.1.to_string()));
        // The pictures are rendered, not drawn as polygons.
        let wireframe = viewray_draw::raster::render(&figure_by_name(name).unwrap().wireframe());
        let has_pictures = [
            "taxonomy",
            "distortion_foreshortening",
            "distortion_verticals",
            "thin_lens",
        ]
        .contains(&name);
        assert_eq!(image != wireframe, has_pictures, "{name}");
    }
}
