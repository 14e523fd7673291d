//! The classical taxonomy of planar geometric projections as named presets.
//!
//! Carlbom and Paciorek (1978) and Foley et al. sort projections into a tree:
//!
//! ```text
//! planar geometric
//! +-- parallel
//! |   +-- orthographic
//! |   |   +-- multiview: front, top, side
//! |   |   +-- axonometric: isometric, dimetric, trimetric
//! |   +-- oblique: cavalier, cabinet
//! +-- perspective: one-point, two-point, three-point
//! ```
//!
//! Every preset is one of the four lecture rules ([`Projection`]) with a frame chosen to
//! show its defining property, aimed at a `target` with a view `size` units tall there.
//! World `+y` is up.

use std::f64::consts::FRAC_PI_4;

use glam::{DVec2, DVec3};

use crate::image_limits::check_not_empty;
use crate::projection::check_positive;
use crate::{Camera, CameraError, Frame, Oblique, Orthographic, Perspective, Projection};

/// A named member of the classical projection taxonomy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Preset {
    /// Multiview front elevation: orthographic, looking along `-z`, image plane parallel
    /// to the xy plane. Only x and y show, both at scale 1.
    Front,
    /// Multiview top (plan) view: orthographic, looking down `-y` with `-z` up in the
    /// image. Only x and z show, both at scale 1.
    Top,
    /// Multiview right side elevation: orthographic, looking along `-x`. Only z and y
    /// show, both at scale 1.
    Side,
    /// Isometric: orthographic, viewing along `(1, 1, 1)` (45 degrees about the vertical,
    /// then arctan(1/sqrt 2) = 35.2644 degrees down). Every axis is foreshortened by
    /// sqrt(2/3) = 0.8165 and the projected axes are 120 degrees apart.
    Isometric,
    /// Dimetric: orthographic, viewing along `(1, 1, sqrt 7)`. x and y are foreshortened
    /// equally by sqrt(8/9) = 0.9428, z by sqrt(2/9) = 0.4714; the projected x and z
    /// axes fall 7.18 and 41.41 degrees below the horizontal.
    Dimetric,
    /// Trimetric: orthographic, viewing along `(1, 2, 3)`. The three axes are
    /// foreshortened differently: x by sqrt(13/14) = 0.9636, y by sqrt(10/14) = 0.8452,
    /// z by sqrt(5/14) = 0.5976.
    Trimetric,
    /// Cavalier: oblique with `L = 1` (projectors at 45 degrees to the image plane),
    /// image plane parallel to the xy plane; depth recedes at `angle` (radians) at full
    /// length.
    Cavalier {
        /// `phi`: the angle at which depth recedes, radians from the image's `u` axis.
        angle: f64,
    },
    /// Cabinet: oblique with `L = 1/2` (projectors at arctan 2 = 63.435 degrees to the
    /// image plane), image plane parallel to the xy plane; depth recedes at `angle`
    /// (radians) at half length.
    Cabinet {
        /// `phi`: the angle at which depth recedes, radians from the image's `u` axis.
        angle: f64,
    },
    /// One-point perspective: image plane parallel to the x and y axes (view along
    /// `-z`), so only z lines converge, to a single vanishing point. The eye sits
    /// 0.35 size to the right of and 0.25 size above the target, and a lens shift
    /// centres the target.
    OnePoint,
    /// Two-point perspective: the camera is level (the vertical y axis is parallel to
    /// the image plane, so verticals stay parallel) and turned 30 degrees about the
    /// vertical, so x and z lines converge to two vanishing points. The eye sits 0.25
    /// size above the target, and a vertical lens shift of `d tan(theta)` centres it.
    TwoPoint,
    /// Three-point perspective: the camera looks at the target from 30 degrees about the
    /// vertical and 30 degrees above, so no axis is parallel to the image plane and lines
    /// along all three converge.
    ThreePoint,
}

/// The perspective presets' vertical field of view: 50 degrees.
pub const PRESET_FOV_Y_DEGREES: f64 = 50.0;

/// How far the parallel presets place the eye from the target, in units of `size`: far
/// enough that the objects around the target lie in front of the image plane.
pub const PARALLEL_EYE_DISTANCE: f64 = 10.0;

impl Preset {
    /// Every preset, in the taxonomy's order, the oblique ones at 45 degrees.
    pub const ALL: [Preset; 11] = [
        Preset::Front,
        Preset::Top,
        Preset::Side,
        Preset::Isometric,
        Preset::Dimetric,
        Preset::Trimetric,
        Preset::Cavalier { angle: FRAC_PI_4 },
        Preset::Cabinet { angle: FRAC_PI_4 },
        Preset::OnePoint,
        Preset::TwoPoint,
        Preset::ThreePoint,
    ];

