//! Atlases of the closed meshes of `../shared/meshes` (or of the meshes given) with 8 cones
//! on closed components: cut through the cones and the handles, flattened with the cone
//! metric's boundary scale, split where a chart overlaps itself, packed into the unit
//! square; against boundary first flattening's command-line tool on the same machine.
//!
//! ```sh
//! cargo run --release -p conformap-atlas --example atlas_table [-- COUNT MESH...]
//! ```

use std::time::Instant;

use conformap_atlas::{build_atlas, AtlasOptions};

/// BFF at 8 cones (hand: 0): (mesh, area spread, mean angle distortion °, packing, seconds).
const BFF: [(&str, f64, f64, f64, f64); 8] = [
    ("spot", 1.01, 2.15, 0.65, 0.07),
    ("armadillo", 2.51, 1.47, 0.40, 1.87),
    ("brain", 0.69, 1.21, 0.51, 1.91),
    ("david_head", 0.57, 0.84, 0.41, 0.45),
    ("kitten_53k", 0.41, 0.30, 0.33, 2.53),
    ("eight", 0.27, 0.66, 0.21, 0.10),
    ("fertility", 0.40, 1.34, 0.26, 0.19),
    ("hand", 5.16, 3.19, 0.69, 0.83),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count: usize = args.first().map(|s| s.parse()).transpose()?.unwrap_or(8);
    let shared = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/meshes");
    let meshes: Vec<String> = if args.len() > 1 {
        args[1..].to_vec()
    } else {
        BFF.iter()
            .map(|b| format!("{shared}/{}.obj", b.0))
            .collect()
    };
    println!("| mesh | genus | charts | spread (BFF) | angle ° (BFF) | flipped | overlap | seam log ratio max | packing (BFF) | ms (BFF s) | cpu ms |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for path in meshes {
        let mesh = conformap_io::read_mesh(&path)?.mesh;
        let name = std::path::Path::new(&path)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let t = Instant::now();
        let c0 = cpu_seconds();
        let options = AtlasOptions::default();
        let options = if count == 8 {
            options
        } else {
            options.with_cones(count)
        };
        let atlas = build_atlas(mesh.positions(), mesh.faces(), &options)?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let cpu_ms = (cpu_seconds() - c0) * 1e3;
        let r = &atlas.report;
        let bff = BFF.iter().find(|b| b.0 == name);
        let f = |x: Option<f64>| x.map_or("–".to_string(), |v| format!("{v:.2}"));
        println!(
            "| {name} | {} | {} | {:.3} ({}) | {:.2} ({}) | {} | {:.1e} | {:.1e} | {:.2} ({}) | {ms:.0} ({}) | {cpu_ms:.0} |",
            mesh.genus().unwrap_or(-1),
            r.charts,
            r.area_spread,
            f(bff.map(|b| b.1)),
            r.angle_mean_deg,
            f(bff.map(|b| b.2)),
            r.flipped,
            r.overlap.fraction,
            r.seam_log_ratio_max,
            r.packing_efficiency,
            f(bff.map(|b| b.3)),
            f(bff.map(|b| b.4)),
        );
    }
    Ok(())
}

/// CPU time of this process so far (user + system), seconds, from `/proc/self/stat` (0 where
/// there is none): on a loaded machine the wall clock mostly measures the others.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // fields after the command name (which may hold spaces) start at its closing ')'
    let rest = stat.rsplit_once(')').map_or("", |r| r.1);
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .filter_map(|x| x.parse().ok())
        .collect();
    f.iter().sum::<f64>() / 100.0
}
