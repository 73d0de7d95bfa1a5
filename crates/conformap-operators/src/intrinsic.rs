//! The intrinsic Delaunay triangulation of a mesh by intrinsic edge flips (Bobenko &
//! Springborn 2007, *A discrete Laplace–Beltrami operator for simplicial surfaces*; data
//! layout after Sharp, Soliman & Crane 2019, *Navigating intrinsic triangulations*), and
//! its cotangent Laplacian.
//!
//! The surface is the mesh's own piecewise-flat metric; only its triangulation changes.
//! Every triangle stores its area, every half-edge its length and the cotangent of the
//! angle opposite it. An interior edge whose two opposite angles sum to more than `π`
//! (cotangent weight `½(cot α + cot β) < 0`) is flipped: the two triangles are unfolded
//! into the plane and the other diagonal of the quad becomes the edge. Boundary edges never
//! flip, and the vertex set never changes, so a map computed with this Laplacian is still
//! one value per input vertex.
//!
//! Numerics (camelhead has 0.55° corners): no Heron formula anywhere. Faces of the input
//! keep the cotangents and areas computed from the 3D positions (cross and dot products,
//! exact for obtuse angles); a flip lays the quad out in the plane with the shared edge on
//! the x-axis, the heights of its two apexes taken from the stored areas (`2A / ℓ`, no
//! cancellation), and computes the new diagonal, areas and cotangents from those planar
//! points. The layout's x-coordinates come from the law of cosines, whose rounding is
//! absolute (relative to the edge lengths), never relative to a small height.

use std::collections::VecDeque;
use std::time::Instant;

use conformap_mesh::{TriMesh, NO_HALFEDGE};
use sprs::CsMat;

use crate::geometry::{face_areas, triangle_cotangents};
use crate::laplacian::add_edge_weight;
use crate::OperatorError;

/// Default Delaunay tolerance: an interior edge is flipped only when
/// `cot α + cot β < −1e-12`. Cotangents are dimensionless, so the tolerance is relative;
/// `1e-12` sits well above their rounding error (about `1e-14` for the 0.55° corners of
/// camelhead, whose cotangent is 104) so that cocircular quads (sum ≈ 0 on both diagonals)
/// are not flipped back and forth by rounding. Remaining weights in `[−½·tol, 0)` are set
/// to exactly 0 by [`IntrinsicTriangulation::laplacian`].
pub const INTRINSIC_DELAUNAY_TOL: f64 = 1e-12;

/// Default flip budget per interior edge: the flip loop stops with
/// [`OperatorError::FlipLimit`] after `64 ×` (number of interior edges) flips. Delaunay
/// flips terminate in exact arithmetic (Bobenko & Springborn 2007, Prop. 10), but no
/// polynomial bound is known for intrinsic flips; on the class-a meshes the loop needs
/// well under one flip per interior edge (camelhead: about 0.3), so 64 only catches a
/// numerical cycle.
pub const INTRINSIC_MAX_FLIPS_PER_EDGE: usize = 64;

/// Options of [`IntrinsicTriangulation::flip_to_delaunay`] and
/// [`intrinsic_delaunay_laplacian_with`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct IntrinsicOptions {
    /// Flip an interior edge when `cot α + cot β < −delaunay_tol`. Default:
    /// [`INTRINSIC_DELAUNAY_TOL`] (1e-12).
    pub delaunay_tol: f64,
    /// Flip budget per interior edge. Default: [`INTRINSIC_MAX_FLIPS_PER_EDGE`] (64).
    pub max_flips_per_edge: usize,
}

impl IntrinsicOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        delaunay_tol: INTRINSIC_DELAUNAY_TOL,
        max_flips_per_edge: INTRINSIC_MAX_FLIPS_PER_EDGE,
    };

    /// Sets [`Self::delaunay_tol`].
    #[must_use]
    pub fn with_delaunay_tol(mut self, tol: f64) -> Self {
        self.delaunay_tol = tol;
        self
    }

    /// Sets [`Self::max_flips_per_edge`].
    #[must_use]
    pub fn with_max_flips_per_edge(mut self, n: usize) -> Self {
        self.max_flips_per_edge = n;
        self
    }
}

