//! A file of the wrong kind, through the real binary: a mesh, an image or another tool's
//! scene where a scene file goes, and a file `import` does not read, are each named for
//! what they are, in one `error:` line with exit code 2 and nothing written.

use std::path::Path;

use crate::support;
use support::{error_line, error_line_in, repository, viewray};

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn an_obj_mesh_given_as_a_scene_is_named_as_a_mesh() {
    let mesh = "fixtures/meshes/cube.obj";
    for args in [
        ["rays", mesh, "--pixel", "0,0"].as_slice(),
        ["render", mesh, "-o", "-"].as_slice(),
        ["frame", mesh].as_slice(),
        ["diagram", mesh, "-o", "side.svg"].as_slice(),
    ] {
        assert_eq!(
            error_line_in(&repository(), args),
            "error: fixtures/meshes/cube.obj: this is an OBJ mesh; a scene file names it in \
             `objects`",
            "{args:?}"
        );
    }
    assert_eq!(
        error_line_in(&repository(), &["rays", "fixtures/meshes/cube.mtl"]),
        "error: fixtures/meshes/cube.mtl: this is an MTL material library; the OBJ mesh that \
         uses it names it (`mtllib`), and a scene file names the mesh in `objects`"
    );
}

#[test]
fn a_png_given_as_a_scene_is_named_as_an_image() {
    let dir = tempfile::tempdir().unwrap();
    let output = dir.path().join("out.png");
    let image = "golden/scenes/axonometric_isometric.png";
    let line = error_line_in(
        &repository(),
        &["render", image, "-o", output.to_str().unwrap()],
    );
    assert_eq!(
        line,
        "error: golden/scenes/axonometric_isometric.png: this is a PNG image, not a viewray \
         scene file"
    );
    assert_eq!(files_in(dir.path()), Vec::<String>::new());
    // Whatever its name says: a PNG renamed .ron is still a PNG.
    let renamed = dir.path().join("scene.ron");
    std::fs::copy(repository().join(image), &renamed).unwrap();
    let line = error_line(&["project", renamed.to_str().unwrap(), "--point", "0,0,0"]);
    assert_eq!(
        line,
        format!(
            "error: {}: this is a PNG image, not a viewray scene file",
            renamed.display()
        )
    );
}

#[test]
fn another_tools_scene_given_as_a_scene_names_the_command_that_converts_it() {
    let dir = tempfile::tempdir().unwrap();
    let xml = dir.path().join("two.xml");
    let exported = viewray(&[
        "export",
        &repository()
            .join("fixtures/scenes/perspective_two_point.ron")
            .display()
            .to_string(),
        "--to",
        "mitsuba",
        "-o",
        xml.to_str().unwrap(),
    ]);
    assert!(exported.status.success());
    let name = xml.display();
    let expected = format!(
        "error: {name}: this is a Mitsuba 3 scene (XML), not a viewray scene file: `viewray \
         import {name} > scene.ron` turns it into one"
    );
    assert_eq!(error_line(&["rays", xml.to_str().unwrap()]), expected);
    assert_eq!(error_line(&["serve", xml.to_str().unwrap()]), expected);
}

#[test]
fn the_blender_script_export_writes_is_not_read_as_pbrt() {
    let dir = tempfile::tempdir().unwrap();
    let script = dir.path().join("model.blender.py");
    let exported = viewray(&[
        "export",
        &repository()
            .join("fixtures/scenes/perspective_two_point.ron")
            .display()
            .to_string(),
        "--to",
        "blender",
        "-o",
        script.to_str().unwrap(),
    ]);
    assert!(exported.status.success());
    let line = error_line(&["import", script.to_str().unwrap()]);
    assert_eq!(
        line,
        format!(
            "error: {}: a Blender script cannot be imported: export the scene from Blender as \
             glTF (File > Export > glTF 2.0) and import that",
            script.display()
        )
    );
    assert_eq!(
        error_line(&["render", script.to_str().unwrap(), "-o", "-"]),
        format!(
            "error: {}: this is a Blender Python script, not a viewray scene file",
            script.display()
        )
    );
}

#[test]
fn import_names_what_it_does_not_read() {
    let reads = "`viewray import` reads other tools' scenes: Mitsuba 3 XML (.xml), pbrt-v4 \
                 (.pbrt), a three.js JSON object (.json) or glTF (.gltf, .glb)";
    // The cube starts with a `#` comment, which once made it a pbrt file.
    assert_eq!(
        error_line_in(&repository(), &["import", "fixtures/meshes/cube.obj"]),
        format!(
            "error: fixtures/meshes/cube.obj: this is an OBJ mesh; a scene file names it in \
             `objects`; {reads}"
        )
    );
    assert_eq!(
        error_line_in(
            &repository(),
            &["import", "golden/scenes/axonometric_isometric.png"]
        ),
        format!(
            "error: golden/scenes/axonometric_isometric.png: this is a PNG image, not a \
             viewray scene file; {reads}"
        )
    );
    assert_eq!(
        error_line_in(
            &repository(),
            &["import", "fixtures/homework/canonical_2x2.ron"]
        ),
        "error: fixtures/homework/canonical_2x2.ron: this is a viewray scene file already: \
         `viewray render fixtures/homework/canonical_2x2.ron` renders it"
    );
    // A file of no kind viewray knows keeps the question of its format.
    let dir = tempfile::tempdir().unwrap();
    let notes = dir.path().join("notes.txt");
    std::fs::write(&notes, "hello\n").unwrap();
    assert_eq!(
        error_line(&["import", notes.to_str().unwrap()]),
        format!(
            "error: {}: cannot tell the format: expected Mitsuba 3 XML (.xml), pbrt-v4 \
             (.pbrt), a three.js JSON object (.json) or glTF (.gltf, .glb); say which with \
             --from",
            notes.display()
        )
    );
}
