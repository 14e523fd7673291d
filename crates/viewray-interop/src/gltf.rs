//! glTF 2.0: `.gltf` (JSON, buffers embedded as base64) and `.glb` (binary).
//!
//! # Conventions
//!
//! - **Axes.** Right-handed, `+y` up, metres. A camera looks down its node's local `-z`
//!   with `+x` right and `+y` up: viewray's `U`, `V`, `W`, so the node's `matrix`
//!   (column-major) has the columns `U`, `V`, `W`, `e`.
//! - **Field of view.** `perspective.yfov` is *vertical*, in radians: `vh = 2 d tan(yfov
//!   / 2)`. `aspectRatio = vw / vh` when given; without it the renderer's viewport
//!   decides (an imported camera then gets a 640 x 480 image and `fov_y`).
//! - **Orthographic.** `xmag` and `ymag` are *half* the viewport: `vw = 2 xmag`,
//!   `vh = 2 ymag`. viewray writes `znear = 0`, `zfar = 10^6`.
//! - **Image size** is not part of glTF: viewray keeps it in the camera's `extras`
//!   (`{"viewray": {"width", "height", "samples"}}`) and reads it back from there.
//! - **Geometry.** glTF has only triangle meshes: spheres become 64 x 32 UV spheres,
//!   infinite planes squares 2 x 10^4 across. Colours are linear `baseColorFactor`s;
//!   lights use `KHR_lights_punctual` (intensities times pi, as for three.js); the
//!   background and ambient light have no glTF counterpart.
//! - **Cannot be expressed**: a shift (glTF's frustum is symmetric), a lens, oblique and
//!   panoramic cameras.

use std::path::Path;

use base64::Engine as _;
use glam::{DMat4, DQuat, DVec2, DVec3, Vec3};
use serde_json::{Value, json};
use viewray_camera::{FovAxis, Projection};
use viewray_scene::{
    Light, Material, ObjectDocument, PerspectiveSize, ProjectionDocument, SceneDocument, Shading,
};

use crate::common::{
    Parts, Shape, TriangleMesh, camera_document, material_name, matrix_from_column_major,
    world_from_camera,
};
use crate::{ExportError, Format, ImportError};

const GLB_MAGIC: &[u8; 4] = b"glTF";
const CHUNK_JSON: u32 = 0x4E4F_534A;
const CHUNK_BIN: u32 = 0x004E_4942;

fn lacks(what: impl Into<String>) -> ExportError {
    ExportError::new(Format::Gltf, what)
}

