//! Generated benchmark meshes, two families that bracket the boundary lengths of real inputs:
//!
//! - `gen:N`: a bumpy height field over the unit square, boundary `n_B ≈ 4 √V` — the longest
//!   boundary a disk-like mesh of that size has (every grid row ends on it), the worst case of
//!   the dense boundary route;
//! - `disk:N`: the same bumps over the unit disk (concentric rings, near-equilateral
//!   triangles), boundary `n_B ≈ 3.5 √V` — as long as the square's nearly, but without
//!   corners;
//! - `cap:N`: a bumpy closed surface (a cube subdivided and pushed onto a sphere with radial
//!   bumps) with the faces near one pole removed, boundary `n_B ≈ 1.4 √V` — the shape of a
//!   scan cut open at a hole (`igea_open.obj`: 310 boundary vertices at 130k, `0.86 √V`;
//!   `hand.obj`: 246 at 53k, `1.07 √V`).

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

/// The bump field of the height fields, on `[0, 1]²`.
fn bump(x: f64, y: f64) -> f64 {
    0.15 * (6.0 * x).sin() * (5.0 * y).cos() + 0.05 * (17.0 * x + 11.0 * y).sin()
}

/// Writes a plain `v`/`f` OBJ (0-based `faces`) to `path` through a temporary sibling, so
/// that a cached file is never half written.
fn write_obj(
    path: &std::path::Path,
    header: &str,
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
) -> Result<(), String> {
    let tmp = path.with_extension("tmp");
    let file = std::fs::File::create(&tmp).map_err(|e| e.to_string())?;
    let mut w = std::io::BufWriter::new(file);
    let io = |e: std::io::Error| e.to_string();
    writeln!(w, "# {header}").map_err(io)?;
    for p in positions {
        writeln!(w, "v {} {} {}", p[0], p[1], p[2]).map_err(io)?;
    }
    for t in faces {
        writeln!(w, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1).map_err(io)?;
    }
    w.flush().map_err(io)?;
    drop(w);
    std::fs::rename(&tmp, path).map_err(|e| e.to_string())
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
    let h = 1.0 / n as f64;
    let mut positions = Vec::with_capacity((n + 1) * (n + 1));
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (i as f64 * h, j as f64 * h);
            positions.push([x, y, bump(x, y)]);
        }
    }
    let id = |i: usize, j: usize| (j * (n + 1) + i) as u32;
    let mut faces = Vec::with_capacity(2 * n * n);
    for j in 0..n {
        for i in 0..n {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            if (i + j) % 2 == 0 {
                faces.extend([[a, b, c], [a, c, d]]);
            } else {
                faces.extend([[a, b, d], [b, c, d]]);
            }
        }
    }
    let header = format!("conformap-bench generated height field, {n} x {n} squares");
    write_obj(&path, &header, &positions, &faces)?;
    Ok(path)
}

