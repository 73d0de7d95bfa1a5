//! The global conformal parameterization of a surface of genus ≥ 1 (Jin et al. 2004,
//! §3.1): homology, cohomology, harmonic and holomorphic bases, a chosen form integrated
//! over the fundamental domain, its zeros, conformal factor and quality.

use std::time::Instant;

use conformap_mesh::{cut_graph, cut_mesh, homology_basis, CutMesh, EdgeIndex, Topology, TriMesh};
use num_complex::Complex64;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::double_cover::double_cover_surface;
use crate::forms::cohomology::{cohomology_basis, edge_weights, wedge_matrix, Cochain};
use crate::forms::conjugate::{conjugation, ConjugateMethod};
use crate::forms::harmonic::{ms, storage, HarmonicFactor};
use crate::forms::layout::integrate;
use crate::forms::optimal::{choose, finish_zeros, ObjectiveReport, Surface};
use crate::forms::options::GlobalMapOptions;
use crate::forms::periods::{
    bilinear_residual, harmonic_periods, holomorphic_basis, period_matrix, reduce_modulus,
    ComplexCochain,
};
use crate::forms::quality::{layout_metrics, LayoutMetrics};
use crate::forms::zeros::{conformal_factor, find_zeros, vertex_stretch, Zero, ZeroReport};
use crate::GlobalError;

/// Wall-clock milliseconds by step of [`global_map`].
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
    /// The basis form named by [`GlobalMapOptions::form`], else the basis form of lowest
    /// uniformity energy (the laid-out form is [`ObjectiveReport::coefficients`]).
    pub form_index: usize,
    /// Uniformity energy of every basis form (over the input's faces).
    pub form_uniformity: Vec<f64>,
    /// The real harmonic forms `ω_k` per edge of [`Self::surface`]: the real parts of the
    /// holomorphic basis ([`Self::basis_forms`]).
    pub harmonic_forms: Vec<Cochain>,
    /// The conjugation `Λ` (row-major `2g × 2g`, of [`GlobalMapOptions::conjugate`]): the
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
            let area = crate::forms::zeros::signed_area(uv[3 * f], uv[3 * f + 1], uv[3 * f + 2]);
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

/// The global conformal parameterization of `mesh` by a holomorphic 1-form (Jin et al.
/// 2004, §3.1 and Gu–Yau): closed surfaces of genus `g ≥ 1` directly, connected surfaces of
/// genus ≥ 1 or with ≥ 2 boundary loops through their double covering (its forms restricted
/// to the first copy). One factorization of the cotangent Laplacian.
///
/// # Errors
/// [`GlobalError::WrongTopology`] for genus-0 surfaces with at most one boundary loop
/// (`conformap sphere` / `conformap disk`), several components; [`GlobalError::Mesh`] if
/// the double covering or the cut fails; [`GlobalError::Operator`] if the Laplacian is not
/// positive definite; [`GlobalError::DegenerateFormBasis`]; [`GlobalError::InvalidOption`]
/// for a form index out of range.
///
/// # Examples
/// ```
/// use conformap_global::{global_map, GlobalMapOptions};
/// # let torus = conformap_mesh::doc_torus();
/// // `torus`: a closed genus-1 mesh (a coarse torus of revolution, radii 2 and 1)
/// let map = global_map(&torus, &GlobalMapOptions::DEFAULT)?;
/// assert_eq!(map.genus, 1);
/// assert!(map.seam_residual < 1e-12); // seams are pure translations
/// assert_eq!(map.zeros.multiplicity_sum, 0); // 2g − 2
/// let tau = map.tau.unwrap();
/// assert!((tau.im - 3f64.sqrt()).abs() < 0.2); // √(R² − r²)/r, coarse mesh
/// # Ok::<(), conformap_global::GlobalError>(())
/// ```
pub fn global_map(mesh: &TriMesh, options: &GlobalMapOptions) -> Result<GlobalMap, GlobalError> {
    global_map_ranked(mesh, options, None)
}

