//! Scene text -> [`Scene`]: parsing, conversion and validation, with every error placed
//! at a file, line and column.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::{Affine3A, DVec2, DVec3, Quat, Vec3};
use ron::error::{Error as RonError, SpannedError};
use ron::value::RawValue;
use viewray_camera::{
    Camera, Fisheye, FovAxis, Frame, ImageLimitError, ImageLimits, Lens, Oblique, Orthographic,
    Perspective, Preset, Projection, SensorFit, ThinLens, aperture_from_f_number,
};

use viewray_geometry::{Aabb, Instance, Object, Plane, Sphere, Triangle, World};

use crate::animation::{CameraDef, MAX_FPS, MAX_FRAMES};
use crate::mesh::MeshCache;
use crate::schema::{
    AnimationDef, EaseDef, ExplicitCamera, ImageDef, KeyDef, LightDef, MaterialDef, ObjectDef,
    PresetDef, ProjectionDef, Scale, SceneFile, SensorFitDef, ShadingDef, Specular, TransformDef,
    V2, V3,
};
use crate::{
    Animation, CameraSpec, Ease, Grid, Key, Light, Material, ObjectMaterial, Position, Scene,
    SceneError, SceneParts, Shading,
};

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

    fn position(self) -> Position {
        Position {
            line: self.line,
            column: self.column,
        }
    }
}

/// Where each line of a file starts, so that the position of any slice of it is found
/// in `O(log lines)`: a scene of many objects looks up one position per object, and
/// counting lines from the start for each made loading quadratic.
struct LineIndex<'a> {
    text: &'a str,
    /// The byte offset of each line's first character; the first line starts at 0.
    starts: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    fn new(text: &'a str) -> Self {
        let starts = std::iter::once(0)
            .chain(text.match_indices('\n').map(|(newline, _)| newline + 1))
            .collect();
        Self { text, starts }
    }

    /// Where `part`, a slice of the indexed text, starts: its 1-based line, and its
    /// column counted in characters.
    fn origin_of(&self, part: &str) -> Origin {
        let offset = (part.as_ptr() as usize)
            .saturating_sub(self.text.as_ptr() as usize)
            .min(self.text.len());
        // The number of lines starting at or before `offset` is `offset`'s line.
        let line = self.starts.partition_point(|&start| start <= offset);
        let line_start = self.starts[line - 1];
        let column = self
            .text
            .get(line_start..offset)
            .map_or(0, |before| before.chars().count());
        Origin {
            line,
            column: column + 1,
        }
    }
}

/// RON as scene files use it: optional fields are written bare, `look_at: (0, 0, 0)`
/// rather than `look_at: Some((0, 0, 0))`.
fn ron_options() -> ron::Options {
    ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
}

/// Settings that override the scene file's, applied before the camera is built (so a
/// field of view or a preset follows the new aspect ratio).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LoadOptions {
    /// Render at `(width, height)` instead of the file's image size.
    pub size: Option<(u32, u32)>,
    /// Take this many samples per pixel instead of the file's.
    pub samples: Option<u32>,
}

