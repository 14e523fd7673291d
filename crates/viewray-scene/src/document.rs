//! A scene file as plain values, written out as RON: what code that makes scene files
//! (an importer of another tool's scene) fills in, so it never spells RON itself.
//!
//! Every number is written with the fewest digits that read back to the same value, so
//! `SceneDocument::to_ron` loaded back with [`crate::SceneLoader`] gives exactly the camera
//! that the document describes.

use std::fmt::Write as _;

use glam::{DVec2, DVec3, Vec3};
use viewray_camera::{FovAxis, Lens, SensorFit};

use crate::{Light, Material, Shading};

/// A whole scene file: image settings, camera, materials, lights and objects.
#[derive(Clone, Debug, PartialEq)]
pub struct SceneDocument {
    /// Lines written as `//` comments at the top of the file (where it came from, what
    /// could not be carried over).
    pub comments: Vec<String>,
    /// `W`, columns.
    pub width: u32,
    /// `H`, rows.
    pub height: u32,
    /// Samples per pixel.
    pub samples: u32,
    /// The camera.
    pub camera: CameraDocument,
    /// The colour of rays that hit nothing (linear RGB).
    pub background: Vec3,
    /// How hits are coloured.
    pub shading: Shading,
    /// Named materials, in the order written.
    pub materials: Vec<(String, Material)>,
    /// The lights.
    pub lights: Vec<Light>,
    /// The objects.
    pub objects: Vec<ObjectDocument>,
}

/// `camera: (eye: .., view: .., up: .., projection: ..)`.
#[derive(Clone, Debug, PartialEq)]
pub struct CameraDocument {
    /// `e`.
    pub eye: DVec3,
    /// The direction the camera looks along (`-w`).
    pub view: DVec3,
    /// The up vector (need not be perpendicular to `view`).
    pub up: DVec3,
    /// The projection.
    pub projection: ProjectionDocument,
}

/// A projection as a scene file spells it.
#[derive(Clone, Debug, PartialEq)]
pub enum ProjectionDocument {
    /// `Perspective(..)`.
    Perspective {
        /// How big the viewport is.
        size: PerspectiveSize,
        /// `(sx, sy)`, on the image plane at distance `d`.
        shift: DVec2,
    },
    /// `ThinLens(..)`.
    ThinLens {
        /// How big the viewport is.
        size: PerspectiveSize,
        /// `(sx, sy)`, on the image plane at distance `d`.
        shift: DVec2,
        /// The lens radius, or an f-number.
        aperture: Aperture,
        /// The distance of the plane in focus.
        focus: f64,
    },
    /// `Orthographic(viewport: .., aperture: .., focus: ..)`.
    Orthographic {
        /// `(vw, vh)`.
        viewport: DVec2,
        /// An optional thin lens.
        lens: Option<Lens>,
    },
    /// `Oblique(viewport: .., ratio: .., angle: ..)`.
    Oblique {
        /// `(vw, vh)`.
        viewport: DVec2,
        /// `L`.
        ratio: f64,
        /// `phi`, degrees.
        angle_degrees: f64,
    },
    /// `Equirectangular`.
    Equirectangular,
    /// `Fisheye(fov: ..)`.
    Fisheye {
        /// `F`, degrees.
        fov_degrees: f64,
    },
}

/// How a perspective viewport is sized in a scene file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PerspectiveSize {
    /// `distance: d, viewport: (vw, vh)`.
    Viewport {
        /// `d`.
        distance: f64,
        /// `(vw, vh)`.
        viewport: DVec2,
    },
    /// `fov_<axis>: degrees` (with `distance` when it is not 1).
    Fov {
        /// The extent the angle spans.
        axis: FovAxis,
        /// The full angle, degrees.
        degrees: f64,
        /// `d`.
        distance: f64,
    },
    /// `focal_length: mm, sensor: (w, h), fit: ..`.
    FocalLength {
        /// Millimetres.
        millimetres: f64,
        /// `(width, height)`, millimetres.
        sensor: DVec2,
        /// Which side the sensor spans.
        fit: SensorFit,
    },
}

/// A thin lens's size: `aperture: r` or `f_number: N` (with a focal length).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Aperture {
    /// The lens radius in scene units.
    Radius(f64),
    /// The f-number; needs [`PerspectiveSize::FocalLength`].
    FNumber(f64),
}

