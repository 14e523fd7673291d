//! The demos show what the lecture says, measured on their frames; frames are exactly
//! the keys' cameras at their times, and depend on nothing but the scene and the frame.

use std::path::Path;

use glam::{DVec2, DVec3};
use image::RgbImage;
use viewray_camera::{Camera, Frame, Perspective, Projection};
use viewray_compare::{InstructorThresholds, judge};
use viewray_render::{RenderSettings, render};
use viewray_scene::{LoadOptions, Scene};

use crate::demos::blocks_orthographic;
use crate::{Movie, MovieError, MovieSettings, demo_by_name};

fn demo_movie(name: &str, frames: u32, samples: u32) -> Movie {
    let demo = demo_by_name(name).unwrap();
    let options = LoadOptions {
        size: None,
        samples: Some(samples),
    };
    let settings = MovieSettings {
        frames: Some(frames),
        ..MovieSettings::default()
    };
    Movie::from_demo(&demo, options, settings).unwrap()
}

/// The rows and columns (first, last) of the pixels that are clearly red: the dolly
/// zoom's card, lit or in shade.
fn red_extent(frame: &RgbImage) -> ((u32, u32), (u32, u32)) {
    let (mut rows, mut cols) = ((u32::MAX, 0), (u32::MAX, 0));
    for (x, y, p) in frame.enumerate_pixels() {
        let [r, g, b] = p.0.map(u32::from);
        if r > 60 && 2 * r > 3 * g && 2 * r > 3 * b {
            rows = (rows.0.min(y), rows.1.max(y));
            cols = (cols.0.min(x), cols.1.max(x));
        }
    }
    (rows, cols)
}

#[test]
fn the_dolly_zoom_keeps_the_card_within_a_pixel_of_its_size() {
    let movie = demo_movie("dolly-zoom", 9, 1);
    let (_, height) = movie.picture_size();
    let mut heights = Vec::new();
    let mut widths = Vec::new();
    for k in 0..movie.frames() {
        let frame = movie.render_frame(k, &RenderSettings::default()).unwrap();
        let (rows, cols) = red_extent(&frame);
        heights.push(rows.1 - rows.0 + 1);
        widths.push(cols.1 - cols.0 + 1);
    }
    let spread = |sizes: &[u32]| sizes.iter().max().unwrap() - sizes.iter().min().unwrap();
    assert!(spread(&heights) <= 1, "card heights {heights:?}");
    assert!(spread(&widths) <= 1, "card widths {widths:?}");
    // The card is 2 units tall at depth D and d = 0.275 D: 2 d / D = 0.55 of vh.
    let expected = 0.55 * f64::from(height);
    for h in &heights {
        assert!(
            (f64::from(*h) - expected).abs() <= 1.5,
            "{h} px, expected {expected}"
        );
    }
    // Meanwhile the field of view changes: the first and last frames' cameras differ.
    let d = |k: u32| match movie.shots(k)[0].camera.projection() {
        Projection::Perspective(p) => p.distance,
        _ => unreachable!("the dolly zoom is perspective"),
    };
    assert!(d(8) > 4.0 * d(0));
}

/// `camera`'s render of `scene`, as RGBA for the comparison.
fn picture(scene: &Scene, camera: Camera) -> image::RgbaImage {
    let scene = scene.clone().with_camera(camera);
    let rendered = render(&scene, &RenderSettings::default(), |_, _| {}).unwrap();
    image::DynamicImage::ImageRgb8(rendered.image.to_rgb_image()).to_rgba8()
}

#[test]
fn the_path_to_orthographic_ends_in_the_orthographic_picture() {
    let movie = demo_movie("perspective-to-orthographic", 5, 4);
    let (width, height) = movie.picture_size();
    let orthographic = picture(movie.scene(), blocks_orthographic(width, height));
    let thresholds = InstructorThresholds::default();
    let last = picture(movie.scene(), movie.shots(4)[0].camera);
    let verdict = judge(&orthographic, &last, &thresholds);
    assert!(verdict.passed(), "{}", verdict.reasons());
    // The first frame, from up close, is far from it: the comparison can tell.
    let first = picture(movie.scene(), movie.shots(0)[0].camera);
    assert!(!judge(&orthographic, &first, &thresholds).passed());
}