/// Parses the scene `text` read from `path` (used in error messages; meshes are found
/// relative to its folder).
pub(crate) fn parse(
    text: &str,
    path: &Path,
    options: LoadOptions,
) -> Result<(Scene, Option<Animation>, Duration), SceneError> {
    // Windows editors may begin a UTF-8 file with a byte-order mark; it is not part of
    // the scene, and columns are counted as an editor shows them, without it.
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    if skip_whitespace_and_comments(text).is_empty() {
        return Err(SceneError::at(path, None, empty_file_message(text)));
    }
    let file: SceneFile<'_> = ron_options()
        .from_str(text)
        .map_err(|e| ron_error(path, text, Origin::FILE, &e))?;
    let loader = Loader {
        lines: LineIndex::new(text),
        path,
    };

    let (mut image, image_origin) = match file.image {
        Some(raw) => loader.value::<ImageDef>(raw)?,
        None => (ImageDef::default(), Origin::FILE),
    };
    if let Some((width, height)) = options.size {
        image.width = width;
        image.height = height;
    }
    if let Some(samples) = options.samples {
        image.samples = samples;
    }
    let (width, height, samples) = check_image(&image, path, image_origin)?;

    let camera_origin = loader.lines.origin_of(file.camera.get_ron());
    let camera = parse_camera(file.camera, camera_origin, path, width, height)?;
    let animation = match file.animation {
        Some(raw) => Some(parse_animation(raw, &loader.lines, path, width, height)?),
        None => None,
    };

    let background = color(file.background)
        .map_err(|m| SceneError::at(path, None, format!("background: {m}")))?;

    let mut materials = Vec::with_capacity(file.materials.len() + 1);
    let mut material_index = BTreeMap::new();
    for (name, raw) in &file.materials {
        let (def, origin) = loader.value::<MaterialDef>(raw)?;
        let material =
            material(&def).map_err(|m| loader.error(origin, format!("material `{name}`: {m}")))?;
        material_index.insert(name.as_str(), index_u32(materials.len()));
        materials.push(material);
    }
    let default_material = index_u32(materials.len());
    materials.push(Material::default());

    let mut lights = Vec::with_capacity(file.lights.len());
    for raw in &file.lights {
        let (def, origin) = loader.value::<LightDef>(raw)?;
        lights.push(light(&def).map_err(|m| loader.error(origin, format!("light: {m}")))?);
    }

    let mut objects = Vec::with_capacity(file.objects.len());
    let mut object_materials = Vec::with_capacity(file.objects.len());
    let mut meshes = MeshCache::default();
    for raw in &file.objects {
        let (def, origin) = loader.value::<ObjectDef>(raw)?;
        let error = |m: String| loader.error(origin, m);
        let named = |name: &Option<String>| -> Result<u32, SceneError> {
            match name {
                None => Ok(default_material),
                Some(name) => material_index.get(name.as_str()).copied().ok_or_else(|| {
                    let known: Vec<&str> = material_index.keys().copied().collect();
                    error(if known.is_empty() {
                        format!("unknown material `{name}`: the scene defines no materials")
                    } else {
                        format!(
                            "unknown material `{name}`, expected one of {}",
                            list(&known)
                        )
                    })
                }),
            }
        };
        let (object, object_material) = match &def {
            ObjectDef::Sphere {
                center,
                radius,
                material,
            } => {
                let sphere = Sphere {
                    center: point("center", *center).map_err(error)?,
                    radius: positive("radius", *radius).map_err(error)?,
                };
                (
                    Object::Sphere(sphere),
                    ObjectMaterial::Single(named(material)?),
                )
            }
            ObjectDef::Plane {
                point: p,
                normal,
                material,
            } => {
                let normal = direction("normal", *normal).map_err(error)?;
                let plane = Plane {
                    point: point("point", *p).map_err(error)?,
                    normal,
                };
                (
                    Object::Plane(plane),
                    ObjectMaterial::Single(named(material)?),
                )
            }
            ObjectDef::Triangle { a, b, c, material } => {
                let triangle = Triangle {
                    a: point("a", *a).map_err(error)?,
                    b: point("b", *b).map_err(error)?,
                    c: point("c", *c).map_err(error)?,
                };
                if triangle.area_normal().length_squared() == 0.0 {
                    return Err(error(
                        "the triangle has zero area: its corners are on one line".to_owned(),
                    ));
                }
                (
                    Object::Triangle(triangle),
                    ObjectMaterial::Single(named(material)?),
                )
            }
            ObjectDef::Box { min, max, material } => {
                let (min, max) = (
                    point("min", *min).map_err(error)?,
                    point("max", *max).map_err(error)?,
                );
                if !min.cmplt(max).all() {
                    return Err(error(format!(
                        "the box needs min < max on every axis, found min {min} and max {max}"
                    )));
                }
                (
                    Object::Box(Aabb { min, max }),
                    ObjectMaterial::Single(named(material)?),
                )
            }
            ObjectDef::Mesh {
                path: mesh_path,
                material,
                transform,
            } => {
                let world_from_object = affine(transform).map_err(error)?;
                let file = self::mesh_path(path, mesh_path);
                let loaded = meshes
                    .load(&file, &mut materials)
                    .map_err(|m| error(format!("mesh `{mesh_path}`: {m}")))?;
                let instance = Instance::new(Arc::clone(&loaded.mesh), world_from_object)
                    .map_err(|e| error(format!("mesh `{mesh_path}`: {e}")))?;
                let object_material = match (material, &loaded.face_materials) {
                    (Some(_), _) | (None, None) => ObjectMaterial::Single(named(material)?),
                    (None, Some(faces)) => ObjectMaterial::PerTriangle(Arc::clone(faces)),
                };
                (Object::Instance(instance), object_material)
            }
        };
        objects.push(object);
        object_materials.push(object_material);
    }
    let started = Instant::now();
    let world = World::new(objects).map_err(|e| SceneError::at(path, None, e.to_string()))?;
    let build_time = meshes.build_time + started.elapsed();

    let scene = Scene::new(SceneParts {
        camera,
        samples,
        background,
        shading: match file.shading {
            ShadingDef::Flat => Shading::Flat,
            ShadingDef::Normals => Shading::Normals,
            ShadingDef::Depth => Shading::Depth,
            ShadingDef::Lit => Shading::Lit,
        },
        materials,
        lights,
        world,
        object_materials,
    })
    .map_err(|e| SceneError::at(path, None, e.to_string()))?;
    Ok((scene, animation, build_time))
}

