//! The lecture figures: each renders, keeps its labels on the canvas and apart, draws
//! only rays its cameras generate, and writes well-formed SVG.

use std::cell::RefCell;

use glam::{DVec2, DVec3, Vec2};
use image::{Rgba, RgbaImage};
use viewray_camera::{CameraSample, Preset};
use viewray_draw::raster::render;
use viewray_draw::svg::{SvgText, document};
use viewray_draw::{Figure, Item, Label, Rect};

use crate::pictures::{PictureRequest, PictureScene, Shape, Wireframes};
use crate::taxonomy::taxonomy_camera;
use crate::thin_lens::{CONE_PIXEL, FOCUS, LENS_POINTS, thin_lens_camera};
use crate::{
    Diagram, NamedFigure, UnknownFigure, all_figures, figure_by_name, figure_names, style,
};

fn diagrams() -> Vec<(NamedFigure, Diagram)> {
    all_figures()
        .into_iter()
        .map(|named| {
            let diagram = named.draw(&Wireframes);
            (named, diagram)
        })
        .collect()
}

pub(super) fn labels(figure: &Figure) -> Vec<&Label> {
    figure
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Label(label) => Some(label),
            _ => None,
        })
        .collect()
}

/// The end points of every line and arrow.
pub(super) fn segments(figure: &Figure) -> Vec<(Vec2, Vec2, viewray_draw::Color)> {
    figure
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Line { from, to, stroke }
            | Item::Arrow {
                from, to, stroke, ..
            } => Some((*from, *to, stroke.color)),
            _ => None,
        })
        .collect()
}

#[test]
fn the_registry_names_every_figure_once() {
    let names = figure_names();
    assert!(names.len() >= 12, "{names:?}");
    for (k, name) in names.iter().enumerate() {
        assert!(
            name.chars().all(|c| c.is_ascii_lowercase() || c == '_'),
            "{name} is not snake_case"
        );
        assert!(!names[k + 1..].contains(name), "{name} twice");
        assert_eq!(figure_by_name(name).map(|f| f.name), Some(*name));
    }
    for expected in [
        "canonical_camera",
        "pixel_to_image_plane",
        "camera_frame",
        "viewing_rays",
        "taxonomy",
        "thin_lens",
    ] {
        assert!(names.contains(&expected), "{expected} missing");
    }
    assert!(figure_by_name("no_such_figure").is_none());
    let message = UnknownFigure::new("no_such_figure").to_string();
    assert!(message.contains("`no_such_figure`"), "{message}");
    assert!(message.contains(&names.join(", ")), "{message}");
}

#[test]
fn every_figure_renders_on_a_lecture_canvas_with_ink() {
    for (named, diagram) in diagrams() {
        let figure = &diagram.figure;
        let size = (figure.width, figure.height);
        assert!(
            size == style::SLIDE || size == style::SQUARE,
            "{}: {size:?}",
            named.name
        );
        let pixels = render(figure);
        let background = Rgba([255, 255, 255, 255]);
        let inked = pixels.pixels().filter(|p| **p != background).count();
        let share = inked as f64 / f64::from(figure.width * figure.height);
        assert!(
            share > 0.03,
            "{}: only {share:.3} of the canvas inked",
            named.name
        );
        assert!(labels(figure).len() >= 4, "{}: too few labels", named.name);
        assert!(!named.summary.is_empty());
    }
}

