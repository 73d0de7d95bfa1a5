//! What `global` returns for a holomorphic-form layout: the seamed texture coordinates,
//! the flat fundamental domain, the metrics, the report sections and the summary line;
//! shared by `global` and `global --topology-opt`.

use conformap_global::{ConjugateMethod, GlobalMap, SeamedLayout};
use conformap_io::CornerUv;
use conformap_mesh::TriMesh;
use conformap_metrics::{corner_map_metrics, MetricsOptions};

use crate::failure::Failure;
use crate::pipeline::{Solved, TexCoords};
use crate::report::{
    FactorizationSection, GlobalDetail, GlobalSection, MetricsExtra, MetricsSection, Sections,
    SolverDetail, SolverSection, Sorted, StageTimings, WrittenMesh, ZeroEntry,
};

/// What `global` returns for the map `map` of `mesh` (the input, whose faces the layout's
/// corners follow) and its seamed layout.
pub(crate) fn map_solved(
    mesh: &TriMesh,
    map: &GlobalMap,
    seamed: SeamedLayout,
) -> Result<Solved, Failure> {
    {
        let t = std::time::Instant::now();
        let written = seamed.mesh.as_ref().unwrap_or(mesh);
        let base = corner_map_metrics(written, &seamed.corner_values(), &MetricsOptions::DEFAULT)?;
        let metrics_ms = map.timings_ms.metrics + crate::report::ms_since(t);
        let (folds_at_zeros, folds_outside_zeros) = map.input_folds();
        let m = &map.metrics;
        let (cf_min, cf_max) = map.conformal_factor_range();
        let metrics = MetricsSection::planar(base).and(MetricsExtra::Global {
            angle_distortion_all_corners_deg: m.angle_distortion_deg,
            angle_distortion_away_from_zeros_deg: m.angle_distortion_away_from_zeros_deg,
            conformal_factor_range: [cf_min, cf_max],
            folds_at_zeros,
            folds_outside_zeros,
            uniformity_energy: m.uniformity_energy,
        });
        let sections = Sections {
            factorization: Some(FactorizationSection::Forms {
                dim: map.factor_dim,
                nnz_factor: map.factor_nnz,
            }),
            global: Some(Sorted(global_section(map, &seamed))),
            ..Sections::default()
        };
        let solver = SolverSection::new(
            map.summary(),
            SolverDetail::Global(GlobalDetail {
                harmonic_residual: map.harmonic_residual,
                residual_is: "Riemann's bilinear relations of the period matrix (relative)",
                seam_residual: map.seam_residual,
            }),
        );
        let tm = &map.timings_ms;
        Ok(Solved {
            picture_domain: None,
            method: format!("holomorphic-1-form-{}", conjugate_name(map.conjugate)),
            summary: summary(mesh, map, folds_at_zeros, folds_outside_zeros)
                + &refinement_note(mesh, map, seamed.mesh.as_ref()),
            strict_violation: (folds_outside_zeros > 0).then(|| {
                format!("{folds_outside_zeros} folded faces lie outside the zeros' clusters")
            }),
            flat: (
                seamed.layout.iter().map(|z| [z.re, z.im, 0.0]).collect(),
                Some(seamed.tex_faces.clone()),
            ),
            uv: tex_coords(seamed),
            solver,
            param: None,
            sections,
            metrics,
            timings: StageTimings {
                assemble: tm.assemble,
                factor: tm.factor,
                solve: tm.total - tm.assemble - tm.factor - tm.metrics,
                metrics: metrics_ms,
                ..StageTimings::default()
            },
        })
    }
}

fn conjugate_name(c: ConjugateMethod) -> &'static str {
    match c {
        ConjugateMethod::GuYau => "gu-yau",
        _ => "nearest",
    }
}

/// What `-o` receives: the input's faces with per-corner texture coordinates, on the input
/// or on its refinement.
fn tex_coords(seamed: SeamedLayout) -> TexCoords {
    let uv = CornerUv {
        texcoords: seamed.texcoords,
        faces: seamed.tex_faces,
    };
    match seamed.mesh {
        Some(mesh) => TexCoords::Refined { mesh, uv },
        None => TexCoords::PerCorner(uv),
    }
}

