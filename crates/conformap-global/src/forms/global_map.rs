//! The result of the global conformal parameterization of a surface of genus ≥ 1 (Jin et
//! al. 2004, §3.1): homology, cohomology, harmonic and holomorphic bases, a chosen form
//! integrated over the fundamental domain, its zeros, conformal factor and quality (the
//! computation is `pipeline.rs`).

use conformap_mesh::{CutMesh, EdgeIndex, TriMesh};
use conformap_operators::planar::triangle_signed_area;
use num_complex::Complex64;
use serde::{Deserialize, Serialize};

use crate::forms::cohomology::Cochain;
use crate::forms::conjugate::ConjugateMethod;
use crate::forms::optimal::ObjectiveReport;
use crate::forms::periods::{holomorphic_basis, ComplexCochain};
use crate::forms::quality::LayoutMetrics;
use crate::forms::zeros::{Zero, ZeroReport};

/// Wall-clock milliseconds by step of [`global_map`](crate::global_map).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct GlobalTimings {
    /// Double covering (surfaces with boundary only).
    pub double_cover: f64,
    /// Tree–cotree, cut graph, cut mesh, cohomology basis (concurrent with `assemble` and
    /// `factor`, on the other core; the total is not their sum).
    pub topology: f64,
    /// Assembling the cotangent Laplacian and its reduced block.
    pub assemble: f64,
    /// Symbolic analysis and numeric factorization of the reduced Laplacian (the
    /// yardstick: one factorization; on a double covering the two half-size ones, see
    /// `harmonic.rs`).
    pub factor: f64,
    /// The blocked solve of the harmonic projection.
    pub solve: f64,
    /// Wedge and Gram matrices, conjugation, holomorphic basis, periods.
    pub conjugate: f64,
    /// The objective: per-face area forms and the search or eigenproblem.
    pub objective: f64,
    /// Combining and normalizing the form, integrating it over the fundamental domain (and,
    /// on the other core meanwhile, the form's per-vertex stretch and conformal factor).
    pub layout: f64,
    /// Windings and zeros.
    pub zeros: f64,
    /// Quality metrics.
    pub metrics: f64,
    /// Total.
    pub total: f64,
}

