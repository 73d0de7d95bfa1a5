//! The topological-optimization table (issue 23) on the shared meshes
//! (`../shared/meshes/`). Run in release:
//!
//! ```text
//! cargo run --release -p conformap-global --example topology_table -- [MESH.obj ...] [--slit-length F] [--max-slits N] [--yardstick-only]
//! ```
//! `--yardstick-only`: print the yardstick alone (to interleave with runs of the CLI).
//! Per mesh: every step (slits added and their centres, genus of the double covering,
//! uniformity energy and its ratio to the starting map's, log-area spread, folds, time as a
//! multiple of the step's own factorization and of the yardstick of issue 23: one
//! factorization of the input's cotangent Laplacian, one vertex pinned, median of 5).

use conformap_global::{topology_opt, TopologyOptOptions};

type Res = Result<(), Box<dyn std::error::Error>>;

fn main() -> Res {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut options = TopologyOptOptions::DEFAULT;
    let mut take = |flag: &str| -> Option<String> {
        let i = args.iter().position(|a| a == flag)?;
        let v = args.get(i + 1).cloned();
        args.drain(i..(i + 2).min(args.len()));
        v
    };
    if let Some(v) = take("--slit-length") {
        options = options.with_slit_length(v.parse()?);
    }
    if let Some(v) = take("--max-slits") {
        options = options.with_max_slits(v.parse()?);
    }
    if let Some(v) = take("--patience") {
        options = options.with_patience(v.parse()?);
    }
    let mut search = options.global.search;
    if let Some(v) = take("--starts") {
        search = search.with_starts(v.parse()?);
    }
    if let Some(v) = take("--basis-starts") {
        search = search.with_basis_starts(v.parse().ok());
    }
    options = options
        .clone()
        .with_global(options.global.clone().with_search(search));
    let yardstick_only = match args.iter().position(|a| a == "--yardstick-only") {
        Some(i) => {
            args.remove(i);
            true
        }
        None => false,
    };
    let names = if args.is_empty() {
        vec!["spot.obj".to_owned(), "armadillo.obj".to_owned()]
    } else {
        args
    };
    for name in names {
        let Some(path) = conformap_testkit::shared_mesh_path(&name) else {
            println!("{name}: not found");
            continue;
        };
        let mesh = conformap_testkit::read_plain_obj(&path)?;
        let yardstick = input_factor_ms(&mesh)?;
        if yardstick_only {
            println!("{name}: one factorization of the input's Laplacian: {yardstick:.1} ms (median of 5)");
            continue;
        }
        let r = topology_opt(&mesh, &options)?;
        println!(
            "{name}: V={} F={} slit length {:.4} ({} of diag); best step {}; stop: {}; total {:.0} ms",
            mesh.num_vertices(),
            mesh.num_faces(),
            r.slit_length,
            options.slit_length,
            r.best_step,
            r.stop,
            r.total_ms
        );
        println!("one factorization of the input's Laplacian: {yardstick:.1} ms (median of 5)");
        println!("step slits +added genus energy      ratio  logA_sd folds(z/out) time_ms factor_ms x_factor x_input objective_ms newton coarse hessians model  centres");
        for (i, s) in r.steps.iter().enumerate() {
            let centres: Vec<String> = s
                .added
                .iter()
                .map(|a| format!("{}({})", a.centre, a.vertices.len() - 1))
                .collect();
            println!(
                "{i:>4} {:>5} {:>6} {:>5} {:.4e} {:>6.3} {:>7.3} {:>4}/{:<4} {:>8.0} {:>8.0} {:>7.1} {:>7.1} {:>8.0} {:>5} {:>5} {:>5} {}  {}",
                s.slits,
                s.added.len(),
                s.surface_genus,
                s.energy,
                s.ratio_to_start,
                s.area_distortion_log.sd,
                s.folds_at_zeros,
                s.folds_outside_zeros,
                s.time_ms,
                s.factor_ms,
                s.time_ms / s.factor_ms.max(1e-9),
                s.time_ms / yardstick,
                s.objective_ms,
                s.newton_iterations,
                s.coarse_iterations,
                s.hessians,
                s.energy_model,
                centres.join(" ")
            );
            if s.surface_genus > 0 {
                println!("       stages (ms): {:?}", s.stages_ms);
            }
        }
    }
    Ok(())
}

/// Milliseconds of one factorization (symbolic and numeric) of the input's cotangent
/// Laplacian with vertex 0 pinned: the median of 5.
fn input_factor_ms(mesh: &conformap_mesh::TriMesh) -> Result<f64, Box<dyn std::error::Error>> {
    use conformap_operators::{cotan_laplacian, Cholesky, LaplacianBlocks, Partition};
    let l = cotan_laplacian(mesh);
    let part = Partition::new(mesh.num_vertices(), &[0]);
    let blocks = LaplacianBlocks::new(&l, &part);
    let mut times = Vec::new();
    for _ in 0..5 {
        let t = std::time::Instant::now();
        let chol = Cholesky::factor_with(
            &blocks.ii,
            &conformap_global::GlobalMapOptions::DEFAULT.cholesky,
        )?;
        times.push(t.elapsed().as_secs_f64() * 1e3);
        drop(chol);
    }
    times.sort_by(f64::total_cmp);
    Ok(times[2])
}
