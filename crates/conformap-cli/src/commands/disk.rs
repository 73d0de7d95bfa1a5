//! `conformap disk MESH -o OUT ...`: conformal map onto the unit disk.

use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::{Args, ValueEnum};
use conformap_disk::{
    run_disk_method, DiskMethod, DiskOptions, DiskProblem, FactorOrdering, ProblemOptions,
};
use conformap_io::{RawMesh, SourceInfo};
use conformap_mesh::{RepairLog, RepairOptions, TriMesh};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use serde_json::json;

use crate::commands::write_json;
use crate::failure::{repair_failure, Failure};
use crate::report::{ms_since, InputInfo, StageTimings};

/// The disk-map method (see `conformap_disk::DiskMethod`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Method {
    /// CCEM with BFGS (Kuo et al. 2021, Algorithm 4.2), started from the harmonic measure
    /// of the boundary (Möbius-aligned) and preconditioned by the exact Hessian there: the
    /// lowest conformal energy, converged, never folded (default).
    #[value(name = "ccem-qn")]
    CcemQn,
    /// CCEM steepest descent with the quadratic step (Algorithm 4.1).
    Ccem,
    /// CEM (Yueh et al. 2017): Angenent initial map and 20 boundary iterations.
    Cem,
    /// Harmonic map to an arc-length circle (baseline; no boundary optimization).
    Harmonic,
}

impl Method {
    fn library(self) -> DiskMethod {
        match self {
            Self::CcemQn => DiskMethod::CcemQn,
            Self::Ccem => DiskMethod::Ccem,
            Self::Cem => DiskMethod::Cem,
            Self::Harmonic => DiskMethod::Harmonic,
        }
    }

    fn name(self) -> &'static str {
        self.library().name()
    }
}

/// The fill-reducing ordering of the factorization of `L_II` (see
/// `conformap_disk::FactorOrdering`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum OrderingArg {
    /// Nested dissection from 200,000 interior vertices, AMD below (default).
    Auto,
    /// Approximate minimum degree.
    Amd,
    /// Nested dissection (breadth-first level separators, AMD on small pieces).
    Nd,
}

impl OrderingArg {
    fn library(self) -> FactorOrdering {
        match self {
            Self::Auto => FactorOrdering::Auto,
            Self::Amd => FactorOrdering::Amd,
            Self::Nd => FactorOrdering::NestedDissection,
        }
    }
}

/// Arguments of `conformap disk`.
#[derive(Debug, Args)]
pub struct DiskArgs {
    /// The mesh (.obj, .gltf, .glb): genus 0 with one boundary loop (the unit disk) or
    /// several (the unit disk with circular holes, by Koebe's iteration).
    pub mesh: PathBuf,
    /// Output mesh with texture coordinates vt = ((u+1)/2, (v+1)/2) (.obj, .gltf, .glb).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Method.
    #[arg(long, value_enum, default_value_t = Method::CcemQn)]
    pub method: Method,
    /// With several boundary loops: the loop (0-based, as `conformap info` lists them) mapped
    /// onto the unit circle. Default: the longest.
    #[arg(long, value_name = "K")]
    pub outer: Option<usize>,
    /// Iteration cap (default: CCEM 1000, CEM 20 as in the papers; several loops: Koebe
    /// sweeps, 200).
    #[arg(long)]
    pub max_iter: Option<usize>,
    /// Relative energy tolerance (default: CCEM 1e-9, CEM 1e-6; several loops: the circle
    /// residual ending the Koebe sweeps, 1e-4, before the polish makes the circles exact).
    #[arg(long)]
    pub tol: Option<f64>,
    /// Also write the raw map as a flat mesh (u, v, 0).
    #[arg(long)]
    pub flat: Option<PathBuf>,
    /// Write a JSON report here.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Keep the folds of a `harmonic` or `cem` map (for comparison with the papers' plain
    /// algorithms) instead of repairing them: by default every method's map is flip-free
    /// (the repair is listed in the report's notes).
    #[arg(long)]
    pub keep_folds: bool,
    /// Exit with code 3 (writing nothing) if the solver did not converge.
    #[arg(long)]
    pub strict: bool,
    /// Repair the input first: drop duplicate faces, keep the largest component, orient the
    /// faces consistently, drop unreferenced vertices. Outputs then hold the repaired mesh
    /// (vt index k belongs to repaired vertex k); the report lists the repairs.
    #[arg(long)]
    pub repair: bool,
    /// With --repair: write the vertex map here, one line per output vertex holding its
    /// 0-based input vertex.
    #[arg(long, requires = "repair")]
    pub vertex_map: Option<PathBuf>,
    /// Refuse (exit 1, nothing computed) if the estimated peak memory exceeds SIZE (bytes,
    /// or with K/M/G/T, e.g. 4G). Default: the memory available (Linux MemAvailable, within
    /// the cgroup limit); no check where that is unknown.
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<u64>,
    /// Fill-reducing ordering of the factorization of the interior Laplacian (one boundary
    /// loop; the map is the same to rounding, only its cost changes)
    #[arg(long, value_enum, default_value_t = OrderingArg::Auto)]
    pub ordering: OrderingArg,
}

