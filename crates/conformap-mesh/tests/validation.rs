//! Every defect class of `TriMesh::try_new` is reported with the element it concerns.

use conformap_mesh::{fill_holes, MeshError, Topology, TriMesh};
use conformap_testkit::grid_faces;

fn square() -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    (
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 2, 3]],
    )
}

/// A grid of `n × n` squares (two triangles each), consistently oriented.
fn grid(n: u32) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            p.push([f64::from(i), f64::from(j), 0.0]);
        }
    }
    (p, grid_faces(n as usize, n as usize))
}

#[test]
fn valid_square_is_a_disk_with_ccw_boundary() {
    let (p, f) = square();
    let m = TriMesh::try_new(p, f).unwrap();
    assert_eq!(m.topology(), Topology::Disk);
    assert_eq!(m.num_edges(), 5);
    assert_eq!(m.euler_characteristic(), 1);
    assert_eq!(m.boundary_loops(), &[vec![0, 1, 2, 3]]);
    assert!(m.well_conditioned().connected);
}

#[test]
fn empty_and_faceless() {
    assert_eq!(
        TriMesh::try_new(vec![], vec![]).unwrap_err(),
        MeshError::NoVertices
    );
    assert_eq!(
        TriMesh::try_new(vec![[0.0; 3]], vec![]).unwrap_err(),
        MeshError::NoFaces { vertices: 1 }
    );
}

#[test]
fn non_finite_coordinate_names_vertex_and_axis() {
    let (mut p, f) = square();
    p[2][1] = f64::NAN;
    match TriMesh::try_new(p, f).unwrap_err() {
        MeshError::NonFiniteCoordinate {
            vertex: 2,
            axis: 'y',
            value,
        } => assert!(value.is_nan()),
        e => panic!("unexpected {e:?}"),
    }
    let (mut p, f) = square();
    p[3][2] = f64::INFINITY;
    assert!(matches!(
        TriMesh::try_new(p, f).unwrap_err(),
        MeshError::NonFiniteCoordinate {
            vertex: 3,
            axis: 'z',
            ..
        }
    ));
}

#[test]
fn index_out_of_range_names_face() {
    let (p, mut f) = square();
    f[1][2] = 7;
    assert_eq!(
        TriMesh::try_new(p, f).unwrap_err(),
        MeshError::IndexOutOfRange {
            face: 1,
            index: 7,
            vertex_count: 4
        }
    );
}

#[test]
fn repeated_index_and_zero_area() {
    let (p, mut f) = square();
    f[1] = [0, 2, 2];
    assert_eq!(
        TriMesh::try_new(p, f).unwrap_err(),
        MeshError::RepeatedVertexInFace { face: 1, vertex: 2 }
    );
    // collinear triangle
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let f = vec![[0, 1, 3], [0, 1, 2]];
    assert!(matches!(
        TriMesh::try_new(p, f).unwrap_err(),
        MeshError::ZeroAreaFace { face: 1, .. }
    ));
}

#[test]
fn duplicate_face_names_both() {
    let (p, mut f) = square();
    f.push([2, 0, 1]); // same vertex set as face 0, rotated
    assert_eq!(
        TriMesh::try_new(p, f).unwrap_err(),
        MeshError::DuplicateFace { face: 2, first: 0 }
    );
}

/// A copy turned over (the same vertex set, the other orientation) matches every edge of
/// the face it copies: found from the matching, the same error as a copy in the same
/// orientation, with the earliest such pair named.
#[test]
fn duplicate_face_turned_over_names_both() {
    // two triangles glued along all three edges (a closed two-face surface) ...
    let p = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    assert_eq!(
        TriMesh::try_new(p.clone(), vec![[0, 1, 2], [0, 2, 1]]).unwrap_err(),
        MeshError::DuplicateFace { face: 1, first: 0 }
    );
    // ... and a turned-over copy of a face of a larger mesh (the edge it shares with face
    // 0 then has three faces, an edge error, which the duplicate still outranks)
    let (p, mut f) = square();
    f.push([f[1][0], f[1][2], f[1][1]]);
    assert_eq!(
        TriMesh::try_new(p, f).unwrap_err(),
        MeshError::DuplicateFace { face: 2, first: 1 }
    );
}

#[test]
fn unreferenced_vertex_is_counted() {
    let (mut p, f) = square();
    p.push([5.0, 5.0, 0.0]);
    p.push([6.0, 5.0, 0.0]);
    assert_eq!(
        TriMesh::try_new(p, f).unwrap_err(),
        MeshError::UnreferencedVertex {
            vertex: 4,
            count: 2
        }
    );
}

