//! Which charts the distortion polish ([`crate::chart::polish()`]) runs on: the atlas's
//! [`Polish`] mode and its thresholds (one module both the atlas and the chart code read,
//! so the chart can prepare the polish the atlas will run).

use conformap_mesh::TriMesh;
use serde::Serialize;

use crate::cones::ConeSet;

/// [`Polish::Auto`] polishes a chart whose cone metric spreads at least this much (sd of
/// the log area ratio): 0.5. The step wins back what the linearized metric misses, which
/// grows with `u`: measured against the same run without, spot (0.82 in the metric) 0.835
/// → 0.790 and armadillo (1.85) 1.860 → 1.718, −5 % and −8 %; below 0.5 it gains 0.4–1.4 %
/// (brain, david_head, kitten_53k, eight, fertility) and on eightsim (0.16) the spread
/// rises 0.164 → 0.173.
pub const POLISH_AUTO_SPREAD: f64 = 0.5;

/// [`Polish::Auto`] polishes charts of components of at most this many vertices: 20,000.
/// The step's factorization (twice the vertices, 2 × 2 blocks) grows faster than the rest
/// of the atlas: spot (2,930 vertices) +15–25 % of the whole run, armadillo (43,243)
/// +44 %, kitten_53k +65 %. Larger surfaces are polished with [`Polish::Always`].
pub const POLISH_AUTO_VERTICES: usize = 20_000;

/// Which charts the distortion polish ([`crate::chart::polish()`]) runs on. Never on a component with
/// boundary and no cones (its free-boundary layout is already the least distortion of its
/// kind; [`crate::AtlasOptions::polish`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Polish {
    /// No chart (`--polish=never`).
    Never,
    /// Charts whose cone metric spreads at least [`POLISH_AUTO_SPREAD`], of components of
    /// at most [`POLISH_AUTO_VERTICES`] vertices (the default): where the step pays and
    /// costs little.
    #[default]
    Auto,
    /// Every chart with cones (`--polish`).
    Always,
}

impl Polish {
    /// Whether the chart of `mesh` with cones `cones` is polished: [`Self::applies`], but
    /// never on a free boundary without cones (boundary first flattening's own least
    /// distortion: the polish would trade its angles for area there).
    pub(crate) fn polishes(self, mesh: &TriMesh, cones: &ConeSet) -> bool {
        let free = cones.cones.is_empty() && !mesh.boundary_loops().is_empty();
        !free && self.applies(mesh.num_vertices(), cones.area_spread)
    }

    /// Whether a chart of a component of `vertices` vertices whose cone metric spreads
    /// `spread` is polished (`spread` NaN: no cones, or not measured).
    pub fn applies(self, vertices: usize, spread: f64) -> bool {
        match self {
            Self::Never => false,
            Self::Always => true,
            Self::Auto => spread >= POLISH_AUTO_SPREAD && vertices <= POLISH_AUTO_VERTICES,
        }
    }
}
