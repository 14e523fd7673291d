//! What a ray sees: the four shading modes, grid lines, lights, shadows and mirrors.

use std::cell::OnceCell;

use glam::{DVec2, Vec3, Vec4};
use viewray_camera::{Camera, Projection};
use viewray_geometry::{Hit, Object, ObjectHit, Ray, World};
use viewray_output::linear_to_srgb;
use viewray_scene::{Grid, Light, Material, Scene, Shading};

use crate::View;
use crate::lanes::{self, Vec3x4};

/// Where primary rays start their search: `t > 0`, as the camera contract says.
const T_MIN: f32 = f32::MIN_POSITIVE;

/// How far a secondary ray's origin is moved off the surface: this much times
/// `1 + max |coordinate|` of the hit point ...
const OFFSET_SCALE: f32 = 1e-4;

/// ... plus this much times the distance the ray travelled to the hit.
///
/// A single-precision hit point is off by a few ulps (about 1e-7 relative) of its
/// coordinates and of the distance travelled; these margins clear that by a factor of a
/// hundred or more (no shadow acne) while staying far below anything visible at a
/// scene's scale (no shadows detached from their objects).
const OFFSET_PER_DISTANCE: f32 = 1e-5;

/// The headlight used when a [`Shading::Lit`] scene has no lights at all: the share of
/// the surface colour every lit point gets regardless of its orientation.
pub(crate) const HEADLIGHT_AMBIENT: f32 = 0.15;

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

/// The rule that turns hit points into [`Shading::Depth`] values.
///
/// ```text
/// z = (p - e) . (-W)      planar projections: distance from the eye's plane along -w
/// z = |p - e|             panoramic projections (no single view direction)
/// s = (z - near) / (far - near)
/// value = 1 - 0.9 s       for s <= 1 (near white, far 0.1 so it stays apart from a
///                         black background)
/// value = 0.1 / s         beyond far (only infinite planes get there): fading to 0 at
///                         the horizon, still decreasing
/// ```
///
/// `near` and `far` come from a pre-pass of one centre ray per pixel (see
/// [`DepthMap::range_of`]), so the rule is the same whatever the threads and tiles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DepthMap {
    eye: Vec3,
    forward: Vec3,
    panoramic: bool,
    near: f32,
    far: f32,
}

impl DepthMap {
    /// The map of `camera` with the range still unknown.
    pub(crate) fn new(camera: &Camera) -> Self {
        let frame = camera.frame();
        Self {
            eye: frame.e.as_vec3(),
            forward: (-frame.w).as_vec3(),
            panoramic: matches!(
                camera.projection(),
                Projection::Equirectangular | Projection::Fisheye(_)
            ),
            near: 0.0,
            far: 0.0,
        }
    }

    /// `z` of the point `p`.
    #[inline]
    pub(crate) fn z(&self, p: Vec3) -> f32 {
        if self.panoramic {
            (p - self.eye).length()
        } else {
            (p - self.eye).dot(self.forward)
        }
    }

    /// The map with `near` and `far` from the depths of the pre-pass: `near` the
    /// smallest `z` of any hit, `far` the largest `z` of a hit on a bounded object (not
    /// an infinite plane), or of any hit if only planes were hit.
    pub(crate) fn with_range(self, range: DepthRange) -> Self {
        let far = if range.far_bounded >= range.near {
            range.far_bounded
        } else {
            range.far_any
        };
        Self {
            near: range.near,
            far,
            ..self
        }
    }

    /// The depth value of `p`, in `(0, 1]`.
    #[inline]
    pub(crate) fn value(&self, p: Vec3) -> f32 {
        let extent = self.far - self.near;
        if !extent.is_finite() || extent <= 0.0 {
            return 1.0;
        }
        let s = ((self.z(p) - self.near) / extent).max(0.0);
        if s <= 1.0 { 1.0 - 0.9 * s } else { 0.1 / s }
    }
}

/// The depths seen by the pre-pass. Combining ranges takes minima and maxima, which
/// give the same result in any order.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DepthRange {
    pub(crate) near: f32,
    pub(crate) far_bounded: f32,
    pub(crate) far_any: f32,
}

impl DepthRange {
    /// No depths yet.
    pub(crate) const EMPTY: DepthRange = DepthRange {
        near: f32::INFINITY,
        far_bounded: f32::NEG_INFINITY,
        far_any: f32::NEG_INFINITY,
    };

    /// Both ranges together.
    pub(crate) fn union(self, other: DepthRange) -> DepthRange {
        DepthRange {
            near: self.near.min(other.near),
            far_bounded: self.far_bounded.max(other.far_bounded),
            far_any: self.far_any.max(other.far_any),
        }
    }
}

/// Everything shading needs, shared read-only by every tile.
pub(crate) struct Shader<'a> {
    scene: &'a Scene,
    /// The camera (for ray differentials) and the shading, which may not be the scene's.
    camera: &'a Camera,
    shading: Shading,
    max_depth: u32,
    depth_map: DepthMap,
    /// The background as stored in the image: the colour itself for colour images,
    /// its sRGB encoding for data images (so it looks the same in a PNG).
    background: Vec3,
}

impl<'a> Shader<'a> {
    pub(crate) fn new(
        scene: &'a Scene,
        view: &'a View,
        max_depth: u32,
        depth_map: DepthMap,
    ) -> Self {
        let background = match view.shading {
            Shading::Flat | Shading::Lit => scene.background(),
            Shading::Normals | Shading::Depth => scene.background().map(linear_to_srgb),
        };
        Self {
            scene,
            camera: &view.camera,
            shading: view.shading,
            max_depth,
            depth_map,
            background,
        }
    }

