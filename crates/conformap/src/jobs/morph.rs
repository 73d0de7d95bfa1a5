//! `conformap morph S1 S2 [S3 …] --landmarks L1 L2 [L3 …] --frames N -o OUT.glb|DIR/
//! [--lambda X | --hard] [--report R.json]`: a morph through key surfaces (CEM §6).
//!
//! Several inputs, so not a [`crate::pipeline::MapJob`]; it reuses the pipeline's
//! pieces: [`read_input`] for every surface, [`check_outputs`] before anything is read,
//! [`Staged`] to write all frames (or the GLB) and the report or nothing, the report's
//! [`InputInfo`] and [`StageTimings`], and [`Failure`] for every error.

use std::path::{Path, PathBuf};
use std::time::Instant;

use conformap_morph::{morph, Morph, MorphOptions, MorphReport, Surface};
use serde::Serialize;

use crate::failure::Failure;
pub use crate::jobs::morph_input::morph_peak_bytes;
use crate::jobs::morph_input::{morph_failure, read_landmarks};
use crate::pipeline::memory::MemoryCheck;
use crate::pipeline::{check_outputs, read_input, Outcome, Staged};
use crate::report::{ms_since, InputInfo, MemoryReport, StageTimings};

/// Arguments of `conformap morph`.
#[non_exhaustive]
#[derive(Debug, Clone)]
pub struct MorphJob {
    /// The key surfaces S1 S2 [S3 …] (disk-like meshes: one boundary loop, no handles).
    /// Every frame has S1's vertices and faces.
    pub surfaces: Vec<PathBuf>,
    /// One landmark file per surface, in the same order: `<0-based vertex> <name>` per
    /// line, the same names in the same order in every file. The first landmark goes to
    /// the centre of the disk, the second fixes the rotation (both interior vertices).
    pub landmarks: Vec<PathBuf>,
    /// Number of frames (key surface k at frame round(k(N−1)/(K−1))).
    pub frames: usize,
    /// `OUT.glb` (S1 with one morph target per key surface and an animation of their
    /// weights, one keyframe per frame at 24 frames per second) or `DIR/` (created when
    /// missing: `frame_0000.obj` …; frame files of an earlier run this run did not write
    /// are removed after the commit).
    pub output: PathBuf,
    /// Landmark weight λ of Eq. 34 (default: the library's `DEFAULT_LAMBDA`). Where
    /// Eq. 34 folds, the largest λ without a fold and a fold-free landmark warp bring the
    /// landmarks to where λ puts them (the report says so).
    pub lambda: Option<f64>,
    /// Put the landmarks exactly on their counterparts (hard constraints; where they
    /// fold, the same fold-free landmark warp finishes).
    pub hard: bool,
    /// Write a JSON report here.
    pub report: Option<PathBuf>,
    /// Refuse (nothing computed) if the estimated peak memory exceeds this many bytes,
    /// before reading (all surfaces) and before solving ([`morph_peak_bytes`]). Default:
    /// `None`, the memory available (no check where that is unknown).
    pub max_memory: Option<u64>,
}

impl MorphJob {
    /// Runs the job.
    ///
    /// # Errors
    /// A [`Failure`] with its exit class and hint; nothing was written.
    pub fn run(&self) -> Result<Outcome, Failure> {
        run(self)
    }
    /// The morph through `surfaces` (with their `landmarks` files) in `frames` frames to
    /// `output`, soft landmarks with the library's weight, no report.
    pub fn new(
        surfaces: Vec<PathBuf>,
        landmarks: Vec<PathBuf>,
        frames: usize,
        output: impl Into<PathBuf>,
    ) -> Self {
        Self {
            surfaces,
            landmarks,
            frames,
            output: output.into(),
            lambda: None,
            hard: false,
            report: None,
            max_memory: None,
        }
    }

    /// With a memory limit (bytes) instead of the memory available.
    pub fn with_max_memory(mut self, bytes: Option<u64>) -> Self {
        self.max_memory = bytes;
        self
    }

