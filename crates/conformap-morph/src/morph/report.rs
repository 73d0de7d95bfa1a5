//! What a morph reports: per key surface, its disk map, registration, location and the
//! quality of its key frame, with the time of every stage.

use serde::Serialize;

use crate::RegistrationReport;

/// Milliseconds per stage for one key surface.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct KeyTimings {
    /// The disk map (setup: Laplacian and factorization, and the method's iterations).
    pub disk_map: f64,
    /// The Möbius normalization.
    pub normalize: f64,
    /// The registration (0 for the first surface).
    pub register: f64,
    /// Point location of the first surface's vertices (0 for the first surface).
    pub locate: f64,
}

/// The disk map of one surface, in brief.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DiskSummary {
    /// Method name (`ccem-qn` by default).
    pub method: String,
    /// Conformal energy `E_C` of the returned map.
    pub conformal_energy: f64,
    /// Iterations of the method.
    pub iterations: usize,
    /// Whether the method converged.
    pub converged: bool,
    /// The method's notes.
    pub notes: Vec<String>,
}

/// How the first surface's vertices were located in this surface's registered disk.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct LocateSummary {
    /// Vertices found outside every triangle (just outside the boundary polygon) and
    /// snapped to the nearest point of the nearest triangle.
    pub snapped: usize,
    /// Largest distance (in the disk) of such a vertex from its triangle.
    pub max_outside: f64,
}

/// Everything about one key surface.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KeyReport {
    /// 0-based position among the surfaces (0 is S1).
    pub surface: usize,
    /// Its key time.
    pub time: f64,
    /// Vertices of its mesh.
    pub vertices: usize,
    /// Faces of its mesh.
    pub faces: usize,
    /// Length of its boundary loop.
    pub boundary_vertices: usize,
    /// Bounding-box diagonal of its mesh (the unit of the relative errors below).
    pub diagonal: f64,
    /// Its disk map.
    pub disk: DiskSummary,
    /// The registration onto S1's disk (`None` for S1 itself).
    pub registration: Option<RegistrationReport>,
    /// The location of S1's vertices in the registered disk (`None` for S1).
    pub locate: Option<LocateSummary>,
    /// Per landmark: the distance from S1's landmark vertex, carried to this surface,
    /// to this surface's landmark vertex, divided by [`Self::diagonal`].
    pub landmark_errors_rel: Vec<f64>,
    /// The largest of [`Self::landmark_errors_rel`].
    pub landmark_error_max_rel: f64,
    /// Faces of the key frame (S1's connectivity at this surface's positions) whose
    /// normal points against this surface's normal where they lie.
    pub key_frame_flipped_faces: usize,
    /// The largest edge-connected group of such faces (1 = isolated slivers only).
    pub key_frame_largest_flip_patch: usize,
    /// Of [`Self::key_frame_flipped_faces`], those away from creases: no crease face of S1
    /// (a face with a vertex on an edge whose faces' normals turn by more than
    /// [`crate::quality::CREASE_ANGLE_DEG`]) and no vertex located in a crease face of
    /// this surface. On the shared faces the creases are the pleated fills of the closed
    /// eye and mouth holes, where "the key surface's normal" flips from face to face.
    pub key_frame_flips_off_creases: usize,
    /// The largest edge-connected group of [`Self::key_frame_flips_off_creases`].
    pub key_frame_largest_flip_patch_off_creases: usize,
    /// Per stage.
    pub timings_ms: KeyTimings,
}

/// The report of a whole morph.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MorphReport {
    /// Landmark names, in order.
    pub landmarks: Vec<String>,
    /// One per surface, S1 first.
    pub keys: Vec<KeyReport>,
    /// Milliseconds of the whole computation (disk maps to homotopy).
    pub total_ms: f64,
}