    /// Whether [`Shader::shade_primaries`] may ask for film points: Lit shading always,
    /// Flat shading where a material has grid lines, the data images never.
    pub(crate) fn uses_film_points(&self) -> bool {
        match self.shading {
            Shading::Lit => true,
            Shading::Flat => self.scene.materials().iter().any(|m| m.grid.is_some()),
            Shading::Normals | Shading::Depth => false,
        }
    }

    /// The value stored where a ray hits nothing (or where a camera has no ray).
    #[inline]
    pub(crate) fn background(&self) -> Vec3 {
        self.background
    }

    /// The closest hits of viewing rays, traced together: `hits[i]` for `rays[i]`.
    #[inline]
    pub(crate) fn trace_primary(&self, rays: &[Ray], hits: &mut [Option<ObjectHit>]) {
        self.scene
            .world()
            .closest_objects(rays, T_MIN..f32::INFINITY, hits);
    }

    /// The values of what the viewing rays `rays` see, given their closest hits (from
    /// [`Shader::trace_primary`]): `emit(i, value)` once for each ray, in no particular
    /// order (straight into the caller's sums: a buffer of colours in between was
    /// written and read back once per ray); `film(i)` is the film point of
    /// `rays[i]`, asked for only where a grid is filtered over the sample's footprint.
    /// Lit shading traces the batch's shadow rays toward each light together, and its
    /// reflected rays together, as packets (see [`Shader::lit_batch`]).
    pub(crate) fn shade_primaries<'f>(
        &self,
        rays: &[Ray],
        hits: &[Option<ObjectHit>],
        film: impl Fn(usize) -> FilmPoint<'f>,
        scratch: &mut LitScratch,
        mut emit: impl FnMut(usize, Vec3),
        count: &mut u64,
    ) {
        *count += rays.len() as u64;
        let world = &self.scene.world();
        if self.shading == Shading::Lit {
            // Shade the hits together; the misses see the background.
            let LitScratch {
                rays: hit_rays,
                surfaces,
                samples,
                colors: lit,
                buffers,
            } = scratch;
            hit_rays.clear();
            surfaces.clear();
            samples.clear();
            for (i, (ray, hit)) in rays.iter().zip(hits).enumerate() {
                match hit {
                    Some(hit) => {
                        push_hit(world, ray, hit, hit_rays, surfaces);
                        samples.push(i);
                    }
                    None => emit(i, self.background),
                }
            }
            lit.clear();
            lit.resize(hit_rays.len(), Vec3::ZERO);
            let film_of = |k: usize| film(samples[k]);
            self.lit_batch(hit_rays, surfaces, Some(&film_of), 0, buffers, lit, count);
            for (&i, &color) in samples.iter().zip(lit.iter()) {
                emit(i, color);
            }
            return;
        }
        for (i, (ray, hit)) in rays.iter().zip(hits).enumerate() {
            let Some(object_hit) = hit else {
                emit(i, self.background);
                continue;
            };
            let color = match self.shading {
                Shading::Flat => {
                    // A plain colour needs no surface details.
                    let material = self.material(object_hit.object, object_hit.primitive);
                    if material.grid.is_none() {
                        material.color
                    } else {
                        let hit = world.surface(ray, object_hit);
                        surface_color(material, &hit, || self.footprint(&film(i), ray, &hit))
                    }
                }
                Shading::Normals => world.surface(ray, object_hit).shading_normal * 0.5 + 0.5,
                // Every shape's hit point is `ray.at(t)`, as in the depth pre-pass.
                Shading::Depth => Vec3::splat(self.depth_map.value(ray.at(object_hit.t))),
                Shading::Lit => unreachable!("lit samples are shaded in a batch above"),
            };
            emit(i, color);
        }
    }

    /// The material of face `primitive` of object `object`.
    #[inline]
    fn material(&self, object: u32, primitive: u32) -> &Material {
        self.scene.material_of(object, primitive)
    }

    /// Blinn-Phong with every light, hard shadows and mirror reflection, for the hits
    /// `hits` of `rays` at mirror bounce `depth` (with their film points for primary
    /// rays, whose grid lines are filtered), into `colors`; see the crate's
    /// documentation for the formulas.
    ///
    /// The batch's shadow rays toward each light are traced together
    /// ([`World::any_hits`](viewray_geometry::World::any_hits)), and so are its
    /// reflected rays, whose hits are then shaded as a batch one bounce deeper. The
    /// lighting is worked out four samples at a time ([`Vec3x4`]), light by light;
    /// each sample's colour is summed in the same order and with the same numbers as
    /// one sample shaded alone, so neither the batch nor the lanes change a pixel.
    #[allow(clippy::too_many_arguments)]
    fn lit_batch<'f, F: Fn(usize) -> FilmPoint<'f>>(
        &self,
        rays: &[Ray],
        hits: &[Hit],
        film: Option<&F>,
        depth: u32,
        buffers: &mut LitBuffers,
        colors: &mut [Vec3],
        count: &mut u64,
    ) {
        let world = &self.scene.world();
        let lights = self.scene.lights();
        let n = rays.len();
        let LitBuffers {
            bases,
            groups,
            mirror,
            shadow_rays,
            shadow_samples,
            answers,
            toward,
            mirrors,
            reflected,
            mirror_rays,
            mirror_hits,
            next_rays,
            next_hits,
            next_colors,
            deeper,
        } = buffers;

        // Each sample's surface colour, one by one (grid lines branch).
        mirror.clear();
        bases.clear();
        for (i, (ray, hit)) in rays.iter().zip(hits).enumerate() {
            let material = self.scene.material(hit);
            bases.push(surface_color(material, hit, || {
                film.map_or(Footprint::Point, |f| self.footprint(&f(i), ray, hit))
            }));
            mirror.push(material.mirror);
        }
        // Then, four at a time, where its secondary rays start and the view direction.
        // Every vector is gathered from where it lies (see `Vec3x4::gather`), and the
        // surface colours long after they were written: through small arrays filled
        // just before, the gathering took about a tenth of the render's time.
        // Each group is written in its slot: pushed, it was built on the stack and copied
        // (a call to memmove that read back stores still on their way).
        groups.resize(n.div_ceil(4), LitGroup::EMPTY);
        for (g, group) in groups.iter_mut().enumerate() {
            // Spare lanes repeat the last sample; no light adds to them.
            let len = (n - 4 * g).min(4);
            let i = [0, 1, 2, 3].map(|j| 4 * g + j.min(len - 1));
            let hit = i.map(|i| &hits[i]);
            let material = hit.map(|hit| self.scene.material(hit));
            let direction = Vec3x4::gather(i.map(|i| &rays[i].direction));
            let point = Vec3x4::gather(hit.map(|hit| &hit.point));
            let normal = Vec3x4::gather(hit.map(|hit| &hit.normal));
            let t = Vec4::new(hit[0].t, hit[1].t, hit[2].t, hit[3].t);
            let specular_lanes = (0..len)
                .filter(|&j| material[j].specular != Vec3::ZERO)
                .fold(0, |lanes, j| lanes | 1 << j);
            *group = LitGroup {
                lanes: (1 << len) - 1,
                base: Vec3x4::gather(i.map(|i| &bases[i])),
                specular: Vec3x4::gather(material.map(|m| &m.specular)),
                shininess: material.map(|m| m.shininess),
                specular_lanes,
                normal,
                shading_normal: Vec3x4::gather(hit.map(|hit| &hit.shading_normal)),
                view: -direction.normalize_or_zero(),
                origin: offset_origin(point, normal, t, direction),
                color: Vec3x4::ZERO,
            };
        }

        // Headlight: a light at the eye, so a scene without lights is still visible.
        if lights.is_empty() {
            for group in groups.iter_mut() {
                let lit = group.blinn_phong(group.view, group.lanes);
                group.color = group.color
                    + (group.base * Vec4::splat(HEADLIGHT_AMBIENT)
                        + lit * Vec4::splat(1.0 - HEADLIGHT_AMBIENT));
            }
        }

        // The lights in order: each light's shadow rays traced together, then what it
        // gives the samples that face it and see it added to their colours.
        // Per group: the lanes facing the light, the direction to it and the squared
        // distance (point lights).
        toward.clear();
        toward.resize(groups.len(), (0_u32, Vec3x4::ZERO, Vec4::ONE));
        for light in lights {
            let (intensity, source) = match *light {
                Light::Ambient { intensity } => {
                    for group in groups.iter_mut() {
                        group.color = group.color + group.base * Vec3x4::splat(intensity);
                    }
                    continue;
                }
                Light::Point {
                    position,
                    intensity,
                } => (intensity, Source::At(position)),
                Light::Directional {
                    direction,
                    intensity,
                } => (intensity, Source::Along(-direction)),
            };
            shadow_rays.clear();
            shadow_samples.clear();
            for (g, (group, toward)) in groups.iter().zip(toward.iter_mut()).enumerate() {
                // The direction toward the light, and the ray's: to the light itself for
                // a point light (the light at t = 1), along the direction for a
                // directional one (whose squared distance is taken as 1: no falloff).
                // No light where it is behind the surface or at the point itself.
                let (l, ray_direction, distance_squared, behind) = match source {
                    Source::At(position) => {
                        let to_light = Vec3x4::splat(position) - group.origin;
                        let distance_squared = to_light.dot(to_light);
                        let l = to_light / distance_squared.sqrt();
                        let behind = distance_squared.cmple(Vec4::ZERO)
                            | group.normal.dot(l).cmple(Vec4::ZERO);
                        (l, to_light, distance_squared, behind)
                    }
                    Source::Along(l) => {
                        let l = Vec3x4::splat(l);
                        (l, l, Vec4::ONE, group.normal.dot(l).cmple(Vec4::ZERO))
                    }
                };
                let facing = !lanes::bits(behind) & group.lanes;
                *toward = (facing, l, distance_squared);
                if facing != 0 {
                    let (origins, directions) = (group.origin.to_lanes(), ray_direction.to_lanes());
                    for j in lanes_of(facing) {
                        shadow_rays.push(Ray::new(origins[j], directions[j]));
                        shadow_samples.push(4 * g + j);
                    }
                }
            }
            *count += shadow_rays.len() as u64;
            answers.clear();
            answers.resize(shadow_rays.len(), false);
            world.any_hits(shadow_rays, source.t_range(), answers);
            for (&i, &blocked) in shadow_samples.iter().zip(answers.iter()) {
                if blocked {
                    toward[i / 4].0 &= !(1 << (i % 4));
                }
            }
            for (group, &(seen, l, distance_squared)) in groups.iter_mut().zip(toward.iter()) {
                if seen == 0 {
                    continue;
                }
                // Inverse-square falloff, intensity / d^2, then times Blinn-Phong (a
                // directional light's d^2 is 1, and dividing by 1 is exact).
                let added =
                    (Vec3x4::splat(intensity) / distance_squared) * group.blinn_phong(l, seen);
                group.color = Vec3x4::select(lanes::mask(seen), group.color + added, group.color);
            }
        }
        for (colors, group) in colors[..n].chunks_mut(4).zip(groups.iter()) {
            // Element by element: `copy_from_slice` of a length not known at compile
            // time is a call to `memcpy`.
            for (color, lane) in colors.iter_mut().zip(group.color.to_lanes()) {
                *color = lane;
            }
        }

        // Follow the mirrors: the reflected rays of the batch are traced and shaded
        // together, one bounce deeper.
        mirrors.clear();
        mirrors.extend((0..n).filter(|&i| mirror[i] > 0.0));
        if mirrors.is_empty() {
            return;
        }
        reflected.clear();
        reflected.resize(mirrors.len(), Vec3::ZERO);
        if depth < self.max_depth {
            mirror_rays.clear();
            mirror_rays.extend(mirrors.iter().map(|&i| {
                let group = &groups[i / 4];
                let view = group.view.lane(i % 4);
                let direction = reflect(-view, hits[i].shading_normal, hits[i].normal);
                Ray::new(group.origin.lane(i % 4), direction)
            }));
            *count += mirror_rays.len() as u64;
            mirror_hits.clear();
            mirror_hits.resize(mirror_rays.len(), None);
            world.closest_objects(mirror_rays, 0.0..f32::INFINITY, mirror_hits);
            next_rays.clear();
            next_hits.clear();
            for ((ray, hit), color) in mirror_rays
                .iter()
                .zip(mirror_hits.iter())
                .zip(reflected.iter_mut())
            {
                match hit {
                    Some(hit) => push_hit(world, ray, hit, next_rays, next_hits),
                    None => *color = self.background,
                }
            }
            next_colors.clear();
            next_colors.resize(next_rays.len(), Vec3::ZERO);
            self.lit_batch::<F>(
                next_rays,
                next_hits,
                None,
                depth + 1,
                deeper.get_or_insert_default(),
                next_colors,
                count,
            );
            let mut next_colors = next_colors.iter();
            for (hit, color) in mirror_hits.iter().zip(reflected.iter_mut()) {
                if hit.is_some() {
                    *color = next_colors.next().copied().unwrap_or(Vec3::ZERO);
                }
            }
        }
        for (&i, &reflected) in mirrors.iter().zip(reflected.iter()) {
            colors[i] = colors[i].lerp(reflected, mirror[i]);
        }
    }

    /// Where the film sample's neighbours (one sample spacing along the image's x and y)
    /// land on the hit's tangent plane, as in ray differentials; unbounded where a
    /// neighbouring ray misses the plane (toward the horizon) or does not exist.
    fn footprint(&self, film: &FilmPoint<'_>, ray: &Ray, hit: &Hit) -> Footprint {
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

    /// The depth of the centre ray of one pixel for the [`Shading::Depth`] pre-pass,
    /// given its closest hit (from [`Shader::trace_primary`]).
    pub(crate) fn depth_probe(&self, ray: &Ray, hit: Option<&ObjectHit>, range: &mut DepthRange) {
        if let Some(hit) = hit {
            // Every shape's hit point is `ray.at(t)`.
            let z = self.depth_map.z(ray.at(hit.t));
            range.near = range.near.min(z);
            range.far_any = range.far_any.max(z);
            let plane = matches!(
                self.scene.world().objects()[hit.object as usize],
                Object::Plane(_)
            );
            if !plane {
                range.far_bounded = range.far_bounded.max(z);
            }
        }
    }
}

