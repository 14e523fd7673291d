//! Mitsuba 3 XML scenes (`mitsuba.load_file`).
//!
//! # Conventions
//!
//! - **Axes.** World space is right-handed, as viewray's. A sensor's local frame has `+z`
//!   forward, `+y` up and `+x` to the image's **left**: `<lookat origin target up>`
//!   builds the columns `left = normalize(up x dir)`, `up' = dir x left`, `dir`. So
//!   `U = -x`, `V = y`, `W = -z`, `e` = the translation, and viewray writes the lookat
//!   `origin = e`, `target = e - W`, `up = V`.
//! - **Field of view.** `fov` (degrees) spans the axis `fov_axis` names: `x` (the
//!   default), `y`, `diagonal`, `smaller`, `larger`, of the film (pixels are square:
//!   `vw / vh = W / H`). Without `fov`, `focal_length` ("50mm", the default) is a 35 mm
//!   equivalent: a diagonal field of view `2 atan(sqrt(36^2 + 24^2) / (2 f))`. viewray
//!   writes `fov` on the `x` axis, `2 atan(vw / (2 d))`.
//! - **Shift.** `principal_point_offset_x = sx / vw`, `principal_point_offset_y =
//!   -sy / vh`: fractions of the film, `y` measured downwards (a positive `y` offset
//!   moves the picture up). The `thinlens` sensor has no principal point.
//! - **Orthographic scale.** The `orthographic` sensor sees `[-1, 1]` across `x` and
//!   `[-1/a, 1/a]` across `y` (`a = W / H`) before `to_world`; a `to_world` scale of
//!   `(sx, sy)` makes `vw = 2 sx`, `vh = 2 sy / a`.
//! - **Thin lens.** `aperture_radius` is `r`, `focus_distance` is `f` (measured along the
//!   view axis, as viewray's).
//! - **Clipping.** Rays start at `near_clip` (default 0.01) along the view axis, not at
//!   the eye: nearer objects are not seen.
//! - **Units of light.** Mitsuba's diffuse BSDF is `albedo / pi`, viewray's Lit shading
//!   `albedo`: a point light of viewray intensity `I` is written as `intensity = pi I`,
//!   a directional one as `irradiance = pi E`; the background is a `constant` emitter.
//!   viewray's ambient light has no counterpart (a comment says so).
//! - **Cannot be expressed**: an oblique camera, an orthographic camera with a lens, a
//!   shifted thin lens, non-square pixels in perspective, the panoramic cameras.
//! - Meshes are written as OBJ files beside the XML (`<stem>-mesh<N>.obj`), one per
//!   material; infinite planes become `rectangle`s 2 x 10^4 across.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

use glam::{DMat3, DMat4, DVec2, DVec3, Vec3};
use viewray_camera::{FovAxis, Perspective, Projection};
use viewray_scene::{
    Aperture, Light, Material, ObjectDocument, PerspectiveSize, ProjectionDocument, SceneDocument,
    Shading,
};

use crate::common::{
    self, Parts, Shape, TriangleMesh, camera_document, look_at, material_name, num, num32,
    square_pixels,
};
use crate::{Export, ExportError, Format, ImportError};

/// Mitsuba's film size when a scene gives none.
const DEFAULT_FILM: (u32, u32) = (768, 576);
/// The `independent` sampler's default sample count.
const DEFAULT_SAMPLES: u32 = 4;

fn lacks(what: impl Into<String>) -> ExportError {
    ExportError::new(Format::Mitsuba, what)
}

