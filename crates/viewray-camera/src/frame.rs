//! The camera frame (e, u, v, w) and how it is built from eye, view and up.

use glam::{DVec2, DVec3};

use crate::CameraError;

/// The camera's pose: the eye `e` and an orthonormal, right-handed basis `u`, `v`, `w`,
/// with the `up` vector it was built from.
///
/// `u` points right in the image, `v` points up, `w` points back (the camera looks
/// along `-w`). A point with camera coordinates `(a, b, c)` is the world point
/// `e + a u + b v + c w`.
///
/// A `Frame` is only made by its constructors, which check their inputs: its fields are
/// private, so every frame that exists is finite and orthonormal (but for the mistaken
/// frames of the catalogue, see [`crate::Camera::with_mistakes`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    e: DVec3,
    u: DVec3,
    v: DVec3,
    w: DVec3,
    up: DVec3,
}

impl Frame {
    /// The lecture's canonical frame: eye at the origin, looking down `-z`, `v` along `+y`
    /// (and up `+y`).
    pub const CANONICAL: Frame = Frame {
        e: DVec3::ZERO,
        u: DVec3::X,
        v: DVec3::Y,
        w: DVec3::Z,
        up: DVec3::Y,
    };

    /// `e`, the eye: the centre of projection, or for parallel cameras a point on the
    /// image plane.
    #[inline]
    pub fn e(&self) -> DVec3 {
        self.e
    }

    /// `u`: points right in the image.
    #[inline]
    pub fn u(&self) -> DVec3 {
        self.u
    }

    /// `v`: points up in the image.
    #[inline]
    pub fn v(&self) -> DVec3 {
        self.v
    }

    /// `w`: points back, away from what the camera sees.
    #[inline]
    pub fn w(&self) -> DVec3 {
        self.w
    }

    /// The up vector the frame was built from, as given (not normalized, not
    /// necessarily perpendicular to the view); `+y` for [`Frame::CANONICAL`].
    #[inline]
    pub fn up(&self) -> DVec3 {
        self.up
    }

    /// The same basis with the eye moved to `eye`.
    ///
    /// # Errors
    /// [`CameraError::NotFinite`] if a coordinate of `eye` is NaN or infinite.
    pub fn with_eye(self, eye: DVec3) -> Result<Self, CameraError> {
        check_finite_vector("eye", eye)?;
        Ok(Self { e: eye, ..self })
    }

    /// A frame from its parts as they are: the catalogue's mistaken frames, which need
    /// not be orthonormal.
    pub(crate) fn from_parts(e: DVec3, u: DVec3, v: DVec3, w: DVec3, up: DVec3) -> Self {
        Self { e, u, v, w, up }
    }

    /// The frame of a camera at `eye` looking along `view`, with `up` fixing its roll
    /// (lecture, "Creating a camera basis").
    ///
    /// ```text
    /// e = eye
    /// w = -view / |view|
    /// u = (up x w) / |up x w|
    /// v = w x u
    /// ```
    ///
    /// `up` need not be perpendicular to `view` or of unit length: `v` is the unit vector
    /// in the plane of `up` and `view` that is perpendicular to `view`, on `up`'s side.
    ///
    /// # Errors
    /// [`CameraError::NotFinite`] if a coordinate is NaN or infinite,
    /// [`CameraError::ZeroView`] or [`CameraError::ZeroUp`] for a zero vector, and
    /// [`CameraError::UpParallelToView`] when `up` is parallel to `view` (the roll is
    /// then undefined).
    pub fn from_eye_view_up(eye: DVec3, view: DVec3, up: DVec3) -> Result<Self, CameraError> {
        check_finite_vector("eye", eye)?;
        check_finite_vector("view", view)?;
        check_finite_vector("up", up)?;
        let given_up = up;
        // Normalize the inputs first so the tests below are relative and so huge or tiny
        // (but finite) vectors do not overflow or underflow.
        let view = normalize_scaled(view).ok_or(CameraError::ZeroView)?;
        let up = normalize_scaled(up).ok_or(CameraError::ZeroUp)?;
        let w = -view;
        let up_cross_w = up.cross(w);
        // |up x w| is the sine of the angle between up and view.
        if up_cross_w.length() < PARALLEL_TOLERANCE {
            return Err(CameraError::UpParallelToView);
        }
        let u = up_cross_w.normalize();
        // w x u is a unit vector in exact arithmetic; normalizing removes the last-bit
        // error (1.0000000000000002) that would otherwise show in a homework answer.
        let v = w.cross(u).normalize();
        Ok(Self {
            e: eye,
            u,
            v,
            w,
            up: given_up,
        })
    }

