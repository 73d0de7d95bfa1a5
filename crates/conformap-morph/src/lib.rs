//! Surface morphing for conformap: landmark registration between disk maps, point
//! location on the disk, cubic-spline homotopy through 2+ surfaces (CEM §6).
//!
//! Depends on `conformap-disk` (the disk map, and its factorization of `L_II`, reused by
//! the registration), `conformap-sphere` (the disk automorphisms of the normalization),
//! `conformap-operators` (the dense Cholesky of the landmark system) and
//! `conformap-mesh`; never touches files and never prints.
//!
//! # Contents (one algorithm per module)
//! - `landmarks`: [`Landmarks`] — parse `<0-based vertex> <name>` lines, check range,
//!   repeats and matching names.
//! - `normalize`: [`normalize_disk_map`] — the paper's `m₁`: first landmark to the centre,
//!   second onto the positive real axis.
//! - `register`: [`register_disk`] — Eq. 34, `E_D + λ Σ|h(l_j) − t_j|²`, boundary sliding
//!   on the circle, soft or hard landmarks ([`LandmarkMode`]), the fold check, the λ
//!   back-off and, where Eq. 34 folds, the fold-free landmark warp ([`WarpOptions`]) that
//!   brings the landmarks the rest of the way ([`Registration`], [`RegistrationReport`]).
//! - `locate`: [`TriangleGrid`] — point location in a registered disk ([`Location`]).
//! - `homotopy`: [`CubicHomotopy`] — the natural cubic spline in time, as K weight
//!   functions.
//! - `morph`: [`morph()`] → [`Morph`] — all of the above for K surfaces, with a
//!   [`MorphReport`] per key surface; [`Morph::frame`] gives the positions at any time.
//! - [`creases`]: closed crease loops (e.g. the rims of zipped hole fills) and how S1's
//!   are carried onto every key surface's.
//! - [`refine`]: the key frames' local refinement on their key surfaces: vertices of faces
//!   that point against the key triangle nearest to them slide within the key surface.
//! - `quality`: checks of frames (flips against the key surface, creases, fold patches,
//!   degenerate faces, steps, point–triangle distance).
//!
//! # Example
//! ```
//! use conformap_morph::{morph, MorphOptions, Surface};
//! # let ((a, la), (b, lb)) = conformap_morph::doc_support::two_bumps_with_landmarks();
//! // `a`, `b`: two disk-like meshes (here a bump on two different grids, the second
//! // deformed); `la`, `lb`: their landmarks, the same names in the same order
//! // (`Landmarks::parse` reads the `<vertex> <name>` lines of a landmark file)
//! let m = morph(&[Surface::new(a.clone(), la), Surface::new(b.clone(), lb)], &MorphOptions::DEFAULT)?;
//! assert_eq!(m.frame(0.0), a.positions()); // frame 0 is S1, bit for bit
//! let key = &m.report.keys[1];
//! assert!(key.landmark_error_max_rel < 0.01);
//! assert_eq!(key.registration.as_ref().map(|r| r.folded_faces), Some(0));
//! # Ok::<(), conformap_morph::MorphError>(())
//! ```

pub mod creases;
mod error;
mod homotopy;
mod landmarks;
mod locate;
mod morph;
mod normalize;
pub mod quality;
pub mod refine;
mod register;

#[doc(hidden)]
pub mod doc_support;

pub use error::MorphError;
pub use homotopy::CubicHomotopy;
pub use landmarks::Landmarks;
pub use locate::{Location, TriangleGrid, LOCATE_INSIDE_TOL, LOCATE_TRIANGLES_PER_CELL};
pub use morph::{
    morph, CreaseSummary, DiskSummary, KeyReport, KeyTimings, LocateSummary, Morph, MorphOptions,
    MorphReport, Surface, CORNER_WARP_SUPPORT,
};
pub use normalize::{normalize_disk_map, Normalized, NORMALIZE_BOUNDARY_TOL};
pub use register::{
    folded_faces, register_disk, LandmarkMode, RegisterOptions, Registration, RegistrationReport,
    WarpOptions, WarpReport, DEFAULT_LAMBDA, LAMBDA_BACKOFF, LAMBDA_BISECTIONS,
    MAX_LAMBDA_BACKOFFS, REGISTER_MAX_SWEEPS, REGISTER_SWEEP_TOL, SEARCH_SWEEPS, WARP_MAX_STEPS,
    WARP_STEP, WARP_SUPPORT,
};
