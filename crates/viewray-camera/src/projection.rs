//! Every projection family of the lecture, plus the panoramic cameras.
//!
//! Each family is a rule that turns a point `(u, v)` on the image plane (or, for the
//! panoramic cameras, a continuous image point `(x, y)`) into a viewing ray expressed in
//! the camera's frame. [`crate::Camera`] supplies the frame and the pixel mapping.

use std::f64::consts::{PI, TAU};

use glam::{DVec2, DVec3};

use crate::{CameraError, image_plane_to_image, image_to_image_plane};

/// A projection: one of the lecture's four rules, or a panoramic camera.
///
/// Build the variants with their constructors or as struct literals; [`crate::Camera::new`]
/// validates them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Projection {
    /// Rays from the eye through the image plane at distance `d`.
    Perspective(Perspective),
    /// A perspective camera with a lens of finite aperture: depth of field.
    ThinLens(ThinLens),
    /// Parallel rays perpendicular to the image plane.
    Orthographic(Orthographic),
    /// Parallel rays slanted to the image plane (cavalier, cabinet).
    Oblique(Oblique),
    /// The full sphere of directions mapped to longitude and latitude.
    Equirectangular,
    /// An equidistant fisheye lens.
    Fisheye(Fisheye),
}

/// The general perspective camera: eye `e`, image plane at distance `d`, a viewport of
/// `vw x vh` and an optional shift of the viewport within the image plane.
///
/// ```text
/// origin    = e
/// direction = (u + sx) U + (v + sy) V - d W
/// ```
///
/// A shift moves the window on the image plane (in the plane's units, at distance `d`)
/// without turning the camera: verticals stay parallel where a tilt would make them
/// converge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Perspective {
    /// `d`: the distance from the eye to the image plane.
    pub distance: f64,
    /// `(vw, vh)`: the viewport's width and height on the image plane.
    pub viewport: DVec2,
    /// `(sx, sy)`: where the viewport's centre sits on the image plane; zero for a
    /// symmetric frustum.
    pub shift: DVec2,
}

/// A perspective camera with a thin lens of radius `r` focused at distance `f`.
///
/// `(lx, ly)` is a point of the aperture in unit-disk coordinates (the lens sample,
/// mapped by the [`Iris`]: the unit disk, or a polygon of blades inscribed in it):
///
/// ```text
/// origin    = e + r (lx U + ly V)
/// direction = (f / d) ((u + sx) U + (v + sy) V - d W) - r (lx U + ly V)
/// ```
///
/// Every ray of one image point passes through the same point of the focus plane (at
/// `t = 1`); with the lens centre `(0, 0)` it is the pinhole ray scaled by `f / d`.
///
/// A lens tilted by `alpha` about `U` or swung by `beta` about `V` (a view camera's
/// movements; `F = d` is then its focal length) focuses on a plane that passes through
/// the Scheimpflug line and the hinge line instead: see the module `scheimpflug` for
/// its formulas, [`crate::Camera::focus_plane`] and [`crate::Camera::tilted_focus`].
///
/// [`Iris`]: crate::Iris
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ThinLens {
    /// `d`: the distance from the eye to the image plane.
    pub distance: f64,
    /// `(vw, vh)`: the viewport's width and height on the image plane.
    pub viewport: DVec2,
    /// `(sx, sy)`: the viewport's shift on the image plane.
    pub shift: DVec2,
    /// `r`: the lens radius (a polygon's circumradius).
    pub aperture: f64,
    /// `f`: the distance from the eye to the plane in focus (of the untilted lens, which
    /// fixes where the sensor sits).
    pub focus: f64,
    /// `alpha`: the lens plane's tilt about `U`, in radians, strictly between `-pi/2` and
    /// `pi/2`; positive turns its top toward the scene (the plane of focus swings down
    /// toward the ground ahead). Zero for the lecture's thin lens.
    pub tilt: f64,
    /// `beta`: the lens plane's swing about `V` (after the tilt), in radians, strictly
    /// between `-pi/2` and `pi/2`; positive turns its right side toward the scene.
    pub swing: f64,
    /// The aperture's shape: round, or a polygon of blades.
    pub iris: crate::Iris,
}