    /// Also writing the JSON report to `path`.
    pub fn with_report(mut self, path: impl Into<PathBuf>) -> Self {
        self.report = Some(path.into());
        self
    }
}

/// Frames per second of the GLB animation.
pub const GLB_FRAMES_PER_SECOND: f64 = 24.0;

/// The report of `conformap morph`.
#[derive(Debug, Clone, Serialize)]
pub struct MorphCommandReport {
    /// The version of conformap that wrote it.
    pub conformap_version: &'static str,
    /// `"morph"`.
    pub command: &'static str,
    /// `"soft"` (Eq. 34 with λ) or `"hard"`.
    pub method: &'static str,
    /// The key surfaces, S1 first.
    pub inputs: Vec<InputInfo>,
    /// The landmark files, in order.
    pub landmark_files: Vec<String>,
    /// Frames written.
    pub frames: usize,
    /// The frame index of every key surface.
    pub key_frames: Vec<usize>,
    /// The library's report: per key surface its disk map, registration (energy, λ used,
    /// folds, notes), how S1's crease loops were carried, landmark errors, flipped faces
    /// of its key frame, stage timings.
    pub morph: MorphReport,
    /// Wall-clock milliseconds: `read` (all surfaces), `solve` (the morph), `write`,
    /// `total`.
    pub timings_ms: StageTimings,
    /// The memory check: estimate, limit, measured peak (filled in by the caller that ran
    /// the check, the CLI or the Python package; `None`, not written, where none ran).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub memory: Option<MemoryReport>,
}

/// Where the frames go.
enum Target {
    Glb(PathBuf),
    Frames(Vec<PathBuf>),
}

impl MorphJob {
    fn check_usage(&self) -> Result<Target, Failure> {
        self.check_counts()?;
        let is_dir =
            self.output.is_dir() || self.output.as_os_str().to_string_lossy().ends_with('/');
        if is_dir {
            let frames = (0..self.frames)
                .map(|i| self.output.join(format!("frame_{i:04}.obj")))
                .collect();
            return Ok(Target::Frames(frames));
        }
        match self.output.extension().and_then(|e| e.to_str()) {
            Some(e) if e.eq_ignore_ascii_case("glb") => Ok(Target::Glb(self.output.clone())),
            _ => Err(Failure::Usage(format!(
                "-o {}: write OUT.glb or a directory DIR/ (created when missing)",
                self.output.display()
            ))),
        }
    }

    /// The usage checks that need no file: at least two surfaces, one landmark list per
    /// surface, enough frames, a valid λ.
    ///
    /// # Errors
    /// [`Failure::Usage`] naming the first that fails.
    pub fn check_counts(&self) -> Result<(), Failure> {
        let k = self.surfaces.len();
        if k < 2 {
            return Err(Failure::Usage(format!(
                "a morph needs at least two surfaces, got {k}"
            )));
        }
        if self.landmarks.len() != k {
            return Err(Failure::Usage(format!(
                "{k} surfaces but {} landmark files: give one --landmarks file per surface, \
                 in the same order",
                self.landmarks.len()
            )));
        }
        if self.frames < k {
            return Err(Failure::Usage(format!(
                "--frames {} cannot hold {k} key surfaces on distinct frames (at least {k})",
                self.frames
            )));
        }
        if let Some(l) = self.lambda.filter(|l| !(*l > 0.0 && l.is_finite())) {
            return Err(Failure::Usage(format!(
                "--lambda must be a finite number > 0, got {l}"
            )));
        }
        Ok(())
    }

    /// The library's options these arguments ask for (λ or hard landmarks, the rest the
    /// library's defaults).
    pub fn options(&self) -> MorphOptions {
        match (self.hard, self.lambda) {
            (true, _) => MorphOptions::DEFAULT.with_hard_landmarks(),
            (false, Some(l)) => MorphOptions::DEFAULT.with_lambda(l),
            (false, None) => MorphOptions::DEFAULT,
        }
    }
}