/// Appends `ray` to `rays` and the shading surface of its hit `hit` to `surfaces`,
/// written in its place (see [`World::shading_surface_into`]).
#[inline]
fn push_hit(
    world: &World,
    ray: &Ray,
    hit: &ObjectHit,
    rays: &mut Vec<Ray>,
    surfaces: &mut Vec<Hit>,
) {
    let slot = surfaces.len();
    surfaces.push(Hit::default());
    world.shading_surface_into(ray, hit, &mut surfaces[slot]);
    rays.push(*ray);
}

/// What Lit shading reuses from batch to batch on one thread, so that a batch of 64
/// samples allocates nothing: the batch's hits in order, and the buffers of each
/// mirror bounce.
#[derive(Default)]
pub(crate) struct LitScratch {
    /// The rays that hit something, their surfaces, and each one's place in the batch.
    rays: Vec<Ray>,
    surfaces: Vec<Hit>,
    samples: Vec<usize>,
    /// Their colours.
    colors: Vec<Vec3>,
    buffers: LitBuffers,
}

/// The buffers of [`Shader::lit_batch`] at one mirror bounce depth, with the next
/// depth's made when a mirror is first met.
#[derive(Default)]
struct LitBuffers {
    /// Each sample's surface colour (with grid lines).
    bases: Vec<Vec3>,
    groups: Vec<LitGroup>,
    /// Each sample's mirror reflectance.
    mirror: Vec<f32>,
    /// The shadow rays toward one light, the sample each starts from, and whether it
    /// is blocked.
    shadow_rays: Vec<Ray>,
    shadow_samples: Vec<usize>,
    answers: Vec<bool>,
    /// Per group: the lanes facing a light, the direction to it and the squared
    /// distance.
    toward: Vec<(u32, Vec3x4, Vec4)>,
    /// The samples on mirrors, what they reflect, and their reflected rays with the
    /// rays' hits.
    mirrors: Vec<usize>,
    reflected: Vec<Vec3>,
    mirror_rays: Vec<Ray>,
    mirror_hits: Vec<Option<ObjectHit>>,
    /// The reflected rays that hit something, their surfaces and colours.
    next_rays: Vec<Ray>,
    next_hits: Vec<Hit>,
    next_colors: Vec<Vec3>,
    deeper: Option<Box<LitBuffers>>,
}