/// A thin lens for a parallel camera: radius `r`, focus plane at distance `f`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lens {
    /// `r`: the lens radius.
    pub aperture: f64,
    /// `f`: the distance from the image plane to the plane in focus.
    pub focus: f64,
}

/// The orthographic camera: parallel rays perpendicular to the image plane, one from
/// each point of the viewport.
///
/// ```text
/// origin    = e + u U + v V
/// direction = -W
/// ```
///
/// With a [`Lens`] of radius `r` and focus `f` the origin moves by the lens sample and the
/// ray still meets the pinhole ray at the focus plane (`t = f`):
///
/// ```text
/// origin    = e + u U + v V + r (lx U + ly V)
/// direction = -W - (r / f) (lx U + ly V)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orthographic {
    /// `(vw, vh)`: the viewport's width and height.
    pub viewport: DVec2,
    /// An optional thin lens for depth of field.
    pub lens: Option<Lens>,
}

/// The oblique parallel camera: parallel rays that are not perpendicular to the image
/// plane.
///
/// ```text
/// origin    = e + u U + v V
/// direction = -W - L (cos(phi) U + sin(phi) V)
/// ```
///
/// A point at depth `D` behind the image plane appears moved by `L * D` along the angle
/// `phi` in the image: `L = 1` is cavalier (projectors at 45 degrees to the plane),
/// `L = 1/2` cabinet (projectors at arctan 2 = 63.435 degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Oblique {
    /// `(vw, vh)`: the viewport's width and height.
    pub viewport: DVec2,
    /// `L`: how far a unit of depth moves in the image.
    pub ratio: f64,
    /// `phi`: the direction, in radians counter-clockwise from `u`, in which depth recedes.
    pub angle: f64,
}

/// An equidistant fisheye: the angle from the optical axis grows linearly with the
/// distance from the image centre, reaching `F / 2` on the circle that touches the
/// image's left and right edges.
///
/// With `x, y` the continuous image coordinates:
///
/// ```text
/// a = 2x/W - 1,   b = (1 - 2y/H) H/W,   r = sqrt(a^2 + b^2),   theta = r F/2
/// direction = sin(theta) (a/r U + b/r V) - cos(theta) W
/// ```
///
/// Points outside the image circle (`r > 1`) have no ray.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fisheye {
    /// `F`: the field of view across the image circle, in radians (at most `2 pi`).
    pub fov: f64,
}

impl Perspective {
    /// The lecture's canonical perspective projection: `d = 1`, a 1 x 1 viewport, no shift.
    pub const CANONICAL: Perspective = Perspective {
        distance: 1.0,
        viewport: DVec2::ONE,
        shift: DVec2::ZERO,
    };

    /// A perspective projection with `d = 1` and the vertical field of view `fov_y`
    /// (radians), the width following from the aspect ratio `W / H`
    /// ([`Perspective::from_fov`] with [`crate::FovAxis::Y`]).
    ///
    /// ```text
    /// vh = 2 tan(fov_y / 2),   vw = aspect * vh
    /// ```
    ///
    /// # Errors
    /// [`CameraError::OutOfRange`] unless `0 < fov_y < pi`; [`CameraError::NotPositive`]
    /// unless `aspect > 0`.
    pub fn from_fov_y(fov_y: f64, aspect: f64) -> Result<Self, CameraError> {
        Self::from_fov(crate::FovAxis::Y, fov_y, aspect)
    }

