//! Outputs of a command: every path checked before anything is computed, and all of them
//! written or none.
//!
//! [`check_command_outputs`] refuses, before reading, an output path that would overwrite an
//! input or another output (usage error), that has no mesh format where a mesh is written,
//! or whose directory is missing or not writable. [`Staged`] then writes each output to a
//! hidden sibling of its target and renames them all into place at [`Staged::commit`]; a
//! failure before the commit removes what was staged, so no output appears.

use std::collections::{HashMap, HashSet};
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use conformap_io::{Format, SourceInfo};
use conformap_mesh::TriMesh;
use rayon::prelude::*;
use serde::Serialize;

use crate::failure::{render_failure, Failure};
use crate::pipeline::options::{InputOptions, OutputOptions};
use crate::pipeline::staging::{self, directory_of};

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// `PREFIX_surface.png` and `PREFIX_map.png`.
pub fn png_paths(prefix: &Path) -> [PathBuf; 2] {
    ["_surface.png", "_map.png"].map(|suffix| {
        let mut name = OsString::from(prefix.as_os_str());
        name.push(suffix);
        PathBuf::from(name)
    })
}

/// Checks the outputs of `output` and `input.vertex_map` against each other and against
/// the inputs (`input.mesh` and `other_inputs`, e.g. a map file or a region).
///
/// # Errors
/// [`Failure::Usage`] for an output that names an input or another output, or a mesh
/// output without a mesh extension; [`Failure::BadInput`] for a directory that does not
/// exist or cannot be written.
pub fn check_command_outputs(
    input: &InputOptions,
    output: &OutputOptions,
    other_inputs: &[&Path],
) -> Result<(), Failure> {
    let mut outputs: Vec<(&str, &Path, bool)> = vec![("-o", &output.output, true)];
    if let Some(p) = &output.flat {
        outputs.push(("--flat", p, true));
    }
    if let Some(p) = &output.report {
        outputs.push(("--report", p, false));
    }
    if let Some(p) = &output.quality {
        check_overlay(p)?;
        outputs.push(("--quality-overlay", p, false));
    }
    if let Some(p) = &input.vertex_map {
        outputs.push(("--vertex-map", p, false));
    }
    let pictures = output.png.as_deref().map(png_paths);
    for p in pictures.iter().flatten() {
        outputs.push(("--png", p, false));
    }
    let inputs: Vec<&Path> = std::iter::once(input.mesh.as_path())
        .chain(other_inputs.iter().copied())
        .collect();
    check_outputs(&outputs, &inputs)
}

/// Whether `format` can hold what `flag` writes: `-o` a mesh with texture coordinates
/// (OBJ, glTF, GLB, PLY), `--flat` a mesh (those, GIfTI and FreeSurfer surfaces); STL and
/// OFF are read only. A usage error (exit 2) before anything is read or computed.
fn check_writable(flag: &str, path: &Path, format: Format) -> Result<(), Failure> {
    let texture = matches!(
        format,
        Format::Obj | Format::Gltf | Format::Glb | Format::Ply
    );
    let surface = texture || matches!(format, Format::Gifti | Format::FreeSurfer);
    let ok = if flag == "-o" { texture } else { surface };
    if ok {
        return Ok(());
    }
    Err(Failure::Usage(format!(
        "{flag} {}: this format cannot hold {}; write {} instead",
        path.display(),
        if flag == "-o" {
            "texture coordinates"
        } else {
            "the map as a surface"
        },
        if flag == "-o" {
            ".obj, .ply, .gltf or .glb (the map itself with --flat as .surf.gii or a \
             FreeSurfer surface)"
        } else {
            ".obj, .ply, .gltf, .glb, .surf.gii or a FreeSurfer surface"
        }
    )))
}

/// `--quality-overlay` names a GIfTI data file: a usage error (exit 2) before anything is
/// read otherwise.
fn check_overlay(path: &Path) -> Result<(), Failure> {
    if Format::from_path(path).is_ok_and(|f| f == Format::Gifti) {
        return Ok(());
    }
    Err(Failure::Usage(format!(
        "--quality-overlay {}: the per-vertex quality is a GIfTI data file: name it \
         .shape.gii (or .func.gii)",
        path.display()
    )))
}

