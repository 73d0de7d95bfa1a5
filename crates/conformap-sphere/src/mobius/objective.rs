//! Area energies of a boosted sphere or disk map and their analytic gradients with respect
//! to the boost vector (the parameters of [`crate::optimize_sphere_mobius`] and
//! [`crate::optimize_disk_mobius`]).

use std::cell::RefCell;

use num_complex::Complex64;
use rayon::prelude::*;

use crate::mobius::maps::{half_tanh_ratio, half_tanh_ratio_dt_over_t};
use conformap_operators::vec3::{cross, dot, norm, sub};

/// Faces per rayon task: large enough that scheduling costs nothing next to the work
/// (about 50 µs of it), small enough to split a 10k-face mesh over a few cores.
const PAR_CHUNK: usize = 4096;

/// Faces per chunk of the gradient's parallel sum: each chunk is summed sequentially and the
/// chunks' sums are added in order (the same rounding on any number of threads); 4096 faces
/// are ~0.1 ms of work, so a 100k-face mesh splits into ~25 chunks over the cores.
const SUM_CHUNK: usize = 4096;

/// What is minimized: the uniformity energy, or minus the emphasized region's image share.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Target<'a> {
    /// `Σ (a_f − s_f)²` with the surface shares `s`.
    Uniform(&'a [f64]),
    /// `−Σ_{f ∈ D} a_f` with the region mask.
    Emphasize(&'a [bool]),
    /// `−Σ_{f ∈ D} s_f log(a_f / s_f) / Σ_{f ∈ D} s_f` with the mask and surface shares.
    EmphasizeDensity(&'a [bool], &'a [f64]),
}

/// Value of the target and `∂E/∂A_f` for every face, from the image areas.
fn area_weights(areas: &[f64], target: Target<'_>) -> (f64, Vec<f64>) {
    let total: f64 = areas.iter().sum();
    match target {
        Target::Uniform(shares) => {
            let mut e = 0.0;
            let mut c = 0.0;
            for (a, s) in areas.iter().zip(shares) {
                let af = a / total;
                e += (af - s) * (af - s);
                c += (af - s) * af;
            }
            let w = areas
                .iter()
                .zip(shares)
                .map(|(a, s)| 2.0 / total * (a / total - s - c))
                .collect();
            (e, w)
        }
        Target::Emphasize(mask) => {
            let share: f64 = areas
                .iter()
                .zip(mask)
                .filter(|(_, &m)| m)
                .map(|(a, _)| a)
                .sum::<f64>()
                / total;
            let w = mask
                .iter()
                .map(|&m| -((if m { 1.0 } else { 0.0 }) - share) / total)
                .collect();
            (-share, w)
        }
        Target::EmphasizeDensity(mask, shares) => {
            let sd: f64 = shares
                .iter()
                .zip(mask)
                .filter(|(_, &m)| m)
                .map(|(s, _)| s)
                .sum();
            let mut e = 0.0;
            let mut w = vec![1.0 / total; areas.len()];
            for ((a, s), (&m, wf)) in areas.iter().zip(shares).zip(mask.iter().zip(&mut w)) {
                if m {
                    e -= s * (a / total / s).ln() / sd;
                    *wf -= s / (sd * a);
                }
            }
            // a collapsed face of the region: no gradient, and the step is rejected
            if !e.is_finite() {
                return (f64::INFINITY, w);
            }
            (e, w)
        }
    }
}

/// `∂(g(|u|) u)/∂u = g I + (g'/|u|) u uᵀ` applied to `v` (the matrix is symmetric).
fn ball_jacobian_t(u: &[f64], v: &[f64]) -> Vec<f64> {
    let t = u.iter().map(|x| x * x).sum::<f64>().sqrt();
    let g = half_tanh_ratio(t);
    let h = half_tanh_ratio_dt_over_t(t);
    let uv: f64 = u.iter().zip(v).map(|(a, b)| a * b).sum();
    u.iter()
        .zip(v)
        .map(|(ui, vi)| g * vi + h * ui * uv)
        .collect()
}

/// The sphere problem: base points on the unit sphere and faces.
pub(crate) struct SphereProblem<'a> {
    points: &'a [[f64; 3]],
    faces: &'a [[u32; 3]],
    /// The per-vertex and per-face arrays of [`Self::eval`], kept between evaluations (each
    /// fresh 1–2 MB array cost its page faults on every one of ~150 evaluations).
    scratch: RefCell<(Vec<[f64; 4]>, Vec<f64>)>,
}

