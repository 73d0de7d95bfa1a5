//! The prepared disk problem: Laplacian, interior/boundary blocks and their factorizations,
//! built once and shared by every disk method.
//!
//! Which Laplacian: see [`LaplacianKind`]. The default solves with the mesh's own
//! cotangent weights (CEM Eq. 6, the operator `E_C` is judged with) and keeps the
//! intrinsic Delaunay Laplacian and Floater's mean value weights in reserve for
//! [`DiskProblem::guarded_extension`], which re-solves an interior that folds.

use std::time::Instant;

use conformap_mesh::{Topology, TriMesh};
use conformap_operators::{
    interior_pattern, quadratic_form, Cholesky, CholeskyOptions, IntrinsicStats, LaplacianBlocks,
    LuSolver, OperatorError, Partition,
};
use num_complex::Complex64;
use sprs::CsMat;

use crate::laplacian_choice::{
    assemble, count_flipped, note, GuardedExtension, InteriorOperator, LaplacianKind,
    ProblemOptions, Reserve,
};
use crate::DiskError;

/// Everything a disk method needs about a mesh with one boundary loop, factored once.
///
/// The boundary vertices are ordered along the boundary loop (counter-clockwise for an
/// orientation-preserving map).
#[derive(Debug)]
pub struct DiskProblem<'m> {
    mesh: &'m TriMesh,
    laplacian: CsMat<f64>,
    partition: Partition,
    blocks: LaplacianBlocks,
    interior_factor: Cholesky,
    boundary_solver: Option<LuSolver>,
    kind: LaplacianKind,
    intrinsic: Option<IntrinsicStats>,
    reserve: Reserve,
    /// Milliseconds spent assembling `L` and its blocks.
    pub assemble_ms: f64,
    /// Milliseconds spent factoring `L_II` (symbolic + numeric).
    pub factor_ms: f64,
    /// Wall-clock milliseconds of the whole setup (topology check, assembly, analysis,
    /// numeric factorization). With the cotangent Laplacian the symbolic analysis runs on
    /// the connectivity alone, on the second core, while the weights are assembled, so
    /// this is less than `assemble_ms + factor_ms` by about the shorter of the assembly
    /// and the analysis.
    pub setup_ms: f64,
}

impl<'m> DiskProblem<'m> {
    /// [`Self::with_options`] with the default [`ProblemOptions`] (the Laplacian chosen by
    /// [`LaplacianKind::Auto`]).
    ///
    /// # Errors
    /// As [`Self::with_options`].
    pub fn new(mesh: &'m TriMesh) -> Result<Self, DiskError> {
        Self::with_options(mesh, &ProblemOptions::DEFAULT)
    }

