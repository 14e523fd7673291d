//! The exported text of a few fixture scenes, as snapshots: a change in what viewray
//! writes for another tool is a visible decision.

use std::path::Path;

use viewray_interop::Format;
use viewray_scene::Scene;

fn fixture(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(name);
    viewray_scene::SceneLoader::file(&path)
        .load()
        .unwrap()
        .scene
}

fn exported(scene: &Scene, format: Format, file_name: &str) -> String {
    let export = viewray_interop::export(scene, format, file_name).unwrap();
    let mut text = String::from_utf8(export.main).unwrap();
    for (name, bytes) in export.extra_files {
        text += &format!(
            "\n----- {name} -----\n{}",
            String::from_utf8(bytes).unwrap()
        );
    }
    text
}

#[test]
fn the_canonical_camera_in_every_format() {
    let scene = fixture("homework/canonical_2x2.ron");
    for (format, name) in [
        (Format::Mitsuba, "canonical.xml"),
        (Format::Pbrt, "canonical.pbrt"),
        (Format::Blender, "canonical.py"),
        (Format::Three, "canonical.json"),
        (Format::Gltf, "canonical.gltf"),
    ] {
        insta::assert_snapshot!(
            format!("canonical_{}", format.name()),
            exported(&scene, format, name)
        );
    }
}

#[test]
fn a_shifted_lens_with_objects_for_mitsuba_and_pbrt() {
    let scene = fixture("scenes/distortion_shifted.ron");
    insta::assert_snapshot!(
        "shifted_mitsuba",
        exported(&scene, Format::Mitsuba, "shifted.xml")
    );
    insta::assert_snapshot!(
        "shifted_pbrt",
        exported(&scene, Format::Pbrt, "shifted.pbrt")
    );
}

#[test]
fn a_thin_lens_for_mitsuba_pbrt_and_blender() {
    let scene = fixture("scenes/thin_lens_small_aperture.ron");
    let camera_only = |text: String| text.split("\nmaterials = []").next().unwrap().to_owned();
    insta::assert_snapshot!(
        "thin_lens_blender_camera",
        camera_only(exported(&scene, Format::Blender, "lens.py"))
    );
    let sensor = |text: String| {
        let start = text.find("<sensor").unwrap();
        let end = text.find("</sensor>").unwrap() + "</sensor>".len();
        text[start..end].to_owned()
    };
    insta::assert_snapshot!(
        "thin_lens_mitsuba_sensor",
        sensor(exported(&scene, Format::Mitsuba, "lens.xml"))
    );
}
