//! The validated triangle mesh and its half-edge connectivity.

use std::sync::atomic::{AtomicU32, Ordering};

use crate::error::MeshError;

/// Marker for "no half-edge" (a boundary half-edge has no opposite).
pub const NO_HALFEDGE: u32 = u32::MAX;

/// Faces whose area is at most `DEGENERATE_AREA_REL × diag²` (diag = bounding-box
/// diagonal) are rejected as degenerate. Default `1e-14`: far below any real triangle
/// (scans have relative areas around 1e-8 and up) and well above f64 round-off for the
/// cross product (≈1e-16 relative), so only numerically collapsed faces trip it.
pub const DEGENERATE_AREA_REL: f64 = 1e-14;

/// Options of [`TriMesh::try_new_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct ValidationOptions {
    /// Relative area threshold for degenerate faces. Default: [`DEGENERATE_AREA_REL`].
    pub degenerate_area_rel: f64,
}

impl ValidationOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        degenerate_area_rel: DEGENERATE_AREA_REL,
    };

    /// Sets [`Self::degenerate_area_rel`].
    #[must_use]
    pub fn with_degenerate_area_rel(mut self, rel: f64) -> Self {
        self.degenerate_area_rel = rel;
        self
    }
}

impl Default for ValidationOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// A triangle mesh that is known to be valid: finite coordinates, indices in range,
/// no degenerate or duplicate faces, no unreferenced vertices, manifold edges and
/// vertices, consistent orientation.
///
/// Half-edge `h = 3 f + k` runs from `faces[f][k]` to `faces[f][(k + 1) % 3]`.
#[derive(Debug, Clone)]
pub struct TriMesh {
    positions: Vec<[f64; 3]>,
    faces: Vec<[u32; 3]>,
    /// Opposite half-edge of each half-edge, or [`NO_HALFEDGE`] on the boundary.
    opposite: Vec<u32>,
    /// Oriented boundary loops (face interior on the left), each starting at its smallest vertex.
    boundary_loops: Vec<Vec<u32>>,
    /// `true` for vertices on a boundary loop.
    is_boundary: Vec<bool>,
    edge_count: usize,
    components: usize,
}

impl TriMesh {
    /// Validates `positions` and `faces` with the default [`ValidationOptions`].
    ///
    /// # Errors
    /// The first defect found, as a [`MeshError`] naming the element.
    ///
    /// # Examples
    /// ```
    /// use conformap_mesh::TriMesh;
    /// let mesh = TriMesh::try_new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [2, 1, 3]],
    /// ).unwrap();
    /// assert_eq!(mesh.boundary_loops().len(), 1);
    /// assert_eq!(mesh.euler_characteristic(), 1);
    /// ```
    pub fn try_new(positions: Vec<[f64; 3]>, faces: Vec<[u32; 3]>) -> Result<Self, MeshError> {
        Self::try_new_with(positions, faces, &ValidationOptions::DEFAULT)
    }

    /// Validates `positions` and `faces` with the given options.
    ///
    /// # Errors
    /// The first defect found, as a [`MeshError`] naming the element.
    pub fn try_new_with(
        positions: Vec<[f64; 3]>,
        faces: Vec<[u32; 3]>,
        options: &ValidationOptions,
    ) -> Result<Self, MeshError> {
        let n = positions.len();
        if n == 0 {
            return Err(MeshError::NoVertices);
        }
        if faces.is_empty() {
            return Err(MeshError::NoFaces { vertices: n });
        }
        if n >= NO_HALFEDGE as usize || faces.len() * 3 >= NO_HALFEDGE as usize {
            return Err(MeshError::TooManyVertices { vertices: n });
        }
        check_coordinates(&positions)?;
        check_indices(&positions, &faces, options)?;
        // every index is valid now: the face checks, the half-edge matching and the
        // components are independent passes, run on both cores; their errors are reported
        // in the order the sequential checks had (faces, then edges)
        let ((checked, opposite), components) = rayon::join(
            || {
                rayon::join(
                    || check_faces(&positions, &faces, options),
                    || match_halfedges(n, &faces),
                )
            },
            || count_components(n, &faces),
        );
        checked?;
        // a duplicate face outranks the edge errors: with a valid matching the duplicates
        // are found from it; after an edge error, by the sort of every face's vertex set
        let opposite = match opposite {
            Ok(opposite) => {
                duplicate_pairs(&opposite)?;
                opposite
            }
            Err(e) => {
                duplicate_faces(n, &faces)?;
                return Err(e);
            }
        };
        let fans = check_fans_and_loops(n, &faces, &opposite)?;
        Ok(Self::checked(positions, faces, opposite, fans, components))
    }

