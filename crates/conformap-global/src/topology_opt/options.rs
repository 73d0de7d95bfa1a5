//! Options of [`crate::topology_opt`].

use crate::forms::{FormSearchOptions, GlobalMapOptions};

/// Default slit length as a fraction of the bounding-box diagonal: `0.04`. The prototype of
/// issue 23 found 3–5 % of the diagonal best; the length is set in 3D units, not in edges,
/// so that a refined mesh gets the same slits (a fixed edge count gave 1.34× instead of
/// 0.58× of the sphere map's energy on a 1-to-4 subdivided mesh).
pub const DEFAULT_SLIT_LENGTH: f64 = 0.04;

/// Default cap on the number of slits: `16`. Enough for a limbed shape such as armadillo
/// to reach the 12–16 slits where the prototype measured its best energies (measured here:
/// 13 slits 0.33×, 18 slits 0.17×, 24 slits 0.155× of the sphere map's energy), while the
/// cost of the form search grows as `F·g⁴` (its moments): 24 slits on armadillo take
/// minutes per step.
pub const DEFAULT_MAX_SLITS: usize = 16;

/// Default number of steps without a new best energy before the loop stops: `3`. The
/// energy is not monotone in the slit count (2 slits on spot: 10× the sphere map's energy,
/// 4 slits ≈ 1×, 8 slits ≈ 0.5×), so one increase is no reason to stop; on the disk
/// alligator the first two steps (2 and 4 slits) cost 7.4× and 1.4× the disk map's energy,
/// the third 1.0×, and 9 slits 0.67×, 16 slits 0.35× (32 slits 0.12×): with a patience of 2
/// the loop stopped before the slits paid.
pub const DEFAULT_PATIENCE: usize = 3;

/// Default share of the surface area taken by the extreme vertices: `0.05`. The vertices of
/// most shrunken area whose 3D vertex areas add up to 5 % of the surface form the clusters
/// (the tips of the limbs on a sphere map of armadillo or spot).
pub const DEFAULT_EXTREME_AREA_FRACTION: f64 = 0.05;

/// Default largest area ratio (image share over surface share, per vertex) that counts as
/// extreme: `0.125`. Vertices shrunk less than 8× are never slit: on a compact shape
/// (a head, a brain) no vertex qualifies and the loop stops at once with the sphere map.
pub const DEFAULT_MAX_EXTREME_AREA_RATIO: f64 = 0.125;

/// Basis forms the uniform search of each slit surface starts from (the lowest-energy
/// ones): `2`. With 2 of them and [`TOPOLOGY_RANDOM_STARTS`] random starts the search
/// reached the same optimum as all `2g` basis forms plus 48 random starts at every step on
/// spot (genus 4 to 15, energies equal to 5 digits) at a third of the time: at genus 15 each
/// start costs hundreds of milliseconds (`O(g⁴)` per Newton step).
pub const TOPOLOGY_BASIS_STARTS: usize = 2;

/// Random starts of the uniform search of each slit surface: `2` (see
/// [`TOPOLOGY_BASIS_STARTS`]).
pub const TOPOLOGY_RANDOM_STARTS: usize = 2;

/// Options of [`crate::topology_opt`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct TopologyOptOptions {
    /// Slit length as a fraction of the bounding-box diagonal. Default
    /// [`DEFAULT_SLIT_LENGTH`].
    pub slit_length: f64,
    /// Most slits in all. Default [`DEFAULT_MAX_SLITS`].
    pub max_slits: usize,
    /// Steps without a new best energy before stopping. Default [`DEFAULT_PATIENCE`].
    pub patience: usize,
    /// Share of the surface area the extreme vertices may hold. Default
    /// [`DEFAULT_EXTREME_AREA_FRACTION`].
    pub extreme_area_fraction: f64,
    /// Largest per-vertex area ratio counted as extreme. Default
    /// [`DEFAULT_MAX_EXTREME_AREA_RATIO`].
    pub max_extreme_area_ratio: f64,
    /// The global maps of the slit surfaces. Default: [`GlobalMapOptions::DEFAULT`] with
    /// the uniform objective, no least-uniform comparison (the loop needs only the most
    /// uniform form), [`TOPOLOGY_BASIS_STARTS`] basis and [`TOPOLOGY_RANDOM_STARTS`] random
    /// starts.
    pub global: GlobalMapOptions,
}

impl TopologyOptOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        slit_length: DEFAULT_SLIT_LENGTH,
        max_slits: DEFAULT_MAX_SLITS,
        patience: DEFAULT_PATIENCE,
        extreme_area_fraction: DEFAULT_EXTREME_AREA_FRACTION,
        max_extreme_area_ratio: DEFAULT_MAX_EXTREME_AREA_RATIO,
        global: GlobalMapOptions {
            search: FormSearchOptions {
                starts: TOPOLOGY_RANDOM_STARTS,
                basis_starts: Some(TOPOLOGY_BASIS_STARTS),
                compare: false,
                ..FormSearchOptions::DEFAULT
            },
            form: GlobalMapOptions::DEFAULT.form,
            objective: crate::forms::Objective::Uniform,
            conjugate: GlobalMapOptions::DEFAULT.conjugate,
            root: GlobalMapOptions::DEFAULT.root,
            cholesky: GlobalMapOptions::DEFAULT.cholesky,
        },
    };

    /// Sets [`Self::slit_length`].
    #[must_use]
    pub fn with_slit_length(mut self, fraction: f64) -> Self {
        self.slit_length = fraction;
        self
    }

    /// Sets [`Self::max_slits`].
    #[must_use]
    pub fn with_max_slits(mut self, max_slits: usize) -> Self {
        self.max_slits = max_slits;
        self
    }

    /// Sets [`Self::patience`].
    #[must_use]
    pub fn with_patience(mut self, patience: usize) -> Self {
        self.patience = patience;
        self
    }

    /// Sets [`Self::global`].
    #[must_use]
    pub fn with_global(mut self, global: GlobalMapOptions) -> Self {
        self.global = global;
        self
    }
}

impl Default for TopologyOptOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