/// Writes `scene` as Mitsuba 3 XML, with its meshes as OBJ files named after `stem`.
///
/// # Errors
/// An [`ExportError`] for a camera Mitsuba 3 cannot express.
pub fn export(scene: &viewray_scene::Scene, stem: &str) -> Result<Export, ExportError> {
    let parts = Parts::of(scene);
    let (width, height) = parts.size();
    let mut out = String::new();
    out += "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n";
    out += "<!-- Written by `viewray export`. The sensor is viewray's camera exactly: U = -x, \
            V = y, W = -z of the sensor's frame. -->\n";
    out += "<scene version=\"3.0.0\">\n";
    let _ = writeln!(
        out,
        "    <integrator type=\"path\">\n        <integer name=\"max_depth\" value=\"8\"/>\n    </integrator>"
    );
    if parts.shading != Shading::Lit {
        out += "    <!-- viewray renders this scene with non-Lit shading; Mitsuba renders light \
                transport. -->\n";
    }
    sensor(&mut out, &parts, width, height)?;
    for (index, material) in parts.materials.iter().enumerate() {
        let c = material.color.clamp(Vec3::ZERO, Vec3::ONE);
        let _ = writeln!(
            out,
            "    <bsdf type=\"diffuse\" id=\"{}\">\n        <rgb name=\"reflectance\" value=\"{}, {}, {}\"/>\n    </bsdf>",
            material_name(index),
            num32(c.x),
            num32(c.y),
            num32(c.z)
        );
    }
    lights(&mut out, &parts);
    let mut extra_files = Vec::new();
    for shape in &parts.shapes {
        match shape {
            Shape::Sphere {
                center,
                radius,
                material,
            } => {
                let _ = writeln!(
                    out,
                    "    <shape type=\"sphere\">\n        <point name=\"center\" x=\"{}\" y=\"{}\" z=\"{}\"/>\n        <float name=\"radius\" value=\"{}\"/>\n        <ref id=\"{}\"/>\n    </shape>",
                    num32(center.x),
                    num32(center.y),
                    num32(center.z),
                    num32(*radius),
                    material_name(*material as usize)
                );
            }
            Shape::Box { min, max, material } => {
                let half = (*max - *min) / 2.0;
                let center = (*max + *min) / 2.0;
                let _ = writeln!(
                    out,
                    "    <shape type=\"cube\">\n        <transform name=\"to_world\">\n            <scale x=\"{}\" y=\"{}\" z=\"{}\"/>\n            <translate x=\"{}\" y=\"{}\" z=\"{}\"/>\n        </transform>\n        <ref id=\"{}\"/>\n    </shape>",
                    num32(half.x),
                    num32(half.y),
                    num32(half.z),
                    num32(center.x),
                    num32(center.y),
                    num32(center.z),
                    material_name(*material as usize)
                );
            }
            Shape::Plane {
                point,
                normal,
                material,
            } => {
                let (t1, t2) = common::tangents(*normal);
                let s = common::PLANE_HALF_SIZE;
                let columns = [t1 * s, t2 * s, *normal, *point];
                let mut values = Vec::new();
                for row in 0..3 {
                    for column in columns {
                        values.push(num32(column[row]));
                    }
                }
                values.extend(["0", "0", "0", "1"].map(str::to_owned));
                let _ = writeln!(
                    out,
                    "    <!-- An infinite plane, as a square 2 x 10^4 across. -->\n    <shape type=\"rectangle\">\n        <transform name=\"to_world\">\n            <matrix value=\"{}\"/>\n        </transform>\n        <ref id=\"{}\"/>\n    </shape>",
                    values.join(" "),
                    material_name(*material as usize)
                );
            }
            Shape::Mesh(mesh) => {
                let name = format!("{stem}-mesh{}.obj", extra_files.len());
                extra_files.push((name.clone(), obj(mesh).into_bytes()));
                let _ = writeln!(
                    out,
                    "    <shape type=\"obj\">\n        <string name=\"filename\" value=\"{}\"/>\n        <boolean name=\"face_normals\" value=\"true\"/>\n        <ref id=\"{}\"/>\n    </shape>",
                    xml_escape(&name),
                    material_name(mesh.material as usize)
                );
            }
        }
    }
    out += "</scene>\n";
    Ok(Export {
        main: out.into_bytes(),
        extra_files,
    })
}

