//! The Laplacian choice and the fold guards on meshes built to fold: harmonic maps folded by
//! negative cotangent weights (fixed by the intrinsic Delaunay Laplacian, or by mean value
//! weights), and a boundary out of order (fixed by putting it back in order).

use conformap_disk::{
    cem, run_disk_method, unfold_disk_map, CemOptions, DiskError, DiskMethod, DiskOptions,
    DiskProblem, InteriorOperator, LaplacianKind, ProblemOptions,
};
use conformap_mesh::TriMesh;
use num_complex::Complex64;

/// xorshift64: a tiny deterministic generator (committed seeds reproduce the meshes).
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Self(seed * 2_654_435_761 + 1)
    }

    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A flat `n × n` grid with the interior vertices jittered by up to `0.45` of a cell and
/// each square split along a random diagonal (many obtuse pairs: negative weights), and
/// a boundary map with random gaps around the circle. From the search that found these
/// seeds: the plain harmonic map folds about 1 in 700 such problems.
fn random_problem(n: u32, seed: u64) -> (TriMesh, Vec<f64>) {
    let mut r = Rng::new(seed);
    let mut p = vec![];
    for j in 0..=n {
        for i in 0..=n {
            let inside = i > 0 && j > 0 && i < n && j < n;
            let (jx, jy) = if inside {
                (0.45 * (2.0 * r.next() - 1.0), 0.45 * (2.0 * r.next() - 1.0))
            } else {
                (0.0, 0.0)
            };
            p.push([f64::from(i) + jx, f64::from(j) + jy, 0.0]);
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut f = vec![];
    for j in 0..n {
        for i in 0..n {
            if r.next() < 0.5 {
                f.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
                f.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
            } else {
                f.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
                f.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
    }
    let mesh = TriMesh::try_new(p, f).expect("valid grid");
    let nb = mesh.boundary_loops()[0].len();
    let gaps: Vec<f64> = (0..nb).map(|_| r.next()).collect();
    let total: f64 = gaps.iter().sum();
    let mut theta = Vec::with_capacity(nb);
    let mut acc = 0.0;
    for g in gaps {
        theta.push(acc);
        acc += g / total * std::f64::consts::TAU;
    }
    (mesh, theta)
}

fn flipped(mesh: &TriMesh, f: &[Complex64]) -> usize {
    mesh.faces()
        .iter()
        .filter(|t| {
            let (a, b, c) = (f[t[0] as usize], f[t[1] as usize], f[t[2] as usize]);
            !(((b - a).conj() * (c - a)).im > 0.0)
        })
        .count()
}

fn circle(theta: &[f64]) -> Vec<Complex64> {
    theta
        .iter()
        .map(|&t| Complex64::from_polar(1.0, t))
        .collect()
}

#[test]
fn a_negative_weight_fold_is_fixed_by_the_intrinsic_laplacian() {
    let (mesh, theta) = random_problem(4, 1631);
    let fb = circle(&theta);
    let auto = DiskProblem::new(&mesh).unwrap();
    assert_eq!(auto.laplacian_kind(), LaplacianKind::Cotan);
    assert!(auto.has_intrinsic_reserve());
    assert!(auto.laplacian_note().contains("negative weights"));
    // nothing is built before a map folds
    assert!(auto.intrinsic_stats().is_none());
    let plain = auto.harmonic_extension(&fb);
    let folded = flipped(&mesh, &plain);
    assert!(folded > 0, "the plain map folds here");
    assert_eq!(auto.reserve_factor_ms(), 0.0);
    let g = auto.guarded_extension(&fb).unwrap();
    assert_eq!(g.flipped_faces_before, folded);
    assert_eq!(
        (g.flipped_faces, g.operator),
        (0, InteriorOperator::IntrinsicDelaunay)
    );
    assert_eq!(flipped(&mesh, &g.map), 0);
    assert!(g.note().is_some_and(|n| n.contains("intrinsic-delaunay")));
    assert!(auto.reserve_factor_ms() > 0.0);
    let stats = auto.intrinsic_stats().unwrap();
    assert!(stats.non_delaunay_before > 0 && stats.non_delaunay_after == 0);
    // the boundary is kept
    for (&v, z) in auto.partition().boundary.iter().zip(&fb) {
        assert_eq!(g.map[v as usize], *z);
    }
    // solving with the intrinsic Laplacian throughout gives the same interior
    let opts = ProblemOptions::DEFAULT.with_laplacian(LaplacianKind::IntrinsicDelaunay);
    let intrinsic = DiskProblem::with_options(&mesh, &opts).unwrap();
    assert_eq!(intrinsic.laplacian_kind(), LaplacianKind::IntrinsicDelaunay);
    for (x, y) in intrinsic.harmonic_extension(&fb).iter().zip(&g.map) {
        assert!((x - y).norm() < 1e-12);
    }
    // unfold_disk_map does the same for a finished map
    let u = unfold_disk_map(&auto, &plain).unwrap();
    assert_eq!(
        (u.flipped_before, u.flipped_after, u.repaired_gaps),
        (folded, 0, 0)
    );
    assert_eq!(u.operator, InteriorOperator::IntrinsicDelaunay);
}

#[test]
fn a_fold_the_intrinsic_map_keeps_is_fixed_by_mean_value_weights() {
    // here the intrinsic map embeds the intrinsic triangulation, but an input face whose
    // edge was flipped folds as a straight triangle
    let (mesh, theta) = random_problem(4, 250);
    let fb = circle(&theta);
    let auto = DiskProblem::new(&mesh).unwrap();
    let folded = flipped(&mesh, &auto.harmonic_extension(&fb));
    assert!(folded > 0);
    let opts = ProblemOptions::DEFAULT.with_laplacian(LaplacianKind::IntrinsicDelaunay);
    let intrinsic = DiskProblem::with_options(&mesh, &opts).unwrap();
    assert!(flipped(&mesh, &intrinsic.harmonic_extension(&fb)) > 0);
    let g = auto.guarded_extension(&fb).unwrap();
    assert_eq!(
        (g.flipped_faces, g.operator),
        (0, InteriorOperator::MeanValue)
    );
    // the plain-cotangent problem has no intrinsic reserve, but the mean value map
    let opts = ProblemOptions::DEFAULT.with_laplacian(LaplacianKind::Cotan);
    let cotan = DiskProblem::with_options(&mesh, &opts).unwrap();
    assert!(!cotan.has_intrinsic_reserve());
    let g = cotan.guarded_extension(&fb).unwrap();
    assert_eq!(
        (g.flipped_faces, g.operator),
        (0, InteriorOperator::MeanValue)
    );
}

#[test]
fn unfold_puts_a_backward_boundary_back_in_order() {
    // a flat hexagonal patch (centre and two rings): CEM maps it without folds
    let mut pos = vec![[0.0, 0.0, 0.0]];
    for r in 1..=2 {
        for k in 0..6 * r {
            let t = f64::from(k) * std::f64::consts::TAU / f64::from(6 * r);
            pos.push([f64::from(r) * t.cos(), f64::from(r) * t.sin(), 0.0]);
        }
    }
    let mesh = TriMesh::try_new(pos, conformap_disk::doc_support::two_ring_faces()).unwrap();
    let mut problem = DiskProblem::new(&mesh).unwrap();
    let good = cem(&mut problem, &CemOptions::DEFAULT).unwrap().map;
    assert_eq!(flipped(&mesh, &good), 0);
    let untouched = unfold_disk_map(&problem, &good).unwrap();
    assert_eq!((untouched.flipped_before, untouched.gap_floor), (0, 0.0));
    assert_eq!(untouched.map, good);
    assert!(untouched.note().is_none());
    // move one boundary vertex backwards past its predecessor
    let lp = problem.partition().boundary.clone();
    let mut fb = problem.partition().boundary_values(&good);
    fb[5] = fb[4] * Complex64::from_polar(1.0, -0.05);
    let bad = problem.harmonic_extension(&fb);
    assert!(flipped(&mesh, &bad) > 0);
    let u = unfold_disk_map(&problem, &bad).unwrap();
    assert_eq!(flipped(&mesh, &u.map), 0);
    assert_eq!(u.repaired_gaps, 1);
    // the boundary winds once counter-clockwise, every gap at least the floor
    let n = lp.len();
    let mut total = 0.0;
    for k in 0..n {
        let (p, q) = (u.map[lp[k] as usize], u.map[lp[(k + 1) % n] as usize]);
        assert!((p.norm() - 1.0).abs() < 1e-12);
        let g = (q / p).arg();
        assert!(g >= 0.5 * u.gap_floor, "gap {k}: {g}");
        total += g;
    }
    assert!((total - std::f64::consts::TAU).abs() < 1e-12);
    // a boundary that winds clockwise (a mirror image) cannot be repaired
    let mirrored: Vec<Complex64> = fb.iter().map(|z| z.conj()).collect();
    let bad = problem.harmonic_extension(&mirrored);
    assert!(matches!(
        unfold_disk_map(&problem, &bad),
        Err(DiskError::Folded { .. })
    ));
}

#[test]
fn harmonic_and_cem_maps_that_fold_come_back_flip_free_unless_kept() {
    // seeds found by searching the random grids: the plain arc-length harmonic map folds
    // one face on seed 25, 20-iteration CEM three on seed 89
    for (seed, method) in [(25, DiskMethod::Harmonic), (89, DiskMethod::Cem)] {
        let (mesh, _) = random_problem(4, seed);
        let mut problem = DiskProblem::new(&mesh).unwrap();
        let keep = DiskOptions::DEFAULT.with_keep_folds(true);
        let raw = run_disk_method(&mut problem, method, &keep).unwrap();
        let folded = flipped(&mesh, &raw.map);
        assert!(folded > 0, "{method} seed {seed}: the plain map folds");
        let out = run_disk_method(&mut problem, method, &DiskOptions::DEFAULT).unwrap();
        assert_eq!(flipped(&mesh, &out.map), 0, "{method} seed {seed}");
        let r = &out.report;
        assert_eq!(r.energy_history.len(), raw.report.energy_history.len() + 1);
        assert_eq!(r.best_iteration, r.energy_history.len() - 1);
        // the repair is one more iteration and where the returned iterate is chosen from
        assert_eq!(
            r.iterations,
            raw.report.iterations + 1,
            "{method} seed {seed}"
        );
        assert_eq!(
            r.energy_history.len(),
            r.iterations + 1,
            "{method} seed {seed}"
        );
        assert_eq!(r.best_from, r.best_iteration, "{method} seed {seed}");
        let e = problem.conformal_energy(&out.map);
        assert!((r.energy_history[r.best_iteration] - e).abs() <= 1e-12 * e.abs());
        assert!(
            r.notes
                .iter()
                .any(|n| n.contains(&format!("the map folded {folded} faces"))),
            "{:?}",
            r.notes
        );
        // the boundary stays on the unit circle
        for &v in &problem.partition().boundary {
            assert!((out.map[v as usize].norm() - 1.0).abs() < 1e-12);
        }
    }
}
