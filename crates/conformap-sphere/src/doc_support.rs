//! Small meshes for the doctests (not part of the API).

use conformap_mesh::TriMesh;

/// The octahedron with every face split into four `levels` times, vertices pushed onto the
/// unit sphere, then squashed to the ellipsoid `(x, y, z/2)` so the map is not trivial.
pub fn octahedron_sphere(levels: u32) -> TriMesh {
    let mut p: Vec<[f64; 3]> = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let mut faces: Vec<[u32; 3]> = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    for _ in 0..levels {
        let mut mid = std::collections::HashMap::new();
        let mut next = Vec::with_capacity(4 * faces.len());
        for f in &faces {
            let mut m = [0u32; 3];
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                m[k] = *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                    let (u, v) = (p[a as usize], p[b as usize]);
                    let s = [u[0] + v[0], u[1] + v[1], u[2] + v[2]];
                    let r = (s[0] * s[0] + s[1] * s[1] + s[2] * s[2]).sqrt();
                    p.push([s[0] / r, s[1] / r, s[2] / r]);
                    (p.len() - 1) as u32
                });
            }
            next.push([f[0], m[0], m[2]]);
            next.push([f[1], m[1], m[0]]);
            next.push([f[2], m[2], m[1]]);
            next.push(m);
        }
        faces = next;
    }
    let squashed = p.iter().map(|q| [q[0], q[1], 0.5 * q[2]]).collect();
    match TriMesh::try_new(squashed, faces) {
        Ok(m) => m,
        Err(e) => panic!("the octahedron is valid: {e}"),
    }
}
