//! Rendered pictures: the figures' scenes are the fixtures' scenes, the renders land in
//! their slots pixel for pixel, and they show what the cameras see.

use std::path::Path;

use glam::Vec3;
use image::{Rgba, RgbaImage};
use viewray_camera::{Camera, Preset, Projection};
use viewray_draw::Item;
use viewray_scene::{Light, Material, ObjectMaterial, Scene};

use crate::figure_by_name;
use crate::pictures::{PictureRequest, PictureScene, Pictures};
use crate::rendered::{RenderedPictures, picture_lights, picture_scene};
use crate::taxonomy::taxonomy_camera;
use crate::thin_lens::{PICTURE_APERTURES, thin_lens_camera};

fn fixture(name: &str) -> Scene {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/scenes")
        .join(name);
    viewray_scene::SceneLoader::file(&path)
        .load()
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}

/// The materials an object uses.
fn materials_of(scene: &Scene, object: usize) -> Vec<Material> {
    let mut materials: Vec<Material> = match &scene.object_materials()[object] {
        ObjectMaterial::Single(index) => vec![scene.materials()[*index as usize]],
        ObjectMaterial::PerTriangle(faces) => faces
            .iter()
            .map(|&index| scene.materials()[index as usize])
            .collect(),
    };
    materials.sort_by(|a, b| a.color.to_array().partial_cmp(&b.color.to_array()).unwrap());
    materials.dedup();
    materials
}

#[track_caller]
fn assert_lights_close(actual: &[Light], expected: &[Light]) {
    assert_eq!(actual.len(), expected.len());
    let parts = |light: &Light| match *light {
        Light::Point {
            position,
            intensity,
        } => (0, position, intensity),
        Light::Directional {
            direction,
            intensity,
        } => (1, direction, intensity),
        Light::Ambient { intensity } => (2, Vec3::ZERO, intensity),
    };
    for (a, e) in actual.iter().zip(expected) {
        let (a, e) = (parts(a), parts(e));
        assert_eq!(a.0, e.0, "{actual:?} vs {expected:?}");
        assert!(a.1.abs_diff_eq(e.1, 1e-6) && a.2.abs_diff_eq(e.2, 1e-6));
    }
}

fn request(scene: PictureScene, camera: Camera, size: (u32, u32)) -> PictureRequest {
    PictureRequest {
        scene,
        camera,
        size,
    }
}

#[test]
fn picture_scenes_are_lit_and_coloured_as_the_fixtures() {
    // The isometric fixture: the grid ground (object 0) and the axis-coloured cube mesh.
    let fixture_scene = fixture("axonometric_isometric.ron");
    let camera = taxonomy_camera(&Preset::Isometric);
    let picture = picture_scene(&request(PictureScene::AxisCube, camera, (24, 18)), 4);
    assert_eq!(picture.background(), fixture_scene.background());
    assert_lights_close(picture.lights(), fixture_scene.lights());
    assert_lights_close(&picture_lights(), fixture_scene.lights());
    assert_eq!(materials_of(&picture, 0), materials_of(&fixture_scene, 0));
    // The cube: object 2 of the picture (after the ground and the earth), 1 of the
    // fixture; three face materials, the fixture's MTL colours.
    let cube = materials_of(&picture, 2);
    assert_eq!(cube.len(), 3);
    assert_eq!(cube, materials_of(&fixture_scene, 1));
    assert_eq!(
        (picture.camera().width(), picture.camera().height()),
        (24, 18)
    );
    assert_eq!(picture.samples(), 4);

    // The spheres of depth of field wear the fixtures' glossy red, green and blue.
    let fixture_scene = fixture("thin_lens_small_aperture.ron");
    let picture = picture_scene(
        &request(PictureScene::DepthOfField, thin_lens_camera(0.1), (24, 18)),
        1,
    );
    let red = materials_of(&fixture_scene, 1);
    let blue = materials_of(&fixture_scene, 3);
    assert_eq!(materials_of(&picture, 2), red);
    assert_eq!(materials_of(&picture, 4), blue);
}

