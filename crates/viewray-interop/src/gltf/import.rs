//! Reading glTF 2.0 (the conventions are in the module's `mod.rs`): the default scene's
//! nodes walked from its roots, with their transforms.

use std::path::Path;

use base64::Engine as _;
use glam::{DMat4, DQuat, DVec2, DVec3, Vec3};
use serde_json::Value;
use viewray_camera::FovAxis;
use viewray_scene::{
    Light, Material, ObjectDocument, PerspectiveSize, ProjectionDocument, SceneDocument, Shading,
};

use super::glb;
use crate::ImportError;
use crate::common::{
    camera_document, material_name, matrix_from_column_major, pixels, square_pixels,
    viewray_intensity,
};

struct Importer<'a> {
    path: &'a Path,
    root: &'a Value,
    bin: Option<&'a [u8]>,
    comments: Vec<String>,
    objects: Vec<ObjectDocument>,
    lights: Vec<Light>,
    used_materials: Vec<(String, Material)>,
    camera: Option<(usize, DMat4)>,
}

fn array<'v>(value: &'v Value, name: &str) -> &'v [Value] {
    value
        .get(name)
        .and_then(Value::as_array)
        .map_or(&[], Vec::as_slice)
}

impl<'a> Importer<'a> {
    fn error(&self, message: impl Into<String>) -> ImportError {
        ImportError::new(self.path, None, message)
    }

    fn node_matrix(&self, node: &Value) -> Result<DMat4, ImportError> {
        if let Some(m) = node.get("matrix") {
            let numbers: Option<Vec<f64>> = m
                .as_array()
                .and_then(|a| a.iter().map(Value::as_f64).collect());
            return numbers
                .as_deref()
                .and_then(matrix_from_column_major)
                .ok_or_else(|| self.error("a node's `matrix` must be 16 finite numbers"));
        }
        let numbers = |name: &str, n: usize| -> Result<Option<Vec<f64>>, ImportError> {
            match node.get(name) {
                None => Ok(None),
                Some(v) => v
                    .as_array()
                    .filter(|a| a.len() == n)
                    .and_then(|a| a.iter().map(Value::as_f64).collect::<Option<Vec<f64>>>())
                    .map(Some)
                    .ok_or_else(|| self.error(format!("a node's `{name}` must be {n} numbers"))),
            }
        };
        let t = numbers("translation", 3)?.map_or(DVec3::ZERO, |v| DVec3::new(v[0], v[1], v[2]));
        let s = numbers("scale", 3)?.map_or(DVec3::ONE, |v| DVec3::new(v[0], v[1], v[2]));
        let r = numbers("rotation", 4)?.map_or(DQuat::IDENTITY, |v| {
            DQuat::from_xyzw(v[0], v[1], v[2], v[3]).normalize()
        });
        let m = DMat4::from_scale_rotation_translation(s, r, t);
        if m.is_finite() {
            Ok(m)
        } else {
            Err(self.error("a node's transform is not finite"))
        }
    }

    fn walk(&mut self, index: usize, parent: DMat4, depth: usize) -> Result<(), ImportError> {
        if depth > 64 {
            return Err(self.error("nodes are nested more than 64 deep (or in a cycle)"));
        }
        let node = array(self.root, "nodes")
            .get(index)
            .ok_or_else(|| self.error(format!("node {index} does not exist")))?;
        let matrix = parent * self.node_matrix(node)?;
        if let Some(camera) = node.get("camera").and_then(Value::as_u64)
            && self.camera.is_none()
        {
            self.camera = Some((camera as usize, matrix));
        }
        if let Some(mesh) = node.get("mesh").and_then(Value::as_u64) {
            self.mesh(mesh as usize, matrix)?;
        }
        if let Some(light) = node
            .pointer("/extensions/KHR_lights_punctual/light")
            .and_then(Value::as_u64)
        {
            self.light(light as usize, matrix);
        }
        for child in array(node, "children").to_vec() {
            let child = child
                .as_u64()
                .ok_or_else(|| self.error("a node's children must be node numbers"))?;
            self.walk(child as usize, matrix, depth + 1)?;
        }
        Ok(())
    }

