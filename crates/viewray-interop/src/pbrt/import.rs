//! Reading a pbrt-v4 scene file (the conventions are in the module's `mod.rs`): an
//! [`Importer`] keeps pbrt's graphics state and has one method per directive. Those of
//! the graphics state and the transforms are here, the camera's and the image's in
//! `camera.rs`, the world's (materials, lights, shapes) in `world.rs`.

mod camera;
mod world;

use std::collections::HashMap;
use std::path::Path;

use glam::{DMat4, DVec3, Vec3};
use viewray_scene::{Light, Material, ObjectDocument, SceneDocument, Shading};

use self::world::transform_object;
use super::parse::{Params, Parser, Token};
use crate::ImportError;

/// pbrt-v4's film size when a scene gives none.
const DEFAULT_FILM: (u32, u32) = (1280, 720);
/// pbrt-v4's default `pixelsamples`.
const DEFAULT_SAMPLES: u32 = 16;

/// A 1-based line and column.
type At = (usize, usize);

/// Reads a pbrt-v4 scene: its camera (perspective, orthographic, spherical
/// equirectangular), film size, pixel samples, and what viewray can hold of the world
/// (spheres, triangle and bilinear meshes, diffuse colours, point, distant and infinite
/// lights). What cannot be carried over is named in a comment of the document.
///
/// # Errors
/// An [`ImportError`] with the line and column for a malformed file, a missing or
/// unsupported camera, or a value of the wrong form.
pub fn import(text: &str, path: &Path) -> Result<SceneDocument, ImportError> {
    let mut importer = Importer::new(text, path);
    while let Some((token, at)) = importer.parser.next()? {
        let Token::Word(directive) = token else {
            return Err(importer.error(at, "expected a directive (a word such as Camera or Shape)"));
        };
        importer.directive(directive, at)?;
    }
    importer.finish()
}

/// The graphics state pbrt keeps per attribute block.
#[derive(Clone)]
struct State {
    /// The current transformation matrix.
    ctm: DMat4,
    /// The name of the current material.
    material: Option<String>,
}

/// The `Camera` directive: its type, parameters, the camera-from-world transform and
/// where it was.
struct CameraDirective {
    kind: String,
    params: Params,
    camera_from_world: DMat4,
    at: At,
}

/// A light as read: point lights keep their position apart, in pbrt's world, until the
/// camera says whether the scene is mirrored.
enum ReadLight {
    Point { position: DVec3, intensity: Vec3 },
    Directional { direction: Vec3, intensity: Vec3 },
}

/// A pbrt file being read: the graphics state, and the scene so far.
struct Importer<'a> {
    parser: Parser<'a>,
    path: &'a Path,
    state: State,
    /// The states `AttributeBegin` and `TransformBegin` saved.
    stack: Vec<State>,
    named_coordinate_systems: HashMap<String, DMat4>,
    camera: Option<CameraDirective>,
    width: u32,
    height: u32,
    samples: u32,
    comments: Vec<String>,
    materials: Vec<(String, Material)>,
    /// Where each name of `materials` is in it.
    material_index: HashMap<String, usize>,
    lights: Vec<ReadLight>,
    background: Vec3,
    /// Objects in their own space, with the transform that places them in pbrt's world.
    objects: Vec<(ObjectDocument, DMat4)>,
    in_world: bool,
}

impl<'a> Importer<'a> {
    fn new(text: &'a str, path: &'a Path) -> Self {
        Self {
            parser: Parser::new(text, path),
            path,
            state: State {
                ctm: DMat4::IDENTITY,
                material: None,
            },
            stack: Vec::new(),
            named_coordinate_systems: HashMap::new(),
            camera: None,
            width: DEFAULT_FILM.0,
            height: DEFAULT_FILM.1,
            samples: DEFAULT_SAMPLES,
            comments: vec![format!(
                "Imported from {} (pbrt-v4) by `viewray import`.",
                path.display()
            )],
            materials: Vec::new(),
            material_index: HashMap::new(),
            lights: Vec::new(),
            background: Vec3::ZERO,
            objects: Vec::new(),
            in_world: false,
        }
    }

    fn error(&self, at: At, message: impl Into<String>) -> ImportError {
        self.parser.error(at, message)
    }