impl Default for IntrinsicOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What the flip loop did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct IntrinsicStats {
    /// Interior edges of the mesh (the same number before and after: flips keep it).
    pub interior_edges: usize,
    /// Interior edges with a negative cotangent weight (`cot α + cot β < −tol`) in the
    /// input triangulation.
    pub non_delaunay_before: usize,
    /// Edge flips performed.
    pub flips: usize,
    /// Interior edges still non-Delaunay at the end: edges that could not be flipped
    /// (the same triangle on both sides, or a quad whose flipped triangles come out with
    /// non-positive area in f64). 0 on every mesh tried.
    pub non_delaunay_after: usize,
    /// Smallest interior-edge weight `½(cot α + cot β)` before the flips.
    pub min_weight_before: f64,
    /// Smallest interior-edge weight after the flips (before the round-off clamp).
    pub min_weight_after: f64,
    /// Boundary edges with a negative weight (opposite angle above 90°): boundary edges
    /// cannot flip, so these stay. They only enter `L_BB`, never the interior rows.
    pub negative_boundary_weights: usize,
    /// Milliseconds spent building the triangulation and flipping.
    pub flip_ms: f64,
}

/// A triangulation of the mesh's surface with the mesh's vertices, stored by lengths:
/// half-edge `h = 3 f + k` runs from `faces()[f][k]` to `faces()[f][(k + 1) % 3]`, as in
/// [`TriMesh`]. Starts as the input triangulation; [`Self::flip_to_delaunay`] makes it
/// intrinsic Delaunay. The triangulation may stop being a simplicial complex (two edges
/// between the same vertices, an edge from a vertex to itself): everything here allows
/// that.
#[derive(Debug, Clone)]
pub struct IntrinsicTriangulation {
    num_vertices: usize,
    faces: Vec<[u32; 3]>,
    twin: Vec<u32>,
    length: Vec<f64>,
    /// Cotangent of the angle opposite each half-edge.
    cot: Vec<f64>,
    area: Vec<f64>,
}

impl IntrinsicTriangulation {
    /// The input triangulation of `mesh`: lengths, areas and cotangents from its positions.
    pub fn from_mesh(mesh: &TriMesh) -> Self {
        let p = mesh.positions();
        let faces = mesh.faces().to_vec();
        let mut length = Vec::with_capacity(3 * faces.len());
        let mut cot = Vec::with_capacity(3 * faces.len());
        for t in &faces {
            let q = [p[t[0] as usize], p[t[1] as usize], p[t[2] as usize]];
            let c = triangle_cotangents(q);
            for k in 0..3 {
                let (a, b) = (q[k], q[(k + 1) % 3]);
                length.push(
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt(),
                );
                // half-edge k is opposite corner k + 2
                cot.push(c[(k + 2) % 3]);
            }
        }
        Self {
            num_vertices: mesh.num_vertices(),
            faces,
            twin: mesh.opposite_halfedges().to_vec(),
            length,
            cot,
            area: face_areas(mesh),
        }
    }

    /// Triangles as vertex triples (counter-clockwise), in face order.
    pub fn faces(&self) -> &[[u32; 3]] {
        &self.faces
    }

    /// Length of every half-edge `3 f + k`.
    pub fn halfedge_lengths(&self) -> &[f64] {
        &self.length
    }

    /// Cotangent of the angle opposite every half-edge `3 f + k`.
    pub fn halfedge_cotangents(&self) -> &[f64] {
        &self.cot
    }

    /// Opposite half-edge of every half-edge, [`NO_HALFEDGE`] on the boundary.
    pub fn opposite_halfedges(&self) -> &[u32] {
        &self.twin
    }

    /// Area of every triangle.
    pub fn face_areas(&self) -> &[f64] {
        &self.area
    }

    /// Total area (equal to the mesh's area: flips keep the area of every quad).
    pub fn total_area(&self) -> f64 {
        self.area.iter().sum()
    }

    /// The weight `½(cot α + cot β)` of the edge of half-edge `h` (`½ cot α` on the
    /// boundary).
    pub fn edge_weight(&self, h: usize) -> f64 {
        match self.twin[h] {
            NO_HALFEDGE => 0.5 * self.cot[h],
            t => 0.5 * (self.cot[h] + self.cot[t as usize]),
        }
    }