/// A mesh to map: as read, or repaired.
pub struct Input {
    /// The validated mesh.
    pub mesh: TriMesh,
    /// Where it came from.
    pub source: SourceInfo,
    /// What `--repair` changed (`None` without `--repair`).
    pub repairs: Option<RepairLog>,
}

/// Reads `path`; with `repair`, reads it raw, applies every repair of
/// [`conformap_mesh::repair`] and validates the result. Errors name input elements and
/// file places either way.
pub fn read_input(path: &Path, repair: bool) -> Result<Input, Failure> {
    if !repair {
        let loaded = conformap_io::read_mesh(path)?;
        return Ok(Input {
            mesh: loaded.mesh,
            source: loaded.source,
            repairs: None,
        });
    }
    repair_input(conformap_io::read_raw_mesh(path)?)
}

/// Applies every repair of [`conformap_mesh::repair`] to `raw` and validates the result;
/// errors name input elements and their file places.
pub fn repair_input(mut raw: RawMesh) -> Result<Input, Failure> {
    let fixed = conformap_mesh::repair(&raw.positions, &raw.faces, &RepairOptions::DEFAULT)
        .map_err(|e| repair_failure(&raw, e))?;
    raw.positions = Vec::new();
    raw.faces = Vec::new();
    let log = fixed.log;
    let mesh = TriMesh::try_new(fixed.positions, fixed.faces)
        .map_err(|e| Failure::from(raw.invalid_mesh(log.to_input_error(e))))?;
    Ok(Input {
        mesh,
        source: raw.source,
        repairs: Some(log),
    })
}

/// The `repairs` object of a report: what changed, and the sizes of the maps back to the
/// input.
pub fn repairs_json(log: &RepairLog) -> serde_json::Value {
    json!({
        "applied": log.actions(),
        "input_vertices": log.input_vertices,
        "input_faces": log.input_faces,
        "duplicate_faces": log.duplicate_faces,
        "components": log.components,
        "component_faces_dropped": log.component_faces_dropped,
        "component_vertices_dropped": log.component_vertices_dropped,
        "flipped_faces": log.flipped_faces,
        "unreferenced_vertices": log.unreferenced_vertices,
        "vertex_map": {
            "repaired_to_input": log.vertex_to_input.len(),
            "input_to_repaired": log.input_to_vertex.len(),
        },
        "face_map": { "repaired_to_input": log.face_to_input.len() },
    })
}

