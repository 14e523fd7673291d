//! The camera: a frame, a projection and an image size; pixel -> ray and point -> pixel.

use glam::{DVec2, DVec3};
use viewray_geometry::{DRay, RayBounds};

use crate::image_limits::check_not_empty;
use crate::{CameraError, Frame, Mistake, Mistakes, Plane3, Projection, TiltedFocus};

mod block;
#[cfg(target_arch = "x86_64")]
mod lanes;

/// Where in a pixel, and where on the lens, a viewing ray is taken.
///
/// The names follow pbrt's `CameraSample`, but the film point differs: pbrt's `pFilm` is
/// a position on the whole film in raster coordinates, while `p_film` here is only the
/// offset `(ox, oy)` inside the pixel, from its top-left corner; [`Camera::generate_ray`]
/// adds the pixel's `(col, row)`. Both fields are points of the unit square `[0, 1)^2`;
/// `p_lens` is mapped to the aperture by its [`crate::Iris`] (the unit disk by
/// [`crate::sample_unit_disk_concentric`], a polygon of blades by
/// [`crate::sample_regular_polygon`]).
/// [`CameraSample::CENTER`] is the pixel centre and the lens centre, the lecture's
/// sample. (The offset `(ox, oy)` is not the lens shift `(sx, sy)` of [`Perspective`].)
///
/// [`Perspective`]: crate::Perspective
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraSample {
    /// The offset `(ox, oy)` inside the pixel; `(0.5, 0.5)` is its centre.
    pub p_film: DVec2,
    /// The lens sample in the unit square; `(0.5, 0.5)` is the lens centre.
    pub p_lens: DVec2,
}

impl CameraSample {
    /// The pixel's centre through the lens's centre: the lecture's viewing ray.
    pub const CENTER: CameraSample = CameraSample {
        p_film: DVec2::splat(0.5),
        p_lens: DVec2::splat(0.5),
    };
}

impl Default for CameraSample {
    fn default() -> Self {
        Self::CENTER
    }
}

/// A viewing ray with its neighbours: the rays through the image points one step to the
/// right and one step down (pbrt's `RayDifferential`).
///
/// Their differences say how the ray changes across the film, which is what a renderer
/// needs to filter textures and grid lines over a sample's footprint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayDifferential {
    /// The ray through the image point itself.
    pub ray: DRay,
    /// The ray through the point `step` pixels to the right (`+x`).
    pub rx: DRay,
    /// The ray through the point `step` pixels down (`+y`).
    pub ry: DRay,
}

/// A camera: where it is ([`Frame`]), how it projects ([`Projection`]) and the image it
/// makes, `W` columns by `H` rows.
///
/// Every `Camera` is valid: [`Camera::new`] checks the projection's parameters and the
/// image size, so ray generation never produces NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    frame: Frame,
    projection: Projection,
    width: u32,
    height: u32,
    /// For a perspective camera, what all its world-space rays share (see [`Pinhole`]).
    pinhole: Option<Pinhole>,
    /// The catalogue's mistakes this camera makes ([`Camera::with_mistakes`]); none for
    /// every camera a scene describes.
    mistakes: Mistakes,
}

/// The parts of a perspective camera's world-space rays that are the same for every
/// image point, worked out once by the very operations a single ray would do, so that
/// the rays come out bit for bit the same (a render asks for millions).
#[derive(Clone, Copy, Debug, PartialEq)]
struct Pinhole {
    /// The eye, as the frame transform of the camera-space origin gives it.
    origin: DVec3,
    /// `-d w`: the last term of the frame transform of every direction `(u, v, -d)`.
    depth: DVec3,
}

impl Camera {
    /// A camera with the given pose, projection and image size.
    ///
    /// # Errors
    /// [`CameraError::Image`] if `width` or `height` is zero, and the projection's
    /// first invalid parameter (see [`Projection::validate`]).
    pub fn new(
        frame: Frame,
        projection: Projection,
        width: u32,
        height: u32,
    ) -> Result<Self, CameraError> {
        check_not_empty(u64::from(width), u64::from(height))?;
        projection.validate()?;
        Ok(Self::from_parts(
            frame,
            projection,
            width,
            height,
            Mistakes::NONE,
        ))
    }