/// Four samples of a lit batch, side by side (see [`Vec3x4`]), from their surface
/// details to their colours.
#[derive(Clone, Copy)]
struct LitGroup {
    /// The lanes that hold a sample (the others repeat the last one).
    lanes: u32,
    /// The surface colour (with grid lines).
    base: Vec3x4,
    /// The material's specular colour and exponent, and the lanes where the specular
    /// colour is not zero.
    specular: Vec3x4,
    shininess: [f32; 4],
    specular_lanes: u32,
    /// The geometric normal and the normal to shade with.
    normal: Vec3x4,
    shading_normal: Vec3x4,
    /// The unit direction toward the eye.
    view: Vec3x4,
    /// Where secondary rays start (see [`offset_origin`]).
    origin: Vec3x4,
    /// The colour summed so far.
    color: Vec3x4,
}

impl LitGroup {
    /// A placeholder for a buffer's slots, every one overwritten before it is read.
    const EMPTY: Self = Self {
        lanes: 0,
        base: Vec3x4::ZERO,
        specular: Vec3x4::ZERO,
        shininess: [0.0; 4],
        specular_lanes: 0,
        normal: Vec3x4::ZERO,
        shading_normal: Vec3x4::ZERO,
        view: Vec3x4::ZERO,
        origin: Vec3x4::ZERO,
        color: Vec3x4::ZERO,
    };

