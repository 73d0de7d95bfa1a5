//! The one error type of this crate.

/// Why charts cannot be packed. Every variant says what to change.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum AtlasError {
    /// A chart point is NaN or infinite.
    #[error("chart {chart} has a non-finite point ({index}); every layout point must be finite")]
    NonFinite {
        /// The chart.
        chart: usize,
        /// The point within it.
        index: usize,
    },
    /// An option is out of range.
    #[error("{name} = {value} is out of range: {why}")]
    InvalidOption {
        /// The option's name.
        name: &'static str,
        /// Its value, as given.
        value: String,
        /// What it must be.
        why: &'static str,
    },
    /// The Laplacian of a chart could not be factored.
    #[error("the surface's Laplacian could not be factored: {why}")]
    Factorization {
        /// The solver's message.
        why: String,
    },
    /// The surface could not be cut into a disk (a cut that does not leave a manifold).
    #[error("the surface could not be cut into a disk: {0}")]
    Mesh(String),
    /// A cut chart could not be flattened.
    #[error("a chart could not be flattened: {0}")]
    Flatten(String),
    /// A connected component of the input is not a valid mesh.
    #[error("component {index} is not a valid mesh: {why}")]
    Component {
        /// The component (in the order of its first face).
        index: usize,
        /// What is wrong.
        why: String,
    },
    /// The margins alone do not fit: too many charts for the resolution.
    #[error(
        "{charts} charts with a margin of {margin} texels do not fit in a {resolution}² \
         texture even at the smallest scale; raise the resolution or lower the margin"
    )]
    TooManyCharts {
        /// Number of charts.
        charts: usize,
        /// Margin in texels.
        margin: f64,
        /// Texels a side.
        resolution: usize,
    },
    /// `--seamless` left folded faces on a component: the zeros of the holomorphic 1-form
    /// of a genus ≥ 2 surface are cones of 4π, whose layout can fold beside them.
    #[error(
        "--seamless could not lay out component {component} (genus {genus}) without folds: \
         {flipped} faces stay flipped beside the zeros of its holomorphic 1-form"
    )]
    SeamlessFolds {
        /// The component (in the order of its first face).
        component: usize,
        /// Its genus.
        genus: i64,
        /// Faces left flipped.
        flipped: usize,
    },
    /// `--seamless` left a seam that is no quarter-turn rigid map (beyond
    /// [`crate::SEAMLESS_TOLERANCE`]).
    #[error(
        "--seamless left a seam that is not rigid: its rotation is {rotation:.2e} rad off a \
         quarter turn and {residual:.2e} of the edge length is left after the rigid map"
    )]
    SeamlessNotRigid {
        /// The largest rotation error, radians.
        rotation: f64,
        /// The largest residual, relative to the edge length.
        residual: f64,
    },
}

impl AtlasError {
    /// What the user can do about it.
    pub fn hint(&self) -> &'static str {
        match self {
            Self::InvalidOption { .. } => "change the option as the message says",
            Self::TooManyCharts { .. } => "raise --resolution or lower --margin",
            Self::SeamlessFolds { .. } | Self::SeamlessNotRigid { .. } => {
                "run without --seamless: the default atlas lays out every genus without folds, \
                 its seams of equal length on both sides but not rigid on genus ≥ 2"
            }
            Self::Component { .. } => {
                "fix that component in the file or remove it (--repair keeps the largest \
                 component only)"
            }
            Self::NonFinite { .. }
            | Self::Factorization { .. }
            | Self::Mesh(_)
            | Self::Flatten(_) => {
                "`conformap info MESH` shows degenerate or nearly coincident faces, which \
                 break the solve; remove them and run again"
            }
        }
    }
}
