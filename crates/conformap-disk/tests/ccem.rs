//! CCEM on real fixtures (woody, alligator, spothead: copies in `fixtures/`) and analytic
//! meshes: energy targets, the bijectivity guard, the Wolfe conditions on every accepted
//! step, and the public API. Larger meshes from `../shared/meshes` run in `#[ignore]`d
//! tests (`cargo test -p conformap-disk --release -- --ignored`).

use conformap_disk::{
    ccem, cem, compute_disk_map, CcemOptions, CcemStart, CcemVariant, CemOptions, DiskError,
    DiskMap, DiskMethod, DiskOptions, DiskProblem, SchurMode, SolverReport,
};
use conformap_mesh::TriMesh;
use conformap_operators::{cotan_laplacian, quadratic_form};
use conformap_testkit::{fixture_mesh as fixture, read_shared_mesh_or_skip};
use num_complex::Complex64;

/// `E_C` with the mesh's own cotangent weights (CEM Eq. 5–8), whatever Laplacian the
/// problem solved with: the number the metrics crate reports and other tools are
/// compared by.
fn mesh_energy(mesh: &TriMesh, problem: &DiskProblem<'_>, f: &[Complex64]) -> f64 {
    quadratic_form(&cotan_laplacian(mesh), f) - problem.image_area(f)
}

fn flipped(mesh: &TriMesh, f: &[Complex64]) -> usize {
    mesh.faces()
        .iter()
        .filter(|t| {
            let (a, b, c) = (f[t[0] as usize], f[t[1] as usize], f[t[2] as usize]);
            ((b - a).conj() * (c - a)).im <= 0.0
        })
        .count()
}

/// Everything a CCEM map must satisfy: boundary on the circle in strictly increasing
/// angular order, no folded face, energy never rising on an accepted step, Wolfe
/// conditions on every step the line search accepted as such, sufficient decrease on the
/// steps the guard cut.
fn check_valid_run(mesh: &TriMesh, problem: &DiskProblem<'_>, out: &DiskMap, opts: &CcemOptions) {
    let boundary = &problem.partition().boundary;
    let mut prev: Option<f64> = None;
    let mut turned = 0.0;
    for &v in boundary.iter().chain(boundary.first()) {
        let z = out.map[v as usize];
        assert!(
            (z.norm() - 1.0).abs() < 1e-12,
            "vertex {v} off the circle: {}",
            z.norm()
        );
        let a = z.arg();
        if let Some(p) = prev {
            let step = (a - p).rem_euclid(std::f64::consts::TAU);
            assert!(
                step > 0.0 && step < std::f64::consts::PI,
                "boundary out of order at {v}"
            );
            turned += step;
        }
        prev = Some(a);
    }
    assert!(
        (turned - std::f64::consts::TAU).abs() < 1e-9,
        "boundary winds {turned}"
    );
    assert_eq!(flipped(mesh, &out.map), 0, "folded faces");
    let r = &out.report;
    let ls = &r.ccem.as_ref().expect("line-search report").line_search;
    // one record per accepted step; the other iterations are the states the notes count
    // (Möbius re-alignments, projections onto a raised floor)
    let raises = r
        .notes
        .iter()
        .filter(|n| n.contains("floor raised to"))
        .count();
    let realignments: usize = r
        .notes
        .iter()
        .filter(|n| n.contains("Möbius re-alignments"))
        .map(|n| {
            n.split(' ')
                .next()
                .and_then(|w| w.parse::<usize>().ok())
                .expect("a count first")
        })
        .sum();
    assert_eq!(ls.steps.len() + raises + realignments, r.iterations);
    // the report is consistent: a history entry per iteration and the start, the
    // returned iterate among them and the least from `best_from` on
    assert_eq!(r.energy_history.len(), r.iterations + 1);
    assert!(r.best_from <= r.best_iteration && r.best_iteration <= r.iterations);
    let least = r.energy_history[r.best_from..]
        .iter()
        .copied()
        .fold(f64::INFINITY, f64::min);
    assert_eq!(r.energy_history[r.best_iteration], least, "{r:?}");
    assert_eq!(r.best_from > 0, raises > 0, "best_from {}", r.best_from);
    for (k, s) in ls.steps.iter().enumerate() {
        assert!(
            s.energy_after <= s.energy_before,
            "step {k} raised the energy: {s:?}"
        );
        assert!(
            s.slope_before < 0.0,
            "step {k} not along a descent direction: {s:?}"
        );
        match s.kind {
            "wolfe" => {
                assert!(
                    s.energy_after <= s.energy_before + opts.gamma1 * s.alpha * s.slope_before,
                    "step {k}: sufficient decrease (Eq. 4.7) fails: {s:?}"
                );
                assert!(
                    s.slope_after >= opts.gamma2 * s.slope_before,
                    "step {k}: curvature condition (Eq. 4.9) fails: {s:?}"
                );
                assert!(s.alpha <= s.alpha_max, "step {k} passed the guard: {s:?}");
            }
            "guard" | "decrease" => assert!(
                s.energy_after <= s.energy_before + opts.gamma1 * s.alpha * s.slope_before,
                "step {k}: sufficient decrease fails: {s:?}"
            ),
            "projected" => {}
            other => panic!("unknown step kind {other}"),
        }
    }
    // the energy history of a run without a raised floor never rises
    if r.ccem
        .as_ref()
        .is_some_and(|c| c.boundary.gap_floor <= opts.min_gap)
    {
        for w in r.energy_history.windows(2) {
            assert!(w[1] <= w[0], "energy rose: {} → {}", w[0], w[1]);
        }
    }
    // θ-form energy of the last iterate = energy of the map returned
    let last = r.energy_history[r.best_iteration];
    let full = problem.conformal_energy(&out.map);
    assert!((last - full).abs() <= 1e-9 * full.abs(), "{last} vs {full}");
    assert_eq!(gradients(r).len(), r.energy_history.len());
}

