//! The steps of a pixel's trace: plain numbers, each one the renderer computed.

use glam::Vec3;
use viewray_geometry::{DRay, Ray};

use crate::PixelKind;

/// The lecture's pseudocode for one pixel, with the renderer's numbers: what
/// [`trace_pixel`](crate::trace_pixel) returns.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelTrace {
    /// The pixel, 0-based from the top-left.
    pub row: u32,
    /// The pixel's column, 0-based from the left.
    pub col: u32,
    /// The steps, in the order the renderer took them.
    pub steps: Vec<Step>,
    /// The pixel's value in the image: the linear colour for Flat and Lit, the data for
    /// Normals and Depth (see [`PixelKind`]).
    pub value: Vec3,
    /// What the value means, which decides its 8-bit encoding.
    pub kind: PixelKind,
    /// The 8 bits per channel the PNG of a one-sample render stores for the pixel.
    pub rgb8: [u8; 3],
}

/// One step of a trace, at mirror bounce `bounce` (0 for the viewing ray, 1 for what a
/// mirror it hits reflects, and so on).
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The mirror bounce.
    pub bounce: u32,
    /// What happened.
    pub kind: StepKind,
}

/// What one step of a trace did.
#[derive(Clone, Debug, PartialEq)]
pub enum StepKind {
    /// Generate a viewing ray for the pixel: the camera's ray through the pixel's
    /// centre and the lens centre, in `f64` as `viewray rays` prints it (the renderer
    /// traces it rounded to `f32`); `None` where the camera has no ray (outside a
    /// fisheye's image circle).
    ViewingRay {
        /// The ray.
        ray: Option<DRay>,
    },
    /// One object of the scene tested against the ray: where it first meets the ray
    /// (`t` in units of the ray's direction), or `None`.
    Test {
        /// The object, by index in the scene's list.
        object: u32,
        /// What kind of object it is.
        shape: Shape,
        /// Where it meets the ray, if it does.
        t: Option<f32>,
    },
    /// The closest object the ray meets, as the renderer found it.
    Closest(ClosestHit),
    /// The ray meets nothing, or there is no ray: the background.
    Background {
        /// The value stored (for data images, the background's sRGB encoding).
        color: Vec3,
    },
    /// Flat shading: the material's colour (with its grid lines).
    Flat {
        /// The material's index in the scene.
        material: usize,
        /// The colour.
        color: Vec3,
        /// The grid lines over it, for a grid material.
        grid: Option<GridLines>,
    },
    /// Normals shading: `n / 2 + 1/2` for the shading normal `n`.
    Normals {
        /// The shading normal `n`.
        normal: Vec3,
        /// `n / 2 + 1/2`.
        value: Vec3,
    },
    /// Depth shading.
    Depth(DepthValue),
    /// Lit shading: the surface's material, where it is seen from, and where its
    /// shadow and mirror rays start.
    Surface(LitSurface),
    /// Lit shading of a scene without lights: the headlight, a light at the eye.
    Headlight(HeadlightTerms),
    /// An ambient light: `color * I`.
    Ambient {
        /// The light, by index in the scene's list.
        light: usize,
        /// Its intensity `I`.
        intensity: Vec3,
        /// `color * I`.
        term: Vec3,
        /// The colour summed so far.
        color: Vec3,
    },
    /// A point or directional light, with its shadow ray.
    Light(LightTerms),
    /// A mirror: the reflected ray, traced the same way one bounce deeper; `None` past
    /// the last bounce, where a mirror reflects black.
    Reflect {
        /// How much of the reflection is mixed in.
        mirror: f32,
        /// The reflected ray.
        ray: Option<Ray>,
    },
    /// A mirror's mix: `(1 - mirror) local + mirror reflected`.
    Mix {
        /// How much of the reflection is mixed in.
        mirror: f32,
        /// The colour of the surface itself, from its lights.
        local: Vec3,
        /// The colour along the reflected ray.
        reflected: Vec3,
        /// The mix.
        color: Vec3,
    },
}

/// The kinds of object a scene holds, as scene files name them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// `Sphere(..)`.
    Sphere,
    /// `Plane(..)`.
    Plane,
    /// `Triangle(..)`.
    Triangle,
    /// `Box(..)`.
    Box,
    /// `Mesh(..)`.
    Mesh,
}

impl Shape {
    /// The name a scene file gives it: `Sphere`, `Plane`, `Triangle`, `Box` or `Mesh`.
    pub fn name(self) -> &'static str {
        match self {
            Shape::Sphere => "Sphere",
            Shape::Plane => "Plane",
            Shape::Triangle => "Triangle",
            Shape::Box => "Box",
            Shape::Mesh => "Mesh",
        }
    }
}

/// The closest hit of a ray, with its surface details.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosestHit {
    /// The object, by index in the scene's list.
    pub object: u32,
    /// What kind of object it is.
    pub shape: Shape,
    /// The face of a mesh (its index in the mesh's file); 0 for other shapes.
    pub primitive: u32,
    /// The material's index in the scene.
    pub material: usize,
    /// Where along the ray, in units of its direction.
    pub t: f32,
    /// The point `p = origin + t direction`.
    pub point: Vec3,
    /// The geometric unit normal, facing the ray.
    pub normal: Vec3,
    /// The unit normal to shade with (a mesh's interpolated normal), facing the ray.
    pub shading_normal: Vec3,
}

