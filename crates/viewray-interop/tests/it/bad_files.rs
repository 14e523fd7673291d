//! Every file in `fixtures/bad/interop/` is refused with one line naming the file (and
//! the line and column where the format has lines) and what was expected. The messages
//! are snapshots.

use std::path::{Path, PathBuf};

use viewray_interop::Format;

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .canonicalize()
        .unwrap()
}

#[test]
fn every_bad_foreign_file_has_a_clear_error() {
    let dir = fixtures().join("bad/interop");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .collect();
    paths.sort();
    assert!(paths.len() >= 15, "too few bad files in {}", dir.display());
    let root = format!("{}/", fixtures().parent().unwrap().display());
    let mut report = String::new();
    for path in &paths {
        let bytes = std::fs::read(path).unwrap();
        let format = Format::detect(path, &bytes).expect("the extension names the format");
        let result = viewray_interop::import(&bytes, path, format).and_then(|document| {
            // A camera viewray cannot use is refused when the scene is loaded.
            viewray_scene::SceneLoader::text(&document.to_ron(), path)
                .load()
                .map(|loaded| loaded.scene)
                .map(|_| ())
                .map_err(|e| panic!("{}: imported, but does not load: {e}", path.display()))
        });
        let message = result
            .expect_err(&format!("{} was imported", path.display()))
            .to_string();
        assert!(!message.contains('\n'), "not one line: {message}");
        assert!(
            message.starts_with(path.to_str().unwrap()),
            "does not name the file: {message}"
        );
        report += &format!("{}\n", message.replace(&root, ""));
    }
    insta::assert_snapshot!(report);
}
