//! Property tests with committed seeds: invariants that must hold on every input of a family,
//! checked on many generated inputs whose seeds are written here (a failure names its seed,
//! and rerunning reproduces it exactly).
//!
//! - Disk maps (CCEM-QN, the default): every boundary vertex on the unit circle, no folded
//!   face, the conformal energy never rising over the accepted iterates.
//! - Möbius maps of the plane and the sphere and automorphisms of the disk: a map composed
//!   with its inverse is the identity; the composition acts as the two maps in turn.
//! - Global maps of jittered tori: seams are pure translations, no zero, no fold.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

use conformap_disk::{compute_disk_map, DiskMethod, DiskOptions};
use conformap_global::{global_map, GlobalMapOptions};
use conformap_mesh::TriMesh;
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use conformap_sphere::{DiskAutomorphism, Mobius};
use conformap_testkit::{flat_disk, jittered_torus};
use num_complex::Complex64;

/// The committed seeds (one generated input each).
const SEEDS: [u64; 12] = [1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233];

/// xorshift64*: a tiny deterministic generator.
struct Rng(u64);

impl Rng {
    fn new(seed: u64) -> Self {
        Self(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }
    /// Uniform in `[0, 1)`.
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in `[lo, hi)`.
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
    fn complex(&mut self, r: f64) -> Complex64 {
        Complex64::new(self.range(-r, r), self.range(-r, r))
    }
}

/// A bumpy disk: the flat ring disk with its interior vertices moved in the plane by up to
/// a fifth of the ring spacing and lifted by a few random Gaussian bumps (a valid surface:
/// the in-plane jitter keeps every triangle positively oriented).
fn bumpy_disk(seed: u64) -> TriMesh {
    let mut r = Rng::new(seed);
    let rings = 6 + (seed % 4) as usize;
    let flat = flat_disk(rings, 6);
    let h = 1.0 / rings as f64;
    let bumps: Vec<(f64, f64, f64, f64)> = (0..4)
        .map(|_| {
            (
                r.range(-0.7, 0.7),
                r.range(-0.7, 0.7),
                r.range(-0.6, 0.6),
                r.range(0.15, 0.4),
            )
        })
        .collect();
    let positions = flat
        .positions()
        .iter()
        .enumerate()
        .map(|(v, p)| {
            let (mut x, mut y) = (p[0], p[1]);
            if !flat.is_boundary_vertex(v) {
                x += r.range(-0.2, 0.2) * h;
                y += r.range(-0.2, 0.2) * h;
            }
            let z = bumps
                .iter()
                .map(|&(cx, cy, a, s)| a * (-((x - cx).powi(2) + (y - cy).powi(2)) / (s * s)).exp())
                .sum();
            [x, y, z]
        })
        .collect();
    TriMesh::try_new(positions, flat.faces().to_vec()).unwrap()
}

#[test]
fn disk_maps_keep_the_circle_never_fold_and_never_raise_the_energy() {
    for seed in SEEDS {
        let mesh = bumpy_disk(seed);
        let out = compute_disk_map(&mesh, DiskMethod::CcemQn, &DiskOptions::DEFAULT)
            .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        for &v in &mesh.boundary_loops()[0] {
            let r = out.map[v as usize].norm();
            assert!((r - 1.0).abs() < 1e-12, "seed {seed}: |f({v})| = {r}");
        }
        let m = planar_map_metrics(&mesh, &out.map, &MetricsOptions::DEFAULT).unwrap();
        assert_eq!(m.flipped_faces, 0, "seed {seed}");
        assert_eq!(m.degenerate_faces, 0, "seed {seed}");
        let h = &out.report.energy_history;
        assert!(h.len() >= 2, "seed {seed}: {h:?}");
        for w in h.windows(2) {
            // accepted steps satisfy the Armijo condition: the energy never rises (up to
            // the rounding of E_C = E_D − A, about 1e-15 relative)
            assert!(w[1] <= w[0] * (1.0 + 1e-12), "seed {seed}: {h:?}");
        }
        assert!(
            (m.conformal_energy - h[out.report.best_iteration]).abs() < 1e-10,
            "seed {seed}: the metrics' E_C is the solver's"
        );
    }
}

#[test]
fn a_mobius_map_composed_with_its_inverse_is_the_identity() {
    for seed in SEEDS {
        let mut r = Rng::new(seed);
        let (a, b, c, d) = (
            r.complex(2.0),
            r.complex(2.0),
            r.complex(2.0),
            r.complex(2.0),
        );
        let Ok(m) = Mobius::try_new(a, b, c, d) else {
            continue; // a (near-)singular draw: not a Möbius map
        };
        let n = Mobius::try_new(
            r.complex(2.0),
            r.complex(2.0),
            r.complex(2.0),
            r.complex(2.0),
        )
        .unwrap();
        let id = m.compose(&m.inverse());
        for _ in 0..20 {
            let z = r.complex(3.0);
            let back = id.apply(z);
            assert!(
                (back - z).norm() < 1e-10 * (1.0 + z.norm()),
                "seed {seed}: {z} → {back}"
            );
            // (m ∘ n)(z) = m(n(z))
            let (one, two) = (m.compose(&n).apply(z), m.apply(n.apply(z)));
            assert!(
                (one - two).norm() < 1e-9 * (1.0 + two.norm()),
                "seed {seed}: {one} vs {two}"
            );
            // on the sphere too
            let t = r.range(0.0, std::f64::consts::TAU);
            let s = r.range(-1.0, 1.0);
            let p = [
                (1.0 - s * s).sqrt() * t.cos(),
                (1.0 - s * s).sqrt() * t.sin(),
                s,
            ];
            let q = m.inverse().apply_sphere(m.apply_sphere(p));
            let err = (0..3).map(|k| (q[k] - p[k]).abs()).fold(0.0, f64::max);
            assert!(err < 1e-10, "seed {seed}: {p:?} → {q:?}");
        }
    }
}

#[test]
fn a_disk_automorphism_composed_with_its_inverse_is_the_identity_and_keeps_the_disk() {
    for seed in SEEDS {
        let mut r = Rng::new(seed);
        let a = Complex64::from_polar(1.0, r.range(0.0, 6.3));
        let b = Complex64::from_polar(r.range(0.0, 0.9), r.range(0.0, 6.3));
        let m = DiskAutomorphism::try_new(a, b).unwrap();
        let id = m.compose(&m.inverse());
        for _ in 0..20 {
            let z = Complex64::from_polar(r.range(0.0, 1.0), r.range(0.0, 6.3));
            assert!((id.apply(z) - z).norm() < 1e-12, "seed {seed}: {z}");
            assert!(
                m.apply(z).norm() < 1.0 + 1e-12,
                "seed {seed}: leaves the disk"
            );
            let on = Complex64::from_polar(1.0, r.range(0.0, 6.3));
            assert!(
                (m.apply(on).norm() - 1.0).abs() < 1e-12,
                "seed {seed}: circle"
            );
        }
    }
}

#[test]
fn global_maps_of_jittered_tori_have_translation_seams_and_no_fold() {
    for seed in &SEEDS[..4] {
        let mut r = Rng::new(*seed);
        let major = r.range(1.8, 3.5);
        let torus = jittered_torus(major, 1.0, 36, 18, 0.2, *seed);
        let map = global_map(&torus, &GlobalMapOptions::DEFAULT)
            .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        assert!(
            map.seam_residual < 1e-9,
            "seed {seed}: {}",
            map.seam_residual
        );
        assert_eq!(map.zeros.multiplicity_sum, 0, "seed {seed}");
        assert_eq!(map.input_folds(), (0, 0), "seed {seed}");
        let tau = map.tau.unwrap();
        let exact = (major * major - 1.0).sqrt();
        // coarse mesh (36 × 18): within 3 % of √(R² − r²)/r
        assert!(
            (tau.im - exact).abs() < 0.03 * exact,
            "seed {seed}: τ {tau}, {exact}"
        );
    }
}