/// The gradient norms of a CCEM report (empty for another method's).
fn gradients(r: &SolverReport) -> &[f64] {
    r.ccem.as_ref().map_or(&[], |c| &c.gradient_norm_history)
}

fn gradient_drop(r: &SolverReport) -> f64 {
    let g = gradients(r);
    g[g.len() - 1] / g[0]
}

fn run(mesh: &TriMesh, opts: &CcemOptions) -> (f64, f64, DiskMap) {
    let mut problem = DiskProblem::new(mesh).expect("disk");
    let c = cem(&mut problem, &CemOptions::DEFAULT).expect("cem");
    let out = ccem(&mut problem, opts).expect("ccem");
    check_valid_run(mesh, &problem, &out, opts);
    let e_cem = mesh_energy(mesh, &problem, &c.map);
    let e = mesh_energy(mesh, &problem, &out.map);
    (e_cem, e, out)
}

#[test]
fn woody_both_variants() {
    let mesh = fixture("woody.obj");
    for variant in [CcemVariant::QuasiNewton, CcemVariant::Gradient] {
        let opts = CcemOptions::DEFAULT
            .with_variant(variant)
            .with_record_steps(true)
            .with_max_iter(300);
        let (e_cem, e, out) = run(&mesh, &opts);
        // best other tool 0.0670; CEM 0.0691
        assert!(
            e <= 0.0670 && e <= e_cem,
            "{variant:?}: E_C {e} (CEM {e_cem})"
        );
        // steepest descent is slow on this ill-conditioned problem; BFGS is not
        let fell = if variant == CcemVariant::Gradient {
            0.2
        } else {
            1e-3
        };
        assert!(
            gradient_drop(&out.report) < fell,
            "{variant:?}: gradient barely fell"
        );
        let ls = out.report.ccem.expect("report").line_search;
        assert!(
            ls.wolfe_steps * 4 >= out.report.iterations * 3,
            "{variant:?}: {ls:?}"
        );
    }
}

