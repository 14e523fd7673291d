//! The side view of any scene's camera: rays the camera generates, drawn to what they
//! hit, in the plane of the camera's v and w.

use std::path::Path;

use glam::DVec3;
use viewray_camera::CameraSample;
use viewray_draw::Item;
use viewray_scene::{Scene, parse_camera};

use super::figures::{assert_drawn_rays_are_generated, labels};
use crate::camera_side::{SideViewCanvas, camera_side_view};
use crate::style;
use crate::view::FigureView;

/// The fixture scenes whose cameras the tests draw: every family, presets, a mesh-free
/// tilted camera.
const SCENES: [(&str, &str); 8] = [
    ("default", include_str!("../../../../fixtures/default.ron")),
    (
        "perspective_three_point",
        include_str!("../../../../fixtures/scenes/perspective_three_point.ron"),
    ),
    (
        "thin_lens_large_aperture",
        include_str!("../../../../fixtures/scenes/thin_lens_large_aperture.ron"),
    ),
    (
        "orthographic",
        include_str!("../../../../fixtures/scenes/orthographic.ron"),
    ),
    (
        "oblique_cabinet",
        include_str!("../../../../fixtures/scenes/oblique_cabinet.ron"),
    ),
    (
        "axonometric_isometric",
        include_str!("../../../../fixtures/scenes/axonometric_isometric.ron"),
    ),
    (
        "panoramic_fisheye",
        include_str!("../../../../fixtures/scenes/panoramic_fisheye.ron"),
    ),
    (
        "panoramic_equirectangular",
        include_str!("../../../../fixtures/scenes/panoramic_equirectangular.ron"),
    ),
];

fn scene(name: &str, text: &str) -> Scene {
    // Meshes would be read from the fixtures' folder: these scenes have none but
    // `cube.obj`, which the ones using it find beside the path given.
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/scenes")
        .join(format!("{name}.ron"));
    Scene::parse(text, &path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_ray_drawn_is_one_the_camera_generates() {
    for (name, text) in SCENES {
        let scene = scene(name, text);
        let camera = *scene.camera();
        let pixel = (camera.height() / 3, camera.width() / 4);
        for canvas in [SideViewCanvas::Slide, SideViewCanvas::Panel] {
            let diagram = camera_side_view(&scene, &camera, Some(pixel), canvas);
            assert_drawn_rays_are_generated(name, &diagram);
        }
        let diagram = camera_side_view(&scene, &camera, Some(pixel), SideViewCanvas::Slide);
        // The five rays of the middle column at least, and the highlighted pixel's.
        let middle = diagram
            .rays
            .iter()
            .filter(|ray| ray.col == camera.width() / 2 && ray.sample == CameraSample::CENTER)
            .count();
        assert!(middle >= 5, "{name}: {middle} rays of the middle column");
        assert!(
            diagram
                .rays
                .iter()
                .any(|ray| (ray.row, ray.col) == pixel && ray.camera == camera),
            "{name}: the pixel's ray is missing"
        );
        assert!(
            diagram.figure.items.iter().any(|item| matches!(
                item,
                Item::Line { stroke, .. } if stroke.color == style::HIGHLIGHT
            )),
            "{name}: the pixel's ray is not highlighted"
        );
    }
}

#[test]
fn rays_stop_at_the_first_thing_they_hit() {
    for (name, text) in SCENES {
        let scene = scene(name, text);
        let camera = *scene.camera();
        let diagram = camera_side_view(&scene, &camera, None, SideViewCanvas::Slide);
        let mut stopped = 0;
        for ray in diagram
            .rays
            .iter()
            .filter(|ray| ray.sample == CameraSample::CENTER)
        {
            let generated = camera.generate_ray(ray.row, ray.col, ray.sample).unwrap();
            let hit = scene
                .world()
                .closest_hit(&generated.as_ray(), f32::MIN_POSITIVE..f32::INFINITY);
            match hit {
                // Drawn up to the hit, unless the hit lies outside the view.
                Some(hit) if (ray.t.1 - f64::from(hit.t)).abs() <= 1e-9 * ray.t.1.max(1.0) => {
                    stopped += 1;
                }
                Some(hit) => assert!(
                    ray.t.1 < f64::from(hit.t),
                    "{name}: ray ({}, {}) drawn past its hit",
                    ray.row,
                    ray.col
                ),
                None => {}
            }
        }
        assert!(stopped >= 2, "{name}: only {stopped} rays end at a hit");
    }
}

#[test]
fn the_view_is_the_plane_of_v_and_w_with_world_up_up() {
    for (name, text) in SCENES {
        let scene = scene(name, text);
        let camera = *scene.camera();
        let diagram = camera_side_view(&scene, &camera, None, SideViewCanvas::Slide);
        let FigureView::Side(view) = diagram.rays[0].view else {
            panic!("{name}: a side view")
        };
        let frame = camera.frame();
        // None of these cameras is rolled: up is the world's.
        assert!(
            view.up.abs_diff_eq(DVec3::Y, 1e-12),
            "{name}: up {}",
            view.up
        );
        let out = view.towards_viewer();
        assert!(out.dot(frame.v).abs() < 1e-12, "{name}: v leaves the plane");
        assert!(out.dot(frame.w).abs() < 1e-12, "{name}: w leaves the plane");
        // u points at the viewer.
        assert!(out.dot(frame.u) > 0.999, "{name}");
        // The camera looks right: -w has a positive right component, or none at all.
        assert!((-frame.w).dot(view.right) >= -1e-12, "{name}");
    }
}

#[test]
fn any_camera_can_be_drawn_over_a_scene_with_its_labels_on_the_canvas_and_apart() {
    let scene = scene("default", SCENES[0].1);
    for camera_text in [
        "Isometric(target: (0.0, 0.5, 0.0), size: 4.0)",
        "Top(target: (0.0, 0.0, 0.0), size: 6.0)",
        "(eye: (0.0, 8.0, 0.0), view: (0.0, -1.0, 0.0), up: (0.0, 0.0, -1.0), projection: Perspective(fov_y: 60.0))",
        "(eye: (3.0, 1.0, 3.0), look_at: (0.0, 0.5, 0.0), up: (1.0, 0.0, 0.0), projection: Perspective(fov_y: 40.0))",
        "(eye: (0.0, 1.0, 6.0), look_at: (0.0, 1.0, 0.0), projection: ThinLens(fov_y: 40.0, aperture: 0.3, focus: 6.0))",
    ] {
        let camera = parse_camera(camera_text, Path::new("camera"), 160, 90).unwrap();
        for canvas in [SideViewCanvas::Slide, SideViewCanvas::Panel] {
            let diagram = camera_side_view(&scene, &camera, Some((45, 80)), canvas);
            assert_drawn_rays_are_generated(camera_text, &diagram);
            let figure = &diagram.figure;
            let labels = labels(figure);
            for (k, a) in labels.iter().enumerate() {
                assert!(
                    figure.bounds().contains_rect(&a.bounds()),
                    "{camera_text}: {:?} leaves the canvas",
                    a.text
                );
                for b in &labels[k + 1..] {
                    assert!(
                        !a.bounds().intersects(&b.bounds()),
                        "{camera_text}: {:?} overlaps {:?}",
                        a.text,
                        b.text
                    );
                }
            }
        }
    }
}