    /// A camera from checked parts, with the perspective shortcut where it applies.
    fn from_parts(
        frame: Frame,
        projection: Projection,
        width: u32,
        height: u32,
        mistakes: Mistakes,
    ) -> Self {
        let pinhole = match projection {
            Projection::Perspective(p) if !mistakes.moves_pixels() && !mistakes.skips_basis() => {
                Some(Pinhole {
                    origin: if mistakes.contains(Mistake::EyeMissing) {
                        frame.world_from_camera_vector(DVec3::ZERO)
                    } else {
                        frame.world_from_camera_point(DVec3::ZERO)
                    },
                    depth: p.direction(DVec2::ZERO).z * frame.w(),
                })
            }
            _ => None,
        };
        Self {
            frame,
            projection,
            width,
            height,
            pinhole,
            mistakes,
        }
    }

    /// The camera a student wrote who made `mistakes` (entries of the lecture's
    /// catalogue, see [`Mistake`]): its rays, frame and pictures are this camera's with
    /// each mistaken formula in place of the right one (`u-not-normalized` takes the
    /// length of the frame's [`Frame::up`] as given).
    ///
    /// A mistaken camera generates rays (finite ones: the catalogue never divides by
    /// zero where it fits) and reports its mistaken [`Camera::frame`] (the basis
    /// entries; with `eye-missing` the frame keeps `e`, only the rays leave it out) and
    /// [`Camera::projection`] (with `distance-sign`, a perspective `d` below zero); it
    /// does not [`Camera::project`]. Mistakes are made on top of the right camera:
    /// calling this on a mistaken camera starts again from its mistaken parts.
    ///
    /// # Errors
    /// [`CameraError::MistakeDoesNotFit`] for a mistake that cannot be made in this
    /// family ([`Mistake::fits`]), or `size-minus-one` in an image one pixel wide or
    /// high.
    pub fn with_mistakes(&self, mistakes: Mistakes) -> Result<Self, CameraError> {
        check_mistakes_fit(mistakes, &self.projection, self.width, self.height)?;
        let f = &self.frame;
        let [e, u, v, w] = mistakes.frame([f.e(), f.u(), f.v(), f.w()], f.up());
        Ok(Self::from_parts(
            Frame::from_parts(e, u, v, w, f.up()),
            mistakes.projection(self.projection),
            self.width,
            self.height,
            mistakes,
        ))
    }

    /// The catalogue's mistakes this camera makes: none unless it was made by
    /// [`Camera::with_mistakes`].
    pub fn mistakes(&self) -> Mistakes {
        self.mistakes
    }

    /// The lecture's canonical camera: eye at the origin looking down `-z`, `d = 1`, a
    /// 1 x 1 viewport, with a `width x height` image.
    ///
    /// # Errors
    /// [`CameraError::Image`] if `width` or `height` is zero.
    pub fn canonical(width: u32, height: u32) -> Result<Self, CameraError> {
        Self::new(
            Frame::CANONICAL,
            Projection::Perspective(crate::Perspective::CANONICAL),
            width,
            height,
        )
    }

    /// The same camera making an image of another size (the projection is unchanged).
    ///
    /// # Errors
    /// [`CameraError::Image`] if `width` or `height` is zero.
    pub fn with_image_size(self, width: u32, height: u32) -> Result<Self, CameraError> {
        check_not_empty(u64::from(width), u64::from(height))?;
        check_mistakes_fit(self.mistakes, &self.projection, width, height)?;
        Ok(Self::from_parts(
            self.frame,
            self.projection,
            width,
            height,
            self.mistakes,
        ))
    }

    /// The camera's pose.
    pub fn frame(&self) -> &Frame {
        &self.frame
    }

    /// The camera's projection.
    pub fn projection(&self) -> &Projection {
        &self.projection
    }

