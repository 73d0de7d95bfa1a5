//! Tests of the CCEM internals on real fixtures: the θ-form energy against the full-mesh
//! energy of the reconstructed map, the analytic gradient and the quadratic model against
//! finite differences, and the two Schur-complement paths against each other.

use num_complex::Complex64;

use crate::angles::unwrap_boundary;
use crate::ccem::energy::{dot, evaluate, quadratic_coefficients, step};
use crate::ccem::schur::{Schur, SchurMode};
use crate::initial::arc_length_boundary;
use crate::{cem, CemOptions, DiskProblem};

/// Reads a committed fixture (`<workspace>/fixtures/<name>`, plain `v`/`f` OBJ).
pub(crate) use conformap_testkit::fixture_mesh as fixture;

/// Boundary angles of the CEM map of a problem (a realistic, non-trivial point).
fn cem_angles(problem: &mut DiskProblem<'_>) -> Vec<f64> {
    let out = cem(problem, &CemOptions::DEFAULT.with_max_iter(3)).expect("cem");
    let fb = problem.partition().boundary_values(&out.map);
    unwrap_boundary(&fb, 0.0).expect("in order").theta
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn theta_energy_is_the_full_mesh_energy() {
    for name in ["woody.obj", "spothead.obj"] {
        let mesh = fixture(name);
        let mut problem = DiskProblem::new(&mesh).expect("disk");
        let theta = cem_angles(&mut problem);
        for mode in [SchurMode::Dense, SchurMode::Implicit] {
            let schur = Schur::new(&problem, mode);
            let e = evaluate(&schur, theta.clone());
            let map = problem.harmonic_extension(&e.f);
            let full = problem.conformal_energy(&map);
            assert!(
                rel(e.energy, full) < 1e-9,
                "{name} {mode:?}: {} vs {full}",
                e.energy
            );
        }
    }
}

#[test]
fn dense_and_implicit_schur_agree() {
    let mesh = fixture("woody.obj");
    let problem = DiskProblem::new(&mesh).expect("disk");
    let (dense, implicit) = (
        Schur::new(&problem, SchurMode::Dense),
        Schur::new(&problem, SchurMode::Implicit),
    );
    assert_eq!(dense.mode(), SchurMode::Dense);
    assert_eq!(implicit.mode(), SchurMode::Implicit);
    let nb = problem.num_boundary();
    let x: Vec<Complex64> = (0..nb)
        .map(|k| Complex64::new((k as f64 * 0.37).sin(), (k as f64 * 1.3).cos()))
        .collect();
    let (a, b) = (dense.apply(&x), implicit.apply(&x));
    let scale = b.iter().map(|z| z.norm()).fold(0.0, f64::max);
    let err = a
        .iter()
        .zip(&b)
        .map(|(p, q)| (p - q).norm())
        .fold(0.0, f64::max);
    assert!(err < 1e-10 * scale, "{err} vs {scale}");
    // A 1 = 0: the constant vector spans the null space (CCEM §3)
    let ones = vec![Complex64::new(1.0, 0.0); nb];
    let a1 = dense.apply(&ones);
    assert!(a1.iter().all(|z| z.norm() < 1e-12 * scale));
    assert_eq!(dense.products(), 2);
}

/// Central differences of fourth order: `(−E(+2h) + 8E(+h) − 8E(−h) + E(−2h)) / 12h`.
fn fd_slope(schur: &Schur<'_, '_>, theta: &[f64], d: &[f64], h: f64) -> f64 {
    let e = |a: f64| evaluate(schur, step(theta, d, a)).energy;
    (-e(2.0 * h) + 8.0 * e(h) - 8.0 * e(-h) + e(-2.0 * h)) / (12.0 * h)
}

#[test]
fn gradient_matches_finite_differences() {
    for name in ["woody.obj", "alligator.obj"] {
        let mesh = fixture(name);
        let mut problem = DiskProblem::new(&mesh).expect("disk");
        let theta = cem_angles(&mut problem);
        let schur = Schur::new(&problem, SchurMode::Dense);
        let at = evaluate(&schur, theta.clone());
        let n = theta.len();
        // the gradient itself, component by component, on a few vertices
        for j in [0, n / 3, n - 1] {
            let mut e = vec![0.0; n];
            e[j] = 1.0;
            let fd = fd_slope(&schur, &theta, &e, 1e-4);
            let scale = at.grad.iter().map(|g| g.abs()).fold(0.0, f64::max);
            assert!(
                (fd - at.grad[j]).abs() < 1e-7 * scale,
                "{name} ∂E/∂θ_{j}: {fd} vs {}",
                at.grad[j]
            );
        }
        // directional derivatives along smooth directions: 1e-9 relative
        for freq in [1.0, 3.0] {
            let d: Vec<f64> = (0..n)
                .map(|k| (freq * std::f64::consts::TAU * k as f64 / n as f64).sin())
                .collect();
            let fd = fd_slope(&schur, &theta, &d, 1e-3);
            let an = dot(&at.grad, &d);
            assert!(
                rel(fd, an) < 1e-9,
                "{name}: slope {fd} vs {an} ({:.1e})",
                rel(fd, an)
            );
        }
        // the gradient is orthogonal to 1 (rotation invariance)
        let sum: f64 = at.grad.iter().sum();
        assert!(sum.abs() < 1e-12 * at.grad.iter().map(|g| g.abs()).sum::<f64>());
    }
}

#[test]
fn quadratic_model_matches_second_differences() {
    let mesh = fixture("woody.obj");
    let mut problem = DiskProblem::new(&mesh).expect("disk");
    let theta = cem_angles(&mut problem);
    let schur = Schur::new(&problem, SchurMode::Implicit);
    let at = evaluate(&schur, theta.clone());
    let d: Vec<f64> = at.grad.iter().map(|g| -g).collect();
    let (c1, c2) = quadratic_coefficients(&schur, &at, &d);
    assert!(rel(c1, -dot(&at.grad, &at.grad)) < 1e-12);
    let h = 1e-3 / at.grad.iter().map(|g| g.abs()).fold(0.0, f64::max);
    let e = |a: f64| evaluate(&schur, step(&theta, &d, a)).energy;
    let second =
        (-e(2.0 * h) + 16.0 * e(h) - 30.0 * e(0.0) + 16.0 * e(-h) - e(-2.0 * h)) / (12.0 * h * h);
    assert!(
        rel(2.0 * c2, second) < 1e-6,
        "2 c2 = {} vs {second}",
        2.0 * c2
    );
}

#[test]
fn arc_length_angles_are_in_order() {
    let mesh = fixture("woody.obj");
    let problem = DiskProblem::new(&mesh).expect("disk");
    let fb = arc_length_boundary(&mesh, &problem.partition().boundary);
    let u = unwrap_boundary(&fb, 1e-13).expect("in order");
    assert_eq!(u.repaired, 0);
    assert!(u.theta.windows(2).all(|w| w[1] > w[0]));
}
