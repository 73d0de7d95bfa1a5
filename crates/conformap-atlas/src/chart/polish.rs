//! The chart's distortion polish: one Gauss–Newton step on the layout that lowers the area
//! spread and the angle distortion together, with every seam kept exactly as rigid as it
//! was.
//!
//! Boundary first flattening lays out the cone metric: the scale factor `u` solves the
//! *linearized* curvature equation, and the layout's faces follow `e^{2u}` only up to the
//! discretization, worst beside strong cones (spot's 709° cone). The layout is not the best
//! one for the two numbers the atlas reports. The polish minimizes, over the positions of
//! the cut disk's vertices,
//!
//! `E = Σ_f (log(A_f^uv / A_f^3D) − m)² + (μ/3) Σ_corners (θ^uv − θ^3D)²`
//!
//! (`m` the faces' mean, `μ` = [`ANGLE_WEIGHT`]): the variance of the log area ratio (the
//! square of the area spread, times the faces) and the squared corner-angle errors. The
//! seams are linear constraints: a seam edge's two copies keep the rotation between them,
//! `w_b′ − w_a′ = R (w_b − w_a)` with `R` the layout's (a cone's rotation on genus 0, a
//! handle cut's bend on genus ≥ 1), so both sides of every seam keep equal lengths and a
//! cone path stays one rotation and one translation. The Gauss–Newton system
//! `(JᵀJ + λ diag) δ = −Jᵀr` under `C δ = 0` is solved by the augmented Lagrangian: one
//! Cholesky factorization of `JᵀJ + λ diag + ρ CᵀC`, then [`CONSTRAINT_ROUNDS`] solves
//! at most with the multiplier updated, until `|C δ|` is at rounding level. A step that
//! would flip a face or raise `E` is halved ([`MAX_HALVINGS`]); the layout is kept as it
//! was when no step helps.
//!
//! Measured (`conformap atlas --polish`, 8 cones, against the same run without): spot's
//! area spread 0.835 → 0.790 and mean angle distortion 2.44° → 2.31°; armadillo 1.860 →
//! 1.718 and 1.60° → 1.45°; fertility 0.283 → 0.279 and 1.53° → 1.20°; kitten_53k 0.283 →
//! 0.282 and 0.43° → 0.36°. A second step gains under 1 % of spread (a prototype of the
//! same step: spot 0.791 → 0.788) for another factorization.

use conformap_mesh::TriMesh;
use conformap_operators::{
    amd_permutation, triangle_angles, Cholesky, CholeskyOptions, OperatorError, Ordering,
    SymbolicAnalysis,
};
use num_complex::Complex64;
use sprs::CsMat;

/// Weight `μ` of the squared corner-angle errors (radians) against the squared log area
/// ratios in the polish's energy: 300. The energy minimized on spot (400 quasi-Newton
/// iterations of a prototype, seams held the same way) gives area spread / angle distortion 0.715 / 2.62° at μ = 100,
/// 0.786 / 2.34° at 300, 0.822 / 2.29° at 1000, from 0.835 / 2.44°: at 300 both fall, and
/// they do on every closed mesh of the atlas table.
pub const ANGLE_WEIGHT: f64 = 300.0;

/// Levenberg damping of the Gauss–Newton system, relative to its diagonal: `1e-3`. The
/// energy does not change when the whole layout is moved, turned or scaled, so `JᵀJ` alone
/// is singular; the damping makes it positive definite and keeps the step from drifting
/// along those motions.
pub const DAMPING: f64 = 1e-3;

/// Multiplier updates of the augmented Lagrangian at most: 8. With `ρ` at [`PENALTY`]
/// times the system's mean diagonal each update shrinks the seams' violation 10³–10⁴-fold
/// (spot, kitten_53k); three bring it under `1e-12` of the step, where the rounds stop.
pub const CONSTRAINT_ROUNDS: usize = 8;

/// The seams' penalty `ρ`, relative to the Gauss–Newton system's mean diagonal: `1e4`.
pub const PENALTY: f64 = 1e4;