#[test]
fn non_manifold_edge_names_edge_and_faces() {
    let (mut p, mut f) = square();
    p.push([0.5, 0.5, 1.0]);
    f.push([0, 2, 4]); // third face on edge (0, 2)
    match TriMesh::try_new(p, f).unwrap_err() {
        MeshError::NonManifoldEdge {
            a: 0,
            b: 2,
            count: 3,
            faces,
        } => {
            assert_eq!(faces, vec![0, 1, 2]);
        }
        e => panic!("unexpected {e:?}"),
    }
}

#[test]
fn inconsistent_orientation_names_faces_and_edge() {
    let (p, mut f) = square();
    f[1] = [0, 3, 2]; // flipped: traverses edge 0→2 like face 0 does... as 2→0? check: face 0 has 2→0
    match TriMesh::try_new(p, f).unwrap_err() {
        MeshError::InconsistentOrientation {
            face: 1,
            other: 0,
            a,
            b,
        } => {
            assert_eq!((a.min(b), a.max(b)), (0, 2));
        }
        e => panic!("unexpected {e:?}"),
    }
}

#[test]
fn bowtie_vertex_is_non_manifold() {
    // two triangles sharing only vertex 0
    let p = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [-1.0, -1.0, 0.0],
    ];
    let f = vec![[0, 1, 2], [0, 3, 4]];
    assert_eq!(
        TriMesh::try_new(p, f).unwrap_err(),
        MeshError::NonManifoldVertex {
            vertex: 0,
            faces: 2
        }
    );
}

#[test]
fn grid_topology_and_hole_filling() {
    let (p, f) = grid(4);
    let m = TriMesh::try_new(p, f).unwrap();
    assert_eq!(m.topology(), Topology::Disk);
    assert_eq!(m.boundary_loops()[0].len(), 16);
    assert_eq!(m.genus(), Some(0));
    // CEM Definition 1 (iv) fails at the two corners whose only neighbours are boundary
    let wc = m.well_conditioned();
    assert!(wc.connected && wc.interior_connected && wc.boundary_connected);
    assert_eq!(wc.boundary_vertices_without_interior_neighbor, vec![4, 20]);
    let adj = m.vertex_adjacency();
    assert_eq!(
        adj.neighbors_of(6),
        &[1, 5, 7, 11, 12, 0]
            .iter()
            .copied()
            .collect::<std::collections::BTreeSet<u32>>()
            .into_iter()
            .collect::<Vec<_>>()[..]
    );
    // closing the one loop of a flat grid puts the centroid inside the plane: still valid
    let filled = fill_holes(&m, &[0]).unwrap();
    assert_eq!(filled.mesh.topology(), Topology::Sphere);
    assert_eq!(filled.original_vertices, 25);
    assert_eq!(filled.mesh.num_faces(), m.num_faces() + 16);
    assert_eq!(&filled.mesh.faces()[..m.num_faces()], m.faces());
}

#[test]
fn two_components_and_annulus() {
    let (p, f) = square();
    let mut p2 = p.clone();
    p2.extend(p.iter().map(|q| [q[0] + 3.0, q[1], q[2]]));
    let mut f2 = f.clone();
    f2.extend(f.iter().map(|t| [t[0] + 4, t[1] + 4, t[2] + 4]));
    let m = TriMesh::try_new(p2, f2).unwrap();
    assert_eq!(m.topology(), Topology::SeveralComponents { components: 2 });
    assert_eq!(m.genus(), None);

    // grid with the middle square removed: an annulus
    let (p, mut f) = grid(5);
    // middle square (2,2) has faces 2*(2*5+2) and +1
    f.drain(24..26);
    let m = TriMesh::try_new(p, f).unwrap();
    assert_eq!(m.topology(), Topology::MultiplyConnected { boundaries: 2 });
    assert_eq!(m.longest_boundary_loop(), Some(0));
    assert_eq!(m.boundary_loops()[1].len(), 4);
    let wc = m.well_conditioned();
    assert!(!wc.boundary_connected);
}

