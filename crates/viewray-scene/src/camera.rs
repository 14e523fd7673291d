//! A scene file's camera: the `camera:` value (an explicit camera or a taxonomy preset)
//! read as written ([`CameraSpec`]) and translated into viewray-camera's [`Camera`] for an
//! image size, fields of view and presets following the image's aspect ratio.

use std::path::Path;

use glam::{DVec2, DVec3};
use ron::value::RawValue;
use viewray_camera::{
    Camera, Fisheye, FovAxis, Frame, Iris, Lens, Oblique, Orthographic, Perspective, Preset,
    Projection, SensorFit, ThinLens, aperture_from_f_number,
};

use crate::SceneError;
use crate::file_kind::skip_whitespace_and_comments;
use crate::ron_text::{self, LineIndex, Origin};
use crate::schema::{
    ExplicitCamera, ImageDef, PerspectiveDef, PresetDef, ProjectionDef, SceneFile, SensorFitDef,
    ThinLensDef, V2, V3,
};

/// A camera as a scene file writes it (the `camera:` value), before it is built for an
/// image size: fields of view and presets follow the image's aspect ratio, as they do for
/// a scene's own camera.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraSpec(pub(crate) CameraDef);

/// The two ways a scene file writes a camera.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum CameraDef {
    Explicit(Box<ExplicitCamera>),
    Preset(PresetDef),
}

impl CameraSpec {
    /// The camera for an image of `width x height` pixels.
    ///
    /// # Errors
    /// What is wrong with the camera (a zero view direction, a negative distance, ..), in
    /// the scene format's words.
    pub fn camera(&self, width: u32, height: u32) -> Result<Camera, String> {
        match &self.0 {
            CameraDef::Explicit(def) => explicit_camera(def, width, height),
            CameraDef::Preset(def) => preset_camera(def, width, height),
        }
    }
}

/// Parses `text` as the `camera:` value of a scene file, on its own, for an image of
/// `width x height` pixels: an explicit camera `(eye: .., look_at: .., projection: ..)`
/// or a taxonomy preset `Isometric(target: .., size: ..)`, exactly as a scene file
/// writes it. Fields of view and presets follow the image's aspect ratio, as they do
/// when a scene is loaded with [`crate::LoadOptions::size`].
///
/// Error positions count from the start of `text` (line 1, column 1), and `name` names
/// it (for example `camera`): `camera:1:9: unknown field ..`.
///
/// # Errors
/// A [`SceneError`] if `text` is not a valid camera or the size is not one a scene
/// file may have.
pub fn parse_camera(
    text: &str,
    name: &Path,
    width: u32,
    height: u32,
) -> Result<Camera, SceneError> {
    let image = ImageDef {
        width,
        height,
        samples: 1,
    };
    let (width, height, _) = crate::values::image(&image)
        .map_err(|message| SceneError::at(name, Some(Origin::FILE.position()), message))?;
    let raw: &RawValue = ron_text::parse(text, Origin::FILE, name)?;
    let origin = LineIndex::new(text).origin_of(raw.get_ron());
    camera_at(raw, origin, name, width, height)
}

/// The `camera:` value of the scene file `text` as written there (comments inside it
/// included), without the surrounding whitespace: what [`parse_camera`] reads back.
///
/// # Errors
/// A [`SceneError`] if `text` is not a scene file (it is not checked any further).
pub fn camera_text<'a>(text: &'a str, path: &Path) -> Result<&'a str, SceneError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let file: SceneFile<'a> = ron_text::parse(text, Origin::FILE, path)?;
    Ok(file.camera.get_ron().trim())
}

/// Parses and builds the camera `raw` (a slice of the file `path` starting at `origin`)
/// for a `width x height` image; what is wrong with it is placed at its start.
pub(crate) fn camera_at(
    raw: &RawValue,
    origin: Origin,
    path: &Path,
    width: u32,
    height: u32,
) -> Result<Camera, SceneError> {
    let camera_error = |message: String| {
        SceneError::at(path, Some(origin.position()), format!("camera: {message}"))
    };
    parse_camera_spec(raw, origin, path)?
        .camera(width, height)
        .map_err(camera_error)
}

/// Parses a camera as written, an explicit `( .. )` or a preset `Name( .. )`, without
/// building it.
pub(crate) fn parse_camera_spec(
    raw: &RawValue,
    origin: Origin,
    path: &Path,
) -> Result<CameraSpec, SceneError> {
    let text = raw.get_ron();
    let def = if skip_whitespace_and_comments(text).starts_with('(') {
        CameraDef::Explicit(Box::new(ron_text::parse(text, origin, path)?))
    } else {
        CameraDef::Preset(ron_text::parse(text, origin, path)?)
    };
    Ok(CameraSpec(def))
}

