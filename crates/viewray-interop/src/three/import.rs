//! Reading a three.js JSON object (the conventions are in the module's `mod.rs`): its
//! object tree walked from the root, with each object's matrix.

use std::collections::HashMap;
use std::f64::consts::PI;
use std::path::Path;

use glam::{DMat4, DQuat, DVec2, DVec3, Vec3};
use serde_json::Value;
use viewray_scene::{
    Light, Material, ObjectDocument, PerspectiveSize, ProjectionDocument, SceneDocument, Shading,
};

use crate::ImportError;
use crate::common::{
    TriangleMesh, camera_document, color_from_hex, matrix_from_column_major, pixels, square_pixels,
    viewray_intensity,
};

/// The image height an imported camera without a `view` gets.
const DEFAULT_ROWS: u32 = 480;

struct Importer<'a> {
    path: &'a Path,
    geometries: HashMap<String, &'a Value>,
    materials: HashMap<String, (String, Material)>,
    used_materials: Vec<(String, Material)>,
    comments: Vec<String>,
    objects: Vec<ObjectDocument>,
    lights: Vec<Light>,
    camera: Option<(&'a Value, DMat4)>,
}

fn number(value: &Value, name: &str) -> Option<f64> {
    value
        .get(name)
        .and_then(Value::as_f64)
        .filter(|x| x.is_finite())
}

impl<'a> Importer<'a> {
    fn error(&self, message: impl Into<String>) -> ImportError {
        ImportError::new(self.path, None, message)
    }

    /// The object's own matrix: `matrix`, or `position`, `quaternion`/`rotation`, `scale`.
    fn local_matrix(&self, object: &Value) -> Result<DMat4, ImportError> {
        if let Some(m) = object.get("matrix") {
            let numbers: Option<Vec<f64>> = m
                .as_array()
                .map(|a| a.iter().map(Value::as_f64).collect())
                .unwrap_or(None);
            return numbers
                .as_deref()
                .and_then(matrix_from_column_major)
                .ok_or_else(|| self.error("an object's `matrix` must be 16 finite numbers"));
        }
        let triple = |name: &str, default: DVec3| -> Result<DVec3, ImportError> {
            match object.get(name) {
                None => Ok(default),
                Some(v) => v
                    .as_array()
                    .filter(|a| a.len() >= 3)
                    .and_then(|a| Some(DVec3::new(a[0].as_f64()?, a[1].as_f64()?, a[2].as_f64()?)))
                    .ok_or_else(|| self.error(format!("`{name}` must be 3 numbers"))),
            }
        };
        let position = triple("position", DVec3::ZERO)?;
        let scale = triple("scale", DVec3::ONE)?;
        let rotation = match object.get("quaternion").and_then(Value::as_array) {
            Some(q) if q.len() == 4 => {
                let q: Option<Vec<f64>> = q.iter().map(Value::as_f64).collect();
                let q = q.ok_or_else(|| self.error("`quaternion` must be 4 numbers"))?;
                DQuat::from_xyzw(q[0], q[1], q[2], q[3]).normalize()
            }
            _ => {
                let r = triple("rotation", DVec3::ZERO)?;
                DQuat::from_euler(glam::EulerRot::XYZ, r.x, r.y, r.z)
            }
        };
        Ok(DMat4::from_scale_rotation_translation(
            scale, rotation, position,
        ))
    }

    fn material(&mut self, object: &Value) -> Option<String> {
        let id = object.get("material").and_then(Value::as_str)?;
        let (name, material) = self.materials.get(id)?.clone();
        if !self.used_materials.iter().any(|(n, _)| *n == name) {
            self.used_materials.push((name.clone(), material));
        }
        Some(name)
    }

    fn walk(&mut self, object: &'a Value, parent: DMat4, depth: usize) -> Result<(), ImportError> {
        if depth > 64 {
            return Err(self.error("objects are nested more than 64 deep"));
        }
        let matrix = parent * self.local_matrix(object)?;
        let kind = object.get("type").and_then(Value::as_str).unwrap_or("");
        match kind {
            "PerspectiveCamera" | "OrthographicCamera" => {
                if self.camera.is_none() {
                    self.camera = Some((object, matrix));
                }
            }
            "Mesh" => self.mesh(object, matrix)?,
            "PointLight" | "DirectionalLight" | "AmbientLight" => self.light(object, kind, matrix),
            "Scene" | "Group" | "Object3D" | "" => {}
            other => self.comments.push(format!("a {other} skipped")),
        }
        if let Some(children) = object.get("children") {
            let children = children
                .as_array()
                .ok_or_else(|| self.error("`children` must be an array"))?;
            for child in children {
                self.walk(child, matrix, depth + 1)?;
            }
        }
        Ok(())
    }