/// Writes (once, cached in the temp directory) an OBJ of a bumpy closed surface with one
/// hole, about `faces` triangles, and returns its path.
///
/// The six faces of the cube `[-n, n]³` are cut into `n × n` squares of side 2 each (vertices on the
/// cube's edges shared through their integer lattice coordinates), every point is pushed
/// onto the sphere and moved radially by a smooth bump field (`±6 %` of the radius), each
/// square is split along its shorter diagonal, and the faces whose centroid lies above
/// `z = 0.8` (a cap of 10 % of the area) are removed. `size@Z` (e.g. `1m@0`) cuts at
/// `z = Z` instead (`-0.9 < Z < 0.95`): a lower cut leaves a longer boundary around a
/// smaller surface (`@0`, a hemisphere: `n_B ≈ 3.1 √V`), which measures where the dense
/// boundary route stops paying.
pub fn generated_cap_obj(size: &str) -> Result<PathBuf, String> {
    use std::collections::HashMap;
    let (size, cut) = match size.split_once('@') {
        Some((s, z)) => (
            s,
            z.parse::<f64>()
                .ok()
                .filter(|z| *z > -0.9 && *z < 0.95)
                .ok_or_else(|| format!("cannot read the cut `{z}` (a number in (-0.9, 0.95))"))?,
        ),
        None => (size, 0.8),
    };
    let faces = parse_size(size).ok_or_else(|| format!("cannot read size `{size}`"))?;
    // 12 n² faces on the whole cube with n squares a side, a share (1 + cut) / 2 of them kept
    let kept_share = (1.0 + cut) / 2.0;
    let half = ((faces as f64 / kept_share / 12.0).sqrt().round() as i64).max(2);
    let path = std::env::temp_dir().join(if cut == 0.8 {
        format!("conformap-bench-cap-{half}.obj")
    } else {
        format!("conformap-bench-cap-{half}-at-{cut}.obj")
    });
    if path.is_file() {
        return Ok(path);
    }
    let n = half; // lattice coordinates run over -n..=n in steps of 2 on a cube of side 2n
    let mut index: HashMap<[i64; 3], u32> = HashMap::new();
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut vertex = |c: [i64; 3]| -> u32 {
        *index.entry(c).or_insert_with(|| {
            let (x, y, z) = (c[0] as f64, c[1] as f64, c[2] as f64);
            let r = (x * x + y * y + z * z).sqrt();
            let (x, y, z) = (x / r, y / r, z / r);
            let bump = 1.0
                + 0.04 * (5.0 * x).sin() * (4.0 * y).cos() * (3.0 * z + 1.0).cos()
                + 0.02 * (13.0 * x + 7.0 * z).sin();
            points.push([bump * x, bump * y, bump * z]);
            (points.len() - 1) as u32
        })
    };
    let mut tris: Vec<[u32; 3]> = Vec::new();
    // each cube face: a fixed axis `a` at sign `s`, and two running axes (u, v) ordered so
    // that u × v points outward
    for a in 0..3usize {
        for s in [-1i64, 1] {
            let (u, v) = if s > 0 {
                ((a + 1) % 3, (a + 2) % 3)
            } else {
                ((a + 2) % 3, (a + 1) % 3)
            };
            let at = |i: i64, j: i64| -> [i64; 3] {
                let mut c = [0i64; 3];
                c[a] = s * n;
                c[u] = -n + 2 * i;
                c[v] = -n + 2 * j;
                c
            };
            for j in 0..n {
                for i in 0..n {
                    let q = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
                    let q = q.map(&mut vertex);
                    tris.push([q[0], q[1], q[2]]);
                    tris.push([q[0], q[2], q[3]]);
                }
            }
        }
    }
    // shorter diagonal: re-split a square where the other diagonal is shorter
    let d2 = |p: u32, q: u32| -> f64 {
        let (p, q) = (points[p as usize], points[q as usize]);
        (0..3).map(|k| (p[k] - q[k]).powi(2)).sum()
    };
    for pair in tris.chunks_exact_mut(2) {
        let (a, b, c, d) = (pair[0][0], pair[0][1], pair[0][2], pair[1][2]);
        if d2(b, d) < d2(a, c) {
            pair[0] = [a, b, d];
            pair[1] = [b, c, d];
        }
    }
    let kept: Vec<[u32; 3]> = tris
        .into_iter()
        .filter(|t| t.iter().map(|&i| points[i as usize][2]).sum::<f64>() / 3.0 <= cut)
        .collect();
    // renumber the vertices that are still referenced, in order of first use
    let mut new_id = vec![u32::MAX; points.len()];
    let mut order = Vec::new();
    for t in &kept {
        for &i in t {
            if new_id[i as usize] == u32::MAX {
                new_id[i as usize] = order.len() as u32;
                order.push(i);
            }
        }
    }
    let positions: Vec<[f64; 3]> = order.iter().map(|&i| points[i as usize]).collect();
    let faces: Vec<[u32; 3]> = kept.iter().map(|t| t.map(|i| new_id[i as usize])).collect();
    let header = format!(
        "conformap-bench generated bumpy sphere cut at z = {cut}, cube {half} squares a side"
    );
    write_obj(&path, &header, &positions, &faces)?;
    Ok(path)
}

/// Writes (once, cached in the temp directory) an OBJ of the unit disk in concentric rings
/// (`conformap_testkit::flat_disk(rings, 6)`, `6 rings² ≈ faces` triangles) lifted by the
/// bump field of [`generated_obj`], and returns its path.
pub fn generated_disk_obj(size: &str) -> Result<PathBuf, String> {
    let faces = parse_size(size).ok_or_else(|| format!("cannot read size `{size}`"))?;
    let rings = ((faces as f64 / 6.0).sqrt().round() as usize).max(2);
    let path = std::env::temp_dir().join(format!("conformap-bench-disk-{rings}.obj"));
    if path.is_file() {
        return Ok(path);
    }
    let mesh = conformap_testkit::flat_disk(rings, 6);
    // the square's field, the disk's [-1, 1]² mapped onto [0, 1]²
    let positions: Vec<[f64; 3]> = mesh
        .positions()
        .iter()
        .map(|p| [p[0], p[1], bump((p[0] + 1.0) / 2.0, (p[1] + 1.0) / 2.0)])
        .collect();
    let header =
        format!("conformap-bench generated height field over the unit disk, {rings} rings");
    write_obj(&path, &header, &positions, mesh.faces())?;
    Ok(path)
}
