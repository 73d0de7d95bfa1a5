//! Summary statistics of the reports' per-corner and per-face values (mean, population sd,
//! max, 95th percentile): one set of structs for every map's metrics (planar, sphere, seamed
//! layouts), and the functions that compute them.

use serde::{Deserialize, Serialize};

/// Angle distortion in degrees: mean, population sd, max and 95th percentile (nearest rank:
/// the `⌈0.95 n⌉`-th smallest of the `n` corners). The field names are those of the
/// `"angle_distortion_deg"` object of the report schema.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct AngleStats {
    /// Mean.
    pub mean: f64,
    /// Population standard deviation.
    pub sd: f64,
    /// Maximum.
    pub max: f64,
    /// 95th percentile (nearest rank).
    pub p95: f64,
}

/// Mean, population sd and max of per-face values (the `"beltrami_abs"` object).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct SummaryStats {
    /// Mean.
    pub mean: f64,
    /// Population standard deviation.
    pub sd: f64,
    /// Maximum.
    pub max: f64,
}

/// Mean absolute value and population sd of a signed per-face log ratio (the
/// `"area_distortion_log"` object).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct LogRatioStats {
    /// Mean of the absolute value.
    pub mean_abs: f64,
    /// Population standard deviation of the signed value.
    pub sd: f64,
}

/// Mean absolute value and maximum absolute value of a signed log ratio (the Möbius-invariant
/// length cross-ratio distortion).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[non_exhaustive]
pub struct AbsLogStats {
    /// Mean of the absolute value.
    pub mean_abs: f64,
    /// Maximum of the absolute value.
    pub max_abs: f64,
}

/// Mean, population sd and max (all 0 for no values), by two-pass summation.
///
/// ```
/// let s = conformap_metrics::summary_stats(&[1.0, 3.0]);
/// assert_eq!((s.mean, s.sd, s.max), (2.0, 1.0, 3.0));
/// ```
pub fn summary_stats(values: &[f64]) -> SummaryStats {
    if values.is_empty() {
        return SummaryStats::default();
    }
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    let max = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    SummaryStats {
        mean,
        sd: var.sqrt(),
        max,
    }
}

/// [`summary_stats`] plus the nearest-rank 95th percentile; reorders `values`.
pub fn angle_stats(values: &mut [f64]) -> AngleStats {
    let s = summary_stats(values);
    let p95 = if values.is_empty() {
        0.0
    } else {
        let rank = (0.95 * values.len() as f64).ceil() as usize;
        let k = rank.clamp(1, values.len()) - 1;
        *values.select_nth_unstable_by(k, f64::total_cmp).1
    };
    AngleStats {
        mean: s.mean,
        sd: s.sd,
        max: s.max,
        p95,
    }
}

/// Mean |x| and sd of signed values.
pub fn log_ratio_stats(values: &[f64]) -> LogRatioStats {
    if values.is_empty() {
        return LogRatioStats::default();
    }
    let n = values.len() as f64;
    let mean = values.iter().sum::<f64>() / n;
    let var = values.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / n;
    LogRatioStats {
        mean_abs: values.iter().map(|v| v.abs()).sum::<f64>() / n,
        sd: var.sqrt(),
    }
}

/// Mean |x| and max |x|.
pub fn abs_log_stats(values: &[f64]) -> AbsLogStats {
    if values.is_empty() {
        return AbsLogStats::default();
    }
    AbsLogStats {
        mean_abs: values.iter().map(|v| v.abs()).sum::<f64>() / values.len() as f64,
        max_abs: values.iter().map(|v| v.abs()).fold(0.0, f64::max),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_a_small_sample() {
        let mut v: Vec<f64> = (1..=20).map(f64::from).collect();
        let a = angle_stats(&mut v);
        assert!((a.mean - 10.5).abs() < 1e-14);
        assert!((a.max - 20.0).abs() < 1e-14);
        assert!((a.p95 - 19.0).abs() < 1e-14);
        let l = log_ratio_stats(&[-1.0, 1.0]);
        assert!((l.mean_abs - 1.0).abs() < 1e-15 && (l.sd - 1.0).abs() < 1e-15);
        let e = abs_log_stats(&[-3.0, 1.0]);
        assert!((e.mean_abs - 2.0).abs() < 1e-15 && (e.max_abs - 3.0).abs() < 1e-15);
        assert_eq!(summary_stats(&[]), SummaryStats::default());
    }
}