/// Parses the values kept as raw text, placing their errors in the file.
struct Loader<'a> {
    lines: LineIndex<'a>,
    path: &'a Path,
}

impl Loader<'_> {
    /// Parses `raw`, a slice of the file, as a `T`; returns it with where it starts.
    fn value<T: serde::de::DeserializeOwned>(
        &self,
        raw: &RawValue,
    ) -> Result<(T, Origin), SceneError> {
        let origin = self.lines.origin_of(raw.get_ron());
        let value = ron_options()
            .from_str(raw.get_ron())
            .map_err(|e| ron_error(self.path, raw.get_ron(), origin, &e))?;
        Ok((value, origin))
    }

    fn error(&self, origin: Origin, message: String) -> SceneError {
        SceneError::at(self.path, Some(origin.position()), message)
    }
}

fn index_u32(index: usize) -> u32 {
    u32::try_from(index).expect("fewer than 2^32 materials")
}

/// A finite `f64` that stays finite as the `f32` the tracer uses.
fn finite32(name: &str, x: f64) -> Result<f32, String> {
    #[allow(clippy::cast_possible_truncation)]
    let y = x as f32;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(format!("{name} must be a finite number, found {x}"))
    }
}

fn point(name: &str, (x, y, z): V3) -> Result<Vec3, String> {
    let v = Vec3::new(finite32(name, x)?, finite32(name, y)?, finite32(name, z)?);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("{name} must be finite, found ({x}, {y}, {z})"))
    }
}

fn direction(name: &str, v: V3) -> Result<Vec3, String> {
    point(name, v)?
        .try_normalize()
        .ok_or_else(|| format!("{name} must not be the zero vector"))
}

fn positive(name: &str, x: f64) -> Result<f32, String> {
    let y = finite32(name, x)?;
    if y > 0.0 {
        Ok(y)
    } else {
        Err(format!("{name} must be positive, found {x}"))
    }
}

fn color(v: V3) -> Result<Vec3, String> {
    let c = point("colour", v)?;
    if c.min_element() < 0.0 {
        return Err(format!(
            "colours cannot be negative, found ({}, {}, {})",
            v.0, v.1, v.2
        ));
    }
    Ok(c)
}

