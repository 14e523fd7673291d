//! viewray's ray-casting core: rays, shapes, triangle meshes and the BVH.
//!
//! This crate owns the geometry a viewing ray meets. It knows nothing about cameras,
//! scene files or images, and it does no I/O.
//!
//! Rays keep the lecture's *unnormalized* directions: a ray is `origin + t * direction`
//! and every `t` this crate reports is in units of the ray's own direction, whatever
//! its length.

mod ray;

pub use ray::{DRay, Ray};
