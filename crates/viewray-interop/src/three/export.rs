//! Writing a three.js JSON object (the conventions are in the module's `mod.rs`).

use std::f64::consts::PI;

use glam::{DMat4, DVec2, Vec3};
use serde_json::{Map, Value, json};
use viewray_camera::Projection;
use viewray_scene::Shading;

use crate::common::{self, LightPower, Parts, Shape, ToolLight, hex_color, world_from_camera};
use crate::{ExportError, Format};

fn lacks(what: impl Into<String>) -> ExportError {
    ExportError::new(Format::Three, what)
}

/// A deterministic UUID-shaped identifier (three.js only needs them unique).
fn uuid(n: usize) -> String {
    format!("00000000-0000-4000-8000-{n:012x}")
}

fn matrix_json(m: DMat4) -> Value {
    json!(m.to_cols_array())
}

/// The camera object of `parts`: a `PerspectiveCamera` or `OrthographicCamera`.
fn camera_json(parts: &Parts<'_>, id: String) -> Result<Value, ExportError> {
    let camera = parts.camera;
    let (width, height) = parts.size();
    let (w, h) = (f64::from(width), f64::from(height));
    let matrix = matrix_json(world_from_camera(camera.frame()));
    let view = |offset: DVec2| {
        json!({
            "enabled": true,
            "fullWidth": w, "fullHeight": h,
            "offsetX": offset.x, "offsetY": offset.y,
            "width": w, "height": h,
        })
    };
    match camera.projection() {
        Projection::Perspective(p) => {
            let fov = (2.0 * (p.viewport.y / (2.0 * p.distance)).atan()).to_degrees();
            let offset = DVec2::new(p.shift.x / p.viewport.x * w, -p.shift.y / p.viewport.y * h);
            Ok(json!({
                "uuid": id, "type": "PerspectiveCamera", "name": "viewray camera",
                "layers": 1, "matrix": matrix, "up": [0.0, 1.0, 0.0],
                "fov": fov, "zoom": 1.0, "near": 0.001, "far": 1.0e6, "focus": 10.0,
                "aspect": p.viewport.x / p.viewport.y,
                "view": view(offset),
                "filmGauge": 35.0, "filmOffset": 0.0,
            }))
        }
        Projection::Orthographic(o) => {
            if o.lens.is_some() {
                return Err(lacks("has no lens: its orthographic camera is a pinhole"));
            }
            let (x, y) = (o.viewport.x / 2.0, o.viewport.y / 2.0);
            Ok(json!({
                "uuid": id, "type": "OrthographicCamera", "name": "viewray camera",
                "layers": 1, "matrix": matrix, "up": [0.0, 1.0, 0.0],
                "zoom": 1.0, "left": -x, "right": x, "top": y, "bottom": -y,
                "near": 0.0, "far": 1.0e6,
                "view": view(DVec2::ZERO),
            }))
        }
        Projection::ThinLens(_) => Err(lacks(
            "has no lens: its cameras are pinholes (PerspectiveCamera.focus is for stereo)",
        )),
        Projection::Oblique(_) => Err(lacks(
            "has no oblique camera: its cameras are perspective and orthographic",
        )),
        Projection::Equirectangular | Projection::Fisheye(_) => Err(lacks(
            "has no panoramic camera: its cameras are perspective and orthographic",
        )),
    }
}

/// A light's `color` (sRGB `0xRRGGBB`) and `intensity`: its colour and strength, or
/// black and 0 for a black light.
fn color_and_intensity(power: LightPower) -> (u32, f64) {
    match power.color() {
        Some(color) => (hex_color(color), f64::from(power.strength())),
        None => (0, 0.0),
    }
}