const KEYED: &str = "(
    image: (width: 64, height: 36),
    camera: (eye: (0.0, 1.0, 4.0), view: (0.0, 0.0, -1.0), projection: Perspective(fov_y: 40.0)),
    objects: [Sphere(center: (0.0, 1.0, -2.0), radius: 1.0)],
    animation: (frames: 5, keys: [
        (t: 0.0, camera: (eye: (0.0, 1.0, 4.0), view: (0.0, 0.0, -1.0), projection: Perspective(fov_y: 40.0))),
        (t: 1.0, camera: (eye: (0.0, 1.0, 8.0), view: (0.0, 0.0, -1.0), projection: Perspective(fov_y: 60.0))),
    ]),
)";

#[test]
fn linear_frame_k_of_n_is_the_camera_at_k_over_n_minus_1() {
    let (scene, animation) = viewray_scene::SceneLoader::text(KEYED, Path::new("keyed.ron"))
        .load()
        .map(|loaded| (loaded.scene, loaded.animation))
        .unwrap();
    let movie =
        Movie::from_animation(scene, &animation.unwrap(), MovieSettings::default()).unwrap();
    assert_eq!(movie.frames(), 5);
    for k in 0..5u32 {
        // t = k / 4: the eye at 4 + k, the field of view 40 + 5 k degrees.
        let k64 = f64::from(k);
        let frame =
            Frame::from_eye_view_up(DVec3::new(0.0, 1.0, 4.0 + k64), DVec3::NEG_Z, DVec3::Y)
                .unwrap();
        let perspective =
            Perspective::from_fov_y((40.0 + 5.0 * k64).to_radians(), 64.0 / 36.0).unwrap();
        let expected = Camera::new(frame, Projection::Perspective(perspective), 64, 36).unwrap();
        assert_eq!(movie.shots(k)[0].camera, expected, "frame {k}");
    }
    assert_eq!(
        *movie.shots(4)[0].camera.projection(),
        Projection::Perspective(Perspective {
            distance: 1.0,
            viewport: DVec2::new(
                64.0 / 36.0 * 2.0 * 30f64.to_radians().tan(),
                2.0 * 30f64.to_radians().tan()
            ),
            shift: DVec2::ZERO,
        })
    );
}

#[test]
fn a_frame_depends_only_on_the_scene_and_its_number() {
    let demo = demo_by_name("tilt-vs-shift").unwrap();
    let options = LoadOptions {
        size: Some((48, 54)),
        samples: Some(2),
    };
    let movie = |frames| {
        let settings = MovieSettings {
            frames: Some(frames),
            with_diagram: true,
            ..MovieSettings::default()
        };
        Movie::from_demo(&demo, options, settings).unwrap()
    };
    let (all, again) = (movie(7), movie(7));
    let one_thread = RenderSettings {
        threads: Some(1),
        ..RenderSettings::default()
    };
    let two_threads = RenderSettings {
        threads: Some(2),
        ..RenderSettings::default()
    };
    // Every frame in order on one thread, against frame 5 alone on two.
    let frames: Vec<RgbImage> = (0..7)
        .map(|k| all.render_frame(k, &one_thread).unwrap())
        .collect();
    assert_eq!(again.render_frame(5, &two_threads).unwrap(), frames[5]);
    assert_ne!(frames[0], frames[6], "the frames do move");
    // Two pictures, each with its side view (16:9 beside 54 pixels: 96).
    assert_eq!(all.frame_size(), (2 * (48 + 96), 54));
    assert_eq!(frames[0].dimensions(), all.frame_size());
}

#[test]
fn frames_are_written_in_order_each_one_its_own() {
    // Each frame is written while the next one renders: the writer still gets frame k
    // as k, every frame once, and `on_frame` counts every render.
    let movie = Movie::from_demo(
        &demo_by_name("focus-pull").unwrap(),
        LoadOptions {
            size: Some((40, 24)),
            samples: Some(2),
        },
        MovieSettings {
            frames: Some(5),
            ..MovieSettings::default()
        },
    )
    .unwrap();
    let settings = RenderSettings::default();
    let (mut written, mut rendered) = (Vec::new(), 0);
    let timings = crate::write_frames(
        &movie,
        &settings,
        || rendered += 1,
        |k, frame| {
            written.push((k, frame.clone()));
            Ok(())
        },
    )
    .unwrap();
    assert_eq!(rendered, 5);
    assert_eq!(
        written.iter().map(|(k, _)| *k).collect::<Vec<_>>(),
        [0, 1, 2, 3, 4]
    );
    for (k, frame) in &written {
        assert_eq!(
            *frame,
            movie.render_frame(*k, &settings).unwrap(),
            "frame {k}"
        );
    }
    assert_ne!(written[0].1, written[4].1, "the frames do move");
    assert!(timings.render > std::time::Duration::ZERO);
}