    /// The mesh of checked arrays: its half-edge matching, boundary flags and loops, and
    /// component count as found; the edges counted from the matching.
    fn checked(
        positions: Vec<[f64; 3]>,
        faces: Vec<[u32; 3]>,
        opposite: Vec<u32>,
        (is_boundary, boundary_loops): (Vec<bool>, Vec<Vec<u32>>),
        components: usize,
    ) -> Self {
        let edge_count = opposite
            .iter()
            .enumerate()
            .filter(|&(h, &o)| o == NO_HALFEDGE || (h as u32) < o)
            .count();
        Self {
            positions,
            faces,
            opposite,
            boundary_loops,
            is_boundary,
            edge_count,
            components,
        }
    }

    /// A mesh opened from a validated one (`topology::cut_mesh`, [`Self::sub_mesh`]): `faces` are the
    /// source's faces with their corners renumbered to copies of its vertices (`positions`
    /// copied from it) and `opposite` its half-edge matching with the opened edges removed,
    /// so the per-face and per-index checks and the half-edge matching of
    /// [`Self::try_new`] would only repeat the source's. What opening can break is checked:
    /// every vertex's fan and the boundary loops; the components are counted.
    ///
    /// # Errors
    /// [`MeshError::NonManifoldVertex`] if a copy's corners do not form one fan.
    pub(crate) fn opened(
        positions: Vec<[f64; 3]>,
        faces: Vec<[u32; 3]>,
        opposite: Vec<u32>,
    ) -> Result<Self, MeshError> {
        let n = positions.len();
        debug_assert_eq!(opposite.len(), 3 * faces.len());
        let (fans, components) = rayon::join(
            || check_fans_and_loops(n, &faces, &opposite),
            || count_components(n, &faces),
        );
        Ok(Self::checked(positions, faces, opposite, fans?, components))
    }

    /// The mesh of the faces `faces` of this one (each once), its vertices renumbered in
    /// the order the faces first use them, and the vertex of this mesh each one is: what
    /// [`TriMesh::try_new`] gives on those faces, without repeating the checks this mesh
    /// passed (the positions, the faces, the half-edge matching, which a subset of faces
    /// inherits). What a subset can break is checked: every vertex's fan and the boundary
    /// loops; the components are counted.
    ///
    /// # Errors
    /// [`MeshError::NoVertices`] for no faces; [`MeshError::NonManifoldVertex`] (as
    /// `try_new` reports it) where a vertex's faces in the subset form two fans.
    ///
    /// # Panics
    /// If a face index is out of range (a caller bug, never user data). A face listed
    /// twice is [`MeshError::DuplicateFace`], as `try_new` reports it.
    ///
    /// # Examples
    /// ```
    /// use conformap_mesh::TriMesh;
    /// let square = TriMesh::try_new(
    ///     vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
    ///     vec![[0, 1, 2], [2, 1, 3]],
    /// )?;
    /// let (half, vertices) = square.sub_mesh(&[1])?;
    /// assert_eq!(half.faces(), &[[0, 1, 2]]);
    /// assert_eq!(vertices, vec![2, 1, 3]);
    /// # Ok::<(), conformap_mesh::MeshError>(())
    /// ```
    pub fn sub_mesh(&self, faces: &[u32]) -> Result<(TriMesh, Vec<u32>), MeshError> {
        let mut local = vec![u32::MAX; self.num_vertices()];
        let mut vertices: Vec<u32> = Vec::new();
        let mut tris = Vec::with_capacity(faces.len());
        for &f in faces {
            tris.push(self.faces[f as usize].map(|v| {
                if local[v as usize] == u32::MAX {
                    local[v as usize] = vertices.len() as u32;
                    vertices.push(v);
                }
                local[v as usize]
            }));
        }
        if tris.is_empty() {
            // as `try_new` reports no faces at all (so no vertex either)
            return Err(MeshError::NoVertices);
        }
        // the matching restricted to the subset: a half-edge's partner, where its face is
        // kept, at that face's new place
        let mut new_face = vec![u32::MAX; self.num_faces()];
        for (k, &f) in faces.iter().enumerate() {
            let first = new_face[f as usize];
            if first != u32::MAX {
                // the subset's faces `first` and `k` are one face: what `try_new` says
                return Err(MeshError::DuplicateFace {
                    face: k,
                    first: first as usize,
                });
            }
            new_face[f as usize] = k as u32;
        }
        let mut opposite = Vec::with_capacity(3 * faces.len());
        for &f in faces {
            for h in 3 * f as usize..3 * f as usize + 3 {
                let o = self.opposite[h];
                opposite.push(if o == NO_HALFEDGE {
                    NO_HALFEDGE
                } else {
                    match new_face[o as usize / 3] {
                        u32::MAX => NO_HALFEDGE,
                        g => 3 * g + o % 3,
                    }
                });
            }
        }
        let positions = vertices
            .iter()
            .map(|&v| self.positions[v as usize])
            .collect();
        Ok((Self::opened(positions, tris, opposite)?, vertices))
    }

