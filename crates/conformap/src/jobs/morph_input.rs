//! What `conformap morph` reads besides the meshes, what it will need and how it fails:
//! the landmark files, the memory estimate of the morph (the CLI and the Python package
//! check it before solving), and the failure of every morph error, naming the file.

use std::path::{Path, PathBuf};

use conformap_morph::{Landmarks, MorphError, MorphOptions, Surface};

use crate::failure::Failure;

/// Bytes per S1 vertex per frame being written: its position (3 f64) and its OBJ text
/// (`v x y z`, up to about 3 × 25 characters): `104`.
const FRAME_WRITE_BYTES_PER_VERTEX: u64 = 24 + 80;

/// Estimated peak resident memory (bytes) of the morph of `surfaces` and its output: every
/// surface's disk problem is prepared at once and kept through the registration (its
/// factorization serves every λ), so their peaks ([`conformap_disk::DiskMethod::peak_bytes`]
/// of the morph's disk method) add; then per key surface the position, location and
/// landing of S1's vertices and faces, and the frames written at once (one per thread).
pub fn morph_peak_bytes(surfaces: &[Surface], options: &MorphOptions) -> u64 {
    let disks: u64 = surfaces
        .iter()
        .map(|s| options.disk_method.peak_bytes(&s.mesh))
        .fold(0, u64::saturating_add);
    let Some(s1) = surfaces.first() else {
        return disks;
    };
    let (n, f) = (s1.mesh.num_vertices() as u64, s1.mesh.num_faces() as u64);
    let location = std::mem::size_of::<conformap_morph::Location>() as u64;
    let keys = (surfaces.len() as u64).saturating_mul(n * (24 + location) + f * location);
    let writers = rayon::current_num_threads() as u64;
    disks
        .saturating_add(keys)
        .saturating_add(writers.saturating_mul(n * FRAME_WRITE_BYTES_PER_VERTEX))
}

/// Reads and parses a landmark file; syntax errors name the file and line.
pub(crate) fn read_landmarks(path: &Path) -> Result<Landmarks, Failure> {
    let text = std::fs::read_to_string(path).map_err(|e| {
        Failure::BadInput(
            format!("{}: cannot read the landmark file: {e}", path.display()),
            Some("check the path and that the file is readable text".to_string()),
        )
    })?;
    Landmarks::parse(&text).map_err(|e| match e {
        MorphError::LandmarkSyntax { line, reason } => Failure::BadInput(
            format!("{}:{line}: {reason}", path.display()),
            Some("each line is `<0-based vertex index> <name>`".to_string()),
        ),
        other => Failure::input(other).in_file(path),
    })
}

/// The failure of a morph error, naming the surface's mesh or landmark file (`surfaces`
/// and `landmarks` name them, in order).
pub(crate) fn morph_failure(e: MorphError, surfaces: &[PathBuf], landmarks: &[PathBuf]) -> Failure {
    let mesh = |k: usize| surfaces[k].as_path();
    let lm = |k: usize| landmarks[k].as_path();
    match e {
        MorphError::Disk { surface, source } => Failure::from(source).in_file(mesh(surface)),
        MorphError::LandmarkOutOfRange { surface, .. }
        | MorphError::RepeatedLandmark { surface, .. }
        | MorphError::LandmarkMismatch { surface, .. }
        | MorphError::LandmarkOnBoundary { surface, .. }
        | MorphError::LandmarkNearCircle { surface, .. } => {
            let hint = match &e {
                MorphError::LandmarkMismatch { .. } => {
                    "every landmark file needs the same names in the same order"
                }
                MorphError::LandmarkOnBoundary { .. } => {
                    "put an interior vertex (e.g. the nose tip) first and second"
                }
                MorphError::LandmarkNearCircle { .. } => {
                    "put landmarks nearer the middle of the surface first and second, away \
                     from long or narrow parts of its boundary"
                }
                _ => "landmark indices are 0-based vertices of that surface's mesh, each once",
            };
            Failure::BadInput(e.to_string(), Some(hint.to_string())).in_file(lm(surface))
        }
        MorphError::TooFewSurfaces { .. } | MorphError::InvalidOption { .. } => {
            Failure::Usage(e.to_string())
        }
        MorphError::TooFewLandmarks { .. } | MorphError::LandmarkSyntax { .. } => Failure::input(e),
        other => Failure::Numerical(other.to_string()),
    }
}
