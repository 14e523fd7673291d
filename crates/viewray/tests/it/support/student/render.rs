//! The student's renderer: the lecture's pseudocode (for each pixel: generate a viewing
//! ray, find the closest object it meets, determine its colour) with its own
//! intersections and its own shading (Lambert, optionally Phong), deliberately unlike
//! viewray's: the tests judge a student's camera whatever their shading.

use super::camera::{CameraSpec, Ray, ray};
use super::mistakes::Mistake;
use super::picture::Picture;
use super::scene::{Light, Material, Scene, Shape};
use super::vec3::Vec3;

/// How the 8-bit values are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Gamma {
    /// sRGB-encoded, as a PNG viewer expects.
    SrgbEncoded,
    /// Linear values written as they are: the classic mistake (too dark).
    Linear,
    /// sRGB-encoded twice (too bright, washed out).
    Twice,
}

/// A light changed from the scene's, for a picture lit differently.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum LightChange {
    /// Point lights moved by this offset; directional lights turned by adding it to their
    /// (normalized) direction.
    Moved(Vec3),
    /// Every light's intensity filtered by this colour.
    Recoloured(Vec3),
}

/// How the student renders.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct RenderOptions {
    /// Samples per pixel, 1 to 64: one is the pixel centre, more are jittered over the
    /// pixel by a hash of (row, col, sample).
    pub(crate) samples: u32,
    /// The ambient level: every surface gets this much of its colour, whatever the
    /// scene's ambient lights (which the student ignores).
    pub(crate) ambient: f64,
    /// Every light's intensity times this (brighter above 1, darker below).
    pub(crate) light_scale: f64,
    /// Phong highlights on the materials that have a specular part.
    pub(crate) phong: bool,
    /// Shadow rays towards each light.
    pub(crate) shadows: bool,
    /// How the values are encoded.
    pub(crate) gamma: Gamma,
    /// A light different from the scene's, if any.
    pub(crate) light_change: Option<LightChange>,
}

impl Default for RenderOptions {
    /// One sample, ambient 0.1, the scene's lights, Phong, shadows, sRGB.
    fn default() -> Self {
        Self {
            samples: 1,
            ambient: 0.1,
            light_scale: 1.0,
            phong: true,
            shadows: true,
            gamma: Gamma::SrgbEncoded,
            light_change: None,
        }
    }
}

/// The image of `scene` through `camera` with the student's `mistakes`, `size = (W, H)`.
///
/// # Panics
///
/// If `options.samples` is not in 1..=64.
pub(crate) fn render(
    scene: &Scene,
    camera: &CameraSpec,
    mistakes: &[Mistake],
    size: (u32, u32),
    options: &RenderOptions,
) -> Picture {
    assert!(
        (1..=64).contains(&options.samples),
        "the student renders 1 to 64 samples per pixel, not {}",
        options.samples
    );
    let lights = lights(scene, options);
    let (width, height) = size;
    let mut values = Vec::with_capacity(width as usize * height as usize);
    for row in 0..height {
        for col in 0..width {
            let mut sum = Vec3::ZERO;
            for sample in 0..options.samples {
                let offset = if options.samples == 1 {
                    (0.5, 0.5)
                } else {
                    (hash01(row, col, sample, 0), hash01(row, col, sample, 1))
                };
                let ray = ray(camera, mistakes, size, (row, col), offset);
                sum = sum + shade(scene, &lights, options, &ray);
            }
            let linear = sum * (1.0 / f64::from(options.samples));
            values.push(linear.to_array().map(|l| encode(l, options.gamma)));
        }
    }
    Picture {
        width,
        height,
        values,
    }
}

/// The linear value `l` encoded as `gamma` says, in [0, 1].
pub(crate) fn encode(l: f64, gamma: Gamma) -> f64 {
    let l = l.clamp(0.0, 1.0);
    match gamma {
        Gamma::SrgbEncoded => srgb(l),
        Gamma::Linear => l,
        Gamma::Twice => srgb(srgb(l)),
    }
}

/// The sRGB transfer function on [0, 1].
fn srgb(l: f64) -> f64 {
    if l <= 0.003_130_8 {
        12.92 * l
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    }
}

