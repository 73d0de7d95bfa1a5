//! The tables of the crate README, on the shared meshes (`../shared/meshes/`, skipped when
//! absent). Run in release:
//!
//! ```text
//! cargo run --release -p conformap-sphere --example global_table -- sphere  # class c
//! cargo run --release -p conformap-sphere --example global_table -- disk    # class a: CEM + Möbius
//! cargo run --release -p conformap-sphere --example global_table -- cover   # double cover vs CEM
//! cargo run --release -p conformap-sphere --example global_table -- methods # all disk methods
//! ```
//! Extra arguments after the mode replace the default mesh list.

use std::time::Instant;

use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_sphere::{
    double_cover_disk_map, optimize_disk_mobius, optimize_sphere_mobius, sphere_map,
    sphere_metrics, DiskAutomorphism, MobiusObjective, MobiusOptions, SphereOptions,
};
use conformap_testkit::{CLASS_A, CLASS_C};
use num_complex::Complex64;

type Res = Result<(), Box<dyn std::error::Error>>;

const COVER: [&str; 6] = [
    "woody.obj",
    "alligator.obj",
    "spothead.obj",
    "camelhead.obj",
    "human_face.obj",
    "chinese_lion.obj",
];

fn main() -> Res {
    let mut args = std::env::args().skip(1);
    let mode = args.next().unwrap_or_else(|| "sphere".to_string());
    let rest: Vec<String> = args.collect();
    let list = |default: &[&str]| -> Vec<String> {
        if rest.is_empty() {
            default.iter().map(|s| s.to_string()).collect()
        } else {
            rest.clone()
        }
    };
    match mode.as_str() {
        "sphere" => sphere_table(&list(&CLASS_C)),
        "disk" => disk_table(&list(&CLASS_A)),
        "cover" => cover_table(&list(&COVER)),
        "methods" => methods_table(&list(&CLASS_A)),
        other => Err(format!("unknown mode {other}: sphere, disk, cover or methods").into()),
    }
}

fn read(name: &str) -> Option<conformap_mesh::TriMesh> {
    let path = conformap_testkit::real_mesh_or_skip(name, "global_table")?;
    conformap_testkit::read_plain_obj(&path).ok()
}

fn sphere_table(names: &[String]) -> Res {
    println!(
        "| mesh | V | mean / max angle dist. (°) | p95 | mean \\|μ\\| | flips | radius res. | stages | sphere time | uniformity before → after | angle after Möbius (°) | cross-ratio before / after | Möbius time |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|---|");
    for name in names {
        let Some(mesh) = read(name) else { continue };
        let t = Instant::now();
        let map = sphere_map(&mesh, &SphereOptions::DEFAULT)?;
        let t_sphere = t.elapsed().as_secs_f64();
        let m = sphere_metrics(&mesh, &map.points)?;
        let t = Instant::now();
        let best = optimize_sphere_mobius(
            &mesh,
            &map.points,
            &MobiusObjective::Uniform,
            &MobiusOptions::DEFAULT,
        )?;
        let t_mob = t.elapsed().as_secs_f64();
        let m2 = sphere_metrics(&mesh, &best.points)?;
        let stages: Vec<String> = map
            .report
            .stages
            .iter()
            .map(|s| format!("{:.3}", s.mean_angle_distortion_deg))
            .collect();
        println!(
            "| {name} | {} | {:.3} / {:.1} | {:.2} | {:.4} | {} | {:.1e} | {} (kept {}) | {:.2} s ({} factorizations, {:.2} s) | {:.4e} → {:.4e} | {:.3} | {:.6} / {:.6} | {:.2} s |",
            mesh.num_vertices(),
            m.angle_distortion_deg.mean,
            m.angle_distortion_deg.max,
            m.angle_distortion_deg.p95,
            m.beltrami_abs.mean,
            m.flipped_faces + m2.flipped_faces,
            m.radius_residual_max.max(m2.radius_residual_max),
            stages.join(" → "),
            map.report.best_stage,
            t_sphere,
            map.report.factorizations,
            map.report.timings_ms.factor / 1e3,
            best.report.uniformity_before,
            best.report.uniformity_after,
            m2.angle_distortion_deg.mean,
            m.cross_ratio_log.mean_abs,
            m2.cross_ratio_log.mean_abs,
            t_mob
        );
    }
    Ok(())
}

fn disk_table(names: &[String]) -> Res {
    println!("| mesh | V | CEM uniformity → after Möbius | boost length | angle dist. before → after (°) | cross-ratio before / after | flips before / after | Möbius time |");
    println!("|---|---|---|---|---|---|---|---|");
    for name in names {
        let Some(mesh) = read(name) else { continue };
        let mut problem = conformap_disk::DiskProblem::new(&mesh)?;
        let cem = conformap_disk::cem(&mut problem, &conformap_disk::CemOptions::DEFAULT)?;
        let t = Instant::now();
        let best = optimize_disk_mobius(
            &mesh,
            &cem.map,
            &MobiusObjective::Uniform,
            &MobiusOptions::DEFAULT,
        )?;
        let t_mob = t.elapsed().as_secs_f64();
        let a = planar_map_metrics(&mesh, &cem.map, &MetricsOptions::default())?;
        let b = planar_map_metrics(&mesh, &best.map, &MetricsOptions::default())?;
        let ca = conformap_metrics::cross_ratio_distortion(&mesh, &cem.map)?;
        let cb = conformap_metrics::cross_ratio_distortion(&mesh, &best.map)?;
        println!(
            "| {name} | {} | {:.4e} → {:.4e} | {:.3} | {:.3} → {:.3} | {:.6} / {:.6} | {} / {} | {:.2} s |",
            mesh.num_vertices(),
            best.report.uniformity_before,
            best.report.uniformity_after,
            best.report.boost_length,
            a.angle_distortion_deg.mean,
            b.angle_distortion_deg.mean,
            ca.mean_abs,
            cb.mean_abs,
            a.flipped_faces,
            b.flipped_faces,
            t_mob
        );
    }
    Ok(())
}