impl<'a> SphereProblem<'a> {
    /// The problem of the unit-sphere `points` (per vertex) and `faces`.
    pub fn new(points: &'a [[f64; 3]], faces: &'a [[u32; 3]]) -> Self {
        Self {
            points,
            faces,
            scratch: RefCell::new((Vec::new(), Vec::new())),
        }
    }

    /// The boosted points `φ_α(x) = (1 − |α|²)(x − α)/|x − α|² − α` (see
    /// [`crate::boost_sphere_point`]), with `α` computed once.
    pub fn boosted(&self, u: &[f64]) -> Vec<[f64; 3]> {
        let g = half_tanh_ratio(u.iter().map(|x| x * x).sum::<f64>().sqrt());
        let al = [g * u[0], g * u[1], g * u[2]];
        let r = 1.0 - dot(al, al);
        self.points
            .par_iter()
            .with_min_len(PAR_CHUNK)
            .map(|x| {
                let d = sub(*x, al);
                let s = r / dot(d, d);
                [s * d[0] - al[0], s * d[1] - al[1], s * d[2] - al[2]]
            })
            .collect()
    }

    /// Energy and gradient with respect to `u ∈ ℝ³`, in three passes: the boosted points
    /// with `1/|x − α|²` per vertex, the image areas per face (then the target's `∂E/∂A_f`),
    /// and `∂E/∂α = Σ_f Σ_k J_{f_k}ᵀ w_f ∇_k A_f` summed face by face in fixed chunks
    /// ([`SUM_CHUNK`]). No per-corner or per-vertex gradient array is stored and scattered:
    /// each corner applies its vertex's Jacobian directly (the `1/|x − α|²` kept from the
    /// first pass, so no division per corner), and the chunks' sums are added in order, so
    /// the result does not depend on the thread count or on scheduling.
    pub fn eval(&self, u: &[f64], target: Target<'_>) -> (f64, Vec<f64>) {
        let t = u.iter().map(|x| x * x).sum::<f64>().sqrt();
        let g = half_tanh_ratio(t);
        let al = [g * u[0], g * u[1], g * u[2]];
        let r = 1.0 - dot(al, al);
        let (points, faces) = (self.points, self.faces);
        let mut scratch = self.scratch.borrow_mut();
        let (yq, areas) = &mut *scratch;
        // y_i = r (x_i − α)/|x_i − α|² − α and 1/|x_i − α|²
        yq.resize(points.len(), [0.0; 4]);
        yq.par_chunks_mut(PAR_CHUNK)
            .zip(points.par_chunks(PAR_CHUNK))
            .for_each(|(out, x)| boost_chunk(out, x, (al, r)));
        let yq = &*yq;
        areas.resize(faces.len(), 0.0);
        areas
            .par_chunks_mut(PAR_CHUNK)
            .zip(faces.par_chunks(PAR_CHUNK))
            .for_each(|(out, f)| area_chunk(out, f, yq));
        let areas = &*areas;
        let (e, w) = area_weights(areas, target);
        if !e.is_finite() {
            return (f64::INFINITY, vec![0.0; 3]);
        }
        // per corner: c = w_f ∇_k A_f = w_f ½ n̂ × (p_{k+2} − p_{k+1}), and
        // J_iᵀ c = −2 α (d·c) q⁻¹ − (r q⁻¹ + 1) c + 2 r d (d·c) q⁻² for d = x_i − α, q = |d|²;
        // summed as a·α + b + c' (a scalar, b and c' vectors): seven numbers per chunk
        let partial: Vec<[f64; 7]> = faces
            .par_chunks(SUM_CHUNK)
            .zip(w.par_chunks(SUM_CHUNK).zip(areas.par_chunks(SUM_CHUNK)))
            .map(|(faces, (w, a))| gradient_chunk(faces, w, a, points, yq, (al, r)))
            .collect();
        let mut sum = [0.0f64; 7];
        for a in &partial {
            for (s, x) in sum.iter_mut().zip(a) {
                *s += x;
            }
        }
        let ga = [0, 1, 2].map(|j| sum[0] * al[j] + sum[1 + j] + sum[4 + j]);
        (e, ball_jacobian_t(u, &ga))
    }
}

