//! The serde types of a scene file. They mirror the RON text and stay inside this crate:
//! [`crate::load::parse`] turns them into the runtime [`crate::Scene`].
//!
//! Field and variant names here are a contract with every scene file ever written:
//! rename nothing, only add.

use std::collections::BTreeMap;

use ron::value::RawValue;
use serde::Deserialize;

mod projection;

pub(crate) use projection::{
    FisheyeDef, ObliqueDef, OrthographicDef, PerspectiveDef, ProjectionDef, ThinLensDef,
};

/// A point or vector written `(x, y, z)`.
pub(crate) type V3 = (f64, f64, f64);
/// A pair written `(a, b)`.
pub(crate) type V2 = (f64, f64);

/// The whole file. `camera` is kept as raw text and parsed in a second step, because it
/// is either an explicit camera `( eye: .. )` or a preset `Isometric( .. )`, a choice RON's
/// self-describing parser cannot make without losing the preset's name.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "scene")]
pub(crate) struct SceneFile<'a> {
    /// Parsed in a second step so its errors can point at it.
    #[serde(default, borrow)]
    pub(crate) image: Option<&'a RawValue>,
    #[serde(borrow)]
    pub(crate) camera: &'a RawValue,
    #[serde(default)]
    pub(crate) background: V3,
    #[serde(default)]
    pub(crate) shading: ShadingDef,
    /// Material name -> material, each parsed in a second step.
    #[serde(default, borrow)]
    pub(crate) materials: BTreeMap<String, &'a RawValue>,
    #[serde(default, borrow)]
    pub(crate) lights: Vec<&'a RawValue>,
    #[serde(default, borrow)]
    pub(crate) objects: Vec<&'a RawValue>,
    /// Parsed in a second step (see [`AnimationDef`]).
    #[serde(default, borrow)]
    pub(crate) animation: Option<&'a RawValue>,
}

/// `animation: (frames: 48, fps: 24, ease: InOut, keys: [(t: 0.0, camera: (..)), ..])`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "animation")]
pub(crate) struct AnimationDef<'a> {
    #[serde(default = "default_frames")]
    pub(crate) frames: u32,
    #[serde(default = "default_fps")]
    pub(crate) fps: u32,
    #[serde(default)]
    pub(crate) ease: EaseDef,
    /// Each parsed in a second step, so that its errors can point at it.
    #[serde(borrow)]
    pub(crate) keys: Vec<&'a RawValue>,
}

fn default_frames() -> u32 {
    48
}

fn default_fps() -> u32 {
    24
}

/// `ease: Linear | InOut`.
#[derive(Deserialize, Default, Clone, Copy)]
#[serde(rename = "ease")]
pub(crate) enum EaseDef {
    #[default]
    Linear,
    InOut,
}

/// `(t: 0.5, camera: ( .. ))`: a whole camera, as the scene's `camera:` value is written.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "key")]
pub(crate) struct KeyDef<'a> {
    pub(crate) t: f64,
    #[serde(borrow)]
    pub(crate) camera: &'a RawValue,
}

/// `shading: Flat | Normals | Depth | Lit`.
#[derive(Deserialize, Default, Clone, Copy)]
#[serde(rename = "shading")]
pub(crate) enum ShadingDef {
    Flat,
    Normals,
    Depth,
    #[default]
    Lit,
}

/// `"red": (color: (0.8, 0.1, 0.1), specular: .., shininess: .., mirror: ..)`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "material")]
pub(crate) struct MaterialDef {
    pub(crate) color: V3,
    #[serde(default)]
    pub(crate) specular: Option<Specular>,
    #[serde(default)]
    pub(crate) shininess: Option<f64>,
    #[serde(default)]
    pub(crate) mirror: f64,
    #[serde(default)]
    pub(crate) grid: Option<GridDef>,
}

/// `grid: (spacing: 1.0, width: 0.04, color: (0.2, 0.2, 0.2))`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "grid")]
pub(crate) struct GridDef {
    pub(crate) spacing: f64,
    pub(crate) width: f64,
    pub(crate) color: V3,
}

/// A specular colour, or one number for a grey.
#[derive(Deserialize, Clone, Copy)]
#[serde(untagged)]
pub(crate) enum Specular {
    Grey(f64),
    Color(V3),
}

