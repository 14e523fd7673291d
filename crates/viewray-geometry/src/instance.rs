//! Meshes placed in the world by affine transforms.

use std::ops::Range;
use std::sync::Arc;

use glam::{Affine3A, Mat3A, Vec3, Vec4};

use crate::hit::{Hit, RawHit};
use crate::packet::{
    BoxPacket, PACKET_GROUPS, PACKET_SIZE, PacketQuery, for_each_packet, lane as packet_lane,
    lanes_of, set_lane,
};
use crate::{Aabb, GeometryError, Mesh, Ray};

/// A shared [`Mesh`] placed by an affine transform (scale, rotation, translation).
///
/// The mesh and its BVH are built once, in object space, and shared through the
/// [`Arc`]; a ray is carried into object space instead of the mesh into the world:
///
/// ```text
/// o' = object_from_world o,   d' = object_from_world d   (linear part only)
/// ```
///
/// The ray parameter is unchanged by an affine map, so `t` needs no conversion; normals
/// go back to the world by the inverse transpose, `n = (M^-1)^T n'`, which keeps them
/// perpendicular to the surface under non-uniform scale.
#[derive(Clone, Debug)]
pub struct Instance {
    mesh: Arc<Mesh>,
    /// Whether the transform is exactly the identity: rays then need no carrying.
    identity: bool,
    world_from_object: Affine3A,
    object_from_world: Affine3A,
    normal_matrix: Mat3A,
    bounds: Aabb,
}

impl Instance {
    /// `mesh` placed by `world_from_object`.
    ///
    /// # Errors
    ///
    /// [`GeometryError::SingularTransform`] when the transform is not finite or its
    /// linear part cannot be inverted (a zero scale, for example).
    pub fn new(mesh: Arc<Mesh>, world_from_object: Affine3A) -> Result<Self, GeometryError> {
        let determinant = world_from_object.matrix3.determinant();
        if !world_from_object.is_finite() || determinant == 0.0 || !determinant.is_finite() {
            return Err(GeometryError::SingularTransform { determinant });
        }
        let object_from_world = world_from_object.inverse();
        if !object_from_world.is_finite() {
            return Err(GeometryError::SingularTransform { determinant });
        }
        let normal_matrix = object_from_world.matrix3.transpose();
        let mesh_bounds = mesh.bounds();
        let bounds = if mesh_bounds.is_empty() {
            Aabb::EMPTY
        } else {
            Aabb::from_points(
                mesh_bounds
                    .corners()
                    .map(|p| world_from_object.transform_point3(p)),
            )
        };
        Ok(Self {
            mesh,
            identity: world_from_object == Affine3A::IDENTITY,
            world_from_object,
            object_from_world,
            normal_matrix,
            bounds,
        })
    }

    /// The mesh, untransformed (the identity placement).
    pub fn from_mesh(mesh: Arc<Mesh>) -> Self {
        let bounds = mesh.bounds();
        Self {
            mesh,
            identity: true,
            world_from_object: Affine3A::IDENTITY,
            object_from_world: Affine3A::IDENTITY,
            normal_matrix: Mat3A::IDENTITY,
            bounds,
        }
    }

    /// The shared mesh.
    pub fn mesh(&self) -> &Arc<Mesh> {
        &self.mesh
    }

    /// The placement: world coordinates from mesh coordinates.
    pub fn world_from_object(&self) -> Affine3A {
        self.world_from_object
    }

