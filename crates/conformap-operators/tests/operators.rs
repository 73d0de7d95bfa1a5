//! Laplacian assembly, blocks and the Cholesky facade, checked with numbers.

use conformap_mesh::TriMesh;
use conformap_operators::{
    cotan_laplacian, interior_pattern, mul_complex, quadratic_form, relative_residual,
    surface_area, Cholesky, CholeskyOptions, LaplacianBlocks, LuSolver, OperatorError, Ordering,
    Partition,
};
use num_complex::Complex64;

/// A jittered planar grid lifted onto a bump, `n × n` squares.
fn bumpy_grid(n: u32, planar: bool) -> TriMesh {
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (f64::from(i) / f64::from(n), f64::from(j) / f64::from(n));
            // deterministic jitter keeps the grid valid but irregular
            let jx = 0.2 / f64::from(n) * ((i * 7 + j * 3) as f64).sin();
            let jy = 0.2 / f64::from(n) * ((i * 5 + j * 11) as f64).cos();
            let z = if planar {
                0.0
            } else {
                0.3 * (3.0 * x).sin() * (2.0 * y).cos()
            };
            p.push([x + jx, y + jy, z]);
        }
    }
    let f = conformap_testkit::grid_faces(n as usize, n as usize);
    TriMesh::try_new(p, f).expect("valid grid")
}

/// The connectivity-only pattern is exactly `L_II`'s, its analysis factors `L_II` to the
/// same solution as a plain factorization, and a matrix of another pattern is refused.
#[test]
fn analysis_of_the_interior_pattern_factors_l_ii() {
    let (m, _, part, blocks) = grid_blocks(10);
    let pattern = interior_pattern(&m, &part);
    assert_eq!(
        pattern.indptr().raw_storage(),
        blocks.ii.indptr().raw_storage()
    );
    assert_eq!(pattern.indices(), blocks.ii.indices());
    let analysed = Cholesky::analyse_with(&pattern, &CholeskyOptions::DEFAULT).expect("analyse");
    assert!(analysed.analyse_ms() >= 0.0);
    let chol = analysed.factor(&blocks.ii).expect("factor");
    let plain = Cholesky::factor(&blocks.ii).expect("factor");
    let n = blocks.ii.rows();
    let b: Vec<f64> = (0..n).map(|k| (k as f64 * 0.7).sin()).collect();
    let (mut x, mut y) = (b.clone(), b.clone());
    chol.solve_in_place(&mut x, 1);
    plain.solve_in_place(&mut y, 1);
    for (a, c) in x.iter().zip(&y) {
        assert!((a - c).abs() <= 1e-13 * c.abs().max(1.0), "{a} vs {c}");
    }
    // another pattern: the block of a coarser grid
    let (_, _, _, bo) = grid_blocks(9);
    let analysed = Cholesky::analyse_with(&pattern, &CholeskyOptions::DEFAULT).expect("analyse");
    assert!(matches!(
        analysed.factor(&bo.ii),
        Err(OperatorError::PatternMismatch)
    ));
}

/// The bumpy grid of `n × n` squares with its cotangent Laplacian, the interior/boundary
/// partition along its boundary loop, and the blocks of CEM Eq. 9.
fn grid_blocks(n: u32) -> (TriMesh, sprs::CsMat<f64>, Partition, LaplacianBlocks) {
    let m = bumpy_grid(n, false);
    let l = cotan_laplacian(&m);
    let part = Partition::new(m.num_vertices(), &m.boundary_loops()[0]);
    let blocks = LaplacianBlocks::new(&l, &part);
    (m, l, part, blocks)
}

#[test]
fn laplacian_is_symmetric_with_zero_row_sums() {
    let m = bumpy_grid(12, false);
    let l = cotan_laplacian(&m);
    let scale = l.diag().data().iter().copied().fold(0.0, f64::max);
    let ones = vec![Complex64::new(1.0, 0.0); m.num_vertices()];
    let r = mul_complex(&l, &ones);
    assert!(r.iter().all(|z| z.norm() < 1e-13 * scale));
    let t = l.transpose_view().to_csc();
    for (a, b) in l.data().iter().zip(t.data()) {
        assert!((a - b).abs() <= 1e-15 * scale);
    }
}

