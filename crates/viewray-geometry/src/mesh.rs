//! Triangle meshes: validated vertex data, triangle packets in leaf order, and the BVH.

use std::collections::HashMap;
use std::ops::Range;
use std::sync::atomic::{AtomicBool, Ordering};

use glam::{BVec4A, Mat4, Vec2, Vec3, Vec4};
use rayon::prelude::*;

use crate::bvh::{BoxRay, BuildItem, BuildParams, Bvh, MAX_ITEMS, advise_huge_pages, prefetch};
use crate::hit::{Hit, RawHit, face_toward};
use crate::packet::{PACKET_GROUPS, PACKET_SIZE, PacketQuery, PacketVisitor, for_each_packet};
use crate::shapes::{WatertightRay, edge_functions_f64};
use crate::{Aabb, GeometryError, Ray};

/// The vertex and face data of a triangle mesh, before validation.
///
/// Vertex attributes are indexed together (one index per corner, as tobj delivers them
/// with `single_index = true`). Build it from vectors with [`MeshData::new`] and the
/// `with_` methods, or from tobj's flat arrays with [`MeshData::from_flat`].
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MeshData {
    /// Vertex positions.
    pub positions: Vec<Vec3>,
    /// Triangles as three vertex indices, counter-clockwise seen from the front.
    pub triangles: Vec<[u32; 3]>,
    /// Per-vertex normals for smooth shading, if any.
    pub normals: Option<Vec<Vec3>>,
    /// Per-vertex texture coordinates, if any.
    pub uvs: Option<Vec<Vec2>>,
}

impl MeshData {
    /// Positions and triangles, without normals or texture coordinates.
    pub fn new(positions: Vec<Vec3>, triangles: Vec<[u32; 3]>) -> Self {
        Self {
            positions,
            triangles,
            normals: None,
            uvs: None,
        }
    }

    /// The same data with per-vertex normals.
    #[must_use]
    pub fn with_normals(mut self, normals: Vec<Vec3>) -> Self {
        self.normals = Some(normals);
        self
    }

    /// The same data with per-vertex texture coordinates.
    #[must_use]
    pub fn with_uvs(mut self, uvs: Vec<Vec2>) -> Self {
        self.uvs = Some(uvs);
        self
    }

    /// Mesh data from flat arrays as tobj's `Mesh` holds them: `positions` and `normals`
    /// as `x, y, z` triples, `texcoords` as `u, v` pairs, `indices` as triangle
    /// corners. An empty `normals` or `texcoords` means the mesh has none.
    ///
    /// # Errors
    ///
    /// [`GeometryError::FlatLength`] when an array does not hold whole elements.
    pub fn from_flat(
        positions: &[f32],
        indices: &[u32],
        normals: &[f32],
        texcoords: &[f32],
    ) -> Result<Self, GeometryError> {
        fn chunks<const N: usize>(
            attribute: &'static str,
            values: &[f32],
        ) -> Result<Vec<[f32; N]>, GeometryError> {
            let (chunks, rest) = values.as_chunks::<N>();
            if rest.is_empty() {
                Ok(chunks.to_vec())
            } else {
                Err(GeometryError::FlatLength {
                    attribute,
                    len: values.len(),
                    stride: N,
                })
            }
        }
        let (triangles, rest) = indices.as_chunks::<3>();
        if !rest.is_empty() {
            return Err(GeometryError::FlatLength {
                attribute: "indices",
                len: indices.len(),
                stride: 3,
            });
        }
        let to_vec3 = |v: Vec<[f32; 3]>| v.into_iter().map(Vec3::from).collect::<Vec<_>>();
        let positions = to_vec3(chunks::<3>("positions", positions)?);
        let normals = chunks::<3>("normals", normals)?;
        let uvs = chunks::<2>("texture coordinates", texcoords)?;
        Ok(Self {
            positions,
            triangles: triangles.to_vec(),
            normals: (!normals.is_empty()).then(|| to_vec3(normals)),
            uvs: (!uvs.is_empty()).then(|| uvs.into_iter().map(Vec2::from).collect()),
        })
    }

