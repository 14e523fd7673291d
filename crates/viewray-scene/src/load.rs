//! Scene text -> [`Scene`]: parsing, conversion and validation, with every error placed
//! at a file, line and column.

use std::path::Path;

use glam::{DVec2, DVec3};
use ron::error::{Error as RonError, SpannedError};
use ron::value::RawValue;
use viewray_camera::{
    Camera, Fisheye, Frame, Lens, Oblique, Orthographic, Perspective, Preset, Projection, ThinLens,
};

use crate::schema::{ExplicitCamera, ImageDef, PresetDef, ProjectionDef, SceneFile, V2, V3};
use crate::{Position, Scene, SceneError};

/// The largest image side viewray renders.
pub const MAX_IMAGE_SIDE: u32 = 16_384;
/// The largest number of pixels viewray renders: 2^28 (a 16384 x 16384 image).
pub const MAX_IMAGE_PIXELS: u64 = 1 << 28;
/// The largest number of samples per pixel.
pub const MAX_SAMPLES: u32 = 65_536;

/// Where a piece of text starts inside the scene file, so positions in it can be turned
/// into positions in the file.
#[derive(Clone, Copy)]
struct Origin {
    line: usize,
    column: usize,
}

impl Origin {
    const FILE: Origin = Origin { line: 1, column: 1 };

    /// The file position of `position` (1-based, relative to this origin).
    fn offset(self, line: usize, column: usize) -> Position {
        if line <= 1 {
            Position {
                line: self.line,
                column: self.column + column.saturating_sub(1),
            }
        } else {
            Position {
                line: self.line + line - 1,
                column,
            }
        }
    }

    /// The origin of `part`, a slice of `text`, which starts at this origin.
    fn of_slice(self, text: &str, part: &str) -> Origin {
        let offset = (part.as_ptr() as usize).saturating_sub(text.as_ptr() as usize);
        let before = &text[..offset.min(text.len())];
        let position = match before.rfind('\n') {
            Some(newline) => {
                let line = 1 + before.matches('\n').count();
                (line, before[newline + 1..].chars().count() + 1)
            }
            None => (1, before.chars().count() + 1),
        };
        let p = self.offset(position.0, position.1);
        Origin {
            line: p.line,
            column: p.column,
        }
    }

    fn position(self) -> Position {
        Position {
            line: self.line,
            column: self.column,
        }
    }
}

/// RON as scene files use it: optional fields are written bare, `look_at: (0, 0, 0)`
/// rather than `look_at: Some((0, 0, 0))`.
fn ron_options() -> ron::Options {
    ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
}

/// Parses the scene `text` read from `path` (used in error messages).
pub(crate) fn parse(text: &str, path: &Path) -> Result<Scene, SceneError> {
    let file: SceneFile<'_> = ron_options()
        .from_str(text)
        .map_err(|e| ron_error(path, Origin::FILE, &e))?;
    let (width, height, samples) = match file.image {
        Some(raw) => {
            let origin = Origin::FILE.of_slice(text, raw.get_ron());
            let image: ImageDef = ron_options()
                .from_str(raw.get_ron())
                .map_err(|e| ron_error(path, origin, &e))?;
            check_image(&image, path, origin)?
        }
        None => check_image(&ImageDef::default(), path, Origin::FILE)?,
    };

    let camera_text = file.camera.get_ron();
    let camera_origin = Origin::FILE.of_slice(text, camera_text);
    let camera = parse_camera(file.camera, camera_origin, path, width, height)?;

    Ok(Scene { camera, samples })
}

fn check_image(
    image: &ImageDef,
    path: &Path,
    origin: Origin,
) -> Result<(u32, u32, u32), SceneError> {
    let error = |message: String| {
        SceneError::at(path, Some(origin.position()), format!("image: {message}"))
    };
    let (width, height) = (image.width, image.height);
    if width == 0 || height == 0 {
        return Err(error(format!(
            "the image must be at least 1 x 1 pixels, found {width} x {height}"
        )));
    }
    if width > MAX_IMAGE_SIDE || height > MAX_IMAGE_SIDE {
        return Err(error(format!(
            "{width} x {height} is too large: each side can be at most {MAX_IMAGE_SIDE} pixels"
        )));
    }
    if u64::from(width) * u64::from(height) > MAX_IMAGE_PIXELS {
        return Err(error(format!(
            "{width} x {height} is too large: at most {MAX_IMAGE_PIXELS} pixels (2^28)"
        )));
    }
    if image.samples == 0 || image.samples > MAX_SAMPLES {
        return Err(error(format!(
            "samples must be between 1 and {MAX_SAMPLES}, found {}",
            image.samples
        )));
    }
    Ok((width, height, image.samples))
}

/// Parses the camera, an explicit `( .. )` or a preset `Name( .. )`.
fn parse_camera(
    raw: &RawValue,
    origin: Origin,
    path: &Path,
    width: u32,
    height: u32,
) -> Result<Camera, SceneError> {
    let text = raw.get_ron();
    let camera_error = |message: String| {
        SceneError::at(path, Some(origin.position()), format!("camera: {message}"))
    };
    if skip_whitespace_and_comments(text).starts_with('(') {
        let def: ExplicitCamera = ron_options()
            .from_str(text)
            .map_err(|e| ron_error(path, origin, &e))?;
        explicit_camera(&def, width, height).map_err(camera_error)
    } else {
        let def: PresetDef = ron_options()
            .from_str(text)
            .map_err(|e| ron_error(path, origin, &e))?;
        preset_camera(&def, width, height).map_err(camera_error)
    }
}