    /// A perspective projection with `d = 1` and the horizontal field of view `fov_x`
    /// (radians), the height following from the aspect ratio `W / H`
    /// ([`Perspective::from_fov`] with [`crate::FovAxis::X`]).
    ///
    /// ```text
    /// vw = 2 tan(fov_x / 2),   vh = vw / aspect
    /// ```
    ///
    /// # Errors
    /// [`CameraError::OutOfRange`] unless `0 < fov_x < pi`; [`CameraError::NotPositive`]
    /// unless `aspect > 0`.
    pub fn from_fov_x(fov_x: f64, aspect: f64) -> Result<Self, CameraError> {
        Self::from_fov(crate::FovAxis::X, fov_x, aspect)
    }

    /// The viewport shift that centres a point at elevation `theta` (radians above the
    /// optical axis) while the image plane stays vertical: `sy = d tan(theta)`.
    pub fn shift_for_elevation(distance: f64, theta: f64) -> f64 {
        distance * theta.tan()
    }

    /// The pinhole ray direction through `(u, v)`, in camera coordinates.
    #[inline]
    pub(crate) fn direction(&self, uv: DVec2) -> DVec3 {
        (uv + self.shift).extend(-self.distance)
    }

    /// The image-plane point `(u, v)` where camera-space point `q` appears; `None` unless
    /// `q` is in front of the eye.
    #[inline]
    fn project(&self, q: DVec3) -> Option<DVec2> {
        let depth = -q.z;
        (depth > 0.0).then(|| DVec2::new(q.x, q.y) * (self.distance / depth) - self.shift)
    }

    fn validate(&self) -> Result<(), CameraError> {
        check_positive("d", self.distance)?;
        check_viewport(self.viewport)?;
        check_finite_vector2("shift", self.shift)
    }
}

impl ThinLens {
    /// The pinhole camera through the lens centre.
    #[inline]
    pub fn pinhole(&self) -> Perspective {
        Perspective {
            distance: self.distance,
            viewport: self.viewport,
            shift: self.shift,
        }
    }

    /// An untilted thin lens with a round aperture over the pinhole camera `pinhole`:
    /// the lecture's thin lens.
    pub fn new(pinhole: Perspective, aperture: f64, focus: f64) -> ThinLens {
        ThinLens {
            distance: pinhole.distance,
            viewport: pinhole.viewport,
            shift: pinhole.shift,
            aperture,
            focus,
            tilt: 0.0,
            swing: 0.0,
            iris: crate::Iris::ROUND,
        }
    }

    fn validate(&self) -> Result<(), CameraError> {
        self.pinhole().validate()?;
        check_positive("aperture", self.aperture)?;
        check_positive("focus", self.focus)?;
        self.validate_tilt()?;
        self.iris.validate()
    }
}

impl Lens {
    fn validate(&self) -> Result<(), CameraError> {
        check_positive("aperture", self.aperture)?;
        check_positive("focus", self.focus)
    }
}

impl Orthographic {
    /// An orthographic projection whose viewport is `height` tall, the width following
    /// from the aspect ratio `W / H`: `vw = aspect * height, vh = height`.
    ///
    /// # Errors
    /// [`CameraError::NotPositive`] unless `height > 0` and `aspect > 0`.
    pub fn from_height(height: f64, aspect: f64) -> Result<Self, CameraError> {
        check_positive("height", height)?;
        check_positive("aspect", aspect)?;
        Ok(Self {
            viewport: DVec2::new(aspect * height, height),
            lens: None,
        })
    }

    fn validate(&self) -> Result<(), CameraError> {
        check_viewport(self.viewport)?;
        self.lens.as_ref().map_or(Ok(()), Lens::validate)
    }
}

impl Oblique {
    /// The cavalier projection: `L = 1`, receding at `angle` (radians).
    pub fn cavalier(viewport: DVec2, angle: f64) -> Self {
        Self {
            viewport,
            ratio: 1.0,
            angle,
        }
    }

