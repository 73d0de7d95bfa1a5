//! The command-specific top-level sections of a report ([`Sections`]).

use conformap_global::{GlobalTimings, ObjectiveReport, TopologyStep};
use serde::Serialize;

use super::sorted::Sorted;

/// The command-specific top-level sections of a report, each present only for the
/// commands that have it (declared in alphabetical order, the order they are written in).
#[derive(Debug, Clone, Default, Serialize)]
pub struct Sections {
    /// The atlas (`atlas`): components, charts, cones, overlap, packing.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub atlas: Option<conformap_atlas::AtlasReport>,
    /// The disk with circular holes (`disk` on several boundary loops).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub circle_domain: Option<CircleDomainSection>,
    /// The one sparse factorization of the solve (`disk`, `global`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub factorization: Option<FactorizationSection>,
    /// The boundary first flattening (`flatten`): boundary mode, corners, the curve's
    /// closing, the boundary scale factors, overlap.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub flatten: Option<conformap_disk::FlattenReport>,
    /// The holomorphic form, its periods, zeros and seams (`global`), keys sorted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub global: Option<Sorted<GlobalSection>>,
    /// The topological optimization's steps and slits (`global --topology-opt`), keys
    /// sorted.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub topology_opt: Option<Sorted<TopologySection>>,
}

/// The `circle_domain` section (fields in alphabetical order, as written).
#[derive(Debug, Clone, Serialize)]
pub struct CircleDomainSection {
    /// Every loop's fitted circle: centre, radius, residual.
    pub circles: Vec<conformap_operators::LoopCircle>,
    /// For two loops, the conformal modulus ln(R/r).
    pub modulus: Option<f64>,
    /// How the domain is normalized.
    pub normalization: &'static str,
    /// The loop mapped onto the unit circle.
    pub outer_loop: usize,
    /// The hole centred at 0 (the lowest loop index), if any.
    pub reference_hole: Option<usize>,
}

/// The `factorization` section: the size of the one sparse factor.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum FactorizationSection {
    /// The interior Laplacian `L_II` of a disk map (fields in alphabetical order).
    Interior {
        /// Interior vertices (the dimension of `L_II`).
        interior_vertices: usize,
        /// Nonzeros of the Cholesky factor.
        nnz_factor: usize,
        /// The fill-reducing ordering used.
        ordering: &'static str,
    },
    /// The Laplacian of the surface the forms live on (`global`).
    Forms {
        /// Its dimension.
        dim: usize,
        /// Nonzeros of the factor.
        nnz_factor: usize,
    },
}

/// The `global` section: the holomorphic form, its periods, zeros and seams.
#[derive(Debug, Clone, Serialize)]
pub struct GlobalSection {
    /// Genus of the input.
    pub genus: usize,
    /// Boundary loops of the input.
    pub boundaries: usize,
    /// Whether the forms live on the double covering.
    pub double_covered: bool,
    /// Genus of the closed surface the forms live on.
    pub surface_genus: usize,
    /// Boundary chords split by the double covering.
    pub split_boundary_chords: usize,
    /// Number of homology generators.
    pub generators: usize,
    /// Their lengths.
    pub generator_lengths: Vec<f64>,
    /// The basis form chosen (for the `basis` objective).
    pub form: usize,
    /// Uniformity of each basis form.
    pub form_uniformity: Vec<f64>,
    /// The objective of the choice of form and what it reached.
    pub objective: ObjectiveReport,
    /// The conjugation: `gu-yau` or `nearest`.
    pub conjugate: &'static str,
    /// Periods: rows generators, columns basis forms, `[re, im]`.
    pub period_matrix: Vec<Vec<[f64; 2]>>,
    /// How `period_matrix` is laid out.
    pub period_matrix_layout: &'static str,
    /// Riemann's bilinear relations of the period matrix (relative).
    pub bilinear_residual: f64,
    /// The same with Gu–Yau's conjugate.
    pub bilinear_residual_gu_yau: f64,
    /// Distance of the conjugation from a complex structure.
    pub complex_structure_defect: f64,
    /// The modulus τ of a torus, `[re, im]`.
    pub tau: Option<[f64; 2]>,
    /// τ by Gu–Yau's conjugate.
    pub tau_gu_yau: Vec<[f64; 2]>,
    /// The zeros of the form on the input.
    pub zeros: Vec<ZeroEntry>,
    /// Sum of the zeros' multiplicities on the surface the forms live on.
    pub zero_multiplicity_sum_surface: i64,
    /// Clusters of negative multiplicity.
    pub negative_clusters: usize,
    /// Residual of the winding numbers.
    pub winding_residual: f64,
    /// Seam edges of the layout.
    pub seam_edges: usize,
    /// Largest mismatch of a seam's two sides from a pure translation.
    pub seam_residual: f64,
    /// Diagonal of the layout's bounding box.
    pub layout_diagonal: f64,
    /// Offset of the texture coordinates.
    pub uv_offset: [f64; 2],
    /// Scale of the texture coordinates.
    pub uv_scale: f64,
    /// How `vt` comes from the layout.
    pub uv_is: &'static str,
    /// The library's timings.
    pub timings_ms: GlobalTimings,
    /// The refinement of the input the outputs are written on, only when there is one
    /// (boundary chords split by the double covering): other reports keep their keys.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub written_mesh: Option<WrittenMesh>,
}

/// The `global.written_mesh` object: the refinement the outputs are written on.
#[derive(Debug, Clone, Serialize)]
pub struct WrittenMesh {
    /// Its vertex count (the input's vertices first).
    pub vertices: usize,
    /// Its face count.
    pub faces: usize,
    /// What it is.
    pub is: &'static str,
}

/// One zero of the form: the vertex nearest it and its multiplicity.
#[derive(Debug, Clone, Serialize)]
pub struct ZeroEntry {
    /// The vertex.
    pub vertex: usize,
    /// Its multiplicity.
    pub multiplicity: i64,
}

/// The `topology_opt` section: every step of the loop and what it returned.
#[derive(Debug, Clone, Serialize)]
pub struct TopologySection {
    /// Which layout was returned: `sphere`, `disk`, `input` or `slits`.
    pub returned: &'static str,
    /// What `returned` means.
    pub returned_is: &'static str,
    /// The step of the returned layout.
    pub best_step: usize,
    /// Uniformity energy of the starting map.
    pub start_energy: f64,
    /// Uniformity energy of the best step.
    pub best_energy: f64,
    /// `best_energy / start_energy`.
    pub ratio_to_start: f64,
    /// The vertex paths of the slits of the returned layout.
    pub slits: Vec<Vec<u32>>,
    /// The slit length used.
    pub slit_length: f64,
    /// The slit length asked, as a fraction.
    pub slit_length_fraction: f64,
    /// The slit budget.
    pub max_slits: usize,
    /// Steps without improvement before stopping.
    pub patience: usize,
    /// Why the loop stopped.
    pub stop: String,
    /// Every step.
    pub steps: Vec<TopologyStep>,
    /// Wall-clock milliseconds of the loop.
    pub total_ms: f64,
}
