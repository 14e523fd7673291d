//! The aperture's shape: round, or a regular polygon of blades (a real lens's iris).

use std::f64::consts::{PI, TAU};

use glam::DVec2;

use crate::{CameraError, sample_regular_polygon, sample_unit_disk_concentric};

/// The shape of a thin lens's aperture, in unit-disk coordinates (the lens point is
/// `e + r (lx U + ly V)`): the unit disk, or the regular polygon of `blades` corners
/// inscribed in the unit circle, turned by `rotation`, as Blender Cycles'
/// `aperture_blades` and `aperture_rotation` make it.
///
/// ```text
/// blades = 0        the unit disk (the round lens of the lecture)
/// blades = N >= 3   corners at the angles rotation + (2k + 1) pi / N, k = 0 .. N-1;
///                   the middle of an edge at the angle rotation, cos(pi / N) from
///                   the centre
/// ```
///
/// Angles are measured from `U` toward `V`. An out-of-focus point light is pictured as
/// this shape, in the image's own directions (`U` right, `V` up), when it lies beyond the
/// plane of focus, and turned half a turn when it lies nearer (its rays cross at the
/// point, before they reach the plane of focus).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iris {
    /// `N`: the number of blades, 0 for a round aperture, else at least 3.
    pub blades: u32,
    /// The polygon's rotation, in radians in `[-pi, pi]` (Blender's range); ignored by a
    /// round aperture.
    pub rotation: f64,
}

impl Iris {
    /// The most blades: a polygon of 64 corners is a circle to within 0.12 % of its
    /// radius (`1 - cos(pi / 64)`).
    pub const MAX_BLADES: u32 = 64;

    /// The round aperture: the unit disk.
    pub const ROUND: Iris = Iris {
        blades: 0,
        rotation: 0.0,
    };

    /// An aperture of `blades` blades (0 for round) turned by `rotation` radians, any
    /// angle: it is wrapped into `[-pi, pi)` by whole turns.
    ///
    /// # Errors
    /// As [`Iris::validate`].
    pub fn new(blades: u32, rotation: f64) -> Result<Iris, CameraError> {
        check_rotation(rotation, rotation.to_degrees())?;
        let iris = Iris {
            blades,
            rotation: rotation - TAU * ((rotation + PI) / TAU).floor(),
        };
        iris.validate()?;
        Ok(iris)
    }

    /// An aperture of `blades` blades turned by `degrees`, any angle: wrapped into
    /// `[-180, 180)` by whole turns (so `-30` and `330` are the same polygon), then
    /// turned into radians, as a scene file's `blade_rotation` is.
    ///
    /// # Errors
    /// As [`Iris::validate`].
    pub fn from_degrees(blades: u32, degrees: f64) -> Result<Iris, CameraError> {
        check_rotation(degrees, degrees)?;
        // Whole turns off: exact for the angles people write.
        let wrapped = degrees - 360.0 * ((degrees + 180.0) / 360.0).floor();
        let iris = Iris {
            blades,
            rotation: wrapped.to_radians(),
        };
        iris.validate()?;
        Ok(iris)
    }

    /// Whether the aperture is the round one.
    pub fn is_round(&self) -> bool {
        self.blades == 0
    }

    /// Checks the blades (0, or 3 to [`Iris::MAX_BLADES`]: one or two blades close no
    /// polygon) and the rotation (finite, within `[-pi, pi]`).
    ///
    /// # Errors
    /// [`CameraError::OutOfRange`] for `blades` 1, 2 or above 64 or a rotation outside
    /// `[-pi, pi]`; [`CameraError::NotFinite`] for a rotation that is not finite.
    pub fn validate(&self) -> Result<(), CameraError> {
        if self.blades == 1 || self.blades == 2 || self.blades > Self::MAX_BLADES {
            return Err(CameraError::OutOfRange {
                name: "blades",
                expected: "0 (a round lens) or 3 to 64 (a polygon)",
                value: f64::from(self.blades),
            });
        }
        check_rotation(self.rotation, self.rotation.to_degrees())?;
        if (-PI..=PI).contains(&self.rotation) {
            Ok(())
        } else {
            Err(CameraError::OutOfRange {
                name: "blade_rotation",
                expected: "between -180 and 180 degrees (Iris::new wraps any angle)",
                value: self.rotation.to_degrees(),
            })
        }
    }

    /// The lens point, in unit-disk coordinates, of the lens sample `p_lens` in the
    /// unit square: [`sample_unit_disk_concentric`] for a round aperture,
    /// [`sample_regular_polygon`] for blades. Both are uniform over the aperture and
    /// send the square's centre to the lens centre.
    #[inline]
    pub fn sample(&self, p_lens: DVec2) -> DVec2 {
        if self.is_round() {
            sample_unit_disk_concentric(p_lens)
        } else {
            sample_regular_polygon(p_lens, self.blades, self.rotation)
        }
    }

    /// Whether the lens point `point` (unit-disk coordinates) lies on the aperture, its
    /// edge included (with a slack of `1e-12` for points typed to a dozen digits): in the
    /// unit disk, or on the inner side of every edge of the polygon.
    pub fn contains(&self, point: DVec2) -> bool {
        const SLACK: f64 = 1e-12;
        if self.is_round() {
            return point.length() <= 1.0 + SLACK;
        }
        // The edge the point faces: its outward normal is the nearest of those at the
        // angles rotation + k 2 pi / N; inside that edge is inside them all.
        let corners = f64::from(self.blades);
        let wedge = TAU / corners;
        let k = ((point.y.atan2(point.x) - self.rotation) / wedge).round();
        let (sin, cos) = (self.rotation + k * wedge).sin_cos();
        point.dot(DVec2::new(cos, sin)) <= (PI / corners).cos() + SLACK
    }

    /// The polygon's corners, in unit-disk coordinates, counter-clockwise from the
    /// angle `rotation + pi / N`; none for a round aperture.
    pub fn corners(&self) -> Vec<DVec2> {
        (0..self.blades)
            .map(|k| {
                let angle =
                    self.rotation + (2.0 * f64::from(k) + 1.0) * PI / f64::from(self.blades);
                let (sin, cos) = angle.sin_cos();
                DVec2::new(cos, sin)
            })
            .collect()
    }
}

impl Default for Iris {
    fn default() -> Self {
        Self::ROUND
    }
}

/// A rotation must be a finite angle; `degrees` is how it is reported.
fn check_rotation(rotation: f64, degrees: f64) -> Result<(), CameraError> {
    if rotation.is_finite() {
        Ok(())
    } else {
        Err(CameraError::NotFinite {
            name: "blade_rotation",
            value: degrees.to_string(),
        })
    }
}