fn material(def: &MaterialDef) -> Result<Material, String> {
    let specular = match def.specular {
        None => Vec3::ZERO,
        Some(Specular::Grey(g)) => color((g, g, g))?,
        Some(Specular::Color(c)) => color(c)?,
    };
    let shininess = match def.shininess {
        None => Material::default().shininess,
        Some(s) => positive("shininess", s)?,
    };
    let mirror = finite32("mirror", def.mirror)?;
    if !(0.0..=1.0).contains(&mirror) {
        return Err(format!(
            "mirror must be between 0 and 1, found {}",
            def.mirror
        ));
    }
    let grid = match &def.grid {
        None => None,
        Some(grid) => {
            let spacing = positive("grid spacing", grid.spacing)?;
            let line_width = positive("grid width", grid.width)?;
            if line_width >= spacing {
                return Err(format!(
                    "grid width {} must be smaller than its spacing {}",
                    grid.width, grid.spacing
                ));
            }
            Some(Grid {
                spacing,
                line_width,
                color: color(grid.color)?,
            })
        }
    };
    Ok(Material {
        color: color(def.color)?,
        specular,
        shininess,
        mirror,
        grid,
    })
}

fn light(def: &LightDef) -> Result<Light, String> {
    Ok(match *def {
        LightDef::Point {
            position,
            intensity,
        } => Light::Point {
            position: point("position", position)?,
            intensity: color(intensity)?,
        },
        LightDef::Directional {
            direction: d,
            intensity,
        } => Light::Directional {
            direction: direction("direction", d)?,
            intensity: color(intensity)?,
        },
        LightDef::Ambient { intensity } => Light::Ambient {
            intensity: color(intensity)?,
        },
    })
}

/// The transform of a mesh: scale, then rotate about x, y and z (degrees), then translate.
fn affine(def: &TransformDef) -> Result<Affine3A, String> {
    let scale = match def.scale {
        Scale::Uniform(s) => {
            let s = finite32("scale", s)?;
            Vec3::splat(s)
        }
        Scale::PerAxis(s) => point("scale", s)?,
    };
    if scale.cmpeq(Vec3::ZERO).any() {
        return Err("scale must not be zero on any axis".to_owned());
    }
    let rotate = point("rotate", def.rotate)?;
    let rotation = Quat::from_rotation_z(rotate.z.to_radians())
        * Quat::from_rotation_y(rotate.y.to_radians())
        * Quat::from_rotation_x(rotate.x.to_radians());
    let translate = point("translate", def.translate)?;
    Ok(Affine3A::from_scale_rotation_translation(
        scale, rotation, translate,
    ))
}

/// A mesh path as written in the scene file, relative to the file's folder.
fn mesh_path(scene: &Path, mesh: &str) -> PathBuf {
    scene.parent().unwrap_or(Path::new("")).join(mesh)
}

/// The image's size and samples, checked against viewray's limits.
fn check_image(
    image: &ImageDef,
    path: &Path,
    origin: Origin,
) -> Result<(u32, u32, u32), SceneError> {
    let error = |message: ImageLimitError| {
        SceneError::at(path, Some(origin.position()), format!("image: {message}"))
    };
    let limits = ImageLimits::VIEWRAY;
    let (width, height) = limits
        .check_size(u64::from(image.width), u64::from(image.height))
        .map_err(error)?;
    let samples = limits
        .check_samples(u64::from(image.samples))
        .map_err(error)?;
    Ok((width, height, samples))
}

/// Parses `text` as a scene file's `camera:` value on its own (an explicit camera or a
/// preset) for a `width x height` image; positions in errors count from the start of
/// `text`, and `path` names it.
pub(crate) fn parse_camera_text(
    text: &str,
    path: &Path,
    width: u32,
    height: u32,
) -> Result<Camera, SceneError> {
    let image = ImageDef {
        width,
        height,
        samples: 1,
    };
    let (width, height, _) = check_image(&image, path, Origin::FILE)?;
    let raw: &RawValue = ron_options()
        .from_str(text)
        .map_err(|e| ron_error(path, text, Origin::FILE, &e))?;
    let origin = LineIndex::new(text).origin_of(raw.get_ron());
    parse_camera(raw, origin, path, width, height)
}

