//! Fields of view on any axis and physical cameras (focal length, sensor, f-number): the
//! ways other tools spell a perspective camera, each turned into the lecture's `d`,
//! `vw` and `vh`.
//!
//! Every constructor here takes the image's aspect ratio `a = W / H` and gives a viewport
//! of that aspect ratio (square pixels), as a field of view in a scene file does.

use std::f64::consts::PI;

use glam::DVec2;

use crate::projection::check_positive;
use crate::{CameraError, Perspective};

/// Which extent of the viewport a field of view spans (Mitsuba 3's `fov_axis`).
///
/// With the aspect ratio `a = W / H`:
///
/// ```text
/// X         the width:     vw = 2 d tan(fov / 2)
/// Y         the height:    vh = 2 d tan(fov / 2)
/// Diagonal  the diagonal:  sqrt(vw^2 + vh^2) = 2 d tan(fov / 2)
/// Smaller   Y when a >= 1 (landscape or square), X otherwise (pbrt's `fov`)
/// Larger    X when a >= 1, Y otherwise
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FovAxis {
    /// The viewport's width (three.js and glTF use the height; Mitsuba's default is x).
    X,
    /// The viewport's height (three.js's `fov`, glTF's `yfov`).
    Y,
    /// The viewport's diagonal (a photographer's "angle of view").
    Diagonal,
    /// The shorter side (pbrt-v4's `fov`).
    Smaller,
    /// The longer side.
    Larger,
}

impl FovAxis {
    /// The axis this one names for an image of aspect ratio `aspect = W / H`: `Smaller`
    /// and `Larger` become `X` or `Y`, the others stay as they are. A square image
    /// counts as landscape (both sides are equal, so either answer gives one viewport).
    pub fn resolve(self, aspect: f64) -> FovAxis {
        match self {
            FovAxis::Smaller if aspect >= 1.0 => FovAxis::Y,
            FovAxis::Smaller => FovAxis::X,
            FovAxis::Larger if aspect >= 1.0 => FovAxis::X,
            FovAxis::Larger => FovAxis::Y,
            axis => axis,
        }
    }

    /// The name scene files use after `fov_`: `x`, `y`, `diagonal`, `smaller`, `larger`.
    pub fn name(self) -> &'static str {
        match self {
            FovAxis::X => "x",
            FovAxis::Y => "y",
            FovAxis::Diagonal => "diagonal",
            FovAxis::Smaller => "smaller",
            FovAxis::Larger => "larger",
        }
    }
}

/// Which side of the image a physical sensor's size fixes (Blender's `sensor_fit`).
///
/// ```text
/// Horizontal  the sensor's width spans the image's width
/// Vertical    the sensor's height spans the image's height
/// Auto        the sensor's WIDTH spans the image's longer side (Blender's default)
/// ```
///
/// The other side follows from the image's aspect ratio, so a 36 x 24 mm sensor on a
/// 16:9 image with `Horizontal` fit uses 36 x 20.25 mm of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SensorFit {
    /// The sensor width spans the longer image side (landscape: horizontal fit; portrait:
    /// vertical fit, still with the sensor *width*). A square image fits horizontally.
    #[default]
    Auto,
    /// The sensor width spans the image width.
    Horizontal,
    /// The sensor height spans the image height.
    Vertical,
}

impl SensorFit {
    /// The name scene files use: `Auto`, `Horizontal`, `Vertical`.
    pub fn name(self) -> &'static str {
        match self {
            SensorFit::Auto => "Auto",
            SensorFit::Horizontal => "Horizontal",
            SensorFit::Vertical => "Vertical",
        }
    }
}

/// Millimetres per scene unit for physical cameras: scene units are metres, as
/// Blender's are (focal lengths and sensors are given in millimetres).
pub const MILLIMETRES_PER_UNIT: f64 = 1000.0;

impl Perspective {
    /// A perspective projection with `d = 1` whose field of view `fov` (radians, the full
    /// angle) spans the viewport's `axis`, for an image of aspect ratio `aspect = W / H`.
    ///
    /// ```text
    /// t = 2 tan(fov / 2)
    /// X:         vw = t,                      vh = vw / a
    /// Y:         vh = t,                      vw = a vh
    /// Diagonal:  vw = t a / sqrt(1 + a^2),    vh = t / sqrt(1 + a^2)
    /// ```
    ///
    /// and `Smaller` / `Larger` as [`FovAxis::resolve`] says. Scale the viewport by `d`
    /// for another distance: the angles stay the same.
    ///
    /// # Errors
    /// [`CameraError::OutOfRange`] unless `0 < fov < pi`; [`CameraError::NotPositive`]
    /// unless `aspect > 0`.
    pub fn from_fov(axis: FovAxis, fov: f64, aspect: f64) -> Result<Self, CameraError> {
        check_fov(axis, fov)?;
        check_positive("aspect", aspect)?;
        let t = 2.0 * (fov / 2.0).tan();
        let viewport = match axis.resolve(aspect) {
            FovAxis::X => DVec2::new(t, t / aspect),
            FovAxis::Y => DVec2::new(aspect * t, t),
            _ => {
                let diagonal_per_height = aspect.hypot(1.0);
                DVec2::new(t * aspect / diagonal_per_height, t / diagonal_per_height)
            }
        };
        Ok(Self {
            distance: 1.0,
            viewport,
            shift: DVec2::ZERO,
        })
    }

