//! Area energies of a boosted sphere or disk map and their analytic gradients with respect
//! to the boost vector (the parameters of [`crate::optimize_sphere_mobius`] and
//! [`crate::optimize_disk_mobius`]).

use num_complex::Complex64;
use rayon::prelude::*;

use crate::mobius::maps::{half_tanh_ratio, half_tanh_ratio_dt_over_t};
use crate::stereo::{cross, norm, sub};

/// Faces per rayon task: large enough that scheduling costs nothing next to the work
/// (about 50 µs of it), small enough to split a 10k-face mesh over a few cores.
const PAR_CHUNK: usize = 4096;

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
    pub points: &'a [[f64; 3]],
    pub faces: &'a [[u32; 3]],
}

impl SphereProblem<'_> {
    /// The boosted points `φ_α(x) = (1 − |α|²)(x − α)/|x − α|² − α` (see
    /// [`crate::boost_sphere_point`]), with `α` computed once.
    pub fn boosted(&self, u: &[f64]) -> Vec<[f64; 3]> {
        let g = half_tanh_ratio(u.iter().map(|x| x * x).sum::<f64>().sqrt());
        let al = [g * u[0], g * u[1], g * u[2]];
        let r = 1.0 - (al[0] * al[0] + al[1] * al[1] + al[2] * al[2]);
        self.points
            .par_iter()
            .with_min_len(PAR_CHUNK)
            .map(|x| {
                let d = sub(*x, al);
                let s = r / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                [s * d[0] - al[0], s * d[1] - al[1], s * d[2] - al[2]]
            })
            .collect()
    }

    /// Energy and gradient with respect to `u ∈ ℝ³`: face areas and each corner's
    /// `w_f ∇_k A_f` in parallel over faces, a sequential scatter into per-vertex `∂E/∂y_i`,
    /// then `∂E/∂α = Σ_i J_iᵀ ∂E/∂y_i` in parallel over vertices (one Jacobian per vertex,
    /// not per corner: six times fewer divisions).
    pub fn eval(&self, u: &[f64], target: Target<'_>) -> (f64, Vec<f64>) {
        let t = u.iter().map(|x| x * x).sum::<f64>().sqrt();
        let g = half_tanh_ratio(t);
        let al = [g * u[0], g * u[1], g * u[2]];
        let r = 1.0 - (al[0] * al[0] + al[1] * al[1] + al[2] * al[2]);
        let y: Vec<[f64; 3]> = self.boosted(u);
        let normals: Vec<[f64; 3]> = self
            .faces
            .par_iter()
            .with_min_len(PAR_CHUNK)
            .map(|f| {
                let p = f.map(|v| y[v as usize]);
                cross(sub(p[1], p[0]), sub(p[2], p[0]))
            })
            .collect();
        let areas: Vec<f64> = normals.iter().map(|n| 0.5 * norm(*n)).collect();
        let (e, w) = area_weights(&areas, target);
        if !e.is_finite() {
            return (f64::INFINITY, vec![0.0; 3]);
        }
        // w_f ∇_k A_f = w_f ½ n̂ × (p_{k+2} − p_{k+1}) for each corner
        let corners: Vec<[[f64; 3]; 3]> = self
            .faces
            .par_iter()
            .with_min_len(PAR_CHUNK)
            .zip(normals.par_iter().zip(w.par_iter()))
            .map(|(f, (n, wf))| {
                let nn = norm(*n);
                if !(nn > 0.0) {
                    return [[0.0; 3]; 3];
                }
                let s = 0.5 * wf / nn;
                let p = f.map(|v| y[v as usize]);
                [0, 1, 2].map(|k| {
                    let c = cross(*n, sub(p[(k + 2) % 3], p[(k + 1) % 3]));
                    [s * c[0], s * c[1], s * c[2]]
                })
            })
            .collect();
        let mut gy = vec![[0.0f64; 3]; y.len()];
        for (f, c) in self.faces.iter().zip(&corners) {
            for k in 0..3 {
                let gi = &mut gy[f[k] as usize];
                for j in 0..3 {
                    gi[j] += c[k][j];
                }
            }
        }
        // Jᵀ G = −2 α (d·G)/q − (r/q + 1) G + 2 r d (d·G)/q² for d = x − α, q = |d|²
        let ga = self
            .points
            .par_iter()
            .with_min_len(PAR_CHUNK)
            .zip(gy.par_iter())
            .fold(
                || [0.0f64; 3],
                |mut acc, (x, gi)| {
                    let d = sub(*x, al);
                    let iq = 1.0 / (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
                    let dg = d[0] * gi[0] + d[1] * gi[1] + d[2] * gi[2];
                    let (c1, c2, c3) = (-2.0 * dg * iq, -(r * iq + 1.0), 2.0 * r * dg * iq * iq);
                    for j in 0..3 {
                        acc[j] += c1 * al[j] + c2 * gi[j] + c3 * d[j];
                    }
                    acc
                },
            )
            .reduce(|| [0.0; 3], |a, b| [a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
        (e, ball_jacobian_t(u, &ga))
    }
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
    use crate::stereo::normalize;

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
        let prob = SphereProblem {
            points: &pts,
            faces: mesh.faces(),
        };
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
