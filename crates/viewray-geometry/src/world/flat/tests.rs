//! Small worlds tested flat against the same worlds walked as packets and traced ray by
//! ray: random worlds with shared edges and coincident shapes, random rays (coherent
//! bundles, rays at edges and vertices, along axes, degenerate ones), closest hits and
//! any hits, compared bit for bit.

use glam::Vec3;

use crate::world::ObjectHit;
use crate::{Aabb, Instance, Mesh, Object, Plane, Ray, Sphere, Triangle, World};

/// Numbers from a fixed seed (SplitMix64): uniform in `[0, 1)`, or in a range.
struct Numbers(u64);

impl Numbers {
    fn uniform(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }

    fn within(&mut self, low: f32, high: f32) -> f32 {
        low + (high - low) * self.uniform()
    }

    fn below(&mut self, n: usize) -> usize {
        ((self.uniform() * n as f32) as usize).min(n - 1)
    }

    fn vector(&mut self, size: f32) -> Vec3 {
        Vec3::new(
            self.within(-size, size),
            self.within(-size, size),
            self.within(-size, size),
        )
    }

    /// A direction: general, along an axis (either sign, sometimes with a negative
    /// zero), or in a coordinate plane.
    fn direction(&mut self) -> Vec3 {
        match self.below(5) {
            0 => {
                let mut d = Vec3::splat(if self.uniform() < 0.5 { -0.0 } else { 0.0 });
                d[self.below(3)] = if self.uniform() < 0.5 { -1.0 } else { 1.0 };
                d
            }
            1 => {
                let mut d = self.vector(1.0);
                d[self.below(3)] = 0.0;
                d
            }
            _ => self.vector(1.0),
        }
    }
}

/// The corners of an axis-aligned cube as 12 triangles, two to a face, each face's two
/// sharing a diagonal and each edge shared by two faces (as the default scene's cube).
fn cube(center: Vec3, half: f32) -> Vec<Triangle> {
    let corner = |i: usize| {
        center
            + half
                * Vec3::new(
                    if i & 1 == 0 { -1.0 } else { 1.0 },
                    if i & 2 == 0 { -1.0 } else { 1.0 },
                    if i & 4 == 0 { -1.0 } else { 1.0 },
                )
    };
    let faces = [
        [0, 2, 6, 4],
        [1, 5, 7, 3],
        [0, 4, 5, 1],
        [2, 3, 7, 6],
        [0, 1, 3, 2],
        [4, 6, 7, 5],
    ];
    faces
        .iter()
        .flat_map(|&[a, b, c, d]| {
            [
                Triangle::new(corner(a), corner(b), corner(c)),
                Triangle::new(corner(a), corner(c), corner(d)),
            ]
        })
        .collect()
}

/// A random shape in the box from `low` to `high` whose bounds are that box: the
/// sphere inscribed in it (when it is a cube), the box itself, or a triangle from
/// corner to corner.
fn shape_filling(numbers: &mut Numbers, low: Vec3, high: Vec3) -> Object {
    let size = high - low;
    match numbers.below(4) {
        0 if size.x == size.y && size.y == size.z => {
            Object::Sphere(Sphere::new((low + high) * 0.5, size.x * 0.5))
        }
        1 => Object::Box(Aabb::new(low, high)),
        _ => {
            let inside = low + size * Vec3::new(numbers.uniform(), numbers.uniform(), 0.5);
            let (a, b) = if numbers.uniform() < 0.5 {
                (low, high)
            } else {
                (high, low)
            };
            Object::Triangle(Triangle::new(a, inside, b))
        }
    }
}

/// A random small world: up to two planes and either one bounded object (a sphere,
/// a triangle, a quad's two triangles' first, a box) or a few that one leaf holds:
/// shapes with the same bounds, among them coincident ones (the same shape twice, a
/// triangle with its vertices rotated) and triangles sharing an edge; sometimes a
/// triangle in a plane.
fn small_world(numbers: &mut Numbers) -> Vec<Object> {
    let mut objects = Vec::new();
    for _ in 0..numbers.below(3) {
        let normal = if numbers.uniform() < 0.5 {
            Vec3::Y
        } else {
            numbers.direction()
        };
        if normal != Vec3::ZERO {
            objects.push(Object::Plane(Plane::new(numbers.vector(1.0), normal)));
        }
    }
    if let Some(Object::Plane(p)) = objects.first()
        && numbers.uniform() < 0.2
    {
        // A triangle in the plane: met at the plane's `t`.
        let (u, v) = p.normal.normalize().any_orthonormal_pair();
        let triangle = Triangle::new(p.point - u - v, p.point + u - v, p.point + v);
        objects.push(Object::Triangle(triangle));
        return objects;
    }
    let center = numbers.vector(1.5);
    let half = numbers.within(0.05, 1.0);
    let (low, high) = (center - half, center + half);
    let count = match numbers.below(3) {
        0 => numbers.below(2),
        _ => 2 + numbers.below(3),
    };
    // The last triangle from corner to corner (`a` and `c` corners, `b` inside).
    let mut corner_triangle: Option<Triangle> = None;
    for _ in 0..count {
        let shape = match (objects.last(), corner_triangle) {
            // A copy, or a triangle with its vertices rotated.
            (Some(Object::Triangle(t)), _) if numbers.uniform() < 0.3 => {
                Object::Triangle(Triangle::new(t.b, t.c, t.a))
            }
            (Some(Object::Sphere(_) | Object::Box(_)), _) if numbers.uniform() < 0.3 => {
                objects.last().cloned().unwrap()
            }
            // A triangle sharing the corner-to-corner edge of one before.
            (_, Some(t)) if numbers.uniform() < 0.5 => {
                Object::Triangle(Triangle::new(t.c, t.a, low + high - t.b))
            }
            _ => {
                let shape = shape_filling(numbers, low, high);
                if let Object::Triangle(t) = shape {
                    corner_triangle = Some(t);
                }
                shape
            }
        };
        objects.push(shape);
    }
    objects
}