/// The `camera:` value of the scene file `text`, as written there (comments inside it
/// included).
pub(crate) fn camera_text<'a>(text: &'a str, path: &Path) -> Result<&'a str, SceneError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let file: SceneFile<'a> = ron_options()
        .from_str(text)
        .map_err(|e| ron_error(path, text, Origin::FILE, &e))?;
    Ok(file.camera.get_ron().trim())
}

/// Parses the camera, an explicit `( .. )` or a preset `Name( .. )`.
fn parse_camera(
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
fn parse_camera_spec(
    raw: &RawValue,
    origin: Origin,
    path: &Path,
) -> Result<CameraSpec, SceneError> {
    let text = raw.get_ron();
    let def = if skip_whitespace_and_comments(text).starts_with('(') {
        CameraDef::Explicit(Box::new(
            ron_options()
                .from_str(text)
                .map_err(|e| ron_error(path, text, origin, &e))?,
        ))
    } else {
        CameraDef::Preset(
            ron_options()
                .from_str(text)
                .map_err(|e| ron_error(path, text, origin, &e))?,
        )
    };
    Ok(CameraSpec(def))
}

/// Parses and checks the `animation:` section (`raw`, a slice of the file `lines` index): the
/// frame count and rate, the keys' times (in `[0, 1]`, strictly increasing), and their
/// cameras, each valid for a `width x height` image and written like its neighbours so
/// that the two can be mixed.
fn parse_animation(
    raw: &RawValue,
    lines: &LineIndex<'_>,
    path: &Path,
    width: u32,
    height: u32,
) -> Result<Animation, SceneError> {
    let origin = lines.origin_of(raw.get_ron());
    let def: AnimationDef<'_> = ron_options()
        .from_str(raw.get_ron())
        .map_err(|e| ron_error(path, raw.get_ron(), origin, &e))?;
    let error = |at: Origin, message: String| {
        SceneError::at(path, Some(at.position()), format!("animation: {message}"))
    };
    if def.frames == 0 || def.frames > MAX_FRAMES {
        return Err(error(
            origin,
            format!(
                "frames must be between 1 and {MAX_FRAMES}, found {}",
                def.frames
            ),
        ));
    }
    if def.fps == 0 || def.fps > MAX_FPS {
        return Err(error(
            origin,
            format!("fps must be between 1 and {MAX_FPS}, found {}", def.fps),
        ));
    }
    if def.keys.is_empty() {
        return Err(error(
            origin,
            "no keys: give at least one, `keys: [(t: 0.0, camera: (..)), (t: 1.0, camera: \
             (..))]`"
                .to_owned(),
        ));
    }
    let mut keys: Vec<Key> = Vec::with_capacity(def.keys.len());
    for (index, raw_key) in def.keys.iter().enumerate() {
        let at = lines.origin_of(raw_key.get_ron());
        let key: KeyDef<'_> = ron_options()
            .from_str(raw_key.get_ron())
            .map_err(|e| ron_error(path, raw_key.get_ron(), at, &e))?;
        let camera_origin = lines.origin_of(key.camera.get_ron());
        let number = index + 1;
        if !(0.0..=1.0).contains(&key.t) {
            return Err(error(
                at,
                format!("key {number}: t must be between 0 and 1, found {}", key.t),
            ));
        }
        if let Some(previous) = keys.last()
            && key.t <= previous.t
        {
            return Err(error(
                at,
                format!(
                    "key {number}: times must increase from key to key, but t = {} follows \
                     t = {}",
                    key.t, previous.t
                ),
            ));
        }
        let camera = parse_camera_spec(key.camera, camera_origin, path)?;
        camera
            .camera(width, height)
            .map_err(|m| error(at, format!("key {number}: camera: {m}")))?;
        if let Some(previous) = keys.last() {
            previous
                .camera
                .mix(&camera, 0.5)
                .map_err(|m| error(at, format!("key {number}: {m}")))?;
        }
        keys.push(Key {
            t: key.t,
            camera,
            position: at.position(),
        });
    }
    Ok(Animation {
        frames: def.frames,
        fps: def.fps,
        ease: match def.ease {
            EaseDef::Linear => Ease::Linear,
            EaseDef::InOut => Ease::InOut,
        },
        keys,
        path: path.to_path_buf(),
        position: origin.position(),
    })
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

pub(crate) fn explicit_camera(
    def: &ExplicitCamera,
    width: u32,
    height: u32,
) -> Result<Camera, String> {
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

/// The fields that size a perspective viewport, as written in the file.
struct PerspectiveExtent {
    distance: Option<f64>,
    viewport: Option<V2>,
    fovs: [(FovAxis, Option<f64>); 5],
    focal_length: Option<f64>,
    sensor: Option<V2>,
    fit: Option<SensorFitDef>,
}

/// Blender's default sensor, 36 x 24 mm, for a `focal_length` given without `sensor`.
const DEFAULT_SENSOR: V2 = (36.0, 24.0);

/// The perspective projection (distance and viewport) from exactly one of `viewport`,
/// a field of view (`fov_x`, `fov_y`, `fov_diagonal`, `fov_smaller`, `fov_larger`, in
/// degrees, scaled by `distance` when one is given) and a physical `focal_length` (mm,
/// with `sensor` in mm and `fit`), the last two following the image's aspect ratio.
fn perspective(extent: &PerspectiveExtent, shift: V2, aspect: f64) -> Result<Perspective, String> {
    let fovs: Vec<(FovAxis, f64)> = extent
        .fovs
        .iter()
        .filter_map(|&(axis, fov)| fov.map(|f| (axis, f)))
        .collect();
    let given = usize::from(extent.viewport.is_some())
        + fovs.len()
        + usize::from(extent.focal_length.is_some());
    if given > 1 {
        return Err(
            "give only one of `viewport`, a field of view (`fov_x`, `fov_y`, \
                    `fov_diagonal`, `fov_smaller`, `fov_larger`) and `focal_length`"
                .to_owned(),
        );
    }
    if extent.focal_length.is_none() && (extent.sensor.is_some() || extent.fit.is_some()) {
        return Err(
            "`sensor` and `fit` describe a physical camera: give `focal_length` \
                    (mm) with them"
                .to_owned(),
        );
    }
    let error = |e: viewray_camera::CameraError| e.to_string();
    let mut projection = if let Some(viewport) = extent.viewport {
        Perspective {
            distance: extent.distance.unwrap_or(1.0),
            viewport: v2(viewport),
            shift: DVec2::ZERO,
        }
    } else if let Some(&(axis, degrees)) = fovs.first() {
        let mut p = Perspective::from_fov(axis, degrees.to_radians(), aspect).map_err(error)?;
        if let Some(distance) = extent.distance {
            p.distance = distance;
            p.viewport *= distance;
        }
        p
    } else if let Some(focal_length) = extent.focal_length {
        if extent.distance.is_some() {
            return Err(
                "`focal_length` sets the distance d (the focal length in metres): \
                        give `distance` or `focal_length`, not both"
                    .to_owned(),
            );
        }
        let fit = match extent.fit.unwrap_or(SensorFitDef::Auto) {
            SensorFitDef::Auto => SensorFit::Auto,
            SensorFitDef::Horizontal => SensorFit::Horizontal,
            SensorFitDef::Vertical => SensorFit::Vertical,
        };
        let sensor = v2(extent.sensor.unwrap_or(DEFAULT_SENSOR));
        Perspective::from_focal_length(focal_length, sensor, fit, aspect).map_err(error)?
    } else {
        return Err("missing `viewport: (vw, vh)` (or a field of view such as `fov_y` in                     degrees, or `focal_length` in mm)"
            .to_owned());
    };
    projection.shift = v2(shift);
    Ok(projection)
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

/// The fields of view as written, each with the axis it spans.
fn fovs(
    x: Option<f64>,
    y: Option<f64>,
    diagonal: Option<f64>,
    smaller: Option<f64>,
    larger: Option<f64>,
) -> [(FovAxis, Option<f64>); 5] {
    [
        (FovAxis::X, x),
        (FovAxis::Y, y),
        (FovAxis::Diagonal, diagonal),
        (FovAxis::Smaller, smaller),
        (FovAxis::Larger, larger),
    ]
}

fn projection(def: &ProjectionDef, aspect: f64) -> Result<Projection, String> {
    Ok(match *def {
        ProjectionDef::Perspective {
            distance,
            viewport,
            fov_x,
            fov_y,
            fov_diagonal,
            fov_smaller,
            fov_larger,
            focal_length,
            sensor,
            fit,
            shift,
        } => {
            let extent = PerspectiveExtent {
                distance,
                viewport,
                fovs: fovs(fov_x, fov_y, fov_diagonal, fov_smaller, fov_larger),
                focal_length,
                sensor,
                fit,
            };
            Projection::Perspective(perspective(&extent, shift, aspect)?)
        }
        ProjectionDef::ThinLens {
            distance,
            viewport,
            fov_x,
            fov_y,
            fov_diagonal,
            fov_smaller,
            fov_larger,
            focal_length,
            sensor,
            fit,
            shift,
            aperture,
            f_number,
            focus,
        } => {
            let extent = PerspectiveExtent {
                distance,
                viewport,
                fovs: fovs(fov_x, fov_y, fov_diagonal, fov_smaller, fov_larger),
                focal_length,
                sensor,
                fit,
            };
            let pinhole = perspective(&extent, shift, aspect)?;
            let aperture = match (aperture, f_number, focal_length) {
                (Some(aperture), None, _) => aperture,
                (None, Some(n), Some(f)) => {
                    aperture_from_f_number(f, n).map_err(|e| e.to_string())?
                }
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
            Projection::ThinLens(ThinLens {
                distance: pinhole.distance,
                viewport: pinhole.viewport,
                shift: pinhole.shift,
                aperture,
                focus,
            })
        }
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

pub(crate) fn preset_camera(def: &PresetDef, width: u32, height: u32) -> Result<Camera, String> {
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

/// A RON error in `text` (which starts at `origin` in the file) as a [`SceneError`], its
/// position moved from `origin`-relative to the file and its message in the scene
/// format's words.
fn ron_error(path: &Path, text: &str, origin: Origin, error: &SpannedError) -> SceneError {
    let start = error.span.start;
    if let Some((line, column, message)) = number_error(text, error) {
        return SceneError::at(path, Some(origin.offset(line, column)), message);
    }
    let position = origin.offset(start.line, start.col);
    SceneError::at(path, Some(position), describe(&error.code))
}

/// What to say about an empty scene file, or one that holds only comments (after its
/// name, as "is not a text file" is).
fn empty_file_message(text: &str) -> String {
    let what = if text.trim().is_empty() {
        "is empty"
    } else {
        "holds only comments"
    };
    format!(
        "{what}: a scene is one value in parentheses, at least \
         `(camera: Front(target: (0.0, 0.0, 0.0), size: 2.0))`"
    )
}

/// The mistakes with whole numbers that RON words in its own terms: something else
/// where a whole number is expected (`width: "wide"`), a decimal point (`width: 8.0`,
/// which RON reads as `8` followed by a stray `.0`), and a negative or huge whole number
/// (`width: -8`). Returns the 1-based
/// line and column of the number in `text` and the message.
fn number_error(text: &str, error: &SpannedError) -> Option<(usize, usize, String)> {
    let at = byte_offset(text, error.span.start.line, error.span.start.col)?;
    if error.code == RonError::ExpectedInteger {
        let name = field_before(&text[..at])?;
        let (line, column) = (error.span.start.line, error.span.start.col);
        return Some((line, column, format!("`{name}` must be a whole number")));
    }
    let (start, token) = number_around(text, at)?;
    let field = field_before(&text[..start]);
    let message = match error.code {
        // `8.0`: the parser stops at the `.`, right after the digits of a whole number.
        RonError::ExpectedComma
            if text[..at].ends_with(|c: char| c.is_ascii_digit())
                && token.contains(['.', 'e', 'E'])
                && token.parse::<f64>().is_ok() =>
        {
            match field {
                Some(name) => format!("`{name}` must be a whole number, found `{token}`"),
                None => format!("expected a whole number, found `{token}`"),
            }
        }
        RonError::IntegerOutOfBounds if token.starts_with('-') => match field {
            Some(name) => format!("`{name}` must be a positive whole number, found `{token}`"),
            None => format!("expected a positive whole number, found `{token}`"),
        },
        RonError::IntegerOutOfBounds => match field {
            Some(name) => format!("`{name}` is out of range: `{token}` is too large"),
            None => format!("`{token}` is too large"),
        },
        _ => return None,
    };
    let before = &text[..start];
    let line = 1 + before.matches('\n').count();
    let column = 1 + before
        .rsplit_once('\n')
        .map_or(before, |(_, last)| last)
        .chars()
        .count();
    Some((line, column, message))
}

/// The byte offset in `text` of the 1-based `line` and character `column`.
fn byte_offset(text: &str, line: usize, column: usize) -> Option<usize> {
    let line_start = if line <= 1 {
        0
    } else {
        text.match_indices('\n').nth(line - 2).map(|(i, _)| i + 1)?
    };
    let rest = &text[line_start..];
    let within = rest
        .char_indices()
        .map(|(i, _)| i)
        .chain(std::iter::once(rest.len()))
        .nth(column.checked_sub(1)?)?;
    Some(line_start + within)
}

/// The number written around byte `at` of `text`: its start and its text.
fn number_around(text: &str, at: usize) -> Option<(usize, &str)> {
    let is_number_char = |c: char| c.is_ascii_alphanumeric() || "+-._".contains(c);
    let start = text[..at]
        .char_indices()
        .rev()
        .take_while(|&(_, c)| is_number_char(c))
        .last()
        .map_or(at, |(i, _)| i);
    let end = text[at..]
        .char_indices()
        .find(|&(_, c)| !is_number_char(c))
        .map_or(text.len(), |(i, _)| at + i);
    let token = &text[start..end];
    token
        .trim_start_matches(['+', '-'])
        .starts_with(|c: char| c.is_ascii_digit())
        .then_some((start, token))
}

/// The name of the field whose value starts right after `before` (`width` in
/// `(width: `), if the value is a field's.
fn field_before(before: &str) -> Option<&str> {
    let before = before.trim_end().strip_suffix(':')?.trim_end();
    let name_start = before
        .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .map_or(0, |i| i + 1);
    let name = &before[name_start..];
    (!name.is_empty()).then_some(name)
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
        RonError::ExpectedInteger => "expected a whole number".to_owned(),
        RonError::ExpectedFloat => "expected a number".to_owned(),
        RonError::ExpectedNamedStructLike("scene") => {
            "expected `(`: a scene file is one value in parentheses, \
             `(camera: .., objects: [..])`"
                .to_owned()
        }
        RonError::ExceededRecursionLimit => {
            "values are nested too deeply (more than 128 levels)".to_owned()
        }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_index_finds_lines_and_columns_in_characters() {
        let text = "(\n  a: 1,\n  é: (2, 3),\n\nz)";
        let index = LineIndex::new(text);
        let at = |needle: &str| {
            let start = text.find(needle).unwrap();
            let origin = index.origin_of(&text[start..]);
            (origin.line, origin.column)
        };
        assert_eq!(at("("), (1, 1));
        assert_eq!(at("a:"), (2, 3));
        // `é` is two bytes but one column: `(2` starts at column 6, not 7.
        assert_eq!(at("(2"), (3, 6));
        assert_eq!(at("3)"), (3, 10));
        assert_eq!(at("z)"), (5, 1));
        assert_eq!(at("\n\nz"), (3, 13));
    }
}