fn sensor(out: &mut String, parts: &Parts<'_>, width: u32, height: u32) -> Result<(), ExportError> {
    let camera = parts.camera;
    let (origin, target, up) = look_at(camera.frame());
    let lookat = format!(
        "<lookat origin=\"{}, {}, {}\" target=\"{}, {}, {}\" up=\"{}, {}, {}\"/>",
        num(origin.x),
        num(origin.y),
        num(origin.z),
        num(target.x),
        num(target.y),
        num(target.z),
        num(up.x),
        num(up.y),
        num(up.z)
    );
    let perspective = |p: &Perspective, kind: &str| -> Result<String, ExportError> {
        if !square_pixels(p.viewport, (width, height)) {
            return Err(lacks(format!(
                "has square pixels only: its {kind} sensor's field of view fixes vh = vw H / W, \
                 but this viewport is {} x {} on a {width} x {height} image",
                num(p.viewport.x),
                num(p.viewport.y)
            )));
        }
        let mut s = format!(
            "        <float name=\"fov\" value=\"{}\"/>\n        <string name=\"fov_axis\" value=\"x\"/>\n",
            num(p.fov(FovAxis::X).to_degrees())
        );
        if p.shift != DVec2::ZERO {
            let _ = write!(
                s,
                "        <float name=\"principal_point_offset_x\" value=\"{}\"/>\n        <float name=\"principal_point_offset_y\" value=\"{}\"/>\n",
                num(p.shift.x / p.viewport.x),
                num(-p.shift.y / p.viewport.y)
            );
        }
        Ok(s)
    };
    let (kind, body, transform) = match camera.projection() {
        Projection::Perspective(p) => ("perspective", perspective(p, "perspective")?, lookat),
        Projection::ThinLens(t) => {
            if t.shift != DVec2::ZERO {
                return Err(lacks(
                    "has no shifted thin lens: its thinlens sensor has no principal point offset",
                ));
            }
            let mut body = perspective(&t.pinhole(), "thinlens")?;
            let _ = write!(
                body,
                "        <float name=\"aperture_radius\" value=\"{}\"/>\n        <float name=\"focus_distance\" value=\"{}\"/>\n",
                num(t.aperture),
                num(t.focus)
            );
            ("thinlens", body, lookat)
        }
        Projection::Orthographic(o) => {
            if o.lens.is_some() {
                return Err(lacks(
                    "has no orthographic camera with a lens: its orthographic sensor is a pinhole",
                ));
            }
            let aspect = f64::from(width) / f64::from(height);
            let transform = format!(
                "<scale x=\"{}\" y=\"{}\" z=\"1\"/>\n            {lookat}",
                num(o.viewport.x / 2.0),
                num(o.viewport.y * aspect / 2.0)
            );
            ("orthographic", String::new(), transform)
        }
        Projection::Oblique(_) => {
            return Err(lacks(
                "has no oblique camera: its sensors are perspective, thinlens and orthographic",
            ));
        }
        Projection::Equirectangular | Projection::Fisheye(_) => {
            return Err(lacks(
                "has no panoramic camera: its sensors are perspective, thinlens and orthographic",
            ));
        }
    };
    let _ = writeln!(
        out,
        "    <sensor type=\"{kind}\">\n{body}        <transform name=\"to_world\">\n            {transform}\n        </transform>\n        <sampler type=\"independent\">\n            <integer name=\"sample_count\" value=\"{}\"/>\n        </sampler>\n        <film type=\"hdrfilm\">\n            <integer name=\"width\" value=\"{width}\"/>\n            <integer name=\"height\" value=\"{height}\"/>\n            <rfilter type=\"box\"/>\n        </film>\n    </sensor>",
        parts.samples
    );
    Ok(())
}

fn lights(out: &mut String, parts: &Parts<'_>) {
    let pi = std::f32::consts::PI;
    let rgb = |c: Vec3| format!("{}, {}, {}", num32(c.x), num32(c.y), num32(c.z));
    for light in parts.lights {
        match *light {
            Light::Point {
                position,
                intensity,
            } => {
                let _ = writeln!(
                    out,
                    "    <emitter type=\"point\">\n        <point name=\"position\" x=\"{}\" y=\"{}\" z=\"{}\"/>\n        <rgb name=\"intensity\" value=\"{}\"/>\n    </emitter>",
                    num32(position.x),
                    num32(position.y),
                    num32(position.z),
                    rgb(intensity * pi)
                );
            }
            Light::Directional {
                direction,
                intensity,
            } => {
                let _ = writeln!(
                    out,
                    "    <emitter type=\"directional\">\n        <vector name=\"direction\" x=\"{}\" y=\"{}\" z=\"{}\"/>\n        <rgb name=\"irradiance\" value=\"{}\"/>\n    </emitter>",
                    num32(direction.x),
                    num32(direction.y),
                    num32(direction.z),
                    rgb(intensity * pi)
                );
            }
            Light::Ambient { intensity } => {
                let _ = writeln!(
                    out,
                    "    <!-- viewray's ambient light ({}) has no Mitsuba counterpart. -->",
                    rgb(intensity)
                );
            }
        }
    }
    if parts.background != Vec3::ZERO {
        let _ = writeln!(
            out,
            "    <emitter type=\"constant\">\n        <rgb name=\"radiance\" value=\"{}\"/>\n    </emitter>",
            rgb(parts.background)
        );
    }
}

