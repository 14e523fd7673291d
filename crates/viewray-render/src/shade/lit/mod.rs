//! Lit shading of a batch of hits, four samples at a time: each group's surface
//! colours and details, then its [`lights`] (each light's shadow rays traced together), then its
//! [`mirrors`] (the reflected rays traced together and shaded one bounce deeper).

mod lights;
mod mirrors;

use glam::{Vec3, Vec4};
use viewray_geometry::{Hit, ObjectHit, Ray, World};

use self::lights::ShadowBuffers;
use self::mirrors::MirrorBuffers;
use super::Shader;
use super::footprint::{FilmPoint, Footprint, RaysX4};
use super::grid::{surface_color, surface_colors};
use super::record::Recorder;
use crate::lanes::Vec3x4;
use crate::trace::{LitSurface, StepKind, material_index};

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

/// The hits Lit shading works on together, at one mirror bounce: `hits[i]` is the
/// surface `rays[i]` hit.
pub(super) struct LitBatch<'b, F> {
    pub(super) rays: &'b [Ray],
    pub(super) hits: &'b [Hit],
    /// The film point of each ray, for primary rays, whose grid lines are filtered over
    /// the sample's footprint; `None` for reflected rays, whose grids are point-sampled.
    pub(super) film: Option<&'b F>,
    /// The mirror bounce: 0 for viewing rays.
    pub(super) depth: u32,
}

/// What Lit shading reuses from batch to batch on one thread, so that a batch of 64
/// samples allocates nothing: the batch's hits in order, and the buffers of each
/// mirror bounce.
#[derive(Default)]
pub(crate) struct LitScratch {
    /// The rays that hit something, their surfaces, and each one's place in the batch.
    pub(super) rays: Vec<Ray>,
    pub(super) surfaces: Vec<Hit>,
    pub(super) samples: Vec<usize>,
    /// Their colours.
    pub(super) colors: Vec<Vec3>,
    pub(super) buffers: LitBuffers,
}

/// The buffers of [`Shader::lit_batch`] at one mirror bounce depth, with the next
/// depth's made when a mirror is first met.
#[derive(Default)]
pub(super) struct LitBuffers {
    groups: Vec<LitGroup>,
    /// Each sample's mirror reflectance.
    mirror: Vec<f32>,
    shadows: ShadowBuffers,
    mirrors: MirrorBuffers,
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
}

