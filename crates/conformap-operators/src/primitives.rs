//! Small geometric primitives with one home: 3D vector arithmetic on `[f64; 3]`
//! ([`vec3`]) and planar polygon and triangle areas on [`num_complex::Complex64`] points
//! ([`planar`]).
//!
//! Every crate of the workspace that needs a dot product or a shoelace area takes it from
//! here, so the rounding of those few operations is the same everywhere (the outputs of the
//! solvers depend on it to the last bit).

/// 3D vector arithmetic on `[f64; 3]`.
pub mod vec3 {
    /// Difference `a − b`.
    #[inline]
    pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    /// Sum `a + b`.
    #[inline]
    pub fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
    }

    /// `s · a`.
    #[inline]
    pub fn scale(s: f64, a: [f64; 3]) -> [f64; 3] {
        [s * a[0], s * a[1], s * a[2]]
    }

    /// `y + s · x`.
    #[inline]
    pub fn axpy(s: f64, x: [f64; 3], y: [f64; 3]) -> [f64; 3] {
        [y[0] + s * x[0], y[1] + s * x[1], y[2] + s * x[2]]
    }

    /// Dot product.
    #[inline]
    pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    /// Cross product.
    #[inline]
    pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    /// Euclidean length.
    #[inline]
    pub fn norm(a: [f64; 3]) -> f64 {
        dot(a, a).sqrt()
    }

    /// `a / |a|`; the zero vector (and a vector whose length is not positive, NaN) stays
    /// as it is.
    #[inline]
    pub fn normalize(a: [f64; 3]) -> [f64; 3] {
        let r = norm(a);
        if r > 0.0 {
            [a[0] / r, a[1] / r, a[2] / r]
        } else {
            a
        }
    }
}

/// Planar areas on complex points.
pub mod planar {
    use num_complex::Complex64;

    /// Signed area of the closed polygon through `z` in order (shoelace; positive
    /// counter-clockwise, 0 for fewer than three points).
    pub fn polygon_area(z: &[Complex64]) -> f64 {
        let m = z.len();
        let mut a = 0.0;
        for k in 0..m {
            let (p, q) = (z[k], z[(k + 1) % m]);
            a += p.re * q.im - q.re * p.im;
        }
        0.5 * a
    }

    /// Signed area of triangle `(p0, p1, p2)` (positive counter-clockwise).
    #[inline]
    pub fn triangle_signed_area(p0: Complex64, p1: Complex64, p2: Complex64) -> f64 {
        let (u, v) = (p1 - p0, p2 - p0);
        0.5 * (u.re * v.im - u.im * v.re)
    }
}

#[cfg(test)]
mod tests {
    use super::{planar, vec3};
    use num_complex::Complex64;

    #[test]
    fn unit_square_and_right_triangle() {
        let sq = [
            Complex64::new(0.0, 0.0),
            Complex64::new(2.0, 0.0),
            Complex64::new(2.0, 3.0),
            Complex64::new(0.0, 3.0),
        ];
        assert_eq!(planar::polygon_area(&sq), 6.0);
        let rev: Vec<_> = sq.iter().rev().copied().collect();
        assert_eq!(planar::polygon_area(&rev), -6.0);
        assert_eq!(planar::triangle_signed_area(sq[0], sq[1], sq[2]), 3.0);
        assert_eq!(planar::polygon_area(&sq[..2]), 0.0);
    }

    #[test]
    fn vector_identities() {
        let (a, b) = ([1.0, 2.0, 3.0], [-2.0, 0.5, 4.0]);
        let c = vec3::cross(a, b);
        assert_eq!(vec3::dot(c, a), 0.0);
        assert_eq!(vec3::dot(c, b), 0.0);
        assert_eq!(vec3::norm([3.0, 4.0, 0.0]), 5.0);
        assert_eq!(vec3::normalize([0.0; 3]), [0.0; 3]);
        assert_eq!(vec3::normalize([0.0, 0.0, 2.0]), [0.0, 0.0, 1.0]);
        assert_eq!(vec3::sub(vec3::add(a, b), b), a);
        assert_eq!(vec3::axpy(2.0, a, b), vec3::add(b, vec3::scale(2.0, a)));
    }
}