/// Halvings of a step that flips a face or raises the energy before the polish gives up
/// and keeps the layout: 12.
pub const MAX_HALVINGS: usize = 12;

/// Vertices from which the polish's factorization runs on every thread: 20,000. Below,
/// faer's thread dispatch costs more than it saves (spot, 2,930 vertices: 5.1 ms on one
/// thread).
pub const PARALLEL_VERTICES: usize = 20_000;

/// What the polish did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PolishReport {
    /// The energy before and after (equal when the layout was kept).
    pub energy: [f64; 2],
    /// The step length taken (1 for the full Gauss–Newton step, 0 when none was).
    pub step: f64,
    /// The largest seam violation `|w_b′ − w_a′ − R (w_b − w_a)|` relative to the edge's
    /// length after the polish.
    pub seam_residual: f64,
}

/// One seam edge: its copies `a → b` on one side, `a′ → b′` on the other, and the
/// rotation `R` from the first to the second.
#[derive(Debug, Clone, Copy)]
struct SeamEdge {
    a: usize,
    b: usize,
    a2: usize,
    b2: usize,
    rotation: Complex64,
}

/// Polishes the layout `uv` of the cut disk `cut` in place (module docs). `uncut` is the
/// surface the disk was cut from: its opposite half-edges name the seams (the cut mesh's
/// faces are the uncut one's, in order). Faces folded or degenerate in `uv` are left out
/// of the energy (the chart's repairs deal with them) and no other face may fold. Leaves
/// `uv` as it is when the system does not factor or no step lowers the energy.
pub fn polish(uncut: &TriMesh, cut: &TriMesh, uv: &mut [Complex64]) -> PolishReport {
    polish_with(PolishPlan::new(uncut, cut), cut, uv)
}

/// What the polish needs of the cut disk before its layout exists: the seams, the system's
/// sparsity and its symbolic analysis, the 3D faces' log areas and angles. The atlas
/// computes it on one core while the other flattens the disk (spot: 3–4 ms of the
/// polish's 12–14 off the critical path).
pub struct PolishPlan {
    /// The seam edges `[a, b, a′, b′]` (module docs).
    seams: Vec<[usize; 4]>,
    pattern: Pattern,
    analysis: Result<SymbolicAnalysis, OperatorError>,
    geometry: Geometry,
}

impl PolishPlan {
    /// The plan for the cut disk `cut` of `uncut` (as [`polish`] takes them): the seams
    /// and the pattern, then the ordering and symbolic analysis beside the 3D targets.
    pub fn new(uncut: &TriMesh, cut: &TriMesh) -> Self {
        let seams: Vec<[usize; 4]> = super::cut::seam_edges(uncut, cut)
            .into_iter()
            .map(|e| e.map(|v| v as usize))
            .collect();
        let pattern = Pattern::new(cut.num_vertices(), cut.faces(), &seams);
        let (analysis, geometry) = rayon::join(|| pattern.analyse(), || Geometry::new(cut));
        Self {
            seams,
            pattern,
            analysis,
            geometry,
        }
    }
}

impl std::fmt::Debug for PolishPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PolishPlan")
            .field("variables", &(self.pattern.starts.len() - 1))
            .field("seam_edges", &self.seams.len())
            .finish_non_exhaustive()
    }
}

