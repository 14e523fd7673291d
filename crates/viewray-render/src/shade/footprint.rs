//! The part of a surface one sample stands for: where the sample's neighbours on the
//! film land on the hit's tangent plane, from the pixel's ray differentials. Grid lines
//! are averaged over it.

use std::cell::OnceCell;

use glam::{DVec2, Vec3, Vec4};
use viewray_geometry::{Hit, Ray};

use super::Shader;

/// A point on the film: the continuous image point of a primary ray, kept so grid lines
/// can be filtered over the sample's footprint.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FilmPoint<'a> {
    /// The pixel's centre `(col + 1/2, row + 1/2)`.
    pub(crate) pixel_center: DVec2,
    /// The side of the square of film this sample stands for, in pixels
    /// (`1 / sqrt(samples)`).
    pub(crate) spacing: f64,
    /// The pixel's ray differentials, worked out by the first sample that needs them.
    pub(crate) differentials: &'a OnceCell<Option<RayDifferentials>>,
}

/// How a viewing ray changes when its film point moves by one sample spacing along the
/// image's x and y: the origin and direction differences of neighbouring rays (pbrt's
/// ray differentials), taken through the lens centre. For every planar projection,
/// thin lenses included, they do not depend on the lens point; for panoramic ones they
/// vary slowly across a pixel, so one set per pixel serves all its samples.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RayDifferentials {
    origin_dx: Vec3,
    direction_dx: Vec3,
    origin_dy: Vec3,
    direction_dy: Vec3,
}

/// The part of a surface one sample stands for, over which grid lines are averaged.
#[derive(Clone, Copy, Debug)]
pub(super) enum Footprint {
    /// A point: no averaging (reflected rays, whose footprint is not tracked).
    Point,
    /// The parallelogram spanned by two world-space vectors.
    Area(Vec3, Vec3),
    /// Larger than anything: the lines' average.
    Unbounded,
}