    /// An icosphere: a regular icosahedron whose faces are each split into four
    /// `subdivisions` times, with every vertex pushed onto the sphere of radius `radius`
    /// around the origin; `20 * 4^subdivisions` triangles sharing their vertices
    /// exactly (a closed, watertight mesh), with the sphere's normals.
    ///
    /// `subdivisions` is clamped to 11 (84 million triangles), the most a mesh can index.
    pub fn icosphere(subdivisions: u32, radius: f32) -> Self {
        let subdivisions = subdivisions.min(11);
        let phi = (1.0 + 5f32.sqrt()) / 2.0;
        let mut unit: Vec<Vec3> = [
            (-1.0, phi, 0.0),
            (1.0, phi, 0.0),
            (-1.0, -phi, 0.0),
            (1.0, -phi, 0.0),
            (0.0, -1.0, phi),
            (0.0, 1.0, phi),
            (0.0, -1.0, -phi),
            (0.0, 1.0, -phi),
            (phi, 0.0, -1.0),
            (phi, 0.0, 1.0),
            (-phi, 0.0, -1.0),
            (-phi, 0.0, 1.0),
        ]
        .map(|(x, y, z)| Vec3::new(x, y, z).normalize())
        .to_vec();
        let mut triangles: Vec<[u32; 3]> = vec![
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ];
        for _ in 0..subdivisions {
            let mut midpoints: HashMap<(u32, u32), u32> =
                HashMap::with_capacity(triangles.len() * 3 / 2);
            let mut midpoint = |a: u32, b: u32, unit: &mut Vec<Vec3>| {
                *midpoints.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    unit.push((unit[a as usize] + unit[b as usize]).normalize());
                    unit.len() as u32 - 1
                })
            };
            let mut next = Vec::with_capacity(triangles.len() * 4);
            for [a, b, c] in triangles {
                let ab = midpoint(a, b, &mut unit);
                let bc = midpoint(b, c, &mut unit);
                let ca = midpoint(c, a, &mut unit);
                next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
            }
            triangles = next;
        }
        let positions = unit.iter().map(|&n| n * radius).collect();
        Self::new(positions, triangles).with_normals(unit)
    }

    /// The closed box mesh of `bounds`: 8 shared corners, 12 outward-facing triangles.
    pub fn cuboid(bounds: Aabb) -> Self {
        let faces = [
            [0, 2, 3, 1], // -z
            [4, 5, 7, 6], // +z
            [0, 1, 5, 4], // -y
            [2, 6, 7, 3], // +y
            [0, 4, 6, 2], // -x
            [1, 3, 7, 5], // +x
        ];
        let triangles = faces
            .iter()
            .flat_map(|&[a, b, c, d]| [[a, b, c], [a, c, d]])
            .collect();
        Self::new(bounds.corners().to_vec(), triangles)
    }
}

/// The closest triangle of a mesh that a ray meets, before the surface details are
/// computed (see [`Mesh::closest_triangle`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TriangleHit {
    /// The ray parameter, in units of the ray's direction.
    pub t: f32,
    /// The face index.
    pub primitive: u32,
    /// The barycentric coordinates `(b1, b2)` of the face's second and third vertices:
    ///
    /// ```text
    /// point = (1 - b1 - b2) a + b1 b + b2 c
    /// ```
    pub barycentric: Vec2,
}

/// Four triangles in structure-of-arrays layout, for one SIMD watertight test.
///
/// `vertices[corner][axis][lane]`; a leaf with a number of triangles that is not a
/// multiple of four repeats its last triangle (a duplicate can only report the same
/// hit). 160 bytes for four triangles.
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C, align(16))]
struct TrianglePacket {
    vertices: [[[f32; 4]; 3]; 3],
    faces: [u32; 4],
}