    /// Vertex positions.
    pub fn positions(&self) -> &[[f64; 3]] {
        &self.positions
    }

    /// Triangles as vertex-index triples, counter-clockwise seen from the front.
    pub fn faces(&self) -> &[[u32; 3]] {
        &self.faces
    }

    /// Number of vertices.
    pub fn num_vertices(&self) -> usize {
        self.positions.len()
    }

    /// Number of faces.
    pub fn num_faces(&self) -> usize {
        self.faces.len()
    }

    /// Number of undirected edges.
    pub fn num_edges(&self) -> usize {
        self.edge_count
    }

    /// Opposite half-edge of every half-edge (`3 f + k`), [`NO_HALFEDGE`] on the boundary.
    pub fn opposite_halfedges(&self) -> &[u32] {
        &self.opposite
    }

    /// Oriented boundary loops: each loop follows the boundary half-edges (the surface lies
    /// to the left), starts at its smallest vertex index; loops are sorted by that vertex.
    pub fn boundary_loops(&self) -> &[Vec<u32>] {
        &self.boundary_loops
    }

    /// Index of the longest boundary loop (ties: the first), or `None` for a closed mesh.
    pub fn longest_boundary_loop(&self) -> Option<usize> {
        let mut best: Option<usize> = None;
        for (i, l) in self.boundary_loops.iter().enumerate() {
            if best.is_none_or(|b| l.len() > self.boundary_loops[b].len()) {
                best = Some(i);
            }
        }
        best
    }

    /// Whether vertex `v` lies on a boundary loop.
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        self.is_boundary[v]
    }

    /// Boundary flag of every vertex.
    pub fn boundary_flags(&self) -> &[bool] {
        &self.is_boundary
    }

    /// Number of connected components.
    pub fn num_components(&self) -> usize {
        self.components
    }

    /// Euler characteristic χ = V − E + F.
    pub fn euler_characteristic(&self) -> i64 {
        self.num_vertices() as i64 - self.edge_count as i64 + self.num_faces() as i64
    }

    /// Genus of a connected mesh, from χ = 2 − 2g − b. `None` if the mesh has several
    /// components (the genus is then per component).
    pub fn genus(&self) -> Option<i64> {
        if self.components != 1 {
            return None;
        }
        Some((2 - self.euler_characteristic() - self.boundary_loops.len() as i64) / 2)
    }

    /// Length of the bounding-box diagonal.
    pub fn bbox_diagonal(&self) -> f64 {
        bbox_diagonal(&self.positions)
    }

    /// The topology class of the mesh, as the commands need it.
    pub fn topology(&self) -> Topology {
        match (self.components, self.genus(), self.boundary_loops.len()) {
            (1, Some(0), 1) => Topology::Disk,
            (1, Some(0), 0) => Topology::Sphere,
            (1, Some(0), b) => Topology::MultiplyConnected { boundaries: b },
            (1, Some(g), 0) => Topology::ClosedHigherGenus { genus: g },
            (1, Some(g), b) => Topology::OpenHigherGenus {
                genus: g,
                boundaries: b,
            },
            (c, _, _) => Topology::SeveralComponents { components: c },
        }
    }

    /// Vertex adjacency in compressed rows: neighbours of `v` are
    /// `adj.neighbors[adj.offsets[v]..adj.offsets[v + 1]]`, sorted ascending.
    pub fn vertex_adjacency(&self) -> Adjacency {
        let n = self.num_vertices();
        let mut counts = vec![0usize; n + 1];
        for (h, &o) in self.opposite.iter().enumerate() {
            let (a, b) = self.halfedge_vertices(h);
            // each undirected edge once: boundary half-edge, or the smaller of the pair
            if o == NO_HALFEDGE || (h as u32) < o {
                counts[a as usize + 1] += 1;
                counts[b as usize + 1] += 1;
            }
        }
        for i in 0..n {
            counts[i + 1] += counts[i];
        }
        let mut fill = counts.clone();
        let mut neighbors = vec![0u32; counts[n]];
        for (h, &o) in self.opposite.iter().enumerate() {
            if o == NO_HALFEDGE || (h as u32) < o {
                let (a, b) = self.halfedge_vertices(h);
                neighbors[fill[a as usize]] = b;
                fill[a as usize] += 1;
                neighbors[fill[b as usize]] = a;
                fill[b as usize] += 1;
            }
        }
        for v in 0..n {
            neighbors[counts[v]..counts[v + 1]].sort_unstable();
        }
        Adjacency {
            offsets: counts,
            neighbors,
        }
    }

    /// Start and end vertex of half-edge `h`.
    pub fn halfedge_vertices(&self, h: usize) -> (u32, u32) {
        let f = self.faces[h / 3];
        (f[h % 3], f[(h % 3 + 1) % 3])
    }

    /// The CEM "well-conditioned" checks (Yueh et al. 2017, Definition 1).
    pub fn well_conditioned(&self) -> WellConditioned {
        let adj = self.vertex_adjacency();
        let n = self.num_vertices();
        let interior: Vec<bool> = self.is_boundary.iter().map(|b| !b).collect();
        let boundary = self.is_boundary.clone();
        let all = vec![true; n];
        let lonely: Vec<u32> = (0..n)
            .filter(|&v| {
                self.is_boundary[v]
                    && adj
                        .neighbors_of(v)
                        .iter()
                        .all(|&w| self.is_boundary[w as usize])
            })
            .map(|v| v as u32)
            .collect();
        WellConditioned {
            connected: induced_components(&adj, &all) <= 1,
            interior_connected: induced_components(&adj, &interior) <= 1,
            boundary_connected: induced_components(&adj, &boundary) <= 1,
            boundary_vertices_without_interior_neighbor: lonely,
        }
    }
}

