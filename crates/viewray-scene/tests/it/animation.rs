//! A scene file's `animation:` section: parsed with its keys in place, and two keys mix
//! field by field, exactly the first key at 0 and the second at 1.

use std::path::Path;

use glam::{DVec2, DVec3};
use viewray_camera::{Camera, Frame, Perspective, Preset, Projection, ThinLens};
use viewray_scene::{Ease, Position, Scene, SceneLoader};

const SCENE: &str = "(
    image: (width: 64, height: 48),
    camera: (eye: (0.0, 1.0, 5.0), look_at: (0.0, 1.0, 0.0), projection: Perspective(fov_y: 40.0)),
    animation: (frames: 12, fps: 30, ease: InOut, keys: [
        (t: 0.0, camera: (eye: (0.0, 1.0, 4.0), view: (0.0, 0.0, -1.0),
                          projection: ThinLens(distance: 1.0, viewport: (1.6, 1.2), aperture: 0.1, focus: 2.0))),
        (t: 0.25, camera: (eye: (2.0, 1.0, 8.0), view: (0.0, 0.5, -1.0), up: (0.0, 1.0, 0.0),
                          projection: ThinLens(distance: 3.0, viewport: (1.6, 1.2), shift: (0.0, 0.4), aperture: 0.5, focus: 6.0))),
    ]),
)";

fn animated(text: &str) -> (Scene, viewray_scene::Animation) {
    let loaded = SceneLoader::text(text, Path::new("anim.ron"))
        .load()
        .unwrap();
    let animation = loaded.animation.expect("the scene has an animation");
    (loaded.scene, animation)
}

#[test]
fn the_section_is_read_with_its_keys_in_place() {
    let (_, animation) = animated(SCENE);
    assert_eq!((animation.frames, animation.fps), (12, 30));
    assert_eq!(animation.ease, Ease::InOut);
    let times: Vec<f64> = animation.keys.iter().map(|k| k.t).collect();
    assert_eq!(times, [0.0, 0.25]);
    assert_eq!(animation.keys[1].position, Position { line: 7, column: 9 });
    assert_eq!(
        animation.key_error(1, "oops").to_string(),
        "anim.ron:7:9: oops"
    );
    // A scene without the section loads with none; the still loaders ignore it.
    let still = SCENE.split("    animation:").next().unwrap().to_owned() + ")";
    let none = SceneLoader::text(&still, Path::new("s.ron"))
        .load()
        .unwrap()
        .animation;
    assert!(none.is_none());
    assert!(
        SceneLoader::text(SCENE, Path::new("anim.ron"))
            .load()
            .is_ok()
    );
}

#[test]
fn defaults_are_48_frames_at_24_fps_linear() {
    let text = "(camera: Top(target: (0.0, 0.0, 0.0), size: 2.0),
                 animation: (keys: [(t: 0.5, camera: Top(target: (0.0, 0.0, 0.0), size: 2.0))]))";
    let (_, animation) = animated(text);
    assert_eq!((animation.frames, animation.fps), (48, 24));
    assert_eq!(animation.ease, Ease::Linear);
}

/// The thin-lens camera with every field given, as the lecture's formulas build it.
fn thin_lens(eye: DVec3, view: DVec3, d: f64, shift: DVec2, aperture: f64, focus: f64) -> Camera {
    let frame = Frame::from_eye_view_up(eye, view, DVec3::Y).unwrap();
    let projection = Projection::ThinLens(ThinLens {
        distance: d,
        viewport: DVec2::new(1.6, 1.2),
        shift,
        aperture,
        focus,
        tilt: 0.0,
        swing: 0.0,
        iris: viewray_camera::Iris::ROUND,
    });
    Camera::new(frame, projection, 64, 48).unwrap()
}

#[test]
fn keys_mix_field_by_field_exactly_at_the_ends() {
    let (_, animation) = animated(SCENE);
    let (a, b) = (&animation.keys[0].camera, &animation.keys[1].camera);
    let first = thin_lens(
        DVec3::new(0.0, 1.0, 4.0),
        DVec3::NEG_Z,
        1.0,
        DVec2::ZERO,
        0.1,
        2.0,
    );
    let second = thin_lens(
        DVec3::new(2.0, 1.0, 8.0),
        DVec3::new(0.0, 0.5, -1.0),
        3.0,
        DVec2::new(0.0, 0.4),
        0.5,
        6.0,
    );
    assert_eq!(a.camera(64, 48).unwrap(), first);
    assert_eq!(a.mix(b, 0.0).unwrap().camera(64, 48).unwrap(), first);
    assert_eq!(a.mix(b, 1.0).unwrap().camera(64, 48).unwrap(), second);
    // A quarter of the way: every number a quarter of the way, the frame built from the
    // mixed eye and view.
    let quarter = thin_lens(
        DVec3::new(0.5, 1.0, 5.0),
        DVec3::new(0.0, 0.125, -1.0),
        1.5,
        DVec2::new(0.0, 0.1),
        0.2,
        3.0,
    );
    assert_eq!(a.mix(b, 0.25).unwrap().camera(64, 48).unwrap(), quarter);
}

