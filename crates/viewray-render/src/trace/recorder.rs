//! The recorder of `viewray trace`: keeps the steps of the one sample it follows.

use std::ops::Range;

use glam::Vec3;
use viewray_geometry::{DRay, Hit, Ray, World};
use viewray_scene::Scene;

use super::{ClosestHit, Shape, Step, StepKind, material_index, shape};
use crate::shade::Recorder;

/// Follows one pixel's sample through the renderer and keeps its steps in order.
pub(super) struct TraceRecorder<'a> {
    scene: &'a Scene,
    /// Each object of the scene alone, to test rays against one object at a time with
    /// the renderer's own single-ray query (every object of a world is valid alone).
    alone: Vec<Option<World>>,
    pixel: (u32, u32),
    /// The index of its viewing ray in the block's rays.
    ray: Option<usize>,
    /// Its index in each mirror bounce's Lit batch.
    batches: Vec<Option<usize>>,
    steps: Vec<Step>,
}

impl<'a> TraceRecorder<'a> {
    /// A recorder following pixel `pixel` of a render of `scene`.
    pub(super) fn new(scene: &'a Scene, pixel: (u32, u32)) -> Self {
        let alone = scene
            .world()
            .objects()
            .iter()
            .map(|object| World::new(vec![object.clone()]).ok())
            .collect();
        Self {
            scene,
            alone,
            pixel,
            ray: None,
            batches: Vec::new(),
            steps: Vec::new(),
        }
    }

    /// Records the pixel's viewing ray, and where it has none, the background it sees.
    pub(super) fn viewing_ray(&mut self, ray: Option<DRay>, background: Vec3) {
        self.push(0, StepKind::ViewingRay { ray });
        if ray.is_none() {
            self.push(0, StepKind::Background { color: background });
        }
    }

    /// The steps recorded.
    pub(super) fn into_steps(self) -> Vec<Step> {
        self.steps
    }

    fn push(&mut self, bounce: u32, kind: StepKind) {
        self.steps.push(Step { bounce, kind });
    }

    /// Where object `object` alone first meets `ray` with `t` in `t_range`.
    fn test(&self, object: usize, ray: &Ray, t_range: Range<f32>) -> Option<f32> {
        let world = self.alone.get(object)?.as_ref()?;
        world.closest_object(ray, t_range).map(|hit| hit.t)
    }

    /// The closest hit of `ray` with `t` in `t_range` among the scene's objects, each
    /// tested alone: `(object, t)`.
    fn first_object(&self, ray: &Ray, t_range: Range<f32>) -> Option<(u32, f32)> {
        (0..self.alone.len())
            .filter_map(|object| {
                let t = self.test(object, ray, t_range.clone())?;
                Some((u32::try_from(object).ok()?, t))
            })
            .min_by(|a, b| a.1.total_cmp(&b.1))
    }
}

impl Recorder for TraceRecorder<'_> {
    const ACTIVE: bool = true;

    fn pixel(&self) -> Option<(u32, u32)> {
        Some(self.pixel)
    }

    fn follow_ray(&mut self, index: Option<usize>) {
        self.ray = index;
    }

    fn followed_ray(&self) -> Option<usize> {
        self.ray
    }

    fn followed(&self, bounce: u32) -> Option<usize> {
        self.batches.get(bounce as usize).copied().flatten()
    }

    fn follow(&mut self, bounce: u32, index: Option<usize>) {
        let bounce = bounce as usize;
        if self.batches.len() <= bounce {
            self.batches.resize(bounce + 1, None);
        }
        self.batches[bounce] = index;
    }

    fn ray(&mut self, bounce: u32, ray: &Ray, t_min: f32) {
        let objects = self.scene.world().objects();
        for (index, object) in (0u32..).zip(objects) {
            let step = StepKind::Test {
                object: index,
                shape: shape(object),
                t: self.test(index as usize, ray, t_min..f32::INFINITY),
            };
            self.push(bounce, step);
        }
    }

    fn closest(&mut self, bounce: u32, hit: &Hit) {
        let closest = ClosestHit {
            object: hit.object,
            shape: shape(&self.scene.world().objects()[hit.object as usize]),
            primitive: hit.primitive,
            material: material_index(self.scene, hit),
            t: hit.t,
            point: hit.point,
            normal: hit.normal,
            shading_normal: hit.shading_normal,
        };
        self.push(bounce, StepKind::Closest(closest));
    }

    fn record(&mut self, bounce: u32, mut step: StepKind) {
        // Which object blocks a shadow ray, for the reader: the renderer only asks
        // whether any does.
        if let StepKind::Light(terms) = &mut step
            && let Some(shadow) = &mut terms.shadow
            && shadow.blocked
        {
            let t_range = shadow.t_min..shadow.t_max;
            shadow.blocker = self.first_object(&shadow.ray, t_range).map(|(object, t)| {
                let shape: Shape = shape(&self.scene.world().objects()[object as usize]);
                (object, shape, t)
            });
        }
        self.push(bounce, step);
    }
}