/// Runs `conformap disk`.
pub fn run(args: &DiskArgs) -> Result<(), Failure> {
    let t_all = Instant::now();
    if let Some(tol) = args.tol {
        if !(tol.is_finite() && tol >= 0.0) {
            return Err(Failure::Usage(format!(
                "--tol must be a finite number ≥ 0, got {tol}"
            )));
        }
    }
    for out in std::iter::once(&args.output).chain(args.flat.iter()) {
        conformap_io::Format::from_path(out).map_err(|e| Failure::Usage(e.to_string()))?;
    }
    let in_mesh_file = |f: Failure| f.in_file(&args.mesh);
    let memory = MemoryCheck::before_reading(&args.mesh, args.max_memory).map_err(in_mesh_file)?;
    let t = Instant::now();
    let input = read_input(&args.mesh, args.repair)?;
    let mesh = &input.mesh;
    let read_ms = ms_since(t);
    let memory = memory
        .before_solving(mesh, args.method)
        .map_err(in_mesh_file)?;
    if let Some(done) = super::disk_holes::dispatch(args, &input, read_ms, memory, t_all) {
        // genus 0 with several boundary loops: the disk with circular holes
        return done;
    }

    let in_file = |e: conformap_disk::DiskError| Failure::from(e).in_file(&args.mesh);
    let problem_options = ProblemOptions::DEFAULT.with_ordering(args.ordering.library());
    let mut problem = DiskProblem::with_options(mesh, &problem_options).map_err(in_file)?;
    let options = DiskOptions::DEFAULT
        .with_max_iter(args.max_iter)
        .with_tol(args.tol)
        .with_keep_folds(args.keep_folds);
    let result = run_disk_method(&mut problem, args.method.library(), &options).map_err(in_file)?;
    let factor_stats = problem.interior_factor().stats().clone();
    let analyse_ms = factor_stats.analyse_ms;
    if args.strict && !result.report.converged {
        return Err(Failure::Numerical(format!(
            "{} did not converge in {} iterations (--strict); nothing written",
            args.method.name(),
            result.report.iterations
        )));
    }
    let t = Instant::now();
    let metrics = planar_map_metrics(mesh, &result.map, &MetricsOptions::default())
        .map_err(|e| Failure::Numerical(e.to_string()))?;
    let metrics_ms = ms_since(t);

    let t = Instant::now();
    let uv: Vec<[f64; 2]> = result
        .map
        .iter()
        .map(|z| [(z.re + 1.0) / 2.0, (z.im + 1.0) / 2.0])
        .collect();
    // a repaired mesh no longer has the file's vertex layout
    let unchanged = input.repairs.as_ref().is_none_or(|log| !log.changed());
    let source = unchanged.then_some(&input.source);
    conformap_io::write_mesh_with_uv(&args.output, mesh, &uv, source)?;
    if let Some(flat) = &args.flat {
        let pts: Vec<[f64; 3]> = result.map.iter().map(|z| [z.re, z.im, 0.0]).collect();
        conformap_io::write_flat(flat, &pts, mesh.faces())?;
    }
    if let (Some(path), Some(log)) = (&args.vertex_map, &input.repairs) {
        write_vertex_map(path, log)?;
    }
    let write_ms = ms_since(t);

    let s = &result.report;
    let timings = StageTimings {
        read: read_ms,
        assemble: s.timings_ms.assemble,
        factor: s.timings_ms.factor,
        analyse: analyse_ms,
        solve: s.timings_ms.solve,
        metrics: metrics_ms,
        write: write_ms,
        total: ms_since(t_all),
    };
    let mut report = json!({
        "conformap_version": env!("CARGO_PKG_VERSION"),
        "command": "disk",
        "method": args.method.name(),
        "input": InputInfo::new(&args.mesh, mesh),
        "solver": s,
        "factorization": {
            "ordering": factor_stats.ordering,
            "interior_vertices": factor_stats.n,
            "nnz_factor": factor_stats.nnz_factor,
        },
        "metrics": metrics,
        "memory": memory.to_json(),
        "timings_ms": timings,
    });
    if let Some(log) = &input.repairs {
        report["repairs"] = repairs_json(log);
    }
    if let Some(path) = &args.report {
        write_json(path, &report)?;
    }
    if let Some(log) = input.repairs.as_ref().filter(|l| l.changed()) {
        eprintln!(
            "{}: repaired: {}",
            args.mesh.display(),
            log.actions().join("; ")
        );
    }
    eprintln!(
        "{}: {} vertices, {} faces; {} in {} iterations{}; E_C = {:.6e}, mean angle distortion \
         {:.3}°, flipped faces {}; {:.0} ms",
        args.mesh.display(),
        mesh.num_vertices(),
        mesh.num_faces(),
        args.method.name(),
        s.iterations,
        if s.converged { " (converged)" } else { "" },
        metrics.conformal_energy,
        metrics.angle_distortion_deg.mean,
        metrics.flipped_faces,
        timings.total
    );
    Ok(())
}

/// Writes the repaired → input vertex map, one 0-based input vertex per line.
pub(crate) fn write_vertex_map(path: &Path, log: &RepairLog) -> Result<(), Failure> {
    let mut text = String::with_capacity(8 * log.vertex_to_input.len());
    for v in &log.vertex_to_input {
        text.push_str(&v.to_string());
        text.push('\n');
    }
    std::fs::write(path, text)
        .map_err(|e| Failure::input(format!("cannot write {}: {e}", path.display())))
}

/// The memory check of a run: the estimates, the limit they were held against, and (at
/// the end of the run) the measured peak.
#[derive(Debug, Clone, Copy)]
pub struct MemoryCheck {
    /// [`READ_BYTES_PER_FILE_BYTE`] × the file size.
    pub read_estimate: u64,
    /// [`estimate_peak_bytes`] of the mesh read.
    pub estimate: u64,
    /// The limit, and where it came from; `None` when unknown (no check).
    pub limit: Option<(u64, &'static str)>,
}

impl MemoryCheck {
    /// Checks that reading `path` fits in `max_memory` or (without it) the memory
    /// available now, before anything is read.
    pub fn before_reading(path: &Path, max_memory: Option<u64>) -> Result<Self, Failure> {
        let limit = match max_memory {
            Some(m) => Some((m, "--max-memory")),
            None => available_memory(),
        };
        let size = std::fs::metadata(path).map_or(0, |m| m.len());
        let check = Self {
            read_estimate: READ_BYTES_PER_FILE_BYTE.saturating_mul(size),
            estimate: 0,
            limit,
        };
        check.refuse_above(
            check.read_estimate,
            &format!("reading this {} file", human_bytes(size)),
        )?;
        Ok(check)
    }