/// The summary line.
fn summary(mesh: &TriMesh, map: &GlobalMap, at_zeros: usize, outside: usize) -> String {
    let tau = map
        .tau
        .map(|t| format!(", τ = {:.6}{:+.6}i", t.re, t.im))
        .unwrap_or_default();
    let cover = if map.double_covered {
        format!(
            " with {} boundary loop(s) (double covering of genus {})",
            map.boundaries, map.surface_genus
        )
    } else {
        String::new()
    };
    format!(
        "{} vertices, {} faces, genus {}{cover}; {}{tau}; {} zero(s), folds {at_zeros} \
         at zeros / {outside} elsewhere; mean angle distortion {:.3}° away from zeros, \
         uniformity {:.3e}",
        mesh.num_vertices(),
        mesh.num_faces(),
        map.genus,
        objective_summary(map),
        map.input_zeros().count(),
        map.metrics.angle_distortion_away_from_zeros_deg.mean,
        map.metrics.uniformity_energy,
    )
}

/// What the summary adds when the outputs are written on a refinement of the input
/// (boundary chords split by the double covering): the written counts.
fn refinement_note(mesh: &TriMesh, map: &GlobalMap, written: Option<&TriMesh>) -> String {
    match written {
        Some(w) => format!(
            "; written on a refinement of the input ({} boundary chord(s) split): {} \
             vertices, {} faces, the input's {} vertices first (`conformap metrics` and \
             `render` read it as it is)",
            map.split_edges,
            w.num_vertices(),
            w.num_faces(),
            mesh.num_vertices()
        ),
        None => String::new(),
    }
}

/// The chosen form, in words: the objective and what it reached.
fn objective_summary(map: &GlobalMap) -> String {
    let o = &map.objective;
    let of = 2 * map.surface_genus;
    let detail = if let Some(e) = &o.emphasis {
        format!(
            " (region share {:.3} of the parameter area, {:.3} of the surface's)",
            e.share, e.surface_share
        )
    } else if let Some(z) = &o.zeros {
        let rings: Vec<String> = z
            .targets
            .iter()
            .map(|t| match t.ring_distance {
                Some(d) => format!("v{} {d}", t.vertex),
                None => format!("v{} none", t.vertex),
            })
            .collect();
        format!(" (edge rings to the nearest zero: {})", rings.join(", "))
    } else if let Some(r) = o.max_min_ratio.filter(|_| o.search.is_some()) {
        format!(" (max/min uniformity {r:.2})")
    } else {
        String::new()
    };
    match o.objective.as_str() {
        "basis" => format!("basis form {} of {of}", map.form_index),
        name => format!("{name} form{detail}"),
    }
}

/// The report's `global` section.
fn global_section(map: &GlobalMap, seamed: &SeamedLayout) -> GlobalSection {
    let n = 2 * map.surface_genus;
    let period_matrix: Vec<Vec<[f64; 2]>> = (0..n)
        .map(|j| {
            (0..n)
                .map(|k| map.period_matrix[j * n + k])
                .map(|z| [z.re, z.im])
                .collect()
        })
        .collect();
    let zeros = map
        .input_zeros()
        .map(|z| ZeroEntry {
            vertex: z.vertex,
            multiplicity: z.multiplicity,
        })
        .collect();
    GlobalSection {
        genus: map.genus,
        boundaries: map.boundaries,
        double_covered: map.double_covered,
        surface_genus: map.surface_genus,
        split_boundary_chords: map.split_edges,
        generators: map.generator_lengths.len(),
        generator_lengths: map.generator_lengths.clone(),
        form: map.form_index,
        form_uniformity: map.form_uniformity.clone(),
        objective: map.objective.clone(),
        conjugate: conjugate_name(map.conjugate),
        period_matrix,
        period_matrix_layout: "rows: generators, columns: basis forms; [re, im]",
        bilinear_residual: map.bilinear_residual,
        bilinear_residual_gu_yau: map.bilinear_residual_gu_yau,
        complex_structure_defect: map.complex_structure_defect,
        tau: map.tau.map(|t| [t.re, t.im]),
        tau_gu_yau: map.tau_gu_yau.iter().map(|t| [t.re, t.im]).collect(),
        zeros,
        zero_multiplicity_sum_surface: map.zeros.multiplicity_sum,
        negative_clusters: map.zeros.negative_clusters,
        winding_residual: map.zeros.winding_residual,
        seam_edges: map.seam_edges,
        seam_residual: map.seam_residual,
        layout_diagonal: map.layout_diagonal,
        uv_offset: seamed.offset,
        uv_scale: seamed.scale,
        uv_is: "vt = (layout − uv_offset) · uv_scale: the layout fitted into the unit square",
        timings_ms: map.timings_ms,
        written_mesh: seamed.mesh.as_ref().map(|w| WrittenMesh {
            vertices: w.num_vertices(),
            faces: w.num_faces(),
            is: "the refinement the outputs are written on (the input's vertices first)",
        }),
    }
}
