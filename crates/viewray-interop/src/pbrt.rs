//! pbrt-v4 scene files.
//!
//! # Conventions
//!
//! - **Handedness.** pbrt's camera space is left-handed: `+x` right in the image, `+y`
//!   up, `+z` forward. `LookAt pos look up` builds `right = up x dir`, which in a
//!   right-handed world is the image's *left*: a right-handed scene seen through a plain
//!   `LookAt` comes out mirrored. viewray writes `Scale -1 1 1` before `LookAt e, e - W,
//!   V`, so that camera `x = U`, `y = V`, `z = -W` (what Blender's pbrt exporter does).
//!   On import, a perspective or orthographic camera whose frame is right-handed in the
//!   world (a plain `LookAt`) is made exact by mirroring the whole scene in `x`, and a
//!   comment says so.
//! - **Field of view.** `fov` (degrees, default 90) spans the *shorter* image side: the
//!   screen window is `[-a, a] x [-1, 1]` for `a = W / H > 1`, else `[-1, 1] x
//!   [-1/a, 1/a]`, and a screen point `(x, y)` is the camera-space point
//!   `(x t, y t, 1)` with `t = tan(fov / 2)`.
//! - **Shift and non-square pixels.** An explicit `screenwindow [x0 x1 y0 y1]` is the
//!   viewport at distance 1 in units of `t`: viewray writes
//!   `[(sx - vw/2)/(d t), (sx + vw/2)/(d t), (sy - vh/2)/(d t), (sy + vh/2)/(d t)]` when
//!   there is a shift or the pixels are not square.
//! - **Orthographic.** The screen window is the viewport itself, in scene units (default
//!   `[-a, a] x [-1, 1]`); viewray always writes it. pbrt's orthographic camera takes a
//!   lens too (`lensradius`, `focaldistance`), as viewray's does.
//! - **Thin lens.** `lensradius` is `r`, `focaldistance` is `f` (along the view axis).
//! - **Panorama.** `Camera "spherical" "string mapping" "equirectangular"`: the image's
//!   centre looks along camera `-x`, its top along `+y`, its left edge along `+x`; viewray
//!   writes `LookAt e, e - U, V` (no mirroring) so that `x = W`, `y = V`, `z = -U`.
//!   pbrt-v4 has no equidistant fisheye.
//! - **Units of light**: as Mitsuba's (`I` and `L` are written times pi); the background
//!   is an `infinite` light; viewray's ambient light has no counterpart.
//! - **Cannot be expressed**: an oblique camera (pbrt warns that a camera transform with
//!   shear or scale breaks its assumptions), the fisheye.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::Path;

use glam::{DMat4, DVec2, DVec3, Vec3};
use viewray_camera::Projection;
use viewray_scene::{
    Aperture, Light, Material, ObjectDocument, PerspectiveSize, ProjectionDocument, SceneDocument,
    Shading,
};

use crate::common::{self, Parts, Shape, TriangleMesh, camera_document, material_name, num, num32};
use crate::{ExportError, Format, ImportError};