/// [`global_map`] whose double covering's two factorizations eliminate the vertices in the
/// order of `rank` (per vertex of `mesh`, see `HarmonicFactor::mirrored`) instead of a
/// fresh fill-reducing ordering; `None`: [`global_map`].
pub(crate) fn global_map_ranked(
    mesh: &TriMesh,
    options: &GlobalMapOptions,
    rank: Option<&[u64]>,
) -> Result<GlobalMap, GlobalError> {
    let t_all = Instant::now();
    let mut timings = GlobalTimings::default();
    let boundaries = mesh.boundary_loops().len();
    let genus = match mesh.topology() {
        Topology::ClosedHigherGenus { genus } => genus as usize,
        Topology::OpenHigherGenus { genus, .. } => genus as usize,
        Topology::MultiplyConnected { .. } => 0,
        found => {
            return Err(GlobalError::WrongTopology {
                operation: "a global conformal map by holomorphic 1-forms",
                expected: "a surface of genus ≥ 1, or with ≥ 2 boundary loops (a closed \
                           genus-0 surface: `conformap sphere`; a disk: `conformap disk`)",
                found,
            })
        }
    };
    let t = Instant::now();
    let (surface, input_vertices, input_faces, split_edges, mirror) = if boundaries > 0 {
        let dc = double_cover_surface(mesh)?;
        let iv = dc.split_vertices;
        let faces = dc.mesh.num_faces() / 2;
        (dc.mesh, iv, faces, dc.split_edges, Some(dc.mirror))
    } else {
        (mesh.clone(), mesh.num_vertices(), mesh.num_faces(), 0, None)
    };
    timings.double_cover = ms(t);
    // The Laplacian depends on the surface alone: it is assembled and factored while the
    // tree–cotree, the cut and the cohomology basis run on the other core. The pinned vertex
    // is the basis's root (`homology_basis` clamps the requested root the same way).
    let pinned = options
        .root
        .unwrap_or(0)
        .min(surface.num_vertices().saturating_sub(1)) as u32;
    let (topology, factor) = rayon::join(
        || -> Result<_, GlobalError> {
            let t = Instant::now();
            let basis = homology_basis(&surface, options.root)?;
            let on_cut = cut_graph(&surface, &basis);
            let cut = cut_mesh(&surface, &basis, on_cut)?;
            // the basis forms are sparse (a few hundred edges each): the wedge matrix now,
            // the Gram matrix from their supports after the projection
            let (closed, closedness_residual) = cohomology_basis(&surface, &basis);
            let wedge = wedge_matrix(&surface, &basis.edges, &closed);
            let weights = edge_weights(&surface, &basis);
            // the projection's output pages, faulted in while the factorization runs
            let storage = storage(closed.len(), basis.edges.len());
            Ok((
                basis,
                cut,
                closed,
                closedness_residual,
                weights,
                wedge,
                storage,
                ms(t),
            ))
        },
        || match &mirror {
            // a double covering: two half-size factorizations (Neumann and Dirichlet on
            // one copy, see `harmonic.rs`)
            Some(m) => {
                HarmonicFactor::mirrored(&surface, m, input_vertices, &options.cholesky, rank)
            }
            None => HarmonicFactor::new(&surface, pinned, &options.cholesky),
        },
    );
    let (basis, cut, closed, closedness_residual, weights, wedge, storage, topology_ms) = topology?;
    timings.topology = topology_ms;
    let n = basis.generators.len();
    let surface_genus = n / 2;
    if let Some(k) = options.form {
        if k >= n {
            return Err(GlobalError::InvalidOption {
                name: "form",
                reason: "must be below 2g, the number of basis forms",
            });
        }
    }
    let factor = match factor? {
        f if f.fits_root(basis.root) => f,
        _ => HarmonicFactor::new(&surface, basis.root, &options.cholesky)?,
    };
    let harmonic = factor.project(&surface, &basis, &weights, &closed, storage)?;
    timings.assemble = harmonic.assemble_ms;
    timings.factor = harmonic.factor.analyse_ms + harmonic.factor.factor_ms;
    timings.solve = harmonic.solve_ms;
    let t = Instant::now();
    let conj = conjugation(wedge, &weights, &closed, &harmonic.forms)?;
    let lambda = conj.matrix(options.conjugate).to_vec();
    let ph = harmonic_periods(&basis, &harmonic.forms);
    let periods = period_matrix(&ph, &lambda, n);
    let plain_periods = period_matrix(&ph, &conj.gu_yau, n);
    let bilinear_residual = bilinear_residual(&periods, &conj.wedge, n);
    let bilinear_residual_gu_yau =
        crate::forms::periods::bilinear_residual(&plain_periods, &conj.wedge, n);
    let (tau, tau_gu_yau) = if n == 2 {
        let tau = reduce_modulus(periods[0], periods[2]);
        let plain_tau = (0..2)
            .filter_map(|k| reduce_modulus(plain_periods[k], plain_periods[2 + k]))
            .collect();
        (tau, plain_tau)
    } else {
        (None, Vec::new())
    };
    timings.conjugate = ms(t);
    let s_area = conformap_operators::face_areas(&surface);
    // the objective works from the real forms and `Λ`: the complex basis (`edges × 2g`,
    // 125 MB of fresh pages on armadillo's 15-slit covering) is never built here
    let mut objective = choose(
        &Surface {
            mesh: &surface,
            edges: &basis.edges,
            harmonic: &harmonic.forms,
            lambda: &lambda,
            input_faces,
            input_vertices,
        },
        &options.objective,
        options.form,
        &options.search,
    )?;
    timings.objective = objective.products_ms + objective.solve_ms;
    let t = Instant::now();
    let form_uniformity = objective.basis_uniformity.clone();
    let form_index = options.form.unwrap_or_else(|| {
        (0..n)
            .min_by(|&a, &b| form_uniformity[a].total_cmp(&form_uniformity[b]))
            .unwrap_or(0)
    });
    let combined = combine(&harmonic.forms, &lambda, &objective.coefficients);
    let phi = &combined;
    let area: f64 = form_face_areas(&basis.edges, phi, surface.num_faces())
        .iter()
        .sum();
    let total: f64 = s_area.iter().sum();
    if !(area > 0.0) {
        return Err(GlobalError::DegenerateFormBasis {
            reason: "the chosen form has no positive layout area",
        });
    }
    let scale = (total / area).sqrt();
    let form: ComplexCochain = phi.iter().map(|z| z * scale).collect();
    // the layout (a sequential walk over the cut mesh) on one core, the per-vertex stretch
    // and conformal factor of the form on the other; the zeros need both
    let (layout, (stretch, conformal_factor)) = rayon::join(
        || integrate(&surface, &cut, &basis.edges, &form),
        || {
            let stretch = vertex_stretch(&surface, &basis.edges, &form);
            let factor = conformal_factor(&surface, &basis.edges, &form);
            (stretch, factor)
        },
    );
    timings.layout = ms(t);
    let t = Instant::now();
    let zeros = find_zeros(&surface, &layout.corner_uv, &stretch);
    finish_zeros(
        &mut objective,
        &surface,
        &basis.edges,
        &form,
        &zeros,
        input_vertices,
    );
    // `layout` is the wall time of the pair above (the stretch and conformal factor
    // included), `zeros` the search for zeros alone
    timings.zeros = ms(t);
    let t = Instant::now();
    let metrics = layout_metrics(
        &surface,
        &layout.corner_uv,
        input_faces,
        &zeros.in_zero_cluster,
    );
    timings.metrics = ms(t);
    timings.total = ms(t_all);
    Ok(GlobalMap {
        genus,
        boundaries,
        double_covered: boundaries > 0,
        surface_genus,
        surface,
        input_vertices,
        input_faces,
        split_edges,
        generator_lengths: basis.generators.iter().map(|g| g.length).collect(),
        edges: basis.edges,
        cut,
        period_matrix: periods,
        wedge_matrix: conj.wedge,
        conjugate: options.conjugate,
        complex_structure_defect: conj.complex_structure_defect,
        projection_change: conj.projection_change,
        bilinear_residual_gu_yau,
        bilinear_residual,
        tau,
        tau_gu_yau,
        harmonic_residual: harmonic.codifferential_residual,
        closedness_residual,
        form_index,
        form_uniformity,
        harmonic_forms: harmonic.forms,
        conjugation: lambda,
        form,
        corner_uv: layout.corner_uv,
        seam_residual: layout.seam_residual,
        seam_edges: layout.seam_edges,
        layout_diagonal: layout.diagonal,
        zeros,
        conformal_factor,
        metrics,
        objective,
        factor_dim: harmonic.factor.n,
        factor_nnz: harmonic.factor.nnz_factor,
        timings_ms: timings,
    })
}

