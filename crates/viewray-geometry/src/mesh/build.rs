//! A [`Mesh`] built: validated data, the BVH over its triangles, and the triangles
//! stored leaf by leaf as packets of four.

use std::sync::atomic::{AtomicBool, Ordering};

use glam::Vec3;
use rayon::prelude::*;

use super::MeshData;
use super::data::validate;
use super::packets::{TrianglePacket, items_capacity, packets_bound};
use crate::bvh::{BuildItem, BuildParams, Bvh, MAX_ITEMS, advise_huge_pages};
use crate::{Aabb, GeometryError};

/// A triangle mesh with its own BVH, built once and shared by any number of
/// [`Instance`](crate::Instance)s.
///
/// [`Mesh::new`] validates the data, drops zero-area triangles, and builds an eight-wide
/// BVH by binned SAH whose leaves point at [packets](crate#design) of four triangles
/// stored in leaf order.
#[derive(Clone, Debug)]
pub struct Mesh {
    pub(super) data: MeshData,
    pub(super) bvh: Bvh,
    pub(super) packets: Vec<TrianglePacket>,
    pub(super) triangle_count: usize,
}

impl Mesh {
    /// Validates `data`, drops its zero-area triangles and builds the BVH (in parallel
    /// on the current rayon pool).
    ///
    /// # Errors
    ///
    /// - [`GeometryError::NonFinitePosition`] for an infinite or NaN position;
    /// - [`GeometryError::VertexOutOfRange`] for a face naming a missing vertex;
    /// - [`GeometryError::AttributeCount`] when normals or texture coordinates are not
    ///   one per vertex;
    /// - [`GeometryError::TooManyTriangles`] beyond 2^27 (134 million) faces.
    pub fn new(data: MeshData) -> Result<Self, GeometryError> {
        validate(&data)?;
        Ok(Self::new_unchecked(data))
    }

    /// The icosphere of [`MeshData::icosphere`], built.
    pub fn icosphere(subdivisions: u32, radius: f32) -> Self {
        Self::new_unchecked(MeshData::icosphere(subdivisions, radius))
    }

    fn new_unchecked(data: MeshData) -> Self {
        let positions = &data.positions;
        // Keep the faces with nonzero area, as build items with their boxes. Every face's
        // item is written in place in parallel (a filtering collect gathers per-thread
        // lists and copies them again); the zero-area faces, rare, get an empty box and
        // are dropped after.
        let faces = &data.triangles[..data.triangles.len().min(MAX_ITEMS)];
        let zero_area = AtomicBool::new(false);
        // The items' buffer becomes the packets' after the build (see below), so it is
        // made large enough for both.
        let mut items: Vec<BuildItem> = Vec::with_capacity(items_capacity(faces.len()));
        advise_huge_pages(&mut items);
        faces
            .par_iter()
            .enumerate()
            .map(|(face, &[a, b, c])| {
                let [a, b, c] = [a, b, c].map(|i| positions[i as usize]);
                if (b - a).cross(c - a) == Vec3::ZERO {
                    zero_area.store(true, Ordering::Relaxed);
                    return BuildItem::new(Aabb::EMPTY, face as u32);
                }
                BuildItem::new(Aabb::from_points([a, b, c]), face as u32)
            })
            .collect_into_vec(&mut items);
        if zero_area.into_inner() {
            items.retain(|item| !item.is_empty());
        }
        let triangle_count = items.len();
        let params = BuildParams {
            block_size: 4,
            max_leaf_items: 8,
            traversal_cost: 1.0,
        };
        let mut bvh = Bvh::build_from(&mut items, params);

        // Store the triangles leaf by leaf in packets of four, and point the leaves at
        // their packets instead of their triangles. The packets are filled in parallel
        // (gathering their vertices waits on memory), each from its run of faces in leaf
        // order, worked out first.
        let mut runs: Vec<(u32, u32)> = Vec::with_capacity(packets_bound(triangle_count));
        bvh.remap_leaves(|start, count| {
            let first_packet = runs.len() as u32;
            runs.extend(
                (start..start + count)
                    .step_by(4)
                    .map(|s| (s, (start + count - s).min(4))),
            );
            (first_packet, runs.len() as u32 - first_packet)
        });
        let order = bvh.item_order();
        // The packets are written into the build items' memory, done with: pages the
        // items touched are not faulted in and zeroed by the kernel again (a tenth of a
        // build went to that). A cast of the whole buffer, from empty to empty.
        items.clear();
        let mut packets: Vec<TrianglePacket> =
            bytemuck::allocation::try_cast_vec(items).unwrap_or_default();
        // A buffer of their own only where the items' is too small (scattered triangles).
        packets.reserve_exact(runs.len());
        advise_huge_pages(&mut packets);
        runs.par_iter()
            .map(|&(start, count)| {
                TrianglePacket::new(&order[start as usize..(start + count) as usize], &data)
            })
            .collect_into_vec(&mut packets);
        bvh.clear_item_order();
        Self {
            data,
            bvh,
            packets,
            triangle_count,
        }
    }

    /// The vertex and face data the mesh was built from.
    pub fn data(&self) -> &MeshData {
        &self.data
    }

    #[cfg(test)]
    pub(crate) fn bvh(&self) -> &Bvh {
        &self.bvh
    }

    /// The number of triangles intersected: the faces less the zero-area ones.
    pub fn triangle_count(&self) -> usize {
        self.triangle_count
    }

    /// The box around every triangle.
    pub fn bounds(&self) -> Aabb {
        self.bvh.bounds()
    }

    /// The number of triangle packets.
    #[cfg(test)]
    pub(crate) fn packet_count(&self) -> usize {
        self.packets.len()
    }

    /// The capacity of the packets' buffer.
    #[cfg(test)]
    pub(crate) fn packet_capacity(&self) -> usize {
        self.packets.capacity()
    }

    /// The memory of the acceleration data: BVH nodes and triangle packets, in bytes.
    pub fn acceleration_bytes(&self) -> usize {
        self.bvh.memory_bytes() + self.packets.len() * std::mem::size_of::<TrianglePacket>()
    }
}
