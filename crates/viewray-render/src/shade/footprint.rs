//! The part of a surface one sample stands for: where the sample's neighbours on the
//! film land on the hit's tangent plane, from the pixel's ray differentials. Grid lines
//! are averaged over it.

use std::cell::OnceCell;

use glam::{DVec2, Vec3, Vec4};
use viewray_geometry::{Hit, Ray};

use super::Shader;
use crate::lanes::{self, Vec3x4};

/// A point on the film: the pixel of a primary ray's sample, kept so grid lines can be
/// filtered over the sample's footprint.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FilmPoint<'a> {
    /// The sample's pixel.
    pub(crate) pixel: &'a FilmPixel,
    /// The side of the square of film this sample stands for, in pixels
    /// (`1 / sqrt(samples)`).
    pub(crate) spacing: f64,
}

/// A pixel as its samples' footprints see it: its centre, set when its tile starts (a
/// sample's film point was worked out from its place in the tile, an integer division
/// for every sample with grid lines, though only the pixel's first one needs it), and
/// its ray differentials, worked out by the first sample that needs them.
#[derive(Debug)]
pub(crate) struct FilmPixel {
    /// The pixel's centre `(col + 1/2, row + 1/2)`.
    pub(crate) center: DVec2,
    /// The pixel's ray differentials, once asked for.
    pub(crate) differentials: OnceCell<Option<RayDifferentials>>,
}

impl FilmPixel {
    /// The pixel whose centre is `center`, its differentials not yet worked out.
    pub(crate) fn new(center: DVec2) -> Self {
        Self {
            center,
            differentials: OnceCell::new(),
        }
    }
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

impl RayDifferentials {
    /// No change: what lanes without differentials hold.
    const ZERO: Self = Self {
        origin_dx: Vec3::ZERO,
        direction_dx: Vec3::ZERO,
        origin_dy: Vec3::ZERO,
        direction_dy: Vec3::ZERO,
    };

    /// Where the neighbours of the sample along `ray` land on the tangent plane of its
    /// hit `hit`: the area between them, or unbounded where one of them misses the plane.
    #[inline(always)]
    fn footprint(&self, ray: &Ray, hit: &Hit) -> Footprint {
        // The two neighbours' rays and where each meets the tangent plane, `t = n.(p -
        // o) / n.d`: both quotients in one division (each lane rounds as alone).
        let origin_x = ray.origin + self.origin_dx;
        let direction_x = ray.direction + self.direction_dx;
        let origin_y = ray.origin + self.origin_dy;
        let direction_y = ray.direction + self.direction_dy;
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

    /// [`RayDifferentials::footprint`] then [`Footprint::widths`] for four samples, lane
    /// `j` with the differentials `differentials[j]`, or unbounded where bit `j` of
    /// `bounded` is clear. Every operation is the scalar one lane by lane, in the same
    /// order (the same sums, products, quotients and comparisons, no fused
    /// multiply-add), so each lane holds the bits its sample's scalar footprint gives.
    #[inline(always)]
    fn widths(differentials: [&Self; 4], bounded: u32, rays: &RaysX4) -> Vec3x4 {
        let gather = |field: fn(&Self) -> &Vec3| Vec3x4::gather(differentials.map(field));
        let origin_x = rays.origin + gather(|d| &d.origin_dx);
        let direction_x = rays.direction + gather(|d| &d.direction_dx);
        let origin_y = rays.origin + gather(|d| &d.origin_dy);
        let direction_y = rays.direction + gather(|d| &d.direction_dy);
        let (n, p) = (rays.normal, rays.point);
        let tx = n.dot(p - origin_x) / n.dot(direction_x);
        let ty = n.dot(p - origin_y) / n.dot(direction_y);
        let infinity = Vec4::splat(f32::INFINITY);
        let area = lanes::mask(bounded)
            & tx.cmpgt(Vec4::ZERO)
            & tx.cmplt(infinity)
            & ty.cmpgt(Vec4::ZERO)
            & ty.cmplt(infinity);
        let dx = origin_x + direction_x * tx - p;
        let dy = origin_y + direction_y * ty - p;
        let widths = abs(dx) + abs(dy);
        Vec3x4::select(area, widths, Vec3x4::splat(Vec3::INFINITY))
    }
}

/// Four samples' viewing rays and their hits, side by side, for their footprints.
pub(super) struct RaysX4 {
    /// The rays' origins and directions.
    pub(super) origin: Vec3x4,
    pub(super) direction: Vec3x4,
    /// The hit points and the geometric normals there.
    pub(super) point: Vec3x4,
    pub(super) normal: Vec3x4,
}

/// Lane by lane, [`Vec3::abs`].
#[inline(always)]
fn abs(v: Vec3x4) -> Vec3x4 {
    Vec3x4 {
        x: v.x.abs(),
        y: v.y.abs(),
        z: v.z.abs(),
    }
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

impl Footprint {
    /// How far the footprint reaches along each world axis, the widths over which grid
    /// lines are averaged: `|dx| + |dy|` for the area spanned by `dx` and `dy`, zero for
    /// a point, infinite where unbounded.
    #[inline]
    pub(super) fn widths(self) -> Vec3 {
        match self {
            Footprint::Point => Vec3::ZERO,
            Footprint::Area(dx, dy) => dx.abs() + dy.abs(),
            Footprint::Unbounded => Vec3::INFINITY,
        }
    }
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
        match self.film_differentials(*film) {
            Some(differentials) => differentials.footprint(ray, hit),
            None => Footprint::Unbounded,
        }
    }

    /// [`Shader::footprint`]'s widths ([`Footprint::widths`]) of four samples at once,
    /// lane `j` for sample `j` (its film point `film(j)`, its viewing ray and hit in
    /// lane `j` of `rays`): see [`RayDifferentials::widths`]. Only the lanes of `lanes` are worked out, their
    /// pixels' differentials computed if no sample asked for them before; the others
    /// hold anything.
    #[inline(always)]
    pub(super) fn footprint_widths<'f>(
        &self,
        film: impl Fn(usize) -> FilmPoint<'f>,
        lanes: u32,
        rays: &RaysX4,
    ) -> Vec3x4 {
        let mut bounded = 0;
        let differentials: [&RayDifferentials; 4] = std::array::from_fn(|j| {
            if lanes & 1 << j == 0 {
                return &RayDifferentials::ZERO;
            }
            match self.film_differentials(film(j)) {
                Some(differentials) => {
                    bounded |= 1 << j;
                    differentials
                }
                None => &RayDifferentials::ZERO,
            }
        });
        RayDifferentials::widths(differentials, bounded, rays)
    }

