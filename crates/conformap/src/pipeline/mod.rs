//! One pipeline for every map job: read → check every output path → estimate memory →
//! solve → metrics → write all outputs or none → report.
//!
//! A job is a small implementation of [`MapJob`]: its [`InputOptions`] and
//! [`OutputOptions`], how much memory its solve needs, and the solve itself, which returns
//! a [`Solved`] (the map as texture coordinates and a flat mesh, the solver's and the
//! metrics' report sections, timings, a summary line). [`run_map`] does everything else,
//! the same way for every job, and returns the typed [`Report`] with the lines a front end
//! prints; [`run_in_memory`] runs the middle of it on a mesh already in memory (the Python
//! package). Nothing here prints.

pub mod context;
pub mod input;
pub mod memory;
pub mod options;
pub mod outputs;
pub mod pictures;
pub mod quality;
pub mod solved;
pub mod staging;

use std::path::Path;
use std::time::Instant;

use conformap_mesh::TriMesh;

pub use input::{
    read_input, read_input_splitting, repair_input, split_non_manifold_mesh, Input, SplitInput,
};
pub use memory::MemoryCheck;
pub use options::{parse_size, InputOptions, OutputOptions};
pub use outputs::{check_command_outputs, check_outputs, Staged};
pub use solved::{PictureDomain, Solved, TexCoords};

use crate::failure::Failure;
use crate::report::{ms_since, InputInfo, RepairsReport, Report, StageTimings};

/// A command that maps a mesh and writes the map.
pub trait MapJob {
    /// Runs the job through [`run_map`].
    ///
    /// # Errors
    /// See [`run_map`].
    fn run(&self) -> Result<Outcome, Failure>
    where
        Self: Sized,
    {
        run_map(self)
    }
    /// The subcommand's name (`"disk"`), the report's `command`.
    fn name(&self) -> &'static str;
    /// What the command computes, for messages (`"a disk map"`).
    fn work(&self) -> &'static str;
    /// The input arguments.
    fn input(&self) -> &InputOptions;
    /// The output arguments.
    fn output(&self) -> &OutputOptions;
    /// Files the command reads besides the mesh (no output may overwrite them).
    fn other_inputs(&self) -> Vec<&Path> {
        Vec::new()
    }
    /// Usage checks that need no file (exit 2).
    fn check_usage(&self) -> Result<(), Failure> {
        Ok(())
    }
    /// The estimated peak memory (bytes) of [`MapJob::solve`] on `mesh`, from the
    /// library's model.
    fn peak_bytes(&self, mesh: &TriMesh) -> u64;
    /// Computes the map, its metrics and its report sections.
    fn solve(&self, input: &Input) -> Result<Solved, Failure>;
    /// Whether the command takes a non-manifold mesh, split at its non-manifold vertices and
    /// edges ([`read_input_splitting`]; `atlas`). Default: false (refused with its hint).
    fn splits_non_manifold(&self) -> bool {
        false
    }
    /// Where the map lands, for the `--png` pictures. Default: the plane.
    fn picture_domain(&self) -> PictureDomain {
        PictureDomain::Plane
    }
}

/// What a command did: its report (map commands), what it prints on stdout (`info`,
/// `metrics`) and the lines for stderr (repairs, the summary).
#[derive(Debug, Default)]
pub struct Outcome {
    /// The report of a map command.
    pub report: Option<Report>,
    /// Text for stdout.
    pub stdout: Option<String>,
    /// Lines for stderr.
    pub messages: Vec<String>,
    /// The exit code of a command that completed with a partial failure (`batch`: 4 when
    /// some input failed); 0 otherwise.
    pub exit_code: u8,
}

