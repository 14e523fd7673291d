//! viewray's ray-casting core: rays, shapes, triangle meshes and the BVH.
//!
//! This crate owns the geometry a viewing ray meets. It knows nothing about cameras,
//! scene files or images, and it does no I/O.
//!
//! Rays keep the lecture's *unnormalized* directions: a ray is `origin + t * direction`
//! and every `t` this crate reports is in units of the ray's own direction, whatever
//! its length.

mod aabb;
mod bvh;
mod error;
mod hit;
mod instance;
mod mesh;
mod ray;
mod shapes;
#[cfg(test)]
mod tests;
mod world;

pub use aabb::Aabb;
pub use bvh::{Bounded, BuildParams, Bvh};
pub use error::GeometryError;
pub use hit::Hit;
pub use instance::Instance;
pub use mesh::{Mesh, MeshData, TriangleHit};
pub use ray::{DRay, Ray};
pub use shapes::{Plane, Sphere, Triangle};
pub use world::{Object, World};