    fn light(&mut self, object: &Value, kind: &str, matrix: DMat4) {
        let color = object
            .get("color")
            .and_then(Value::as_u64)
            .map_or(Vec3::ONE, |c| color_from_hex(c as u32));
        let intensity =
            viewray_intensity(number(object, "intensity").unwrap_or(1.0) as f32 * color);
        let position = matrix.w_axis.truncate();
        match kind {
            "PointLight" => self.lights.push(Light::Point {
                position: position.as_vec3(),
                intensity,
            }),
            "DirectionalLight" => match (-position).try_normalize() {
                Some(direction) => self.lights.push(Light::Directional {
                    direction: direction.as_vec3(),
                    intensity,
                }),
                None => self
                    .comments
                    .push("a DirectionalLight at its target skipped".to_owned()),
            },
            _ => self.lights.push(Light::Ambient { intensity }),
        }
    }

    fn mesh(&mut self, object: &Value, matrix: DMat4) -> Result<(), ImportError> {
        let material = self.material(object);
        let Some(geometry) = object
            .get("geometry")
            .and_then(Value::as_str)
            .and_then(|id| self.geometries.get(id).copied())
        else {
            return Err(self.error("a Mesh names a geometry that is not in `geometries`"));
        };
        let kind = geometry.get("type").and_then(Value::as_str).unwrap_or("");
        let point = |p: DVec3| matrix.transform_point3(p).as_vec3();
        match kind {
            "SphereGeometry" => {
                let whole = number(geometry, "phiLength").is_none_or(|x| x >= 2.0 * PI - 1e-9)
                    && number(geometry, "thetaLength").is_none_or(|x| x >= PI - 1e-9);
                let linear = glam::DMat3::from_mat4(matrix);
                let scale = linear.x_axis.length();
                let uniform = [linear.y_axis, linear.z_axis]
                    .iter()
                    .all(|a| (a.length() - scale).abs() <= 1e-9 * scale);
                if !whole || !uniform {
                    self.comments
                        .push("a partial or unevenly scaled SphereGeometry skipped".to_owned());
                    return Ok(());
                }
                self.objects.push(ObjectDocument::Sphere {
                    center: point(DVec3::ZERO),
                    radius: (number(geometry, "radius").unwrap_or(1.0) * scale) as f32,
                    material,
                });
            }
            "BoxGeometry" => {
                let size = DVec3::new(
                    number(geometry, "width").unwrap_or(1.0),
                    number(geometry, "height").unwrap_or(1.0),
                    number(geometry, "depth").unwrap_or(1.0),
                ) / 2.0;
                let cube = TriangleMesh::cuboid((-size).as_vec3(), size.as_vec3(), 0).data;
                let corners: Vec<DVec3> = cube.positions.iter().map(|p| p.as_dvec3()).collect();
                self.triangles(&corners, &cube.triangles, matrix, &material);
            }
            "PlaneGeometry" => {
                let (w, h) = (
                    number(geometry, "width").unwrap_or(1.0) / 2.0,
                    number(geometry, "height").unwrap_or(1.0) / 2.0,
                );
                let corners = [
                    DVec3::new(-w, -h, 0.0),
                    DVec3::new(w, -h, 0.0),
                    DVec3::new(w, h, 0.0),
                    DVec3::new(-w, h, 0.0),
                ];
                self.triangles(&corners, &[[0, 1, 2], [0, 2, 3]], matrix, &material);
            }
            "BufferGeometry" => {
                let data = geometry.get("data").ok_or_else(|| self.error("a BufferGeometry has no `data`"))?;
                let positions: Vec<f64> = data
                    .pointer("/attributes/position/array")
                    .and_then(Value::as_array)
                    .and_then(|a| a.iter().map(Value::as_f64).collect())
                    .ok_or_else(|| self.error("a BufferGeometry needs `data.attributes.position.array` of numbers"))?;
                if data.pointer("/attributes/position/itemSize").and_then(Value::as_u64) != Some(3)
                    || !positions.len().is_multiple_of(3)
                {
                    return Err(self.error("a BufferGeometry's positions must have itemSize 3"));
                }
                let points: Vec<DVec3> = positions.chunks_exact(3).map(|c| DVec3::new(c[0], c[1], c[2])).collect();
                let indices: Vec<u32> = match data.pointer("/index/array") {
                    Some(array) => array
                        .as_array()
                        .and_then(|a| a.iter().map(|v| v.as_u64().and_then(|i| u32::try_from(i).ok())).collect())
                        .ok_or_else(|| self.error("a BufferGeometry's index must be whole numbers"))?,
                    None => (0..u32::try_from(points.len()).unwrap_or(u32::MAX)).collect(),
                };
                if !indices.len().is_multiple_of(3) || indices.iter().any(|&i| i as usize >= points.len()) {
                    return Err(self.error("a BufferGeometry's index must be triangles of vertex numbers"));
                }
                let triangles: Vec<[u32; 3]> = indices.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
                self.triangles(&points, &triangles, matrix, &material);
            }
            other => self.comments.push(format!("a {other} skipped (viewray reads SphereGeometry, BoxGeometry, PlaneGeometry and BufferGeometry)")),
        }
        Ok(())
    }