/// [`polish`] with its plan made already (for the same `cut`; the layout `uv` may have
/// been made after it). A plan of another disk (other vertex or face counts) leaves `uv`
/// as it is, its energy NaN.
pub fn polish_with(plan: PolishPlan, cut: &TriMesh, uv: &mut [Complex64]) -> PolishReport {
    let kept = |e: f64| PolishReport {
        energy: [e, e],
        step: 0.0,
        seam_residual: 0.0,
    };
    let PolishPlan {
        seams,
        pattern,
        analysis,
        geometry,
    } = plan;
    let faces = cut.faces();
    if pattern.neighbours.len() != uv.len()
        || uv.len() != cut.num_vertices()
        || geometry.log_area.len() != faces.len()
    {
        return kept(f64::NAN);
    }
    let seams = seam_rotations(&seams, uv);
    let n = uv.len();
    let target = Target::new(geometry, faces, uv);
    let Some(e0) = target.energy(faces, uv) else {
        return kept(f64::NAN);
    };
    let mut values = vec![0.0; pattern.rows.len()];
    let mut gradient = vec![0.0; 2 * n];
    target.assemble(faces, uv, &pattern, &mut values, &mut gradient);
    let mean_diagonal = (0..2 * n).map(|p| values[pattern.at(p, p)]).sum::<f64>() / (2 * n) as f64;
    for p in 0..2 * n {
        values[pattern.at(p, p)] *= 1.0 + DAMPING;
    }
    let rho = PENALTY * mean_diagonal;
    for s in &seams {
        for row in s.rows() {
            for &(p, x) in &row {
                for &(q, y) in &row {
                    if p <= q {
                        values[pattern.at(p, q)] += rho * x * y;
                    }
                }
            }
        }
    }
    let matrix = pattern.matrix(values);
    let Ok(chol) = analysis.and_then(|a| a.factor(&matrix)) else {
        return kept(e0);
    };
    // augmented Lagrangian: δ = K⁻¹(−g − Cᵀν), ν += ρ C δ
    let mut multiplier = vec![[0.0; 2]; seams.len()];
    let mut step = vec![0.0; 2 * n];
    for _ in 0..CONSTRAINT_ROUNDS {
        step.iter_mut().zip(&gradient).for_each(|(d, g)| *d = -g);
        for (s, nu) in seams.iter().zip(&multiplier) {
            for (row, &l) in s.rows().iter().zip(nu) {
                for &(p, x) in row {
                    step[p] -= x * l;
                }
            }
        }
        chol.solve_in_place(&mut step, 1);
        let mut worst: f64 = 0.0;
        let mut scale: f64 = 0.0;
        for (s, nu) in seams.iter().zip(multiplier.iter_mut()) {
            for (row, l) in s.rows().iter().zip(nu.iter_mut()) {
                let c: f64 = row.iter().map(|&(p, x)| x * step[p]).sum();
                *l += rho * c;
                worst = worst.max(c.abs());
            }
        }
        for d in &step {
            scale = scale.max(d.abs());
        }
        if worst <= 1e-12 * scale.max(f64::MIN_POSITIVE) {
            break;
        }
    }
    let slope: f64 = step.iter().zip(&gradient).map(|(d, g)| d * g).sum();
    let mut t = 1.0;
    let mut trial = uv.to_vec();
    for _ in 0..=MAX_HALVINGS {
        for (k, w) in trial.iter_mut().enumerate() {
            *w = uv[k] + t * Complex64::new(step[2 * k], step[2 * k + 1]);
        }
        if let Some(e) = target.energy(faces, &trial) {
            if e <= e0 + 1e-4 * t * slope && e < e0 {
                uv.copy_from_slice(&trial);
                return PolishReport {
                    energy: [e0, e],
                    step: t,
                    seam_residual: seam_residual(&seams, uv),
                };
            }
        }
        t *= 0.5;
    }
    kept(e0)
}

impl SeamEdge {
    /// The two real rows of `w_b′ − w_a′ − R (w_b − w_a) = 0` over the interleaved
    /// variables `(u_0, v_0, u_1, v_1, …)`, as (variable, coefficient): six entries each,
    /// padded to eight with zeros so both rows name the same eight variables (a vertex
    /// named twice, as a cut's tip on both sides, adds up).
    fn rows(&self) -> [[(usize, f64); 8]; 2] {
        let (c, s) = (self.rotation.re, self.rotation.im);
        let (u, v) = (|k: usize| 2 * k, |k: usize| 2 * k + 1);
        [
            [
                (u(self.b2), 1.0),
                (u(self.a2), -1.0),
                (u(self.b), -c),
                (v(self.b), s),
                (u(self.a), c),
                (v(self.a), -s),
                (v(self.b2), 0.0),
                (v(self.a2), 0.0),
            ],
            [
                (v(self.b2), 1.0),
                (v(self.a2), -1.0),
                (u(self.b), -s),
                (v(self.b), -c),
                (u(self.a), s),
                (v(self.a), c),
                (u(self.b2), 0.0),
                (u(self.a2), 0.0),
            ],
        ]
    }
}