impl Shader<'_> {
    /// Where the film sample's neighbours (one sample spacing along the image's x and y)
    /// land on the hit's tangent plane, as in ray differentials; unbounded where a
    /// neighbouring ray misses the plane (toward the horizon) or does not exist.
    ///
    /// Always inlined: the trace's copies of the shading code (see `record`) are more
    /// callers, and with them the compiler stopped inlining it into the render's (3% more
    /// instructions in the default scene's render).
    #[inline(always)]
    pub(super) fn footprint(&self, film: &FilmPoint<'_>, ray: &Ray, hit: &Hit) -> Footprint {
        let differentials = film
            .differentials
            .get_or_init(|| self.differentials(film.pixel_center, film.spacing));
        let Some(differentials) = differentials else {
            return Footprint::Unbounded;
        };
        // The two neighbours' rays and where each meets the tangent plane, `t = n.(p -
        // o) / n.d`: both quotients in one division (each lane rounds as alone).
        let origin_x = ray.origin + differentials.origin_dx;
        let direction_x = ray.direction + differentials.direction_dx;
        let origin_y = ray.origin + differentials.origin_dy;
        let direction_y = ray.direction + differentials.direction_dy;
        let (n, p) = (hit.normal, hit.point);
        let t = Vec4::new(n.dot(p - origin_x), n.dot(p - origin_y), 0.0, 0.0)
            / Vec4::new(n.dot(direction_x), n.dot(direction_y), 1.0, 1.0);
        // Positive and finite (a NaN is neither).
        let (tx, ty) = (t.x, t.y);
        if tx > 0.0 && tx < f32::INFINITY && ty > 0.0 && ty < f32::INFINITY {
            Footprint::Area(
                origin_x + tx * direction_x - p,
                origin_y + ty * direction_y - p,
            )
        } else {
            Footprint::Unbounded
        }
    }

    /// The ray differentials at the image point `center` for a step of `spacing` pixels,
    /// or `None` where a neighbouring ray does not exist (outside a fisheye's circle).
    fn differentials(&self, center: DVec2, spacing: f64) -> Option<RayDifferentials> {
        let differential =
            self.camera
                .generate_ray_differential(center, DVec2::splat(0.5), spacing)?;
        let [c, x, y] = [differential.ray, differential.rx, differential.ry].map(|r| r.as_ray());
        Some(RayDifferentials {
            origin_dx: x.origin - c.origin,
            direction_dx: x.direction - c.direction,
            origin_dy: y.origin - c.origin,
            direction_dy: y.direction - c.direction,
        })
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use viewray_scene::Scene;

    use super::*;
    use crate::View;
    use crate::shade::DepthMap;
    use crate::shade::primary::T_MIN;

    /// A scene of one ground plane `y = 0` seen by `camera` (a RON camera), 40 x 30.
    fn ground(camera: &str) -> Scene {
        let text = format!(
            "(image: (width: 40, height: 30), camera: {camera}, shading: Lit,
              materials: {{ \"ground\": (color: (0.5, 0.5, 0.5),
                              grid: (spacing: 1.0, width: 0.1, color: (0.0, 0.0, 0.0))) }},
              objects: [Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 1.0, 0.0), material: \"ground\")])"
        );
        viewray_scene::SceneLoader::text(&text, std::path::Path::new("ground.ron"))
            .load()
            .unwrap()
            .scene
    }

    /// The footprint the shader gives the sample through the centre of `pixel` for
    /// neighbours `spacing` pixels away, and the one worked out in f64: where the
    /// neighbouring rays (through the lens centre) meet the hit's tangent plane, minus the
    /// hit point, or `None` where one does not meet it ahead of its origin.
    fn footprints(scene: &Scene, pixel: DVec2, spacing: f64) -> (Footprint, Option<[DVec3; 2]>) {
        let view = View::of(scene);
        let camera = &view.camera;
        let shader = Shader::new(scene, &view, 4, DepthMap::new(camera));
        let center = DVec2::splat(0.5);
        let ray = camera.generate_ray_through(pixel, center).unwrap().as_ray();
        let world = scene.world();
        let hit = world.surface(
            &ray,
            &world.closest_object(&ray, T_MIN..f32::INFINITY).unwrap(),
        );
        let differentials = OnceCell::new();
        let film = FilmPoint {
            pixel_center: pixel,
            spacing,
            differentials: &differentials,
        };
        let got = shader.footprint(&film, &ray, &hit);
        let (p, n) = (hit.point.as_dvec3(), hit.normal.as_dvec3());
        let on_plane = |offset: DVec2| {
            let r = camera
                .generate_ray_through(pixel + offset * spacing, center)
                .unwrap();
            let t = n.dot(p - r.origin) / n.dot(r.direction);
            (t > 0.0 && t.is_finite()).then(|| r.origin + t * r.direction - p)
        };
        let expected = on_plane(DVec2::X)
            .zip(on_plane(DVec2::Y))
            .map(|(dx, dy)| [dx, dy]);
        (got, expected)
    }

    #[track_caller]
    fn check_area(got: Footprint, expected: Option<[DVec3; 2]>) {
        let [ex, ey] = expected.expect("both neighbours meet the plane");
        let Footprint::Area(dx, dy) = got else {
            panic!("{got:?}, expected the area {ex} x {ey}");
        };
        for (got, expected) in [(dx, ex), (dy, ey)] {
            assert!(
                got.as_dvec3()
                    .abs_diff_eq(expected, 1e-4 * expected.length()),
                "{got} != {expected}"
            );
            assert!(expected.length() > 1e-3, "a footprint that says something");
        }
    }

    #[test]
    fn footprints_are_where_the_neighbouring_rays_meet_the_tangent_plane() {
        // A perspective camera looking down at the ground: the neighbours' directions
        // differ, their origin is the eye.
        let tilted = ground(
            "(eye: (0.5, 3.0, 4.0), view: (0.1, -1.0, -1.2), up: (0.0, 1.0, 0.0),
              projection: Perspective(fov_y: 50.0))",
        );
        for (pixel, spacing) in [((20.5, 15.5), 1.0), ((7.5, 26.5), 0.25), ((33.0, 4.0), 0.5)] {
            let (got, expected) = footprints(&tilted, DVec2::from(pixel), spacing);
            check_area(got, expected);
        }
        // An orthographic one: the neighbours' origins differ, their direction is the same.
        let parallel = ground(
            "(eye: (0.0, 5.0, 3.0), view: (0.2, -1.0, -0.7), up: (0.0, 1.0, 0.0),
              projection: Orthographic(viewport: (8.0, 6.0)))",
        );
        for (pixel, spacing) in [((20.5, 15.5), 1.0), ((3.5, 2.5), 0.5)] {
            let (got, expected) = footprints(&parallel, DVec2::from(pixel), spacing);
            check_area(got, expected);
        }
    }

    #[test]
    fn footprints_are_unbounded_where_a_neighbour_misses_the_plane() {
        // Level and upside down: image rows run up the world, the horizon at row 15.
        let level = ground(
            "(eye: (0.0, 1.0, 0.0), view: (0.0, 0.0, -1.0), up: (0.0, -1.0, 0.0),
              projection: Perspective(fov_y: 60.0))",
        );
        // Half a pixel below the horizon: the neighbour a pixel up looks above it.
        let (got, expected) = footprints(&level, DVec2::new(20.5, 14.5), 1.0);
        assert!(expected.is_none());
        assert!(matches!(got, Footprint::Unbounded), "{got:?}");
        // Half a pixel up, the neighbour looks along the horizon: parallel to the
        // plane, it meets it at infinity.
        let (got, expected) = footprints(&level, DVec2::new(20.5, 14.5), 0.5);
        assert!(expected.is_none());
        assert!(matches!(got, Footprint::Unbounded), "{got:?}");
        // A whole pixel below the horizon, a pixel up still meets the plane.
        let (got, expected) = footprints(&level, DVec2::new(20.5, 13.5), 1.0);
        check_area(got, expected);
        // From below the ground, upright, looking along +z: the neighbour half a pixel
        // down looks along the horizon, and with every product of its `n.d` a negative
        // zero (left of centre its x is positive) it meets the plane at t = +infinity,
        // which is no footprint either.
        let below = ground(
            "(eye: (0.0, -1.0, 0.0), view: (0.0, 0.0, 1.0), up: (0.0, 1.0, 0.0),
              projection: Perspective(fov_y: 60.0))",
        );
        let (got, expected) = footprints(&below, DVec2::new(10.5, 14.5), 0.5);
        assert!(expected.is_none());
        assert!(matches!(got, Footprint::Unbounded), "{got:?}");
        // The same turned a quarter (image x runs down the world, the horizon is column
        // 20): now the neighbour along x meets the plane at t = +infinity.
        let turned = ground(
            "(eye: (0.0, -1.0, 0.0), view: (0.0, 0.0, 1.0), up: (-1.0, 0.0, 0.0),
              projection: Perspective(fov_y: 60.0))",
        );
        let (got, expected) = footprints(&turned, DVec2::new(19.5, 20.5), 0.5);
        assert!(expected.is_none());
        assert!(matches!(got, Footprint::Unbounded), "{got:?}");
    }
}