#[test]
fn quasi_newton_converges_on_woody() {
    let mesh = fixture("woody.obj");
    let opts = CcemOptions::DEFAULT.with_record_steps(true);
    let (_, e, out) = run(&mesh, &opts);
    assert!(out.report.converged, "{:?}", out.report.notes);
    assert!(out.report.iterations < 200);
    assert!(gradient_drop(&out.report) < 1e-3);
    assert!((e - 0.061_516).abs() < 1e-5, "{e}");
    assert_eq!(out.report.method, "ccem-qn");
}

#[test]
fn spothead_beats_cem_and_other_tools() {
    let mesh = fixture("spothead.obj");
    let opts = CcemOptions::DEFAULT.with_record_steps(true);
    let (e_cem, e, out) = run(&mesh, &opts);
    // best other tool 0.0130
    assert!(e <= 0.0130 && e <= e_cem, "E_C {e} (CEM {e_cem})");
    assert!(out.report.converged);
    assert!(gradient_drop(&out.report) < 1e-2);
}

#[test]
fn alligator_guard_keeps_a_valid_map() {
    let mesh = fixture("alligator.obj");
    let opts = CcemOptions::DEFAULT.with_record_steps(true);
    let (e_cem, e, out) = run(&mesh, &opts);
    // best other tool 0.0187, CEM 0.01853: the legs and the tail crowd below 1e-13 rad
    assert!(e <= 0.0187 && e <= e_cem, "E_C {e} (CEM {e_cem})");
    let b = out.report.ccem.expect("boundary report").boundary;
    assert!(
        b.gaps_at_floor > 0,
        "the alligator's limbs crowd the boundary"
    );
    // held gaps sit at the floor up to the rounding of the angles (~1e-15)
    assert!(b.min_gap >= 0.5 * b.gap_floor, "{b:?}");
    assert!(out
        .report
        .notes
        .iter()
        .any(|n| n.contains("held at the floor")));
}

#[test]
fn repaired_start_is_preconditioned_and_restarts_confirm_the_stop() {
    // Angenent's boundary on the alligator steps backwards at the crowded limbs, so the
    // start is repaired; the Hessian at that start still preconditions BFGS, and a
    // tolerance stop with a stale model restarts it once before stopping
    let mesh = fixture("alligator.obj");
    let mut problem = DiskProblem::new(&mesh).expect("disk");
    let opts = CcemOptions::DEFAULT.with_start(CcemStart::Angenent);
    let out = ccem(&mut problem, &opts).expect("ccem");
    let r = &out.report;
    let b = &r.ccem.as_ref().expect("boundary report").boundary;
    assert!(b.start_repaired_gaps > 0, "{b:?}");
    assert!(
        r.notes
            .iter()
            .any(|n| n.contains("preconditioned by the exact Hessian")),
        "{:?}",
        r.notes
    );
    let ls = &r.ccem.as_ref().expect("line search report").line_search;
    assert!(ls.qn_restarts >= 1, "{ls:?}");
    assert!(r.converged);
    // 151 iterations without the preconditioner, 49 with it, to the same E_C
    assert!(r.iterations <= 80, "{} iterations", r.iterations);
    let e = *r.energy_history.last().expect("history");
    assert!(e <= 1.0738351841e-2 * (1.0 + 1e-9), "E_C {e}");
}