    /// Flips every interior edge that is not Delaunay (`cot α + cot β < −delaunay_tol`)
    /// until none is left, processing a queue seeded with every interior edge; after each
    /// flip the four edges of the quad are queued again.
    ///
    /// # Errors
    /// [`OperatorError::FlipLimit`] if the flip budget of the options runs out (a
    /// numerical cycle: not seen on any mesh).
    pub fn flip_to_delaunay(
        &mut self,
        options: &IntrinsicOptions,
    ) -> Result<IntrinsicStats, OperatorError> {
        let t0 = Instant::now();
        let tol = options.delaunay_tol;
        let interior: Vec<usize> = (0..self.twin.len())
            .filter(|&h| self.twin[h] != NO_HALFEDGE && (self.twin[h] as usize) > h)
            .collect();
        let mut stats = IntrinsicStats {
            interior_edges: interior.len(),
            min_weight_before: self.min_interior_weight(),
            ..IntrinsicStats::default()
        };
        stats.non_delaunay_before = interior
            .iter()
            .filter(|&&h| self.is_non_delaunay(h, tol))
            .count();
        let cap = options.max_flips_per_edge.saturating_mul(interior.len());
        let mut queue: VecDeque<usize> = interior.into_iter().collect();
        while let Some(h) = queue.pop_front() {
            if !self.is_non_delaunay(h, tol) {
                continue;
            }
            if stats.flips >= cap {
                return Err(OperatorError::FlipLimit {
                    flips: stats.flips,
                    limit: cap,
                });
            }
            if let Some(outer) = self.flip(h) {
                stats.flips += 1;
                queue.extend(outer);
            }
        }
        stats.non_delaunay_after = (0..self.twin.len())
            .filter(|&h| self.twin[h] != NO_HALFEDGE && (self.twin[h] as usize) > h)
            .filter(|&h| self.is_non_delaunay(h, tol))
            .count();
        stats.min_weight_after = self.min_interior_weight();
        stats.negative_boundary_weights = (0..self.twin.len())
            .filter(|&h| self.twin[h] == NO_HALFEDGE && self.cot[h] < 0.0)
            .count();
        stats.flip_ms = t0.elapsed().as_secs_f64() * 1e3;
        Ok(stats)
    }

    fn is_non_delaunay(&self, h: usize, tol: f64) -> bool {
        match self.twin[h] {
            NO_HALFEDGE => false,
            t => self.cot[h] + self.cot[t as usize] < -tol,
        }
    }

    fn min_interior_weight(&self) -> f64 {
        (0..self.twin.len())
            .filter(|&h| self.twin[h] != NO_HALFEDGE)
            .map(|h| self.edge_weight(h))
            .fold(f64::INFINITY, f64::min)
    }

    /// Flips the edge of half-edge `h` (`a → b` in face `(a, b, c)`, its twin `b → a` in
    /// face `(b, a, d)`) to the edge `c — d`: the faces become `(d, b, c)` and `(c, a, d)`.
    /// Returns the four outer half-edges of the quad, or `None` if the edge cannot be
    /// flipped (boundary, the same face on both sides, or a flipped triangle without
    /// positive area in f64).
    fn flip(&mut self, h: usize) -> Option<[usize; 4]> {
        let t = self.twin[h];
        if t == NO_HALFEDGE {
            return None;
        }
        let t = t as usize;
        let (f0, f1) = (h / 3, t / 3);
        if f0 == f1 {
            return None;
        }
        let next = |x: usize| 3 * (x / 3) + (x % 3 + 1) % 3;
        let prev = |x: usize| 3 * (x / 3) + (x % 3 + 2) % 3;
        let (hn, hp, tn, tp) = (next(h), prev(h), next(t), prev(t));
        let a = self.faces[f0][h % 3];
        let b = self.faces[f0][(h % 3 + 1) % 3];
        let c = self.faces[f0][(h % 3 + 2) % 3];
        let d = self.faces[f1][(t % 3 + 2) % 3];
        let (l_ab, l_bc, l_ca) = (self.length[h], self.length[hn], self.length[hp]);
        let (l_ad, l_db) = (self.length[tn], self.length[tp]);
        // unfold: a = (0, 0), b = (ℓ_ab, 0), c above the axis, d below
        let pc = [
            (l_ab * l_ab + l_ca * l_ca - l_bc * l_bc) / (2.0 * l_ab),
            2.0 * self.area[f0] / l_ab,
        ];
        let pd = [
            (l_ab * l_ab + l_ad * l_ad - l_db * l_db) / (2.0 * l_ab),
            -2.0 * self.area[f1] / l_ab,
        ];
        let (pa, pb) = ([0.0, 0.0], [l_ab, 0.0]);
        let area0 = 0.5 * cross2(sub2(pb, pd), sub2(pc, pd));
        let area1 = 0.5 * cross2(sub2(pa, pc), sub2(pd, pc));
        let l_cd = (pc[0] - pd[0]).hypot(pc[1] - pd[1]);
        if !(area0 > 0.0 && area1 > 0.0 && l_cd > 0.0 && l_cd.is_finite()) {
            return None;
        }
        let cot0 = triangle_cotangents([lift(pd), lift(pb), lift(pc)]);
        let cot1 = triangle_cotangents([lift(pc), lift(pa), lift(pd)]);
        let outer_old = [self.twin[tp], self.twin[hn], self.twin[hp], self.twin[tn]];
        let (g0, g1) = (3 * f0, 3 * f1);
        // old outer half-edge -> its new index
        let remap = |x: u32| -> u32 {
            match x as usize {
                x if x == tp => g0 as u32,
                x if x == hn => (g0 + 1) as u32,
                x if x == hp => g1 as u32,
                x if x == tn => (g1 + 1) as u32,
                _ => x,
            }
        };
        let outer_twins = outer_old.map(remap);
        self.faces[f0] = [d, b, c];
        self.faces[f1] = [c, a, d];
        self.length[g0..g0 + 3].copy_from_slice(&[l_db, l_bc, l_cd]);
        self.length[g1..g1 + 3].copy_from_slice(&[l_ca, l_ad, l_cd]);
        for k in 0..3 {
            self.cot[g0 + k] = cot0[(k + 2) % 3];
            self.cot[g1 + k] = cot1[(k + 2) % 3];
        }
        self.area[f0] = area0;
        self.area[f1] = area1;
        self.twin[g0 + 2] = (g1 + 2) as u32;
        self.twin[g1 + 2] = (g0 + 2) as u32;
        let outer_new = [g0, g0 + 1, g1, g1 + 1];
        for (&new, &o) in outer_new.iter().zip(&outer_twins) {
            self.twin[new] = o;
            if o != NO_HALFEDGE {
                self.twin[o as usize] = new as u32;
            }
        }
        Some(outer_new)
    }

