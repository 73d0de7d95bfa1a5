//! The disk with circular holes (CEM Algorithm 2, then the circle-domain polish) on the
//! multiply-connected meshes of `../shared/meshes/` (class b): one table row per mesh.
//!
//! ```text
//! cargo run --release -p conformap-tests --example koebe_table [-- NAME.obj ...] [--history]
//!     [--no-polish] [--tol=T]
//! ```
//! Columns: loops, Koebe sweeps, polish iterations, worst circle residual
//! `max ||f − c| − r| / r` over every loop, `E_C` (CEM Eq. 7, outer disk minus the holes),
//! mean angle distortion, flipped faces, the modulus `ln(1/r)` for two loops, time.

use std::time::Instant;

use conformap_disk::{koebe, KoebeOptions};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_testkit::{read_plain_obj, real_mesh_or_skip};

const CLASS_B: &[&str] = &[
    "halftunnel.obj",
    "peaks_7holes.obj",
    "alex_3holes.obj",
    "sophie_annulus.obj",
];

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let history = args.iter().any(|a| a == "--history");
    let polish = !args.iter().any(|a| a == "--no-polish");
    let mut options = KoebeOptions::DEFAULT.with_polish(polish);
    if !polish {
        options = options.with_tol(KoebeOptions::TOL_WITHOUT_POLISH);
    }
    if let Some(t) = args.iter().find_map(|a| a.strip_prefix("--tol=")) {
        match t.parse() {
            Ok(tol) => options = options.with_tol(tol),
            Err(e) => {
                eprintln!("--tol={t}: {e}");
                return;
            }
        }
    }
    let given: Vec<&str> = args
        .iter()
        .filter(|a| !a.starts_with("--"))
        .map(String::as_str)
        .collect();
    let names = if given.is_empty() {
        CLASS_B.to_vec()
    } else {
        given
    };
    println!(
        "| mesh | V | loops | Koebe sweeps | polish its | worst circle residual | E_C | \
         mean angle dist. (°) | flips | modulus | time (s) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|");
    for name in names {
        let Some(path) = real_mesh_or_skip(name, "koebe_table") else {
            continue;
        };
        let mesh = match read_plain_obj(&path) {
            Ok(m) => m,
            Err(e) => {
                println!("| {name} | cannot read: {e} |");
                continue;
            }
        };
        let t = Instant::now();
        let out = match koebe(&mesh, &options) {
            Ok(o) => o,
            Err(e) => {
                println!("| {name} | failed: {e} |");
                continue;
            }
        };
        let secs = t.elapsed().as_secs_f64();
        let metrics_options = MetricsOptions::DEFAULT.with_outer_loop(out.report.outer_loop);
        let m = match planar_map_metrics(&mesh, &out.map, &metrics_options) {
            Ok(m) => m,
            Err(e) => {
                println!("| {name} | metrics failed: {e} |");
                continue;
            }
        };
        let r = &out.report;
        println!(
            "| {name} | {} | {} | {} | {} | {:.1e} | {:.4e} | {:.3} | {} | {} | {secs:.2} |",
            mesh.num_vertices(),
            mesh.boundary_loops().len(),
            r.sweeps,
            r.polish
                .as_ref()
                .map_or("-".to_string(), |p| p.iterations.to_string()),
            m.circle_residual_max,
            m.conformal_energy,
            m.angle_distortion_deg.mean,
            m.flipped_faces,
            out.modulus.map_or("-".to_string(), |x| format!("{x:.6}")),
        );
        if history {
            let h: Vec<String> = r
                .residual_history
                .iter()
                .map(|x| format!("{x:.1e}"))
                .collect();
            println!(
                "  residual after the first map and each sweep: {}",
                h.join(" ")
            );
            if let Some(p) = &r.polish {
                let e: Vec<String> = p
                    .energy_history
                    .iter()
                    .map(|x| format!("{x:.4e}"))
                    .collect();
                println!(
                    "  polish E_C: {} (held vertices {})",
                    e.join(" "),
                    p.held_vertices
                );
            }
            println!("  timings (ms): {:?}", r.timings_ms);
            for c in &out.circles {
                println!(
                    "  loop {} ({} vertices{}): centre ({:.6}, {:.6}), radius {:.6}, residual {:.1e}",
                    c.loop_index,
                    c.vertices,
                    if c.outer { ", outer" } else { "" },
                    c.center[0],
                    c.center[1],
                    c.radius,
                    c.residual_max
                );
            }
            for note in &r.notes {
                println!("  note: {note}");
            }
        }
    }
}
