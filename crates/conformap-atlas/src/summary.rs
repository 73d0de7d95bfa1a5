//! The [`SolverSummary`] of an atlas (the atlas decides whether it is clean) and its
//! peak-memory estimate.

use conformap_disk::{flatten_peak_bytes, FlattenOptions};
use conformap_mesh::TriMesh;
use conformap_operators::SolverSummary;

use crate::{AtlasOptions, AtlasReport};

impl AtlasReport {
    /// A direct method (no iteration): converged when the atlas is clean (no flipped face,
    /// no texel covered twice), its residual the largest seam length mismatch
    /// [`Self::seam_log_ratio_max`].
    pub fn summary(&self) -> SolverSummary {
        let clean = self.flipped == 0 && self.overlap.covered_twice == 0;
        SolverSummary::direct(clean, self.seam_log_ratio_max)
    }
}

/// Estimated peak resident memory (bytes) of [`crate::build_atlas`] on `mesh`: the cone
/// metric's factorization beside each chart's flattening.
pub fn atlas_peak_bytes(mesh: &TriMesh) -> u64 {
    2 * flatten_peak_bytes(mesh, &FlattenOptions::DEFAULT)
}

/// [`atlas_peak_bytes`] with the options' extra work: the polish factors a system of twice
/// the chart's vertices with 2 × 2 blocks, about as much again as the estimate without
/// (measured peak resident memory: kitten_53k 160 → 274 MB, armadillo 121 → 202 MB with
/// the polish, against 202 and 166 MB estimated without; 400 and 330 MB with). Counted
/// whenever the mode may polish a surface of this size (the spread is not known yet).
pub fn atlas_peak_bytes_with(mesh: &TriMesh, options: &AtlasOptions) -> u64 {
    let plain = atlas_peak_bytes(mesh);
    if options.polish.applies(mesh.num_vertices(), f64::INFINITY) {
        2 * plain
    } else {
        plain
    }
}
