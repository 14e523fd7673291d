//! Each tool's camera conventions, checked against hand-worked numbers: one test per row
//! of the pitfalls table in docs/cameras-in-other-tools.md.

use std::path::Path;

use glam::DVec3;
use viewray_camera::Projection;
use viewray_interop::Format;
use viewray_scene::Scene;

fn scene(width: u32, height: u32, projection: &str) -> Scene {
    let text = format!(
        "(image: (width: {width}, height: {height}),
          camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0), up: (0.0, 1.0, 0.0),
                   projection: {projection}))"
    );
    viewray_scene::SceneLoader::text(&text, Path::new("case.ron"))
        .load()
        .unwrap()
        .scene
}

fn export(scene: &Scene, format: Format) -> String {
    let name = match format {
        Format::Gltf => "scene.gltf",
        _ => "scene.out",
    };
    let export = viewray_interop::export(scene, format, name).unwrap();
    String::from_utf8(export.main).unwrap()
}

fn import(text: &str, name: &str, format: Format) -> Scene {
    let document = viewray_interop::import(text.as_bytes(), Path::new(name), format)
        .unwrap_or_else(|e| panic!("{e}"));
    let ron = document.to_ron();
    viewray_scene::SceneLoader::text(&ron, Path::new(name))
        .load()
        .unwrap_or_else(|e| panic!("{e}\n{ron}"))
        .scene
}

#[track_caller]
fn contains(text: &str, wanted: &str) {
    assert!(text.contains(wanted), "`{wanted}` not in:\n{text}");
}

#[track_caller]
fn close(a: f64, b: f64) {
    assert!((a - b).abs() <= 1e-12 * b.abs().max(1.0), "{a} != {b}");
}

fn perspective(scene: &Scene) -> viewray_camera::Perspective {
    match scene.camera().projection() {
        Projection::Perspective(p) => *p,
        other => panic!("not perspective: {other:?}"),
    }
}

// Mitsuba 3 -------------------------------------------------------------------------------