/// Signed layout area of each of the first `faces` faces under `phi`, from its edge values:
/// `½ Im(conj(φ(v0→v1)) φ(v0→v2))`.
fn form_face_areas(edges: &EdgeIndex, phi: &[Complex64], faces: usize) -> Vec<f64> {
    let val = |h: usize| edges.sign(h) * phi[edges.edge_of[h] as usize];
    (0..faces)
        .map(|f| {
            let (a, b) = (val(3 * f), -val(3 * f + 2));
            0.5 * (a.conj() * b).im
        })
        .collect()
}

/// `Σ_k c_k φ_k` (real `c`) per edge for the holomorphic basis `φ_k = ω_k + i Σ_j Λ_jk ω_j`
/// of the real forms `h` and the conjugation `lambda` (row-major), without the basis: it is
/// `Σ_j ω_j d_j` with `d_j = c_j + i Σ_k Λ_jk c_k`.
fn combine(h: &[Cochain], lambda: &[f64], c: &[f64]) -> ComplexCochain {
    let n = h.len();
    let d: Vec<Complex64> = (0..n)
        .map(|j| {
            let conj: f64 = (0..n).map(|k| lambda[j * n + k] * c[k]).sum();
            Complex64::new(c[j], conj)
        })
        .collect();
    let edges = h.first().map_or(0, Vec::len);
    (0..edges)
        .into_par_iter()
        .with_min_len(4096)
        .map(|e| h.iter().zip(&d).map(|(w, dj)| dj * w[e]).sum())
        .collect()
}
