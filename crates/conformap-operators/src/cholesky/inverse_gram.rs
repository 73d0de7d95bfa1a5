//! `Rᵀ A⁻¹ R` for a factored sparse `A = P⁻¹ G Gᵀ P⁻ᵀ` and a sparse `R` with few non-zeros
//! per column, by one forward solve `W = G⁻¹ P R` restricted to the elimination-tree paths
//! of `R`'s non-zeros, then `Rᵀ A⁻¹ R = WᵀW`.
//!
//! With `A = L_II` and `R = L_IB` this is the update of the Schur complement
//! `L_BB − L_IBᵀ L_II⁻¹ L_IB` (CCEM Eq. 3.15): a column of `L_IB` is non-zero only at the
//! interior neighbours of one boundary vertex, so its forward solve touches only the
//! supernodes on their paths to the root of the elimination tree, and the backward solve
//! is not needed at all. The work is done supernode by supernode with dense kernels
//! (triangular solve, product, rank-`w` update) on exactly the columns of `R` whose paths
//! pass through the supernode; the rows of `W` of a supernode are dropped once they have
//! updated its ancestors and `WᵀW`, so `W` is never stored whole.

use faer::linalg::matmul::matmul;
use faer::linalg::matmul::triangular::{self, BlockStructure};
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::sparse::linalg::cholesky::{
    supernodal::SupernodalLltRef, SymbolicCholesky, SymbolicCholeskyRaw,
};
use faer::{Accum, MatMut, MatRef, Par};
use sprs::CsMat;

/// Dense work (multiply–adds) of one kernel call above which it runs on all threads of the
/// factorization (`CholeskyOptions::threads`); smaller calls run sequentially, where
/// faer's thread dispatch costs more than it saves (measured on 2 cores: break-even near
/// 10⁶).
const PARALLEL_WORK: usize = 1 << 21;

/// The result of [`crate::Cholesky::inverse_gram`].
#[derive(Debug, Clone, PartialEq)]
pub struct InverseGram {
    /// Number of columns `k` of `R`.
    pub dim: usize,
    /// `Rᵀ A⁻¹ R`, `k × k`, column-major, exactly symmetric.
    pub values: Vec<f64>,
    /// Entries of `W = G⁻¹ P R` computed (rows of the supernodes on the paths, times the
    /// columns of `R` reaching them).
    pub w_entries: usize,
    /// Supernodes (or columns, for a simplicial factor) the paths visited.
    pub panels_visited: usize,
    /// Supernodes (or columns) of the factor.
    pub panels: usize,
    /// Milliseconds spent.
    pub ms: f64,
}

impl InverseGram {
    /// Entry `(i, j)`.
    pub fn get(&self, i: usize, j: usize) -> f64 {
        self.values[j * self.dim + i]
    }
}

/// One diagonal block of the factor with the rows below it: columns
/// `start..start + width`, values `(width + pattern.len()) × width`, column-major, the
/// lower-triangular diagonal block on top.
struct Panel<'a> {
    start: usize,
    width: usize,
    pattern: &'a [usize],
    val: MatRef<'a, f64>,
}

/// The factor seen as a sequence of panels in elimination order (children before parents).
enum Panels<'a> {
    Supernodal(SupernodalLltRef<'a, usize, f64>),
    /// One panel per column; the diagonal entry first in each column.
    Simplicial {
        col_ptr: &'a [usize],
        row_idx: &'a [usize],
        values: &'a [f64],
    },
}

impl<'a> Panels<'a> {
    fn new(symbolic: &'a SymbolicCholesky<usize>, values: &'a [f64]) -> Self {
        match symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => {
                Self::Supernodal(SupernodalLltRef::new(s, values))
            }
            SymbolicCholeskyRaw::Simplicial(s) => Self::Simplicial {
                col_ptr: s.col_ptr(),
                row_idx: s.row_idx(),
                values,
            },
        }
    }

    fn len(&self) -> usize {
        match self {
            Self::Supernodal(f) => f.symbolic().n_supernodes(),
            Self::Simplicial { col_ptr, .. } => col_ptr.len() - 1,
        }
    }

    fn get(&self, p: usize) -> Panel<'a> {
        match *self {
            Self::Supernodal(f) => {
                let s = f.supernode(p);
                let val = s.val();
                Panel {
                    start: s.start(),
                    width: val.ncols(),
                    pattern: s.pattern(),
                    val,
                }
            }
            Self::Simplicial {
                col_ptr,
                row_idx,
                values,
            } => {
                let (a, b) = (col_ptr[p], col_ptr[p + 1]);
                Panel {
                    start: p,
                    width: 1,
                    pattern: &row_idx[a + 1..b],
                    val: MatRef::from_column_major_slice(&values[a..b], b - a, 1),
                }
            }
        }
    }
}