/// The seam edges of the cut disk with the rotations the layout `uv` gives them.
fn seam_rotations(seams: &[[usize; 4]], uv: &[Complex64]) -> Vec<SeamEdge> {
    seams
        .iter()
        .map(|&[a, b, a2, b2]| {
            let r = (uv[b2] - uv[a2]) / (uv[b] - uv[a]);
            SeamEdge {
                a,
                b,
                a2,
                b2,
                rotation: r / r.norm(),
            }
        })
        .collect()
}

/// The largest `|w_b′ − w_a′ − R (w_b − w_a)| / |w_b − w_a|` over the seams.
fn seam_residual(seams: &[SeamEdge], uv: &[Complex64]) -> f64 {
    seams
        .iter()
        .map(|s| {
            let e = uv[s.b] - uv[s.a];
            (uv[s.b2] - uv[s.a2] - s.rotation * e).norm() / e.norm()
        })
        .fold(0.0, f64::max)
}

/// The upper triangle of the system's sparsity, column by column: vertex `j`'s columns
/// `2j, 2j+1` hold the rows of its neighbours `i ≤ j` (faces and seams).
struct Pattern {
    starts: Vec<usize>,
    rows: Vec<usize>,
    /// Per vertex, its neighbours `i ≤ j`, sorted (itself last).
    neighbours: Vec<Vec<usize>>,
}

impl Pattern {
    fn new(n: usize, faces: &[[u32; 3]], seams: &[[usize; 4]]) -> Self {
        let mut neighbours: Vec<Vec<usize>> = (0..n).map(|j| vec![j]).collect();
        let mut link = |x: usize, y: usize| {
            let (i, j) = (x.min(y), x.max(y));
            neighbours[j].push(i);
        };
        for t in faces {
            for k in 0..3 {
                link(t[k] as usize, t[(k + 1) % 3] as usize);
            }
        }
        for &all in seams {
            for x in 0..4 {
                for y in x + 1..4 {
                    if all[x] != all[y] {
                        link(all[x], all[y]);
                    }
                }
            }
        }
        for list in &mut neighbours {
            list.sort_unstable();
            list.dedup();
        }
        let mut starts = vec![0];
        let mut rows = Vec::new();
        for (j, list) in neighbours.iter().enumerate() {
            for b in 0..2 {
                for &i in list {
                    rows.push(2 * i);
                    if i < j || b == 1 {
                        rows.push(2 * i + 1);
                    }
                }
                starts.push(rows.len());
            }
        }
        Self {
            starts,
            rows,
            neighbours,
        }
    }

    /// The system of this pattern with `values`.
    fn matrix(&self, values: Vec<f64>) -> CsMat<f64> {
        let size = self.starts.len() - 1;
        CsMat::new_csc((size, size), self.starts.clone(), self.rows.clone(), values)
    }

    /// The symbolic analysis of the system: the vertices' minimum-degree order (computed on
    /// the vertex graph, half the size), each vertex's two variables kept together; on one
    /// thread below [`PARALLEL_VERTICES`] vertices.
    fn analyse(&self) -> Result<SymbolicAnalysis, OperatorError> {
        let n = self.neighbours.len();
        let mut starts = vec![0];
        let mut rows = Vec::new();
        for list in &self.neighbours {
            rows.extend_from_slice(list);
            starts.push(rows.len());
        }
        let ones = vec![1.0; rows.len()];
        let graph = CsMat::new_csc((n, n), starts, rows, ones);
        let threads = if n < PARALLEL_VERTICES { 1 } else { 0 };
        let options = CholeskyOptions::DEFAULT.with_threads(threads);
        let options = match amd_permutation(&graph) {
            Ok(order) => {
                let expanded = order.iter().flat_map(|&v| [2 * v, 2 * v + 1]).collect();
                options.with_ordering(Ordering::Custom(expanded))
            }
            Err(_) => options,
        };
        // the values are not read by the analysis
        Cholesky::analyse_with(&self.matrix(vec![0.0; self.rows.len()]), &options)
    }

