//! A mesh's vertex and face data before it is built, its generators, and the checks
//! [`Mesh::new`](crate::Mesh::new) runs on it.

use std::collections::HashMap;

use glam::{Vec2, Vec3};

use crate::bvh::MAX_ITEMS;
use crate::{Aabb, GeometryError};

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

/// Why `data` cannot be built into a mesh, if it cannot.
pub(super) fn validate(data: &MeshData) -> Result<(), GeometryError> {
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
