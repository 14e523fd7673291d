//! Reading Mitsuba 3 XML (the conventions are in the module's `mod.rs`): the sensor, then
//! the scene's emitters, materials and shapes, each in world space.

use std::collections::HashMap;
use std::path::Path;

use glam::{DMat3, DMat4, DVec2, DVec3, Vec3};
use viewray_camera::{FovAxis, Perspective};
use viewray_scene::{
    Aperture, CameraDocument, Light, Material, ObjectDocument, PerspectiveSize, ProjectionDocument,
    SceneDocument, Shading,
};

use super::xml::Node;
use crate::ImportError;
use crate::common::{TriangleMesh, camera_document, viewray_intensity};

/// Mitsuba's film size when a scene gives none.
const DEFAULT_FILM: (u32, u32) = (768, 576);
/// The `independent` sampler's default sample count.
const DEFAULT_SAMPLES: u32 = 4;

/// Reads a Mitsuba 3 XML scene: its sensor (perspective, thinlens or orthographic), film
/// size, sample count, and what viewray can hold of the rest (spheres, cubes,
/// rectangles, OBJ meshes, diffuse colours, point, directional and constant emitters).
/// What cannot be carried over is named in a comment of the document.
///
/// # Errors
/// An [`ImportError`] with the line and column for malformed XML, a missing or
/// unsupported sensor, or a value of the wrong form.
pub fn import(text: &str, path: &Path) -> Result<SceneDocument, ImportError> {
    let options = roxmltree::ParsingOptions {
        allow_dtd: false,
        nodes_limit: 1 << 20,
        ..roxmltree::ParsingOptions::default()
    };
    let document = roxmltree::Document::parse_with_options(text, options).map_err(|e| {
        let pos = e.pos();
        ImportError::new(path, Some((pos.row as usize, pos.col as usize)), {
            // roxmltree's message ends with the position, which the error already has.
            let message = e.to_string();
            let suffix = format!(" at {}:{}", pos.row, pos.col);
            format!(
                "not well-formed XML: {}",
                message.strip_suffix(&suffix).unwrap_or(&message)
            )
        })
    })?;
    let root = document.root_element();
    let mut reader = Reader {
        path,
        document: &document,
        defaults: HashMap::new(),
        ids: HashMap::new(),
        comments: Vec::new(),
        materials: Vec::new(),
        material_ids: HashMap::new(),
    };
    if root.tag_name().name() != "scene" {
        return Err(reader.error(
            root,
            format!(
                "expected a Mitsuba <scene> element, found <{}>",
                root.tag_name().name()
            ),
        ));
    }
    for node in root.descendants().filter(roxmltree::Node::is_element) {
        if let Some(id) = node.attribute("id") {
            reader.ids.insert(id.to_owned(), node);
        }
    }
    for node in root.children().filter(|n| n.has_tag_name("default")) {
        let name = reader.attribute(node, "name")?;
        let value = reader.attribute(node, "value")?;
        reader.defaults.insert(name.to_owned(), value.to_owned());
    }
    let sensors: Vec<_> = root
        .children()
        .filter(|n| n.has_tag_name("sensor"))
        .collect();
    let Some(&sensor) = sensors.first() else {
        return Err(reader.error(
            root,
            "the scene has no <sensor>: there is no camera to import",
        ));
    };
    if sensors.len() > 1 {
        reader.comments.push(format!(
            "{} sensors: the first one is imported.",
            sensors.len()
        ));
    }
    let (camera, width, height, samples) = reader.sensor(sensor)?;

    let mut lights = Vec::new();
    let mut background = Vec3::ZERO;
    let mut objects = Vec::new();
    for node in root.children().filter(roxmltree::Node::is_element) {
        match node.tag_name().name() {
            "emitter" => reader.emitter(node, &mut lights, &mut background)?,
            "shape" => reader.shape(node, &mut objects)?,
            "bsdf" => {
                reader.bsdf_material(node)?;
            }
            "sensor" | "default" | "integrator" | "texture" | "spectrum" | "rfilter"
            | "sampler" | "film" => {}
            other => {
                let line = reader.line(node);
                reader
                    .comments
                    .push(format!("line {line}: <{other}> skipped"));
            }
        }
    }
    let mut comments = vec![format!(
        "Imported from {} (Mitsuba 3 XML) by `viewray import`.",
        path.display()
    )];
    comments.append(&mut reader.comments);
    Ok(SceneDocument {
        comments,
        width,
        height,
        samples,
        camera,
        background,
        shading: Shading::Lit,
        materials: reader.materials,
        lights,
        objects,
    })
}

