//! The cubic-spline homotopy of CEM §6 (Fig. 13): every vertex moves along the natural
//! cubic spline through its positions on the K key surfaces, per coordinate, C² in time.
//!
//! The spline is linear in the data, and its times are the same for every vertex, so it
//! is computed once as K cardinal weight functions `φ_k(t)` (the spline through the unit
//! vector `e_k`): a frame is `x(t) = Σ_k φ_k(t) P_k`. At a key time `t_j` the formula
//! gives `φ_k(t_j) = δ_kj` exactly (not to rounding), so key frames are the key positions
//! bit for bit. The weights also sum to 1 at every time (the spline reproduces
//! constants), so `x(t) = P_0 + Σ_{k≥1} φ_k(t) (P_k − P_0)`: the glTF morph targets.

use crate::MorphError;

/// The natural cubic spline basis on given knot times.
#[derive(Debug, Clone, PartialEq)]
pub struct CubicHomotopy {
    times: Vec<f64>,
    /// `second[k][i]`: second derivative at knot `i` of the cardinal spline `φ_k`.
    second: Vec<Vec<f64>>,
}

impl CubicHomotopy {
    /// Key times `0, 1/(K−1), …, 1`.
    ///
    /// # Errors
    /// [`MorphError::InvalidOption`] for `k < 2`.
    pub fn evenly_spaced(k: usize) -> Result<Self, MorphError> {
        if k < 2 {
            return Err(MorphError::InvalidOption {
                name: "key_times",
                reason: format!("need at least 2 key surfaces, got {k}"),
            });
        }
        Self::new((0..k).map(|i| i as f64 / (k - 1) as f64).collect())
    }

    /// The natural cubic spline basis (zero second derivative at both ends) on `times`.
    ///
    /// # Errors
    /// [`MorphError::InvalidOption`] unless there are at least two times, all finite and
    /// strictly increasing.
    ///
    /// # Examples
    /// ```
    /// use conformap_morph::CubicHomotopy;
    /// let h = CubicHomotopy::new(vec![0.0, 0.3, 1.0])?;
    /// assert_eq!(h.weights(0.3), vec![0.0, 1.0, 0.0]); // exact at a key time
    /// let w = h.weights(0.62);
    /// assert!((w.iter().sum::<f64>() - 1.0).abs() < 1e-15);
    /// # Ok::<(), conformap_morph::MorphError>(())
    /// ```
    pub fn new(times: Vec<f64>) -> Result<Self, MorphError> {
        let bad = |reason: String| MorphError::InvalidOption {
            name: "key_times",
            reason,
        };
        if times.len() < 2 {
            return Err(bad(format!(
                "need at least 2 key times, got {}",
                times.len()
            )));
        }
        if let Some(w) = times
            .windows(2)
            .find(|w| !(w[1] > w[0] && w[0].is_finite() && w[1].is_finite()))
        {
            return Err(bad(format!(
                "key times must be finite and strictly increasing ({} then {})",
                w[0], w[1]
            )));
        }
        let n = times.len();
        let second = (0..n)
            .map(|k| {
                let mut y = vec![0.0; n];
                y[k] = 1.0;
                natural_second_derivatives(&times, &y)
            })
            .collect();
        Ok(Self { times, second })
    }

    /// The key times.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// `φ_k(t)` for every key `k`. Meant for `t` within the key times; outside them the
    /// cubic of the nearest end interval is continued.
    pub fn weights(&self, t: f64) -> Vec<f64> {
        let n = self.times.len();
        let i = self.times[1..n - 1].partition_point(|&x| x <= t);
        let (t0, t1) = (self.times[i], self.times[i + 1]);
        let h = t1 - t0;
        let s = (t - t0) / h;
        let r = 1.0 - s;
        let c = h * h / 6.0;
        (0..n)
            .map(|k| {
                let y0 = f64::from(u8::from(k == i));
                let y1 = f64::from(u8::from(k == i + 1));
                let m = &self.second[k];
                r * y0 + s * y1 + c * ((r * r * r - r) * m[i] + (s * s * s - s) * m[i + 1])
            })
            .collect()
    }
}

