//! How a map file's elements correspond to the mesh's, beyond "the same file": a
//! per-vertex map only needs the mesh's vertex order (another tool may write the faces in
//! another order, or start each face at another corner), and a seamed flat layout
//! (`global --flat`: one vertex per corner class, the mesh's faces in order) is a map per
//! face corner.

use std::collections::HashMap;

use conformap_io::CornerUv;
use conformap_mesh::TriMesh;

/// A face rotated to start at its smallest index (orientation kept).
fn canonical(f: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| f[k]).unwrap_or(0);
    [f[k], f[(k + 1) % 3], f[(k + 2) % 3]]
}

/// For each face of `mesh_faces`, the face of `map_faces` with the same corners in the same
/// cyclic order, and the corner of that face where the mesh face's corner 0 is:
/// `None` when the faces are the same, face for face; `Err(f)` names the first mesh face
/// the map does not have.
///
/// # Errors
/// The first face of `mesh_faces` with no counterpart in `map_faces`.
pub fn match_faces(
    map_faces: &[[u32; 3]],
    mesh_faces: &[[u32; 3]],
) -> Result<Option<Vec<(usize, usize)>>, usize> {
    if map_faces == mesh_faces {
        return Ok(None);
    }
    let index: HashMap<[u32; 3], usize> = map_faces
        .iter()
        .enumerate()
        .map(|(i, &f)| (canonical(f), i))
        .collect();
    mesh_faces
        .iter()
        .enumerate()
        .map(|(f, &face)| {
            let i = *index.get(&canonical(face)).ok_or(f)?;
            let rot = (0..3).find(|&k| map_faces[i][k] == face[0]).ok_or(f)?;
            Ok((i, rot))
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Some)
}

/// `corner` (per face of the map file) per face of the mesh, through [`match_faces`]'s
/// correspondence.
pub fn reorder_corners(corner: CornerUv, order: &[(usize, usize)]) -> CornerUv {
    let faces = order
        .iter()
        .map(|&(i, rot)| {
            let t = corner.faces[i];
            [t[rot], t[(rot + 1) % 3], t[(rot + 2) % 3]]
        })
        .collect();
    CornerUv {
        texcoords: corner.texcoords,
        faces,
    }
}

/// A seamed flat layout (`global --flat`: more vertices than the mesh, one per corner
/// class, and the mesh's faces in order) as a map per face corner, with one position per
/// mesh vertex (that of its first corner class); `None` when `positions` / `faces` are not
/// such a layout of `mesh` (a corner class belonging to two mesh vertices, a class no face
/// uses, another face count).
pub fn seamed_flat(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    mesh: &TriMesh,
) -> Option<(CornerUv, Vec<[f64; 3]>)> {
    if faces.len() != mesh.num_faces() || positions.len() <= mesh.num_vertices() {
        return None;
    }
    let mut owner: Vec<Option<u32>> = vec![None; positions.len()];
    let mut first: Vec<Option<u32>> = vec![None; mesh.num_vertices()];
    for (map_face, mesh_face) in faces.iter().zip(mesh.faces()) {
        for k in 0..3 {
            let (class, vertex) = (map_face[k] as usize, mesh_face[k]);
            match owner.get(class)? {
                Some(o) if *o != vertex => return None,
                _ => owner[class] = Some(vertex),
            }
            first[vertex as usize].get_or_insert(map_face[k]);
        }
    }
    if owner.iter().any(Option::is_none) {
        return None;
    }
    let per_vertex = first
        .iter()
        .map(|c| c.map(|c| positions[c as usize]))
        .collect::<Option<Vec<_>>>()?;
    let corner = CornerUv {
        texcoords: positions.iter().map(|p| [p[0], p[1]]).collect(),
        faces: faces.to_vec(),
    };
    Some((corner, per_vertex))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotated_and_reordered_faces_match() {
        let mesh = [[0, 1, 2], [0, 2, 3]];
        let map = [[2, 3, 0], [1, 2, 0]];
        let order = match_faces(&map, &mesh).unwrap().unwrap();
        assert_eq!(order, vec![(1, 2), (0, 2)]);
        for (f, &(i, rot)) in order.iter().enumerate() {
            assert_eq!(map[i][rot], mesh[f][0]);
        }
        // a flipped face is another face
        assert_eq!(match_faces(&[[0, 2, 1], [0, 2, 3]], &mesh), Err(0));
        assert_eq!(match_faces(&mesh, &mesh), Ok(None));
    }
}