#[test]
fn presets_mix_their_target_size_and_angle() {
    let text = "(camera: Cabinet(target: (0.0, 0.0, 0.0), size: 2.0),
                 animation: (keys: [
                     (t: 0.0, camera: Cabinet(target: (0.0, 0.0, 0.0), size: 2.0, angle: 0.0)),
                     (t: 1.0, camera: Cabinet(target: (4.0, 0.0, 0.0), size: 6.0, angle: 90.0)),
                 ]))";
    let (_, animation) = animated(text);
    let (a, b) = (&animation.keys[0].camera, &animation.keys[1].camera);
    let half = a.mix(b, 0.5).unwrap().camera(320, 240).unwrap();
    let expected = Preset::Cabinet {
        angle: 45f64.to_radians(),
    }
    .camera(DVec3::new(2.0, 0.0, 0.0), 4.0, 320, 240)
    .unwrap();
    assert_eq!(half, expected);
}

#[test]
fn keys_written_differently_do_not_mix() {
    let (_, animation) = animated(SCENE);
    let perspective = animated(
        "(camera: (eye: (0.0, 0.0, 1.0), view: (0.0, 0.0, -1.0), projection: Perspective(fov_y: 30.0)),
          animation: (keys: [(t: 0.0, camera: (eye: (0.0, 0.0, 1.0), view: (0.0, 0.0, -1.0),
                                               projection: Perspective(fov_y: 30.0)))]))",
    )
    .1;
    let error = animation.keys[0]
        .camera
        .mix(&perspective.keys[0].camera, 0.5)
        .unwrap_err();
    assert_eq!(
        error,
        "cannot interpolate between the projection families `ThinLens` and `Perspective`: \
         the keys of an animation share one family (`viewray animate --demo \
         perspective-to-orthographic` shows a path between two)"
    );
    // A field of view mixes with a field of view, in degrees.
    let wide = Perspective::from_fov_y(30f64.to_radians(), 4.0 / 3.0).unwrap();
    assert_eq!(
        *perspective.keys[0]
            .camera
            .camera(320, 240)
            .unwrap()
            .projection(),
        Projection::Perspective(wide)
    );
}

#[test]
fn physical_cameras_mix_their_focal_length_and_keep_their_fit() {
    let keyed = |fit_a: &str, fit_b: &str| {
        format!(
            "(camera: (eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0),
                       projection: Perspective(focal_length: 24.0, fit: {fit_a})),
              animation: (keys: [
                  (t: 0.0, camera: (eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0),
                                    projection: Perspective(focal_length: 24.0, fit: {fit_a}))),
                  (t: 1.0, camera: (eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0),
                                    projection: Perspective(focal_length: 85.0, fit: {fit_b}))),
              ]))"
        )
    };
    let (_, animation) = animated(&keyed("Horizontal", "Horizontal"));
    let half = animation.keys[0]
        .camera
        .mix(&animation.keys[1].camera, 0.5)
        .unwrap()
        .camera(320, 240)
        .unwrap();
    // Half way: a 54.5 mm lens, as a scene file writes it.
    let written = SceneLoader::text(
        "(camera: (eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0),
                   projection: Perspective(focal_length: 54.5, fit: Horizontal)))",
        Path::new("s.ron"),
    )
    .load()
    .unwrap()
    .scene;
    assert_eq!(half, *written.camera());
    let error = SceneLoader::text(&keyed("Horizontal", "Vertical"), Path::new("fit.ron"))
        .load()
        .unwrap_err();
    assert_eq!(
        error.message(),
        "animation: key 2: the keys give different `fit`: it is a choice, not a number, so \
         every key of an animation gives the same"
    );
}

#[test]
fn tilts_and_blade_rotations_mix_while_blades_stay_the_same() {
    let keyed = |blades_b: u32| {
        format!(
            "(camera: (eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0),
                       projection: ThinLens(focal_length: 50.0, f_number: 2.0, focus: 3.0)),
              animation: (keys: [
                  (t: 0.0, camera: (eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0),
                                    projection: ThinLens(focal_length: 50.0, f_number: 2.0, focus: 3.0,
                                                         blades: 6, blade_rotation: -20.0))),
                  (t: 1.0, camera: (eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0),
                                    projection: ThinLens(focal_length: 50.0, f_number: 2.0, focus: 3.0,
                                                         lens_tilt: 8.0, lens_swing: -4.0,
                                                         blades: {blades_b}, blade_rotation: 40.0))),
              ]))"
        )
    };
    let (_, animation) = animated(&keyed(6));
    let half = animation.keys[0]
        .camera
        .mix(&animation.keys[1].camera, 0.5)
        .unwrap()
        .camera(320, 240)
        .unwrap();
    let written = SceneLoader::text(
        "(camera: (eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0),
                   projection: ThinLens(focal_length: 50.0, f_number: 2.0, focus: 3.0,
                                        lens_tilt: 4.0, lens_swing: -2.0,
                                        blades: 6, blade_rotation: 10.0)))",
        Path::new("s.ron"),
    )
    .load()
    .unwrap()
    .scene;
    assert_eq!(half, written.camera().with_image_size(320, 240).unwrap());
    let error = SceneLoader::text(&keyed(5), Path::new("blades.ron"))
        .load()
        .unwrap_err();
    assert_eq!(
        error.message(),
        "animation: key 2: the keys give different `blades`: it is a choice, not a number, so \
         every key of an animation gives the same"
    );
}