    /// Blinn-Phong for the light direction `l` (unit vectors), per unit of the light's
    /// irradiance, in the lanes of `lanes` (zero in the others):
    ///
    /// ```text
    /// color max(0, n.l) + specular max(0, n.h)^shininess,   h = (l + v) / |l + v|
    /// ```
    ///
    /// (zero where `n.l <= 0`; no specular term where the specular colour is zero).
    /// `powf` is taken lane by lane.
    #[inline]
    fn blinn_phong(&self, l: Vec3x4, lanes: u32) -> Vec3x4 {
        let n = self.shading_normal;
        let n_dot_l = n.dot(l);
        let lit = !lanes::bits(n_dot_l.cmple(Vec4::ZERO)) & lanes;
        let mut color = self.base * n_dot_l;
        let specular = lit & self.specular_lanes;
        if specular != 0 {
            let h = (l + self.view).normalize_or_zero();
            // Read lane by lane through an array (indexing a `Vec4` is a `match`).
            let n_dot_h = n.dot(h).to_array();
            let mut power = [0.0; 4];
            for j in lanes_of(specular) {
                power[j] = n_dot_h[j].max(0.0).powf(self.shininess[j]);
            }
            color = Vec3x4::select(
                lanes::mask(specular),
                color + self.specular * Vec4::from_array(power),
                color,
            );
        }
        Vec3x4::select(lanes::mask(lit), color, Vec3x4::ZERO)
    }
}

/// Where a point or directional light is, as its shadow rays see it.
#[derive(Clone, Copy)]
enum Source {
    /// A point light at this position: shadow rays end at it, at `t = 1`.
    At(Vec3),
    /// A directional light: the unit direction toward it; shadow rays never end.
    Along(Vec3),
}

impl Source {
    /// Where along a shadow ray a blocker counts.
    fn t_range(self) -> std::ops::Range<f32> {
        match self {
            Source::At(_) => 0.0..1.0,
            Source::Along(_) => 0.0..f32::INFINITY,
        }
    }
}

/// The set bits of `mask`, lowest first.
#[inline]
fn lanes_of(mask: u32) -> impl Iterator<Item = usize> {
    (0..4).filter(move |j| mask & (1 << j) != 0)
}

/// The mirror direction of the unit direction `d` about the shading normal `n`,
/// `d - 2 (d.n) n`; about the geometric normal `ng` instead if the shading normal would
/// send it into the surface.
#[inline]
fn reflect(d: Vec3, n: Vec3, ng: Vec3) -> Vec3 {
    let r = d - 2.0 * d.dot(n) * n;
    if r.dot(ng) > 0.0 {
        r
    } else {
        d - 2.0 * d.dot(ng) * ng
    }
}

/// Where secondary rays start, four hits at a time: the hit point `point` moved off
/// the surface along the geometric normal `normal` (on the side the ray came from), by
/// [`OFFSET_SCALE`] of the size of its coordinates plus [`OFFSET_PER_DISTANCE`] of the
/// distance the ray travelled (`t` times the length of its direction `direction`):
///
/// ```text
/// point + normal (OFFSET_SCALE (1 + max |coordinate|) + OFFSET_PER_DISTANCE t |direction|)
/// ```
#[inline]
fn offset_origin(point: Vec3x4, normal: Vec3x4, t: Vec4, direction: Vec3x4) -> Vec3x4 {
    let magnitude = point.abs_max_element();
    let travelled = t * direction.dot(direction).sqrt();
    point
        + normal
            * (Vec4::splat(OFFSET_SCALE) * (Vec4::ONE + magnitude)
                + Vec4::splat(OFFSET_PER_DISTANCE) * travelled)
}

/// The part of a surface one sample stands for, over which grid lines are averaged.
#[derive(Clone, Copy, Debug)]
enum Footprint {
    /// A point: no averaging (reflected rays, whose footprint is not tracked).
    Point,
    /// The parallelogram spanned by two world-space vectors.
    Area(Vec3, Vec3),
    /// Larger than anything: the lines' average.
    Unbounded,
}