/// `Point(..) | Directional(..) | Ambient(..)`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "light")]
pub(crate) enum LightDef {
    Point { position: V3, intensity: V3 },
    Directional { direction: V3, intensity: V3 },
    Ambient { intensity: V3 },
}

/// `Sphere(..) | Plane(..) | Triangle(..) | Box(..) | Mesh(..)`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "object")]
pub(crate) enum ObjectDef {
    Sphere {
        center: V3,
        radius: f64,
        #[serde(default)]
        material: Option<String>,
    },
    Plane {
        point: V3,
        normal: V3,
        #[serde(default)]
        material: Option<String>,
    },
    Triangle {
        a: V3,
        b: V3,
        c: V3,
        #[serde(default)]
        material: Option<String>,
    },
    Box {
        min: V3,
        max: V3,
        #[serde(default)]
        material: Option<String>,
    },
    Mesh {
        path: String,
        #[serde(default)]
        material: Option<String>,
        #[serde(default)]
        transform: TransformDef,
    },
}

/// `transform: (translate: .., rotate: .., scale: ..)`; rotations in degrees about x, then
/// y, then z, after scaling and before translating.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "transform", default)]
pub(crate) struct TransformDef {
    pub(crate) translate: V3,
    pub(crate) rotate: V3,
    pub(crate) scale: Scale,
}

impl Default for TransformDef {
    fn default() -> Self {
        Self {
            translate: (0.0, 0.0, 0.0),
            rotate: (0.0, 0.0, 0.0),
            scale: Scale::Uniform(1.0),
        }
    }
}

/// `scale: 2.0` or `scale: (1.0, 2.0, 1.0)`.
#[derive(Deserialize, Clone, Copy)]
#[serde(untagged)]
pub(crate) enum Scale {
    Uniform(f64),
    PerAxis(V3),
}

/// `image: (width: 320, height: 240, samples: 16)`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "image", default)]
pub(crate) struct ImageDef {
    pub(crate) width: u32,
    pub(crate) height: u32,
    pub(crate) samples: u32,
}

impl Default for ImageDef {
    fn default() -> Self {
        Self {
            width: 320,
            height: 240,
            samples: 1,
        }
    }
}

/// `camera: (eye: .., look_at: .. | view: .., up: .., projection: ..)`.
#[derive(Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields, rename = "camera")]
pub(crate) struct ExplicitCamera {
    pub(crate) eye: V3,
    #[serde(default)]
    pub(crate) look_at: Option<V3>,
    #[serde(default)]
    pub(crate) view: Option<V3>,
    #[serde(default = "default_up")]
    pub(crate) up: V3,
    pub(crate) projection: ProjectionDef,
}

fn default_up() -> V3 {
    (0.0, 1.0, 0.0)
}

/// `fit: Auto | Horizontal | Vertical`, as Blender's sensor fit.
#[derive(Deserialize, Clone, Copy, Debug, PartialEq, Eq)]
#[serde(rename = "fit")]
pub(crate) enum SensorFitDef {
    Auto,
    Horizontal,
    Vertical,
}

fn default_oblique_angle() -> f64 {
    45.0
}

/// `camera: Isometric(target: (0, 0, 0), size: 4)` and the other taxonomy presets.
#[derive(Deserialize, Clone, Debug, PartialEq)]
#[serde(deny_unknown_fields, rename = "camera preset")]
pub(crate) enum PresetDef {
    Front {
        target: V3,
        size: f64,
    },
    Top {
        target: V3,
        size: f64,
    },
    Side {
        target: V3,
        size: f64,
    },
    Isometric {
        target: V3,
        size: f64,
    },
    Dimetric {
        target: V3,
        size: f64,
    },
    Trimetric {
        target: V3,
        size: f64,
    },
    Cavalier {
        target: V3,
        size: f64,
        /// Degrees.
        #[serde(default = "default_oblique_angle")]
        angle: f64,
    },
    Cabinet {
        target: V3,
        size: f64,
        /// Degrees.
        #[serde(default = "default_oblique_angle")]
        angle: f64,
    },
    OnePoint {
        target: V3,
        size: f64,
    },
    TwoPoint {
        target: V3,
        size: f64,
    },
    ThreePoint {
        target: V3,
        size: f64,
    },
}