#[test]
fn mitsuba_fov_is_horizontal_and_the_principal_point_is_a_fraction_of_the_film_y_down() {
    // vw = 2 at d = 1: 90 degrees across x. A shift of (0.5, 0.25) on a 2 x 1 viewport is
    // a quarter of the width right and a quarter of the height up: y is measured down.
    let text = export(
        &scene(
            200,
            100,
            "Perspective(distance: 1.0, viewport: (2.0, 1.0), shift: (0.5, 0.25))",
        ),
        Format::Mitsuba,
    );
    contains(&text, r#"<float name="fov" value="90.0"/>"#);
    contains(&text, r#"<string name="fov_axis" value="x"/>"#);
    contains(
        &text,
        r#"<float name="principal_point_offset_x" value="0.25"/>"#,
    );
    contains(
        &text,
        r#"<float name="principal_point_offset_y" value="-0.25"/>"#,
    );
    // The sensor's +x is the image's left: the lookat target is e - W and up is V.
    contains(
        &text,
        r#"<lookat origin="0.0, 0.0, 0.0" target="0.0, 0.0, -1.0" up="0.0, 1.0, 0.0"/>"#,
    );
}

#[test]
fn mitsuba_fov_axis_smaller_on_a_portrait_film_spans_the_width() {
    let xml = r#"<scene version="3.0.0"><sensor type="perspective">
        <float name="fov" value="90"/><string name="fov_axis" value="smaller"/>
        <film type="hdrfilm"><integer name="width" value="100"/><integer name="height" value="200"/></film>
        </sensor></scene>"#;
    let p = perspective(&import(xml, "portrait.xml", Format::Mitsuba));
    close(p.viewport.x / p.distance, 2.0);
    close(p.viewport.y / p.distance, 4.0);
}

#[test]
fn mitsuba_focal_length_is_a_35mm_equivalent_diagonal() {
    // focal_length="50mm" (the default): the diagonal of a 36 x 24 frame, on a 3:2 film
    // that is 36 mm across: vw / d = 36 / 50.
    let xml = r#"<scene version="3.0.0"><sensor type="perspective">
        <film type="hdrfilm"><integer name="width" value="300"/><integer name="height" value="200"/></film>
        </sensor></scene>"#;
    let p = perspective(&import(xml, "default.xml", Format::Mitsuba));
    close(p.viewport.x / p.distance, 0.72);
}

#[test]
fn mitsuba_orthographic_extent_is_the_to_world_scale() {
    // A 4 x 3 viewport on a 400 x 300 film: scale (2, 2): x spans [-1, 1] scaled by 2,
    // y spans [-1/a, 1/a] = [-0.75, 0.75] scaled by 2.
    let text = export(
        &scene(400, 300, "Orthographic(viewport: (4.0, 3.0))"),
        Format::Mitsuba,
    );
    contains(&text, r#"<scale x="2.0" y="2.0" z="1"/>"#);
}

// pbrt-v4 ---------------------------------------------------------------------------------

#[test]
fn pbrt_mirrors_x_and_its_fov_spans_the_shorter_side() {
    // A 2 x 1 viewport at d = 1 on a 200 x 100 image: the shorter side is the height,
    // 2 atan(1/2) = 53.13 degrees; Scale -1 1 1 turns pbrt's left-handed camera around.
    let text = export(
        &scene(200, 100, "Perspective(distance: 1.0, viewport: (2.0, 1.0))"),
        Format::Pbrt,
    );
    contains(
        &text,
        "Scale -1 1 1\nLookAt 0.0 0.0 0.0  0.0 0.0 -1.0  0.0 1.0 0.0\n",
    );
    contains(
        &text,
        &format!(
            "Camera \"perspective\" \"float fov\" [ {:?} ]\n",
            (2.0 * 0.5f64.atan()).to_degrees()
        ),
    );
    // Portrait: the shorter side is the width.
    let text = export(
        &scene(100, 200, "Perspective(distance: 1.0, viewport: (1.0, 2.0))"),
        Format::Pbrt,
    );
    contains(
        &text,
        &format!(
            "\"float fov\" [ {:?} ]\n",
            (2.0 * 0.5f64.atan()).to_degrees()
        ),
    );
}

#[test]
fn pbrt_shift_is_a_screen_window_in_units_of_the_half_shorter_side() {
    // vh = 1 at d = 1, so t = tan(fov/2) = 1/2: the window is the viewport divided by 1/2.
    let text = export(
        &scene(
            200,
            100,
            "Perspective(distance: 1.0, viewport: (2.0, 1.0), shift: (0.5, 0.25))",
        ),
        Format::Pbrt,
    );
    contains(&text, "\"float screenwindow\" [ -1.0 3.0 -0.5 1.5 ]");
}

#[test]
fn pbrt_plain_look_at_is_imported_mirrored_so_the_picture_is_pbrts() {
    // A plain LookAt in a right-handed world: pbrt's image right is world -x. The import
    // mirrors the scene in x, so the sphere at x = 1 (on pbrt's image left) moves to -1,
    // and viewray's camera (u = +x) sees it on the left too.
    let pbrt = "LookAt 0 0 5  0 0 0  0 1 0\nCamera \"perspective\" \"float fov\" [ 90 ]\n\
                Film \"rgb\" \"integer xresolution\" [ 100 ] \"integer yresolution\" [ 100 ]\n\
                WorldBegin\nTranslate 1 0 0\nShape \"sphere\" \"float radius\" 0.5\n";
    let document =
        viewray_interop::import(pbrt.as_bytes(), Path::new("plain.pbrt"), Format::Pbrt).unwrap();
    assert!(
        document
            .comments
            .iter()
            .any(|c| c.contains("mirrored in x"))
    );
    let scene = viewray_scene::SceneLoader::text(&document.to_ron(), Path::new("plain.pbrt"))
        .load()
        .unwrap()
        .scene;
    let x = scene
        .camera()
        .project(DVec3::new(-1.0, 0.0, 0.0))
        .unwrap()
        .x;
    assert!(x < 50.0, "the sphere should be on the left, at x = {x}");
    match &document.objects[0] {
        viewray_scene::ObjectDocument::Sphere { center, .. } => assert_eq!(center.x, -1.0),
        other => panic!("{other:?}"),
    }
}

// Blender ---------------------------------------------------------------------------------

#[test]
fn blender_shift_is_in_units_of_the_fitted_side_for_both_axes() {
    // Horizontal fit on a 2 x 1 viewport: shift_y = 0.25 / 2 (of the width), not 0.25 / 1.
    // The lens is 36 mm x d / vw = 18 mm.
    let text = export(
        &scene(
            200,
            100,
            "Perspective(distance: 1.0, viewport: (2.0, 1.0), shift: (0.5, 0.25))",
        ),
        Format::Blender,
    );
    contains(
        &text,
        "cam.sensor_fit = 'HORIZONTAL'\ncam.sensor_width = 36.0\ncam.lens = 18.0\ncam.shift_x = 0.25\ncam.shift_y = 0.125\n",
    );
}

#[test]
fn blender_ortho_scale_spans_the_fitted_side() {
    let text = export(
        &scene(400, 300, "Orthographic(viewport: (4.0, 3.0))"),
        Format::Blender,
    );
    contains(
        &text,
        "cam.type = 'ORTHO'\ncam.sensor_fit = 'HORIZONTAL'\ncam.ortho_scale = 4.0\n",
    );
}

#[test]
fn blender_f_stop_gives_back_the_f_number() {
    // 50 mm at f/2.8: Cycles' radius is 50 / 1000 / (2 x 2.8); exported with a 36 mm
    // sensor that is again a 50 mm lens at f/2.8.
    let text = export(
        &scene(
            300,
            200,
            "ThinLens(focal_length: 50.0, sensor: (36.0, 24.0), f_number: 2.8, focus: 5.0)",
        ),
        Format::Blender,
    );
    contains(&text, "cam.lens = 50.0");
    let fstop: f64 = text
        .split("cam.dof.aperture_fstop = ")
        .nth(1)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    close(fstop, 2.8);
}

#[test]
fn blender_takes_the_blades_and_their_rotation_exactly() {
    // Six blades turned by -30 degrees (written as 330: wrapped by a whole turn): Cycles'
    // aperture_blades and aperture_rotation, in radians.
    let text = export(
        &scene(
            300,
            200,
            "ThinLens(focal_length: 50.0, f_number: 2.8, focus: 5.0, blades: 6, \
             blade_rotation: 330.0)",
        ),
        Format::Blender,
    );
    contains(&text, "cam.dof.aperture_blades = 6\n");
    let rotation: f64 = text
        .split("cam.dof.aperture_rotation = ")
        .nth(1)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(rotation, (-30f64).to_radians());
    // A round lens is Cycles' round one.
    let text = export(
        &scene(
            300,
            200,
            "ThinLens(focal_length: 50.0, f_number: 2.8, focus: 5.0)",
        ),
        Format::Blender,
    );
    contains(
        &text,
        "cam.dof.aperture_blades = 0\ncam.dof.aperture_rotation = 0.0\n",
    );
}

#[test]
fn blender_non_square_pixels_are_a_pixel_aspect() {
    // 2 x 1 on a 100 x 100 image: pixels twice as wide as tall.
    let text = export(
        &scene(100, 100, "Perspective(distance: 1.0, viewport: (2.0, 1.0))"),
        Format::Blender,
    );
    contains(
        &text,
        "scene.render.pixel_aspect_x = 2.0\nscene.render.pixel_aspect_y = 1.0\n",
    );
}

// three.js --------------------------------------------------------------------------------

#[test]
fn three_fov_is_vertical_and_a_shift_is_a_view_offset_in_pixels_down() {
    let text = export(
        &scene(
            200,
            100,
            "Perspective(distance: 1.0, viewport: (2.0, 1.0), shift: (0.5, 0.25))",
        ),
        Format::Three,
    );
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    let camera = &json["object"]["children"][0];
    close(
        camera["fov"].as_f64().unwrap(),
        (2.0 * 0.5f64.atan()).to_degrees(),
    );
    close(camera["aspect"].as_f64().unwrap(), 2.0);
    close(camera["view"]["offsetX"].as_f64().unwrap(), 50.0);
    close(camera["view"]["offsetY"].as_f64().unwrap(), -25.0);
}

#[test]
fn three_zoom_divides_the_field_of_view() {
    // fov 90 at zoom 2: vh = 2 tan(45) / 2 = 1.
    let json = r#"{"metadata": {"version": 4.6, "type": "Object"}, "object": {"type": "PerspectiveCamera",
        "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "fov": 90, "zoom": 2, "aspect": 1.5,
        "view": {"enabled": true, "fullWidth": 300, "fullHeight": 200, "offsetX": 0, "offsetY": 0, "width": 300, "height": 200}}}"#;
    let p = perspective(&import(json, "zoom.json", Format::Three));
    close(p.viewport.y / p.distance, 1.0);
    close(p.viewport.x / p.distance, 1.5);
}

// glTF ------------------------------------------------------------------------------------

#[test]
fn gltf_yfov_is_vertical_radians_and_xmag_is_half_the_width() {
    let text = export(
        &scene(200, 100, "Perspective(distance: 1.0, viewport: (2.0, 1.0))"),
        Format::Gltf,
    );
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    close(
        json["cameras"][0]["perspective"]["yfov"].as_f64().unwrap(),
        2.0 * 0.5f64.atan(),
    );
    close(
        json["cameras"][0]["perspective"]["aspectRatio"]
            .as_f64()
            .unwrap(),
        2.0,
    );
    let text = export(
        &scene(400, 300, "Orthographic(viewport: (4.0, 3.0))"),
        Format::Gltf,
    );
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    close(
        json["cameras"][0]["orthographic"]["xmag"].as_f64().unwrap(),
        2.0,
    );
    close(
        json["cameras"][0]["orthographic"]["ymag"].as_f64().unwrap(),
        1.5,
    );
}

#[test]
fn a_gltf_camera_without_an_image_size_gets_one_of_its_aspect_ratio() {
    let json = r#"{"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
        "nodes": [{"camera": 0, "translation": [0, 1, 5]}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 1.5, "znear": 0.1}}]}"#;
    let scene = import(json, "bare.gltf", Format::Gltf);
    assert_eq!(
        (scene.camera().width(), scene.camera().height()),
        (720, 480)
    );
    let p = perspective(&scene);
    close(p.viewport.y, 2.0 * 0.4f64.tan());
    close(scene.camera().frame().e().y, 1.0);
}

