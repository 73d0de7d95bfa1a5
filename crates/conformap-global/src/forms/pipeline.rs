//! [`global_map`] and its steps, in order: the closed surface the forms
//! live on, its topology (concurrent with the Laplacian's factorization), the harmonic
//! projection, the conjugation and periods, the objective's choice of form, the layout, the
//! zeros and the metrics. Each step hands the next a named struct.

use std::time::Instant;

use conformap_mesh::{
    cut_graph, cut_mesh, homology_basis, CutMesh, HomologyBasis, Topology, TriMesh,
};
use conformap_sphere::double_cover_surface;
use num_complex::Complex64;
use rayon::prelude::*;

use crate::forms::cohomology::{
    cohomology_basis, edge_weights, wedge_matrix, Cochain, SparseCochain,
};
use crate::forms::conjugate::{conjugation, Conjugation};
use crate::forms::global_map::{GlobalMap, GlobalTimings};
use crate::forms::harmonic::{ms, storage, HarmonicFactor, HarmonicSolve};
use crate::forms::layout::{integrate, Layout};
use crate::forms::optimal::{choose, finish_zeros, ObjectiveReport, Surface};
use crate::forms::options::GlobalMapOptions;
use crate::forms::periods::{
    bilinear_residual, harmonic_periods, period_matrix, reduce_modulus, ComplexCochain,
};
use crate::forms::quality::{layout_metrics, LayoutMetrics};
use crate::forms::zeros::{conformal_factor, find_zeros, vertex_stretch, ZeroReport};
use crate::GlobalError;

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

/// [`global_map`] whose double covering's two factorizations eliminate
/// the vertices in the order of `rank` (per vertex of `mesh`, see
/// `HarmonicFactor::mirrored`) instead of a fresh fill-reducing ordering; `None`: the plain
/// [`global_map`].
pub(crate) fn global_map_ranked(
    mesh: &TriMesh,
    options: &GlobalMapOptions,
    rank: Option<&[u64]>,
) -> Result<GlobalMap, GlobalError> {
    let t_all = Instant::now();
    let mut timings = GlobalTimings::default();
    let boundaries = mesh.boundary_loops().len();
    let genus = input_genus(mesh)?;
    let t = Instant::now();
    let closed = closed_surface(mesh)?;
    timings.double_cover = ms(t);
    let (mut parts, harmonic) = topology_and_harmonic(&closed, options, rank, &mut timings)?;
    let t = Instant::now();
    let wedge = std::mem::take(&mut parts.wedge);
    let conj = conjugate(&parts, wedge, &harmonic, options)?;
    timings.conjugate = ms(t);
    let mut objective = choose_form(&closed, &parts, &harmonic, &conj, options)?;
    timings.objective = objective.products_ms + objective.solve_ms;
    let t = Instant::now();
    let form_uniformity = objective.basis_uniformity.clone();
    let n = parts.basis.generators.len();
    let form_index = options
        .form
        .unwrap_or_else(|| most_uniform_form(&form_uniformity));
    let form = scaled_form(&closed.mesh, &parts.basis, &harmonic, &conj, &objective)?;
    let laid = lay_out(&closed.mesh, &parts, &form);
    timings.layout = ms(t);
    let (zeros, metrics) =
        zeros_and_metrics(&closed, &parts, &form, &laid, &mut objective, &mut timings);
    timings.total = ms(t_all);
    let Parts {
        basis,
        cut,
        closedness_residual,
        ..
    } = parts;
    Ok(GlobalMap {
        genus,
        boundaries,
        double_covered: boundaries > 0,
        surface_genus: n / 2,
        surface: closed.mesh,
        input_vertices: closed.input_vertices,
        input_faces: closed.input_faces,
        split_edges: closed.split_edges,
        generator_lengths: basis.generators.iter().map(|g| g.length).collect(),
        edges: basis.edges,
        cut,
        period_matrix: conj.periods,
        wedge_matrix: conj.conjugation.wedge,
        conjugate: options.conjugate,
        complex_structure_defect: conj.conjugation.complex_structure_defect,
        projection_change: conj.conjugation.projection_change,
        bilinear_residual_gu_yau: conj.bilinear_residual_gu_yau,
        bilinear_residual: conj.bilinear_residual,
        tau: conj.tau,
        tau_gu_yau: conj.tau_gu_yau,
        harmonic_residual: harmonic.codifferential_residual,
        closedness_residual,
        form_index,
        form_uniformity,
        harmonic_forms: harmonic.forms,
        conjugation: conj.lambda,
        form,
        corner_uv: laid.layout.corner_uv,
        seam_residual: laid.layout.seam_residual,
        seam_edges: laid.layout.seam_edges,
        layout_diagonal: laid.layout.diagonal,
        zeros,
        conformal_factor: laid.conformal_factor,
        metrics,
        objective,
        factor_dim: harmonic.factor.n,
        factor_nnz: harmonic.factor.nnz_factor,
        timings_ms: timings,
    })
}

