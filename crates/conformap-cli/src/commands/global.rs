//! `conformap global MESH -o OUT ...`: the global conformal parameterization of a surface
//! of genus ≥ 1 (or with several boundary loops, through its double covering) by a
//! holomorphic 1-form (Jin, Wang, Yau, Gu 2004, §3.1).
//!
//! `-o` gets the input's vertices in the input's order with one `vt` per corner class
//! (`f v/vt`): across a seam the two sides differ by a period, a pure translation. The
//! layout is scaled uniformly into the unit square (offset and scale in the report), which
//! changes neither angles nor seam translations. `--flat` gets the fundamental domain (the
//! surface cut open along the seams) with the raw layout as `(u, v, 0)`.

use clap::{Args, ValueEnum};
use conformap_global::{global_map, ConjugateMethod, GlobalMap, GlobalMapOptions};
use conformap_io::CornerUv;
use conformap_mesh::TriMesh;
use conformap_metrics::{corner_map_metrics, MetricsOptions};
use conformap_operators::PeakMemory;
use num_complex::Complex64;
use serde_json::json;

use crate::failure::Failure;
use crate::pipeline::{Input, InputArgs, MapCommand, OutputArgs, Solved, TexCoords};
use crate::report::{MetricsSection, SolverSection, StageTimings};

/// The conjugate forms (the discrete Hodge star).
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum Conjugate {
    /// The nearest exact complex structure to the Gu–Yau solve (the default: Riemann's
    /// bilinear relations to rounding, one τ for every form of a torus).
    Nearest,
    /// Gu–Yau's wedge-product system as solved.
    GuYau,
}

/// Arguments of `conformap global`.
#[derive(Debug, Clone, Args)]
pub struct GlobalArgs {
    /// The mesh (connected; genus ≥ 1, or ≥ 2 boundary loops) and how to read it.
    #[command(flatten)]
    pub input: InputArgs,
    /// The outputs: `-o` the mesh with one `vt` per corner (`f v/vt`; glTF: vertices split
    /// along the seams); `--flat` the fundamental domain with the layout as positions.
    #[command(flatten)]
    pub output: OutputArgs,
    /// The holomorphic basis form to lay out (0 ≤ K < 2g). Default: the basis form of
    /// lowest uniformity energy.
    #[arg(long, value_name = "K")]
    pub form: Option<usize>,
    /// The conjugate forms.
    #[arg(long, value_enum, default_value_t = Conjugate::Nearest)]
    pub conjugate: Conjugate,
    /// Root vertex of the homology generators' shortest-path tree (0-based). Default 0.
    #[arg(long, value_name = "V")]
    pub root: Option<usize>,
}

impl GlobalArgs {
    /// The library options these arguments ask for.
    pub fn options(&self) -> GlobalMapOptions {
        GlobalMapOptions::DEFAULT
            .with_form(self.form)
            .with_root(self.root)
            .with_conjugate(match self.conjugate {
                Conjugate::Nearest => ConjugateMethod::NearestComplexStructure,
                Conjugate::GuYau => ConjugateMethod::GuYau,
            })
    }
}

