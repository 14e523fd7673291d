//! Rays in single and double precision.

use glam::{DVec3, Vec3};

/// A ray `origin + t * direction` in single precision, the form the tracer uses.
///
/// The direction is not normalized: `t` is measured in units of `direction`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// Where the ray starts (`t = 0`).
    pub origin: Vec3,
    /// The direction, not necessarily of unit length.
    pub direction: Vec3,
}

impl Ray {
    /// A ray from `origin` along `direction`.
    #[inline]
    pub const fn new(origin: Vec3, direction: Vec3) -> Self {
        Self { origin, direction }
    }

    /// The point at parameter `t`:
    ///
    /// ```text
    /// p(t) = origin + t * direction
    /// ```
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.direction
    }
}

/// A ray `origin + t * direction` in double precision, the form the camera computes.
///
/// Viewing rays are computed in `f64` so that the numbers printed for a homework
/// problem are the lecture's formula evaluated exactly; [`DRay::as_ray`] rounds a
/// ray to the tracer's `f32`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DRay {
    /// Where the ray starts (`t = 0`).
    pub origin: DVec3,
    /// The direction, not necessarily of unit length.
    pub direction: DVec3,
}

impl DRay {
    /// A ray from `origin` along `direction`.
    #[inline]
    pub const fn new(origin: DVec3, direction: DVec3) -> Self {
        Self { origin, direction }
    }

    /// The point at parameter `t`:
    ///
    /// ```text
    /// p(t) = origin + t * direction
    /// ```
    #[inline]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + t * self.direction
    }

    /// This ray rounded to single precision.
    #[inline]
    pub fn as_ray(&self) -> Ray {
        Ray::new(self.origin.as_vec3(), self.direction.as_vec3())
    }
}

/// A box of rays: every ray whose origin lies in the box from `origin[0]` to
/// `origin[1]` and whose direction lies in the box from `direction[0]` to
/// `direction[1]`, such as all the viewing rays a block of pixels can take (any film
/// point in its pixels, any point of the lens). [`World::reach`] says what any of them
/// may meet.
///
/// [`World::reach`]: crate::World::reach
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayBounds {
    /// The least and the greatest origin, coordinate by coordinate.
    pub origin: [DVec3; 2],
    /// The least and the greatest direction, coordinate by coordinate.
    pub direction: [DVec3; 2],
}

impl RayBounds {
    /// The smallest box of rays holding each of `rays`; `None` for no ray.
    ///
    /// A family of rays whose origin and direction are affine in some parameters (a
    /// planar camera's rays in the image point and the lens point) takes its extremes
    /// at the parameters' extremes: the box around the rays at the corners of a
    /// parameter box holds every ray of it.
    pub fn around(rays: impl IntoIterator<Item = DRay>) -> Option<Self> {
        let mut rays = rays.into_iter();
        let first = rays.next()?;
        let start = Self {
            origin: [first.origin; 2],
            direction: [first.direction; 2],
        };
        Some(rays.fold(start, |bounds, ray| Self {
            origin: [
                bounds.origin[0].min(ray.origin),
                bounds.origin[1].max(ray.origin),
            ],
            direction: [
                bounds.direction[0].min(ray.direction),
                bounds.direction[1].max(ray.direction),
            ],
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_is_measured_in_units_of_the_direction() {
        let ray = DRay::new(DVec3::new(1.0, 2.0, 3.0), DVec3::new(0.0, 0.0, -2.0));
        assert_eq!(ray.at(0.0), DVec3::new(1.0, 2.0, 3.0));
        assert_eq!(ray.at(1.5), DVec3::new(1.0, 2.0, 0.0));
        assert_eq!(ray.as_ray().at(1.5), Vec3::new(1.0, 2.0, 0.0));
    }

    #[test]
    fn bounds_hold_every_ray_and_touch_each_extreme() {
        let rays = [
            DRay::new(DVec3::new(1.0, -2.0, 0.0), DVec3::new(0.5, 0.0, -1.0)),
            DRay::new(DVec3::new(-1.0, 3.0, 0.5), DVec3::new(-0.5, 0.25, -2.0)),
            DRay::new(DVec3::new(0.0, 0.0, -4.0), DVec3::new(0.0, -0.75, -1.5)),
        ];
        let bounds = RayBounds::around(rays).unwrap();
        assert_eq!(
            bounds.origin,
            [DVec3::new(-1.0, -2.0, -4.0), DVec3::new(1.0, 3.0, 0.5)]
        );
        assert_eq!(
            bounds.direction,
            [DVec3::new(-0.5, -0.75, -2.0), DVec3::new(0.5, 0.25, -1.0)]
        );
        assert_eq!(RayBounds::around([]), None);
    }
}
