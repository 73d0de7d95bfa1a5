//! The summary statistics of the reports are conformap-metrics' ([`conformap_metrics::AngleStats`]
//! and its siblings): one set of structs for every map's metrics.

pub use conformap_metrics::{AbsLogStats, AngleStats, LogRatioStats, SummaryStats};

pub(crate) use conformap_metrics::{
    abs_log_stats, angle_stats, log_ratio_stats, summary_stats as summary,
};
