//! Writing a pbrt-v4 scene file (the conventions are in the module's `mod.rs`).

use std::fmt::Write as _;

use glam::{DVec2, DVec3, Vec3};
use viewray_camera::Projection;
use viewray_scene::Shading;

use crate::common::{self, Parts, Shape, ToolLight, TriangleMesh, material_name, num, num32};
use crate::{ExportError, Format};

fn lacks(what: impl Into<String>) -> ExportError {
    ExportError::new(Format::Pbrt, what)
}

/// Writes `scene` as a pbrt-v4 scene file.
///
/// # Errors
/// An [`ExportError`] for a camera pbrt-v4 cannot express (oblique, fisheye).
pub fn export(scene: &viewray_scene::Scene) -> Result<Vec<u8>, ExportError> {
    let parts = Parts::of(scene);
    let (width, height) = parts.size();
    let camera = parts.camera;
    let frame = camera.frame();
    let mut out = String::from(
        "# Written by `viewray export`: viewray's camera exactly. pbrt's camera space is\n\
         # left-handed, so `Scale -1 1 1` makes camera x = U, y = V, z = -W.\n",
    );
    let look_at = |out: &mut String, look: DVec3, up: DVec3| {
        let e = frame.e();
        let _ = writeln!(
            out,
            "LookAt {} {} {}  {} {} {}  {} {} {}",
            num(e.x),
            num(e.y),
            num(e.z),
            num(look.x),
            num(look.y),
            num(look.z),
            num(up.x),
            num(up.y),
            num(up.z)
        );
    };
    let window = |w: [f64; 4]| {
        format!(
            " \"float screenwindow\" [ {} {} {} {} ]",
            num(w[0]),
            num(w[1]),
            num(w[2]),
            num(w[3])
        )
    };
    let perspective = |d: f64, viewport: DVec2, shift: DVec2| -> String {
        // fov spans the shorter image side; t = tan(fov / 2) is half that side at d = 1.
        let side = if width >= height {
            viewport.y
        } else {
            viewport.x
        };
        let t = side / (2.0 * d);
        let fov = (2.0 * t.atan()).to_degrees();
        let mut s = format!(" \"float fov\" [ {} ]", num(fov));
        if shift != DVec2::ZERO || !common::square_pixels(viewport, (width, height)) {
            let k = d * t;
            s += &window([
                (shift.x - viewport.x / 2.0) / k,
                (shift.x + viewport.x / 2.0) / k,
                (shift.y - viewport.y / 2.0) / k,
                (shift.y + viewport.y / 2.0) / k,
            ]);
        }
        s
    };
    let lens = |r: f64, f: f64| {
        format!(
            " \"float lensradius\" [ {} ] \"float focaldistance\" [ {} ]",
            num(r),
            num(f)
        )
    };
    match camera.projection() {
        Projection::Perspective(p) => {
            out += "Scale -1 1 1\n";
            look_at(&mut out, frame.e() - frame.w(), frame.v());
            let _ = writeln!(
                out,
                "Camera \"perspective\"{}",
                perspective(p.distance, p.viewport, p.shift)
            );
        }
        Projection::ThinLens(t) => {
            if t.is_tilted() {
                return Err(lacks(
                    "has no lens tilt or swing: its perspective camera's thin lens stays \
                     parallel to the film",
                ));
            }
            if !t.iris.is_round() {
                return Err(lacks(
                    "has no aperture blades: its perspective camera's lens is round (only \
                     the realistic camera takes an aperture image)",
                ));
            }
            out += "Scale -1 1 1\n";
            look_at(&mut out, frame.e() - frame.w(), frame.v());
            let _ = writeln!(
                out,
                "Camera \"perspective\"{}{}",
                perspective(t.distance, t.viewport, t.shift),
                lens(t.aperture, t.focus)
            );
        }
        Projection::Orthographic(o) => {
            out += "Scale -1 1 1\n";
            look_at(&mut out, frame.e() - frame.w(), frame.v());
            let (vw, vh) = (o.viewport.x / 2.0, o.viewport.y / 2.0);
            let _ = writeln!(
                out,
                "Camera \"orthographic\"{}{}",
                window([-vw, vw, -vh, vh]),
                o.lens.map_or(String::new(), |l| lens(l.aperture, l.focus))
            );
        }
        Projection::Equirectangular => {
            out += "# The spherical camera looks along camera -x: x = W, y = V, z = -U.\n";
            look_at(&mut out, frame.e() - frame.u(), frame.v());
            out += "Camera \"spherical\" \"string mapping\" \"equirectangular\"\n";
        }
        Projection::Oblique(_) => {
            return Err(lacks(
                "has no oblique camera: its cameras are perspective, orthographic, \
                 realistic and spherical, and it warns that a sheared camera transform \
                 breaks its assumptions",
            ));
        }
        Projection::Fisheye(_) => {
            return Err(lacks(
                "has no equidistant fisheye: its spherical camera maps equirectangular or \
                 equal-area",
            ));
        }
    }
    let _ = writeln!(
        out,
        "Sampler \"independent\" \"integer pixelsamples\" [ {} ]",
        parts.samples
    );
    let _ = writeln!(
        out,
        "Film \"rgb\" \"integer xresolution\" [ {width} ] \"integer yresolution\" [ {height} ]"
    );
    out += "PixelFilter \"box\"\nIntegrator \"path\" \"integer maxdepth\" [ 8 ]\n";
    if parts.shading != Shading::Lit {
        out += "# viewray renders this scene with non-Lit shading; pbrt renders light transport.\n";
    }
    out += "\nWorldBegin\n\n";
    let rgb = |c: Vec3| format!("[ {} {} {} ]", num32(c.x), num32(c.y), num32(c.z));
    for light in parts.lights() {
        match light {
            ToolLight::Point { position, power } => {
                let _ = writeln!(
                    out,
                    "LightSource \"point\" \"point3 from\" [ {} {} {} ] \"rgb I\" {}",
                    num32(position.x),
                    num32(position.y),
                    num32(position.z),
                    rgb(power.rgb())
                );
            }
            ToolLight::Directional { direction, power } => {
                let _ = writeln!(
                    out,
                    "LightSource \"distant\" \"point3 from\" [ 0 0 0 ] \"point3 to\" [ {} {} {} ] \"rgb L\" {}",
                    num32(direction.x),
                    num32(direction.y),
                    num32(direction.z),
                    rgb(power.rgb())
                );
            }
            ToolLight::Ambient { power } => {
                let _ = writeln!(
                    out,
                    "# viewray's ambient light {} has no pbrt counterpart.",
                    rgb(power.viewray())
                );
            }
        }
    }
    if parts.background != Vec3::ZERO {
        let _ = writeln!(
            out,
            "LightSource \"infinite\" \"rgb L\" {}",
            rgb(parts.background)
        );
    }
    out += "\n";
    for material in parts.materials() {
        let _ = writeln!(
            out,
            "MakeNamedMaterial \"{}\" \"string type\" \"diffuse\" \"rgb reflectance\" {}",
            material.name,
            rgb(material.reflectance())
        );
    }
    for shape in &parts.shapes {
        out += "\nAttributeBegin\n";
        let mesh = match shape {
            Shape::Sphere {
                center,
                radius,
                material,
            } => {
                let _ = writeln!(
                    out,
                    "  NamedMaterial \"{}\"\n  Translate {} {} {}\n  Shape \"sphere\" \"float radius\" [ {} ]",
                    material_name(*material as usize),
                    num32(center.x),
                    num32(center.y),
                    num32(center.z),
                    num32(*radius)
                );
                None
            }
            Shape::Box { min, max, material } => Some(TriangleMesh::cuboid(*min, *max, *material)),
            Shape::Plane {
                point,
                normal,
                material,
            } => {
                out += "  # An infinite plane, as a square 2 x 10^4 across.\n";
                Some(TriangleMesh::plane(*point, *normal, *material))
            }
            Shape::Mesh(mesh) => {
                write_mesh(&mut out, mesh);
                None
            }
        };
        if let Some(mesh) = mesh {
            write_mesh(&mut out, &mesh);
        }
        out += "AttributeEnd\n";
    }
    Ok(out.into_bytes())
}

fn write_mesh(out: &mut String, mesh: &TriangleMesh) {
    let _ = writeln!(
        out,
        "  NamedMaterial \"{}\"",
        material_name(mesh.material as usize)
    );
    *out += "  Shape \"trianglemesh\"\n    \"point3 P\" [";
    for p in &mesh.data.positions {
        let _ = write!(out, " {} {} {}", num32(p.x), num32(p.y), num32(p.z));
    }
    *out += " ]\n    \"integer indices\" [";
    for t in &mesh.data.triangles {
        let _ = write!(out, " {} {} {}", t[0], t[1], t[2]);
    }
    *out += " ]\n";
}
