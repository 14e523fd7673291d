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
}