fn par_for(work: usize, par: Par) -> Par {
    if work >= PARALLEL_WORK {
        par
    } else {
        Par::Seq
    }
}

/// Which panels the columns of `R` reach: the symbolic half of [`inverse_gram`].
pub(super) struct Plan<'a> {
    panels: Panels<'a>,
    /// First column of every panel, and `n` at the end.
    start: Vec<usize>,
    /// `owner[row]` = the panel holding column `row` of the factor.
    owner: Vec<u32>,
    /// The entries of `R` by panel: (row within the panel, column, value).
    direct: Vec<Vec<(u32, u32, f64)>>,
    /// The columns of `R` whose paths pass through each panel, sorted.
    sets: Vec<Vec<u32>>,
}

impl<'a> Plan<'a> {
    /// Which panels each column of `r` reaches. `perm_inv[i]` is the position of row `i`
    /// of `A` in the elimination order; `r` must be CSC with `A`'s number of rows.
    pub(super) fn new(
        symbolic: &'a SymbolicCholesky<usize>,
        values: &'a [f64],
        perm_inv: &[usize],
        r: &CsMat<f64>,
    ) -> Self {
        let panels = Panels::new(symbolic, values);
        let np = panels.len();
        let mut owner = vec![0u32; perm_inv.len()];
        let mut start = Vec::with_capacity(np + 1);
        for p in 0..np {
            let panel = panels.get(p);
            start.push(panel.start);
            owner[panel.start..panel.start + panel.width].fill(p as u32);
        }
        start.push(perm_inv.len());
        let mut direct: Vec<Vec<(u32, u32, f64)>> = vec![Vec::new(); np];
        for (c, col) in r.outer_iterator().enumerate() {
            for (i, &v) in col.iter() {
                let row = perm_inv[i];
                let p = owner[row] as usize;
                direct[p].push(((row - start[p]) as u32, c as u32, v));
            }
        }
        // a panel is reached by its own columns and by its children's
        let mut sets: Vec<Vec<u32>> = vec![Vec::new(); np];
        for p in 0..np {
            let mut set = std::mem::take(&mut sets[p]);
            set.extend(direct[p].iter().map(|e| e.1));
            set.sort_unstable();
            set.dedup();
            if !set.is_empty() {
                if let Some(&first) = panels.get(p).pattern.first() {
                    let parent = owner[first] as usize;
                    sets[parent].extend_from_slice(&set);
                }
            }
            sets[p] = set;
        }
        Self {
            panels,
            start,
            owner,
            direct,
            sets,
        }
    }

    /// Multiply–adds of the numeric pass: per panel of width `w` reached by `m` columns
    /// with `p` rows below, `w²m/2` (triangular solve) + `wm²/2` (`WᵀW`) + `pwm` (update).
    pub(super) fn multiply_adds(&self) -> f64 {
        (0..self.panels.len())
            .filter(|&p| !self.sets[p].is_empty())
            .map(|p| {
                let panel = self.panels.get(p);
                let (w, m, pl) = (
                    panel.width as f64,
                    self.sets[p].len() as f64,
                    panel.pattern.len() as f64,
                );
                0.5 * w * w * m + 0.5 * w * m * m + pl * w * m
            })
            .sum()
    }
}

/// The lower triangle of `XᵀX` added to (`Accum::Add`) or written into (`Accum::Replace`)
/// `dst`.
fn lower_gram(dst: MatMut<'_, f64>, accum: Accum, x: MatRef<'_, f64>, par: Par) {
    triangular::matmul(
        dst,
        BlockStructure::TriangularLower,
        accum,
        x.transpose(),
        BlockStructure::Rectangular,
        x,
        BlockStructure::Rectangular,
        1.0,
        par,
    );
}

