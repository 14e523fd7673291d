//! OBJ meshes: loaded with tobj, each file once per scene.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use glam::Vec3;
use viewray_geometry::{Mesh, MeshData};

use crate::Material;

/// The largest OBJ file a scene may load: 1 GiB, some 20 million triangles.
const MAX_OBJ_BYTES: u64 = 1 << 30;

/// A mesh as loaded from an OBJ file.
pub(crate) struct LoadedMesh {
    /// The mesh with its BVH, shared by every object that places it.
    pub(crate) mesh: Arc<Mesh>,
    /// The material of each face, as indices into the scene's materials, when the OBJ
    /// assigns MTL materials to its faces.
    pub(crate) face_materials: Option<Arc<[u32]>>,
}

/// The meshes of one scene, by file, so a mesh placed twice is loaded (and its BVH built)
/// once.
#[derive(Default)]
pub(crate) struct MeshCache {
    loaded: HashMap<PathBuf, Arc<LoadedMesh>>,
    /// The time spent building the meshes' BVHs.
    pub(crate) build_time: Duration,
}

impl MeshCache {
    /// The mesh in the OBJ file at `path`, loading it the first time; its MTL materials are
    /// appended to `materials`.
    pub(crate) fn load(
        &mut self,
        path: &Path,
        materials: &mut Vec<Material>,
    ) -> Result<Arc<LoadedMesh>, String> {
        let key = std::fs::canonicalize(path).map_err(|e| read_error(path, &e))?;
        if let Some(mesh) = self.loaded.get(&key) {
            return Ok(Arc::clone(mesh));
        }
        let mesh = Arc::new(load_obj(&key, path, materials, &mut self.build_time)?);
        self.loaded.insert(key, Arc::clone(&mesh));
        Ok(mesh)
    }
}

fn read_error(path: &Path, error: &std::io::Error) -> String {
    match error.kind() {
        std::io::ErrorKind::NotFound => format!("no such file (looked for {})", path.display()),
        _ => format!("cannot read {}: {error}", path.display()),
    }
}

fn load_obj(
    file: &Path,
    shown: &Path,
    materials: &mut Vec<Material>,
    build_time: &mut Duration,
) -> Result<LoadedMesh, String> {
    let metadata = std::fs::metadata(file).map_err(|e| read_error(shown, &e))?;
    if !metadata.is_file() {
        return Err("is a directory, not an OBJ file".to_owned());
    }
    if metadata.len() > MAX_OBJ_BYTES {
        return Err(format!(
            "is {} MiB, larger than the {} MiB an OBJ file may have",
            metadata.len() >> 20,
            MAX_OBJ_BYTES >> 20
        ));
    }
    let bytes = std::fs::read(file).map_err(|e| read_error(shown, &e))?;
    let folder = file.parent().unwrap_or(Path::new("")).to_path_buf();
    let mtl_loader = move |mtl: &Path| {
        let mtl = folder.join(mtl);
        match std::fs::metadata(&mtl) {
            Ok(m) if m.is_file() && m.len() <= MAX_OBJ_BYTES => tobj::load_mtl(&mtl),
            _ => Err(tobj::LoadError::OpenFileFailed),
        }
    };
    parse_obj(&bytes, mtl_loader, materials, build_time)
}

