//! The lights of a lit batch, one after another: the headlight of a scene without
//! lights, ambient light, and point and directional lights with hard shadows, each
//! light's shadow rays traced together; Blinn-Phong four samples at a time.

use glam::{Vec3, Vec4};
use viewray_geometry::Ray;
use viewray_scene::Light;

use super::LitGroup;
use crate::lanes::{self, Vec3x4, lanes_of};
use crate::shade::Shader;
use crate::shade::record::Recorder;
use crate::trace::{
    BlinnPhong, HeadlightTerms, LightSource, LightTerms, LitTerm, ShadowRay, Specular, StepKind,
};

/// The headlight used when a [`Shading::Lit`](viewray_scene::Shading::Lit) scene has no
/// lights at all: the share of the surface colour every lit point gets regardless of its
/// orientation.
const HEADLIGHT_AMBIENT: f32 = 0.15;

/// The buffers of one light's shadow rays.
#[derive(Default)]
pub(super) struct ShadowBuffers {
    /// The shadow rays toward one light, the sample each starts from, and whether it
    /// is blocked.
    rays: Vec<Ray>,
    samples: Vec<usize>,
    answers: Vec<bool>,
    /// Per group: the lanes facing a light, the direction to it and the squared
    /// distance.
    toward: Vec<(u32, Vec3x4, Vec4)>,
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

impl Shader<'_> {
    /// Adds what every light gives each sample of `groups` (the batch of mirror bounce
    /// `bounce`) to its colour, light by light in the scene's order; counts the shadow
    /// rays in `count`, and tells `recorder` each light's terms for the sample it
    /// follows.
    #[inline]
    pub(super) fn add_lights<R: Recorder>(
        &self,
        groups: &mut [LitGroup],
        buffers: &mut ShadowBuffers,
        (bounce, recorder): (u32, &mut R),
        count: &mut u64,
    ) {
        let world = &self.scene.world();
        let lights = self.scene.lights();
        let ShadowBuffers {
            rays: shadow_rays,
            samples: shadow_samples,
            answers,
            toward,
        } = buffers;

        // Headlight: a light at the eye, so a scene without lights is still visible.
        if lights.is_empty() {
            for (g, group) in groups.iter_mut().enumerate() {
                let lit = group.blinn_phong(group.view, group.lanes);
                let term = group.base * Vec4::splat(HEADLIGHT_AMBIENT)
                    + lit.color * Vec4::splat(1.0 - HEADLIGHT_AMBIENT);
                group.color = group.color + term;
                if R::ACTIVE
                    && let Some(j) = recorder.lane_of(bounce, g)
                {
                    let terms = HeadlightTerms {
                        ambient: HEADLIGHT_AMBIENT,
                        lit: lit.lane(j),
                        term: term.lane(j),
                        color: group.color.lane(j),
                    };
                    recorder.record(bounce, StepKind::Headlight(terms));
                }
            }
        }

        // The lights in order: each light's shadow rays traced together, then what it
        // gives the samples that face it and see it added to their colours.
        // Per group: the lanes facing the light, the direction to it and the squared
        // distance (point lights).
        toward.clear();
        toward.resize(groups.len(), (0_u32, Vec3x4::ZERO, Vec4::ONE));
        for (index, light) in lights.iter().enumerate() {
            let (intensity, source) = match *light {
                Light::Ambient { intensity } => {
                    for (g, group) in groups.iter_mut().enumerate() {
                        let term = group.base * Vec3x4::splat(intensity);
                        group.color = group.color + term;
                        if R::ACTIVE
                            && let Some(j) = recorder.lane_of(bounce, g)
                        {
                            let step = StepKind::Ambient {
                                light: index,
                                intensity,
                                term: term.lane(j),
                                color: group.color.lane(j),
                            };
                            recorder.record(bounce, step);
                        }
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
                *count += u64::from(facing.count_ones());
                // Rays that surely reach the light (outside the box around every
                // object, past every plane) need no trace: the world would answer
                // "not blocked". Each ray is traced when a sample is followed, so that
                // its trace shows it.
                let traced = if R::ACTIVE || facing == 0 {
                    facing
                } else {
                    let (o, d) = (group.origin, ray_direction);
                    facing & !world.surely_clear([o.x, o.y, o.z], [d.x, d.y, d.z], source.t_range())
                };
                if traced != 0 {
                    let (origins, directions) = (group.origin.to_lanes(), ray_direction.to_lanes());
                    for j in lanes_of(traced) {
                        shadow_rays.push(Ray::new(origins[j], directions[j]));
                        shadow_samples.push(4 * g + j);
                    }
                }
            }
            answers.clear();
            answers.resize(shadow_rays.len(), false);
            world.any_hits(shadow_rays, source.t_range(), answers);
            for (&i, &blocked) in shadow_samples.iter().zip(answers.iter()) {
                if blocked {
                    toward[i / 4].0 &= !(1 << (i % 4));
                }
            }
            for (g, (group, &(seen, l, distance_squared))) in
                groups.iter_mut().zip(toward.iter()).enumerate()
            {
                let mut lit = None;
                if seen != 0 {
                    // Inverse-square falloff, intensity / d^2, then times Blinn-Phong (a
                    // directional light's d^2 is 1, and dividing by 1 is exact).
                    let scale = Vec3x4::splat(intensity) / distance_squared;
                    let terms = group.blinn_phong(l, seen);
                    let added = scale * terms.color;
                    group.color =
                        Vec3x4::select(lanes::mask(seen), group.color + added, group.color);
                    if R::ACTIVE {
                        lit = Some((scale, terms, added, seen));
                    }
                }
                if R::ACTIVE
                    && let Some(j) = recorder.lane_of(bounce, g)
                {
                    let i = 4 * g + j;
                    let shadow = shadow_samples
                        .iter()
                        .position(|&s| s == i)
                        .map(|n| ShadowRay {
                            ray: shadow_rays[n],
                            t_min: source.t_range().start,
                            t_max: source.t_range().end,
                            blocked: answers[n],
                            blocker: None,
                        });
                    let lit = lit.filter(|&(.., seen)| seen & 1 << j != 0).map(
                        |(scale, terms, added, _)| LitTerm {
                            scale: scale.lane(j),
                            blinn_phong: terms.lane(j),
                            term: added.lane(j),
                        },
                    );
                    let terms = LightTerms {
                        light: index,
                        source: match source {
                            Source::At(position) => LightSource::Point(position),
                            Source::Along(l) => LightSource::Directional(-l),
                        },
                        intensity,
                        l: l.lane(j),
                        distance_squared: distance_squared[j],
                        shadow,
                        lit,
                        color: group.color.lane(j),
                    };
                    recorder.record(bounce, StepKind::Light(terms));
                }
            }
        }
    }
}

/// Blinn-Phong for four samples, with the numbers it is made of (see
/// [`LitGroup::blinn_phong`]).
#[derive(Clone, Copy)]
struct BlinnPhongLanes {
    /// `n.l`.
    n_dot_l: Vec4,
    /// `color n.l`.
    diffuse: Vec3x4,
    /// The lanes with a specular term, and its numbers: `h`, `n.h`, the power and
    /// `specular max(0, n.h)^shininess`.
    specular: u32,
    h: Vec3x4,
    n_dot_h: [f32; 4],
    power: [f32; 4],
    specular_term: Vec3x4,
    /// The result: `diffuse + specular` in the lanes lit, zero in the others.
    color: Vec3x4,
}

impl BlinnPhongLanes {
    /// The numbers of lane `j`.
    fn lane(&self, j: usize) -> BlinnPhong {
        BlinnPhong {
            n_dot_l: self.n_dot_l[j],
            diffuse: self.diffuse.lane(j),
            specular: (self.specular & 1 << j != 0).then(|| Specular {
                h: self.h.lane(j),
                n_dot_h: self.n_dot_h[j],
                power: self.power[j],
                term: self.specular_term.lane(j),
            }),
            sum: self.color.lane(j),
        }
    }
}

impl LitGroup {
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
    fn blinn_phong(&self, l: Vec3x4, lanes: u32) -> BlinnPhongLanes {
        let n = self.shading_normal;
        let n_dot_l = n.dot(l);
        let lit = !lanes::bits(n_dot_l.cmple(Vec4::ZERO)) & lanes;
        let diffuse = self.base * n_dot_l;
        let mut color = diffuse;
        let specular = lit & self.specular_lanes;
        let (mut h, mut n_dot_h, mut power) = (Vec3x4::ZERO, [0.0; 4], [0.0; 4]);
        let mut specular_term = Vec3x4::ZERO;
        if specular != 0 {
            h = (l + self.view).normalize_or_zero();
            // Read lane by lane through an array (indexing a `Vec4` is a `match`).
            n_dot_h = n.dot(h).to_array();
            for j in lanes_of(specular) {
                power[j] = n_dot_h[j].max(0.0).powf(self.shininess[j]);
            }
            specular_term = self.specular * Vec4::from_array(power);
            color = Vec3x4::select(lanes::mask(specular), color + specular_term, color);
        }
        BlinnPhongLanes {
            n_dot_l,
            diffuse,
            specular,
            h,
            n_dot_h,
            power,
            specular_term,
            color: Vec3x4::select(lanes::mask(lit), color, Vec3x4::ZERO),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_numbers::Numbers;

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
            let got = group.blinn_phong(Vec3x4::gather(l.each_ref()), lanes).color;
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
}