/// pbrt-v4's film size when a scene gives none.
const DEFAULT_FILM: (u32, u32) = (1280, 720);
/// pbrt-v4's default `pixelsamples`.
const DEFAULT_SAMPLES: u32 = 16;

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
        let e = frame.e;
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
            look_at(&mut out, frame.e - frame.w, frame.v);
            let _ = writeln!(
                out,
                "Camera \"perspective\"{}",
                perspective(p.distance, p.viewport, p.shift)
            );
        }
        Projection::ThinLens(t) => {
            out += "Scale -1 1 1\n";
            look_at(&mut out, frame.e - frame.w, frame.v);
            let _ = writeln!(
                out,
                "Camera \"perspective\"{}{}",
                perspective(t.distance, t.viewport, t.shift),
                lens(t.aperture, t.focus)
            );
        }
        Projection::Orthographic(o) => {
            out += "Scale -1 1 1\n";
            look_at(&mut out, frame.e - frame.w, frame.v);
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
            look_at(&mut out, frame.e - frame.u, frame.v);
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
    let pi = std::f32::consts::PI;
    for light in parts.lights {
        match *light {
            Light::Point {
                position,
                intensity,
            } => {
                let _ = writeln!(
                    out,
                    "LightSource \"point\" \"point3 from\" [ {} {} {} ] \"rgb I\" {}",
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
                    "LightSource \"distant\" \"point3 from\" [ 0 0 0 ] \"point3 to\" [ {} {} {} ] \"rgb L\" {}",
                    num32(direction.x),
                    num32(direction.y),
                    num32(direction.z),
                    rgb(intensity * pi)
                );
            }
            Light::Ambient { intensity } => {
                let _ = writeln!(
                    out,
                    "# viewray's ambient light {} has no pbrt counterpart.",
                    rgb(intensity)
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
    for (index, material) in parts.materials.iter().enumerate() {
        let _ = writeln!(
            out,
            "MakeNamedMaterial \"{}\" \"string type\" \"diffuse\" \"rgb reflectance\" {}",
            material_name(index),
            rgb(material.color.clamp(Vec3::ZERO, Vec3::ONE))
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
    for p in &mesh.positions {
        let _ = write!(out, " {} {} {}", num32(p.x), num32(p.y), num32(p.z));
    }
    *out += " ]\n    \"integer indices\" [";
    for t in &mesh.triangles {
        let _ = write!(out, " {} {} {}", t[0], t[1], t[2]);
    }
    *out += " ]\n";
}

// ---------------------------------------------------------------------------------------
// Import
// ---------------------------------------------------------------------------------------

/// A token of a pbrt file, with its 1-based line and column.
#[derive(Clone, Debug, PartialEq)]
enum Token<'a> {
    Word(&'a str),
    Text(&'a str),
    Number(f64),
    Open,
    Close,
}

/// A token and its 1-based line and column.
type Located<'a> = (Token<'a>, (usize, usize));

struct Tokens<'a> {
    text: &'a str,
    offset: usize,
    line: usize,
    line_start: usize,
}

impl<'a> Tokens<'a> {
    fn position(&self) -> (usize, usize) {
        let column = self.text[self.line_start..self.offset.min(self.text.len())]
            .chars()
            .count()
            + 1;
        (self.line, column)
    }

    /// The next token and where it starts; `None` at the end.
    fn next(&mut self, path: &Path) -> Result<Option<Located<'a>>, ImportError> {
        let bytes = self.text.as_bytes();
        loop {
            match bytes.get(self.offset) {
                None => return Ok(None),
                Some(b'\n') => {
                    self.offset += 1;
                    self.line += 1;
                    self.line_start = self.offset;
                }
                Some(b' ' | b'\t' | b'\r') => self.offset += 1,
                Some(b'#') => {
                    while let Some(&b) = bytes.get(self.offset) {
                        if b == b'\n' {
                            break;
                        }
                        self.offset += 1;
                    }
                }
                Some(_) => break,
            }
        }
        let at = self.position();
        let start = self.offset;
        let token = match bytes[start] {
            b'[' => {
                self.offset += 1;
                Token::Open
            }
            b']' => {
                self.offset += 1;
                Token::Close
            }
            b'"' => {
                let end = self.text[start + 1..]
                    .find(['"', '\n'])
                    .map(|i| start + 1 + i)
                    .filter(|&i| bytes[i] == b'"')
                    .ok_or_else(|| ImportError::new(path, Some(at), "unterminated string"))?;
                self.offset = end + 1;
                Token::Text(&self.text[start + 1..end])
            }
            _ => {
                let end = self.text[start..]
                    .find(|c: char| c.is_whitespace() || matches!(c, '[' | ']' | '"' | '#'))
                    .map_or(self.text.len(), |i| start + i);
                self.offset = end;
                let word = &self.text[start..end];
                match word.parse::<f64>() {
                    Ok(x) if x.is_finite() => Token::Number(x),
                    Ok(_) => {
                        return Err(ImportError::new(
                            path,
                            Some(at),
                            format!("`{word}` is not a finite number"),
                        ));
                    }
                    Err(_) if word.chars().next().is_some_and(|c| c.is_ascii_alphabetic()) => {
                        Token::Word(word)
                    }
                    Err(_) => {
                        return Err(ImportError::new(
                            path,
                            Some(at),
                            format!(
                                "unexpected `{word}`, expected a directive, a string, a number or [ ]"
                            ),
                        ));
                    }
                }
            }
        };
        Ok(Some((token, at)))
    }
}

/// A parameter's values.
#[derive(Clone, Debug)]
enum Values {
    Numbers(Vec<f64>),
    Strings(Vec<String>),
}

/// `"type name" value` parameters of a directive.
#[derive(Default)]
struct Params {
    list: Vec<(String, String, Values, (usize, usize))>,
}

impl Params {
    fn numbers(&self, name: &str) -> Option<(&[f64], (usize, usize))> {
        self.list.iter().find_map(|(_, n, v, at)| match v {
            Values::Numbers(x) if n == name => Some((x.as_slice(), *at)),
            _ => None,
        })
    }

    fn string(&self, name: &str) -> Option<&str> {
        self.list.iter().find_map(|(_, n, v, _)| match v {
            Values::Strings(s) if n == name => s.first().map(String::as_str),
            _ => None,
        })
    }
}

struct Parser<'a> {
    tokens: Tokens<'a>,
    peeked: Option<Located<'a>>,
    path: &'a Path,
}

impl<'a> Parser<'a> {
    fn peek(&mut self) -> Result<Option<&Located<'a>>, ImportError> {
        if self.peeked.is_none() {
            self.peeked = self.tokens.next(self.path)?;
        }
        Ok(self.peeked.as_ref())
    }

    fn next(&mut self) -> Result<Option<Located<'a>>, ImportError> {
        match self.peeked.take() {
            Some(t) => Ok(Some(t)),
            None => self.tokens.next(self.path),
        }
    }

    fn error(&self, at: (usize, usize), message: impl Into<String>) -> ImportError {
        ImportError::new(self.path, Some(at), message)
    }

    /// `n` numbers, bare or in brackets.
    fn numbers(
        &mut self,
        n: usize,
        directive: &str,
        at: (usize, usize),
    ) -> Result<Vec<f64>, ImportError> {
        let bracketed = matches!(self.peek()?, Some((Token::Open, _)));
        if bracketed {
            self.next()?;
        }
        let mut out = Vec::with_capacity(n);
        for _ in 0..n {
            match self.next()? {
                Some((Token::Number(x), _)) => out.push(x),
                Some((_, at)) => {
                    return Err(self.error(at, format!("{directive} takes {n} numbers")));
                }
                None => {
                    return Err(
                        self.error(at, format!("{directive} takes {n} numbers, the file ends"))
                    );
                }
            }
        }
        if bracketed {
            match self.next()? {
                Some((Token::Close, _)) => {}
                Some((_, at)) => {
                    return Err(self.error(at, format!("expected ] after {n} numbers")));
                }
                None => return Err(self.error(at, "expected ], the file ends")),
            }
        }
        Ok(out)
    }

    /// A directive's quoted type (`Shape "sphere"`).
    fn kind(&mut self, directive: &str, at: (usize, usize)) -> Result<String, ImportError> {
        let at = match self.next()? {
            Some((Token::Text(s), _)) => return Ok(s.to_owned()),
            Some((_, at)) => at,
            None => at,
        };
        Err(self.error(
            at,
            format!("{directive} needs a quoted name, e.g. {directive} \"name\""),
        ))
    }

    /// The `"type name" value` parameters that follow a directive.
    fn params(&mut self) -> Result<Params, ImportError> {
        let mut params = Params::default();
        while let Some((Token::Text(_), _)) = self.peek()? {
            let Some((Token::Text(decl), at)) = self.next()? else {
                unreachable!("peeked a string")
            };
            let mut words = decl.split_whitespace();
            let (Some(ty), Some(name), None) = (words.next(), words.next(), words.next()) else {
                return Err(self.error(
                    at,
                    format!("expected a parameter \"type name\", found \"{decl}\""),
                ));
            };
            let (ty, name) = (ty.to_owned(), name.to_owned());
            let mut numbers = Vec::new();
            let mut strings = Vec::new();
            let mut one = |token: Token<'_>, at| -> Result<(), ImportError> {
                match token {
                    Token::Number(x) => numbers.push(x),
                    Token::Text(s) => strings.push(s.to_owned()),
                    Token::Word(w @ ("true" | "false")) => strings.push(w.to_owned()),
                    _ => {
                        return Err(ImportError::new(
                            self.path,
                            Some(at),
                            format!("parameter \"{decl}\" needs a value"),
                        ));
                    }
                }
                Ok(())
            };
            match self.next()? {
                Some((Token::Open, _)) => loop {
                    match self.next()? {
                        Some((Token::Close, _)) => break,
                        Some((token, at)) => one(token, at)?,
                        None => {
                            return Err(ImportError::new(
                                self.path,
                                Some(at),
                                format!("parameter \"{decl}\": expected ], the file ends"),
                            ));
                        }
                    }
                },
                Some((token, at)) => one(token, at)?,
                None => return Err(self.error(at, format!("parameter \"{decl}\" needs a value"))),
            }
            let values = if strings.is_empty() {
                Values::Numbers(numbers)
            } else if numbers.is_empty() {
                Values::Strings(strings)
            } else {
                return Err(self.error(
                    at,
                    format!("parameter \"{decl}\" mixes numbers and strings"),
                ));
            };
            params.list.push((ty, name, values, at));
        }
        Ok(params)
    }
}

