//! Tests of the slits: topology after cutting, numbering, refusals, proposed paths.

use super::*;
use crate::topology::grid_torus;

/// A closed genus-0 mesh: the octahedron, each face subdivided `n × n`, projected onto the
/// unit sphere.
fn sphere(n: usize) -> TriMesh {
    let corners = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let tris = [
        [0, 1, 4],
        [1, 2, 4],
        [2, 3, 4],
        [3, 0, 4],
        [1, 0, 5],
        [2, 1, 5],
        [3, 2, 5],
        [0, 3, 5],
    ];
    let mut positions: Vec<[f64; 3]> = Vec::new();
    let mut index = HashMap::new();
    let mut id = |p: [f64; 3]| {
        let r = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
        let q = p.map(|x| x / r);
        let key = q.map(|x| (x * 1e9).round() as i64);
        *index.entry(key).or_insert_with(|| {
            positions.push(q);
            (positions.len() - 1) as u32
        })
    };
    let mut faces = Vec::new();
    for t in tris {
        let [a, b, c] = t.map(|i| corners[i]);
        let at = |i: usize, j: usize| {
            let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
            std::array::from_fn(|k| a[k] + u * (b[k] - a[k]) + v * (c[k] - a[k]))
        };
        for i in 0..n {
            for j in 0..n - i {
                let (p, q, r) = (id(at(i, j)), id(at(i + 1, j)), id(at(i, j + 1)));
                faces.push([p, q, r]);
                if i + j + 1 < n {
                    faces.push([q, id(at(i + 1, j + 1)), r]);
                }
            }
        }
    }
    TriMesh::try_new(positions, faces).expect("valid sphere")
}

fn check_cut(mesh: &TriMesh, cut: &SlitMesh) {
    let k = cut.slits.len();
    let interior: usize = cut.slits.iter().map(|p| p.len() - 2).sum();
    assert_eq!(cut.mesh.num_faces(), mesh.num_faces());
    assert_eq!(cut.mesh.num_vertices(), mesh.num_vertices() + interior);
    assert_eq!(
        cut.mesh.euler_characteristic(),
        mesh.euler_characteristic() - k as i64
    );
    assert_eq!(
        cut.mesh.boundary_loops().len(),
        mesh.boundary_loops().len() + k
    );
    assert_eq!(cut.mesh.genus(), mesh.genus());
    let mut loop_lengths: Vec<usize> = cut.mesh.boundary_loops().iter().map(Vec::len).collect();
    let mut expected: Vec<usize> = cut.slits.iter().map(|p| 2 * (p.len() - 1)).collect();
    loop_lengths.sort_unstable();
    expected.sort_unstable();
    assert_eq!(loop_lengths, expected);
    for (f, t) in mesh.faces().iter().enumerate() {
        for c in 0..3 {
            let v = cut.mesh.faces()[f][c];
            assert_eq!(cut.original[v as usize], t[c]);
            assert_eq!(
                cut.mesh.positions()[v as usize],
                mesh.positions()[t[c] as usize]
            );
        }
    }
}

#[test]
fn slits_on_a_sphere_add_one_loop_each() {
    let mesh = sphere(12);
    let diag = mesh.bbox_diagonal();
    let mut planner = SlitPlanner::new(&mesh);
    // the six octahedron corners, far apart
    let corners = [
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 0.0, -1.0],
    ];
    for c in corners {
        let v = (0..mesh.num_vertices() as u32)
            .find(|&v| mesh.positions()[v as usize] == c)
            .expect("corner");
        let p = planner.propose(&mesh, v, 0.15 * diag).expect("a slit");
        assert!(p.len() >= 3 && p.contains(&v), "{p:?}");
        let len: f64 = p.windows(2).map(|w| dist(&mesh, w[0], w[1])).sum();
        assert!(len > 0.1 * diag && len < 0.2 * diag, "{len}");
        planner.add(p).expect("valid");
        let cut = planner.cut(&mesh).expect("cut");
        check_cut(&mesh, &cut);
    }
    assert_eq!(planner.slits().len(), 4);
}

#[test]
fn slits_on_a_torus_keep_the_genus() {
    let mesh = grid_torus(24, 12, 3.0, 1.0);
    let cut = cut_slits(&mesh, &[vec![0, 1, 2, 3], vec![12, 13, 14]]).expect("valid");
    check_cut(&mesh, &cut);
    assert_eq!(cut.mesh.num_vertices(), mesh.num_vertices() + 3);
    assert_eq!(cut.mesh.genus(), Some(1));
}

#[test]
fn bad_slits_are_refused() {
    let mesh = grid_torus(24, 12, 3.0, 1.0);
    let reason = |slits: &[Vec<u32>]| match cut_slits(&mesh, slits) {
        Err(MeshError::InvalidSlit { reason, .. }) => reason,
        other => panic!("{other:?}"),
    };
    assert_eq!(reason(&[vec![0, 1]]), "fewer than two edges");
    assert_eq!(reason(&[vec![0, 2, 3]]), "no edge to the next vertex");
    // 0 → 1 → 25 → 24 (grid (0,1)): 24 is joined to 0 — a chord
    assert_eq!(
        reason(&[vec![0, 1, 25, 24]]),
        "an edge joins two non-consecutive slit vertices"
    );
    assert_eq!(
        reason(&[vec![0, 1, 2], vec![26, 27, 28]]),
        "on or next to the boundary or another slit"
    );
    // a disk: the boundary ring and its neighbours are blocked
    let disk = cut_slits(&mesh, &[vec![0, 1, 2, 3]]).expect("valid").mesh;
    let planner = SlitPlanner::new(&disk);
    assert!(!planner.is_free(1) && !planner.is_free(25) && planner.is_free(100));
}