/// A global conformal parameterization and everything measured on the way.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct GlobalMap {
    /// Genus of the input.
    pub genus: usize,
    /// Boundary loops of the input.
    pub boundaries: usize,
    /// Whether the forms live on the double covering (input with boundary).
    pub double_covered: bool,
    /// Genus of the closed surface the forms live on (`2g + b − 1` for a double covering).
    pub surface_genus: usize,
    /// The closed surface the forms live on: the input, or its double covering (whose
    /// first [`Self::input_vertices`] vertices and [`Self::input_faces`] faces are the input's
    /// when no boundary chord had to be split).
    pub surface: TriMesh,
    /// Vertices of the surface belonging to the input (after chord splitting).
    pub input_vertices: usize,
    /// Faces of the surface belonging to the input (after chord splitting).
    pub input_faces: usize,
    /// Boundary chords split by the double covering (0: the input's numbering is kept).
    pub split_edges: usize,
    /// Edge numbering of [`Self::surface`] used by the forms.
    pub edges: EdgeIndex,
    /// Lengths of the `2g` homology generators, shortest first.
    pub generator_lengths: Vec<f64>,
    /// The fundamental domain: the surface cut open into a disk.
    pub cut: CutMesh,
    /// Periods `P_jk = ∮_{γ_j} φ_k` (row-major `2g × 2g`: generator `j`, form `k`).
    pub period_matrix: Vec<Complex64>,
    /// `W_kj = ∫ ω_k ∧ ω_j` of the harmonic basis (intersection numbers up to rounding).
    pub wedge_matrix: Vec<f64>,
    /// The conjugate used.
    pub conjugate: ConjugateMethod,
    /// `‖Λ² + I‖_F / √(2g)` of the plain Gu–Yau solve.
    pub complex_structure_defect: f64,
    /// `‖Λ_J − Λ‖_F / ‖Λ‖_F`.
    pub projection_change: f64,
    /// Riemann's bilinear relations with the plain Gu–Yau conjugate (discretization error,
    /// `O(h²)`).
    pub bilinear_residual_gu_yau: f64,
    /// The same for the conjugate used (rounding level for the exact complex structure).
    pub bilinear_residual: f64,
    /// Genus-1 surfaces: the conformal modulus from the conjugate used, reduced to the
    /// fundamental domain.
    pub tau: Option<Complex64>,
    /// Genus 1: τ from each of the two basis forms with the plain Gu–Yau conjugate.
    pub tau_gu_yau: Vec<Complex64>,
    /// Largest relative codifferential left by the harmonic projection.
    pub harmonic_residual: f64,
    /// Largest `|dω|` on the root face of the cohomology peeling.
    pub closedness_residual: f64,
    /// The basis form named by [`GlobalMapOptions::form`](crate::GlobalMapOptions::form), else the basis form of lowest
    /// uniformity energy (the laid-out form is [`ObjectiveReport::coefficients`]).
    pub form_index: usize,
    /// Uniformity energy of every basis form (over the input's faces).
    pub form_uniformity: Vec<f64>,
    /// The real harmonic forms `ω_k` per edge of [`Self::surface`]: the real parts of the
    /// holomorphic basis ([`Self::basis_forms`]).
    pub harmonic_forms: Vec<Cochain>,
    /// The conjugation `Λ` (row-major `2g × 2g`, of [`GlobalMapOptions::conjugate`](crate::GlobalMapOptions::conjugate)): the
    /// conjugate forms are `*ω_k = Σ_j Λ_jk ω_j`.
    pub conjugation: Vec<f64>,
    /// The laid-out form per edge of [`Self::surface`], scaled so that the layout's area
    /// equals the surface's (Jin et al. Eq. 6).
    pub form: ComplexCochain,
    /// UV per corner of the surface (`3 f + k`); the input's corners come first.
    pub corner_uv: Vec<Complex64>,
    /// Largest seam defect relative to the layout diagonal (pure translations: rounding
    /// level).
    pub seam_residual: f64,
    /// Seam edges of the cut.
    pub seam_edges: usize,
    /// Diagonal of the layout's bounding box.
    pub layout_diagonal: f64,
    /// Zeros and folds, over the whole closed surface.
    pub zeros: ZeroReport,
    /// Conformal factor (Eq. 12) per vertex of the surface (`+∞` where the form vanishes on
    /// an edge).
    pub conformal_factor: Vec<f64>,
    /// Quality of the layout over the input's faces.
    pub metrics: LayoutMetrics,
    /// The objective that chose the form and what it measured.
    pub objective: ObjectiveReport,
    /// Dimension of the factored Laplacian block (a double covering: the sum of its two
    /// half-size blocks).
    pub factor_dim: usize,
    /// Non-zeros of the Cholesky factor.
    pub factor_nnz: usize,
    /// Timings.
    pub timings_ms: GlobalTimings,
}

impl GlobalMap {
    /// The holomorphic basis `φ_k = ω_k + i *ω_k` per edge of [`Self::surface`] (the
    /// objective's coefficients combine these), built from [`Self::harmonic_forms`] and
    /// [`Self::conjugation`] (`edges × 2g` complex numbers: kept only on demand).
    pub fn basis_forms(&self) -> Vec<ComplexCochain> {
        holomorphic_basis(&self.harmonic_forms, &self.conjugation)
    }

    /// UV of every corner of the input's faces (`3 f + k`).
    pub fn input_corner_uv(&self) -> &[Complex64] {
        &self.corner_uv[..3 * self.input_faces]
    }

    /// Folded faces of the input's layout (non-positive signed area): `(at zeros, outside)`,
    /// a face counting as at a zero when one of its vertices lies in a zero cluster.
    pub fn input_folds(&self) -> (usize, usize) {
        let uv = self.input_corner_uv();
        let near = &self.zeros.in_zero_cluster;
        let (mut at, mut outside) = (0, 0);
        for (f, t) in self.surface.faces()[..self.input_faces].iter().enumerate() {
            let area = triangle_signed_area(uv[3 * f], uv[3 * f + 1], uv[3 * f + 2]);
            if area > 0.0 {
                continue;
            }
            if t.iter().any(|&v| near[v as usize]) {
                at += 1;
            } else {
                outside += 1;
            }
        }
        (at, outside)
    }

    /// The zeros of the form at the input's vertices (all of them for a closed input; for
    /// a double covering, those of the first copy and its boundary).
    pub fn input_zeros(&self) -> impl Iterator<Item = &Zero> {
        self.zeros
            .zeros
            .iter()
            .filter(|z| z.vertex < self.input_vertices)
    }

    /// `(min, max)` of the finite conformal factors of the input's vertices.
    pub fn conformal_factor_range(&self) -> (f64, f64) {
        self.conformal_factor[..self.input_vertices]
            .iter()
            .filter(|x| x.is_finite())
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), &x| {
                (lo.min(x), hi.max(x))
            })
    }
}
