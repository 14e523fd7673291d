//! Mirrors: a lit batch's reflected rays, traced together, their hits shaded as a batch
//! one bounce deeper and mixed into the colours by each material's reflectance.

use glam::Vec3;
use viewray_geometry::{Hit, ObjectHit, Ray};

use super::{LitBatch, LitBuffers, push_hit};
use crate::shade::Shader;
use crate::shade::footprint::FilmPoint;
use crate::shade::record::Recorder;
use crate::trace::StepKind;

/// Where reflected rays start their search: at their origin, which is already off the
/// surface.
const MIRROR_T_MIN: f32 = 0.0;

/// The buffers of one bounce's reflected rays, with the next bounce's made when a
/// mirror is first met.
#[derive(Default)]
pub(super) struct MirrorBuffers {
    /// The samples on mirrors, what they reflect, and their reflected rays with the
    /// rays' hits.
    samples: Vec<usize>,
    reflected: Vec<Vec3>,
    rays: Vec<Ray>,
    hits: Vec<Option<ObjectHit>>,
    /// The reflected rays that hit something, their surfaces and colours.
    next_rays: Vec<Ray>,
    next_hits: Vec<Hit>,
    next_colors: Vec<Vec3>,
    deeper: Option<Box<LitBuffers>>,
}

impl Shader<'_> {
    /// Mixes what the mirrors of `batch` reflect into `colors` (the batch's colours so
    /// far): `(1 - mirror) local + mirror reflected`, the reflected colour traced and
    /// shaded one bounce deeper, or the background, or black past the last bounce.
    /// Counts the reflected rays in `count`.
    ///
    /// `recorder` follows its sample's reflected ray into the next bounce's batch.
    #[inline]
    pub(super) fn follow_mirrors<'f, F: Fn(usize) -> FilmPoint<'f>, R: Recorder>(
        &self,
        batch: &LitBatch<'_, F>,
        buffers: &mut LitBuffers,
        colors: &mut [Vec3],
        recorder: &mut R,
        count: &mut u64,
    ) {
        let (hits, depth) = (batch.hits, batch.depth);
        let world = &self.scene.world();
        let LitBuffers {
            groups,
            mirror,
            mirrors,
            ..
        } = buffers;
        let MirrorBuffers {
            samples: mirrors,
            reflected,
            rays: mirror_rays,
            hits: mirror_hits,
            next_rays,
            next_hits,
            next_colors,
            deeper,
        } = mirrors;

        // Follow the mirrors: the reflected rays of the batch are traced and shaded
        // together, one bounce deeper.
        mirrors.clear();
        mirrors.extend((0..batch.rays.len()).filter(|&i| mirror[i] > 0.0));
        // The followed sample, if it is on a mirror: its place among the mirrors.
        let followed = if R::ACTIVE {
            recorder.follow(depth + 1, None);
            recorder
                .followed(depth)
                .and_then(|i| mirrors.iter().position(|&m| m == i))
        } else {
            None
        };
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
            world.closest_objects(mirror_rays, MIRROR_T_MIN..f32::INFINITY, mirror_hits);
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
            if R::ACTIVE
                && let Some(m) = followed
            {
                let step = StepKind::Reflect {
                    mirror: mirror[mirrors[m]],
                    ray: Some(mirror_rays[m]),
                };
                recorder.record(depth, step);
                recorder.ray(depth + 1, &mirror_rays[m], MIRROR_T_MIN);
                if mirror_hits[m].is_none() {
                    let color = self.background;
                    recorder.record(depth + 1, StepKind::Background { color });
                }
                // Its place in the next batch: among the reflected rays that hit.
                let next = mirror_hits[m]
                    .is_some()
                    .then(|| mirror_hits[..m].iter().filter(|h| h.is_some()).count());
                recorder.follow(depth + 1, next);
            }
            next_colors.clear();
            next_colors.resize(next_rays.len(), Vec3::ZERO);
            let next = LitBatch::<F> {
                rays: next_rays,
                hits: next_hits,
                film: None,
                depth: depth + 1,
            };
            let deeper = deeper.get_or_insert_default();
            self.lit_batch(next, deeper, next_colors, recorder, count);
            let mut next_colors = next_colors.iter();
            for (hit, color) in mirror_hits.iter().zip(reflected.iter_mut()) {
                if hit.is_some() {
                    *color = next_colors.next().copied().unwrap_or(Vec3::ZERO);
                }
            }
        } else if R::ACTIVE
            && let Some(m) = followed
        {
            // Past the last bounce: the mirror reflects black.
            let step = StepKind::Reflect {
                mirror: mirror[mirrors[m]],
                ray: None,
            };
            recorder.record(depth, step);
        }
        for (m, (&i, &reflected)) in mirrors.iter().zip(reflected.iter()).enumerate() {
            let local = colors[i];
            colors[i] = local.lerp(reflected, mirror[i]);
            if R::ACTIVE && followed == Some(m) {
                let step = StepKind::Mix {
                    mirror: mirror[i],
                    local,
                    reflected,
                    color: colors[i],
                };
                recorder.record(depth, step);
            }
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

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
