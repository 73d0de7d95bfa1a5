//! One timed run of the `conformap disk` pipeline, stage by stage, and the table rows.
//!
//! Stages, as in the `timings_ms` of `conformap disk --report`:
//! - `read`: reading and validating the file (ms, and in brackets MB/s of the file);
//! - `assemble`: the cotangent Laplacian and its blocks;
//! - `analyse`: the symbolic factorization of `L_II` (fill-reducing ordering, structure);
//! - `factor`: its numeric factorization;
//! - `iterate`: everything the method does after that — for CCEM: forming the Schur
//!   complement (`schur`), the starting boundary (`start`), the iterations on the boundary
//!   angles (`iterations`), the final harmonic solve and fold check (`finish`);
//! - `metrics`, `write` (ms, and in brackets MB/s of the OBJ written).
//!
//! `solver` = the wall-clock setup of the problem (`DiskProblem::setup_ms`: assembly and
//! symbolic analysis at once on the two cores, then the numeric factorization) + iterate,
//! the map computation proper, so less than the sum of its stages; `total` = every stage.
//! `ref` ("one factorization") is the fastest analyse + factor of the same `L_II` among
//! the pipeline's own and those run in the same process after the pipeline (after its
//! peak memory was read): with AMD (the facade's default) and, when the pipeline ordered
//! by nested dissection, with that too. It is the yardstick of the performance model
//! (`solver / ref`). `ordering` is the pipeline's (`--ordering`, default `auto`:
//! `conformap_operators::Ordering::Auto`).

use std::path::Path;
use std::time::Instant;

use conformap_disk::{run_disk_method, DiskMethod, DiskOptions, DiskProblem, ProblemOptions};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_operators::{Cholesky, CholeskyOptions, Ordering};

use crate::row::{row_struct, Row};

row_struct! {
    /// Stage times (ms) and sizes of one run.
    #[derive(Debug, Clone, Default)]
    pub struct StageRow {
        vertices,
        faces,
        boundary,
        read,
        assemble,
        analyse,
        factor,
        schur,
        start,
        iterations,
        finish,
        iterate,
        metrics,
        write,
        solver,
        total,
        reference,
        peak_rss_mib,
        energy,
        steps,
        flipped,
        /// 1 when `L_II` was ordered by nested dissection, 0 for AMD.
        nested,
        /// Size of the input file, MB (10⁶ bytes), for the read column's MB/s.
        read_mb,
        /// Size of the written OBJ, MB, for the write column's MB/s.
        write_mb,
    }
}

impl Row for StageRow {
    /// The solver time as a multiple of one factorization of `L_II`.
    fn ratio(&self) -> f64 {
        self.solver / self.reference.max(1e-9)
    }
}

impl StageRow {
    /// The Markdown header.
    pub fn header() -> String {
        "| mesh | V | F | n_B | ordering | read (MB/s) | assemble | analyse | factor | iterate (schur + start + iterations + finish) | metrics | write (MB/s) | solver | total | one factorization | solver / factorization (min–max) | peak RSS MiB | E_C | CCEM iterations |\n\
         |---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
            .to_string()
    }

    /// One Markdown row.
    pub fn to_markdown(&self, name: &str, lo: f64, hi: f64) -> String {
        let name = Path::new(name)
            .file_name()
            .map_or(name.to_string(), |n| n.to_string_lossy().to_string());
        format!(
            "| {name} | {:.0} | {:.0} | {:.0} | {} | {:.0} ({:.0}) | {:.0} | {:.0} | {:.0} | {:.0} ({:.0} + {:.0} + {:.0} + {:.0}) | {:.0} | {:.0} ({:.0}) | {:.0} | {:.0} | {:.0} | **{:.2}** ({:.2}–{:.2}) | {:.0} | {:.6} | {:.0}{} |",
            self.vertices,
            self.faces,
            self.boundary,
            if self.nested > 0.0 { "ND" } else { "AMD" },
            self.read,
            mb_per_s(self.read_mb, self.read),
            self.assemble,
            self.analyse,
            self.factor,
            self.iterate,
            self.schur,
            self.start,
            self.iterations,
            self.finish,
            self.metrics,
            self.write,
            mb_per_s(self.write_mb, self.write),
            self.solver,
            self.total,
            self.reference,
            self.ratio(),
            lo,
            hi,
            self.peak_rss_mib,
            self.energy,
            self.steps,
            if self.flipped > 0.0 {
                format!(" ({:.0} flipped)", self.flipped)
            } else {
                String::new()
            }
        )
    }
}

