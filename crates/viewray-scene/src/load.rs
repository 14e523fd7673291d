//! Scene text -> [`Scene`]: the file parsed in steps (each value kept as raw text and
//! parsed in place, so its errors point at it), converted and validated.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use ron::value::RawValue;
use viewray_geometry::{Aabb, Instance, Object, Plane, Sphere, Triangle, World};

use crate::animation::parse_animation;
use crate::camera::camera_at;
use crate::file_kind::skip_whitespace_and_comments;
use crate::mesh::MeshCache;
use crate::ron_text::{self, LineIndex, Origin, empty_file_message, list};
use crate::schema::{ImageDef, LightDef, MaterialDef, ObjectDef, SceneFile, ShadingDef};
use crate::values::{affine, color, direction, light, material, point, positive};
use crate::{
    Animation, LoadOptions, Material, ObjectMaterial, Scene, SceneError, SceneParts, Shading,
};

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
    let file: SceneFile<'_> = ron_text::parse(text, Origin::FILE, path)?;
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
    let (width, height, samples) = crate::values::image(&image)
        .map_err(|message| SceneError::at(path, Some(image_origin.position()), message))?;

    let camera_origin = loader.lines.origin_of(file.camera.get_ron());
    let camera = camera_at(file.camera, camera_origin, path, width, height)?;
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
        let value = ron_text::parse(raw.get_ron(), origin, self.path)?;
        Ok((value, origin))
    }

    fn error(&self, origin: Origin, message: String) -> SceneError {
        SceneError::at(self.path, Some(origin.position()), message)
    }
}

fn index_u32(index: usize) -> u32 {
    u32::try_from(index).expect("fewer than 2^32 materials")
}

/// A mesh path as written in the scene file, relative to the file's folder.
fn mesh_path(scene: &Path, mesh: &str) -> PathBuf {
    scene.parent().unwrap_or(Path::new("")).join(mesh)
}
