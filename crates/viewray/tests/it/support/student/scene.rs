//! The student's scene: spheres, axis-aligned boxes and infinite planes, point,
//! directional and ambient lights, named materials and a background, as plain data; and
//! the same scene written as a viewray scene file, so that viewray can render it with the
//! student's camera.

use std::fmt::Write as _;

use super::camera::{Aim, CameraSpec, Projection};
use super::vec3::Vec3;

/// A surface's look: a diffuse colour and, optionally, a highlight.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Material {
    /// The diffuse colour (linear RGB).
    pub(crate) color: Vec3,
    /// The highlight, if any.
    pub(crate) specular: Option<Specular>,
}

/// A highlight: how strong, and how sharp.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Specular {
    /// The highlight's strength (a grey).
    pub(crate) strength: f64,
    /// The exponent: the larger, the smaller the highlight.
    pub(crate) shininess: f64,
}

/// A light.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Light {
    /// A point light whose `intensity` is the light at distance 1, falling off with the
    /// square of the distance.
    Point {
        /// Where it is.
        position: Vec3,
        /// Its colour and strength at distance 1.
        intensity: Vec3,
    },
    /// A light from infinitely far, travelling along `direction`.
    Directional {
        /// Where its light goes (not where it comes from).
        direction: Vec3,
        /// Its colour and strength.
        intensity: Vec3,
    },
    /// Light from everywhere, unshadowed.
    Ambient {
        /// Its colour and strength.
        intensity: Vec3,
    },
}

/// A shape of the scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Shape {
    /// A sphere.
    Sphere {
        /// Its centre.
        center: Vec3,
        /// Its radius (positive).
        radius: f64,
    },
    /// An axis-aligned box, `min < max` on every axis.
    Box {
        /// The corner with the smallest coordinates.
        min: Vec3,
        /// The corner with the largest coordinates.
        max: Vec3,
    },
    /// An infinite plane.
    Plane {
        /// A point of the plane.
        point: Vec3,
        /// Its normal (need not be a unit vector).
        normal: Vec3,
    },
}

/// A shape and the name of its material.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Object {
    /// The shape.
    pub(crate) shape: Shape,
    /// A name of [`Scene::materials`].
    pub(crate) material: String,
}

/// Everything but the camera and the image's size.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Scene {
    /// The colour of rays that hit nothing (linear RGB).
    pub(crate) background: Vec3,
    /// The materials by name, in the order they are written.
    pub(crate) materials: Vec<(String, Material)>,
    /// The lights.
    pub(crate) lights: Vec<Light>,
    /// The objects.
    pub(crate) objects: Vec<Object>,
}

impl Scene {
    /// A lit red sphere and a blue box on a grey ground plane under a pale sky, lit by a
    /// directional light, a point light and an ambient one.
    pub(crate) fn example() -> Self {
        let object = |shape, material: &str| Object {
            shape,
            material: material.to_owned(),
        };
        Scene {
            background: Vec3::new(0.55, 0.70, 0.90),
            materials: vec![
                (
                    "ground".to_owned(),
                    Material {
                        color: Vec3::new(0.6, 0.6, 0.58),
                        specular: None,
                    },
                ),
                (
                    "red".to_owned(),
                    Material {
                        color: Vec3::new(0.8, 0.12, 0.08),
                        specular: Some(Specular {
                            strength: 0.4,
                            shininess: 40.0,
                        }),
                    },
                ),
                (
                    "blue".to_owned(),
                    Material {
                        color: Vec3::new(0.1, 0.25, 0.8),
                        specular: Some(Specular {
                            strength: 0.2,
                            shininess: 20.0,
                        }),
                    },
                ),
            ],
            lights: vec![
                Light::Directional {
                    direction: Vec3::new(-0.4, -1.0, -0.6),
                    intensity: Vec3::new(0.85, 0.85, 0.8),
                },
                Light::Point {
                    position: Vec3::new(-4.0, 5.0, 6.0),
                    intensity: Vec3::new(18.0, 18.0, 20.0),
                },
                Light::Ambient {
                    intensity: Vec3::new(0.2, 0.2, 0.25),
                },
            ],
            objects: vec![
                object(
                    Shape::Plane {
                        point: Vec3::ZERO,
                        normal: Vec3::Y,
                    },
                    "ground",
                ),
                object(
                    Shape::Sphere {
                        center: Vec3::new(-0.9, 0.7, 0.0),
                        radius: 0.7,
                    },
                    "red",
                ),
                object(
                    Shape::Box {
                        min: Vec3::new(0.3, 0.0, -0.6),
                        max: Vec3::new(1.5, 1.2, 0.6),
                    },
                    "blue",
                ),
            ],
        }
    }