/// Points rays are aimed at exactly: the vertices, edge midpoints and centres of the
/// triangles, the spheres' centres and the boxes' corners.
fn targets(objects: &[Object]) -> Vec<Vec3> {
    let mut targets = Vec::new();
    for object in objects {
        match object {
            Object::Triangle(t) => {
                targets.extend([t.a, t.b, t.c, (t.a + t.b) * 0.5, (t.b + t.c) * 0.5]);
                targets.extend([(t.c + t.a) * 0.5, (t.a + t.b + t.c) / 3.0]);
            }
            Object::Sphere(s) => targets.push(s.center),
            Object::Box(b) => targets.extend([b.min, b.max]),
            Object::Plane(p) => targets.push(p.point),
            Object::Instance(_) => {}
        }
    }
    targets
}

/// A batch of 1 to 64 rays: a bundle from one eye (viewing rays), rays from random
/// points at the objects' vertices and edges, rays from those points, or random rays;
/// a few degenerate.
fn batch(numbers: &mut Numbers, targets: &[Vec3]) -> Vec<Ray> {
    let count = 1 + numbers.below(64);
    let eye = numbers.vector(4.0);
    let kind = numbers.below(4);
    let (forward, spread) = (numbers.direction(), numbers.within(0.0, 0.5));
    let mut rays: Vec<Ray> = (0..count)
        .map(|_| match kind {
            0 => Ray::new(eye, forward + spread * numbers.vector(1.0)),
            1 if !targets.is_empty() => {
                let target = targets[numbers.below(targets.len())];
                let origin = numbers.vector(4.0);
                let length = [1.0, 0.25, 3.0][numbers.below(3)];
                Ray::new(origin, (target - origin) * length)
            }
            2 if !targets.is_empty() => {
                // From a vertex, an edge or a surface point: hits at `t = 0`.
                Ray::new(targets[numbers.below(targets.len())], numbers.direction())
            }
            _ => Ray::new(numbers.vector(3.0), numbers.direction()),
        })
        .collect();
    for _ in 0..numbers.below(3) {
        let i = numbers.below(rays.len());
        let degenerate = [Vec3::ZERO, Vec3::NAN, Vec3::new(f32::INFINITY, 0.0, 1.0)];
        rays[i].direction = degenerate[numbers.below(3)];
    }
    if numbers.uniform() < 0.05 {
        rays[0].origin = Vec3::new(f32::NAN, 0.0, 0.0);
    }
    rays
}

/// A hit's numbers as bits: `t`, object, primitive and the raw barycentrics.
fn bits(hit: &Option<ObjectHit>) -> Option<(u32, u32, u32, [u32; 2])> {
    hit.map(|h| {
        let b = h.raw.barycentric;
        (
            h.t.to_bits(),
            h.object,
            h.primitive,
            [b.x.to_bits(), b.y.to_bits()],
        )
    })
}

/// What a comparison of the flat and packet paths covered.
#[derive(Default)]
struct Coverage {
    rays: usize,
    hits: usize,
    /// Rays whose closest hit is met by another object at exactly the same `t`.
    ties: usize,
    blocked: usize,
}