    /// The frame of a camera at `eye` looking at the point `look_at`, with `up` fixing its
    /// roll: [`Frame::from_eye_view_up`] with `view = look_at - eye`.
    ///
    /// # Errors
    /// As [`Frame::from_eye_view_up`]; [`CameraError::ZeroView`] when `look_at == eye`.
    pub fn from_eye_look_at_up(eye: DVec3, look_at: DVec3, up: DVec3) -> Result<Self, CameraError> {
        check_finite_vector("look_at", look_at)?;
        Self::from_eye_view_up(eye, look_at - eye, up)
    }

    /// The world vector with camera coordinates `c`: `c.x u + c.y v + c.z w`.
    #[inline]
    pub fn world_from_camera_vector(&self, c: DVec3) -> DVec3 {
        self.world_from_camera_xy(c.truncate(), c.z * self.w)
    }

    /// `c.x u + c.y v + w_term`: [`Frame::world_from_camera_vector`] of `(c.x, c.y, z)`
    /// with its last term `z w` given, bit for bit the same when `w_term == z * w`. A
    /// camera whose rays all share `z` works that term out once.
    #[inline]
    pub(crate) fn world_from_camera_xy(&self, c: DVec2, w_term: DVec3) -> DVec3 {
        c.x * self.u + c.y * self.v + w_term
    }

    /// The world point with camera coordinates `c`: `e + c.x u + c.y v + c.z w`.
    #[inline]
    pub fn world_from_camera_point(&self, c: DVec3) -> DVec3 {
        self.e + self.world_from_camera_vector(c)
    }

    /// The camera coordinates of the world point `p`: `((p-e).u, (p-e).v, (p-e).w)`.
    #[inline]
    pub fn camera_from_world_point(&self, p: DVec3) -> DVec3 {
        let q = p - self.e;
        DVec3::new(q.dot(self.u), q.dot(self.v), q.dot(self.w))
    }
}

/// Up and view count as parallel when the sine of the angle between them is below this.
const PARALLEL_TOLERANCE: f64 = 1e-9;

/// `value / |value|`, computed so that a finite vector never overflows or underflows on
/// the way; `None` for the zero vector.
fn normalize_scaled(value: DVec3) -> Option<DVec3> {
    let largest = value.abs().max_element();
    if largest == 0.0 {
        return None;
    }
    (value / largest).try_normalize()
}

pub(crate) fn check_finite_vector(name: &'static str, value: DVec3) -> Result<(), CameraError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(CameraError::NotFinite {
            name,
            value: format!("({}, {}, {})", value.x, value.y, value.z),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check_error(eye: DVec3, view: DVec3, up: DVec3, expected: CameraError) {
        assert_eq!(Frame::from_eye_view_up(eye, view, up), Err(expected));
    }

    #[test]
    fn degenerate_inputs_are_errors_not_nans() {
        let o = DVec3::ZERO;
        check_error(o, DVec3::ZERO, DVec3::Y, CameraError::ZeroView);
        check_error(o, -DVec3::Z, DVec3::ZERO, CameraError::ZeroUp);
        check_error(o, DVec3::Y, DVec3::Y, CameraError::UpParallelToView);
        check_error(o, DVec3::Y, -3.0 * DVec3::Y, CameraError::UpParallelToView);
        check_error(
            DVec3::new(f64::NAN, 0.0, 0.0),
            -DVec3::Z,
            DVec3::Y,
            CameraError::NotFinite {
                name: "eye",
                value: "(NaN, 0, 0)".into(),
            },
        );
        assert_eq!(
            Frame::from_eye_look_at_up(DVec3::ONE, DVec3::ONE, DVec3::Y),
            Err(CameraError::ZeroView)
        );
    }

    #[test]
    fn extreme_but_finite_vectors_work() {
        let frame =
            Frame::from_eye_view_up(DVec3::ZERO, DVec3::new(0.0, 0.0, -1e300), 1e-300 * DVec3::Y)
                .unwrap();
        assert_eq!(frame.w, DVec3::Z);
        assert_eq!(frame.u, DVec3::X);
        assert_eq!(frame.v, DVec3::Y);
    }
}
