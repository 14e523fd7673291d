//! What every format shares: the scene as shapes with materials, meshes in world space,
//! numbers written exactly, and the camera frame as a matrix.

use std::f32::consts::PI as PI32;

use glam::{DMat4, DVec2, DVec3, Vec3};
use viewray_camera::{Camera, Frame};
use viewray_geometry::{Aabb, MeshData, Object, Triangle};
use viewray_output::{linear_to_srgb8, srgb_to_linear};
use viewray_scene::{
    CameraDocument, Light, Material, ObjectMaterial, ProjectionDocument, Scene, Shading,
};

/// How far an infinite plane reaches when a tool has only finite surfaces: a square
/// 2 x 10^4 scene units across, centred on the plane's point.
pub(crate) const PLANE_HALF_SIZE: f32 = 1.0e4;

/// The order in which a box's faces are written, as indices into [`MeshData::cuboid`]'s
/// (-z, +z, -y, +y, -x, +x): -z, +z, -x, +x, -y, +y, the order exported files (and
/// imported boxes' triangles) have always had, so that they stay byte for byte the same.
const EXPORTED_FACE_ORDER: [usize; 6] = [0, 1, 4, 5, 2, 3];

/// Segments around and rings from pole to pole when a sphere becomes triangles (glTF,
/// Blender).
pub(crate) const SPHERE_SEGMENTS: u32 = 64;
pub(crate) const SPHERE_RINGS: u32 = 32;

/// The parts of a scene an exporter writes.
pub(crate) struct Parts<'a> {
    pub(crate) camera: &'a Camera,
    pub(crate) samples: u32,
    pub(crate) background: Vec3,
    pub(crate) shading: Shading,
    materials: &'a [Material],
    lights: &'a [Light],
    pub(crate) shapes: Vec<Shape>,
}

/// An object of the scene as exporters see it.
pub(crate) enum Shape {
    Sphere {
        center: Vec3,
        radius: f32,
        material: u32,
    },
    Box {
        min: Vec3,
        max: Vec3,
        material: u32,
    },
    /// An infinite plane.
    Plane {
        point: Vec3,
        normal: Vec3,
        material: u32,
    },
    /// Triangles in world space, one material (a mesh with per-face materials is split).
    Mesh(TriangleMesh),
}

/// Triangles in world space with one material.
pub(crate) struct TriangleMesh {
    /// The positions and triangles (no normals, no texture coordinates).
    pub(crate) data: MeshData,
    pub(crate) material: u32,
}

impl<'a> Parts<'a> {
    pub(crate) fn of(scene: &'a Scene) -> Self {
        let mut shapes = Vec::new();
        for (object, material) in scene.world().objects().iter().zip(scene.object_materials()) {
            let single = match material {
                ObjectMaterial::Single(index) => Some(*index),
                ObjectMaterial::PerTriangle(_) => None,
            };
            let one = single.unwrap_or(0);
            match object {
                Object::Sphere(s) => shapes.push(Shape::Sphere {
                    center: s.center,
                    radius: s.radius,
                    material: one,
                }),
                Object::Box(b) => shapes.push(Shape::Box {
                    min: b.min,
                    max: b.max,
                    material: one,
                }),
                Object::Plane(p) => shapes.push(Shape::Plane {
                    point: p.point,
                    normal: p.normal,
                    material: one,
                }),
                Object::Triangle(Triangle { a, b, c }) => shapes.push(Shape::Mesh(TriangleMesh {
                    data: MeshData::new(vec![*a, *b, *c], vec![[0, 1, 2]]),
                    material: one,
                })),
                Object::Instance(instance) => {
                    let data = instance.mesh().data();
                    let transform = instance.world_from_object();
                    let world: Vec<Vec3> = data
                        .positions
                        .iter()
                        .map(|&p| transform.transform_point3(p))
                        .collect();
                    let face_material = |face: usize| match material {
                        ObjectMaterial::Single(index) => *index,
                        ObjectMaterial::PerTriangle(faces) => faces[face],
                    };
                    // One mesh per material, in the order materials first appear.
                    let mut order: Vec<u32> = Vec::new();
                    for face in 0..data.triangles.len() {
                        let m = face_material(face);
                        if !order.contains(&m) {
                            order.push(m);
                        }
                    }
                    for m in order {
                        let faces: Vec<[u32; 3]> = data
                            .triangles
                            .iter()
                            .enumerate()
                            .filter(|&(face, _)| face_material(face) == m)
                            .map(|(_, t)| *t)
                            .collect();
                        shapes.push(Shape::Mesh(compact(&world, &faces, m)));
                    }
                }
            }
        }
        Parts {
            camera: scene.camera(),
            samples: scene.samples(),
            background: scene.background(),
            shading: scene.shading(),
            materials: scene.materials(),
            lights: scene.lights(),
            shapes,
        }
    }