/// One chunk of the boosted points `y = r (x − α)/|x − α|² − α` with `1/|x − α|²`, and one
/// chunk of the boosted faces' areas: functions of their own (as [`gradient_chunk`]) so
/// that the loops compile the same whatever rayon's adapters around them inline.
#[inline(never)]
fn boost_chunk(out: &mut [[f64; 4]], points: &[[f64; 3]], (al, r): ([f64; 3], f64)) {
    for (o, x) in out.iter_mut().zip(points) {
        let d = sub(*x, al);
        let iq = 1.0 / dot(d, d);
        let s = r * iq;
        *o = [s * d[0] - al[0], s * d[1] - al[1], s * d[2] - al[2], iq];
    }
}

/// See [`boost_chunk`].
#[inline(never)]
fn area_chunk(out: &mut [f64], faces: &[[u32; 3]], yq: &[[f64; 4]]) {
    for (a, f) in out.iter_mut().zip(faces) {
        let p = f.map(|v| {
            let q = yq[v as usize];
            [q[0], q[1], q[2]]
        });
        *a = 0.5 * norm(cross(sub(p[1], p[0]), sub(p[2], p[0])));
    }
}

/// One chunk's share of the sphere gradient's seven sums (see [`SphereProblem::eval`]):
/// a function of its own, so that the hot loop is compiled the same whatever rayon's
/// adapters around it inline (a closure inlined into them measured 30–50 % slower).
#[inline(never)]
fn gradient_chunk(
    faces: &[[u32; 3]],
    w: &[f64],
    a: &[f64],
    points: &[[f64; 3]],
    yq: &[[f64; 4]],
    (al, r): ([f64; 3], f64),
) -> [f64; 7] {
    // s_f = ½ w_f/|n_f| = w_f/(4 A_f), in a loop of its own (vectorized divisions, off the
    // per-face dependency chain); 0 for a collapsed face
    let coef: Vec<f64> = w
        .iter()
        .zip(a)
        .map(|(wf, af)| if *af > 0.0 { wf / (4.0 * af) } else { 0.0 })
        .collect();
    let mut acc = [0.0f64; 7];
    for (f, &s) in faces.iter().zip(&coef) {
        if s == 0.0 {
            continue;
        }
        let p = f.map(|v| {
            let q = yq[v as usize];
            [q[0], q[1], q[2]]
        });
        let n = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        for k in 0..3 {
            let e = cross(n, sub(p[(k + 2) % 3], p[(k + 1) % 3]));
            let c = [s * e[0], s * e[1], s * e[2]];
            let v = f[k] as usize;
            let d = sub(points[v], al);
            let iq = yq[v][3];
            let dc = dot(d, c);
            let (c2, c3) = (-(r * iq + 1.0), 2.0 * r * dc * iq * iq);
            acc[0] -= 2.0 * dc * iq;
            for j in 0..3 {
                acc[1 + j] += c2 * c[j];
                acc[4 + j] += c3 * d[j];
            }
        }
    }
    acc
}

/// The disk problem: a planar map in the closed unit disk and faces.
pub(crate) struct DiskProblemM<'a> {
    pub map: &'a [Complex64],
    pub faces: &'a [[u32; 3]],
}