fn v3((x, y, z): V3) -> DVec3 {
    DVec3::new(x, y, z)
}

fn v2((x, y): V2) -> DVec2 {
    DVec2::new(x, y)
}

/// The camera `(eye: .., look_at: .. | view: .., up: .., projection: ..)` for a
/// `width x height` image.
fn explicit_camera(def: &ExplicitCamera, width: u32, height: u32) -> Result<Camera, String> {
    let eye = v3(def.eye);
    let up = v3(def.up);
    let frame = match (def.look_at, def.view) {
        (Some(look_at), None) => Frame::from_eye_look_at_up(eye, v3(look_at), up),
        (None, Some(view)) => Frame::from_eye_view_up(eye, v3(view), up),
        (Some(_), Some(_)) => {
            return Err("give either `look_at` or `view`, not both".to_owned());
        }
        (None, None) => {
            return Err("missing `look_at` (a point) or `view` (a direction)".to_owned());
        }
    }
    .map_err(|e| e.to_string())?;
    let aspect = f64::from(width) / f64::from(height);
    let projection = projection(&def.projection, aspect)?;
    Camera::new(frame, projection, width, height).map_err(|e| e.to_string())
}

/// Blender's default sensor, 36 x 24 mm, for a `focal_length` given without `sensor`.
const DEFAULT_SENSOR: V2 = (36.0, 24.0);

/// The perspective projection (distance, viewport and shift) from exactly one of
/// `viewport`, a field of view (`fov_x`, `fov_y`, `fov_diagonal`, `fov_smaller`,
/// `fov_larger`, in degrees, scaled by `distance` when one is given) and a physical
/// `focal_length` (mm, with `sensor` in mm and `fit`), the last two following the image's
/// aspect ratio.
fn perspective(def: &PerspectiveDef, aspect: f64) -> Result<Perspective, String> {
    let fovs: Vec<(FovAxis, f64)> = [
        (FovAxis::X, def.fov_x),
        (FovAxis::Y, def.fov_y),
        (FovAxis::Diagonal, def.fov_diagonal),
        (FovAxis::Smaller, def.fov_smaller),
        (FovAxis::Larger, def.fov_larger),
    ]
    .into_iter()
    .filter_map(|(axis, fov)| fov.map(|f| (axis, f)))
    .collect();
    let given =
        usize::from(def.viewport.is_some()) + fovs.len() + usize::from(def.focal_length.is_some());
    if given > 1 {
        return Err(
            "give only one of `viewport`, a field of view (`fov_x`, `fov_y`, \
                    `fov_diagonal`, `fov_smaller`, `fov_larger`) and `focal_length`"
                .to_owned(),
        );
    }
    if def.focal_length.is_none() && (def.sensor.is_some() || def.fit.is_some()) {
        return Err(
            "`sensor` and `fit` describe a physical camera: give `focal_length` \
                    (mm) with them"
                .to_owned(),
        );
    }
    let error = |e: viewray_camera::CameraError| e.to_string();
    let mut projection = if let Some(viewport) = def.viewport {
        Perspective {
            distance: def.distance.unwrap_or(1.0),
            viewport: v2(viewport),
            shift: DVec2::ZERO,
        }
    } else if let Some(&(axis, degrees)) = fovs.first() {
        let mut p = Perspective::from_fov(axis, degrees.to_radians(), aspect).map_err(error)?;
        if let Some(distance) = def.distance {
            p.distance = distance;
            p.viewport *= distance;
        }
        p
    } else if let Some(focal_length) = def.focal_length {
        if def.distance.is_some() {
            return Err(
                "`focal_length` sets the distance d (the focal length in metres): \
                        give `distance` or `focal_length`, not both"
                    .to_owned(),
            );
        }
        let fit = match def.fit.unwrap_or(SensorFitDef::Auto) {
            SensorFitDef::Auto => SensorFit::Auto,
            SensorFitDef::Horizontal => SensorFit::Horizontal,
            SensorFitDef::Vertical => SensorFit::Vertical,
        };
        let sensor = v2(def.sensor.unwrap_or(DEFAULT_SENSOR));
        Perspective::from_focal_length(focal_length, sensor, fit, aspect).map_err(error)?
    } else {
        return Err("missing `viewport: (vw, vh)` (or a field of view such as `fov_y` in                     degrees, or `focal_length` in mm)"
            .to_owned());
    };
    projection.shift = v2(def.shift);
    Ok(projection)
}

