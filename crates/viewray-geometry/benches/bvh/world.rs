//! A world of several objects (the icosphere, three small spheres and a ground of two
//! triangles) and its secondary rays: mirror rays and shadow rays from the primary
//! rays' hits.

use std::sync::Arc;

use glam::{Affine3A, Quat, Vec3};
use rayon::prelude::*;
use viewray_geometry::{Instance, Mesh, MeshData, Object, Ray, Triangle, World};

/// The small spheres: centre and radius, each an icosphere of 1,280 triangles placed
/// by an instance's transform, in the camera's view beside the large one.
const SPHERES: [(Vec3, f32); 3] = [
    (Vec3::new(1.2, 0.9, 0.3), 0.3),
    (Vec3::new(-1.1, -0.8, 0.6), 0.35),
    (Vec3::new(-1.0, 1.0, -1.0), 0.4),
];

/// The ground: a square of side 20 at y = -1.3, two triangles.
const GROUND: [[Vec3; 3]; 2] = [
    [
        Vec3::new(-10.0, -1.3, -10.0),
        Vec3::new(-10.0, -1.3, 10.0),
        Vec3::new(10.0, -1.3, 10.0),
    ],
    [
        Vec3::new(-10.0, -1.3, -10.0),
        Vec3::new(10.0, -1.3, 10.0),
        Vec3::new(10.0, -1.3, -10.0),
    ],
];

/// The direction toward the sun, which the shadow rays take.
pub(crate) fn sun() -> Vec3 {
    Vec3::new(1.0, 2.0, 1.5).normalize()
}

/// The world for viewray (the large mesh and the small spheres as instances, the ground
/// as two triangles, under a top-level BVH), and the same triangles in world space for
/// a peer: the large mesh's, each small sphere's moved by its transform, and the
/// ground's.
pub(crate) fn world(mesh: &Arc<Mesh>, data: &MeshData) -> (World, Vec<MeshData>) {
    let small = MeshData::icosphere(3, 1.0);
    let small_mesh = Arc::new(Mesh::new(small.clone()).expect("an icosphere"));
    let mut objects = vec![Object::Instance(Instance::from_mesh(Arc::clone(mesh)))];
    let mut triangles = vec![data.clone()];
    for (centre, radius) in SPHERES {
        let transform =
            Affine3A::from_scale_rotation_translation(Vec3::splat(radius), Quat::IDENTITY, centre);
        objects.push(Object::Instance(
            Instance::new(Arc::clone(&small_mesh), transform).expect("a placed sphere"),
        ));
        let positions = (small.positions.iter())
            .map(|&p| transform.transform_point3(p))
            .collect();
        triangles.push(MeshData::new(positions, small.triangles.clone()));
    }
    for [a, b, c] in GROUND {
        objects.push(Object::Triangle(Triangle { a, b, c }));
    }
    triangles.push(MeshData::new(
        GROUND.iter().flatten().copied().collect(),
        vec![[0, 1, 2], [3, 4, 5]],
    ));
    (World::new(objects).expect("a world"), triangles)
}

/// For each ray of `primary` that hits `world`, the ray `secondary(point, normal,
/// direction)` gives from its hit (the normal faces the ray), in `primary`'s order.
pub(crate) fn secondary_rays(
    world: &World,
    primary: &[Ray],
    secondary: impl Fn(Vec3, Vec3, Vec3) -> Ray + Sync,
) -> Vec<Ray> {
    primary
        .par_iter()
        .filter_map(|ray| {
            let hit = world.closest_hit(ray, 0.0..f32::INFINITY)?;
            Some(secondary(hit.point, hit.normal, ray.direction))
        })
        .collect()
}

/// The mirror ray from a hit, its origin moved off the surface by 1e-3.
pub(crate) fn mirror(point: Vec3, normal: Vec3, direction: Vec3) -> Ray {
    Ray::new(
        point + normal * 1e-3,
        direction - 2.0 * direction.dot(normal) * normal,
    )
}

/// The shadow ray from a hit toward the sun, its origin moved off the surface by 1e-3.
pub(crate) fn shadow(point: Vec3, normal: Vec3, _direction: Vec3) -> Ray {
    Ray::new(point + normal * 1e-3, sun())
}
