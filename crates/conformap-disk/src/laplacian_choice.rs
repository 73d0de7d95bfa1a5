//! Which Laplacian a disk problem solves with, and the operators kept in reserve for a
//! folded interior.
//!
//! Why a choice at all. The mesh's own cotangent weights (CEM Eq. 6) are what the design's
//! `E_C` is measured with, and the maps minimizing it are the papers' maps. On a
//! non-Delaunay mesh (camelhead 14%, human_face 5%, igea_open 3% of interior edges with
//! negative weights) that Laplacian is no M-matrix, and a harmonic extension can fold even
//! with the boundary in order on the circle. The cotangent Laplacian of the *intrinsic
//! Delaunay triangulation* of the same surface (same vertices, same piecewise-flat metric;
//! [`conformap_operators::intrinsic_delaunay_laplacian`]) has no negative interior weight,
//! so with the boundary in order on the circle (a strictly convex polygon) the harmonic
//! extension is an embedding of *that* triangulation (Tutte 1963, Floater 2003); an input
//! face whose edge was flipped can still fold as a straight triangle. Floater's mean value
//! weights are positive on the input triangulation itself: one-to-one there, not conformal.
//!
//! Measured on the class-a meshes (`E_C` judged with the mesh's weights): solving with the
//! intrinsic Laplacian throughout costs +0.02% (spothead) to +2.0% (hand, 13 flips among
//! 158k edges; +4.9% with CEM) of `E_C` over the plain map, and no plain map with the
//! boundary in order folded, not even on camelhead with arbitrary ordered boundaries. On
//! random jittered grids about 1 in 700 plain harmonic maps folds; the intrinsic Laplacian
//! fixes about a quarter of those, the mean value map the rest. Hence the default,
//! [`LaplacianKind::Auto`]: solve with the plain Laplacian, and re-solve only an interior
//! that folds ([`crate::DiskProblem::guarded_extension`]).

use std::sync::OnceLock;
use std::time::Instant;

use conformap_mesh::TriMesh;
use conformap_operators::{
    cotan_laplacian, intrinsic_delaunay_laplacian_with, mean_value_matrix, Cholesky,
    IntrinsicOptions, IntrinsicStats, LaplacianBlocks, LuSolver, OperatorError, Ordering,
    Partition,
};
use num_complex::Complex64;
use sprs::CsMat;

use crate::DiskError;

/// Which cotangent Laplacian a [`crate::DiskProblem`] assembles and solves with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum LaplacianKind {
    /// The cotangent weights of the input triangulation (CEM Eq. 6): the papers' operator
    /// and the one `E_C` is judged with. May fold a harmonic map on a non-Delaunay mesh.
    Cotan,
    /// The cotangent Laplacian of the intrinsic Delaunay triangulation of the mesh's
    /// surface: no negative interior weight, so `L_II` is an M-matrix.
    IntrinsicDelaunay,
    /// Solve with [`Self::Cotan`]; on a mesh with a negative weight at an interior vertex
    /// keep the intrinsic Delaunay Laplacian in reserve (built and factored only when
    /// [`crate::DiskProblem::guarded_extension`] meets a folded interior). The default.
    #[default]
    Auto,
}

impl LaplacianKind {
    /// The name used in reports: `cotan`, `intrinsic-delaunay` or `auto`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Cotan => "cotan",
            Self::IntrinsicDelaunay => "intrinsic-delaunay",
            Self::Auto => "auto",
        }
    }
}

/// Options of [`crate::DiskProblem::with_options`].
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct ProblemOptions {
    /// The Laplacian. Default: [`LaplacianKind::Auto`].
    pub laplacian: LaplacianKind,
    /// Options of the intrinsic Delaunay flips. Default: [`IntrinsicOptions::DEFAULT`].
    pub intrinsic: IntrinsicOptions,
    /// The fill-reducing ordering of the factorization of `L_II` (resolved for the
    /// number of interior vertices, see [`Ordering::resolve`]; the map is the same to
    /// rounding, only its cost changes). Default: [`Ordering::Auto`].
    pub ordering: Ordering,
}

impl ProblemOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        laplacian: LaplacianKind::Auto,
        intrinsic: IntrinsicOptions::DEFAULT,
        ordering: Ordering::Auto,
    };

    /// Sets [`Self::ordering`].
    #[must_use]
    ///
    /// ```
    /// use conformap_disk::ProblemOptions;
    /// use conformap_operators::Ordering;
    /// let o = ProblemOptions::DEFAULT.with_ordering("nd".parse()?);
    /// assert_eq!(o.ordering, Ordering::NestedDissection);
    /// # Ok::<(), conformap_operators::OperatorError>(())
    /// ```
    pub fn with_ordering(mut self, ordering: Ordering) -> Self {
        self.ordering = ordering;
        self
    }

    /// Sets [`Self::laplacian`].
    #[must_use]
    pub fn with_laplacian(mut self, laplacian: LaplacianKind) -> Self {
        self.laplacian = laplacian;
        self
    }

    /// Sets [`Self::intrinsic`].
    #[must_use]
    pub fn with_intrinsic(mut self, intrinsic: IntrinsicOptions) -> Self {
        self.intrinsic = intrinsic;
        self
    }
}