/// The topology class of a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum Topology {
    /// Connected, genus 0, one boundary loop: maps to the unit disk.
    Disk,
    /// Connected, genus 0, closed: maps to the unit sphere.
    Sphere,
    /// Connected, genus 0, several boundary loops: maps to a disk with circular holes.
    MultiplyConnected {
        /// Number of boundary loops.
        boundaries: usize,
    },
    /// Connected, closed, genus ≥ 1.
    ClosedHigherGenus {
        /// The genus.
        genus: i64,
    },
    /// Connected, genus ≥ 1, with boundary.
    OpenHigherGenus {
        /// The genus.
        genus: i64,
        /// Number of boundary loops.
        boundaries: usize,
    },
    /// Several connected components.
    SeveralComponents {
        /// Number of components.
        components: usize,
    },
}

impl std::fmt::Display for Topology {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Disk => write!(f, "a disk (genus 0, one boundary loop)"),
            Self::Sphere => write!(f, "a closed genus-0 surface"),
            Self::MultiplyConnected { boundaries } => {
                write!(f, "a genus-0 surface with {boundaries} boundary loops")
            }
            Self::ClosedHigherGenus { genus } => write!(f, "a closed surface of genus {genus}"),
            Self::OpenHigherGenus { genus, boundaries } => {
                write!(
                    f,
                    "a surface of genus {genus} with {boundaries} boundary loop(s)"
                )
            }
            Self::SeveralComponents { components } => {
                write!(f, "a mesh of {components} separate components")
            }
        }
    }
}

/// Compressed vertex adjacency, see [`TriMesh::vertex_adjacency`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Adjacency {
    /// Row offsets, length `n + 1`.
    pub offsets: Vec<usize>,
    /// Concatenated neighbour lists.
    pub neighbors: Vec<u32>,
}

impl Adjacency {
    /// Neighbours of vertex `v`, sorted.
    pub fn neighbors_of(&self, v: usize) -> &[u32] {
        &self.neighbors[self.offsets[v]..self.offsets[v + 1]]
    }
}

/// Result of the CEM Definition 1 checks. CEM's convergence theory assumes all four hold;
/// the solvers still run when they do not, and the report says which one failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct WellConditioned {
    /// (i) the mesh graph is connected.
    pub connected: bool,
    /// (ii) the subgraph on the interior vertices is connected.
    pub interior_connected: bool,
    /// (iii) the subgraph on the boundary vertices is connected.
    pub boundary_connected: bool,
    /// (iv) fails for these boundary vertices: none of their neighbours is interior.
    pub boundary_vertices_without_interior_neighbor: Vec<u32>,
}

impl WellConditioned {
    /// Whether all four conditions hold.
    pub fn holds(&self) -> bool {
        self.connected
            && self.interior_connected
            && self.boundary_connected
            && self.boundary_vertices_without_interior_neighbor.is_empty()
    }
}

