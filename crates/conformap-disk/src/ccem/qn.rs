//! The quasi-Newton direction of CCEM Algorithm 4.2: BFGS on the boundary angles, kept as
//! the list of curvature pairs `(s_k, y_k)` and applied by the two-loop recursion
//! (Nocedal & Wright Algorithm 7.4), so that memory and work per iteration are `O(m n_B)`
//! for `m` stored pairs instead of the `n_B²` of a dense inverse Hessian.
//!
//! With unlimited memory and a fixed initial scale this is exactly the BFGS update of
//! Algorithm 4.2, step 9. The initial inverse Hessian is `H₀ = (sᵀy / yᵀy) I`, the inverse
//! of the Hessian scale `δ₁ = yᵀs / sᵀs` that step 3 of Algorithm 4.2 writes for `H₁`
//! (`δ₁ I` approximates the Hessian, not its inverse).

use std::collections::VecDeque;

use crate::ccem::energy::dot;

/// Curvature pairs with `sᵀy ≤ PAIR_TOL · ‖s‖ ‖y‖` are not stored: they would make the
/// update indefinite or ill-conditioned (a step cut by the guard can have `sᵀy ≈ 0`).
const PAIR_TOL: f64 = 1e-10;

/// Inverse-Hessian approximation from curvature pairs.
#[derive(Debug, Clone)]
pub(crate) struct Bfgs {
    pairs: VecDeque<(Vec<f64>, Vec<f64>, f64)>,
    memory: usize,
    /// Scale of `H₀`; `None` until the first pair.
    gamma: Option<f64>,
    rescale: bool,
    /// Pairs rejected by the curvature test.
    pub skipped: usize,
}

impl Bfgs {
    /// `memory` pairs at most (0: unlimited); `rescale`: set `H₀`'s scale from the latest
    /// pair on every update (limited-memory practice) instead of only from the first
    /// (Algorithm 4.2).
    pub fn new(memory: usize, rescale: bool) -> Self {
        Self {
            pairs: VecDeque::new(),
            memory,
            gamma: None,
            rescale,
            skipped: 0,
        }
    }

    /// Whether any pair is stored (else the direction is the steepest descent).
    /// Pairs stored.
    pub fn len(&self) -> usize {
        self.pairs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Forgets every pair.
    pub fn reset(&mut self) {
        self.pairs.clear();
        self.gamma = None;
    }

    /// Adds the pair `s = θ_{k+1} − θ_k`, `y = ∇E(θ_{k+1}) − ∇E(θ_k)` (Algorithm 4.2, steps
    /// 6–9). Returns whether it was accepted.
    pub fn update(&mut self, s: Vec<f64>, y: Vec<f64>) -> bool {
        let sy = dot(&s, &y);
        let yy = dot(&y, &y);
        let ss = dot(&s, &s);
        if !(sy > PAIR_TOL * (ss * yy).sqrt()) {
            self.skipped += 1;
            return false;
        }
        if self.gamma.is_none() || self.rescale {
            self.gamma = Some(sy / yy);
        }
        if self.memory > 0 && self.pairs.len() == self.memory {
            self.pairs.pop_front();
        }
        self.pairs.push_back((s, y, 1.0 / sy));
        true
    }

    /// `−H g` with the initial inverse Hessian `H₀` applied in place by `apply_h0` instead
    /// of `(sᵀy / yᵀy) I` (a preconditioned BFGS: the two-loop recursion is unchanged).
    pub fn direction_with(&self, g: &[f64], apply_h0: impl Fn(&mut [f64])) -> Vec<f64> {
        let mut q: Vec<f64> = g.to_vec();
        let mut alphas = Vec::with_capacity(self.pairs.len());
        for (s, y, rho) in self.pairs.iter().rev() {
            let a = rho * dot(s, &q);
            q.iter_mut().zip(y).for_each(|(qi, yi)| *qi -= a * yi);
            alphas.push(a);
        }
        apply_h0(&mut q);
        for ((s, y, rho), a) in self.pairs.iter().zip(alphas.iter().rev()) {
            let b = rho * dot(y, &q);
            q.iter_mut().zip(s).for_each(|(qi, si)| *qi += (a - b) * si);
        }
        q.iter_mut().for_each(|x| *x = -*x);
        q
    }

    /// `−H g` (Algorithm 4.2, step 10).
    pub fn direction(&self, g: &[f64]) -> Vec<f64> {
        let gamma = self.gamma.unwrap_or(1.0);
        self.direction_with(g, |q| q.iter_mut().for_each(|x| *x *= gamma))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a quadratic `½ xᵀ D x` with exact line searches, BFGS with unlimited memory
    /// satisfies the secant equation `H y = s` for the latest pair.
    #[test]
    fn secant_equation() {
        let d = [1.0, 3.0, 10.0];
        let mut b = Bfgs::new(0, false);
        let s = vec![1.0, -2.0, 0.5];
        let y: Vec<f64> = s.iter().zip(d).map(|(a, b)| a * b).collect();
        assert!(b.update(s.clone(), y.clone()));
        let s2 = vec![0.3, 0.1, -1.0];
        let y2: Vec<f64> = s2.iter().zip(d).map(|(a, b)| a * b).collect();
        assert!(b.update(s2.clone(), y2.clone()));
        let hy = b.direction(&y2);
        for (h, s) in hy.iter().zip(&s2) {
            assert!((h + s).abs() < 1e-12);
        }
        // a pair of negative curvature is refused
        assert!(!b.update(vec![1.0, 0.0, 0.0], vec![-1.0, 0.0, 0.0]));
        assert_eq!(b.skipped, 1);
    }
}