/// The operator whose solution an interior map is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub enum InteriorOperator {
    /// Harmonic for the mesh's cotangent Laplacian.
    Cotan,
    /// Harmonic for the intrinsic Delaunay cotangent Laplacian.
    IntrinsicDelaunay,
    /// Floater's mean value map ([`conformap_operators::mean_value_matrix`]): every
    /// interior vertex the mean of its neighbours with positive weights, one-to-one on the
    /// input triangulation for a boundary in convex position. Not conformal.
    MeanValue,
}

impl InteriorOperator {
    /// The name used in reports: `cotan`, `intrinsic-delaunay`, `mean-value`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Cotan => "cotan",
            Self::IntrinsicDelaunay => "intrinsic-delaunay",
            Self::MeanValue => "mean-value",
        }
    }
}

/// A harmonic extension checked for folds (see [`crate::DiskProblem::guarded_extension`]).
#[derive(Debug, Clone, PartialEq)]
pub struct GuardedExtension {
    /// The map, one value per vertex.
    pub map: Vec<Complex64>,
    /// Faces of `map` with non-positive signed image area.
    pub flipped_faces: usize,
    /// The first of them (0-based), if any.
    pub first_flipped: Option<usize>,
    /// Faces the extension with the problem's own Laplacian folded.
    pub flipped_faces_before: usize,
    /// The operator `map`'s interior solves.
    pub operator: InteriorOperator,
}

impl GuardedExtension {
    /// A line for a solver report when the problem's own Laplacian folded, else `None`.
    pub fn note(&self) -> Option<String> {
        (self.flipped_faces_before > 0).then(|| {
            format!(
                "the harmonic interior folded {} faces with the problem's Laplacian; the \
                 interior was re-solved with the {} operator: {} folded faces",
                self.flipped_faces_before,
                self.operator.name(),
                self.flipped_faces
            )
        })
    }
}

/// Faces whose image has non-positive signed area: their number and the first one (the one
/// fold count of the crate: CCEM's final check, the guarded extension, unfolding and the
/// Koebe polish all use it).
pub(crate) fn count_flipped(mesh: &TriMesh, f: &[Complex64]) -> (usize, Option<usize>) {
    let mut count = 0;
    let mut first = None;
    for (k, t) in mesh.faces().iter().enumerate() {
        let (a, b, c) = (f[t[0] as usize], f[t[1] as usize], f[t[2] as usize]);
        if !(((b - a).conj() * (c - a)).im > 0.0) {
            count += 1;
            first.get_or_insert(k);
        }
    }
    (count, first)
}

/// [`count_flipped`]'s number over the faces `keep` accepts.
pub(crate) fn count_flipped_where(
    mesh: &TriMesh,
    f: &[Complex64],
    keep: impl Fn(usize) -> bool,
) -> usize {
    let mut count = 0;
    for (k, t) in mesh.faces().iter().enumerate() {
        if !keep(k) {
            continue;
        }
        let (a, b, c) = (f[t[0] as usize], f[t[1] as usize], f[t[2] as usize]);
        if !(((b - a).conj() * (c - a)).im > 0.0) {
            count += 1;
        }
    }
    count
}

/// The intrinsic Delaunay operator, built and factored on first use.
type IntrinsicBuilt = (IntrinsicStats, LaplacianBlocks, Cholesky);

/// The operators kept in reserve for a folded interior, built and factored on first use
/// (interior mutability: the problem is shared read-only, also across threads), so the
/// default costs nothing until a map folds.
#[derive(Debug, Default)]
pub(crate) struct Reserve {
    /// Whether the problem was built with [`LaplacianKind::Auto`].
    auto: bool,
    /// `Auto` on a mesh with a negative weight at an interior vertex: the flip options.
    intrinsic_options: Option<IntrinsicOptions>,
    /// Edges at an interior vertex with a negative cotangent weight (`Auto` only).
    negative_weights: usize,
    intrinsic: OnceLock<Result<IntrinsicBuilt, OperatorError>>,
    mean_value: OnceLock<Result<(LaplacianBlocks, LuSolver), OperatorError>>,
    /// Milliseconds spent building and factoring the reserves used so far.
    factor_ms: std::sync::Mutex<f64>,
}

impl Reserve {
    /// Whether an intrinsic Delaunay Laplacian stands by.
    pub(crate) fn has_intrinsic(&self) -> bool {
        self.intrinsic_options.is_some()
    }

    /// The flip statistics, once the intrinsic operator was built.
    pub(crate) fn intrinsic_stats(&self) -> Option<&IntrinsicStats> {
        self.intrinsic
            .get()
            .and_then(|r| r.as_ref().ok())
            .map(|b| &b.0)
    }

    /// Milliseconds spent building and factoring the reserve operators so far.
    pub(crate) fn factor_ms(&self) -> f64 {
        self.factor_ms.lock().map_or(0.0, |g| *g)
    }