#[test]
fn dense_implicit_and_starts_reach_the_same_minimum() {
    let mesh = fixture("woody.obj");
    let mut problem = DiskProblem::new(&mesh).expect("disk");
    let base = CcemOptions::DEFAULT.with_tol(1e-12);
    let mut energies = Vec::new();
    for opts in [
        base.with_schur(SchurMode::Dense),
        base.with_schur(SchurMode::Implicit),
        base.with_start(CcemStart::ArcLength),
    ] {
        let out = ccem(&mut problem, &opts).expect("ccem");
        energies.push(problem.conformal_energy(&out.map));
        let schur = out.report.ccem.expect("schur report").schur;
        match opts.schur {
            SchurMode::Dense => assert_eq!(schur.mode, "dense"),
            SchurMode::Implicit => assert_eq!(schur.mode, "implicit"),
            _ => {}
        }
    }
    for e in &energies[1..] {
        assert!((e - energies[0]).abs() < 1e-8 * energies[0], "{energies:?}");
    }
}

/// A bumpy height field over the unit square (the shape of the generated benchmark meshes):
/// its four corners crowd the conformal map's boundary, and the discrete energy is nearly
/// flat along the disk's Möbius automorphisms.
fn bumpy_square(n: usize) -> TriMesh {
    let grid = conformap_testkit::square_grid(n, n);
    let pos = grid
        .positions()
        .iter()
        .map(|p| {
            let (x, y) = (p[0], p[1]);
            let z = 0.05 * (7.0 * x).sin() * (5.0 * y).cos() + 0.03 * (11.0 * (x + y)).sin();
            [x, y, z]
        })
        .collect();
    TriMesh::try_new(pos, grid.faces().to_vec()).expect("mesh")
}

/// The harmonic-measure start, Möbius-aligned (the default), reaches the minimum that
/// Angenent's start reaches, in a fraction of the iterations, on the dense and the
/// implicit Schur complement alike; the alignment lowers the energy and says so.
#[test]
fn harmonic_measure_start_reaches_angenents_minimum_in_fewer_iterations() {
    let mesh = bumpy_square(80);
    let mut problem = DiskProblem::new(&mesh).expect("disk");
    assert_eq!(CcemOptions::DEFAULT.start, CcemStart::HarmonicMeasure);
    let base = CcemOptions::DEFAULT.with_record_steps(true);
    let hm = ccem(&mut problem, &base).expect("ccem");
    let an = ccem(&mut problem, &base.with_start(CcemStart::Angenent)).expect("ccem");
    // without the dense A the fluxes come from a solve of their own: the same aligned
    // start (there is no Hessian preconditioner then, and plain BFGS's tolerance stop
    // comes early, so only the start is compared tightly)
    let implicit = base.with_schur(SchurMode::Implicit).with_tol(1e-12);
    let imp = ccem(&mut problem, &implicit).expect("ccem");
    check_valid_run(&mesh, &problem, &hm, &base);
    let e = |m: &DiskMap| problem.conformal_energy(&m.map);
    let (e_hm, e_an, e_imp) = (e(&hm), e(&an), e(&imp));
    assert!((e_hm - e_an).abs() <= 1e-9 * e_an, "{e_hm} vs {e_an}");
    assert!((e_imp - e_an).abs() <= 1e-7 * e_an, "{e_imp} vs {e_an}");
    let (s_hm, s_imp) = (hm.report.energy_history[0], imp.report.energy_history[0]);
    assert!((s_hm - s_imp).abs() <= 1e-9 * s_hm, "{s_hm} vs {s_imp}");
    let (i_hm, i_an) = (hm.report.iterations, an.report.iterations);
    assert!(3 * i_hm <= i_an, "{i_hm} iterations vs Angenent's {i_an}");
    let note = hm
        .report
        .notes
        .iter()
        .find(|n| n.starts_with("Möbius-aligned"))
        .expect("alignment note");
    assert!(!note.starts_with("Möbius-aligned: 0 rounds"), "{note}");
    assert!(
        hm.report
            .notes
            .iter()
            .any(|n| n.starts_with("started from the harmonic measure")),
        "{:?}",
        hm.report.notes
    );
    // the aligned start is far closer to the minimum than Angenent's map
    let (h0, a0) = (hm.report.energy_history[0], an.report.energy_history[0]);
    assert!(
        h0 - e_an < 0.1 * (a0 - e_an),
        "start {h0} vs Angenent's {a0}, minimum {e_an}"
    );
}