    /// The world-space box around the transformed mesh box.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    fn object_ray(&self, ray: &Ray) -> Ray {
        Ray::new(
            self.object_from_world.transform_point3(ray.origin),
            self.object_from_world.transform_vector3(ray.direction),
        )
    }

    /// The closest hit with `t` in `t_range`, in world space.
    pub fn closest_hit(&self, ray: &Ray, t_range: Range<f32>) -> Option<Hit> {
        let raw = self.intersect(ray, t_range.start, t_range.end)?;
        Some(self.surface(ray, &raw))
    }

    /// Whether the mesh is hit with `t` in `t_range`.
    pub fn any_hit(&self, ray: &Ray, t_range: Range<f32>) -> bool {
        if self.identity {
            // As in `intersect`: the ray is its own object-space ray.
            self.mesh.any_hit(ray, t_range)
        } else {
            self.mesh.any_hit(&self.object_ray(ray), t_range)
        }
    }

    /// Which rays of `lanes` of a packet (in world space, filled from `rays`) hit the
    /// mesh with `t` in `t_range`: the answers of [`Instance::any_hit`] ray by ray. As in
    /// [`Instance::intersect_packet`], the rays are carried into the mesh's space and
    /// regrouped into packets there, unless the transform is the identity.
    pub(crate) fn any_packet(
        &self,
        packet: &BoxPacket<'_>,
        rays: &[Ray],
        lanes: u64,
        t_range: Range<f32>,
    ) -> u64 {
        if self.identity {
            return self.mesh.any_packet(packet, rays, lanes, t_range);
        }
        let mut object_rays = [Ray::new(Vec3::ZERO, Vec3::ZERO); PACKET_SIZE];
        let mut lane_of = [0u8; PACKET_SIZE];
        let mut count = 0;
        for lane in lanes_of(lanes) {
            object_rays[count] = self.object_ray(&rays[usize::from(packet.rays()[lane])]);
            lane_of[count] = lane as u8;
            count += 1;
        }
        let object_rays = &object_rays[..count];
        let mut found = 0;
        for_each_packet(object_rays, |object_packet| {
            let hit = self.mesh.any_packet(
                object_packet,
                object_rays,
                object_packet.all_lanes(),
                t_range.clone(),
            );
            for object_lane in lanes_of(hit) {
                let ray = usize::from(object_packet.rays()[object_lane]);
                found |= 1 << lane_of[ray];
            }
        });
        found
    }

    pub(crate) fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<RawHit> {
        if self.identity {
            // The identity maps a ray onto itself (up to the sign of zero components,
            // which no test depends on).
            self.mesh.intersect(ray, t_min, t_max)
        } else {
            self.mesh.intersect(&self.object_ray(ray), t_min, t_max)
        }
    }

    /// The closest hits of a query's rays (in world space), as hits on object `object`:
    /// see [`Mesh::intersect_packet`]. Rays are carried into the mesh's space and
    /// regrouped into packets there, unless the transform is the identity.
    pub(crate) fn intersect_packet(&self, query: PacketQuery<'_>, object: u32) {
        if self.identity {
            self.mesh.intersect_packet(query, object);
            return;
        }
        let mut object_rays = [Ray::new(Vec3::ZERO, Vec3::ZERO); PACKET_SIZE];
        let mut lane_of = [0u8; PACKET_SIZE];
        let mut count = 0;
        for lane in lanes_of(query.lanes) {
            object_rays[count] = self.object_ray(query.ray(lane));
            lane_of[count] = lane as u8;
            count += 1;
        }
        let object_rays = &object_rays[..count];
        for_each_packet(object_rays, |object_packet| {
            let lanes = object_packet
                .rays()
                .iter()
                .map(|&i| usize::from(lane_of[usize::from(i)]));
            let mut object_t_max = [Vec4::ZERO; PACKET_GROUPS];
            for (object_lane, lane) in lanes.clone().enumerate() {
                set_lane(
                    &mut object_t_max,
                    object_lane,
                    packet_lane(query.t_max, lane),
                );
            }
            let mut object_best = [None; PACKET_SIZE];
            let object_query = PacketQuery {
                packet: object_packet,
                rays: object_rays,
                lanes: object_packet.all_lanes(),
                t_min: query.t_min,
                t_max: &mut object_t_max,
                best: &mut object_best,
            };
            self.mesh.intersect_packet(object_query, object);
            for (object_lane, lane) in lanes.enumerate() {
                if let Some(hit) = object_best[object_lane] {
                    query.best[lane] = Some(hit);
                    set_lane(query.t_max, lane, hit.t);
                }
            }
        });
    }

    pub(crate) fn surface(&self, ray: &Ray, raw: &RawHit) -> Hit {
        let local = self.mesh.surface_of(&self.object_ray(ray), raw);
        let to_world = |n: Vec3| (self.normal_matrix * n).normalize_or(n);
        Hit {
            point: ray.at(raw.t),
            normal: to_world(local.normal),
            shading_normal: to_world(local.shading_normal),
            ..local
        }
    }
}