    /// Where vertex `i ≤ j`'s rows sit in vertex `j`'s columns: entry `(2i + a, 2j + b)`
    /// (`a ≤ b` when `i = j`) is at `starts[2j + b] + 2 · block(i, j) + a`.
    fn block(&self, i: usize, j: usize) -> usize {
        self.neighbours[j]
            .binary_search(&i)
            .expect("the pattern holds every coupled pair")
    }

    /// The position of entry `(p, q)` (any order) in the values.
    fn at(&self, p: usize, q: usize) -> usize {
        let (p, q) = (p.min(q), p.max(q));
        self.starts[q] + 2 * self.block(p / 2, q / 2) + p % 2
    }
}

/// The 3D faces' log areas and corner angles the layout is measured against.
struct Geometry {
    log_area: Vec<f64>,
    angles: Vec<[f64; 3]>,
}

impl Geometry {
    fn new(cut: &TriMesh) -> Self {
        let p = cut.positions();
        let points = |t: &[u32; 3]| t.map(|v| p[v as usize]);
        let faces = cut.faces();
        Self {
            log_area: faces
                .iter()
                .map(|t| {
                    let q = points(t);
                    conformap_mesh::triangle_area(q[0], q[1], q[2]).ln()
                })
                .collect(),
            angles: faces.iter().map(|t| triangle_angles(points(t))).collect(),
        }
    }
}

/// [`Geometry`] and the faces of the layout the polish measures.
struct Target {
    log_area: Vec<f64>,
    angles: Vec<[f64; 3]>,
    /// Faces folded or degenerate in the layout polished: left out.
    skip: Vec<bool>,
    /// Faces measured.
    count: usize,
}

/// `√(μ/3)`: the weight of one corner's angle residual.
fn angle_scale() -> f64 {
    (ANGLE_WEIGHT / 3.0).sqrt()
}

impl Target {
    fn new(geometry: Geometry, faces: &[[u32; 3]], uv: &[Complex64]) -> Self {
        let skip: Vec<bool> = faces
            .iter()
            .map(|t| {
                let z = t.map(|v| uv[v as usize]);
                let twice = cross(z[1] - z[0], z[2] - z[0]);
                !(twice > 0.0 && twice.is_finite())
            })
            .collect();
        Self {
            count: skip.iter().filter(|&&s| !s).count(),
            skip,
            log_area: geometry.log_area,
            angles: geometry.angles,
        }
    }

    /// The polish's energy of layout `uv`; `None` when a face measured is folded or
    /// degenerate (or none is measured).
    fn energy(&self, faces: &[[u32; 3]], uv: &[Complex64]) -> Option<f64> {
        if self.count == 0 {
            return None;
        }
        let mut logs = Vec::with_capacity(self.count);
        let mut angle = 0.0;
        for (f, t) in faces.iter().enumerate() {
            if self.skip[f] {
                continue;
            }
            let z = t.map(|v| uv[v as usize]);
            let twice = cross(z[1] - z[0], z[2] - z[0]);
            if !(twice > 0.0 && twice.is_finite()) {
                return None;
            }
            logs.push((0.5 * twice).ln() - self.log_area[f]);
            for k in 0..3 {
                let d = corner_angle(z, k) - self.angles[f][k];
                angle += d * d;
            }
        }
        let m = logs.iter().sum::<f64>() / self.count as f64;
        let area: f64 = logs.iter().map(|x| (x - m) * (x - m)).sum();
        Some(area + ANGLE_WEIGHT / 3.0 * angle)
    }

