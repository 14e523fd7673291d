//! `Scene::new`: a scene built in code is checked as a loaded one is, so its parallel
//! arrays (objects, their materials, a mesh's faces) always agree.

use std::sync::Arc;

use glam::Vec3;
use viewray_camera::Camera;
use viewray_geometry::{Aabb, Instance, Mesh, MeshData, Object, Sphere, World};
use viewray_scene::{InvalidScene, Material, ObjectMaterial, Scene, SceneParts, Shading};

/// A unit sphere and a box mesh of 12 faces, with two materials.
fn parts(object_materials: Vec<ObjectMaterial>, samples: u32) -> SceneParts {
    let cube = Mesh::new(MeshData::cuboid(Aabb::new(Vec3::ZERO, Vec3::ONE))).unwrap();
    let world = World::new(vec![
        Object::Sphere(Sphere::new(Vec3::new(0.0, 0.0, -5.0), 1.0)),
        Object::Instance(Instance::from_mesh(Arc::new(cube))),
    ])
    .unwrap();
    SceneParts {
        camera: Camera::canonical(4, 3).unwrap(),
        samples,
        background: Vec3::ZERO,
        shading: Shading::Flat,
        materials: vec![Material::default(); 2],
        lights: Vec::new(),
        world,
        object_materials,
    }
}

fn faces(materials: &[u32]) -> ObjectMaterial {
    ObjectMaterial::PerTriangle(materials.into())
}

#[track_caller]
fn check(object_materials: Vec<ObjectMaterial>, samples: u32, expected: Result<(), InvalidScene>) {
    let built = Scene::new(parts(object_materials, samples));
    assert_eq!(built.map(|_| ()), expected);
}

#[test]
fn consistent_parts_make_a_scene() {
    check(
        vec![ObjectMaterial::Single(0), ObjectMaterial::Single(1)],
        1,
        Ok(()),
    );
    check(
        vec![ObjectMaterial::Single(1), faces(&[0, 1].repeat(6))],
        4,
        Ok(()),
    );
}

#[test]
fn inconsistent_parts_are_refused() {
    let single = ObjectMaterial::Single;
    check(vec![single(0), single(0)], 0, Err(InvalidScene::NoSamples));
    check(
        vec![single(0)],
        1,
        Err(InvalidScene::MaterialCount {
            objects: 2,
            given: 1,
        }),
    );
    check(
        vec![single(0), single(0), single(0)],
        1,
        Err(InvalidScene::MaterialCount {
            objects: 2,
            given: 3,
        }),
    );
    check(
        vec![single(0), single(2)],
        1,
        Err(InvalidScene::MaterialOutOfRange {
            object: 1,
            index: 2,
            count: 2,
        }),
    );
    check(
        vec![single(0), faces(&[[0; 11].as_slice(), &[7]].concat())],
        1,
        Err(InvalidScene::MaterialOutOfRange {
            object: 1,
            index: 7,
            count: 2,
        }),
    );
    check(
        vec![faces(&[0]), single(0)],
        1,
        Err(InvalidScene::PerTriangleWithoutMesh { object: 0 }),
    );
    check(
        vec![single(0), faces(&[0; 11])],
        1,
        Err(InvalidScene::FaceCount {
            object: 1,
            given: 11,
            faces: 12,
        }),
    );
}

#[test]
fn a_scene_finds_each_face_its_material_and_reads_back_its_parts() {
    let mut colours = vec![Material::default(); 2];
    colours[1].color = Vec3::X;
    let mut parts = parts(vec![ObjectMaterial::Single(1), faces(&[0, 1].repeat(6))], 3);
    parts.materials = colours;
    let scene = Scene::new(parts).unwrap();
    assert_eq!(scene.material_of(0, 99).color, Vec3::X);
    assert_eq!(scene.material_of(1, 0).color, Vec3::splat(0.8));
    assert_eq!(scene.material_of(1, 11).color, Vec3::X);
    assert_eq!(scene.samples(), 3);
    assert_eq!(scene.world().objects().len(), 2);
    assert_eq!(scene.object_materials().len(), 2);
    assert_eq!(scene.camera().width(), 4);

    let wider = Camera::canonical(8, 3).unwrap();
    assert_eq!(scene.with_camera(wider).camera().width(), 8);
}
