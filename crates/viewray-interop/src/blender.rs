//! Blender: a Python script that builds the scene (`blender -b -P OUT.py`, or `python
//! OUT.py` with the `bpy` module), rendered by Cycles.
//!
//! # Conventions
//!
//! - **Axes.** Right-handed; a camera object looks down its local `-z` with `+x` right and
//!   `+y` up: viewray's `U`, `V`, `W`, so `matrix_world` has the columns `U`, `V`, `W`,
//!   `e`. (Blender's world is `+z` up, but a matrix carries any frame exactly.)
//! - **Field of view.** A `lens` (focal length, mm) in front of a sensor
//!   (`sensor_width`, `sensor_height`, mm) fitted as `sensor_fit` says: `AUTO` fits
//!   `sensor_width` to the *larger* image side, `HORIZONTAL` the width, `VERTICAL`
//!   `sensor_height` to the height. The fitted side spans `2 atan(sensor / (2 lens))`.
//!   viewray writes `HORIZONTAL` with a 36 mm sensor and `lens = 36 d / vw` (a lens below
//!   Blender's 1 mm minimum becomes 1 mm with a wider sensor).
//! - **Shift.** `shift_x` and `shift_y` are both in units of the *fitted* side (here the
//!   width): `shift_x = sx / vw`, `shift_y = sy / vw`.
//! - **Pixels.** Non-square pixels are `pixel_aspect_x` / `pixel_aspect_y` (each at
//!   least 1); the resolution is set at 100 %.
//! - **Orthographic.** `ortho_scale` spans the fitted side: `ortho_scale = vw`.
//! - **Thin lens.** `dof.focus_distance = f`; Cycles turns `aperture_fstop` into the lens
//!   radius `lens / (2 N)` (mm to metres: `r = lens / 1000 / (2 N)`), or `1 / (2 N)` for
//!   an orthographic camera: viewray writes `N = lens / 1000 / (2 r)` or `1 / (2 r)`.
//! - **Blades.** `dof.aperture_blades = N` and `dof.aperture_rotation` (radians, in
//!   `[-pi, pi]`) are viewray's blades and rotation exactly: Cycles' polygon
//!   (`regular_polygon_sample`) is inscribed in the lens's circle, its corners at
//!   `rotation + (2k + 1) pi / N` from the camera's `+x` toward `+y`, as viewray's. Blender
//!   takes at most 16 blades.
//! - **Panorama** (Cycles): `EQUIRECTANGULAR` over the whole sphere, and
//!   `FISHEYE_EQUIDISTANT` with `fisheye_fov = F`. Cycles maps the fisheye's image circle
//!   onto the whole frame, so it is a circle only in a square image: viewray's fisheye
//!   on a non-square image cannot be expressed.
//! - **Units of light**: a sun's strength is irradiance (`pi E`), a point light's power
//!   `P` gives the intensity `P / (4 pi)` (`P = 4 pi^2 I`); the world colour is the
//!   background; viewray's ambient light has no counterpart.
//! - **Cannot be expressed**: an oblique camera, a fisheye on a non-square image, a
//!   fisheye narrower than Blender's 10 degrees, a tilted or swung lens (Cycles' lens
//!   stays parallel to its sensor), more than 16 blades.

use std::f64::consts::PI;
use std::fmt::Write as _;

use glam::{DVec2, Vec3};
use viewray_camera::{Iris, Projection};
use viewray_scene::Shading;

use crate::common::{Parts, Shape, ToolLight, TriangleMesh, num, num32};
use crate::{ExportError, Format};

/// Blender's default sensor width, mm.
const SENSOR_WIDTH: f64 = 36.0;

/// The most aperture blades Blender takes (`aperture_blades` runs 0 to 16).
const MAX_BLADES: u32 = 16;

fn lacks(what: impl Into<String>) -> ExportError {
    ExportError::new(Format::Blender, what)
}

fn v3(v: Vec3) -> String {
    format!("({}, {}, {})", num32(v.x), num32(v.y), num32(v.z))
}

