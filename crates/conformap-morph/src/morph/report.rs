//! What a morph reports: per key surface, its disk map, registration, location and the
//! quality of its key frame, with the time of every stage.

use serde::Serialize;

use crate::{RegistrationReport, WarpReport};

/// Milliseconds per stage for one key surface.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct KeyTimings {
    /// The disk map (setup: Laplacian and factorization, and the method's iterations).
    pub disk_map: f64,
    /// The Möbius normalization.
    pub normalize: f64,
    /// Finding the crease loops of every surface and factoring S1's extension (once for
    /// the whole morph, repeated in every key's report; 0 for the first surface).
    pub creases_setup: f64,
    /// The registration (0 for the first surface).
    pub register: f64,
    /// Carrying S1's crease loops (matching, targets, extension, fold check), point
    /// location of the first surface's vertices and faces, and the key frame's refinement
    /// (0 for the first surface).
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
    /// How S1's crease loops were carried onto this surface's (`None` for S1 and when
    /// [`crate::MorphOptions::match_creases`] is off).
    pub creases: Option<CreaseSummary>,
    /// The key frame's refinement on this surface (`None` for S1 and when
    /// [`crate::MorphOptions::refine_key_frames`] is off): faces whose normal pointed
    /// against the nearest key triangle before and after, the moves.
    pub refine: Option<crate::refine::RefineSummary>,
    /// Faces of the key frame (S1's connectivity at this surface's positions) whose
    /// normal points against this surface's normal where the face lies (the key face
    /// under the image of its centroid, [`crate::quality::flipped_against_key`]).
    pub key_frame_flipped_faces: usize,
    /// The largest edge-connected group of such faces (1 = isolated slivers only).
    pub key_frame_largest_flip_patch: usize,
    /// The same count with the earlier measure, the normals of the key faces the three
    /// vertices were located in ([`crate::quality::flipped_at_vertices`]), for
    /// comparison: it also counts faces along a crease of this surface whose vertices sit
    /// on the crease.
    pub key_frame_flipped_faces_at_vertices: usize,
    /// The largest edge-connected group of [`Self::key_frame_flipped_faces_at_vertices`].
    pub key_frame_largest_flip_patch_at_vertices: usize,
    /// Per stage.
    pub timings_ms: KeyTimings,
}

/// How S1's closed crease loops were carried onto one key surface's
/// ([`crate::creases`]).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct CreaseSummary {
    /// Closed crease loops of S1.
    pub loops_s1: usize,
    /// Closed crease loops of this surface.
    pub loops: usize,
    /// Pairs matched (each S1 loop and the loop of this surface nearest to it in the disk).
    pub matched: usize,
    /// Matched pairs cut at the points nearest to the landmarks near them (the mouth and
    /// eye corners of the shared faces): S1's loop vertices go to the same share of arc
    /// length between the same two anchors.
    pub landmark_anchored: usize,
    /// Landmarks used as anchors, over all matched pairs.
    pub landmark_anchors: usize,
    /// Matched pairs with no landmark near them, anchored where the ray from S1's
    /// loop's centre towards the nearest landmark crosses them.
    pub ray_anchored: usize,
    /// Matched pairs cut at their two vertices farthest apart in 3D (the corners of a
    /// slit) instead: tried only when the landmark cut's carry folds S1's disk
    /// ([`Self::folded_at_full_move`] > 0) and leaves flipped faces in the key frame,
    /// taken only when this cut leaves fewer ([`Self::flipped_faces_cut_at_landmarks`]).
    pub corner_anchored: usize,
    /// The key frame's flipped faces (the morph's own count,
    /// [`crate::quality::flipped_against_key`]) with the loops cut at the landmarks, when
    /// the corner cut was tried too (`None`: not tried; the landmark cut flipped nothing
    /// or its carry folded nothing, or no loop was matched).
    pub flipped_faces_cut_at_landmarks: Option<usize>,
    /// The same with the loops cut at their corners, when tried (`None` also when that
    /// cut's corner warp could not be solved: the landmark cut is kept).
    pub flipped_faces_cut_at_corners: Option<usize>,
    /// The rim vertices share arc length in the disk (S1's and the registered disk),
    /// not along the rims in 3D: taken only when it folds fewer faces of S1's moved disk.
    pub arc_length_in_disk: bool,
    /// Vertices of S1 placed exactly on this surface's loops (their whole move applied).
    pub rim_vertices: usize,
    /// The largest move (in the disk) of an S1 loop vertex onto this surface's loop.
    pub largest_move: f64,
    /// The smallest share of its move a loop vertex got: 1 when S1's disk, moved and
    /// untangled, folds no face; the moves near faces that would still fold are halved (up to
    /// [`crate::creases::RIM_MOVE_HALVINGS`] rounds), and those vertices are located
    /// where their partial move puts them; 0 when faces still folded then.
    pub smallest_share: f64,
    /// Faces of S1's disk the harmonic extension of the full move folds (before the
    /// untangling).
    pub folded_at_full_move: usize,
    /// Faces of S1's disk still folded after the untangling of the full move (before the
    /// corner warp).
    pub folded_after_untangling: usize,
    /// Corners of this surface's loops moved onto S1's by the corner warp (only corners
    /// near faces that fold after the untangling; 0: no corner warp).
    pub warped_corners: usize,
    /// The corner warp of this surface's registered disk (`None`: not needed). The
    /// registration's report describes the disk before it.
    pub corner_warp: Option<WarpReport>,
    /// `E_D` of the registered disk after the corner warp (`None`: no corner warp; the
    /// registration's `dirichlet_energy` is the one before).
    pub dirichlet_energy_after_corner_warp: Option<f64>,
    /// Free vertices of S1's moved disk the untangling moved into the kernel of their
    /// ring (`crate::creases` module docs; 0 when nothing folded).
    pub untangled_vertices: usize,
    /// Rounds of the untangling (at most [`crate::creases::UNTANGLE_MAX_ROUNDS`]) at the
    /// share of the move finally applied.
    pub untangling_rounds: usize,
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
