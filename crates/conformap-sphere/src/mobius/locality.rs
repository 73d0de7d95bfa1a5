//! A cache-friendly numbering of a mesh for the Möbius optimizer's evaluations.
//!
//! Every evaluation of the boosted map's energy gathers each face's three vertices, ~150
//! times per optimization. Meshes are often numbered with little locality (armadillo.obj:
//! half its faces span more than 1,000 vertex numbers, consecutive faces jump ~7,000), so
//! on a 43k-vertex mesh most of those gathers miss the core's cache. The optimizer
//! evaluates a renumbered copy instead: vertices along a Morton (Z-order) curve of their
//! input positions, faces by their first vertex in that order. The energy and its gradient
//! are sums over faces, so they do not depend on the numbering (up to rounding: the order
//! of the sums); the optimal boost is applied to the map in its own numbering.

/// A renumbered copy of a mesh's faces and of per-vertex points.
pub(crate) struct Renumbered {
    /// The points in the new vertex order.
    pub points: Vec<[f64; 3]>,
    /// The faces in the new order, on the new vertex numbers.
    pub faces: Vec<[u32; 3]>,
    /// `face_order[k]`: the input face that is new face `k`.
    pub face_order: Vec<u32>,
}

impl Renumbered {
    /// Renumbers `faces` and `points` (per vertex) by the Morton order of `positions` (per
    /// vertex, the mesh's 3D positions).
    pub fn new(positions: &[[f64; 3]], faces: &[[u32; 3]], points: &[[f64; 3]]) -> Self {
        let order = morton_order(positions);
        let mut new_of = vec![0u32; order.len()];
        for (k, &v) in order.iter().enumerate() {
            new_of[v as usize] = k as u32;
        }
        let mut keyed: Vec<(u32, u32)> = faces
            .iter()
            .enumerate()
            .map(|(f, t)| {
                let first = t.iter().map(|&v| new_of[v as usize]).min().unwrap_or(0);
                (first, f as u32)
            })
            .collect();
        keyed.sort_unstable();
        let face_order: Vec<u32> = keyed.iter().map(|&(_, f)| f).collect();
        Self {
            points: order.iter().map(|&v| points[v as usize]).collect(),
            faces: face_order
                .iter()
                .map(|&f| faces[f as usize].map(|v| new_of[v as usize]))
                .collect(),
            face_order,
        }
    }

    /// Per-face values in the new face order.
    pub fn faces_of<T: Copy>(&self, per_face: &[T]) -> Vec<T> {
        self.face_order
            .iter()
            .map(|&f| per_face[f as usize])
            .collect()
    }
}

/// The vertices sorted by the Morton code of their positions (21 bits per axis over the
/// bounding box), ties by index: `order[k]` is the vertex at place `k`.
fn morton_order(positions: &[[f64; 3]]) -> Vec<u32> {
    let (lo, hi) = conformap_mesh::bounding_box(positions);
    let span = (0..3).map(|j| hi[j] - lo[j]).fold(0.0f64, f64::max);
    let scale = if span > 0.0 && span.is_finite() {
        ((1u64 << 21) - 1) as f64 / span
    } else {
        0.0
    };
    let mut keyed: Vec<(u64, u32)> = positions
        .iter()
        .enumerate()
        .map(|(v, p)| {
            // `as` saturates (NaN to 0): a bad coordinate only moves the vertex in the order
            let q = [0, 1, 2].map(|j| ((p[j] - lo[j]) * scale) as u64 & 0x1f_ffff);
            (
                spread(q[0]) | spread(q[1]) << 1 | spread(q[2]) << 2,
                v as u32,
            )
        })
        .collect();
    keyed.sort_unstable();
    keyed.into_iter().map(|(_, v)| v).collect()
}

/// The low 21 bits of `x` moved to every third bit.
fn spread(x: u64) -> u64 {
    let mut x = x & 0x1f_ffff;
    x = (x | x << 32) & 0x1f_0000_0000_ffff;
    x = (x | x << 16) & 0x1f_0000_ff00_00ff;
    x = (x | x << 8) & 0x100f_00f0_0f00_f00f;
    x = (x | x << 4) & 0x10c3_0c30_c30c_30c3;
    x = (x | x << 2) & 0x1249_2492_4924_9249;
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spread_interleaves_bits() {
        assert_eq!(spread(0b1), 0b1);
        assert_eq!(spread(0b11), 0b1001);
        assert_eq!(spread(0x1f_ffff), 0x1249_2492_4924_9249);
        // x, y, z of (1, 0, 1): bits 0 and 2
        assert_eq!(spread(1) | spread(0) << 1 | spread(1) << 2, 0b101);
    }

    #[test]
    fn renumbering_is_a_permutation_of_vertices_and_faces() {
        let mesh = crate::doc_support::octahedron_sphere(3);
        let r = Renumbered::new(mesh.positions(), mesh.faces(), mesh.positions());
        let mut fo = r.face_order.clone();
        fo.sort_unstable();
        assert!(fo.iter().enumerate().all(|(k, &f)| f as usize == k));
        let mut pts = r.points.clone();
        let mut orig = mesh.positions().to_vec();
        pts.sort_by(|a, b| a.partial_cmp(b).unwrap());
        orig.sort_by(|a, b| a.partial_cmp(b).unwrap());
        assert_eq!(pts, orig);
        // every new face is the old one on the new numbers: the same corner positions
        for (k, t) in r.faces.iter().enumerate() {
            let old = mesh.faces()[r.face_order[k] as usize];
            for c in 0..3 {
                assert_eq!(r.points[t[c] as usize], mesh.positions()[old[c] as usize]);
            }
        }
        let ids: Vec<u32> = (0..mesh.num_faces() as u32).collect();
        assert_eq!(r.faces_of(&ids), r.face_order);
        // consecutive new faces are near each other: their first vertices are sorted
        let firsts: Vec<u32> = r.faces.iter().map(|t| *t.iter().min().unwrap()).collect();
        assert!(firsts.windows(2).all(|w| w[0] <= w[1]));
    }
}