    /// `W`: the number of columns.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// `H`: the number of rows.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// `(W, H)` as floating-point numbers.
    fn size(&self) -> DVec2 {
        DVec2::new(f64::from(self.width), f64::from(self.height))
    }

    /// The viewing ray for pixel `(row, col)` (0-based, row 0 at the top) through the
    /// film and lens points of `sample`, with the lecture's unnormalized direction.
    ///
    /// For a planar projection, the pixel maps to the image plane by
    /// [`pixel_to_image_plane`]; the ray is then the family's rule (see
    /// [`Projection`]). Returns `None` only where the projection has no ray (outside a
    /// fisheye's image circle). Pixels outside the image are extrapolated.
    #[inline]
    pub fn generate_ray(&self, row: u32, col: u32, sample: CameraSample) -> Option<DRay> {
        let image = DVec2::new(f64::from(col), f64::from(row)) + sample.p_film;
        self.generate_ray_through(image, sample.p_lens)
    }

    /// The image-plane point `(u, v)` of pixel `(row, col)` at the offset `p_film` in it
    /// ([`pixel_to_image_plane`] with this camera's size and viewport, after the pixel
    /// mistakes of a mistaken camera); `None` for the panoramic cameras, which have no
    /// image plane.
    pub fn image_plane_point(&self, row: u32, col: u32, p_film: DVec2) -> Option<DVec2> {
        let viewport = self.projection.viewport()?;
        let image = DVec2::new(f64::from(col), f64::from(row)) + p_film;
        let image = self.mistakes.image_point(image, self.size());
        Some(image_to_image_plane(image, self.size(), viewport))
    }

    /// The viewing ray through the continuous image point `image = (x, y)` (`x` from the
    /// left edge, `y` from the top, in pixels) for the lens sample `p_lens` in
    /// `[0, 1)^2`.
    #[inline]
    pub fn generate_ray_through(&self, image: DVec2, p_lens: DVec2) -> Option<DRay> {
        if let (Projection::Perspective(p), Some(pinhole)) = (&self.projection, &self.pinhole) {
            let uv = image_to_image_plane(image, self.size(), p.viewport);
            let direction = p.direction(uv);
            return Some(DRay::new(
                pinhole.origin,
                self.frame
                    .world_from_camera_xy(direction.truncate(), pinhole.depth),
            ));
        }
        self.generate_general_ray(image, p_lens)
    }

    /// [`Camera::generate_ray_through`] for every family: the camera-space rule, then the
    /// frame transform.
    fn generate_general_ray(&self, image: DVec2, p_lens: DVec2) -> Option<DRay> {
        self.ray_at_lens_point(image, self.projection.lens_point(p_lens))
    }

    /// The viewing ray through the continuous image point `image` from the lens point
    /// `lens` given in unit-disk coordinates, not as a sample of the unit square: for a
    /// camera with a lens the ray starts at `e + r (lx U + ly V)` (the lens point
    /// `(lx, ly)`, which [`crate::Iris::contains`] says is on the aperture or not), and
    /// every ray of one image point meets the others on the plane of focus
    /// ([`Camera::focus_plane`]). A camera without a lens ignores `lens`.
    ///
    /// `viewray rays --lens LX,LY` prints these rays, so that a student can check a thin
    /// lens's rays by hand. `None` where the projection has no ray.
    pub fn generate_ray_at_lens(&self, image: DVec2, lens: DVec2) -> Option<DRay> {
        if self.projection.has_lens() {
            self.ray_at_lens_point(image, lens)
        } else {
            self.generate_ray_through(image, DVec2::splat(0.5))
        }
    }

