//! The default method never refuses a disk a simpler method maps (a real mesh stretched 3×,
//! whose obtuse triangles fold CCEM's harmonic interior, falls back to the flip-free CEM or
//! harmonic map of lower energy), and `--method ccem` starts from the CEM map as Kuo et al.
//! §6 do, so it never ends above CEM. Class-a meshes of `../shared/meshes` in the
//! `#[ignore]`d test (`cargo test -p conformap-disk --release --test fallback -- --ignored`).

use conformap_disk::{compute_disk_map, DiskError, DiskMethod, DiskOptions};
use conformap_mesh::TriMesh;
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_testkit::{fixture_mesh as fixture, read_real_mesh_or_skip};

fn stretched(mesh: &TriMesh, axis: usize, factor: f64) -> TriMesh {
    let p = mesh
        .positions()
        .iter()
        .map(|q| {
            let mut q = *q;
            q[axis] *= factor;
            q
        })
        .collect();
    TriMesh::try_new(p, mesh.faces().to_vec()).expect("a stretched valid mesh is valid")
}

fn energy(mesh: &TriMesh, method: DiskMethod) -> Result<f64, DiskError> {
    let out = compute_disk_map(mesh, method, &DiskOptions::DEFAULT)?;
    Ok(planar_map_metrics(mesh, &out.map, &MetricsOptions::DEFAULT)
        .expect("a finite map")
        .conformal_energy)
}

#[test]
fn a_stretched_woody_falls_back_instead_of_being_refused() {
    // woody stretched 3× along x: 30 faces of CCEM's map would fold (its obtuse triangles'
    // negative cotangent weights), CEM and harmonic map it with their flip-free guards
    let mesh = stretched(&fixture("woody.obj"), 0, 3.0);
    let keep = DiskOptions::DEFAULT.with_keep_folds(true);
    assert!(matches!(
        compute_disk_map(&mesh, DiskMethod::CcemQn, &keep),
        Err(DiskError::Folded { .. })
    ));
    let out = compute_disk_map(&mesh, DiskMethod::CcemQn, &DiskOptions::DEFAULT).expect("mapped");
    let r = &out.report;
    assert_eq!(r.fallback_from.as_deref(), Some("ccem-qn"));
    assert!(r.method == "cem" || r.method == "harmonic", "{}", r.method);
    assert!(
        r.notes.iter().any(|n| n.contains("ccem-qn refused")),
        "{:?}",
        r.notes
    );
    let m = planar_map_metrics(&mesh, &out.map, &MetricsOptions::DEFAULT).expect("finite");
    assert_eq!(m.flipped_faces, 0);
    // the lower of the two simpler methods' energies
    let best = energy(&mesh, DiskMethod::Cem)
        .unwrap()
        .min(energy(&mesh, DiskMethod::Harmonic).unwrap());
    assert!(
        (m.conformal_energy - best).abs() <= 1e-12 * best,
        "{} vs {best}",
        m.conformal_energy
    );
}

#[test]
fn ccem_from_the_cem_map_never_ends_above_cem() {
    for name in ["woody.obj", "alligator.obj", "spothead.obj"] {
        let mesh = fixture(name);
        let (ccem, cem) = (
            energy(&mesh, DiskMethod::Ccem).unwrap(),
            energy(&mesh, DiskMethod::Cem).unwrap(),
        );
        assert!(
            ccem <= cem * (1.0 + 1e-12),
            "{name}: ccem {ccem} > cem {cem}"
        );
        let out = compute_disk_map(&mesh, DiskMethod::Ccem, &DiskOptions::DEFAULT).unwrap();
        assert!(
            out.report
                .notes
                .iter()
                .any(|n| n.to_lowercase().contains("cem")),
            "{name}: {:?}",
            out.report.notes
        );
    }
}

#[test]
#[ignore = "class-a meshes of ../shared/meshes; run with --ignored in release"]
fn ccem_at_or_below_cem_on_every_class_a_mesh() {
    for name in conformap_testkit::CLASS_A {
        let Some(mesh) = read_real_mesh_or_skip(name, "ccem_at_or_below_cem") else {
            continue;
        };
        let (ccem, cem) = (
            energy(&mesh, DiskMethod::Ccem).unwrap(),
            energy(&mesh, DiskMethod::Cem).unwrap(),
        );
        eprintln!("{name}: ccem {ccem:.6e}, cem {cem:.6e}");
        assert!(
            ccem <= cem * (1.0 + 1e-12),
            "{name}: ccem {ccem} > cem {cem}"
        );
    }
}
