//! `conformap global MESH -o OUT ...`: the global conformal parameterization of a surface
//! of genus ≥ 1 (or with several boundary loops, through its double covering) by a
//! holomorphic 1-form (Jin, Wang, Yau, Gu 2004, §3.1).
//!
//! `-o` gets the input's vertices in the input's order with one `vt` per corner class
//! (`f v/vt`): across a seam the two sides differ by a period, a pure translation. The
//! layout is scaled uniformly into the unit square (offset and scale in the report), which
//! changes neither angles nor seam translations. `--flat` gets the fundamental domain (the
//! surface cut open along the seams) with the raw layout as `(u, v, 0)`.

use std::path::{Path, PathBuf};

use conformap_global::{
    global_map, ConjugateMethod, GlobalMap, GlobalMapOptions, Objective, SeamedLayout,
};
use conformap_io::CornerUv;
use conformap_mesh::TriMesh;
use conformap_metrics::{corner_map_metrics, MetricsOptions};
use conformap_operators::PeakMemory;
use serde_json::json;

use crate::failure::Failure;
use crate::jobs::param::read_region;
use crate::pipeline::{Input, InputOptions, MapJob, OutputOptions, Solved, TexCoords};
use crate::report::{MetricsSection, SolverSection, StageTimings};

crate::choice! {
    /// The conjugate forms (the discrete Hodge star).
    pub enum Conjugate {
        /// The nearest exact complex structure to the Gu–Yau solve (the default: Riemann's
        /// bilinear relations to rounding, one τ for every form of a torus).
        Nearest = "nearest",
        /// Gu–Yau's wedge-product system as solved.
        GuYau = "gu-yau",
    }
}

crate::choice! {
    /// Which holomorphic form `global` lays out.
    pub enum FormObjective {
        /// The most uniform form (Jin et al. Eq. 6–7): a seeded multistart Newton search on the
        /// coefficient sphere (milliseconds: the energy is a quadratic form of precomputed
        /// moments). The least uniform form is searched too, for the report's max/min ratio.
        Uniform = "uniform",
        /// The least uniform form (the other end, as the paper's figures compare them).
        LeastUniform = "least-uniform",
        /// The form giving the faces of `--region` the largest share of the parameter area
        /// (Eq. 8–9, a 2g × 2g generalized eigenproblem).
        Emphasize = "emphasize",
        /// The form giving the faces of `--region` the smallest share of the parameter area.
        DeEmphasize = "de-emphasize",
        /// The form whose zeros are nearest the vertices of `--zeros` (Eq. 13–14; genus ≥ 2;
        /// exact for at most g − 1 targets, a least-squares compromise beyond).
        Zeros = "zeros",
        /// The basis form of lowest uniformity energy (no search).
        Basis = "basis",
    }
}

/// Arguments of `conformap global`.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct GlobalJob {
    /// The mesh (connected; genus ≥ 1, or ≥ 2 boundary loops) and how to read it.
    pub input: InputOptions,
    /// The outputs: `-o` the mesh with one `vt` per corner (`f v/vt`; glTF: vertices split
    /// along the seams); `--flat` the fundamental domain with the layout as positions.
    pub output: OutputOptions,
    /// The holomorphic basis form to lay out (0 ≤ K < 2g), overriding `--objective`.
    pub form: Option<usize>,
    /// The conjugate forms.
    pub conjugate: Conjugate,
    /// Which form to lay out (Jin et al. §3.2–3.3, §3.6).
    pub objective: FormObjective,
    /// The faces to emphasize or de-emphasize: one 0-based face index per line, `#`
    /// comments (the format `mobius --region` reads). Needed by `--objective emphasize` and
    /// `de-emphasize`.
    pub region: Option<PathBuf>,
    /// The vertices (0-based, comma-separated) where `--objective zeros` puts the form's
    /// zeros.
    pub zeros: Option<Vec<usize>>,
    /// Random starts of the uniform search (besides the 2g basis forms). Default: the
    /// library's.
    pub starts: Option<usize>,
    /// Root vertex of the homology generators' shortest-path tree (0-based). Default 0.
    pub root: Option<usize>,
    /// Topological optimization (Jin et al. §3.5): slit the surface at the extreme points
    /// of its map (limb tips) and map the slit surface by its most uniform form, greedily;
    /// returns the most uniform layout seen, the starting map included. Also takes closed
    /// genus-0 meshes (the starting map is then the uniform-Möbius sphere map) and disks
    /// (the uniform-Möbius disk map).
    pub topology_opt: bool,
    /// Most slits of `--topology-opt`. Default: the library's (16).
    pub max_slits: Option<usize>,
    /// Slit length of `--topology-opt` as a fraction of the bounding-box diagonal.
    /// Default: the library's (0.04).
    pub slit_length: Option<f64>,
    /// The region's faces given in memory instead of read from [`GlobalJob::region`] (the
    /// Python package's arrays; each checked with [`crate::jobs::param::region_face`]).
    /// Default: none.
    pub region_faces: Option<Vec<usize>>,
}