/// The graphics state pbrt keeps per attribute block.
#[derive(Clone)]
struct State {
    ctm: DMat4,
    material: Option<String>,
}

/// Reads a pbrt-v4 scene: its camera (perspective, orthographic, spherical
/// equirectangular), film size, pixel samples, and what viewray can hold of the world
/// (spheres, triangle and bilinear meshes, diffuse colours, point, distant and infinite
/// lights). What cannot be carried over is named in a comment of the document.
///
/// # Errors
/// An [`ImportError`] with the line and column for a malformed file, a missing or
/// unsupported camera, or a value of the wrong form.
pub fn import(text: &str, path: &Path) -> Result<SceneDocument, ImportError> {
    let mut parser = Parser {
        tokens: Tokens {
            text,
            offset: 0,
            line: 1,
            line_start: 0,
        },
        peeked: None,
        path,
    };
    let mut state = State {
        ctm: DMat4::IDENTITY,
        material: None,
    };
    let mut stack: Vec<State> = Vec::new();
    let mut named_coordinate_systems: HashMap<String, DMat4> = HashMap::new();
    let mut camera: Option<(String, Params, DMat4, (usize, usize))> = None;
    let (mut width, mut height) = DEFAULT_FILM;
    let mut samples = DEFAULT_SAMPLES;
    let mut comments = vec![format!(
        "Imported from {} (pbrt-v4) by `viewray import`.",
        path.display()
    )];
    let mut materials: Vec<(String, Material)> = Vec::new();
    let mut material_index: HashMap<String, usize> = HashMap::new();
    let mut lights = Vec::new();
    let mut background = Vec3::ZERO;
    let mut objects: Vec<(ObjectDocument, DMat4)> = Vec::new();
    let mut in_world = false;

    while let Some((token, at)) = parser.next()? {
        let Token::Word(directive) = token else {
            return Err(parser.error(at, "expected a directive (a word such as Camera or Shape)"));
        };
        match directive {
            "Identity" => state.ctm = DMat4::IDENTITY,
            "Translate" => {
                let v = parser.numbers(3, directive, at)?;
                state.ctm *= DMat4::from_translation(DVec3::new(v[0], v[1], v[2]));
            }
            "Scale" => {
                let v = parser.numbers(3, directive, at)?;
                state.ctm *= DMat4::from_scale(DVec3::new(v[0], v[1], v[2]));
            }
            "Rotate" => {
                let v = parser.numbers(4, directive, at)?;
                let axis = DVec3::new(v[1], v[2], v[3])
                    .try_normalize()
                    .ok_or_else(|| parser.error(at, "Rotate: the axis is zero"))?;
                state.ctm *= DMat4::from_axis_angle(axis, v[0].to_radians());
            }
            "LookAt" => {
                let v = parser.numbers(9, directive, at)?;
                let pos = DVec3::new(v[0], v[1], v[2]);
                let look = DVec3::new(v[3], v[4], v[5]);
                let up = DVec3::new(v[6], v[7], v[8]);
                let dir = (look - pos)
                    .try_normalize()
                    .ok_or_else(|| parser.error(at, "LookAt: the eye is the look-at point"))?;
                let right = up
                    .try_normalize()
                    .map(|up| up.cross(dir))
                    .and_then(DVec3::try_normalize)
                    .ok_or_else(|| parser.error(at, "LookAt: up is parallel to the view"))?;
                let new_up = dir.cross(right);
                let world_from_camera = DMat4::from_cols(
                    right.extend(0.0),
                    new_up.extend(0.0),
                    dir.extend(0.0),
                    pos.extend(1.0),
                );
                state.ctm *= world_from_camera.inverse();
            }
            "Transform" | "ConcatTransform" => {
                let v = parser.numbers(16, directive, at)?;
                // pbrt lists the matrix with its translation last: column-major.
                let m = DMat4::from_cols_array(&v.try_into().expect("16 numbers"));
                if directive == "Transform" {
                    state.ctm = m;
                } else {
                    state.ctm *= m;
                }
            }
            "CoordinateSystem" => {
                let name = parser.kind(directive, at)?;
                named_coordinate_systems.insert(name, state.ctm);
            }
            "CoordSysTransform" => {
                let name = parser.kind(directive, at)?;
                state.ctm = if name == "camera" {
                    camera.as_ref().map_or(DMat4::IDENTITY, |c| c.2.inverse())
                } else {
                    *named_coordinate_systems.get(&name).ok_or_else(|| {
                        parser.error(at, format!("no coordinate system named \"{name}\""))
                    })?
                };
            }
            "Camera" => {
                let kind = parser.kind(directive, at)?;
                let params = parser.params()?;
                if !state.ctm.is_finite() || state.ctm.determinant() == 0.0 {
                    return Err(parser.error(at, "the camera transform is singular"));
                }
                named_coordinate_systems.insert("camera".to_owned(), state.ctm.inverse());
                camera = Some((kind, params, state.ctm, at));
            }
            "Film" => {
                parser.kind(directive, at)?;
                let params = parser.params()?;
                let integer = |name: &str, default: u32| -> Result<u32, ImportError> {
                    match params.numbers(name) {
                        None => Ok(default),
                        Some(([x], _))
                            if x.fract() == 0.0 && *x >= 1.0 && *x <= f64::from(u32::MAX) =>
                        {
                            Ok(*x as u32)
                        }
                        Some((_, at)) => Err(parser
                            .error(at, format!("\"{name}\" must be one positive whole number"))),
                    }
                };
                width = integer("xresolution", DEFAULT_FILM.0)?;
                height = integer("yresolution", DEFAULT_FILM.1)?;
            }
            "Sampler" => {
                parser.kind(directive, at)?;
                let params = parser.params()?;
                match params.numbers("pixelsamples") {
                    None => {}
                    Some(([x], _)) if x.fract() == 0.0 && *x >= 1.0 && *x <= 1e9 => {
                        samples = *x as u32
                    }
                    Some((_, at)) => {
                        return Err(
                            parser.error(at, "\"pixelsamples\" must be one positive whole number")
                        );
                    }
                }
            }
            "Integrator" | "PixelFilter" | "Accelerator" | "ColorSpace" | "MakeNamedMedium"
            | "Texture" | "ObjectBegin" | "AreaLightSource" => {
                let kind = parser.kind(directive, at)?;
                if directive == "Texture" {
                    // Texture "name" "type" "class" params.
                    parser.kind(directive, at)?;
                    parser.kind(directive, at)?;
                }
                parser.params()?;
                if matches!(directive, "AreaLightSource" | "ObjectBegin") {
                    comments.push(format!("line {}: {directive} \"{kind}\" skipped", at.0));
                }
            }
            "Option" | "Attribute" => {
                parser.kind(directive, at)?;
                parser.params()?;
            }
            "MediumInterface" => {
                parser.kind(directive, at)?;
                if let Some((Token::Text(_), _)) = parser.peek()? {
                    parser.next()?;
                }
            }
            "ObjectInstance" => {
                let name = parser.kind(directive, at)?;
                comments.push(format!("line {}: ObjectInstance \"{name}\" skipped", at.0));
            }
            "ObjectEnd" | "ReverseOrientation" | "ActiveTransform" | "TransformBegin"
            | "TransformEnd" | "TransformTimes" => match directive {
                "ActiveTransform" => {
                    parser.next()?;
                }
                "TransformTimes" => {
                    parser.numbers(2, directive, at)?;
                }
                "TransformBegin" => stack.push(state.clone()),
                "TransformEnd" => {
                    let restored = stack
                        .pop()
                        .ok_or_else(|| parser.error(at, "TransformEnd without TransformBegin"))?;
                    state.ctm = restored.ctm;
                }
                _ => {}
            },
            "WorldBegin" => {
                in_world = true;
                state.ctm = DMat4::IDENTITY;
                named_coordinate_systems.insert("world".to_owned(), DMat4::IDENTITY);
            }
            "WorldEnd" => {}
            "AttributeBegin" => stack.push(state.clone()),
            "AttributeEnd" => {
                state = stack
                    .pop()
                    .ok_or_else(|| parser.error(at, "AttributeEnd without AttributeBegin"))?;
            }
            "Material" => {
                let kind = parser.kind(directive, at)?;
                let params = parser.params()?;
                let name = format!("material_{}", materials.len());
                state.material = Some(add_material(
                    &mut materials,
                    &mut material_index,
                    name,
                    &params,
                    &kind,
                    at,
                    &mut comments,
                ));
            }
            "MakeNamedMaterial" => {
                let name = parser.kind(directive, at)?;
                let params = parser.params()?;
                let kind = params.string("type").unwrap_or("diffuse").to_owned();
                add_material(
                    &mut materials,
                    &mut material_index,
                    name,
                    &params,
                    &kind,
                    at,
                    &mut comments,
                );
            }
            "NamedMaterial" => {
                let name = parser.kind(directive, at)?;
                if !material_index.contains_key(&name) {
                    return Err(parser.error(
                        at,
                        format!("no material named \"{name}\" (MakeNamedMaterial defines one)"),
                    ));
                }
                state.material = Some(name);
            }
            "LightSource" => {
                let kind = parser.kind(directive, at)?;
                let params = parser.params()?;
                let scale = params
                    .numbers("scale")
                    .and_then(|(x, _)| x.first().copied())
                    .unwrap_or(1.0) as f32;
                let rgb = |name: &str| -> Option<Vec3> {
                    match params.numbers(name) {
                        Some(([r, g, b], _)) => Some(Vec3::new(*r as f32, *g as f32, *b as f32)),
                        _ => None,
                    }
                };
                let point3 = |name: &str, default: DVec3| -> DVec3 {
                    match params.numbers(name) {
                        Some(([x, y, z], _)) => DVec3::new(*x, *y, *z),
                        _ => default,
                    }
                };
                let pi = std::f32::consts::PI;
                match kind.as_str() {
                    "point" => lights.push((
                        Light::Point {
                            position: Vec3::ZERO,
                            intensity: rgb("I").unwrap_or(Vec3::ONE) * scale / pi,
                        },
                        state.ctm.transform_point3(point3("from", DVec3::ZERO)),
                    )),
                    "distant" => {
                        let from = point3("from", DVec3::ZERO);
                        let to = point3("to", DVec3::new(0.0, 0.0, 1.0));
                        let direction = state.ctm.transform_vector3(to - from);
                        let direction = direction.try_normalize().ok_or_else(|| {
                            parser.error(at, "a distant light with from = to has no direction")
                        })?;
                        lights.push((
                            Light::Directional {
                                direction: direction.as_vec3(),
                                intensity: rgb("L").unwrap_or(Vec3::ONE) * scale / pi,
                            },
                            DVec3::NAN,
                        ));
                    }
                    "infinite" if params.string("filename").is_none() => {
                        background = rgb("L").unwrap_or(Vec3::ONE) * scale;
                    }
                    other => comments.push(format!("line {}: light \"{other}\" skipped", at.0)),
                }
            }
            "Shape" => {
                let kind = parser.kind(directive, at)?;
                let params = parser.params()?;
                if !in_world {
                    return Err(parser.error(at, "a Shape before WorldBegin"));
                }
                let material = state.material.clone();
                match kind.as_str() {
                    "sphere" => {
                        let radius = params
                            .numbers("radius")
                            .and_then(|(x, _)| x.first().copied())
                            .unwrap_or(1.0);
                        let partial = ["zmin", "zmax", "phimax"]
                            .iter()
                            .any(|n| params.numbers(n).is_some());
                        if partial {
                            comments.push(format!("line {}: a partial sphere skipped", at.0));
                        } else {
                            objects.push((
                                ObjectDocument::Sphere {
                                    center: Vec3::ZERO,
                                    radius: radius as f32,
                                    material,
                                },
                                state.ctm,
                            ));
                        }
                    }
                    "trianglemesh" | "bilinearmesh" => {
                        let Some((p, p_at)) = params.numbers("P") else {
                            return Err(parser.error(at, format!("a {kind} needs \"point3 P\"")));
                        };
                        if !p.len().is_multiple_of(3) {
                            return Err(
                                parser.error(p_at, "\"point3 P\" needs a multiple of 3 numbers")
                            );
                        }
                        let points: Vec<DVec3> = p
                            .chunks_exact(3)
                            .map(|c| DVec3::new(c[0], c[1], c[2]))
                            .collect();
                        let corners = if kind == "trianglemesh" { 3 } else { 4 };
                        let indices: Vec<usize> = match params.numbers("indices") {
                            Some((i, i_at)) => {
                                if i.len() % corners != 0 || i.iter().any(|&k| k < 0.0 || k.fract() != 0.0 || k as usize >= points.len()) {
                                    return Err(parser.error(i_at, format!("\"integer indices\" must be groups of {corners} indices into P")));
                                }
                                i.iter().map(|&k| k as usize).collect()
                            }
                            None if points.len() == corners => (0..corners).collect(),
                            None => return Err(parser.error(at, format!("a {kind} of more than {corners} points needs \"integer indices\""))),
                        };
                        for face in indices.chunks_exact(corners) {
                            let tris: Vec<[usize; 3]> = if corners == 3 {
                                vec![[face[0], face[1], face[2]]]
                            } else {
                                // pbrt's bilinear patch p00 p10 p01 p11.
                                vec![[face[0], face[1], face[3]], [face[0], face[3], face[2]]]
                            };
                            for t in tris {
                                let corners = t.map(|i| points[i].as_vec3());
                                objects.push((
                                    ObjectDocument::Triangle {
                                        corners,
                                        material: material.clone(),
                                    },
                                    state.ctm,
                                ));
                            }
                        }
                    }
                    other => comments.push(format!("line {}: shape \"{other}\" skipped", at.0)),
                }
            }
            "Include" | "Import" => {
                let file = parser.kind(directive, at)?;
                return Err(parser.error(
                    at,
                    format!("{directive} \"{file}\" is not supported: merge the files into one"),
                ));
            }
            other if other.starts_with(|c: char| c.is_ascii_lowercase()) => {
                return Err(parser.error(
                    at,
                    format!("unknown directive `{other}` (pbrt's directives are capitalized: is a quote missing before it?)"),
                ));
            }
            other => {
                return Err(parser.error(at, format!("unknown directive `{other}`")));
            }
        }
    }
    let Some((kind, params, camera_from_world, camera_at)) = camera else {
        return Err(ImportError::new(
            path,
            None,
            "the file has no Camera directive: there is no camera to import",
        ));
    };
    let world_from_camera = camera_from_world.inverse();
    let (x, y, z) = (
        world_from_camera.x_axis.truncate(),
        world_from_camera.y_axis.truncate(),
        world_from_camera.z_axis.truncate(),
    );
    let handedness = x.cross(y).dot(z);
    let aspect = f64::from(width) / f64::from(height);
    let frame_aspect = params
        .numbers("frameaspectratio")
        .and_then(|(x, _)| x.first().copied())
        .unwrap_or(aspect);
    let screen = match params.numbers("screenwindow") {
        Some(([x0, x1, y0, y1], _)) => [*x0, *x1, *y0, *y1],
        Some((_, at)) => return Err(parser.error(at, "\"screenwindow\" needs four numbers")),
        None if frame_aspect > 1.0 => [-frame_aspect, frame_aspect, -1.0, 1.0],
        None => [-1.0, 1.0, -1.0 / frame_aspect, 1.0 / frame_aspect],
    };
    let lens = params
        .numbers("lensradius")
        .and_then(|(x, _)| x.first().copied())
        .unwrap_or(0.0);
    let focus = params
        .numbers("focaldistance")
        .and_then(|(x, _)| x.first().copied())
        .unwrap_or(1e6);
    let (projection, mirror, columns) = match kind.as_str() {
        "perspective" | "orthographic" => {
            let mirror = handedness > 0.0;
            let viewport = DVec2::new(screen[1] - screen[0], screen[3] - screen[2]);
            let centre = DVec2::new(screen[1] + screen[0], screen[3] + screen[2]) / 2.0;
            let projection = if kind == "perspective" {
                let fov = params
                    .numbers("fov")
                    .and_then(|(x, _)| x.first().copied())
                    .unwrap_or(90.0);
                if !(fov > 0.0 && fov < 180.0) {
                    return Err(parser.error(
                        camera_at,
                        format!("\"fov\" must be between 0 and 180 degrees, found {fov}"),
                    ));
                }
                let t = (fov.to_radians() / 2.0).tan();
                let size = PerspectiveSize::Viewport {
                    distance: 1.0,
                    viewport: viewport * t,
                };
                if lens > 0.0 {
                    ProjectionDocument::ThinLens {
                        size,
                        shift: centre * t,
                        aperture: Aperture::Radius(lens),
                        focus,
                    }
                } else {
                    ProjectionDocument::Perspective {
                        size,
                        shift: centre * t,
                    }
                }
            } else {
                if centre != DVec2::ZERO {
                    comments.push("pbrt's orthographic screen window is off-centre: the eye is moved to its centre.".to_owned());
                }
                ProjectionDocument::Orthographic {
                    viewport,
                    lens: (lens > 0.0).then_some(viewray_camera::Lens {
                        aperture: lens,
                        focus,
                    }),
                }
            };
            // U = x, V = y, W = -z; an off-centre orthographic window moves the eye.
            let eye = if kind == "orthographic" {
                world_from_camera.transform_point3(centre.extend(0.0))
            } else {
                world_from_camera.w_axis.truncate()
            };
            (projection, mirror, [x, y, -z, eye])
        }
        "spherical" => {
            let mapping = params.string("mapping").unwrap_or("equalarea");
            if mapping != "equirectangular" {
                return Err(parser.error(camera_at, format!("the spherical camera's mapping \"{mapping}\" has no viewray counterpart (viewray has equirectangular)")));
            }
            // x = W, y = V, z = -U.
            (
                ProjectionDocument::Equirectangular,
                handedness < 0.0,
                [-z, y, x, world_from_camera.w_axis.truncate()],
            )
        }
        other => {
            return Err(parser.error(camera_at, format!("unsupported camera \"{other}\", expected perspective, orthographic or spherical")));
        }
    };
    let mirror_matrix = if mirror {
        comments.push("pbrt's camera is left-handed and this one was set up with a plain LookAt: the scene is mirrored in x so that the picture is pbrt's.".to_owned());
        DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0))
    } else {
        DMat4::IDENTITY
    };
    let m = mirror_matrix
        * DMat4::from_cols(
            columns[0].extend(0.0),
            columns[1].extend(0.0),
            columns[2].extend(0.0),
            columns[3].extend(1.0),
        );
    let camera =
        camera_document(m, projection).map_err(|message| parser.error(camera_at, message))?;
    let lights = lights
        .into_iter()
        .map(|(light, position)| match light {
            Light::Point { intensity, .. } => Light::Point {
                position: mirror_matrix.transform_point3(position).as_vec3(),
                intensity,
            },
            Light::Directional {
                direction,
                intensity,
            } => Light::Directional {
                direction: mirror_matrix
                    .transform_vector3(direction.as_dvec3())
                    .as_vec3(),
                intensity,
            },
            other => other,
        })
        .collect();
    let objects = objects
        .into_iter()
        .filter_map(|(object, ctm)| transform_object(object, mirror_matrix * ctm, &mut comments))
        .collect();
    Ok(SceneDocument {
        comments,
        width,
        height,
        samples,
        camera,
        background,
        shading: Shading::Lit,
        materials,
        lights,
        objects,
    })
}