/// The pixel at the centre of the image.
fn centre(image: &RgbaImage) -> Rgba<u8> {
    *image.get_pixel(image.width() / 2, image.height() / 2)
}

/// Which of red, green and blue dominates a pixel.
fn dominant(pixel: Rgba<u8>) -> usize {
    let [r, g, b, _] = pixel.0;
    [r, g, b]
        .iter()
        .enumerate()
        .max_by_key(|(_, c)| **c)
        .map(|(k, _)| k)
        .unwrap()
}

#[test]
fn multiview_pictures_show_the_face_perpendicular_to_the_view() {
    let pictures = RenderedPictures {
        samples: 1,
        ..RenderedPictures::default()
    };
    // Front looks along -z at the blue face, top down at the green one, side at the red.
    for (preset, axis) in [(Preset::Front, 2), (Preset::Top, 1), (Preset::Side, 0)] {
        let asked = request(PictureScene::AxisCube, taxonomy_camera(&preset), (80, 60));
        let image = pictures.picture(&asked).expect("a render");
        assert_eq!(image.dimensions(), (80, 60), "{}", preset.name());
        assert_eq!(dominant(centre(&image)), axis, "{}", preset.name());
        assert!(image.pixels().all(|p| p.0[3] == 255), "opaque");
    }
    // Looking along the ground, the earth fills the image below the horizon, not sky.
    let asked = request(
        PictureScene::AxisCube,
        taxonomy_camera(&Preset::Front),
        (80, 60),
    );
    let image = pictures.picture(&asked).expect("a render");
    let sky = *image.get_pixel(2, 2);
    let below = *image.get_pixel(2, 58);
    assert_eq!(dominant(sky), 2, "the sky is blue: {sky:?}");
    let [r, g, b, _] = below.0;
    assert!(
        r.abs_diff(g) < 12 && g.abs_diff(b) < 16 && r < sky.0[0],
        "the earth is grey and darker than the sky: {below:?}"
    );
}

#[test]
fn renders_are_deterministic_on_any_number_of_threads() {
    let asked = request(PictureScene::DepthOfField, thin_lens_camera(0.25), (64, 48));
    let pictures = |threads| RenderedPictures {
        samples: 4,
        lens_samples: 8,
        threads: Some(threads),
    };
    let one = pictures(1).picture(&asked).expect("a render");
    let two = pictures(2).picture(&asked).expect("a render");
    assert!(one == two, "a render depends on the thread count");
}

/// The mean absolute difference per channel between two images over the columns
/// `columns` (fractions of the width).
fn mean_difference(a: &RgbaImage, b: &RgbaImage, columns: (f64, f64)) -> f64 {
    let width = f64::from(a.width());
    let (from, to) = ((columns.0 * width) as u32, (columns.1 * width) as u32);
    let mut sum = 0u64;
    let mut count = 0u64;
    for y in 0..a.height() {
        for x in from..to {
            let (p, q) = (a.get_pixel(x, y), b.get_pixel(x, y));
            sum += (0..3)
                .map(|c| u64::from(p.0[c].abs_diff(q.0[c])))
                .sum::<u64>();
            count += 3;
        }
    }
    sum as f64 / count as f64
}

