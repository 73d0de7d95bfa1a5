//! Measurements of the disk methods on real meshes (not a test): CEM, CCEM (Algorithm 4.1)
//! and CCEM-QN (Algorithm 4.2) per mesh, with `E_C` judged by the mesh's own cotangent
//! weights, iterations, line-search counts, the Schur path and per-stage times.
//!
//! `cargo run --release -p conformap-disk --example disk_methods -- [--tol T]
//! [--max-iter N] [--min-gap G] [--rho R] [--qn-memory M] [--schur dense|implicit]
//! [--start arc|angenent|N] [--no-precond] [--only cem|ccem|qn] [--table] [--steps K] [-v] MESH.obj...`
//!
//! Reads plain `v`/`f` OBJ files (the meshes in `../shared/meshes`) with the testkit's reader.
use std::time::Instant;

use conformap_disk::*;
use conformap_testkit::read_plain_obj;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut opts = CcemOptions::DEFAULT;
    let mut only: Option<String> = None;
    let mut verbose = false;
    let mut table = false;
    let mut steps = 0usize;
    let mut files = vec![];
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--tol" => opts = opts.with_tol(args.next().ok_or("tol")?.parse()?),
            "--max-iter" => opts = opts.with_max_iter(args.next().ok_or("n")?.parse()?),
            "--min-gap" => opts = opts.with_min_gap(args.next().ok_or("g")?.parse()?),
            "--rho" => opts = opts.with_rho(args.next().ok_or("r")?.parse()?),
            "--qn-memory" => opts = opts.with_qn_memory(args.next().ok_or("m")?.parse()?),
            "--schur" => {
                opts = opts.with_schur(match args.next().as_deref() {
                    Some("dense") => SchurMode::Dense,
                    Some("implicit") => SchurMode::Implicit,
                    _ => SchurMode::Auto,
                })
            }
            "--start" => {
                let s = args.next().ok_or("start")?;
                opts = opts.with_start(if s == "arc" {
                    CcemStart::ArcLength
                } else if s == "angenent" {
                    CcemStart::Angenent
                } else {
                    CcemStart::Cem(CemOptions::DEFAULT.with_max_iter(s.parse()?))
                });
            }
            "--only" => only = args.next(),
            "--no-precond" => opts = opts.with_hessian_preconditioner(false),
            "-v" => verbose = true,
            "--table" => table = true,
            "--steps" => {
                steps = args.next().ok_or("k")?.parse()?;
                opts = opts.with_record_steps(true);
            }
            _ => files.push(a),
        }
    }
    for name in files {
        let mesh = read_plain_obj(std::path::Path::new(&name))?;
        let short = name.rsplit('/').next().unwrap_or(&name).to_string();
        let t = Instant::now();
        let lmesh = conformap_operators::cotan_laplacian(&mesh);
        let mut p = match DiskProblem::new(&mesh) {
            Ok(p) => p,
            Err(e) => {
                println!("{short}: {e}");
                continue;
            }
        };
        let prep = t.elapsed().as_secs_f64() * 1e3;
        println!(
            "{short}: n={} nb={} nnz(L_II factor)={} assemble+factor {:.0} ms (factor {:.0})",
            mesh.num_vertices(),
            p.num_boundary(),
            p.interior_factor().stats().nnz_factor,
            prep,
            p.factor_ms,
        );
        let runs: Vec<(&str, Option<CcemVariant>)> = vec![
            ("cem", None),
            ("ccem", Some(CcemVariant::Gradient)),
            ("qn", Some(CcemVariant::QuasiNewton)),
        ];
        for (label, variant) in runs {
            if only.as_deref().is_some_and(|o| o != label) {
                continue;
            }
            let t = Instant::now();
            let out = match variant {
                None => cem(&mut p, &CemOptions::DEFAULT),
                Some(v) => ccem(&mut p, &opts.with_variant(v)),
            };
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let out = match out {
                Ok(o) => o,
                Err(e) => {
                    println!("  {label:5} error: {e}");
                    continue;
                }
            };
            let r = &out.report;
            let e_full = p.conformal_energy(&out.map);
            let e_mesh =
                conformap_operators::quadratic_form(&lmesh, &out.map) - p.image_area(&out.map);
            let e_theta = r.energy_history[r.best_iteration];
            let flips = mesh
                .faces()
                .iter()
                .filter(|f| {
                    let (a, b, c) = (
                        out.map[f[0] as usize],
                        out.map[f[1] as usize],
                        out.map[f[2] as usize],
                    );
                    ((b - a).conj() * (c - a)).im <= 0.0
                })
                .count();
            let c = r.ccem.clone().unwrap_or_default();
            let ls = c.line_search.clone();
            if table {
                let (mode, form, prods) = r.ccem.as_ref().map_or(("-".to_string(), 0.0, 0), |c| {
                    (c.schur.mode.clone(), c.schur.form_ms, c.schur.products)
                });
                let st = c.stages_ms.clone();
                println!(
                    "TABLE {short} {label} start_ms {:.0} iter_ms {:.0} finish_ms {:.0} E_mesh {e_mesh:.6e} E_prob {e_full:.6e} it {} conv {} flips {flips} total_ms {:.0} factor_ms {:.0} method_ms {ms:.0} schur {mode} form_ms {form:.0} prods {prods} evals {} held {}",
                    st.start,
                    st.iterations,
                    st.finish,
                    r.iterations,
                    r.converged,
                    prep + ms,
                    p.factor_ms,
                    ls.evaluations,
                    c.boundary.gaps_at_floor
                );
                continue;
            }
            let (schur, form, prods) = r.ccem.as_ref().map_or(("-".to_string(), 0.0, 0), |c| {
                (c.schur.mode.clone(), c.schur.form_ms, c.schur.products)
            });
            let b = c.boundary.clone();
            println!(
                "  {label:5} E_C(mesh) {e_mesh:.6e} E_C {e_full:.6e} (θ-form rel diff {:.1e}) it {:4} conv {} flips {flips} \
                 t {ms:.0} ms (solve {:.0}) | ls evals {} wolfe {} guard {} proj {} dec {} fb {} | schur {schur} form {form:.0} ms prods {prods} | gap {:.1e} held {} repaired {}",
                (e_theta - e_full).abs() / e_full.abs(),
                r.iterations,
                r.converged,
                r.timings_ms.solve,
                ls.evaluations,
                ls.wolfe_steps,
                ls.guard_limited_steps,
                ls.projected_steps,
                ls.decrease_only_steps,
                ls.gradient_fallbacks,
                b.min_gap,
                b.gaps_at_floor,
                b.start_repaired_gaps,
            );
            if !c.gradient_norm_history.is_empty() {
                let g = &c.gradient_norm_history;
                println!(
                    "      |grad| first {:.3e} last {:.3e} min {:.3e}",
                    g[0],
                    g[g.len() - 1],
                    g.iter().cloned().fold(f64::INFINITY, f64::min)
                );
            }
            if steps > 0 {
                for (k, s) in ls.steps.iter().enumerate() {
                    if k % steps == 0 || k + 1 == ls.steps.len() {
                        println!(
                            "      step {k:4} E {:.9e} α {:.3e} αmax {:.3e} slope {:.2e}->{:.2e} evals {} {} |g| {:.2e}",
                            s.energy_after, s.alpha, s.alpha_max, s.slope_before, s.slope_after, s.evaluations, s.kind, c.gradient_norm_history[k + 1]
                        );
                    }
                }
            }
            if verbose {
                for n in &r.notes {
                    println!("      note: {n}");
                }
            }
        }
    }
    Ok(())
}