impl GlobalJob {
    /// The most uniform global map of `input` written to `output`, every option at its
    /// default.
    pub fn new(input: InputOptions, output: OutputOptions) -> Self {
        Self {
            input,
            output,
            form: None,
            conjugate: Conjugate::Nearest,
            objective: FormObjective::Uniform,
            region: None,
            zeros: None,
            starts: None,
            root: None,
            topology_opt: false,
            max_slits: None,
            slit_length: None,
            region_faces: None,
        }
    }

    /// With the objective choosing the form.
    pub fn with_objective(mut self, objective: FormObjective) -> Self {
        self.objective = objective;
        self
    }

    /// With the topological optimization (Jin et al. §3.5).
    pub fn with_topology_opt(mut self, on: bool) -> Self {
        self.topology_opt = on;
        self
    }
}

impl GlobalJob {
    /// `--objective` as spelled on the command line.
    fn objective_name(&self) -> String {
        crate::Choice::name(self.objective).to_string()
    }

    /// The library options these arguments ask for; `region` the faces of `--region`, as
    /// read (empty when there is none).
    pub fn options(&self, region: Vec<usize>) -> GlobalMapOptions {
        let mut search = conformap_global::FormSearchOptions::DEFAULT;
        search.starts = self.starts.unwrap_or(search.starts);
        GlobalMapOptions::DEFAULT
            .with_objective(match self.objective {
                FormObjective::Basis => Objective::BestBasisForm,
                FormObjective::Uniform => Objective::Uniform,
                FormObjective::LeastUniform => Objective::LeastUniform,
                FormObjective::Emphasize | FormObjective::DeEmphasize => Objective::Emphasize {
                    faces: region,
                    maximize: self.objective == FormObjective::Emphasize,
                },
                FormObjective::Zeros => Objective::Zeros {
                    vertices: self.zeros.clone().unwrap_or_default(),
                },
            })
            .with_search(search)
            .with_form(self.form)
            .with_root(self.root)
            .with_conjugate(match self.conjugate {
                Conjugate::Nearest => ConjugateMethod::NearestComplexStructure,
                Conjugate::GuYau => ConjugateMethod::GuYau,
            })
    }
}

impl MapJob for GlobalJob {
    fn name(&self) -> &'static str {
        "global"
    }

    fn work(&self) -> &'static str {
        "a global conformal map"
    }

    fn input(&self) -> &InputOptions {
        &self.input
    }

    fn output(&self) -> &OutputOptions {
        &self.output
    }

    fn other_inputs(&self) -> Vec<&Path> {
        self.region.as_deref().into_iter().collect()
    }

    fn check_usage(&self) -> Result<(), Failure> {
        if self.topology_opt {
            crate::jobs::global_topology::check_usage(self)?;
        }
        let regional = matches!(
            self.objective,
            FormObjective::Emphasize | FormObjective::DeEmphasize
        );
        match (
            regional,
            self.region.is_some() || self.region_faces.is_some(),
        ) {
            (true, false) => {
                return Err(Failure::Usage(format!(
                    "--objective {} needs --region FACES.txt",
                    self.objective_name()
                )))
            }
            (false, true) => {
                return Err(Failure::Usage(
                    "--region is only used with --objective emphasize or de-emphasize".to_string(),
                ))
            }
            _ => {}
        }
        match (self.objective == FormObjective::Zeros, &self.zeros) {
            (true, None) => Err(Failure::Usage(
                "--objective zeros needs --zeros V1,V2,… (0-based vertices)".to_string(),
            )),
            (false, Some(_)) => Err(Failure::Usage(
                "--zeros is only used with --objective zeros".to_string(),
            )),
            _ => Ok(()),
        }
    }

    fn peak_bytes(&self, mesh: &TriMesh) -> u64 {
        // one factorization of the Laplacian of the surface the forms live on: the input,
        // or its double covering (twice the vertices and edges)
        let copies = if mesh.boundary_loops().is_empty() && !self.topology_opt {
            1
        } else {
            2
        };
        let (v, e) = (copies * mesh.num_vertices(), copies * mesh.num_edges());
        PeakMemory::laplacian(v, e, v).bytes()
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let region = match (&self.region_faces, &self.region) {
            (Some(faces), _) => faces.clone(),
            (None, Some(path)) => read_region(path, mesh.num_faces())?,
            (None, None) => Vec::new(),
        };
        self.solve_with_region(input, region)
    }
}

