//! Initial boundary maps: Angenent et al.'s map (CEM Eq. 13–16) and the arc-length circle.

use conformap_mesh::TriMesh;
use conformap_operators::{face_areas, solve_dense_spd, Cholesky, LaplacianBlocks, Partition};
use num_complex::Complex64;

use crate::problem::DiskProblem;
use crate::DiskError;
use conformap_operators::planar::polygon_area;

/// Outcome of the Angenent initial map.
#[derive(Debug, Clone)]
pub struct InitialBoundary {
    /// Boundary values on the unit circle, in boundary-loop order.
    pub boundary: Vec<Complex64>,
    /// The face `[a, b, c]` whose Dirac source defines the map.
    pub face: usize,
    /// Whether the map had to be conjugated to preserve orientation.
    pub conjugated: bool,
    /// Milliseconds spent in the factorization of the reduced Laplacian.
    pub factor_ms: f64,
}

/// The face nearest the surface's centre of mass (area-weighted centroid), preferring faces
/// without boundary vertices so that the singularity of Eq. 11 sits inside the surface.
pub fn centre_face(mesh: &TriMesh) -> usize {
    let areas = face_areas(mesh);
    let pos = mesh.positions();
    let centroid = |t: &[u32; 3]| -> [f64; 3] {
        let mut c = [0.0; 3];
        for &v in t {
            for k in 0..3 {
                c[k] += pos[v as usize][k] / 3.0;
            }
        }
        c
    };
    let total: f64 = areas.iter().sum();
    let mut m = [0.0; 3];
    for (t, a) in mesh.faces().iter().zip(&areas) {
        let c = centroid(t);
        for k in 0..3 {
            m[k] += c[k] * a / total;
        }
    }
    let mut best = (f64::INFINITY, 0usize, true);
    for (f, t) in mesh.faces().iter().enumerate() {
        let c = centroid(t);
        let d = (0..3).map(|k| (c[k] - m[k]).powi(2)).sum::<f64>();
        let touches = t.iter().any(|&v| mesh.is_boundary_vertex(v as usize));
        // interior faces first, then distance
        if (!touches, -d) > (!best.2, -best.0) {
            best = (d, f, touches);
        }
    }
    best.1
}

/// The right-hand side of CEM Eq. 14 for face `[a, b, c]`: a discrete
/// `(∂/∂u − i ∂/∂v) δ_p` in the local frame of the face (u along `ab`).
pub fn angenent_rhs(mesh: &TriMesh, face: usize) -> [(u32, Complex64); 3] {
    let t = mesh.faces()[face];
    let p = |v: u32| mesh.positions()[v as usize];
    let (pa, pb, pc) = (p(t[0]), p(t[1]), p(t[2]));
    use conformap_operators::vec3::{axpy, dot, sub};
    let ab = sub(pb, pa);
    let ab_len2 = dot(ab, ab);
    let alpha = dot(sub(pc, pa), ab) / ab_len2;
    let foot = axpy(alpha, ab, pa);
    let h = dot(sub(pc, foot), sub(pc, foot)).sqrt();
    let len = ab_len2.sqrt();
    [
        (t[0], Complex64::new(-1.0 / len, (1.0 - alpha) / h)),
        (t[1], Complex64::new(1.0 / len, alpha / h)),
        (t[2], Complex64::new(0.0, -1.0 / h)),
    ]
}

/// Angenent's initial boundary map (CEM Algorithm 1, steps 2–4): solve `L f = b`
/// (Eq. 13–14) with one vertex pinned to 0 (Theorem 1), then centralize (Eq. 15) and
/// normalize (Eq. 16) the boundary values.
///
/// Orientation: Eq. 13–14 as written give the mirror image on the meshes we tried; rather
/// than conjugating blindly, the boundary polygon's signed area is checked and the values
/// conjugated when it is negative, so the result always preserves orientation.
///
/// # Errors
/// [`DiskError::Operator`] if the reduced Laplacian cannot be factored;
/// [`DiskError::BoundaryCollapsed`] if a boundary value is at the centre.
pub fn angenent_boundary(problem: &DiskProblem<'_>) -> Result<InitialBoundary, DiskError> {
    let mesh = problem.mesh();
    let n = mesh.num_vertices();
    let face = centre_face(mesh);
    let boundary = &problem.partition().boundary;
    // pin the first boundary vertex: L with its row and column removed is positive definite
    let pinned = boundary[0];
    let reduced = Partition::new(n, &[pinned]);
    let t0 = std::time::Instant::now();
    let blocks = LaplacianBlocks::new(problem.laplacian(), &reduced);
    let factor = Cholesky::factor(&blocks.ii)?;
    let factor_ms = t0.elapsed().as_secs_f64() * 1e3;
    let mut rhs = vec![Complex64::new(0.0, 0.0); n - 1];
    for (v, val) in angenent_rhs(mesh, face) {
        if v != pinned {
            rhs[reduced.local[v as usize] as usize] += val;
        }
    }
    let sol = factor.solve_complex(&rhs);
    let full = reduced.assemble(&sol, &[Complex64::new(0.0, 0.0)]);
    let fb = problem.partition().boundary_values(&full);
    oriented_initial(fb, boundary, face, factor_ms)
}

