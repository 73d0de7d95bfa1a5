//! `repair`: each repair on its own, their combination, the maps back to the input, and the
//! defects it refuses (with the element they name).
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

use conformap_mesh::{repair, MeshError, RepairOptions, Topology, TriMesh, DROPPED};
use conformap_testkit::{grid_faces, XorShift64Star};

/// A grid of `n × n` squares (two triangles each), consistently oriented.
fn grid(n: u32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            p.push([f64::from(i), f64::from(j), 0.1 * f64::from(i * j % 3)]);
        }
    }
    (p, grid_faces(n as usize, n as usize))
}

/// A Möbius strip of `n` quads: the last quad glues the ends with a half twist.
fn mobius(n: u32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut p = Vec::new();
    for i in 0..n {
        let t = std::f64::consts::TAU * f64::from(i) / f64::from(n);
        let (c, s) = (t.cos(), t.sin());
        let (h, z) = ((t / 2.0).cos() * 0.3, (t / 2.0).sin() * 0.3);
        p.push([c * (1.0 + h), s * (1.0 + h), z]); // top i = 2i
        p.push([c * (1.0 - h), s * (1.0 - h), -z]); // bottom i = 2i + 1
    }
    let mut f = Vec::new();
    for i in 0..n {
        let (t0, b0) = (2 * i, 2 * i + 1);
        // the ends meet swapped: top n is bottom 0
        let (t1, b1) = if i + 1 == n {
            (1, 0)
        } else {
            (2 * i + 2, 2 * i + 3)
        };
        f.push([t0, b0, b1]);
        f.push([t0, b1, t1]);
    }
    (p, f)
}

#[test]
fn a_valid_mesh_is_left_alone() {
    let (p, f) = grid(4);
    let r = repair(&p, &f, &RepairOptions::DEFAULT).unwrap();
    assert!(!r.log.changed());
    assert!(r.log.actions().is_empty());
    assert_eq!((r.positions, r.faces), (p, f.clone()));
    assert_eq!(r.log.face_to_input, (0..f.len() as u32).collect::<Vec<_>>());
    assert_eq!(r.log.components, 1);
}

#[test]
fn each_repair_fixes_its_defect_and_logs_it() {
    let (p, f) = grid(3);
    let valid = |r: &conformap_mesh::Repaired| {
        TriMesh::try_new(r.positions.clone(), r.faces.clone()).unwrap()
    };

    // duplicate (same vertex set, other order): the later copy goes
    let mut g = f.clone();
    g.push([f[5][1], f[5][2], f[5][0]]);
    assert!(matches!(
        TriMesh::try_new(p.clone(), g.clone()).unwrap_err(),
        MeshError::DuplicateFace { face: 18, first: 5 }
    ));
    let r = repair(&p, &g, &RepairOptions::DEFAULT).unwrap();
    assert_eq!(r.log.duplicate_faces, 1);
    assert!(!r.log.face_to_input.contains(&18));
    assert_eq!(r.faces, f);
    valid(&r);

    // unreferenced vertices: dropped, the others keep their order
    let mut q = p.clone();
    q.insert(0, [7.0, 7.0, 7.0]);
    let g: Vec<[u32; 3]> = f.iter().map(|t| t.map(|v| v + 1)).collect();
    let r = repair(&q, &g, &RepairOptions::DEFAULT).unwrap();
    assert_eq!(r.log.unreferenced_vertices, 1);
    assert_eq!(r.log.input_to_vertex[0], DROPPED);
    assert_eq!(r.log.vertex_to_input[0], 1);
    assert_eq!((&r.positions, &r.faces), (&p, &f));
    valid(&r);

    // flipped faces: the minority is flipped back
    let mut g = f.clone();
    g[4].swap(0, 1);
    g[7].swap(1, 2);
    let r = repair(&p, &g, &RepairOptions::DEFAULT).unwrap();
    assert_eq!(r.log.flipped_faces, 2);
    let m = valid(&r);
    assert_eq!(m.topology(), Topology::Disk);
    // same orientation as the original grid: the boundary loop runs the same way
    let orig = TriMesh::try_new(p.clone(), f.clone()).unwrap();
    assert_eq!(m.boundary_loops(), orig.boundary_loops());
}

#[test]
fn the_largest_component_is_kept_with_maps_back() {
    let (p, f) = grid(2); // 9 vertices, 8 faces
    let (small_p, small_f) = grid(1); // 4 vertices, 2 faces
                                      // small component first, so the kept one is renumbered
    let mut pos: Vec<[f64; 3]> = small_p.iter().map(|q| [q[0] + 10.0, q[1], q[2]]).collect();
    pos.extend(&p);
    let mut faces = small_f.clone();
    faces.extend(f.iter().map(|t| t.map(|v| v + 4)));
    let m = TriMesh::try_new(pos.clone(), faces.clone()).unwrap();
    assert_eq!(m.topology(), Topology::SeveralComponents { components: 2 });

    let r = repair(&pos, &faces, &RepairOptions::DEFAULT).unwrap();
    let log = &r.log;
    assert_eq!(log.components, 2);
    assert_eq!(log.component_faces_dropped, 2);
    assert_eq!(log.component_vertices_dropped, 4);
    assert_eq!(log.unreferenced_vertices, 0);
    assert_eq!(log.vertex_to_input, (4..13).collect::<Vec<u32>>());
    assert_eq!(log.face_to_input, (2..10).collect::<Vec<u32>>());
    for (k, &v) in log.vertex_to_input.iter().enumerate() {
        assert_eq!(log.input_to_vertex[v as usize], k as u32);
        assert_eq!(r.positions[k], pos[v as usize]);
    }
    assert_eq!(log.input_to_vertex[..4], [DROPPED; 4]);
    assert_eq!((&r.positions, &r.faces), (&p, &f));
    let repaired = TriMesh::try_new(r.positions, r.faces).unwrap();
    assert_eq!(repaired.topology(), Topology::Disk);
    assert_eq!(
        log.actions(),
        vec!["largest of 2 components kept (2 faces and 4 vertices dropped)"]
    );
}

