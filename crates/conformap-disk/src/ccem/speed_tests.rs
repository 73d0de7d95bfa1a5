//! Tests of the fast paths against the paths they replace: the Schur complement formed by
//! the restricted forward solve against `n_B` column solves, Angenent's map from the Schur
//! complement against its own factorization, the Hessian of the preconditioner against
//! finite differences of the gradient, and the energies of CCEM-QN on the fast paths
//! against the unoptimized ones.

use num_complex::Complex64;

use crate::angles::unwrap_boundary;
use crate::ccem::energy::{evaluate, step};
use crate::ccem::hessian::{hessian, hessian_band};
use crate::ccem::schur::{form_dense, form_dense_by_solves, Schur, SchurMode};
use crate::ccem::tests::fixture;
use crate::initial::{angenent_boundary, angenent_from_schur, angenent_rhs, centre_face};
use crate::{ccem, CcemOptions, CcemStart, CemOptions, DiskProblem};

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn restricted_forward_solve_forms_the_same_schur_complement() {
    for name in ["woody.obj", "spothead.obj", "alligator.obj"] {
        let mesh = fixture(name);
        let problem = DiskProblem::new(&mesh).expect("disk");
        let nb = problem.num_boundary();
        let face = centre_face(&mesh);
        let rhs = angenent_rhs(&mesh, face);
        let (fast, coupling) = form_dense(&problem, &rhs).expect("dense");
        let slow = form_dense_by_solves(&problem);
        let scale = slow.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let err = fast
            .iter()
            .zip(&slow)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(err <= 1e-12 * scale, "{name}: {err:e} of {scale:e}");
        // the coupling L_BI L_II⁻¹ b_I against a solve
        let part = problem.partition();
        let mut bi = vec![Complex64::new(0.0, 0.0); part.interior.len()];
        for (v, z) in rhs {
            if part.is_interior[v as usize] {
                bi[part.local[v as usize] as usize] += z;
            }
        }
        let x = problem.interior_factor().solve_complex(&bi);
        let want = problem.blocks().bi_mul(&x);
        let cscale = want.iter().fold(0.0f64, |m, z| m.max(z.norm()));
        for (a, b) in coupling.iter().zip(&want) {
            assert!((a - b).norm() <= 1e-11 * cscale, "{name}: {a} vs {b}");
        }
        assert_eq!(coupling.len(), nb);
    }
}

#[test]
fn angenent_from_the_schur_complement_is_angenent() {
    for name in ["woody.obj", "spothead.obj"] {
        let mesh = fixture(name);
        let problem = DiskProblem::new(&mesh).expect("disk");
        let face = centre_face(&mesh);
        let schur = Schur::with_rhs(&problem, SchurMode::Dense, &angenent_rhs(&mesh, face));
        let (Some(a), Some(c)) = (schur.dense(), schur.coupling()) else {
            panic!("{name}: no dense Schur complement");
        };
        let fast = angenent_from_schur(&problem, face, a, c).expect("schur");
        let slow = angenent_boundary(&problem).expect("factor");
        assert_eq!(fast.face, slow.face);
        assert_eq!(fast.conjugated, slow.conjugated);
        for (p, q) in fast.boundary.iter().zip(&slow.boundary) {
            assert!((p - q).norm() < 1e-10, "{name}: {p} vs {q}");
        }
    }
}

/// Runs `check` with the dense Schur complement of woody.obj, its matrix and the
/// arc-length boundary angles: the point both Hessian checks below are made at.
fn at_woody_arc_length(check: impl FnOnce(&Schur<'_, '_>, &[f64], Vec<f64>)) {
    let mesh = fixture("woody.obj");
    let problem = DiskProblem::new(&mesh).expect("disk");
    let schur = Schur::new(&problem, SchurMode::Dense);
    let a = schur.dense().expect("dense").to_vec();
    let fb = crate::initial::arc_length_boundary(&mesh, &problem.partition().boundary);
    let theta = unwrap_boundary(&fb, 0.0).expect("in order").theta;
    check(&schur, &a, theta);
}

#[test]
fn hessian_matches_differences_of_the_gradient() {
    at_woody_arc_length(|schur, a, theta| {
        let at = evaluate(schur, theta.clone());
        let n = theta.len();
        let h = hessian(a, &at);
        let d: Vec<f64> = (0..n)
            .map(|k| {
                (3.0 * std::f64::consts::TAU * k as f64 / n as f64).sin() + 0.1 * (k % 7) as f64
            })
            .collect();
        let eps = 1e-5;
        let gp = evaluate(schur, step(&theta, &d, eps)).grad;
        let gm = evaluate(schur, step(&theta, &d, -eps)).grad;
        let scale = gp.iter().fold(0.0f64, |m, g| m.max(g.abs())) / eps;
        for j in 0..n {
            let fd = (gp[j] - gm[j]) / (2.0 * eps);
            let hd: f64 = (0..n).map(|k| h[k * n + j] * d[k]).sum();
            assert!((fd - hd).abs() < 1e-6 * scale, "row {j}: {fd} vs {hd}");
        }
    });
}

/// The banded preconditioner's entries are the whole Hessian's inside the cyclic band
/// (wrap-around included), read from the other triangle of `A`.
#[test]
fn band_of_the_hessian_is_the_hessian_in_the_band() {
    at_woody_arc_length(|schur, a, theta| {
        let at = evaluate(schur, theta);
        let n = at.theta.len();
        let h = hessian(a, &at);
        let b = 7;
        let band = hessian_band(a, &at, b);
        let scale = h.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        for (j, row) in band.iter().enumerate() {
            for (slot, d) in (0..=2 * b).zip(-(b as isize)..=b as isize) {
                let k = (j as isize + d).rem_euclid(n as isize) as usize;
                let want = h[k * n + j];
                assert!(
                    (row[slot] - want).abs() <= 1e-14 * scale,
                    "({j}, {k}): {} vs {want}",
                    row[slot]
                );
            }
        }
    });
}

/// CCEM-QN energies: the dense Schur complement (formed by the restricted forward solve)
/// against the implicit one (a sparse solve per product, the unoptimized path), same start
/// and iteration; and the default fast path (Angenent's start, Hessian preconditioner)
/// against the former default (CEM start, plain BFGS, implicit).
#[test]
fn fast_paths_reach_the_same_energy() {
    for name in ["woody.obj", "spothead.obj"] {
        let mesh = fixture(name);
        let mut problem = DiskProblem::new(&mesh).expect("disk");
        let plain = CcemOptions::DEFAULT
            .with_start(CcemStart::Cem(CemOptions::DEFAULT))
            .with_hessian_preconditioner(false);
        let mut energy = |o: &CcemOptions| {
            let out = ccem(&mut problem, o).expect("ccem");
            (problem.conformal_energy(&out.map), out.report)
        };
        let (slow, _) = energy(&plain.with_schur(SchurMode::Implicit));
        let (dense, _) = energy(&plain.with_schur(SchurMode::Dense));
        assert!(rel(dense, slow) < 1e-9, "{name}: {dense} vs {slow}");
        let (fast, report) = energy(&CcemOptions::DEFAULT);
        assert_eq!(report.factorizations, 1, "{name}");
        assert!(rel(fast, slow) < 1e-6, "{name}: {fast} vs {slow}");
    }
}