/// Runs a map command through the pipeline.
///
/// # Errors
/// Every [`Failure`] of the stages; nothing is written when any stage fails.
pub fn run_map(cmd: &dyn MapJob) -> Result<Outcome, Failure> {
    let t_all = Instant::now();
    let (input_args, output) = (cmd.input(), cmd.output());
    cmd.check_usage()?;
    if input_args.vertex_map.is_some() && !input_args.repair && !cmd.splits_non_manifold() {
        return Err(Failure::Usage(
            "--vertex-map needs --repair (only `atlas` writes one without it: the map of the \
             vertices it splits on a non-manifold mesh)"
                .into(),
        ));
    }
    check_command_outputs(input_args, output, &cmd.other_inputs())?;
    let mesh_path = &input_args.mesh;
    let memory = MemoryCheck::before_reading(mesh_path, input_args.max_memory)
        .map_err(|f| f.in_file(mesh_path))?;
    let reading = context::reserve(memory.read_estimate);
    context::stage(format!("reading {}", mesh_path.display()));
    let t = Instant::now();
    let input = if cmd.splits_non_manifold() && !input_args.repair {
        read_input_splitting(mesh_path)?
    } else {
        read_input(mesh_path, input_args.repair)?
    };
    let read_ms = ms_since(t);
    drop(reading);
    let (solved, mut report) = solve_and_report(cmd, &input, memory, read_ms)?;
    if let Some(why) = solved.strict_violation.as_ref().filter(|_| output.strict) {
        return Err(input.fail(Failure::Numerical(format!(
            "{why} (--strict); nothing written"
        ))));
    }

    let mesh = &input.mesh;
    let t = Instant::now();
    context::stage(format!("{}: writing", mesh_path.display()));
    let mut staged = Staged::new();
    match &solved.uv {
        TexCoords::PerVertex(uv) => {
            staged.mesh_with_uv(&output.output, mesh, uv, input.file_layout())?;
        }
        TexCoords::PerCorner(uv) => staged.mesh_with_corner_uv(&output.output, mesh, uv)?,
        TexCoords::Refined { mesh, uv } => staged.mesh_with_corner_uv(&output.output, mesh, uv)?,
    }
    if let Some(path) = &output.flat {
        let faces = solved.flat.1.as_deref().unwrap_or(mesh.faces());
        staged.flat(path, &solved.flat.0, faces, input.file_layout())?;
    }
    if let Some(path) = &output.quality {
        let domain = solved.picture_domain.unwrap_or(cmd.picture_domain());
        quality::stage_quality(&mut staged, path, mesh, &solved, domain)?;
    }
    if let Some(prefix) = &output.png {
        context::stage(format!("{}: drawing the pictures", mesh_path.display()));
        let domain = solved.picture_domain.unwrap_or(cmd.picture_domain());
        pictures::stage_pictures(&mut staged, prefix, mesh, &solved, domain)?;
        context::stage(format!("{}: writing", mesh_path.display()));
    }
    if let (Some(path), Some(log)) = (&input_args.vertex_map, &input.repairs) {
        staged.text(path, &input::vertex_map_text(log))?;
    } else if let Some(path) = &input_args.vertex_map {
        // a command that splits non-manifold input: the split's map, or the identity
        let identity: Vec<u32>;
        let map = match &input.split {
            Some(split) => &split.vertex_to_input,
            None => {
                identity = (0..mesh.num_vertices() as u32).collect();
                &identity
            }
        };
        staged.text(path, &input::vertex_list_text(map))?;
    }
    report.timings_ms.write = ms_since(t);
    report.timings_ms.total = ms_since(t_all);
    if let Some(path) = &output.report {
        staged.json(path, &report)?;
    }
    staged.commit()?;

    let mut messages = Vec::new();
    if let Some(log) = input.repairs.as_ref().filter(|l| l.changed()) {
        messages.push(format!(
            "{}: repaired: {}",
            mesh_path.display(),
            log.actions().join("; ")
        ));
    }
    messages.push(format!(
        "{}: {}; {:.0} ms",
        mesh_path.display(),
        solved.summary,
        report.timings_ms.total
    ));
    Ok(Outcome {
        report: Some(report),
        stdout: None,
        messages,
        exit_code: 0,
    })
}