#[test]
fn a_wider_aperture_blurs_what_is_off_the_focus_plane() {
    let pictures = RenderedPictures {
        samples: 4,
        lens_samples: 16,
        threads: None,
    };
    let render = |camera| {
        let asked = request(PictureScene::DepthOfField, camera, (120, 90));
        pictures.picture(&asked).expect("a render")
    };
    // The pinhole camera of the same lens: everything sharp.
    let lens = thin_lens_camera(PICTURE_APERTURES[0]);
    let Projection::ThinLens(thin) = lens.projection() else {
        panic!("a thin-lens camera");
    };
    let pinhole = Camera::new(
        *lens.frame(),
        Projection::Perspective(thin.pinhole()),
        lens.width(),
        lens.height(),
    )
    .expect("a camera");
    let sharp = render(pinhole);
    let [small, large] = PICTURE_APERTURES.map(|aperture| render(thin_lens_camera(aperture)));
    // The near red sphere fills the left third: blurred more by the wider lens.

    let left = (0.0, 1.0 / 3.0);
    let (small_blur, large_blur) = (
        mean_difference(&small, &sharp, left),
        mean_difference(&large, &sharp, left),
    );
    assert!(
        large_blur > 3.0 * small_blur && large_blur > 5.0,
        "r = {}: {small_blur}, r = {}: {large_blur}",
        PICTURE_APERTURES[0],
        PICTURE_APERTURES[1]
    );
    // The green sphere sits on the focus plane: sharp at both apertures. CONE_PIXEL,
    // (100, 120) of the 240 x 180 camera, sees its centre: (50, 60) at half the size.
    for image in [&small, &large] {
        let green = *image.get_pixel(60, 50);
        assert_eq!(dominant(green), 1, "{green:?}");
        let around = |image: &RgbaImage| *image.get_pixel(60 + 6, 50);
        let (a, b) = (around(image).0, around(&sharp).0);
        assert!(
            (0..3).all(|c| a[c].abs_diff(b[c]) < 12),
            "in focus: {a:?} vs {b:?}"
        );
    }
}

#[test]
fn rendered_pictures_fill_their_slots_pixel_for_pixel() {
    let asked = std::cell::RefCell::new(Vec::new());
    let record = |request: &PictureRequest| {
        asked.borrow_mut().push(*request);
        None
    };
    for name in [
        "taxonomy",
        "distortion_foreshortening",
        "distortion_verticals",
        "thin_lens",
    ] {
        asked.borrow_mut().clear();
        let figure = figure_by_name(name).expect(name).draw(&record).figure;
        // No picture was given, so no images; each slot is framed by a closed polyline
        // round its rectangle, and the request's size is the rectangle's.
        let frames: Vec<(u32, u32)> = figure
            .items
            .iter()
            .filter_map(|item| match item {
                Item::Polyline {
                    points,
                    closed: true,
                    ..
                } if points.len() == 4 => {
                    let size = (points[2] - points[0]).round();
                    Some((size.x as u32, size.y as u32))
                }
                _ => None,
            })
            .collect();
        for request in asked.borrow().iter() {
            let (w, h) = request.size;
            let framed = frames.contains(&(w, h));
            assert!(framed, "{name}: no {w} x {h} slot");
            // Same aspect ratio as the camera's image, within a pixel.
            let (cw, ch) = (request.camera.width(), request.camera.height());
            let expected_h = f64::from(w) * f64::from(ch) / f64::from(cw);
            assert!(
                (expected_h - f64::from(h)).abs() <= 1.0,
                "{name}: {w} x {h}"
            );
        }
        assert!(!asked.borrow().is_empty(), "{name}");
    }
    // And a rendered picture is exactly the slot's size.
    let pictures = RenderedPictures {
        samples: 1,
        lens_samples: 1,
        threads: None,
    };
    let request = request(
        PictureScene::Towers,
        taxonomy_camera(&Preset::TwoPoint),
        (33, 25),
    );
    let image = pictures.picture(&request).expect("a render");
    assert_eq!(image.dimensions(), (33, 25));
}

#[test]
fn a_figure_as_users_see_it_has_its_pictures_rendered_at_the_slot_size() {
    let named = figure_by_name("distortion_verticals").expect("registered");
    let figure = named.figure();
    let images: Vec<(u32, u32, f32, f32)> = figure
        .items
        .iter()
        .filter_map(|item| match item {
            Item::Image { pixels, rect, .. } => {
                Some((pixels.width(), pixels.height(), rect.width(), rect.height()))
            }
            _ => None,
        })
        .collect();
    assert_eq!(
        images.len(),
        2,
        "the tilted and the shifted camera's pictures"
    );
    for (w, h, rect_w, rect_h) in images {
        assert_eq!((w as f32, h as f32), (rect_w.round(), rect_h.round()));
    }
    // The labels are the wireframe figure's: rendering moves nothing.
    let labels = |f: &viewray_draw::Figure| -> Vec<Item> {
        f.items
            .iter()
            .filter(|item| matches!(item, Item::Label(_)))
            .cloned()
            .collect()
    };
    assert_eq!(labels(&figure), labels(&named.wireframe()));
}