/// The axis-aligned bounding box `(lo, hi)` of a point set (`lo` = +∞ and `hi` = −∞ in
/// every coordinate for an empty set).
///
/// ```
/// let (lo, hi) = conformap_mesh::bounding_box(&[[0.0, 2.0, -1.0], [1.0, 0.0, 3.0]]);
/// assert_eq!((lo, hi), ([0.0, 0.0, -1.0], [1.0, 2.0, 3.0]));
/// ```
pub fn bounding_box(positions: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in positions {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    (lo, hi)
}

/// Length of the bounding-box diagonal of a point set (0 for an empty set).
pub fn bbox_diagonal(positions: &[[f64; 3]]) -> f64 {
    if positions.is_empty() {
        return 0.0;
    }
    let (lo, hi) = bounding_box(positions);
    ((hi[0] - lo[0]).powi(2) + (hi[1] - lo[1]).powi(2) + (hi[2] - lo[2]).powi(2)).sqrt()
}

/// Area of the triangle `(a, b, c)` in 3D.
pub fn triangle_area(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let v = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let x = u[1] * v[2] - u[2] * v[1];
    let y = u[2] * v[0] - u[0] * v[2];
    let z = u[0] * v[1] - u[1] * v[0];
    0.5 * (x * x + y * y + z * z).sqrt()
}

fn check_coordinates(positions: &[[f64; 3]]) -> Result<(), MeshError> {
    for (vertex, p) in positions.iter().enumerate() {
        for (k, &value) in p.iter().enumerate() {
            if !value.is_finite() {
                let axis = ['x', 'y', 'z'][k];
                return Err(MeshError::NonFiniteCoordinate {
                    vertex,
                    axis,
                    value,
                });
            }
        }
    }
    Ok(())
}

/// The first face whose indices are out of range or repeat a vertex, as its error; the
/// faces before it are checked for a degenerate area first, so the error is the one a
/// face-by-face check (indices, then area) meets first.
fn check_indices(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    options: &ValidationOptions,
) -> Result<(), MeshError> {
    let n = positions.len();
    let index_error = |face: usize, f: &[u32; 3]| -> Option<MeshError> {
        if let Some(&index) = f.iter().find(|&&i| i as usize >= n) {
            return Some(MeshError::IndexOutOfRange {
                face,
                index,
                vertex_count: n,
            });
        }
        if f[0] == f[1] || f[0] == f[2] {
            return Some(MeshError::RepeatedVertexInFace { face, vertex: f[0] });
        }
        (f[1] == f[2]).then_some(MeshError::RepeatedVertexInFace { face, vertex: f[1] })
    };
    let Some((bad, error)) = faces
        .iter()
        .enumerate()
        .find_map(|(face, f)| index_error(face, f).map(|e| (face, e)))
    else {
        return Ok(());
    };
    let threshold = area_threshold(positions, options);
    for (face, f) in faces[..bad].iter().enumerate() {
        degenerate(positions, face, f, threshold)?;
    }
    Err(error)
}

/// The smallest face area accepted: [`ValidationOptions::degenerate_area_rel`] times the
/// squared bounding-box diagonal.
fn area_threshold(positions: &[[f64; 3]], options: &ValidationOptions) -> f64 {
    let diag = bbox_diagonal(positions);
    options.degenerate_area_rel * diag * diag
}

/// [`MeshError::ZeroAreaFace`] for a face (valid indices) of area at most `threshold`.
fn degenerate(
    positions: &[[f64; 3]],
    face: usize,
    f: &[u32; 3],
    threshold: f64,
) -> Result<(), MeshError> {
    let area = triangle_area(
        positions[f[0] as usize],
        positions[f[1] as usize],
        positions[f[2] as usize],
    );
    // a NaN area (overflowing coordinates) is degenerate too
    if area.is_nan() || area <= threshold {
        return Err(MeshError::ZeroAreaFace {
            face,
            area,
            threshold,
        });
    }
    Ok(())
}

/// Degenerate faces and unreferenced vertices of faces whose indices [`check_indices`]
/// accepted (duplicate faces: [`duplicate_pairs`], [`duplicate_faces`]).
fn check_faces(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    options: &ValidationOptions,
) -> Result<(), MeshError> {
    let n = positions.len();
    let threshold = area_threshold(positions, options);
    let mut referenced = vec![false; n];
    for (face, f) in faces.iter().enumerate() {
        for &index in f {
            referenced[index as usize] = true;
        }
        degenerate(positions, face, f, threshold)?;
    }
    if let Some(vertex) = referenced.iter().position(|r| !r) {
        let count = referenced.iter().filter(|r| !**r).count();
        return Err(MeshError::UnreferencedVertex { vertex, count });
    }
    Ok(())
}

/// [`MeshError::DuplicateFace`] for two faces with the same vertex set, whatever the
/// order: of all such pairs (the second and first face of each set in face order), the
/// one whose second face comes first.
fn duplicate_faces(n: usize, faces: &[[u32; 3]]) -> Result<(), MeshError> {
    // grouped by smallest vertex
    let (sorted, offsets) = sort_by_bucket(
        n,
        faces.len(),
        faces.iter().enumerate().map(|(i, f)| {
            let mut k = *f;
            k.sort_unstable();
            let rest = (u128::from(k[1]) << 64) | (u128::from(k[2]) << 32) | i as u128;
            (k[0], rest)
        }),
    );
    let mut dup: Option<(usize, usize)> = None;
    for bucket in offsets.windows(2) {
        for w in sorted[bucket[0]..bucket[1]].windows(2) {
            if w[0] >> 32 == w[1] >> 32 {
                let cand = ((w[1] as u32) as usize, (w[0] as u32) as usize);
                if dup.is_none_or(|d| cand.0 < d.0) {
                    dup = Some(cand);
                }
            }
        }
    }
    if let Some((face, first)) = dup {
        return Err(MeshError::DuplicateFace { face, first });
    }
    Ok(())
}

/// [`duplicate_faces`] of faces whose half-edges matched without error (no edge of more
/// than two faces, opposite half-edges run opposite ways): two faces share their vertex
/// set exactly when the three opposites of one lie in the other, and no set then has a
/// third face, so the pairs are found without sorting (the same error as
/// [`duplicate_faces`] reports).
fn duplicate_pairs(opposite: &[u32]) -> Result<(), MeshError> {
    let dup = opposite
        .chunks_exact(3)
        .enumerate()
        .filter_map(|(f, o)| {
            let g = o[0] / 3;
            (o[0] != NO_HALFEDGE
                && o[1] / 3 == g
                && o[2] / 3 == g
                && o[1] != NO_HALFEDGE
                && o[2] != NO_HALFEDGE)
                .then(|| (f.max(g as usize), f.min(g as usize)))
        })
        .min();
    match dup {
        Some((face, first)) => Err(MeshError::DuplicateFace { face, first }),
        None => Ok(()),
    }
}

/// Sorts `(bucket, rest)` items by bucket (a counting sort: buckets are vertex indices
/// below `n`) and then by `rest` within each bucket, which orders them exactly as a full
/// sort of `(bucket, rest)` would, in linear time plus sorts of a few items each. Returns
/// the `rest` values and the bucket offsets (`n + 1`).
fn bucket_scatter<T: Ord + Copy + Default>(
    n: usize,
    len: usize,
    items: impl Iterator<Item = (u32, T)> + Clone,
) -> (Vec<T>, Vec<usize>) {
    let mut offsets = vec![0usize; n + 1];
    for (b, _) in items.clone() {
        offsets[b as usize + 1] += 1;
    }
    for i in 0..n {
        offsets[i + 1] += offsets[i];
    }
    let mut sorted = vec![T::default(); len];
    // `offsets[b]` is the next free place of bucket `b` while filling, so it ends as the
    // start of bucket `b + 1`: shifted back by one place afterwards (no second array)
    for (b, rest) in items {
        sorted[offsets[b as usize]] = rest;
        offsets[b as usize] += 1;
    }
    if n > 0 {
        offsets.copy_within(0..n - 1, 1);
        offsets[0] = 0;
    }
    (sorted, offsets)
}

/// [`bucket_scatter`], then each bucket sorted: `(bucket, rest)` items in the order of a
/// full sort (see [`bucket_scatter`]).
fn sort_by_bucket<T: Ord + Copy + Default>(
    n: usize,
    len: usize,
    items: impl Iterator<Item = (u32, T)> + Clone,
) -> (Vec<T>, Vec<usize>) {
    let (mut sorted, offsets) = bucket_scatter(n, len, items);
    for w in offsets.windows(2) {
        sorted[w[0]..w[1]].sort_unstable();
    }
    (sorted, offsets)
}

/// Vertices per piece of the bucket range below which [`match_halfedges`] stops splitting
/// it between threads (a piece then takes ~1 ms).
const MATCH_SPLIT_VERTICES: usize = 1 << 14;

/// Pairs half-edges into opposites; rejects non-manifold edges and inconsistent orientation
/// with the error of [`match_halfedges_in_order`].
///
/// The buckets (half-edges by smaller vertex) are sorted and matched in pieces on all
/// threads; a piece that meets any error stops, and the matching is then redone in order
/// by [`match_halfedges_in_order`], which picks the error to report (the rule depends on
/// the order errors are met in).
fn match_halfedges(n: usize, faces: &[[u32; 3]]) -> Result<Vec<u32>, MeshError> {
    let nh = faces.len() * 3;
    let (mut keys, offsets) = bucket_scatter(n, nh, halfedge_keys(faces));
    let opposite: Vec<AtomicU32> = (0..nh).map(|_| AtomicU32::new(NO_HALFEDGE)).collect();
    if !match_buckets(&mut keys, &offsets, 0..n, faces, &opposite) {
        return match_halfedges_in_order(n, faces);
    }
    Ok(opposite.into_iter().map(AtomicU32::into_inner).collect())
}

/// The half-edges of `faces` as `(smaller vertex, larger vertex << 32 | half-edge)`.
fn halfedge_keys(faces: &[[u32; 3]]) -> impl Iterator<Item = (u32, u64)> + Clone + '_ {
    faces.iter().enumerate().flat_map(|(f, tri)| {
        (0..3).map(move |k| {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            let rest = (u64::from(a.max(b)) << 32) | (3 * f + k) as u64;
            (a.min(b), rest)
        })
    })
}

