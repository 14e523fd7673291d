//! Every file in `fixtures/bad/` is rejected with one message naming the file, line and
//! column where known, what was found and what was expected. The messages are snapshots,
//! so changing their wording is a visible decision.

use std::path::{Path, PathBuf};

use viewray_scene::{FileKind, SceneLoader};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .canonicalize()
        .unwrap()
}

#[test]
fn every_bad_scene_has_a_clear_error() {
    let dir = fixtures().join("bad");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    assert!(paths.len() >= 10, "too few bad scenes in {}", dir.display());
    let mut report = String::new();
    for path in &paths {
        let name = path.file_name().unwrap().to_str().unwrap();
        let error = SceneLoader::file(path)
            .load()
            .err()
            .unwrap_or_else(|| panic!("{name} loaded, but it is a bad scene"));
        let message = error.to_string();
        assert!(!message.contains('\n'), "{name}: not one line: {message}");
        let shown = path.to_str().unwrap();
        assert!(
            message.starts_with(shown),
            "{name}: does not name the file: {message}"
        );
        // The snapshot shows paths from the repository root, wherever it is checked out.
        let root = format!("{}/", fixtures().parent().unwrap().display());
        report += &format!("{}\n", message.replace(&root, ""));
    }
    insta::assert_snapshot!(report);
}

#[test]
fn a_missing_file_is_named() {
    let error = SceneLoader::file(Path::new("no/such/scene.ron"))
        .load()
        .unwrap_err();
    assert!(
        error
            .to_string()
            .starts_with("no/such/scene.ron: no such scene file")
    );
}

#[test]
fn a_byte_order_mark_is_accepted() {
    // Windows editors may save UTF-8 with a byte-order mark in front.
    let text =
        "\u{feff}(image: (width: 4, height: 2), camera: Front(target: (0.0, 0.0, 0.0), size: 2.0))";
    let scene = SceneLoader::text(text, Path::new("bom.ron"))
        .load()
        .unwrap()
        .scene;
    assert_eq!((scene.camera().width(), scene.camera().height()), (4, 2));
}

#[test]
fn a_file_of_another_kind_is_named_for_what_it_is() {
    let mesh = fixtures().join("meshes/cube.obj");
    let error = SceneLoader::file(&mesh).load().unwrap_err();
    assert_eq!(error.found(), Some(FileKind::ObjMesh));
    assert_eq!(
        error.to_string(),
        format!(
            "{}: this is an OBJ mesh; a scene file names it in `objects`",
            mesh.display()
        )
    );
    // Standard input has no name to go by: its first bytes say what it is.
    let png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR";
    let error = SceneLoader::reader(&png[..], Path::new("<stdin>"))
        .load()
        .unwrap_err();
    assert_eq!(error.found(), Some(FileKind::Png));
    assert_eq!(
        error.to_string(),
        "<stdin>: this is a PNG image, not a viewray scene file"
    );
    // A scene file's own mistakes are a scene file's, whatever it is called.
    let error = SceneLoader::reader(&b"(camera: Top())"[..], Path::new("camera.json"))
        .load()
        .unwrap_err();
    assert_eq!(error.found(), None);
    assert_eq!(
        error.to_string(),
        "camera.json:1:14: missing field `target` in `Top`"
    );
}