/// The thin lens: a perspective window and a lens of radius `aperture`, or of a focal
/// length's `f_number`, focused at `focus`, tilted and swung (a physical camera's only),
/// with its blades.
fn thin_lens(def: &ThinLensDef, aspect: f64) -> Result<ThinLens, String> {
    let pinhole = perspective(&def.perspective, aspect)?;
    let aperture = match (def.aperture, def.f_number, def.perspective.focal_length) {
        (Some(aperture), None, _) => aperture,
        (None, Some(n), Some(f)) => aperture_from_f_number(f, n).map_err(|e| e.to_string())?,
        (None, Some(_), None) => {
            return Err(
                "`f_number` needs a `focal_length` (mm): the lens radius is \
                        focal_length / (2 f_number)"
                    .to_owned(),
            );
        }
        (Some(_), Some(_), _) => {
            return Err("give either `aperture` (the lens radius) or `f_number`, \
                        not both"
                .to_owned());
        }
        (None, None, _) => {
            return Err("missing `aperture` (the lens radius) or `f_number` (with \
                        `focal_length`)"
                .to_owned());
        }
    };
    if (def.lens_tilt != 0.0 || def.lens_swing != 0.0) && def.perspective.focal_length.is_none() {
        return Err(
            "`lens_tilt` and `lens_swing` tilt the lens of a physical camera: give \
             `focal_length` (mm) with them (the plane of focus turns about the hinge line, \
             focal_length / sin(tilt) from the lens)"
                .to_owned(),
        );
    }
    Ok(ThinLens {
        tilt: def.lens_tilt.to_radians(),
        swing: def.lens_swing.to_radians(),
        iris: Iris::from_degrees(def.blades, def.blade_rotation).map_err(|e| e.to_string())?,
        ..ThinLens::new(pinhole, aperture, def.focus)
    })
}

/// The viewport of a parallel projection from exactly one of `viewport` and `height`.
fn parallel_viewport(
    viewport: Option<V2>,
    height: Option<f64>,
    aspect: f64,
) -> Result<DVec2, String> {
    match (viewport, height) {
        (Some(viewport), None) => Ok(v2(viewport)),
        (None, Some(height)) => Orthographic::from_height(height, aspect)
            .map(|o| o.viewport)
            .map_err(|e| e.to_string()),
        (None, None) => Err("missing `viewport: (vw, vh)` (or `height`)".to_owned()),
        (Some(_), Some(_)) => Err("give either `viewport` or `height`, not both".to_owned()),
    }
}

/// The projection as written, for an image of aspect ratio `aspect` (width / height).
fn projection(def: &ProjectionDef, aspect: f64) -> Result<Projection, String> {
    Ok(match def {
        ProjectionDef::Perspective(def) => Projection::Perspective(perspective(def, aspect)?),
        ProjectionDef::ThinLens(def) => Projection::ThinLens(thin_lens(def, aspect)?),
        ProjectionDef::Orthographic(def) => {
            let lens = match (def.aperture, def.focus) {
                (None, None) => None,
                (Some(aperture), Some(focus)) => Some(Lens { aperture, focus }),
                _ => return Err("a lens needs both `aperture` and `focus`".to_owned()),
            };
            Projection::Orthographic(Orthographic {
                viewport: parallel_viewport(def.viewport, def.height, aspect)?,
                lens,
            })
        }
        ProjectionDef::Oblique(def) => Projection::Oblique(Oblique {
            viewport: parallel_viewport(def.viewport, def.height, aspect)?,
            ratio: def.ratio,
            angle: def.angle.to_radians(),
        }),
        ProjectionDef::Equirectangular => Projection::Equirectangular,
        ProjectionDef::Fisheye(def) => Projection::Fisheye(Fisheye {
            fov: def.fov.to_radians(),
        }),
    })
}

/// The camera of a taxonomy preset for a `width x height` image.
fn preset_camera(def: &PresetDef, width: u32, height: u32) -> Result<Camera, String> {
    let (preset, target, size) = match *def {
        PresetDef::Front { target, size } => (Preset::Front, target, size),
        PresetDef::Top { target, size } => (Preset::Top, target, size),
        PresetDef::Side { target, size } => (Preset::Side, target, size),
        PresetDef::Isometric { target, size } => (Preset::Isometric, target, size),
        PresetDef::Dimetric { target, size } => (Preset::Dimetric, target, size),
        PresetDef::Trimetric { target, size } => (Preset::Trimetric, target, size),
        PresetDef::Cavalier {
            target,
            size,
            angle,
        } => (
            Preset::Cavalier {
                angle: angle.to_radians(),
            },
            target,
            size,
        ),
        PresetDef::Cabinet {
            target,
            size,
            angle,
        } => (
            Preset::Cabinet {
                angle: angle.to_radians(),
            },
            target,
            size,
        ),
        PresetDef::OnePoint { target, size } => (Preset::OnePoint, target, size),
        PresetDef::TwoPoint { target, size } => (Preset::TwoPoint, target, size),
        PresetDef::ThreePoint { target, size } => (Preset::ThreePoint, target, size),
    };
    preset
        .camera(v3(target), size, width, height)
        .map_err(|e| e.to_string())
}
