//! Flipped faces and conformal energy of the disk maps with the plain cotangent Laplacian
//! and with the intrinsic Delaunay one, on real meshes (a measurement, not a test):
//!
//! `cargo run --release -p conformap-disk --example flip_table -- [--ccem] MESH.obj...`
//!
//! `E_C` is always judged with the mesh's own cotangent weights (docs/design.md, CEM Eq. 5–8),
//! whatever Laplacian the map was computed with.
use std::time::Instant;

use conformap_disk::{
    ccem, cem, polygon_area_of, CcemOptions, CemOptions, DiskMap, DiskProblem, LaplacianKind,
    ProblemOptions,
};
use conformap_mesh::TriMesh;
use conformap_operators::{cotan_laplacian, quadratic_form};
use conformap_testkit::read_plain_obj;
use num_complex::Complex64;

/// Faces with non-positive signed image area, and the smallest positive image area.
fn flips(mesh: &TriMesh, f: &[Complex64]) -> (usize, f64) {
    let mut n = 0;
    let mut min_area = f64::INFINITY;
    for t in mesh.faces() {
        let (a, b, c) = (f[t[0] as usize], f[t[1] as usize], f[t[2] as usize]);
        let twice = ((b - a).conj() * (c - a)).im;
        if twice > 0.0 {
            min_area = min_area.min(0.5 * twice);
        } else {
            n += 1;
        }
    }
    (n, min_area)
}

/// Smallest angle between consecutive boundary values, and boundary steps that go backwards.
fn boundary_gaps(lp: &[u32], f: &[Complex64]) -> (f64, usize) {
    let m = lp.len();
    let mut min_gap = f64::INFINITY;
    let mut backwards = 0;
    for k in 0..m {
        let (p, q) = (f[lp[k] as usize], f[lp[(k + 1) % m] as usize]);
        let g = (q / p).arg();
        if g <= 0.0 {
            backwards += 1;
        } else {
            min_gap = min_gap.min(g);
        }
    }
    (min_gap, backwards)
}

fn judge(mesh: &TriMesh, l: &sprs::CsMat<f64>, f: &[Complex64]) -> f64 {
    quadratic_form(l, f) - polygon_area_of(&mesh.boundary_loops()[0], f)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut use_ccem = false;
    let mut files = vec![];
    for a in std::env::args().skip(1) {
        if a == "--ccem" {
            use_ccem = true;
        } else {
            files.push(a);
        }
    }
    println!(
        "mesh | laplacian | flips | E_C (mesh cotan) | E_C (solver L) | min gap | backward \
         | min image area | assemble ms | factor ms | solve ms"
    );
    for name in files {
        let mesh = read_plain_obj(std::path::Path::new(&name))?;
        let short = name.rsplit('/').next().unwrap_or(&name).to_string();
        let t = Instant::now();
        let l_mesh = cotan_laplacian(&mesh);
        let cotan_ms = t.elapsed().as_secs_f64() * 1e3;
        let t = Instant::now();
        let (_, stats) = conformap_operators::intrinsic_delaunay_laplacian(&mesh)?;
        let intrinsic_ms = t.elapsed().as_secs_f64() * 1e3;
        println!(
            "{short}: cotan_laplacian {cotan_ms:.1} ms; intrinsic Delaunay Laplacian \
             {intrinsic_ms:.1} ms, of which building the triangulation and {} flips {:.1} ms",
            stats.flips, stats.flip_ms
        );
        let mut plain_ec = None;
        for kind in [LaplacianKind::Cotan, LaplacianKind::IntrinsicDelaunay] {
            let opts = ProblemOptions::DEFAULT.with_laplacian(kind);
            let mut p = match DiskProblem::with_options(&mesh, &opts) {
                Ok(p) => p,
                Err(e) => {
                    println!("{short} | {} | error: {e}", kind.name());
                    continue;
                }
            };
            let t = Instant::now();
            let out: Result<DiskMap, _> = if use_ccem {
                ccem(&mut p, &CcemOptions::DEFAULT)
            } else {
                cem(&mut p, &CemOptions::DEFAULT)
            };
            let solve = t.elapsed().as_secs_f64() * 1e3;
            let out = match out {
                Ok(o) => o,
                Err(e) => {
                    println!("{short} | {} | error: {e}", kind.name());
                    continue;
                }
            };
            let (nf, min_area) = flips(&mesh, &out.map);
            let (gap, back) = boundary_gaps(&mesh.boundary_loops()[0], &out.map);
            let ec = judge(&mesh, &l_mesh, &out.map);
            let rel = match plain_ec {
                Some(e0) => format!(" ({:+.3}%)", 100.0 * (ec - e0) / e0),
                None => String::new(),
            };
            if kind == LaplacianKind::Cotan {
                plain_ec = Some(ec);
            }
            println!(
                "{short} | {} | {nf} | {ec:.6e}{rel} | {:.6e} | {gap:.2e} | {back} | {min_area:.2e} \
                 | {:.0} | {:.0} | {solve:.0}",
                p.laplacian_kind().name(),
                p.conformal_energy(&out.map),
                p.assemble_ms,
                p.factor_ms,
            );
            if let Some(s) = p.intrinsic_stats() {
                println!(
                    "    intrinsic: {} non-Delaunay of {} interior edges, {} flips, {} left, \
                     min weight {:.3e} -> {:.3e}, {} negative boundary weights, {:.1} ms",
                    s.non_delaunay_before,
                    s.interior_edges,
                    s.flips,
                    s.non_delaunay_after,
                    s.min_weight_before,
                    s.min_weight_after,
                    s.negative_boundary_weights,
                    s.flip_ms
                );
            }
            if nf > 0 {
                match conformap_disk::unfold_disk_map(&p, &out.map) {
                    Ok(u) => {
                        let (nf2, min_area2) = flips(&mesh, &u.map);
                        let (gap2, back2) = boundary_gaps(&mesh.boundary_loops()[0], &u.map);
                        println!(
                            "    unfolded: {nf2} flips, E_C {:.6e}, min gap {gap2:.2e}, backward \
                             {back2}, min area {min_area2:.2e}; {:?}",
                            judge(&mesh, &l_mesh, &u.map),
                            u.note()
                        );
                    }
                    Err(e) => println!("    unfold refused: {e}"),
                }
            }
            for n in &out.report.notes {
                println!("    note: {n}");
            }
        }
    }
    Ok(())
}
