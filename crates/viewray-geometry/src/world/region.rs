//! Boxes of rays ruled out whole: before a renderer makes a block's viewing rays, it asks
//! what any ray the block can take may meet. If nothing, it makes none of them (the sky
//! above a ground plane, the background around a model); if planes at most, it meets
//! them with the planes alone, without packets or the hierarchy (the open ground); if
//! one sphere or triangle besides, with it alone (the ground around a ball).

use std::ops::Range;

use glam::{DVec3, Vec4};

use super::flat::{plane_hit, ray_lanes};
use super::loose::Loose;
use super::{CLEAR_MARGIN, ClearBox, ObjectHit, World, enlarged};
use crate::{Aabb, Plane, Ray, RayBounds};

/// How far a ray's coordinates may move between a [`RayBounds`] and the tracer, per unit
/// of the largest coordinate of its origin (or direction): the camera's own arithmetic
/// in `f64` and the rounding to `f32` move them by less than a sixteenth of this.
const ROUNDING: f64 = 1e-6;

/// How far from zero a plane's `n.d` and `n.(p - o)` must be for their signs to be
/// taken as certain, per unit of the sizes of their terms: far above the rounding of the
/// plane test in `f32`.
const PLANE_MARGIN: f64 = 1e-5;

/// What the rays of a [`RayBounds`] may meet ([`World::reach`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reach {
    /// Nothing: every ray surely meets nothing ahead of its origin.
    Nothing,
    /// Planes at most: every ray surely misses every bounded object, so that its
    /// closest hit is its closest plane's ([`World::closest_plane_hits`]).
    Planes,
    /// Planes and this one bounded object at most, a sphere or a triangle: every ray
    /// surely misses every other, so that its closest hit is found among these
    /// ([`World::closest_hits_with`]).
    One(u32),
    /// Anything, as far as the test can tell.
    Anything,
}

impl World {
    /// What the rays of `rays`, rounded to `f32` as the tracer takes them, may meet
    /// ahead of their origins (`t >= 0`).
    ///
    /// Every bounded object is surely missed when each ray passes outside its box
    /// enlarged by a thousandth of one plus the largest coordinate of the box around
    /// them all and of the rays' origins (far above the rounding of the box tests every
    /// query makes before it tests an object), found down the hierarchy through
    /// the boxes the rays may enter. A plane is surely missed when it lies behind every
    /// origin with every direction turned away from it (or ahead of every origin with
    /// every direction turned away). [`World::closest_objects`] then finds no hit, or
    /// only the planes', for any of them.
    ///
    /// Where one bounded object alone may be met, a sphere or a triangle, the answer is
    /// [`Reach::One`] of it.
    ///
    /// The test is of the whole box of rays, one axis at a time: it answers
    /// [`Reach::Anything`] whenever some ray of the box may hit two bounded objects, or a
    /// box or a mesh. A world with a single bounded object, which rays meet without a box
    /// test, rules out no ray.
    pub fn reach(&self, rays: &RayBounds) -> Reach {
        let rays = widened(rays);
        let bounded_missed = match self.clear_box {
            ClearBox::Nothing => true,
            ClearBox::Unknown => false,
            ClearBox::Around(_) => {
                // Down the hierarchy through the boxes the rays may enter, to the
                // objects' own boxes: a box around every object is too loose for a
                // lens's rays, which start all over the aperture.
                // The one object met, if only one may be (a loose shape: meshes keep
                // their packets); the walk stops at a second.
                let margin = box_margin(&rays, self.bvh.bounds());
                let enters = |bounds: &Aabb| !misses_box(&rays, *bounds, margin);
                let mut one = None;
                let several = self.bvh.any_leaf_entered(enters, |start, count| {
                    let (start, count) = (start as usize, count as usize);
                    for &object in &self.leaf_objects[start..start + count] {
                        let shape = &self.objects[object as usize];
                        if !shape.bounds().is_none_or(|bounds| enters(&bounds)) {
                            continue;
                        }
                        if one.is_some() || Loose::of(shape).is_none() {
                            return true;
                        }
                        one = Some(object);
                    }
                    false
                });
                match (several, one) {
                    (true, _) => return Reach::Anything,
                    (false, Some(object)) => return Reach::One(object),
                    (false, None) => true,
                }
            }
        };
        if !bounded_missed {
            Reach::Anything
        } else if self
            .plane_objects()
            .all(|(_, plane)| misses_plane(&rays, plane))
        {
            Reach::Nothing
        } else {
            Reach::Planes
        }
    }