/// Writes `scene` as a Blender Python script that builds it in an empty scene: camera
/// (active, with the render resolution at 100 %), objects, materials, lights, samples.
///
/// # Errors
/// An [`ExportError`] for a camera Blender cannot express.
pub fn export(scene: &viewray_scene::Scene) -> Result<Vec<u8>, ExportError> {
    let parts = Parts::of(scene);
    let (width, height) = parts.size();
    let camera = parts.camera;
    let frame = camera.frame();
    let mut out = String::from(
        "# Written by `viewray export`: run `blender -b -P this.py`, or `python this.py` with\n\
         # the bpy module. The camera is viewray's exactly: its matrix_world has the columns\n\
         # U, V, W and e, and it looks down its local -z.\n\
         import bpy\nfrom mathutils import Matrix, Vector\n\n\
         scene = bpy.context.scene\n\
         for obj in list(bpy.data.objects):\n    bpy.data.objects.remove(obj, do_unlink=True)\n\
         scene.render.engine = 'CYCLES'\n",
    );
    let _ = writeln!(
        out,
        "scene.render.resolution_x = {width}\nscene.render.resolution_y = {height}\nscene.render.resolution_percentage = 100\nscene.cycles.samples = {}",
        parts.samples
    );
    let mut pixel_aspect = (1.0, 1.0);
    out += "\ncam = bpy.data.cameras.new('viewray camera')\n";
    out += "cam.clip_start = 1e-4\ncam.clip_end = 1e6\n";
    let perspective = |out: &mut String, d: f64, viewport: DVec2, shift: DVec2| -> f64 {
        let mut lens = SENSOR_WIDTH * d / viewport.x;
        let mut sensor = SENSOR_WIDTH;
        if lens < 1.0 {
            lens = 1.0;
            sensor = viewport.x / d;
        }
        let _ = writeln!(
            out,
            "cam.type = 'PERSP'\ncam.sensor_fit = 'HORIZONTAL'\ncam.sensor_width = {}\ncam.lens = {}\ncam.shift_x = {}\ncam.shift_y = {}",
            num(sensor),
            num(lens),
            num(shift.x / viewport.x),
            num(shift.y / viewport.x)
        );
        lens
    };
    let dof = |out: &mut String, f_number: f64, focus: f64, iris: Iris| {
        let _ = writeln!(
            out,
            "cam.dof.use_dof = True\ncam.dof.focus_distance = {}\ncam.dof.aperture_fstop = {}\ncam.dof.aperture_blades = {}\ncam.dof.aperture_rotation = {}\ncam.dof.aperture_ratio = 1.0",
            num(focus),
            num(f_number),
            iris.blades,
            num(iris.rotation)
        );
    };
    match camera.projection() {
        Projection::Perspective(p) => {
            perspective(&mut out, p.distance, p.viewport, p.shift);
            pixel_aspect = aspect_of(p.viewport, width, height);
        }
        Projection::ThinLens(t) => {
            if t.is_tilted() {
                return Err(lacks(
                    "has no lens tilt or swing: Cycles' thin lens stays parallel to its sensor",
                ));
            }
            if t.iris.blades > MAX_BLADES {
                return Err(lacks(format!(
                    "takes at most {MAX_BLADES} aperture blades (aperture_blades), not {}",
                    t.iris.blades
                )));
            }
            let lens = perspective(&mut out, t.distance, t.viewport, t.shift);
            dof(
                &mut out,
                lens / 1000.0 / (2.0 * t.aperture),
                t.focus,
                t.iris,
            );
            pixel_aspect = aspect_of(t.viewport, width, height);
        }
        Projection::Orthographic(o) => {
            let _ = writeln!(
                out,
                "cam.type = 'ORTHO'\ncam.sensor_fit = 'HORIZONTAL'\ncam.ortho_scale = {}",
                num(o.viewport.x)
            );
            if let Some(lens) = o.lens {
                dof(
                    &mut out,
                    1.0 / (2.0 * lens.aperture),
                    lens.focus,
                    Iris::ROUND,
                );
            }
            pixel_aspect = aspect_of(o.viewport, width, height);
        }
        Projection::Equirectangular => {
            out += "cam.type = 'PANO'\ncam.panorama_type = 'EQUIRECTANGULAR'\n";
            let _ = writeln!(
                out,
                "cam.latitude_min = {}\ncam.latitude_max = {}\ncam.longitude_min = {}\ncam.longitude_max = {}",
                num(-PI / 2.0),
                num(PI / 2.0),
                num(-PI),
                num(PI)
            );
        }
        Projection::Fisheye(f) => {
            if width != height {
                return Err(lacks(format!(
                    "has no fisheye on a non-square image: Cycles stretches the image circle \
                     over the whole {width} x {height} frame"
                )));
            }
            if f.fov < 10f64.to_radians() {
                return Err(lacks(
                    "has no fisheye narrower than 10 degrees (fisheye_fov)",
                ));
            }
            let _ = writeln!(
                out,
                "cam.type = 'PANO'\ncam.panorama_type = 'FISHEYE_EQUIDISTANT'\ncam.fisheye_fov = {}",
                num(f.fov)
            );
        }
        Projection::Oblique(_) => {
            return Err(lacks(
                "has no oblique camera: its cameras are perspective, orthographic and \
                 panoramic",
            ));
        }
    }
    let _ = writeln!(
        out,
        "scene.render.pixel_aspect_x = {}\nscene.render.pixel_aspect_y = {}",
        num(pixel_aspect.0),
        num(pixel_aspect.1)
    );
    let (u, v, w, e) = (frame.u(), frame.v(), frame.w(), frame.e());
    let _ = writeln!(
        out,
        "camera = bpy.data.objects.new('viewray camera', cam)\ncamera.matrix_world = Matrix((\n    ({}, {}, {}, {}),\n    ({}, {}, {}, {}),\n    ({}, {}, {}, {}),\n    (0.0, 0.0, 0.0, 1.0),\n))\nscene.collection.objects.link(camera)\nscene.camera = camera",
        num(u.x),
        num(v.x),
        num(w.x),
        num(e.x),
        num(u.y),
        num(v.y),
        num(w.y),
        num(e.y),
        num(u.z),
        num(v.z),
        num(w.z),
        num(e.z),
    );
    if parts.shading != Shading::Lit {
        out +=
            "# viewray renders this scene with non-Lit shading; Cycles renders light transport.\n";
    }
    out += "\nworld = bpy.data.worlds.new('viewray background')\nworld.use_nodes = True\n";
    let _ = writeln!(
        out,
        "world.node_tree.nodes['Background'].inputs['Color'].default_value = ({}, {}, {}, 1.0)\nscene.world = world",
        num32(parts.background.x),
        num32(parts.background.y),
        num32(parts.background.z)
    );
    out += "\nmaterials = []\n";
    for material in parts.materials() {
        let c = material.color;
        let _ = writeln!(
            out,
            "m = bpy.data.materials.new('{}')\nm.diffuse_color = ({}, {}, {}, 1.0)\nm.use_nodes = True\nbsdf = m.node_tree.nodes.get('Principled BSDF')\nif bsdf is not None:\n    bsdf.inputs['Base Color'].default_value = ({}, {}, {}, 1.0)\n    bsdf.inputs['Roughness'].default_value = 1.0\nmaterials.append(m)",
            material.name,
            num32(c.x),
            num32(c.y),
            num32(c.z),
            num32(c.x),
            num32(c.y),
            num32(c.z)
        );
    }
    out += "\n\ndef add_mesh(name, vertices, faces, material):\n    \
            mesh = bpy.data.meshes.new(name)\n    \
            mesh.from_pydata(vertices, [], faces)\n    \
            mesh.materials.append(materials[material])\n    \
            obj = bpy.data.objects.new(name, mesh)\n    \
            scene.collection.objects.link(obj)\n\n";
    for (index, shape) in parts.shapes.iter().enumerate() {
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
        let _ = write!(out, "add_mesh('object_{index}', [");
        for p in &mesh.data.positions {
            let _ = write!(out, "{}, ", v3(*p));
        }
        out += "], [";
        for t in &mesh.data.triangles {
            let _ = write!(out, "({}, {}, {}), ", t[0], t[1], t[2]);
        }
        let _ = writeln!(out, "], {})", mesh.material);
    }
    let pi = std::f32::consts::PI;
    for (index, light) in parts.lights().enumerate() {
        match light {
            ToolLight::Point { position, power } => {
                let _ = writeln!(
                    out,
                    "light = bpy.data.lights.new('light_{index}', 'POINT')\nlight.energy = {}\nlight.color = {}\nlight.shadow_soft_size = 0.0\nobj = bpy.data.objects.new('light_{index}', light)\nobj.location = {}\nscene.collection.objects.link(obj)",
                    num32(4.0 * pi * pi * power.peak()),
                    v3(power.color().unwrap_or(Vec3::ONE)),
                    v3(position)
                );
            }
            ToolLight::Directional { direction, power } => {
                let _ = writeln!(
                    out,
                    "light = bpy.data.lights.new('light_{index}', 'SUN')\nlight.energy = {}\nlight.color = {}\nlight.angle = 0.0\nobj = bpy.data.objects.new('light_{index}', light)\nobj.rotation_mode = 'QUATERNION'\nobj.rotation_quaternion = Vector((0.0, 0.0, -1.0)).rotation_difference(Vector({}))\nscene.collection.objects.link(obj)",
                    num32(power.strength()),
                    v3(power.color().unwrap_or(Vec3::ONE)),
                    v3(direction)
                );
            }
            ToolLight::Ambient { power } => {
                let _ = writeln!(
                    out,
                    "# viewray's ambient light {} has no Blender counterpart.",
                    v3(power.viewray())
                );
            }
        }
    }
    Ok(out.into_bytes())
}

/// Blender's `(pixel_aspect_x, pixel_aspect_y)` for a viewport of `vw x vh` on a
/// `W x H` image: a pixel is `vw / W` wide and `vh / H` tall, and each is at least 1.
fn aspect_of(viewport: DVec2, width: u32, height: u32) -> (f64, f64) {
    let x = viewport.x / f64::from(width);
    let y = viewport.y / f64::from(height);
    if crate::common::square_pixels(viewport, (width, height)) {
        (1.0, 1.0)
    } else if x >= y {
        (x / y, 1.0)
    } else {
        (1.0, y / x)
    }
}