/// Writes `scene` as glTF 2.0: `.gltf` JSON with the buffer embedded, or `.glb`.
///
/// # Errors
/// An [`ExportError`] for a camera glTF cannot express.
pub fn export(scene: &viewray_scene::Scene, binary: bool) -> Result<Vec<u8>, ExportError> {
    let parts = Parts::of(scene);
    let (width, height) = parts.size();
    let camera = parts.camera;
    let extras =
        json!({ "viewray": { "width": width, "height": height, "samples": parts.samples } });
    let camera_json = match camera.projection() {
        Projection::Perspective(p) => {
            if p.shift != DVec2::ZERO {
                return Err(lacks(
                    "has no shift: its perspective camera's frustum is symmetric (yfov and \
                     aspectRatio only)",
                ));
            }
            json!({
                "type": "perspective",
                "perspective": {
                    "yfov": 2.0 * (p.viewport.y / (2.0 * p.distance)).atan(),
                    "aspectRatio": p.viewport.x / p.viewport.y,
                    "znear": 0.001,
                },
                "extras": extras,
            })
        }
        Projection::Orthographic(o) => {
            if o.lens.is_some() {
                return Err(lacks("has no lens: its cameras are pinholes"));
            }
            json!({
                "type": "orthographic",
                "orthographic": {
                    "xmag": o.viewport.x / 2.0, "ymag": o.viewport.y / 2.0,
                    "znear": 0.0, "zfar": 1.0e6,
                },
                "extras": extras,
            })
        }
        Projection::ThinLens(_) => {
            return Err(lacks(
                "has no lens: its cameras are pinholes (no aperture, no focus)",
            ));
        }
        Projection::Oblique(_) => {
            return Err(lacks(
                "has no oblique camera: its cameras are perspective and orthographic",
            ));
        }
        Projection::Equirectangular | Projection::Fisheye(_) => {
            return Err(lacks(
                "has no panoramic camera: its cameras are perspective and orthographic",
            ));
        }
    };
    let mut nodes = vec![json!({
        "name": "viewray camera",
        "camera": 0,
        "matrix": world_from_camera(camera.frame()).to_cols_array(),
    })];
    let mut buffer: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    for shape in &parts.shapes {
        let mesh = match shape {
            Shape::Sphere {
                center,
                radius,
                material,
            } => TriangleMesh::sphere(*center, *radius, *material),
            Shape::Box { min, max, material } => TriangleMesh::cuboid(*min, *max, *material),
            Shape::Plane {
                point,
                normal,
                material,
            } => TriangleMesh::plane(*point, *normal, *material),
            Shape::Mesh(mesh) => TriangleMesh {
                positions: mesh.positions.clone(),
                triangles: mesh.triangles.clone(),
                material: mesh.material,
            },
        };
        let (min, max) = mesh.positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let positions_at = buffer.len();
        for p in &mesh.positions {
            for x in p.to_array() {
                buffer.extend_from_slice(&x.to_le_bytes());
            }
        }
        let indices_at = buffer.len();
        for t in &mesh.triangles {
            for i in t {
                buffer.extend_from_slice(&i.to_le_bytes());
            }
        }
        views.push(json!({ "buffer": 0, "byteOffset": positions_at, "byteLength": indices_at - positions_at, "target": 34962 }));
        views.push(json!({ "buffer": 0, "byteOffset": indices_at, "byteLength": buffer.len() - indices_at, "target": 34963 }));
        let view = views.len() - 2;
        accessors.push(json!({
            "bufferView": view, "componentType": 5126, "count": mesh.positions.len(), "type": "VEC3",
            "min": min.to_array(), "max": max.to_array(),
        }));
        accessors.push(json!({
            "bufferView": view + 1, "componentType": 5125, "count": mesh.triangles.len() * 3, "type": "SCALAR",
        }));
        let accessor = accessors.len() - 2;
        meshes.push(json!({
            "primitives": [{
                "attributes": { "POSITION": accessor },
                "indices": accessor + 1,
                "material": mesh.material,
                "mode": 4,
            }],
        }));
        nodes.push(json!({ "mesh": meshes.len() - 1 }));
    }
    let materials: Vec<Value> = parts
        .materials
        .iter()
        .enumerate()
        .map(|(i, m)| {
            json!({
                "name": material_name(i),
                "pbrMetallicRoughness": {
                    "baseColorFactor": [m.color.x, m.color.y, m.color.z, 1.0],
                    "metallicFactor": 0.0, "roughnessFactor": 1.0,
                },
                "doubleSided": true,
            })
        })
        .collect();
    let pi = std::f32::consts::PI;
    let mut lights = Vec::new();
    for light in parts.lights {
        let (kind, intensity, node) = match *light {
            Light::Point {
                position,
                intensity,
            } => (
                "point",
                intensity,
                json!({ "translation": position.to_array() }),
            ),
            Light::Directional {
                direction,
                intensity,
            } => {
                let rotation = DQuat::from_rotation_arc(DVec3::NEG_Z, direction.as_dvec3());
                (
                    "directional",
                    intensity,
                    json!({ "rotation": rotation.to_array() }),
                )
            }
            Light::Ambient { .. } => continue,
        };
        let peak = intensity.max_element();
        let color = if peak > 0.0 {
            intensity / peak
        } else {
            Vec3::ZERO
        };
        let mut node = node;
        node["extensions"] = json!({ "KHR_lights_punctual": { "light": lights.len() } });
        nodes.push(node);
        lights.push(json!({ "type": kind, "color": color.to_array(), "intensity": peak * pi }));
    }
    while !buffer.len().is_multiple_of(4) {
        buffer.push(0);
    }
    let mut document = json!({
        "asset": { "version": "2.0", "generator": "viewray export" },
        "scene": 0,
        "scenes": [{ "nodes": (0..nodes.len()).collect::<Vec<_>>() }],
        "nodes": nodes,
        "cameras": [camera_json],
        "materials": materials,
    });
    if !meshes.is_empty() {
        document["meshes"] = json!(meshes);
        document["accessors"] = json!(accessors);
        document["bufferViews"] = json!(views);
        let mut buffer_json = json!({ "byteLength": buffer.len() });
        if !binary {
            buffer_json["uri"] = json!(format!(
                "data:application/octet-stream;base64,{}",
                base64::engine::general_purpose::STANDARD.encode(&buffer)
            ));
        }
        document["buffers"] = json!([buffer_json]);
    }
    if !lights.is_empty() {
        document["extensionsUsed"] = json!(["KHR_lights_punctual"]);
        document["extensions"] = json!({ "KHR_lights_punctual": { "lights": lights } });
    }
    if binary {
        let mut json_bytes = serde_json::to_vec(&document).expect("JSON values serialize");
        while !json_bytes.len().is_multiple_of(4) {
            json_bytes.push(b' ');
        }
        let has_bin = !meshes.is_empty();
        let total = 12 + 8 + json_bytes.len() + if has_bin { 8 + buffer.len() } else { 0 };
        let mut out = Vec::with_capacity(total);
        out.extend_from_slice(GLB_MAGIC);
        out.extend_from_slice(&2u32.to_le_bytes());
        out.extend_from_slice(&u32::try_from(total).unwrap_or(u32::MAX).to_le_bytes());
        out.extend_from_slice(
            &u32::try_from(json_bytes.len())
                .unwrap_or(u32::MAX)
                .to_le_bytes(),
        );
        out.extend_from_slice(&CHUNK_JSON.to_le_bytes());
        out.extend_from_slice(&json_bytes);
        if has_bin {
            out.extend_from_slice(
                &u32::try_from(buffer.len())
                    .unwrap_or(u32::MAX)
                    .to_le_bytes(),
            );
            out.extend_from_slice(&CHUNK_BIN.to_le_bytes());
            out.extend_from_slice(&buffer);
        }
        Ok(out)
    } else {
        let mut text = serde_json::to_string_pretty(&document).expect("JSON values serialize");
        text.push('\n');
        Ok(text.into_bytes())
    }
}

