//! Options of the Möbius optimization: the objective, caps and tolerances.

/// Default Newton iteration cap per start: 100. Starts converge in 5–15 iterations on the
/// meshes measured; the cap only stops a start crawling along the ball's boundary.
pub const MOBIUS_MAX_ITER: usize = 100;

/// Default step tolerance: stop a start when an accepted step moves the boost by less than
/// `1e-9` (hyperbolic length), i.e. areas change by a relative 2e-9.
pub const MOBIUS_STEP_TOL: f64 = 1e-9;

/// Default hyperbolic length of the non-zero starts: 1 (area magnification `e² ≈ 7.4` at
/// the boost's centre), far enough to leave the basin of `u = 0` if there is another.
pub const MOBIUS_START_RADIUS: f64 = 1.0;

/// Default cap on the boost length for the uniformity energy: 15 (area magnification
/// `e³⁰ ≈ 1e13`); the optimum is far inside, the cap only keeps f64 meaningful.
pub const MOBIUS_MAX_BOOST: f64 = 15.0;

/// Default cap on the largest area magnification `e^{2|u|}` of the boost when emphasizing a
/// region: 10 (boost length `½ ln 10 ≈ 1.15`; no face grows or shrinks by more than 10×
/// through the Möbius map). Without a cap the emphasized share tends to 1 and the boost to
/// infinity (see the module docs); the share at the optimum is set by the cap — measured on
/// spot's and david_head's halves: cap 5 → 84–85 %, 10 → 91–92 %, 100 → 99 %, 10⁴ → 99.9 %.
pub const EMPHASIZE_MAX_AREA_SCALE: f64 = 10.0;

/// Largest `||x| − 1|` accepted for a given sphere map, and `|z| − 1` for a disk map: 1e-6.
/// Maps stored as f32 (glTF) carry ~1e-7 of rounding; anything farther is not such a map.
pub const MAP_RADIUS_TOL: f64 = 1e-6;

/// The area energy a Möbius transformation is chosen for.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum MobiusObjective {
    /// Minimize the uniformity energy `Σ (a_f − s_f)²` (Eq. 1–2, 7; §3.4).
    Uniform,
    /// Maximize the image-area share of these faces (Eq. 3–4, 8, 10), with the boost capped
    /// by [`MobiusOptions::max_area_scale`]. Repeated indices count once.
    Emphasize {
        /// 0-based face indices.
        region: Vec<usize>,
    },
    /// Maximize the region's mean log area magnification
    /// `Σ_{f ∈ D} s_f log(a_f / s_f) / Σ_{f ∈ D} s_f` (the log of its geometric-mean sampling
    /// density): a well-posed variant of [`Self::Emphasize`] with an interior optimum, since
    /// the faces of the region far from the boost's centre shrink without bound. Not in the
    /// paper; no cap needed (the uniformity cap [`MobiusOptions::max_boost`] applies).
    EmphasizeDensity {
        /// 0-based face indices.
        region: Vec<usize>,
    },
}

impl MobiusObjective {
    pub(crate) fn name(&self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Emphasize { .. } => "emphasize",
            Self::EmphasizeDensity { .. } => "emphasize-density",
        }
    }
}

/// Options of [`crate::optimize_sphere_mobius`] and [`crate::optimize_disk_mobius`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct MobiusOptions {
    /// Newton iterations per start. Default: [`MOBIUS_MAX_ITER`].
    pub max_iter: usize,
    /// Step tolerance. Default: [`MOBIUS_STEP_TOL`].
    pub step_tol: f64,
    /// Length of the non-zero starts. Default: [`MOBIUS_START_RADIUS`].
    pub start_radius: f64,
    /// Run the extra starts (`false`: only `u = 0`). Default: `true`: `u = 0` and the
    /// `±` axis directions at [`Self::start_radius`] (7 starts on the sphere, 5 on the
    /// disk). On every mesh measured all starts reached the same optimum; they are a guard,
    /// as the paper's random starts are.
    pub multi_start: bool,
    /// Cap on the boost length for [`MobiusObjective::Uniform`]. Default:
    /// [`MOBIUS_MAX_BOOST`].
    pub max_boost: f64,
    /// Cap on the boost's own largest area magnification for
    /// [`MobiusObjective::Emphasize`]. Default: [`EMPHASIZE_MAX_AREA_SCALE`]; must be > 1.
    pub max_area_scale: f64,
}

impl MobiusOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        max_iter: MOBIUS_MAX_ITER,
        step_tol: MOBIUS_STEP_TOL,
        start_radius: MOBIUS_START_RADIUS,
        multi_start: true,
        max_boost: MOBIUS_MAX_BOOST,
        max_area_scale: EMPHASIZE_MAX_AREA_SCALE,
    };

    /// Sets [`Self::max_iter`].
    #[must_use]
    pub fn with_max_iter(mut self, n: usize) -> Self {
        self.max_iter = n;
        self
    }

    /// Sets [`Self::multi_start`].
    #[must_use]
    pub fn with_multi_start(mut self, on: bool) -> Self {
        self.multi_start = on;
        self
    }

    /// Sets [`Self::start_radius`].
    #[must_use]
    pub fn with_start_radius(mut self, r: f64) -> Self {
        self.start_radius = r;
        self
    }

    /// Sets [`Self::max_area_scale`].
    #[must_use]
    pub fn with_max_area_scale(mut self, s: f64) -> Self {
        self.max_area_scale = s;
        self
    }

    /// Sets [`Self::max_boost`].
    #[must_use]
    pub fn with_max_boost(mut self, t: f64) -> Self {
        self.max_boost = t;
        self
    }

    /// Sets [`Self::step_tol`].
    #[must_use]
    pub fn with_step_tol(mut self, tol: f64) -> Self {
        self.step_tol = tol;
        self
    }
}

impl Default for MobiusOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