    fn charge(&self, t: Instant) {
        if let Ok(mut g) = self.factor_ms.lock() {
            *g += t.elapsed().as_secs_f64() * 1e3;
        }
    }

    /// Interior values of the harmonic extension of `boundary` with the intrinsic
    /// Delaunay Laplacian, `None` if there is none in reserve.
    pub(crate) fn intrinsic_solution(
        &self,
        mesh: &TriMesh,
        partition: &Partition,
        boundary: &[Complex64],
    ) -> Result<Option<Vec<Complex64>>, DiskError> {
        let Some(options) = &self.intrinsic_options else {
            return Ok(None);
        };
        let built = self.intrinsic.get_or_init(|| {
            let t = Instant::now();
            let r = intrinsic_delaunay_laplacian_with(mesh, options).and_then(|(l, stats)| {
                let blocks = LaplacianBlocks::new(&l, partition);
                Cholesky::factor(&blocks.ii).map(|c| (stats, blocks, c))
            });
            self.charge(t);
            r
        });
        let (_, blocks, chol) = built.as_ref().map_err(|e| DiskError::Operator(e.clone()))?;
        Ok(Some(chol.solve_complex(&negated(blocks.ib_mul(boundary)))))
    }

    /// Interior values of the mean value map with boundary values `boundary`.
    pub(crate) fn mean_value_solution(
        &self,
        mesh: &TriMesh,
        partition: &Partition,
        boundary: &[Complex64],
    ) -> Result<Vec<Complex64>, DiskError> {
        let built = self.mean_value.get_or_init(|| {
            let t = Instant::now();
            let blocks = LaplacianBlocks::new(&mean_value_matrix(mesh), partition);
            let r = LuSolver::factor(&blocks.ii).map(|lu| (blocks, lu));
            self.charge(t);
            r
        });
        let (blocks, lu) = built.as_ref().map_err(|e| DiskError::Operator(e.clone()))?;
        Ok(lu.solve_complex(&negated(blocks.ib_mul(boundary))))
    }
}

fn negated(mut v: Vec<Complex64>) -> Vec<Complex64> {
    for z in &mut v {
        *z = -*z;
    }
    v
}

/// Edges with a negative weight (positive off-diagonal entry) at an interior vertex.
fn negative_interior_weights(l: &CsMat<f64>, partition: &Partition) -> usize {
    let mut count = 0;
    for (j, col) in l.outer_iterator().enumerate() {
        for (i, &v) in col.iter() {
            let interior = partition.is_interior[i] || partition.is_interior[j];
            if i < j && v > 0.0 && interior {
                count += 1;
            }
        }
    }
    count
}

/// The assembled operator of a problem.
pub(crate) struct Assembled {
    pub laplacian: CsMat<f64>,
    pub kind: LaplacianKind,
    pub stats: Option<IntrinsicStats>,
    pub reserve: Reserve,
}

/// Assembles the Laplacian `options` ask for (see [`LaplacianKind`]).
pub(crate) fn assemble(
    mesh: &TriMesh,
    partition: &Partition,
    options: &ProblemOptions,
) -> Result<Assembled, DiskError> {
    Ok(match options.laplacian {
        LaplacianKind::IntrinsicDelaunay => {
            let (l, stats) = intrinsic_delaunay_laplacian_with(mesh, &options.intrinsic)?;
            Assembled {
                laplacian: l,
                kind: LaplacianKind::IntrinsicDelaunay,
                stats: Some(stats),
                reserve: Reserve::default(),
            }
        }
        kind => {
            let laplacian = cotan_laplacian(mesh);
            let mut reserve = Reserve::default();
            if kind == LaplacianKind::Auto {
                reserve.auto = true;
                // on a Delaunay mesh the two operators are one: nothing in reserve
                reserve.negative_weights = negative_interior_weights(&laplacian, partition);
                reserve.intrinsic_options =
                    (reserve.negative_weights > 0).then_some(options.intrinsic);
            }
            Assembled {
                laplacian,
                kind: LaplacianKind::Cotan,
                stats: None,
                reserve,
            }
        }
    })
}

/// One line for a report: which Laplacian a problem solves with, and why.
pub(crate) fn note(
    kind: LaplacianKind,
    stats: Option<&IntrinsicStats>,
    reserve: &Reserve,
) -> String {
    match (kind, stats) {
        (LaplacianKind::IntrinsicDelaunay, Some(s)) => format!(
            "Laplacian: intrinsic Delaunay ({} of {} interior edges had negative cotangent \
             weights; {} intrinsic flips in {:.0} ms)",
            s.non_delaunay_before, s.interior_edges, s.flips, s.flip_ms
        ),
        _ if reserve.has_intrinsic() => format!(
            "Laplacian: cotangent of the input ({} edges at interior vertices have negative \
             weights; the intrinsic Delaunay Laplacian stands by for a folded interior)",
            reserve.negative_weights
        ),
        _ if reserve.auto => "Laplacian: cotangent of the input (no negative weight at an \
                              interior vertex: the intrinsic Delaunay Laplacian is the same)"
            .into(),
        _ => "Laplacian: cotangent of the input triangulation (as asked)".into(),
    }
}