/// Second derivatives of the natural cubic spline through `(t_i, y_i)`: the tridiagonal
/// system `h_{i−1} M_{i−1} + 2(h_{i−1} + h_i) M_i + h_i M_{i+1} = 6 (Δ_i − Δ_{i−1})`,
/// `M_0 = M_{n−1} = 0`, by the Thomas algorithm (diagonally dominant: no pivoting).
fn natural_second_derivatives(t: &[f64], y: &[f64]) -> Vec<f64> {
    let n = t.len();
    let mut m = vec![0.0; n];
    if n < 3 {
        return m;
    }
    let h: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
    let slope: Vec<f64> = (0..n - 1).map(|i| (y[i + 1] - y[i]) / h[i]).collect();
    let k = n - 2;
    let mut diag = vec![0.0; k];
    let mut rhs = vec![0.0; k];
    for j in 0..k {
        diag[j] = 2.0 * (h[j] + h[j + 1]);
        rhs[j] = 6.0 * (slope[j + 1] - slope[j]);
    }
    for j in 1..k {
        let f = h[j] / diag[j - 1];
        diag[j] -= f * h[j];
        rhs[j] -= f * rhs[j - 1];
    }
    m[k] = rhs[k - 1] / diag[k - 1];
    for j in (0..k - 1).rev() {
        m[j + 1] = (rhs[j] - h[j + 1] * m[j + 2]) / diag[j];
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spline(times: Vec<f64>) -> CubicHomotopy {
        match CubicHomotopy::new(times) {
            Ok(h) => h,
            Err(e) => panic!("{e}"),
        }
    }

    fn value(h: &CubicHomotopy, y: &[f64], t: f64) -> f64 {
        h.weights(t).iter().zip(y).map(|(w, y)| w * y).sum()
    }

    #[test]
    fn interpolates_and_is_c2() {
        let times = vec![0.0, 0.2, 0.5, 0.6, 1.0];
        let h = spline(times.clone());
        let y = [1.0, -2.0, 0.5, 3.0, 0.0];
        for (t, v) in times.iter().zip(&y) {
            assert_eq!(value(&h, &y, *t), *v);
        }
        // C²: second-order one-sided first differences (error O(e²)) agree at the inner
        // knots, and so do the one-sided second differences (error O(e), the third
        // derivative jumps there); a kink or a curvature jump would show as O(1)
        let e = 1e-4;
        for &t in &times[1..4] {
            let f = |s: f64| value(&h, &y, s);
            let d1l = (3.0 * f(t) - 4.0 * f(t - e) + f(t - 2.0 * e)) / (2.0 * e);
            let d1r = (-3.0 * f(t) + 4.0 * f(t + e) - f(t + 2.0 * e)) / (2.0 * e);
            assert!((d1l - d1r).abs() < 1e-3, "slope jump at {t}: {d1l} {d1r}");
            let d2l = (f(t) - 2.0 * f(t - e) + f(t - 2.0 * e)) / (e * e);
            let d2r = (f(t + 2.0 * e) - 2.0 * f(t + e) + f(t)) / (e * e);
            assert!(
                (d2l - d2r).abs() < 0.5,
                "curvature jump at {t}: {d2l} {d2r}"
            );
        }
        // natural ends: second difference → 0
        let d2 = (value(&h, &y, 2.0 * e) - 2.0 * value(&h, &y, e) + value(&h, &y, 0.0)) / (e * e);
        assert!(d2.abs() < 0.5, "{d2}");
    }

    #[test]
    fn reproduces_lines_and_two_keys_is_linear() {
        let h = spline(vec![0.0, 0.1, 0.7, 1.0]);
        let y = [3.0, 3.2, 4.4, 5.0]; // y = 3 + 2t
        for k in 0..=20 {
            let t = k as f64 / 20.0;
            assert!((value(&h, &y, t) - (3.0 + 2.0 * t)).abs() < 1e-14);
            assert!((h.weights(t).iter().sum::<f64>() - 1.0).abs() < 1e-15);
        }
        let two = spline(vec![0.0, 1.0]);
        assert_eq!(two.weights(0.25), vec![0.75, 0.25]);
    }

    #[test]
    fn bad_times_are_refused() {
        assert!(CubicHomotopy::new(vec![0.0]).is_err());
        assert!(CubicHomotopy::new(vec![0.0, 0.5, 0.5]).is_err());
        assert!(CubicHomotopy::new(vec![0.0, f64::NAN]).is_err());
        assert!(CubicHomotopy::evenly_spaced(1).is_err());
    }
}
