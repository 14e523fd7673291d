//! Rendered pictures: the figures' little scenes built as `viewray-scene` scenes and
//! rendered with `viewray-render`, lit as the fixtures are.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use image::RgbaImage;
use viewray_geometry::{Aabb, Instance, Mesh, MeshData, Object, Plane, Sphere, World};
use viewray_render::{RenderSettings, render};
use viewray_scene::{Grid, Light, Material, ObjectMaterial, Scene, SceneParts, Shading};

use crate::pictures::{AXIS_COLOURS, GROUND, Paint, PictureRequest, Pictures, SKY, Shape};

/// Pictures rendered by the ray tracer: what viewray's users see in the figures.
///
/// Each request becomes a [`Scene`] ([`picture_scene`]): the request's objects on a grid
/// ground plane under the sky, lit by the fixtures' rig (a directional key light, a
/// point light and ambient light), rendered with [`Shading::Lit`] at the size of the slot
/// it fills, so the picture lands on the figure pixel for pixel. Renders are
/// deterministic, so a figure is the same byte for byte on every run and every thread
/// count.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct RenderedPictures {
    /// Samples per pixel for pinhole and parallel cameras: enough to antialias edges and
    /// grid lines.
    pub(crate) samples: u32,
    /// Samples per pixel for cameras with a lens, whose blur needs many lens samples to
    /// look smooth rather than grainy.
    pub(crate) lens_samples: u32,
    /// Render threads, as [`RenderSettings::threads`]; the pictures do not depend on it.
    pub(crate) threads: Option<usize>,
}

impl Default for RenderedPictures {
    /// 9 samples per pixel (a 3 x 3 grid), 64 with a lens, on every core.
    fn default() -> Self {
        Self {
            samples: 9,
            lens_samples: 64,
            threads: None,
        }
    }
}

impl Pictures for RenderedPictures {
    fn picture(&self, request: &PictureRequest) -> Option<RgbaImage> {
        let samples = if request.camera.projection().has_lens() {
            self.lens_samples
        } else {
            self.samples
        };
        let scene = picture_scene(request, samples);
        let settings = RenderSettings {
            threads: self.threads,
            ..RenderSettings::default()
        };
        // A thread pool that cannot start leaves the slot to the polygon drawing.
        let rendered = render(&scene, &settings, |_, _| {}).ok()?;
        let (width, height) = (rendered.image.width(), rendered.image.height());
        let rgba = rendered
            .image
            .to_srgb8()
            .chunks_exact(3)
            .flat_map(|rgb| [rgb[0], rgb[1], rgb[2], 255])
            .collect();
        RgbaImage::from_raw(width, height, rgba)
    }
}

/// The fixtures' light rig: a directional key light from above, from `+x` and `+z`, a
/// slightly blue point light up at `(-4, 5, 6)`, and ambient light (as in every scene of
/// `fixtures/scenes/`).
pub(crate) fn picture_lights() -> Vec<Light> {
    vec![
        Light::Directional {
            direction: Vec3::new(-0.4, -1.0, -0.6).normalize(),
            intensity: Vec3::new(0.85, 0.85, 0.80),
        },
        Light::Point {
            position: Vec3::new(-4.0, 5.0, 6.0),
            intensity: Vec3::new(18.0, 18.0, 20.0),
        },
        Light::Ambient {
            intensity: Vec3::new(0.22, 0.23, 0.26),
        },
    ]
}

