//! The runtime scene: what the renderer needs, resolved and validated.

use std::sync::Arc;

use glam::Vec3;
use viewray_camera::Camera;
use viewray_geometry::{Hit, Object, World};

/// A validated scene: the camera, the geometry with its acceleration structure, materials
/// resolved to indices, and lights.
///
/// Its parts agree by construction ([`Scene::new`] checks them, and the fields are
/// private): every object of the world has a material, every material index names a
/// material, a mesh's per-face materials cover its faces, and there is at least one
/// sample per pixel. So [`Scene::material`] never fails for a hit on its world.
#[derive(Clone, Debug)]
pub struct Scene {
    camera: Camera,
    samples: u32,
    background: Vec3,
    shading: Shading,
    materials: Vec<Material>,
    lights: Vec<Light>,
    world: World,
    object_materials: Vec<ObjectMaterial>,
}

/// The parts of a [`Scene`], for code that builds one without a scene file; checked by
/// [`Scene::new`].
#[derive(Clone, Debug)]
pub struct SceneParts {
    /// The camera, with the image size.
    pub camera: Camera,
    /// Samples per pixel, at least 1.
    pub samples: u32,
    /// The colour of rays that hit nothing (linear RGB).
    pub background: Vec3,
    /// How hits are coloured.
    pub shading: Shading,
    /// Every material, named by index in `object_materials`.
    pub materials: Vec<Material>,
    /// The lights, for [`Shading::Lit`].
    pub lights: Vec<Light>,
    /// The geometry.
    pub world: World,
    /// The material of each object of the world, one per object, in the world's order.
    pub object_materials: Vec<ObjectMaterial>,
}

/// Why [`Scene::new`] refused its parts.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum InvalidScene {
    /// `samples` is 0.
    #[error("a scene needs at least 1 sample per pixel")]
    NoSamples,
    /// `object_materials` does not have one entry per object of the world.
    #[error("the world has {objects} objects but {given} object materials: one per object")]
    MaterialCount {
        /// The number of objects in the world.
        objects: usize,
        /// The number of object materials given.
        given: usize,
    },
    /// A material index beyond `materials`.
    #[error("object {object} uses material {index}, but there are {count} materials")]
    MaterialOutOfRange {
        /// The object, by index in the world.
        object: usize,
        /// The index it names.
        index: u32,
        /// The number of materials.
        count: usize,
    },
    /// [`ObjectMaterial::PerTriangle`] on an object that is not a mesh.
    #[error("object {object} has per-triangle materials but is not a mesh")]
    PerTriangleWithoutMesh {
        /// The object, by index in the world.
        object: usize,
    },
    /// [`ObjectMaterial::PerTriangle`] with not one material per face of the mesh.
    #[error("object {object} has {given} face materials for a mesh of {faces} faces")]
    FaceCount {
        /// The object, by index in the world.
        object: usize,
        /// The number of face materials given.
        given: usize,
        /// The mesh's faces (zero-area ones included: they keep their index).
        faces: usize,
    },
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
    /// A scene from its parts, checked to agree.
    ///
    /// # Errors
    /// An [`InvalidScene`] when `samples` is 0, `object_materials` does not hold one entry
    /// per object of `world`, an index names no material, or per-triangle materials are
    /// on an object that is not a mesh or do not match its faces one for one.
    pub fn new(parts: SceneParts) -> Result<Scene, InvalidScene> {
        let SceneParts {
            camera,
            samples,
            background,
            shading,
            materials,
            lights,
            world,
            object_materials,
        } = parts;
        if samples == 0 {
            return Err(InvalidScene::NoSamples);
        }
        let objects = world.objects();
        if objects.len() != object_materials.len() {
            return Err(InvalidScene::MaterialCount {
                objects: objects.len(),
                given: object_materials.len(),
            });
        }
        for (object, (shape, material)) in objects.iter().zip(&object_materials).enumerate() {
            let indices: &[u32] = match material {
                ObjectMaterial::Single(index) => std::slice::from_ref(index),
                ObjectMaterial::PerTriangle(faces) => {
                    let Object::Instance(instance) = shape else {
                        return Err(InvalidScene::PerTriangleWithoutMesh { object });
                    };
                    let mesh_faces = instance.mesh().data().triangles.len();
                    if faces.len() != mesh_faces {
                        return Err(InvalidScene::FaceCount {
                            object,
                            given: faces.len(),
                            faces: mesh_faces,
                        });
                    }
                    faces
                }
            };
            if let Some(&index) = indices.iter().find(|&&i| i as usize >= materials.len()) {
                return Err(InvalidScene::MaterialOutOfRange {
                    object,
                    index,
                    count: materials.len(),
                });
            }
        }
        Ok(Scene {
            camera,
            samples,
            background,
            shading,
            materials,
            lights,
            world,
            object_materials,
        })
    }

    /// The same scene seen through `camera` (with its image size).
    #[must_use]
    pub fn with_camera(self, camera: Camera) -> Scene {
        Scene { camera, ..self }
    }

    /// The camera, with the image size.
    pub fn camera(&self) -> &Camera {
        &self.camera
    }

    /// Samples per pixel, at least 1.
    pub fn samples(&self) -> u32 {
        self.samples
    }

    /// The colour of rays that hit nothing (linear RGB).
    pub fn background(&self) -> Vec3 {
        self.background
    }

    /// How hits are coloured.
    pub fn shading(&self) -> Shading {
        self.shading
    }

    /// Every material; [`Scene::material`] finds a hit's.
    pub fn materials(&self) -> &[Material] {
        &self.materials
    }

    /// The lights, for [`Shading::Lit`].
    pub fn lights(&self) -> &[Light] {
        &self.lights
    }

    /// The geometry: object `i` of the world is `objects[i]` of the scene file.
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The material of each object of the world, by object index.
    pub fn object_materials(&self) -> &[ObjectMaterial] {
        &self.object_materials
    }

    /// The material of what `hit` hit.
    ///
    /// # Panics
    /// If `hit` is not on this scene's world (an object or face it does not have).
    pub fn material(&self, hit: &Hit) -> &Material {
        self.material_of(hit.object, hit.primitive)
    }

    /// The material of face `primitive` of object `object` (the face is ignored for a
    /// single-material object), as a hit on this scene's world names them.
    ///
    /// # Panics
    /// If the object or the face is not in this scene's world.
    #[inline]
    pub fn material_of(&self, object: u32, primitive: u32) -> &Material {
        let index = match &self.object_materials[object as usize] {
            ObjectMaterial::Single(index) => *index,
            ObjectMaterial::PerTriangle(faces) => faces[primitive as usize],
        };
        // In range: `Scene::new` checked every index.
        &self.materials[index as usize]
    }
}
