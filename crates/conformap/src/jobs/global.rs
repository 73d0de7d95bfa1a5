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
    global_map, global_map_peak_bytes, topology_opt_peak_bytes, ConjugateMethod, GlobalMapOptions,
    Objective, TopologyOptOptions,
};
use conformap_mesh::TriMesh;

use crate::failure::Failure;
use crate::jobs::param::{read_region, region_face};
use crate::jobs::{global_solved, global_topology};
use crate::pipeline::{Input, InputOptions, MapJob, OutputOptions, Solved};

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
            check_topology_usage(self)?;
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
        if self.topology_opt {
            topology_opt_peak_bytes(mesh)
        } else {
            global_map_peak_bytes(mesh)
        }
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let region = match (&self.region_faces, &self.region) {
            // checked again here: a batch template's faces meet each input's mesh only now
            (Some(faces), _) => faces
                .iter()
                .enumerate()
                .map(|(k, &f)| region_face(f, mesh.num_faces(), &format!("region[{k}]")))
                .collect::<Result<_, _>>()?,
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
            return global_topology::solve(&topology_options(self), input);
        }
        let fail = |e: conformap_global::GlobalError| input.fail(e.into());
        let map = global_map(mesh, &self.options(region)).map_err(|e| match (&e, self.form) {
            // a usage error with the number given (2g is known once the mesh is read)
            (
                conformap_global::GlobalError::InvalidOption {
                    name: "form",
                    reason,
                },
                Some(k),
            ) => Failure::Usage(match basis_forms(mesh) {
                Some(n) => format!("--form {k}: {reason}, {n} on this mesh (0..={})", n - 1),
                None => format!("--form {k}: {reason}"),
            }),
            _ => fail(e),
        })?;
        let seamed = map.seamed_layout(mesh).map_err(fail)?;
        global_solved::map_solved(mesh, &map, seamed)
    }
}

/// The flags `--topology-opt` does not combine with (exit 2).
fn check_topology_usage(args: &GlobalJob) -> Result<(), Failure> {
    let conflict = if args.objective != FormObjective::Uniform {
        Some("--objective (the loop needs the most uniform form)")
    } else if args.form.is_some() {
        Some("--form")
    } else {
        None
    };
    if let Some(flag) = conflict {
        return Err(Failure::Usage(format!(
            "--topology-opt does not combine with {flag}"
        )));
    }
    match args.slit_length {
        Some(f) if !(f > 0.0 && f < 1.0) => Err(Failure::Usage(format!(
            "--slit-length {f}: must lie in (0, 1) (a fraction of the bounding-box diagonal)"
        ))),
        _ => Ok(()),
    }
}

/// The options `args` ask for.
fn topology_options(args: &GlobalJob) -> TopologyOptOptions {
    let mut o = TopologyOptOptions::DEFAULT;
    let mut global = o.global.clone().with_root(args.root);
    global = global.with_conjugate(args.options(Vec::new()).conjugate);
    if let Some(s) = args.starts {
        let search = global.search.with_starts(s);
        global = global.with_search(search);
    }
    o = o.with_global(global);
    if let Some(n) = args.max_slits {
        o = o.with_max_slits(n);
    }
    if let Some(f) = args.slit_length {
        o = o.with_slit_length(f);
    }
    o
}

/// The number of basis forms of `mesh` (connected, orientable): 2g on a closed surface of
/// genus g; with b ≥ 1 boundary loops the forms are those of the double (genus 2g + b − 1),
/// 2(2g + b − 1). `None` when the genus is unknown or the count would be 0.
fn basis_forms(mesh: &TriMesh) -> Option<usize> {
    let g = usize::try_from(mesh.genus()?).ok()?;
    let b = mesh.boundary_loops().len();
    let n = if b == 0 { 2 * g } else { 2 * (2 * g + b - 1) };
    (n > 0).then_some(n)
}
