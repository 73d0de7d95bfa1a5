//! Probe (not a test): the cost of a picture. Reads a mesh, computes its disk map (CCEM-QN)
//! once, then renders the surface view (checkerboard, default supersampling 3) and the map
//! view (angle distortion) RUNS times each at SIZE × SIZE (SUPERSAMPLE², default 3² samples per pixel), printing every run and the median.
//! `cargo run --release -p conformap-bench --example render_probe -- MESH.obj [SIZE] [RUNS] [SUPERSAMPLE]`
use std::time::Instant;

use conformap_disk::{compute_disk_map, DiskMethod, DiskOptions};
use conformap_render::{render, ColorBy, MapCoords, RenderOptions, UvValues, View};

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().ok_or("MESH.obj")?;
    let size: u32 = args.next().map_or(Ok(1024), |s| s.parse())?;
    let runs: usize = args.next().map_or(Ok(5), |r| r.parse())?;
    let supersample: u32 = args.next().map_or(Ok(3), |r| r.parse())?;
    let mesh = conformap_io::read_mesh(std::path::Path::new(&path))?.mesh;
    let t = Instant::now();
    let map = compute_disk_map(&mesh, DiskMethod::CcemQn, &DiskOptions::DEFAULT)?;
    println!(
        "{path}: {} vertices, {} faces; disk map {:.0} ms; {} threads",
        mesh.num_vertices(),
        mesh.num_faces(),
        t.elapsed().as_secs_f64() * 1e3,
        rayon::current_num_threads()
    );
    let coords = MapCoords::Planar(UvValues::PerVertex(&map.map));
    let base = RenderOptions::DEFAULT
        .with_size(size)
        .with_supersample(supersample);
    let views = [
        ("surface checker", base),
        (
            "map angle",
            base.with_view(View::Map).with_color(ColorBy::Angle),
        ),
    ];
    for (name, options) in views {
        let mut times = Vec::new();
        for run in 0..runs {
            let t = Instant::now();
            let image = render(&mesh, &coords, &options)?;
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let t = Instant::now();
            let png = image.to_png()?;
            let png_ms = t.elapsed().as_secs_f64() * 1e3;
            println!(
                "  {name} run {run}: render {ms:.0} ms, PNG encode {png_ms:.0} ms ({} KiB)",
                png.len() / 1024
            );
            times.push(ms);
        }
        println!("  {name}: median {:.0} ms of {runs}", median(times));
    }
    Ok(())
}
