//! Renders of tiny scenes, checked against what the geometry determines.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use glam::{DVec3, Vec3};
use viewray_render::{
    Image, RenderError, RenderSettings, Rendered, View, render, render_view,
    render_view_cancellable,
};
use viewray_scene::{LoadOptions, Scene};

/// A scene from RON text.
#[track_caller]
fn scene(text: &str) -> Scene {
    viewray_scene::SceneLoader::text(text, Path::new("test.ron"))
        .load()
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}

#[track_caller]
fn render_with(scene: &Scene, settings: RenderSettings) -> Rendered {
    render(scene, &settings, |_, _| {}).unwrap()
}

#[track_caller]
fn image(text: &str) -> Image {
    render_with(&scene(text), RenderSettings::default()).image
}

/// The pixel `(row, col)` that shows the world point `p`.
#[track_caller]
fn pixel_of(scene: &Scene, p: DVec3) -> (u32, u32) {
    let xy = scene.camera().project(p).expect("the point is visible");
    scene
        .camera()
        .pixel_at(xy)
        .expect("the point is inside the image")
}

#[track_caller]
fn assert_close(got: Vec3, expected: Vec3, tolerance: f32) {
    assert!(
        (got - expected).abs().max_element() <= tolerance,
        "got {got}, expected {expected}"
    );
}