    fn light(&mut self, index: usize, matrix: DMat4) {
        let Some(light) = self
            .root
            .pointer("/extensions/KHR_lights_punctual/lights")
            .and_then(Value::as_array)
            .and_then(|l| l.get(index))
        else {
            self.comments
                .push(format!("light {index} does not exist: skipped"));
            return;
        };
        let color = light
            .get("color")
            .and_then(Value::as_array)
            .and_then(|c| {
                let c: Option<Vec<f64>> = c.iter().map(Value::as_f64).collect();
                c.filter(|c| c.len() == 3)
                    .map(|c| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32))
            })
            .unwrap_or(Vec3::ONE);
        let intensity = viewray_intensity(
            light
                .get("intensity")
                .and_then(Value::as_f64)
                .unwrap_or(1.0) as f32
                * color,
        );
        match light.get("type").and_then(Value::as_str) {
            Some("point") => self.lights.push(Light::Point {
                position: matrix.w_axis.truncate().as_vec3(),
                intensity,
            }),
            Some("directional") => match (-matrix.z_axis.truncate()).try_normalize() {
                Some(direction) => self.lights.push(Light::Directional {
                    direction: direction.as_vec3(),
                    intensity,
                }),
                None => self
                    .comments
                    .push("a directional light with no direction skipped".to_owned()),
            },
            other => self
                .comments
                .push(format!("a {} light skipped", other.unwrap_or("?"))),
        }
    }

    /// The bytes of accessor `index` and its component type, count and element size.
    fn accessor(&self, index: usize) -> Result<(Vec<u8>, u64, usize, &'a str), ImportError> {
        let accessor = array(self.root, "accessors")
            .get(index)
            .ok_or_else(|| self.error(format!("accessor {index} does not exist")))?;
        let component = accessor
            .get("componentType")
            .and_then(Value::as_u64)
            .unwrap_or(0);
        let count = accessor
            .get("count")
            .and_then(Value::as_u64)
            .ok_or_else(|| self.error("an accessor needs a `count`"))? as usize;
        let kind = accessor.get("type").and_then(Value::as_str).unwrap_or("");
        let components = match kind {
            "SCALAR" => 1,
            "VEC3" => 3,
            _ => return Err(self.error(format!("accessor {index}: type {kind} is not read"))),
        };
        let size = match component {
            5121 => 1,
            5123 => 2,
            5125 | 5126 => 4,
            _ => {
                return Err(self.error(format!(
                    "accessor {index}: componentType {component} is not read"
                )));
            }
        };
        let Some(view_index) = accessor.get("bufferView").and_then(Value::as_u64) else {
            return Ok((vec![0; count * components * size], component, count, kind));
        };
        let view = array(self.root, "bufferViews")
            .get(view_index as usize)
            .ok_or_else(|| self.error(format!("bufferView {view_index} does not exist")))?;
        let buffer_index = view.get("buffer").and_then(Value::as_u64).unwrap_or(0) as usize;
        let buffer = self.buffer(buffer_index)?;
        let view_offset = view.get("byteOffset").and_then(Value::as_u64).unwrap_or(0) as usize;
        let view_length = view.get("byteLength").and_then(Value::as_u64).unwrap_or(0) as usize;
        let stride = view
            .get("byteStride")
            .and_then(Value::as_u64)
            .map_or(components * size, |s| s as usize);
        let offset = view_offset
            + accessor
                .get("byteOffset")
                .and_then(Value::as_u64)
                .unwrap_or(0) as usize;
        let element = components * size;
        let end = view_offset
            .checked_add(view_length)
            .filter(|&e| e <= buffer.len())
            .ok_or_else(|| self.error(format!("bufferView {view_index} runs past its buffer")))?;
        let mut out = Vec::with_capacity(count.min(1 << 24) * element);
        for i in 0..count {
            let start = offset
                .checked_add(
                    i.checked_mul(stride)
                        .ok_or_else(|| self.error("accessor too large"))?,
                )
                .ok_or_else(|| self.error("accessor too large"))?;
            let bytes = buffer
                .get(start..start + element)
                .filter(|_| start + element <= end)
                .ok_or_else(|| self.error(format!("accessor {index} runs past its bufferView")))?;
            out.extend_from_slice(bytes);
        }
        Ok((out, component, count, kind))
    }

    fn buffer(&self, index: usize) -> Result<std::borrow::Cow<'a, [u8]>, ImportError> {
        let buffer = array(self.root, "buffers")
            .get(index)
            .ok_or_else(|| self.error(format!("buffer {index} does not exist")))?;
        match buffer.get("uri").and_then(Value::as_str) {
            None => self.bin.map(std::borrow::Cow::Borrowed).ok_or_else(|| {
                self.error(format!(
                    "buffer {index} has no uri and the file has no binary chunk"
                ))
            }),
            Some(uri) => {
                let data = uri
                    .strip_prefix("data:")
                    .and_then(|rest| rest.split_once(";base64,"))
                    .map(|(_, data)| data);
                let Some(data) = data else {
                    return Err(self.error(format!("buffer {index} is the external file `{uri}`: only embedded (data:) buffers and .glb are read")));
                };
                base64::engine::general_purpose::STANDARD
                    .decode(data)
                    .map(std::borrow::Cow::Owned)
                    .map_err(|e| self.error(format!("buffer {index}: bad base64: {e}")))
            }
        }
    }

    fn mesh(&mut self, index: usize, matrix: DMat4) -> Result<(), ImportError> {
        let mesh = array(self.root, "meshes")
            .get(index)
            .ok_or_else(|| self.error(format!("mesh {index} does not exist")))?;
        for primitive in array(mesh, "primitives") {
            let mode = primitive.get("mode").and_then(Value::as_u64).unwrap_or(4);
            if mode != 4 {
                self.comments.push(format!(
                    "a primitive of mode {mode} (not triangles) skipped"
                ));
                continue;
            }
            let Some(position) = primitive
                .pointer("/attributes/POSITION")
                .and_then(Value::as_u64)
            else {
                return Err(self.error("a primitive has no POSITION"));
            };
            let (bytes, component, count, kind) = match self.accessor(position as usize) {
                Ok(a) => a,
                Err(e) if e.message().contains("external file") => {
                    self.comments.push(e.message().to_owned());
                    continue;
                }
                Err(e) => return Err(e),
            };
            if component != 5126 || kind != "VEC3" {
                return Err(self.error("POSITION must be a FLOAT VEC3 accessor"));
            }
            let points: Vec<DVec3> = bytes
                .chunks_exact(12)
                .map(|c| {
                    let f = |i: usize| {
                        f64::from(f32::from_le_bytes(c[i..i + 4].try_into().expect("4 bytes")))
                    };
                    DVec3::new(f(0), f(4), f(8))
                })
                .collect();
            let indices: Vec<usize> = match primitive.get("indices").and_then(Value::as_u64) {
                None => (0..count).collect(),
                Some(i) => {
                    let (bytes, component, _, kind) = self.accessor(i as usize)?;
                    if kind != "SCALAR" {
                        return Err(self.error("indices must be a SCALAR accessor"));
                    }
                    match component {
                        5121 => bytes.iter().map(|&b| usize::from(b)).collect(),
                        5123 => bytes
                            .chunks_exact(2)
                            .map(|c| usize::from(u16::from_le_bytes([c[0], c[1]])))
                            .collect(),
                        5125 => bytes
                            .chunks_exact(4)
                            .map(|c| u32::from_le_bytes(c.try_into().expect("4 bytes")) as usize)
                            .collect(),
                        _ => return Err(self.error("indices must be unsigned integers")),
                    }
                }
            };
            if indices.iter().any(|&i| i >= points.len()) {
                return Err(self.error("an index is past the end of POSITION"));
            }
            let material = match primitive.get("material").and_then(Value::as_u64) {
                Some(m) => Some(self.material(m as usize)?),
                None => None,
            };
            for t in indices.chunks_exact(3) {
                let corners =
                    [t[0], t[1], t[2]].map(|i| matrix.transform_point3(points[i]).as_vec3());
                let area = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
                if area != Vec3::ZERO && area.is_finite() {
                    self.objects.push(ObjectDocument::Triangle {
                        corners,
                        material: material.clone(),
                    });
                }
            }
        }
        Ok(())
    }

    fn material(&mut self, index: usize) -> Result<String, ImportError> {
        let material = array(self.root, "materials")
            .get(index)
            .ok_or_else(|| self.error(format!("material {index} does not exist")))?;
        let name = material
            .get("name")
            .and_then(Value::as_str)
            .filter(|n| !n.is_empty())
            .map_or_else(|| material_name(index), str::to_owned);
        if !self.used_materials.iter().any(|(n, _)| *n == name) {
            let color = material
                .pointer("/pbrMetallicRoughness/baseColorFactor")
                .and_then(Value::as_array)
                .and_then(|c| {
                    let c: Option<Vec<f64>> = c.iter().map(Value::as_f64).collect();
                    c.filter(|c| c.len() == 4)
                        .map(|c| Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32))
                })
                .unwrap_or(Vec3::ONE);
            self.used_materials.push((
                name.clone(),
                Material {
                    color: color.max(Vec3::ZERO),
                    ..Material::default()
                },
            ));
        }
        Ok(name)
    }
}