    /// The sparsity pattern of the Laplacian: per vertex (column) itself and its
    /// neighbours, sorted, in one flat array (no allocation per vertex).
    fn pattern(&self) -> (Vec<usize>, Vec<usize>) {
        let n = self.num_vertices;
        // every half-edge i -> j lists j at i and i at j; interior edges come twice
        let mut start = vec![0usize; n + 1];
        for t in &self.faces {
            for &v in t {
                start[v as usize + 1] += 2;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v] + 1;
        }
        let mut fill: Vec<usize> = start[..n].to_vec();
        let mut raw = vec![0usize; start[n]];
        for v in 0..n {
            raw[fill[v]] = v;
            fill[v] += 1;
        }
        for t in &self.faces {
            for k in 0..3 {
                let (i, j) = (t[k] as usize, t[(k + 1) % 3] as usize);
                raw[fill[i]] = j;
                fill[i] += 1;
                raw[fill[j]] = i;
                fill[j] += 1;
            }
        }
        let mut indptr = Vec::with_capacity(n + 1);
        let mut indices = Vec::with_capacity(start[n] / 2 + n);
        indptr.push(0);
        for v in 0..n {
            let seg = &mut raw[start[v]..start[v + 1]];
            seg.sort_unstable();
            let first = indices.len();
            for &r in seg.iter() {
                if indices.len() == first || indices.last() != Some(&r) {
                    indices.push(r);
                }
            }
            indptr.push(indices.len());
        }
        (indptr, indices)
    }