    /// The preset's name as scene files spell it, e.g. `"Isometric"`.
    pub fn name(&self) -> &'static str {
        match self {
            Preset::Front => "Front",
            Preset::Top => "Top",
            Preset::Side => "Side",
            Preset::Isometric => "Isometric",
            Preset::Dimetric => "Dimetric",
            Preset::Trimetric => "Trimetric",
            Preset::Cavalier { .. } => "Cavalier",
            Preset::Cabinet { .. } => "Cabinet",
            Preset::OnePoint => "OnePoint",
            Preset::TwoPoint => "TwoPoint",
            Preset::ThreePoint => "ThreePoint",
        }
    }

    /// The preset's path in the taxonomy, from the root's child down, e.g.
    /// `["parallel", "orthographic", "axonometric"]` for isometric.
    pub fn taxonomy(&self) -> &'static [&'static str] {
        match self {
            Preset::Front | Preset::Top | Preset::Side => {
                &["parallel", "orthographic", "multiview"]
            }
            Preset::Isometric | Preset::Dimetric | Preset::Trimetric => {
                &["parallel", "orthographic", "axonometric"]
            }
            Preset::Cavalier { .. } | Preset::Cabinet { .. } => &["parallel", "oblique"],
            Preset::OnePoint | Preset::TwoPoint | Preset::ThreePoint => &["perspective"],
        }
    }

    /// The direction from the target towards the eye of the orthographic presets, and
    /// the up vector they use.
    fn orthographic_direction(&self) -> Option<(DVec3, DVec3)> {
        Some(match self {
            Preset::Front => (DVec3::Z, DVec3::Y),
            Preset::Top => (DVec3::Y, DVec3::NEG_Z),
            Preset::Side => (DVec3::X, DVec3::Y),
            Preset::Isometric => (DVec3::ONE, DVec3::Y),
            Preset::Dimetric => (DVec3::new(1.0, 1.0, 7f64.sqrt()), DVec3::Y),
            Preset::Trimetric => (DVec3::new(1.0, 2.0, 3.0), DVec3::Y),
            _ => return None,
        })
    }

    /// A camera of this preset aimed at `target`, showing a view `size` units tall there,
    /// with an image of `width x height` pixels (the viewport's aspect ratio follows the
    /// image's).
    ///
    /// Parallel presets: an orthographic or oblique viewport `size * W/H` by `size`, the
    /// eye [`PARALLEL_EYE_DISTANCE`] sizes from the target. Perspective presets: `d = 1`,
    /// a vertical field of view of [`PRESET_FOV_Y_DEGREES`], the eye at the distance
    /// where the view spans `size`.
    ///
    /// # Errors
    /// [`CameraError::NotPositive`] unless `size` is positive and finite,
    /// [`CameraError::NotFinite`] for a non-finite target or angle, and
    /// [`CameraError::Image`] for a zero image size.
    pub fn camera(
        &self,
        target: DVec3,
        size: f64,
        width: u32,
        height: u32,
    ) -> Result<Camera, CameraError> {
        crate::frame::check_finite_vector("target", target)?;
        check_positive("size", size)?;
        check_not_empty(u64::from(width), u64::from(height))?;
        let aspect = f64::from(width) / f64::from(height);
        let viewport = DVec2::new(aspect * size, size);
        let parallel_distance = PARALLEL_EYE_DISTANCE * size;

        if let Some((towards_eye, up)) = self.orthographic_direction() {
            let eye = target + parallel_distance * towards_eye.normalize();
            let frame = Frame::from_eye_look_at_up(eye, target, up)?;
            let projection = Projection::Orthographic(Orthographic {
                viewport,
                lens: None,
            });
            return Camera::new(frame, projection, width, height);
        }

        let oblique = match *self {
            Preset::Cavalier { angle } => Some(Oblique::cavalier(viewport, angle)),
            Preset::Cabinet { angle } => Some(Oblique::cabinet(viewport, angle)),
            _ => None,
        };
        if let Some(oblique) = oblique {
            // The image plane is parallel to xy. Slide the eye along the projectors so the
            // target, `parallel_distance` behind the plane, appears at the image centre.
            Projection::Oblique(oblique).validate()?;
            let (sin, cos) = oblique.angle.sin_cos();
            let slide = oblique.ratio * DVec3::new(cos, sin, 0.0);
            let eye = target + parallel_distance * (DVec3::Z + slide);
            let frame = Frame::from_eye_view_up(eye, DVec3::NEG_Z, DVec3::Y)?;
            return Camera::new(frame, Projection::Oblique(oblique), width, height);
        }

        let mut perspective = Perspective::from_fov_y(PRESET_FOV_Y_DEGREES.to_radians(), aspect)?;
        let distance = size / perspective.viewport.y;
        let d = perspective.distance;
        let frame = match self {
            Preset::OnePoint => {
                let offset = DVec3::new(0.35 * size, 0.25 * size, distance);
                // The target sits at camera coordinates (-0.35 size, -0.25 size, -D);
                // shifting the window by d q/D centres it.
                perspective.shift = DVec2::new(-offset.x, -offset.y) * (d / distance);
                Frame::from_eye_view_up(target + offset, DVec3::NEG_Z, DVec3::Y)?
            }
            Preset::TwoPoint => {
                let azimuth = 30f64.to_radians();
                let (sin, cos) = azimuth.sin_cos();
                let horizontal = DVec3::new(sin, 0.0, cos);
                let rise = 0.25 * size;
                let elevation = (-rise / distance).atan();
                perspective.shift.y = Perspective::shift_for_elevation(d, elevation);
                let eye = target + distance * horizontal + rise * DVec3::Y;
                Frame::from_eye_view_up(eye, -horizontal, DVec3::Y)?
            }
            _ => {
                let (sin_az, cos_az) = 30f64.to_radians().sin_cos();
                let (sin_el, cos_el) = 30f64.to_radians().sin_cos();
                let towards_eye = DVec3::new(cos_el * sin_az, sin_el, cos_el * cos_az);
                Frame::from_eye_look_at_up(target + distance * towards_eye, target, DVec3::Y)?
            }
        };
        Camera::new(frame, Projection::Perspective(perspective), width, height)
    }
}