/// Both maps moved to their uniformity optimum (unique up to rotation), then rotated onto
/// each other by least squares: the largest remaining distance between them.
fn aligned_difference(
    mesh: &conformap_mesh::TriMesh,
    a: &[Complex64],
    b: &[Complex64],
) -> Result<(f64, f64), Box<dyn std::error::Error>> {
    let opts = MobiusOptions::DEFAULT.with_multi_start(false);
    let na = optimize_disk_mobius(mesh, a, &MobiusObjective::Uniform, &opts)?.map;
    let nb = optimize_disk_mobius(mesh, b, &MobiusObjective::Uniform, &opts)?.map;
    let s: Complex64 = na.iter().zip(&nb).map(|(x, y)| y * x.conj()).sum();
    let rot = DiskAutomorphism::rotation(s.arg());
    let d: Vec<f64> = na
        .iter()
        .zip(&nb)
        .map(|(x, y)| (rot.apply(*x) - y).norm())
        .collect();
    Ok((
        d.iter().cloned().fold(0.0, f64::max),
        d.iter().sum::<f64>() / d.len() as f64,
    ))
}

fn cover_table(names: &[String]) -> Res {
    println!("| mesh | V (cover) | route | E_C | mean / max angle dist. (°) | mean \\|μ\\| | flips | time | aligned max / mean \\|Δz\\| |");
    println!("|---|---|---|---|---|---|---|---|---|");
    for name in names {
        let Some(mesh) = read(name) else { continue };
        let t = Instant::now();
        let dc = double_cover_disk_map(&mesh, &SphereOptions::DEFAULT)?;
        let t_dc = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut problem = conformap_disk::DiskProblem::new(&mesh)?;
        let cem = conformap_disk::cem(&mut problem, &conformap_disk::CemOptions::DEFAULT)?;
        let t_cem = t.elapsed().as_secs_f64();
        let a = planar_map_metrics(&mesh, &dc.map, &MetricsOptions::default())?;
        let b = planar_map_metrics(&mesh, &cem.map, &MetricsOptions::default())?;
        let (dmax, dmean) = aligned_difference(&mesh, &dc.map, &cem.map)?;
        println!(
            "| {name} | {} ({}) | double cover | {:.4e} | {:.3} / {:.1} | {:.4} | {} | {:.2} s | {:.1e} / {:.1e} |",
            mesh.num_vertices(),
            dc.report.cover_vertices,
            a.conformal_energy,
            a.angle_distortion_deg.mean,
            a.angle_distortion_deg.max,
            a.beltrami_abs.mean,
            a.flipped_faces,
            t_dc,
            dmax,
            dmean
        );
        println!(
            "| | | CEM | {:.4e} | {:.3} / {:.1} | {:.4} | {} | {:.2} s | |",
            b.conformal_energy,
            b.angle_distortion_deg.mean,
            b.angle_distortion_deg.max,
            b.beltrami_abs.mean,
            b.flipped_faces,
            t_cem
        );
        eprintln!(
            "  {name}: split edges {}, boundary plane residual {:.1e}, symmetry defect {:.1e}, interior change {:.1e}, winding {:.3}",
            dc.report.split_edges,
            dc.report.boundary_plane_residual,
            dc.report.symmetry_defect_max,
            dc.report.interior_change_max,
            dc.report.boundary_winding
        );
    }
    Ok(())
}

/// The double-cover disk map beside `ccem-qn`, `cem` and `harmonic` (each from the mesh:
/// problem setup included in its time), judged by the same metrics.
fn methods_table(names: &[String]) -> Res {
    use conformap_disk::{compute_disk_map, DiskMethod, DiskOptions};
    println!("| mesh | V | method | E_C | mean angle dist. (°) | flips | time (ms) |");
    println!("|---|---|---|---|---|---|---|");
    for name in names {
        let Some(mesh) = read(name) else { continue };
        let mut rows: Vec<MethodRow> = vec![];
        for method in [DiskMethod::CcemQn, DiskMethod::Cem, DiskMethod::Harmonic] {
            let t = Instant::now();
            let out = compute_disk_map(&mesh, method, &DiskOptions::DEFAULT);
            let ms = t.elapsed().as_secs_f64() * 1e3;
            rows.push((
                method.to_string(),
                out.map(|m| (m.map, ms)).map_err(|e| e.to_string()),
            ));
        }
        let t = Instant::now();
        let dc = double_cover_disk_map(&mesh, &SphereOptions::DEFAULT);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        rows.push((
            "double-cover".to_string(),
            dc.map(|d| (d.map, ms)).map_err(|e| e.to_string()),
        ));
        for (k, (method, out)) in rows.into_iter().enumerate() {
            let head = if k == 0 {
                format!("{name} | {}", mesh.num_vertices())
            } else {
                " | ".to_string()
            };
            match out {
                Ok((map, ms)) => {
                    let m = planar_map_metrics(&mesh, &map, &MetricsOptions::default())?;
                    println!(
                        "| {head} | {method} | {:.4e} | {:.3} | {} | {:.0} |",
                        m.conformal_energy, m.angle_distortion_deg.mean, m.flipped_faces, ms
                    );
                }
                Err(e) => println!("| {head} | {method} | failed: {e} | | | |"),
            }
        }
    }
    Ok(())
}

/// One method's result on a mesh: its name, and the map with its time (ms) or the error.
type MethodRow = (String, Result<(Vec<Complex64>, f64), String>);
