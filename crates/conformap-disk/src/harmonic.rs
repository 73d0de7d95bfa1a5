//! The harmonic map to an arc-length-parameterized circle: the usual baseline (libigl's
//! `harmonic` with `map_vertices_to_circle`), one factorization and one solve.

use std::time::Instant;

use crate::cem::interior_residual;
use crate::initial::arc_length_boundary;
use crate::problem::DiskProblem;
use crate::report::{DiskMap, SolverReport, Timings};

/// Harmonic extension of the arc-length boundary map (no boundary optimization).
///
/// # Examples
/// ```
/// use conformap_disk::{harmonic_arc_length, DiskProblem};
/// use conformap_mesh::TriMesh;
/// let mut pos = vec![[0.0, 0.0, 0.0]];
/// for k in 0..6 {
///     let t = k as f64 * std::f64::consts::PI / 3.0;
///     pos.push([t.cos(), t.sin(), 0.0]);
/// }
/// let faces = (0..6u32).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
/// let mesh = TriMesh::try_new(pos, faces).unwrap();
/// let problem = DiskProblem::new(&mesh).unwrap();
/// let out = harmonic_arc_length(&problem);
/// assert!(out.map[0].norm() < 1e-12); // the centre stays at the centre
/// ```
pub fn harmonic_arc_length(problem: &DiskProblem<'_>) -> DiskMap {
    let t0 = Instant::now();
    let fb = arc_length_boundary(problem.mesh(), &problem.partition().boundary);
    let map = problem.harmonic_extension(&fb);
    let e = problem.conformal_energy(&map);
    let solve = t0.elapsed().as_secs_f64() * 1e3;
    let report = SolverReport {
        method: "harmonic".to_string(),
        iterations: 0,
        converged: true,
        energy_history: vec![e],
        best_iteration: 0,
        residual: interior_residual(problem, &map),
        factorizations: 1,
        notes: vec!["boundary by arc length, no boundary optimization".to_string()],
        fallback_from: None,
        timings_ms: Timings {
            assemble: problem.assemble_ms,
            factor: problem.factor_ms,
            solve,
            total: problem.setup_ms + solve,
        },
        ..SolverReport::default()
    };
    DiskMap { map, report }
}
