//! The rest of the hole surgery of CEM §3.3 (Algorithm 2): the centroid-fan patch `P_i` of
//! one loop as faces, "fill every hole but one", and the inverse of [`fill_holes`]
//! ("open all holes").
//!
//! Conventions shared with [`fill_holes`]: original vertices keep their indices, the centre
//! of the `j`-th filled loop is vertex `original_vertices + j`, the original faces come
//! first, and the patch of a loop `(v_0, …, v_{m−1})` (surface on its left) is the fan
//! `[v_{i+1}, v_i, c]`, which runs the loop the other way so that the filled surface stays
//! consistently oriented.

use crate::surgery::{fill_holes, FilledMesh};
use crate::{MeshError, TriMesh};

/// The faces of the centroid-fan patch that closes the boundary loop `lp` (vertices in loop
/// order, surface on the left) around the vertex `centre`: `[lp[i + 1], lp[i], centre]` for
/// every edge of the loop, in loop order. These are exactly the faces [`fill_holes`] adds
/// for that loop.
///
/// # Examples
/// ```
/// use conformap_mesh::centroid_fan_faces;
/// assert_eq!(
///     centroid_fan_faces(&[4, 7, 9], 12),
///     vec![[7, 4, 12], [9, 7, 12], [4, 9, 12]]
/// );
/// ```
pub fn centroid_fan_faces(lp: &[u32], centre: u32) -> Vec<[u32; 3]> {
    (0..lp.len())
        .map(|i| [lp[(i + 1) % lp.len()], lp[i], centre])
        .collect()
}

/// Fills every boundary loop of `mesh` except loop `keep` (an index into
/// `mesh.boundary_loops()`) with its centroid fan: the simply-connected surface `M^(keep)` of
/// CEM Algorithm 2, whose only boundary loop is loop `keep`.
///
/// # Errors
/// [`MeshError`] as [`fill_holes`] (a degenerate fan triangle). Asking to keep a loop that
/// does not exist fills every loop (the result is then closed).
///
/// # Examples
/// ```
/// use conformap_mesh::{fill_all_holes_except, Topology, TriMesh};
/// // a square with a square hole (8 vertices, 8 faces): two loops
/// let p = [[0., 0.], [3., 0.], [3., 3.], [0., 3.], [1., 1.], [2., 1.], [2., 2.], [1., 2.]];
/// let positions = p.iter().map(|q| [q[0], q[1], 0.0]).collect();
/// let faces = vec![
///     [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7],
/// ];
/// let mesh = TriMesh::try_new(positions, faces)?;
/// let outer = mesh.longest_boundary_loop().unwrap_or(0);
/// let filled = fill_all_holes_except(&mesh, outer)?;
/// assert_eq!(filled.mesh.topology(), Topology::Disk);
/// assert_eq!(filled.mesh.num_vertices(), 9);
/// # Ok::<(), conformap_mesh::MeshError>(())
/// ```
pub fn fill_all_holes_except(mesh: &TriMesh, keep: usize) -> Result<FilledMesh, MeshError> {
    let loops: Vec<usize> = (0..mesh.boundary_loops().len())
        .filter(|&l| l != keep)
        .collect();
    fill_holes(mesh, &loops)
}

impl FilledMesh {
    /// The centre vertex added for boundary loop `loop_index` of the input mesh, or `None`
    /// if that loop was not filled.
    pub fn centre_vertex(&self, loop_index: usize) -> Option<u32> {
        self.filled_loops
            .iter()
            .position(|&l| l == loop_index)
            .map(|j| (self.original_vertices + j) as u32)
    }

    /// Whether vertex `v` of the filled mesh is a vertex of the input mesh (not a centre).
    pub fn is_original_vertex(&self, v: usize) -> bool {
        v < self.original_vertices
    }