/// The surface colour of `material` at `hit`: its colour, with grid lines over it.
///
/// Grid lines are lines of constant world coordinate every `spacing` along the two
/// world axes closest to the surface's plane (the axis nearest the normal is left out),
/// `line_width` wide, centred on the multiples of `spacing`. Each sample averages the
/// lines over its own footprint on the surface (`footprint`, computed only for grid
/// materials), so they stay smooth toward the horizon; without a footprint (reflected
/// rays) they are point-sampled.
#[inline]
fn surface_color(material: &Material, hit: &Hit, footprint: impl FnOnce() -> Footprint) -> Vec3 {
    let Some(grid) = material.grid else {
        return material.color;
    };
    let n = hit.normal.abs();
    let (a, b) = if n.x >= n.y && n.x >= n.z {
        (1, 2)
    } else if n.y >= n.z {
        (0, 2)
    } else {
        (0, 1)
    };
    let widths = match footprint() {
        Footprint::Point => Vec3::ZERO,
        Footprint::Area(dx, dy) => dx.abs() + dy.abs(),
        Footprint::Unbounded => Vec3::INFINITY,
    };
    let coverage_a = line_coverage(hit.point[a], widths[a], &grid);
    let coverage_b = line_coverage(hit.point[b], widths[b], &grid);
    let coverage = 1.0 - (1.0 - coverage_a) * (1.0 - coverage_b);
    material.color.lerp(grid.color, coverage)
}

/// The fraction of the interval `[x - width/2, x + width/2]` covered by grid lines
/// (centred on multiples of `spacing`, `line_width` wide): the box-filtered line
/// pattern. Width 0 point-samples it; a width of many spacings gives the average,
/// `line_width / spacing`.
#[inline]
fn line_coverage(x: f32, width: f32, grid: &Grid) -> f32 {
    let spacing = grid.spacing;
    let half = 0.5 * grid.line_width.min(spacing);
    // The offset from the nearest line's centre, in [-spacing/2, spacing/2].
    let d = x - round(x / spacing) * spacing;
    if width <= 1e-6 * spacing {
        return f32::from(u8::from(d.abs() < half));
    }
    if width >= 64.0 * spacing {
        return 2.0 * half / spacing;
    }
    let (a, b) = (d - 0.5 * width, d + 0.5 * width);
    if width < spacing {
        // The window meets at most the nearest line and its two neighbours.
        if a >= -half && b <= half {
            return 1.0;
        }
        // Between two lines, touching neither (most samples): every overlap below is
        // zero, and so is the coverage. (The far edge's test decides only where rounding
        // put `d` a little past half a spacing, far from the origin: there a window
        // can reach the next line.)
        if (a >= half && b <= spacing - half) || (a >= -spacing + half && b <= -half) {
            return 0.0;
        }
        let overlap = |centre: f32| (b.min(centre + half) - a.max(centre - half)).max(0.0);
        return ((overlap(-spacing) + overlap(0.0) + overlap(spacing)) / width).clamp(0.0, 1.0);
    }
    // Wider windows: the pattern's integral from 0 to y, with lines shifted to occupy
    // [k spacing, k spacing + 2 half), is k 2 half + min(y - k spacing, 2 half) for
    // k = floor(y / spacing); the coverage is its difference over the window / width.
    let integral = |y: f32| {
        let k = floor(y / spacing);
        (k, (y - k * spacing).clamp(0.0, spacing).min(2.0 * half))
    };
    let (k0, m0) = integral(a + half);
    let (k1, m1) = integral(b + half);
    (((k1 - k0) * 2.0 * half + m1 - m0) / width).clamp(0.0, 1.0)
}

/// Floats from 2^23 up in magnitude are all integers (and NaN and the infinities round
/// to themselves), so [`round`] and [`floor`] return them as they are.
const ALL_INTEGERS: f32 = 8_388_608.0;

/// `x.round()`, half-way cases away from zero, bit for bit (a NaN stays a NaN, though
/// perhaps not as quiet a one), without the call into the
/// maths library that `f32::round` makes on CPUs before SSE4.1 (every grid sample
/// rounds once). Below 2^23 the truncation `x as i32` is exact, and so are `x - t`
/// and `t +- 1`.
#[inline]
fn round(x: f32) -> f32 {
    if x.is_nan() || x.abs() >= ALL_INTEGERS {
        return x;
    }
    // Truncate toward zero, keeping the sign of a zero result (`-0.3` rounds to `-0`).
    let t = ((x as i32) as f32).copysign(x);
    if (x - t).abs() >= 0.5 {
        t + 1.0f32.copysign(x)
    } else {
        t
    }
}