/// Sorts and matches the buckets `range` (their keys are `keys`, which starts at bucket
/// `range.start`), splitting the range between threads; `false` at the first error.
fn match_buckets(
    keys: &mut [u64],
    offsets: &[usize],
    range: std::ops::Range<usize>,
    faces: &[[u32; 3]],
    opposite: &[AtomicU32],
) -> bool {
    if range.len() > MATCH_SPLIT_VERTICES {
        let mid = range.start + range.len() / 2;
        let (lo, hi) = keys.split_at_mut(offsets[mid] - offsets[range.start]);
        let (a, b) = rayon::join(
            || match_buckets(lo, offsets, range.start..mid, faces, opposite),
            || match_buckets(hi, offsets, mid..range.end, faces, opposite),
        );
        return a && b;
    }
    let base = offsets[range.start];
    for v in range {
        let bucket = &mut keys[offsets[v] - base..offsets[v + 1] - base];
        bucket.sort_unstable();
        for run in bucket.chunk_by(|x, y| x >> 32 == y >> 32) {
            match run {
                [_] => {}
                [x, y] => {
                    let (h0, h1) = ((*x as u32) as usize, (*y as u32) as usize);
                    // the two half-edges of an edge run opposite ways
                    if faces[h0 / 3][h0 % 3] == faces[h1 / 3][h1 % 3] {
                        return false;
                    }
                    opposite[h0].store(h1 as u32, Ordering::Relaxed);
                    opposite[h1].store(h0 as u32, Ordering::Relaxed);
                }
                _ => return false,
            }
        }
    }
    true
}

