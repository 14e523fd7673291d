//! What a ray query reports.

use glam::{Vec2, Vec3};

/// The closest intersection of a ray with a shape, a mesh or a [`World`](crate::World).
///
/// Both normals are unit vectors on the side the ray came from
/// (`normal . direction <= 0`), so shading never has to flip them;
/// [`Hit::front_face`] keeps the side that was hit. The default hit, all zeros, is
/// only a placeholder for buffers that
/// [`World::shading_surface_into`](crate::World::shading_surface_into) fills.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Hit {
    /// The ray parameter of the hit, in units of the ray's (unnormalized) direction.
    pub t: f32,
    /// The hit point `origin + t * direction`.
    pub point: Vec3,
    /// The geometric (true surface) unit normal, facing the ray's side.
    pub normal: Vec3,
    /// The unit normal to shade with, flipped together with [`Hit::normal`]: the
    /// interpolated vertex normal for meshes that have them, else the geometric normal.
    pub shading_normal: Vec3,
    /// Whether the ray hit the front: the outside of a sphere or box, the side a plane's
    /// normal points to, or the side from which a triangle's vertices `a, b, c` run
    /// counter-clockwise.
    pub front_face: bool,
    /// Surface coordinates: the mesh's texture coordinates when it has them, else the
    /// barycentric `(b1, b2)` of vertices `b` and `c` for triangles; see each shape for
    /// its own rule.
    pub uv: Vec2,
    /// The triangle's face index in its mesh's input (zero-area faces are skipped but
    /// keep their place in the numbering); 0 for other shapes.
    pub primitive: u32,
    /// The index of the object in the list the [`World`](crate::World) was built from
    /// (0 for queries on a single shape or mesh).
    pub object: u32,
}

/// A hit found during traversal, before the surface details are worked out.
///
/// Traversal finds many candidate hits and keeps only the closest; normals and texture
/// coordinates are computed once, for the winner, by the shape's `surface` method.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct RawHit {
    pub(crate) t: f32,
    /// The object index in the world.
    pub(crate) object: u32,
    /// The triangle index, or a shape-specific tag (the box face).
    pub(crate) primitive: u32,
    /// Barycentric coordinates `(b1, b2)` of vertices `b` and `c` for triangles.
    pub(crate) barycentric: Vec2,
}

/// Orients a surface frame toward the ray: flips both normals when the geometric one
/// faces along the direction, and reports whether it faced against it (the front).
pub(crate) fn face_toward(
    direction: Vec3,
    normal: Vec3,
    shading_normal: Vec3,
) -> (Vec3, Vec3, bool) {
    let front_face = normal.dot(direction) <= 0.0;
    if front_face {
        (normal, shading_normal, true)
    } else {
        (-normal, -shading_normal, false)
    }
}
