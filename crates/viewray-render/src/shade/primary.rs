//! The block driver: a block's viewing rays traced together and shaded by the view's
//! mode, Flat, Normals and Depth sample by sample, Lit as one batch.

use std::ops::Range;

use glam::{DVec2, Vec3};
use viewray_geometry::{ObjectHit, Ray, Reach};
use viewray_scene::{Material, Shading};

use super::Shader;
use super::footprint::FilmPoint;
use super::grid::surface_color;
use super::lit::{LitBatch, LitScratch, push_hit};
use super::record::Recorder;
use crate::trace::{StepKind, material_index};

/// Where primary rays start their search: `t > 0`, as the camera contract says.
pub(crate) const T_MIN: f32 = f32::MIN_POSITIVE;

impl Shader<'_> {
    /// Whether [`Shader::shade_primaries`] may ask for film points: Lit shading always,
    /// Flat shading where a material has grid lines, the data images never.
    pub(crate) fn uses_film_points(&self) -> bool {
        match self.shading {
            Shading::Lit => true,
            Shading::Flat => self.scene.materials().iter().any(|m| m.grid.is_some()),
            Shading::Normals | Shading::Depth => false,
        }
    }

    /// What the viewing rays of the pixels `rows x cols`, through any sample, may meet
    /// ([`Camera::ray_bounds`], [`World::reach`]): nothing, and then each sees the
    /// background and the renderer need not make them at all (the sky above a ground
    /// plane, the background around a model); planes at most, or planes and one sphere
    /// or triangle, and then they are traced against those alone
    /// ([`Shader::trace_primary_within`]: the open ground, the ground around a ball); or
    /// anything. [`Reach::Anything`] for cameras whose rays the camera cannot bound.
    ///
    /// [`Camera::ray_bounds`]: viewray_camera::Camera::ray_bounds
    /// [`World::reach`]: viewray_geometry::World::reach
    pub(crate) fn block_reach(&self, rows: Range<u32>, cols: Range<u32>) -> Reach {
        let corners = [
            DVec2::new(f64::from(cols.start), f64::from(rows.start)),
            DVec2::new(f64::from(cols.end), f64::from(rows.end)),
        ];
        match self.camera.ray_bounds(corners) {
            Some(rays) => self.scene.world().reach(&rays),
            None => Reach::Anything,
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

    /// [`Shader::trace_primary`] for the viewing rays of a block whose
    /// [`Shader::block_reach`] is `reach`: for [`Reach::Planes`] the planes alone, for
    /// [`Reach::One`] the planes and that object alone, otherwise the whole world; the
    /// same hits.
    #[inline]
    pub(crate) fn trace_primary_within(
        &self,
        reach: Reach,
        rays: &[Ray],
        hits: &mut [Option<ObjectHit>],
    ) {
        let world = self.scene.world();
        match reach {
            Reach::Planes => world.closest_plane_hits(rays, T_MIN..f32::INFINITY, hits),
            Reach::One(object) => world.closest_hits_with(object, rays, T_MIN..f32::INFINITY, hits),
            Reach::Nothing | Reach::Anything => self.trace_primary(rays, hits),
        }
    }

    /// The values of what the viewing rays `rays` see, given their closest hits (from
    /// [`Shader::trace_primary`]): `emit(i, value)` once for each ray, in no particular
    /// order (straight into the caller's sums: a buffer of colours in between was
    /// written and read back once per ray); `film(i)` is the film point of
    /// `rays[i]`, asked for only where a grid is filtered over the sample's footprint.
    /// Lit shading traces the batch's shadow rays toward each light together, and its
    /// reflected rays together, as packets (see [`Shader::lit_batch`]). `recorder` is
    /// told the numbers of the ray it follows ([`Recorder::followed_ray`]).
    pub(crate) fn shade_primaries<'f, R: Recorder>(
        &self,
        rays: &[Ray],
        hits: &[Option<ObjectHit>],
        film: impl Fn(usize) -> FilmPoint<'f>,
        (scratch, recorder): (&mut LitScratch, &mut R),
        mut emit: impl FnMut(usize, Vec3),
        count: &mut u64,
    ) {
        let followed = if R::ACTIVE {
            recorder.followed_ray()
        } else {
            None
        };
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
                        if R::ACTIVE && followed == Some(i) {
                            recorder.follow(0, Some(samples.len()));
                        }
                        push_hit(world, ray, hit, hit_rays, surfaces);
                        samples.push(i);
                    }
                    None => {
                        if R::ACTIVE && followed == Some(i) {
                            let color = self.background;
                            recorder.record(0, StepKind::Background { color });
                        }
                        emit(i, self.background);
                    }
                }
            }
            lit.clear();
            lit.resize(hit_rays.len(), Vec3::ZERO);
            let film_of = |k: usize| film(samples[k]);
            let batch = LitBatch {
                rays: hit_rays,
                hits: surfaces,
                film: Some(&film_of),
                depth: 0,
            };
            self.lit_batch(batch, buffers, lit, recorder, count);
            for (&i, &color) in samples.iter().zip(lit.iter()) {
                emit(i, color);
            }
            return;
        }
        for (i, (ray, hit)) in rays.iter().zip(hits).enumerate() {
            let Some(object_hit) = hit else {
                if R::ACTIVE && followed == Some(i) {
                    let color = self.background;
                    recorder.record(0, StepKind::Background { color });
                }
                emit(i, self.background);
                continue;
            };
            let is_followed = R::ACTIVE && followed == Some(i);
            let color = match self.shading {
                Shading::Flat => {
                    // A plain colour needs no surface details.
                    let material = self.material(object_hit.object, object_hit.primitive);
                    let mut grid = None;
                    let color = if material.grid.is_none() {
                        material.color
                    } else {
                        let hit = world.surface(ray, object_hit);
                        let footprint = || self.footprint(&film(i), ray, &hit);
                        surface_color::<R>(material, &hit, footprint, &mut grid)
                    };
                    if is_followed {
                        let hit = world.surface(ray, object_hit);
                        recorder.closest(0, &hit);
                        let material = material_index(self.scene, &hit);
                        let step = StepKind::Flat {
                            material,
                            color,
                            grid,
                        };
                        recorder.record(0, step);
                    }
                    color
                }
                Shading::Normals => {
                    let hit = world.surface(ray, object_hit);
                    let value = hit.shading_normal * 0.5 + 0.5;
                    if is_followed {
                        recorder.closest(0, &hit);
                        let normal = hit.shading_normal;
                        recorder.record(0, StepKind::Normals { normal, value });
                    }
                    value
                }
                // Every shape's hit point is `ray.at(t)`, as in the depth pre-pass.
                Shading::Depth => {
                    let depth = self.depth_map.evaluate(ray.at(object_hit.t));
                    if is_followed {
                        recorder.closest(0, &world.surface(ray, object_hit));
                        recorder.record(0, StepKind::Depth(depth));
                    }
                    Vec3::splat(depth.value)
                }
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
}
