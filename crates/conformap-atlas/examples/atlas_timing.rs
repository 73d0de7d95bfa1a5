//! Where an atlas spends its time, per mesh: the cone metric's factorization, the cone
//! placement (on genus ≥ 1 the chart places its cones in another metric, pinned along the
//! handle loops), the chart (metric, placement, cut, flatten, unfold) and the whole atlas
//! (charts, splits, packing, report). Each stage is timed on its own, so the chart column
//! includes the first two again and the atlas column all of them.
//!
//! ```sh
//! cargo run --release -p conformap-atlas --example atlas_timing -- MESH...
//! ```

use std::time::Instant;

use conformap_atlas::{
    build_atlas, chart_component, place_cones, AtlasOptions, ConeMetric, ConeOptions,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let paths: Vec<String> = std::env::args().skip(1).collect();
    if paths.is_empty() {
        return Err("usage: atlas_timing MESH...\nhint: give one or more mesh files".into());
    }
    println!("| mesh | faces | metric ms | placement ms | chart ms | atlas ms |");
    println!("|---|---:|---:|---:|---:|---:|");
    for path in paths {
        let mesh = conformap_io::read_mesh(&path)?.mesh;
        let ms = |t: Instant| t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let metric = ConeMetric::new(&mesh)?;
        let metric_ms = ms(t);
        let t = Instant::now();
        // 8 cones on a closed mesh (the atlas's default), none on one with boundary
        let count = if mesh.boundary_loops().is_empty() {
            8
        } else {
            0
        };
        let _ = place_cones(&metric, count, &ConeOptions::default());
        let place_ms = ms(t);
        let t = Instant::now();
        let _ = chart_component(&mesh, None, &ConeOptions::default())?;
        let chart_ms = ms(t);
        let t = Instant::now();
        let _ = build_atlas(mesh.positions(), mesh.faces(), &AtlasOptions::default())?;
        let atlas_ms = ms(t);
        println!(
            "| {path} | {} | {metric_ms:.0} | {place_ms:.0} | {chart_ms:.0} | {atlas_ms:.0} |",
            mesh.num_faces()
        );
    }
    Ok(())
}
