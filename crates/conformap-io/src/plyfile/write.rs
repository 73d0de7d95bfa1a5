//! Writing binary little-endian PLY: `x y z` (double), per-vertex `texture_u texture_v`
//! (double) or a per-corner `texcoord` list on the faces (a seamed map).
//!
//! Why `texture_u`/`texture_v`: it is the one per-vertex name that VTK (ParaView) reads
//! besides `u`/`v`, MeshLab's own name, and one that trimesh, Blender's importer and Open3D
//! (rply) accept; `s`/`t` is not read by VTK. The per-corner `texcoord` list is MeshLab's
//! (and trimesh reads it). Doubles keep every bit: PLY → PLY is exact.

use crate::corner_uv::CornerUv;

/// The texture coordinates to write with the mesh.
pub(crate) enum PlyUv<'a> {
    None,
    PerVertex(&'a [[f64; 2]]),
    PerCorner(&'a CornerUv),
}

/// The bytes of a binary little-endian PLY of `positions` and `faces` with `uv`. The
/// caller checked indices and lengths.
pub(crate) fn encode_ply(positions: &[[f64; 3]], faces: &[[u32; 3]], uv: PlyUv<'_>) -> Vec<u8> {
    let mut h = String::from("ply\nformat binary_little_endian 1.0\ncomment conformap\n");
    h.push_str(&format!(
        "element vertex {}\nproperty double x\nproperty double y\nproperty double z\n",
        positions.len()
    ));
    if let PlyUv::PerVertex(_) = uv {
        h.push_str("property double texture_u\nproperty double texture_v\n");
    }
    h.push_str(&format!(
        "element face {}\nproperty list uchar int vertex_indices\n",
        faces.len()
    ));
    if let PlyUv::PerCorner(_) = uv {
        h.push_str("property list uchar double texcoord\n");
    }
    h.push_str("end_header\n");
    let per_vertex = match uv {
        PlyUv::PerVertex(_) => 40,
        _ => 24,
    };
    let per_face = match uv {
        PlyUv::PerCorner(_) => 63,
        _ => 13,
    };
    let mut out =
        Vec::with_capacity(h.len() + per_vertex * positions.len() + per_face * faces.len());
    out.extend_from_slice(h.as_bytes());
    for (k, p) in positions.iter().enumerate() {
        for x in p {
            out.extend_from_slice(&x.to_le_bytes());
        }
        if let PlyUv::PerVertex(t) = uv {
            out.extend_from_slice(&t[k][0].to_le_bytes());
            out.extend_from_slice(&t[k][1].to_le_bytes());
        }
    }
    for (f, tri) in faces.iter().enumerate() {
        out.push(3);
        for &i in tri {
            // indices below 2^31 (checked by the caller through TooLarge)
            out.extend_from_slice(&(i as i32).to_le_bytes());
        }
        if let PlyUv::PerCorner(c) = uv {
            out.push(6);
            for k in 0..3 {
                for x in c.corner(f, k) {
                    out.extend_from_slice(&x.to_le_bytes());
                }
            }
        }
    }
    out
}