/// [`match_halfedges`] in one pass over the buckets in order.
///
/// The half-edges are grouped by their undirected edge `(min, max)` in the order of a sort
/// by `(min, max, half-edge)` (see [`sort_by_bucket`]); the first error in that order
/// wins as described below.
fn match_halfedges_in_order(n: usize, faces: &[[u32; 3]]) -> Result<Vec<u32>, MeshError> {
    let nh = faces.len() * 3;
    // bucket: the smaller vertex; rest: the larger vertex << 32 | half-edge
    let (keys, offsets) = sort_by_bucket(n, nh, halfedge_keys(faces));
    let mut opposite = vec![NO_HALFEDGE; nh];
    let mut first_error: Option<(usize, MeshError)> = None;
    for (a, bucket) in offsets.windows(2).enumerate() {
        let a = a as u32;
        for run in keys[bucket[0]..bucket[1]].chunk_by(|x, y| x >> 32 == y >> 32) {
            let b = (run[0] >> 32) as u32;
            let he = |i: usize| (run[i] as u32) as usize;
            match run.len() {
                1 => {}
                2 => {
                    let (h0, h1) = (he(0), he(1));
                    let start = |h: usize| faces[h / 3][h % 3];
                    if start(h0) == start(h1) {
                        let e = MeshError::InconsistentOrientation {
                            face: h1 / 3,
                            other: h0 / 3,
                            a: start(h0),
                            b: faces[h0 / 3][(h0 % 3 + 1) % 3],
                        };
                        if first_error.as_ref().is_none_or(|(f, _)| h1 / 3 < *f) {
                            first_error = Some((h1 / 3, e));
                        }
                    } else {
                        opposite[h0] = h1 as u32;
                        opposite[h1] = h0 as u32;
                    }
                }
                count => {
                    let fs: Vec<usize> = (0..count.min(4)).map(|i| he(i) / 3).collect();
                    let at = fs[0];
                    // non-manifold edges outrank orientation problems at the same place
                    if first_error.as_ref().is_none_or(|(f, e)| {
                        at < *f || !matches!(e, MeshError::NonManifoldEdge { .. })
                    }) {
                        first_error = Some((
                            at,
                            MeshError::NonManifoldEdge {
                                a,
                                b,
                                count,
                                faces: fs,
                            },
                        ));
                    }
                }
            }
        }
    }
    match first_error {
        Some((_, e)) => Err(e),
        None => Ok(opposite),
    }
}