// ---------------------------------------------------------------------------------------
// Import
// ---------------------------------------------------------------------------------------

/// The JSON and the binary chunk of a `.glb`, or the JSON of a `.gltf`.
fn split_glb<'a>(
    bytes: &'a [u8],
    path: &Path,
) -> Result<(&'a [u8], Option<&'a [u8]>), ImportError> {
    if !bytes.starts_with(GLB_MAGIC) {
        return Ok((bytes, None));
    }
    let error = |m: &str| ImportError::new(path, None, format!("not a valid .glb: {m}"));
    let word = |at: usize| -> Option<u32> {
        bytes
            .get(at..at + 4)
            .map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")))
    };
    if word(4) != Some(2) {
        return Err(error("only glTF 2 binaries are read"));
    }
    let mut at = 12;
    let mut json = None;
    let mut bin = None;
    while at + 8 <= bytes.len() {
        let length = word(at).ok_or_else(|| error("truncated chunk header"))? as usize;
        let kind = word(at + 4).ok_or_else(|| error("truncated chunk header"))?;
        let data = bytes
            .get(at + 8..at + 8 + length)
            .ok_or_else(|| error("a chunk runs past the end of the file"))?;
        match kind {
            CHUNK_JSON if json.is_none() => json = Some(data),
            CHUNK_BIN if bin.is_none() => bin = Some(data),
            _ => {}
        }
        at += 8 + length;
    }
    Ok((json.ok_or_else(|| error("no JSON chunk"))?, bin))
}

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
        let intensity = light
            .get("intensity")
            .and_then(Value::as_f64)
            .unwrap_or(1.0) as f32
            * color
            / std::f32::consts::PI;
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
    let (json, bin) = split_glb(bytes, path)?;
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
                Some(a)
                    if !crate::common::square_pixels(DVec2::new(a * vh, vh), (width, height)) =>
                {
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

fn pixels(x: f64) -> u32 {
    // Clamped into u32's range first.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = x
        .round()
        .clamp(1.0, f64::from(viewray_scene::MAX_IMAGE_SIDE)) as u32;
    n
}
