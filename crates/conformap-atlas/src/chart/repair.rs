//! Folded faces of a chart unfolded locally: the faces around every fold are laid out again
//! with Floater's mean value weights inside a ring of vertices that keep their places.
//!
//! A strongly varying cone metric (spread 2–3 on armadillo's limbs) on a mesh with obtuse
//! triangles folds a few faces of the harmonic interior even where the boundary curve is
//! right. Mean value weights are positive, so the relaxed region is an embedding whenever
//! its fixed ring is convex (Floater 2003); a few rings of a smooth map around a fold are
//! nearly convex, and the region is grown until no face is folded. Only interior vertices
//! move: the chart's boundary, and so every seam's lengths, stay exactly as they were.
//! Where the boundary curve itself turns back at a fold, no interior layout helps: those
//! faces become pieces of their own ([`detach_folded`]).

use std::collections::VecDeque;

use conformap_mesh::{Adjacency, TriMesh};
use num_complex::Complex64;

use super::piece::{sub_piece, Piece};
use crate::error::AtlasError;

/// Ring counts tried around the folds, smallest first, while each leaves fewer folded
/// faces than the last (what a wider ring cannot reduce is folded by the boundary curve).
pub const REPAIR_RINGS: [usize; 5] = [2, 4, 8, 16, 32];

/// Gauss–Seidel sweeps per relaxation, at most; it stops earlier once no vertex moves by
/// more than [`REPAIR_TOLERANCE`] of the region's size.
const SWEEPS: usize = 2000;

/// Relative movement below which the relaxation has converged (the sign of a face's
/// area is all that is asked of it).
pub const REPAIR_TOLERANCE: f64 = 1e-9;

/// Faces of `mesh` whose image under `uv` is not counter-clockwise.
pub(crate) fn folded_faces(mesh: &TriMesh, uv: &[Complex64]) -> Vec<usize> {
    mesh.faces()
        .iter()
        .enumerate()
        .filter(|(_, t)| {
            let z = t.map(|v| uv[v as usize]);
            let (e1, e2) = (z[1] - z[0], z[2] - z[0]);
            e1.re * e2.im - e1.im * e2.re <= 0.0
        })
        .map(|(f, _)| f)
        .collect()
}

/// Unfolds the folded faces of the layout `uv` of disk `mesh` in place; returns the faces
/// still folded (0 unless a fold sits where no ring around it is convex enough).
pub fn unfold(mesh: &TriMesh, uv: &mut [Complex64]) -> usize {
    let folded = folded_faces(mesh, uv);
    if folded.is_empty() {
        return 0;
    }
    // the rings from the mesh's adjacency, the weights of the region's vertices alone (a
    // fold is a few faces: spot's chart spent 1.5 ms weighing all 17,568 corners)
    let adjacency = mesh.vertex_adjacency();
    let mut on_boundary = vec![false; mesh.num_vertices()];
    for &v in mesh.boundary_loops().iter().flatten() {
        on_boundary[v as usize] = true;
    }
    let mut best = folded.len();
    for rings in REPAIR_RINGS {
        let folded = folded_faces(mesh, uv);
        let free = region(mesh, &adjacency, &folded, rings, &on_boundary);
        let mut in_region = vec![false; mesh.num_vertices()];
        free.iter().for_each(|&v| in_region[v as usize] = true);
        let weights = mean_value_weights_where(mesh, &in_region);
        let mut trial = uv.to_vec();
        relax(&weights, &free, &mut trial);
        let left = folded_faces(mesh, &trial).len();
        if left >= best {
            // a wider ring did not help: what is left is folded by the boundary itself
            break;
        }
        best = left;
        uv.copy_from_slice(&trial);
        if best == 0 {
            break;
        }
    }
    best
}

/// The faces still folded after [`unfold`] (where the boundary curve itself turns back,
/// no interior layout helps) taken out of `piece` as pieces of one face each, laid out as
/// their mirror image: the same three edge lengths, so every seam keeps its length, turned
/// counter-clockwise. The rest stays one piece (or is returned whole should taking the
/// faces out leave it invalid).
///
/// # Errors
/// None in practice: sub-pieces of a valid piece are valid (see the `split` module).
pub fn detach_folded(piece: Piece) -> Result<Vec<Piece>, AtlasError> {
    let folded = folded_faces(&piece.mesh, &piece.uv);
    if folded.is_empty() {
        return Ok(vec![piece]);
    }
    let mut is_folded = vec![false; piece.mesh.num_faces()];
    folded.iter().for_each(|&f| is_folded[f] = true);
    let rest: Vec<u32> = (0..piece.mesh.num_faces() as u32)
        .filter(|&f| !is_folded[f as usize])
        .collect();
    let Ok(main) = sub_piece(&piece, &rest) else {
        return Ok(vec![piece]);
    };
    let mut out = vec![main];
    for f in folded {
        let mut single = sub_piece(&piece, &[f as u32])?;
        single.uv.iter_mut().for_each(|z| *z = z.conj());
        out.push(single);
    }
    Ok(out)
}

