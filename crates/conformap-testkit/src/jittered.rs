//! A torus of revolution with jittered vertices: every vertex moved along the surface by a
//! seeded pseudo-random fraction of a grid cell, so the mesh is irregular but every vertex
//! still lies exactly on the torus (the conformal modulus is the analytic one).

use std::f64::consts::TAU;

use conformap_mesh::TriMesh;

use crate::grid::wrapped_grid_faces;
use crate::planar::build;
use crate::surfaces::check_torus;

/// SplitMix64: a tiny, well-mixed, seedable generator (no dependency for test meshes).
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A torus of revolution like [`crate::torus`] (`major` R, `minor` r, vertex `(i, j)` at
/// index `j · n_major + i`), with vertex `(i, j)` at angles `φ = 2π (i + δ_φ) / n_major`,
/// `θ = 2π (j + δ_θ) / n_minor` where `δ` is uniform in `[−jitter, jitter]` (seeded by
/// `seed`). `jitter < ½` keeps every face positively oriented; 0 gives the regular torus.
/// Its conformal modulus is `τ = i r / √(R² − r²)` (periods `2π` and `2π r / √(R² − r²)`).
///
/// # Panics
/// If not `0 < minor < major`, `n_major < 3`, `n_minor < 3` or not `0 ≤ jitter < 0.5`.
///
/// # Examples
/// ```
/// use conformap_testkit::jittered_torus;
/// let t = jittered_torus(3.0, 1.0, 40, 20, 0.2, 7);
/// assert_eq!(t.num_faces(), 1600);
/// assert_eq!(t.genus(), Some(1));
/// for p in t.positions() {
///     // on the torus: (√(x² + y²) − R)² + z² = r²
///     let rho = p[0].hypot(p[1]) - 3.0;
///     assert!((rho * rho + p[2] * p[2] - 1.0).abs() < 1e-12);
/// }
/// ```
pub fn jittered_torus(
    major: f64,
    minor: f64,
    n_major: usize,
    n_minor: usize,
    jitter: f64,
    seed: u64,
) -> TriMesh {
    check_torus(major, minor, n_major, n_minor);
    assert!((0.0..0.5).contains(&jitter), "jitter must be in [0, 0.5)");
    let mut rng = SplitMix64(seed);
    let mut positions = Vec::with_capacity(n_major * n_minor);
    for j in 0..n_minor {
        for i in 0..n_major {
            let dphi = jitter * (2.0 * rng.next_f64() - 1.0);
            let dtheta = jitter * (2.0 * rng.next_f64() - 1.0);
            let phi = TAU * (i as f64 + dphi) / n_major as f64;
            let theta = TAU * (j as f64 + dtheta) / n_minor as f64;
            let rho = major + minor * theta.cos();
            positions.push([rho * phi.cos(), rho * phi.sin(), minor * theta.sin()]);
        }
    }
    let faces = wrapped_grid_faces(n_major, n_minor, true, true);
    build("jittered torus", positions, faces)
}
