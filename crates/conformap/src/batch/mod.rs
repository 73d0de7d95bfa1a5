//! `conformap batch --command disk|sphere|global|flatten|atlas --out-dir DIR [--jobs N]
//! [--skip-existing] [--report R.jsonl] MANIFEST|MESH… [-- OPTIONS]`: one map command over
//! many meshes.
//!
//! Each input runs as the single command would: the [`BatchTemplate`] job with the input's
//! mesh, `-o DIR/<stem>.<ext>` and `--report DIR/<stem>.json`, run by the same [`run_map`],
//! so the outputs equal a single run's byte for byte. One JSON line per input (in input order) and a summary line
//! go to the caller's sink and to `--report`. `--jobs N` runs N inputs at once, each on one
//! thread, as far as their memory estimates fit the memory available at the start
//! ([`crate::pipeline::context::MemoryBudget`]).
//!
//! Peak memory: with `--jobs 1` every input's `memory.peak_rss_bytes` (in its line and in
//! `DIR/<stem>.json`) is that run's own peak: the process's high-water mark is reset before
//! each input (Linux `/proc/self/clear_refs`), and the line's `memory.peak_rss_scope` says
//! `"job"`.
//! With several jobs at once (or where the reset is refused) runs share the process, so the
//! value is the process's peak so far and the scope says `"process"`. The summary's
//! `peak_rss_bytes` is the process's peak over the whole batch.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use serde_json::{json, Value};

use crate::batch::inputs::{collect_inputs, BatchInput};
use crate::failure::Failure;
use crate::jobs::{
    atlas::AtlasJob, disk::DiskJob, flatten::FlattenJob, global::GlobalJob, sphere::SphereJob,
};
use crate::pipeline::context::{self, MemoryBudget, RunContext};
use crate::pipeline::{check_outputs, run_map, InputOptions, MapJob, Outcome, OutputOptions};
use crate::report::ms_since;

pub mod inputs;
/// One input of a batch on its own ([`one::run_one`]: the Python package's `batch_one`).
pub mod one;

crate::choice! {
    /// The map command a batch runs.
    pub enum BatchCommand {
        /// `conformap disk` (one boundary loop, or the disk with holes).
        Disk = "disk",
        /// `conformap sphere`.
        Sphere = "sphere",
        /// `conformap global` (surfaces with handles or several boundary loops; seamed outputs).
        Global = "global",
        /// `conformap flatten` (boundary first flattening: free boundary by default).
        Flatten = "flatten",
        /// `conformap atlas` (a texture atlas of any mesh; seamed outputs).
        Atlas = "atlas",
    }
}

/// The job a batch runs on every input, with the options every input shares; its mesh and
/// output paths are replaced by each input's.
#[derive(Debug, Clone)]
pub enum BatchTemplate {
    /// A disk map.
    Disk(DiskJob),
    /// A sphere map.
    Sphere(SphereJob),
    /// A global map.
    Global(GlobalJob),
    /// A boundary first flattening.
    Flatten(FlattenJob),
    /// A texture atlas.
    Atlas(AtlasJob),
}

impl BatchTemplate {
    /// The template of `command` with every option at its default.
    pub fn new(command: BatchCommand) -> Self {
        let (input, output) = (InputOptions::new(""), OutputOptions::new(""));
        match command {
            BatchCommand::Disk => Self::Disk(DiskJob::new(input, output)),
            BatchCommand::Sphere => Self::Sphere(SphereJob::new(input, output)),
            BatchCommand::Global => Self::Global(GlobalJob::new(input, output)),
            BatchCommand::Flatten => Self::Flatten(FlattenJob::new(input, output)),
            BatchCommand::Atlas => Self::Atlas(AtlasJob::new(input, output)),
        }
    }

    /// The job as a map job.
    pub fn as_map(&self) -> &(dyn MapJob + Send + Sync) {
        match self {
            Self::Disk(j) => j,
            Self::Sphere(j) => j,
            Self::Global(j) => j,
            Self::Flatten(j) => j,
            Self::Atlas(j) => j,
        }
    }

    /// The same job on `input` writing `output`.
    fn with_io(&self, input: InputOptions, output: OutputOptions) -> Self {
        let mut job = self.clone();
        let (i, o) = match &mut job {
            Self::Disk(j) => (&mut j.input, &mut j.output),
            Self::Sphere(j) => (&mut j.input, &mut j.output),
            Self::Global(j) => (&mut j.input, &mut j.output),
            Self::Flatten(j) => (&mut j.input, &mut j.output),
            Self::Atlas(j) => (&mut j.input, &mut j.output),
        };
        *i = input;
        *o = output;
        job
    }
}

