//! The student's camera, straight from the lecture: pixel to image plane (`u`, `v`), the
//! frame from eye, view and up (`e`, `U`, `V`, `W`), and each family's viewing ray; and
//! the inverse, `project`. Each step takes a set of the lecture's mistakes and makes those
//! that belong to it, each by its own formula, so that any combination can be made.
//!
//! Sample offsets: `(ox, oy)` in `[0, 1)^2` picks a point in the pixel, the centre
//! `(1/2, 1/2)` giving the lecture's ray. The mistakes that drop the 1/2 (`pixel-corner`,
//! `pixel-one-based`, `size-minus-one`) keep the offset relative to the centre,
//! `ox - 1/2`, so that their centre sample is the catalogue's formula and the other
//! samples move with it, as a student's jittered samples would around their own point.

use super::mistakes::Mistake;
use super::vec3::Vec3;

/// Where the camera looks: at a point, or along a direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Aim {
    /// `view = target - eye` (the scene file's `look_at`).
    LookAt(Vec3),
    /// The view direction itself (the scene file's `view`).
    View(Vec3),
}

/// One of the lecture's projection families, with the scene file's fields.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Projection {
    /// Origin `e`, direction `(u + sx) U + (v + sy) V - d W`.
    Perspective {
        /// The distance `d` from the eye to the image plane.
        d: f64,
        /// The viewport `(vw, vh)` on the image plane.
        viewport: (f64, f64),
        /// The lens shift `(sx, sy)`, in the image plane's units.
        shift: (f64, f64),
    },
    /// Origin `e + u U + v V`, direction `-W`.
    Orthographic {
        /// The viewport `(vw, vh)`.
        viewport: (f64, f64),
    },
    /// Origin `e + u U + v V`, direction `-W - L (cos phi U + sin phi V)`.
    Oblique {
        /// The viewport `(vw, vh)`.
        viewport: (f64, f64),
        /// The ratio `L` (1 cavalier, 1/2 cabinet).
        ratio: f64,
        /// The angle `phi`, in degrees (as the scene file writes it).
        angle_degrees: f64,
    },
}

impl Projection {
    /// The viewport `(vw, vh)`, whatever the family.
    pub(crate) fn viewport(&self) -> (f64, f64) {
        match *self {
            Projection::Perspective { viewport, .. }
            | Projection::Orthographic { viewport }
            | Projection::Oblique { viewport, .. } => viewport,
        }
    }
}

/// A camera as a scene file writes it: eye, where it looks, up, and the projection.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CameraSpec {
    /// The eye `e`.
    pub(crate) eye: Vec3,
    /// `look_at` or `view`.
    pub(crate) aim: Aim,
    /// The up vector.
    pub(crate) up: Vec3,
    /// The projection family and its numbers.
    pub(crate) projection: Projection,
}

impl CameraSpec {
    /// The lecture's canonical camera: eye at the origin looking down `-z`, `d = 1`, a
    /// 1 x 1 viewport.
    pub(crate) fn canonical() -> Self {
        Self {
            eye: Vec3::ZERO,
            aim: Aim::View(-Vec3::Z),
            up: Vec3::Y,
            projection: Projection::Perspective {
                d: 1.0,
                viewport: (1.0, 1.0),
                shift: (0.0, 0.0),
            },
        }
    }

    /// The view direction, `target - eye` for [`Aim::LookAt`].
    pub(crate) fn view(&self) -> Vec3 {
        match self.aim {
            Aim::LookAt(target) => target - self.eye,
            Aim::View(view) => view,
        }
    }
}

/// The camera frame `(e, U, V, W)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Frame {
    /// The eye `e`.
    pub(crate) e: Vec3,
    /// `U`, pointing right.
    pub(crate) u: Vec3,
    /// `V`, pointing up.
    pub(crate) v: Vec3,
    /// `W`, pointing back.
    pub(crate) w: Vec3,
}

/// A viewing ray `origin + t direction`, `t > 0`; the direction is not normalized.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ray {
    /// Where it starts.
    pub(crate) origin: Vec3,
    /// Where it goes, exactly as the lecture's formula gives it.
    pub(crate) direction: Vec3,
}

impl Ray {
    /// The point `origin + t direction`.
    pub(crate) fn at(&self, t: f64) -> Vec3 {
        self.origin + self.direction * t
    }
}