    /// Reads the directive `directive` (its name already read) and what follows it.
    fn directive(&mut self, directive: &str, at: At) -> Result<(), ImportError> {
        match directive {
            "Identity" => self.state.ctm = DMat4::IDENTITY,
            "Translate" => self.translate(at)?,
            "Scale" => self.scale(at)?,
            "Rotate" => self.rotate(at)?,
            "LookAt" => self.look_at(at)?,
            "Transform" | "ConcatTransform" => self.transform(directive, at)?,
            "CoordinateSystem" => self.coordinate_system(at)?,
            "CoordSysTransform" => self.coord_sys_transform(at)?,
            "Camera" => self.camera(at)?,
            "Film" => self.film(at)?,
            "Sampler" => self.sampler(at)?,
            "Integrator" | "PixelFilter" | "Accelerator" | "ColorSpace" | "MakeNamedMedium"
            | "Texture" | "ObjectBegin" | "AreaLightSource" => self.skipped(directive, at)?,
            "Option" | "Attribute" => {
                self.parser.kind(directive, at)?;
                self.parser.params()?;
            }
            "MediumInterface" => self.medium_interface(at)?,
            "ObjectInstance" => self.object_instance(at)?,
            "ActiveTransform" => {
                self.parser.next()?;
            }
            "TransformTimes" => {
                self.parser.numbers(2, directive, at)?;
            }
            "TransformBegin" => self.stack.push(self.state.clone()),
            "TransformEnd" => self.transform_end(at)?,
            "ObjectEnd" | "ReverseOrientation" | "WorldEnd" => {}
            "WorldBegin" => self.world_begin(),
            "AttributeBegin" => self.stack.push(self.state.clone()),
            "AttributeEnd" => self.attribute_end(at)?,
            "Material" => self.material(at)?,
            "MakeNamedMaterial" => self.make_named_material(at)?,
            "NamedMaterial" => self.named_material(at)?,
            "LightSource" => self.light_source(at)?,
            "Shape" => self.shape(at)?,
            "Include" | "Import" => {
                let file = self.parser.kind(directive, at)?;
                return Err(self.error(
                    at,
                    format!("{directive} \"{file}\" is not supported: merge the files into one"),
                ));
            }
            other if other.starts_with(|c: char| c.is_ascii_lowercase()) => {
                return Err(self.error(
                    at,
                    format!(
                        "unknown directive `{other}` (pbrt's directives are capitalized: is a \
                         quote missing before it?)"
                    ),
                ));
            }
            other => return Err(self.error(at, format!("unknown directive `{other}`"))),
        }
        Ok(())
    }

    /// `Translate x y z`.
    fn translate(&mut self, at: At) -> Result<(), ImportError> {
        let v = self.parser.numbers(3, "Translate", at)?;
        self.state.ctm *= DMat4::from_translation(DVec3::new(v[0], v[1], v[2]));
        Ok(())
    }

    /// `Scale x y z`.
    fn scale(&mut self, at: At) -> Result<(), ImportError> {
        let v = self.parser.numbers(3, "Scale", at)?;
        self.state.ctm *= DMat4::from_scale(DVec3::new(v[0], v[1], v[2]));
        Ok(())
    }

    /// `Rotate degrees x y z`.
    fn rotate(&mut self, at: At) -> Result<(), ImportError> {
        let v = self.parser.numbers(4, "Rotate", at)?;
        let axis = DVec3::new(v[1], v[2], v[3])
            .try_normalize()
            .ok_or_else(|| self.error(at, "Rotate: the axis is zero"))?;
        self.state.ctm *= DMat4::from_axis_angle(axis, v[0].to_radians());
        Ok(())
    }

    /// `LookAt eye look up`: pbrt's left-handed camera frame, `right = up x dir`.
    fn look_at(&mut self, at: At) -> Result<(), ImportError> {
        let v = self.parser.numbers(9, "LookAt", at)?;
        let pos = DVec3::new(v[0], v[1], v[2]);
        let look = DVec3::new(v[3], v[4], v[5]);
        let up = DVec3::new(v[6], v[7], v[8]);
        let dir = (look - pos)
            .try_normalize()
            .ok_or_else(|| self.error(at, "LookAt: the eye is the look-at point"))?;
        let right = up
            .try_normalize()
            .map(|up| up.cross(dir))
            .and_then(DVec3::try_normalize)
            .ok_or_else(|| self.error(at, "LookAt: up is parallel to the view"))?;
        let new_up = dir.cross(right);
        let world_from_camera = DMat4::from_cols(
            right.extend(0.0),
            new_up.extend(0.0),
            dir.extend(0.0),
            pos.extend(1.0),
        );
        self.state.ctm *= world_from_camera.inverse();
        Ok(())
    }

    /// `Transform m00 .. m33` (replaces) or `ConcatTransform m00 .. m33` (multiplies).
    fn transform(&mut self, directive: &str, at: At) -> Result<(), ImportError> {
        let v = self.parser.numbers(16, directive, at)?;
        // pbrt lists the matrix with its translation last: column-major.
        let m = DMat4::from_cols_array(&v.try_into().expect("16 numbers"));
        if directive == "Transform" {
            self.state.ctm = m;
        } else {
            self.state.ctm *= m;
        }
        Ok(())
    }

