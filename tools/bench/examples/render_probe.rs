//! Probe (not a test): the cost of a picture. Reads a mesh, computes its disk map (CCEM-QN)
//! once (cached beside the mesh in the temp directory, so that repeated processes measure
//! rendering only), then renders the surface view (checkerboard) and the map view (angle
//! distortion) RUNS times each at SIZE × SIZE (SUPERSAMPLE² samples per pixel, default
//! 3²), printing every run's wall time, the user CPU time of the process during the run,
//! the PNG encoding time and size, and the medians.
//!
//! `cargo run --release -p conformap-bench --example render_probe -- MESH.obj [SIZE] [RUNS] [SUPERSAMPLE] [VIEW]`
//! (VIEW: `surface`, `map` or `both`, the default). Before/after comparisons run two
//! builds of this probe alternately, one run per process (`RUNS` = 1), so that both see the
//! same machine load.
use std::path::{Path, PathBuf};
use std::time::Instant;

use conformap_disk::{compute_disk_map, DiskMethod, DiskOptions};
use conformap_render::{render, ColorBy, MapCoords, RenderOptions, UvValues, View};
use num_complex::Complex64;

/// The median (upper of the two middle values); NaN for none.
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v.get(v.len() / 2).copied().unwrap_or(f64::NAN)
}

/// User CPU time of this process so far, in ms (Linux `/proc/self/stat` field 14, in clock
/// ticks of 10 ms); 0 elsewhere.
fn user_cpu_ms() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // the command name (field 2) may hold spaces: count fields after its closing ')'
    let after = stat.rsplit(')').next().unwrap_or("");
    after
        .split_whitespace()
        .nth(11)
        .and_then(|t| t.parse::<f64>().ok())
        .map_or(0.0, |ticks| ticks * 10.0)
}

/// The disk map of `mesh` read from `path` (one `re im` pair of f64 per vertex, native
/// endian) when it was cached there for this vertex count, else computed and cached.
fn disk_map(
    mesh: &conformap_mesh::TriMesh,
    path: &Path,
) -> Result<Vec<Complex64>, Box<dyn std::error::Error>> {
    if let Ok(bytes) = std::fs::read(path) {
        if bytes.len() == 16 * mesh.num_vertices() {
            let f = |c: &[u8]| f64::from_ne_bytes(c.try_into().unwrap_or([0; 8]));
            return Ok(bytes
                .chunks_exact(16)
                .map(|c| Complex64::new(f(&c[..8]), f(&c[8..])))
                .collect());
        }
    }
    let t = Instant::now();
    let map = compute_disk_map(mesh, DiskMethod::CcemQn, &DiskOptions::DEFAULT)?.map;
    println!("disk map {:.0} ms", t.elapsed().as_secs_f64() * 1e3);
    let mut bytes = Vec::with_capacity(16 * map.len());
    for z in &map {
        bytes.extend_from_slice(&z.re.to_ne_bytes());
        bytes.extend_from_slice(&z.im.to_ne_bytes());
    }
    std::fs::write(path, bytes)?;
    Ok(map)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let path = args.next().ok_or("MESH.obj")?;
    let size: u32 = args.next().map_or(Ok(1024), |s| s.parse())?;
    let runs: usize = args.next().map_or(Ok(5), |r| r.parse())?;
    let supersample: u32 = args.next().map_or(Ok(3), |r| r.parse())?;
    let which = args.next().unwrap_or_else(|| "both".to_string());
    let mesh = conformap_io::read_mesh(Path::new(&path))?.mesh;
    let stem = Path::new(&path)
        .file_stem()
        .map_or("mesh".into(), |s| s.to_string_lossy());
    let cache: PathBuf = std::env::temp_dir().join(format!("render-probe-{stem}.uv"));
    let map = disk_map(&mesh, &cache)?;
    println!(
        "{path}: {} vertices, {} faces; {} threads",
        mesh.num_vertices(),
        mesh.num_faces(),
        rayon::current_num_threads()
    );
    let coords = MapCoords::Planar(UvValues::PerVertex(&map));
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
        let wanted = match which.as_str() {
            "surface" => options.view == View::Surface,
            "map" => options.view == View::Map,
            _ => true,
        };
        if !wanted {
            continue;
        }
        let (mut times, mut cpus) = (Vec::new(), Vec::new());
        for run in 0..runs {
            let (t, c) = (Instant::now(), user_cpu_ms());
            let image = render(&mesh, &coords, &options)?;
            let ms = t.elapsed().as_secs_f64() * 1e3;
            let cpu = user_cpu_ms() - c;
            let (t, c) = (Instant::now(), user_cpu_ms());
            let png = image.to_png()?;
            let png_ms = t.elapsed().as_secs_f64() * 1e3;
            let png_cpu = user_cpu_ms() - c;
            println!(
                "  {name} run {run}: render {ms:.0} ms (user CPU {cpu:.0} ms), PNG encode {png_ms:.0} ms (user CPU {png_cpu:.0} ms, {} KiB)",
                png.len() / 1024
            );
            times.push(ms);
            cpus.push(cpu);
        }
        println!(
            "  {name}: median {:.0} ms, user CPU {:.0} ms, of {runs}",
            median(times),
            median(cpus)
        );
    }
    Ok(())
}