    /// A physical camera: a lens of focal length `f` millimetres in front of a sensor of
    /// `sensor = (sw, sh)` millimetres, fitted to an image of aspect ratio `a = W / H` as
    /// `fit` says. The image plane is the sensor itself, mirrored in front of the lens, so
    /// in scene units of metres:
    ///
    /// ```text
    /// d = f / 1000
    /// Horizontal:            vw = sw / 1000,   vh = vw / a
    /// Vertical:              vh = sh / 1000,   vw = a vh
    /// Auto, a >= 1:          vw = sw / 1000,   vh = vw / a
    /// Auto, a < 1:           vh = sw / 1000,   vw = a vh
    /// ```
    ///
    /// The field of view across the fitted side is `2 atan(s / (2 f))`: Blender's default
    /// 50 mm lens on its 36 mm sensor sees 39.598 degrees across.
    ///
    /// # Errors
    /// [`CameraError::NotPositive`] unless the focal length, both sensor sides and
    /// `aspect` are positive.
    pub fn from_focal_length(
        focal_length: f64,
        sensor: DVec2,
        fit: SensorFit,
        aspect: f64,
    ) -> Result<Self, CameraError> {
        check_positive("focal_length", focal_length)?;
        check_positive("sensor width", sensor.x)?;
        check_positive("sensor height", sensor.y)?;
        check_positive("aspect", aspect)?;
        let sensor = sensor / MILLIMETRES_PER_UNIT;
        let viewport = match fit {
            SensorFit::Horizontal => DVec2::new(sensor.x, sensor.x / aspect),
            SensorFit::Vertical => DVec2::new(aspect * sensor.y, sensor.y),
            SensorFit::Auto if aspect >= 1.0 => DVec2::new(sensor.x, sensor.x / aspect),
            SensorFit::Auto => DVec2::new(aspect * sensor.x, sensor.x),
        };
        Ok(Self {
            distance: focal_length / MILLIMETRES_PER_UNIT,
            viewport,
            shift: DVec2::ZERO,
        })
    }

    /// The full angle (radians) the viewport spans across `axis`, for a viewport centred
    /// on the axis (no shift): `2 atan(extent / (2 d))` with the extent `vw`, `vh` or
    /// `sqrt(vw^2 + vh^2)`; `Smaller` and `Larger` pick by the viewport's own shape.
    pub fn fov(&self, axis: FovAxis) -> f64 {
        let (vw, vh) = (self.viewport.x, self.viewport.y);
        let extent = match axis.resolve(vw / vh) {
            FovAxis::X => vw,
            FovAxis::Y => vh,
            _ => vw.hypot(vh),
        };
        2.0 * (extent / (2.0 * self.distance)).atan()
    }
}

/// The lens radius `r` of a lens of focal length `f` millimetres at the f-number `N`,
/// in scene units of metres (as Blender's Cycles computes it):
///
/// ```text
/// r = f / (2 N) / 1000
/// ```
///
/// Blender's 50 mm lens at f/2.8 has a radius of 8.93 mm, 0.00893 scene units.
///
/// # Errors
/// [`CameraError::NotPositive`] unless both are positive.
pub fn aperture_from_f_number(focal_length: f64, f_number: f64) -> Result<f64, CameraError> {
    check_positive("focal_length", focal_length)?;
    check_positive("f_number", f_number)?;
    Ok(focal_length / (2.0 * f_number) / MILLIMETRES_PER_UNIT)
}

fn check_fov(axis: FovAxis, fov: f64) -> Result<(), CameraError> {
    let name = match axis {
        FovAxis::X => "fov_x",
        FovAxis::Y => "fov_y",
        FovAxis::Diagonal => "fov_diagonal",
        FovAxis::Smaller => "fov_smaller",
        FovAxis::Larger => "fov_larger",
    };
    if !fov.is_finite() {
        return Err(CameraError::NotFinite {
            name,
            value: fov.to_string(),
        });
    }
    if fov > 0.0 && fov < PI {
        Ok(())
    } else {
        Err(CameraError::OutOfRange {
            name,
            expected: "between 0 and 180 degrees",
            value: fov.to_degrees(),
        })
    }
}