    /// The cabinet projection: `L = 1/2`, receding at `angle` (radians).
    pub fn cabinet(viewport: DVec2, angle: f64) -> Self {
        Self {
            viewport,
            ratio: 0.5,
            angle,
        }
    }

    /// The direction of every ray, in camera coordinates: `(-L cos phi, -L sin phi, -1)`.
    #[inline]
    pub(crate) fn direction(&self) -> DVec3 {
        let (sin, cos) = self.angle.sin_cos();
        DVec3::new(-self.ratio * cos, -self.ratio * sin, -1.0)
    }

    fn validate(&self) -> Result<(), CameraError> {
        check_viewport(self.viewport)?;
        check_finite("L", self.ratio)?;
        if self.ratio < 0.0 {
            return Err(CameraError::OutOfRange {
                name: "L",
                expected: "zero or positive",
                value: self.ratio,
            });
        }
        check_finite("phi", self.angle)
    }
}

/// Where a continuous image point `(x, y)` lies on a fisheye's image: its coordinates
/// `(a, b)` from the image centre in units of half the image's width (`b` up), its
/// distance `r` from the centre, and the angle `theta` of its ray from the optical axis
/// `-W`:
///
/// ```text
/// a = 2x/W - 1,   b = (1 - 2y/H) H/W,   r = sqrt(a^2 + b^2),   theta = r F/2
/// ```
///
/// The point has a ray only inside the image circle, `r <= 1` (`theta <= F/2`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FisheyePoint {
    /// `a = 2x/W - 1`: across, from -1 at the left edge to 1 at the right edge.
    pub a: f64,
    /// `b = (1 - 2y/H) H/W`: up, in the same units as `a`.
    pub b: f64,
    /// `r = sqrt(a^2 + b^2)`: the distance from the centre, 1 on the image circle.
    pub r: f64,
    /// `theta = r F/2`: the angle between the ray and `-W`, in radians.
    pub theta: f64,
}

impl Fisheye {
    /// The point `image = (x, y)` of an image of `size = (W, H)` pixels on this
    /// fisheye's image, the numbers its ray is made of (see [`FisheyePoint`]).
    ///
    /// ```
    /// use std::f64::consts::{FRAC_PI_4, PI};
    ///
    /// use glam::DVec2;
    /// use viewray_camera::{Fisheye, FisheyePoint};
    ///
    /// // A 180-degree fisheye, 4 x 2 pixels: x = 3, y = 1 is half-way to the right edge,
    /// // its ray 45 degrees from -W.
    /// let fisheye = Fisheye { fov: PI };
    /// let point = fisheye.image_point(DVec2::new(3.0, 1.0), DVec2::new(4.0, 2.0));
    /// let expected = FisheyePoint { a: 0.5, b: 0.0, r: 0.5, theta: FRAC_PI_4 };
    /// assert_eq!(point, expected);
    /// ```
    pub fn image_point(&self, image: DVec2, size: DVec2) -> FisheyePoint {
        let a = 2.0 * image.x / size.x - 1.0;
        let b = (1.0 - 2.0 * image.y / size.y) * size.y / size.x;
        let r = a.hypot(b);
        FisheyePoint {
            a,
            b,
            r,
            theta: r * self.fov / 2.0,
        }
    }

    fn validate(&self) -> Result<(), CameraError> {
        check_finite("fov", self.fov)?;
        if !(self.fov > 0.0 && self.fov <= TAU) {
            return Err(CameraError::OutOfRange {
                name: "fov",
                expected: "in (0, 360] degrees",
                value: self.fov.to_degrees(),
            });
        }
        Ok(())
    }
}