impl MapCommand for GlobalArgs {
    fn name(&self) -> &'static str {
        "global"
    }

    fn work(&self) -> &'static str {
        "a global conformal map"
    }

    fn input(&self) -> &InputArgs {
        &self.input
    }

    fn output(&self) -> &OutputArgs {
        &self.output
    }

    fn peak_bytes(&self, mesh: &TriMesh) -> u64 {
        // one factorization of the Laplacian of the surface the forms live on: the input,
        // or its double covering (twice the vertices and edges)
        let copies = if mesh.boundary_loops().is_empty() {
            1
        } else {
            2
        };
        let (v, e) = (copies * mesh.num_vertices(), copies * mesh.num_edges());
        PeakMemory::laplacian(v, e, v).bytes()
    }

    fn solve(&self, input: &Input) -> Result<Solved, Failure> {
        let mesh = &input.mesh;
        if let Some(root) = self.root.filter(|&r| r >= mesh.num_vertices()) {
            return Err(Failure::Usage(format!(
                "--root {root} is not a vertex: the mesh has {} (0-based)",
                mesh.num_vertices()
            )));
        }
        let map = global_map(mesh, &self.options()).map_err(|e| input.fail(e.into()))?;
        let mut written = Written::new(mesh, &map)?;
        let t = std::time::Instant::now();
        let base = corner_map_metrics(
            written.refined.as_ref().unwrap_or(mesh),
            &written.corner_values(),
            &MetricsOptions::DEFAULT,
        )?;
        let metrics_ms = map.timings_ms.metrics + crate::report::ms_since(t);
        let (folds_at_zeros, folds_outside_zeros) = map.input_folds();
        let zeros: Vec<_> = map
            .input_zeros()
            .map(|z| json!({"vertex": z.vertex, "multiplicity": z.multiplicity}))
            .collect();
        let (cf_min, cf_max) = map.conformal_factor_range();
        let m = &map.metrics;
        let metrics = MetricsSection::planar(base)
            .with("angle_distortion_all_corners_deg", m.angle_distortion_deg)
            .with(
                "angle_distortion_away_from_zeros_deg",
                m.angle_distortion_away_from_zeros_deg,
            )
            .with("uniformity_energy", m.uniformity_energy)
            .with("folds_at_zeros", folds_at_zeros)
            .with("folds_outside_zeros", folds_outside_zeros)
            .with("conformal_factor_range", [cf_min, cf_max]);
        let global = global_section(&map, &zeros, &written);
        let mut sections = serde_json::Map::new();
        sections.insert("global".to_string(), global);
        sections.insert(
            "factorization".to_string(),
            json!({"dim": map.factor_dim, "nnz_factor": map.factor_nnz}),
        );
        let solver = SolverSection::new(0, true, Vec::new(), map.bilinear_residual, &json!({}))
            .with(
                "residual_is",
                "Riemann's bilinear relations of the period matrix (relative)",
            )
            .with("seam_residual", map.seam_residual)
            .with("harmonic_residual", map.harmonic_residual);
        let tau = map
            .tau
            .map(|t| format!(", τ = {:.6}{:+.6}i", t.re, t.im))
            .unwrap_or_default();
        let summary = format!(
            "{} vertices, {} faces, genus {}{}; form {} of {}{tau}; {} zero(s), folds {} at \
             zeros / {} elsewhere; mean angle distortion {:.3}° away from zeros, uniformity \
             {:.3e}",
            mesh.num_vertices(),
            mesh.num_faces(),
            map.genus,
            if map.double_covered {
                format!(
                    " with {} boundary loop(s) (double covering of genus {})",
                    map.boundaries, map.surface_genus
                )
            } else {
                String::new()
            },
            map.form_index,
            2 * map.surface_genus,
            zeros.len(),
            folds_at_zeros,
            folds_outside_zeros,
            m.angle_distortion_away_from_zeros_deg.mean,
            m.uniformity_energy,
        );
        let strict_violation = (folds_outside_zeros > 0)
            .then(|| format!("{folds_outside_zeros} folded faces lie outside the zeros' clusters"));
        let tm = &map.timings_ms;
        Ok(Solved {
            method: format!("holomorphic-1-form-{}", conjugate_name(map.conjugate)),
            flat: (
                std::mem::take(&mut written.flat_points),
                Some(std::mem::take(&mut written.flat_faces)),
            ),
            uv: written.tex_coords(),
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
            strict_violation,
            summary,
        })
    }
}

fn conjugate_name(c: ConjugateMethod) -> &'static str {
    match c {
        ConjugateMethod::GuYau => "gu-yau",
        _ => "nearest",
    }
}

