//! The cone metric: the conformal scale factor `u` that flattens a surface everywhere but at
//! a few cone vertices, from one factorization of the cotangent Laplacian.
//!
//! With `L` the positive semi-definite cotangent Laplacian, `K` the angle defects of the
//! surface (`2π − Σ angles` inside, `π − Σ angles` on a boundary) and `K̃` the target
//! defects (the cone defects `k_c` at the cones, 0 elsewhere), the scale factor of the
//! target metric `e^{2u} g` solves the linearized Yamabe equation `L u = K̃ − K`.
//! - Closed surface: `Σ k_c = 2πχ` makes the system consistent; `u` is fixed up to a
//!   constant by pinning one vertex (`u = 0` there).
//! - Surface with boundary: `u = 0` on the boundary (the free boundary of boundary first
//!   flattening: lengths kept there), no condition on the defects.
//!
//! `u` is linear in the defects, so `u = Σ k_c g_c − u_K` with `g_c = L⁻¹ e_c` (the
//! Green's function of cone `c`) and `u_K = L⁻¹ K` on the free vertices: every question
//! about cones — which angles, which vertices — is a few solves with one factor.

use conformap_mesh::TriMesh;
use conformap_operators::{
    corner_angles, cotan_laplacian, interior_pattern, Cholesky, CholeskyOptions, LaplacianBlocks,
    OperatorError, Partition, SymbolicAnalysis,
};

use crate::error::AtlasError;

/// One factorization of a surface's Laplacian with its pinned vertices, and its curvature.
pub struct ConeMetric {
    part: Partition,
    chol: Cholesky,
    /// Angle defects per vertex.
    curvature: Vec<f64>,
    /// `u_K = L⁻¹ K` on the free vertices, 0 on the pinned ones (vertex order).
    u_k: Vec<f64>,
    closed: bool,
    faces: Vec<[u32; 3]>,
    positions: Vec<[f64; 3]>,
    /// `√(surface area)`, the length scale of cone spacing.
    length: f64,
    /// Neighbours of each vertex (compressed rows: `ring_start[v]..ring_start[v + 1]`).
    ring_start: Vec<usize>,
    ring: Vec<u32>,
}

impl ConeMetric {
    /// Factors the Laplacian of `mesh` (one component, closed or with boundary).
    ///
    /// # Errors
    /// [`AtlasError::Factorization`] when the Laplacian cannot be factored (a mesh the
    /// validation let through with degenerate weights).
    pub fn new(mesh: &TriMesh) -> Result<Self, AtlasError> {
        let n = mesh.num_vertices();
        let loops = mesh.boundary_loops();
        if loops.is_empty() {
            // the vertex pinned is the one of highest index: any vertex would do (u is
            // defined up to a constant), a fixed one keeps results deterministic
            Self::build(mesh, &[(n - 1) as u32], true)
        } else {
            let pinned: Vec<u32> = loops.iter().flatten().copied().collect();
            Self::build(mesh, &pinned, false)
        }
    }

    /// The cone metric with `u = 0` on the `pinned` vertices (besides any boundary): the
    /// handle cut of a surface of genus ≥ 1, which then takes up whatever curvature the
    /// cones leave, as the boundary of a disk does.
    ///
    /// # Errors
    /// As [`ConeMetric::new`].
    pub fn with_pinned(mesh: &TriMesh, pinned: &[u32]) -> Result<Self, AtlasError> {
        Self::build(mesh, &with_boundary(mesh, pinned), false)
    }

    /// [`ConeMetric::with_pinned`] with the pinned vertices computed by `pinned` on one
    /// core while the other assembles what does not depend on them (the Laplacian's
    /// weights, the curvature, the rings, the area): a handle cut's tree–cotree search
    /// beside them. Returns `pinned`'s other result too. The same metric as
    /// `with_pinned` on the same vertices.
    ///
    /// # Errors
    /// As [`ConeMetric::new`], or `pinned`'s own error.
    pub(crate) fn with_pinned_from<R: Send>(
        mesh: &TriMesh,
        pinned: impl FnOnce() -> Result<(Vec<u32>, R), AtlasError> + Send,
    ) -> Result<(Self, R), AtlasError> {
        let (found, (laplacian, (curvature, rings, area))) = rayon::join(pinned, || {
            rayon::join(
                || cotan_laplacian(mesh),
                || {
                    (
                        angle_defects(mesh),
                        one_rings(mesh),
                        conformap_operators::surface_area(mesh),
                    )
                },
            )
        });
        let (pinned, other) = found?;
        let part = Partition::new(mesh.num_vertices(), &with_boundary(mesh, &pinned));
        let options = CholeskyOptions::DEFAULT;
        let (blocks, analysis) = rayon::join(
            || LaplacianBlocks::new(&laplacian, &part),
            || Cholesky::analyse_with(&interior_pattern(mesh, &part), &options),
        );
        let metric = Self::assemble(mesh, part, blocks, analysis, curvature, rings, area, false)?;
        Ok((metric, other))
    }

