//! Writing Mitsuba 3 XML (the conventions are in the module's `mod.rs`).

use std::fmt::Write as _;

use glam::{DVec2, Vec3};
use viewray_camera::{FovAxis, Perspective, Projection};
use viewray_scene::{Shading, obj_text};

use crate::common::{
    self, Parts, Shape, ToolLight, look_at, material_name, num, num32, square_pixels,
};
use crate::{Export, ExportError, Format};

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
    for material in parts.materials() {
        let c = material.reflectance();
        let _ = writeln!(
            out,
            "    <bsdf type=\"diffuse\" id=\"{}\">\n        <rgb name=\"reflectance\" value=\"{}, {}, {}\"/>\n    </bsdf>",
            material.name,
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
                let obj = obj_text(&mesh.data, "Written by `viewray export`.");
                extra_files.push((name.clone(), obj.into_bytes()));
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
            if t.is_tilted() {
                return Err(lacks(
                    "has no lens tilt or swing: its thinlens sensor's lens stays parallel to \
                     the film",
                ));
            }
            if !t.iris.is_round() {
                return Err(lacks(
                    "has no aperture blades: its thinlens sensor's aperture is round",
                ));
            }
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
    let rgb = |c: Vec3| format!("{}, {}, {}", num32(c.x), num32(c.y), num32(c.z));
    for light in parts.lights() {
        match light {
            ToolLight::Point { position, power } => {
                let _ = writeln!(
                    out,
                    "    <emitter type=\"point\">\n        <point name=\"position\" x=\"{}\" y=\"{}\" z=\"{}\"/>\n        <rgb name=\"intensity\" value=\"{}\"/>\n    </emitter>",
                    num32(position.x),
                    num32(position.y),
                    num32(position.z),
                    rgb(power.rgb())
                );
            }
            ToolLight::Directional { direction, power } => {
                let _ = writeln!(
                    out,
                    "    <emitter type=\"directional\">\n        <vector name=\"direction\" x=\"{}\" y=\"{}\" z=\"{}\"/>\n        <rgb name=\"irradiance\" value=\"{}\"/>\n    </emitter>",
                    num32(direction.x),
                    num32(direction.y),
                    num32(direction.z),
                    rgb(power.rgb())
                );
            }
            ToolLight::Ambient { power } => {
                let _ = writeln!(
                    out,
                    "    <!-- viewray's ambient light ({}) has no Mitsuba counterpart. -->",
                    rgb(power.viewray())
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

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
        .replace('\'', "&apos;")
}