/// Writes `scene` as a three.js JSON object (a `Scene` holding the camera, lights and
/// meshes), loadable with `THREE.ObjectLoader().parse`.
///
/// # Errors
/// An [`ExportError`] for a camera three.js cannot express.
pub fn export(scene: &viewray_scene::Scene) -> Result<Vec<u8>, ExportError> {
    let parts = Parts::of(scene);
    let mut ids = 0;
    let mut next = || {
        ids += 1;
        uuid(ids)
    };
    let mut children = vec![camera_json(&parts, next())?];
    for light in parts.lights() {
        let value = match light {
            ToolLight::Point { position, power } => {
                let (color, intensity) = color_and_intensity(power);
                json!({
                    "uuid": next(), "type": "PointLight", "layers": 1,
                    "matrix": matrix_json(DMat4::from_translation(position.as_dvec3())),
                    "color": color, "intensity": intensity, "distance": 0.0, "decay": 2.0,
                })
            }
            ToolLight::Directional { direction, power } => {
                let (color, intensity) = color_and_intensity(power);
                json!({
                    "uuid": next(), "type": "DirectionalLight", "layers": 1,
                    "matrix": matrix_json(DMat4::from_translation(-direction.as_dvec3())),
                    "color": color, "intensity": intensity,
                })
            }
            ToolLight::Ambient { power } => {
                let (color, intensity) = color_and_intensity(power);
                json!({
                    "uuid": next(), "type": "AmbientLight", "layers": 1,
                    "matrix": matrix_json(DMat4::IDENTITY),
                    "color": color, "intensity": intensity,
                })
            }
        };
        children.push(value);
    }
    let materials: Vec<Value> = parts
        .materials()
        .map(|m| {
            json!({
                "uuid": uuid(1_000_000 + m.index), "type": "MeshLambertMaterial",
                "name": m.name, "color": hex_color(m.color), "side": 2,
            })
        })
        .collect();
    let mut geometries = Vec::new();
    for shape in &parts.shapes {
        let geometry_id = next();
        let (geometry, matrix, material) = match shape {
            Shape::Sphere {
                center,
                radius,
                material,
            } => (
                json!({
                    "uuid": geometry_id, "type": "SphereGeometry", "radius": radius,
                    "widthSegments": common::SPHERE_SEGMENTS, "heightSegments": common::SPHERE_RINGS,
                    "phiStart": 0.0, "phiLength": 2.0 * PI, "thetaStart": 0.0, "thetaLength": PI,
                }),
                DMat4::from_translation(center.as_dvec3()),
                *material,
            ),
            Shape::Box { min, max, material } => {
                let size = *max - *min;
                (
                    json!({
                        "uuid": geometry_id, "type": "BoxGeometry",
                        "width": size.x, "height": size.y, "depth": size.z,
                        "widthSegments": 1, "heightSegments": 1, "depthSegments": 1,
                    }),
                    DMat4::from_translation(((*min + *max) / 2.0).as_dvec3()),
                    *material,
                )
            }
            Shape::Plane {
                point,
                normal,
                material,
            } => {
                let (t1, t2) = common::tangents(*normal);
                let size = 2.0 * common::PLANE_HALF_SIZE;
                (
                    json!({
                        "uuid": geometry_id, "type": "PlaneGeometry",
                        "width": size, "height": size, "widthSegments": 1, "heightSegments": 1,
                    }),
                    DMat4::from_cols(
                        t1.as_dvec3().extend(0.0),
                        t2.as_dvec3().extend(0.0),
                        normal.as_dvec3().extend(0.0),
                        point.as_dvec3().extend(1.0),
                    ),
                    *material,
                )
            }
            Shape::Mesh(mesh) => {
                let positions: Vec<f32> = mesh
                    .data
                    .positions
                    .iter()
                    .flat_map(|p| p.to_array())
                    .collect();
                let indices: Vec<u32> = mesh.data.triangles.iter().flatten().copied().collect();
                (
                    json!({
                        "uuid": geometry_id, "type": "BufferGeometry",
                        "data": {
                            "attributes": {
                                "position": {
                                    "itemSize": 3, "type": "Float32Array",
                                    "array": positions, "normalized": false,
                                },
                            },
                            "index": { "type": "Uint32Array", "array": indices },
                        },
                    }),
                    DMat4::IDENTITY,
                    mesh.material,
                )
            }
        };
        children.push(json!({
            "uuid": next(), "type": "Mesh", "layers": 1, "matrix": matrix_json(matrix),
            "geometry": geometry["uuid"].clone(),
            "material": uuid(1_000_000 + material as usize),
        }));
        geometries.push(geometry);
    }
    let mut object = json!({
        "uuid": next(), "type": "Scene", "name": "viewray scene", "layers": 1,
        "matrix": matrix_json(DMat4::IDENTITY), "up": [0.0, 1.0, 0.0],
        "children": children,
    });
    if parts.background != Vec3::ZERO {
        object["background"] = json!(hex_color(parts.background));
    }
    let mut samples = Map::new();
    samples.insert("samples".to_owned(), json!(parts.samples));
    if parts.shading != Shading::Lit {
        samples.insert("shading".to_owned(), json!(format!("{:?}", parts.shading)));
    }
    object["userData"] = json!({ "viewray": samples });
    let document = json!({
        "metadata": { "version": 4.6, "type": "Object", "generator": "viewray export" },
        "geometries": geometries,
        "materials": materials,
        "object": object,
    });
    let mut text = serde_json::to_string_pretty(&document).expect("JSON values serialize");
    text.push('\n');
    Ok(text.into_bytes())
}