/// The index of the most uniform basis form (the lowest uniformity energy).
fn most_uniform_form(form_uniformity: &[f64]) -> usize {
    (0..form_uniformity.len())
        .min_by(|&a, &b| form_uniformity[a].total_cmp(&form_uniformity[b]))
        .unwrap_or(0)
}

/// The zeros of the laid-out `form` (completing the objective's report of targeted zeros)
/// and the layout's metrics. `timings.zeros` is the search for zeros alone (`layout` is the
/// wall time of [`lay_out`], the stretch and conformal factor included).
fn zeros_and_metrics(
    closed: &ClosedSurface,
    parts: &Parts,
    form: &[Complex64],
    laid: &Laid,
    objective: &mut ObjectiveReport,
    timings: &mut GlobalTimings,
) -> (ZeroReport, LayoutMetrics) {
    let t = Instant::now();
    let zeros = find_zeros(&closed.mesh, &laid.layout.corner_uv, &laid.stretch);
    finish_zeros(
        objective,
        &closed.mesh,
        &parts.basis.edges,
        form,
        &zeros,
        closed.input_vertices,
    );
    timings.zeros = ms(t);
    let t = Instant::now();
    let metrics = layout_metrics(
        &closed.mesh,
        &laid.layout.corner_uv,
        closed.input_faces,
        &zeros.in_zero_cluster,
    );
    timings.metrics = ms(t);
    (zeros, metrics)
}

/// The genus of the input, or [`GlobalError::WrongTopology`] for a genus-0 surface with at
/// most one boundary loop (and several components).
fn input_genus(mesh: &TriMesh) -> Result<usize, GlobalError> {
    match mesh.topology() {
        Topology::ClosedHigherGenus { genus } => Ok(genus as usize),
        Topology::OpenHigherGenus { genus, .. } => Ok(genus as usize),
        Topology::MultiplyConnected { .. } => Ok(0),
        found => Err(GlobalError::WrongTopology {
            operation: "a global conformal map by holomorphic 1-forms",
            expected: "a surface of genus ≥ 1, or with ≥ 2 boundary loops (a closed \
                       genus-0 surface: `conformap sphere`; a disk: `conformap disk`)",
            found,
        }),
    }
}

/// The closed surface the forms live on: the input, or its double covering.
struct ClosedSurface {
    mesh: TriMesh,
    /// Vertices and faces of `mesh` that belong to the input (they come first).
    input_vertices: usize,
    input_faces: usize,
    /// Boundary chords split by the double covering.
    split_edges: usize,
    /// A double covering's vertex mirror (`None`: the input is closed).
    mirror: Option<Vec<u32>>,
}

fn closed_surface(mesh: &TriMesh) -> Result<ClosedSurface, GlobalError> {
    if mesh.boundary_loops().is_empty() {
        return Ok(ClosedSurface {
            mesh: mesh.clone(),
            input_vertices: mesh.num_vertices(),
            input_faces: mesh.num_faces(),
            split_edges: 0,
            mirror: None,
        });
    }
    let dc = double_cover_surface(mesh)?;
    Ok(ClosedSurface {
        input_vertices: dc.split_vertices,
        input_faces: dc.mesh.num_faces() / 2,
        split_edges: dc.split_edges,
        mirror: Some(dc.mirror),
        mesh: dc.mesh,
    })
}

