//! The rule that turns hit points into Depth values, and the pre-pass that finds the
//! range it maps.

use glam::Vec3;
use viewray_camera::{Camera, Projection};
use viewray_geometry::{Object, ObjectHit, Ray};

use super::Shader;
use crate::trace::DepthValue;

/// The rule that turns hit points into [`Shading::Depth`](viewray_scene::Shading::Depth)
/// values.
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
/// [`Shader::depth_probe`] and [`DepthMap::with_range`]), so the rule is the same
/// whatever the threads and tiles.
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
            eye: frame.e().as_vec3(),
            forward: (-frame.w()).as_vec3(),
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

    /// The depth value of `p`, in `(0, 1]`, with the numbers it comes from.
    #[inline]
    pub(crate) fn evaluate(&self, p: Vec3) -> DepthValue {
        let z = self.z(p);
        let extent = self.far - self.near;
        let (s, value) = if !extent.is_finite() || extent <= 0.0 {
            (None, 1.0)
        } else {
            let s = ((z - self.near) / extent).max(0.0);
            (Some(s), if s <= 1.0 { 1.0 - 0.9 * s } else { 0.1 / s })
        };
        DepthValue {
            panoramic: self.panoramic,
            z,
            near: self.near,
            far: self.far,
            s,
            value,
        }
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

impl Shader<'_> {
    /// The depth of the centre ray of one pixel for the
    /// [`Shading::Depth`](viewray_scene::Shading::Depth) pre-pass, given its closest hit
    /// (from [`Shader::trace_primary`]).
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