    /// Adds `JᵀJ` (upper triangle, into `values` at `pattern`) and `Jᵀr` (into `gradient`)
    /// of the energy's residuals at `uv`, which must have no folded face.
    fn assemble(
        &self,
        faces: &[[u32; 3]],
        uv: &[Complex64],
        pattern: &Pattern,
        values: &mut [f64],
        gradient: &mut [f64],
    ) {
        let log_ratio = |f: usize, z: [Complex64; 3]| {
            (0.5 * cross(z[1] - z[0], z[2] - z[0])).ln() - self.log_area[f]
        };
        let m = faces
            .iter()
            .enumerate()
            .filter(|&(f, _)| !self.skip[f])
            .map(|(f, t)| log_ratio(f, t.map(|v| uv[v as usize])))
            .sum::<f64>()
            / self.count as f64;
        let w = angle_scale();
        for (f, t) in faces.iter().enumerate() {
            if self.skip[f] {
                continue;
            }
            let z = t.map(|v| uv[v as usize]);
            let twice = cross(z[1] - z[0], z[2] - z[0]);
            // local variables (u_0, v_0, u_1, v_1, u_2, v_2); four residual rows
            let mut rows = [[0.0; 6]; 4];
            let mut residuals = [log_ratio(f, z) - m, 0.0, 0.0, 0.0];
            for i in 0..3 {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                rows[0][2 * i] = (z[j].im - z[k].im) / twice;
                rows[0][2 * i + 1] = (z[k].re - z[j].re) / twice;
            }
            for i in 0..3 {
                let (j, k) = ((i + 1) % 3, (i + 2) % 3);
                let (a, b) = (z[j] - z[i], z[k] - z[i]);
                let (na, nb) = (a.norm_sqr(), b.norm_sqr());
                let dk = [-b.im / nb, b.re / nb];
                let dj = [a.im / na, -a.re / na];
                let row = &mut rows[1 + i];
                row[2 * k] = w * dk[0];
                row[2 * k + 1] = w * dk[1];
                row[2 * j] = w * dj[0];
                row[2 * j + 1] = w * dj[1];
                row[2 * i] = -w * (dk[0] + dj[0]);
                row[2 * i + 1] = -w * (dk[1] + dj[1]);
                residuals[1 + i] = w * (corner_angle(z, i) - self.angles[f][i]);
            }
            let var = |l: usize| 2 * t[l / 2] as usize + l % 2;
            for x in 0..6 {
                gradient[var(x)] += (0..4).map(|r| rows[r][x] * residuals[r]).sum::<f64>();
            }
            // one lookup per pair of corners (the 2 × 2 block of their variables)
            for cx in 0..3 {
                for cy in 0..3 {
                    let (vx, vy) = (t[cx] as usize, t[cy] as usize);
                    if vx > vy {
                        continue;
                    }
                    let block = pattern.block(vx, vy);
                    for a in 0..2 {
                        for b in 0..2 {
                            if vx == vy && a > b {
                                continue;
                            }
                            let (x, y) = (2 * cx + a, 2 * cy + b);
                            values[pattern.starts[2 * vy + b] + 2 * block + a] +=
                                (0..4).map(|r| rows[r][x] * rows[r][y]).sum::<f64>();
                        }
                    }
                }
            }
        }
    }
}

/// `Im(conj(a) b)`: twice the signed area of the triangle `0, a, b`.
#[inline]
fn cross(a: Complex64, b: Complex64) -> f64 {
    a.re * b.im - a.im * b.re
}

/// The signed corner angle of planar triangle `z` at corner `k`.
#[inline]
fn corner_angle(z: [Complex64; 3], k: usize) -> f64 {
    let (a, b) = (z[(k + 1) % 3] - z[k], z[(k + 2) % 3] - z[k]);
    cross(a, b).atan2(a.re * b.re + a.im * b.im)
}
