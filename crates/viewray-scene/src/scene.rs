//! The runtime scene: what the renderer needs, resolved and validated.

use std::sync::Arc;

use glam::Vec3;
use viewray_camera::Camera;
use viewray_geometry::{Hit, World};

/// A loaded, validated scene: the camera, the geometry with its acceleration structure,
/// materials resolved to indices, and lights.
#[derive(Clone, Debug)]
pub struct Scene {
    /// The camera, with the image size.
    pub camera: Camera,
    /// Samples per pixel, at least 1.
    pub samples: u32,
    /// The colour of rays that hit nothing (linear RGB).
    pub background: Vec3,
    /// How hits are coloured.
    pub shading: Shading,
    /// Every material; [`Scene::material`] finds a hit's.
    pub materials: Vec<Material>,
    /// The lights, for [`Shading::Lit`].
    pub lights: Vec<Light>,
    /// The geometry: object `i` of the world is `objects[i]` of the scene file.
    pub world: World,
    /// The material of each object of the world, by object index.
    pub object_materials: Vec<ObjectMaterial>,
}

/// How a render colours what a ray hits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Shading {
    /// The material's colour as is: a pure-colour render is a coverage mask.
    Flat,
    /// The shading normal mapped from [-1, 1] to [0, 1] per channel.
    Normals,
    /// Distance along the view direction, near bright and far dark.
    Depth,
    /// Blinn-Phong with the scene's lights, hard shadows and mirror reflection.
    #[default]
    Lit,
}

impl Shading {
    /// Every shading, in the order scene files list them.
    pub const ALL: [Shading; 4] = [
        Shading::Flat,
        Shading::Normals,
        Shading::Depth,
        Shading::Lit,
    ];

    /// The name a scene file writes: `Flat`, `Normals`, `Depth` or `Lit`.
    pub fn name(self) -> &'static str {
        match self {
            Shading::Flat => "Flat",
            Shading::Normals => "Normals",
            Shading::Depth => "Depth",
            Shading::Lit => "Lit",
        }
    }
}

impl std::str::FromStr for Shading {
    type Err = String;

    /// The shading a scene file names `text`; the error says which names there are.
    fn from_str(text: &str) -> Result<Shading, String> {
        Shading::ALL
            .into_iter()
            .find(|shading| shading.name() == text)
            .ok_or_else(|| {
                format!(
                    "unknown shading `{text}`, expected one of `Flat`, `Normals`, `Depth` or `Lit`"
                )
            })
    }
}

/// A surface's appearance. Colours are linear RGB.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// The diffuse colour (and the flat colour).
    pub color: Vec3,
    /// The Blinn-Phong specular colour; zero for none.
    pub specular: Vec3,
    /// The Blinn-Phong exponent.
    pub shininess: f32,
    /// How much of the mirror reflection is mixed in, in [0, 1].
    pub mirror: f32,
    /// Grid lines drawn over the colour, to make projections legible on the ground.
    pub grid: Option<Grid>,
}

/// World-space grid lines over a surface: lines of constant coordinate every `spacing`
/// units along the two world axes closest to the surface's plane (x and z on the ground).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grid {
    /// The distance between lines.
    pub spacing: f32,
    /// The width of a line, in world units.
    pub line_width: f32,
    /// The colour of the lines (linear RGB).
    pub color: Vec3,
}

impl Default for Material {
    /// A matte light grey.
    fn default() -> Self {
        Self {
            color: Vec3::splat(0.8),
            specular: Vec3::ZERO,
            shininess: 32.0,
            mirror: 0.0,
            grid: None,
        }
    }
}

/// A light source. Intensities are linear RGB.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A point light; its intensity falls off with the square of the distance.
    Point {
        /// Where it is.
        position: Vec3,
        /// Its intensity: the irradiance at distance 1.
        intensity: Vec3,
    },
    /// Light from infinitely far away along `direction` (the way the light travels).
    Directional {
        /// The direction the light travels, normalized.
        direction: Vec3,
        /// Its irradiance.
        intensity: Vec3,
    },
    /// Light from everywhere, unshadowed.
    Ambient {
        /// Its intensity.
        intensity: Vec3,
    },
}

/// Which material an object uses.
#[derive(Clone, Debug, PartialEq)]
pub enum ObjectMaterial {
    /// One material for the whole object: an index into [`Scene::materials`].
    Single(u32),
    /// One material per triangle of a mesh (from its MTL file), by face index.
    PerTriangle(Arc<[u32]>),
}

impl Scene {
    /// The material of what `hit` hit.
    pub fn material(&self, hit: &Hit) -> &Material {
        let index = match &self.object_materials[hit.object as usize] {
            ObjectMaterial::Single(index) => *index,
            ObjectMaterial::PerTriangle(faces) => faces[hit.primitive as usize],
        };
        &self.materials[index as usize]
    }
}
