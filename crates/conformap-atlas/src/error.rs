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
}