#[test]
fn dirichlet_energy_of_identity_is_area_and_of_affine_map_is_known() {
    let m = bumpy_grid(10, true);
    let l = cotan_laplacian(&m);
    let area = surface_area(&m);
    let z: Vec<Complex64> = m
        .positions()
        .iter()
        .map(|p| Complex64::new(p[0], p[1]))
        .collect();
    assert!((quadratic_form(&l, &z) - area).abs() < 1e-13 * area);
    // f = a z + b z̄ : E_D = (|a|² + |b|²) area
    let (a, b) = (Complex64::new(1.3, -0.4), Complex64::new(0.2, 0.1));
    let f: Vec<Complex64> = z.iter().map(|&w| a * w + b * w.conj()).collect();
    let expected = (a.norm_sqr() + b.norm_sqr()) * area;
    assert!((quadratic_form(&l, &f) - expected).abs() < 1e-12 * expected);
}

/// Right-hand sides with a few non-zeros (one vertex; the boundary's interior neighbours,
/// as in the harmonic extension) are solved to round-off with every ordering: the forward
/// solve skips the supernodes they never reach.
#[test]
fn sparse_right_hand_sides_solve_to_round_off() {
    let (_, _, part, blocks) = grid_blocks(24);
    let n = blocks.ii.rows();
    let fb: Vec<Complex64> = (0..part.boundary.len())
        .map(|k| Complex64::from_polar(1.0, 0.1 * k as f64))
        .collect();
    let near_boundary: Vec<Complex64> = blocks.ib_mul(&fb).iter().map(|z| -z).collect();
    let mut single = vec![Complex64::new(0.0, 0.0); n];
    single[n / 3] = Complex64::new(1.0, -2.0);
    for ordering in [
        Ordering::Amd,
        Ordering::NestedDissection,
        Ordering::Identity,
    ] {
        let chol = Cholesky::factor_with(
            &blocks.ii,
            &CholeskyOptions::DEFAULT.with_ordering(ordering),
        )
        .expect("factor");
        for b in [&near_boundary, &single] {
            let x = chol.solve_complex(b);
            let r = relative_residual(&blocks.ii, &x, b);
            assert!(r < 1e-13, "residual {r}");
        }
    }
}

#[test]
fn blocks_reassemble_the_laplacian_action() {
    let (m, l, part, blocks) = grid_blocks(8);
    let f: Vec<Complex64> = (0..m.num_vertices())
        .map(|k| Complex64::new((k as f64).sin(), (k as f64 * 0.3).cos()))
        .collect();
    let lf = mul_complex(&l, &f);
    let (fi, fb) = (part.interior_values(&f), part.boundary_values(&f));
    let top: Vec<Complex64> = mul_complex(&blocks.ii, &fi)
        .iter()
        .zip(blocks.ib_mul(&fb))
        .map(|(a, b)| a + b)
        .collect();
    let bottom: Vec<Complex64> = blocks
        .bi_mul(&fi)
        .iter()
        .zip(mul_complex(&blocks.bb, &fb))
        .map(|(a, b)| a + b)
        .collect();
    for (k, &v) in part.interior.iter().enumerate() {
        assert!((top[k] - lf[v as usize]).norm() < 1e-12);
    }
    for (k, &v) in part.boundary.iter().enumerate() {
        assert!((bottom[k] - lf[v as usize]).norm() < 1e-12);
    }
    assert_eq!(part.assemble(&fi, &fb), f);
}