    /// The camera-space rule through `image` from the unit-disk lens point `lens`, then
    /// the frame transform (with the mistakes' changes).
    fn ray_at_lens_point(&self, image: DVec2, lens: DVec2) -> Option<DRay> {
        let image = if self.mistakes.moves_pixels() {
            self.mistakes.image_point(image, self.size())
        } else {
            image
        };
        let mut ray = self.projection.camera_space_ray(image, self.size(), lens)?;
        if self.mistakes.contains(Mistake::OrthoOriginFixed) {
            ray.origin = DVec3::ZERO;
        }
        if self.mistakes.skips_basis() {
            // The camera's coordinates taken as the world's, from e (or 0).
            let e = if self.mistakes.contains(Mistake::EyeMissing) {
                DVec3::ZERO
            } else {
                self.frame.e()
            };
            return Some(DRay::new(e + ray.origin, ray.direction));
        }
        let origin = if self.mistakes.contains(Mistake::EyeMissing) {
            // The student's origin: 0 + u U + v V, without e.
            self.frame.world_from_camera_vector(ray.origin)
        } else {
            self.frame.world_from_camera_point(ray.origin)
        };
        Some(DRay::new(
            origin,
            self.frame.world_from_camera_vector(ray.direction),
        ))
    }

    /// The viewing ray through the continuous image point `image` and the lens sample
    /// `p_lens`, with its neighbours through `image + (step, 0)` and `image + (0, step)`
    /// and the same lens sample (pbrt's `GenerateRayDifferential`, with the step chosen
    /// by the caller: one pixel, or the spacing of a pixel's samples).
    ///
    /// For the planar families the differences are constant across the image, e.g. for
    /// a perspective camera
    ///
    /// ```text
    /// rx.direction - ray.direction = step (vw / W) U,   ry.direction - ray.direction = -step (vh / H) V
    /// ```
    ///
    /// and for a parallel camera the origins differ by the same amounts while the
    /// directions agree. Returns `None` where any of the three rays does not exist
    /// (outside a fisheye's image circle).
    pub fn generate_ray_differential(
        &self,
        image: DVec2,
        p_lens: DVec2,
        step: f64,
    ) -> Option<RayDifferential> {
        let ray = |offset: DVec2| self.generate_ray_through(image + offset * step, p_lens);
        Some(RayDifferential {
            ray: ray(DVec2::ZERO)?,
            rx: ray(DVec2::X)?,
            ry: ray(DVec2::Y)?,
        })
    }

    /// A box holding every viewing ray through the image region from `corners[0]` to
    /// `corners[1]` (continuous image coordinates, as [`Camera::generate_ray_through`]
    /// takes them), at any point of the lens: all the rays a block of pixels can take,
    /// whatever its samples, so that a renderer can ask the world about them at once
    /// ([`World::reach`]).
    ///
    /// The planar families' rays are affine in the image point and in the lens point
    /// (`e + r (lx U + ly V)` and `f / d (u + sx, v + sy, -d) - r (lx, ly, 0)` for a thin
    /// lens), so the box around the rays at the region's corners, from the corners of the
    /// square around the unit disk (which holds every iris), holds them all. `None` for
    /// the cameras whose rays are not affine: the panoramic ones, a tilted lens, and a
    /// camera with mistakes.
    ///
    /// [`World::reach`]: viewray_geometry::World::reach
    pub fn ray_bounds(&self, corners: [DVec2; 2]) -> Option<RayBounds> {
        let affine = match &self.projection {
            Projection::Perspective(_) | Projection::Orthographic(_) | Projection::Oblique(_) => {
                true
            }
            Projection::ThinLens(lens) => !lens.is_tilted(),
            Projection::Equirectangular | Projection::Fisheye(_) => false,
        };
        if !affine || !self.mistakes.is_empty() {
            return None;
        }
        let lens_corners: &[DVec2] = if self.projection.has_lens() {
            &[
                DVec2::new(-1.0, -1.0),
                DVec2::new(1.0, -1.0),
                DVec2::new(-1.0, 1.0),
                DVec2::new(1.0, 1.0),
            ]
        } else {
            &[DVec2::ZERO]
        };
        let [low, high] = corners;
        let image_corners = [
            low,
            DVec2::new(high.x, low.y),
            DVec2::new(low.x, high.y),
            high,
        ];
        let rays = image_corners.iter().flat_map(|&image| {
            lens_corners
                .iter()
                .filter_map(move |&lens| self.generate_ray_at_lens(image, lens))
        });
        RayBounds::around(rays)
    }