    /// `CoordinateSystem "name"`: names the current transform.
    fn coordinate_system(&mut self, at: At) -> Result<(), ImportError> {
        let name = self.parser.kind("CoordinateSystem", at)?;
        self.named_coordinate_systems.insert(name, self.state.ctm);
        Ok(())
    }

    /// `CoordSysTransform "name"`: makes a named transform (or the camera's) current.
    fn coord_sys_transform(&mut self, at: At) -> Result<(), ImportError> {
        let name = self.parser.kind("CoordSysTransform", at)?;
        self.state.ctm = if name == "camera" {
            self.camera
                .as_ref()
                .map_or(DMat4::IDENTITY, |c| c.camera_from_world.inverse())
        } else {
            *self
                .named_coordinate_systems
                .get(&name)
                .ok_or_else(|| self.error(at, format!("no coordinate system named \"{name}\"")))?
        };
        Ok(())
    }

    /// A directive viewray reads past: `Integrator`, `Texture`, `AreaLightSource`, ...
    /// (the ones that would change the picture are named in a comment).
    fn skipped(&mut self, directive: &str, at: At) -> Result<(), ImportError> {
        let kind = self.parser.kind(directive, at)?;
        if directive == "Texture" {
            // Texture "name" "type" "class" params.
            self.parser.kind(directive, at)?;
            self.parser.kind(directive, at)?;
        }
        self.parser.params()?;
        if matches!(directive, "AreaLightSource" | "ObjectBegin") {
            self.comments
                .push(format!("line {}: {directive} \"{kind}\" skipped", at.0));
        }
        Ok(())
    }

    /// `MediumInterface "inside" ["outside"]`: read past.
    fn medium_interface(&mut self, at: At) -> Result<(), ImportError> {
        self.parser.kind("MediumInterface", at)?;
        if let Some((Token::Text(_), _)) = self.parser.peek()? {
            self.parser.next()?;
        }
        Ok(())
    }

    /// `ObjectInstance "name"`: skipped with a comment.
    fn object_instance(&mut self, at: At) -> Result<(), ImportError> {
        let name = self.parser.kind("ObjectInstance", at)?;
        self.comments
            .push(format!("line {}: ObjectInstance \"{name}\" skipped", at.0));
        Ok(())
    }

    /// `TransformEnd`: the transform `TransformBegin` saved (the material stays).
    fn transform_end(&mut self, at: At) -> Result<(), ImportError> {
        let restored = self
            .stack
            .pop()
            .ok_or_else(|| self.error(at, "TransformEnd without TransformBegin"))?;
        self.state.ctm = restored.ctm;
        Ok(())
    }

    /// `WorldBegin`: the camera is set up; the transform starts again from the world's.
    fn world_begin(&mut self) {
        self.in_world = true;
        self.state.ctm = DMat4::IDENTITY;
        self.named_coordinate_systems
            .insert("world".to_owned(), DMat4::IDENTITY);
    }

    /// `AttributeEnd`: the whole state `AttributeBegin` saved.
    fn attribute_end(&mut self, at: At) -> Result<(), ImportError> {
        self.state = self
            .stack
            .pop()
            .ok_or_else(|| self.error(at, "AttributeEnd without AttributeBegin"))?;
        Ok(())
    }

    /// The document, once every directive is read: the camera from its directive and
    /// the film, and the world mirrored in `x` where pbrt's left-handed camera needs it.
    fn finish(mut self) -> Result<SceneDocument, ImportError> {
        let Some(directive) = self.camera.take() else {
            return Err(ImportError::new(
                self.path,
                None,
                "the file has no Camera directive: there is no camera to import",
            ));
        };
        let (camera, mirror) = self.camera_document(&directive)?;
        let lights = self
            .lights
            .into_iter()
            .map(|light| match light {
                ReadLight::Point {
                    position,
                    intensity,
                } => Light::Point {
                    position: mirror.transform_point3(position).as_vec3(),
                    intensity,
                },
                ReadLight::Directional {
                    direction,
                    intensity,
                } => Light::Directional {
                    direction: mirror.transform_vector3(direction.as_dvec3()).as_vec3(),
                    intensity,
                },
            })
            .collect();
        let mut comments = self.comments;
        let objects = self
            .objects
            .into_iter()
            .filter_map(|(object, ctm)| transform_object(object, mirror * ctm, &mut comments))
            .collect();
        Ok(SceneDocument {
            comments,
            width: self.width,
            height: self.height,
            samples: self.samples,
            camera,
            background: self.background,
            shading: Shading::Lit,
            materials: self.materials,
            lights,
            objects,
        })
    }
}