/// The canonical camera looking down -z at a red sphere five units away.
fn sphere_ahead(width: u32, height: u32, samples: u32, shading: &str, extra: &str) -> String {
    format!(
        "(image: (width: {width}, height: {height}, samples: {samples}), shading: {shading},
          camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                   projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))),
          materials: {{ \"red\": (color: (0.8, 0.1, 0.1)) }},
          objects: [Sphere(center: (0.0, 0.0, -5.0), radius: 1.0, material: \"red\")],
          {extra})"
    )
}

#[test]
fn the_centre_of_a_sphere_straight_ahead_is_its_flat_colour() {
    let red = Vec3::new(0.8, 0.1, 0.1);
    for samples in [1, 5, 16] {
        let image = image(&sphere_ahead(33, 33, samples, "Flat", ""));
        assert_close(image.pixel(16, 16), red, 1e-6);
        assert_eq!(image.pixel(0, 0), Vec3::ZERO, "{samples} samples");
    }
}

#[test]
fn an_orthographic_sphere_covers_pi_r_squared() {
    // Viewport 4 x 4 over 200 x 200 pixels: each pixel is 0.02 x 0.02.
    let text = |samples: u32| {
        format!(
            "(image: (width: 200, height: 200, samples: {samples}), shading: Flat,
              camera: (eye: (0.3, -0.2, 10.0), view: (0.0, 0.0, -1.0),
                       projection: Orthographic(viewport: (4.0, 4.0))),
              materials: {{ \"white\": (color: (1.0, 1.0, 1.0)) }},
              objects: [Sphere(center: (0.0, 0.0, 0.0), radius: 1.3, material: \"white\")])"
        )
    };
    let expected = std::f32::consts::PI * 1.3 * 1.3 / (0.02 * 0.02);
    // One sample: a pixel is covered when its centre ray hits.
    let covered = image(&text(1))
        .pixels()
        .iter()
        .filter(|p| p.x == 1.0)
        .count() as f32;
    assert!(
        (covered - expected).abs() < 0.005 * expected,
        "{covered} pixels, expected {expected}"
    );
    // Sixteen samples: the coverage sums to the area.
    let coverage: f32 = image(&text(16)).pixels().iter().map(|p| p.x).sum();
    assert!(
        (coverage - expected).abs() < 0.002 * expected,
        "{coverage} pixels' worth, expected {expected}"
    );
}

/// A ground plane seen from straight above, with `objects` on it and a directional light
/// travelling along (1, -1, 0) plus an ambient 0.1.
fn top_view(objects: &str) -> Scene {
    scene(&format!(
        "(image: (width: 300, height: 300), shading: Lit,
          camera: (eye: (0.0, 20.0, 0.0), view: (0.0, -1.0, 0.0), up: (0.0, 0.0, -1.0),
                   projection: Orthographic(viewport: (6.0, 6.0))),
          materials: {{ \"grey\": (color: (0.5, 0.5, 0.5)) }},
          lights: [Directional(direction: (1.0, -1.0, 0.0), intensity: (1.0, 1.0, 1.0)),
                   Ambient(intensity: (0.1, 0.1, 0.1))],
          objects: [Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 1.0, 0.0), material: \"grey\"),
                    {objects}])"
    ))
}

#[test]
fn a_shadowed_point_is_darker_than_a_lit_one() {
    let scene = top_view("Sphere(center: (0.0, 1.5, 0.0), radius: 0.5, material: \"grey\")");
    let image = render_with(&scene, RenderSettings::default()).image;
    // The sphere's shadow falls 1.5 units along +x: only the ambient light reaches it.
    let (row, col) = pixel_of(&scene, DVec3::new(1.5, 0.0, 0.0));
    let shadowed = image.pixel(row, col);
    assert_close(shadowed, Vec3::splat(0.05), 1e-6);
    // Elsewhere the ground sees the light at 45 degrees.
    let (row, col) = pixel_of(&scene, DVec3::new(-2.0, 0.0, 1.0));
    let lit = image.pixel(row, col);
    assert_close(
        lit,
        Vec3::splat(0.05 + 0.5 * std::f32::consts::FRAC_1_SQRT_2),
        1e-6,
    );
}

/// A Lit scene of `objects` seen from straight above (v = +y) through an orthographic
/// camera of 0.02 units per pixel, centred on the origin, under the lights
/// [`blinn_phong_sum`] adds: a point light, a directional light and an ambient one.
fn under_three_lights(width: u32, height: u32, materials: &str, objects: &str) -> Scene {
    let viewport = |pixels: u32| f64::from(pixels) / 50.0;
    scene(&format!(
        "(image: (width: {width}, height: {height}), shading: Lit,
          camera: (eye: (0.0, 20.0, 0.0), view: (0.0, -1.0, 0.0), up: (0.0, 0.0, -1.0),
                   projection: Orthographic(viewport: ({:?}, {:?}))),
          materials: {{ {materials} }},
          lights: [Point(position: (1.0, 3.0, -0.5), intensity: (9.0, 8.0, 7.0)),
                   Directional(direction: (1.0, -1.0, 0.0), intensity: (0.5, 0.6, 0.7)),
                   Ambient(intensity: (0.1, 0.1, 0.1))],
          objects: [{objects}])",
        viewport(width),
        viewport(height),
    ))
}

/// Lit shading's sum over the lights, written out for a point with normal `n` seen from
/// `v` (unit vectors), with colour `color`, specular colour `specular` and exponent
/// `shininess`: ambient `color I`, a point light `(I / r^2) (color n.l + specular
/// (n.h)^shininess)`, a directional light the same without the falloff.
fn blinn_phong_sum(p: DVec3, n: DVec3, v: DVec3, color: DVec3, specular: DVec3) -> DVec3 {
    let shininess = 20.0;
    let term = |l: DVec3| {
        let h = (l + v).normalize();
        color * n.dot(l).max(0.0) + specular * n.dot(h).max(0.0).powf(shininess)
    };
    let to_point = DVec3::new(1.0, 3.0, -0.5) - p;
    let point = DVec3::new(9.0, 8.0, 7.0) / to_point.length_squared() * term(to_point.normalize());
    let directional = DVec3::new(0.5, 0.6, 0.7) * term(-DVec3::new(1.0, -1.0, 0.0).normalize());
    let ambient = color * DVec3::splat(0.1);
    point + directional + ambient
}

#[test]
fn lit_pixels_are_the_sum_of_their_lights() {
    // Seen from straight above (v = +y): a glossy ground and, on it, the top of a matte
    // sphere (normal +y there too), under a point light, a directional light and an
    // ambient one. 300 x 300 pixels over 6 x 6 units: pixel (row, col) shows the
    // centre x = 0.02 (col + 1/2) - 3, z = 0.02 (row + 1/2) - 3.
    let scene = under_three_lights(
        300,
        300,
        "\"glossy\": (color: (0.5, 0.4, 0.3), specular: (0.3, 0.3, 0.3), shininess: 20.0),
         \"matte\": (color: (0.2, 0.6, 0.3))",
        "Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 1.0, 0.0), material: \"glossy\"),
         Sphere(center: (2.01, 0.5, 2.01), radius: 0.5, material: \"matte\")",
    );
    let image = render_with(&scene, RenderSettings::default()).image;
    let up = DVec3::Y;
    let centre = |row: u32, col: u32, y: f64| {
        DVec3::new(
            0.02 * (f64::from(col) + 0.5) - 3.0,
            y,
            0.02 * (f64::from(row) + 0.5) - 3.0,
        )
    };
    // The ground, at pixels near the point light (a strong highlight), far from it, and
    // in between.
    for (row, col) in [
        (125, 200),
        (126, 201),
        (10, 20),
        (290, 30),
        (150, 150),
        (77, 233),
    ] {
        let p = centre(row, col, 0.0);
        assert_eq!(pixel_of(&scene, p), (row, col));
        let expected = blinn_phong_sum(p, up, up, DVec3::new(0.5, 0.4, 0.3), DVec3::splat(0.3));
        assert_close(image.pixel(row, col), expected.as_vec3(), 2e-3);
    }
    // The top of the matte sphere, (2.01, 1, 2.01): no specular term.
    let p = centre(250, 250, 1.0);
    assert_eq!(pixel_of(&scene, p), (250, 250));
    let expected = blinn_phong_sum(p, up, up, DVec3::new(0.2, 0.6, 0.3), DVec3::ZERO);
    assert_close(image.pixel(250, 250), expected.as_vec3(), 2e-3);
}

#[test]
fn lit_renders_count_one_shadow_ray_per_light_above_each_hit() {
    // A ground seen from above and two lights above it: every pixel's ray hits, and
    // each hit sends one shadow ray to each of the two lights (the ambient one needs
    // none). 301 x 299 pixels, so that blocks hold numbers of rays that are not
    // multiples of four.
    let scene = under_three_lights(
        301,
        299,
        "\"grey\": (color: (0.5, 0.5, 0.5))",
        "Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 1.0, 0.0), material: \"grey\")",
    );
    let rendered = render_with(&scene, RenderSettings::default());
    assert_eq!(rendered.stats.rays, 301 * 299 * 3);
}

#[test]
fn shadows_have_no_acne_and_touch_the_objects_that_cast_them() {
    let scene = top_view("Box(min: (-1.0, 0.0, -1.0), max: (1.0, 1.0, 1.0), material: \"grey\")");
    let image = render_with(&scene, RenderSettings::default()).image;
    let ambient = Vec3::splat(0.05);
    let lit = Vec3::splat(0.05 + 0.5 * std::f32::consts::FRAC_1_SQRT_2);
    // The box's shadow runs from x = 1 to x = 2; elsewhere the ground is lit.
    let (shadow_row, _) = pixel_of(&scene, DVec3::new(0.0, 0.0, 0.0));
    for x in [1.015, 1.5, 1.985] {
        let (row, col) = pixel_of(&scene, DVec3::new(x, 0.0, 0.0));
        assert_eq!(row, shadow_row);
        assert_close(image.pixel(row, col), ambient, 1e-6);
    }
    // Every ground pixel outside the box and its shadow is exactly lit: no acne.
    let mut checked = 0;
    for row in 0..300 {
        for col in 0..300 {
            let x = (f64::from(col) + 0.5) / 50.0 - 3.0;
            let z = (f64::from(row) + 0.5) / 50.0 - 3.0;
            let in_box_or_shadow = (-1.02..2.02).contains(&x) && (-1.02..1.02).contains(&z);
            if !in_box_or_shadow {
                assert_close(image.pixel(row, col), lit, 1e-6);
                checked += 1;
            }
        }
    }
    assert!(checked > 70_000);
}

#[test]
fn curved_surfaces_far_from_the_camera_have_no_acne() {
    // Light from behind a distant camera: every visible point of the sphere is lit, so
    // no pixel may show the ambient light alone.
    let scene = scene(
        "(image: (width: 120, height: 120), shading: Lit,
          camera: (eye: (30.0, 40.0, 100.0), look_at: (3.0, 4.0, 5.0),
                   projection: Orthographic(viewport: (2.5, 2.5))),
          materials: { \"white\": (color: (1.0, 1.0, 1.0)) },
          lights: [Directional(direction: (-27.0, -36.0, -95.0), intensity: (1.0, 1.0, 1.0)),
                   Ambient(intensity: (0.1, 0.1, 0.1))],
          objects: [Sphere(center: (3.0, 4.0, 5.0), radius: 1.0, material: \"white\")])",
    );
    let image = render_with(&scene, RenderSettings::default()).image;
    let sphere_pixels: Vec<f32> = image
        .pixels()
        .iter()
        .map(|p| p.x)
        .filter(|&x| x > 0.0)
        .collect();
    // pi r^2 / pixel area = 7238 pixels.
    assert!(sphere_pixels.len() > 7000, "{}", sphere_pixels.len());
    let unlit = sphere_pixels.iter().filter(|&&x| x <= 0.1).count();
    assert_eq!(unlit, 0, "{unlit} pixels in shadow of their own surface");
}

/// Outside a fisheye's image circle there is no viewing ray: those pixels are the
/// background, exactly, with one sample (the block of centre rays) and with several.
#[test]
fn pixels_outside_the_fisheye_circle_are_the_background() {
    for samples in [1, 4] {
        let image = image(&format!(
            "(image: (width: 24, height: 16, samples: {samples}), shading: Flat,
              background: (0.25, 0.5, 0.75),
              camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                       projection: Fisheye(fov: 180.0)),
              objects: [Sphere(center: (0.0, 0.0, -5.0), radius: 1.0)])"
        ));
        for (row, col) in [(0, 0), (0, 23), (15, 0), (15, 23), (0, 3), (8, 0)] {
            assert_eq!(
                image.pixel(row, col),
                Vec3::new(0.25, 0.5, 0.75),
                "{samples} samples, ({row}, {col})"
            );
        }
    }
}

/// One sample per pixel is the pixel centre, so a silhouette is hard; more samples
/// are jittered over the pixel, so pixels on the silhouette mix the sphere's colour with
/// the background.
#[test]
fn more_samples_soften_a_silhouette_and_one_does_not() {
    let mixed = |samples: u32| {
        let image = image(&sphere_ahead(33, 33, samples, "Flat", ""));
        image
            .pixels()
            .iter()
            .filter(|p| p.x > 0.0 && p.x < 0.8)
            .count()
    };
    assert_eq!(mixed(1), 0);
    assert!(mixed(4) > 10, "{} mixed pixels", mixed(4));
}

#[test]
fn depth_falls_off_along_a_ground_plane() {
    let scene = scene(
        "(image: (width: 40, height: 60), shading: Depth,
          camera: (eye: (0.0, 1.5, 0.0), view: (0.0, -0.3, -1.0),
                   projection: Perspective(distance: 1.0, viewport: (1.0, 1.5))),
          objects: [Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 1.0, 0.0))])",
    );
    let rendered = render_with(&scene, RenderSettings::default());
    // One pre-pass ray and one sample per pixel.
    assert_eq!(rendered.stats.rays, 2 * 40 * 60);
    let image = rendered.image;
    let column: Vec<f32> = (0..60).rev().map(|row| image.pixel(row, 20).x).collect();
    // The bottom row is the nearest: white.
    assert!(column[0] > 0.9999, "{}", column[0]);
    // Going up the image the ground recedes, and gets darker, until the sky (black).
    let ground = column.iter().take_while(|&&v| v > 0.0).count();
    assert!((20..60).contains(&ground), "{ground} ground rows");
    for pair in column[..ground].windows(2) {
        assert!(pair[1] < pair[0], "not decreasing: {column:?}");
    }
    assert!(column[ground..].iter().all(|&v| v == 0.0));
    // A depth image is data: stored in 8 bits as is.
    assert_eq!(image.to_rgb8()[(59 * 40 + 20) * 3..][..3], [255, 255, 255]);
}

#[test]
fn depth_puts_nearer_objects_brighter() {
    let image = image(
        "(image: (width: 64, height: 32), shading: Depth, background: (0.5, 0.5, 0.5),
          camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                   projection: Perspective(distance: 1.0, viewport: (2.0, 1.0))),
          objects: [Sphere(center: (-2.0, 0.0, -5.0), radius: 1.0),
                    Box(min: (1.0, -1.0, -12.0), max: (3.0, 1.0, -10.0))])",
    );
    let (near, far) = (image.pixel(16, 19), image.pixel(16, 38));
    assert!(near.x > far.x, "near {near}, far {far}");
    assert!(far.x >= 0.1 && far.x < 0.5, "far {far}");
    // The nearest point seen is white.
    let brightest = image.pixels().iter().map(|p| p.x).fold(0.0, f32::max);
    assert_eq!(brightest, 1.0);
    // The background keeps its look: stored sRGB-encoded, as a colour image would.
    assert_eq!(image.to_rgb8()[..3], [188, 188, 188]);
}

/// A camera at the origin looking at a mirror plane at z = -5, with a red sphere behind
/// the camera; ambient light only, so every surface shows exactly its colour.
fn mirror(mirror: f64) -> String {
    format!(
        "(image: (width: 21, height: 21), shading: Lit,
          camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                   projection: Perspective(distance: 1.0, viewport: (0.2, 0.2))),
          materials: {{ \"red\": (color: (0.8, 0.1, 0.1)),
                       \"glass\": (color: (0.1, 0.2, 0.9), mirror: {mirror}) }},
          lights: [Ambient(intensity: (1.0, 1.0, 1.0))],
          objects: [Plane(point: (0.0, 0.0, -5.0), normal: (0.0, 0.0, 1.0), material: \"glass\"),
                    Sphere(center: (0.0, 0.0, 5.0), radius: 2.0, material: \"red\")])"
    )
}

#[test]
fn a_mirror_shows_the_colour_of_what_it_reflects() {
    let red = Vec3::new(0.8, 0.1, 0.1);
    let blue = Vec3::new(0.1, 0.2, 0.9);
    assert_close(image(&mirror(1.0)).pixel(10, 10), red, 1e-6);
    assert_close(image(&mirror(0.0)).pixel(10, 10), blue, 1e-6);
    assert_close(
        image(&mirror(0.25)).pixel(10, 10),
        0.75 * blue + 0.25 * red,
        1e-6,
    );
}

#[test]
fn facing_mirrors_stop_after_the_bounce_limit() {
    let scene = scene(
        "(image: (width: 8, height: 8), shading: Lit,
          camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                   projection: Perspective(distance: 1.0, viewport: (0.1, 0.1))),
          materials: { \"mirror\": (color: (1.0, 1.0, 1.0), mirror: 0.5) },
          lights: [Ambient(intensity: (1.0, 1.0, 1.0))],
          objects: [Plane(point: (0.0, 0.0, -1.0), normal: (0.0, 0.0, 1.0), material: \"mirror\"),
                    Plane(point: (0.0, 0.0, 1.0), normal: (0.0, 0.0, -1.0), material: \"mirror\")])",
    );
    for (depth, value) in [(0, 0.5), (1, 0.75), (4, 0.96875)] {
        let settings = RenderSettings {
            max_reflection_depth: depth,
            ..RenderSettings::default()
        };
        let rendered = render_with(&scene, settings);
        // One primary ray and `depth` reflected rays per pixel; no lights to shadow-test.
        assert_eq!(rendered.stats.rays, 64 * (1 + u64::from(depth)));
        // Each bounce adds half of what is left: 1/2 + 1/4 + ... (black beyond the limit).
        assert_close(rendered.image.pixel(4, 4), Vec3::splat(value), 1e-6);
    }
}

#[test]
fn a_scene_without_lights_gets_a_headlight() {
    let image = image(&sphere_ahead(33, 33, 1, "Lit", ""));
    // Facing the eye, the headlight shows the full colour; the rim fades to 15%.
    assert_close(image.pixel(16, 16), Vec3::new(0.8, 0.1, 0.1), 1e-4);
    let rim = image.pixel(16, 10);
    assert!(rim.x < 0.7 && rim.x > 0.15 * 0.8, "{rim}");
}

#[test]
fn normals_face_the_viewer_and_are_stored_as_data() {
    let image = image(&sphere_ahead(33, 33, 1, "Normals", ""));
    assert_close(image.pixel(16, 16), Vec3::new(0.5, 0.5, 1.0), 1e-6);
    assert_eq!(image.to_rgb8()[(16 * 33 + 16) * 3..][..3], [128, 128, 255]);
    // Left of centre the normal turns toward -x.
    assert!(image.pixel(16, 14).x < 0.5);
}

#[test]
fn flat_grey_half_is_stored_as_srgb_188() {
    let image = image(
        "(image: (width: 4, height: 4), shading: Flat, background: (0.5, 0.5, 0.5),
          camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0),
                   projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))))",
    );
    let mut png = Vec::new();
    image.write_png(&mut png).unwrap();
    let decoded = ::image::load_from_memory(&png).unwrap().to_rgb8();
    assert!(decoded.pixels().all(|p| p.0 == [188, 188, 188]));
}

/// A ground grid seen from above: lines every unit, 0.1 wide.
const GRID: &str = "
    materials: { \"ground\": (color: (1.0, 1.0, 1.0),
                              grid: (spacing: 1.0, width: 0.1, color: (0.0, 0.0, 0.0))) },
    objects: [Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 1.0, 0.0), material: \"ground\")]";

#[test]
fn grid_lines_follow_world_coordinates() {
    let scene = scene(&format!(
        "(image: (width: 400, height: 400, samples: 4), shading: Flat,
          camera: (eye: (0.0, 10.0, 0.0), view: (0.0, -1.0, 0.0), up: (0.0, 0.0, -1.0),
                   projection: Orthographic(viewport: (4.0, 4.0))), {GRID})"
    ));
    let image = render_with(&scene, RenderSettings::default()).image;
    let at = |x: f64, z: f64| {
        let (row, col) = pixel_of(&scene, DVec3::new(x, 0.0, z));
        image.pixel(row, col).x
    };
    // On the lines x = 1 and z = -1, and their crossing: the line colour.
    assert_eq!(at(1.0, 0.5), 0.0);
    assert_eq!(at(-0.5, -1.0), 0.0);
    assert_eq!(at(1.0, -1.0), 0.0);
    // Between the lines: the material's colour.
    assert_eq!(at(0.5, 0.5), 1.0);
    assert_eq!(at(-1.5, 1.3), 1.0);
    // Overall, lines 0.1 wide every unit cover 1 - 0.9^2 of the ground.
    let mean = image.pixels().iter().map(|p| f64::from(p.x)).sum::<f64>() / 160_000.0;
    assert!((mean - 0.81).abs() < 0.01, "{mean}");
}

#[test]
fn grids_fade_to_their_average_toward_the_horizon() {
    let scene = scene(&format!(
        "(image: (width: 200, height: 100, samples: 1), shading: Flat,
          background: (1.0, 0.0, 0.0),
          camera: (eye: (0.0, 1.0, 0.0), view: (0.0, 0.0, -1.0),
                   projection: Perspective(distance: 1.0, viewport: (2.0, 1.0))), {GRID})"
    ));
    let image = render_with(&scene, RenderSettings::default()).image;
    // The row just below the horizon spans hundreds of lines per pixel in depth and a
    // few across: no moire, close to the average 0.81 all along the row (point samples
    // would give 0, 0.9 or 1).
    for col in 0..200 {
        let v = image.pixel(50, col);
        assert!((v.x - 0.81).abs() < 0.03, "col {col}: {v}");
    }
    // Above the horizon: the sky.
    assert_eq!(image.pixel(49, 100), Vec3::X);
}