impl GlobalJob {
    /// [`MapJob::solve`] with the faces of `--region` already in memory (the Python
    /// package's arrays; each checked with [`crate::jobs::param::region_face`]; empty
    /// when there is none). `--root` and `--zeros` are checked against the mesh here.
    ///
    /// # Errors
    /// Usage failures for a root or zero that is not a vertex; every failure of the map
    /// and of its metrics.
    pub fn solve_with_region(&self, input: &Input, region: Vec<usize>) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        if let Some(root) = self.root.filter(|&r| r >= mesh.num_vertices()) {
            return Err(Failure::Usage(format!(
                "--root {root} is not a vertex: the mesh has {} (0-based)",
                mesh.num_vertices()
            )));
        }
        if let Some(&v) = self
            .zeros
            .iter()
            .flatten()
            .find(|&&v| v >= mesh.num_vertices())
        {
            return Err(Failure::Usage(format!(
                "--zeros: {v} is not a vertex: the mesh has {} (0-based)",
                mesh.num_vertices()
            )));
        }
        if self.topology_opt {
            return crate::jobs::global_topology::solve(self, input);
        }
        let fail = |e: conformap_global::GlobalError| input.fail(e.into());
        let map = global_map(mesh, &self.options(region)).map_err(fail)?;
        let seamed = map.seamed_layout(mesh).map_err(fail)?;
        map_solved(mesh, &map, seamed)
    }
}

/// What `global` returns for the map `map` of `mesh` (the input, whose faces the layout's
/// corners follow) and its seamed layout.
pub(crate) fn map_solved(
    mesh: &TriMesh,
    map: &GlobalMap,
    seamed: SeamedLayout,
) -> Result<Solved, Failure> {
    {
        let t = std::time::Instant::now();
        let written = seamed.mesh.as_ref().unwrap_or(mesh);
        let base = corner_map_metrics(written, &seamed.corner_values(), &MetricsOptions::DEFAULT)?;
        let metrics_ms = map.timings_ms.metrics + crate::report::ms_since(t);
        let (folds_at_zeros, folds_outside_zeros) = map.input_folds();
        let m = &map.metrics;
        let (cf_min, cf_max) = map.conformal_factor_range();
        let metrics = MetricsSection::planar(base)
            .with("angle_distortion_all_corners_deg", m.angle_distortion_deg)
            .with(
                "angle_distortion_away_from_zeros_deg",
                m.angle_distortion_away_from_zeros_deg,
            )
            .with("uniformity_energy", m.uniformity_energy)
            .with("folds_at_zeros", folds_at_zeros)
            .with("folds_outside_zeros", folds_outside_zeros)
            .with("conformal_factor_range", [cf_min, cf_max]);
        let mut sections = serde_json::Map::new();
        sections.insert("global".to_string(), global_section(map, &seamed));
        sections.insert(
            "factorization".to_string(),
            json!({"dim": map.factor_dim, "nnz_factor": map.factor_nnz}),
        );
        let solver = SolverSection::new(0, true, Vec::new(), map.bilinear_residual, &json!({}))
            .with(
                "residual_is",
                "Riemann's bilinear relations of the period matrix (relative)",
            )
            .with("seam_residual", map.seam_residual)
            .with("harmonic_residual", map.harmonic_residual);
        let tm = &map.timings_ms;
        Ok(Solved {
            picture_domain: None,
            method: format!("holomorphic-1-form-{}", conjugate_name(map.conjugate)),
            summary: summary(mesh, map, folds_at_zeros, folds_outside_zeros),
            strict_violation: (folds_outside_zeros > 0).then(|| {
                format!("{folds_outside_zeros} folded faces lie outside the zeros' clusters")
            }),
            flat: (
                seamed.layout.iter().map(|z| [z.re, z.im, 0.0]).collect(),
                Some(seamed.tex_faces.clone()),
            ),
            uv: tex_coords(seamed),
            solver,
            param: None,
            sections,
            metrics,
            timings: StageTimings {
                assemble: tm.assemble,
                factor: tm.factor,
                solve: tm.total - tm.assemble - tm.factor - tm.metrics,
                metrics: metrics_ms,
                ..StageTimings::default()
            },
        })
    }
}

fn conjugate_name(c: ConjugateMethod) -> &'static str {
    match c {
        ConjugateMethod::GuYau => "gu-yau",
        _ => "nearest",
    }
}