/// The camera frame from eye, view and up, with the frame's mistakes made:
///
/// ```text
/// e = eye;  w = -view/|view|;  u = (up x w)/|up x w|;  v = w x u
/// ```
///
/// A degenerate camera (zero view, up parallel to view) gives not-a-number, as a student's
/// code would.
pub(crate) fn frame(camera: &CameraSpec, mistakes: &[Mistake]) -> Frame {
    let has = |m| mistakes.contains(&m);
    let view = camera.view();
    let up = camera.up;
    // Step 1: e = eye.
    let e = camera.eye;
    // Step 2: w points back, away from the view direction.
    let w = if has(Mistake::WView) {
        view * (1.0 / view.length())
    } else {
        -view * (1.0 / view.length())
    };
    // Step 3: u points right.
    let u_unnormalized = if has(Mistake::UCrossOrder) {
        w.cross(up)
    } else {
        up.cross(w)
    };
    let u = if has(Mistake::UNotNormalized) {
        u_unnormalized
    } else {
        u_unnormalized.normalized()
    };
    // Step 4: v points up.
    let v = if has(Mistake::VCrossOrder) {
        u.cross(w)
    } else {
        w.cross(u)
    };
    Frame { e, u, v, w }
}

/// The image-plane point `(u, v)` of the sample at `offset = (ox, oy)` in pixel
/// `pixel = (row, col)` of an image of `size = (W, H)`, with the pixel's mistakes made:
///
/// ```text
/// u =  ((col + ox)/W - 1/2) vw
/// v = -((row + oy)/H - 1/2) vh
/// ```
pub(crate) fn image_plane(
    camera: &CameraSpec,
    mistakes: &[Mistake],
    size: (u32, u32),
    pixel: (u32, u32),
    offset: (f64, f64),
) -> (f64, f64) {
    let has = |m| mistakes.contains(&m);
    let (width, height) = (f64::from(size.0), f64::from(size.1));
    let (row, col) = (f64::from(pixel.0), f64::from(pixel.1));
    let (ox, oy) = offset;
    // The viewport.
    let (mut vw, mut vh) = camera.projection.viewport();
    if has(Mistake::ViewportSwapped) {
        (vw, vh) = (vh, vw);
    }
    if has(Mistake::ViewportMissing) {
        (vw, vh) = (1.0, 1.0);
    }
    // The sample's position across the image, in pixels (the numerator).
    let (x, y) = if has(Mistake::PixelOneBased) {
        // (j - 1/2) written as j = col + 1.
        (col + 1.0 + (ox - 0.5), row + 1.0 + (oy - 0.5))
    } else if has(Mistake::PixelCorner) || has(Mistake::SizeMinusOne) {
        // The corner, col, where the centre col + 1/2 belongs.
        (col + (ox - 0.5), row + (oy - 0.5))
    } else {
        (col + ox, row + oy)
    };
    // The image's size (the denominator).
    let (across, down) = if has(Mistake::SizeMinusOne) {
        (width - 1.0, height - 1.0)
    } else {
        (width, height)
    };
    // The fractions across and down the image.
    let (fraction_u, fraction_v) = if has(Mistake::IJSwapped) {
        (y / across, x / down)
    } else {
        (x / across, y / down)
    };
    // The signs.
    let u = if has(Mistake::USign) {
        -(fraction_u - 0.5) * vw
    } else {
        (fraction_u - 0.5) * vw
    };
    let v = if has(Mistake::VSign) {
        (fraction_v - 0.5) * vh
    } else {
        -(fraction_v - 0.5) * vh
    };
    (u, v)
}