    /// The closest hits of rays that meet no bounded object but `object`, a sphere or a
    /// triangle (rays of a box for which [`World::reach`] answered [`Reach::One`] of
    /// it): their closest planes, then the object behind its own enlarged box, four rays
    /// at a time with the arithmetic, order and ties of [`World::closest_objects`],
    /// which for such rays finds the same hits, bit for bit (the planes win ties, as in
    /// every query). For other rays the hits of other bounded objects are missing.
    ///
    /// # Panics
    ///
    /// When `rays` and `hits` differ in length, or `object` is not a bounded object.
    pub fn closest_hits_with(
        &self,
        object: u32,
        rays: &[Ray],
        t_range: Range<f32>,
        hits: &mut [Option<ObjectHit>],
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit per ray");
        let bounds = self.objects[object as usize]
            .bounds()
            .expect("a bounded object");
        let objects = [(object, enlarged(bounds))];
        self.closest_flat_among(None, &objects, rays, t_range, hits);
    }

    /// The closest hits of rays that meet no bounded object (rays of a box for which
    /// [`World::reach`] answered [`Reach::Planes`] or [`Reach::Nothing`]): their closest
    /// planes, four rays at a time, with the arithmetic, order and ties of
    /// [`World::closest_objects`], which for such rays finds the same hits, bit for bit.
    /// For other rays the hits of bounded objects are missing.
    ///
    /// # Panics
    ///
    /// When `rays` and `hits` differ in length.
    pub fn closest_plane_hits(
        &self,
        rays: &[Ray],
        t_range: Range<f32>,
        hits: &mut [Option<ObjectHit>],
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit per ray");
        let t_min = Vec4::splat(t_range.start);
        for (rays, hits) in rays.chunks(4).zip(hits.chunks_mut(4)) {
            let (lanes, valid) = ray_lanes(rays);
            let mut t_max = Vec4::splat(t_range.end);
            let (found, planes) = self.closest_plane_lanes(&lanes, valid, t_min, &mut t_max);
            let t = t_max.to_array();
            for (lane, hit) in hits.iter_mut().enumerate() {
                // A plane's hit names no face: `object_hit`'s, without its look-up.
                *hit = (found & 1 << lane != 0).then(|| {
                    let raw = plane_hit(t[lane], planes[lane]);
                    ObjectHit {
                        t: raw.t,
                        object: raw.object,
                        primitive: 0,
                        raw,
                    }
                });
            }
        }
    }
}

/// `rays` with each box widened by [`ROUNDING`] of its largest coordinate.
fn widened(rays: &RayBounds) -> RayBounds {
    let widen = |[low, high]: [DVec3; 2]| {
        let margin = ROUNDING * low.abs().max(high.abs()).max_element();
        [low - margin, high + margin]
    };
    RayBounds {
        origin: widen(rays.origin),
        direction: widen(rays.direction),
    }
}

/// The margin of [`World::reach`]'s boxes: [`CLEAR_MARGIN`] of the largest
/// coordinate of the box around every bounded object, `around`, and of the rays'
/// origins, plus one.
fn box_margin(rays: &RayBounds, around: Aabb) -> f64 {
    let size = [
        around.min.as_dvec3(),
        around.max.as_dvec3(),
        rays.origin[0],
        rays.origin[1],
    ]
    .map(|v| v.abs().max_element())
    .into_iter()
    .fold(0.0, f64::max);
    f64::from(CLEAR_MARGIN) * (1.0 + size)
}