/// `x.floor()`, bit for bit, without a call into the maths library (see [`round`]).
#[inline]
fn floor(x: f32) -> f32 {
    if x.is_nan() || x.abs() >= ALL_INTEGERS {
        return x;
    }
    let t = ((x as i32) as f32).copysign(x);
    if t > x { t - 1.0 } else { t }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

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

    #[track_caller]
    fn check_rounding(x: f32) {
        if x.is_nan() {
            assert!(round(x).is_nan() && floor(x).is_nan());
            return;
        }
        assert_eq!(round(x).to_bits(), x.round().to_bits(), "round({x:e})");
        assert_eq!(floor(x).to_bits(), x.floor().to_bits(), "floor({x:e})");
    }

    #[test]
    fn round_and_floor_are_the_standard_ones_bit_for_bit() {
        let edges = [
            0.0,
            0.5,
            1.5,
            2.5,
            0.499_999_97,
            0.3,
            1.0,
            8_388_607.5,
            8_388_608.0,
            8_388_609.0,
            1e30,
            f32::MIN_POSITIVE,
            1e-45,
            f32::MAX,
            f32::INFINITY,
            f32::NAN,
        ];
        for x in edges {
            check_rounding(x);
            check_rounding(-x);
        }
        // Every float of a few binades around the integers, and a spread of bit patterns.
        let mut bits = 0x3e00_0000_u32; // 0.125
        while bits < 0x4b80_0000 {
            // up to 2^24
            check_rounding(f32::from_bits(bits));
            check_rounding(-f32::from_bits(bits));
            bits += 97;
        }
        let mut state = 0x9e37_79b9_u32;
        for _ in 0..1_000_000 {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            check_rounding(f32::from_bits(state));
        }
    }

    const GRID: Grid = Grid {
        spacing: 1.0,
        line_width: 0.1,
        color: Vec3::ZERO,
    };

    #[track_caller]
    fn check(x: f32, width: f32, expected: f32) {
        check_grid(&GRID, x, width, expected);
    }

    #[track_caller]
    fn check_grid(grid: &Grid, x: f32, width: f32, expected: f32) {
        let got = line_coverage(x, width, grid);
        assert!(
            (got - expected).abs() < 1e-5,
            "x {x} width {width}: {got}, expected {expected}"
        );
    }

    #[test]
    fn line_coverage_is_the_box_filtered_pattern() {
        // Point samples: on a line within 0.05 of an integer.
        check(0.0, 0.0, 1.0);
        check(2.04, 0.0, 1.0);
        check(-3.04, 0.0, 1.0);
        check(0.5, 0.0, 0.0);
        check(0.06, 0.0, 0.0);
        // A footprint of one spacing always covers one line.
        for x in [0.0, 0.3, 0.77, -5.2] {
            check(x, 1.0, 0.1);
        }
        // Half a line in a window of 0.1 centred on a line's edge.
        check(0.05, 0.1, 0.5);
        // Entirely inside a line, or entirely between lines.
        check(1.0, 0.05, 1.0);
        check(1.5, 0.5, 0.0);
        // Huge footprints: the average.
        check(0.3, 1e9, 0.1);
        check(0.3, f32::INFINITY, 0.1);
    }

    #[test]
    fn line_coverage_follows_the_grid_spacing() {
        // Lines 0.2 wide every 2 units: a spacing of 1 would hide a position divided
        // where it should be multiplied.
        let grid = Grid {
            spacing: 2.0,
            line_width: 0.2,
            color: Vec3::ZERO,
        };
        let check = |x, width, expected| check_grid(&grid, x, width, expected);
        // Point samples: on a line within 0.1 of a multiple of 2.
        check(0.0, 0.0, 1.0);
        check(4.08, 0.0, 1.0);
        check(-6.09, 0.0, 1.0);
        check(1.0, 0.0, 0.0);
        check(2.12, 0.0, 0.0);
        // A footprint of one spacing covers a tenth; half a line at a line's edge.
        for x in [0.0, 0.7, 1.5, -3.3] {
            check(x, 2.0, 0.1);
        }
        check(2.1, 0.2, 0.5);
        check(1.0, 0.5, 0.0);
        // Two and a half spacings around a midpoint, [-1.5, 3.5]: the lines at 0 and 2.
        check(1.0, 5.0, 0.08);
    }

    /// Windows narrower than a spacing: the coverage is the window's overlap with the
    /// nearest line and its two neighbours, bit for bit, also where a window lies between
    /// two lines and the overlaps are not computed. Windows are placed with an edge within
    /// ulps of a line's edge, also far from the origin, where the offset from the nearest
    /// line can come out a little over half a spacing.
    #[test]
    fn narrow_windows_cover_the_three_nearest_lines() {
        let grids = [
            GRID,
            Grid {
                spacing: 2.0,
                line_width: 0.2,
                color: Vec3::ZERO,
            },
            Grid {
                spacing: 0.25,
                line_width: 0.0,
                color: Vec3::ZERO,
            },
            // Spacings that are not powers of two round `x / spacing`.
            Grid {
                spacing: 0.1,
                line_width: 0.006,
                color: Vec3::ZERO,
            },
            Grid {
                spacing: 3.0,
                line_width: 0.4,
                color: Vec3::ZERO,
            },
        ];
        let mut state = 0x2545_f491_u32;
        let mut random = move || {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            state as f32 / u32::MAX as f32
        };
        let mut beyond_half = 0;
        for grid in &grids {
            let (spacing, half) = (grid.spacing, 0.5 * grid.line_width.min(grid.spacing));
            for _ in 0..100_000 {
                // Up to 2,000 spacings from the origin, on a line, half-way between two,
                // or anywhere.
                let line = (4000.0 * random()).floor() - 2000.0;
                let x = match (random() * 3.0) as u32 {
                    0 => line * spacing,
                    1 => (line + 0.5) * spacing,
                    _ => (line + random()) * spacing,
                };
                let d = x - round(x / spacing) * spacing;
                if d.abs() > 0.5 * spacing {
                    beyond_half += 1;
                }
                // Windows anywhere, and windows whose left edge is on the right edge of
                // the nearest line or of the one before, or whose right edge is on the
                // left edge of the nearest line or of the one after.
                let edges = [
                    spacing * (1e-5 + 0.99 * random()),
                    2.0 * (d - half),
                    2.0 * (d + spacing - half),
                    2.0 * (-half - d),
                    2.0 * (spacing - half - d),
                ];
                for edge in edges {
                    let nudge = (random() * 8.0) as u32;
                    let width = f32::from_bits(edge.to_bits().wrapping_add(nudge).wrapping_sub(4));
                    if !(width > 1e-6 * spacing && width < spacing) {
                        continue;
                    }
                    let (a, b) = (d - 0.5 * width, d + 0.5 * width);
                    let expected = if a >= -half && b <= half {
                        1.0
                    } else {
                        let overlap =
                            |centre: f32| (b.min(centre + half) - a.max(centre - half)).max(0.0);
                        ((overlap(-spacing) + overlap(0.0) + overlap(spacing)) / width)
                            .clamp(0.0, 1.0)
                    };
                    let got = line_coverage(x, width, grid);
                    assert_eq!(
                        got.to_bits(),
                        expected.to_bits(),
                        "x {x} width {width}: {got}, expected {expected}"
                    );
                }
            }
        }
        assert!(beyond_half > 0, "no offset past half a spacing was tried");
    }

    /// Random vectors from a fixed seed: unit vectors, or colours in `[0, 1)`.
    struct Numbers(u32);

    impl Numbers {
        fn uniform(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 17;
            self.0 ^= self.0 << 5;
            (self.0 >> 8) as f32 / (1 << 24) as f32
        }

        fn color(&mut self) -> Vec3 {
            Vec3::new(self.uniform(), self.uniform(), self.uniform())
        }

        fn unit(&mut self) -> Vec3 {
            (self.color() * 2.0 - 1.0).normalize_or(Vec3::Y)
        }
    }

    /// Blinn-Phong for one sample, as the crate docs write it (the scalar code the
    /// four-lane one replaced).
    fn blinn_phong(base: Vec3, specular: Vec3, shininess: f32, n: Vec3, l: Vec3, v: Vec3) -> Vec3 {
        let n_dot_l = n.dot(l);
        if n_dot_l <= 0.0 {
            return Vec3::ZERO;
        }
        let mut color = base * n_dot_l;
        if specular != Vec3::ZERO {
            let h = (l + v).normalize_or_zero();
            color += specular * n.dot(h).max(0.0).powf(shininess);
        }
        color
    }

    #[test]
    fn four_lanes_of_blinn_phong_are_the_formula_bit_for_bit() {
        let mut numbers = Numbers(0x0bad_5eed);
        for round in 0..20_000 {
            let base: [Vec3; 4] = std::array::from_fn(|_| numbers.color());
            // Some materials without a specular colour, some with a zero component.
            let specular: [Vec3; 4] = std::array::from_fn(|j| match (round + j) % 5 {
                0 => Vec3::ZERO,
                1 => Vec3::new(0.0, 0.5, 0.0),
                _ => numbers.color(),
            });
            let shininess: [f32; 4] = std::array::from_fn(|_| 1.0 + 299.0 * numbers.uniform());
            let n: [Vec3; 4] = std::array::from_fn(|_| numbers.unit());
            let l: [Vec3; 4] = std::array::from_fn(|_| numbers.unit());
            // Also the headlight's case, v = l.
            let v: [Vec3; 4] =
                std::array::from_fn(|j| if round % 7 == 0 { l[j] } else { numbers.unit() });
            let lanes = (round % 16) as u32;
            let group = LitGroup {
                lanes: 0b1111,
                base: Vec3x4::gather(base.each_ref()),
                specular: Vec3x4::gather(specular.each_ref()),
                shininess,
                specular_lanes: (0..4)
                    .filter(|&j| specular[j] != Vec3::ZERO)
                    .fold(0, |m, j| m | 1 << j),
                normal: Vec3x4::gather(n.each_ref()),
                shading_normal: Vec3x4::gather(n.each_ref()),
                view: Vec3x4::gather(v.each_ref()),
                origin: Vec3x4::ZERO,
                color: Vec3x4::ZERO,
            };
            let got = group.blinn_phong(Vec3x4::gather(l.each_ref()), lanes);
            for j in 0..4 {
                let expected = if lanes & (1 << j) != 0 {
                    blinn_phong(base[j], specular[j], shininess[j], n[j], l[j], v[j])
                } else {
                    Vec3::ZERO
                };
                assert_eq!(
                    got.lane(j).to_array().map(f32::to_bits),
                    expected.to_array().map(f32::to_bits),
                    "lane {j}: {} against {expected}",
                    got.lane(j)
                );
            }
        }
    }

    #[test]
    fn four_lanes_of_offset_origins_are_the_formula_bit_for_bit() {
        let mut numbers = Numbers(0x5eed_0ff5);
        for _ in 0..20_000 {
            // Points from near the origin to far out, hits near and far along the ray.
            let scale = 10.0_f32.powf(6.0 * numbers.uniform() - 2.0);
            let point: [Vec3; 4] = std::array::from_fn(|_| (numbers.color() - 0.5) * scale);
            let normal: [Vec3; 4] = std::array::from_fn(|_| numbers.unit());
            let direction: [Vec3; 4] =
                std::array::from_fn(|_| numbers.unit() * (0.1 + numbers.uniform()));
            let t: [f32; 4] = std::array::from_fn(|_| 1e3 * numbers.uniform());
            let got = offset_origin(
                Vec3x4::gather(point.each_ref()),
                Vec3x4::gather(normal.each_ref()),
                Vec4::from_array(t),
                Vec3x4::gather(direction.each_ref()),
            );
            for j in 0..4 {
                // `OFFSET_SCALE (1 + max |coordinate|) + OFFSET_PER_DISTANCE t |direction|`.
                let magnitude = point[j].abs().max_element();
                let travelled = t[j] * direction[j].length();
                let expected = point[j]
                    + normal[j]
                        * (OFFSET_SCALE * (1.0 + magnitude) + OFFSET_PER_DISTANCE * travelled);
                assert_eq!(
                    got.lane(j).to_array().map(f32::to_bits),
                    expected.to_array().map(f32::to_bits)
                );
            }
        }
    }

    #[test]
    fn reflection_mirrors_about_the_normal_and_never_enters_the_surface() {
        let d = Vec3::new(1.0, -1.0, 0.0).normalize();
        let r = reflect(d, Vec3::Y, Vec3::Y);
        assert!((r - Vec3::new(1.0, 1.0, 0.0).normalize()).length() < 1e-6);
        // A shading normal tilted so far that the mirror direction would go below.
        let tilted = Vec3::new(1.0, 0.2, 0.0).normalize();
        assert!(reflect(d, tilted, Vec3::Y).dot(Vec3::Y) > 0.0);
    }
}
