//! OBJ meshes written: the Wavefront OBJ text a scene's `Mesh` object loads back.
//!
//! The loader is `mesh.rs` (tobj); this is its inverse for a mesh's positions and
//! triangles, so that what viewray writes as OBJ (Mitsuba's meshes beside an exported
//! scene, the geometry benchmark's icosphere) is written in the one crate that reads it.

use std::fmt::Write as _;

use viewray_geometry::MeshData;

/// `mesh` as Wavefront OBJ text: each line of `comment` as a `# ` line, then one
/// `v x y z` line per position, then one `f a b c` line per triangle with 1-based
/// indices, in the mesh's order. Normals and texture coordinates are not written.
///
/// A coordinate is written with the fewest digits that read back as the same `f32`
/// (Rust's `{:?}`: `1.0`, `0.1`, `1e-7`), a negative zero as `0.0`. Loading the text as
/// a scene's `Mesh` gives back the same triangles, corner for corner, in the same order
/// (the loader numbers the vertices in the order the faces first use them).
pub fn obj_text(mesh: &MeshData, comment: &str) -> String {
    let mut text = String::new();
    // Writing to a String cannot fail.
    for line in comment.lines() {
        let _ = writeln!(text, "# {line}");
    }
    for p in &mesh.positions {
        let _ = writeln!(
            text,
            "v {} {} {}",
            coordinate(p.x),
            coordinate(p.y),
            coordinate(p.z)
        );
    }
    for [a, b, c] in &mesh.triangles {
        let _ = writeln!(text, "f {} {} {}", a + 1, b + 1, c + 1);
    }
    text
}

/// The shortest decimal that reads back as `x`, minus zero written `0.0`: the rule of
/// every number other programs read (viewray-output's).
fn coordinate(x: f32) -> String {
    viewray_output::number::round_trip_f32(x)
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use glam::Vec3;
    use viewray_geometry::Aabb;

    use super::*;

    /// The text the OBJ loader of a scene's `Mesh` reads, as a mesh.
    fn load(text: &str) -> MeshData {
        let mut materials = Vec::new();
        let no_mtl = |_: &std::path::Path| Err(tobj::LoadError::OpenFileFailed);
        let mut build_time = Duration::ZERO;
        let loaded =
            crate::mesh::parse_obj(text.as_bytes(), no_mtl, &mut materials, &mut build_time)
                .expect("the written OBJ loads");
        assert!(loaded.face_materials.is_none(), "no MTL materials");
        loaded.mesh.data().clone()
    }

    /// Each triangle of `mesh` as the bits of its three corners, a negative zero taken as
    /// zero.
    fn corner_bits(mesh: &MeshData) -> Vec<[[u32; 3]; 3]> {
        mesh.triangles
            .iter()
            .map(|t| {
                t.map(|i| {
                    (mesh.positions[i as usize] + 0.0)
                        .to_array()
                        .map(f32::to_bits)
                })
            })
            .collect()
    }

    #[test]
    fn a_written_mesh_loads_back_exactly() {
        let awkward = Aabb::new(
            Vec3::new(-0.1, -0.0, 1e-7),
            Vec3::new(1.0 / 3.0, 2.5e6, 7.0),
        );
        let ico = MeshData::icosphere(1, 0.7);
        for mesh in [
            MeshData::cuboid(awkward),
            MeshData::new(ico.positions, ico.triangles),
        ] {
            let loaded = load(&obj_text(&mesh, "a test mesh"));
            assert_eq!(corner_bits(&loaded), corner_bits(&mesh));
        }
    }

    #[test]
    fn the_text_is_comment_vertices_faces() {
        let triangle = MeshData::new(
            vec![
                Vec3::new(-0.0, 0.5, 1.0),
                Vec3::new(2.0, -0.25, 1e-7),
                Vec3::new(0.1, 3.0, -4.0),
            ],
            vec![[0, 1, 2]],
        );
        assert_eq!(
            obj_text(&triangle, "Written by a test.\nTwo lines."),
            "# Written by a test.\n# Two lines.\n\
             v 0.0 0.5 1.0\nv 2.0 -0.25 1e-7\nv 0.1 3.0 -4.0\n\
             f 1 2 3\n"
        );
    }
}