/// Checks `outputs` (flag, path, is a mesh) against each other and against `inputs`, each
/// path normalized once and each directory probed once (a morph's thousands of frames in
/// one directory cost one probe), and removes from every output directory the staging
/// files of runs that were killed ([`staging::remove_stale_staging`]; the watcher is told).
pub fn check_outputs(outputs: &[(&str, &Path, bool)], inputs: &[&Path]) -> Result<(), Failure> {
    let inputs: Vec<(PathBuf, &Path)> = inputs.iter().map(|i| (normalized(i), *i)).collect();
    let mut seen: HashMap<PathBuf, &str> = HashMap::with_capacity(outputs.len());
    let mut directories: HashSet<PathBuf> = HashSet::new();
    for &(flag, path, mesh) in outputs {
        if mesh {
            let format =
                Format::from_path(path).map_err(|e| Failure::Usage(format!("{flag}: {e}")))?;
            check_writable(flag, path, format)?;
        }
        let key = normalized(path);
        if let Some((_, input)) = inputs.iter().find(|(k, _)| *k == key) {
            return Err(Failure::Usage(format!(
                "{flag} {} names the input file {}: it would be overwritten; write the \
                 output elsewhere",
                path.display(),
                input.display()
            )));
        }
        let dir = key.parent().map(Path::to_path_buf).unwrap_or_default();
        if let Some(other) = seen.insert(key, flag) {
            return Err(Failure::Usage(format!(
                "{other} and {flag} both name {}: one output would overwrite the other",
                path.display()
            )));
        }
        if directories.insert(dir) {
            check_directory(path)?;
            remove_stale(path);
        }
    }
    Ok(())
}

/// Removes the stale staging files in the directory of `path` and tells the watcher.
fn remove_stale(path: &Path) {
    let removed = staging::remove_stale_staging(&directory_of(path));
    if removed.is_empty() {
        return;
    }
    let names: Vec<String> = removed.iter().map(|p| p.display().to_string()).collect();
    crate::pipeline::context::notice(format!(
        "removed {} staging file(s) left by an interrupted earlier run: {}",
        removed.len(),
        names.join(", ")
    ));
}

/// `path` made absolute, its directory resolved through links where it exists.
fn normalized(path: &Path) -> PathBuf {
    let abs = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    match (abs.parent(), abs.file_name()) {
        (Some(dir), Some(name)) => dir
            .canonicalize()
            .map_or_else(|_| abs.clone(), |d| d.join(name)),
        _ => abs,
    }
}

/// The directory of `path` exists and accepts a new file.
fn check_directory(path: &Path) -> Result<(), Failure> {
    let dir = directory_of(path);
    // a file where a directory is expected (`-o file.obj/x.obj`): say so
    if let Some(file) = dir.ancestors().find(|a| a.is_file()) {
        return Err(Failure::BadInput(
            format!(
                "cannot write {}: {} is a file, not a directory",
                path.display(),
                file.display()
            ),
            Some("write the output into a directory (check the -o path)".to_string()),
        ));
    }
    if !dir.is_dir() {
        return Err(Failure::BadInput(
            format!(
                "cannot write {}: the directory {} does not exist",
                path.display(),
                dir.display()
            ),
            Some("create the directory first, or write the output elsewhere".to_string()),
        ));
    }
    let probe = dir.join(format!(
        ".conformap-probe-{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    match std::fs::File::create(&probe) {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => Err(Failure::BadInput(
            format!("cannot write {}: {e}", path.display()),
            Some("check the directory's permissions, or write the output elsewhere".into()),
        )),
    }
}

/// Outputs written beside their targets, renamed into place together by [`Staged::commit`]
/// (dropped uncommitted, they are removed).
#[derive(Debug, Default)]
pub struct Staged {
    files: Vec<(PathBuf, PathBuf)>,
}

impl Staged {
    /// No output staged yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// A registered hidden sibling of `target` with the same extension (the writers pick
    /// the format by extension): [`staging::stage_path`].
    fn stage_path(&mut self, target: &Path) -> PathBuf {
        let staged = staging::stage_path(target);
        self.files.push((staged.clone(), target.to_path_buf()));
        staged
    }

    /// Stages `mesh` with one texture coordinate per vertex (see
    /// [`conformap_io::write_mesh_with_uv`]).
    pub fn mesh_with_uv(
        &mut self,
        target: &Path,
        mesh: &TriMesh,
        uv: &[[f64; 2]],
        source: Option<&SourceInfo>,
    ) -> Result<(), Failure> {
        let path = self.stage_path(target);
        conformap_io::write_mesh_with_uv(&path, mesh, uv, source)
            .map_err(|e| renamed(e.into(), &path, target))
    }

    /// Stages `mesh` with a seamed map (see [`conformap_io::write_mesh_with_corner_uv`]).
    pub fn mesh_with_corner_uv(
        &mut self,
        target: &Path,
        mesh: &TriMesh,
        uv: &conformap_io::CornerUv,
    ) -> Result<(), Failure> {
        let path = self.stage_path(target);
        conformap_io::write_mesh_with_corner_uv(&path, mesh, uv)
            .map_err(|e| renamed(e.into(), &path, target))
    }