/// The multiply–adds of the numeric factorization (see `Cholesky::factor_cost`).
pub(super) fn factor_cost(symbolic: &SymbolicCholesky<usize>, values: &[f64]) -> f64 {
    let panels = Panels::new(symbolic, values);
    (0..panels.len())
        .map(|p| {
            let panel = panels.get(p);
            let (w, pl) = (panel.width as f64, panel.pattern.len() as f64);
            if matches!(panels, Panels::Simplicial { .. }) {
                0.5 * pl * pl + pl
            } else {
                w * w * w / 6.0 + 0.5 * w * w * pl + 0.5 * w * pl * pl
            }
        })
        .sum()
}

/// `Rᵀ A⁻¹ R` from the factor of `A` (see the module docs), `R` of `k` columns given by
/// its [`Plan`].
pub(super) fn inverse_gram(plan: Plan<'_>, k: usize, par: Par) -> InverseGram {
    let t0 = std::time::Instant::now();
    let Plan {
        panels,
        start,
        owner,
        direct,
        sets,
    } = plan;
    let np = panels.len();
    let mut gram = vec![0.0; k * k];
    // rows of W of panels not yet reached, allocated on their first update
    let mut pending: Vec<Vec<f64>> = vec![Vec::new(); np];
    let mut update: Vec<f64> = Vec::new();
    let mut local_gram: Vec<f64> = Vec::new();
    let mut positions: Vec<usize> = Vec::new();
    let (mut w_entries, mut visited) = (0usize, 0usize);
    for p in 0..np {
        let set = &sets[p];
        let m = set.len();
        if m == 0 {
            continue;
        }
        visited += 1;
        let panel = panels.get(p);
        let w = panel.width;
        let plen = panel.pattern.len();
        w_entries += w * m;
        let mut x = std::mem::take(&mut pending[p]);
        if x.is_empty() {
            x = vec![0.0; w * m];
        }
        for &(row, c, v) in &direct[p] {
            // `set` is sorted and holds every column with a direct entry
            if let Ok(j) = set.binary_search(&c) {
                x[j * w + row as usize] += v;
            }
        }
        let (top, bottom) = panel.val.split_at_row(w);
        {
            let xm = MatMut::from_column_major_slice_mut(&mut x, w, m);
            solve_lower_triangular_in_place(top, xm, par_for(w * w * m / 2, par));
        }
        let xr = MatRef::from_column_major_slice(&x, w, m);
        // WᵀW: this panel's rows
        let gram_par = par_for(w * m * m / 2, par);
        if m == k {
            // every column of R passes here (set = 0..k): straight into the result
            let dst = MatMut::from_column_major_slice_mut(&mut gram, k, k);
            lower_gram(dst, Accum::Add, xr, gram_par);
        } else {
            local_gram.clear();
            local_gram.resize(m * m, 0.0);
            let dst = MatMut::from_column_major_slice_mut(&mut local_gram, m, m);
            lower_gram(dst, Accum::Replace, xr, gram_par);
            for b in 0..m {
                let cb = set[b] as usize;
                let src = &local_gram[b * m..(b + 1) * m];
                let dst = &mut gram[cb * k..(cb + 1) * k];
                for a in b..m {
                    dst[set[a] as usize] += src[a];
                }
            }
        }
        if plen == 0 {
            continue;
        }
        // the update of the ancestors' rows: −L_{pattern, panel} X
        update.clear();
        update.resize(plen * m, 0.0);
        matmul(
            MatMut::from_column_major_slice_mut(&mut update, plen, m),
            Accum::Replace,
            bottom,
            xr,
            1.0,
            par_for(plen * w * m, par),
        );
        drop(x);
        // scatter, one run of rows per ancestor panel
        let mut idx = 0;
        while idx < plen {
            let t = owner[panel.pattern[idx]] as usize;
            let end = idx + panel.pattern[idx..].partition_point(|&row| row < start[t + 1]);
            let tset = &sets[t];
            let tw = start[t + 1] - start[t];
            positions.clear();
            let mut lo = 0;
            for &c in set {
                // set ⊆ tset, both sorted
                let j = lo + tset[lo..].partition_point(|&d| d < c);
                positions.push(j);
                lo = j + 1;
            }
            let target = &mut pending[t];
            if target.is_empty() {
                *target = vec![0.0; tw * tset.len()];
            }
            for (j, &pj) in positions.iter().enumerate() {
                let src = &update[j * plen..(j + 1) * plen];
                let dst = &mut target[pj * tw..(pj + 1) * tw];
                for q in idx..end {
                    dst[panel.pattern[q] - start[t]] -= src[q];
                }
            }
            idx = end;
        }
    }
    // mirror the lower triangle
    for j in 0..k {
        for i in (j + 1)..k {
            gram[i * k + j] = gram[j * k + i];
        }
    }
    InverseGram {
        dim: k,
        values: gram,
        w_entries,
        panels_visited: visited,
        panels: np,
        ms: t0.elapsed().as_secs_f64() * 1e3,
    }
}

