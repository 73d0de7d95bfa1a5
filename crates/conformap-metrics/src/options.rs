//! Options of [`crate::planar_map_metrics`].

/// What the outer boundary loop is compared with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum OuterCircle {
    /// The unit circle `|f| = 1`, the target of conformap's disk maps: the residual is
    /// `max ||f| − 1|`.
    #[default]
    Unit,
    /// Its own best-fit circle, like the other loops (for maps normalized differently, e.g.
    /// another tool's disk of radius ½ centred at ½ + ½i).
    BestFit,
}

/// Options of [`crate::planar_map_metrics`].
///
/// ```
/// use conformap_metrics::{MetricsOptions, OuterCircle};
/// let options = MetricsOptions::DEFAULT.with_outer_loop(2).with_outer_circle(OuterCircle::BestFit);
/// assert_eq!(options.outer_loop, Some(2));
/// assert_eq!(MetricsOptions::default(), MetricsOptions::DEFAULT);
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct MetricsOptions {
    /// Index into `mesh.boundary_loops()` of the loop that maps to the outer circle.
    /// Default: `None`, the longest loop (ties: the first), as `conformap disk` chooses.
    pub outer_loop: Option<usize>,
    /// What the outer loop is compared with. Default: [`OuterCircle::Unit`].
    pub outer_circle: OuterCircle,
    /// Whether a mirrored map (negative image area) is conjugated before it is scored, so a
    /// tool that flips `v` is not punished for it. Default: `true`.
    pub fix_orientation: bool,
}

impl MetricsOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        outer_loop: None,
        outer_circle: OuterCircle::Unit,
        fix_orientation: true,
    };

    /// Sets [`Self::outer_loop`] to loop `index`.
    #[must_use]
    pub fn with_outer_loop(mut self, index: usize) -> Self {
        self.outer_loop = Some(index);
        self
    }

    /// Sets [`Self::outer_circle`].
    #[must_use]
    pub fn with_outer_circle(mut self, outer_circle: OuterCircle) -> Self {
        self.outer_circle = outer_circle;
        self
    }

    /// Sets [`Self::fix_orientation`].
    #[must_use]
    pub fn with_fix_orientation(mut self, fix: bool) -> Self {
        self.fix_orientation = fix;
        self
    }
}

impl Default for MetricsOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
