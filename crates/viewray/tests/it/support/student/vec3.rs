//! The student's own three-vector: points, directions and linear colours, in f64, with just
//! the operations a small ray tracer needs.

use std::ops::{Add, Mul, Neg, Sub};

/// A point, a direction or a linear RGB colour.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct Vec3 {
    /// The first coordinate (or red).
    pub(crate) x: f64,
    /// The second coordinate (or green).
    pub(crate) y: f64,
    /// The third coordinate (or blue).
    pub(crate) z: f64,
}

impl Vec3 {
    /// The origin, and black.
    pub(crate) const ZERO: Self = Self::new(0.0, 0.0, 0.0);
    /// The world's x axis.
    pub(crate) const X: Self = Self::new(1.0, 0.0, 0.0);
    /// The world's y axis.
    pub(crate) const Y: Self = Self::new(0.0, 1.0, 0.0);
    /// The world's z axis.
    pub(crate) const Z: Self = Self::new(0.0, 0.0, 1.0);

    /// The vector `(x, y, z)`.
    pub(crate) const fn new(x: f64, y: f64, z: f64) -> Self {
        Self { x, y, z }
    }

    /// The grey `(g, g, g)`.
    pub(crate) const fn splat(g: f64) -> Self {
        Self::new(g, g, g)
    }

    /// The dot product `a . b`.
    pub(crate) fn dot(self, b: Self) -> f64 {
        self.x * b.x + self.y * b.y + self.z * b.z
    }

    /// The cross product `a x b` (right-handed).
    pub(crate) fn cross(self, b: Self) -> Self {
        Self::new(
            self.y * b.z - self.z * b.y,
            self.z * b.x - self.x * b.z,
            self.x * b.y - self.y * b.x,
        )
    }

    /// The length `|a|`.
    pub(crate) fn length(self) -> f64 {
        self.dot(self).sqrt()
    }

    /// `a / |a|` (not a number for the zero vector, as a student's code would give).
    pub(crate) fn normalized(self) -> Self {
        self * (1.0 / self.length())
    }

    /// The product coordinate by coordinate (a colour filtered by another).
    pub(crate) fn times(self, b: Self) -> Self {
        Self::new(self.x * b.x, self.y * b.y, self.z * b.z)
    }

    /// The coordinates as an array.
    pub(crate) fn to_array(self) -> [f64; 3] {
        [self.x, self.y, self.z]
    }

    /// The vector with these coordinates.
    pub(crate) fn from_array([x, y, z]: [f64; 3]) -> Self {
        Self::new(x, y, z)
    }
}

impl Add for Vec3 {
    type Output = Self;
    fn add(self, b: Self) -> Self {
        Self::new(self.x + b.x, self.y + b.y, self.z + b.z)
    }
}

impl Sub for Vec3 {
    type Output = Self;
    fn sub(self, b: Self) -> Self {
        Self::new(self.x - b.x, self.y - b.y, self.z - b.z)
    }
}

impl Neg for Vec3 {
    type Output = Self;
    fn neg(self) -> Self {
        Self::new(-self.x, -self.y, -self.z)
    }
}

impl Mul<f64> for Vec3 {
    type Output = Self;
    fn mul(self, k: f64) -> Self {
        Self::new(self.x * k, self.y * k, self.z * k)
    }
}

impl Mul<Vec3> for f64 {
    type Output = Vec3;
    fn mul(self, a: Vec3) -> Vec3 {
        a * self
    }
}
