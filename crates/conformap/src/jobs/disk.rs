//! `conformap disk MESH -o OUT ...`: conformal map onto the unit disk (one boundary loop),
//! or onto the disk with circular holes (several loops, [`super::disk_holes`]).

use std::time::Instant;

use conformap_disk::{koebe_peak_bytes, unfold_disk_map, ProblemOptions};
use conformap_disk::{run_disk_method, DiskMethod, DiskOptions, DiskProblem};
use conformap_mesh::{Topology, TriMesh};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_operators::Ordering as FactorOrdering;
use conformap_sphere::{double_cover_disk_map, double_cover_peak_bytes, SphereOptions};

use crate::failure::Failure;
use crate::jobs::{disk_holes, disk_tiny};
use crate::pipeline::{disk_uv, planar_points, Input, InputOptions, MapJob, OutputOptions, Solved};
use crate::report::{
    ms_since, DoubleCoverDetail, FactorizationSection, MetricsSection, Sections, SolverDetail,
    SolverSection, StageTimings, UnfoldedSection,
};

crate::choice! {
    /// The disk-map method (see `conformap_disk::DiskMethod`).
    pub enum Method {
        /// CCEM with BFGS (Kuo et al. 2021, Algorithm 4.2), started from the harmonic measure
        /// of the boundary (Möbius-aligned) and preconditioned by the exact Hessian there: the
        /// lowest conformal energy, converged, never folded (default).
        CcemQn = "ccem-qn",
        /// CCEM steepest descent with the quadratic step (Algorithm 4.1).
        Ccem = "ccem",
        /// CEM (Yueh et al. 2017): Angenent initial map and 20 boundary iterations.
        Cem = "cem",
        /// Harmonic map to an arc-length circle (baseline; no boundary optimization).
        Harmonic = "harmonic",
        /// Through the symmetric double cover and its sphere map (Jin et al. 2004, §3.1): an
        /// independent route to the disk map, with no boundary iteration.
        DoubleCover = "double-cover",
    }
}

impl Method {
    /// The library's method (`None` for the double cover, which lives in conformap-global).
    fn library(self) -> Option<DiskMethod> {
        match self {
            Self::CcemQn => Some(DiskMethod::CcemQn),
            Self::Ccem => Some(DiskMethod::Ccem),
            Self::Cem => Some(DiskMethod::Cem),
            Self::Harmonic => Some(DiskMethod::Harmonic),
            Self::DoubleCover => None,
        }
    }

    /// The name on the command line and in reports.
    pub fn name(self) -> &'static str {
        self.library().map_or("double-cover", DiskMethod::name)
    }
}

crate::choice! {
    /// The fill-reducing ordering of the factorization of `L_II` (see
    /// `conformap_operators::Ordering`).
    pub enum FactorOrder {
        /// Nested dissection from 200,000 interior vertices, AMD below (default).
        Auto = "auto",
        /// Approximate minimum degree.
        Amd = "amd",
        /// Nested dissection (breadth-first level separators, AMD on small pieces).
        Nd = "nd",
    }
}

impl FactorOrder {
    fn library(self) -> FactorOrdering {
        match self {
            Self::Auto => FactorOrdering::Auto,
            Self::Amd => FactorOrdering::Amd,
            Self::Nd => FactorOrdering::NestedDissection,
        }
    }
}

/// Arguments of `conformap disk`.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct DiskJob {
    /// The mesh and how to read it: genus 0 with one boundary loop (the unit disk) or
    /// several (the unit disk with circular holes, by Koebe's iteration).
    pub input: InputOptions,
    /// The outputs: `-o` holds texture coordinates vt = ((u+1)/2, (v+1)/2).
    pub output: OutputOptions,
    /// Method.
    pub method: Method,
    /// With several boundary loops: the loop (0-based, as `conformap info` lists them) mapped
    /// onto the unit circle. Default: the longest.
    pub outer: Option<usize>,
    /// Iteration cap (default: CCEM 1000, CEM 20 as in the papers; several loops: Koebe
    /// sweeps, 200).
    pub max_iter: Option<usize>,
    /// Relative energy tolerance (default: CCEM 1e-9, CEM 1e-6; several loops: the circle
    /// residual ending the Koebe sweeps, 1e-4, before the polish makes the circles exact).
    pub tol: Option<f64>,
    /// Keep the folds of a `harmonic` or `cem` map (for comparison with the papers' plain
    /// algorithms) instead of repairing them: by default every method's map is flip-free
    /// (the repair is listed in the report's notes).
    pub keep_folds: bool,
    /// Fill-reducing ordering of the factorization of the interior Laplacian (one boundary
    /// loop; the map is the same to rounding, only its cost changes)
    pub ordering: FactorOrder,
}