/// The banded Hessian preconditioner (the default from 2000 boundary vertices; forced here
/// on a 320-vertex boundary) reaches the minimum of the whole-Hessian run, says so, and
/// needs a few more iterations, not many.
#[test]
fn banded_hessian_preconditioner_reaches_the_same_minimum() {
    let mesh = bumpy_square(80);
    let mut problem = DiskProblem::new(&mesh).expect("disk");
    let base = CcemOptions::DEFAULT.with_record_steps(true);
    assert!(problem.num_boundary() < base.banded_hessian_min_nb);
    let whole = ccem(&mut problem, &base).expect("ccem");
    let banded_opts = base.with_banded_hessian_min_nb(64);
    let banded = ccem(&mut problem, &banded_opts).expect("ccem");
    check_valid_run(&mesh, &problem, &banded, &banded_opts);
    let note = |m: &DiskMap, what: &str| m.report.notes.iter().any(|n| n.contains(what));
    assert!(
        note(&banded, "the band (half-width"),
        "{:?}",
        banded.report.notes
    );
    assert!(
        note(&whole, "the exact Hessian"),
        "{:?}",
        whole.report.notes
    );
    let (e_w, e_b) = (
        problem.conformal_energy(&whole.map),
        problem.conformal_energy(&banded.map),
    );
    assert!((e_b - e_w).abs() <= 1e-9 * e_w, "{e_b} vs {e_w}");
    // descent steps (the iterations also count the band's Möbius re-alignments)
    let steps = |m: &DiskMap| {
        m.report
            .ccem
            .as_ref()
            .expect("a ccem report")
            .line_search
            .steps
            .len()
    };
    let (i_w, i_b) = (steps(&whole), steps(&banded));
    assert!(i_b <= 4 * i_w.max(2), "{i_b} banded steps vs {i_w}");
}

/// A planar regular hexagon with a centre vertex: the identity (scaled) is conformal, so
/// the minimum of `E_C` is 0 and CCEM must find it from any start.
#[test]
fn planar_hexagon_reaches_zero_energy() {
    let mut pos = vec![[0.0, 0.0, 0.0]];
    for k in 0..6 {
        let t = k as f64 * std::f64::consts::PI / 3.0 + 0.2 * (k % 2) as f64;
        pos.push([t.cos(), t.sin(), 0.0]);
    }
    let faces = (0..6u32).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
    let mesh = TriMesh::try_new(pos, faces).expect("valid");
    for method in [DiskMethod::CcemQn, DiskMethod::Ccem] {
        let out = compute_disk_map(&mesh, method, &DiskOptions::DEFAULT).expect("map");
        let e = out.report.energy_history[out.report.best_iteration];
        assert!(e.abs() < 1e-10, "{method}: {e}");
    }
}

#[test]
fn methods_by_name() {
    for m in DiskMethod::ALL {
        assert_eq!(m.name().parse::<DiskMethod>().expect("parses"), m);
    }
    assert_eq!(DiskMethod::default(), DiskMethod::CcemQn);
    assert!(matches!(
        "lscm".parse::<DiskMethod>(),
        Err(DiskError::InvalidOption { name: "method", .. })
    ));
    let mesh = fixture("woody.obj");
    let capped = DiskOptions::DEFAULT.with_max_iter(Some(3));
    let out = compute_disk_map(&mesh, DiskMethod::Ccem, &capped).expect("map");
    assert_eq!(
        (out.report.method.as_str(), out.report.iterations),
        ("ccem", 3)
    );
    assert!(!out.report.converged);
    let bad = DiskOptions::DEFAULT.with_tol(Some(f64::NAN));
    assert!(matches!(
        compute_disk_map(&mesh, DiskMethod::Cem, &bad),
        Err(DiskError::InvalidOption { name: "tol", .. })
    ));
}