    fn triangles(
        &mut self,
        points: &[DVec3],
        triangles: &[[u32; 3]],
        matrix: DMat4,
        material: &Option<String>,
    ) {
        for t in triangles {
            let corners = t.map(|i| matrix.transform_point3(points[i as usize]).as_vec3());
            let area = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            if area != Vec3::ZERO && area.is_finite() {
                self.objects.push(ObjectDocument::Triangle {
                    corners,
                    material: material.clone(),
                });
            }
        }
    }
}

/// Reads a three.js JSON object: a camera's (`camera.toJSON()`) or a scene's
/// (`scene.toJSON()`, whose first camera is imported), with its spheres, boxes, planes and
/// buffer geometries, Lambert/standard colours and point, directional and ambient lights.
///
/// # Errors
/// An [`ImportError`] naming the file for malformed JSON (with the line and column), no
/// camera, or values of the wrong form.
pub fn import(text: &str, path: &Path) -> Result<SceneDocument, ImportError> {
    let value: Value = serde_json::from_str(text).map_err(|e| {
        ImportError::new(
            path,
            Some((e.line(), e.column())),
            format!("not valid JSON: {e}"),
        )
    })?;
    let object = value.get("object").ok_or_else(|| {
        ImportError::new(
            path,
            None,
            "expected a three.js JSON object with an `object` (from object.toJSON())",
        )
    })?;
    let mut importer = Importer {
        path,
        geometries: HashMap::new(),
        materials: HashMap::new(),
        used_materials: Vec::new(),
        comments: vec![format!(
            "Imported from {} (three.js JSON) by `viewray import`.",
            path.display()
        )],
        objects: Vec::new(),
        lights: Vec::new(),
        camera: None,
    };
    for g in value
        .get("geometries")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
    {
        if let Some(id) = g.get("uuid").and_then(Value::as_str) {
            importer.geometries.insert(id.to_owned(), g);
        }
    }
    for (i, m) in value
        .get("materials")
        .and_then(Value::as_array)
        .into_iter()
        .flatten()
        .enumerate()
    {
        let Some(id) = m.get("uuid").and_then(Value::as_str) else {
            continue;
        };
        let name = m
            .get("name")
            .and_then(Value::as_str)
            .filter(|n| !n.is_empty())
            .map_or_else(|| format!("material_{i}"), str::to_owned);
        let color = m
            .get("color")
            .and_then(Value::as_u64)
            .map_or(Vec3::splat(1.0), |c| color_from_hex(c as u32));
        importer.materials.insert(
            id.to_owned(),
            (
                name,
                Material {
                    color,
                    ..Material::default()
                },
            ),
        );
    }
    importer.walk(object, DMat4::IDENTITY, 0)?;
    let Some((camera, matrix)) = importer.camera else {
        return Err(ImportError::new(
            path,
            None,
            "the object holds no PerspectiveCamera or OrthographicCamera",
        ));
    };
    let (projection, width, height, eye_offset) = projection(camera, path)?;
    let matrix = matrix * DMat4::from_translation(eye_offset);
    let camera =
        camera_document(matrix, projection).map_err(|m| ImportError::new(path, None, m))?;
    let samples = object
        .pointer("/userData/viewray/samples")
        .and_then(Value::as_u64)
        .and_then(|s| u32::try_from(s).ok())
        .filter(|&s| s > 0)
        .unwrap_or(1);
    let background = object
        .get("background")
        .and_then(Value::as_u64)
        .map_or(Vec3::ZERO, |c| color_from_hex(c as u32));
    Ok(SceneDocument {
        comments: importer.comments,
        width,
        height,
        samples,
        camera,
        background,
        shading: Shading::Lit,
        materials: importer.used_materials,
        lights: importer.lights,
        objects: importer.objects,
    })
}