/// Checks that a flat world's batch queries give exactly what its BVH walked as packets
/// and its rays traced alone give.
#[track_caller]
fn check_flat(world: &World, rays: &[Ray], t_range: std::ops::Range<f32>, coverage: &mut Coverage) {
    assert!(world.flat.is_some());
    let mut flat = vec![None; rays.len()];
    let mut packets = vec![None; rays.len()];
    world.closest_objects(rays, t_range.clone(), &mut flat);
    world.closest_packets(rays, t_range.clone(), &mut packets);
    for ((ray, flat), packets) in rays.iter().zip(&flat).zip(&packets) {
        let single = world.closest_object(ray, t_range.clone());
        assert_eq!(
            bits(flat),
            bits(packets),
            "flat against packets for {ray:?} in {t_range:?}"
        );
        assert_eq!(
            bits(flat),
            bits(&single),
            "flat against a single ray for {ray:?}"
        );
        coverage.rays += 1;
        if let Some(hit) = flat {
            coverage.hits += 1;
            let tied = (0..world.objects().len() as u32).any(|object| {
                object != hit.object
                    && world
                        .intersect_object(object, ray, t_range.start, t_range.end)
                        .is_some_and(|other| other.t == hit.t)
            });
            coverage.ties += usize::from(tied);
        }
    }
    let mut flat = vec![false; rays.len()];
    let mut packets = vec![false; rays.len()];
    world.any_hits(rays, t_range.clone(), &mut flat);
    world.any_packets(rays, t_range.clone(), &mut packets);
    for ((ray, &flat), &packets) in rays.iter().zip(&flat).zip(&packets) {
        assert_eq!(
            flat, packets,
            "any hit, flat against packets, for {ray:?} in {t_range:?}"
        );
        assert_eq!(
            flat,
            world.any_hit(ray, t_range.clone()),
            "against a single ray: {ray:?}"
        );
        coverage.blocked += usize::from(flat);
    }
}

#[test]
fn small_worlds_find_the_hits_of_their_packets_and_single_rays_bit_for_bit() {
    let mut numbers = Numbers(0x5eed_f1a7);
    let mut coverage = Coverage::default();
    for _ in 0..400 {
        let world = World::new(small_world(&mut numbers)).unwrap();
        let targets = targets(world.objects());
        for _ in 0..4 {
            let rays = batch(&mut numbers, &targets);
            for t_range in [0.0..f32::INFINITY, 1e-3..f32::INFINITY, 0.5..2.0, 1.0..1.0] {
                check_flat(&world, &rays, t_range, &mut coverage);
            }
        }
    }
    // The rays met the shapes often, and many met two at exactly the same distance
    // (coincident shapes, shared edges), where the order of the tests decides.
    assert!(coverage.hits > coverage.rays / 5, "{} hits", coverage.hits);
    assert!(coverage.ties > 1000, "{} ties", coverage.ties);
    assert!(
        coverage.blocked > coverage.rays / 5,
        "{} blocked",
        coverage.blocked
    );
}

#[test]
fn coincident_shapes_go_to_the_first_listed() {
    let sphere = Sphere::new(Vec3::new(0.0, 0.0, -3.0), 1.0);
    let objects = vec![
        Object::Sphere(sphere),
        Object::Sphere(sphere),
        Object::Plane(Plane::new(Vec3::new(0.0, 0.0, -2.0), Vec3::Z)),
    ];
    let world = World::new(objects).unwrap();
    let rays = [
        Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0)),
        Ray::new(Vec3::new(0.0, 0.0, -2.5), Vec3::new(0.0, 0.0, -1.0)),
    ];
    let mut hits = [None; 2];
    world.closest_objects(&rays, 0.0..f32::INFINITY, &mut hits);
    // The plane, touching the spheres, comes first; from inside the spheres, the
    // first of the two.
    assert_eq!(
        hits.map(|h| h.map(|h| (h.t, h.object))),
        [Some((2.0, 2)), Some((1.5, 0))]
    );
    check_flat(&world, &rays, 0.0..f32::INFINITY, &mut Coverage::default());
}

#[test]
fn one_object_or_one_leaf_is_flat_and_the_lecture_scenes_walk_their_tree() {
    let spheres = |n: usize| -> Vec<Object> {
        (0..n)
            .map(|i| Object::Sphere(Sphere::new(Vec3::new(i as f32, 0.5, -2.0), 0.4)))
            .collect()
    };
    let ground = Object::Plane(Plane::new(Vec3::ZERO, Vec3::Y));
    let flat = |objects: Vec<Object>| World::new(objects).unwrap().flat;
    assert!(flat(vec![ground.clone()]).is_some_and(|flat| flat.leaf.is_none()));
    assert!(flat([vec![ground.clone()], spheres(1)].concat()).is_some_and(|f| f.leaf.is_none()));
    let twice = [spheres(1), spheres(1)].concat();
    assert!(flat(twice).is_some_and(|flat| flat.leaf.is_some()));
    // The aperture demos' three spheres and the default scene's cube and spheres.
    assert!(flat([vec![ground.clone()], spheres(3)].concat()).is_none());
    let cube = cube(Vec3::new(0.0, 0.6, 0.0), 0.6)
        .into_iter()
        .map(Object::Triangle);
    assert!(flat([vec![ground], cube.collect(), spheres(3)].concat()).is_none());
    let mesh = Object::Instance(Instance::from_mesh(std::sync::Arc::new(Mesh::icosphere(
        1, 0.5,
    ))));
    assert!(flat(vec![mesh]).is_none());
}