    /// Stages points and triangles, keeping what `source` says about the input surface
    /// when the output has its format (see [`conformap_io::write_flat_like`]).
    pub fn flat(
        &mut self,
        target: &Path,
        points: &[[f64; 3]],
        faces: &[[u32; 3]],
        source: Option<&SourceInfo>,
    ) -> Result<(), Failure> {
        let path = self.stage_path(target);
        conformap_io::write_flat_like(&path, points, faces, source)
            .map_err(|e| renamed(e.into(), &path, target))
    }

    /// Stages per-vertex data arrays as a GIfTI data file (see
    /// [`conformap_io::write_vertex_data`]).
    pub fn vertex_data(
        &mut self,
        target: &Path,
        columns: &[(&str, &[f64])],
    ) -> Result<(), Failure> {
        let path = self.stage_path(target);
        conformap_io::write_vertex_data(&path, columns)
            .map_err(|e| renamed(e.into(), &path, target))
    }

    /// Stages OBJ frames of one set of triangles: `points(i)` gives the vertex positions
    /// of the frame written to `targets[i]`. The face lines are formatted once
    /// ([`conformap_io::ObjFrames`]); the frames are computed, formatted and written in
    /// parallel, one buffered write each.
    pub fn obj_frames(
        &mut self,
        targets: &[PathBuf],
        faces: &[[u32; 3]],
        points: impl Fn(usize) -> Vec<[f64; 3]> + Sync,
    ) -> Result<(), Failure> {
        let frames = conformap_io::ObjFrames::new(faces);
        let staged: Vec<PathBuf> = targets.iter().map(|t| self.stage_path(t)).collect();
        staged
            .par_iter()
            .zip(targets)
            .enumerate()
            .try_for_each(|(i, (path, target))| {
                if staging::interrupted() {
                    return Err(Failure::input("the run was interrupted"));
                }
                frames
                    .write(path, &points(i))
                    .map_err(|e| renamed(e.into(), path, target))
            })
    }

    /// Stages a PNG picture.
    pub fn png(&mut self, target: &Path, image: &conformap_render::Image) -> Result<(), Failure> {
        let path = self.stage_path(target);
        image
            .save_png(&path)
            .map_err(|e| renamed(render_failure(e, &path), &path, target))
    }

    /// Stages a GLB with morph targets and an animation (see
    /// [`conformap_io::write_morph_glb`]).
    pub fn morph_glb(
        &mut self,
        target: &Path,
        morph: &conformap_io::MorphGlb<'_>,
    ) -> Result<(), Failure> {
        let path = self.stage_path(target);
        conformap_io::write_morph_glb(&path, morph).map_err(|e| renamed(e.into(), &path, target))
    }

    /// Stages a text file.
    pub fn text(&mut self, target: &Path, text: &str) -> Result<(), Failure> {
        let path = self.stage_path(target);
        std::fs::write(&path, text)
            .map_err(|e| Failure::input(format!("cannot write {}: {e}", target.display())))
    }

    /// Stages `value` as pretty JSON.
    pub fn json(&mut self, target: &Path, value: &impl Serialize) -> Result<(), Failure> {
        let text = serde_json::to_string_pretty(value)
            .map_err(|e| Failure::Numerical(format!("cannot serialize the report: {e}")))?;
        self.text(target, &(text + "\n"))
    }

    /// Renames every staged file onto its target (all of them while an interrupt waits,
    /// or none after one).
    pub fn commit(mut self) -> Result<(), Failure> {
        let files = std::mem::take(&mut self.files);
        staging::rename_all(&files).map_err(|(k, e)| {
            let rest: Vec<&Path> = files[k..].iter().map(|(s, _)| s.as_path()).collect();
            staging::discard(&rest);
            Failure::input(format!("cannot write {}: {e}", files[k].1.display()))
        })
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        let files: Vec<&Path> = self.files.iter().map(|(s, _)| s.as_path()).collect();
        staging::discard(&files);
    }
}

/// A write failure that names the target, not the staging file.
fn renamed(f: Failure, staged: &Path, target: &Path) -> Failure {
    let (s, t) = (staged.display().to_string(), target.display().to_string());
    match f {
        Failure::BadInput(m, h) => Failure::BadInput(m.replace(&s, &t), h),
        Failure::Usage(m) => Failure::Usage(m.replace(&s, &t)),
        Failure::Numerical(m) => Failure::Numerical(m.replace(&s, &t)),
    }
}