    fn build(mesh: &TriMesh, pinned: &[u32], closed: bool) -> Result<Self, AtlasError> {
        let n = mesh.num_vertices();
        let part = Partition::new(n, pinned);
        // the Laplacian's weights, then the curvature, the rings and the area (one core)
        // beside the symbolic analysis of the Laplacian's pattern, which is the mesh's
        // connectivity (the longer of the two: spot 2.9 against 1.8 ms), then the numeric
        // factorization
        let options = CholeskyOptions::DEFAULT;
        let ((blocks, (curvature, (ring_start, ring), area)), analysis) = rayon::join(
            || {
                let blocks = LaplacianBlocks::new(&cotan_laplacian(mesh), &part);
                let rest = (
                    angle_defects(mesh),
                    one_rings(mesh),
                    conformap_operators::surface_area(mesh),
                );
                (blocks, rest)
            },
            || Cholesky::analyse_with(&interior_pattern(mesh, &part), &options),
        );
        Self::assemble(
            mesh,
            part,
            blocks,
            analysis,
            curvature,
            (ring_start, ring),
            area,
            closed,
        )
    }

    /// The metric from its parts: the Laplacian's blocks factored (on `analysis` of their
    /// pattern), `u_K` solved.
    #[allow(clippy::too_many_arguments)] // the parts computed side by side
    fn assemble(
        mesh: &TriMesh,
        part: Partition,
        blocks: LaplacianBlocks,
        analysis: Result<SymbolicAnalysis, OperatorError>,
        curvature: Vec<f64>,
        (ring_start, ring): (Vec<usize>, Vec<u32>),
        area: f64,
        closed: bool,
    ) -> Result<Self, AtlasError> {
        let options = CholeskyOptions::DEFAULT;
        let chol = match analysis.and_then(|a| a.factor(&blocks.ii)) {
            // not expected (the pattern is the same connectivity's), but then the
            // analysis is redone on the matrix itself
            Err(OperatorError::PatternMismatch) => Cholesky::factor_with(&blocks.ii, &options),
            other => other,
        };
        let chol = chol.map_err(|e| AtlasError::Factorization { why: e.to_string() })?;
        let mut metric = Self {
            part,
            chol,
            curvature,
            u_k: Vec::new(),
            closed,
            faces: mesh.faces().to_vec(),
            positions: mesh.positions().to_vec(),
            length: area.sqrt(),
            ring_start,
            ring,
        };
        metric.u_k = metric.solve_full(&metric.curvature.clone());
        Ok(metric)
    }

    /// Whether the surface is closed (cone defects must then sum to `2πχ`).
    pub fn closed(&self) -> bool {
        self.closed
    }

    /// Angle defects of the surface, per vertex (`2π − Σ angles` inside, `π − Σ angles` on
    /// the boundary: its geodesic curvature).
    pub fn curvature(&self) -> &[f64] {
        &self.curvature
    }

    /// Total defect the cones of a closed surface must carry: `Σ K = 2πχ` (0 when the
    /// surface has a boundary, which takes up whatever the cones leave).
    pub fn total_defect(&self) -> f64 {
        if self.closed {
            self.curvature.iter().sum()
        } else {
            0.0
        }
    }

    /// Whether vertex `v` is pinned (`u = 0` there: the boundary, or the one pinned vertex
    /// of a closed surface).
    pub fn pinned(&self, v: u32) -> bool {
        !self.part.is_interior[v as usize]
    }

    /// `L⁻¹ b` on the free vertices, 0 on the pinned ones, in vertex order.
    fn solve_full(&self, b: &[f64]) -> Vec<f64> {
        let mut x = self.part.interior_values(b);
        self.chol.solve_in_place(&mut x, 1);
        let zeros = vec![0.0; self.part.boundary.len()];
        self.part.assemble(&x, &zeros)
    }

    /// The Green's function of vertex `v`: `L⁻¹ e_v` (zero for a pinned vertex).
    pub fn green(&self, v: u32) -> Vec<f64> {
        let mut e = vec![0.0; self.curvature.len()];
        e[v as usize] = 1.0;
        self.solve_full(&e)
    }

    /// The Green's functions of `vertices` (as [`Self::green`]) from one solve with as
    /// many right-hand sides: the factor is read once for all of them.
    pub fn greens(&self, vertices: &[u32]) -> Vec<Vec<f64>> {
        let ni = self.part.interior.len();
        if ni == 0 {
            return vec![vec![0.0; self.curvature.len()]; vertices.len()];
        }
        // zeros written, not a fresh zero-filled allocation: the solve reads the unset
        // pages before it writes them, and a first read maps the shared zero page whose
        // copy-on-write at the write flushes every core's TLB (spot: 12 % of the cone
        // search was page faults)
        let mut rhs = written_zeros(ni * vertices.len());
        for (j, &v) in vertices.iter().enumerate() {
            if self.part.is_interior[v as usize] {
                rhs[j * ni + self.part.local[v as usize] as usize] = 1.0;
            }
        }
        self.chol.solve_in_place(&mut rhs, vertices.len());
        let zeros = vec![0.0; self.part.boundary.len()];
        rhs.chunks_exact(ni)
            .map(|x| self.part.assemble(x, &zeros))
            .collect()
    }