/// The longitude and latitude (radians) of the continuous image point `image = (x, y)`
/// of an equirectangular image of `size = (W, H)` pixels:
///
/// ```text
/// longitude = 2 pi (x/W - 1/2),   latitude = pi (1/2 - y/H)
/// ```
///
/// Longitude 0 looks along `-W`, growing toward `U`; latitude grows toward `V`. The ray
/// is `sin(longitude) cos(latitude) U + sin(latitude) V - cos(longitude) cos(latitude) W`.
///
/// ```
/// use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
///
/// use glam::DVec2;
/// use viewray_camera::equirectangular_angles;
///
/// // 8 x 4 pixels: x = 6, y = 1 looks a quarter turn to the right, 45 degrees up.
/// let angles = equirectangular_angles(DVec2::new(6.0, 1.0), DVec2::new(8.0, 4.0));
/// assert_eq!(angles, (FRAC_PI_2, FRAC_PI_4));
/// ```
pub fn equirectangular_angles(image: DVec2, size: DVec2) -> (f64, f64) {
    let longitude = TAU * (image.x / size.x - 0.5);
    let latitude = PI * (0.5 - image.y / size.y);
    (longitude, latitude)
}

/// A viewing ray in camera coordinates: `origin + t direction`, both relative to the
/// frame `(e; U, V, W)`.
pub(crate) struct CameraSpaceRay {
    pub(crate) origin: DVec3,
    pub(crate) direction: DVec3,
}

impl Projection {
    /// The viewport `(vw, vh)` of the planar projections; `None` for the panoramic ones.
    pub fn viewport(&self) -> Option<DVec2> {
        match self {
            Projection::Perspective(p) => Some(p.viewport),
            Projection::ThinLens(p) => Some(p.viewport),
            Projection::Orthographic(p) => Some(p.viewport),
            Projection::Oblique(p) => Some(p.viewport),
            Projection::Equirectangular | Projection::Fisheye(_) => None,
        }
    }

    /// The principal point: where the optical axis (the ray through `u + sx = 0`, `v +
    /// sy = 0`) meets the image, as fractions `(x / W, y / H)` of its width and height,
    /// from the top-left corner:
    ///
    /// ```text
    /// x / W = 1/2 - sx / vw,   y / H = 1/2 + sy / vh
    /// ```
    ///
    /// The image's centre `(1/2, 1/2)` without a shift and for the parallel families;
    /// `None` for the panoramic ones, which have no image plane.
    pub fn principal_point(&self) -> Option<DVec2> {
        let shifted = |viewport: DVec2, shift: DVec2| {
            DVec2::new(0.5 - shift.x / viewport.x, 0.5 + shift.y / viewport.y)
        };
        match self {
            Projection::Perspective(p) => Some(shifted(p.viewport, p.shift)),
            Projection::ThinLens(p) => Some(shifted(p.viewport, p.shift)),
            Projection::Orthographic(_) | Projection::Oblique(_) => Some(DVec2::splat(0.5)),
            Projection::Equirectangular | Projection::Fisheye(_) => None,
        }
    }

    /// Whether all rays are parallel (orthographic and oblique).
    pub fn is_parallel(&self) -> bool {
        matches!(self, Projection::Orthographic(_) | Projection::Oblique(_))
    }

    /// Whether the camera samples a lens (thin lens, or orthographic with a lens).
    pub fn has_lens(&self) -> bool {
        matches!(
            self,
            Projection::ThinLens(_) | Projection::Orthographic(Orthographic { lens: Some(_), .. })
        )
    }

