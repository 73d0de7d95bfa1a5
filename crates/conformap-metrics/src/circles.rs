//! Circles of boundary loops: the distance from the unit circle, and the best-fit circle
//! (the one copy in `conformap_operators::fit_circle`) of a loop's image.

use conformap_operators::Circle;
use num_complex::Complex64;

/// The image points of loop `lp`.
fn points(lp: &[u32], map: &[Complex64]) -> Vec<Complex64> {
    lp.iter().map(|&v| map[v as usize]).collect()
}

/// The least-squares circle through the map values of loop `lp` (see
/// [`conformap_operators::fit_circle`]).
pub(crate) fn fit_circle(lp: &[u32], map: &[Complex64]) -> Circle {
    conformap_operators::fit_circle(&points(lp, map))
}

/// `max ||f_v| − 1|` over the loop: distance from the unit circle.
pub(crate) fn unit_circle_residual(lp: &[u32], map: &[Complex64]) -> f64 {
    lp.iter()
        .map(|&v| (map[v as usize].norm() - 1.0).abs())
        .fold(0.0, f64::max)
}

/// `max ||f_v − c| − r| / r` over the loop; 1 (a full radius) if the circle has radius 0
/// (the loop collapsed to a point).
pub(crate) fn relative_residual(lp: &[u32], map: &[Complex64], fit: Circle) -> f64 {
    conformap_operators::circle_residual(&points(lp, map), fit)
}
