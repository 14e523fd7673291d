//! The details of single figures that a reader would stumble on: where a thumbnail's
//! horizon falls, a label straddling a border or touching its arrow, numbers for another
//! picture than the one shown.

use std::cell::RefCell;

use glam::{DVec3, Vec2};
use viewray_camera::Preset;
use viewray_draw::{Item, Rect};

use super::figures::labels;
use crate::pictures::{PictureRequest, PictureScene, Shape};
use crate::taxonomy::taxonomy_camera;
use crate::{figure_by_name, style};

#[test]
fn one_and_two_point_thumbnails_look_down_on_the_cubes_top() {
    for preset in [Preset::OnePoint, Preset::TwoPoint] {
        let camera = taxonomy_camera(&preset);
        let frame = camera.frame();
        let height = f64::from(camera.height());
        // The horizon: where a point far ahead at the eye's height appears.
        let ahead = DVec3::new(-frame.w().x, 0.0, -frame.w().z).normalize();
        let horizon = camera
            .project(frame.e() + ahead * 1e6)
            .expect("ahead of the eye")
            .y;
        // The cube's top corners (the cube is [-1, 1]^3 lifted onto the ground).
        for (x, z) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
            let top = camera
                .project(DVec3::new(x, 2.0, z))
                .expect("in front of the camera");
            assert!(
                top.y > horizon + 0.08 * height,
                "{}: the top corner ({x}, 2, {z}) at row {:.1}, the horizon at {horizon:.1}",
                preset.name(),
                top.y
            );
        }
    }
}

#[test]
fn taxonomy_thumbnails_keep_the_cube_off_their_frames() {
    for preset in Preset::ALL {
        let camera = taxonomy_camera(&preset);
        let size = glam::DVec2::new(f64::from(camera.width()), f64::from(camera.height()));
        let margin = 0.03 * size.y;
        for corner in 0..8 {
            let p = DVec3::new(
                if corner & 1 == 0 { -1.0 } else { 1.0 },
                if corner & 2 == 0 { 0.0 } else { 2.0 },
                if corner & 4 == 0 { -1.0 } else { 1.0 },
            );
            let image = camera.project(p).expect("in front of the camera");
            assert!(
                image.cmpge(glam::DVec2::splat(margin)).all() && image.cmple(size - margin).all(),
                "{}: corner {p} at {image}, within {margin} of the frame",
                preset.name()
            );
        }
    }
}

#[test]
fn the_worked_pixels_coordinates_sit_inside_its_cell() {
    let figure = figure_by_name("pixel_to_image_plane")
        .expect("registered")
        .wireframe();
    let cell = figure
        .items
        .iter()
        .find_map(|item| match item {
            Item::Polygon { points, fill, .. } if *fill == style::HIGHLIGHT.with_alpha(0.3) => {
                let min = points.iter().fold(Vec2::INFINITY, |a, &b| a.min(b));
                let max = points.iter().fold(Vec2::NEG_INFINITY, |a, &b| a.max(b));
                Some(Rect::from_corners(min, max))
            }
            _ => None,
        })
        .expect("the worked pixel's cell");
    let label = labels(&figure)
        .into_iter()
        .find(|label| label.text == "(0.25, 0.5)")
        .expect("the worked pixel's (u, v)");
    assert!(
        cell.contains_rect(&label.bounds()),
        "{:?} leaves the cell {cell:?}",
        label.bounds()
    );
}

#[test]
fn the_eyes_label_stands_clear_of_its_arrow() {
    let figure = figure_by_name("assumption_eye")
        .expect("registered")
        .wireframe();
    let (from, to) = figure
        .items
        .iter()
        .find_map(|item| match item {
            Item::Arrow {
                from, to, stroke, ..
            } if stroke.color == style::EYE => Some((*from, *to)),
            _ => None,
        })
        .expect("the arrow from the origin to e");
    let label = labels(&figure)
        .into_iter()
        .find(|label| label.text.starts_with("*e* = "))
        .expect("e's coordinates");
    let bounds = label.bounds();
    // The distance from the arrow's line to the label's nearest corner.
    let along = (to - from).normalize();
    let corners = [
        bounds.min,
        Vec2::new(bounds.max.x, bounds.min.y),
        bounds.max,
        Vec2::new(bounds.min.x, bounds.max.y),
    ];
    let gap = corners
        .iter()
        .map(|&c| along.perp_dot(c - from).abs())
        .fold(f32::INFINITY, f32::min);
    let sides: Vec<f32> = corners.iter().map(|&c| along.perp_dot(c - from)).collect();
    assert!(
        sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0),
        "the arrow crosses the label {bounds:?}"
    );
    assert!(gap >= 8.0, "the label is {gap:.1} px from its arrow");
}

#[test]
fn foreshortenings_pixel_heights_are_those_of_the_picture_shown() {
    let requests = RefCell::new(Vec::<PictureRequest>::new());
    let recording = |request: &PictureRequest| {
        requests.borrow_mut().push(*request);
        None
    };
    let diagram = figure_by_name("distortion_foreshortening")
        .expect("registered")
        .draw(&recording);
    let requests = requests.borrow();
    let [request] = requests.as_slice() else {
        panic!("one picture, not {}", requests.len())
    };
    let camera = request.camera;
    assert_eq!(
        (camera.width(), camera.height()),
        request.size,
        "the camera's image is the picture's slot"
    );
    // Each post's height in that picture, as its line says.
    let lines: Vec<String> = labels(&diagram.figure)
        .iter()
        .filter(|label| label.text.starts_with("depth "))
        .map(|label| label.text.clone())
        .collect();
    let posts: Vec<_> = PictureScene::Posts
        .objects()
        .into_iter()
        .filter_map(|object| match object.shape {
            Shape::Box { min, max } => Some((min, max)),
            Shape::Sphere { .. } => None,
        })
        .collect();
    assert_eq!(lines.len(), posts.len(), "{lines:?}");
    for (line, (min, max)) in lines.iter().zip(posts) {
        let x = (min.x + max.x) / 2.0;
        let top = camera.project(DVec3::new(x, max.y, max.z)).unwrap();
        let foot = camera.project(DVec3::new(x, min.y, max.z)).unwrap();
        let pixels = (foot.y - top.y).abs().round();
        assert!(
            line.ends_with(&format!("({pixels} px)")),
            "{line:?}: the picture shows {pixels} px"
        );
    }
}