#[test]
fn options_are_validated() {
    let mesh = fixture("woody.obj");
    let mut problem = DiskProblem::new(&mesh).expect("disk");
    for (opts, name) in [
        (CcemOptions::DEFAULT.with_wolfe(0.9, 0.1), "gamma1/gamma2"),
        (CcemOptions::DEFAULT.with_rho(0.0), "rho"),
        (CcemOptions::DEFAULT.with_min_gap(-1.0), "min_gap"),
        (CcemOptions::DEFAULT.with_tol(f64::INFINITY), "tol"),
        (
            CcemOptions::DEFAULT.with_max_line_evals(0),
            "max_line_evals",
        ),
    ] {
        match ccem(&mut problem, &opts) {
            Err(DiskError::InvalidOption { name: n, .. }) => assert_eq!(n, name),
            other => panic!("{name}: {other:?}"),
        }
    }
}

#[test]
fn report_serializes_the_new_fields() {
    let mesh = fixture("woody.obj");
    let out = compute_disk_map(&mesh, DiskMethod::CcemQn, &DiskOptions::DEFAULT).expect("map");
    let r = &out.report;
    let ls = &r.ccem.as_ref().expect("line search").line_search;
    assert!(ls.evaluations >= r.iterations);
    assert!(ls.steps.is_empty(), "steps are recorded only on request");
    let schur = &r.ccem.as_ref().expect("schur").schur;
    assert!(schur.products >= ls.evaluations);
    assert!(r
        .ccem
        .as_ref()
        .is_some_and(|c| c.boundary.flipped_faces == 0));
    // CEM's report leaves the CCEM fields out
    let c = compute_disk_map(&mesh, DiskMethod::Cem, &DiskOptions::DEFAULT).expect("map");
    assert!(c.report.ccem.is_none());
}

/// Class-a targets on the larger shared meshes (release mode: `--ignored`).
#[test]
#[ignore = "large meshes from ../shared/meshes; run in release"]
fn class_a_targets_on_shared_meshes() {
    let targets = [
        ("camelhead.obj", 0.0457),
        ("human_face.obj", 0.00324),
        ("chinese_lion.obj", 0.0139),
        ("hand.obj", 0.0110),
        ("igea_open.obj", 0.0322),
    ];
    for (name, target) in targets {
        let Some(mesh) = read_shared_mesh_or_skip(name, "class_a_targets_on_shared_meshes") else {
            continue;
        };
        let opts = CcemOptions::DEFAULT.with_record_steps(true);
        let (e_cem, e, _) = run(&mesh, &opts);
        eprintln!("{name}: CCEM-QN E_C {e:.6e} (CEM {e_cem:.6e}, target {target})");
        assert!(
            e <= target && e <= e_cem,
            "{name}: {e} (CEM {e_cem}, target {target})"
        );
    }
}

/// maze.obj: 3,064 boundary vertices along long corridors. The conformal map crowds almost
/// all of them below what f64 resolves; CCEM must return a valid map (raising the floor:
/// twice, to 1e-7 rad) and a consistent report: its iterations count the projections
/// onto the raised floors (the report once said `best_iteration` 84 with `iterations` 82),
/// and the returned energy is the least since the last raise (`best_from`), the lower
/// ones before it being of maps that fold.
#[test]
fn maze_never_folds_and_reports_its_raised_floors() {
    let mesh = fixture("maze.obj");
    let mut problem = DiskProblem::new(&mesh).expect("disk");
    let opts = CcemOptions::DEFAULT.with_record_steps(true);
    let out = ccem(&mut problem, &opts).expect("maze maps");
    check_valid_run(&mesh, &problem, &out, &opts);
    let r = &out.report;
    assert!(r.best_from > 0, "the floor was raised: {:?}", r.notes);
    let floor = r.ccem.as_ref().expect("a ccem report").boundary.gap_floor;
    assert!(floor > opts.min_gap, "floor {floor}");
}