/// A mesh as OBJ text, positions with the fewest digits that read back exactly.
fn obj(mesh: &TriangleMesh) -> String {
    let mut out = String::from("# Written by `viewray export`.\n");
    for p in &mesh.positions {
        let _ = writeln!(out, "v {} {} {}", num32(p.x), num32(p.y), num32(p.z));
    }
    for t in &mesh.triangles {
        let _ = writeln!(out, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    out
}

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
}

// ---------------------------------------------------------------------------------------
// Import
// ---------------------------------------------------------------------------------------

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

struct Reader<'a, 'input> {
    path: &'a Path,
    document: &'a roxmltree::Document<'input>,
    defaults: HashMap<String, String>,
    ids: HashMap<String, roxmltree::Node<'a, 'input>>,
    comments: Vec<String>,
    materials: Vec<(String, Material)>,
    material_ids: HashMap<roxmltree::NodeId, String>,
}

type Node<'a, 'input> = roxmltree::Node<'a, 'input>;

impl<'a, 'input> Reader<'a, 'input> {
    fn line(&self, node: Node<'_, '_>) -> u32 {
        self.document.text_pos_at(node.range().start).row
    }

    fn error(&self, node: Node<'_, '_>, message: impl Into<String>) -> ImportError {
        let pos = self.document.text_pos_at(node.range().start);
        ImportError::new(
            self.path,
            Some((pos.row as usize, pos.col as usize)),
            message,
        )
    }

    /// An attribute, with `$name` replaced by its `<default>`.
    fn attribute<'s>(&'s self, node: Node<'s, 's>, name: &str) -> Result<&'s str, ImportError> {
        let value = node.attribute(name).ok_or_else(|| {
            self.error(
                node,
                format!("<{}> needs a `{name}` attribute", node.tag_name().name()),
            )
        })?;
        Ok(self.substitute(value))
    }

    fn substitute<'s>(&'s self, value: &'s str) -> &'s str {
        match value.strip_prefix('$') {
            Some(name) => self.defaults.get(name).map_or(value, String::as_str),
            None => value,
        }
    }

    /// The child property element named `name` (`<float name="fov" ..>`).
    fn property(&self, node: Node<'a, 'input>, name: &str) -> Option<Node<'a, 'input>> {
        node.children()
            .filter(Node::is_element)
            .find(|c| c.attribute("name") == Some(name))
    }

    fn float(&self, node: Node<'_, '_>) -> Result<f64, ImportError> {
        let text = self.attribute(node, "value")?;
        parse_number(text)
            .ok_or_else(|| self.error(node, format!("expected a number, found `{text}`")))
    }

    fn float_property(
        &self,
        parent: Node<'a, 'input>,
        name: &str,
    ) -> Result<Option<f64>, ImportError> {
        self.property(parent, name)
            .map(|n| self.float(n))
            .transpose()
    }

    fn integer_property(
        &self,
        parent: Node<'a, 'input>,
        name: &str,
    ) -> Result<Option<u32>, ImportError> {
        match self.property(parent, name) {
            None => Ok(None),
            Some(node) => {
                let text = self.attribute(node, "value")?;
                text.trim()
                    .parse::<u32>()
                    .ok()
                    .filter(|&v| v > 0)
                    .map(Some)
                    .ok_or_else(|| {
                        self.error(
                            node,
                            format!("expected a positive whole number, found `{text}`"),
                        )
                    })
            }
        }
    }

    fn string_property(
        &self,
        parent: Node<'a, 'input>,
        name: &str,
    ) -> Result<Option<String>, ImportError> {
        self.property(parent, name)
            .map(|n| self.attribute(n, "value").map(str::to_owned))
            .transpose()
    }

    /// `x`, `y`, `z` attributes or `value="x, y, z"` (one number for all three).
    fn vector(&self, node: Node<'_, '_>, default: f64) -> Result<DVec3, ImportError> {
        if let Some(value) = node.attribute("value") {
            return self.triple(node, self.substitute(value));
        }
        let mut v = [default; 3];
        for (slot, name) in v.iter_mut().zip(["x", "y", "z"]) {
            if let Some(text) = node.attribute(name) {
                let text = self.substitute(text);
                *slot = parse_number(text).ok_or_else(|| {
                    self.error(
                        node,
                        format!("expected a number for `{name}`, found `{text}`"),
                    )
                })?;
            }
        }
        Ok(DVec3::from_array(v))
    }

    fn triple(&self, node: Node<'_, '_>, text: &str) -> Result<DVec3, ImportError> {
        let numbers = numbers(text)
            .ok_or_else(|| self.error(node, format!("expected numbers, found `{text}`")))?;
        match numbers.as_slice() {
            [x] => Ok(DVec3::splat(*x)),
            [x, y, z] => Ok(DVec3::new(*x, *y, *z)),
            _ => Err(self.error(
                node,
                format!("expected one or three numbers, found {}", numbers.len()),
            )),
        }
    }

    /// An RGB colour from `<rgb value="r, g, b">` or `<float value="g">`.
    fn color(&self, node: Node<'_, '_>) -> Result<Option<Vec3>, ImportError> {
        match node.tag_name().name() {
            "rgb" | "float" => {
                let text = self.attribute(node, "value")?;
                Ok(Some(self.triple(node, text)?.as_vec3()))
            }
            _ => Ok(None),
        }
    }

    /// The transform of `<transform name="to_world">` under `parent`; identity if absent.
    fn to_world(&self, parent: Node<'_, '_>) -> Result<DMat4, ImportError> {
        let Some(node) = parent
            .children()
            .find(|c| c.has_tag_name("transform") && c.attribute("name") == Some("to_world"))
        else {
            return Ok(DMat4::IDENTITY);
        };
        let mut m = DMat4::IDENTITY;
        for op in node.children().filter(Node::is_element) {
            let step = match op.tag_name().name() {
                "translate" => DMat4::from_translation(self.vector(op, 0.0)?),
                "scale" => DMat4::from_scale(self.vector(op, 1.0)?),
                "rotate" => {
                    let axis = self.vector(op, 0.0)?;
                    let angle = parse_number(self.attribute(op, "angle")?)
                        .ok_or_else(|| self.error(op, "expected a number for `angle`"))?;
                    let axis = axis
                        .try_normalize()
                        .ok_or_else(|| self.error(op, "the rotation axis is zero"))?;
                    DMat4::from_axis_angle(axis, angle.to_radians())
                }
                "matrix" => {
                    let text = self.attribute(op, "value")?;
                    let values = numbers(text).ok_or_else(|| {
                        self.error(op, format!("expected numbers, found `{text}`"))
                    })?;
                    match values.len() {
                        16 => DMat4::from_cols_array(&values.try_into().expect("16")).transpose(),
                        9 => DMat4::from_mat3(
                            DMat3::from_cols_array(&values.try_into().expect("9")).transpose(),
                        ),
                        n => {
                            return Err(self.error(
                                op,
                                format!("a matrix needs 16 (or 9) numbers, found {n}"),
                            ));
                        }
                    }
                }
                "lookat" => {
                    let origin = self.triple(op, self.attribute(op, "origin")?)?;
                    let target = self.triple(op, self.attribute(op, "target")?)?;
                    let up = match op.attribute("up") {
                        Some(up) => self.triple(op, self.substitute(up))?,
                        None => DVec3::Y,
                    };
                    let dir = (target - origin)
                        .try_normalize()
                        .ok_or_else(|| self.error(op, "lookat: the target is the origin"))?;
                    let left = up
                        .cross(dir)
                        .try_normalize()
                        .ok_or_else(|| self.error(op, "lookat: up is parallel to the view"))?;
                    let new_up = dir.cross(left);
                    DMat4::from_cols(
                        left.extend(0.0),
                        new_up.extend(0.0),
                        dir.extend(0.0),
                        origin.extend(1.0),
                    )
                }
                other => {
                    return Err(self.error(
                        op,
                        format!(
                            "unknown transform step <{other}>, expected translate, rotate, \
                             scale, matrix or lookat"
                        ),
                    ));
                }
            };
            m = step * m;
        }
        if !m.is_finite() {
            return Err(self.error(node, "the transform is not finite"));
        }
        Ok(m)
    }

    fn sensor(
        &mut self,
        sensor: Node<'a, 'input>,
    ) -> Result<(viewray_scene::CameraDocument, u32, u32, u32), ImportError> {
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
        let pi = std::f32::consts::PI;
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
                    intensity: intensity / pi,
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
                    intensity: irradiance / pi,
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
                    let corners: Vec<DVec3> = (0..8)
                        .map(|i| {
                            DVec3::new(
                                if i & 1 == 0 { -1.0 } else { 1.0 },
                                if i & 2 == 0 { -1.0 } else { 1.0 },
                                if i & 4 == 0 { -1.0 } else { 1.0 },
                            )
                        })
                        .collect();
                    let faces = TriangleMesh::cuboid(Vec3::splat(-1.0), Vec3::ONE, 0)
                        .triangles
                        .iter()
                        .map(|t| t.map(|i| i as usize))
                        .collect::<Vec<_>>();
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

/// A number as Mitsuba writes one.
fn parse_number(text: &str) -> Option<f64> {
    text.trim().parse::<f64>().ok().filter(|x| x.is_finite())
}

/// Numbers separated by commas and/or whitespace.
fn numbers(text: &str) -> Option<Vec<f64>> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(parse_number)
        .collect()
}