/// Reads a glTF 2.0 file (`.gltf` with embedded buffers, or `.glb`): the first camera of
/// the default scene, and its triangle meshes, base colours and punctual lights.
///
/// # Errors
/// An [`ImportError`] for malformed JSON or GLB, no camera, or values of the wrong form.
pub fn import(bytes: &[u8], path: &Path) -> Result<SceneDocument, ImportError> {
    let (json, bin) = glb::split(bytes, path)?;
    let root: Value = serde_json::from_slice(json).map_err(|e| {
        ImportError::new(
            path,
            Some((e.line(), e.column())),
            format!("not valid JSON: {e}"),
        )
    })?;
    if root
        .pointer("/asset/version")
        .and_then(Value::as_str)
        .is_none_or(|v| !v.starts_with("2."))
    {
        return Err(ImportError::new(
            path,
            None,
            "expected glTF 2.0 (asset.version \"2.0\")",
        ));
    }
    let mut importer = Importer {
        path,
        root: &root,
        bin,
        comments: vec![format!(
            "Imported from {} (glTF 2.0) by `viewray import`.",
            path.display()
        )],
        objects: Vec::new(),
        lights: Vec::new(),
        used_materials: Vec::new(),
        camera: None,
    };
    let scene_index = root.get("scene").and_then(Value::as_u64).unwrap_or(0) as usize;
    let roots: Vec<usize> = match array(&root, "scenes").get(scene_index) {
        Some(scene) => array(scene, "nodes")
            .iter()
            .filter_map(Value::as_u64)
            .map(|n| n as usize)
            .collect(),
        None => (0..array(&root, "nodes").len()).collect(),
    };
    for node in roots {
        importer.walk(node, DMat4::IDENTITY, 0)?;
    }
    let Some((camera_index, matrix)) = importer.camera else {
        return Err(ImportError::new(
            path,
            None,
            "no node of the scene holds a camera",
        ));
    };
    let camera = array(&root, "cameras").get(camera_index).ok_or_else(|| {
        ImportError::new(path, None, format!("camera {camera_index} does not exist"))
    })?;
    let error = |m: &str| ImportError::new(path, None, m.to_owned());
    let extras = camera.pointer("/extras/viewray");
    let size = |name: &str| {
        extras
            .and_then(|e| e.get(name))
            .and_then(Value::as_u64)
            .and_then(|x| u32::try_from(x).ok())
            .filter(|&x| x > 0 && x <= viewray_scene::MAX_IMAGE_SIDE)
    };
    let samples = size("samples").unwrap_or(1);
    let (projection, width, height) = match camera.get("type").and_then(Value::as_str) {
        Some("perspective") => {
            let p = camera
                .get("perspective")
                .ok_or_else(|| error("a perspective camera needs `perspective`"))?;
            let yfov = p
                .get("yfov")
                .and_then(Value::as_f64)
                .filter(|y| *y > 0.0 && *y < std::f64::consts::PI)
                .ok_or_else(|| error("`yfov` must be between 0 and pi radians"))?;
            let aspect = p.get("aspectRatio").and_then(Value::as_f64);
            if aspect.is_some_and(|a| !(a > 0.0 && a.is_finite())) {
                return Err(error("`aspectRatio` must be positive"));
            }
            let (width, height) = match (size("width"), size("height"), aspect) {
                (Some(w), Some(h), _) => (w, h),
                (_, _, Some(a)) => (pixels(480.0 * a), 480),
                _ => (640, 480),
            };
            let vh = 2.0 * (yfov / 2.0).tan();
            let size = match aspect {
                Some(a) if !square_pixels(DVec2::new(a * vh, vh), (width, height)) => {
                    PerspectiveSize::Viewport {
                        distance: 1.0,
                        viewport: DVec2::new(a * vh, vh),
                    }
                }
                _ => PerspectiveSize::Fov {
                    axis: FovAxis::Y,
                    degrees: yfov.to_degrees(),
                    distance: 1.0,
                },
            };
            (
                ProjectionDocument::Perspective {
                    size,
                    shift: DVec2::ZERO,
                },
                width,
                height,
            )
        }
        Some("orthographic") => {
            let o = camera
                .get("orthographic")
                .ok_or_else(|| error("an orthographic camera needs `orthographic`"))?;
            let mag = |name: &str| {
                o.get(name)
                    .and_then(Value::as_f64)
                    .filter(|m| *m != 0.0 && m.is_finite())
                    .map(f64::abs)
                    .ok_or_else(|| error("`xmag` and `ymag` must be non-zero numbers"))
            };
            let viewport = DVec2::new(2.0 * mag("xmag")?, 2.0 * mag("ymag")?);
            let (width, height) = match (size("width"), size("height")) {
                (Some(w), Some(h)) => (w, h),
                _ => (pixels(480.0 * viewport.x / viewport.y), 480),
            };
            (
                ProjectionDocument::Orthographic {
                    viewport,
                    lens: None,
                },
                width,
                height,
            )
        }
        _ => return Err(error("a camera's type must be perspective or orthographic")),
    };
    let camera =
        camera_document(matrix, projection).map_err(|m| ImportError::new(path, None, m))?;
    Ok(SceneDocument {
        comments: importer.comments,
        width,
        height,
        samples,
        camera,
        background: Vec3::ZERO,
        shading: Shading::Lit,
        materials: importer.used_materials,
        lights: importer.lights,
        objects: importer.objects,
    })
}
