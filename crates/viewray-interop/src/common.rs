//! What every format shares: the scene as shapes with materials, meshes in world space,
//! numbers written exactly, and the camera frame as a matrix.

use std::f32::consts::PI as PI32;

use glam::{DMat4, DVec2, DVec3, Vec3};
use viewray_camera::{Camera, Frame};
use viewray_geometry::{Object, Triangle};
use viewray_scene::{
    CameraDocument, Light, Material, ObjectMaterial, ProjectionDocument, Scene, Shading,
};

/// How far an infinite plane reaches when a tool has only finite surfaces: a square
/// 2 x 10^4 scene units across, centred on the plane's point.
pub(crate) const PLANE_HALF_SIZE: f32 = 1.0e4;

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
    pub(crate) materials: &'a [Material],
    pub(crate) lights: &'a [Light],
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
    pub(crate) positions: Vec<Vec3>,
    pub(crate) triangles: Vec<[u32; 3]>,
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
                    positions: vec![*a, *b, *c],
                    triangles: vec![[0, 1, 2]],
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
}

/// The vertices `faces` use, renumbered from 0.
fn compact(positions: &[Vec3], faces: &[[u32; 3]], material: u32) -> TriangleMesh {
    let mut map = vec![u32::MAX; positions.len()];
    let mut out = TriangleMesh {
        positions: Vec::new(),
        triangles: Vec::with_capacity(faces.len()),
        material,
    };
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
    out
}

impl TriangleMesh {
    /// A box's 8 corners and 12 triangles, facing out.
    pub(crate) fn cuboid(min: Vec3, max: Vec3, material: u32) -> Self {
        let corner = |i: u32| {
            Vec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            )
        };
        let positions = (0..8).map(corner).collect();
        let triangles = vec![
            [0, 2, 3],
            [0, 3, 1], // -z
            [4, 5, 7],
            [4, 7, 6], // +z
            [0, 4, 6],
            [0, 6, 2], // -x
            [1, 3, 7],
            [1, 7, 5], // +x
            [0, 1, 5],
            [0, 5, 4], // -y
            [2, 6, 7],
            [2, 7, 3], // +y
        ];
        Self {
            positions,
            triangles,
            material,
        }
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
            positions,
            triangles: vec![[0, 1, 2], [0, 2, 3]],
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
            positions,
            triangles,
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

/// The shortest decimal that reads back as the same `f64`.
pub(crate) fn num(x: f64) -> String {
    let s = format!("{x:?}");
    // `-0.0` reads back as zero in every tool; write it without the sign.
    if s == "-0.0" { "0.0".to_owned() } else { s }
}

/// The shortest decimal that reads back as the same `f32`.
pub(crate) fn num32(x: f32) -> String {
    let s = format!("{x:?}");
    if s == "-0.0" { "0.0".to_owned() } else { s }
}

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

/// Linear RGB in [0, 1] to an sRGB-encoded byte (three.js's hex colours).
pub(crate) fn linear_to_srgb_byte(x: f32) -> u32 {
    let x = x.clamp(0.0, 1.0);
    let encoded = if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    };
    // In range 0..=255 after the clamp.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let byte = (encoded * 255.0).round() as u32;
    byte
}

/// An sRGB-encoded byte to linear RGB.
pub(crate) fn srgb_byte_to_linear(byte: u32) -> f32 {
    #[allow(clippy::cast_precision_loss)]
    let x = (byte & 0xff) as f32 / 255.0;
    if x <= 0.040_45 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

/// A linear colour as three.js's `0xRRGGBB` (sRGB-encoded).
pub(crate) fn hex_color(color: Vec3) -> u32 {
    (linear_to_srgb_byte(color.x) << 16)
        | (linear_to_srgb_byte(color.y) << 8)
        | linear_to_srgb_byte(color.z)
}

/// three.js's `0xRRGGBB` as a linear colour.
pub(crate) fn color_from_hex(hex: u32) -> Vec3 {
    Vec3::new(
        srgb_byte_to_linear(hex >> 16),
        srgb_byte_to_linear(hex >> 8),
        srgb_byte_to_linear(hex),
    )
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