    /// The scale factor `u` with defect `k` at each cone `(vertex, k)` and 0 elsewhere
    /// (`Σ k = 2πχ` on a closed surface; see the module docs).
    pub fn scale_factor(&self, cones: &[(u32, f64)]) -> Vec<f64> {
        let mut b = vec![0.0; self.curvature.len()];
        for &(v, k) in cones {
            b[v as usize] += k;
        }
        let mut u = self.solve_full(&b);
        for (x, y) in u.iter_mut().zip(&self.u_k) {
            *x -= y;
        }
        u
    }

    /// Whether vertices `a` and `b` lie within `fraction · √(surface area)` of each other
    /// (straight-line distance).
    pub fn near(&self, a: u32, b: u32, fraction: f64) -> bool {
        let (p, q) = (self.positions[a as usize], self.positions[b as usize]);
        let d2 = (0..3).map(|k| (p[k] - q[k]) * (p[k] - q[k])).sum::<f64>();
        d2 < (fraction * self.length).powi(2)
    }

    /// The vertices joined to `v` by an edge.
    pub fn neighbours(&self, v: u32) -> &[u32] {
        &self.ring[self.ring_start[v as usize]..self.ring_start[v as usize + 1]]
    }

    /// `u_K = L⁻¹ K` (the part of every scale factor the cones do not set).
    pub fn curvature_potential(&self) -> &[f64] {
        &self.u_k
    }

    /// Per face, the mean of `2u` over its corners: the log area scale of the face in the
    /// cone metric (up to a constant).
    pub fn face_log_scale(&self, u: &[f64]) -> Vec<f64> {
        self.faces
            .iter()
            .map(|f| 2.0 * (u[f[0] as usize] + u[f[1] as usize] + u[f[2] as usize]) / 3.0)
            .collect()
    }

    /// `⟨r, face_log_scale(green(w))⟩` for every vertex `w` at once, from one solve:
    /// the face log scale is linear in `u` and `L⁻¹` is symmetric, so the product is the
    /// Green's solve of the corners' share of `r` (0 at the pinned vertices).
    pub fn face_pullback(&self, r: &[f64]) -> Vec<f64> {
        // added to: zeros written first (see `greens`)
        let mut b = written_zeros(self.curvature.len());
        for (f, &x) in self.faces.iter().zip(r) {
            for &v in f {
                b[v as usize] += 2.0 * x / 3.0;
            }
        }
        self.solve_full(&b)
    }

    /// The area spread of the cone metric: the standard deviation over faces of
    /// [`Self::face_log_scale`], which the flattened layout reproduces (its
    /// `sd log(uv area share / 3D area share)`).
    pub fn area_spread(&self, u: &[f64]) -> f64 {
        sd(&self.face_log_scale(u))
    }
}

/// `n` zeros written one by one (see [`ConeMetric::greens`]).
pub(crate) fn written_zeros(n: usize) -> Vec<f64> {
    let mut v = Vec::with_capacity(n);
    v.resize(n, 0.0);
    v
}

/// The boundary vertices of `mesh` and `pinned`, sorted, each once.
fn with_boundary(mesh: &TriMesh, pinned: &[u32]) -> Vec<u32> {
    let mut all: Vec<u32> = mesh.boundary_loops().iter().flatten().copied().collect();
    all.extend_from_slice(pinned);
    all.sort_unstable();
    all.dedup();
    all
}

/// The one-rings of `mesh` as compressed rows (sorted, no repeats): its vertex adjacency
/// (each edge once, so no repeats on a valid mesh).
fn one_rings(mesh: &TriMesh) -> (Vec<usize>, Vec<u32>) {
    let adjacency = mesh.vertex_adjacency();
    (adjacency.offsets, adjacency.neighbors)
}

/// Standard deviation (population) of `x`.
pub(crate) fn sd(x: &[f64]) -> f64 {
    let n = x.len().max(1) as f64;
    let mean = x.iter().sum::<f64>() / n;
    (x.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n).sqrt()
}

/// Angle defects: `2π − Σ angles` at interior vertices, `π − Σ angles` on the boundary.
fn angle_defects(mesh: &TriMesh) -> Vec<f64> {
    let n = mesh.num_vertices();
    let mut sum = vec![0.0; n];
    for (f, a) in mesh.faces().iter().zip(corner_angles(mesh)) {
        for k in 0..3 {
            sum[f[k] as usize] += a[k];
        }
    }
    let mut on_boundary = vec![false; n];
    for &v in mesh.boundary_loops().iter().flatten() {
        on_boundary[v as usize] = true;
    }
    (0..n)
        .map(|v| {
            let full = if on_boundary[v] {
                std::f64::consts::PI
            } else {
                std::f64::consts::TAU
            };
            full - sum[v]
        })
        .collect()
}