    /// `(W, H)`.
    pub(crate) fn size(&self) -> (u32, u32) {
        (self.camera.width(), self.camera.height())
    }

    /// The scene's lights in the order of its list, as every exporter writes them.
    pub(crate) fn lights(&self) -> impl Iterator<Item = ToolLight> + '_ {
        self.lights.iter().map(|light| match *light {
            Light::Point {
                position,
                intensity,
            } => ToolLight::Point {
                position,
                power: LightPower(intensity),
            },
            Light::Directional {
                direction,
                intensity,
            } => ToolLight::Directional {
                direction,
                power: LightPower(intensity),
            },
            Light::Ambient { intensity } => ToolLight::Ambient {
                power: LightPower(intensity),
            },
        })
    }

    /// The scene's materials in the order of its list, as every exporter writes them.
    pub(crate) fn materials(&self) -> impl Iterator<Item = ToolMaterial> + '_ {
        self.materials
            .iter()
            .enumerate()
            .map(|(index, material)| ToolMaterial {
                index,
                name: material_name(index),
                color: material.color,
            })
    }
}

/// A light of the scene in the exporters' shared terms. Where it has a counterpart in
/// the tool, its strength is [`LightPower`]'s.
#[derive(Clone, Copy)]
pub(crate) enum ToolLight {
    /// A point light at `position`.
    Point { position: Vec3, power: LightPower },
    /// A light from infinitely far away, shining along `direction`.
    Directional { direction: Vec3, power: LightPower },
    /// viewray's ambient light: only three.js has one (the other formats name it in a
    /// comment, or leave it out).
    Ambient { power: LightPower },
}

/// A light's strength: viewray's RGB intensity, and the tools' terms for it.
///
/// The tools' diffuse surfaces reflect `albedo / pi` of the light where viewray's Lit
/// shading reflects `albedo`, so a tool's light is pi times viewray's:
///
/// ```text
/// tool intensity = pi I,   tool strength = pi max(I_r, I_g, I_b)
/// ```
#[derive(Clone, Copy)]
pub(crate) struct LightPower(pub(crate) Vec3);

impl LightPower {
    /// viewray's RGB intensity, as a comment names it.
    pub(crate) fn viewray(self) -> Vec3 {
        self.0
    }

    /// The tools' RGB intensity, `pi I`: pbrt's `I` and `L`, Mitsuba's `intensity` and
    /// `irradiance`.
    pub(crate) fn rgb(self) -> Vec3 {
        self.0 * PI32
    }

    /// The largest channel of viewray's intensity, for the tools that take a light as a
    /// colour times one number.
    pub(crate) fn peak(self) -> f32 {
        self.0.max_element()
    }

    /// The tools' strength of a colour-times-number light, `pi` times [`Self::peak`].
    pub(crate) fn strength(self) -> f32 {
        self.peak() * PI32
    }

    /// The light's colour, its intensity over [`Self::peak`]; `None` for a black light.
    pub(crate) fn color(self) -> Option<Vec3> {
        let peak = self.peak();
        (peak > 0.0).then(|| self.0 / peak)
    }
}

/// viewray's RGB intensity of a tool's light of RGB intensity `tool`: the inverse of
/// [`LightPower::rgb`], `tool / pi`.
pub(crate) fn viewray_intensity(tool: Vec3) -> Vec3 {
    tool / PI32
}

/// A material of the scene in the exporters' shared terms.
pub(crate) struct ToolMaterial {
    /// Its place in the scene's list, which [`Shape`]s refer to.
    pub(crate) index: usize,
    /// Its name in the exported file ([`material_name`]).
    pub(crate) name: String,
    /// The diffuse colour, linear, as the scene gives it.
    pub(crate) color: Vec3,
}