/// What `-o` receives: the input's faces with per-corner texture coordinates, on the input
/// or on its refinement.
fn tex_coords(seamed: SeamedLayout) -> TexCoords {
    let uv = CornerUv {
        texcoords: seamed.texcoords,
        faces: seamed.tex_faces,
    };
    match seamed.mesh {
        Some(mesh) => TexCoords::Refined { mesh, uv },
        None => TexCoords::PerCorner(uv),
    }
}

/// The summary line.
fn summary(mesh: &TriMesh, map: &GlobalMap, at_zeros: usize, outside: usize) -> String {
    let tau = map
        .tau
        .map(|t| format!(", τ = {:.6}{:+.6}i", t.re, t.im))
        .unwrap_or_default();
    let cover = if map.double_covered {
        format!(
            " with {} boundary loop(s) (double covering of genus {})",
            map.boundaries, map.surface_genus
        )
    } else {
        String::new()
    };
    format!(
        "{} vertices, {} faces, genus {}{cover}; {}{tau}; {} zero(s), folds {at_zeros} \
         at zeros / {outside} elsewhere; mean angle distortion {:.3}° away from zeros, \
         uniformity {:.3e}",
        mesh.num_vertices(),
        mesh.num_faces(),
        map.genus,
        objective_summary(map),
        map.input_zeros().count(),
        map.metrics.angle_distortion_away_from_zeros_deg.mean,
        map.metrics.uniformity_energy,
    )
}

/// The chosen form, in words: the objective and what it reached.
fn objective_summary(map: &GlobalMap) -> String {
    let o = &map.objective;
    let of = 2 * map.surface_genus;
    let detail = if let Some(e) = &o.emphasis {
        format!(
            " (region share {:.3} of the parameter area, {:.3} of the surface's)",
            e.share, e.surface_share
        )
    } else if let Some(z) = &o.zeros {
        let rings: Vec<String> = z
            .targets
            .iter()
            .map(|t| match t.ring_distance {
                Some(d) => format!("v{} {d}", t.vertex),
                None => format!("v{} none", t.vertex),
            })
            .collect();
        format!(" (edge rings to the nearest zero: {})", rings.join(", "))
    } else if let Some(r) = o.max_min_ratio.filter(|_| o.search.is_some()) {
        format!(" (max/min uniformity {r:.2})")
    } else {
        String::new()
    };
    match o.objective.as_str() {
        "basis" => format!("basis form {} of {of}", map.form_index),
        name => format!("{name} form{detail}"),
    }
}

/// The report's `global` section.
fn global_section(map: &GlobalMap, seamed: &SeamedLayout) -> serde_json::Value {
    let n = 2 * map.surface_genus;
    let periods: Vec<Vec<[f64; 2]>> = (0..n)
        .map(|j| {
            (0..n)
                .map(|k| map.period_matrix[j * n + k])
                .map(|z| [z.re, z.im])
                .collect()
        })
        .collect();
    let zeros: Vec<_> = map
        .input_zeros()
        .map(|z| json!({"vertex": z.vertex, "multiplicity": z.multiplicity}))
        .collect();
    json!({
        "genus": map.genus,
        "boundaries": map.boundaries,
        "double_covered": map.double_covered,
        "surface_genus": map.surface_genus,
        "split_boundary_chords": map.split_edges,
        "generators": map.generator_lengths.len(),
        "generator_lengths": map.generator_lengths,
        "form": map.form_index,
        "form_uniformity": map.form_uniformity,
        "objective": map.objective,
        "conjugate": conjugate_name(map.conjugate),
        "period_matrix": periods,
        "period_matrix_layout": "rows: generators, columns: basis forms; [re, im]",
        "bilinear_residual": map.bilinear_residual,
        "bilinear_residual_gu_yau": map.bilinear_residual_gu_yau,
        "complex_structure_defect": map.complex_structure_defect,
        "tau": map.tau.map(|t| [t.re, t.im]),
        "tau_gu_yau": map.tau_gu_yau.iter().map(|t| [t.re, t.im]).collect::<Vec<_>>(),
        "zeros": zeros,
        "zero_multiplicity_sum_surface": map.zeros.multiplicity_sum,
        "negative_clusters": map.zeros.negative_clusters,
        "winding_residual": map.zeros.winding_residual,
        "seam_edges": map.seam_edges,
        "seam_residual": map.seam_residual,
        "layout_diagonal": map.layout_diagonal,
        "uv_offset": seamed.offset,
        "uv_scale": seamed.scale,
        "uv_is": "vt = (layout − uv_offset) · uv_scale: the layout fitted into the unit square",
        "timings_ms": map.timings_ms,
    })
}