/// An object of a scene file.
#[derive(Clone, Debug, PartialEq)]
pub enum ObjectDocument {
    /// `Sphere(center, radius, material)`.
    Sphere {
        /// The centre.
        center: Vec3,
        /// The radius.
        radius: f32,
        /// A material name.
        material: Option<String>,
    },
    /// `Plane(point, normal, material)`.
    Plane {
        /// A point on the plane.
        point: Vec3,
        /// Its normal.
        normal: Vec3,
        /// A material name.
        material: Option<String>,
    },
    /// `Triangle(a, b, c, material)`.
    Triangle {
        /// The corners.
        corners: [Vec3; 3],
        /// A material name.
        material: Option<String>,
    },
    /// `Box(min, max, material)`.
    Box {
        /// The smallest corner.
        min: Vec3,
        /// The largest corner.
        max: Vec3,
        /// A material name.
        material: Option<String>,
    },
    /// `Mesh(path, material, transform)`.
    Mesh {
        /// The OBJ file, relative to the scene file (or absolute).
        path: String,
        /// A material name (none: the OBJ's own MTL colours).
        material: Option<String>,
        /// Translation.
        translate: Vec3,
        /// Rotations about x, then y, then z, degrees.
        rotate_degrees: Vec3,
        /// Scale per axis.
        scale: Vec3,
    },
}

impl SceneDocument {
    /// The scene file's text.
    pub fn to_ron(&self) -> String {
        let mut out = String::new();
        for line in &self.comments {
            for part in line.lines() {
                let _ = writeln!(out, "// {part}");
            }
        }
        out += "(\n";
        let _ = writeln!(
            out,
            "    image: (width: {}, height: {}, samples: {}),",
            self.width, self.height, self.samples
        );
        let c = &self.camera;
        out += "    camera: (\n";
        let _ = writeln!(out, "        eye: {},", d3(c.eye));
        let _ = writeln!(out, "        view: {},", d3(c.view));
        let _ = writeln!(out, "        up: {},", d3(c.up));
        let _ = writeln!(out, "        projection: {},", projection(&c.projection));
        out += "    ),\n";
        let _ = writeln!(out, "    background: {},", f3(self.background));
        let shading = match self.shading {
            Shading::Flat => "Flat",
            Shading::Normals => "Normals",
            Shading::Depth => "Depth",
            Shading::Lit => "Lit",
        };
        let _ = writeln!(out, "    shading: {shading},");
        if !self.materials.is_empty() {
            out += "    materials: {\n";
            for (name, m) in &self.materials {
                let _ = writeln!(out, "        {}: {},", string(name), material(m));
            }
            out += "    },\n";
        }
        if !self.lights.is_empty() {
            out += "    lights: [\n";
            for light in &self.lights {
                let _ = writeln!(out, "        {},", self::light(light));
            }
            out += "    ],\n";
        }
        if !self.objects.is_empty() {
            out += "    objects: [\n";
            for object in &self.objects {
                let _ = writeln!(out, "        {},", self::object(object));
            }
            out += "    ],\n";
        }
        out += ")\n";
        out
    }
}

/// The shortest decimal that reads back as the same `f64` (Rust's `{:?}`), always with a
/// decimal point or an exponent so RON reads it as a float.
fn d(x: f64) -> String {
    format!("{x:?}")
}

/// As [`d`] for an `f32`: the shortest decimal that reads back as the same `f32`.
fn f(x: f32) -> String {
    format!("{x:?}")
}

fn d2(v: DVec2) -> String {
    format!("({}, {})", d(v.x), d(v.y))
}

fn d3(v: DVec3) -> String {
    format!("({}, {}, {})", d(v.x), d(v.y), d(v.z))
}

fn f3(v: Vec3) -> String {
    format!("({}, {}, {})", f(v.x), f(v.y), f(v.z))
}