/// The scene a [`RenderedPictures`] renders for `request`: its camera at the slot's
/// size ([`PictureRequest::size`]), `samples` per pixel, [`SKY`] as the background, the
/// ground plane `y = 0` with the fixtures' 1-unit grid (and the earth below it, see
/// [`EARTH_DEPTH`]), the objects of the request's scene
/// ([`PictureScene::objects`](crate::pictures::PictureScene::objects)), and the fixtures' lights
/// ([`picture_lights`]).
///
/// Materials are the fixtures': the axis colours are matte (`cube.mtl`), uniform
/// colours get a little specular highlight (the `red`, `green` and `blue` materials),
/// banded surfaces (the towers' stone) a grid of lines `bands` units apart.
///
/// # Panics
/// Never for the figures' requests: their cameras and objects are valid by construction.
pub(crate) fn picture_scene(request: &PictureRequest, samples: u32) -> Scene {
    let (width, height) = request.size;
    let camera = request
        .camera
        .with_image_size(width.max(1), height.max(1))
        .expect("a camera of at least 1 x 1 pixels");

    // The ground: the fixtures' grid plane, with the earth below it (see EARTH_DEPTH).
    let ground = Material {
        color: vec3(GROUND),
        grid: Some(Grid {
            spacing: 1.0,
            line_width: 0.03,
            color: Vec3::splat(0.25),
        }),
        ..Material::default()
    };
    // The earth is seen only from inside, where only the ambient light reaches: white,
    // so that the band below the horizon reads as ground in shade.
    let earth = Material {
        color: Vec3::ONE,
        ..Material::default()
    };
    let glossy = |color: DVec3| Material {
        color: vec3(color),
        specular: Vec3::splat(0.3),
        shininess: 40.0,
        ..Material::default()
    };
    let mut materials = vec![ground, earth];
    // The axis colours, x y z, at indices 2, 3 and 4: matte, as `cube.mtl` gives them.
    materials.extend(AXIS_COLOURS.map(|color| Material {
        color: vec3(color),
        ..Material::default()
    }));
    let (x_faces, y_faces, z_faces) = (2, 3, 4);
    let mut objects = vec![
        Object::Plane(Plane {
            point: Vec3::ZERO,
            normal: Vec3::Y,
        }),
        Object::Box(Aabb::new(
            Vec3::new(-EARTH_HALF_SIZE, -EARTH_HALF_SIZE, -EARTH_HALF_SIZE),
            Vec3::new(EARTH_HALF_SIZE, -EARTH_DEPTH, EARTH_HALF_SIZE),
        )),
    ];
    let mut object_materials = vec![ObjectMaterial::Single(0), ObjectMaterial::Single(1)];

    for object in request.scene.objects() {
        let material = match object.paint {
            Paint::AxisColours => None,
            Paint::Uniform { color, bands: None } => Some(glossy(color)),
            Paint::Uniform {
                color,
                bands: Some(spacing),
            } => Some(Material {
                color: vec3(color),
                grid: Some(Grid {
                    spacing: spacing as f32,
                    line_width: 0.04,
                    color: Vec3::new(0.20, 0.22, 0.30),
                }),
                ..Material::default()
            }),
        };
        let index = |materials: &mut Vec<Material>, material: Material| {
            materials.push(material);
            u32::try_from(materials.len() - 1).expect("a handful of materials")
        };
        match (object.shape, material) {
            (Shape::Box { min, max }, None) => {
                objects.push(cuboid(vec3(min), vec3(max)));
                object_materials.push(per_face([
                    z_faces, z_faces, y_faces, y_faces, x_faces, x_faces,
                ]));
            }
            (Shape::Box { min, max }, Some(material)) => {
                objects.push(Object::Box(Aabb::new(vec3(min), vec3(max))));
                object_materials.push(ObjectMaterial::Single(index(&mut materials, material)));
            }
            (Shape::Sphere { center, radius }, material) => {
                let material = material.unwrap_or_else(|| glossy(AXIS_COLOURS[0]));
                objects.push(Object::Sphere(Sphere::new(vec3(center), radius as f32)));
                object_materials.push(ObjectMaterial::Single(index(&mut materials, material)));
            }
        }
    }

    Scene::new(SceneParts {
        camera,
        samples: samples.max(1),
        background: vec3(SKY),
        shading: Shading::Lit,
        materials,
        lights: picture_lights(),
        world: World::new(objects).expect("the picture scenes' objects are valid"),
        object_materials,
    })
    .expect("a material for every object and face")
}

/// How far below the ground plane the earth begins: a box under the ground, so that a
/// parallel camera looking exactly along the ground (the front and side views), whose
/// rays below the horizon start under the ground and never meet the plane, sees the
/// earth's inside as a band below the horizon, where with the plane alone the object
/// would float in the sky. Cameras looking down meet the plane first and never see the
/// earth; the gap keeps the two from fighting over the same depth.
pub(crate) const EARTH_DEPTH: f32 = 1e-3;

/// Half the width of the earth box (and its depth): far beyond any picture's view.
const EARTH_HALF_SIZE: f32 = 1000.0;

/// A box as a triangle mesh, so that its faces can take materials of their own.
fn cuboid(min: Vec3, max: Vec3) -> Object {
    let mesh = Mesh::new(MeshData::cuboid(Aabb::new(min, max))).expect("a finite cuboid");
    Object::Instance(Instance::from_mesh(Arc::new(mesh)))
}

/// The per-triangle materials of a [`cuboid`] from one material per face, in
/// [`MeshData::cuboid`]'s face order: -z, +z, -y, +y, -x, +x (two triangles each).
fn per_face(faces: [u32; 6]) -> ObjectMaterial {
    let triangles: Vec<u32> = faces.into_iter().flat_map(|m| [m, m]).collect();
    ObjectMaterial::PerTriangle(triangles.into())
}

/// `v` in `f32`, as the renderer works.
fn vec3(v: DVec3) -> Vec3 {
    v.as_vec3()
}