/// The topology of the closed surface: homology basis, fundamental domain, cohomology
/// basis and what the harmonic projection needs of it.
struct Parts {
    basis: HomologyBasis,
    cut: CutMesh,
    /// The closed (cohomology) forms, sparse.
    closed: Vec<SparseCochain>,
    closedness_residual: f64,
    weights: Vec<f64>,
    /// The wedge matrix of the closed forms (handed on to the conjugation).
    wedge: Vec<f64>,
    /// The projection's output pages.
    storage: Vec<Cochain>,
    ms: f64,
}

fn topology_parts(surface: &TriMesh, root: Option<usize>) -> Result<Parts, GlobalError> {
    let t = Instant::now();
    let basis = homology_basis(surface, root)?;
    let on_cut = cut_graph(surface, &basis);
    let cut = cut_mesh(surface, &basis, on_cut)?;
    // the basis forms are sparse (a few hundred edges each): the wedge matrix now,
    // the Gram matrix from their supports after the projection
    let (closed, closedness_residual) = cohomology_basis(surface, &basis);
    let wedge = wedge_matrix(surface, &basis.edges, &closed);
    let weights = edge_weights(surface, &basis);
    // the projection's output pages, faulted in while the factorization runs
    let storage = storage(closed.len(), basis.edges.len());
    Ok(Parts {
        basis,
        cut,
        closed,
        closedness_residual,
        weights,
        wedge,
        storage,
        ms: ms(t),
    })
}

/// The topology and the factored Laplacian (which depends on the surface alone: it is
/// assembled and factored while the tree–cotree, the cut and the cohomology basis run on
/// the other core), then the harmonic projection of the cohomology basis.
fn topology_and_harmonic(
    closed: &ClosedSurface,
    options: &GlobalMapOptions,
    rank: Option<&[u64]>,
    timings: &mut GlobalTimings,
) -> Result<(Parts, HarmonicSolve), GlobalError> {
    let surface = &closed.mesh;
    // the pinned vertex is the basis's root (`homology_basis` clamps the requested root
    // the same way)
    let pinned = options
        .root
        .unwrap_or(0)
        .min(surface.num_vertices().saturating_sub(1)) as u32;
    let (parts, factor) = rayon::join(
        || topology_parts(surface, options.root),
        || match &closed.mirror {
            // a double covering: two half-size factorizations (Neumann and Dirichlet on
            // one copy, see `harmonic.rs`)
            Some(m) => {
                HarmonicFactor::mirrored(surface, m, closed.input_vertices, &options.cholesky, rank)
            }
            None => HarmonicFactor::new(surface, pinned, &options.cholesky),
        },
    );
    let mut parts = parts?;
    timings.topology = parts.ms;
    let n = parts.basis.generators.len();
    if let Some(k) = options.form {
        if k >= n {
            return Err(GlobalError::InvalidOption {
                name: "form",
                reason: "must be below 2g, the number of basis forms",
            });
        }
    }
    let factor = match factor? {
        f if f.fits_root(parts.basis.root) => f,
        _ => HarmonicFactor::new(surface, parts.basis.root, &options.cholesky)?,
    };
    let storage = std::mem::take(&mut parts.storage);
    let harmonic = factor.project(
        surface,
        &parts.basis,
        &parts.weights,
        &parts.closed,
        storage,
    )?;
    timings.assemble = harmonic.assemble_ms;
    timings.factor = harmonic.factor.analyse_ms + harmonic.factor.factor_ms;
    timings.solve = harmonic.solve_ms;
    Ok((parts, harmonic))
}

/// The conjugation `Λ` and what it gives: periods, bilinear residuals, τ (genus 1).
struct Conjugated {
    conjugation: Conjugation,
    lambda: Vec<f64>,
    periods: Vec<Complex64>,
    bilinear_residual: f64,
    bilinear_residual_gu_yau: f64,
    tau: Option<Complex64>,
    tau_gu_yau: Vec<Complex64>,
}