// What each tool lacks --------------------------------------------------------------------

#[test]
fn a_camera_a_tool_cannot_express_is_refused_with_what_it_lacks() {
    let cases = [
        (
            Format::Mitsuba,
            100,
            100,
            "Oblique(height: 2.0, ratio: 0.5, angle: 45.0)",
            "Mitsuba 3 has no oblique camera",
        ),
        (
            Format::Pbrt,
            100,
            100,
            "Oblique(height: 2.0, ratio: 1.0, angle: 30.0)",
            "pbrt-v4 has no oblique camera",
        ),
        (
            Format::Gltf,
            100,
            100,
            "Oblique(height: 2.0, ratio: 1.0, angle: 30.0)",
            "glTF has no oblique camera",
        ),
        (
            Format::Gltf,
            100,
            100,
            "Perspective(fov_y: 40.0, shift: (0.0, 0.1))",
            "glTF has no shift",
        ),
        (
            Format::Gltf,
            100,
            100,
            "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0)",
            "glTF has no lens",
        ),
        (
            Format::Three,
            100,
            100,
            "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0)",
            "three.js has no lens",
        ),
        (
            Format::Three,
            100,
            50,
            "Equirectangular",
            "three.js has no panoramic camera",
        ),
        (
            Format::Mitsuba,
            100,
            100,
            "Fisheye(fov: 180.0)",
            "Mitsuba 3 has no panoramic camera",
        ),
        (
            Format::Pbrt,
            100,
            100,
            "Fisheye(fov: 180.0)",
            "pbrt-v4 has no equidistant fisheye",
        ),
        (
            Format::Blender,
            100,
            50,
            "Fisheye(fov: 180.0)",
            "Blender has no fisheye on a non-square image",
        ),
        (
            Format::Mitsuba,
            100,
            100,
            "Perspective(distance: 1.0, viewport: (2.0, 1.0))",
            "Mitsuba 3 has square pixels only",
        ),
        (
            Format::Mitsuba,
            100,
            100,
            "ThinLens(fov_y: 40.0, shift: (0.1, 0.0), aperture: 0.1, focus: 3.0)",
            "Mitsuba 3 has no shifted thin lens",
        ),
        (
            Format::Mitsuba,
            100,
            100,
            "Orthographic(height: 2.0, aperture: 0.1, focus: 3.0)",
            "Mitsuba 3 has no orthographic camera with a lens",
        ),
        // Tilted lenses and blades: only Blender has blades, no one tilts.
        (
            Format::Blender,
            100,
            100,
            "ThinLens(focal_length: 90.0, f_number: 4.0, focus: 5.0, lens_tilt: 3.0)",
            "Blender has no lens tilt or swing",
        ),
        (
            Format::Mitsuba,
            100,
            100,
            "ThinLens(focal_length: 90.0, f_number: 4.0, focus: 5.0, lens_swing: -2.0)",
            "Mitsuba 3 has no lens tilt or swing",
        ),
        (
            Format::Pbrt,
            100,
            100,
            "ThinLens(focal_length: 90.0, f_number: 4.0, focus: 5.0, lens_tilt: 3.0)",
            "pbrt-v4 has no lens tilt or swing",
        ),
        (
            Format::Mitsuba,
            100,
            100,
            "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0, blades: 5)",
            "Mitsuba 3 has no aperture blades",
        ),
        (
            Format::Pbrt,
            100,
            100,
            "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0, blades: 5)",
            "pbrt-v4 has no aperture blades",
        ),
        (
            Format::Blender,
            100,
            100,
            "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0, blades: 17)",
            "Blender takes at most 16 aperture blades",
        ),
        (
            Format::Gltf,
            100,
            100,
            "ThinLens(focal_length: 90.0, f_number: 4.0, focus: 5.0, lens_tilt: 3.0)",
            "glTF has no lens",
        ),
        (
            Format::Three,
            100,
            100,
            "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0, blades: 5)",
            "three.js has no lens",
        ),
    ];
    for (format, width, height, projection, wanted) in cases {
        let error = viewray_interop::export(&scene(width, height, projection), format, "out")
            .unwrap_err()
            .to_string();
        assert!(
            error.starts_with(wanted),
            "{format:?} {projection}: {error}"
        );
        assert!(!error.contains('\n'));
    }
    // What each can hold, it holds.
    for (format, projection) in [
        (Format::Pbrt, "Equirectangular"),
        (Format::Blender, "Equirectangular"),
        (
            Format::Pbrt,
            "Orthographic(height: 2.0, aperture: 0.1, focus: 3.0)",
        ),
        (
            Format::Blender,
            "Orthographic(height: 2.0, aperture: 0.1, focus: 3.0)",
        ),
        (
            Format::Blender,
            "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 3.0, blades: 16)",
        ),
        (Format::Three, "Perspective(fov_y: 40.0, shift: (0.1, 0.2))"),
    ] {
        let scene = scene(100, 50, projection);
        assert!(
            viewray_interop::export(&scene, format, "out").is_ok(),
            "{format:?} {projection}"
        );
    }
}
