//! A packet's box tests: the whole packet against a node's eight boxes by interval
//! arithmetic, and the rays of some lanes against one box, each with exactly the
//! single-ray test.

use glam::Vec4;

use super::lanes::Lanes;
use super::rays::BoxPacket;
use crate::bvh::{
    BoxRay, ChildBoxes, GROUPS, Node, WIDTH, node_planes, per_axis, plane_distances, plane_index,
    slab_test,
};

impl BoxPacket<'_> {
    /// Tests the whole packet against a node's eight boxes: returns the mask of boxes
    /// that some ray of the packet may hit with `t` in `[t_min, t_max]`, and a lower
    /// bound of the distances at which the rays enter them.
    ///
    /// For each slab plane the distance `(plane - o) * inverse` of every ray lies
    /// between the products of the packet's bounding origin and its two extreme
    /// reciprocals, because rounded subtraction and multiplication are monotonic; so
    /// a box culled here is culled by the single-ray test of every ray in the packet.
    #[inline(always)]
    pub(super) fn hit_children_sse<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: Vec4,
        t_max: Vec4,
    ) -> (u32, [f32; WIDTH]) {
        let mut mask = 0;
        let mut t_near_all = [0.0; WIDTH];
        for group in 0..GROUPS {
            let lanes = 4 * group..4 * group + 4;
            let (near_plane, far_plane) = node_planes::<OCTANT>(&node.planes, lanes.clone());
            let near = per_axis(|axis| {
                let near = near_plane[axis] - self.bound_origin_near[axis];
                (near * self.inverse_min[axis]).min(near * self.inverse_max[axis])
            });
            let far = per_axis(|axis| {
                let far = far_plane[axis] - self.bound_origin_far[axis];
                (far * self.inverse_min[axis]).max(far * self.inverse_max[axis])
            });
            let (hit, t_near) = slab_test(near, far, t_min, t_max);
            mask |= hit << (4 * group);
            t_near.write_to_slice(&mut t_near_all[lanes]);
        }
        (mask, t_near_all)
    }

    /// The rays of `lanes` that hit child `slot` of `node` with `t` in `[t_min,
    /// t_max[lane]]`: for each ray exactly the test of [`BoxRay::hit_children_sse`], four
    /// rays at a time.
    #[inline(always)]
    pub(crate) fn rays_hitting<const OCTANT: u8>(
        &self,
        node: &Node,
        slot: usize,
        lanes: u64,
        t_min: Vec4,
        t_max: &Lanes,
    ) -> u64 {
        let plane = |axis: usize, far: bool| {
            Vec4::splat(node.planes[plane_index::<OCTANT>(axis, far)][slot])
        };
        let near_plane = per_axis(|axis| plane(axis, false));
        let far_plane = per_axis(|axis| plane(axis, true));
        let mut hit = 0;
        let mut rest = lanes;
        while rest != 0 {
            let group = rest.trailing_zeros() as usize / 4;
            rest &= !(0xf << (4 * group));
            let (near, far) = plane_distances(
                near_plane,
                far_plane,
                per_axis(|axis| self.numbers.origin_near[axis][group]),
                per_axis(|axis| self.numbers.origin_far[axis][group]),
                per_axis(|axis| self.numbers.inverse[axis][group]),
            );
            let (group_hit, _) = slab_test(near, far, t_min, t_max[group]);
            hit |= u64::from(group_hit) << (4 * group);
        }
        hit & lanes
    }
}

/// A packet's box tests: the whole packet's test of a node's eight boxes (see
/// [`BoxPacket::hit_children_sse`]) and its lanes' single rays, with SSE
/// ([`BoxPacket`]) or in AVX registers where the processor has them
/// (`avx::AvxPacket`), with the same bits.
pub(crate) trait PacketBoxes {
    /// A lane's ray.
    type Ray: ChildBoxes;

    /// The packet tested.
    fn packet(&self) -> &BoxPacket<'_>;

    /// The mask of the boxes some ray of the packet may hit with `t` in `[t_min,
    /// t_max]`, and a lower bound of their entry distances.
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]);

    /// The ray of lane `lane`.
    fn lane_ray(&self, lane: usize) -> Self::Ray;

    /// The rays of `lanes` that hit child `slot` of `node` with `t` in `[t_min,
    /// t_max[lane]]`, each with exactly its single-ray test (see
    /// [`BoxPacket::rays_hitting`]).
    fn rays_hitting<const OCTANT: u8>(
        &self,
        node: &Node,
        slot: usize,
        lanes: u64,
        t_min: f32,
        t_max: &Lanes,
    ) -> u64;
}

impl PacketBoxes for BoxPacket<'_> {
    type Ray = BoxRay;

    #[inline(always)]
    fn packet(&self) -> &BoxPacket<'_> {
        self
    }

    #[inline(always)]
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]) {
        self.hit_children_sse::<OCTANT>(node, Vec4::splat(t_min), Vec4::splat(t_max))
    }

    #[inline(always)]
    fn lane_ray(&self, lane: usize) -> BoxRay {
        BoxPacket::lane_ray(self, lane)
    }

    #[inline(always)]
    fn rays_hitting<const OCTANT: u8>(
        &self,
        node: &Node,
        slot: usize,
        lanes: u64,
        t_min: f32,
        t_max: &Lanes,
    ) -> u64 {
        BoxPacket::rays_hitting::<OCTANT>(self, node, slot, lanes, Vec4::splat(t_min), t_max)
    }
}