/// Vertices not `fixed` within `rings` edges of a folded face's vertices, ascending.
fn region(
    mesh: &TriMesh,
    adjacency: &Adjacency,
    folded: &[usize],
    rings: usize,
    fixed: &[bool],
) -> Vec<u32> {
    let n = mesh.num_vertices();
    let dist = ring_distances(mesh, folded, rings, |v, next| {
        next.extend_from_slice(adjacency.neighbors_of(v as usize));
    });
    // the outermost ring stays fixed: it is the convex-enough frame
    (0..n as u32)
        .filter(|&v| dist[v as usize] < rings && !fixed[v as usize])
        .collect()
}

/// Edge steps from the vertices of the `folded` faces, breadth-first up to `rings` steps
/// (`usize::MAX` beyond), the steps from a vertex those `neighbours` pushes (its one-ring;
/// the seamless repair adds a seam vertex's twin).
pub(crate) fn ring_distances(
    mesh: &TriMesh,
    folded: &[usize],
    rings: usize,
    neighbours: impl Fn(u32, &mut Vec<u32>),
) -> Vec<usize> {
    let mut dist = vec![usize::MAX; mesh.num_vertices()];
    let mut queue = VecDeque::new();
    for &f in folded {
        for v in mesh.faces()[f] {
            if dist[v as usize] == usize::MAX {
                dist[v as usize] = 0;
                queue.push_back(v);
            }
        }
    }
    let mut next = Vec::new();
    while let Some(v) = queue.pop_front() {
        let d = dist[v as usize];
        if d >= rings {
            continue;
        }
        next.clear();
        neighbours(v, &mut next);
        for &w in &next {
            if dist[w as usize] == usize::MAX {
                dist[w as usize] = d + 1;
                queue.push_back(w);
            }
        }
    }
    dist
}

/// Floater's mean value weights `w_ij = (tan(α/2) + tan(β/2)) / |x_j − x_i|` (α, β the
/// 3D angles at `i` beside edge `ij`), per vertex as `(j, w_ij)`; all positive.
pub(crate) fn mean_value_weights(mesh: &TriMesh) -> Vec<Vec<(u32, f64)>> {
    mean_value_weights_where(mesh, &vec![true; mesh.num_vertices()])
}