/// `batch`: one map job over many meshes.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct BatchJob {
    /// The job run on every input (its own paths are ignored).
    pub template: BatchTemplate,
    /// Where the outputs go: `DIR/<stem>.<ext>` and `DIR/<stem>.json` (created if missing).
    pub out_dir: PathBuf,
    /// Inputs run at once (each on one thread), as far as their memory estimates fit.
    /// Default: 1.
    pub jobs: u32,
    /// Skip an input whose outputs all exist already. Default: false.
    pub skip_existing: bool,
    /// Also write the JSON lines here. Default: none.
    pub report: Option<PathBuf>,
    /// Output mesh format (obj, gltf, glb). Default: the input's.
    pub ext: Option<String>,
    /// Also write `DIR/<stem>_surface.png` and `DIR/<stem>_map.png`. Default: false.
    pub png: bool,
    /// The memory all jobs together may use (bytes); every run's memory limit. Default:
    /// the memory available at the start.
    pub max_memory: Option<u64>,
    /// Meshes, and manifests (any other extension: one path per line, or CSV with a `path`
    /// column; relative paths from the manifest's directory).
    pub inputs: Vec<PathBuf>,
}

impl BatchJob {
    /// `template` over `inputs`, writing to `out_dir`, every other option at its default.
    pub fn new(template: BatchTemplate, out_dir: impl Into<PathBuf>, inputs: Vec<PathBuf>) -> Self {
        Self {
            template,
            out_dir: out_dir.into(),
            jobs: 1,
            skip_existing: false,
            report: None,
            ext: None,
            png: false,
            max_memory: None,
            inputs,
        }
    }

    /// With `n` inputs at once.
    pub fn with_jobs(mut self, n: u32) -> Self {
        self.jobs = n;
        self
    }

    /// With the JSON lines also written to `path`.
    pub fn with_report(mut self, path: impl Into<PathBuf>) -> Self {
        self.report = Some(path.into());
        self
    }

    /// The name of the command run on every input.
    pub fn command_name(&self) -> &'static str {
        self.template.as_map().name()
    }

    /// Usage checks of the template: options naming one file cannot serve every input.
    fn check_template(&self) -> Result<(), Failure> {
        let map = self.template.as_map();
        let output = map.output();
        if output.flat.is_some() || output.quality.is_some() || map.input().vertex_map.is_some() {
            return Err(Failure::Usage(
                "--flat, --quality-overlay and --vertex-map name one file, not one per input: \
                 batch writes DIR/<stem>.<ext> and DIR/<stem>.json"
                    .to_string(),
            ));
        }
        if map.output().png.is_some() {
            return Err(Failure::Usage(
                "--png PREFIX names one prefix, not one per input: use `batch --png`".into(),
            ));
        }
        Ok(())
    }

    /// The single run of `input`: the template on its mesh and outputs.
    fn plan(&self, input: &BatchInput) -> Result<Job, Failure> {
        self.check_template()?;
        let ext = match &self.ext {
            Some(e) => e.trim_start_matches('.').to_string(),
            None => input
                .mesh
                .extension()
                .map(|e| e.to_string_lossy().to_ascii_lowercase())
                .filter(|e| matches!(e.as_str(), "obj" | "gltf" | "glb" | "ply"))
                .unwrap_or_else(|| "obj".to_string()),
        };
        let mesh_out = self.out_dir.join(format!("{}.{ext}", input.stem));
        let report = self.out_dir.join(format!("{}.json", input.stem));
        let template = self.template.as_map();
        let mut input_options = template.input().clone();
        input_options.mesh = input.mesh.clone();
        if self.max_memory.is_some() {
            input_options.max_memory = self.max_memory;
        }
        let mut output = template.output().clone();
        output.output = mesh_out.clone();
        output.report = Some(report.clone());
        let mut outputs = vec![mesh_out, report];
        if self.png {
            let prefix = self.out_dir.join(&input.stem);
            outputs.extend(crate::pipeline::outputs::png_paths(&prefix));
            output.png = Some(prefix);
        }
        Ok(Job {
            input: input.clone(),
            job: self.template.with_io(input_options, output),
            outputs,
        })
    }
}