/// A number in [0, 1) from (row, col, sample, axis) alone: a splitmix64 of their bits.
fn hash01(row: u32, col: u32, sample: u32, axis: u32) -> f64 {
    let mut z = (u64::from(row) << 40)
        ^ (u64::from(col) << 16)
        ^ (u64::from(sample) << 2)
        ^ u64::from(axis);
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

/// The lights the student shades with: the scene's point and directional lights, scaled
/// and changed as the options say.
fn lights(scene: &Scene, options: &RenderOptions) -> Vec<Light> {
    scene
        .lights
        .iter()
        .filter_map(|light| {
            let changed = match (*light, options.light_change) {
                (Light::Ambient { .. }, _) => return None,
                (
                    Light::Point {
                        position,
                        intensity,
                    },
                    Some(LightChange::Moved(offset)),
                ) => Light::Point {
                    position: position + offset,
                    intensity,
                },
                (
                    Light::Directional {
                        direction,
                        intensity,
                    },
                    Some(LightChange::Moved(offset)),
                ) => Light::Directional {
                    direction: direction.normalized() + offset,
                    intensity,
                },
                (light, _) => light,
            };
            let filter = match options.light_change {
                Some(LightChange::Recoloured(colour)) => colour,
                _ => Vec3::splat(1.0),
            } * options.light_scale;
            Some(match changed {
                Light::Point {
                    position,
                    intensity,
                } => Light::Point {
                    position,
                    intensity: intensity.times(filter),
                },
                Light::Directional {
                    direction,
                    intensity,
                } => Light::Directional {
                    direction,
                    intensity: intensity.times(filter),
                },
                Light::Ambient { .. } => unreachable!("ambient lights were left out"),
            })
        })
        .collect()
}

/// A ray's hit: how far along, the unit normal facing the ray, and the object's index.
struct Hit {
    t: f64,
    normal: Vec3,
    object: usize,
}

/// The nearest hit with `t` in `(t_min, t_max)`.
fn closest(scene: &Scene, ray: &Ray, t_min: f64, t_max: f64) -> Option<Hit> {
    let mut best: Option<Hit> = None;
    for (object, o) in scene.objects.iter().enumerate() {
        let limit = best.as_ref().map_or(t_max, |b| b.t);
        if let Some((t, normal)) = intersect(&o.shape, ray, t_min, limit) {
            let normal = if normal.dot(ray.direction) > 0.0 {
                -normal
            } else {
                normal
            };
            best = Some(Hit { t, normal, object });
        }
    }
    best
}

/// Where `ray` first meets `shape` with `t` in `(t_min, t_max)`, and the outward unit
/// normal there.
fn intersect(shape: &Shape, ray: &Ray, t_min: f64, t_max: f64) -> Option<(f64, Vec3)> {
    let inside = |t: f64| t > t_min && t < t_max;
    match *shape {
        Shape::Sphere { center, radius } => {
            // |o + t d - c|^2 = r^2: a t^2 + 2 b t + c = 0.
            let oc = ray.origin - center;
            let a = ray.direction.dot(ray.direction);
            let b = oc.dot(ray.direction);
            let c = oc.dot(oc) - radius * radius;
            let discriminant = b * b - a * c;
            if discriminant < 0.0 {
                return None;
            }
            let root = discriminant.sqrt();
            let t = [(-b - root) / a, (-b + root) / a]
                .into_iter()
                .find(|&t| inside(t))?;
            Some((t, (ray.at(t) - center) * (1.0 / radius)))
        }
        Shape::Box { min, max } => {
            // The slab test: the interval of t inside all three slabs.
            let (o, d) = (ray.origin.to_array(), ray.direction.to_array());
            let (lo, hi) = (min.to_array(), max.to_array());
            let (mut enter, mut leave) = (f64::NEG_INFINITY, f64::INFINITY);
            let (mut enter_axis, mut leave_axis) = (0, 0);
            for axis in 0..3 {
                let t1 = (lo[axis] - o[axis]) / d[axis];
                let t2 = (hi[axis] - o[axis]) / d[axis];
                let (near, far) = if t1 <= t2 { (t1, t2) } else { (t2, t1) };
                if near > enter {
                    (enter, enter_axis) = (near, axis);
                }
                if far < leave {
                    (leave, leave_axis) = (far, axis);
                }
            }
            if enter > leave {
                return None;
            }
            let (t, axis) = if inside(enter) {
                (enter, enter_axis)
            } else if inside(leave) {
                (leave, leave_axis)
            } else {
                return None;
            };
            // The face's normal points away from the box's centre.
            let centre = (min + max) * 0.5;
            let mut normal = [0.0; 3];
            normal[axis] = (ray.at(t) - centre).to_array()[axis].signum();
            Some((t, Vec3::from_array(normal)))
        }
        Shape::Plane { point, normal } => {
            let denominator = ray.direction.dot(normal);
            if denominator == 0.0 {
                return None;
            }
            let t = (point - ray.origin).dot(normal) / denominator;
            inside(t).then(|| (t, normal.normalized()))
        }
    }
}

/// The linear colour seen along `ray`.
fn shade(scene: &Scene, lights: &[Light], options: &RenderOptions, ray: &Ray) -> Vec3 {
    let Some(hit) = closest(scene, ray, 1e-9, f64::INFINITY) else {
        return scene.background;
    };
    let material: &Material = scene.material(&scene.objects[hit.object].material);
    let point = ray.at(hit.t);
    let n = hit.normal;
    let to_eye = -ray.direction.normalized();
    let mut colour = material.color * options.ambient;
    for light in lights {
        let (to_light, distance, intensity) = match *light {
            Light::Point {
                position,
                intensity,
            } => {
                let apart = position - point;
                let distance = apart.length();
                (
                    apart * (1.0 / distance),
                    distance,
                    intensity * (1.0 / (distance * distance)),
                )
            }
            Light::Directional {
                direction,
                intensity,
            } => (-direction.normalized(), f64::INFINITY, intensity),
            Light::Ambient { .. } => continue,
        };
        let facing = n.dot(to_light);
        if facing <= 0.0 {
            continue;
        }
        if options.shadows {
            let shadow = Ray {
                origin: point + n * 1e-6,
                direction: to_light,
            };
            if closest(scene, &shadow, 1e-9, distance).is_some() {
                continue;
            }
        }
        // Lambert.
        colour = colour + material.color.times(intensity) * facing;
        // Phong: the light's mirror direction against the direction to the eye.
        if let (true, Some(specular)) = (options.phong, material.specular) {
            let mirrored = n * (2.0 * facing) - to_light;
            let alignment = mirrored.dot(to_eye);
            if alignment > 0.0 {
                colour =
                    colour + intensity * (specular.strength * alignment.powf(specular.shininess));
            }
        }
    }
    colour
}
