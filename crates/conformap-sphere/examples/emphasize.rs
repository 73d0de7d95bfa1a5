//! Emphasized area: split a closed mesh into two halves by a plane through its centroid
//! (normal along x) and report the image-area share the emphasized half gets, for the
//! capped share objective (Eq. 10) at several caps and for the log-density objective.
//!
//! `cargo run --release -p conformap-sphere --example emphasize -- spot.obj david_head.obj`
//! (file names in `fixtures/` or `../shared/meshes/`).

use conformap_operators::face_areas;
use conformap_sphere::{
    optimize_sphere_mobius, sphere_map, MobiusObjective, MobiusOptions, SphereOptions,
};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let names: Vec<String> = std::env::args().skip(1).collect();
    let names = if names.is_empty() {
        vec!["spot.obj".to_string()]
    } else {
        names
    };
    println!(
        "| mesh | half (surface share) | objective | cap | image share | boost length | time |"
    );
    println!("|---|---|---|---|---|---|---|");
    for name in names {
        let Some(path) = conformap_testkit::real_mesh_or_skip(&name, "emphasize") else {
            continue;
        };
        let mesh = conformap_testkit::read_plain_obj(&path)?;
        let areas = face_areas(&mesh);
        let total: f64 = areas.iter().sum();
        let centroid = |t: &[u32; 3]| {
            t.iter()
                .map(|&v| mesh.positions()[v as usize][0])
                .sum::<f64>()
                / 3.0
        };
        let cx: f64 = mesh
            .faces()
            .iter()
            .zip(&areas)
            .map(|(t, a)| centroid(t) * a)
            .sum::<f64>()
            / total;
        let left: Vec<usize> = (0..mesh.num_faces())
            .filter(|&f| centroid(&mesh.faces()[f]) < cx)
            .collect();
        let map = sphere_map(&mesh, &SphereOptions::DEFAULT)?;
        let surf: f64 = left.iter().map(|&f| areas[f]).sum::<f64>() / total;
        for cap in [5.0, 10.0, 100.0, 1e4] {
            let t = std::time::Instant::now();
            let opts = MobiusOptions::DEFAULT.with_max_area_scale(cap);
            let r = optimize_sphere_mobius(
                &mesh,
                &map.points,
                &MobiusObjective::Emphasize {
                    region: left.clone(),
                },
                &opts,
            )?
            .report;
            println!(
                "| {name} | left x < {cx:.3} ({:.1} %) | share (Eq. 10) | {cap} | {:.2} % → {:.2} % | {:.3} | {:.2} s |",
                100.0 * surf,
                100.0 * r.region_share_before.unwrap_or(0.0),
                100.0 * r.region_share_after.unwrap_or(0.0),
                r.boost_length,
                t.elapsed().as_secs_f64()
            );
        }
        let t = std::time::Instant::now();
        let r = optimize_sphere_mobius(
            &mesh,
            &map.points,
            &MobiusObjective::EmphasizeDensity {
                region: left.clone(),
            },
            &MobiusOptions::DEFAULT,
        )?
        .report;
        println!(
            "| {name} | left ({:.1} %) | log density | none | {:.2} % → {:.2} % | {:.3} | {:.2} s |",
            100.0 * surf,
            100.0 * r.region_share_before.unwrap_or(0.0),
            100.0 * r.region_share_after.unwrap_or(0.0),
            r.boost_length,
            t.elapsed().as_secs_f64()
        );
    }
    Ok(())
}
