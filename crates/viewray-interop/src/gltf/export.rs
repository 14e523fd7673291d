//! Writing glTF 2.0 (the conventions are in the module's `mod.rs`).

use base64::Engine as _;
use glam::{DQuat, DVec2, DVec3, Vec3};
use serde_json::{Value, json};
use viewray_camera::Projection;

use super::glb;
use crate::common::{Parts, Shape, ToolLight, TriangleMesh, world_from_camera};
use crate::{ExportError, Format};

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
        let triangulated;
        let mesh = match shape {
            Shape::Sphere {
                center,
                radius,
                material,
            } => {
                triangulated = TriangleMesh::sphere(*center, *radius, *material);
                &triangulated
            }
            Shape::Box { min, max, material } => {
                triangulated = TriangleMesh::cuboid(*min, *max, *material);
                &triangulated
            }
            Shape::Plane {
                point,
                normal,
                material,
            } => {
                triangulated = TriangleMesh::plane(*point, *normal, *material);
                &triangulated
            }
            Shape::Mesh(mesh) => mesh,
        };
        let (positions, triangles) = (&mesh.data.positions, &mesh.data.triangles);
        let (min, max) = positions.iter().fold(
            (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let positions_at = buffer.len();
        for p in positions {
            for x in p.to_array() {
                buffer.extend_from_slice(&x.to_le_bytes());
            }
        }
        let indices_at = buffer.len();
        for t in triangles {
            for i in t {
                buffer.extend_from_slice(&i.to_le_bytes());
            }
        }
        views.push(json!({ "buffer": 0, "byteOffset": positions_at, "byteLength": indices_at - positions_at, "target": 34962 }));
        views.push(json!({ "buffer": 0, "byteOffset": indices_at, "byteLength": buffer.len() - indices_at, "target": 34963 }));
        let view = views.len() - 2;
        accessors.push(json!({
            "bufferView": view, "componentType": 5126, "count": positions.len(), "type": "VEC3",
            "min": min.to_array(), "max": max.to_array(),
        }));
        accessors.push(json!({
            "bufferView": view + 1, "componentType": 5125, "count": triangles.len() * 3, "type": "SCALAR",
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
        .materials()
        .map(|m| {
            json!({
                "name": m.name,
                "pbrMetallicRoughness": {
                    "baseColorFactor": [m.color.x, m.color.y, m.color.z, 1.0],
                    "metallicFactor": 0.0, "roughnessFactor": 1.0,
                },
                "doubleSided": true,
            })
        })
        .collect();
    let mut lights = Vec::new();
    for light in parts.lights() {
        let (kind, power, node) = match light {
            ToolLight::Point { position, power } => (
                "point",
                power,
                json!({ "translation": position.to_array() }),
            ),
            ToolLight::Directional { direction, power } => {
                let rotation = DQuat::from_rotation_arc(DVec3::NEG_Z, direction.as_dvec3());
                (
                    "directional",
                    power,
                    json!({ "rotation": rotation.to_array() }),
                )
            }
            ToolLight::Ambient { .. } => continue,
        };
        let color = power.color().unwrap_or(Vec3::ZERO);
        let mut node = node;
        node["extensions"] = json!({ "KHR_lights_punctual": { "light": lights.len() } });
        nodes.push(node);
        lights.push(
            json!({ "type": kind, "color": color.to_array(), "intensity": power.strength() }),
        );
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
        Ok(glb::write(
            &document,
            (!meshes.is_empty()).then_some(buffer.as_slice()),
        ))
    } else {
        let mut text = serde_json::to_string_pretty(&document).expect("JSON values serialize");
        text.push('\n');
        Ok(text.into_bytes())
    }
}
