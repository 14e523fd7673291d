//! Triangle packets: a leaf's triangles four at a time in structure-of-arrays layout,
//! and the watertight test of one ray against the four at once.

use glam::{BVec4A, Mat4, Vec4};

use super::MeshData;
use crate::bvh::BuildItem;
use crate::shapes::{WatertightRay, edge_functions_f64};

/// Four triangles in structure-of-arrays layout, for one SIMD watertight test.
///
/// `vertices[corner][axis][lane]`; a leaf with a number of triangles that is not a
/// multiple of four repeats its last triangle (a duplicate can only report the same
/// hit). 160 bytes for four triangles.
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(16))]
pub(super) struct TrianglePacket {
    vertices: [[[f32; 4]; 3]; 3],
    pub(super) faces: [u32; 4],
}

impl TrianglePacket {
    /// The packet of the faces `chunk` (one to four) of `data`; a short chunk repeats its
    /// last face in the spare lanes.
    pub(super) fn new(chunk: &[u32], data: &MeshData) -> Self {
        let faces: [u32; 4] = std::array::from_fn(|lane| chunk[lane.min(chunk.len() - 1)]);
        let corners = faces.map(|face| data.triangles[face as usize]);
        // Each corner's four points as the columns of a matrix, transposed into rows of
        // x, y and z: written whole, not lane by lane (a packet assembled from 36 small
        // stores and then copied out waits on those stores).
        let vertices = std::array::from_fn(|corner| {
            let point = |lane: usize| data.positions[corners[lane][corner] as usize].extend(0.0);
            let rows = Mat4::from_cols(point(0), point(1), point(2), point(3)).transpose();
            [rows.x_axis, rows.y_axis, rows.z_axis].map(|row| row.to_array())
        });
        Self { vertices, faces }
    }
}

/// How many packets the leaves of a mesh of `triangles` triangles take at most, as a
/// rule: a leaf of `n` triangles takes `ceil(n / 4)`, and the leaves of a surface mesh
/// hold 4 to 8 triangles but for a few, so an eighth more than a quarter. (Scattered
/// triangles make small leaves and may take more.)
pub(crate) fn packets_bound(triangles: usize) -> usize {
    triangles.div_ceil(4) + triangles / 8
}

/// How many build items take the memory of one triangle packet.
pub(crate) const ITEMS_PER_PACKET: usize =
    std::mem::size_of::<TrianglePacket>() / std::mem::size_of::<BuildItem>();
const _: () = assert!(
    ITEMS_PER_PACKET * std::mem::size_of::<BuildItem>() == std::mem::size_of::<TrianglePacket>()
);

/// The capacity of a mesh's build items for `faces` faces: at least one item per face,
/// and room for [`packets_bound`] packets, in whole packets.
pub(crate) fn items_capacity(faces: usize) -> usize {
    faces
        .max(packets_bound(faces) * ITEMS_PER_PACKET)
        .next_multiple_of(ITEMS_PER_PACKET)
}

/// A ray prepared for packet tests: [`WatertightRay`] with its numbers splatted.
#[derive(Clone, Copy, Debug)]
pub(super) struct PacketRay {
    k: [usize; 3],
    origin: [Vec4; 3],
    shear: [Vec4; 3],
}

impl PacketRay {
    pub(super) fn new(ray: &WatertightRay) -> Self {
        Self {
            k: ray.k,
            origin: ray.k.map(|k| Vec4::splat(ray.origin.to_array()[k])),
            shear: [
                Vec4::splat(ray.shear.x),
                Vec4::splat(ray.shear.y),
                Vec4::splat(ray.shear.z),
            ],
        }
    }

    /// The four triangles' edge functions for this ray (see [`WatertightRay`]), or
    /// `None` when the ray passes beside all four: most of a leaf's triangles do, and
    /// their edges alone decide it, before the division for `t` in
    /// [`PacketEdges::hits`]. (Callers skip to the next packet on `None`; folded into
    /// one expression with the hits, the check was compiled away in some builds.)
    #[inline(always)]
    pub(super) fn edges(&self, packet: &TrianglePacket) -> Option<PacketEdges> {
        let [kx, ky, kz] = self.k;
        let corner = |i: usize| {
            let v = &packet.vertices[i];
            let z = Vec4::from_array(v[kz]) - self.origin[2];
            let x = Vec4::from_array(v[kx]) - self.origin[0] - self.shear[0] * z;
            let y = Vec4::from_array(v[ky]) - self.origin[1] - self.shear[1] * z;
            (x, y, z)
        };
        let (ax, ay, az) = corner(0);
        let (bx, by, bz) = corner(1);
        let (cx, cy, cz) = corner(2);
        let mut u = cx * by - cy * bx;
        let mut v = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        let zero = Vec4::ZERO;
        if (u.cmpeq(zero) | v.cmpeq(zero) | w.cmpeq(zero)).any() {
            [u, v, w] = recompute_edges_f64([ax, ay, bx, by, cx, cy], [u, v, w]);
        }
        // Outside where the edge functions differ in sign: some below zero and some
        // above, that is the least below and the greatest above. (A NaN lane may come
        // out either way here; its `det`, and so its `t`, is NaN, and no NaN is a hit.)
        let negative = u.min(v).min(w).cmplt(zero);
        let positive = u.max(v).max(w).cmpgt(zero);
        let inside = !(negative & positive);
        inside.any().then_some(PacketEdges {
            inside,
            edges: [u, v, w],
            z: [az, bz, cz],
            sz: self.shear[2],
        })
    }
}

/// A ray's edge functions for four triangles of which it passes beside at most three
/// (see [`PacketRay::edges`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct PacketEdges {
    /// The lanes whose edge functions do not differ in sign.
    inside: BVec4A,
    edges: [Vec4; 3],
    /// The corners' sheared `z`, and the ray's `z` shear.
    z: [Vec4; 3],
    sz: Vec4,
}

impl PacketEdges {
    /// The lanes that the ray hits with `t_min <= t < t_max`, with their `t`, edge
    /// functions and determinants.
    #[inline(always)]
    pub(super) fn hits(&self, t_min: Vec4, t_max: Vec4) -> (BVec4A, Vec4, [Vec4; 3], Vec4) {
        let [u, v, w] = self.edges;
        let [az, bz, cz] = self.z;
        let sz = self.sz;
        let det = u + v + w;
        let t = (u * (sz * az) + v * (sz * bz) + w * (sz * cz)) / det;
        let valid = self.inside & det.cmpne(Vec4::ZERO) & t.cmpge(t_min) & t.cmplt(t_max);
        (valid, t, self.edges, det)
    }
}

/// Recomputes in `f64` the lanes where an edge function rounded to exactly zero.
#[cold]
#[inline(never)]
fn recompute_edges_f64(coords: [Vec4; 6], edges: [Vec4; 3]) -> [Vec4; 3] {
    let [ax, ay, bx, by, cx, cy] = coords.map(|c| c.to_array());
    let [mut u, mut v, mut w] = edges.map(|e| e.to_array());
    for lane in 0..4 {
        if u[lane] == 0.0 || v[lane] == 0.0 || w[lane] == 0.0 {
            (u[lane], v[lane], w[lane]) = edge_functions_f64(
                [ax[lane], ay[lane]],
                [bx[lane], by[lane]],
                [cx[lane], cy[lane]],
            );
        }
    }
    [u, v, w].map(Vec4::from_array)
}
