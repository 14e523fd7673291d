//! The side view of any camera over a scene: rays the camera generates, drawn to what
//! they hit, in the plane of the camera's v and w, in a window fitted to one camera or
//! fixed for an animation.

use std::path::Path;

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample};
use viewray_draw::{Item, Rect};
use viewray_scene::{Scene, parse_camera};

use super::figures::{assert_drawn_rays_are_generated, labels};
use crate::Diagram;
use crate::camera_side::{SideViewCanvas, SideWindow, side_view};
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
    viewray_scene::SceneLoader::text(text, &path)
        .load()
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}

/// The side view of `camera` in a window fitted to it alone.
fn fitted(
    scene: &Scene,
    camera: &Camera,
    pixel: Option<(u32, u32)>,
    canvas: SideViewCanvas,
) -> Diagram {
    let window = SideWindow::fit(scene, std::slice::from_ref(camera));
    side_view(scene, camera, &window, canvas, pixel)
}

const CANVASES: [SideViewCanvas; 6] = [
    SideViewCanvas::Slide,
    SideViewCanvas::Panel,
    SideViewCanvas::Square,
    SideViewCanvas::Fitted {
        width: 1700,
        height: 600,
    },
    SideViewCanvas::Fitted {
        width: 600,
        height: 600,
    },
    SideViewCanvas::Beside,
];