/// Runs `conformap morph`.
///
/// # Errors
/// Usage errors (exit 2), bad surfaces or landmark files (exit 1, naming the file and
/// the line or vertex), numerical failures (exit 3); nothing is written then.
fn run(args: &MorphJob) -> Result<Outcome, Failure> {
    let t_all = Instant::now();
    let target = args.check_usage()?;
    if let Target::Frames(_) = &target {
        crate::jobs::morph_frames::create_frame_directory(&args.output)?;
    }
    check_morph_outputs(args, &target)?;
    let paths: Vec<&Path> = args.surfaces.iter().map(PathBuf::as_path).collect();
    let memory = MemoryCheck::before_reading_all(&paths, args.max_memory)?;
    let t = Instant::now();
    let surfaces = read_surfaces(args)?;
    let read_ms = ms_since(t);
    let memory = memory.before_solving(
        morph_peak_bytes(&surfaces, &args.options()),
        &format!("the morph through these {} surfaces", surfaces.len()),
    )?;
    let solution = solve(args, &surfaces)?;

    let t = Instant::now();
    let mut staged = Staged::new();
    stage_frames(&mut staged, &target, &solution)?;
    let timings = StageTimings {
        read: read_ms,
        write: ms_since(t),
        total: ms_since(t_all),
        ..StageTimings::default()
    };
    let mut report = command_report(args, &surfaces, &solution, timings);
    report.memory = Some(memory.report());
    if let Some(path) = &args.report {
        staged.json(path, &report)?;
    }
    staged.commit()?;
    let mut messages = morph_messages(args, &report, ms_since(t_all));
    if let Target::Frames(frames) = &target {
        messages.extend(crate::jobs::morph_frames::remove_stale_frames(
            &args.output,
            frames,
        ));
    }
    Ok(Outcome {
        messages,
        ..Outcome::default()
    })
}

/// Refuses outputs that would overwrite an input or land in a missing directory.
fn check_morph_outputs(args: &MorphJob, target: &Target) -> Result<(), Failure> {
    let mut outputs: Vec<(&str, &Path, bool)> = match target {
        Target::Glb(p) => vec![("-o", p.as_path(), true)],
        Target::Frames(ps) => ps.iter().map(|p| ("-o", p.as_path(), true)).collect(),
    };
    if let Some(p) = &args.report {
        outputs.push(("--report", p, false));
    }
    let inputs: Vec<&Path> = args
        .surfaces
        .iter()
        .chain(&args.landmarks)
        .map(PathBuf::as_path)
        .collect();
    check_outputs(&outputs, &inputs)
}

/// Reads every key surface with its landmarks.
fn read_surfaces(args: &MorphJob) -> Result<Vec<Surface>, Failure> {
    let mut surfaces = Vec::with_capacity(args.surfaces.len());
    for (mesh_path, lm_path) in args.surfaces.iter().zip(&args.landmarks) {
        let input = read_input(mesh_path, false)?;
        let landmarks = read_landmarks(lm_path)?;
        surfaces.push(Surface::new(input.mesh, landmarks));
    }
    Ok(surfaces)
}

/// Stages the frames (OBJ files or one GLB) of `solution`.
fn stage_frames(
    staged: &mut Staged,
    target: &Target,
    solution: &MorphSolution,
) -> Result<(), Failure> {
    let (m, times) = (&solution.morph, &solution.times);
    match target {
        Target::Frames(paths) => staged.obj_frames(paths, m.faces(), |i| m.frame(times[i])),
        Target::Glb(path) => stage_glb(staged, path, m, times),
    }
}

/// The registration notes of every key surface, then the summary line.
fn morph_messages(args: &MorphJob, report: &MorphCommandReport, total_ms: f64) -> Vec<String> {
    let worst = report
        .morph
        .keys
        .iter()
        .map(|k| k.landmark_error_max_rel)
        .fold(0.0, f64::max);
    let summary = format!(
        "{}: morph through {} surfaces, {} frames to {}; landmark error ≤ {:.2} % of the \
         diagonal; {:.0} ms",
        args.surfaces[0].display(),
        args.surfaces.len(),
        args.frames,
        args.output.display(),
        100.0 * worst,
        total_ms
    );
    let mut messages: Vec<String> = report
        .morph
        .keys
        .iter()
        .filter_map(|k| k.registration.as_ref().map(|r| (k.surface, r)))
        .flat_map(|(k, r)| {
            r.notes
                .iter()
                .map(move |n| format!("{}: {n}", args.surfaces[k].display()))
        })
        .collect();
    messages.push(summary);
    messages
}

