//! The paper's `m₁` (CEM §6, Fig. 14): the disk automorphism that sends the first
//! landmark to the centre, followed by the rotation that turns the second landmark onto
//! the positive real axis. After it, the disks of all surfaces agree at two landmarks'
//! worth of position (the centre and a direction), and the registration only has to
//! correct what the conformal maps disagree on.

use conformap_sphere::DiskAutomorphism;
use num_complex::Complex64;

use crate::MorphError;

/// Landmarks whose map value has `|z|` at least this close to 1 count as on the boundary
/// for the normalization (the automorphism centring a point at `|z| → 1` has unbounded
/// coefficients). `1e-9`: far above rounding of a unit-circle value (`1e-16`), far below
/// the radius of the outermost interior vertex of any mesh the disk map resolves.
pub const NORMALIZE_BOUNDARY_TOL: f64 = 1e-9;

/// The normalization of one disk map.
#[derive(Debug, Clone, PartialEq)]
pub struct Normalized {
    /// `m(f(v))` for every vertex `v`.
    pub map: Vec<Complex64>,
    /// The transform `m`: centring, then rotation.
    pub mobius: DiskAutomorphism,
}

/// Applies the paper's `m₁` to `map`: `m = R ∘ φ` with `φ(z) = (z − z₁)/(1 − z̄₁ z)`
/// (`z₁ = map[centre]`, so `φ(z₁) = 0`) and `R` the rotation taking `φ(map[direction])`
/// onto the positive real axis.
///
/// # Errors
/// [`MorphError::LandmarkOnBoundary`] if either landmark is (within
/// [`NORMALIZE_BOUNDARY_TOL`]) on the unit circle; [`MorphError::Mobius`] if the transform
/// cannot be formed.
///
/// # Examples
/// ```
/// use conformap_morph::normalize_disk_map;
/// use num_complex::Complex64;
/// let map = vec![Complex64::new(0.3, 0.2), Complex64::new(-0.1, 0.5), Complex64::new(1.0, 0.0)];
/// let n = normalize_disk_map(&map, 0, 1, 0)?;
/// assert!(n.map[0].norm() < 1e-15);
/// assert!(n.map[1].im.abs() < 1e-15 && n.map[1].re > 0.0);
/// assert!((n.map[2].norm() - 1.0).abs() < 1e-15); // the circle is kept
/// # Ok::<(), conformap_morph::MorphError>(())
/// ```
pub fn normalize_disk_map(
    map: &[Complex64],
    centre: u32,
    direction: u32,
    surface: usize,
) -> Result<Normalized, MorphError> {
    let check = |index: usize, vertex: u32| -> Result<Complex64, MorphError> {
        let z = map[vertex as usize];
        let radius = z.norm();
        if !(radius < 1.0 - NORMALIZE_BOUNDARY_TOL) {
            return Err(MorphError::LandmarkOnBoundary {
                surface,
                index,
                vertex,
                radius,
            });
        }
        Ok(z)
    };
    let z1 = check(0, centre)?;
    let z2 = check(1, direction)?;
    let centring = DiskAutomorphism::try_new(Complex64::new(1.0, 0.0), -z1)
        .map_err(|source| MorphError::Mobius { surface, source })?;
    let w2 = centring.apply(z2);
    let mobius = DiskAutomorphism::rotation(-w2.arg()).compose(&centring);
    let mut out: Vec<Complex64> = map.iter().map(|&z| mobius.apply(z)).collect();
    // exactly the centre (the composed coefficients leave ~1e-17 there)
    out[centre as usize] = Complex64::new(0.0, 0.0);
    Ok(Normalized { map: out, mobius })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn centre_and_direction_and_inverse() {
        let map: Vec<Complex64> = (0..40)
            .map(|k| Complex64::from_polar(0.05 + 0.9 * (k as f64 / 40.0), 2.4 * k as f64))
            .collect();
        let n = match normalize_disk_map(&map, 7, 23, 0) {
            Ok(n) => n,
            Err(e) => panic!("{e}"),
        };
        assert_eq!(n.map[7], Complex64::new(0.0, 0.0));
        assert!(n.map[23].arg().abs() < 1e-14 && n.map[23].re > 0.0);
        let inv = n.mobius.inverse();
        for (z, w) in map.iter().zip(&n.map).filter(|(_, w)| w.norm() > 0.0) {
            assert!((inv.apply(*w) - z).norm() < 1e-13);
            assert!(w.norm() < 1.0);
        }
    }

    #[test]
    fn boundary_landmarks_are_refused() {
        let map = vec![
            Complex64::new(0.2, 0.0),
            Complex64::new(0.0, 1.0),
            Complex64::new(0.0, 0.3),
        ];
        assert!(matches!(
            normalize_disk_map(&map, 1, 2, 3),
            Err(MorphError::LandmarkOnBoundary {
                surface: 3,
                index: 0,
                vertex: 1,
                ..
            })
        ));
        assert!(matches!(
            normalize_disk_map(&map, 0, 1, 0),
            Err(MorphError::LandmarkOnBoundary { index: 1, .. })
        ));
    }
}