impl DiskJob {
    /// The arguments of `conformap disk MESH -o OUTPUT` with every option at its default.
    pub fn new(input: InputOptions, output: OutputOptions) -> Self {
        Self {
            input,
            output,
            method: Method::CcemQn,
            outer: None,
            max_iter: None,
            tol: None,
            keep_folds: false,
            ordering: FactorOrder::Auto,
        }
    }

    /// With the method `method`.
    pub fn with_method(mut self, method: Method) -> Self {
        self.method = method;
        self
    }

    /// With at most `n` iterations (`None`: the method's default).
    pub fn with_max_iter(mut self, n: Option<usize>) -> Self {
        self.max_iter = n;
        self
    }

    /// With the stopping tolerance `tol` (`None`: the method's default).
    pub fn with_tol(mut self, tol: Option<f64>) -> Self {
        self.tol = tol;
        self
    }
}

/// The refusal of a mesh in several pieces, with what `--repair` would do (the same code as
/// the repair: a triangle soup is welded whole, not cut down to its largest face).
fn components_failure(mesh: &TriMesh, components: usize) -> Failure {
    let e = conformap_disk::DiskError::WrongTopology {
        found: Topology::SeveralComponents { components },
    };
    let actions = crate::jobs::info::available_repairs(mesh);
    Failure::BadInput(
        e.to_string(),
        Some(format!(
            "`conformap atlas` charts all {components} components as they are; or rerun \
             with --repair, which would do this: {}; `conformap info --repair MESH` describes \
             the result",
            actions.join("; ")
        )),
    )
}

/// Several boundary loops on a connected genus-0 mesh: the disk with circular holes.
fn has_holes(mesh: &TriMesh) -> bool {
    matches!(mesh.topology(), Topology::MultiplyConnected { .. })
}

impl MapJob for DiskJob {
    fn name(&self) -> &'static str {
        "disk"
    }

    fn work(&self) -> &'static str {
        "a disk map"
    }

    fn input(&self) -> &InputOptions {
        &self.input
    }

    fn output(&self) -> &OutputOptions {
        &self.output
    }

    fn check_usage(&self) -> Result<(), Failure> {
        match self.tol {
            Some(tol) if !(tol.is_finite() && tol >= 0.0) => Err(Failure::Usage(format!(
                "--tol must be a finite number ≥ 0, got {tol}"
            ))),
            _ => Ok(()),
        }
    }

    fn peak_bytes(&self, mesh: &TriMesh) -> u64 {
        match self.method.library() {
            _ if has_holes(mesh) => koebe_peak_bytes(mesh),
            Some(method) => method.peak_bytes(mesh),
            None => double_cover_peak_bytes(mesh),
        }
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let loops = mesh.boundary_loops().len();
        if let Some(k) = self.outer.filter(|&k| k >= loops.max(1)) {
            return Err(Failure::Usage(format!(
                "--outer {k}: the mesh has {loops} boundary loop(s), numbered from 0 \
                 (`conformap info` lists them)"
            )));
        }
        if let Topology::SeveralComponents { components } = mesh.topology() {
            return Err(input.fail(components_failure(mesh, components)));
        }
        let solved = if has_holes(mesh) {
            let options = disk_holes::koebe_options(self.outer, self.max_iter, self.tol);
            disk_holes::solve(&options, input)
        } else if mesh.topology() == Topology::Disk && disk_tiny::has_no_interior(mesh) {
            disk_tiny::solve(input)
        } else {
            match self.method.library() {
                Some(method) => self.solve_disk(input, method),
                None => self.solve_double_cover(input),
            }
        }?;
        Ok(self.with_ignored(mesh, solved))
    }
}