    /// The cotangent Laplacian of this triangulation (CEM Eq. 6 with its boundary
    /// convention, see [`crate::cotan_laplacian`]): symmetric CSC, full storage, sorted row
    /// indices, on the mesh's vertices. Edges from a vertex to itself contribute nothing;
    /// parallel edges add up. Weights in `[−½·tol, 0)` (a cocircular quad's rounding) are
    /// set to 0 so an intrinsic Delaunay triangulation gives no negative interior weight.
    /// For a triangulation that was never flipped the result equals
    /// [`crate::cotan_laplacian`] entry for entry, up to that clamp.
    pub fn laplacian(&self, tol: f64) -> CsMat<f64> {
        let n = self.num_vertices;
        let (indptr, indices) = self.pattern();
        let mut data = vec![0.0; indices.len()];
        let pos = |col: usize, row: usize| -> usize {
            let s = &indices[indptr[col]..indptr[col + 1]];
            indptr[col] + s.partition_point(|&r| r < row)
        };
        // the corner order of `cotan_laplacian`, so an unflipped mesh gives the same bits
        for (f, t) in self.faces.iter().enumerate() {
            for k in 0..3 {
                let i = t[(k + 1) % 3] as usize;
                let j = t[(k + 2) % 3] as usize;
                if i == j {
                    continue;
                }
                let w = 0.5 * self.cot[3 * f + (k + 1) % 3];
                add_edge_weight(&mut data, &pos, i, j, w);
            }
        }
        // round-off negative weights (positive off-diagonal entries) to zero
        let clamp = 0.5 * tol;
        for col in 0..n {
            let mut moved = 0.0;
            for p in indptr[col]..indptr[col + 1] {
                let r = indices[p];
                if r != col && data[p] > 0.0 && data[p] <= clamp {
                    moved += data[p];
                    data[p] = 0.0;
                }
            }
            if moved != 0.0 {
                let d = pos(col, col);
                data[d] += moved;
            }
        }
        CsMat::new_csc((n, n), indptr, indices, data)
    }
}

#[inline]
fn sub2(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

#[inline]
fn cross2(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

#[inline]
fn lift(p: [f64; 2]) -> [f64; 3] {
    [p[0], p[1], 0.0]
}

/// The cotangent Laplacian of the intrinsic Delaunay triangulation of `mesh`, with the
/// default [`IntrinsicOptions`]; see [`intrinsic_delaunay_laplacian_with`].
///
/// # Errors
/// As [`intrinsic_delaunay_laplacian_with`].
///
/// # Examples
/// ```
/// use conformap_mesh::TriMesh;
/// use conformap_operators::{cotan_laplacian, intrinsic_delaunay_laplacian};
/// // a kite whose diagonal 0–2 faces two 150° angles: not Delaunay
/// let h = 0.2679491924311227; // tan 15°
/// let mesh = TriMesh::try_new(
///     vec![[-1.0, 0.0, 0.0], [0.0, -h, 0.0], [1.0, 0.0, 0.0], [0.0, h, 0.0]],
///     vec![[0, 1, 2], [0, 2, 3]],
/// )?;
/// assert!(cotan_laplacian(&mesh).get(0, 2).copied().unwrap_or(0.0) > 0.0);
/// let (l, stats) = intrinsic_delaunay_laplacian(&mesh)?;
/// assert_eq!((stats.non_delaunay_before, stats.flips), (1, 1));
/// // the flipped diagonal 1–3 carries the weight now; 0–2 is no longer an edge
/// assert!(l.get(1, 3).copied().unwrap_or(0.0) < 0.0);
/// assert_eq!(l.get(0, 2), None);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn intrinsic_delaunay_laplacian(
    mesh: &TriMesh,
) -> Result<(CsMat<f64>, IntrinsicStats), OperatorError> {
    intrinsic_delaunay_laplacian_with(mesh, &IntrinsicOptions::DEFAULT)
}

/// The cotangent Laplacian of the intrinsic Delaunay triangulation of `mesh` (Bobenko &
/// Springborn 2007, Eq. 4 with the boundary convention of [`crate::cotan_laplacian`]):
/// same size and vertex order as [`crate::cotan_laplacian`], every interior-edge weight
/// `≥ 0`, so `L_II` of any interior/boundary split is an M-matrix and a harmonic map with a
/// convex boundary is an embedding of the intrinsic triangulation (Tutte, Floater).
/// For a Delaunay mesh (no negative interior weight) it equals [`crate::cotan_laplacian`].
///
/// # Errors
/// [`OperatorError::InvalidOption`] for a negative or non-finite tolerance;
/// [`OperatorError::FlipLimit`] if the flip budget runs out.
pub fn intrinsic_delaunay_laplacian_with(
    mesh: &TriMesh,
    options: &IntrinsicOptions,
) -> Result<(CsMat<f64>, IntrinsicStats), OperatorError> {
    if !(options.delaunay_tol >= 0.0 && options.delaunay_tol.is_finite()) {
        return Err(OperatorError::InvalidOption {
            name: "delaunay_tol",
            reason: "must be a finite number ≥ 0",
        });
    }
    let mut tri = IntrinsicTriangulation::from_mesh(mesh);
    let stats = tri.flip_to_delaunay(options)?;
    Ok((tri.laplacian(options.delaunay_tol), stats))
}