/// A Mitsuba document being read, and what has been read of it.
pub(super) struct Reader<'a, 'input> {
    /// The file, for errors and relative mesh paths.
    pub(super) path: &'a Path,
    pub(super) document: &'a roxmltree::Document<'input>,
    /// `<default name value>`: what `$name` stands for.
    pub(super) defaults: HashMap<String, String>,
    /// Every element with an `id`, for `<ref>`.
    ids: HashMap<String, Node<'a, 'input>>,
    comments: Vec<String>,
    materials: Vec<(String, Material)>,
    /// The material made of each `<bsdf>` read so far.
    material_ids: HashMap<roxmltree::NodeId, String>,
}

impl<'a, 'input> Reader<'a, 'input> {
    fn sensor(
        &mut self,
        sensor: Node<'a, 'input>,
    ) -> Result<(CameraDocument, u32, u32, u32), ImportError> {
        let kind = self.attribute(sensor, "type")?.to_owned();
        let film = sensor.children().find(|c| c.has_tag_name("film"));
        let (mut width, mut height) = DEFAULT_FILM;
        if let Some(film) = film {
            if let Some(w) = self.integer_property(film, "width")? {
                width = w;
            }
            if let Some(h) = self.integer_property(film, "height")? {
                height = h;
            }
        }
        let samples = match sensor.children().find(|c| c.has_tag_name("sampler")) {
            Some(sampler) => self
                .integer_property(sampler, "sample_count")?
                .unwrap_or(DEFAULT_SAMPLES),
            None => DEFAULT_SAMPLES,
        };
        let aspect = f64::from(width) / f64::from(height);
        let to_world = self.to_world(sensor)?;
        // Mitsuba's sensor frame: +x is the image's left, +y up, +z forward.
        let columns = DMat4::from_cols(
            -to_world.x_axis,
            to_world.y_axis,
            -to_world.z_axis,
            to_world.w_axis,
        );
        let projection = match kind.as_str() {
            "perspective" | "thinlens" => {
                let (size, viewport) = self.field_of_view(sensor, aspect)?;
                let ppo = DVec2::new(
                    self.float_property(sensor, "principal_point_offset_x")?
                        .unwrap_or(0.0),
                    self.float_property(sensor, "principal_point_offset_y")?
                        .unwrap_or(0.0),
                );
                let shift = DVec2::new(ppo.x * viewport.x, -ppo.y * viewport.y);
                if kind == "perspective" {
                    ProjectionDocument::Perspective { size, shift }
                } else {
                    let aperture =
                        self.float_property(sensor, "aperture_radius")?
                            .ok_or_else(|| {
                                self.error(sensor, "a thinlens sensor needs `aperture_radius`")
                            })?;
                    let focus = self
                        .float_property(sensor, "focus_distance")?
                        .unwrap_or(0.0);
                    if shift != DVec2::ZERO {
                        self.comments.push(
                            "Mitsuba's thinlens sensor ignores principal_point_offset: dropped."
                                .to_owned(),
                        );
                    }
                    ProjectionDocument::ThinLens {
                        size,
                        shift: DVec2::ZERO,
                        aperture: Aperture::Radius(aperture),
                        focus,
                    }
                }
            }
            "orthographic" => {
                let sx = to_world.x_axis.truncate().length();
                let sy = to_world.y_axis.truncate().length();
                ProjectionDocument::Orthographic {
                    viewport: DVec2::new(2.0 * sx, 2.0 * sy / aspect),
                    lens: None,
                }
            }
            other => {
                return Err(self.error(
                    sensor,
                    format!(
                        "unsupported sensor type `{other}`, expected perspective, thinlens or \
                         orthographic"
                    ),
                ));
            }
        };
        let camera = camera_document(columns, projection).map_err(|m| self.error(sensor, m))?;
        Ok((camera, width, height, samples))
    }