/// `A⁻¹ rhs` in place (`ncols` columns, column-major) for the factor `A = P⁻¹ G Gᵀ P⁻ᵀ`,
/// with the forward solve skipping every panel whose rows of the right-hand side are
/// still exactly zero when it is reached (its solution there is zero and it updates
/// nothing): a right-hand side supported near the boundary, as in the harmonic extension
/// `−L_II⁻¹ L_IB f_B`, touches only the paths of its support to the root. Exact; the
/// backward solve is the full one.
pub(super) fn solve_skipping_zeros(
    symbolic: &SymbolicCholesky<usize>,
    values: &[f64],
    rhs: &mut [f64],
    ncols: usize,
) {
    let n = symbolic.nrows();
    let panels = Panels::new(symbolic, values);
    let mut x = vec![0.0; n * ncols];
    let perm = symbolic.perm().map(|p| p.arrays());
    for j in 0..ncols {
        let (src, dst) = (&rhs[j * n..(j + 1) * n], &mut x[j * n..(j + 1) * n]);
        match perm {
            Some((fwd, _)) => dst.iter_mut().zip(fwd).for_each(|(d, &f)| *d = src[f]),
            None => dst.copy_from_slice(src),
        }
    }
    let mut tmp: Vec<f64> = Vec::new();
    for p in 0..panels.len() {
        let panel = panels.get(p);
        let (w, start, plen) = (panel.width, panel.start, panel.pattern.len());
        let live = (0..ncols).any(|j| {
            x[j * n + start..j * n + start + w]
                .iter()
                .any(|&v| v != 0.0)
        });
        if !live {
            continue;
        }
        let (top, bottom) = panel.val.split_at_row(w);
        {
            let xm = MatMut::from_column_major_slice_mut(&mut x, n, ncols);
            solve_lower_triangular_in_place(top, xm.subrows_mut(start, w), Par::Seq);
        }
        if plen == 0 {
            continue;
        }
        tmp.clear();
        tmp.resize(plen * ncols, 0.0);
        {
            let xr = MatRef::from_column_major_slice(&x, n, ncols);
            matmul(
                MatMut::from_column_major_slice_mut(&mut tmp, plen, ncols),
                Accum::Replace,
                bottom,
                xr.subrows(start, w),
                1.0,
                Par::Seq,
            );
        }
        for j in 0..ncols {
            let col = &mut x[j * n..(j + 1) * n];
            for (&i, &t) in panel.pattern.iter().zip(&tmp[j * plen..(j + 1) * plen]) {
                col[i] -= t;
            }
        }
    }
    for p in (0..panels.len()).rev() {
        let panel = panels.get(p);
        let (w, start, plen) = (panel.width, panel.start, panel.pattern.len());
        let (top, bottom) = panel.val.split_at_row(w);
        if plen > 0 {
            tmp.clear();
            tmp.resize(plen * ncols, 0.0);
            for j in 0..ncols {
                let col = &x[j * n..(j + 1) * n];
                for (t, &i) in tmp[j * plen..(j + 1) * plen].iter_mut().zip(panel.pattern) {
                    *t = col[i];
                }
            }
            let xm = MatMut::from_column_major_slice_mut(&mut x, n, ncols);
            matmul(
                xm.subrows_mut(start, w),
                Accum::Add,
                bottom.transpose(),
                MatRef::from_column_major_slice(&tmp, plen, ncols),
                -1.0,
                Par::Seq,
            );
        }
        let xm = MatMut::from_column_major_slice_mut(&mut x, n, ncols);
        faer::linalg::triangular_solve::solve_upper_triangular_in_place(
            top.transpose(),
            xm.subrows_mut(start, w),
            Par::Seq,
        );
    }
    for j in 0..ncols {
        let (src, dst) = (&x[j * n..(j + 1) * n], &mut rhs[j * n..(j + 1) * n]);
        match perm {
            Some((_, inv)) => dst.iter_mut().zip(inv).for_each(|(d, &v)| *d = src[v]),
            None => dst.copy_from_slice(src),
        }
    }
}