/// [`mean_value_weights`] of the vertices `wanted` (the rows of the others left empty), each
/// row exactly as the whole computation gives it.
fn mean_value_weights_where(mesh: &TriMesh, wanted: &[bool]) -> Vec<Vec<(u32, f64)>> {
    let p = mesh.positions();
    let mut out: Vec<Vec<(u32, f64)>> = vec![Vec::new(); mesh.num_vertices()];
    let sub = |a: [f64; 3], b: [f64; 3]| [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
    let norm = |a: [f64; 3]| (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    for t in mesh.faces() {
        for k in 0..3 {
            let (i, j, l) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
            if !wanted[i as usize] {
                continue;
            }
            let (a, b) = (
                sub(p[j as usize], p[i as usize]),
                sub(p[l as usize], p[i as usize]),
            );
            let (la, lb) = (norm(a), norm(b));
            let cos = ((a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb)).clamp(-1.0, 1.0);
            let half_tan = (0.5 * cos.acos()).tan();
            // the angle at i lies beside both edges ij and il
            for (v, len) in [(j, la), (l, lb)] {
                let w = if len > 0.0 { half_tan / len } else { 0.0 };
                let row = &mut out[i as usize];
                match row.iter_mut().find(|e| e.0 == v) {
                    Some(e) => e.1 += w,
                    None => row.push((v, w)),
                }
            }
        }
    }
    out
}

/// Gauss–Seidel on `x_i = Σ w_ij x_j / Σ w_ij` over the `free` vertices.
fn relax(weights: &[Vec<(u32, f64)>], free: &[u32], uv: &mut [Complex64]) {
    if free.is_empty() {
        return;
    }
    let (mut lo, mut hi) = (uv[free[0] as usize], uv[free[0] as usize]);
    for &v in free {
        let z = uv[v as usize];
        lo = Complex64::new(lo.re.min(z.re), lo.im.min(z.im));
        hi = Complex64::new(hi.re.max(z.re), hi.im.max(z.im));
    }
    let size = (hi - lo).norm_sqr().max(f64::MIN_POSITIVE);
    for _ in 0..SWEEPS {
        let mut moved = 0.0f64;
        for &v in free {
            let (mut sum, mut total) = (Complex64::new(0.0, 0.0), 0.0);
            for &(j, w) in &weights[v as usize] {
                sum += uv[j as usize] * w;
                total += w;
            }
            if total > 0.0 {
                let z = sum / total;
                moved = moved.max((z - uv[v as usize]).norm_sqr());
                uv[v as usize] = z;
            }
        }
        if moved < REPAIR_TOLERANCE * REPAIR_TOLERANCE * size {
            break;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An `n × n` grid of unit squares, each split in two counter-clockwise triangles.
    fn grid(n: u32) -> (TriMesh, Vec<Complex64>) {
        let id = |i: u32, j: u32| j * (n + 1) + i;
        let mut p = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                p.push([f64::from(i), f64::from(j), 0.0]);
            }
        }
        let mut f = Vec::new();
        for j in 0..n {
            for i in 0..n {
                f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        let uv = p.iter().map(|q| Complex64::new(q[0], q[1])).collect();
        (TriMesh::try_new(p, f).expect("grid"), uv)
    }

    /// The weights of a region are the whole computation's rows for its vertices, entry for
    /// entry and in the same order (the relaxation's sums, and so the unfolded layout, are
    /// those of the whole computation), and empty rows elsewhere.
    #[test]
    fn the_weights_of_a_region_are_the_whole_computations_rows() {
        let (mut mesh, _) = grid(6);
        // uneven positions, so the weights differ from vertex to vertex
        let p: Vec<[f64; 3]> = mesh
            .positions()
            .iter()
            .enumerate()
            .map(|(k, q)| {
                [
                    q[0] + 0.1 * ((k * 7 % 5) as f64),
                    q[1],
                    0.3 * ((k % 3) as f64),
                ]
            })
            .collect();
        mesh = TriMesh::try_new(p, mesh.faces().to_vec()).expect("mesh");
        let all = mean_value_weights(&mesh);
        let wanted: Vec<bool> = (0..mesh.num_vertices()).map(|v| v % 3 == 1).collect();
        let some = mean_value_weights_where(&mesh, &wanted);
        for v in 0..mesh.num_vertices() {
            if wanted[v] {
                assert!(!all[v].is_empty());
                assert_eq!(some[v], all[v], "vertex {v}");
            } else {
                assert!(some[v].is_empty(), "vertex {v}");
            }
        }
    }

    #[test]
    fn a_fold_inside_is_unfolded_and_the_boundary_stays() {
        let (mesh, mut uv) = grid(12);
        // drag an interior vertex across two of its neighbours
        uv[6 * 13 + 6] = Complex64::new(8.5, 6.5);
        let before = folded_faces(&mesh, &uv).len();
        assert!(before >= 2, "{before}");
        let boundary: Vec<Complex64> = mesh.boundary_loops()[0]
            .iter()
            .map(|&v| uv[v as usize])
            .collect();
        assert_eq!(unfold(&mesh, &mut uv), 0);
        assert!(folded_faces(&mesh, &uv).is_empty());
        for (&v, z) in mesh.boundary_loops()[0].iter().zip(&boundary) {
            assert_eq!(uv[v as usize], *z);
        }
    }

    #[test]
    fn a_face_folded_at_the_boundary_becomes_its_own_mirrored_piece() {
        let (mesh, mut uv) = grid(4);
        // push a boundary corner inward past its diagonal: its face turns over
        uv[0] = Complex64::new(1.3, 1.2);
        let folded = folded_faces(&mesh, &uv);
        assert_eq!(folded.len(), 2);
        assert_eq!(unfold(&mesh, &mut uv), 2, "the boundary is what folds here");
        let faces = mesh.num_faces() as u32;
        let piece = Piece {
            faces: (0..faces).collect(),
            original: (0..mesh.num_vertices() as u32).collect(),
            mesh,
            uv,
        };
        let pieces = detach_folded(piece.clone()).expect("pieces");
        assert_eq!(pieces.len(), 3);
        let total: usize = pieces.iter().map(|p| p.faces.len()).sum();
        assert_eq!(total, faces as usize);
        for p in &pieces {
            assert!(folded_faces(&p.mesh, &p.uv).is_empty());
        }
        // each mirrored face keeps its three edge lengths exactly
        for (single, &f) in pieces[1..].iter().zip(&folded) {
            let t = single.mesh.faces()[0];
            let parent = piece.mesh.faces()[f];
            for k in 0..3 {
                let (a, b) = (t[k] as usize, t[(k + 1) % 3] as usize);
                let (pa, pb) = (parent[k] as usize, parent[(k + 1) % 3] as usize);
                let l1 = (single.uv[a] - single.uv[b]).norm();
                let l2 = (piece.uv[pa] - piece.uv[pb]).norm();
                assert!((l1 - l2).abs() <= 1e-15 * l2, "{l1} {l2}");
            }
        }
    }
}