/// Whether no ray of `rays` comes within `margin` of `bounds` at any `t >= 0`.
///
/// At `t`, the rays' coordinates on an axis span `[o_low + t d_low, o_high + t d_high]`;
/// some ray may be inside the box only at the times when, on every axis, that span
/// reaches below the box's top and above its bottom. Each condition keeps the times on
/// one side of a bound; when none is left, no ray of the box (nor of the wider set of
/// rays whose coordinates are picked axis by axis) reaches the box.
fn misses_box(rays: &RayBounds, bounds: Aabb, margin: f64) -> bool {
    let (low, high) = (
        bounds.min.as_dvec3() - margin,
        bounds.max.as_dvec3() + margin,
    );
    let mut times = Some((0.0, f64::INFINITY));
    for axis in 0..3 {
        let [origin_low, origin_high] = rays.origin.map(|o| o[axis]);
        let [direction_low, direction_high] = rays.direction.map(|d| d[axis]);
        // Some ray below the top, and (mirrored) some ray above the bottom.
        times = times
            .and_then(|times| at_most(times, origin_low, direction_low, high[axis]))
            .and_then(|times| at_most(times, -origin_high, -direction_high, -low[axis]));
    }
    times.is_none()
}

/// The times of `first..=last` at which `origin + t direction <= limit`, if any.
fn at_most(
    (first, last): (f64, f64),
    origin: f64,
    direction: f64,
    limit: f64,
) -> Option<(f64, f64)> {
    let room = limit - origin;
    let (first, last) = if direction > 0.0 {
        (first, last.min(room / direction))
    } else if direction < 0.0 {
        (first.max(room / direction), last)
    } else if room >= 0.0 {
        (first, last)
    } else {
        return None;
    };
    (first <= last).then_some((first, last))
}

/// Whether every ray of `rays` meets `plane` only behind its origin, or never: the
/// plane's test `t = n.(p - o) / n.d` is negative for each, its numerator and
/// denominator of opposite signs by more than [`PLANE_MARGIN`] of their terms' sizes.
fn misses_plane(rays: &RayBounds, plane: &Plane) -> bool {
    let (n, p) = (plane.normal.as_dvec3(), plane.point.as_dvec3());
    let toward = dot_range(n, rays.direction);
    let from = dot_range(n, rays.origin);
    let at = n.dot(p);
    // `n.(p - o) = n.p - n.o`, least and greatest.
    let ahead = [at - from[1], at - from[0]];
    let largest = |[low, high]: [DVec3; 2]| low.abs().max(high.abs());
    let toward_margin = PLANE_MARGIN * n.abs().dot(largest(rays.direction));
    let ahead_margin = PLANE_MARGIN * n.abs().dot(p.abs() + largest(rays.origin));
    (toward[0] > toward_margin && ahead[1] < -ahead_margin)
        || (toward[1] < -toward_margin && ahead[0] > ahead_margin)
}

/// The least and greatest `n.v` for `v` in the box from `low` to `high`.
fn dot_range(n: DVec3, [low, high]: [DVec3; 2]) -> [f64; 2] {
    let (a, b) = (n * low, n * high);
    [a.min(b).element_sum(), a.max(b).element_sum()]
}

#[cfg(test)]
mod tests {
    use glam::{DVec2, Vec3};

    use super::*;
    use crate::{DRay, Object, Sphere};

    /// A ground plane `y = 0` under two spheres.
    fn ground_and_spheres() -> World {
        World::new(vec![
            Object::Plane(Plane {
                point: Vec3::ZERO,
                normal: Vec3::Y,
            }),
            Object::Sphere(Sphere {
                center: Vec3::new(-1.0, 0.5, -4.0),
                radius: 0.5,
            }),
            Object::Sphere(Sphere {
                center: Vec3::new(1.0, 1.0, -6.0),
                radius: 1.0,
            }),
        ])
        .unwrap()
    }