/// The viewing ray of the sample at `offset = (ox, oy)` in pixel `pixel = (row, col)` of an
/// image of `size = (W, H)`, with every mistake of `mistakes` made at its step:
///
/// ```text
/// Perspective:  origin e            direction (u + sx) U + (v + sy) V - d W
/// Orthographic: origin e + u U + v V direction -W
/// Oblique:      origin e + u U + v V direction -W - L (cos phi U + sin phi V)
/// ```
///
/// `basis-missing` takes the frame as the world's axes: the perspective direction
/// `(u + sx, v + sy, -d)`, and for the parallel families the origin `e + (u, v, 0)`.
pub(crate) fn ray(
    camera: &CameraSpec,
    mistakes: &[Mistake],
    size: (u32, u32),
    pixel: (u32, u32),
    offset: (f64, f64),
) -> Ray {
    let has = |m| mistakes.contains(&m);
    let (u, v) = image_plane(camera, mistakes, size, pixel, offset);
    let frame = frame(camera, mistakes);
    // The vectors the student multiplies u, v and d by.
    let (axis_u, axis_v, axis_w) = if has(Mistake::BasisMissing) {
        (Vec3::X, Vec3::Y, Vec3::Z)
    } else {
        (frame.u, frame.v, frame.w)
    };
    let eye = if has(Mistake::EyeMissing) {
        Vec3::ZERO
    } else {
        frame.e
    };
    match camera.projection {
        Projection::Perspective { d, shift, .. } => {
            let (mut sx, mut sy) = shift;
            if has(Mistake::ShiftSign) {
                (sx, sy) = (-sx, -sy);
            }
            if has(Mistake::ShiftMissing) {
                (sx, sy) = (0.0, 0.0);
            }
            let d = if has(Mistake::DistanceMissing) {
                1.0
            } else {
                d
            };
            let toward_w = if has(Mistake::DistanceSign) { d } else { -d };
            Ray {
                origin: eye,
                direction: (u + sx) * axis_u + (v + sy) * axis_v + toward_w * axis_w,
            }
        }
        Projection::Orthographic { .. } => {
            if has(Mistake::OrthoAsPerspective) {
                Ray {
                    origin: eye,
                    direction: u * axis_u + v * axis_v - axis_w,
                }
            } else if has(Mistake::OrthoOriginFixed) {
                Ray {
                    origin: eye,
                    direction: -axis_w,
                }
            } else {
                Ray {
                    origin: eye + u * axis_u + v * axis_v,
                    direction: -axis_w,
                }
            }
        }
        Projection::Oblique {
            ratio,
            angle_degrees,
            ..
        } => {
            let (sin, cos) = angle_degrees.to_radians().sin_cos();
            let slant = ratio * (cos * axis_u + sin * axis_v);
            let direction = if has(Mistake::ObliqueAsOrtho) {
                -axis_w
            } else if has(Mistake::ObliqueSign) {
                -axis_w + slant
            } else {
                -axis_w - slant
            };
            Ray {
                origin: eye + u * axis_u + v * axis_v,
                direction,
            }
        }
    }
}

/// Where `point` appears in the correct camera's image of `size = (W, H)`: continuous
/// image coordinates `(x, y)`, `x` from the left edge and `y` from the top, in pixels; `None`
/// where no ray of the camera reaches it (at or behind a perspective eye's plane, at or
/// behind a parallel camera's image plane). With `q = point - e` in the frame,
/// `(a, b, c) = (q.U, q.V, q.W)` and the depth `D = -c`:
///
/// ```text
/// Perspective:  u = a d/D - sx,        v = b d/D - sy
/// Orthographic: u = a,                 v = b
/// Oblique:      u = a + L D cos(phi),  v = b + L D sin(phi)
/// x = (u/vw + 1/2) W,  y = (1/2 - v/vh) H
/// ```
pub(crate) fn project(camera: &CameraSpec, size: (u32, u32), point: Vec3) -> Option<(f64, f64)> {
    let frame = frame(camera, &[]);
    let q = point - frame.e;
    let (a, b, depth) = (q.dot(frame.u), q.dot(frame.v), -q.dot(frame.w));
    if depth <= 0.0 {
        return None;
    }
    let (u, v) = match camera.projection {
        Projection::Perspective { d, shift, .. } => {
            (a * d / depth - shift.0, b * d / depth - shift.1)
        }
        Projection::Orthographic { .. } => (a, b),
        Projection::Oblique {
            ratio,
            angle_degrees,
            ..
        } => {
            let (sin, cos) = angle_degrees.to_radians().sin_cos();
            (a + ratio * depth * cos, b + ratio * depth * sin)
        }
    };
    let (vw, vh) = camera.projection.viewport();
    let (width, height) = (f64::from(size.0), f64::from(size.1));
    Some(((u / vw + 0.5) * width, (0.5 - v / vh) * height))
}