    /// The field of view of a perspective or thinlens sensor, and its viewport at d = 1.
    fn field_of_view(
        &mut self,
        sensor: Node<'a, 'input>,
        aspect: f64,
    ) -> Result<(PerspectiveSize, DVec2), ImportError> {
        let fov = self.float_property(sensor, "fov")?;
        let focal = self.string_property(sensor, "focal_length")?;
        let (axis, degrees) = match (fov, focal) {
            (Some(_), Some(_)) => {
                return Err(self.error(sensor, "give either `fov` or `focal_length`, not both"));
            }
            (Some(fov), None) => {
                let axis = match self
                    .string_property(sensor, "fov_axis")?
                    .unwrap_or_else(|| "x".to_owned())
                    .to_ascii_lowercase()
                    .as_str()
                {
                    "x" => FovAxis::X,
                    "y" => FovAxis::Y,
                    "diagonal" => FovAxis::Diagonal,
                    "smaller" => FovAxis::Smaller,
                    "larger" => FovAxis::Larger,
                    other => {
                        return Err(self.error(
                            sensor,
                            format!(
                                "unknown fov_axis `{other}`, expected x, y, diagonal, smaller \
                                 or larger"
                            ),
                        ));
                    }
                };
                (axis, fov)
            }
            (None, focal) => {
                let text = focal.unwrap_or_else(|| "50mm".to_owned());
                let millimetres = text
                    .trim()
                    .strip_suffix("mm")
                    .and_then(|f| f.trim().parse::<f64>().ok())
                    .filter(|f| *f > 0.0 && f.is_finite())
                    .ok_or_else(|| {
                        self.error(
                            sensor,
                            format!("expected a focal length like `50mm`, found `{text}`"),
                        )
                    })?;
                let degrees = (2.0 * (36f64.hypot(24.0) / (2.0 * millimetres)).atan()).to_degrees();
                self.comments.push(format!(
                    "Mitsuba's focal_length {text} is a 35 mm equivalent: a diagonal field of view."
                ));
                (FovAxis::Diagonal, degrees)
            }
        };
        let p = Perspective::from_fov(axis, degrees.to_radians(), aspect).map_err(|e| {
            self.error(
                sensor,
                format!("the sensor's field of view of {degrees} degrees: {e}"),
            )
        })?;
        Ok((
            PerspectiveSize::Fov {
                axis,
                degrees,
                distance: 1.0,
            },
            p.viewport,
        ))
    }

    fn emitter(
        &mut self,
        node: Node<'a, 'input>,
        lights: &mut Vec<Light>,
        background: &mut Vec3,
    ) -> Result<(), ImportError> {
        let kind = self.attribute(node, "type")?.to_owned();
        let color_of = |reader: &Self, name: &str| -> Result<Option<Vec3>, ImportError> {
            match reader.property(node, name) {
                Some(p) => reader.color(p),
                None => Ok(None),
            }
        };
        match kind.as_str() {
            "point" => {
                let position = match self.property(node, "position") {
                    Some(p) => self.vector(p, 0.0)?,
                    None => self.to_world(node)?.w_axis.truncate(),
                };
                let intensity = color_of(self, "intensity")?.unwrap_or(Vec3::ONE);
                lights.push(Light::Point {
                    position: position.as_vec3(),
                    intensity: viewray_intensity(intensity),
                });
            }
            "directional" => {
                let direction = match self.property(node, "direction") {
                    Some(p) => self.vector(p, 0.0)?,
                    None => self.to_world(node)?.z_axis.truncate(),
                };
                let direction = direction
                    .try_normalize()
                    .ok_or_else(|| self.error(node, "the light's direction is zero"))?;
                let irradiance = color_of(self, "irradiance")?.unwrap_or(Vec3::ONE);
                lights.push(Light::Directional {
                    direction: direction.as_vec3(),
                    intensity: viewray_intensity(irradiance),
                });
            }
            "constant" => {
                *background = color_of(self, "radiance")?.unwrap_or(Vec3::ONE);
            }
            other => {
                let line = self.line(node);
                self.comments
                    .push(format!("line {line}: emitter `{other}` skipped"));
            }
        }
        Ok(())
    }

