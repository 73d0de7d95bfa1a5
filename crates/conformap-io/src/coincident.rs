//! Coincident vertices: finding and welding vertices at bit-identical positions.
//!
//! The glTF reader welds them always (exporters split vertices along texture seams, and a
//! split surface is not the surface); the OBJ reader never does (vertex `k` is the file's
//! `k`-th `v` line, and a map's `vt k` must belong to it). A caller that wants an OBJ read
//! the way a glTF one is — an unwelded triangle soup, or duplicated vertices that open a
//! slit — welds it with [`RawMesh::weld_coincident`] (or [`weld_coincident`] on plain
//! arrays) before validating; [`coincident_vertices`] says whether there is anything to weld
//! (for `conformap info`).
//!
//! Rule (both readers): positions are equal when their three coordinates have the same
//! bits, with −0.0 = 0.0; the first vertex of each class keeps its place, so welded
//! vertices are numbered in order of first occurrence. The classes come from one sort of
//! the position keys (no hash map), parallel for large inputs.

use rayon::slice::ParallelSliceMut;

use crate::error::{Origin, UvProblem};
use crate::loaded::NO_VERTEX;
use crate::raw::RawMesh;

/// Inputs with more vertices than this are sorted in parallel.
const PARALLEL_SORT_MIN: usize = 1 << 16;

/// The result of [`weld_coincident`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Welded {
    /// One position per class of coincident vertices, in order of first occurrence.
    pub positions: Vec<[f64; 3]>,
    /// The faces renumbered (a face may now repeat a vertex: validation rejects it).
    pub faces: Vec<[u32; 3]>,
    /// For each input vertex, its welded vertex.
    pub map: Vec<u32>,
    /// For each welded vertex, its first input vertex.
    pub first: Vec<usize>,
}

impl Welded {
    /// Input vertices merged into an earlier one (`0`: nothing was welded).
    pub fn merged(&self) -> usize {
        self.map.len() - self.positions.len()
    }
}

/// The comparison key: the bits of each coordinate, −0.0 taken as 0.0.
fn key(p: &[f64; 3]) -> [u64; 3] {
    p.map(|x| (x + 0.0).to_bits())
}

/// Classes of coincident positions among the vertices with `keep[i]` (all if `None`):
/// `map[i]` is the class of vertex `i` (classes numbered by first occurrence,
/// [`NO_VERTEX`] for a vertex not kept), `first[c]` the first vertex of class `c`.
pub(crate) fn classes(positions: &[[f64; 3]], keep: Option<&[bool]>) -> (Vec<u32>, Vec<usize>) {
    let kept = |i: usize| keep.is_none_or(|k| k[i]);
    let mut keyed: Vec<([u64; 3], u32)> = (0..positions.len())
        .filter(|&i| kept(i))
        .map(|i| (key(&positions[i]), i as u32))
        .collect();
    if keyed.len() > PARALLEL_SORT_MIN {
        keyed.par_sort_unstable();
    } else {
        keyed.sort_unstable();
    }
    // the representative of each vertex: the smallest index with its key (sorted first)
    let mut rep = vec![NO_VERTEX; positions.len()];
    for run in keyed.chunk_by(|a, b| a.0 == b.0) {
        let r = run[0].1;
        for &(_, i) in run {
            rep[i as usize] = r;
        }
    }
    let mut map = vec![NO_VERTEX; positions.len()];
    let mut first = Vec::with_capacity(keyed.len());
    for i in 0..positions.len() {
        let r = rep[i];
        if r == NO_VERTEX {
            continue;
        }
        if r as usize == i {
            map[i] = first.len() as u32;
            first.push(i);
        } else {
            // r < i, so its class is numbered already
            map[i] = map[r as usize];
        }
    }
    (map, first)
}

/// How many vertices sit at the position of an earlier vertex (bit-identical, −0.0 = 0.0);
/// `0` when every position is distinct.
///
/// # Examples
/// ```
/// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [-0.0, 0.0, 0.0]];
/// assert_eq!(conformap_io::coincident_vertices(&p), 1);
/// ```
pub fn coincident_vertices(positions: &[[f64; 3]]) -> usize {
    positions.len() - classes(positions, None).1.len()
}

/// Welds coincident vertices (positions with the same bits, −0.0 = 0.0): one vertex per class, in
/// order of first occurrence, and the faces renumbered.
///
/// # Examples
/// ```
/// // two triangles of a square exported as a soup: six vertices, four positions
/// let p = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0],
///          [0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
/// let w = conformap_io::weld_coincident(&p, &[[0, 1, 2], [3, 4, 5]]);
/// assert_eq!(w.faces, vec![[0, 1, 2], [0, 2, 3]]);
/// assert_eq!((w.positions.len(), w.merged()), (4, 2));
/// ```
pub fn weld_coincident(positions: &[[f64; 3]], faces: &[[u32; 3]]) -> Welded {
    let (map, first) = classes(positions, None);
    Welded {
        positions: first.iter().map(|&i| positions[i]).collect(),
        // an index past the positions stays past them (validation names it)
        faces: faces
            .iter()
            .map(|f| f.map(|i| map.get(i as usize).copied().unwrap_or(i)))
            .collect(),
        map,
        first,
    }
}