    /// The differentials of `film`'s pixel, worked out by the first sample that asks.
    #[inline(always)]
    fn film_differentials<'f>(&self, film: FilmPoint<'f>) -> &'f Option<RayDifferentials> {
        let FilmPoint { pixel, spacing } = film;
        pixel
            .differentials
            .get_or_init(|| self.differentials(pixel.center, spacing))
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

    use crate::test_numbers::Numbers;

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
        let film_pixel = FilmPixel::new(pixel);
        let film = FilmPoint {
            pixel: &film_pixel,
            spacing,
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

    /// Four samples at once, with differentials small and large, neighbours that meet
    /// the tangent plane and neighbours that run parallel to it or away from it, and
    /// lanes without differentials: each lane holds the bits of the scalar footprint's
    /// widths.
    #[test]
    fn four_lanes_of_footprint_widths_are_the_scalar_ones_bit_for_bit() {
        let mut numbers = Numbers(0xf00d_0f00);
        let mut kinds = [0; 3];
        for _ in 0..100_000 {
            let bounded = (0..4).fold(0, |bits, j| bits | u32::from(numbers.uniform() < 0.9) << j);
            let lanes: [(RayDifferentials, Ray, Hit); 4] = std::array::from_fn(|_| {
                let scale = 10.0_f32.powf(4.0 * numbers.uniform() - 3.0);
                let origin = numbers.vector() * 10.0;
                let direction = numbers.vector().normalize_or(Vec3::Z);
                let t = 0.1 + 20.0 * numbers.uniform();
                let normal = numbers.vector().normalize_or(Vec3::Y);
                let mut differentials = RayDifferentials {
                    origin_dx: numbers.vector() * scale,
                    direction_dx: numbers.vector() * scale,
                    origin_dy: numbers.vector() * scale,
                    direction_dy: numbers.vector() * scale,
                };
                let mut hit = Hit {
                    t,
                    point: origin + t * direction,
                    normal: -normal * normal.dot(direction).signum(),
                    ..Hit::default()
                };
                if numbers.uniform() < 0.1 {
                    // A neighbour parallel to the plane `y = c`: `n.d` is zero.
                    hit.normal = Vec3::Y;
                    differentials.direction_dx.y = -direction.y;
                }
                (differentials, Ray::new(origin, direction), hit)
            });
            let rays = RaysX4 {
                origin: Vec3x4::gather(lanes.each_ref().map(|(_, ray, _)| &ray.origin)),
                direction: Vec3x4::gather(lanes.each_ref().map(|(_, ray, _)| &ray.direction)),
                point: Vec3x4::gather(lanes.each_ref().map(|(_, _, hit)| &hit.point)),
                normal: Vec3x4::gather(lanes.each_ref().map(|(_, _, hit)| &hit.normal)),
            };
            let got = RayDifferentials::widths(lanes.each_ref().map(|(d, _, _)| d), bounded, &rays);
            for (j, (differentials, ray, hit)) in lanes.iter().enumerate() {
                let footprint = if bounded & 1 << j != 0 {
                    differentials.footprint(ray, hit)
                } else {
                    Footprint::Unbounded
                };
                kinds[match footprint {
                    Footprint::Area(..) => 0,
                    _ if bounded & 1 << j != 0 => 1,
                    _ => 2,
                }] += 1;
                assert_eq!(
                    got.lane(j).to_array().map(f32::to_bits),
                    footprint.widths().to_array().map(f32::to_bits),
                    "lane {j}: {differentials:?} {ray:?} {hit:?}"
                );
            }
        }
        assert!(kinds.iter().all(|&n| n > 1000), "{kinds:?}");
    }

    /// Through the shader: four samples' film points, some sharing a pixel, some whose
    /// neighbours miss the ground, give the widths of [`Shader::footprint`], and the
    /// differentials of lanes left out are not worked out.
    #[test]
    fn footprint_widths_through_the_shader_are_the_footprints_widths() {
        // Level and upside down, as above: rows below 15 see the ground.
        let scene = ground(
            "(eye: (0.0, 1.0, 0.0), view: (0.0, 0.0, -1.0), up: (0.0, -1.0, 0.0),
              projection: Perspective(fov_y: 60.0))",
        );
        let view = View::of(&scene);
        let camera = &view.camera;
        let shader = Shader::new(&scene, &view, 4, DepthMap::new(camera));
        let world = scene.world();
        let pixels: Vec<FilmPixel> = (0..40 * 30)
            .map(|i| FilmPixel::new(DVec2::new(f64::from(i % 40), f64::from(i / 40)) + 0.5))
            .collect();
        let film = |pixel: (u32, u32), spacing: f64| FilmPoint {
            pixel: &pixels[(pixel.1 * 40 + pixel.0) as usize],
            spacing,
        };
        // Samples from the bottom row to half a pixel below the horizon (whose
        // neighbour a pixel up misses the ground), two in one pixel.
        let samples = [
            ((20, 0), (0.25, 0.75)),
            ((3, 6), (0.5, 0.5)),
            ((3, 6), (0.9, 0.1)),
            ((37, 14), (0.5, 0.5)),
        ];
        let lanes = samples.map(|(pixel, offset)| {
            let ray = camera
                .generate_ray_through(
                    DVec2::new(f64::from(pixel.0), f64::from(pixel.1)) + DVec2::from(offset),
                    DVec2::splat(0.5),
                )
                .unwrap()
                .as_ray();
            let hit = world.surface(
                &ray,
                &world.closest_object(&ray, T_MIN..f32::INFINITY).unwrap(),
            );
            (pixel, ray, hit)
        });
        let rays = RaysX4 {
            origin: Vec3x4::gather(lanes.each_ref().map(|(_, ray, _)| &ray.origin)),
            direction: Vec3x4::gather(lanes.each_ref().map(|(_, ray, _)| &ray.direction)),
            point: Vec3x4::gather(lanes.each_ref().map(|(_, _, hit)| &hit.point)),
            normal: Vec3x4::gather(lanes.each_ref().map(|(_, _, hit)| &hit.normal)),
        };
        // Lane 0 left out: its pixel's differentials stay unknown.
        let got = shader.footprint_widths(|j| film(lanes[j].0, 1.0), 0b1110, &rays);
        assert!(pixels[20].differentials.get().is_none());
        let mut unbounded = 0;
        for (j, (pixel, ray, hit)) in lanes.iter().enumerate().skip(1) {
            let expected = shader.footprint(&film(*pixel, 1.0), ray, hit).widths();
            unbounded += usize::from(expected == Vec3::INFINITY);
            assert_eq!(
                got.lane(j).to_array().map(f32::to_bits),
                expected.to_array().map(f32::to_bits),
                "lane {j}"
            );
        }
        assert_eq!(unbounded, 1, "one sample's neighbour misses the ground");
    }
}