/// The middle of [`run_map`] on an input already in memory: the memory check before
/// solving, the solve and the report, with nothing read or written (`timings_ms.read` is
/// `read_ms`, `write` is 0, `total` is `read_ms` + the solve). The Python package calls
/// it on arrays; `--strict` is the caller's (see [`Solved::strict_violation`]).
///
/// # Errors
/// The memory check's refusal and every failure of [`MapJob::solve`].
pub fn solve_and_report(
    cmd: &dyn MapJob,
    input: &Input,
    memory: MemoryCheck,
    read_ms: f64,
) -> Result<(Solved, Report), Failure> {
    let t_solve = Instant::now();
    let mesh = &input.mesh;
    let what = format!(
        "{} of this mesh ({} vertices, {} faces)",
        cmd.work(),
        mesh.num_vertices(),
        mesh.num_faces()
    );
    let memory = memory
        .before_solving(cmd.peak_bytes(mesh), &what)
        .map_err(|f| input.fail(f))?;
    // in a batch, the memory this solve holds while it runs (a no-op elsewhere)
    let _solving = context::reserve(memory.estimate);
    context::stage(format!("{}: computing {what}", input.path.display()));
    let mut solved = cmd.solve(input)?;
    let timings = StageTimings {
        read: read_ms + solved.timings.read,
        write: 0.0,
        total: read_ms + ms_since(t_solve),
        ..solved.timings
    };
    let report = Report {
        conformap_version: env!("CARGO_PKG_VERSION"),
        command: cmd.name(),
        method: std::mem::take(&mut solved.method),
        input: InputInfo::new(&input.path, mesh),
        param: solved.param.take(),
        solver: solved.solver.clone(),
        sections: std::mem::take(&mut solved.sections),
        metrics: solved.metrics.clone(),
        memory: memory.report(),
        repairs: input.repairs.clone().map(RepairsReport),
        timings_ms: timings,
    };
    Ok((solved, report))
}

/// Runs `job` on `input`, a mesh already in memory: the job's usage check, the memory
/// check against `max_memory` (or the memory available), the solve and the report, with
/// nothing read or written. `strict` refuses what `--strict` refuses (the message says
/// `(strict=True)`, as the Python keyword is spelled).
///
/// # Errors
/// The usage check's, the memory check's and the solve's [`Failure`]s.
pub fn run_in_memory(
    job: &dyn MapJob,
    input: &Input,
    max_memory: Option<u64>,
    strict: bool,
) -> Result<(Solved, Report), Failure> {
    job.check_usage()?;
    let limit = match max_memory {
        Some(m) => Some((m, "max_memory")),
        None => conformap_operators::available_memory(),
    };
    // arrays in memory: nothing read, no file text kept
    let memory = MemoryCheck {
        read_estimate: 0,
        estimate: 0,
        file_bytes: 0,
        limit,
    };
    let (solved, report) = solve_and_report(job, input, memory, 0.0)?;
    if let Some(why) = solved.strict_violation.as_ref().filter(|_| strict) {
        return Err(input.fail(Failure::Numerical(format!("{why} (strict=True)"))));
    }
    Ok((solved, report))
}

/// The flat mesh of a planar map: `(u, v, 0)` per vertex.
pub fn planar_points(map: &[num_complex::Complex64]) -> Vec<[f64; 3]> {
    map.iter().map(|z| [z.re, z.im, 0.0]).collect()
}

/// Texture coordinates of a disk map: `((u + 1)/2, (v + 1)/2)`.
pub fn disk_uv(map: &[num_complex::Complex64]) -> Vec<[f64; 2]> {
    map.iter()
        .map(|z| [(z.re + 1.0) / 2.0, (z.im + 1.0) / 2.0])
        .collect()
}