    /// Estimates the peak memory of `disk` with `method` on `mesh` and refuses the run,
    /// before anything is assembled or factored, if it is above the limit.
    pub fn before_solving(mut self, mesh: &TriMesh, method: Method) -> Result<Self, Failure> {
        let loops = mesh.boundary_loops();
        let boundary = loops.iter().map(Vec::len).max().unwrap_or(0);
        let (v, e) = (mesh.num_vertices(), mesh.num_edges());
        // CCEM may form the dense Schur complement; CEM keeps more per vertex
        let dense = matches!(method, Method::Ccem | Method::CcemQn);
        let extra = match method {
            Method::Cem => CEM_EXTRA_BYTES_PER_VERTEX * v as f64,
            _ => 0.0,
        };
        let estimate = estimate_peak_bytes(v, e, boundary, dense) as f64 + extra;
        self.estimate = (estimate as u64).max(self.read_estimate);
        let what = format!(
            "a disk map of this mesh ({} vertices, {} faces)",
            mesh.num_vertices(),
            mesh.num_faces()
        );
        self.refuse_above(self.estimate, &what)?;
        Ok(self)
    }

    fn refuse_above(&self, estimate: u64, what: &str) -> Result<(), Failure> {
        match self.limit {
            Some((limit, from)) if estimate > limit => Err(Failure::BadInput(
                format!(
                    "{what} needs an estimated {} at peak, more than the {} allowed \
                     ({from}); nothing was computed",
                    human_bytes(estimate),
                    human_bytes(limit)
                ),
                Some(
                    "free memory or use a larger machine, or decimate the mesh; if the \
                     estimate is too cautious, --max-memory SIZE raises the limit"
                        .to_string(),
                ),
            )),
            _ => Ok(()),
        }
    }