    /// The material a shape refers to (by `<ref>` or a nested `<bsdf>`), by name.
    fn shape_material(&mut self, shape: Node<'a, 'input>) -> Result<Option<String>, ImportError> {
        for child in shape.children().filter(Node::is_element) {
            match child.tag_name().name() {
                "ref" => {
                    let id = self.attribute(child, "id")?.to_owned();
                    let Some(&target) = self.ids.get(&id) else {
                        return Err(self.error(child, format!("no element has id `{id}`")));
                    };
                    if target.has_tag_name("bsdf") {
                        return self.bsdf_material(target).map(Some);
                    }
                }
                "bsdf" => return self.bsdf_material(child).map(Some),
                _ => {}
            }
        }
        Ok(None)
    }

    /// The viewray material of a `<bsdf>`: its diffuse colour (through `twosided` and
    /// the usual colour parameters), named by its id.
    fn bsdf_material(&mut self, bsdf: Node<'a, 'input>) -> Result<String, ImportError> {
        if let Some(name) = self.material_ids.get(&bsdf.id()) {
            return Ok(name.clone());
        }
        let mut node = bsdf;
        while let Some(inner) = node.children().find(|c| c.has_tag_name("bsdf")) {
            node = inner;
        }
        let mut color = None;
        for name in ["reflectance", "base_color", "diffuse_reflectance"] {
            if let Some(p) = self.property(node, name) {
                color = self.color(p)?;
                if color.is_some() {
                    break;
                }
            }
        }
        let kind = node.attribute("type").unwrap_or("?");
        let color = color.unwrap_or_else(|| {
            let line = self.line(node);
            self.comments.push(format!(
                "line {line}: bsdf `{kind}` has no RGB colour viewray reads: grey 0.5"
            ));
            Vec3::splat(0.5)
        });
        let name = bsdf
            .attribute("id")
            .map_or_else(|| format!("bsdf_{}", self.materials.len()), str::to_owned);
        self.materials.push((
            name.clone(),
            Material {
                color: color.max(Vec3::ZERO),
                ..Material::default()
            },
        ));
        self.material_ids.insert(bsdf.id(), name.clone());
        Ok(name)
    }

