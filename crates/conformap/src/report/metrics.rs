//! The `metrics` object of a report: the library's metrics of the map (planar or sphere),
//! then the command's own entries ([`MetricsExtra`]).

use conformap_metrics::{AbsLogStats, AngleStats};
use serde::Serialize;

use super::sorted::Sorted;

/// The `metrics` object: a metrics struct of the library (planar or sphere), plus the
/// command's own entries (values before a Möbius move, cross ratios, …), written after it
/// with their keys sorted.
#[derive(Debug, Clone, Serialize)]
pub struct MetricsSection {
    /// The library's metrics.
    #[serde(flatten)]
    pub base: MapQuality,
    /// The command's own entries.
    #[serde(flatten)]
    pub extra: Sorted<MetricsExtra>,
}

/// The metrics of a map, by domain.
#[derive(Debug, Clone, Serialize)]
#[serde(untagged)]
pub enum MapQuality {
    /// A planar map (disk, disk with holes).
    Planar(conformap_metrics::MapMetrics),
    /// A sphere map.
    Sphere(conformap_sphere::SphereMetrics),
}

/// The command's own entries of the `metrics` object.
#[derive(Debug, Clone, Default, Serialize)]
#[serde(untagged)]
pub enum MetricsExtra {
    /// None.
    #[default]
    None,
    /// `sphere --mobius uniform`: the sphere map before its normalization.
    SphereMobius {
        /// Angle distortion before the Möbius normalization.
        angle_distortion_deg_before_mobius: AngleStats,
        /// Uniformity energy before it.
        uniformity_energy_before_mobius: f64,
    },
    /// `mobius --domain disk`: the map before and after.
    MobiusDisk {
        /// Angle distortion of the given map.
        angle_distortion_deg_before: AngleStats,
        /// Cross-ratio distortion of the returned map.
        cross_ratio_log: AbsLogStats,
        /// Cross-ratio distortion of the given map.
        cross_ratio_log_before: AbsLogStats,
        /// Uniformity energy of the returned map.
        uniformity_energy: f64,
        /// Uniformity energy of the given map.
        uniformity_energy_before: f64,
    },
    /// `mobius --domain sphere`: the given map (the returned one's values are the
    /// library's sphere metrics).
    MobiusSphere {
        /// Angle distortion of the given map.
        angle_distortion_deg_before: AngleStats,
        /// Cross-ratio distortion of the given map.
        cross_ratio_log_before: AbsLogStats,
        /// Uniformity energy of the given map.
        uniformity_energy_before: f64,
    },
    /// `global`: the layout's own measures on the surface the forms live on.
    Global {
        /// Angle distortion over every corner, those at zeros included.
        angle_distortion_all_corners_deg: AngleStats,
        /// Angle distortion away from the zeros.
        angle_distortion_away_from_zeros_deg: AngleStats,
        /// Smallest and largest conformal factor.
        conformal_factor_range: [f64; 2],
        /// Folded faces at zeros.
        folds_at_zeros: usize,
        /// Folded faces elsewhere.
        folds_outside_zeros: usize,
        /// Uniformity energy of the layout.
        uniformity_energy: f64,
    },
    /// The uniformity energy of a map whose library metrics do not hold it.
    Uniformity {
        /// Uniformity energy.
        uniformity_energy: f64,
    },
}

impl MetricsSection {
    /// The metrics of a planar map.
    pub fn planar(m: conformap_metrics::MapMetrics) -> Self {
        Self::new(MapQuality::Planar(m), MetricsExtra::None)
    }

    /// The metrics of a sphere map.
    pub fn sphere(m: conformap_sphere::SphereMetrics) -> Self {
        Self::new(MapQuality::Sphere(m), MetricsExtra::None)
    }

    /// The metrics `base` and the command's `extra` entries.
    pub fn new(base: MapQuality, extra: MetricsExtra) -> Self {
        Self {
            base,
            extra: Sorted(extra),
        }
    }

    /// With the command's own entries `extra`.
    pub fn and(mut self, extra: MetricsExtra) -> Self {
        self.extra = Sorted(extra);
        self
    }

    /// `(conformal energy or uniformity, mean angle distortion in degrees, flipped faces)`:
    /// the numbers a summary line or a batch line shows.
    pub fn headline(&self) -> (f64, f64, usize) {
        match &self.base {
            MapQuality::Planar(m) => (
                m.conformal_energy,
                m.angle_distortion_deg.mean,
                m.flipped_faces,
            ),
            MapQuality::Sphere(m) => (
                m.uniformity_energy,
                m.angle_distortion_deg.mean,
                m.flipped_faces,
            ),
        }
    }
}
