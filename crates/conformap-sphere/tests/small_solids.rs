//! Small closed meshes map: the regular solids (exactly, to their radial projections up to
//! a Möbius map), the same with noise, and a cube split into triangles.

mod common;

use common::Lcg;
use conformap_mesh::TriMesh;
use conformap_sphere::{sphere_map, sphere_metrics, SphereOptions};
use conformap_testkit::icosphere;

/// A convex polyhedron centred at the origin with every face turned outwards.
fn outward(p: Vec<[f64; 3]>, faces: Vec<[u32; 3]>) -> TriMesh {
    let faces = faces
        .into_iter()
        .map(|[a, b, c]| {
            let (x, y, z) = (p[a as usize], p[b as usize], p[c as usize]);
            let d = x[0] * (y[1] * z[2] - y[2] * z[1]) - x[1] * (y[0] * z[2] - y[2] * z[0])
                + x[2] * (y[0] * z[1] - y[1] * z[0]);
            if d > 0.0 {
                [a, b, c]
            } else {
                [a, c, b]
            }
        })
        .collect();
    TriMesh::try_new(p, faces).expect("a valid solid")
}

fn tetrahedron() -> TriMesh {
    let p = vec![
        [1.0, 1.0, 1.0],
        [1.0, -1.0, -1.0],
        [-1.0, 1.0, -1.0],
        [-1.0, -1.0, 1.0],
    ];
    outward(p, vec![[0, 1, 2], [0, 1, 3], [0, 2, 3], [1, 2, 3]])
}

fn octahedron() -> TriMesh {
    let p = vec![
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let faces = vec![
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    outward(p, faces)
}

fn icosahedron() -> TriMesh {
    icosphere(1.0, 0)
}

/// The cube `[-1, 1]³`, each square split along a diagonal.
fn cube() -> TriMesh {
    let p: Vec<[f64; 3]> = (0..8)
        .map(|k| [k & 1, (k >> 1) & 1, (k >> 2) & 1].map(|b| 2.0 * b as f64 - 1.0))
        .collect();
    let quads = [
        [0, 1, 3, 2],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 3, 7, 6],
        [0, 2, 6, 4],
        [1, 3, 7, 5],
    ];
    let faces = quads
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    outward(p, faces)
}

/// `mesh` with every coordinate moved by up to `amp` (seeded).
fn noisy(mesh: &TriMesh, amp: f64, seed: u64) -> TriMesh {
    let mut rng = Lcg(seed);
    let p = mesh
        .positions()
        .iter()
        .map(|q| q.map(|x| x + rng.range(-amp, amp)))
        .collect();
    TriMesh::try_new(p, mesh.faces().to_vec()).expect("still valid")
}

fn solids() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("tetrahedron", tetrahedron()),
        ("octahedron", octahedron()),
        ("icosahedron", icosahedron()),
    ]
}

#[test]
fn regular_solids_map_to_their_radial_projections() {
    for (name, mesh) in solids() {
        let map =
            sphere_map(&mesh, &SphereOptions::DEFAULT).unwrap_or_else(|e| panic!("{name}: {e}"));
        let m = sphere_metrics(&mesh, &map.points).expect("metrics");
        eprintln!("{name}: {m:?} {:?}", map.report);
        assert_eq!(m.flipped_faces, 0, "{name}");
        assert!(map.points.iter().flatten().all(|x| x.is_finite()), "{name}");
        // inscribed solids: chordal lengths are the mesh's, so the length cross-ratios of
        // the radial projection are the mesh's; a Möbius map keeps them
        assert!(
            m.cross_ratio_log.max_abs < 1e-9,
            "{name}: {:?}",
            m.cross_ratio_log
        );
    }
}

#[test]
fn noisy_solids_and_a_cube_map_without_inverted_faces() {
    let mut cases: Vec<(String, TriMesh)> = solids()
        .into_iter()
        .flat_map(|(name, mesh)| {
            (1..=4).map(move |seed| {
                (
                    format!("{name} + 1e-3 noise (seed {seed})"),
                    noisy(&mesh, 1e-3, seed),
                )
            })
        })
        .collect();
    cases.push(("cube".to_string(), cube()));
    cases.push(("cube + 1e-3 noise".to_string(), noisy(&cube(), 1e-3, 7)));
    for (name, mesh) in cases {
        let map =
            sphere_map(&mesh, &SphereOptions::DEFAULT).unwrap_or_else(|e| panic!("{name}: {e}"));
        let m = sphere_metrics(&mesh, &map.points).expect("metrics");
        eprintln!(
            "{name}: flipped {} cr {:?}",
            m.flipped_faces, m.cross_ratio_log
        );
        assert_eq!(m.flipped_faces, 0, "{name}");
        assert!(map.points.iter().flatten().all(|x| x.is_finite()), "{name}");
    }
}