impl DiskProblemM<'_> {
    /// `β = g(|v|) v` as a complex number.
    fn beta(v: &[f64]) -> Complex64 {
        let g = half_tanh_ratio(v[0].hypot(v[1]));
        Complex64::new(g * v[0], g * v[1])
    }

    /// The moved map `(z − β)/(1 − β̄z)`.
    pub fn moved(&self, v: &[f64]) -> Vec<Complex64> {
        let b = Self::beta(v);
        self.map
            .iter()
            .map(|&z| (z - b) / (1.0 - b.conj() * z))
            .collect()
    }

    /// Energy and gradient with respect to `v ∈ ℝ²`.
    pub fn eval(&self, v: &[f64], target: Target<'_>) -> (f64, Vec<f64>) {
        let b = Self::beta(v);
        let y = self.moved(v);
        let signed: Vec<f64> = self
            .faces
            .iter()
            .map(|f| {
                let p = f.map(|k| y[k as usize]);
                crate::mobius::energy::planar_signed_area(p)
            })
            .collect();
        let areas: Vec<f64> = signed.iter().map(|a| a.abs()).collect();
        let (e, w) = area_weights(&areas, target);
        if !e.is_finite() {
            return (f64::INFINITY, vec![0.0; 2]);
        }
        // G_i = ∂E/∂x_i + i ∂E/∂y_i; ∇_{z_i} A = ½ (y_j − y_k, x_k − x_j) for the signed area
        let mut gz = vec![Complex64::new(0.0, 0.0); y.len()];
        for ((f, wf), sa) in self.faces.iter().zip(&w).zip(&signed) {
            let s = if *sa < 0.0 { -wf } else { *wf };
            for k in 0..3 {
                let zj = y[f[(k + 1) % 3] as usize];
                let zk = y[f[(k + 2) % 3] as usize];
                gz[f[k] as usize] += 0.5 * s * Complex64::new(zj.im - zk.im, zk.re - zj.re);
            }
        }
        // ∂z'/∂β = −1/(1 − β̄z), ∂z'/∂β̄ = (z − β) z/(1 − β̄z)²
        let mut gb = [0.0f64; 2];
        for (z, gi) in self.map.iter().zip(&gz) {
            let den = 1.0 - b.conj() * z;
            let db = -1.0 / den;
            let dbc = (z - b) * z / (den * den);
            let dx = db + dbc;
            let dy = Complex64::new(0.0, 1.0) * (db - dbc);
            gb[0] += (gi.conj() * dx).re;
            gb[1] += (gi.conj() * dy).re;
        }
        (e, ball_jacobian_t(v, &gb))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use conformap_operators::vec3::normalize;

    fn fd_check(eval: &crate::mobius::newton::EvalFn<'_>, x: &[f64]) {
        let (_, g) = eval(x);
        for j in 0..x.len() {
            let h = 1e-6;
            let mut xp = x.to_vec();
            let mut xm = x.to_vec();
            xp[j] += h;
            xm[j] -= h;
            let fd = (eval(&xp).0 - eval(&xm).0) / (2.0 * h);
            let scale = g.iter().map(|v| v.abs()).fold(1e-12, f64::max);
            assert!(
                (fd - g[j]).abs() < 1e-6 * scale + 1e-9,
                "component {j}: fd {fd} vs {}",
                g[j]
            );
        }
    }

    #[test]
    fn sphere_gradients_match_finite_differences() {
        let mesh = crate::doc_support::octahedron_sphere(2);
        let pts: Vec<[f64; 3]> = mesh.positions().iter().map(|p| normalize(*p)).collect();
        let shares = crate::mobius::energy::surface_shares(&mesh);
        let mask: Vec<bool> = (0..mesh.num_faces()).map(|f| f % 3 == 0).collect();
        let prob = SphereProblem::new(&pts, mesh.faces());
        for u in [
            [0.0, 0.0, 0.0],
            [0.3, -0.5, 0.2],
            [1e-5, 2e-5, 0.0],
            [1.2, 0.4, -0.9],
        ] {
            fd_check(&|x| prob.eval(x, Target::Uniform(&shares)), &u);
            fd_check(&|x| prob.eval(x, Target::Emphasize(&mask)), &u);
            fd_check(
                &|x| prob.eval(x, Target::EmphasizeDensity(&mask, &shares)),
                &u,
            );
        }
    }

    #[test]
    fn disk_gradients_match_finite_differences() {
        let mesh = conformap_testkit::flat_disk(6, 8);
        let map: Vec<Complex64> = mesh
            .positions()
            .iter()
            .map(|p| Complex64::new(p[0], 0.7 * p[1]))
            .collect();
        let shares = crate::mobius::energy::surface_shares(&mesh);
        let mask: Vec<bool> = (0..mesh.num_faces()).map(|f| f % 2 == 0).collect();
        let prob = DiskProblemM {
            map: &map,
            faces: mesh.faces(),
        };
        for v in [[0.0, 0.0], [0.3, -0.5], [1e-5, 0.0], [1.1, 0.7]] {
            fd_check(&|x| prob.eval(x, Target::Uniform(&shares)), &v);
            fd_check(&|x| prob.eval(x, Target::Emphasize(&mask)), &v);
            fd_check(
                &|x| prob.eval(x, Target::EmphasizeDensity(&mask, &shares)),
                &v,
            );
        }
    }
}
