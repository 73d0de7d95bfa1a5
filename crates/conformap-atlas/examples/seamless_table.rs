//! Seamless atlases against the default ones on the closed meshes of the atlas issue's table
//! (or the meshes given): area spread, mean angle distortion, flipped faces, texels covered
//! twice at 1024², charts, packing, the seams' largest rotation error from a quarter turn
//! and residual after the quarter-turn rigid map, and the atlas's CPU time (median of
//! `ROUNDS` runs, the two builds interleaved: the machine is shared).
//!
//! ```sh
//! cargo build --release --workspace --examples
//! target/release/examples/seamless_table [MESH...]
//! ```

use std::time::Instant;

use conformap_atlas::{build_atlas, AtlasOptions, AtlasReport};

/// Runs of each build per mesh, interleaved; the median CPU time is reported: 3.
const ROUNDS: usize = 3;

const MESHES: [&str; 7] = [
    "spot",
    "armadillo",
    "brain",
    "david_head",
    "kitten_53k",
    "eight",
    "fertility",
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let shared = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/meshes");
    let meshes: Vec<String> = if args.is_empty() {
        MESHES.iter().map(|m| format!("{shared}/{m}.obj")).collect()
    } else {
        args
    };
    println!("| mesh | genus | build | cones (angles °) | charts | area spread | angle ° | flipped | covered twice | packing | seam rotation error | seam rigid residual | atlas CPU s | wall s |");
    println!("|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for path in meshes {
        let mesh = conformap_io::read_mesh(&path)?.mesh;
        let name = std::path::Path::new(&path)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let mut runs: [Vec<(f64, f64)>; 2] = [Vec::new(), Vec::new()];
        let mut reports: [Option<AtlasReport>; 2] = [None, None];
        for _ in 0..ROUNDS {
            for (k, seamless) in [false, true].into_iter().enumerate() {
                let options = AtlasOptions::default().with_seamless(seamless);
                let (t, c0) = (Instant::now(), cpu_seconds());
                let atlas = build_atlas(mesh.positions(), mesh.faces(), &options)?;
                runs[k].push((cpu_seconds() - c0, t.elapsed().as_secs_f64()));
                reports[k] = Some(atlas.report);
            }
        }
        for (k, label) in ["default", "--seamless"].into_iter().enumerate() {
            let Some(r) = &reports[k] else { continue };
            let mut cpu: Vec<f64> = runs[k].iter().map(|x| x.0).collect();
            let mut wall: Vec<f64> = runs[k].iter().map(|x| x.1).collect();
            cpu.sort_by(f64::total_cmp);
            wall.sort_by(f64::total_cmp);
            let mut angles: Vec<String> = r
                .cone_list
                .iter()
                .map(|c| format!("{:.0}", c.angle_deg))
                .collect();
            angles.sort();
            angles.dedup();
            println!(
                "| {name} | {} | {label} | {} ({}) | {} | {:.3} | {:.2} | {} | {} | {:.2} | {:.1e} | {:.1e} | {:.2} | {:.2} |",
                mesh.genus().unwrap_or(-1),
                r.cones,
                angles.join(", "),
                r.charts,
                r.area_spread,
                r.angle_mean_deg,
                r.flipped,
                r.overlap.covered_twice,
                r.packing_efficiency,
                r.seam_rotation_error_max,
                r.seam_rigid_residual_max,
                cpu[cpu.len() / 2],
                wall[wall.len() / 2],
            );
        }
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