    /// The material called `name`.
    ///
    /// # Panics
    ///
    /// If the scene has no material of that name.
    pub(crate) fn material(&self, name: &str) -> &Material {
        self.materials
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, m)| m)
            .unwrap_or_else(|| panic!("the scene has no material {name:?}"))
    }

    /// The scene as a viewray scene file, seen through `camera` in an image of
    /// `width x height` pixels with `samples` samples per pixel, shaded `Lit`.
    pub(crate) fn to_ron(
        &self,
        camera: &CameraSpec,
        width: u32,
        height: u32,
        samples: u32,
    ) -> String {
        let mut ron = String::new();
        let mut line = |text: String| {
            ron.push_str(&text);
            ron.push('\n');
        };
        line("// A scene written by the student's ray tracer of viewray's tests.".to_owned());
        line("(".to_owned());
        line(format!(
            "    image: (width: {width}, height: {height}, samples: {samples}),"
        ));
        line(format!("    camera: {},", camera_ron(camera)));
        line(format!("    background: {},", vec_ron(self.background)));
        line("    shading: Lit,".to_owned());
        line("    materials: {".to_owned());
        for (name, material) in &self.materials {
            let mut fields = format!("color: {}", vec_ron(material.color));
            if let Some(specular) = material.specular {
                write!(
                    fields,
                    ", specular: {}, shininess: {}",
                    number(specular.strength),
                    number(specular.shininess)
                )
                .unwrap();
            }
            line(format!("        {name:?}: ({fields}),"));
        }
        line("    },".to_owned());
        line("    lights: [".to_owned());
        for light in &self.lights {
            line(format!("        {},", light_ron(light)));
        }
        line("    ],".to_owned());
        line("    objects: [".to_owned());
        for object in &self.objects {
            let shape = match object.shape {
                Shape::Sphere { center, radius } => format!(
                    "Sphere(center: {}, radius: {}",
                    vec_ron(center),
                    number(radius)
                ),
                Shape::Box { min, max } => {
                    format!("Box(min: {}, max: {}", vec_ron(min), vec_ron(max))
                }
                Shape::Plane { point, normal } => format!(
                    "Plane(point: {}, normal: {}",
                    vec_ron(point),
                    vec_ron(normal)
                ),
            };
            line(format!(
                "        {shape}, material: {:?}),",
                object.material
            ));
        }
        line("    ],".to_owned());
        line(")".to_owned());
        ron
    }
}

/// A camera as the scene file's `camera:` value.
pub(crate) fn camera_ron(camera: &CameraSpec) -> String {
    let aim = match camera.aim {
        Aim::LookAt(target) => format!("look_at: {}", vec_ron(target)),
        Aim::View(view) => format!("view: {}", vec_ron(view)),
    };
    let projection = match camera.projection {
        Projection::Perspective { d, viewport, shift } => format!(
            "Perspective(distance: {}, viewport: {}, shift: {})",
            number(d),
            pair_ron(viewport),
            pair_ron(shift)
        ),
        Projection::Orthographic { viewport } => {
            format!("Orthographic(viewport: {})", pair_ron(viewport))
        }
        Projection::Oblique {
            viewport,
            ratio,
            angle_degrees,
        } => format!(
            "Oblique(viewport: {}, ratio: {}, angle: {})",
            pair_ron(viewport),
            number(ratio),
            number(angle_degrees)
        ),
    };
    format!(
        "(eye: {}, {aim}, up: {}, projection: {projection})",
        vec_ron(camera.eye),
        vec_ron(camera.up)
    )
}

fn light_ron(light: &Light) -> String {
    match *light {
        Light::Point {
            position,
            intensity,
        } => format!(
            "Point(position: {}, intensity: {})",
            vec_ron(position),
            vec_ron(intensity)
        ),
        Light::Directional {
            direction,
            intensity,
        } => format!(
            "Directional(direction: {}, intensity: {})",
            vec_ron(direction),
            vec_ron(intensity)
        ),
        Light::Ambient { intensity } => format!("Ambient(intensity: {})", vec_ron(intensity)),
    }
}

/// A number as RON writes it, exactly: the shortest text that reads back as the same f64.
fn number(x: f64) -> String {
    format!("{x:?}")
}

fn vec_ron(a: Vec3) -> String {
    format!("({}, {}, {})", number(a.x), number(a.y), number(a.z))
}

fn pair_ron((a, b): (f64, f64)) -> String {
    format!("({}, {})", number(a), number(b))
}