    /// Where the world point `p` appears: continuous image coordinates `(x, y)`, `x` from
    /// the left edge and `y` from the top, so pixel `(row, col)` spans
    /// `[col, col + 1) x [row, row + 1)`.
    ///
    /// The inverse of ray generation: `project(ray(row, col, (ox, oy)).at(t)) ==
    /// (col + ox, row + oy)` for every `t > 0` (through the lens centre for a thin lens).
    /// `None` where the point is not visible: behind a perspective eye or behind a
    /// parallel camera's image plane, at a panoramic camera's eye, or outside a
    /// fisheye's field of view, and always for a camera with mistakes
    /// ([`Camera::with_mistakes`]). Points beyond the image's edges still project (to
    /// coordinates outside `[0, W) x [0, H)`).
    pub fn project(&self, p: DVec3) -> Option<DVec2> {
        if !self.mistakes.is_empty() {
            return None;
        }
        let q = self.frame.camera_from_world_point(p);
        self.projection.project_camera_space(q, self.size())
    }

    /// The plane of sharp focus of a camera with a lens: its point nearest the lens
    /// centre and its unit normal toward the lens, so `e - f w` and `w` for an untilted
    /// thin lens (for an orthographic lens: `e - f w`, `f` from the image plane). A
    /// tilted thin lens's plane passes through its Scheimpflug and hinge lines
    /// ([`Camera::tilted_focus`]). `None` without a lens.
    pub fn focus_plane(&self) -> Option<Plane3> {
        match &self.projection {
            Projection::ThinLens(p) => Some(p.focus_plane(&self.frame)),
            Projection::Orthographic(o) => o.lens.map(|lens| Plane3 {
                point: self.frame.e() - lens.focus * self.frame.w(),
                normal: self.frame.w(),
            }),
            _ => None,
        }
    }

    /// The sensor, lens, front focal and focus planes of a tilted (or swung) thin lens,
    /// with its Scheimpflug and hinge lines, in world coordinates; `None` for every
    /// other camera (an untilted lens's lines lie at infinity).
    pub fn tilted_focus(&self) -> Option<TiltedFocus> {
        match &self.projection {
            Projection::ThinLens(p) => p.tilted_focus(&self.frame),
            _ => None,
        }
    }

    /// The pixel `(row, col)` holding the continuous image point `image`, or `None` if it
    /// lies outside the image.
    pub fn pixel_at(&self, image: DVec2) -> Option<(u32, u32)> {
        let inside =
            image.x >= 0.0 && image.y >= 0.0 && image.x < self.size().x && image.y < self.size().y;
        // Truncation is floor here: both coordinates are non-negative and below W or H.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        inside.then_some((image.y as u32, image.x as u32))
    }
}

/// The point `(u, v)` on the image plane of pixel `(row, col)` at the offset in the pixel
/// `p_film = (ox, oy)`, for an image of `W x H` pixels and a viewport of `vw x vh`.
///
/// ```text
/// u =  ((col + ox) / W - 1/2) * vw
/// v = -((row + oy) / H - 1/2) * vh
/// ```
///
/// Indices are 0-based, row 0 at the top, and `(ox, oy) = (0.5, 0.5)` is the pixel
/// centre. A lens shift `(sx, sy)` is not part of `(u, v)`: the perspective families add
/// it to the direction. With the lecture's 1-based indices `i = row + 1`, `j = col + 1` and the centre
/// sample this is exactly the lecture's
///
/// ```text
/// u =  ((j - 1/2) / W - 1/2) vw
/// v = -((i - 1/2) / H - 1/2) vh
/// ```
pub fn pixel_to_image_plane(
    row: u32,
    col: u32,
    p_film: DVec2,
    (width, height): (u32, u32),
    viewport: DVec2,
) -> DVec2 {
    let image = DVec2::new(f64::from(col), f64::from(row)) + p_film;
    image_to_image_plane(
        image,
        DVec2::new(f64::from(width), f64::from(height)),
        viewport,
    )
}

