//! The one error type of this crate: invalid geometry rejected where it is built.

use glam::Vec3;

/// Why a mesh, an instance or a world could not be built.
///
/// Each message says what is wrong with which element, so a scene loader can prefix it
/// with a file position and show it as is.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum GeometryError {
    /// A flat attribute array does not hold whole vectors.
    #[error("{attribute} has {len} numbers, which is not a multiple of {stride}")]
    FlatLength {
        /// The attribute ("positions", "indices", "normals", "texture coordinates").
        attribute: &'static str,
        /// Its number of `f32`s or `u32`s.
        len: usize,
        /// How many numbers make one element.
        stride: usize,
    },
    /// A face names a vertex that does not exist.
    #[error("face {face} refers to vertex {vertex} but the mesh has {vertex_count} vertices")]
    VertexOutOfRange {
        /// The face (triangle) index.
        face: usize,
        /// The vertex index it holds.
        vertex: u32,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// A vertex position is infinite or NaN.
    #[error("vertex {vertex} has the non-finite position {position}")]
    NonFinitePosition {
        /// The vertex index.
        vertex: usize,
        /// Its position.
        position: Vec3,
    },
    /// A per-vertex attribute does not have one entry per vertex.
    #[error("the mesh has {vertex_count} vertices but {count} {attribute}")]
    AttributeCount {
        /// The attribute ("normals" or "texture coordinates").
        attribute: &'static str,
        /// How many entries it has.
        count: usize,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// A mesh has more faces than the BVH can index.
    #[error("the mesh has {count} triangles; at most {limit} are supported")]
    TooManyTriangles {
        /// The number of faces.
        count: usize,
        /// The most a mesh may have.
        limit: usize,
    },
    /// An instance transform cannot be inverted or is not finite.
    #[error("the transform is not invertible (determinant {determinant})")]
    SingularTransform {
        /// The determinant of its linear part.
        determinant: f32,
    },
    /// A shape's parameters do not describe a surface.
    #[error("object {object}: {reason}")]
    InvalidObject {
        /// The object's index in the world's list.
        object: usize,
        /// What is wrong, e.g. "sphere radius -1 is not positive".
        reason: String,
    },
}