    /// Checks the topology, assembles the Laplacian the options ask for (CEM Eq. 6 on the
    /// input or on the intrinsic Delaunay triangulation), splits it into the blocks of
    /// CEM Eq. 9 and factors `L_II` with a sparse Cholesky.
    ///
    /// # Errors
    /// [`DiskError::WrongTopology`] unless the mesh is a disk; [`DiskError::NoInteriorVertex`];
    /// [`DiskError::Operator`] if `L_II` is not positive definite or the intrinsic flips
    /// fail (bad options, flip budget exhausted).
    ///
    /// # Examples
    /// ```
    /// use conformap_disk::{DiskProblem, LaplacianKind, ProblemOptions};
    /// use conformap_mesh::TriMesh;
    /// // a flat hexagonal patch (centre and two rings); one outer vertex is pulled in
    /// // towards the first ring, so the ring edge in front of it faces 60° + 146° > 180°
    /// let mut pos = vec![[0.0, 0.0, 0.0]];
    /// for r in 1..=2 {
    ///     for k in 0..6 * r {
    ///         let t = k as f64 * std::f64::consts::TAU / (6 * r) as f64;
    ///         pos.push([r as f64 * t.cos(), r as f64 * t.sin(), 0.0]);
    ///     }
    /// }
    /// pos[8] = [0.88, 0.508, 0.0];
    /// # let faces = conformap_disk::doc_support::two_ring_faces();
    /// let mesh = TriMesh::try_new(pos, faces)?;
    /// let plain = DiskProblem::with_options(
    ///     &mesh,
    ///     &ProblemOptions::DEFAULT.with_laplacian(LaplacianKind::Cotan),
    /// )?;
    /// let intrinsic = DiskProblem::with_options(
    ///     &mesh,
    ///     &ProblemOptions::DEFAULT.with_laplacian(LaplacianKind::IntrinsicDelaunay),
    /// )?;
    /// assert_eq!(plain.laplacian_kind(), LaplacianKind::Cotan);
    /// assert_eq!(intrinsic.laplacian_kind(), LaplacianKind::IntrinsicDelaunay);
    /// assert!(intrinsic.intrinsic_stats().is_some_and(|s| s.flips > 0));
    /// // the default solves with the plain Laplacian and keeps the intrinsic one in reserve
    /// let auto = DiskProblem::new(&mesh)?;
    /// assert_eq!(auto.laplacian_kind(), LaplacianKind::Cotan);
    /// assert!(auto.has_intrinsic_reserve());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn with_options(mesh: &'m TriMesh, options: &ProblemOptions) -> Result<Self, DiskError> {
        let found = mesh.topology();
        if found != Topology::Disk {
            return Err(DiskError::WrongTopology { found });
        }
        let t0 = Instant::now();
        let boundary = mesh.boundary_loops()[0].clone();
        let partition = Partition::new(mesh.num_vertices(), &boundary);
        if partition.interior.is_empty() {
            return Err(DiskError::NoInteriorVertex);
        }
        // the cotangent Laplacian's pattern is the mesh's connectivity: analyse it on one
        // core while the other computes the weights (the intrinsic Laplacian's pattern
        // comes from its flips, so it is analysed after)
        let overlap = options.laplacian != LaplacianKind::IntrinsicDelaunay;
        let factor_options = CholeskyOptions::DEFAULT
            .with_ordering(options.ordering.resolve(partition.interior.len()));
        let (assembled, analysis) = rayon::join(
            || {
                let t = Instant::now();
                assemble(mesh, &partition, options).map(|a| {
                    let blocks = LaplacianBlocks::new(&a.laplacian, &partition);
                    (a, blocks, t.elapsed().as_secs_f64() * 1e3)
                })
            },
            || {
                overlap.then(|| {
                    let pattern = interior_pattern(mesh, &partition);
                    Cholesky::analyse_with(&pattern, &factor_options)
                })
            },
        );
        let (assembled, blocks, assemble_ms) = assembled?;
        let laplacian = assembled.laplacian;
        let interior_factor = match analysis {
            Some(Ok(symbolic)) => match symbolic.factor(&blocks.ii) {
                Ok(f) => f,
                // not expected (the pattern is built from the same connectivity), but
                // then the analysis is simply redone on the real pattern
                Err(OperatorError::PatternMismatch) => {
                    Cholesky::factor_with(&blocks.ii, &factor_options)?
                }
                Err(e) => return Err(e.into()),
            },
            _ => Cholesky::factor_with(&blocks.ii, &factor_options)?,
        };
        // analysis (on the other core, overlapped) + numeric factorization
        let factor_ms = interior_factor.stats().analyse_ms + interior_factor.stats().factor_ms;
        let setup_ms = t0.elapsed().as_secs_f64() * 1e3;
        Ok(Self {
            mesh,
            laplacian,
            partition,
            blocks,
            interior_factor,
            boundary_solver: None,
            kind: assembled.kind,
            intrinsic: assembled.stats,
            reserve: assembled.reserve,
            assemble_ms,
            factor_ms,
            setup_ms,
        })
    }

    /// The mesh.
    pub fn mesh(&self) -> &'m TriMesh {
        self.mesh
    }

    /// The full Laplacian `L` the problem solves with (see [`Self::laplacian_kind`]).
    pub fn laplacian(&self) -> &CsMat<f64> {
        &self.laplacian
    }

    /// The Laplacian the problem solves with: [`LaplacianKind::Cotan`] or
    /// [`LaplacianKind::IntrinsicDelaunay`] (`Auto` resolves to `Cotan`, with the intrinsic
    /// Delaunay Laplacian in reserve on a non-Delaunay mesh).
    pub fn laplacian_kind(&self) -> LaplacianKind {
        self.kind
    }

    /// What the intrinsic Delaunay flips did: for [`LaplacianKind::IntrinsicDelaunay`]
    /// always, for `Auto` once the reserve was built (a folded interior), else `None`.
    pub fn intrinsic_stats(&self) -> Option<&IntrinsicStats> {
        self.intrinsic
            .as_ref()
            .or_else(|| self.reserve.intrinsic_stats())
    }

    /// Whether an intrinsic Delaunay Laplacian different from the one solved with stands by
    /// for [`Self::guarded_extension`] (`Auto` on a non-Delaunay mesh).
    pub fn has_intrinsic_reserve(&self) -> bool {
        self.reserve.has_intrinsic()
    }

    /// Milliseconds [`Self::guarded_extension`] spent building and factoring the operators
    /// in reserve (0 until a map folds; not in [`Self::assemble_ms`] or
    /// [`Self::factor_ms`]).
    pub fn reserve_factor_ms(&self) -> f64 {
        self.reserve.factor_ms()
    }

    /// One line for a solver report saying which Laplacian was used and why.
    pub fn laplacian_note(&self) -> String {
        note(self.kind, self.intrinsic.as_ref(), &self.reserve)
    }

    /// The interior/boundary partition (boundary in loop order).
    pub fn partition(&self) -> &Partition {
        &self.partition
    }

    /// The blocks `L_II`, `L_IB`, `L_BB`.
    pub fn blocks(&self) -> &LaplacianBlocks {
        &self.blocks
    }

    /// The Cholesky factor of `L_II`.
    pub fn interior_factor(&self) -> &Cholesky {
        &self.interior_factor
    }

    /// Number of boundary vertices.
    pub fn num_boundary(&self) -> usize {
        self.partition.boundary.len()
    }

    /// Harmonic extension: solves `L_II f_I = −L_IB f_B` (CEM Eq. 10) and returns the whole
    /// map in vertex order.
    pub fn harmonic_extension(&self, boundary: &[Complex64]) -> Vec<Complex64> {
        let interior = self.interior_solution(boundary);
        self.partition.assemble(&interior, boundary)
    }

    /// The harmonic extension of `boundary`, checked for folds. With the problem's own
    /// Laplacian first; if faces fold, the interior is re-solved with the operators in
    /// reserve, in this order, until one folds no face (the one folding the fewest is kept):
    /// 1. the intrinsic Delaunay Laplacian ([`LaplacianKind::Auto`] on a mesh with a
    ///    negative weight at an interior vertex):
    ///    no negative interior weight, so with the boundary in order on the circle the map
    ///    is an embedding of the intrinsic triangulation (Tutte, Floater); an input face
    ///    that is not in that triangulation (a flipped edge's) can still fold as a straight
    ///    triangle;
    /// 2. Floater's mean value map: positive weights on the input triangulation itself, so
    ///    with the boundary in strictly convex position (distinct points on the circle, in
    ///    order) no input face folds (Floater 2003); not conformal, a last resort.
    ///
    /// Folds that remain come from the boundary (out of order, or crowded below what f64
    /// resolves): see [`crate::unfold_disk_map`].
    ///
    /// # Errors
    /// [`DiskError::Operator`] if a reserve operator cannot be factored.
    pub fn guarded_extension(&self, boundary: &[Complex64]) -> Result<GuardedExtension, DiskError> {
        let map = self.harmonic_extension(boundary);
        let (flips, first) = count_flipped(self.mesh, &map);
        let own = match self.kind {
            LaplacianKind::IntrinsicDelaunay => InteriorOperator::IntrinsicDelaunay,
            _ => InteriorOperator::Cotan,
        };
        let mut best = GuardedExtension {
            map,
            flipped_faces: flips,
            first_flipped: first,
            flipped_faces_before: flips,
            operator: own,
        };
        if flips == 0 {
            return Ok(best);
        }
        let consider = |best: &mut GuardedExtension, interior: &[Complex64], operator| {
            let alt = self.partition.assemble(interior, boundary);
            let (n, first) = count_flipped(self.mesh, &alt);
            if n < best.flipped_faces {
                best.map = alt;
                best.flipped_faces = n;
                best.first_flipped = first;
                best.operator = operator;
            }
        };
        if let Some(interior) =
            self.reserve
                .intrinsic_solution(self.mesh, &self.partition, boundary)?
        {
            consider(&mut best, &interior, InteriorOperator::IntrinsicDelaunay);
        }
        if best.flipped_faces > 0 {
            let interior =
                self.reserve
                    .mean_value_solution(self.mesh, &self.partition, boundary)?;
            consider(&mut best, &interior, InteriorOperator::MeanValue);
        }
        Ok(best)
    }

    /// Interior values of the harmonic extension of `boundary` (interior order).
    pub fn interior_solution(&self, boundary: &[Complex64]) -> Vec<Complex64> {
        let mut rhs = self.blocks.ib_mul(boundary);
        for z in &mut rhs {
            *z = -*z;
        }
        self.interior_factor.solve_complex(&rhs)
    }

    /// Solves `L_BB x = b` (factoring `L_BB` on first use, sparse LU: `L_BB` need not be
    /// positive definite on a non-Delaunay mesh).
    ///
    /// # Errors
    /// [`DiskError::Operator`] if `L_BB` is singular.
    pub fn solve_boundary_block(&mut self, b: &[Complex64]) -> Result<Vec<Complex64>, DiskError> {
        if self.boundary_solver.is_none() {
            self.boundary_solver = Some(LuSolver::factor(&self.blocks.bb)?);
        }
        match &self.boundary_solver {
            Some(s) => Ok(s.solve_complex(b)),
            None => unreachable!("factored above"),
        }
    }

    /// Dirichlet energy `½ fᴴ L f` (CEM Eq. 5) with the problem's Laplacian: on the
    /// intrinsic Delaunay triangulation it is never above the mesh's own (Rippa's theorem,
    /// intrinsic form: Bobenko & Springborn 2007), which the metrics crate reports.
    pub fn dirichlet_energy(&self, f: &[Complex64]) -> f64 {
        quadratic_form(&self.laplacian, f)
    }

    /// Image area of CEM Eq. 8 along the boundary loop.
    pub fn image_area(&self, f: &[Complex64]) -> f64 {
        polygon_area_of(&self.partition.boundary, f)
    }

    /// Conformal energy `E_C = E_D − A` (CEM Eq. 7) with the problem's Laplacian (the
    /// energy the solvers minimize; see [`Self::dirichlet_energy`]).
    pub fn conformal_energy(&self, f: &[Complex64]) -> f64 {
        self.dirichlet_energy(f) - self.image_area(f)
    }
}

/// Signed area of the polygon through `f[loop[0]], f[loop[1]], …` (CEM Eq. 8).
pub fn polygon_area_of(lp: &[u32], f: &[Complex64]) -> f64 {
    let m = lp.len();
    let mut a = 0.0;
    for k in 0..m {
        let p = f[lp[k] as usize];
        let q = f[lp[(k + 1) % m] as usize];
        a += p.re * q.im - q.re * p.im;
    }
    0.5 * a
}