/// Builds the mesh in the OBJ text `bytes`, loading MTL libraries with `mtl_loader`; its
/// MTL materials are appended to `materials`.
pub(crate) fn parse_obj(
    bytes: &[u8],
    mtl_loader: impl Fn(&Path) -> tobj::MTLLoadResult,
    materials: &mut Vec<Material>,
    build_time: &mut Duration,
) -> Result<LoadedMesh, String> {
    let options = tobj::LoadOptions {
        triangulate: true,
        single_index: true,
        ignore_points: true,
        ignore_lines: true,
    };
    let (models, mtl) = tobj::load_obj_buf(&mut std::io::Cursor::new(bytes), &options, mtl_loader)
        .map_err(
            |e| match locate_obj_error(&String::from_utf8_lossy(bytes)) {
                Some((line, problem)) => format!("line {line}: {problem}"),
                None => format!("not a valid OBJ file: {e}"),
            },
        )?;
    // A missing or broken MTL file leaves the faces with the object's material.
    let mtl = mtl.unwrap_or_default();

    // Append the MTL materials this mesh uses to the scene's list.
    let first = materials.len();
    materials.extend(mtl.iter().map(|m| {
        let defaults = Material::default();
        Material {
            color: m.diffuse.map_or(defaults.color, Vec3::from),
            specular: m.specular.map_or(defaults.specular, Vec3::from),
            shininess: m
                .shininess
                .filter(|s| s.is_finite() && *s > 0.0)
                .unwrap_or(defaults.shininess),
            mirror: 0.0,
            grid: None,
        }
    }));

    // Concatenate the OBJ's models into one mesh.
    let mut data = MeshData::new(Vec::new(), Vec::new());
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    let mut face_materials = Vec::new();
    let every_model_has_normals = models.iter().all(|m| !m.mesh.normals.is_empty());
    let every_model_has_uvs = models.iter().all(|m| !m.mesh.texcoords.is_empty());
    let any_material = models.iter().any(|m| m.mesh.material_id.is_some());
    for model in &models {
        let part = MeshData::from_flat(
            &model.mesh.positions,
            &model.mesh.indices,
            &model.mesh.normals,
            &model.mesh.texcoords,
        )
        .map_err(|e| e.to_string())?;
        let offset =
            u32::try_from(data.positions.len()).map_err(|_| "has too many vertices".to_owned())?;
        data.triangles.extend(
            part.triangles
                .iter()
                .map(|t| t.map(|i| i.saturating_add(offset))),
        );
        data.positions.extend(&part.positions);
        if every_model_has_normals {
            normals.extend(part.normals.unwrap_or_default());
        }
        if every_model_has_uvs {
            uvs.extend(part.uvs.unwrap_or_default());
        }
        if any_material {
            let material = model
                .mesh
                .material_id
                .filter(|&id| id < mtl.len())
                .map_or(u32::MAX, |id| (first + id) as u32);
            face_materials.extend(std::iter::repeat_n(material, part.triangles.len()));
        }
    }
    if data.triangles.is_empty() {
        return Err("has no faces (is it an OBJ file?)".to_owned());
    }
    if every_model_has_normals {
        data = data.with_normals(normals);
    }
    if every_model_has_uvs {
        data = data.with_uvs(uvs);
    }
    let faces = data.triangles.len();
    let started = Instant::now();
    let mesh = Mesh::new(data).map_err(|e| e.to_string())?;
    *build_time += started.elapsed();
    if mesh.triangle_count() == 0 {
        return Err(format!(
            "all {faces} faces are degenerate (zero area), so there is nothing to see"
        ));
    }

    // Faces without an MTL material take the default material, the last of the scene's
    // list once loading is done; resolve them to an explicit material here instead.
    let face_materials = if any_material {
        let fallback = u32::try_from(materials.len()).expect("fewer than 2^32 materials");
        materials.push(Material::default());
        Some(
            face_materials
                .into_iter()
                .map(|m| if m == u32::MAX { fallback } else { m })
                .collect::<Arc<[u32]>>(),
        )
    } else {
        None
    };
    Ok(LoadedMesh {
        mesh: Arc::new(mesh),
        face_materials,
    })
}

/// Finds the first line of the OBJ `text` that tobj would reject, for an error
/// message that names it: `(line number, what is wrong)`. Only run after tobj failed, so
/// it only needs to know the usual mistakes.
fn locate_obj_error(text: &str) -> Option<(usize, String)> {
    let (mut positions, mut texcoords, mut normals) = (0i64, 0i64, 0i64);
    for (number, line) in text.lines().enumerate() {
        let number = number + 1;
        let mut words = line.split_whitespace();
        let keyword = words.next().unwrap_or_default();
        let values: Vec<&str> = words.collect();
        let numbers = |min: usize, what: &str| -> Option<String> {
            let bad = values.iter().find(|v| v.parse::<f32>().is_err());
            match bad {
                Some(word) => Some(format!("`{word}` in `{}` is not a number", line.trim())),
                None if values.len() < min => {
                    Some(format!("{what} needs {min} numbers: `{}`", line.trim()))
                }
                None => None,
            }
        };
        let problem = match keyword {
            "v" => {
                positions += 1;
                numbers(3, "a vertex")
            }
            "vt" => {
                texcoords += 1;
                numbers(1, "a texture coordinate")
            }
            "vn" => {
                normals += 1;
                numbers(3, "a normal")
            }
            "f" if values.len() < 3 => Some(format!("a face needs 3 vertices: `{}`", line.trim())),
            "f" => values.iter().find_map(|corner| {
                let counts = [
                    ("vertex", positions),
                    ("texture coordinate", texcoords),
                    ("normal", normals),
                ];
                corner
                    .split('/')
                    .zip(counts)
                    .find_map(|(index, (what, count))| {
                        if index.is_empty() {
                            return None;
                        }
                        let Ok(i) = index.parse::<i64>() else {
                            return Some(format!("`{index}` in `{}` is not an index", line.trim()));
                        };
                        // OBJ indices are 1-based; negative ones count back from the last.
                        let resolved = if i < 0 { count + i + 1 } else { i };
                        (resolved < 1 || resolved > count).then(|| {
                            format!(
                                "face refers to {what} {i}, but only {count} are defined before it"
                            )
                        })
                    })
            }),
            _ => None,
        };
        if let Some(problem) = problem {
            return Some((number, problem));
        }
    }
    None
}