#[test]
fn equal_components_keep_the_one_with_the_lowest_face() {
    let (p, f) = grid(1);
    let mut pos = p.clone();
    pos.extend(p.iter().map(|q| [q[0] + 5.0, q[1], q[2]]));
    // the second copy's faces come first in the list
    let mut faces: Vec<[u32; 3]> = f.iter().map(|t| t.map(|v| v + 4)).collect();
    faces.extend(&f);
    let r = repair(&pos, &faces, &RepairOptions::DEFAULT).unwrap();
    assert_eq!(r.log.face_to_input, vec![0, 1]);
    assert_eq!(r.log.vertex_to_input, vec![4, 5, 6, 7]);
}

#[test]
fn random_minority_flips_are_undone_exactly() {
    let (p, f) = grid(8);
    let mut rng = XorShift64Star(0x05ee_d0ff_11b5);
    for _ in 0..50 {
        let mut g = f.clone();
        let mut flipped = 0;
        for t in &mut g {
            if rng.next_u64() % 4 == 0 {
                t.swap(0, 2);
                flipped += 1;
            }
        }
        let r = repair(&p, &g, &RepairOptions::DEFAULT).unwrap();
        assert_eq!(r.log.flipped_faces, flipped);
        // each face is the original up to rotation
        for (a, b) in r.faces.iter().zip(&f) {
            let rot = |t: [u32; 3], k: usize| [t[k], t[(k + 1) % 3], t[(k + 2) % 3]];
            assert!((0..3).any(|k| rot(*a, k) == *b), "{a:?} vs {b:?}");
        }
    }
}

#[test]
fn a_mobius_strip_is_not_orientable_and_says_where() {
    let (p, f) = mobius(8);
    // validation sees an orientation conflict; repair sees that none can fix it
    assert!(matches!(
        TriMesh::try_new(p.clone(), f.clone()).unwrap_err(),
        MeshError::InconsistentOrientation { .. }
    ));
    match repair(&p, &f, &RepairOptions::DEFAULT).unwrap_err() {
        MeshError::NonOrientable { face, other, a, b } => {
            assert!(face < f.len() && other < f.len() && face != other);
            // a, b is an edge of both faces
            for t in [f[face], f[other]] {
                assert!(t.contains(&a) && t.contains(&b), "{t:?} {a} {b}");
            }
            let msg = repair(&p, &f, &RepairOptions::DEFAULT)
                .unwrap_err()
                .to_string();
            assert!(msg.contains("not orientable") && msg.contains(&format!("face {face}")));
        }
        e => panic!("unexpected {e:?}"),
    }
    // without orienting, the strip passes the repair (and fails validation as before)
    let r = repair(&p, &f, &RepairOptions::DEFAULT.with_orient(false)).unwrap();
    assert!(!r.log.changed());
}

#[test]
fn defects_repair_cannot_touch_name_input_elements() {
    let (p, f) = grid(2);
    // preconditions: input numbering
    let mut g = f.clone();
    g[5][1] = 99;
    assert_eq!(
        repair(&p, &g, &RepairOptions::DEFAULT).unwrap_err(),
        MeshError::IndexOutOfRange {
            face: 5,
            index: 99,
            vertex_count: 9
        }
    );
    let mut g = f.clone();
    g[3] = [4, 4, 5];
    assert_eq!(
        repair(&p, &g, &RepairOptions::DEFAULT).unwrap_err(),
        MeshError::RepeatedVertexInFace { face: 3, vertex: 4 }
    );
    assert_eq!(
        repair(&[], &[], &RepairOptions::DEFAULT).unwrap_err(),
        MeshError::NoVertices
    );
    assert_eq!(
        repair(&p, &[], &RepairOptions::DEFAULT).unwrap_err(),
        MeshError::NoFaces { vertices: 9 }
    );

    // a NaN vertex and a degenerate face survive the repair; validation names them in
    // repaired numbering and the log renames them to the input's
    let mut q = p.clone();
    q.insert(0, [1.0, 2.0, 3.0]); // unreferenced: dropped, so numbers shift by one
    let mut g: Vec<[u32; 3]> = f.iter().map(|t| t.map(|v| v + 1)).collect();
    g.insert(0, g[0]); // duplicate: dropped, so faces shift by one
    q[6][2] = f64::NAN; // input vertex 6 = repaired vertex 5
    let r = repair(&q, &g, &RepairOptions::DEFAULT).unwrap();
    let e = TriMesh::try_new(r.positions.clone(), r.faces.clone()).unwrap_err();
    assert!(matches!(
        e,
        MeshError::NonFiniteCoordinate { vertex: 5, .. }
    ));
    assert!(matches!(
        r.log.to_input_error(e),
        MeshError::NonFiniteCoordinate { vertex: 6, .. }
    ));
    q[6][2] = 0.0;
    // collapse edge (4, 7) of the grid (input vertices 5, 8): its faces are grid faces 4
    // and 7, repaired faces 4 and 7, input faces 5 and 8 (after the duplicate at 0)
    q[8] = q[5];
    let r = repair(&q, &g, &RepairOptions::DEFAULT).unwrap();
    let e = TriMesh::try_new(r.positions.clone(), r.faces.clone()).unwrap_err();
    assert!(matches!(e, MeshError::ZeroAreaFace { face: 4, .. }));
    assert!(matches!(
        r.log.to_input_error(e),
        MeshError::ZeroAreaFace { face: 5, .. }
    ));
}
