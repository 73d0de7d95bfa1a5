//! Read and write speed of conformap-io on real files: median of `RUNS` in-process runs.
//!
//! ```text
//! cargo run --release -p conformap-io --example io_speed -- MESH.obj...
//! ```
//!
//! Per file: `parse` = `read_raw_mesh` (bytes from the page cache, parsed, not validated),
//! `read` = `read_mesh` (the same plus `TriMesh::try_new`), `write obj` / `write glb` =
//! `write_mesh_with_uv` with a texture coordinate per vertex (the shape of `conformap
//! disk`'s output); `write obj, numbers copied` = the same with the file's `SourceInfo`,
//! whose vertex numbers are copied as written (what `conformap disk` does). MB/s are of the input file for reading and of the output file for
//! writing (1 MB = 10⁶ bytes).

use std::time::Instant;

/// Runs per measurement; the median is printed.
const RUNS: usize = 5;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn time(mut f: impl FnMut()) -> f64 {
    let runs = (0..RUNS)
        .map(|_| {
            let t = Instant::now();
            f();
            t.elapsed().as_secs_f64()
        })
        .collect();
    median(runs)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    println!("| file | MB | parse ms | parse MB/s | read ms | read MB/s | write obj ms | obj MB | write obj MB/s | write obj, numbers copied ms | MB/s | write glb ms | write glb MB/s |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |");
    let dir = std::env::temp_dir().join(format!("conformap-io-speed-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    for arg in std::env::args().skip(1) {
        let mb = std::fs::metadata(&arg)?.len() as f64 / 1e6;
        let parse = time(|| {
            let _ = std::hint::black_box(conformap_io::read_raw_mesh(&arg));
        });
        let read = time(|| {
            let _ = std::hint::black_box(conformap_io::read_mesh(&arg));
        });
        let loaded = conformap_io::read_mesh(&arg)?;
        let uv: Vec<[f64; 2]> = loaded
            .mesh
            .positions()
            .iter()
            .map(|p| [p[0], p[1]])
            .collect();
        let obj = dir.join("out.obj");
        let glb = dir.join("out.glb");
        let wobj = time(|| {
            let _ = std::hint::black_box(conformap_io::write_mesh_with_uv(
                &obj,
                &loaded.mesh,
                &uv,
                None,
            ));
        });
        let obj_mb = std::fs::metadata(&obj)?.len() as f64 / 1e6;
        // the same with the file's source: the vertices' numbers copied, not formatted
        let wobj_src = time(|| {
            let _ = std::hint::black_box(conformap_io::write_mesh_with_uv(
                &obj,
                &loaded.mesh,
                &uv,
                Some(&loaded.source),
            ));
        });
        let wglb = time(|| {
            let _ = std::hint::black_box(conformap_io::write_mesh_with_uv(
                &glb,
                &loaded.mesh,
                &uv,
                None,
            ));
        });
        let glb_mb = std::fs::metadata(&glb)?.len() as f64 / 1e6;
        let name = std::path::Path::new(&arg)
            .file_name()
            .map_or(arg.clone(), |n| n.to_string_lossy().into_owned());
        println!(
            "| {name} | {mb:.1} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {obj_mb:.1} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} |",
            parse * 1e3, mb / parse, read * 1e3, mb / read, wobj * 1e3, obj_mb / wobj, wobj_src * 1e3, obj_mb / wobj_src, wglb * 1e3, glb_mb / wglb
        );
    }
    std::fs::remove_dir_all(&dir)?;
    Ok(())
}