/// Grid lines over a surface colour, box-filtered over the sample's footprint.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GridLines {
    /// The two world axes (0 = x, 1 = y, 2 = z) whose constant values the lines are.
    pub axes: [usize; 2],
    /// The width of the sample's footprint along each axis (0: a point, infinite:
    /// larger than anything).
    pub footprint: [f32; 2],
    /// The fraction of the footprint covered by the lines of each axis.
    pub coverage: [f32; 2],
    /// Both together: `1 - (1 - a) (1 - b)`.
    pub total: f32,
    /// The lines' colour.
    pub line_color: Vec3,
    /// The material's colour.
    pub base: Vec3,
    /// `base` mixed with the lines' colour by `total`.
    pub color: Vec3,
}

/// The Depth value of a hit point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DepthValue {
    /// Whether `z` is the distance from the eye (panoramic cameras) rather than along
    /// the view direction `-w`.
    pub panoramic: bool,
    /// The point's depth `z`.
    pub z: f32,
    /// The nearest and farthest depths of the image, from its pre-pass.
    pub near: f32,
    /// See `near`.
    pub far: f32,
    /// `s = (z - near) / (far - near)`, `None` when the range is empty.
    pub s: Option<f32>,
    /// `1 - 0.9 s` up to `far`, `0.1 / s` beyond; 1 for an empty range.
    pub value: f32,
}

/// What Lit shading reads of a surface.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LitSurface {
    /// The material's index in the scene.
    pub material: usize,
    /// The surface colour (with its grid lines).
    pub color: Vec3,
    /// The grid lines, for a grid material.
    pub grid: Option<GridLines>,
    /// The specular colour and exponent.
    pub specular: Vec3,
    /// See `specular`.
    pub shininess: f32,
    /// How much of the mirror reflection is mixed in.
    pub mirror: f32,
    /// `v`: the unit direction toward the eye, `-d / |d|`.
    pub view: Vec3,
    /// Where shadow and mirror rays start: the hit point moved off the surface along
    /// the geometric normal.
    pub origin: Vec3,
}

/// Blinn-Phong per unit of a light's irradiance, for the unit direction `l` toward it:
/// `color max(0, n.l) + specular max(0, n.h)^shininess`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BlinnPhong {
    /// `n.l` with the shading normal `n`; at most 0, nothing is lit.
    pub n_dot_l: f32,
    /// `color max(0, n.l)`.
    pub diffuse: Vec3,
    /// The specular term, where the material has one and `n.l > 0`.
    pub specular: Option<Specular>,
    /// Their sum.
    pub sum: Vec3,
}

/// Blinn-Phong's specular term.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Specular {
    /// `h = (l + v) / |l + v|`.
    pub h: Vec3,
    /// `n.h`.
    pub n_dot_h: f32,
    /// `max(0, n.h)^shininess`.
    pub power: f32,
    /// `specular max(0, n.h)^shininess`.
    pub term: Vec3,
}

/// The headlight of a scene without lights: `0.15 color + 0.85 (Blinn-Phong with
/// l = v)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeadlightTerms {
    /// The share of the surface colour every point gets, 0.15.
    pub ambient: f32,
    /// Blinn-Phong with the light at the eye.
    pub lit: BlinnPhong,
    /// `ambient color + (1 - ambient) lit`.
    pub term: Vec3,
    /// The colour summed so far.
    pub color: Vec3,
}

/// Where a light is.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LightSource {
    /// A point light at this position.
    Point(Vec3),
    /// A directional light travelling along this direction.
    Directional(Vec3),
}

/// What a point or directional light gives a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LightTerms {
    /// The light, by index in the scene's list.
    pub light: usize,
    /// Where it is.
    pub source: LightSource,
    /// Its intensity `I`.
    pub intensity: Vec3,
    /// `l`: the unit direction toward the light.
    pub l: Vec3,
    /// `r^2`, the squared distance to a point light (1 for a directional light).
    pub distance_squared: f32,
    /// The shadow ray toward the light; `None` where the light is behind the surface.
    pub shadow: Option<ShadowRay>,
    /// What the light adds, where it is in front and not blocked.
    pub lit: Option<LitTerm>,
    /// The colour summed so far.
    pub color: Vec3,
}

/// A shadow ray: from the surface toward a light, ending at a point light (`t = 1`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShadowRay {
    /// The ray.
    pub ray: Ray,
    /// Where along it a blocker counts: from `t_min` (0, the ray starts off the
    /// surface) up to `t_max` (1 for a point light, at the light; infinite for a
    /// directional light).
    pub t_min: f32,
    /// See `t_min`.
    pub t_max: f32,
    /// Whether something lies before the light.
    pub blocked: bool,
    /// The first object in the way and where, for a blocked ray.
    pub blocker: Option<(u32, Shape, f32)>,
}

/// What a light adds: `(I / r^2) (Blinn-Phong)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LitTerm {
    /// `I / r^2`.
    pub scale: Vec3,
    /// Blinn-Phong.
    pub blinn_phong: BlinnPhong,
    /// `(I / r^2) (diffuse + specular)`.
    pub term: Vec3,
}
