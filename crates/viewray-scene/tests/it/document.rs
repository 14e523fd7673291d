//! A `SceneDocument` written as RON reads back as the scene it describes, bit for bit.

use std::path::Path;

use glam::{DVec2, DVec3, Vec3};
use viewray_camera::{FovAxis, Frame, Lens, Perspective, Projection, SensorFit};
use viewray_scene::{
    Aperture, CameraDocument, Light, Material, ObjectDocument, PerspectiveSize, ProjectionDocument,
    SceneDocument, SceneLoader, Shading,
};

fn document(projection: ProjectionDocument) -> SceneDocument {
    SceneDocument {
        comments: vec!["Written by a test.".to_owned(), "Two lines.".to_owned()],
        width: 64,
        height: 48,
        samples: 3,
        camera: CameraDocument {
            eye: DVec3::new(0.1, 1.0 / 3.0, 5.0),
            view: DVec3::new(-0.1, -1.0 / 3.0, -5.0),
            up: DVec3::Y,
            projection,
        },
        background: Vec3::new(0.1, 0.2, 0.3),
        shading: Shading::Flat,
        materials: vec![(
            "a \"red\" one".to_owned(),
            Material {
                color: Vec3::new(0.8, 0.1, 1.0 / 3.0),
                ..Material::default()
            },
        )],
        lights: vec![
            Light::Point {
                position: Vec3::new(1.0, 2.0, 3.0),
                intensity: Vec3::splat(7.5),
            },
            Light::Ambient {
                intensity: Vec3::splat(0.1),
            },
        ],
        objects: vec![
            ObjectDocument::Sphere {
                center: Vec3::new(0.0, 0.0, -1.0),
                radius: 0.7,
                material: Some("a \"red\" one".to_owned()),
            },
            ObjectDocument::Triangle {
                corners: [Vec3::ZERO, Vec3::X, Vec3::Y],
                material: None,
            },
            ObjectDocument::Box {
                min: Vec3::splat(-1.0),
                max: Vec3::splat(1.0e-7),
                material: None,
            },
            ObjectDocument::Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
                material: None,
            },
        ],
    }
}

#[track_caller]
fn check(projection: ProjectionDocument, expected: Projection) {
    let doc = document(projection);
    let text = doc.to_ron();
    let scene = SceneLoader::text(&text, Path::new("doc.ron"))
        .load()
        .unwrap_or_else(|e| panic!("{e}\n{text}"))
        .scene;
    let camera = scene.camera();
    assert_eq!(camera.projection(), &expected, "{text}");
    let frame = Frame::from_eye_view_up(doc.camera.eye, doc.camera.view, doc.camera.up).unwrap();
    assert_eq!(camera.frame(), &frame);
    assert_eq!(
        (camera.width(), camera.height(), scene.samples()),
        (64, 48, 3)
    );
    assert_eq!(scene.world().objects().len(), 4);
    assert_eq!(scene.materials()[0].color, Vec3::new(0.8, 0.1, 1.0 / 3.0));
    assert!(text.starts_with("// Written by a test.\n// Two lines.\n("));
}

#[test]
fn every_projection_reads_back_exactly() {
    let aspect = 64.0 / 48.0;
    let viewport = DVec2::new(0.1 + 0.2, 1.0 / 7.0);
    let shift = DVec2::new(1e-3, -1.0 / 9.0);
    let plain = |size| ProjectionDocument::Perspective {
        size,
        shift: DVec2::ZERO,
    };
    check(
        ProjectionDocument::Perspective {
            size: PerspectiveSize::Viewport {
                distance: 0.3,
                viewport,
            },
            shift,
        },
        Projection::Perspective(Perspective {
            distance: 0.3,
            viewport,
            shift,
        }),
    );
    let fov = Perspective::from_fov(FovAxis::Diagonal, 0.9, aspect).unwrap();
    check(
        plain(PerspectiveSize::Fov {
            axis: FovAxis::Diagonal,
            degrees: 0.9f64.to_degrees(),
            distance: 1.0,
        }),
        Projection::Perspective(
            Perspective::from_fov(FovAxis::Diagonal, 0.9f64.to_degrees().to_radians(), aspect)
                .unwrap(),
        ),
    );
    assert!((fov.viewport.x - 2.0 * (0.45f64).tan() * 0.8).abs() < 1e-12);
    let physical = PerspectiveSize::FocalLength {
        millimetres: 35.0,
        sensor: DVec2::new(36.0, 24.0),
        fit: SensorFit::Vertical,
    };
    let pinhole =
        Perspective::from_focal_length(35.0, DVec2::new(36.0, 24.0), SensorFit::Vertical, aspect)
            .unwrap();
    check(
        ProjectionDocument::ThinLens {
            size: physical,
            shift,
            aperture: Aperture::FNumber(2.8),
            focus: 4.0,
        },
        Projection::ThinLens(viewray_camera::ThinLens {
            distance: pinhole.distance,
            viewport: pinhole.viewport,
            shift,
            aperture: viewray_camera::aperture_from_f_number(35.0, 2.8).unwrap(),
            focus: 4.0,
            tilt: 0.0,
            swing: 0.0,
            iris: viewray_camera::Iris::ROUND,
        }),
    );
    let lens = Lens {
        aperture: 0.25,
        focus: 3.0,
    };
    check(
        ProjectionDocument::Orthographic {
            viewport,
            lens: Some(lens),
        },
        Projection::Orthographic(viewray_camera::Orthographic {
            viewport,
            lens: Some(lens),
        }),
    );
    check(
        ProjectionDocument::Oblique {
            viewport,
            ratio: 0.5,
            angle_degrees: 30.0,
        },
        Projection::Oblique(viewray_camera::Oblique {
            viewport,
            ratio: 0.5,
            angle: 30f64.to_radians(),
        }),
    );
    check(
        ProjectionDocument::Equirectangular,
        Projection::Equirectangular,
    );
    check(
        ProjectionDocument::Fisheye { fov_degrees: 190.0 },
        Projection::Fisheye(viewray_camera::Fisheye {
            fov: 190f64.to_radians(),
        }),
    );
}