fn string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out += "\\\"",
            '\\' => out += "\\\\",
            c if c.is_control() => {
                let _ = write!(out, "\\u{{{:x}}}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn size(size: &PerspectiveSize) -> String {
    match *size {
        PerspectiveSize::Viewport { distance, viewport } => {
            format!("distance: {}, viewport: {}", d(distance), d2(viewport))
        }
        PerspectiveSize::Fov {
            axis,
            degrees,
            distance,
        } => {
            let fov = format!("fov_{}: {}", axis.name(), d(degrees));
            if distance == 1.0 {
                fov
            } else {
                format!("distance: {}, {fov}", d(distance))
            }
        }
        PerspectiveSize::FocalLength {
            millimetres,
            sensor,
            fit,
        } => format!(
            "focal_length: {}, sensor: {}, fit: {}",
            d(millimetres),
            d2(sensor),
            fit.name()
        ),
    }
}

fn shift(shift: DVec2) -> String {
    if shift == DVec2::ZERO {
        String::new()
    } else {
        format!(", shift: {}", d2(shift))
    }
}

fn projection(p: &ProjectionDocument) -> String {
    match p {
        ProjectionDocument::Perspective { size: s, shift: sh } => {
            format!("Perspective({}{})", size(s), shift(*sh))
        }
        ProjectionDocument::ThinLens {
            size: s,
            shift: sh,
            aperture,
            focus,
        } => {
            let aperture = match aperture {
                Aperture::Radius(r) => format!("aperture: {}", d(*r)),
                Aperture::FNumber(n) => format!("f_number: {}", d(*n)),
            };
            format!(
                "ThinLens({}{}, {aperture}, focus: {})",
                size(s),
                shift(*sh),
                d(*focus)
            )
        }
        ProjectionDocument::Orthographic { viewport, lens } => match lens {
            None => format!("Orthographic(viewport: {})", d2(*viewport)),
            Some(lens) => format!(
                "Orthographic(viewport: {}, aperture: {}, focus: {})",
                d2(*viewport),
                d(lens.aperture),
                d(lens.focus)
            ),
        },
        ProjectionDocument::Oblique {
            viewport,
            ratio,
            angle_degrees,
        } => format!(
            "Oblique(viewport: {}, ratio: {}, angle: {})",
            d2(*viewport),
            d(*ratio),
            d(*angle_degrees)
        ),
        ProjectionDocument::Equirectangular => "Equirectangular".to_owned(),
        ProjectionDocument::Fisheye { fov_degrees } => format!("Fisheye(fov: {})", d(*fov_degrees)),
    }
}

fn material(m: &Material) -> String {
    let mut out = format!("(color: {}", f3(m.color));
    if m.specular != Vec3::ZERO {
        let _ = write!(
            out,
            ", specular: {}, shininess: {}",
            f3(m.specular),
            f(m.shininess)
        );
    }
    if m.mirror != 0.0 {
        let _ = write!(out, ", mirror: {}", f(m.mirror));
    }
    if let Some(grid) = &m.grid {
        let _ = write!(
            out,
            ", grid: (spacing: {}, width: {}, color: {})",
            f(grid.spacing),
            f(grid.line_width),
            f3(grid.color)
        );
    }
    out + ")"
}

fn light(light: &Light) -> String {
    match light {
        Light::Point {
            position,
            intensity,
        } => format!(
            "Point(position: {}, intensity: {})",
            f3(*position),
            f3(*intensity)
        ),
        Light::Directional {
            direction,
            intensity,
        } => format!(
            "Directional(direction: {}, intensity: {})",
            f3(*direction),
            f3(*intensity)
        ),
        Light::Ambient { intensity } => format!("Ambient(intensity: {})", f3(*intensity)),
    }
}

fn material_field(material: &Option<String>) -> String {
    match material {
        Some(name) => format!(", material: {}", string(name)),
        None => String::new(),
    }
}

fn object(object: &ObjectDocument) -> String {
    match object {
        ObjectDocument::Sphere {
            center,
            radius,
            material,
        } => format!(
            "Sphere(center: {}, radius: {}{})",
            f3(*center),
            f(*radius),
            material_field(material)
        ),
        ObjectDocument::Plane {
            point,
            normal,
            material,
        } => format!(
            "Plane(point: {}, normal: {}{})",
            f3(*point),
            f3(*normal),
            material_field(material)
        ),
        ObjectDocument::Triangle { corners, material } => format!(
            "Triangle(a: {}, b: {}, c: {}{})",
            f3(corners[0]),
            f3(corners[1]),
            f3(corners[2]),
            material_field(material)
        ),
        ObjectDocument::Box { min, max, material } => format!(
            "Box(min: {}, max: {}{})",
            f3(*min),
            f3(*max),
            material_field(material)
        ),
        ObjectDocument::Mesh {
            path,
            material,
            translate,
            rotate_degrees,
            scale,
        } => format!(
            "Mesh(path: {}{}, transform: (translate: {}, rotate: {}, scale: {}))",
            string(path),
            material_field(material),
            f3(*translate),
            f3(*rotate_degrees),
            f3(*scale)
        ),
    }
}