impl TrianglePacket {
    /// The packet of the faces `chunk` (one to four) of `data`; a short chunk repeats its
    /// last face in the spare lanes.
    fn new(chunk: &[u32], data: &MeshData) -> Self {
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
struct PacketRay {
    k: [usize; 3],
    origin: [Vec4; 3],
    shear: [Vec4; 3],
}

impl PacketRay {
    fn new(ray: &WatertightRay) -> Self {
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
    fn edges(&self, packet: &TrianglePacket) -> Option<PacketEdges> {
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
struct PacketEdges {
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
    fn hits(&self, t_min: Vec4, t_max: Vec4) -> (BVec4A, Vec4, [Vec4; 3], Vec4) {
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

/// A triangle mesh with its own BVH, built once and shared by any number of
/// [`Instance`](crate::Instance)s.
///
/// [`Mesh::new`] validates the data, drops zero-area triangles, and builds an eight-wide
/// BVH by binned SAH whose leaves point at [packets](crate#design) of four triangles
/// stored in leaf order.
#[derive(Clone, Debug)]
pub struct Mesh {
    data: MeshData,
    bvh: Bvh,
    packets: Vec<TrianglePacket>,
    triangle_count: usize,
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

    /// The closest hit with `t` in `t_range` (`t_range.start <= t < t_range.end`).
    ///
    /// [`Hit::primitive`] is the face index; [`Hit::object`] is 0.
    pub fn closest_hit(&self, ray: &Ray, t_range: Range<f32>) -> Option<Hit> {
        let raw = self.intersect(ray, t_range.start, t_range.end)?;
        Some(self.surface_of(ray, &raw))
    }

    /// The closest triangle hit with `t` in `t_range`: its distance, face and
    /// barycentrics, without the surface details (no vertex data is read), for
    /// visibility queries and deferred shading; [`Mesh::surface`] completes it.
    pub fn closest_triangle(&self, ray: &Ray, t_range: Range<f32>) -> Option<TriangleHit> {
        self.intersect(ray, t_range.start, t_range.end)
            .map(|raw| TriangleHit {
                t: raw.t,
                primitive: raw.primitive,
                barycentric: raw.barycentric,
            })
    }

    /// The full [`Hit`] for a triangle hit of `ray` found by [`Mesh::closest_triangle`]:
    /// the normals, shading normal and uv interpolated at its barycentrics.
    pub fn surface(&self, ray: &Ray, hit: &TriangleHit) -> Hit {
        self.surface_of(
            ray,
            &RawHit {
                t: hit.t,
                object: 0,
                primitive: hit.primitive,
                barycentric: hit.barycentric,
            },
        )
    }

    /// Whether any triangle is hit with `t` in `t_range`; stops at the first one found.
    pub fn any_hit(&self, ray: &Ray, t_range: Range<f32>) -> bool {
        let packet_ray = PacketRay::new(&WatertightRay::new(ray));
        let (t_min, t_max) = (Vec4::splat(t_range.start), Vec4::splat(t_range.end));
        self.bvh.any_prepared(
            &BoxRay::new(ray),
            t_range.start,
            t_range.end,
            |start, count| {
                self.packets[start as usize..(start + count) as usize]
                    .iter()
                    .any(|packet| {
                        packet_ray
                            .edges(packet)
                            .is_some_and(|edges| edges.hits(t_min, t_max).0.any())
                    })
            },
        )
    }

    /// The closest hit as a raw hit: `t`, face and barycentrics.
    pub(crate) fn intersect(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<RawHit> {
        self.intersect_prepared(ray, &BoxRay::new(ray), t_min, t_max)
    }

    /// [`Mesh::intersect`] with the ray's box numbers already worked out.
    #[inline]
    pub(crate) fn intersect_prepared(
        &self,
        ray: &Ray,
        box_ray: &BoxRay,
        t_min: f32,
        t_max: f32,
    ) -> Option<RawHit> {
        // The triangle test's setup waits for the first leaf: most rays of a typical
        // image miss a given mesh's boxes altogether.
        let mut packet_ray = None;
        let t_min4 = Vec4::splat(t_min);
        let mut best = None;
        self.bvh.closest_prepared(
            box_ray,
            t_min,
            t_max,
            |start, count, t_max| {
                let packet_ray =
                    packet_ray.get_or_insert_with(|| PacketRay::new(&WatertightRay::new(ray)));
                match self.intersect_leaf(packet_ray, start, count, t_min4, t_max) {
                    Some(hit) => {
                        best = Some(hit);
                        hit.t
                    }
                    None => t_max,
                }
            },
            |start, count| self.prefetch_leaf(start, count),
        );
        best
    }

    /// Intersects the triangle packets `start..start + count` with a ray whose closest
    /// hit so far is at `t_max`: the closest hit below it, as a hit on object 0.
    #[inline(always)]
    fn intersect_leaf(
        &self,
        packet_ray: &PacketRay,
        start: u32,
        count: u32,
        t_min4: Vec4,
        mut t_max: f32,
    ) -> Option<RawHit> {
        let mut best = None;
        for packet in &self.packets[start as usize..(start + count) as usize] {
            let Some(edges) = packet_ray.edges(packet) else {
                continue;
            };
            let (valid, t, [_, v, w], det) = edges.hits(t_min4, Vec4::splat(t_max));
            if valid.any() {
                let t_valid = Vec4::select(valid, t, Vec4::INFINITY);
                t_max = t_valid.min_element();
                let lane = t_valid.cmpeq(Vec4::splat(t_max)).bitmask().trailing_zeros() as usize;
                let (v, w, det) = (v.to_array()[lane], w.to_array()[lane], det.to_array()[lane]);
                best = Some(RawHit {
                    t: t_max,
                    object: 0,
                    primitive: packet.faces[lane],
                    barycentric: Vec2::new(v / det, w / det),
                });
            }
        }
        best
    }

    /// Starts loading the first triangle packets of a leaf.
    #[inline(always)]
    fn prefetch_leaf(&self, start: u32, count: u32) {
        // Packets are 160 bytes, 16-byte aligned: the first of a leaf touches at most 4
        // cache lines, the first two at most 6.
        if count == 1 {
            prefetch(&self.packets, start as usize, [0, 64, 128, 159]);
        } else {
            prefetch(&self.packets, start as usize, [0, 64, 128, 192, 256, 319]);
        }
    }

    /// The closest hits of a query's rays (in the mesh's space), as hits on object
    /// `object`: lowers each lane's `t_max` and `best`.
    pub(crate) fn intersect_packet(&self, query: PacketQuery<'_>, object: u32) {
        struct Visitor<'a> {
            mesh: &'a Mesh,
            rays: &'a [Ray],
            rays_of_lanes: &'a [u8],
            packet_rays: [Option<PacketRay>; PACKET_SIZE],
            t_min4: Vec4,
            object: u32,
            best: &'a mut [Option<RawHit>; PACKET_SIZE],
        }
        impl PacketVisitor for Visitor<'_> {
            #[inline(always)]
            fn leaf(&mut self, lane: usize, start: u32, count: u32, t_max: f32) -> f32 {
                let ray = &self.rays[usize::from(self.rays_of_lanes[lane])];
                let packet_ray = self.packet_rays[lane]
                    .get_or_insert_with(|| PacketRay::new(&WatertightRay::new(ray)));
                match self
                    .mesh
                    .intersect_leaf(packet_ray, start, count, self.t_min4, t_max)
                {
                    Some(hit) => {
                        self.best[lane] = Some(RawHit {
                            object: self.object,
                            ..hit
                        });
                        hit.t
                    }
                    None => t_max,
                }
            }
        }
        let PacketQuery {
            packet,
            rays,
            lanes,
            t_min,
            t_max,
            best,
        } = query;
        let mut visitor = Visitor {
            mesh: self,
            rays,
            rays_of_lanes: packet.rays(),
            packet_rays: [None; PACKET_SIZE],
            t_min4: Vec4::splat(t_min),
            object,
            best,
        };
        self.bvh
            .closest_packet(packet, lanes, t_min, t_max, &mut visitor, |start, count| {
                self.prefetch_leaf(start, count)
            });
    }

    /// The closest triangle hit of each ray of `rays` with `t` in `t_range`, into
    /// `hits`: the same hits as [`Mesh::closest_triangle`] ray by ray, found faster
    /// when the rays are coherent (neighbouring pixels' viewing rays, in blocks of up to
    /// 64 such as 8 x 8 pixels), because each block is traced as a packet through the
    /// upper levels of the BVH. Incoherent rays (origins and directions all over) gain
    /// too on meshes too large for the caches (from about 150k triangles): their walks
    /// down the BVH take turns, so that their waits for memory overlap.
    ///
    /// # Panics
    ///
    /// When `rays` and `hits` differ in length.
    pub fn closest_triangles(
        &self,
        rays: &[Ray],
        t_range: Range<f32>,
        hits: &mut [Option<TriangleHit>],
    ) {
        assert_eq!(rays.len(), hits.len(), "one hit per ray");
        for (rays, hits) in rays.chunks(PACKET_SIZE).zip(hits.chunks_mut(PACKET_SIZE)) {
            hits.fill(None);
            for_each_packet(rays, |packet| {
                let mut t_max = [Vec4::splat(t_range.end); PACKET_GROUPS];
                let mut best = [None; PACKET_SIZE];
                let query = PacketQuery {
                    packet,
                    rays,
                    lanes: packet.all_lanes(),
                    t_min: t_range.start,
                    t_max: &mut t_max,
                    best: &mut best,
                };
                self.intersect_packet(query, 0);
                for (&ray, raw) in packet.rays().iter().zip(&best) {
                    hits[usize::from(ray)] = raw.map(|raw| TriangleHit {
                        t: raw.t,
                        primitive: raw.primitive,
                        barycentric: raw.barycentric,
                    });
                }
            });
        }
    }

    /// The surface details of a raw hit on face `raw.primitive`.
    pub(crate) fn surface_of(&self, ray: &Ray, raw: &RawHit) -> Hit {
        let data = &self.data;
        let [ia, ib, ic] = data.triangles[raw.primitive as usize].map(|i| i as usize);
        let [a, b, c] = [ia, ib, ic].map(|i| data.positions[i]);
        let Vec2 { x: b1, y: b2 } = raw.barycentric;
        let b0 = 1.0 - b1 - b2;
        let geometric = (b - a).cross(c - a).normalize_or(Vec3::Z);
        let shading = data
            .normals
            .as_ref()
            .and_then(|n| (b0 * n[ia] + b1 * n[ib] + b2 * n[ic]).try_normalize())
            .unwrap_or(geometric);
        let uv = data.uvs.as_ref().map_or(raw.barycentric, |uv| {
            b0 * uv[ia] + b1 * uv[ib] + b2 * uv[ic]
        });
        let (normal, shading_normal, front_face) = face_toward(ray.direction, geometric, shading);
        Hit {
            t: raw.t,
            point: ray.at(raw.t),
            normal,
            shading_normal,
            front_face,
            uv,
            primitive: raw.primitive,
            object: 0,
        }
    }

    /// The closest hit by testing every triangle, without the BVH: the reference the
    /// tests hold the BVH to.
    #[cfg(test)]
    pub(crate) fn brute_force(&self, ray: &Ray, t_min: f32, t_max: f32) -> Option<RawHit> {
        let w = WatertightRay::new(ray);
        let mut best: Option<RawHit> = None;
        for (face, tri) in self.data.triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|i| self.data.positions[i as usize]);
            let limit = best.map_or(t_max, |b| b.t);
            if (b - a).cross(c - a) == Vec3::ZERO {
                continue;
            }
            if let Some(hit) = w.intersect(a, b, c, t_min, limit) {
                best = Some(RawHit {
                    primitive: face as u32,
                    ..hit
                });
            }
        }
        best
    }
}

fn validate(data: &MeshData) -> Result<(), GeometryError> {
    if data.triangles.len() > MAX_ITEMS {
        return Err(GeometryError::TooManyTriangles {
            count: data.triangles.len(),
            limit: MAX_ITEMS,
        });
    }
    let vertex_count = data.positions.len();
    if let Some((vertex, &position)) = data
        .positions
        .iter()
        .enumerate()
        .find(|(_, p)| !p.is_finite())
    {
        return Err(GeometryError::NonFinitePosition { vertex, position });
    }
    for (face, triangle) in data.triangles.iter().enumerate() {
        if let Some(&vertex) = triangle.iter().find(|&&v| v as usize >= vertex_count) {
            return Err(GeometryError::VertexOutOfRange {
                face,
                vertex,
                vertex_count,
            });
        }
    }
    let counts = [
        ("normals", data.normals.as_ref().map(Vec::len)),
        ("texture coordinates", data.uvs.as_ref().map(Vec::len)),
    ];
    for (attribute, count) in counts {
        if let Some(count) = count.filter(|&c| c != vertex_count) {
            return Err(GeometryError::AttributeCount {
                attribute,
                count,
                vertex_count,
            });
        }
    }
    Ok(())
}