impl Shader<'_> {
    /// Blinn-Phong with every light, hard shadows and mirror reflection, for the hits of
    /// `batch`, into `colors`; see the crate's documentation for the formulas.
    ///
    /// The batch's shadow rays toward each light are traced together
    /// ([`World::any_hits`](viewray_geometry::World::any_hits)), and so are its
    /// reflected rays, whose hits are then shaded as a batch one bounce deeper. The
    /// lighting is worked out four samples at a time ([`Vec3x4`]), light by light;
    /// each sample's colour is summed in the same order and with the same numbers as
    /// one sample shaded alone, so neither the batch nor the lanes change a pixel.
    ///
    /// `recorder` is told the numbers of the sample it follows (see
    /// [`Recorder`]).
    pub(super) fn lit_batch<'f, F: Fn(usize) -> FilmPoint<'f>, R: Recorder>(
        &self,
        batch: LitBatch<'_, F>,
        buffers: &mut LitBuffers,
        colors: &mut [Vec3],
        recorder: &mut R,
        count: &mut u64,
    ) {
        self.gather_groups(&batch, buffers, recorder);
        let shadows = &mut buffers.shadows;
        self.add_lights(&mut buffers.groups, shadows, (batch.depth, recorder), count);
        let n = batch.rays.len();
        for (colors, group) in colors[..n].chunks_mut(4).zip(buffers.groups.iter()) {
            // Element by element: `copy_from_slice` of a length not known at compile
            // time is a call to `memcpy`.
            for (color, lane) in colors.iter_mut().zip(group.color.to_lanes()) {
                *color = lane;
            }
        }
        self.follow_mirrors(&batch, buffers, colors, recorder, count);
    }

    /// Fills `buffers` with each sample's mirror reflectance, and its groups of four
    /// with their surface colours (with grid lines, see [`surface_colors`]) and details,
    /// where their secondary rays start, the view direction, and no colour yet; tells
    /// `recorder` the surface of the sample it follows.
    #[inline]
    fn gather_groups<'f, F: Fn(usize) -> FilmPoint<'f>, R: Recorder>(
        &self,
        batch: &LitBatch<'_, F>,
        buffers: &mut LitBuffers,
        recorder: &mut R,
    ) {
        let LitBatch {
            rays,
            hits,
            film,
            depth,
        } = *batch;
        let followed = if R::ACTIVE {
            recorder.followed(depth)
        } else {
            None
        };
        let n = rays.len();
        let LitBuffers { groups, mirror, .. } = buffers;

        // Four at a time, each sample's surface colour (with grid lines), where its
        // secondary rays start and the view direction. Every vector is gathered from
        // where it lies (see `Vec3x4::gather`): through small arrays filled just before,
        // the gathering took about a tenth of the render's time.
        // Each group is written in its slot: pushed, it was built on the stack and copied
        // (a call to memmove that read back stores still on their way).
        mirror.clear();
        groups.resize(n.div_ceil(4), LitGroup::EMPTY);
        for (g, group) in groups.iter_mut().enumerate() {
            // Spare lanes repeat the last sample; no light adds to them.
            let len = (n - 4 * g).min(4);
            let i = [0, 1, 2, 3].map(|j| 4 * g + j.min(len - 1));
            let hit = i.map(|i| &hits[i]);
            let material = hit.map(|hit| self.scene.material(hit));
            mirror.extend(material[..len].iter().map(|m| m.mirror));
            let direction = Vec3x4::gather(i.map(|i| &rays[i].direction));
            let point = Vec3x4::gather(hit.map(|hit| &hit.point));
            let normal = Vec3x4::gather(hit.map(|hit| &hit.normal));
            // Grid lines are filtered over the footprints of viewing rays, point-sampled
            // for reflected rays.
            let base = surface_colors(material, point, normal, |lanes| match film {
                Some(film) => {
                    let rays = RaysX4 {
                        origin: Vec3x4::gather(i.map(|i| &rays[i].origin)),
                        direction,
                        point,
                        normal,
                    };
                    self.footprint_widths(|j| film(i[j]), lanes, &rays)
                }
                None => Vec3x4::ZERO,
            });
            let t = Vec4::new(hit[0].t, hit[1].t, hit[2].t, hit[3].t);
            let specular_lanes = (0..len)
                .filter(|&j| material[j].specular != Vec3::ZERO)
                .fold(0, |lanes, j| lanes | 1 << j);
            *group = LitGroup {
                lanes: (1 << len) - 1,
                base,
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
        if R::ACTIVE
            && let Some(i) = followed
        {
            let (group, j) = (&groups[i / 4], i % 4);
            let (ray, hit) = (&rays[i], &hits[i]);
            let material = self.scene.material(hit);
            recorder.closest(depth, hit);
            // How the lines were mixed in, from the scalar rule the lanes follow bit for
            // bit; the colour is the lanes' own.
            let mut grid = None;
            surface_color::<R>(
                material,
                hit,
                || film.map_or(Footprint::Point, |f| self.footprint(&f(i), ray, hit)),
                &mut grid,
            );
            let surface = LitSurface {
                material: material_index(self.scene, hit),
                color: group.base.lane(j),
                grid,
                specular: material.specular,
                shininess: material.shininess,
                mirror: material.mirror,
                view: group.view.lane(j),
                origin: group.origin.lane(j),
            };
            recorder.record(depth, StepKind::Surface(surface));
        }
    }
}

/// Appends `ray` to `rays` and the shading surface of its hit `hit` to `surfaces`,
/// written in its place (see [`World::shading_surface_into`]).
#[inline]
pub(super) fn push_hit(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_numbers::Numbers;

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
}