/// The report's `global` section.
fn global_section(map: &GlobalMap, zeros: &[serde_json::Value], w: &Written) -> serde_json::Value {
    let n = 2 * map.surface_genus;
    let periods: Vec<Vec<[f64; 2]>> = (0..n)
        .map(|j| {
            (0..n)
                .map(|k| map.period_matrix[j * n + k])
                .map(|z| [z.re, z.im])
                .collect()
        })
        .collect();
    json!({
        "genus": map.genus,
        "boundaries": map.boundaries,
        "double_covered": map.double_covered,
        "surface_genus": map.surface_genus,
        "split_boundary_chords": map.split_edges,
        "generators": map.generator_lengths.len(),
        "generator_lengths": map.generator_lengths,
        "form": map.form_index,
        "form_uniformity": map.form_uniformity,
        "conjugate": conjugate_name(map.conjugate),
        "period_matrix": periods,
        "period_matrix_layout": "rows: generators, columns: basis forms; [re, im]",
        "bilinear_residual": map.bilinear_residual,
        "bilinear_residual_gu_yau": map.bilinear_residual_gu_yau,
        "complex_structure_defect": map.complex_structure_defect,
        "tau": map.tau.map(|t| [t.re, t.im]),
        "tau_gu_yau": map.tau_gu_yau.iter().map(|t| [t.re, t.im]).collect::<Vec<_>>(),
        "zeros": zeros,
        "zero_multiplicity_sum_surface": map.zeros.multiplicity_sum,
        "negative_clusters": map.zeros.negative_clusters,
        "winding_residual": map.zeros.winding_residual,
        "seam_edges": map.seam_edges,
        "seam_residual": map.seam_residual,
        "layout_diagonal": map.layout_diagonal,
        "uv_offset": w.offset,
        "uv_scale": w.scale,
        "uv_is": "vt = (layout − uv_offset) · uv_scale: the layout fitted into the unit square",
        "timings_ms": map.timings_ms,
    })
}

/// What `-o` and `--flat` receive.
struct Written {
    /// The mesh written to `-o` when it is not the input: its refinement, when the double
    /// covering split boundary chords.
    refined: Option<TriMesh>,
    uv: CornerUv,
    flat_points: Vec<[f64; 3]>,
    flat_faces: Vec<[u32; 3]>,
    offset: [f64; 2],
    scale: f64,
}

impl Written {
    fn new(input: &TriMesh, map: &GlobalMap) -> Result<Self, Failure> {
        let nf = map.input_faces;
        let cut_faces = &map.cut.mesh.faces()[..nf];
        let corner = map.input_corner_uv();
        // cut vertices of the input's faces, numbered by first use
        let mut index = vec![u32::MAX; map.cut.mesh.num_vertices()];
        let mut layout: Vec<Complex64> = Vec::new();
        let flat_faces: Vec<[u32; 3]> = cut_faces
            .iter()
            .enumerate()
            .map(|(f, t)| {
                std::array::from_fn(|k| {
                    let c = t[k] as usize;
                    if index[c] == u32::MAX {
                        index[c] = layout.len() as u32;
                        layout.push(corner[3 * f + k]);
                    }
                    index[c]
                })
            })
            .collect();
        let (lo, hi) = layout.iter().fold(
            ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
            |(lo, hi), z| {
                (
                    [lo[0].min(z.re), lo[1].min(z.im)],
                    [hi[0].max(z.re), hi[1].max(z.im)],
                )
            },
        );
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if !(extent > 0.0 && extent.is_finite()) {
            return Err(Failure::Numerical(format!(
                "the layout has no extent ({extent}); the form degenerated"
            )));
        }
        let scale = 1.0 / extent;
        let texcoords = layout
            .iter()
            .map(|z| [(z.re - lo[0]) * scale, (z.im - lo[1]) * scale])
            .collect();
        let surface_faces = &map.surface.faces()[..nf];
        let same = map.split_edges == 0
            && map.input_vertices == input.num_vertices()
            && surface_faces == input.faces();
        let refined = if same {
            None
        } else {
            Some(
                TriMesh::try_new(
                    map.surface.positions()[..map.input_vertices].to_vec(),
                    surface_faces.to_vec(),
                )
                .map_err(|e| {
                    Failure::Numerical(format!(
                        "the refined input copy of the double covering is not a valid mesh: {e}"
                    ))
                })?,
            )
        };
        Ok(Self {
            refined,
            uv: CornerUv {
                texcoords,
                faces: flat_faces.clone(),
            },
            flat_points: layout.iter().map(|z| [z.re, z.im, 0.0]).collect(),
            flat_faces,
            offset: lo,
            scale,
        })
    }

    /// The written texture coordinates per corner (`3 f + k`), as `metrics` reads them back.
    fn corner_values(&self) -> Vec<Complex64> {
        (0..self.uv.faces.len())
            .flat_map(|f| (0..3).map(move |k| (f, k)))
            .map(|(f, k)| {
                let t = self.uv.corner(f, k);
                Complex64::new(t[0], t[1])
            })
            .collect()
    }

    fn tex_coords(self) -> TexCoords {
        match self.refined {
            Some(mesh) => TexCoords::Refined { mesh, uv: self.uv },
            None => TexCoords::PerCorner(self.uv),
        }
    }
}
