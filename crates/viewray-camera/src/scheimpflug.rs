//! A tilted thin lens: the plane of sharp focus from the Scheimpflug and hinge rules,
//! and the rays that meet on it.
//!
//! # The geometry
//!
//! In camera coordinates (the lens centre `e` at the origin, `U`, `V`, `W` the axes, the
//! camera looking down `-W`), a thin lens of focal length `F` focused at the distance
//! `f` has its sensor behind it, where the untilted lens images the plane at `f`
//! (`1/s + 1/f = 1/F`):
//!
//! ```text
//! s = F f / (f - F)                         the sensor plane: z = s
//! ```
//!
//! A physical camera's image plane is its sensor mirrored in front of the lens at the
//! focal length, so `F = d` (the focal length in metres). Tilting the lens by `alpha`
//! about `U` (its top toward the scene) and then swinging it by `beta` about `V` (its
//! right side toward the scene) turns the lens's axis, its unit normal toward the scene,
//! from `-W` to
//!
//! ```text
//! n = (-cos(alpha) sin(beta), -sin(alpha), -cos(alpha) cos(beta))
//! ```
//!
//! while the sensor stays where it was. The plane of sharp focus is the lens's image of
//! the sensor plane: a point `P` in front of the lens images to `F P / (F - n.P)`
//! behind it, which lies on `z = s` exactly when
//!
//! ```text
//! m . P = F,   m = n + (1 - F/f) W          the plane of focus
//! ```
//!
//! It holds both lines of the view-camera rules:
//!
//! - the **Scheimpflug line**, where the sensor plane and the lens plane meet
//!   (`z = s`, `n.P = 0`): sensor, lens and plane of focus share this line;
//! - the **hinge line**, where the lens's front focal plane (`n.P = F`) meets the plane
//!   through the lens centre parallel to the sensor (`z = 0`): at the distance
//!   `J = F / sin(theta)` from the lens centre, `theta` the angle between the lens's axis
//!   and the camera's (`cos(theta) = cos(alpha) cos(beta)`). Refocusing (changing `f`)
//!   turns the plane of focus about this line.
//!
//! Untilted (`n = -W`), the plane of focus is `z = -f`, the lecture's focus plane. A
//! 90 mm lens tilted 3 degrees has its hinge line `90 / sin(3 deg) = 1720` mm below the
//! lens centre.
//!
//! # The rays
//!
//! A pixel's centre ray goes through the lens centre along the pinhole direction
//! `c = (u + sx) U + (v + sy) V - d W`; it meets the plane of focus at `t = F / (m.c)`.
//! Every ray of the pixel goes from its lens point `L = r (lx U + ly V)` (the aperture
//! stays in the plane of `U` and `V`, as for the untilted lens) through that point:
//!
//! ```text
//! origin    = e + L
//! direction = (F / m.c) c - L          when m.c > 0: t = 1 is on the plane
//! direction = c - (m.c / F) L          otherwise
//! ```
//!
//! The second line is the same family of lines through the (virtual) meeting point,
//! written so that it stays finite: where the centre ray runs parallel to the plane of
//! focus (its horizon, `m.c = 0`) or meets it behind the lens, the sharp point lies at
//! infinity or behind the eye and the lens's rays leave parallel or spreading, as a real
//! lens's do. (Near the horizon `F / m.c` is large: the direction is long, the ray the
//! same.)
//! Untilted (`m.c = F d / f`) the first line is the lecture's thin lens,
//! `(f / d) c - L`.

use glam::{DVec2, DVec3};

use crate::projection::CameraSpaceRay;
use crate::{CameraError, Frame, ThinLens};

/// A plane: a point on it and its unit normal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane3 {
    /// A point of the plane.
    pub point: DVec3,
    /// The unit normal.
    pub normal: DVec3,
}

/// A straight line: a point on it and its unit direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Line3 {
    /// A point of the line.
    pub point: DVec3,
    /// The unit direction.
    pub direction: DVec3,
}

/// The planes and lines of a tilted thin lens in world space (see the module
/// `scheimpflug`'s doc for the formulas): sensor, lens and plane of focus meet in the
/// Scheimpflug line; the plane of focus also holds the hinge line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TiltedFocus {
    /// The sensor, behind the lens at `s = F f / (f - F)`: point `e + s w`, normal `w`.
    pub sensor: Plane3,
    /// The lens plane through `e`, normal `n` (toward the scene).
    pub lens: Plane3,
    /// The lens's front focal plane, `F` in front of the lens plane: normal `n`.
    pub front_focal: Plane3,
    /// The plane of sharp focus ([`crate::Camera::focus_plane`]).
    pub focus: Plane3,
    /// Where the sensor plane and the lens plane meet; the plane of focus holds it too.
    /// Its point is the one nearest the sensor's centre `e + s w`; its direction
    /// `w x n`, normalized.
    pub scheimpflug_line: Line3,
    /// Where the front focal plane meets the plane through `e` parallel to the sensor,
    /// `F / sin(theta)` from `e`; the plane of focus turns about it as the focus
    /// changes. Its point is the one nearest `e`; its direction `w x n`, normalized.
    pub hinge_line: Line3,
}

impl ThinLens {
    /// Whether the lens plane is tilted or swung.
    pub fn is_tilted(&self) -> bool {
        self.tilt != 0.0 || self.swing != 0.0
    }

