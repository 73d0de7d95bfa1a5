//! The boundary a flattening targets ([`FlattenBoundary`]): the free boundary, given scale
//! factors or exterior angles, BFF's circle, rectangles and polygons.

/// The boundary a flattening targets. Vertices are 0-based indices of the input mesh;
/// angles are exterior (turning) angles in radians, positive where the boundary turns left
/// (the surface lies to the left of the boundary loop).
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub enum FlattenBoundary {
    /// `u = 0` on the boundary: the boundary keeps its lengths; of all conformal
    /// flattenings, the one of least area distortion. The default.
    #[default]
    Free,
    /// Given boundary scale factors `(vertex, u)`, every boundary vertex once.
    Scale(Vec<(u32, f64)>),
    /// Given exterior angles `(vertex, angle)`, every boundary vertex once, summing to `2π`.
    Angles(Vec<(u32, f64)>),
    /// BFF's disk: the boundary on a circle, spaced by the flattening's own lengths.
    Circle,
    /// A rectangle: `π/2` at four corners, straight sides.
    Rectangle {
        /// The corners in boundary order (the first to the second is the width); `None`
        /// chooses them automatically (see [`CLEAR_CORNER_RAD`](crate::CLEAR_CORNER_RAD) for the rule).
        corners: Option<[u32; 4]>,
        /// Width over height; `None` keeps the conformal modulus of the quadrilateral.
        /// Otherwise the conformal rectangle is stretched affinely to it (the extremal
        /// quasiconformal map between rectangles).
        aspect: Option<f64>,
    },
    /// A polygon: `(vertex, exterior angle)` per corner in boundary order, summing to `2π`;
    /// straight sides between corners.
    Polygon(Vec<(u32, f64)>),
}

impl FlattenBoundary {
    /// The name used in reports: `free`, `scale`, `angles`, `circle`, `rectangle`, `polygon`.
    pub fn name(&self) -> &'static str {
        match self {
            Self::Free => "free",
            Self::Scale(_) => "scale",
            Self::Angles(_) => "angles",
            Self::Circle => "circle",
            Self::Rectangle { .. } => "rectangle",
            Self::Polygon(_) => "polygon",
        }
    }

    /// Whether this target solves a Neumann problem (a second factorization, of `L`).
    pub fn needs_neumann(&self) -> bool {
        !matches!(self, Self::Free | Self::Scale(_))
    }
}
