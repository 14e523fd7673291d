//! What the shading code tells a recorder about the one sample it follows: the hooks
//! through which `viewray trace` reads the renderer's own numbers.
//!
//! Every hook is called as `if R::ACTIVE { .. }`: for [`NoRecorder`], the renderer's,
//! `ACTIVE` is `false` and the hooks and the values built for them compile away, so a
//! render runs the same machine code as without them. A recorder follows one sample
//! through the batches it belongs to: its viewing ray's index in the block of rays, and
//! at each mirror bounce its index in that bounce's Lit batch. (The viewing ray itself
//! is recorded before the block is traced: ray generation calls no hook.)

use viewray_geometry::{Hit, Ray};

use crate::trace::StepKind;

/// Receives the numbers of the sample it follows (see the module docs).
pub(crate) trait Recorder {
    /// Whether the hooks are called at all.
    const ACTIVE: bool;

    /// The pixel whose viewing ray is followed.
    fn pixel(&self) -> Option<(u32, u32)>;

    /// The index of the followed pixel's viewing ray in the block's rays (`None` where
    /// the camera has no ray for it).
    fn follow_ray(&mut self, index: Option<usize>);

    /// The index of the followed viewing ray in the block's rays.
    fn followed_ray(&self) -> Option<usize>;

    /// The index of the followed sample in the Lit batch of mirror bounce `bounce`.
    fn followed(&self, bounce: u32) -> Option<usize>;

    /// Follows the sample `index` of bounce `bounce`'s Lit batch (`None`: none of it).
    fn follow(&mut self, bounce: u32, index: Option<usize>);

    /// The followed sample's ray at bounce `bounce`, traced for hits from `t_min` on.
    fn ray(&mut self, bounce: u32, ray: &Ray, t_min: f32);

    /// The surface the renderer shades for the followed sample at bounce `bounce`.
    fn closest(&mut self, bounce: u32, hit: &Hit);

    /// A step of the followed sample's shading at bounce `bounce`.
    fn record(&mut self, bounce: u32, step: StepKind);

    /// The lane of the followed sample in group `group` (four samples) of bounce
    /// `bounce`'s Lit batch, if it is there.
    #[inline]
    fn lane_of(&self, bounce: u32, group: usize) -> Option<usize> {
        self.followed(bounce)
            .filter(|&i| i / 4 == group)
            .map(|i| i % 4)
    }
}

/// The renderer's recorder: records nothing, and every hook compiles away.
pub(crate) struct NoRecorder;

impl Recorder for NoRecorder {
    const ACTIVE: bool = false;

    #[inline]
    fn pixel(&self) -> Option<(u32, u32)> {
        None
    }

    #[inline]
    fn follow_ray(&mut self, _: Option<usize>) {}

    #[inline]
    fn followed_ray(&self) -> Option<usize> {
        None
    }

    #[inline]
    fn followed(&self, _: u32) -> Option<usize> {
        None
    }

    #[inline]
    fn follow(&mut self, _: u32, _: Option<usize>) {}

    #[inline]
    fn ray(&mut self, _: u32, _: &Ray, _: f32) {}

    #[inline]
    fn closest(&mut self, _: u32, _: &Hit) {}

    #[inline]
    fn record(&mut self, _: u32, _: StepKind) {}
}