    /// The rays from the points of the square `origin +- spread` (in x and y) through
    /// the points of `target +- size` (in x and y) at `t = 1`, corners only: their box.
    fn beam(origin: DVec3, spread: f64, target: DVec3, size: f64) -> RayBounds {
        let corners = [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)].map(DVec2::from);
        RayBounds::around(corners.iter().flat_map(|&a| {
            corners.iter().map(move |&b| {
                let o = origin + (a * spread).extend(0.0);
                DRay::new(o, target + (b * size).extend(0.0) - o)
            })
        }))
        .unwrap()
    }

    #[test]
    fn the_sky_meets_nothing_the_open_ground_only_the_plane_a_sphere_itself() {
        let world = ground_and_spheres();
        let eye = DVec3::new(0.0, 0.6, 0.0);
        let reach = |spread, target, size| world.reach(&beam(eye, spread, target, size));
        // Upward, above every sphere, with a pinhole and with a lens.
        assert_eq!(reach(0.0, DVec3::new(0.0, 2.5, -1.0), 0.1), Reach::Nothing);
        assert_eq!(reach(0.3, DVec3::new(0.0, 4.0, -1.0), 0.1), Reach::Nothing);
        // Down to the ground in front of the spheres, and level toward the horizon
        // beside them.
        assert_eq!(reach(0.0, DVec3::new(0.0, -0.5, -1.0), 0.1), Reach::Planes);
        assert_eq!(reach(0.0, DVec3::new(3.0, 0.6, -1.0), 0.01), Reach::Planes);
        // At a sphere (object 1), at the big sphere's top (object 2), and upward from a
        // lens a little wider (still missing the small sphere) to that top.
        assert_eq!(reach(0.0, DVec3::new(-1.0, 0.5, -4.0), 0.01), Reach::One(1));
        assert_eq!(reach(0.0, DVec3::new(1.0, 1.9, -6.0), 0.01), Reach::One(2));
        assert_eq!(reach(0.3, DVec3::new(1.0, 2.2, -6.0), 0.05), Reach::One(2));
        // A lens so wide that its rays may reach both spheres, and a beam over both.
        assert_eq!(reach(1.5, DVec3::new(1.0, 2.5, -6.0), 0.1), Reach::Anything);
        assert_eq!(reach(0.0, DVec3::new(0.0, 0.5, -5.0), 1.5), Reach::Anything);
        // Below the ground looking down: the plane is behind every origin.
        let below = DVec3::new(0.0, -1.0, 0.0);
        let down = beam(below, 0.1, DVec3::new(0.0, -2.0, -1.0), 0.1);
        assert_eq!(world.reach(&down), Reach::Nothing);
    }

    #[test]
    fn a_single_object_rules_out_nothing_and_no_object_only_the_planes() {
        let sphere = Object::Sphere(Sphere {
            center: Vec3::new(0.0, 0.0, -5.0),
            radius: 1.0,
        });
        let ground = Object::Plane(Plane {
            point: Vec3::new(0.0, -1.0, 0.0),
            normal: Vec3::Y,
        });
        let away = beam(DVec3::ZERO, 0.0, DVec3::new(0.0, 0.0, 1.0), 0.1);
        let reach = |objects: Vec<Object>| World::new(objects).unwrap().reach(&away);
        assert_eq!(reach(vec![sphere.clone()]), Reach::Anything);
        assert_eq!(reach(vec![]), Reach::Nothing);
        let down = beam(DVec3::ZERO, 0.0, DVec3::new(0.0, -1.0, 1.0), 0.1);
        assert_eq!(
            World::new(vec![ground]).unwrap().reach(&down),
            Reach::Planes
        );
    }

    /// Numbers from a fixed seed (SplitMix64), uniform in `[low, high)`.
    struct Numbers(u64);

    impl Numbers {
        fn within(&mut self, low: f64, high: f64) -> f64 {
            self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
            let mut z = self.0;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            low + (high - low) * ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        }

        fn vector(&mut self, size: f64) -> DVec3 {
            DVec3::new(
                self.within(-size, size),
                self.within(-size, size),
                self.within(-size, size),
            )
        }
    }

    #[test]
    fn a_box_said_missed_holds_no_ray_that_hits() {
        let mut numbers = Numbers(0x0b0c_5eed);
        let (mut missed, mut planes, mut ones) = (0, 0, 0);
        for _ in 0..4_000 {
            // Spheres and a triangle about the origin, a plane through a random point;
            // beams from near the origin (some grazing the plane) with and without a lens.
            let mut objects: Vec<Object> = (0..numbers.within(2.0, 30.0) as usize)
                .map(|_| {
                    Object::Sphere(Sphere {
                        center: numbers.vector(4.0).as_vec3(),
                        radius: numbers.within(0.05, 0.6) as f32,
                    })
                })
                .collect();
            let [a, b, c] = [0; 3].map(|_| numbers.vector(4.0).as_vec3());
            objects.push(Object::Triangle(crate::Triangle { a, b, c }));
            let normal = numbers.vector(1.0);
            if normal.length() > 0.1 {
                objects.push(Object::Plane(Plane {
                    point: numbers.vector(3.0).as_vec3(),
                    normal: normal.as_vec3(),
                }));
            }
            let world = World::new(objects).unwrap();
            let eye = numbers.vector(6.0);
            let spread = if numbers.within(0.0, 1.0) < 0.5 {
                0.0
            } else {
                numbers.within(0.0, 0.5)
            };
            let mut target = eye + numbers.vector(3.0);
            let mut size = numbers.within(0.001, 0.5);
            if numbers.within(0.0, 1.0) < 0.3 {
                // A thin beam all but parallel to the plane, where rounding decides.
                let n = normal.normalize();
                let along = target - eye;
                target = eye + along - n * n.dot(along) + n * numbers.within(-1e-6, 1e-6);
                size = numbers.within(0.0, 1e-6);
            }
            let reach = world.reach(&beam(eye, spread, target, size));
            match reach {
                Reach::Nothing => missed += 1,
                Reach::Planes => planes += 1,
                Reach::One(_) => ones += 1,
                Reach::Anything => continue,
            }
            let mut rays = Vec::new();
            // The corners' rays and rays inside, as the tracer takes them.
            for k in 0..40 {
                let corner = |numbers: &mut Numbers| {
                    let pick = |numbers: &mut Numbers| match k % 2 {
                        0 => {
                            if numbers.within(0.0, 1.0) < 0.5 {
                                -1.0
                            } else {
                                1.0
                            }
                        }
                        _ => numbers.within(-1.0, 1.0),
                    };
                    DVec2::new(pick(numbers), pick(numbers))
                };
                let o = eye + (corner(&mut numbers) * spread).extend(0.0);
                let to = target + (corner(&mut numbers) * size).extend(0.0);
                rays.push(DRay::new(o, to - o).as_ray());
            }
            // Nothing hit, or the planes' hits alone, as every query finds them.
            let t_range = f32::MIN_POSITIVE..f32::INFINITY;
            let mut hits = vec![None; rays.len()];
            world.closest_objects(&rays, t_range.clone(), &mut hits);
            let mut plane_hits = vec![None; rays.len()];
            match reach {
                Reach::One(object) => {
                    world.closest_hits_with(object, &rays, t_range.clone(), &mut plane_hits);
                }
                _ => world.closest_plane_hits(&rays, t_range.clone(), &mut plane_hits),
            }
            for ((ray, hit), plane_hit) in rays.iter().zip(&hits).zip(&plane_hits) {
                let alone = world.closest_object(ray, t_range.clone());
                let bits = |h: &Option<ObjectHit>| h.map(|h| (h.t.to_bits(), h.object));
                assert_eq!(bits(hit), bits(&alone), "{ray:?}");
                assert_eq!(bits(hit), bits(plane_hit), "{ray:?}: {reach:?}");
                if reach == Reach::Nothing {
                    assert!(
                        hit.is_none(),
                        "{ray:?} hits {hit:?} in a box said to meet nothing"
                    );
                }
            }
        }
        // Every answer is common: the test checks many boxes of each.
        assert!(
            missed > 400 && planes > 400 && ones > 400,
            "{missed} missed, {planes} planes, {ones} one object"
        );
    }
}