#[test]
fn labels_stay_on_the_canvas_and_apart() {
    let mut problems = Vec::new();
    for (named, diagram) in diagrams() {
        let figure = &diagram.figure;
        let canvas = figure.bounds();
        let labels = labels(figure);
        for (k, a) in labels.iter().enumerate() {
            if !canvas.contains_rect(&a.bounds()) {
                problems.push(format!(
                    "{}: {:?} leaves the canvas ({:?})",
                    named.name,
                    a.text,
                    a.bounds()
                ));
            }
            for b in &labels[k + 1..] {
                if a.bounds().intersects(&b.bounds()) {
                    problems.push(format!(
                        "{}: {:?} overlaps {:?}",
                        named.name, a.text, b.text
                    ));
                }
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[track_caller]
fn assert_close(a: DVec3, b: DVec3, what: &str) {
    let scale = a.abs().max(b.abs()).max_element().max(1.0);
    assert!(a.abs_diff_eq(b, 1e-9 * scale), "{what}: {a} vs {b}");
}

#[test]
fn drawn_rays_are_the_rays_the_cameras_generate() {
    for (named, diagram) in diagrams() {
        assert_drawn_rays_are_generated(named.name, &diagram);
    }
}

/// Every ray recorded on `diagram` is the ray its camera generates, drawn where the
/// view puts its ends, as a line of the figure; and every line in the ray colour is a
/// recorded ray.
#[track_caller]
pub(super) fn assert_drawn_rays_are_generated(name: &str, diagram: &Diagram) {
    let figure = &diagram.figure;
    let drawn_segments = segments(figure);
    for ray in &diagram.rays {
        let what = format!("{name} ray ({}, {})", ray.row, ray.col);
        let generated = ray
            .camera
            .generate_ray(ray.row, ray.col, ray.sample)
            .expect("a ray");
        assert!(ray.t.0 >= 0.0 && ray.t.1 > ray.t.0, "{what}: t {:?}", ray.t);
        assert_close(generated.at(ray.t.0), ray.from, &what);
        assert_close(generated.at(ray.t.1), ray.to, &what);
        let from_px = ray.view.to_figure(ray.from).expect("in view");
        let to_px = ray.view.to_figure(ray.to).expect("in view");
        assert!(
            from_px.abs_diff_eq(ray.from_px, 1e-3),
            "{what}: drawn elsewhere"
        );
        assert!(
            to_px.abs_diff_eq(ray.to_px, 1e-3),
            "{what}: drawn elsewhere"
        );
        assert!(
            drawn_segments
                .iter()
                .any(|(a, b, _)| *a == ray.from_px && *b == ray.to_px),
            "{what}: no line on the figure"
        );
    }
    // Conversely, every line in the ray colour is one of the recorded rays.
    for (a, b, color) in &drawn_segments {
        if *color == style::RAY {
            assert!(
                diagram
                    .rays
                    .iter()
                    .any(|ray| ray.from_px == *a && ray.to_px == *b),
                "{name}: a ray-coloured line {a} -> {b} that no camera generated"
            );
        }
    }
}

#[test]
fn ray_figures_draw_rays() {
    let expected = [
        ("canonical_camera", 50),
        ("assumption_distance", 7),
        ("assumption_eye", 10),
        ("assumption_basis", 24),
        ("viewing_rays", 24),
        ("distortion_foreshortening", 8),
        ("distortion_verticals", 4),
        ("thin_lens", 5),
        ("scheimpflug", 9),
    ];
    for (name, at_least) in expected {
        let diagram = figure_by_name(name).expect(name).draw(&Wireframes);
        assert!(
            diagram.rays.len() >= at_least,
            "{name}: {} rays",
            diagram.rays.len()
        );
    }
}

#[test]
fn the_canonical_figure_works_the_lecture_formula() {
    // The worked pixel (i, j) = (2, 4) of the 5 x 5 canonical camera: u = (j - 1/2)/W - 1/2
    // = 0.2, v = -((i - 1/2)/H - 1/2) = 0.2, direction (u, v, -1).
    let diagram = figure_by_name("canonical_camera")
        .expect("registered")
        .draw(&Wireframes);
    let (i, j, w, h) = (2.0, 4.0, 5.0, 5.0);
    let u: f64 = (j - 0.5) / w - 0.5;
    let v: f64 = -((i - 0.5) / h - 0.5);
    let ray = diagram
        .rays
        .iter()
        .find(|ray| (ray.row, ray.col) == (1, 3))
        .expect("the worked pixel's ray");
    assert_close(
        ray.to - ray.from,
        DVec3::new(u, v, -1.0) * (ray.t.1 - ray.t.0),
        "direction",
    );
    let texts: Vec<&str> = labels(&diagram.figure)
        .iter()
        .map(|label| label.text.as_str())
        .collect();
    assert!(
        texts.contains(&"direction (0.2, 0.2, \u{2212}1)"),
        "{texts:?}"
    );
    assert_eq!(
        diagram.rays.len(),
        50,
        "25 pixels, before and beyond the plane"
    );
}

#[test]
fn thin_lens_cone_meets_at_the_focus_plane() {
    let diagram = figure_by_name("thin_lens")
        .expect("registered")
        .draw(&Wireframes);
    let cone: Vec<_> = diagram
        .rays
        .iter()
        .filter(|ray| (ray.row, ray.col) == CONE_PIXEL)
        .collect();
    assert_eq!(cone.len(), LENS_POINTS.len());
    let frame = *cone[0].camera.frame();
    let pinhole = cone[0]
        .camera
        .generate_ray(CONE_PIXEL.0, CONE_PIXEL.1, CameraSample::CENTER)
        .expect("a ray");
    let focus_point = pinhole.at(1.0);
    assert!(
        (-(focus_point - frame.e()).dot(frame.w()) - FOCUS).abs() < 1e-9,
        "the pinhole ray reaches the focus plane at t = 1"
    );
    let mut origins: Vec<DVec3> = Vec::new();
    for ray in &cone {
        let generated = ray
            .camera
            .generate_ray(ray.row, ray.col, ray.sample)
            .expect("a ray");
        // Where the ray crosses the focus plane: camera depth -(p - e).w = f.
        let t = (FOCUS + (generated.origin - frame.e()).dot(frame.w()))
            / -generated.direction.dot(frame.w());
        assert_close(generated.at(t), focus_point, "meets at the focus plane");
        assert!(ray.t.1 > t, "drawn past the focus plane");
        assert!(
            origins.iter().all(|o| o.distance(generated.origin) > 0.05),
            "distinct lens points"
        );
        origins.push(generated.origin);
    }
    // The lens points span the aperture.
    let spread = origins
        .iter()
        .map(|o| o.distance(frame.e()))
        .fold(0.0, f64::max);
    assert!(spread > 0.3, "{spread}");
}

#[test]
fn scheimpflug_rays_meet_on_the_tilted_plane_through_both_lines() {
    use crate::scheimpflug::{COLUMN, FOCUS, LENS_POINTS, ROWS, TILT_DEGREES};
    let diagram = figure_by_name("scheimpflug")
        .expect("registered")
        .draw(&Wireframes);
    let camera = crate::scheimpflug::scheimpflug_camera();
    let plane = camera.focus_plane().expect("a lens");
    let tilted = camera.tilted_focus().expect("tilted");
    // F = d = 1: the hinge line F / sin 20 = 2.924 below the lens.
    let e = camera.frame().e();
    assert_close(
        tilted.hinge_line.point,
        e - DVec3::Y / TILT_DEGREES.to_radians().sin(),
        "the hinge line",
    );
    // The sensor s = F f / (f - F) behind the lens; the Scheimpflug line on it.
    let s = FOCUS / (FOCUS - 1.0);
    assert!((tilted.scheimpflug_line.point.z - s).abs() < 1e-12);
    for line in [tilted.hinge_line, tilted.scheimpflug_line] {
        assert!(plane.normal.dot(line.point - plane.point).abs() < 1e-12);
    }
    for row in ROWS {
        let rays: Vec<_> = diagram
            .rays
            .iter()
            .filter(|ray| (ray.row, ray.col) == (row, COLUMN))
            .collect();
        // One ray per lens point.
        assert_eq!(rays.len(), LENS_POINTS.len(), "row {row}");
        let centre = camera
            .generate_ray(row, COLUMN, CameraSample::CENTER)
            .expect("a ray");
        let meet = centre.at(1.0);
        assert!(plane.normal.dot(meet - plane.point).abs() < 1e-9);
        for ray in &rays {
            let generated = ray
                .camera
                .generate_ray(ray.row, ray.col, ray.sample)
                .expect("a ray");
            assert_close(generated.at(1.0), meet, "meets on the plane of focus");
            assert!(ray.t.1 > 1.0, "drawn past the plane");
        }
    }
}

#[test]
fn every_figure_writes_well_formed_svg() {
    for (named, diagram) in diagrams() {
        let svg = document(&diagram.figure, SvgText::Paths);
        let doc =
            roxmltree::Document::parse(&svg).unwrap_or_else(|e| panic!("{}: {e}", named.name));
        let root = doc.root_element();
        assert_eq!(root.tag_name().name(), "svg");
        let labelled = doc
            .descendants()
            .filter(|n| n.attribute("aria-label").is_some())
            .count();
        assert_eq!(labelled, labels(&diagram.figure).len(), "{}", named.name);
    }
}

#[test]
fn rendered_pictures_fill_the_same_slots_without_moving_anything() {
    let requests = RefCell::new(Vec::<PictureRequest>::new());
    let rendered = |request: &PictureRequest| {
        requests.borrow_mut().push(*request);
        let (w, h) = (request.camera.width(), request.camera.height());
        Some(RgbaImage::from_pixel(w, h, Rgba([200, 30, 30, 255])))
    };
    for name in [
        "taxonomy",
        "distortion_foreshortening",
        "distortion_verticals",
        "thin_lens",
    ] {
        let named = figure_by_name(name).expect("registered");
        requests.borrow_mut().clear();
        let with = named.draw(&rendered).figure;
        let without = named.wireframe();
        let images: Vec<Rect> = with
            .items
            .iter()
            .filter_map(|item| match item {
                Item::Image { rect, .. } => Some(*rect),
                _ => None,
            })
            .collect();
        assert_eq!(images.len(), requests.borrow().len(), "{name}");
        assert!(!images.is_empty(), "{name}");
        let bounds = |figure: &Figure| -> Vec<Rect> {
            labels(figure).iter().map(|label| label.bounds()).collect()
        };
        assert_eq!(bounds(&with), bounds(&without), "{name}: labels moved");
        // Each slot's frame is drawn around the image, as around the polygons.
        for rect in &images {
            let frame = with.items.iter().any(|item| {
                matches!(item, Item::Polyline { points, closed: true, .. }
                    if points.first() == Some(&rect.min))
            });
            assert!(frame, "{name}: slot {rect:?} has no frame");
        }
    }
    // The taxonomy asks for the cube through every preset's camera, in order.
    requests.borrow_mut().clear();
    figure_by_name("taxonomy")
        .expect("registered")
        .draw(&rendered);
    let asked: Vec<_> = requests
        .borrow()
        .iter()
        .map(|r| (r.scene, r.camera))
        .collect();
    let expected: Vec<_> = Preset::ALL
        .iter()
        .map(|preset| (PictureScene::AxisCube, taxonomy_camera(preset)))
        .collect();
    assert_eq!(asked, expected);
}

#[test]
fn taxonomy_pictures_show_the_whole_cube() {
    for preset in Preset::ALL {
        let camera = taxonomy_camera(&preset);
        let size = DVec2::new(f64::from(camera.width()), f64::from(camera.height()));
        for corner in 0..8 {
            let p = DVec3::new(
                if corner & 1 == 0 { -1.0 } else { 1.0 },
                if corner & 2 == 0 { 0.0 } else { 2.0 },
                if corner & 4 == 0 { -1.0 } else { 1.0 },
            );
            let image = camera.project(p).expect("in front of the camera");
            assert!(
                image.cmpge(DVec2::ZERO).all() && image.cmple(size).all(),
                "{}: corner {p} at {image}",
                preset.name()
            );
        }
    }
}

#[test]
fn the_axis_cube_is_the_fixture_cube() {
    let obj = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/meshes/cube.obj"
    ))
    .expect("fixtures/meshes/cube.obj");
    let vertices: Vec<DVec3> = obj
        .lines()
        .filter_map(|line| line.strip_prefix("v "))
        .map(|rest| {
            let xyz: Vec<f64> = rest
                .split_whitespace()
                .map(|n| n.parse().expect("a number"))
                .collect();
            DVec3::new(xyz[0], xyz[1], xyz[2])
        })
        .collect();
    let min = vertices.iter().fold(DVec3::INFINITY, |a, &b| a.min(b));
    let max = vertices.iter().fold(DVec3::NEG_INFINITY, |a, &b| a.max(b));
    let objects = PictureScene::AxisCube.objects();
    assert_eq!(objects.len(), 1);
    // The scenes lift the fixture's cube onto the ground by (0, 1, 0).
    assert_eq!(
        objects[0].shape,
        Shape::Box {
            min: min + DVec3::Y,
            max: max + DVec3::Y
        }
    );
    let _ = thin_lens_camera(0.1);
}