#[test]
fn every_projection_family_renders() {
    // (projection, eye, panoramic); the oblique camera's eye is moved so that its
    // slanted centre ray meets the sphere.
    let projections = [
        (
            "Perspective(distance: 1.0, viewport: (2.0, 1.5))",
            "0.0, 0.0",
            false,
        ),
        (
            "ThinLens(distance: 1.0, viewport: (2.0, 1.5), aperture: 0.2, focus: 5.0)",
            "0.0, 0.0",
            false,
        ),
        ("Orthographic(viewport: (8.0, 6.0))", "0.0, 0.0", false),
        (
            "Orthographic(viewport: (8.0, 6.0), aperture: 0.2, focus: 5.0)",
            "0.0, 0.0",
            false,
        ),
        (
            "Oblique(viewport: (8.0, 6.0), ratio: 0.5, angle: 45.0)",
            "1.7678, 1.7678",
            false,
        ),
        ("Equirectangular", "0.0, 0.0", true),
        ("Fisheye(fov: 180.0)", "0.0, 0.0", true),
    ];
    for (projection, eye, panoramic) in projections {
        let text = format!(
            "(image: (width: 40, height: 30, samples: 4), shading: Flat,
              background: (0.0, 0.0, 1.0),
              camera: (eye: ({eye}, 10.0), view: (0.0, 0.0, -1.0),
                       projection: {projection}),
              materials: {{ \"red\": (color: (1.0, 0.0, 0.0)) }},
              objects: [Sphere(center: (0.0, 0.0, 5.0), radius: 1.0, material: \"red\")])"
        );
        let image = image(&text);
        let centre = image.pixel(15, 20);
        assert_close(centre, Vec3::X, 1e-6);
        if projection.starts_with("Fisheye") {
            // A corner lies outside the image circle, where no ray exists: the
            // background, exactly.
            assert_eq!(image.pixel(0, 0), Vec3::Z);
            assert_eq!(image.pixel(29, 39), Vec3::Z);
        }
        let background = image.pixels().iter().filter(|p| **p == Vec3::Z).count();
        assert!(
            background > 100,
            "{projection}: {background} background pixels"
        );
        if panoramic {
            // The panoramic cameras see the sphere small, in the middle.
            assert!(background > 1000, "{projection}");
        }
    }
}

#[test]
fn the_image_is_the_same_on_any_number_of_threads_and_tiles() {
    let scene = scene(&format!(
        "(image: (width: 67, height: 45, samples: 6), shading: Lit,
          camera: (eye: (3.0, 2.0, 4.0), look_at: (0.0, 0.3, 0.0),
                   projection: ThinLens(distance: 1.0, viewport: (1.2, 0.8), aperture: 0.1,
                                        focus: 4.0)),
          lights: [Point(position: (2.0, 4.0, 3.0), intensity: (10.0, 10.0, 10.0)),
                   Ambient(intensity: (0.1, 0.1, 0.1))],
          {GRID}
          )"
    ));
    let png = |settings: RenderSettings| {
        let mut bytes = Vec::new();
        render_with(&scene, settings)
            .image
            .write_png(&mut bytes)
            .unwrap();
        bytes
    };
    let one = png(RenderSettings {
        threads: Some(1),
        ..RenderSettings::default()
    });
    let two = png(RenderSettings {
        threads: Some(2),
        ..RenderSettings::default()
    });
    let small_tiles = png(RenderSettings {
        threads: Some(2),
        tile_size: 5,
        ..RenderSettings::default()
    });
    assert!(one == two, "1 and 2 threads differ");
    assert!(one == small_tiles, "tile sizes differ");
}

/// Through a fisheye the neighbouring rays of each pixel differ from pixel to pixel, so
/// a grid's filter width depends on where the pixel lies: one sample per pixel (blocks
/// of shared samples), square tiles of 16 and 5 and tiles of one pixel give the same
/// image, pixel for pixel within the tiles too.
#[test]
fn a_fisheye_grid_is_the_same_for_any_tile_size() {
    let scene = scene(&format!(
        "(image: (width: 67, height: 45, samples: 1), shading: Flat,
          camera: (eye: (0.0, 1.5, 0.0), look_at: (2.0, 0.0, -3.0),
                   projection: Fisheye(fov: 180.0)),
          {GRID}
          )"
    ));
    let image = |tile_size: u32| {
        render_with(
            &scene,
            RenderSettings {
                threads: Some(1),
                tile_size,
                ..RenderSettings::default()
            },
        )
        .image
    };
    let (one, five, sixteen) = (image(1), image(5), image(16));
    let grey = (0..45)
        .flat_map(|row| (0..67).map(move |col| (row, col)))
        .filter(|&(row, col)| {
            let p = one.pixel(row, col);
            p.x > 0.05 && p.x < 0.95
        })
        .count();
    assert!(
        grey > 100,
        "{grey} filtered pixels: the grid is not filtered"
    );
    for (row, col) in (0..45).flat_map(|row| (0..67).map(move |col| (row, col))) {
        assert_eq!(
            one.pixel(row, col),
            five.pixel(row, col),
            "({row}, {col}), tiles of 5"
        );
        assert_eq!(
            one.pixel(row, col),
            sixteen.pixel(row, col),
            "({row}, {col}), tiles of 16"
        );
    }
}

#[test]
fn progress_reaches_the_total_and_rays_are_counted() {
    let scene = scene(&sphere_ahead(40, 20, 3, "Flat", ""));
    let calls = AtomicUsize::new(0);
    let finished = AtomicUsize::new(0);
    let rendered = render(&scene, &RenderSettings::default(), |done, total| {
        assert_eq!(total, 800);
        calls.fetch_add(1, Ordering::Relaxed);
        finished.fetch_max(done as usize, Ordering::Relaxed);
    })
    .unwrap();
    // 16 x 16 tiles: 3 columns by 2 rows.
    assert_eq!(calls.into_inner(), 6);
    assert_eq!(finished.into_inner(), 800);
    assert_eq!(rendered.stats.rays, 800 * 3);
}

#[test]
fn a_cancelled_render_stops_at_the_next_tile_and_an_uncancelled_one_is_the_same() {
    let scene = scene(&sphere_ahead(40, 20, 3, "Flat", ""));
    let view = View::of(&scene);
    // One thread: the flag set after the first of the 6 tiles stops the render there.
    let settings = RenderSettings {
        threads: Some(1),
        ..RenderSettings::default()
    };
    let cancelled = AtomicBool::new(false);
    let tiles = AtomicUsize::new(0);
    let result = render_view_cancellable(
        &scene,
        &view,
        &settings,
        |_, _| {
            tiles.fetch_add(1, Ordering::Relaxed);
            cancelled.store(true, Ordering::Relaxed);
        },
        &cancelled,
    );
    assert!(matches!(result, Err(RenderError::Cancelled)), "{result:?}");
    assert_eq!(tiles.into_inner(), 1);
    // A flag never set changes nothing.
    let never = AtomicBool::new(false);
    assert_eq!(
        render_view_cancellable(&scene, &view, &settings, |_, _| {}, &never).unwrap(),
        render_with(&scene, RenderSettings::default())
    );
}

/// The scene files of the repository: `fixtures/scenes/*.ron` and the default scene.
fn fixture_scenes() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(root.join("scenes"))
        .map(|entries| {
            entries
                .map(|entry| entry.unwrap().path())
                .filter(|path| path.extension().is_some_and(|e| e == "ron"))
                .collect()
        })
        .unwrap_or_default();
    paths.sort();
    paths.push(root.join("default.ron"));
    paths
}

#[test]
fn every_fixture_scene_renders() {
    let options = LoadOptions {
        size: Some((48, 36)),
        samples: Some(2),
    };
    for path in fixture_scenes() {
        let scene = viewray_scene::SceneLoader::file(&path)
            .options(options)
            .load()
            .unwrap_or_else(|e| panic!("{e}"))
            .scene;
        let image = render_with(&scene, RenderSettings::default()).image;
        assert_eq!((image.width(), image.height()), (48, 36));
        let name = path.display();
        assert!(
            image.pixels().iter().all(|p| p.is_finite()),
            "{name}: not finite"
        );
        let first = image.pixels()[0];
        assert!(
            image.pixels().iter().any(|&p| p != first),
            "{name}: an image of one colour"
        );
    }
}

#[test]
fn a_view_renders_the_loaded_scene_as_a_scene_loaded_with_its_camera() {
    // One scene loaded once, rendered through the cameras, sizes, samples and shadings of
    // other scene files: each image is the one those files render.
    let scene_with = |camera: &str, size: (u32, u32), samples: u32, shading: &str| {
        format!(
            "(image: (width: {}, height: {}, samples: {samples}), shading: {shading},
              camera: {camera},
              background: (0.2, 0.3, 0.4),
              lights: [Point(position: (2.0, 4.0, 3.0), intensity: (10.0, 10.0, 10.0)),
                       Ambient(intensity: (0.1, 0.1, 0.1))],
              {GRID})",
            size.0, size.1
        )
    };
    let loaded = scene(&scene_with(
        "(eye: (0.0, 1.0, 5.0), look_at: (0.0, 0.0, 0.0), projection: Perspective(fov_y: 40.0))",
        (40, 30),
        1,
        "Lit",
    ));
    for (camera, size, samples, shading) in [
        (
            "(eye: (3.0, 2.0, 4.0), look_at: (0.0, 0.3, 0.0),
              projection: ThinLens(distance: 1.0, fov_y: 50.0, aperture: 0.1, focus: 4.0))",
            (37, 21),
            4,
            "Lit",
        ),
        (
            "Isometric(target: (0.0, 0.5, 0.0), size: 4.0)",
            (30, 30),
            1,
            "Depth",
        ),
        (
            "(eye: (0.0, 2.0, 3.0), view: (0.0, -0.5, -1.0),
              projection: Oblique(height: 3.0, ratio: 0.5, angle: 30.0))",
            (25, 40),
            2,
            "Normals",
        ),
        (
            "(eye: (0.0, 0.5, 0.0), view: (0.0, 0.0, -1.0), projection: Fisheye(fov: 180.0))",
            (20, 20),
            1,
            "Flat",
        ),
    ] {
        let expected = render_with(
            &scene(&scene_with(camera, size, samples, shading)),
            RenderSettings::default(),
        );
        let reference = scene(&scene_with(camera, size, samples, shading));
        let view = View {
            camera: *reference.camera(),
            samples,
            shading: reference.shading(),
        };
        let got = render_view(&loaded, &view, &RenderSettings::default(), |_, _| {}).unwrap();
        assert_eq!(got, expected, "{camera}");
    }
    // The scene's own view is what `render` uses.
    assert_eq!(
        render_view(
            &loaded,
            &View::of(&loaded),
            &RenderSettings::default(),
            |_, _| {}
        )
        .unwrap(),
        render_with(&loaded, RenderSettings::default())
    );
}
