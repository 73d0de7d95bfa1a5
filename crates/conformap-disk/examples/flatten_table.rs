//! Boundary first flattening with a free boundary on real meshes, beside the disk map:
//! area spread (sd over faces of the log area ratio), mean angle distortion, flipped faces,
//! boundary self-touches and times (median of 3) — a measurement, not a test.
//!
//! `cargo run --release -p conformap-disk --example flatten_table -- [--conjugate] [--rectangle] [--reps N] MESH.obj...`
//!
//! `--conjugate` extends `y` as the conjugate of `x`; `--rectangle` maps onto a rectangle with
//! automatic corners instead of the free boundary; `--height-field N` runs a generated height
//! field of `N × N` cells (`2 N²` faces: `--height-field 708` is 1M faces) instead of meshes.
//!
//! Without meshes it runs every mesh with a boundary in the shared mesh directory
//! (`$CONFORMAP_SHARED_MESHES`, else `/work/shared/meshes`). `flatten` is timed as the whole
//! call (fill, assemble, factor, solve, metrics); `disk` as the default disk map
//! (`compute_disk_map` with CCEM-QN for one loop, `koebe` for several), each from the mesh
//! in memory.
use std::path::PathBuf;
use std::time::Instant;

use conformap_disk::{
    compute_disk_map, flatten, koebe, DiskMethod, DiskOptions, FlattenBoundary, FlattenInterior,
    FlattenOptions, KoebeOptions,
};
use conformap_mesh::{Topology, TriMesh};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_testkit::{grid_faces, read_plain_obj};

const WITH_BOUNDARY: [&str; 10] = [
    "hand",
    "igea_open",
    "human_face",
    "camelhead",
    "chinese_lion",
    "alligator",
    "alex_3holes",
    "peaks_7holes",
    "sophie_annulus",
    "maze",
];

/// A height field over the unit square, `n × n` cells (`2 n²` faces): smooth bumps.
fn height_field(n: usize) -> Result<TriMesh, Box<dyn std::error::Error>> {
    let mut p = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
            let z = 0.15 * (6.0 * x).sin() * (4.0 * y).cos()
                + 0.1 * (-20.0 * ((x - 0.6).powi(2) + (y - 0.3).powi(2))).exp();
            p.push([x, y, z]);
        }
    }
    Ok(TriMesh::try_new(p, grid_faces(n, n))?)
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The disk map and its metrics (what the `disk` process computes besides reading and
/// writing), seconds.
fn disk_seconds(mesh: &TriMesh) -> Result<f64, Box<dyn std::error::Error>> {
    let t = Instant::now();
    let map = match mesh.topology() {
        Topology::Disk => compute_disk_map(mesh, DiskMethod::default(), &DiskOptions::DEFAULT)?.map,
        _ => koebe(mesh, &KoebeOptions::default())?.map,
    };
    planar_map_metrics(mesh, &map, &MetricsOptions::DEFAULT)?;
    Ok(t.elapsed().as_secs_f64())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let conjugate = args.iter().any(|a| a == "--conjugate");
    let rectangle = args.iter().any(|a| a == "--rectangle");
    args.retain(|a| a != "--conjugate" && a != "--rectangle");
    let mut reps = 3;
    if let Some(i) = args.iter().position(|a| a == "--reps") {
        reps = args.get(i + 1).and_then(|s| s.parse().ok()).unwrap_or(3);
        args.drain(i..(i + 2).min(args.len()));
    }
    let mut field = None;
    if let Some(i) = args.iter().position(|a| a == "--height-field") {
        field = args.get(i + 1).and_then(|s| s.parse::<usize>().ok());
        args.drain(i..(i + 2).min(args.len()));
    }
    let paths: Vec<PathBuf> = if field.is_some() {
        vec![PathBuf::from("height_field")]
    } else if args.is_empty() {
        let dir = std::env::var("CONFORMAP_SHARED_MESHES")
            .unwrap_or_else(|_| "/work/shared/meshes".into());
        WITH_BOUNDARY
            .iter()
            .map(|n| PathBuf::from(&dir).join(format!("{n}.obj")))
            .collect()
    } else {
        args.iter().map(PathBuf::from).collect()
    };
    let interior = if conjugate {
        FlattenInterior::Conjugate
    } else {
        FlattenInterior::Harmonic
    };
    let mut options = FlattenOptions::DEFAULT.with_interior(interior);
    if rectangle {
        options = options.with_boundary(FlattenBoundary::Rectangle {
            corners: None,
            aspect: None,
        });
    }
    println!(
        "| mesh | V | area spread | angle ° | flipped | degenerate | touches | operator (folds \
         before) | closure | flatten s | disk s | flatten/disk |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|");
    for path in paths {
        let name = path
            .file_stem()
            .map_or("?".into(), |s| s.to_string_lossy().into_owned());
        let read = match field {
            Some(n) => height_field(n),
            None => read_plain_obj(&path).map_err(Into::into),
        };
        let mesh = match read {
            Ok(m) => m,
            Err(e) => {
                println!("| {name} | skipped: {e} |");
                continue;
            }
        };
        let mut tf = Vec::new();
        let mut td = Vec::new();
        let mut last = None;
        for _ in 0..reps {
            let t = Instant::now();
            let out = flatten(&mesh, &options)?;
            tf.push(t.elapsed().as_secs_f64());
            last = Some(out);
            td.push(disk_seconds(&mesh)?);
        }
        let Some(out) = last else { continue };
        if std::env::var_os("FLATTEN_TIMINGS").is_some() {
            eprintln!("{name}: {:?}", out.report.timings_ms);
        }
        let r = &out.report;
        let (f, d) = (median(tf), median(td));
        println!(
            "| {name} | {} | {:.4} | {:.3} | {} | {} | {} | {} ({}) | {:.1e} | {:.3} | {:.3} | {:.2} |",
            mesh.num_vertices(),
            r.metrics.area_distortion_log.sd,
            r.metrics.angle_distortion_deg.mean,
            r.metrics.flipped_faces,
            r.metrics.degenerate_faces,
            r.boundary_touches,
            r.interior_operator,
            r.flipped_before_fallback,
            r.closure_residual,
            f,
            d,
            f / d
        );
    }
    Ok(())
}
