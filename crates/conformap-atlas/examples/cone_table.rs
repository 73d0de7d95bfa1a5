//! The area spread of automatically placed cones on the closed meshes of `../shared/meshes`
//! (or the meshes given), against boundary first flattening's 8 cones measured with its
//! command-line tool on the same machine.
//!
//! ```sh
//! cargo run --release -p conformap-atlas --example cone_table [-- COUNT MESH...]
//! ```

use std::time::Instant;

use conformap_atlas::{place_cones, ConeMetric, ConeOptions};

/// BFF's area spread at its default 8 cones (the atlas issue's table).
const BFF: [(&str, f64); 4] = [
    ("spot", 1.01),
    ("armadillo", 2.51),
    ("brain", 0.69),
    ("david_head", 0.57),
];

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count: usize = args.first().map(|s| s.parse()).transpose()?.unwrap_or(8);
    let shared = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/meshes");
    let meshes: Vec<String> = if args.len() > 1 {
        args[1..].to_vec()
    } else {
        BFF.iter()
            .map(|(m, _)| format!("{shared}/{m}.obj"))
            .collect()
    };
    println!("| mesh | faces | cones | greedy spread | spread | moves | BFF 8 cones | ratio | factor ms | place ms |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for path in meshes {
        let loaded = conformap_io::read_mesh(&path)?;
        let mesh = loaded.mesh;
        let name = std::path::Path::new(&path)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let t = Instant::now();
        let metric = ConeMetric::new(&mesh)?;
        let factor_ms = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let set = place_cones(&metric, count, &ConeOptions::default());
        let place_ms = t.elapsed().as_secs_f64() * 1e3;
        let bff = BFF.iter().find(|(m, _)| *m == name).map(|b| b.1);
        println!(
            "| {name} | {} | {} | {:.3} | {:.3} | {} | {} | {} | {factor_ms:.0} | {place_ms:.0} |",
            mesh.num_faces(),
            set.cones.len(),
            set.greedy_spread,
            set.area_spread,
            set.moves,
            bff.map_or("–".into(), |b| format!("{b:.2}")),
            bff.map_or("–".into(), |b| format!("{:.2}", set.area_spread / b)),
        );
        let angles: Vec<String> = set
            .cones
            .iter()
            .map(|c| format!("{}:{:.0}°", c.vertex, c.angle_deg()))
            .collect();
        eprintln!("{name}: {}", angles.join(" "));
    }
    Ok(())
}