/// One input, planned: its job and its outputs.
struct Job {
    input: BatchInput,
    job: BatchTemplate,
    outputs: Vec<PathBuf>,
}

/// Runs `conformap batch`, collecting the JSON lines as the outcome's stdout.
///
/// # Errors
/// See [`run_streaming`].
pub fn run(args: &BatchJob) -> Result<Outcome, Failure> {
    let mut lines = Vec::new();
    let mut outcome = run_streaming(args, &mut |l| lines.push(l.to_string()))?;
    outcome.stdout = Some(lines.join("\n"));
    Ok(outcome)
}

/// Runs `conformap batch`, giving each JSON line to `sink` as soon as it and every line
/// before it are known (input order), telling the thread's [`context::Watcher`] of each input done. The outcome's exit
/// code is 4 when some input failed.
///
/// # Errors
/// Usage (2): no input, two inputs with one stem, options that do not fit the command, an
/// output naming an input. Bad input (1): an unreadable manifest, an output directory
/// that cannot be created or written, a `--report` that cannot be written. A failing input
/// is not an error: it is a `failed` line.
pub fn run_streaming(args: &BatchJob, sink: &mut dyn FnMut(&str)) -> Result<Outcome, Failure> {
    let t_all = Instant::now();
    let inputs = collect_inputs(&args.inputs)?;
    create_out_dir(&args.out_dir)?;
    let jobs = inputs
        .iter()
        .map(|i| args.plan(i))
        .collect::<Result<Vec<_>, _>>()?;
    let meshes: Vec<&Path> = jobs.iter().map(|j| j.input.mesh.as_path()).collect();
    let mut report = match &args.report {
        Some(p) => {
            check_outputs(&[("--report", p, false)], &meshes)?;
            Some(
                std::fs::File::create(p)
                    .map_err(|e| Failure::input(format!("cannot write {}: {e}", p.display())))?,
            )
        }
        None => None,
    };
    let workers = (args.jobs as usize).min(jobs.len()).max(1);
    let budget = (workers > 1)
        .then(|| {
            args.max_memory
                .or_else(|| conformap_operators::available_memory().map(|(m, _)| m))
        })
        .flatten()
        .map(MemoryBudget::new);

    let watcher = context::watcher();
    if let Some(w) = &watcher {
        w.started(jobs.len());
    }
    let (mut ok, mut failed, mut skipped) = (0usize, 0usize, 0usize);
    let mut at_cap: Vec<String> = Vec::new();
    let mut emit = |line: &Value| {
        let text = line.to_string();
        match &watcher {
            Some(w) => w.suspend(&mut || sink(&text)),
            None => sink(&text),
        }
        if let Some(f) = report.as_mut() {
            // the JSON lines file is a by-product: a full disk must not stop the batch
            let _ = writeln!(f, "{text}").and_then(|()| f.flush());
        }
    };
    let next = AtomicUsize::new(0);
    let mut job_peak = 0u64;
    let (tx, rx) = mpsc::channel::<(usize, Value)>();
    std::thread::scope(|s| {
        for _ in 0..workers {
            let tx = tx.clone();
            let (jobs, next, budget) = (&jobs, &next, budget.clone());
            s.spawn(move || {
                let pool = (workers > 1)
                    .then(|| rayon::ThreadPoolBuilder::new().num_threads(1).build().ok())
                    .flatten();
                let context = RunContext {
                    watcher: None,
                    budget,
                };
                loop {
                    let k = next.fetch_add(1, Ordering::Relaxed);
                    let Some(job) = jobs.get(k) else { break };
                    let line = context.scope(|| match &pool {
                        Some(p) => p.install(|| run_job(job, args.skip_existing, false)),
                        None => run_job(job, args.skip_existing, workers == 1),
                    });
                    if tx.send((k, line)).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        let mut pending = BTreeMap::new();
        let mut due = 0;
        for (k, line) in rx {
            if let Some(p) = line["memory"]["peak_rss_bytes"].as_u64() {
                job_peak = job_peak.max(p);
            }
            pending.insert(k, line);
            while let Some(line) = pending.remove(&due) {
                if stopped_at_cap(&line) {
                    at_cap.push(line["input"].as_str().unwrap_or_default().to_string());
                }
                match line["status"].as_str() {
                    Some("ok") => ok += 1,
                    Some("skipped") => skipped += 1,
                    _ => failed += 1,
                }
                if let Some(w) = &watcher {
                    w.advanced(due + 1, &jobs[due].input.stem);
                }
                emit(&line);
                due += 1;
            }
        }
    });
    let exit_code = if failed > 0 { 4 } else { 0 };
    // the process's high-water mark, reset before every input when jobs = 1: the largest
    // of the inputs' peaks and what came after the last reset
    let peak = conformap_operators::peak_rss_bytes().map(|p| p.max(job_peak));
    emit(&json!({ "summary": {
        "command": args.command_name(),
        "inputs": jobs.len(),
        "ok": ok,
        "failed": failed,
        "skipped": skipped,
        "jobs": workers,
        "exit_code": exit_code,
        "peak_rss_bytes": peak,
        "total_ms": ms_since(t_all),
    }}));
    let cap_note = if at_cap.is_empty() {
        String::new()
    } else {
        format!(
            "; stopped at the iteration cap (not converged): {}",
            at_cap.join(", ")
        )
    };
    Ok(Outcome {
        messages: vec![format!(
            "batch {}: {} inputs, {ok} ok, {failed} failed, {skipped} skipped{cap_note}; {:.0} ms",
            args.command_name(),
            jobs.len(),
            ms_since(t_all)
        )],
        exit_code,
        ..Outcome::default()
    })
}

/// Creates the output directory (and its parents) if missing.
fn create_out_dir(dir: &Path) -> Result<(), Failure> {
    std::fs::create_dir_all(dir).map_err(|e| {
        Failure::BadInput(
            format!("cannot create {}: {e}", dir.display()),
            Some("write the outputs elsewhere (--out-dir)".to_string()),
        )
    })
}

/// Resets the process's peak resident memory (Linux `VmHWM`) to its current resident
/// memory, by writing `5` to `/proc/self/clear_refs`; `false` where that is refused or
/// unsupported.
fn reset_peak_rss() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// Runs one input (or skips it) and describes the result as its JSON line. `own_peak`:
/// this run is alone in the process, so its peak memory can be measured on its own (the
/// high-water mark is reset first).
fn run_job(job: &Job, skip_existing: bool, own_peak: bool) -> Value {
    let input = job.input.mesh.display().to_string();
    let outputs: Vec<String> = job
        .outputs
        .iter()
        .map(|p| p.display().to_string())
        .collect();
    if skip_existing && job.outputs.iter().all(|p| p.exists()) {
        return json!({ "input": input, "status": "skipped", "outputs": outputs });
    }
    let scope = if own_peak && reset_peak_rss() {
        "job"
    } else {
        "process"
    };
    let t = Instant::now();
    let cmd = job.job.as_map();
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| run_map(cmd)))
        .unwrap_or_else(|_| {
            Err(Failure::Numerical(
                "internal error (a panic) while mapping this input: please report it with \
                 the file"
                    .to_string(),
            ))
        });
    let mut line = match result {
        Ok(Outcome {
            report: Some(r), ..
        }) => json!({
            "input": input,
            "status": "ok",
            "command": r.command,
            "method": r.method,
            "outputs": outputs,
            "converged": r.solver.summary.converged,
            "metrics": r.metrics,
            "timings_ms": r.timings_ms,
            "memory": r.memory,
        }),
        Ok(_) => json!({ "input": input, "status": "failed", "error": "no report" }),
        Err(f) => json!({
            "input": input,
            "status": "failed",
            "exit_code": f.exit_code(),
            "exit_class": exit_class(&f),
            "error": f.to_string(),
            "hint": f.hint(),
            "time_ms": ms_since(t),
        }),
    };
    if let Some(memory) = line.get_mut("memory").and_then(Value::as_object_mut) {
        memory.insert("peak_rss_scope".to_string(), json!(scope));
    }
    line
}

/// The name of a failure's exit class.
fn exit_class(f: &Failure) -> &'static str {
    match f {
        Failure::BadInput(..) => "bad input",
        Failure::Usage(_) => "usage",
        Failure::Numerical(_) => "numerical",
    }
}

/// Whether an input's line says its solver stopped at the iteration cap: a map that did not
/// converge, or a `--strict` refusal of one (exit 3, "did not converge").
fn stopped_at_cap(line: &Value) -> bool {
    let refused = line["exit_code"].as_u64() == Some(3)
        && line["error"]
            .as_str()
            .is_some_and(|e| e.contains("did not converge"));
    line["converged"].as_bool() == Some(false) || refused
}