/// Throughput of `mb` MB in `ms` milliseconds (0 when nothing was timed).
fn mb_per_s(mb: f64, ms: f64) -> f64 {
    if ms > 0.0 {
        mb / (ms / 1e3)
    } else {
        0.0
    }
}

fn file_mb(path: &Path) -> f64 {
    std::fs::metadata(path).map_or(0.0, |m| m.len() as f64 / 1e6)
}

pub(crate) fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// Peak resident set size of this process in MiB (Linux `VmHWM`), 0 where unknown.
pub(crate) fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines().find(|l| l.starts_with("VmHWM:")).and_then(|l| {
                l.split_whitespace()
                    .nth(1)
                    .and_then(|k| k.parse::<f64>().ok())
            })
        })
        .map_or(0.0, |kib| kib / 1024.0)
}

/// Runs read → disk map → metrics → write once, timing each stage, then the reference
/// factorizations of `L_II` (AMD, and nested dissection too when the pipeline used it).
pub fn run_once(path: &Path, method: &str, ordering: &str) -> Result<StageRow, String> {
    let method: DiskMethod = method.parse().map_err(|e| format!("{e}"))?;
    let ordering: Ordering = ordering.parse().map_err(|e| format!("{e}"))?;
    let t_all = Instant::now();
    let t = Instant::now();
    let loaded = conformap_io::read_mesh(path).map_err(|e| e.to_string())?;
    let read = ms(t);
    let mesh = &loaded.mesh;
    let mut problem =
        DiskProblem::with_options(mesh, &ProblemOptions::DEFAULT.with_ordering(ordering))
            .map_err(|e| e.to_string())?;
    let stats = problem.interior_factor().stats().clone();
    let t = Instant::now();
    let out =
        run_disk_method(&mut problem, method, &DiskOptions::DEFAULT).map_err(|e| e.to_string())?;
    let iterate = ms(t);
    let t = Instant::now();
    let m = planar_map_metrics(mesh, &out.map, &MetricsOptions::default())
        .map_err(|e| e.to_string())?;
    let metrics = ms(t);
    let t = Instant::now();
    let uv: Vec<[f64; 2]> = out
        .map
        .iter()
        .map(|z| [(z.re + 1.0) / 2.0, (z.im + 1.0) / 2.0])
        .collect();
    let dest = std::env::temp_dir().join(format!("conformap-bench-out-{}.obj", std::process::id()));
    conformap_io::write_mesh_with_uv(&dest, mesh, &uv, Some(&loaded.source))
        .map_err(|e| e.to_string())?;
    let write = ms(t);
    let write_mb = file_mb(&dest);
    let _ = std::fs::remove_file(&dest);
    let total = ms(t_all);
    let peak = peak_rss_mib();
    let stages = out
        .report
        .ccem
        .as_ref()
        .map(|c| c.stages_ms.clone())
        .unwrap_or_default();
    // the yardstick: one more factorization of the same matrix with the facade's defaults
    // (AMD), and one with nested dissection when the pipeline used it; the fastest of
    // these and the pipeline's own is "one factorization"
    let nested = stats.ordering == Ordering::NestedDissection.name();
    let mut reference = stats.analyse_ms + stats.factor_ms;
    let mut orderings = vec![Ordering::Amd];
    if nested {
        orderings.push(Ordering::NestedDissection);
    }
    for o in orderings {
        let f = Cholesky::factor_with(
            &problem.blocks().ii,
            &CholeskyOptions::DEFAULT.with_ordering(o),
        )
        .map_err(|e| e.to_string())?;
        reference = reference.min(f.stats().analyse_ms + f.stats().factor_ms);
    }
    Ok(StageRow {
        vertices: mesh.num_vertices() as f64,
        faces: mesh.num_faces() as f64,
        boundary: problem.num_boundary() as f64,
        read,
        read_mb: file_mb(path),
        write_mb,
        assemble: problem.assemble_ms,
        analyse: stats.analyse_ms,
        factor: stats.factor_ms,
        schur: stages.schur,
        start: stages.start,
        iterations: stages.iterations,
        finish: stages.finish,
        iterate,
        metrics,
        write,
        solver: problem.setup_ms + iterate,
        total,
        // the fastest factorization of the same matrix in this process: one slow run
        // (page faults on fresh memory, the other tenant of the core), or an ordering
        // slower than the other, must not make the ratio look better than it is
        reference,
        peak_rss_mib: peak,
        energy: m.conformal_energy,
        steps: out.report.iterations as f64,
        flipped: m.flipped_faces as f64,
        nested: if nested { 1.0 } else { 0.0 },
    })
}
