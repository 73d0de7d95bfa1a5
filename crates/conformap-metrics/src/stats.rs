//! Streaming summaries (mean, standard deviation, max), the 95th percentile and histograms.

/// Bin edges (degrees) of the angle-distortion histogram: bin `k` counts corners with
/// `EDGES[k] ≤ d < EDGES[k + 1]`; the last bin also holds `d = 180°`. Fine near zero, where
/// good conformal maps put almost every corner, coarse beyond 20°.
pub const ANGLE_HISTOGRAM_EDGES_DEG: [f64; 14] = [
    0.0, 0.5, 1.0, 2.0, 3.0, 5.0, 10.0, 15.0, 20.0, 30.0, 45.0, 60.0, 90.0, 180.0,
];

/// Running count, mean, population variance (Welford) and maximum of a stream of values.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Running {
    n: u64,
    mean: f64,
    m2: f64,
    max: f64,
}

impl Running {
    /// Adds one finite value.
    #[inline]
    pub(crate) fn push(&mut self, x: f64) {
        self.n += 1;
        let delta = x - self.mean;
        self.mean += delta / self.n as f64;
        self.m2 += delta * (x - self.mean);
        if self.n == 1 || x > self.max {
            self.max = x;
        }
    }

    /// Adds the values summarized by `other` (Chan et al.'s pairwise update), as if they
    /// had been pushed after this summary's.
    pub(crate) fn merge(&mut self, other: &Self) {
        if other.n == 0 {
            return;
        }
        if self.n == 0 {
            *self = *other;
            return;
        }
        let n = self.n + other.n;
        let delta = other.mean - self.mean;
        let (a, b) = (self.n as f64, other.n as f64);
        self.mean += delta * b / n as f64;
        self.m2 += other.m2 + delta * delta * a * b / n as f64;
        self.max = self.max.max(other.max);
        self.n = n;
    }

    /// Mean (0 for no values).
    pub(crate) fn mean(&self) -> f64 {
        self.mean
    }

    /// Population standard deviation (divides by `n`; 0 for no values).
    pub(crate) fn sd(&self) -> f64 {
        if self.n == 0 {
            0.0
        } else {
            (self.m2.max(0.0) / self.n as f64).sqrt()
        }
    }

    /// Maximum (0 for no values).
    pub(crate) fn max(&self) -> f64 {
        self.max
    }
}

/// The 95th percentile by nearest rank: the `⌈0.95 n⌉`-th smallest value (0 for no values).
/// Reorders `values` (linear-time selection, no full sort).
pub(crate) fn p95(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    let rank = (0.95 * values.len() as f64).ceil() as usize;
    let k = rank.clamp(1, values.len()) - 1;
    *values.select_nth_unstable_by(k, f64::total_cmp).1
}

/// The histogram bin of an angle distortion `d ∈ [0°, 180°]`.
#[inline]
pub(crate) fn angle_bin(d: f64) -> usize {
    let bins = ANGLE_HISTOGRAM_EDGES_DEG.len() - 1;
    ANGLE_HISTOGRAM_EDGES_DEG
        .partition_point(|&e| e <= d)
        .clamp(1, bins)
        - 1
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Blocks merged in order summarize what one stream does (empty blocks included).
    #[test]
    fn merged_blocks_match_one_stream() {
        let xs: Vec<f64> = (0..1000)
            .map(|i| ((i * 7919) % 1013) as f64 * 0.37 - 50.0)
            .collect();
        let mut one = Running::default();
        xs.iter().for_each(|&x| one.push(x));
        let mut merged = Running::default();
        for block in [&xs[..0], &xs[..1], &xs[1..400], &xs[400..400], &xs[400..]] {
            let mut r = Running::default();
            block.iter().for_each(|&x| r.push(x));
            merged.merge(&r);
        }
        assert_eq!(merged.n, one.n);
        assert!((merged.mean() - one.mean()).abs() < 1e-12 * one.mean().abs().max(1.0));
        assert!((merged.sd() - one.sd()).abs() < 1e-12 * one.sd());
        assert_eq!(merged.max(), one.max());
    }

    #[test]
    fn running_matches_two_pass() {
        let xs = [1.0, 4.0, 2.0, 8.0, 5.0];
        let mut r = Running::default();
        xs.iter().for_each(|&x| r.push(x));
        let mean = 4.0;
        let var = xs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / 5.0;
        assert!((r.mean() - mean).abs() < 1e-15);
        assert!((r.sd() - var.sqrt()).abs() < 1e-15);
        assert!((r.max() - 8.0).abs() < 1e-15);
        let empty = Running::default();
        assert_eq!((empty.mean(), empty.sd(), empty.max()), (0.0, 0.0, 0.0));
    }

    #[test]
    fn p95_is_nearest_rank() {
        let mut v: Vec<f64> = (1..=100).rev().map(f64::from).collect();
        assert!((p95(&mut v) - 95.0).abs() < 1e-15);
        let mut one = [3.5];
        assert!((p95(&mut one) - 3.5).abs() < 1e-15);
        let mut twenty: Vec<f64> = (1..=20).map(f64::from).collect();
        assert!((p95(&mut twenty) - 19.0).abs() < 1e-15);
        assert!(p95(&mut []).abs() < 1e-300);
    }

    #[test]
    fn bins_follow_the_edges() {
        assert_eq!(angle_bin(0.0), 0);
        assert_eq!(angle_bin(0.4999), 0);
        assert_eq!(angle_bin(0.5), 1);
        assert_eq!(angle_bin(44.9), 9);
        assert_eq!(angle_bin(179.0), 12);
        assert_eq!(angle_bin(180.0), 12);
    }
}