impl ToolMaterial {
    /// The diffuse colour as a reflectance a physically based renderer accepts: each
    /// channel in `[0, 1]`.
    pub(crate) fn reflectance(&self) -> Vec3 {
        self.color.clamp(Vec3::ZERO, Vec3::ONE)
    }
}

/// The vertices `faces` use, renumbered from 0.
fn compact(positions: &[Vec3], faces: &[[u32; 3]], material: u32) -> TriangleMesh {
    let mut map = vec![u32::MAX; positions.len()];
    let mut out = MeshData::new(Vec::new(), Vec::with_capacity(faces.len()));
    for face in faces {
        let mut t = [0; 3];
        for (k, &i) in face.iter().enumerate() {
            let slot = &mut map[i as usize];
            if *slot == u32::MAX {
                *slot = u32::try_from(out.positions.len()).expect("a mesh has < 2^32 vertices");
                out.positions.push(positions[i as usize]);
            }
            t[k] = *slot;
        }
        out.triangles.push(t);
    }
    TriangleMesh {
        data: out,
        material,
    }
}

impl TriangleMesh {
    /// A box as [`MeshData::cuboid`] makes it: its 8 corners ([`Aabb::corners`]) and 12
    /// triangles, facing out, two a face, the faces in [`EXPORTED_FACE_ORDER`].
    pub(crate) fn cuboid(min: Vec3, max: Vec3, material: u32) -> Self {
        let mut data = MeshData::cuboid(Aabb::new(min, max));
        let pairs = data.triangles.chunks_exact(2).collect::<Vec<_>>();
        data.triangles = EXPORTED_FACE_ORDER
            .iter()
            .flat_map(|&face| pairs[face].iter().copied())
            .collect();
        Self { data, material }
    }

    /// An infinite plane as a square [`PLANE_HALF_SIZE`] on each side of its point, facing
    /// along its normal.
    pub(crate) fn plane(point: Vec3, normal: Vec3, material: u32) -> Self {
        let (t1, t2) = tangents(normal);
        let s = PLANE_HALF_SIZE;
        let positions = vec![
            point - s * t1 - s * t2,
            point + s * t1 - s * t2,
            point + s * t1 + s * t2,
            point - s * t1 + s * t2,
        ];
        Self {
            data: MeshData::new(positions, vec![[0, 1, 2], [0, 2, 3]]),
            material,
        }
    }

    /// A UV sphere of [`SPHERE_SEGMENTS`] x [`SPHERE_RINGS`], triangles facing out.
    pub(crate) fn sphere(center: Vec3, radius: f32, material: u32) -> Self {
        let mut positions = vec![center + radius * Vec3::Y];
        for ring in 1..SPHERE_RINGS {
            let theta = PI32 * ring as f32 / SPHERE_RINGS as f32;
            for segment in 0..SPHERE_SEGMENTS {
                let phi = 2.0 * PI32 * segment as f32 / SPHERE_SEGMENTS as f32;
                let direction = Vec3::new(
                    theta.sin() * phi.sin(),
                    theta.cos(),
                    theta.sin() * phi.cos(),
                );
                positions.push(center + radius * direction);
            }
        }
        positions.push(center - radius * Vec3::Y);
        let south = u32::try_from(positions.len() - 1).expect("small");
        let at =
            |ring: u32, segment: u32| 1 + (ring - 1) * SPHERE_SEGMENTS + segment % SPHERE_SEGMENTS;
        let mut triangles = Vec::new();
        for s in 0..SPHERE_SEGMENTS {
            triangles.push([0, at(1, s), at(1, s + 1)]);
            for ring in 1..SPHERE_RINGS - 1 {
                let (a, b) = (at(ring, s), at(ring, s + 1));
                let (c, d) = (at(ring + 1, s), at(ring + 1, s + 1));
                triangles.push([a, c, d]);
                triangles.push([a, d, b]);
            }
            triangles.push([at(SPHERE_RINGS - 1, s), south, at(SPHERE_RINGS - 1, s + 1)]);
        }
        Self {
            data: MeshData::new(positions, triangles),
            material,
        }
    }
}

/// Two unit vectors that, with `normal`, make a right-handed orthonormal basis
/// `(t1, t2, normal)`.
pub(crate) fn tangents(normal: Vec3) -> (Vec3, Vec3) {
    let helper = if normal.x.abs() < 0.9 {
        Vec3::X
    } else {
        Vec3::Y
    };
    let t1 = helper.cross(normal).normalize();
    let t2 = normal.cross(t1);
    (t1, t2)
}

