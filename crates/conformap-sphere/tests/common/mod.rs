//! Helpers shared by the integration tests.
#![allow(dead_code)]

use conformap_mesh::TriMesh;
use conformap_sphere::{
    optimize_disk_mobius, optimize_sphere_mobius, DiskMobius, MobiusObjective, MobiusOptions,
    MobiusReport, SphereMobius,
};
use num_complex::Complex64;

/// A deterministic pseudo-random stream in [0, 1) (64-bit LCG, Knuth's constants), so the
/// "random" cases are the same on every run.
pub struct Lcg(pub u64);

impl Lcg {
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

pub fn read(name: &str) -> Option<TriMesh> {
    conformap_testkit::read_real_mesh_or_skip(name, name)
}

pub fn norm(p: [f64; 3]) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}

/// A sphere map moved by its most uniform Möbius transformation (default options).
pub fn uniform_sphere(mesh: &TriMesh, points: &[[f64; 3]]) -> SphereMobius {
    optimize_sphere_mobius(
        mesh,
        points,
        &MobiusObjective::Uniform,
        &MobiusOptions::DEFAULT,
    )
    .expect("sphere Möbius optimization")
}

/// A disk map moved by its most uniform automorphism of the disk (default options).
pub fn uniform_disk(mesh: &TriMesh, map: &[Complex64]) -> DiskMobius {
    optimize_disk_mobius(
        mesh,
        map,
        &MobiusObjective::Uniform,
        &MobiusOptions::DEFAULT,
    )
    .expect("disk Möbius optimization")
}

/// Asserts that the optimization lowered the uniformity energy (`what` names the case).
pub fn assert_more_uniform(r: &MobiusReport, what: &str) {
    assert!(
        r.uniformity_after < r.uniformity_before,
        "{what}: {} -> {}",
        r.uniformity_before,
        r.uniformity_after
    );
}