/// The initial boundary from the solved values `fb` of Eq. 14: centralized, normalized and,
/// if clockwise, conjugated (so the boundary runs counter-clockwise).
fn oriented_initial(
    mut fb: Vec<Complex64>,
    boundary: &[u32],
    face: usize,
    factor_ms: f64,
) -> Result<InitialBoundary, DiskError> {
    centralize_normalize(&mut fb, boundary, "initial map")?;
    let conjugated = polygon_area(&fb) < 0.0;
    if conjugated {
        for z in &mut fb {
            *z = z.conj();
        }
    }
    Ok(InitialBoundary {
        boundary: fb,
        face,
        conjugated,
        factor_ms,
    })
}

/// Angenent's initial boundary map (as [`angenent_boundary`]) from the dense Schur
/// complement `A` of the problem, without a second factorization: with `b` the
/// right-hand side of Eq. 14 for `face` ([`angenent_rhs`]), the boundary values of
/// `L f = b` solve `A f_B = b_B − L_BI L_II⁻¹ b_I` (block elimination of the interior), with
/// the first boundary vertex pinned to 0 as in [`angenent_boundary`]. `a` is `A`
/// (column-major `n_B × n_B`) and `coupling` is `L_BI L_II⁻¹ b_I`; the reduced system is
/// solved by a dense Cholesky factorization (`n_B³ / 3` flops).
///
/// # Errors
/// [`DiskError::Operator`] if the reduced `A` is not positive definite (an interior cut
/// off from the boundary); [`DiskError::BoundaryCollapsed`] / [`DiskError::NonFinite`] if a
/// boundary value is at the centre.
pub(crate) fn angenent_from_schur(
    problem: &DiskProblem<'_>,
    face: usize,
    a: &[f64],
    coupling: &[Complex64],
) -> Result<InitialBoundary, DiskError> {
    let t0 = std::time::Instant::now();
    let part = problem.partition();
    let nb = part.boundary.len();
    let mut rb: Vec<Complex64> = coupling.iter().map(|c| -c).collect();
    for (v, val) in angenent_rhs(problem.mesh(), face) {
        if !part.is_interior[v as usize] {
            rb[part.local[v as usize] as usize] += val;
        }
    }
    // pin boundary vertex 0: the system on boundary vertices 1..n_B
    let m = nb - 1;
    let mut reduced = vec![0.0; m * m];
    for j in 0..m {
        reduced[j * m..(j + 1) * m].copy_from_slice(&a[(j + 1) * nb + 1..(j + 2) * nb]);
    }
    let mut x = Vec::with_capacity(2 * m);
    x.extend(rb[1..].iter().map(|z| z.re));
    x.extend(rb[1..].iter().map(|z| z.im));
    solve_dense_spd(&mut reduced, m, &mut x, 2, 0)?;
    let mut fb = Vec::with_capacity(nb);
    fb.push(Complex64::new(0.0, 0.0));
    fb.extend((0..m).map(|k| Complex64::new(x[k], x[m + k])));
    let factor_ms = t0.elapsed().as_secs_f64() * 1e3;
    oriented_initial(fb, &part.boundary, face, factor_ms)
}

/// Centralization (CEM Eq. 15/24) and normalization (Eq. 16/25) of boundary values.
///
/// # Errors
/// [`DiskError::NonFinite`] or [`DiskError::BoundaryCollapsed`] naming the vertex.
pub fn centralize_normalize(
    fb: &mut [Complex64],
    boundary: &[u32],
    stage: &'static str,
) -> Result<(), DiskError> {
    let mean = fb.iter().sum::<Complex64>() / fb.len() as f64;
    for (k, z) in fb.iter_mut().enumerate() {
        *z -= mean;
        let r = z.norm();
        if !r.is_finite() {
            return Err(DiskError::NonFinite {
                vertex: boundary[k] as usize,
                stage,
            });
        }
        if r <= f64::MIN_POSITIVE {
            return Err(DiskError::BoundaryCollapsed {
                vertex: boundary[k] as usize,
                stage,
            });
        }
        *z /= r;
    }
    Ok(())
}

/// Boundary values spaced on the unit circle by the 3D arc length along the loop
/// (the usual starting point of harmonic disk maps), counter-clockwise from angle 0.
pub fn arc_length_boundary(mesh: &TriMesh, boundary: &[u32]) -> Vec<Complex64> {
    let p = mesh.positions();
    let m = boundary.len();
    let seg: Vec<f64> = (0..m)
        .map(|k| {
            let (a, b) = (p[boundary[k] as usize], p[boundary[(k + 1) % m] as usize]);
            ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
        })
        .collect();
    let total: f64 = seg.iter().sum();
    let mut s = 0.0;
    let mut out = Vec::with_capacity(m);
    for len in seg {
        out.push(Complex64::from_polar(
            1.0,
            std::f64::consts::TAU * s / total,
        ));
        s += len;
    }
    out
}
