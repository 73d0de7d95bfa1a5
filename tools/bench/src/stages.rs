//! One timed run of the disk pipeline, stage by stage, and the table rows.

use std::path::Path;
use std::time::Instant;

use conformap_disk::{cem, harmonic_arc_length, CemOptions, DiskProblem};
use conformap_metrics::{planar_map_metrics, MetricsOptions};

/// Stage times (ms) and sizes of one run.
#[derive(Debug, Clone, Default)]
pub struct StageRow {
    vertices: f64,
    faces: f64,
    boundary: f64,
    read: f64,
    assemble: f64,
    analyse: f64,
    factor: f64,
    iterate: f64,
    metrics: f64,
    write: f64,
    total: f64,
    peak_rss_mib: f64,
    energy: f64,
}

const FIELDS: usize = 13;

impl StageRow {
    fn values(&self) -> [f64; FIELDS] {
        [
            self.vertices,
            self.faces,
            self.boundary,
            self.read,
            self.assemble,
            self.analyse,
            self.factor,
            self.iterate,
            self.metrics,
            self.write,
            self.total,
            self.peak_rss_mib,
            self.energy,
        ]
    }

    fn from_values(v: &[f64]) -> Self {
        Self {
            vertices: v[0],
            faces: v[1],
            boundary: v[2],
            read: v[3],
            assemble: v[4],
            analyse: v[5],
            factor: v[6],
            iterate: v[7],
            metrics: v[8],
            write: v[9],
            total: v[10],
            peak_rss_mib: v[11],
            energy: v[12],
        }
    }

    /// One line for the child → parent pipe.
    pub fn to_line(&self) -> String {
        self.values()
            .iter()
            .map(|v| format!("{v:e}"))
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// Parses [`Self::to_line`].
    pub fn from_line(line: &str) -> Option<Self> {
        let v: Vec<f64> = line
            .split_whitespace()
            .filter_map(|t| t.parse().ok())
            .collect();
        (v.len() == FIELDS).then(|| Self::from_values(&v))
    }

    /// Field-wise median.
    pub fn median(rows: &[Self]) -> Option<Self> {
        if rows.is_empty() {
            return None;
        }
        let mut out = [0.0; FIELDS];
        for (k, slot) in out.iter_mut().enumerate() {
            let mut col: Vec<f64> = rows.iter().map(|r| r.values()[k]).collect();
            col.sort_by(f64::total_cmp);
            *slot = col[col.len() / 2];
        }
        Some(Self::from_values(&out))
    }

    /// The Markdown header.
    pub fn header() -> String {
        "| mesh | V | F | n_b | read | assemble | analyse | factor | iterate | metrics | write | \
         total | total / (analyse+factor) | peak RSS MiB | E_C |\n\
         |---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
            .to_string()
    }

    /// One Markdown row.
    pub fn to_markdown(&self, name: &str) -> String {
        let one_factor = (self.analyse + self.factor).max(1e-9);
        let name = Path::new(name)
            .file_name()
            .map_or(name.to_string(), |n| n.to_string_lossy().to_string());
        format!(
            "| {name} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.2} | {:.0} | {:.5} |",
            self.vertices,
            self.faces,
            self.boundary,
            self.read,
            self.assemble,
            self.analyse,
            self.factor,
            self.iterate,
            self.metrics,
            self.write,
            self.total,
            self.total / one_factor,
            self.peak_rss_mib,
            self.energy
        )
    }
}

fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}

/// Peak resident set size of this process in MiB (Linux `VmHWM`), 0 where unknown.
fn peak_rss_mib() -> f64 {
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

/// Runs read → disk map → metrics → write once, timing each stage.
pub fn run_once(path: &Path, method: &str) -> Result<StageRow, String> {
    let t_all = Instant::now();
    let t = Instant::now();
    let loaded = conformap_io::read_mesh(path).map_err(|e| e.to_string())?;
    let read = ms(t);
    let mesh = &loaded.mesh;
    let mut problem = DiskProblem::new(mesh).map_err(|e| e.to_string())?;
    let stats = problem.interior_factor().stats().clone();
    let t = Instant::now();
    let out = match method {
        "harmonic" => harmonic_arc_length(&problem),
        "cem" => cem(&mut problem, &CemOptions::DEFAULT).map_err(|e| e.to_string())?,
        other => return Err(format!("unknown method `{other}`")),
    };
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
    let _ = std::fs::remove_file(&dest);
    let write = ms(t);
    Ok(StageRow {
        vertices: mesh.num_vertices() as f64,
        faces: mesh.num_faces() as f64,
        boundary: problem.num_boundary() as f64,
        read,
        assemble: problem.assemble_ms,
        analyse: stats.analyse_ms,
        factor: stats.factor_ms,
        // the method's own time, minus nothing: it includes any further factorization
        iterate,
        metrics,
        write,
        total: ms(t_all),
        peak_rss_mib: peak_rss_mib(),
        energy: m.conformal_energy,
    })
}