/// Checks that the faces around each vertex form one fan; returns boundary flags and loops.
fn check_fans_and_loops(
    n: usize,
    faces: &[[u32; 3]],
    opposite: &[u32],
) -> Result<(Vec<bool>, Vec<Vec<u32>>), MeshError> {
    let mut face_count = vec![0u32; n];
    let mut out_he = vec![NO_HALFEDGE; n];
    let mut boundary_out = vec![NO_HALFEDGE; n];
    let mut boundary_out_count = vec![0u32; n];
    for (f, tri) in faces.iter().enumerate() {
        for k in 0..3 {
            let v = tri[k] as usize;
            let h = (3 * f + k) as u32;
            face_count[v] += 1;
            if out_he[v] == NO_HALFEDGE {
                out_he[v] = h;
            }
            if opposite[h as usize] == NO_HALFEDGE {
                boundary_out[v] = h;
                boundary_out_count[v] += 1;
            }
        }
    }
    let prev = |h: u32| -> u32 { 3 * (h / 3) + (h % 3 + 2) % 3 };
    for v in 0..n {
        let start = if boundary_out[v] != NO_HALFEDGE {
            boundary_out[v]
        } else {
            out_he[v]
        };
        let mut h = start;
        let mut visited = 0u32;
        loop {
            visited += 1;
            let o = opposite[prev(h) as usize];
            if o == NO_HALFEDGE || o == start || visited > face_count[v] {
                break;
            }
            h = o;
        }
        if visited != face_count[v] || boundary_out_count[v] > 1 {
            return Err(MeshError::NonManifoldVertex {
                vertex: v,
                faces: face_count[v] as usize,
            });
        }
    }
    let is_boundary: Vec<bool> = boundary_out.iter().map(|&h| h != NO_HALFEDGE).collect();
    let mut loops = Vec::new();
    let mut seen = vec![false; n];
    for v in 0..n {
        if !is_boundary[v] || seen[v] {
            continue;
        }
        let mut lp = Vec::new();
        let mut w = v;
        while !seen[w] {
            seen[w] = true;
            lp.push(w as u32);
            let h = boundary_out[w] as usize;
            w = faces[h / 3][(h % 3 + 1) % 3] as usize;
        }
        loops.push(lp);
    }
    Ok((is_boundary, loops))
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[x as usize];
        parent[x as usize] = parent[p as usize];
        x = p;
    }
    x
}

fn count_components(n: usize, faces: &[[u32; 3]]) -> usize {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    for f in faces {
        for k in 1..3 {
            let (a, b) = (find(&mut parent, f[0]), find(&mut parent, f[k]));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
            }
        }
    }
    (0..n as u32).filter(|&v| find(&mut parent, v) == v).count()
}

fn induced_components(adj: &Adjacency, keep: &[bool]) -> usize {
    let n = keep.len();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    for v in 0..n {
        if !keep[v] {
            continue;
        }
        for &w in adj.neighbors_of(v) {
            if keep[w as usize] {
                let (a, b) = (find(&mut parent, v as u32), find(&mut parent, w));
                if a != b {
                    parent[a.max(b) as usize] = a.min(b);
                }
            }
        }
    }
    (0..n as u32)
        .filter(|&v| keep[v as usize] && find(&mut parent, v) == v)
        .count()
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    /// Triangles of an `n × n` grid of squares, consistently oriented.
    fn grid_faces(n: u32) -> Vec<[u32; 3]> {
        let at = |i: u32, j: u32| i * (n + 1) + j;
        (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .flat_map(|(i, j)| {
                [
                    [at(i, j), at(i, j + 1), at(i + 1, j + 1)],
                    [at(i, j), at(i + 1, j + 1), at(i + 1, j)],
                ]
            })
            .collect()
    }

    /// The matching split between threads gives the one in order: the opposites of a
    /// valid mesh large enough to be split, and the error (found again in order) when
    /// faces far apart in the bucket range break it in different ways.
    #[test]
    fn split_matching_agrees_with_the_matching_in_order() {
        let n = 300; // 90,601 vertices: several pieces of MATCH_SPLIT_VERTICES
        let faces = grid_faces(n);
        let v = ((n + 1) * (n + 1)) as usize;
        assert!(v > 4 * MATCH_SPLIT_VERTICES);
        let split = match_halfedges(v, &faces).unwrap();
        assert_eq!(split, match_halfedges_in_order(v, &faces).unwrap());
        assert_eq!(
            split.iter().filter(|&&o| o == NO_HALFEDGE).count(),
            4 * n as usize
        );
        // a face turned over near the end and a third face on an edge near the start
        let mut broken = faces.clone();
        let last = broken.len() - 7;
        broken[last].swap(1, 2);
        broken.push([broken[10][0], broken[10][1], (v - 1) as u32]);
        assert_eq!(
            match_halfedges(v, &broken).unwrap_err(),
            match_halfedges_in_order(v, &broken).unwrap_err()
        );
    }
}