    /// The family's name as scene files spell it, e.g. `"Perspective"`.
    pub fn family_name(&self) -> &'static str {
        match self {
            Projection::Perspective(_) => "Perspective",
            Projection::ThinLens(_) => "ThinLens",
            Projection::Orthographic(_) => "Orthographic",
            Projection::Oblique(_) => "Oblique",
            Projection::Equirectangular => "Equirectangular",
            Projection::Fisheye(_) => "Fisheye",
        }
    }

    /// The shape of the aperture of a camera with a lens: the thin lens's [`Iris`],
    /// the round one of an orthographic lens; `None` without a lens.
    ///
    /// [`Iris`]: crate::Iris
    pub fn iris(&self) -> Option<crate::Iris> {
        match self {
            Projection::ThinLens(p) => Some(p.iris),
            Projection::Orthographic(Orthographic { lens: Some(_), .. }) => {
                Some(crate::Iris::ROUND)
            }
            _ => None,
        }
    }

    /// Checks every parameter: viewport, distance, aperture and focus positive and
    /// finite; shift and angles finite; a fisheye's field of view in (0, 2 pi]; a thin
    /// lens's tilt and swing within (-90, 90) degrees (focused beyond its focal length
    /// when tilted) and its blades 0 or 3 to 64.
    ///
    /// # Errors
    /// The first invalid parameter, named in the lecture's notation.
    pub fn validate(&self) -> Result<(), CameraError> {
        match self {
            Projection::Perspective(p) => p.validate(),
            Projection::ThinLens(p) => p.validate(),
            Projection::Orthographic(p) => p.validate(),
            Projection::Oblique(p) => p.validate(),
            Projection::Equirectangular => Ok(()),
            Projection::Fisheye(p) => p.validate(),
        }
    }

    /// The lens point, in unit-disk coordinates, of the lens sample `p_lens` in the unit
    /// square (see [`crate::Iris::sample`]); the centre for a camera without a lens.
    #[inline]
    pub(crate) fn lens_point(&self, p_lens: DVec2) -> DVec2 {
        self.iris().map_or(DVec2::ZERO, |iris| iris.sample(p_lens))
    }

    /// The viewing ray, in camera coordinates, through the continuous image point
    /// `image = (x, y)` of an image of `size = (W, H)` pixels, for the unit-disk lens
    /// point `lens`. `None` where the projection has no ray (outside a fisheye's circle).
    pub(crate) fn camera_space_ray(
        &self,
        image: DVec2,
        size: DVec2,
        lens: DVec2,
    ) -> Option<CameraSpaceRay> {
        let uv = || image_to_image_plane(image, size, self.viewport().unwrap_or(DVec2::ONE));
        let ray = match self {
            Projection::Perspective(p) => CameraSpaceRay {
                origin: DVec3::ZERO,
                direction: p.direction(uv()),
            },
            Projection::ThinLens(p) if p.is_tilted() => p.tilted_ray(uv(), lens),
            Projection::ThinLens(p) => {
                // Point on the lens, then the direction through the point of the focus
                // plane that the pinhole ray reaches at t = 1.
                let lens_offset = (p.aperture * lens).extend(0.0);
                CameraSpaceRay {
                    origin: lens_offset,
                    direction: (p.focus / p.distance) * p.pinhole().direction(uv()) - lens_offset,
                }
            }
            Projection::Orthographic(p) => {
                let on_plane = uv().extend(0.0);
                match p.lens {
                    None => CameraSpaceRay {
                        origin: on_plane,
                        direction: DVec3::NEG_Z,
                    },
                    Some(l) => {
                        let lens_offset = (l.aperture * lens).extend(0.0);
                        CameraSpaceRay {
                            origin: on_plane + lens_offset,
                            direction: DVec3::NEG_Z - lens_offset / l.focus,
                        }
                    }
                }
            }
            Projection::Oblique(p) => CameraSpaceRay {
                origin: uv().extend(0.0),
                direction: p.direction(),
            },
            Projection::Equirectangular => {
                let (longitude, latitude) = equirectangular_angles(image, size);
                let (sin_lon, cos_lon) = longitude.sin_cos();
                let (sin_lat, cos_lat) = latitude.sin_cos();
                CameraSpaceRay {
                    origin: DVec3::ZERO,
                    direction: DVec3::new(sin_lon * cos_lat, sin_lat, -cos_lon * cos_lat),
                }
            }
            Projection::Fisheye(p) => {
                let FisheyePoint { a, b, r, theta } = p.image_point(image, size);
                if r > 1.0 {
                    return None;
                }
                let (sin, cos) = theta.sin_cos();
                // At the centre (r = 0) the direction is -W whatever a/r and b/r would be.
                let (a_r, b_r) = if r > 0.0 { (a / r, b / r) } else { (0.0, 0.0) };
                CameraSpaceRay {
                    origin: DVec3::ZERO,
                    direction: DVec3::new(sin * a_r, sin * b_r, -cos),
                }
            }
        };
        Some(ray)
    }

    /// Where the camera-space point `q` appears, in continuous image coordinates `(x, y)`
    /// of an image of `size = (W, H)` pixels; `None` where it is not visible.
    pub(crate) fn project_camera_space(&self, q: DVec3, size: DVec2) -> Option<DVec2> {
        let on_plane =
            |uv: DVec2| image_plane_to_image(uv, size, self.viewport().unwrap_or(DVec2::ONE));
        match self {
            Projection::Perspective(p) => p.project(q).map(on_plane),
            Projection::ThinLens(p) => p.pinhole().project(q).map(on_plane),
            Projection::Orthographic(_) => (q.z < 0.0).then(|| on_plane(DVec2::new(q.x, q.y))),
            Projection::Oblique(p) => {
                let depth = -q.z;
                let (sin, cos) = p.angle.sin_cos();
                (depth > 0.0).then(|| {
                    on_plane(DVec2::new(
                        q.x + p.ratio * depth * cos,
                        q.y + p.ratio * depth * sin,
                    ))
                })
            }
            Projection::Equirectangular => {
                if q == DVec3::ZERO {
                    return None;
                }
                let longitude = q.x.atan2(-q.z);
                let latitude = q.y.atan2(q.x.hypot(q.z));
                let mut x = size.x * (longitude / TAU + 0.5);
                // Longitude pi is the image's left edge as well as its right.
                if x >= size.x {
                    x -= size.x;
                }
                let y = size.y * (0.5 - latitude / PI);
                Some(DVec2::new(x, y))
            }
            Projection::Fisheye(p) => {
                if q == DVec3::ZERO {
                    return None;
                }
                let radial = q.x.hypot(q.y);
                let theta = radial.atan2(-q.z);
                let half_fov = p.fov / 2.0;
                // Seen up to theta = F/2, the image circle included, with a slack of
                // 1e-12 for the rounding of a ray through the circle projected back.
                let seen = theta <= half_fov * (1.0 + 1e-12);
                if !seen {
                    return None;
                }
                let r = theta / half_fov;
                // On the axis the way out from the centre is undefined. Straight ahead
                // (r = 0) that is the centre itself; straight back (r = 1, only a
                // 360-degree fisheye sees it) it is the whole circle, and the point taken
                // is its rightmost, where the ray through (W, H/2) looks.
                let (a, b) = if radial > 0.0 {
                    (r * q.x / radial, r * q.y / radial)
                } else {
                    (r, 0.0)
                };
                let x = (a + 1.0) * size.x / 2.0;
                let y = size.y / 2.0 - b * size.x / 2.0;
                Some(DVec2::new(x, y))
            }
        }
    }
}

fn check_finite(name: &'static str, value: f64) -> Result<(), CameraError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(CameraError::NotFinite {
            name,
            value: value.to_string(),
        })
    }
}

pub(crate) fn check_positive(name: &'static str, value: f64) -> Result<(), CameraError> {
    check_finite(name, value)?;
    if value > 0.0 {
        Ok(())
    } else {
        Err(CameraError::NotPositive { name, value })
    }
}

fn check_finite_vector2(name: &'static str, value: DVec2) -> Result<(), CameraError> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(CameraError::NotFinite {
            name,
            value: format!("({}, {})", value.x, value.y),
        })
    }
}

fn check_viewport(viewport: DVec2) -> Result<(), CameraError> {
    check_positive("vw", viewport.x)?;
    check_positive("vh", viewport.y)
}