    /// The values of the input's vertices in a per-vertex array of the filled mesh (a map
    /// of the filled mesh restricted to the input: "open all holes", CEM Algorithm 2 step 4),
    /// or `None` if `values` is shorter than the input's vertex count.
    ///
    /// # Examples
    /// ```
    /// # use conformap_mesh::{fill_holes, TriMesh};
    /// # let p = [[0., 0.], [3., 0.], [3., 3.], [0., 3.], [1., 1.], [2., 1.], [2., 2.], [1., 2.]];
    /// # let faces = vec![
    /// #     [0, 1, 5], [0, 5, 4], [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7],
    /// # ];
    /// # let mesh = TriMesh::try_new(p.iter().map(|q| [q[0], q[1], 0.0]).collect(), faces)?;
    /// let filled = fill_holes(&mesh, &[0, 1])?;
    /// let per_vertex: Vec<usize> = (0..filled.mesh.num_vertices()).collect();
    /// assert_eq!(filled.open_values(&per_vertex), Some(&per_vertex[..8]));
    /// # Ok::<(), conformap_mesh::MeshError>(())
    /// ```
    pub fn open_values<'a, T>(&self, values: &'a [T]) -> Option<&'a [T]> {
        values.get(..self.original_vertices)
    }

    /// The input mesh back: the filled mesh without the centre vertices and their fans
    /// (the inverse of [`fill_holes`]), with the input's vertex and face order.
    ///
    /// # Errors
    /// [`MeshError`] only if the filled mesh was not made by [`fill_holes`] (the first
    /// `original_faces` faces then need not form a valid mesh).
    pub fn open_holes(&self) -> Result<TriMesh, MeshError> {
        let positions = self.mesh.positions()[..self.original_vertices].to_vec();
        let faces = self.mesh.faces()[..self.original_faces].to_vec();
        TriMesh::try_new(positions, faces)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Topology;

    /// An `n × n` grid of unit squares (with a little relief) whose listed cells are left out.
    fn grid_with_holes(n: u32, removed: &[(u32, u32)]) -> TriMesh {
        let mut p = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let z = 0.1 * f64::from((i * 7 + j * 3) % 5);
                p.push([f64::from(i), f64::from(j), z]);
            }
        }
        let id = |i: u32, j: u32| j * (n + 1) + i;
        let mut f = Vec::new();
        for j in 0..n {
            for i in 0..n {
                if removed.contains(&(i, j)) {
                    continue;
                }
                f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        // drop unreferenced vertices, keeping the order of the others
        let mut used = vec![false; p.len()];
        for t in &f {
            for &v in t {
                used[v as usize] = true;
            }
        }
        let mut new_index = vec![u32::MAX; p.len()];
        let mut q = Vec::new();
        for (v, pos) in p.iter().enumerate() {
            if used[v] {
                new_index[v] = q.len() as u32;
                q.push(*pos);
            }
        }
        let f = f
            .into_iter()
            .map(|t| t.map(|v| new_index[v as usize]))
            .collect();
        TriMesh::try_new(q, f).expect("valid grid")
    }

    fn two_hole_mesh() -> TriMesh {
        grid_with_holes(7, &[(1, 1), (2, 1), (4, 4), (5, 5), (4, 5), (5, 4)])
    }

    #[test]
    fn fan_faces_are_those_of_fill_holes() {
        let mesh = two_hole_mesh();
        assert_eq!(
            mesh.topology(),
            Topology::MultiplyConnected { boundaries: 3 }
        );
        let filled = fill_holes(&mesh, &[2, 0]).expect("fill");
        let mut next = mesh.num_faces();
        for (j, &l) in filled.filled_loops.iter().enumerate() {
            let lp = &mesh.boundary_loops()[l];
            let centre = filled.centre_vertex(l).expect("filled loop has a centre");
            assert_eq!(centre as usize, mesh.num_vertices() + j);
            let fan = centroid_fan_faces(lp, centre);
            assert_eq!(&filled.mesh.faces()[next..next + lp.len()], &fan[..]);
            next += lp.len();
        }
        assert_eq!(next, filled.mesh.num_faces());
        assert_eq!(filled.centre_vertex(1), None);
    }

    #[test]
    fn fill_all_but_one_leaves_a_disk_bounded_by_that_loop() {
        let mesh = two_hole_mesh();
        for keep in 0..mesh.boundary_loops().len() {
            let filled = fill_all_holes_except(&mesh, keep).expect("fill");
            assert_eq!(filled.mesh.topology(), Topology::Disk);
            let kept = &mesh.boundary_loops()[keep];
            let now = &filled.mesh.boundary_loops()[0];
            // the same cycle (both start at their smallest vertex)
            assert_eq!(kept, now);
            // original vertices untouched
            assert_eq!(
                &filled.mesh.positions()[..mesh.num_vertices()],
                mesh.positions()
            );
            assert_eq!(&filled.mesh.faces()[..mesh.num_faces()], mesh.faces());
        }
    }

    #[test]
    fn open_holes_inverts_fill_holes() {
        let mesh = two_hole_mesh();
        let filled = fill_holes(&mesh, &[0, 1, 2]).expect("fill");
        assert_eq!(filled.mesh.topology(), Topology::Sphere);
        let opened = filled.open_holes().expect("open");
        assert_eq!(opened.positions(), mesh.positions());
        assert_eq!(opened.faces(), mesh.faces());
        assert_eq!(opened.boundary_loops(), mesh.boundary_loops());
        assert!(filled.is_original_vertex(mesh.num_vertices() - 1));
        assert!(!filled.is_original_vertex(mesh.num_vertices()));
        let values: Vec<f64> = (0..filled.mesh.num_vertices()).map(|v| v as f64).collect();
        let open = filled.open_values(&values).expect("long enough");
        assert_eq!(open.len(), mesh.num_vertices());
        assert_eq!(filled.open_values(&values[..3]), None);
    }
}