fn conjugate(
    parts: &Parts,
    wedge: Vec<f64>,
    harmonic: &HarmonicSolve,
    options: &GlobalMapOptions,
) -> Result<Conjugated, GlobalError> {
    let n = parts.basis.generators.len();
    let conj = conjugation(wedge, &parts.weights, &parts.closed, &harmonic.forms)?;
    let lambda = conj.matrix(options.conjugate).to_vec();
    let ph = harmonic_periods(&parts.basis, &harmonic.forms);
    let periods = period_matrix(&ph, &lambda, n);
    let plain_periods = period_matrix(&ph, &conj.gu_yau, n);
    let residual = bilinear_residual(&periods, &conj.wedge, n);
    let residual_gu_yau = bilinear_residual(&plain_periods, &conj.wedge, n);
    let (tau, tau_gu_yau) = if n == 2 {
        let tau = reduce_modulus(periods[0], periods[2]);
        let plain_tau = (0..2)
            .filter_map(|k| reduce_modulus(plain_periods[k], plain_periods[2 + k]))
            .collect();
        (tau, plain_tau)
    } else {
        (None, Vec::new())
    };
    Ok(Conjugated {
        conjugation: conj,
        lambda,
        periods,
        bilinear_residual: residual,
        bilinear_residual_gu_yau: residual_gu_yau,
        tau,
        tau_gu_yau,
    })
}

/// The objective's choice of coefficients. It works from the real forms and `Λ`: the
/// complex basis (`edges × 2g`, 125 MB of fresh pages on armadillo's 15-slit covering) is
/// never built here.
fn choose_form(
    closed: &ClosedSurface,
    parts: &Parts,
    harmonic: &HarmonicSolve,
    conj: &Conjugated,
    options: &GlobalMapOptions,
) -> Result<ObjectiveReport, GlobalError> {
    choose(
        &Surface {
            mesh: &closed.mesh,
            edges: &parts.basis.edges,
            harmonic: &harmonic.forms,
            lambda: &conj.lambda,
            input_faces: closed.input_faces,
            input_vertices: closed.input_vertices,
        },
        &options.objective,
        options.form,
        &options.search,
    )
}

/// The chosen form, scaled so that its layout's area equals the surface's (Jin et al.
/// Eq. 6).
///
/// # Errors
/// [`GlobalError::DegenerateFormBasis`] if its layout has no positive area.
fn scaled_form(
    surface: &TriMesh,
    basis: &HomologyBasis,
    harmonic: &HarmonicSolve,
    conj: &Conjugated,
    objective: &ObjectiveReport,
) -> Result<ComplexCochain, GlobalError> {
    let s_area = conformap_operators::face_areas(surface);
    let combined = combine(&harmonic.forms, &conj.lambda, &objective.coefficients);
    let area: f64 = form_face_areas(&basis.edges, &combined, surface.num_faces())
        .iter()
        .sum();
    let total: f64 = s_area.iter().sum();
    if !(area > 0.0) {
        return Err(GlobalError::DegenerateFormBasis {
            reason: "the chosen form has no positive layout area",
        });
    }
    let scale = (total / area).sqrt();
    Ok(combined.iter().map(|z| z * scale).collect())
}

/// The layout and the form's per-vertex stretch and conformal factor.
struct Laid {
    layout: Layout,
    stretch: Vec<f64>,
    conformal_factor: Vec<f64>,
}

/// The layout (a sequential walk over the cut mesh) on one core, the per-vertex stretch
/// and conformal factor of the form on the other; the zeros need both.
fn lay_out(surface: &TriMesh, parts: &Parts, form: &[Complex64]) -> Laid {
    let edges = &parts.basis.edges;
    let (layout, (stretch, conformal_factor)) = rayon::join(
        || integrate(surface, &parts.cut, edges, form),
        || {
            let stretch = vertex_stretch(surface, edges, form);
            let factor = conformal_factor(surface, edges, form);
            (stretch, factor)
        },
    );
    Laid {
        layout,
        stretch,
        conformal_factor,
    }
}

/// Signed layout area of each of the first `faces` faces under `phi`, from its edge values:
/// `½ Im(conj(φ(v0→v1)) φ(v0→v2))`.
fn form_face_areas(edges: &conformap_mesh::EdgeIndex, phi: &[Complex64], faces: usize) -> Vec<f64> {
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