fn skip_whitespace_and_comments(mut text: &str) -> &str {
    loop {
        let trimmed = text.trim_start();
        if let Some(rest) = trimmed.strip_prefix("//") {
            text = rest.split_once('\n').map_or("", |(_, after)| after);
        } else if let Some(rest) = trimmed.strip_prefix("/*") {
            text = rest.split_once("*/").map_or("", |(_, after)| after);
        } else {
            return trimmed;
        }
    }
}

fn v3((x, y, z): V3) -> DVec3 {
    DVec3::new(x, y, z)
}

fn v2((x, y): V2) -> DVec2 {
    DVec2::new(x, y)
}

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

/// The viewport of a perspective projection from exactly one of `viewport`, `fov_y` and
/// `fov_x` (degrees).
fn perspective_viewport(
    viewport: Option<V2>,
    fov_y: Option<f64>,
    fov_x: Option<f64>,
    aspect: f64,
) -> Result<DVec2, String> {
    match (viewport, fov_y, fov_x) {
        (Some(viewport), None, None) => Ok(v2(viewport)),
        (None, Some(fov_y), None) => Perspective::from_fov_y(fov_y.to_radians(), aspect)
            .map(|p| p.viewport)
            .map_err(|e| e.to_string()),
        (None, None, Some(fov_x)) => Perspective::from_fov_x(fov_x.to_radians(), aspect)
            .map(|p| p.viewport)
            .map_err(|e| e.to_string()),
        (None, None, None) => {
            Err("missing `viewport: (vw, vh)` (or `fov_y` or `fov_x` in degrees)".to_owned())
        }
        _ => Err("give only one of `viewport`, `fov_y` and `fov_x`".to_owned()),
    }
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

fn projection(def: &ProjectionDef, aspect: f64) -> Result<Projection, String> {
    Ok(match *def {
        ProjectionDef::Perspective {
            distance,
            viewport,
            fov_y,
            fov_x,
            shift,
        } => Projection::Perspective(Perspective {
            distance,
            viewport: perspective_viewport(viewport, fov_y, fov_x, aspect)?,
            shift: v2(shift),
        }),
        ProjectionDef::ThinLens {
            distance,
            viewport,
            fov_y,
            fov_x,
            shift,
            aperture,
            focus,
        } => Projection::ThinLens(ThinLens {
            distance,
            viewport: perspective_viewport(viewport, fov_y, fov_x, aspect)?,
            shift: v2(shift),
            aperture,
            focus,
        }),
        ProjectionDef::Orthographic {
            viewport,
            height,
            aperture,
            focus,
        } => {
            let lens = match (aperture, focus) {
                (None, None) => None,
                (Some(aperture), Some(focus)) => Some(Lens { aperture, focus }),
                _ => return Err("a lens needs both `aperture` and `focus`".to_owned()),
            };
            Projection::Orthographic(Orthographic {
                viewport: parallel_viewport(viewport, height, aspect)?,
                lens,
            })
        }
        ProjectionDef::Oblique {
            viewport,
            height,
            ratio,
            angle,
        } => Projection::Oblique(Oblique {
            viewport: parallel_viewport(viewport, height, aspect)?,
            ratio,
            angle: angle.to_radians(),
        }),
        ProjectionDef::Equirectangular => Projection::Equirectangular,
        ProjectionDef::Fisheye { fov } => Projection::Fisheye(Fisheye {
            fov: fov.to_radians(),
        }),
    })
}

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

/// A RON error as a [`SceneError`], its position moved from `origin`-relative to the
/// file and its message in the scene format's words.
fn ron_error(path: &Path, origin: Origin, error: &SpannedError) -> SceneError {
    let start = error.span.start;
    let position = origin.offset(start.line, start.col);
    SceneError::at(path, Some(position), describe(&error.code))
}

/// The name a scene file's author knows a RON struct or enum by.
fn user_name(outer: Option<&String>) -> String {
    match outer.map(String::as_str) {
        None | Some("scene") => "the scene".to_owned(),
        Some(name) => format!("`{name}`"),
    }
}

fn list(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    match quoted.as_slice() {
        [] => "nothing".to_owned(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// A sentence for a RON error, saying what was found and what was expected.
fn describe(code: &RonError) -> String {
    match code {
        RonError::NoSuchEnumVariant {
            expected,
            found,
            outer,
        } => format!(
            "unknown {} `{found}`, expected one of {}",
            match outer.as_deref() {
                Some(name) => name.to_owned(),
                None => "variant".to_owned(),
            },
            list(expected)
        ),
        RonError::NoSuchStructField {
            expected,
            found,
            outer,
        } => format!(
            "unknown field `{found}` in {}, expected {}",
            user_name(outer.as_ref()),
            list(expected)
        ),
        RonError::MissingStructField { field, outer } => {
            format!("missing field `{field}` in {}", user_name(outer.as_ref()))
        }
        RonError::DuplicateStructField { field, outer } => {
            format!(
                "field `{field}` appears twice in {}",
                user_name(outer.as_ref())
            )
        }
        RonError::ExpectedDifferentLength { expected, found } => {
            format!("expected {expected}, found {found} elements")
        }
        RonError::Eof => "unexpected end of file".to_owned(),
        other => {
            // RON's own wording, as a sentence fragment like the others.
            let text = other.to_string();
            let mut chars = text.chars();
            match chars.next() {
                Some(first) => first.to_lowercase().chain(chars).collect(),
                None => text,
            }
        }
    }
}
