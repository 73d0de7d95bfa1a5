//! One input of a batch on its own: what [`crate::batch::run_streaming`] does for each input,
//! callable by a front end that distributes the inputs itself (a Dask or SLURM cluster
//! through the Python package's `batch_one`), so that its lines cannot drift from
//! `conformap batch`'s.

use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

use serde_json::{json, Value};

use crate::batch::inputs::{collect_inputs, is_manifest};
use crate::batch::{create_out_dir, run_job, BatchJob};
use crate::failure::Failure;

/// Runs of [`run_one`] in this process right now.
static RUNNING: AtomicUsize = AtomicUsize::new(0);
/// Runs of [`run_one`] started in this process so far.
static STARTED: AtomicUsize = AtomicUsize::new(0);

/// Counts a run as running until dropped.
struct Running;

impl Running {
    /// Starts a run: whether it is alone in the process, and the start count after it.
    fn start() -> (Self, bool, usize) {
        let alone = RUNNING.fetch_add(1, Ordering::SeqCst) == 0;
        let started = STARTED.fetch_add(1, Ordering::SeqCst) + 1;
        (Self, alone, started)
    }
}

impl Drop for Running {
    fn drop(&mut self) {
        RUNNING.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Runs `args`' job on the one mesh `mesh` exactly as `conformap batch` runs each of its
/// inputs (the same planning, outputs `DIR/<stem>.<ext>` and `DIR/<stem>.json`, skipping,
/// failure capture), and returns that input's JSON line (`args.inputs`, `jobs` and
/// `report` are not used). A failing input is a `failed` line, not an error.
///
/// Peak memory: a run alone in the process from its start to its end measures its own
/// peak (`memory.peak_rss_scope` `"job"`, as `batch --jobs 1`); runs that overlap share
/// the process's peak (`"process"`).
///
/// # Errors
/// What `conformap batch` refuses before it runs anything: usage (2) for a `mesh` without
/// a mesh format (a manifest: give its meshes one by one) or template options naming one
/// file; bad input (1) for an output directory that cannot be created.
///
/// # Examples
/// ```
/// use conformap::{BatchCommand, BatchJob, BatchTemplate};
/// # let dir = std::env::temp_dir().join(format!("conformap-one-doc-{}", std::process::id()));
/// let mesh = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/woody.obj");
/// let batch = BatchJob::new(BatchTemplate::new(BatchCommand::Disk), &dir, vec![]);
/// let line = conformap::batch::one::run_one(&batch, mesh.as_ref())?;
/// assert_eq!(line["status"], "ok");
/// assert!(line["metrics"]["conformal_energy"].as_f64().is_some_and(|e| e < 0.07));
/// assert!(dir.join("woody.obj").exists() && dir.join("woody.json").exists());
/// # std::fs::remove_dir_all(&dir).map_err(conformap::Failure::input)?;
/// # Ok::<(), conformap::Failure>(())
/// ```
pub fn run_one(args: &BatchJob, mesh: &Path) -> Result<Value, Failure> {
    if is_manifest(mesh) {
        return Err(Failure::Usage(format!(
            "{}: not a mesh (.obj, .gltf, .glb, .ply, .stl, .off, .gii or a FreeSurfer \
             surface); one input is one mesh: run the meshes of a manifest one by one",
            mesh.display()
        )));
    }
    let inputs = collect_inputs(&[mesh.to_path_buf()])?;
    let Some(input) = inputs.first() else {
        return Err(Failure::Usage("no input".to_string()));
    };
    create_out_dir(&args.out_dir)?;
    let job = args.plan(input)?;
    let (running, alone, started) = Running::start();
    let mut line = run_job(&job, args.skip_existing, alone);
    let overlapped = STARTED.load(Ordering::SeqCst) != started;
    drop(running);
    if overlapped {
        if let Some(memory) = line.get_mut("memory").and_then(Value::as_object_mut) {
            memory.insert("peak_rss_scope".to_string(), json!("process"));
        }
    }
    Ok(line)
}

#[cfg(test)]
mod tests {
    use std::path::PathBuf;

    use super::*;
    use crate::batch::{run, BatchCommand, BatchTemplate};

    fn fixture(name: &str) -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../fixtures")
            .join(name)
    }

    /// A line without what differs between two runs (times, memory) and with the
    /// output directory `from` replaced by `to`.
    fn masked(mut line: Value, from: &Path, to: &Path) -> Value {
        if let Some(o) = line.as_object_mut() {
            for key in ["timings_ms", "memory", "time_ms"] {
                o.remove(key);
            }
        }
        let text = line.to_string();
        let (from, to) = (from.display().to_string(), to.display().to_string());
        serde_json::from_str(&text.replace(&from, &to)).unwrap_or(Value::Null)
    }

    #[test]
    fn run_one_gives_batch_lines_for_ok_failed_and_skipped_inputs() {
        let root = std::env::temp_dir().join(format!("conformap-run-one-{}", std::process::id()));
        let (a, b) = (root.join("batch"), root.join("one"));
        // woody is a disk (ok); spot is closed (failed: no disk map)
        let meshes = vec![fixture("woody.obj"), fixture("spot.obj")];
        let template = BatchTemplate::new(BatchCommand::Disk);
        let batch = BatchJob::new(template.clone(), &a, meshes.clone());
        let out = run(&batch).unwrap_or_default();
        let lines: Vec<Value> = out
            .stdout
            .unwrap_or_default()
            .lines()
            .filter_map(|l| serde_json::from_str(l).ok())
            .collect();
        assert_eq!((lines.len(), out.exit_code), (3, 4));
        let single = BatchJob::new(template, &b, Vec::new());
        for (mesh, line) in meshes.iter().zip(&lines) {
            let mine = run_one(&single, mesh).unwrap_or_default();
            assert_eq!(masked(mine.clone(), &b, &a), masked(line.clone(), &a, &a));
            assert_eq!(mine["status"], line["status"]);
            if mine["status"] == "ok" {
                assert_eq!(mine["memory"]["peak_rss_scope"], "job");
                let bytes = |dir: &Path| std::fs::read(dir.join("woody.obj")).unwrap_or_default();
                assert!(!bytes(&a).is_empty() && bytes(&a) == bytes(&b));
            }
        }
        // skipped: the outputs exist
        let mut skipping = BatchJob::new(BatchTemplate::new(BatchCommand::Disk), &a, meshes);
        skipping.skip_existing = true;
        let again = run(&skipping)
            .unwrap_or_default()
            .stdout
            .unwrap_or_default();
        let first: Value = again
            .lines()
            .next()
            .and_then(|l| serde_json::from_str(l).ok())
            .unwrap_or_default();
        assert_eq!(first["status"], "skipped");
        let one = run_one(&skipping, &fixture("woody.obj")).unwrap_or_default();
        assert_eq!(one, first);
        // a manifest is refused (usage)
        let err = run_one(&skipping, &root.join("list.txt")).map(|_| ());
        assert!(matches!(err, Err(Failure::Usage(m)) if m.contains("one by one")));
        let _ = std::fs::remove_dir_all(&root);
    }
}
