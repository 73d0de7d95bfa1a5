//! A disk with no interior vertex (one or two triangles, a fan of boundary vertices): every
//! vertex lies on the unit circle, so the map is the placement of the boundary alone, and
//! there is nothing to iterate. Each boundary edge gets the arc its chord subtends in a
//! circle through its face's corners (twice the angle opposite it, the inscribed angle
//! theorem), normalized to a full turn: exact (no angle distortion) for one triangle and
//! for any mesh whose corners already lie on one circle.

use std::f64::consts::TAU;
use std::time::Instant;

use conformap_mesh::TriMesh;
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_operators::{corner_angles, SolverSummary};
use num_complex::Complex64;

use crate::failure::Failure;
use crate::pipeline::{disk_uv, planar_points, Input, Solved};
use crate::report::{
    ms_since, MetricsSection, NoteDetail, Sections, SolverDetail, SolverSection, StageTimings,
};

/// Whether `mesh` (a disk) has no interior vertex: every vertex on its one boundary loop.
pub fn has_no_interior(mesh: &TriMesh) -> bool {
    mesh.boundary_loops()
        .first()
        .is_some_and(|b| b.len() == mesh.num_vertices())
}

/// The angle opposite the boundary edge `a → b` in its face.
fn opposite_angle(mesh: &TriMesh, angles: &[[f64; 3]], a: u32, b: u32) -> Option<f64> {
    mesh.faces().iter().zip(angles).find_map(|(f, ang)| {
        let k = (0..3).find(|&k| {
            let (x, y) = (f[(k + 1) % 3], f[(k + 2) % 3]);
            (x == a && y == b) || (x == b && y == a)
        })?;
        Some(ang[k])
    })
}

/// The map of a disk without interior vertices: boundary vertex `i` at `e^{iθ_i}`, the arcs
/// twice the opposite angles, scaled to sum to 2π, oriented as the faces.
///
/// # Errors
/// [`Failure::BadInput`] when a boundary edge has no face (not a valid disk).
pub fn tiny_disk_map(mesh: &TriMesh) -> Result<Vec<Complex64>, Failure> {
    let boundary = &mesh.boundary_loops()[0];
    let angles = corner_angles(mesh);
    let k = boundary.len();
    let arcs = (0..k)
        .map(|i| {
            let (a, b) = (boundary[i], boundary[(i + 1) % k]);
            opposite_angle(mesh, &angles, a, b).map(|t| 2.0 * t)
        })
        .collect::<Option<Vec<f64>>>()
        .ok_or_else(|| Failure::input("a boundary edge belongs to no face".to_string()))?;
    let scale = TAU / arcs.iter().sum::<f64>();
    let mut map = vec![Complex64::new(0.0, 0.0); mesh.num_vertices()];
    let mut theta = 0.0;
    for (i, &v) in boundary.iter().enumerate() {
        map[v as usize] = Complex64::from_polar(1.0, theta);
        theta += arcs[i] * scale;
    }
    let f = mesh.faces()[0].map(|v| map[v as usize]);
    if ((f[1] - f[0]).conj() * (f[2] - f[0])).im < 0.0 {
        map.iter_mut().for_each(|z| *z = z.conj());
    }
    Ok(map)
}

/// [`tiny_disk_map`] as the `disk` command's result (method `boundary-only`).
///
/// # Errors
/// As [`tiny_disk_map`], and the metrics'.
pub fn solve(input: &Input) -> Result<Solved, Failure> {
    let mesh = &input.mesh;
    let t = Instant::now();
    let map = tiny_disk_map(mesh).map_err(|e| input.fail(e))?;
    let solve_ms = ms_since(t);
    let t = Instant::now();
    let metrics = planar_map_metrics(mesh, &map, &MetricsOptions::default())?;
    let summary = format!(
        "{} vertices, {} faces; no interior vertex: every vertex on the circle, nothing to \
         iterate; mean angle distortion {:.3}°, flipped faces {}",
        mesh.num_vertices(),
        mesh.num_faces(),
        metrics.angle_distortion_deg.mean,
        metrics.flipped_faces,
    );
    Ok(Solved {
        picture_domain: None,
        method: "boundary-only".to_string(),
        uv: disk_uv(&map).into(),
        flat: (planar_points(&map), None),
        solver: SolverSection::new(
            SolverSummary::direct(true, 0.0),
            SolverDetail::Note(NoteDetail {
                note: "no interior vertex: each boundary edge gets twice its opposite angle \
                       of arc (exact for one triangle)",
            }),
        ),
        param: None,
        sections: Sections::default(),
        metrics: MetricsSection::planar(metrics),
        timings: StageTimings {
            solve: solve_ms,
            metrics: ms_since(t),
            ..StageTimings::default()
        },
        strict_violation: None,
        summary,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One triangle maps to the inscribed triangle with its angles: no distortion.
    #[test]
    fn one_triangle_is_exact() {
        let mesh = TriMesh::try_new(
            vec![[0.0, 0.0, 0.0], [3.0, 0.0, 0.0], [0.5, 2.0, 0.0]],
            vec![[0, 1, 2]],
        )
        .unwrap();
        assert!(has_no_interior(&mesh));
        let map = tiny_disk_map(&mesh).unwrap();
        let m = planar_map_metrics(&mesh, &map, &MetricsOptions::default()).unwrap();
        assert!(
            m.angle_distortion_deg.max < 1e-9,
            "{}",
            m.angle_distortion_deg.max
        );
        assert_eq!(m.flipped_faces, 0);
        assert!(map.iter().all(|z| (z.norm() - 1.0).abs() < 1e-15));
    }
}