    fn shape(
        &mut self,
        node: Node<'a, 'input>,
        objects: &mut Vec<ObjectDocument>,
    ) -> Result<(), ImportError> {
        let kind = self.attribute(node, "type")?.to_owned();
        let material = self.shape_material(node)?;
        let to_world = self.to_world(node)?;
        if node.children().any(|c| c.has_tag_name("emitter")) {
            let line = self.line(node);
            self.comments.push(format!(
                "line {line}: the area emitter of a `{kind}` skipped"
            ));
        }
        let triangles =
            |corners: &[DVec3], faces: &[[usize; 3]], objects: &mut Vec<ObjectDocument>| {
                for f in faces {
                    let corners = f.map(|i| to_world.transform_point3(corners[i]).as_vec3());
                    if (corners[1] - corners[0]).cross(corners[2] - corners[0]) != Vec3::ZERO {
                        objects.push(ObjectDocument::Triangle {
                            corners,
                            material: material.clone(),
                        });
                    }
                }
            };
        match kind.as_str() {
            "sphere" => {
                let center = match self.property(node, "center") {
                    Some(p) => self.vector(p, 0.0)?,
                    None => DVec3::ZERO,
                };
                let radius = self.float_property(node, "radius")?.unwrap_or(1.0);
                // A sphere under a uniform scale and a translation stays a sphere.
                let linear = DMat3::from_mat4(to_world);
                let scale = linear.x_axis.length();
                let uniform = [linear.y_axis, linear.z_axis]
                    .iter()
                    .all(|a| (a.length() - scale).abs() <= 1e-9 * scale);
                if !uniform {
                    let line = self.line(node);
                    self.comments.push(format!(
                        "line {line}: a sphere scaled unevenly is an ellipsoid: skipped"
                    ));
                    return Ok(());
                }
                objects.push(ObjectDocument::Sphere {
                    center: to_world.transform_point3(center).as_vec3(),
                    radius: (radius * scale) as f32,
                    material,
                });
            }
            "cube" => {
                let linear = DMat3::from_mat4(to_world);
                let axis_aligned = linear.x_axis.y == 0.0
                    && linear.x_axis.z == 0.0
                    && linear.y_axis.x == 0.0
                    && linear.y_axis.z == 0.0
                    && linear.z_axis.x == 0.0
                    && linear.z_axis.y == 0.0;
                if axis_aligned {
                    let a = to_world.transform_point3(DVec3::splat(-1.0)).as_vec3();
                    let b = to_world.transform_point3(DVec3::splat(1.0)).as_vec3();
                    objects.push(ObjectDocument::Box {
                        min: a.min(b),
                        max: a.max(b),
                        material,
                    });
                } else {
                    let cube = TriangleMesh::cuboid(Vec3::splat(-1.0), Vec3::ONE, 0).data;
                    let corners: Vec<DVec3> = cube.positions.iter().map(|p| p.as_dvec3()).collect();
                    let faces: Vec<[usize; 3]> = cube
                        .triangles
                        .iter()
                        .map(|t| t.map(|i| i as usize))
                        .collect();
                    triangles(&corners, &faces, objects);
                }
            }
            "rectangle" => {
                let corners = [
                    DVec3::new(-1.0, -1.0, 0.0),
                    DVec3::new(1.0, -1.0, 0.0),
                    DVec3::new(1.0, 1.0, 0.0),
                    DVec3::new(-1.0, 1.0, 0.0),
                ];
                triangles(&corners, &[[0, 1, 2], [0, 2, 3]], objects);
            }
            "obj" => {
                let filename = self
                    .string_property(node, "filename")?
                    .ok_or_else(|| self.error(node, "an obj shape needs a `filename`"))?;
                let file = self.path.parent().unwrap_or(Path::new("")).join(&filename);
                let file = std::path::absolute(&file).unwrap_or(file);
                match decompose(&to_world) {
                    Some((translate, rotate_degrees, scale)) => {
                        objects.push(ObjectDocument::Mesh {
                            path: file.display().to_string(),
                            material,
                            translate,
                            rotate_degrees,
                            scale,
                        })
                    }
                    None => {
                        let line = self.line(node);
                        self.comments.push(format!(
                            "line {line}: mesh `{filename}` skipped: its transform shears it"
                        ));
                    }
                }
            }
            other => {
                let line = self.line(node);
                self.comments.push(format!(
                    "line {line}: shape `{other}` skipped (viewray reads sphere, cube, \
                     rectangle and obj)"
                ));
            }
        }
        Ok(())
    }
}

/// `translate`, rotations about x then y then z (degrees), and per-axis `scale` whose
/// product is `m`, when `m` is such a product (no shear).
fn decompose(m: &DMat4) -> Option<(Vec3, Vec3, Vec3)> {
    let linear = DMat3::from_mat4(*m);
    let scale = DVec3::new(
        linear.x_axis.length(),
        linear.y_axis.length(),
        linear.z_axis.length(),
    );
    if scale.min_element() == 0.0 {
        return None;
    }
    let mut rotation = DMat3::from_cols(
        linear.x_axis / scale.x,
        linear.y_axis / scale.y,
        linear.z_axis / scale.z,
    );
    let mut scale = scale;
    if rotation.determinant() < 0.0 {
        scale.x = -scale.x;
        rotation.x_axis = -rotation.x_axis;
    }
    let orthonormal = (rotation.transpose() * rotation).abs_diff_eq(DMat3::IDENTITY, 1e-6);
    if !orthonormal {
        return None;
    }
    let (z, y, x) = glam::DQuat::from_mat3(&rotation).to_euler(glam::EulerRot::ZYX);
    Some((
        m.w_axis.truncate().as_vec3(),
        Vec3::new(
            x.to_degrees() as f32,
            y.to_degrees() as f32,
            z.to_degrees() as f32,
        ),
        scale.as_vec3(),
    ))
}