/// The first defect face by face wins, whichever check finds it: a degenerate face before
/// a bad index, a bad index before a degenerate face, a degenerate face before a duplicate
/// and before a non-manifold edge (the checks run in parallel once the indices are valid).
#[test]
fn the_first_defect_face_by_face_is_reported() {
    let (mut p, f) = grid(3);
    // vertex 10 onto the line through 5 and 6: face 8 = [5, 6, 10] loses its area
    assert_eq!(f[8], [5, 6, 10]);
    p[10] = [2.5, 1.0, 0.0];
    let first = 8;
    assert!(matches!(
        TriMesh::try_new(p.clone(), f.clone()).unwrap_err(),
        MeshError::ZeroAreaFace { face: 8, .. }
    ));
    // a bad index after the degenerate face: the degenerate face is reported
    let mut late = f.clone();
    late[first + 1][0] = 99;
    assert!(matches!(
        TriMesh::try_new(p.clone(), late).unwrap_err(),
        MeshError::ZeroAreaFace { face, .. } if face == first
    ));
    // a bad index before it: the index is reported
    let mut early = f.clone();
    early[first - 1][0] = 99;
    assert!(matches!(
        TriMesh::try_new(p.clone(), early).unwrap_err(),
        MeshError::IndexOutOfRange { face, index: 99, .. } if face == first - 1
    ));
    // a duplicate face and a non-manifold edge rank after the degenerate face
    let mut dup = f.clone();
    dup.push(f[0]);
    assert!(matches!(
        TriMesh::try_new(p.clone(), dup).unwrap_err(),
        MeshError::ZeroAreaFace { face, .. } if face == first
    ));
    // with the geometry repaired the duplicate is found
    let (good, _) = grid(3);
    let mut dup = f.clone();
    dup.push(f[0]);
    assert!(matches!(
        TriMesh::try_new(good, dup).unwrap_err(),
        MeshError::DuplicateFace { .. }
    ));
}

/// The faces `ids` of `(p, f)` with their vertices renumbered in order of first use: the
/// vertices kept, their positions, the faces.
#[allow(clippy::type_complexity)]
fn renumbered(
    p: &[[f64; 3]],
    f: &[[u32; 3]],
    ids: &[u32],
) -> (Vec<u32>, Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut local = vec![u32::MAX; p.len()];
    let mut vertices = Vec::new();
    let tris = ids
        .iter()
        .map(|&k| {
            f[k as usize].map(|v| {
                if local[v as usize] == u32::MAX {
                    local[v as usize] = vertices.len() as u32;
                    vertices.push(v);
                }
                local[v as usize]
            })
        })
        .collect();
    let points = vertices.iter().map(|&v| p[v as usize]).collect();
    (vertices, points, tris)
}

/// `sub_mesh` is `try_new` on the same faces (renumbered in order of first use), without
/// the checks the whole passed: the same mesh where the subset is valid, the same error
/// where a vertex's faces split into two fans, on random subsets of a grid.
#[test]
fn a_sub_mesh_is_the_mesh_of_its_faces() {
    let (p, f) = grid(8);
    let whole = TriMesh::try_new(p.clone(), f.clone()).expect("grid");
    let mut rng = conformap_testkit::XorShift64Star(0x5eed);
    let (mut valid, mut pinched) = (0, 0);
    for trial in 0..200 {
        // a random share of the faces, in a shuffled order
        let keep = 1 + trial % 10;
        let mut faces: Vec<u32> = (0..f.len() as u32)
            .filter(|_| rng.next_u64() % 10 < keep as u64)
            .collect();
        for i in (1..faces.len()).rev() {
            faces.swap(i, (rng.next_u64() % (i as u64 + 1)) as usize);
        }
        if faces.is_empty() {
            continue;
        }
        let (vertices, points, tris) = renumbered(&p, &f, &faces);
        match (TriMesh::try_new(points, tris), whole.sub_mesh(&faces)) {
            (Ok(a), Ok((b, kept))) => {
                assert_eq!(kept, vertices);
                assert_eq!(a.faces(), b.faces());
                assert_eq!(a.positions(), b.positions());
                assert_eq!(a.opposite_halfedges(), b.opposite_halfedges());
                assert_eq!(a.boundary_loops(), b.boundary_loops());
                assert_eq!(a.num_components(), b.num_components());
                assert_eq!(a.num_edges(), b.num_edges());
                valid += 1;
            }
            (Err(a), Err(b)) => {
                assert_eq!(a, b, "trial {trial}");
                pinched += 1;
            }
            (a, b) => panic!("trial {trial}: try_new {a:?}, sub_mesh {b:?}"),
        }
    }
    // both outcomes seen
    assert!(
        valid > 20 && pinched > 20,
        "{valid} valid, {pinched} pinched"
    );
    // a face listed twice and no face at all: the errors `try_new` gives
    let twice = [3u32, 7, 3];
    let (_, points, tris) = renumbered(&p, &f, &twice);
    let expected = TriMesh::try_new(points, tris).expect_err("a face twice");
    assert_eq!(whole.sub_mesh(&twice).expect_err("a face twice"), expected);
    assert_eq!(
        whole.sub_mesh(&[]).expect_err("no face"),
        TriMesh::try_new(Vec::new(), Vec::new()).expect_err("no face")
    );
}