#[test]
fn frames_that_would_not_fit_in_memory_are_refused() {
    let demo = demo_by_name("dolly-zoom").unwrap();
    let huge = LoadOptions {
        size: Some((4096, 4096)),
        samples: None,
    };
    let with_diagram = MovieSettings {
        with_diagram: true,
        ..MovieSettings::default()
    };
    let error = Movie::from_demo(&demo, huge, with_diagram).unwrap_err();
    assert!(matches!(error, MovieError::FrameTooLarge { .. }), "{error}");
    assert_eq!(
        error.to_string(),
        "a frame of 11378 x 4096 pixels is too large to animate: at most 16777216 pixels \
         (4096 x 4096), side views included"
    );
    let none = MovieSettings {
        frames: Some(0),
        ..MovieSettings::default()
    };
    let error = Movie::from_demo(&demo, LoadOptions::default(), none).unwrap_err();
    assert_eq!(
        error.to_string(),
        "frames must be between 1 and 10000, found 0"
    );
}

#[test]
fn the_lens_tilt_lays_the_plane_of_focus_on_the_table() {
    let demo = demo_by_name("lens-tilt").unwrap();
    let camera = |frame| demo.shots(frame, 9, 480, 270)[0].camera;
    // Untilted: the upright plane 2.475 m ahead, f = F / (1 - cos(asin(F / h))) with
    // F = 50 mm and h = 25 cm: 0.05 / (1 - sqrt(0.96)).
    let focus = 0.05 / (1.0 - 0.96f64.sqrt());
    let first = camera(0);
    let plane = first.focus_plane().unwrap();
    assert!(first.tilted_focus().is_none());
    assert!(plane.normal.abs_diff_eq(DVec3::Z, 1e-15));
    assert!(
        (plane.point.z - (0.6 - focus)).abs() < 1e-12,
        "{}",
        plane.point
    );
    // Tilted asin(0.2) = 11.54 degrees at the end: the hinge line F / sin = 0.25 below
    // the lens, on the table, and the plane of focus the table itself.
    let last = camera(8);
    let hinge = last.tilted_focus().unwrap().hinge_line;
    assert!(
        hinge.point.abs_diff_eq(DVec3::new(0.0, 0.0, 0.6), 1e-12),
        "{}",
        hinge.point
    );
    let plane = last.focus_plane().unwrap();
    assert!(
        plane.normal.abs_diff_eq(DVec3::Y, 1e-12),
        "{}",
        plane.normal
    );
    assert!(plane.point.y.abs() < 1e-12, "{}", plane.point);
    // Between, the hinge line rises toward the table as the tilt grows.
    let middle = camera(4).tilted_focus().unwrap().hinge_line.point.y;
    assert!(middle < 0.0 && middle > -0.5, "{middle}");
}

#[test]
fn the_bokeh_demo_steps_through_the_blades_to_round() {
    let demo = demo_by_name("bokeh").unwrap();
    let blades: Vec<u32> = (0..16)
        .map(
            |frame| match demo.shots(frame, 16, 480, 270)[0].camera.projection() {
                Projection::ThinLens(p) => p.iris.blades,
                _ => unreachable!("a thin lens"),
            },
        )
        .collect();
    // Sixteen frames, two for each of the eight apertures.
    assert_eq!(
        blades,
        [5, 5, 6, 6, 7, 7, 8, 8, 10, 10, 12, 12, 16, 16, 0, 0]
    );
    let captions: Vec<String> = [0, 15]
        .map(|frame| demo.shots(frame, 16, 480, 270)[0].caption.clone().unwrap())
        .to_vec();
    assert_eq!(captions, ["5 blades", "round aperture"]);
}