impl DiskJob {
    /// The options given that the map of `mesh` does not use (each with why).
    pub fn ignored_options(&self, mesh: &TriMesh) -> Vec<String> {
        let mut ignored = Vec::new();
        if has_holes(mesh) {
            if self.method != Method::CcemQn {
                ignored.push(format!(
                    "--method {}: several boundary loops are mapped by Koebe's iteration",
                    self.method.name()
                ));
            }
            if self.ordering != FactorOrder::Auto {
                ignored.push(
                    "--ordering: several boundary loops are mapped by Koebe's iteration"
                        .to_string(),
                );
            }
            return ignored;
        }
        if disk_tiny::has_no_interior(mesh) {
            if self.method != Method::CcemQn || self.max_iter.is_some() || self.tol.is_some() {
                ignored.push(
                    "--method, --max-iter, --tol: no interior vertex, nothing to iterate"
                        .to_string(),
                );
            }
            return ignored;
        }
        if self.keep_folds && self.method == Method::CcemQn {
            ignored.push("--keep-folds: ccem-qn never folds (only harmonic and cem do)".into());
        }
        let iterates = matches!(self.method, Method::CcemQn | Method::Ccem | Method::Cem);
        if !iterates && (self.max_iter.is_some() || self.tol.is_some()) {
            ignored.push(format!(
                "--max-iter, --tol: {} does not iterate",
                self.method.name()
            ));
        }
        ignored
    }

    /// `solved` with the ignored options said in its summary (printed on stderr) and in the
    /// report (`solver.ignored_options`).
    fn with_ignored(&self, mesh: &TriMesh, mut solved: Solved) -> Solved {
        let ignored = self.ignored_options(mesh);
        if !ignored.is_empty() {
            solved.summary = format!("{}; ignored: {}", solved.summary, ignored.join("; "));
            solved.solver = solved.solver.with_ignored_options(ignored);
        }
        solved
    }
}

