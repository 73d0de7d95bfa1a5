//! Genus-0 conformal maps for conformap: sphere maps of closed genus-0 meshes, stereographic
//! projection, Möbius transforms of disk and sphere maps and their optimization, the double
//! covering of a disk.
//!
//! Depends on `conformap-mesh` (validated meshes), `conformap-operators` (cotangent
//! Laplacian, sparse Cholesky, vector primitives), `conformap-disk` (Angenent's dipole
//! right-hand side, and the harmonic extension used by the double-cover route) and
//! `conformap-metrics` (summary statistics); never touches files, never prints, owns no
//! planar-map metric (those are `conformap-metrics'`) and no holomorphic 1-form (genus ≥ 1
//! surfaces are `conformap-global`'s).
//!
//! # Contents
//! - **Sphere maps** of closed genus-0 meshes: [`sphere_map`] (Angenent's map, inverse
//!   stereographic projection, harmonic corrections in the opposite chart) →
//!   [`SphereMap`], configured by [`SphereOptions`], judged by [`sphere_metrics`] →
//!   [`SphereMetrics`] (radius residual, inverted faces, chord-angle distortion, Beltrami
//!   `|μ|` in stereographic charts, area distortion, uniformity energy, Möbius-invariant
//!   cross-ratio distortion).
//! - **Stereographic projection** and its inverse in both charts ([`stereographic`],
//!   [`inverse_stereographic`], …), and the equirectangular texture coordinates of a sphere
//!   map ([`equirectangular_uv`], [`from_equirectangular_uv`]); the texture to write,
//!   one coordinate per face corner, split along the seam meridian and with the poles
//!   treated ([`equirectangular_corner_uv`] → [`SphereTexture`], read back by
//!   [`sphere_points_from_corner_uv`]).
//! - **Möbius maps**: [`Mobius`] (`(az + b)/(cz + d)`, `ad − bc = 1`, acting on the sphere
//!   through [`stereographic`]) and [`DiskAutomorphism`] (`(az + b)/(b̄z + ā)`); their
//!   optimization for the uniformity or emphasized-area energies of Jin et al. (2004, §3.4):
//!   [`optimize_sphere_mobius`], [`optimize_disk_mobius`] with [`MobiusObjective`] and
//!   [`MobiusOptions`] → [`MobiusReport`].
//! - **Double covering** of a disk mesh: [`double_cover`], and the disk map through it,
//!   [`double_cover_disk_map`] — a second route to the disk map, independent of CEM.
//!   [`double_cover_surface`] doubles any surface with boundary (the closed surface
//!   `conformap-global` maps by 1-forms).
//! - Energies on their own: [`sphere_uniformity_energy`], [`disk_uniformity_energy`],
//!   [`sphere_region_share`], [`disk_region_share`], [`region_mask`], and their per-face
//!   parts ([`surface_shares`], [`sphere_face_areas`], [`planar_face_areas`],
//!   [`uniformity_from_areas`]).
//! - [`SphereError`]: the one error type.
//!
//! # Example
//! ```
//! use conformap_sphere::{
//!     optimize_sphere_mobius, sphere_map, sphere_metrics, MobiusObjective, MobiusOptions,
//!     SphereOptions,
//! };
//! # let mesh = conformap_sphere::doc_support::octahedron_sphere(3);
//! // `mesh`: a closed genus-0 mesh (here an ellipsoid of 258 vertices)
//! let map = sphere_map(&mesh, &SphereOptions::DEFAULT)?;
//! let before = sphere_metrics(&mesh, &map.points)?;
//! assert!(before.radius_residual_max < 1e-12);
//! assert_eq!(before.flipped_faces, 0);
//! // the Möbius map that spreads area most evenly: lower energy, same conformality
//! let best = optimize_sphere_mobius(&mesh, &map.points, &MobiusObjective::Uniform, &MobiusOptions::DEFAULT)?;
//! let after = sphere_metrics(&mesh, &best.points)?;
//! assert!(after.uniformity_energy < before.uniformity_energy);
//! assert!((after.cross_ratio_log.mean_abs - before.cross_ratio_log.mean_abs).abs() < 1e-12);
//! # Ok::<(), conformap_sphere::SphereError>(())
//! ```

mod double_cover;
mod error;
mod mobius;
mod sphere;
mod stereo;
mod summary;
mod texture;

#[doc(hidden)]
pub mod doc_support;

pub use double_cover::{
    double_cover, double_cover_disk_map, double_cover_surface, DoubleCover, DoubleCoverDisk,
    DoubleCoverReport,
};
pub use error::SphereError;
pub use mobius::energy::{
    disk_region_share, disk_uniformity_energy, planar_face_areas, region_mask, sphere_face_areas,
    sphere_region_share, sphere_uniformity_energy, surface_shares, uniformity_from_areas,
};
pub use mobius::maps::{
    boost_sphere_point, DiskAutomorphism, Mobius, MobiusCoefficients, MOBIUS_SINGULAR_REL,
};
pub use mobius::optimize::{
    optimize_disk_mobius, optimize_sphere_mobius, DiskMobius, MobiusReport, SphereMobius,
    StartRecord,
};
pub use mobius::options::{
    MobiusObjective, MobiusOptions, EMPHASIZE_MAX_AREA_SCALE, MAP_RADIUS_TOL, MOBIUS_MAX_BOOST,
    MOBIUS_MAX_ITER, MOBIUS_START_RADIUS, MOBIUS_STEP_TOL,
};
pub use sphere::map::{
    sphere_map, SphereMap, SphereOptions, SPHERE_FIXED_FRACTION, SPHERE_MAX_CORRECTIONS,
    SPHERE_MIN_GAIN, SPHERE_SOLVE_RESIDUAL_TOL,
};
pub use sphere::metrics::{
    sphere_cross_ratio_distortion, sphere_metrics, SphereMetrics, SPHERE_BELTRAMI_CAP,
};
pub use sphere::report::{SphereReport, StageRecord, Timings};
pub use sphere::source::sphere_source_face;
pub use stereo::{
    equirectangular_uv, from_equirectangular_uv, inverse_stereographic,
    inverse_stereographic_south, stereographic, stereographic_south,
};
pub use summary::{double_cover_peak_bytes, mobius_peak_bytes, sphere_peak_bytes};
pub use texture::{
    equirectangular_corner_uv, sphere_points_from_corner_uv, SphereTexture, SPHERE_POLAR_READ,
    SPHERE_POLE_REL, SPHERE_UV_AGREE_TOL,
};

/// The README's example, compiled and run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
