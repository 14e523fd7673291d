//! obvhs's CWBVH, the peer for memory and for the check that the hits agree.

use std::time::Duration;

use glam::Vec3A;
use viewray_geometry::{MeshData, Ray};

/// obvhs's CWBVH with its triangles stored in BVH order, as its examples recommend.
pub(crate) struct Obvhs {
    bvh: obvhs::cwbvh::CwBvh,
    triangles: Vec<obvhs::triangle::Triangle>,
}

impl Obvhs {
    /// Builds the CWBVH of `data`'s triangles (medium quality).
    pub(crate) fn build(data: &MeshData) -> Self {
        let triangles: Vec<obvhs::triangle::Triangle> = data
            .triangles
            .iter()
            .map(|t| {
                let [v0, v1, v2] = t.map(|i| Vec3A::from(data.positions[i as usize]));
                obvhs::triangle::Triangle { v0, v1, v2 }
            })
            .collect();
        let bvh = obvhs::cwbvh::builder::build_cwbvh_from_tris(
            &triangles,
            obvhs::BvhBuildParams::medium_build(),
            &mut Duration::default(),
        );
        let triangles = bvh
            .primitive_indices
            .iter()
            .map(|&i| triangles[i as usize])
            .collect();
        Self { bvh, triangles }
    }

    /// The closest hit's `t`.
    pub(crate) fn closest_t(&self, ray: &Ray) -> Option<f32> {
        let ray = obvhs::ray::Ray::new_inf(ray.origin.into(), ray.direction.into());
        let mut hit = obvhs::ray::RayHit::none();
        self.bvh
            .ray_traverse(ray, &mut hit, |ray, id| self.triangles[id].intersect(ray))
            .then_some(hit.t)
    }

    /// The bytes of the nodes, the indices and the triangles.
    pub(crate) fn bytes(&self) -> usize {
        self.bvh.nodes.len() * std::mem::size_of::<obvhs::cwbvh::node::CwBvhNode>()
            + self.bvh.primitive_indices.len() * 4
            + self.triangles.len() * std::mem::size_of::<obvhs::triangle::Triangle>()
    }
}