/// The projection of a three.js camera object, the image size, and how far the eye moves
/// in camera coordinates (an orthographic window's centre and near plane).
fn projection(
    camera: &Value,
    path: &Path,
) -> Result<(ProjectionDocument, u32, u32, DVec3), ImportError> {
    let error = |m: &str| ImportError::new(path, None, m.to_owned());
    let zoom = number(camera, "zoom").unwrap_or(1.0);
    if zoom <= 0.0 {
        return Err(error("the camera's `zoom` must be positive"));
    }
    let view = camera
        .get("view")
        .filter(|v| v.get("enabled").and_then(Value::as_bool) != Some(false) && v.is_object());
    let view_numbers = match view {
        Some(v) => {
            let get = |name: &str| {
                number(v, name).ok_or_else(|| error("the camera's `view` needs fullWidth, fullHeight, offsetX, offsetY, width and height"))
            };
            let n = [
                get("fullWidth")?,
                get("fullHeight")?,
                get("offsetX")?,
                get("offsetY")?,
                get("width")?,
                get("height")?,
            ];
            if n[0] <= 0.0 || n[1] <= 0.0 || n[4] <= 0.0 || n[5] <= 0.0 {
                return Err(error("the camera's `view` sizes must be positive"));
            }
            Some(n)
        }
        None => None,
    };
    // At unit distance: the window's left and top edges, its width and height.
    let (mut left, mut top, mut width, mut height, perspective) =
        match camera.get("type").and_then(Value::as_str) {
            Some("PerspectiveCamera") => {
                let fov = number(camera, "fov").unwrap_or(50.0);
                if !(fov > 0.0 && fov < 180.0) {
                    return Err(error(
                        "the camera's `fov` must be between 0 and 180 degrees",
                    ));
                }
                let aspect = number(camera, "aspect").unwrap_or(1.0);
                if aspect <= 0.0 {
                    return Err(error("the camera's `aspect` must be positive"));
                }
                let top = (fov.to_radians() / 2.0).tan() / zoom;
                let (height, width) = (2.0 * top, aspect * 2.0 * top);
                let mut left = -width / 2.0;
                let film_offset = number(camera, "filmOffset").unwrap_or(0.0);
                let film_gauge = number(camera, "filmGauge").unwrap_or(35.0);
                if film_offset != 0.0 && film_gauge > 0.0 {
                    left += film_offset / (film_gauge * aspect.min(1.0));
                }
                (left, top, width, height, true)
            }
            _ => {
                let get = |name: &str, default: f64| number(camera, name).unwrap_or(default);
                let (l, r, t, b) = (
                    get("left", -1.0),
                    get("right", 1.0),
                    get("top", 1.0),
                    get("bottom", -1.0),
                );
                let (dx, dy) = ((r - l) / (2.0 * zoom), (t - b) / (2.0 * zoom));
                let (cx, cy) = ((r + l) / 2.0, (t + b) / 2.0);
                if dx <= 0.0 || dy <= 0.0 {
                    return Err(error(
                        "the camera's left < right and bottom < top are needed",
                    ));
                }
                (cx - dx, cy + dy, 2.0 * dx, 2.0 * dy, false)
            }
        };
    let (image_width, image_height) = if let Some([full_w, full_h, x, y, w, h]) = view_numbers {
        if perspective {
            left += x * width / full_w;
            top -= y * height / full_h;
            width *= w / full_w;
            height *= h / full_h;
        } else {
            let (sw, sh) = (width / full_w, height / full_h);
            left += sw * x;
            top -= sh * y;
            width = sw * w;
            height = sh * h;
        }
        (pixels(full_w), pixels(full_h))
    } else {
        let rows = DEFAULT_ROWS;
        (pixels(f64::from(rows) * width / height), rows)
    };
    let viewport = DVec2::new(width, height);
    let centre = DVec2::new(left + width / 2.0, top - height / 2.0);
    if perspective {
        let square = square_pixels(viewport, (image_width, image_height));
        let size = if square && centre == DVec2::ZERO && zoom == 1.0 && view_numbers.is_none() {
            PerspectiveSize::Fov {
                axis: viewray_camera::FovAxis::Y,
                degrees: number(camera, "fov").unwrap_or(50.0),
                distance: 1.0,
            }
        } else {
            PerspectiveSize::Viewport {
                distance: 1.0,
                viewport,
            }
        };
        Ok((
            ProjectionDocument::Perspective {
                size,
                shift: centre,
            },
            image_width,
            image_height,
            DVec3::ZERO,
        ))
    } else {
        let near = number(camera, "near").unwrap_or(0.1);
        Ok((
            ProjectionDocument::Orthographic {
                viewport,
                lens: None,
            },
            image_width,
            image_height,
            DVec3::new(centre.x, centre.y, -near),
        ))
    }
}