    /// The `memory` object of a report. `limit_bytes` and `peak_rss_bytes` are measurements
    /// of the machine and the run (like timings), not of the input.
    pub(crate) fn to_json(self) -> serde_json::Value {
        json!({
            "estimated_peak_bytes": self.estimate,
            "limit_bytes": self.limit.map(|l| l.0),
            "limit_source": self.limit.map(|l| l.1),
            "peak_rss_bytes": peak_rss_bytes(),
        })
    }
}

/// `1.23 GiB`, `45.6 MiB`, `789 KiB`.
fn human_bytes(b: u64) -> String {
    let b = b as f64;
    if b >= 1073741824.0 {
        format!("{:.2} GiB", b / 1073741824.0)
    } else if b >= 1048576.0 {
        format!("{:.1} MiB", b / 1048576.0)
    } else {
        format!("{:.0} KiB", b / 1024.0)
    }
}

/// Peak memory of reading a file per byte of it (the bytes, the text `tobj` parses, its
/// and our index arrays). Measured: 590 MiB for the 84 MB OBJ of a 2M-face grid (7.4×).
pub const READ_BYTES_PER_FILE_BYTE: u64 = 8;
/// Fixed cost of the process (binary, allocator, threads). Measured: 5.4 MiB in all for
/// woody.obj (694 vertices) with the release binary; a debug binary's code pages and the
/// two rayon workers' stacks add about 2 MiB (spothead.obj: 13.8–14.5 MiB peak in debug
/// runs), so 10 MiB.
const BASE_BYTES: f64 = 10.0 * 1048576.0;
/// Bytes per vertex for everything but the factor and the Laplacian's entries: mesh,
/// half-edges, assembly, intrinsic Delaunay triangulation, blocks, maps, metrics.
const BYTES_PER_VERTEX: f64 = 500.0;
/// Bytes per `n log₂ n` (n = interior vertices) for the Cholesky factor of `L_II` under AMD
/// (measured nnz(L) = 3.4 n log₂ n on hand.obj, 4.1 on igea_open.obj; 8-byte values plus
/// structure and workspace) and what grows with it.
const FACTOR_BYTES_PER_NLOGN: f64 = 60.0;
/// What CEM keeps beyond CCEM and the harmonic map, per vertex, including the repair of a
/// folded CEM map (measured: 490 on spothead.obj, 520 on hand.obj, 680 on igea_open.obj;
/// maze.obj, whose CEM map folds and is repaired, needed 720).
const CEM_EXTRA_BYTES_PER_VERTEX: f64 = 1000.0;
/// At most this much for a dense boundary-sized block (CCEM's Schur complement).
const DENSE_MAX_BYTES: f64 = 512.0 * 1048576.0;

/// Estimated peak resident memory (bytes) of `disk` on a mesh with `vertices` vertices,
/// `edges` edges and a boundary loop of `boundary` vertices: a linear part (mesh, Laplacian
/// with `vertices + 2 edges` entries of 16 bytes and the analysed pattern of its interior
/// block beside it, intrinsic triangulation, maps) plus the
/// Cholesky factor of the interior block, whose fill under AMD grows like `n log n` on
/// surface meshes, plus, for a method that forms one (`dense_boundary`), a dense
/// boundary-sized block (`8 n_B²` bytes, at most 512 MiB).
///
/// Calibrated against the measured peak (VmHWM) of CCEM-QN and the harmonic map (CEM adds
/// [`CEM_EXTRA_BYTES_PER_VERTEX`]): 1.3× to 1.5× of it on the disk meshes of
/// `../shared/meshes` (4.5k to 130k vertices) and on a generated 2M-face grid (peak
/// 1.42 GiB); `memory_estimate_bounds_the_measured_peak` in `tests/resources.rs`
/// re-measures it.
pub fn estimate_peak_bytes(
    vertices: usize,
    edges: usize,
    boundary: usize,
    dense_boundary: bool,
) -> u64 {
    let n = vertices as f64;
    let interior = vertices.saturating_sub(boundary).max(2) as f64;
    let laplacian_nnz = n + 2.0 * edges as f64;
    // the Laplacian's entries (16 bytes each), and as many again for the pattern of `L_II`
    // that the symbolic analysis holds while the assembly runs beside it
    let linear = BYTES_PER_VERTEX * n + 2.0 * 16.0 * laplacian_nnz;
    let factor = FACTOR_BYTES_PER_NLOGN * interior * interior.log2();
    let dense = if dense_boundary {
        (8.0 * (boundary as f64).powi(2)).min(DENSE_MAX_BYTES)
    } else {
        0.0
    };
    (BASE_BYTES + linear + factor + dense) as u64
}

/// The memory this process may still use: `MemAvailable` of `/proc/meminfo`, lowered to
/// what the cgroup (v2) limit leaves, if there is one. `None` where unknown.
fn available_memory() -> Option<(u64, &'static str)> {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok()?;
    let kib = meminfo
        .lines()
        .find_map(|l| l.strip_prefix("MemAvailable:"))?
        .split_whitespace()
        .next()?
        .parse::<u64>()
        .ok()?;
    let avail = kib.saturating_mul(1024);
    let read = |p: &str| -> Option<u64> { std::fs::read_to_string(p).ok()?.trim().parse().ok() };
    match (
        read("/sys/fs/cgroup/memory.max"),
        read("/sys/fs/cgroup/memory.current"),
    ) {
        (Some(max), Some(current)) if max.saturating_sub(current) < avail => {
            Some((max.saturating_sub(current), "cgroup memory.max"))
        }
        _ => Some((avail, "MemAvailable")),
    }
}

/// Peak resident set size of this process (Linux `VmHWM`), `None` where unknown.
fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let kib = status
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))?
        .split_whitespace()
        .next()?
        .parse::<u64>()
        .ok()?;
    Some(kib * 1024)
}

/// Parses `4G`, `512M`, `1.5GiB`, `100000` (bytes; K, M, G, T are powers of 1024).
pub fn parse_size(s: &str) -> Result<u64, String> {
    let t = s.trim();
    let lower = t.to_ascii_lowercase();
    let body = lower
        .strip_suffix("ib")
        .or_else(|| lower.strip_suffix('b'))
        .unwrap_or(&lower);
    let (num, shift) = match body.chars().last() {
        Some('k') => (&body[..body.len() - 1], 10),
        Some('m') => (&body[..body.len() - 1], 20),
        Some('g') => (&body[..body.len() - 1], 30),
        Some('t') => (&body[..body.len() - 1], 40),
        _ => (body, 0),
    };
    let value: f64 = num
        .trim()
        .parse()
        .map_err(|_| format!("`{t}` is not a size (e.g. 4G, 512M, 1000000)"))?;
    let bytes = value * 2f64.powi(shift);
    if !(bytes.is_finite() && bytes >= 1.0) || bytes > u64::MAX as f64 {
        return Err(format!("`{t}` is not a positive size"));
    }
    Ok(bytes as u64)
}