#[cfg(test)]
mod tests {
    use sprs::TriMat;

    use crate::{Cholesky, CholeskyOptions, Ordering};

    /// The 5-point Laplacian of an `n × n` grid with a Dirichlet frame (SPD).
    fn grid(n: usize) -> sprs::CsMat<f64> {
        let id = |i: usize, j: usize| i * n + j;
        let mut t = TriMat::new((n * n, n * n));
        for i in 0..n {
            for j in 0..n {
                t.add_triplet(
                    id(i, j),
                    id(i, j),
                    4.0 + 1e-3 * ((i * 7 + j * 3) % 5) as f64,
                );
                for (a, b) in [(i + 1, j), (i, j + 1)] {
                    if a < n && b < n {
                        t.add_triplet(id(i, j), id(a, b), -1.0);
                        t.add_triplet(id(a, b), id(i, j), -1.0);
                    }
                }
            }
        }
        t.to_csc()
    }

    /// A sparse `R` whose column `c` touches the frame vertices near position `c`.
    fn frame_columns(n: usize, k: usize) -> sprs::CsMat<f64> {
        let mut t = TriMat::new((n * n, k));
        for c in 0..k {
            let a = (c * 13) % n;
            t.add_triplet(a, c, -0.5 - 0.01 * c as f64);
            t.add_triplet((a + 1) % n, c, -0.25);
            t.add_triplet(n * (n - 1) + (c * 5) % n, c, 0.125);
        }
        t.to_csc()
    }

    fn reference(chol: &Cholesky, r: &sprs::CsMat<f64>) -> Vec<f64> {
        let (n, k) = (r.rows(), r.cols());
        let dense = r.to_dense();
        let mut x = vec![0.0; n * k];
        for c in 0..k {
            for i in 0..n {
                x[c * n + i] = dense[[i, c]];
            }
        }
        chol.solve_in_place(&mut x, k);
        let mut out = vec![0.0; k * k];
        for a in 0..k {
            for b in 0..k {
                out[b * k + a] = (0..n).map(|i| dense[[i, a]] * x[b * n + i]).sum();
            }
        }
        out
    }

    #[test]
    fn factor_cost_of_a_dense_matrix() {
        // n I + 1 1ᵀ: one dense block, n³/6 multiply–adds as one supernode, or
        // Σ c²/2 + c over the columns' c = n − 1 − j entries below the diagonal
        let n = 60;
        let mut t = TriMat::new((n, n));
        for i in 0..n {
            for j in 0..n {
                t.add_triplet(i, j, if i == j { n as f64 + 1.0 } else { 1.0 });
            }
        }
        let chol = Cholesky::factor(&t.to_csc()).unwrap();
        let got = chol.factor_cost();
        let nf = n as f64;
        let supernodal = nf * nf * nf / 6.0;
        let simplicial: f64 = (0..n)
            .map(|j| {
                let c = (n - 1 - j) as f64;
                0.5 * c * c + c
            })
            .sum();
        assert!(
            (got - supernodal).abs() < 1e-9 * supernodal
                || (got - simplicial).abs() < 1e-9 * simplicial,
            "{got} vs {supernodal} or {simplicial}"
        );
    }

    #[test]
    fn matches_column_solves() {
        for (n, k) in [(3, 2), (6, 5), (40, 37)] {
            let a = grid(n);
            let r = frame_columns(n, k);
            for ordering in [Ordering::Amd, Ordering::Identity] {
                let options = CholeskyOptions::DEFAULT.with_ordering(ordering.clone());
                let chol = Cholesky::factor_with(&a, &options).unwrap();
                let g = chol.inverse_gram(&r).unwrap();
                let want = reference(&chol, &r);
                let scale = want.iter().fold(0.0f64, |m, v| m.max(v.abs()));
                for (got, want) in g.values.iter().zip(&want) {
                    assert!(
                        (got - want).abs() <= 1e-13 * scale,
                        "n = {n}, {ordering:?}: {got} vs {want}"
                    );
                }
                assert!(g.panels_visited <= g.panels);
            }
        }
    }
}
