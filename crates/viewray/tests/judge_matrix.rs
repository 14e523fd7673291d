//! Calibration (temporary): the geometry judge's agreements over the student's pictures.

mod support;

use std::path::Path;

use support::student::{
    Aim, CameraSpec, Gamma, LightChange, Mistake as StudentMistake, Projection, RenderOptions,
    Scene, Vec3, render,
};
use viewray_compare::RgbaImage;
use viewray_judge::{CameraVerdict, PictureJudge};

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(x, y, z)
}

fn cameras() -> Vec<(&'static str, CameraSpec, (u32, u32))> {
    let look = |eye, at, projection| CameraSpec {
        eye,
        aim: Aim::LookAt(at),
        up: Vec3::Y,
        projection,
    };
    vec![
        (
            "general",
            look(
                v(0.35, 2.0, 6.0),
                v(0.27, 0.5, 0.0),
                Projection::Perspective {
                    d: 1.5,
                    viewport: (1.2, 0.9),
                    shift: (0.0, 0.0),
                },
            ),
            (160, 120),
        ),
        (
            "shifted",
            look(
                v(0.3, 1.0, 6.0),
                v(0.3, 1.0, 0.0),
                Projection::Perspective {
                    d: 1.0,
                    viewport: (0.8, 0.6),
                    shift: (0.0, -0.15),
                },
            ),
            (160, 120),
        ),
        (
            "ortho",
            look(
                v(2.0, 3.0, 6.0),
                v(0.3, 0.5, 0.0),
                Projection::Orthographic {
                    viewport: (5.0, 3.75),
                },
            ),
            (160, 120),
        ),
        (
            "oblique",
            look(
                v(0.3, 0.8, 6.0),
                v(0.3, 0.8, 0.0),
                Projection::Oblique {
                    viewport: (5.0, 3.75),
                    ratio: 0.5,
                    angle_degrees: 30.0,
                },
            ),
            (160, 120),
        ),
    ]
}

fn to_rgba(picture: &support::student::Picture) -> RgbaImage {
    RgbaImage::from_fn(picture.width, picture.height, |x, y| {
        let [r, g, b] = picture.pixel8(y, x);
        image::Rgba([r, g, b, 255])
    })
}

#[test]
fn calibration() {
    let scene = Scene::example();
    for (name, camera, size) in cameras() {
        let ron = scene.to_ron(&camera, size.0, size.1, 1);
        let loaded = viewray_scene::SceneLoader::text(&ron, Path::new("student.ron"))
            .load()
            .unwrap()
            .scene;
        let judge = PictureJudge::new(&loaded);
        println!("== {name}: groups {:?}", judge.entries());
        let variants: Vec<(&str, RenderOptions)> = vec![
            ("plain", RenderOptions::default()),
            (
                "bright",
                RenderOptions {
                    ambient: 0.35,
                    light_scale: 1.6,
                    ..RenderOptions::default()
                },
            ),
            (
                "linear",
                RenderOptions {
                    gamma: Gamma::Linear,
                    ..RenderOptions::default()
                },
            ),
            (
                "noshadow",
                RenderOptions {
                    shadows: false,
                    phong: false,
                    ..RenderOptions::default()
                },
            ),
            (
                "moved-light",
                RenderOptions {
                    light_change: Some(LightChange::Moved(v(3.0, 0.0, -4.0))),
                    ..RenderOptions::default()
                },
            ),
            (
                "16spp",
                RenderOptions {
                    samples: 16,
                    ..RenderOptions::default()
                },
            ),
        ];
        for (variant, options) in &variants {
            let picture = to_rgba(&render(&scene, &camera, &[], size, options));
            println!("  right/{variant}: {:?}", judge.judge(&picture));
        }
        for mistake in StudentMistake::ALL {
            if !mistake.applies_to(&camera.projection) {
                continue;
            }
            for (variant, options) in &variants[..1] {
                let picture = to_rgba(&render(&scene, &camera, &[mistake], size, options));
                let verdict = judge.judge(&picture);
                let ok = match &verdict {
                    CameraVerdict::Mistaken { explanation, .. } => {
                        explanation.mistakes.iter().any(|m| m.id() == mistake.id())
                    }
                    _ => false,
                };
                println!(
                    "  {}{} /{variant}: {:?}",
                    if ok { "OK " } else { "XX " },
                    mistake.id(),
                    verdict
                );
            }
        }
    }
}