/// The image-plane point `(u, v)` of the continuous image point `(x, y)`:
/// `u = (x / W - 1/2) vw`, `v = -(y / H - 1/2) vh`.
#[inline]
pub(crate) fn image_to_image_plane(image: DVec2, size: DVec2, viewport: DVec2) -> DVec2 {
    DVec2::new(
        image_x_to_u(image.x, size.x, viewport.x),
        image_y_to_v(image.y, size.y, viewport.y),
    )
}

/// `u = (x / W - 1/2) vw`: the first coordinate of [`image_to_image_plane`].
#[inline]
fn image_x_to_u(x: f64, width: f64, vw: f64) -> f64 {
    (x / width - 0.5) * vw
}

/// `v = -(y / H - 1/2) vh`: the second coordinate of [`image_to_image_plane`].
#[inline]
fn image_y_to_v(y: f64, height: f64, vh: f64) -> f64 {
    -(y / height - 0.5) * vh
}

/// The inverse of [`image_to_image_plane`]: `x = (u / vw + 1/2) W`, `y = (1/2 - v / vh) H`.
#[inline]
pub(crate) fn image_plane_to_image(uv: DVec2, size: DVec2, viewport: DVec2) -> DVec2 {
    DVec2::new(
        (uv.x / viewport.x + 0.5) * size.x,
        (0.5 - uv.y / viewport.y) * size.y,
    )
}

/// Whether every one of `mistakes` can be made in a camera of `projection` making images
/// of `width` x `height` pixels: the family must fit ([`Mistake::fits`]), and
/// `size-minus-one`, which divides by `n - 1`, needs two pixels each way.
fn check_mistakes_fit(
    mistakes: Mistakes,
    projection: &Projection,
    width: u32,
    height: u32,
) -> Result<(), CameraError> {
    for mistake in mistakes.iter() {
        let detail = if !mistake.fits(projection) {
            String::new()
        } else if mistake == Mistake::SizeMinusOne && (width < 2 || height < 2) {
            format!(" of {width} x {height} pixels")
        } else {
            continue;
        };
        return Err(CameraError::MistakeDoesNotFit {
            id: mistake.id(),
            family: projection.family_name(),
            detail,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::Perspective;

    /// A coordinate, now and then a signed zero (where `e + 0` and `e` can differ).
    pub(super) fn coordinate() -> impl Strategy<Value = f64> {
        prop_oneof![Just(0.0), Just(-0.0), -10.0..10.0f64]
    }

    proptest! {
        /// The perspective rays' shared terms change no bit: every ray equals the
        /// family's camera-space rule followed by the whole frame transform.
        #[test]
        fn perspective_rays_are_the_general_rule_bit_for_bit(
            eye in (coordinate(), coordinate(), coordinate()),
            view in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
            distance in 0.05..5.0f64,
            viewport in (0.1..10.0f64, 0.1..10.0f64),
            shift in (-1.0..1.0f64, -1.0..1.0f64),
            size in (1u32..2000, 1u32..2000),
            image in (-10.0..2000.0f64, -10.0..2000.0f64),
        ) {
            let frame = Frame::from_eye_view_up(eye.into(), view.into(), DVec3::Y);
            prop_assume!(frame.is_ok());
            let frame = frame.unwrap();
            let projection = Projection::Perspective(Perspective {
                distance,
                viewport: viewport.into(),
                shift: shift.into(),
            });
            let camera = Camera::new(frame, projection, size.0, size.1).unwrap();
            let image = DVec2::from(image);
            let ray = camera.generate_ray_through(image, DVec2::splat(0.3)).unwrap();
            let general = projection
                .camera_space_ray(image, camera.size(), DVec2::ZERO)
                .unwrap();
            let bits = |v: DVec3| v.to_array().map(f64::to_bits);
            prop_assert_eq!(bits(ray.origin), bits(frame.world_from_camera_point(general.origin)));
            prop_assert_eq!(
                bits(ray.direction),
                bits(frame.world_from_camera_vector(general.direction))
            );
        }
    }
}
