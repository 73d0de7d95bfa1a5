//! The sums over faces that every energy model of the uniformity search returns (the
//! direct sums of `faces.rs` and the second moments of `moments.rs` alike), so the Newton
//! step of `uniform.rs` is written once for both.

/// The sums over faces that the gradient and Hessian of `uniform.rs` are made of, at a unit
/// `μ` (`a_f = μᵀ Q̃_f μ`, `u_f = Q̃_f μ`, `r_f = a_f − s_f`).
pub struct Aggregates {
    /// `Σ r_f²`.
    pub energy: f64,
    /// `Σ r_f a_f`.
    pub rho: f64,
    /// `Σ a_f²`.
    pub a2: f64,
    /// `Σ r_f u_f`.
    pub big_r: Vec<f64>,
    /// `Σ a_f u_f`.
    pub au: Vec<f64>,
    /// `Σ u_f u_fᵀ`, row-major.
    pub uu: Vec<f64>,
    /// `Σ r_f Q̃_f`, row-major.
    pub rq: Vec<f64>,
}