/// Defines (or redefines) the material `name` from a pbrt material's parameters: its
/// `rgb reflectance`, or grey with a comment.
fn add_material(
    materials: &mut Vec<(String, Material)>,
    index: &mut HashMap<String, usize>,
    name: String,
    params: &Params,
    kind: &str,
    at: (usize, usize),
    comments: &mut Vec<String>,
) -> String {
    let color = match params.numbers("reflectance") {
        Some(([r, g, b], _)) => Vec3::new(*r as f32, *g as f32, *b as f32),
        Some(([g], _)) => Vec3::splat(*g as f32),
        _ => {
            comments.push(format!(
                "line {}: material `{kind}` has no RGB reflectance viewray reads: grey 0.5",
                at.0
            ));
            Vec3::splat(0.5)
        }
    };
    let material = Material {
        color: color.max(Vec3::ZERO),
        ..Material::default()
    };
    match index.get(&name) {
        Some(&i) => materials[i].1 = material,
        None => {
            index.insert(name.clone(), materials.len());
            materials.push((name.clone(), material));
        }
    }
    name
}

/// `object` placed by `m`; a sphere under a non-uniform scale is dropped with a comment.
fn transform_object(
    object: ObjectDocument,
    m: DMat4,
    comments: &mut Vec<String>,
) -> Option<ObjectDocument> {
    match object {
        ObjectDocument::Sphere {
            center,
            radius,
            material,
        } => {
            let linear = glam::DMat3::from_mat4(m);
            let scale = linear.x_axis.length();
            let uniform = [linear.y_axis, linear.z_axis]
                .iter()
                .all(|a| (a.length() - scale).abs() <= 1e-9 * scale.max(1e-300));
            if !uniform {
                comments.push("a sphere scaled unevenly (an ellipsoid) skipped".to_owned());
                return None;
            }
            Some(ObjectDocument::Sphere {
                center: m.transform_point3(center.as_dvec3()).as_vec3(),
                radius: (f64::from(radius) * scale) as f32,
                material,
            })
        }
        ObjectDocument::Triangle { corners, material } => {
            let corners = corners.map(|c| m.transform_point3(c.as_dvec3()).as_vec3());
            let area = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            (area != Vec3::ZERO && area.is_finite())
                .then_some(ObjectDocument::Triangle { corners, material })
        }
        other => Some(other),
    }
}
