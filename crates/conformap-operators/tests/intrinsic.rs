//! The intrinsic Delaunay triangulation and its Laplacian, checked against exact facts.

use conformap_mesh::{TriMesh, NO_HALFEDGE};
use conformap_operators::{
    cotan_laplacian, intrinsic_delaunay_laplacian, intrinsic_delaunay_laplacian_with,
    quadratic_form, surface_area, IntrinsicOptions, IntrinsicTriangulation, OperatorError,
};
use num_complex::Complex64;
use sprs::CsMat;

/// A triangular lattice (`n × n` rhombi, each split along its short diagonal) with a
/// deterministic jitter of `jitter` edge lengths, optionally lifted onto a bump.
fn lattice(n: u32, jitter: f64, bump: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (fi, fj) = (f64::from(i), f64::from(j));
            let jx = jitter * ((i * 7 + j * 3) as f64).sin();
            let jy = jitter * ((i * 5 + j * 11) as f64).cos();
            let x = fi + 0.5 * fj + jx;
            let y = fj * 3f64.sqrt() / 2.0 + jy;
            let z = bump * (0.7 * x).sin() * (0.9 * y).cos();
            p.push([x, y, z]);
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut f = Vec::new();
    for j in 0..n {
        for i in 0..n {
            // rhombus (i,j) (i+1,j) (i+1,j+1) (i,j+1); short diagonal (i+1,j)-(i,j+1)
            f.push([id(i, j), id(i + 1, j), id(i, j + 1)]);
            f.push([id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    (p, f)
}

fn mesh(p: Vec<[f64; 3]>, f: Vec<[u32; 3]>) -> TriMesh {
    TriMesh::try_new(p, f).expect("valid test mesh")
}

fn identity_map(m: &TriMesh) -> Vec<Complex64> {
    m.positions()
        .iter()
        .map(|p| Complex64::new(p[0], p[1]))
        .collect()
}

fn max_abs_diff(a: &CsMat<f64>, b: &CsMat<f64>) -> f64 {
    let mut d: f64 = 0.0;
    for (v, (i, j)) in a.iter() {
        d = d.max((v - b.get(i, j).copied().unwrap_or(0.0)).abs());
    }
    for (v, (i, j)) in b.iter() {
        d = d.max((v - a.get(i, j).copied().unwrap_or(0.0)).abs());
    }
    d
}

/// Interior vertices' columns have no positive off-diagonal entry (no negative weight).
fn assert_interior_rows_m_matrix(m: &TriMesh, l: &CsMat<f64>) {
    for (j, col) in l.outer_iterator().enumerate() {
        if m.is_boundary_vertex(j) {
            continue;
        }
        for (i, &v) in col.iter() {
            assert!(
                i == j || v <= 0.0,
                "L[{i},{j}] = {v} > 0 at an interior vertex"
            );
        }
    }
}

#[test]
fn delaunay_mesh_is_left_alone() {
    let (p, f) = lattice(8, 0.05, 0.0);
    let m = mesh(p, f);
    let (l, stats) = intrinsic_delaunay_laplacian(&m).unwrap();
    assert_eq!(stats.non_delaunay_before, 0);
    assert_eq!(stats.flips, 0);
    assert_eq!(stats.non_delaunay_after, 0);
    let plain = cotan_laplacian(&m);
    // same pattern and the same bits: unflipped faces keep their positional cotangents
    assert_eq!(l.indptr(), plain.indptr());
    assert_eq!(l.indices(), plain.indices());
    assert_eq!(l.data(), plain.data());
}

#[test]
fn one_non_delaunay_quad_gets_exactly_that_flip() {
    // the lattice with one interior rhombus split along its long diagonal instead:
    // opposite angles 120° + 120° > 180°
    let (p, mut f) = lattice(6, 0.0, 0.0);
    let reference = mesh(p.clone(), f.clone());
    let id = |i: u32, j: u32| j * 7 + i;
    let (i, j) = (2, 3);
    let k = 2 * (j * 6 + i) as usize;
    f[k] = [id(i, j), id(i + 1, j), id(i + 1, j + 1)];
    f[k + 1] = [id(i, j), id(i + 1, j + 1), id(i, j + 1)];
    let m = mesh(p, f);
    assert!(cotan_laplacian(&m)
        .get(id(i, j) as usize, id(i + 1, j + 1) as usize)
        .is_some_and(|&v| v > 0.0));
    let mut tri = IntrinsicTriangulation::from_mesh(&m);
    let stats = tri.flip_to_delaunay(&IntrinsicOptions::DEFAULT).unwrap();
    assert_eq!(
        (
            stats.non_delaunay_before,
            stats.flips,
            stats.non_delaunay_after
        ),
        (1, 1, 0)
    );
    // the short diagonal is back, with unit length
    let short = (id(i + 1, j), id(i, j + 1));
    let lens = tri.halfedge_lengths();
    let found: Vec<f64> = (0..lens.len())
        .filter(|&h| {
            let t = tri.faces()[h / 3];
            (t[h % 3], t[(h % 3 + 1) % 3]) == short
        })
        .map(|h| lens[h])
        .collect();
    assert_eq!(found.len(), 1);
    assert!((found[0] - 1.0).abs() < 1e-14);
    // and the Laplacian is the lattice's
    let (l, _) = intrinsic_delaunay_laplacian(&m).unwrap();
    assert!(max_abs_diff(&l, &cotan_laplacian(&reference)) < 1e-14);
}

#[test]
fn flips_remove_every_negative_interior_weight_and_keep_the_area() {
    // strong jitter on a bump: many obtuse pairs
    let (p, f) = lattice(24, 0.33, 2.0);
    let m = mesh(p, f);
    let mut tri = IntrinsicTriangulation::from_mesh(&m);
    let stats = tri.flip_to_delaunay(&IntrinsicOptions::DEFAULT).unwrap();
    assert!(stats.non_delaunay_before > 20, "{stats:?}");
    assert!(stats.flips >= stats.non_delaunay_before);
    assert_eq!(stats.non_delaunay_after, 0);
    assert!(stats.min_weight_before < 0.0);
    assert!(stats.min_weight_after >= -0.5 * IntrinsicOptions::DEFAULT.delaunay_tol);
    // every interior edge is Delaunay, every triangle has positive area
    let twin = tri.opposite_halfedges();
    for h in 0..twin.len() {
        if twin[h] != NO_HALFEDGE {
            assert!(
                tri.edge_weight(h) >= -1e-12,
                "edge {h}: {}",
                tri.edge_weight(h)
            );
            assert_eq!(
                tri.halfedge_lengths()[h],
                tri.halfedge_lengths()[twin[h] as usize]
            );
        }
    }
    assert!(tri.face_areas().iter().all(|&a| a > 0.0));
    let area = surface_area(&m);
    assert!((tri.total_area() - area).abs() <= 1e-12 * area);
    let (l, _) = intrinsic_delaunay_laplacian(&m).unwrap();
    assert_interior_rows_m_matrix(&m, &l);
    // still a Laplacian: symmetric, zero row sums
    let scale = l.diag().data().iter().copied().fold(0.0, f64::max);
    let ones = vec![Complex64::new(1.0, 0.0); m.num_vertices()];
    assert!(quadratic_form(&l, &ones).abs() < 1e-12 * scale);
    let lt = l.transpose_view().to_csc();
    assert!(max_abs_diff(&l, &lt) <= 1e-15 * scale);
}

#[test]
fn planar_identity_and_affine_maps_keep_their_energy() {
    // a flat non-Delaunay mesh: every triangulation of it carries the same linear maps
    let (p, f) = lattice(20, 0.33, 0.0);
    let m = mesh(p, f);
    let (l, stats) = intrinsic_delaunay_laplacian(&m).unwrap();
    assert!(stats.flips > 10, "{stats:?}");
    let plain = cotan_laplacian(&m);
    let z = identity_map(&m);
    let area = surface_area(&m);
    assert!((quadratic_form(&l, &z) - area).abs() < 1e-12 * area);
    assert!((quadratic_form(&plain, &z) - area).abs() < 1e-12 * area);
    let (a, b) = (Complex64::new(0.7, 0.4), Complex64::new(-0.3, 0.2));
    let g: Vec<Complex64> = z.iter().map(|&w| a * w + b * w.conj()).collect();
    let expected = (a.norm_sqr() + b.norm_sqr()) * area;
    assert!((quadratic_form(&l, &g) - expected).abs() < 1e-12 * expected);
}

#[test]
fn delaunay_minimizes_the_dirichlet_energy_of_any_data() {
    // Rippa (1990) in the plane, Bobenko & Springborn (2007) intrinsically: the Delaunay
    // triangulation has the least Dirichlet energy for every vertex function
    for bump in [0.0, 1.5] {
        let (p, f) = lattice(16, 0.3, bump);
        let m = mesh(p, f);
        let (l, _) = intrinsic_delaunay_laplacian(&m).unwrap();
        let plain = cotan_laplacian(&m);
        for seed in 0..5u32 {
            let g: Vec<Complex64> = (0..m.num_vertices())
                .map(|k| {
                    let x = (k as f64 * 0.37 + f64::from(seed)).sin() * 1e3;
                    Complex64::new(x.fract(), (x * 1.7).cos())
                })
                .collect();
            let (ei, ee) = (quadratic_form(&l, &g), quadratic_form(&plain, &g));
            assert!(
                ei <= ee * (1.0 + 1e-12),
                "bump {bump} seed {seed}: {ei} > {ee}"
            );
        }
    }
}

#[test]
fn options_are_checked_and_the_flip_budget_is_enforced() {
    let (p, f) = lattice(10, 0.33, 0.0);
    let m = mesh(p, f);
    let bad = IntrinsicOptions::DEFAULT.with_delaunay_tol(f64::NAN);
    assert!(matches!(
        intrinsic_delaunay_laplacian_with(&m, &bad),
        Err(OperatorError::InvalidOption { .. })
    ));
    let none = IntrinsicOptions::DEFAULT.with_max_flips_per_edge(0);
    assert!(matches!(
        intrinsic_delaunay_laplacian_with(&m, &none),
        Err(OperatorError::FlipLimit { flips: 0, .. })
    ));
}
