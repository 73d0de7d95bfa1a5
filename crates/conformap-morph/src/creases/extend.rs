//! The harmonic extension of prescribed moves of some vertices of a disk map to the others:
//! `L_FF δ_F = −L_FH δ_H` with `L` the disk problem's Laplacian (the one its map is
//! harmonic for), `H` the held vertices (boundary, rims, landmarks) and `F` the rest.
//! Factored once per S1 and reused for every key surface.

use conformap_operators::{Cholesky, OperatorError};
use num_complex::Complex64;
use sprs::{CsMat, TriMat};

/// `L_FF` factored, and the coupling `L_FH`, for one set of held vertices.
#[derive(Debug)]
pub struct RimExtension {
    /// For every vertex: its index among the free vertices, `u32::MAX` when held.
    free_index: Vec<u32>,
    /// `(free index, held vertex, L entry)` for every nonzero of `L_FH`.
    coupling: Vec<(u32, u32, f64)>,
    /// The factor of `L_FF` (`None` when no vertex is free).
    factor: Option<Cholesky>,
}

impl RimExtension {
    /// Factors `L_FF` of the symmetric `n × n` `laplacian` (CSC) for the vertices with
    /// `held[v]` false.
    ///
    /// # Errors
    /// [`OperatorError`] if `L_FF` cannot be factored (not positive definite: a free
    /// component touches no held vertex).
    pub fn new(laplacian: &CsMat<f64>, held: &[bool]) -> Result<Self, OperatorError> {
        let mut free_index = vec![u32::MAX; held.len()];
        let mut nf = 0u32;
        for (v, &h) in held.iter().enumerate() {
            if !h {
                free_index[v] = nf;
                nf += 1;
            }
        }
        let mut tri = TriMat::new((nf as usize, nf as usize));
        let mut coupling = Vec::new();
        for (j, col) in laplacian.outer_iterator().enumerate() {
            for (i, &value) in col.iter() {
                let (fi, fj) = (free_index[i], free_index[j]);
                match (fi != u32::MAX, fj != u32::MAX) {
                    (true, true) => tri.add_triplet(fi as usize, fj as usize, value),
                    (true, false) => coupling.push((fi, j as u32, value)),
                    _ => {}
                }
            }
        }
        let factor = if nf > 0 {
            Some(Cholesky::factor(&tri.to_csc())?)
        } else {
            None
        };
        Ok(Self {
            free_index,
            coupling,
            factor,
        })
    }

    /// The extension of `moves` (read at the held vertices) to every vertex: the held
    /// vertices keep their move, the free ones get the harmonic interpolant.
    pub fn extend(&self, moves: &[Complex64]) -> Vec<Complex64> {
        let Some(factor) = &self.factor else {
            return moves.to_vec();
        };
        let mut rhs = vec![Complex64::new(0.0, 0.0); factor.dim()];
        for &(fi, h, value) in &self.coupling {
            rhs[fi as usize] -= value * moves[h as usize];
        }
        let x = factor.solve_complex(&rhs);
        moves
            .iter()
            .zip(&self.free_index)
            .map(|(&m, &fi)| if fi == u32::MAX { m } else { x[fi as usize] })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The path Laplacian of 5 vertices: the extension of moves held at both ends (and
    /// the middle) is linear in between.
    #[test]
    fn the_extension_on_a_path_is_linear() {
        let n = 5;
        let mut t = TriMat::new((n, n));
        for i in 0..n - 1 {
            t.add_triplet(i, i, 1.0);
            t.add_triplet(i + 1, i + 1, 1.0);
            t.add_triplet(i, i + 1, -1.0);
            t.add_triplet(i + 1, i, -1.0);
        }
        let l = t.to_csc();
        let held = [true, false, true, false, true];
        let e = RimExtension::new(&l, &held).unwrap_or_else(|e| panic!("{e}"));
        let c = |x: f64| Complex64::new(x, -x);
        let moves = [c(0.0), c(99.0), c(2.0), c(99.0), c(0.0)];
        let d = e.extend(&moves);
        let expect = [c(0.0), c(1.0), c(2.0), c(1.0), c(0.0)];
        for (a, b) in d.iter().zip(&expect) {
            assert!((a - b).norm() < 1e-14, "{d:?}");
        }
    }
}
