//! The choice of form for an [`Objective`]: [`choose`] dispatches to one named step per
//! objective (a basis form, the uniformity search, the emphasized area, zeros at given
//! vertices), each returning a [`Choice`]; [`finish_zeros`] completes the zero report once
//! the layout's zeros are known.

use conformap_mesh::{EdgeIndex, TriMesh};

use crate::forms::cohomology::Cochain;
use crate::forms::optimal::eigen::{self, EmphasisReport};
use crate::forms::optimal::faces::{self, FaceForms};
use crate::forms::optimal::moments::Moments;
use crate::forms::optimal::objective::{
    Objective, ObjectiveReport, ZeroAllocationReport, ZeroTarget,
};
use crate::forms::optimal::products::{self, AreaProducts};
use crate::forms::optimal::search::{self, FormSearchOptions, UniformSearch};
use crate::forms::optimal::targets;
use crate::forms::optimal::uniform::EnergyModel;
use crate::forms::periods::holomorphic_basis;
use crate::forms::zeros::{vertex_stretch, ZeroReport};
use crate::GlobalError;

/// Inputs of [`choose`].
pub(crate) struct Surface<'a> {
    pub mesh: &'a TriMesh,
    pub edges: &'a EdgeIndex,
    /// The real harmonic forms and the conjugation `Λ` (row-major): the holomorphic basis
    /// is `a_k = h_k + i Σ_j Λ_jk h_j`.
    pub harmonic: &'a [Cochain],
    pub lambda: &'a [f64],
    pub input_faces: usize,
    pub input_vertices: usize,
}