    /// `n`: the lens's unit normal toward the scene, in camera coordinates:
    /// `(-cos(alpha) sin(beta), -sin(alpha), -cos(alpha) cos(beta))`, so `(0, 0, -1)`
    /// untilted.
    pub fn lens_normal(&self) -> DVec3 {
        let (sin_tilt, cos_tilt) = self.tilt.sin_cos();
        let (sin_swing, cos_swing) = self.swing.sin_cos();
        DVec3::new(-cos_tilt * sin_swing, -sin_tilt, -cos_tilt * cos_swing)
    }

    /// `s = F f / (f - F)`: how far behind the lens the sensor sits, with `F = d` the
    /// focal length, for a lens focused at `f` beyond it.
    pub fn sensor_distance(&self) -> f64 {
        self.distance * self.focus / (self.focus - self.distance)
    }

    /// The plane of focus in camera coordinates as `(m, F)`, the plane `m . P = F`:
    /// `m = n + (1 - F/f) W`.
    fn focus_plane_equation(&self) -> (DVec3, f64) {
        let focal_length = self.distance;
        let m = self.lens_normal() + DVec3::Z * (1.0 - focal_length / self.focus);
        (m, focal_length)
    }

    /// Checks the tilt and swing (finite, strictly between -90 and 90 degrees) and, for a
    /// tilted lens, that it focuses beyond its focal length (`f > d`, so the sensor lies
    /// at a finite distance behind it).
    pub(crate) fn validate_tilt(&self) -> Result<(), CameraError> {
        check_tilt_angle("lens_tilt", self.tilt)?;
        check_tilt_angle("lens_swing", self.swing)?;
        if self.is_tilted() && self.focus <= self.distance {
            return Err(CameraError::FocusWithinFocalLength {
                focus: self.focus,
                focal_length: self.distance,
            });
        }
        Ok(())
    }

    /// The tilted lens's ray through the image-plane point `uv` from the unit-disk lens
    /// point `lens`, in camera coordinates (see the module doc).
    pub(crate) fn tilted_ray(&self, uv: DVec2, lens: DVec2) -> CameraSpaceRay {
        let centre = self.pinhole().direction(uv);
        let lens_offset = (self.aperture * lens).extend(0.0);
        let (m, focal_length) = self.focus_plane_equation();
        let along = m.dot(centre);
        // Where the centre ray meets the plane ahead, every ray reaches the point at
        // t = 1; elsewhere (behind the eye, or parallel: along <= 0) they spread from it.
        let direction = if along > 0.0 {
            (focal_length / along) * centre - lens_offset
        } else {
            centre - (along / focal_length) * lens_offset
        };
        CameraSpaceRay {
            origin: lens_offset,
            direction,
        }
    }

    /// The plane of focus in world coordinates for the frame `frame`: its point nearest
    /// the lens centre, and its unit normal toward the lens centre (`w` untilted, where
    /// the point is `e - f w`).
    pub(crate) fn focus_plane(&self, frame: &Frame) -> Plane3 {
        if !self.is_tilted() {
            return Plane3 {
                point: frame.e() - self.focus * frame.w(),
                normal: frame.w(),
            };
        }
        let (m, focal_length) = self.focus_plane_equation();
        Plane3 {
            point: frame.world_from_camera_point(focal_length / m.length_squared() * m),
            normal: frame.world_from_camera_vector(-m.normalize()),
        }
    }

    /// The tilted lens's planes and lines in world coordinates; `None` untilted (the
    /// lines are at infinity).
    pub(crate) fn tilted_focus(&self, frame: &Frame) -> Option<TiltedFocus> {
        if !self.is_tilted() {
            return None;
        }
        let n = self.lens_normal();
        let focal_length = self.distance;
        let s = self.sensor_distance();
        let plane = |point: DVec3, normal: DVec3| Plane3 {
            point: frame.world_from_camera_point(point),
            normal: frame.world_from_camera_vector(normal),
        };
        // Both lines run along w x n; in the plane z = z0 the line n.P = c is the set
        // n_xy . P_xy = c - n_z z0, whose point nearest (0, 0, z0) is that over |n_xy|^2
        // along n_xy.
        let across = DVec3::new(n.x, n.y, 0.0);
        let direction = DVec3::new(-n.y, n.x, 0.0).normalize();
        let line = |z0: f64, c: f64| Line3 {
            point: frame.world_from_camera_point(
                (c - n.z * z0) / across.length_squared() * across + DVec3::Z * z0,
            ),
            direction: frame.world_from_camera_vector(direction),
        };
        Some(TiltedFocus {
            sensor: plane(DVec3::Z * s, DVec3::Z),
            lens: plane(DVec3::ZERO, n),
            front_focal: plane(focal_length * n, n),
            focus: self.focus_plane(frame),
            scheimpflug_line: line(s, 0.0),
            hinge_line: line(0.0, focal_length),
        })
    }
}

/// A tilt or swing must be finite and strictly between -90 and 90 degrees.
fn check_tilt_angle(name: &'static str, angle: f64) -> Result<(), CameraError> {
    if !angle.is_finite() {
        return Err(CameraError::NotFinite {
            name,
            value: angle.to_degrees().to_string(),
        });
    }
    if angle.abs() < std::f64::consts::FRAC_PI_2 {
        Ok(())
    } else {
        Err(CameraError::OutOfRange {
            name,
            expected: "strictly between -90 and 90 degrees",
            value: angle.to_degrees(),
        })
    }
}