/// A morph computed, before anything is written.
#[derive(Debug)]
pub struct MorphSolution {
    /// The morph.
    pub morph: Morph,
    /// The time of every frame (`--frames` of them).
    pub times: Vec<f64>,
    /// The frame index of every key surface.
    pub key_frames: Vec<usize>,
    /// Wall-clock milliseconds of the morph, frame times included (the report's `solve`).
    pub solve_ms: f64,
}

/// The morph of `surfaces` (read, or given as arrays to the Python package) with the
/// options and frame count of `args`; `args.surfaces` and `args.landmarks` name the
/// surfaces and landmark lists in errors. Nothing is read or written.
///
/// # Errors
/// Bad surfaces or landmarks (naming the mesh or landmark file), numerical failures.
pub fn solve(args: &MorphJob, surfaces: &[Surface]) -> Result<MorphSolution, Failure> {
    let t = Instant::now();
    let m = morph(surfaces, &args.options())
        .map_err(|e| morph_failure(e, &args.surfaces, &args.landmarks))?;
    let times = m
        .frame_times(args.frames)
        .map_err(|e| morph_failure(e, &args.surfaces, &args.landmarks))?;
    let key_frames = m
        .key_frames(args.frames)
        .map_err(|e| morph_failure(e, &args.surfaces, &args.landmarks))?;
    Ok(MorphSolution {
        morph: m,
        times,
        key_frames,
        solve_ms: ms_since(t),
    })
}

/// The report of a morph: `timings` holds `read`, `write` and `total` (the caller's), the
/// solution its `solve` time.
pub fn command_report(
    args: &MorphJob,
    surfaces: &[Surface],
    solution: &MorphSolution,
    timings: StageTimings,
) -> MorphCommandReport {
    MorphCommandReport {
        conformap_version: env!("CARGO_PKG_VERSION"),
        command: "morph",
        method: if args.hard { "hard" } else { "soft" },
        inputs: args
            .surfaces
            .iter()
            .zip(surfaces)
            .map(|(p, s)| InputInfo::new(p, &s.mesh))
            .collect(),
        landmark_files: args
            .landmarks
            .iter()
            .map(|p| p.display().to_string())
            .collect(),
        frames: args.frames,
        key_frames: solution.key_frames.clone(),
        morph: solution.morph.report.clone(),
        timings_ms: StageTimings {
            solve: solution.solve_ms,
            ..timings
        },
        memory: None,
    }
}

/// Stages the GLB: S1 with target `k` = `P_k − P_0` and the weights of every frame.
fn stage_glb(staged: &mut Staged, path: &Path, m: &Morph, times: &[f64]) -> Result<(), Failure> {
    let base = &m.keys()[0];
    let targets: Vec<Vec<[f64; 3]>> = m.keys()[1..]
        .iter()
        .map(|key| {
            key.iter()
                .zip(base)
                .map(|(p, q)| [p[0] - q[0], p[1] - q[1], p[2] - q[2]])
                .collect()
        })
        .collect();
    let names: Vec<String> = (1..m.keys().len()).map(|k| format!("key_{k}")).collect();
    let seconds: Vec<f64> = (0..times.len())
        .map(|i| i as f64 / GLB_FRAMES_PER_SECOND)
        .collect();
    let weights: Vec<Vec<f64>> = times.iter().map(|&t| m.target_weights(t)).collect();
    staged.morph_glb(
        path,
        &conformap_io::MorphGlb {
            positions: base,
            faces: m.faces(),
            targets: &targets,
            target_names: &names,
            times: &seconds,
            weights: &weights,
        },
    )
}