impl RawMesh {
    /// Welds coincident vertices (see [`weld_coincident`]) so that an OBJ is read as a glTF
    /// is; returns the mesh and the number of vertices merged. The OBJ line of a welded
    /// vertex is that of its first `v`; per-vertex texture coordinates survive when the
    /// welded vertices agree, otherwise [`Self::uv_problem`] names the seam. A glTF read is
    /// welded already (nothing changes).
    ///
    /// # Examples
    /// ```
    /// use conformap_io::{read_raw_mesh_from_bytes, Format};
    /// let soup = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 4 5 6\n";
    /// let raw = read_raw_mesh_from_bytes(soup, Format::Obj)?;
    /// let (raw, merged) = raw.weld_coincident();
    /// assert_eq!(merged, 2);
    /// let mesh = raw.validate()?.mesh;
    /// assert_eq!(mesh.boundary_loops()[0].len(), 4); // one square, not two triangles
    /// # Ok::<(), conformap_io::IoError>(())
    /// ```
    pub fn weld_coincident(mut self) -> (Self, usize) {
        let w = weld_coincident(&self.positions, &self.faces);
        let merged = w.merged();
        if merged == 0 {
            return (self, 0);
        }
        if let Some(uv) = self.uv.take() {
            match merge_uv(&self, &uv, &w) {
                Ok(merged_uv) => self.uv = Some(merged_uv),
                Err(problem) => self.uv_problem = Some(problem),
            }
        }
        if let Some(lines) = &mut self.source.vertex_lines {
            *lines = w.first.iter().map(|&i| lines[i]).collect();
        }
        self.source.notes.push(format!(
            "welded {} vertices into {} (coincident positions)",
            w.map.len(),
            w.positions.len()
        ));
        self.positions = w.positions;
        self.faces = w.faces;
        self.reset_origins(&w.first);
        (self, merged)
    }
}

/// The texture coordinate of each welded vertex, or the first seam: two welded vertices
/// with different ones.
fn merge_uv(
    raw: &RawMesh,
    uv: &[Option<[f64; 2]>],
    w: &Welded,
) -> Result<Vec<Option<[f64; 2]>>, UvProblem> {
    // the fallback is never used: only OBJ reads have coincident vertices, and OBJ
    // vertices all have a line
    let place = |i: usize| raw.vertex_place(i).unwrap_or(Origin::Line(0));
    let mut out: Vec<Option<([f64; 2], usize)>> = vec![None; w.positions.len()];
    for (i, t) in uv.iter().enumerate() {
        let (Some(t), Some(&c)) = (t, w.map.get(i)) else {
            continue;
        };
        match &out[c as usize] {
            None => out[c as usize] = Some((*t, i)),
            Some((t0, i0)) => {
                if t0.map(f64::to_bits) != t.map(f64::to_bits) {
                    return Err(UvProblem::Seam {
                        vertex: c as usize,
                        origin: place(i),
                        first: place(*i0),
                    });
                }
            }
        }
    }
    Ok(out.into_iter().map(|s| s.map(|(t, _)| t)).collect())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    #[test]
    fn classes_in_order_of_first_occurrence() {
        let p = [
            [2.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [2.0, -0.0, 0.0],
            [1.0, 0.0, 0.0],
            [3.0, 0.0, 0.0],
        ];
        let (map, first) = classes(&p, None);
        assert_eq!(map, vec![0, 1, 0, 1, 2]);
        assert_eq!(first, vec![0, 1, 4]);
        let (map, first) = classes(&p, Some(&[false, true, true, true, true]));
        assert_eq!(map, vec![NO_VERTEX, 0, 1, 0, 2]);
        assert_eq!(first, vec![1, 2, 4]);
        assert_eq!(coincident_vertices(&p), 2);
    }

    #[test]
    fn large_inputs_sort_in_parallel_with_the_same_classes() {
        let n = 3 * PARALLEL_SORT_MIN;
        let p: Vec<[f64; 3]> = (0..n).map(|i| [(i % 1000) as f64, 0.5, 0.0]).collect();
        let (map, first) = classes(&p, None);
        assert_eq!(first.len(), 1000);
        assert!(map.iter().enumerate().all(|(i, &m)| m as usize == i % 1000));
    }
}