impl DiskJob {
    /// One boundary loop, a method of conformap-disk.
    fn solve_disk(&self, input: &Input, method: DiskMethod) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let fail = |e: conformap_disk::DiskError| input.fail(e.into());
        let problem_options = ProblemOptions::DEFAULT.with_ordering(self.ordering.library());
        let mut problem = DiskProblem::with_options(mesh, &problem_options).map_err(fail)?;
        let options = DiskOptions::DEFAULT
            .with_max_iter(self.max_iter)
            .with_tol(self.tol)
            .with_keep_folds(self.keep_folds);
        let result = run_disk_method(&mut problem, method, &options).map_err(fail)?;
        let stats = problem.interior_factor().stats().clone();
        let t = Instant::now();
        let metrics = planar_map_metrics(mesh, &result.map, &MetricsOptions::default())?;
        let s = &result.report;
        let summary = format!(
            "{} vertices, {} faces; {} in {} iterations{}; E_C = {:.6e}, mean angle \
             distortion {:.3}°, flipped faces {}",
            mesh.num_vertices(),
            mesh.num_faces(),
            match &s.fallback_from {
                Some(asked) => format!("{} (fallback: {asked} would fold)", s.method),
                None => s.method.clone(),
            },
            s.iterations,
            stop_words(s),
            metrics.conformal_energy,
            metrics.angle_distortion_deg.mean,
            metrics.flipped_faces,
        );
        let sections = Sections {
            factorization: Some(FactorizationSection::Interior {
                interior_vertices: stats.n,
                nnz_factor: stats.nnz_factor,
                ordering: stats.ordering,
            }),
            ..Sections::default()
        };
        Ok(Solved {
            picture_domain: None,
            method: s.method.clone(),
            uv: disk_uv(&result.map).into(),
            flat: (planar_points(&result.map), None),
            solver: SolverSection::new(s.summary(), SolverDetail::Disk(s.clone())),
            param: None,
            sections,
            metrics: MetricsSection::planar(metrics),
            timings: StageTimings {
                assemble: s.timings_ms.assemble,
                factor: s.timings_ms.factor,
                analyse: stats.analyse_ms,
                solve: s.timings_ms.solve,
                metrics: ms_since(t),
                ..StageTimings::default()
            },
            strict_violation: match &s.fallback_from {
                Some(asked) => Some(format!(
                    "{asked} would fold; the {} map was returned",
                    s.method
                )),
                None => (!s.converged).then(|| {
                    format!(
                        "{} did not converge in {} iterations",
                        s.method, s.iterations
                    )
                }),
            },
            summary,
        })
    }

    /// One boundary loop, through the double cover and its sphere map.
    fn solve_double_cover(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        let out = double_cover_disk_map(mesh, &SphereOptions::DEFAULT)
            .map_err(|e| input.fail(e.into()))?;
        let t = Instant::now();
        let mut metrics = planar_map_metrics(mesh, &out.map, &MetricsOptions::default())?;
        let mut map = out.map.clone();
        // the covering's map can fold crowded faces (maze, igea_open): the disk crate's
        // flip-free guard repairs it, as for every other method
        let mut unfolded = None;
        if metrics.flipped_faces > 0 && !self.keep_folds {
            let fail = |e: conformap_disk::DiskError| input.fail(e.into());
            let problem =
                DiskProblem::with_options(mesh, &ProblemOptions::DEFAULT).map_err(fail)?;
            let u = unfold_disk_map(&problem, &map).map_err(fail)?;
            map = u.map.clone();
            metrics = planar_map_metrics(mesh, &map, &MetricsOptions::default())?;
            unfolded = Some(UnfoldedSection {
                flipped_before: u.flipped_before,
                flipped_after: u.flipped_after,
                repaired_gaps: u.repaired_gaps,
                gap_floor: u.gap_floor,
            });
        }
        let r = &out.report;
        let summary = format!(
            "{} vertices, {} faces; double cover ({} vertices) and its sphere map; E_C = \
             {:.6e}, mean angle distortion {:.3}°, flipped faces {}",
            mesh.num_vertices(),
            mesh.num_faces(),
            r.cover_vertices,
            metrics.conformal_energy,
            metrics.angle_distortion_deg.mean,
            metrics.flipped_faces,
        );
        let st = &r.sphere.timings_ms;
        Ok(Solved {
            picture_domain: None,
            method: "double-cover".to_string(),
            uv: disk_uv(&map).into(),
            flat: (planar_points(&map), None),
            // a direct method: one stage per sphere-map stage; the residual is Angenent's
            solver: SolverSection::new(
                r.summary(),
                SolverDetail::DoubleCover(DoubleCoverDetail {
                    report: r.clone(),
                    energy_history_is: "mean chord-angle distortion (degrees) of the \
                                        covering's sphere map after each stage",
                    unfolded,
                }),
            ),
            param: None,
            sections: Sections::default(),
            metrics: MetricsSection::planar(metrics),
            timings: StageTimings {
                assemble: st.assemble,
                factor: st.factor,
                solve: r.time_ms - st.assemble - st.factor,
                metrics: ms_since(t),
                ..StageTimings::default()
            },
            strict_violation: None,
            summary,
        })
    }
}

/// How a disk method's iterations ended, for the summary line: `" (converged)"`, or why
/// not when the method said (the iteration cap, a stalled line search), with the option
/// that changes it.
fn stop_words(s: &conformap_disk::SolverReport) -> String {
    if s.converged {
        " (converged)".to_string()
    } else if s.notes.iter().any(|n| n == "stopped at the iteration cap") {
        let qn = if s.method == "ccem" {
            "; the default ccem-qn converges in far fewer"
        } else {
            ""
        };
        format!(" (stopped at the iteration cap: --max-iter raises it{qn})")
    } else if let Some(n) = s.notes.iter().find(|n| n.starts_with("stopped:")) {
        format!(" ({n})")
    } else {
        String::new()
    }
}
