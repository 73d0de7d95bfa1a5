//! Generated benchmark meshes: a bumpy height field over the unit square.

use std::io::Write;
use std::path::PathBuf;

/// Parses `250k`, `1m`, `2M`, `100000` into a face count.
fn parse_size(s: &str) -> Option<usize> {
    let s = s.to_ascii_lowercase();
    let (num, mul) = if let Some(n) = s.strip_suffix('k') {
        (n, 1_000.0)
    } else if let Some(n) = s.strip_suffix('m') {
        (n, 1_000_000.0)
    } else {
        (s.as_str(), 1.0)
    };
    num.parse::<f64>().ok().map(|v| (v * mul) as usize)
}

/// Writes (once, cached in the temp directory) an OBJ of an `n × n` grid with
/// `2 n² ≈ faces` triangles over the unit square lifted by a smooth bump field, and returns
/// its path. The triangulation alternates diagonals so that it stays Delaunay-like.
pub fn generated_obj(size: &str) -> Result<PathBuf, String> {
    let faces = parse_size(size).ok_or_else(|| format!("cannot read size `{size}`"))?;
    let n = ((faces as f64 / 2.0).sqrt().round() as usize).max(2);
    let path = std::env::temp_dir().join(format!("conformap-bench-grid-{n}.obj"));
    if path.is_file() {
        return Ok(path);
    }
    let tmp = path.with_extension("tmp");
    let file = std::fs::File::create(&tmp).map_err(|e| e.to_string())?;
    let mut w = std::io::BufWriter::new(file);
    let h = 1.0 / n as f64;
    let io = |e: std::io::Error| e.to_string();
    writeln!(
        w,
        "# conformap-bench generated height field, {n} x {n} squares"
    )
    .map_err(io)?;
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 * h, j as f64 * h);
            let z = 0.15 * (6.0 * x).sin() * (5.0 * y).cos() + 0.05 * (17.0 * x + 11.0 * y).sin();
            writeln!(w, "v {x} {y} {z}").map_err(io)?;
        }
    }
    let id = |i: usize, j: usize| j * (n + 1) + i + 1;
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                writeln!(w, "f {a} {b} {c}\nf {a} {c} {d}").map_err(io)?;
            } else {
                writeln!(w, "f {a} {b} {d}\nf {b} {c} {d}").map_err(io)?;
            }
        }
    }
    w.flush().map_err(io)?;
    drop(w);
    std::fs::rename(&tmp, &path).map_err(|e| e.to_string())?;
    Ok(path)
}