#[test]
fn cholesky_solves_interior_block_to_round_off_with_every_ordering() {
    let (_, _, _, blocks) = grid_blocks(20);
    let n = blocks.ii.rows();
    let b: Vec<Complex64> = (0..n)
        .map(|k| Complex64::new(1.0 + (k % 7) as f64, -(k as f64).sqrt()))
        .collect();
    let reversed: Vec<usize> = (0..n).rev().collect();
    for ordering in [
        Ordering::Amd,
        Ordering::Identity,
        Ordering::Custom(reversed),
    ] {
        let chol = Cholesky::factor_with(
            &blocks.ii,
            &CholeskyOptions::DEFAULT.with_ordering(ordering.clone()),
        )
        .unwrap_or_else(|e| panic!("{ordering:?}: {e}"));
        let x = chol.solve_complex(&b);
        assert!(relative_residual(&blocks.ii, &x, &b) < 1e-12);
        assert!(chol.stats().nnz_factor >= n);
    }
    // the permutation chosen by AMD, given back as a custom ordering, factors with the
    // same fill; the analysis alone reports it too
    let amd = CholeskyOptions::DEFAULT.with_ordering(Ordering::Amd);
    let chol = Cholesky::factor_with(&blocks.ii, &amd).unwrap();
    let perm = chol.permutation();
    let mut sorted = perm.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, (0..n).collect::<Vec<_>>());
    assert_eq!(
        Cholesky::analyse_with(&blocks.ii, &amd)
            .unwrap()
            .permutation(),
        perm
    );
    let again = Cholesky::factor_with(
        &blocks.ii,
        &CholeskyOptions::DEFAULT.with_ordering(Ordering::Custom(perm)),
    )
    .unwrap();
    assert_eq!(again.stats().nnz_factor, chol.stats().nnz_factor);
    assert!(relative_residual(&blocks.ii, &again.solve_complex(&b), &b) < 1e-12);
    // refactor with a scaled matrix reuses the analysis
    let mut chol = Cholesky::factor(&blocks.ii).unwrap();
    let scaled = blocks.ii.map(|v| 2.0 * v);
    chol.refactor(&scaled).unwrap();
    let x = chol.solve_complex(&b);
    assert!(relative_residual(&scaled, &x, &b) < 1e-12);
    // the boundary block solves with LU
    let lu = LuSolver::factor(&blocks.bb).unwrap();
    let bb: Vec<Complex64> = (0..blocks.bb.rows())
        .map(|k| Complex64::new(k as f64, 1.0))
        .collect();
    assert!(relative_residual(&blocks.bb, &lu.solve_complex(&bb), &bb) < 1e-12);
}

#[test]
fn indefinite_matrix_is_reported_with_a_pivot() {
    let m = bumpy_grid(4, false);
    let l = cotan_laplacian(&m);
    let negated = l.map(|v| -v);
    let err = Cholesky::factor(&negated).unwrap_err();
    assert!(
        matches!(
            err,
            conformap_operators::OperatorError::NotPositiveDefinite { .. }
        ),
        "{err:?}"
    );
    let bad = Cholesky::factor_with(
        &l,
        &CholeskyOptions::DEFAULT.with_ordering(Ordering::Custom(vec![0, 0])),
    );
    assert!(matches!(
        bad,
        Err(conformap_operators::OperatorError::BadPermutation { .. })
    ));
}

/// The column-wise assembly gives, bit for bit, what scattering every corner's weight into
/// the sorted pattern gives (the definition: `−½ cot` per corner on the opposite edge, the
/// diagonal its negated column sum in face order), on real meshes with and without
/// boundary, in their file's vertex order.
#[test]
fn column_assembly_equals_the_corner_scatter() {
    for name in ["woody.obj", "spot.obj", "punctured_torus.obj"] {
        let mesh = conformap_testkit::fixture_mesh(name);
        let l = cotan_laplacian(&mesh);
        let n = mesh.num_vertices();
        let mut dense: std::collections::BTreeMap<(usize, usize), f64> = Default::default();
        let cots = conformap_operators::corner_cotangents(&mesh);
        for (t, c) in mesh.faces().iter().zip(&cots) {
            for k in 0..3 {
                let (i, j) = (t[(k + 1) % 3] as usize, t[(k + 2) % 3] as usize);
                let w = 0.5 * c[k];
                *dense.entry((i, j)).or_default() -= w;
                *dense.entry((j, i)).or_default() -= w;
                *dense.entry((i, i)).or_default() += w;
                *dense.entry((j, j)).or_default() += w;
            }
        }
        assert_eq!(l.nnz(), dense.len(), "{name}");
        for (col, column) in l.outer_iterator().enumerate() {
            for (row, &v) in column.iter() {
                assert_eq!(
                    v.to_bits(),
                    dense[&(row, col)].to_bits(),
                    "{name} ({row}, {col})"
                );
            }
        }
        assert_eq!(l.rows(), n);
    }
}
