//! Helpers shared by the integration tests.
#![allow(dead_code)]

use conformap_mesh::TriMesh;

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
    let path = conformap_testkit::real_mesh_or_skip(name, name)?;
    Some(conformap_testkit::read_plain_obj(&path).expect("fixture reads"))
}

pub fn norm(p: [f64; 3]) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()
}
