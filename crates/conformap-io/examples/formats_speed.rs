//! Read speed of the PLY reader against the OBJ reader on the same mesh, and the converted
//! files themselves (for checking other tools and the CLI on them).
//!
//! ```text
//! cargo run --release -p conformap-io --example formats_speed -- MESH.obj [OUT_DIR]
//! ```
//!
//! Writes `OUT_DIR/<stem>.bin.ply` (binary, double), `<stem>.ascii.ply`, `<stem>.f32.ply`
//! (binary float32, the common scanner layout), `<stem>.stl` (binary), `<stem>.ascii.stl`,
//! `<stem>.off`, `<stem>.surf.gii` (GIfTI, gzip) and `lh.<stem>.white` (FreeSurfer), then
//! prints the fastest of nine runs of `read_raw_mesh` (parse) and `read_mesh` (parse and
//! validation) of each, with MB/s (1 MB = 10⁶ bytes of the file read).

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

/// The fastest of nine runs of `read` on `path`, in milliseconds (the machine is shared:
/// the fastest run is the one least disturbed).
fn median_ms<T>(
    path: &Path,
    read: impl Fn(&Path) -> Result<T, conformap_io::IoError>,
) -> Result<f64, conformap_io::IoError> {
    let mut runs = Vec::new();
    for _ in 0..9 {
        let t = Instant::now();
        read(path)?;
        runs.push(t.elapsed().as_secs_f64() * 1e3);
    }
    runs.sort_by(f64::total_cmp);
    Ok(runs[0])
}

/// The text and binary files other tools write, from `p` and `f`.
fn conversions(p: &[[f64; 3]], f: &[[u32; 3]]) -> Vec<(&'static str, Vec<u8>)> {
    let mut ascii_ply = format!(
        "ply\nformat ascii 1.0\nelement vertex {}\nproperty float x\nproperty float y\n\
         property float z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        p.len(),
        f.len()
    );
    let mut f32_ply = ascii_ply
        .replace("ascii", "binary_little_endian")
        .into_bytes();
    let mut off = format!("OFF\n{} {} 0\n", p.len(), f.len());
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&(f.len() as u32).to_le_bytes());
    let mut ascii_stl = String::from("solid mesh\n");
    for q in p {
        let _ = writeln!(ascii_ply, "{} {} {}", q[0] as f32, q[1] as f32, q[2] as f32);
        let _ = writeln!(off, "{:?} {:?} {:?}", q[0], q[1], q[2]);
        for x in q {
            f32_ply.extend_from_slice(&(*x as f32).to_le_bytes());
        }
    }
    for t in f {
        let _ = writeln!(ascii_ply, "3 {} {} {}", t[0], t[1], t[2]);
        let _ = writeln!(off, "3 {} {} {}", t[0], t[1], t[2]);
        f32_ply.push(3);
        stl.extend_from_slice(&[0u8; 12]);
        ascii_stl.push_str(" facet normal 0 0 0\n  outer loop\n");
        for &i in t {
            f32_ply.extend_from_slice(&(i as i32).to_le_bytes());
            let q = p[i as usize].map(|x| x as f32);
            q.iter()
                .for_each(|x| stl.extend_from_slice(&x.to_le_bytes()));
            let _ = writeln!(ascii_stl, "   vertex {:e} {:e} {:e}", q[0], q[1], q[2]);
        }
        stl.extend_from_slice(&[0u8; 2]);
        ascii_stl.push_str("  endloop\n endfacet\n");
    }
    ascii_stl.push_str("endsolid mesh\n");
    vec![
        ("ascii.ply", ascii_ply.into_bytes()),
        ("f32.ply", f32_ply),
        ("off", off.into_bytes()),
        ("stl", stl),
        ("ascii.stl", ascii_stl.into_bytes()),
    ]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let obj = args
        .next()
        .ok_or("usage: formats_speed MESH.obj [OUT_DIR]")?;
    let dir = args
        .next()
        .map(Into::into)
        .unwrap_or_else(|| std::env::temp_dir().join("conformap-formats-speed"));
    std::fs::create_dir_all(&dir)?;
    let stem = Path::new(&obj)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or("mesh");
    let mesh = conformap_io::read_mesh(&obj)?.mesh;
    let bin = dir.join(format!("{stem}.bin.ply"));
    conformap_io::write_flat(&bin, mesh.positions(), mesh.faces())?;
    let gii = dir.join(format!("{stem}.surf.gii"));
    conformap_io::write_flat(&gii, mesh.positions(), mesh.faces())?;
    let fs = dir.join(format!("lh.{stem}.white"));
    conformap_io::write_flat(&fs, mesh.positions(), mesh.faces())?;
    let mut files = vec![Path::new(&obj).to_path_buf(), bin, gii, fs];
    for (ext, bytes) in conversions(mesh.positions(), mesh.faces()) {
        let path = dir.join(format!("{stem}.{ext}"));
        std::fs::write(&path, bytes)?;
        files.push(path);
    }
    println!("| file | MB | parse ms | parse MB/s | read ms | read MB/s |");
    println!("| --- | ---: | ---: | ---: | ---: | ---: |");
    for path in files {
        let mb = std::fs::metadata(&path)?.len() as f64 / 1e6;
        let parse = median_ms(&path, |p| conformap_io::read_raw_mesh(p))?;
        let read = median_ms(&path, |p| conformap_io::read_mesh(p))?;
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("?");
        println!(
            "| {name} | {mb:.2} | {parse:.1} | {:.0} | {read:.1} | {:.0} |",
            mb / parse * 1e3,
            mb / read * 1e3
        );
    }
    Ok(())
}