#[test]
fn every_ray_drawn_is_one_the_camera_generates() {
    for (name, text) in SCENES {
        let scene = scene(name, text);
        let camera = *scene.camera();
        let pixel = (camera.height() / 3, camera.width() / 4);
        for canvas in CANVASES {
            let diagram = fitted(&scene, &camera, Some(pixel), canvas);
            assert_drawn_rays_are_generated(name, &diagram);
        }
        let diagram = fitted(&scene, &camera, Some(pixel), SideViewCanvas::Slide);
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
        let diagram = fitted(&scene, &camera, None, SideViewCanvas::Slide);
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
        let diagram = fitted(&scene, &camera, None, SideViewCanvas::Slide);
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
        assert!(
            out.dot(frame.v()).abs() < 1e-12,
            "{name}: v leaves the plane"
        );
        assert!(
            out.dot(frame.w()).abs() < 1e-12,
            "{name}: w leaves the plane"
        );
        // u points at the viewer.
        assert!(out.dot(frame.u()) > 0.999, "{name}");
        // The camera looks right: -w has a positive right component, or none at all.
        assert!((-frame.w()).dot(view.right) >= -1e-12, "{name}");
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
        // Captions longer than a panel is wide.
        "(eye: (5.2, 1.6, 6.0), look_at: (0.0, 0.5, 0.0), projection: ThinLens(fov_y: 33.7, shift: (-0.32571, -0.21987), aperture: 0.061234, focus: 7.7777))",
        "(eye: (0.5, 1.5, 9.0), view: (0.0, 0.0, -1.0), projection: Oblique(viewport: (7.33333, 4.12345), ratio: 0.55555, angle: 37.5))",
    ] {
        let camera = parse_camera(camera_text, Path::new("camera"), 160, 90).unwrap();
        for canvas in CANVASES {
            let diagram = fitted(&scene, &camera, Some((45, 80)), canvas);
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

/// A unit sphere at the origin, and nothing else.
fn sphere_scene() -> Scene {
    viewray_scene::SceneLoader::text(
        "(camera: (eye: (0.0, 0.0, 5.0), look_at: (0.0, 0.0, 0.0), \
         projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))), \
         image: (width: 40, height: 40), \
         materials: { \"grey\": (color: (0.5, 0.5, 0.5)) }, \
         objects: [Sphere(center: (0.0, 0.0, 0.0), radius: 1.0, material: \"grey\")])",
        Path::new("sphere.ron"),
    )
    .load()
    .map(|loaded| loaded.scene)
    .unwrap()
}

/// The camera of `sphere_scene` with its eye at `(0, 0, z)`.
fn looking_down_minus_z(z: f64) -> Camera {
    let text = format!(
        "(eye: (0.0, 0.0, {z:?}), look_at: (0.0, 0.0, 0.0), \
         projection: Perspective(distance: 1.0, viewport: (1.0, 1.0)))"
    );
    parse_camera(&text, Path::new("camera"), 40, 40).unwrap()
}

#[test]
fn a_window_holds_the_objects_the_camera_and_room_for_its_frame() {
    let scene = sphere_scene();
    let camera = looking_down_minus_z(5.0);
    let window = SideWindow::fit(&scene, &[camera]);
    // The camera looks down -z, up y: -z is drawn right and y up, plane point
    // (-p.z, p.y). The sphere spans [-1, 1] both ways; the eye is at (-5, 0); the image
    // plane's edges at (-4, +-0.5). Fitted: from -5 to 1 across, size 6, so w (+z) and v
    // (+y) reach 0.1 * 6 past the eye: -5.6 across, 0.6 up (inside the sphere's 1). With
    // the margin of 0.1 * 6.6 = 0.66 all round:
    assert!(
        window.right.abs_diff_eq(DVec3::NEG_Z, 1e-12),
        "{}",
        window.right
    );
    assert!(window.up.abs_diff_eq(DVec3::Y, 1e-12), "{}", window.up);
    assert!(
        window.min.abs_diff_eq(DVec2::new(-6.26, -1.66), 1e-9),
        "{}",
        window.min
    );
    assert!(
        window.max.abs_diff_eq(DVec2::new(1.66, 1.66), 1e-9),
        "{}",
        window.max
    );
}

#[test]
fn an_animations_window_keeps_the_objects_still_and_far_eyes_as_arrows() {
    let scene = sphere_scene();
    let cameras = [5.0, 10.0, 10_000.0].map(looking_down_minus_z);
    let window = SideWindow::fit(&scene, &cameras);
    // The nearest eye (5) sets the size, 6 across; eyes within three times the size of
    // that are in (10), farther ones are not (10000).
    assert!(
        window.min.x < -10.0 && window.min.x > -20.0,
        "{}",
        window.min
    );
    let spheres: Vec<Item> = cameras
        .iter()
        .map(|camera| {
            let diagram = side_view(&scene, camera, &window, SideViewCanvas::Beside, None);
            assert_drawn_rays_are_generated("moving camera", &diagram);
            let texts: Vec<&str> = labels(&diagram.figure)
                .iter()
                .map(|label| label.text.as_str())
                .collect();
            let far = camera.frame().e().z > 100.0;
            assert_eq!(texts.contains(&"*e*"), !far, "{texts:?}");
            // 10000 from the sphere's centre, the middle of the objects.
            assert_eq!(texts.contains(&"*e*, 10000 away"), far, "{texts:?}");
            let arrows_to_eye = diagram
                .figure
                .items
                .iter()
                .filter(
                    |item| matches!(item, Item::Arrow { stroke, .. } if stroke.color == style::EYE),
                )
                .count();
            assert_eq!(arrows_to_eye, usize::from(far));
            diagram
                .figure
                .items
                .iter()
                .find(|item| matches!(item, Item::Ellipse { rotation, .. } if *rotation == 0.0))
                .expect("the sphere")
                .clone()
        })
        .collect();
    // The sphere is drawn in the same place in every frame: only the camera moves.
    assert_eq!(spheres[0], spheres[1]);
    assert_eq!(spheres[0], spheres[2]);
}

#[test]
fn a_caption_too_long_for_its_canvas_wraps_between_its_parts() {
    let scene = scene("default", SCENES[0].1);
    let camera = parse_camera(
        "(eye: (5.2, 1.6, 6.0), look_at: (0.0, 0.5, 0.0), projection: ThinLens(fov_y: 33.7, \
         shift: (-0.32571, -0.21987), aperture: 0.061234, focus: 7.7777))",
        Path::new("camera"),
        640,
        360,
    )
    .unwrap();
    for canvas in CANVASES {
        let diagram = fitted(&scene, &camera, None, canvas);
        let texts: Vec<&str> = labels(&diagram.figure)
            .iter()
            .map(|label| label.text.as_str())
            .collect();
        // Every part whole, the shift's numbers on one line.
        for label in labels(&diagram.figure) {
            assert!(
                diagram.figure.bounds().contains_rect(&label.bounds()),
                "{canvas:?}: {:?} leaves the canvas",
                label.text
            );
        }
        for part in [
            "thin lens:  $d$ = 1",
            "$vw$ × $vh$ = 1.077 × 0.606",
            "shift (−0.326, −0.22)",
            "aperture $r$ = 0.0612",
            "focus $f$ = 7.778",
        ] {
            assert!(
                texts.iter().any(|text| text.contains(part)),
                "{canvas:?}: no label holds {part:?}: {texts:?}"
            );
        }
    }
}

/// The extent `(across, up)` of the scene's bounded objects in `window`'s plane.
fn objects_extent(scene: &Scene, window: &SideWindow) -> DVec2 {
    let (mut min, mut max) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
    for object in scene.world().objects() {
        if let Some(bounds) = object.bounds() {
            for p in bounds.corners() {
                let p = p.as_dvec3();
                let q = DVec2::new(p.dot(window.right), p.dot(window.up));
                min = min.min(q);
                max = max.max(q);
            }
        }
    }
    max - min
}

#[test]
fn far_cameras_leave_the_scene_large_and_point_at_their_eye() {
    let scene = scene("default", SCENES[0].1);
    for camera_text in [
        "Top(target: (0.0, 0.5, 0.0), size: 6.0)",
        "Cabinet(target: (0.0, 0.5, 0.0), size: 5.0)",
        // A late frame of perspective to orthographic: 164 from the objects.
        "(eye: (82.0, 82.0, 120.0), look_at: (0.0, 0.5, 0.0), \
         projection: Perspective(distance: 1.0, viewport: (0.1, 0.05625)))",
    ] {
        let camera = parse_camera(camera_text, Path::new("camera"), 640, 360).unwrap();
        let window = SideWindow::fit(&scene, &[camera]);
        // What a panel's drawing (900 x 440) shows of the plane: the window, widened or
        // heightened to the drawing's shape.
        let mut shown = window.max - window.min;
        let aspect = 900.0 / 440.0;
        shown = shown.max(DVec2::new(shown.y * aspect, shown.x / aspect));
        let objects = objects_extent(&scene, &window);
        let share = (objects / shown).max_element();
        assert!(
            share > 0.2,
            "{camera_text}: the objects fill {share:.3} of the drawing"
        );
        let diagram = fitted(&scene, &camera, None, SideViewCanvas::Panel);
        assert_drawn_rays_are_generated(camera_text, &diagram);
        let arrows_to_eye = diagram
            .figure
            .items
            .iter()
            .filter(|item| matches!(item, Item::Arrow { stroke, .. } if stroke.color == style::EYE))
            .count();
        assert_eq!(arrows_to_eye, 1, "{camera_text}: an arrow towards the eye");
    }
}

#[test]
fn a_far_eyes_distance_is_measured_from_the_middle_of_the_objects() {
    // The sphere's centre is the origin: the eye is 164 from it, as a caption saying
    // "eye 164 from the target" means.
    let scene = sphere_scene();
    let back = DVec3::new(0.3, 0.4, 1.0).normalize();
    let text = format!(
        "(eye: ({:?}, {:?}, {:?}), look_at: (0.0, 0.0, 0.0), \
         projection: Perspective(distance: 1.0, viewport: (0.02, 0.02)))",
        back.x * 164.0,
        back.y * 164.0,
        back.z * 164.0
    );
    let camera = parse_camera(&text, Path::new("camera"), 40, 40).unwrap();
    for canvas in CANVASES {
        let diagram = fitted(&scene, &camera, None, canvas);
        let texts: Vec<&str> = labels(&diagram.figure)
            .iter()
            .map(|label| label.text.as_str())
            .collect();
        assert!(texts.contains(&"*e*, 164 away"), "{canvas:?}: {texts:?}");
    }
}

/// Whether the segment from `a` to `b` crosses the rectangle `rect`.
fn segment_meets(rect: &Rect, a: Vec2, b: Vec2) -> bool {
    // Liang-Barsky: clip the segment's parameter to the rectangle's slabs.
    let d = b - a;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for (start, slope, low, high) in [
        (a.x, d.x, rect.min.x, rect.max.x),
        (a.y, d.y, rect.min.y, rect.max.y),
    ] {
        if slope == 0.0 {
            if start < low || start > high {
                return false;
            }
            continue;
        }
        let (p, q) = ((low - start) / slope, (high - start) / slope);
        t0 = t0.max(p.min(q));
        t1 = t1.min(p.max(q));
    }
    t0 <= t1
}

/// Whether `rect` overlaps the convex polygon `points` (or its outline crosses it).
fn polygon_meets(rect: &Rect, points: &[Vec2]) -> bool {
    let edges = points.iter().zip(points.iter().cycle().skip(1));
    if edges.clone().any(|(&a, &b)| segment_meets(rect, a, b)) {
        return true;
    }
    // The rectangle wholly inside: its centre on the inner side of every edge.
    let c = rect.center();
    let sides: Vec<f32> = edges.map(|(&a, &b)| (b - a).perp_dot(c - a)).collect();
    sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0)
}

#[test]
fn side_view_labels_keep_off_the_rays_and_the_objects() {
    let default = scene("default", SCENES[0].1);
    let street = viewray_scene::SceneLoader::text(
        include_str!("../../../viewray-animation/scenes/street.ron"),
        Path::new("street.ron"),
    )
    .load()
    .unwrap()
    .scene;
    let cases = [
        (
            &default,
            "(eye: (5.2, 1.6, 6.0), view: (-5.2, 0.0, -6.0), up: (0.0, 1.0, 0.0), \
             projection: ThinLens(fov_y: 32.0, shift: (0.0, -0.17), aperture: 0.06, focus: 7.0))",
        ),
        (
            &default,
            "(eye: (3.0, 2.0, 4.0), look_at: (0.0, 0.5, 0.0), projection: Perspective(fov_y: 40.0))",
        ),
        // The dolly zoom, early and midway.
        (
            &street,
            "(eye: (0.0, 1.0, 3.0), view: (0.0, 0.0, -1.0), \
             projection: Perspective(distance: 0.825, viewport: (1.7778, 1.0)))",
        ),
        (
            &street,
            "(eye: (0.0, 1.0, 7.25), view: (0.0, 0.0, -1.0), \
             projection: Perspective(distance: 1.99375, viewport: (1.7778, 1.0)))",
        ),
    ];
    for (scene, camera_text) in cases {
        let camera = parse_camera(camera_text, Path::new("camera"), 480, 270).unwrap();
        for canvas in [SideViewCanvas::Slide, SideViewCanvas::Panel] {
            let diagram = fitted(scene, &camera, Some((160, 260)), canvas);
            let items = &diagram.figure.items;
            let rays: Vec<(Vec2, Vec2)> = items
                .iter()
                .filter_map(|item| match item {
                    // Rays and the frustum's edges, not a label's thin leader line.
                    Item::Line { from, to, stroke }
                        if (stroke.color == style::RAY || stroke.color == style::HIGHLIGHT)
                            && stroke.width >= style::LINE_THIN =>
                    {
                        Some((*from, *to))
                    }
                    _ => None,
                })
                .collect();
            let objects: Vec<Vec<Vec2>> = items
                .iter()
                .filter_map(|item| match item {
                    Item::Polygon {
                        points,
                        stroke: Some(stroke),
                        ..
                    } if stroke.color == style::OBJECT => Some(points.clone()),
                    _ => None,
                })
                .collect();
            for label in labels(&diagram.figure) {
                let named = [
                    "*e*",
                    "*u*",
                    "*v*",
                    "*w*",
                    "image plane",
                    "focus plane",
                    "$i$",
                ];
                if !named.iter().any(|name| label.text.starts_with(name)) {
                    continue;
                }
                let bounds = label.bounds();
                for (a, b) in &rays {
                    assert!(
                        !segment_meets(&bounds, *a, *b),
                        "{camera_text} ({canvas:?}): {:?} sits on a ray",
                        label.text
                    );
                }
                for points in &objects {
                    assert!(
                        !polygon_meets(&bounds, points),
                        "{camera_text} ({canvas:?}): {:?} covers an object",
                        label.text
                    );
                }
            }
        }
    }
}

#[test]
fn the_top_view_is_the_plane_of_u_and_w_with_the_view_up_the_page() {
    for (name, text) in SCENES {
        let scene = scene(name, text);
        let camera = *scene.camera();
        let window = SideWindow::fit_top(&scene, &[camera]);
        let frame = camera.frame();
        // u to the right, the view (-w) up: left and right are the picture's.
        assert!(window.right.abs_diff_eq(frame.u(), 1e-12), "{name}");
        assert!(window.up.abs_diff_eq(-frame.w(), 1e-12), "{name}");
        assert!(
            window.right.cross(window.up).abs_diff_eq(frame.v(), 1e-12),
            "{name}: seen from v's side"
        );
        let pixel = (camera.height() / 3, camera.width() / 4);
        for canvas in CANVASES {
            let diagram = side_view(&scene, &camera, &window, canvas, Some(pixel));
            assert_drawn_rays_are_generated(name, &diagram);
        }
        let diagram = side_view(&scene, &camera, &window, SideViewCanvas::Square, None);
        // The rays of the middle row, spread over its columns.
        let middle: Vec<u32> = diagram
            .rays
            .iter()
            .filter(|ray| ray.row == camera.height() / 2 && ray.sample == CameraSample::CENTER)
            .map(|ray| ray.col)
            .collect();
        assert!(middle.len() >= 5, "{name}: {middle:?}");
        let spread = middle.iter().max().unwrap() - middle.iter().min().unwrap();
        assert!(spread > camera.width() / 2, "{name}: {middle:?}");
        if matches!(name, "default" | "perspective_three_point") {
            let texts: Vec<&str> = labels(&diagram.figure)
                .iter()
                .map(|label| label.text.as_str())
                .collect();
            for axis in ["*e*", "*u*", "*v*", "*w*"] {
                assert!(texts.contains(&axis), "{name}: {axis} missing in {texts:?}");
            }
        }
    }
}

#[test]
fn a_fitted_panel_of_the_panels_size_is_the_panel() {
    let scene = scene("default", SCENES[0].1);
    let camera = *scene.camera();
    let panel = fitted(&scene, &camera, Some((10, 20)), SideViewCanvas::Panel);
    let sized = fitted(
        &scene,
        &camera,
        Some((10, 20)),
        SideViewCanvas::Fitted {
            width: 1000,
            height: 600,
        },
    );
    assert_eq!(panel, sized);
}