/// Numbers other tools read back: the shortest text that reads back as the same value,
/// minus zero written `0.0` (viewray-output's one rule for them).
pub(crate) use viewray_output::number::{round_trip as num, round_trip_f32 as num32};

/// The matrix taking camera coordinates `(a, b, c)` to the world point
/// `e + a U + b V + c W`: columns `U`, `V`, `W`, `e`.
pub(crate) fn world_from_camera(frame: &Frame) -> DMat4 {
    DMat4::from_cols(
        frame.u().extend(0.0),
        frame.v().extend(0.0),
        frame.w().extend(0.0),
        frame.e().extend(1.0),
    )
}

/// Whether a viewport of `(vw, vh)` on a `W x H` image has square pixels,
/// `vw / W = vh / H`, to a few units in the last place.
pub(crate) fn square_pixels(viewport: DVec2, (width, height): (u32, u32)) -> bool {
    let a = viewport.x * f64::from(height);
    let b = viewport.y * f64::from(width);
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs())
}

/// The camera of a scene document from a world-from-camera matrix whose columns are
/// `U`, `V`, `W` (any lengths: they are normalized) and the eye.
pub(crate) fn camera_document(
    matrix: DMat4,
    projection: ProjectionDocument,
) -> Result<CameraDocument, String> {
    let u = matrix.x_axis.truncate();
    let v = matrix.y_axis.truncate();
    let w = matrix.z_axis.truncate();
    let eye = matrix.w_axis.truncate();
    if !(u.is_finite() && v.is_finite() && w.is_finite() && eye.is_finite()) {
        return Err("the camera's transform is not finite".to_owned());
    }
    let (Some(u), Some(v), Some(w)) = (u.try_normalize(), v.try_normalize(), w.try_normalize())
    else {
        return Err("the camera's transform squashes an axis to zero".to_owned());
    };
    // The frame must be orthonormal and right-handed: u x v = w.
    let tolerance = 1e-5;
    if u.dot(v).abs() > tolerance || u.dot(w).abs() > tolerance || v.dot(w).abs() > tolerance {
        return Err(
            "the camera's transform shears its axes (they are not perpendicular)".to_owned(),
        );
    }
    if u.cross(v).dot(w) < 0.0 {
        return Err(
            "the camera's transform mirrors the image (its axes are left-handed)".to_owned(),
        );
    }
    Ok(CameraDocument {
        eye,
        view: -w,
        up: v,
        projection,
    })
}

/// `matrix` with 16 numbers in column-major order (OpenGL's, glTF's, three.js's).
pub(crate) fn matrix_from_column_major(m: &[f64]) -> Option<DMat4> {
    let m: [f64; 16] = m.try_into().ok()?;
    let matrix = DMat4::from_cols_array(&m);
    matrix.is_finite().then_some(matrix)
}

/// A linear colour as three.js's `0xRRGGBB` (sRGB-encoded).
pub(crate) fn hex_color(color: Vec3) -> u32 {
    let [r, g, b] = color.to_array().map(|x| u32::from(linear_to_srgb8(x)));
    (r << 16) | (g << 8) | b
}

/// three.js's `0xRRGGBB` as a linear colour.
pub(crate) fn color_from_hex(hex: u32) -> Vec3 {
    let channel = |shift: u32| {
        let code = u8::try_from((hex >> shift) & 0xff).expect("masked to 8 bits");
        srgb_to_linear(f32::from(code) / 255.0)
    };
    Vec3::new(channel(16), channel(8), channel(0))
}

/// The name a scene document gives material `index`.
pub(crate) fn material_name(index: usize) -> String {
    format!("material_{index}")
}

/// The eye, the view direction and up as a look-at point for tools that take one:
/// `target = e - W`, `up = V`.
pub(crate) fn look_at(frame: &Frame) -> (DVec3, DVec3, DVec3) {
    (frame.e(), frame.e() - frame.w(), frame.v())
}

/// A number of pixels, at least 1 and at most viewray's largest side: the image size of
/// an imported camera whose file gives only an aspect ratio.
pub(crate) fn pixels(x: f64) -> u32 {
    // Clamped into u32's range first.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = x
        .round()
        .clamp(1.0, f64::from(viewray_scene::MAX_IMAGE_SIDE)) as u32;
    n
}