fn ms(t: std::time::Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// The whitened coefficients one objective chose and what it measured on the way (the
/// parts of [`ObjectiveReport`] that depend on the objective).
#[derive(Default)]
struct Choice {
    mu: Vec<f64>,
    search: Option<UniformSearch>,
    opposite: Option<UniformSearch>,
    ratio: Option<f64>,
    emphasis: Option<EmphasisReport>,
    zeros: Option<ZeroAllocationReport>,
    energy_model: String,
}

impl Choice {
    /// Just the coefficients `mu`.
    fn of(mu: Vec<f64>) -> Self {
        Self {
            mu,
            ..Self::default()
        }
    }
}

/// The whitened basis forms and their uniformity energies.
struct Basis {
    mu: Vec<Vec<f64>>,
    uniformity: Vec<f64>,
}

/// Picks the coefficients for `objective`. `forced`: a basis form named by the user.
pub(crate) fn choose(
    s: &Surface<'_>,
    objective: &Objective,
    forced: Option<usize>,
    search: &FormSearchOptions,
) -> Result<ObjectiveReport, GlobalError> {
    let t = std::time::Instant::now();
    let ff = FaceForms::from_harmonic(s.mesh, s.edges, s.harmonic, s.lambda, s.input_faces)?;
    let products_ms = ms(t);
    let t = std::time::Instant::now();
    let n = ff.n;
    let basis = Basis {
        mu: (0..n).map(|k| ff.whiten(&unit_vector(n, k))).collect(),
        uniformity: ff.basis_energy.clone(),
    };
    let best_basis = (0..n)
        .min_by(|&a, &b| basis.uniformity[a].total_cmp(&basis.uniformity[b]))
        .unwrap_or(0);
    let choice = match (forced, objective) {
        (Some(k), _) => Choice::of(basis.mu[k].clone()),
        (None, Objective::BestBasisForm) => Choice::of(basis.mu[best_basis].clone()),
        (None, Objective::Uniform | Objective::LeastUniform) if n == 2 => Choice {
            ratio: Some(1.0),
            ..Choice::of(basis.mu[0].clone())
        },
        (None, Objective::Uniform | Objective::LeastUniform) => {
            let maximize = matches!(objective, Objective::LeastUniform);
            choose_uniform(&ff, &basis, maximize, search)
        }
        (None, Objective::Emphasize { faces, maximize }) => {
            choose_emphasized(s, &ff, faces, *maximize)?
        }
        (None, Objective::Zeros { vertices }) => choose_zeros(s, &ff, vertices, search)?,
    };
    Ok(ObjectiveReport {
        objective: if forced.is_some() {
            "basis".to_owned()
        } else {
            objective.name().to_owned()
        },
        coefficients: ff.coefficients(&choice.mu),
        uniformity: ff.energy(&choice.mu),
        basis_uniformity: basis.uniformity,
        search: choice.search,
        opposite: choice.opposite,
        max_min_ratio: choice.ratio,
        emphasis: choice.emphasis,
        zeros: choice.zeros,
        energy_model: choice.energy_model,
        products_ms,
        solve_ms: ms(t),
    })
}

/// The most (or, `maximize`, least) uniform form by the seeded multistart, on the second
/// moments or on the faces (with coarse levels first), whichever costs less for the
/// search's starts; with [`FormSearchOptions::compare`] also the opposite extreme.
fn choose_uniform(
    ff: &FaceForms,
    basis: &Basis,
    maximize: bool,
    search: &FormSearchOptions,
) -> Choice {
    let n = ff.n;
    let runs = if search.compare { 2 } else { 1 };
    let basis_starts = search.basis_starts.map_or(n, |k| k.clamp(1, n));
    let starts = runs * (basis_starts + search.starts);
    let starts_from = (basis.mu.as_slice(), basis.uniformity.as_slice());
    let (found, other, energy_model) = if faces::use_moments(ff.faces(), n, starts) {
        let moments = Moments::from_faces(ff);
        let (found, other) = search_pair(&moments, &[], starts_from, maximize, search);
        (found, other, "moments".to_owned())
    } else {
        let strides = faces::coarse_strides(ff.faces());
        let samples: Vec<FaceForms> = strides.iter().map(|&s| ff.sample(s)).collect();
        let levels: Vec<&dyn EnergyModel> = samples.iter().map(|s| s as &dyn EnergyModel).collect();
        let (found, other) = search_pair(ff, &levels, starts_from, maximize, search);
        (found, other, direct_model_name(&strides))
    };
    let ratio = other.as_ref().map(|other| {
        let (hi, lo) = if maximize {
            (found.energy, other.energy)
        } else {
            (other.energy, found.energy)
        };
        hi / lo
    });
    Choice {
        mu: found.mu.clone(),
        search: Some(found),
        opposite: other,
        ratio,
        energy_model,
        ..Choice::default()
    }
}

/// The report's name of the direct energy model with coarse levels `strides`.
fn direct_model_name(strides: &[usize]) -> String {
    match strides {
        [] => "direct".to_owned(),
        _ => format!(
            "direct, coarse levels {} of the faces",
            strides
                .iter()
                .map(|s| format!("1/{s}"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The form that gives the region `faces` the largest (`maximize`) or smallest share of
/// the layout's area: an eigenproblem (Eq. 8–9).
fn choose_emphasized(
    s: &Surface<'_>,
    ff: &FaceForms,
    faces: &[usize],
    maximize: bool,
) -> Result<Choice, GlobalError> {
    let mask = conformap_sphere::region_mask(s.input_faces, faces)?;
    let p = AreaProducts::from_faces(ff);
    let (mu, report) = eigen::emphasize(&p, &mask, maximize);
    Ok(Choice {
        emphasis: Some(report),
        ..Choice::of(mu)
    })
}

/// Checks the zero targets `vertices` of a basis of `n` forms.
fn check_zero_targets(
    vertices: &[usize],
    n: usize,
    input_vertices: usize,
) -> Result<(), GlobalError> {
    if n < 4 {
        return Err(GlobalError::InvalidOption {
            name: "objective zeros",
            reason: "a genus-1 form has no zeros: zero allocation needs genus ≥ 2",
        });
    }
    if let Some(&v) = vertices.iter().find(|&&v| v >= input_vertices) {
        return Err(GlobalError::ZeroTargetOutOfRange {
            vertex: v,
            vertices: input_vertices,
        });
    }
    if vertices.is_empty() {
        return Err(GlobalError::InvalidOption {
            name: "objective zeros",
            reason: "needs at least one target vertex",
        });
    }
    Ok(())
}

/// The form with zeros at `vertices` (Eq. 13–14): exactly, the most uniform form of the
/// subspace vanishing there, when that subspace has dimension ≥ 2; else the least
/// `Σ|ω(v_i)|²` per unit area.
fn choose_zeros(
    s: &Surface<'_>,
    ff: &FaceForms,
    vertices: &[usize],
    search: &FormSearchOptions,
) -> Result<Choice, GlobalError> {
    let n = ff.n;
    check_zero_targets(vertices, n, s.input_vertices)?;
    let mut targets = vertices.to_vec();
    targets.sort_unstable();
    targets.dedup();
    let p = AreaProducts::from_faces(ff);
    // the condition rows need the basis's values at the target vertices
    let forms = holomorphic_basis(s.harmonic, s.lambda);
    let m = targets::condition_gram(s.mesh, s.edges, &forms, &p, &targets);
    let free = n.saturating_sub(2 * targets.len());
    let mut choice = if free >= 2 {
        exact_zeros(&p, &m, n, free, search)
    } else {
        // no form vanishes at all targets: the least Σ|ω(v_i)|² per unit area
        let (_, mu, _) = eigen::extreme_eigenpair(&m, n, false);
        Choice::of(mu)
    };
    let value = products::quadratic(&m, &choice.mu);
    choice.zeros = Some(ZeroAllocationReport {
        targets: targets
            .iter()
            .map(|&vertex| ZeroTarget {
                vertex,
                ring_distance: None,
                nearest_zero: None,
                residual: f64::NAN,
            })
            .collect(),
        exact_expected: free >= 2,
        method: if free >= 2 { "exact" } else { "least-squares" }.to_owned(),
        median_stretch: f64::NAN,
        eigenvalue: value,
    });
    Ok(choice)
}

/// Exact zeros: the most uniform form of the `free`-dimensional subspace vanishing at the
/// targets (condition Gram matrix `m`).
fn exact_zeros(
    p: &AreaProducts,
    m: &[f64],
    n: usize,
    free: usize,
    search: &FormSearchOptions,
) -> Choice {
    let basis = targets::null_space(m, n, free);
    let sub = targets::restricted(p, &basis, free);
    let moments = Moments::new(&sub);
    let sub_basis: Vec<Vec<f64>> = (0..free)
        .map(|k| sub.whiten(&unit_vector(free, k)))
        .collect();
    let found = search::multistart(
        &moments,
        &[],
        &sub_basis,
        None,
        false,
        &search.with_compare(false),
    );
    Choice {
        mu: targets::lift(&basis, &found.mu, n),
        search: Some(found),
        energy_model: "moments".to_owned(),
        ..Choice::default()
    }
}

/// The `k`-th unit vector of dimension `n`.
fn unit_vector(n: usize, k: usize) -> Vec<f64> {
    let mut e = vec![0.0; n];
    e[k] = 1.0;
    e
}

/// The search for `maximize` on `model` from the whitened basis forms (with their
/// energies) and, with [`FormSearchOptions::compare`], the opposite extreme's.
fn search_pair<M: EnergyModel + ?Sized>(
    model: &M,
    coarse: &[&dyn EnergyModel],
    (basis, energy): (&[Vec<f64>], &[f64]),
    maximize: bool,
    search: &FormSearchOptions,
) -> (UniformSearch, Option<UniformSearch>) {
    let run = |maximize| search::multistart(model, coarse, basis, Some(energy), maximize, search);
    let found = run(maximize);
    let other = search.compare.then(|| run(!maximize));
    (found, other)
}

/// Fills the zero-allocation report once the layout's zeros are known: `form` is the
/// laid-out form per edge of `mesh`.
pub(crate) fn finish_zeros(
    report: &mut ObjectiveReport,
    mesh: &TriMesh,
    edges: &EdgeIndex,
    form: &[num_complex::Complex64],
    zeros: &ZeroReport,
    input_vertices: usize,
) {
    let Some(z) = report.zeros.as_mut() else {
        return;
    };
    let stretch = vertex_stretch(mesh, edges, form);
    let mut goal = vec![false; mesh.num_vertices()];
    for zero in &zeros.zeros {
        goal[zero.vertex] = true;
    }
    for t in &mut z.targets {
        t.residual = stretch[t.vertex];
        if let Some((d, v)) = eigen::ring_distance(mesh, t.vertex, &goal) {
            t.ring_distance = Some(d);
            t.nearest_zero = Some(v);
        }
    }
    let mut s: Vec<f64> = stretch[..input_vertices].to_vec();
    s.sort_by(f64::total_cmp);
    z.median_stretch = s.get(s.len() / 2).copied().unwrap_or(f64::NAN);
}
