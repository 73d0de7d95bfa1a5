//! [`Camera`]: an orthographic camera that fits what it looks at, by default along the
//! smallest principal axis of the surface.

use conformap_operators::vec3::{axpy, cross, dot, normalize, sub};

/// Fraction of the viewport left free on every side when a camera fits its points: 4 %.
pub const FIT_MARGIN: f64 = 0.04;

/// `|d · y|` above which the world `y` axis is too close to the view direction to serve as
/// the picture's up direction (then `z`, then the largest principal axis are tried): 0.95.
const UP_PARALLEL: f64 = 0.95;

/// An orthographic camera: an orthonormal frame (right, up, forward) and a scale from
/// world units to sample pixels around a centre.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Direction the camera looks along (unit), into the picture.
    pub forward: [f64; 3],
    /// Picture's up direction (unit, orthogonal to `forward`).
    pub up: [f64; 3],
    /// Picture's right direction, `forward × up`.
    pub right: [f64; 3],
    /// World point drawn at `screen_center`.
    pub center: [f64; 3],
    /// Sample pixels per world unit.
    pub scale: f64,
    /// Screen position (in sample pixels, `y` down) of `center`.
    pub screen_center: [f64; 2],
}

/// A rectangle of the picture in pixels: `[x0, y0, x1, y1]` (`y` down).
pub type Viewport = [f64; 4];

impl Camera {
    /// A camera looking along `forward` with `up` as near the picture's up as possible,
    /// turned by `azimuth_deg` around `up` and tilted by `elevation_deg` (positive looks
    /// down on the object). Not yet fitted: call [`Camera::fit`].
    pub fn looking(forward: [f64; 3], up: [f64; 3], azimuth_deg: f64, elevation_deg: f64) -> Self {
        let d = normalize(forward);
        let u = normalize(axpy(-dot(up, d), d, up));
        let r = cross(d, u);
        let (sa, ca) = azimuth_deg.to_radians().sin_cos();
        let d1 = [
            d[0] * ca - r[0] * sa,
            d[1] * ca - r[1] * sa,
            d[2] * ca - r[2] * sa,
        ];
        let r1 = [
            r[0] * ca + d[0] * sa,
            r[1] * ca + d[1] * sa,
            r[2] * ca + d[2] * sa,
        ];
        let (se, ce) = elevation_deg.to_radians().sin_cos();
        let d2 = [
            d1[0] * ce - u[0] * se,
            d1[1] * ce - u[1] * se,
            d1[2] * ce - u[2] * se,
        ];
        let u2 = [
            u[0] * ce + d1[0] * se,
            u[1] * ce + d1[1] * se,
            u[2] * ce + d1[2] * se,
        ];
        Self {
            forward: d2,
            up: u2,
            right: r1,
            center: [0.0; 3],
            scale: 1.0,
            screen_center: [0.0; 2],
        }
    }

    /// The default camera for a surface: looks along the smallest principal axis of the
    /// vertex positions, from the side most face normals point to (`normals_sum`: the sum
    /// of the area-weighted face normals; for closed surfaces, where it vanishes, from the
    /// positive side of the axis' largest component), with the world `y` axis up where it is
    /// not too close to the view direction (else `z`, else the largest principal axis).
    pub fn principal(
        positions: &[[f64; 3]],
        normals_sum: [f64; 3],
        azimuth_deg: f64,
        elevation_deg: f64,
    ) -> Self {
        let axes = principal_axes(positions);
        let mut d = axes[2];
        let total = dot(normals_sum, normals_sum).sqrt();
        let s = dot(normals_sum, d);
        let flip = if s.abs() > 1e-6 * total && total > 0.0 {
            // the camera looks against the normals
            s > 0.0
        } else {
            let k = (0..3)
                .max_by(|&a, &b| d[a].abs().total_cmp(&d[b].abs()))
                .unwrap_or(0);
            d[k] > 0.0
        };
        if flip {
            d = d.map(|x| -x);
        }
        let up = if dot(d, [0.0, 1.0, 0.0]).abs() < UP_PARALLEL {
            [0.0, 1.0, 0.0]
        } else if dot(d, [0.0, 0.0, 1.0]).abs() < UP_PARALLEL {
            [0.0, 0.0, 1.0]
        } else {
            axes[0]
        };
        Self::looking(d, up, azimuth_deg, elevation_deg)
    }

    /// Centres and scales the camera so every point of `points` lands inside `viewport`
    /// (sample pixels) with [`FIT_MARGIN`] free on each side; `None` if the points have no
    /// extent (empty, or all projected onto one point).
    pub fn fit<'a>(
        mut self,
        points: impl Iterator<Item = &'a [f64; 3]>,
        viewport: Viewport,
    ) -> Option<Self> {
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in points {
            let (x, y) = (dot(*p, self.right), dot(*p, self.up));
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        let (w, h) = (x1 - x0, y1 - y0);
        if !(w.max(h) > 0.0) || !w.is_finite() || !h.is_finite() {
            return None;
        }
        let (vw, vh) = (viewport[2] - viewport[0], viewport[3] - viewport[1]);
        let free = 1.0 - 2.0 * FIT_MARGIN;
        self.scale = (free * vw / w).min(free * vh / h);
        let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        self.center = axpy(
            cy,
            self.up,
            [cx * self.right[0], cx * self.right[1], cx * self.right[2]],
        );
        self.screen_center = [
            0.5 * (viewport[0] + viewport[2]),
            0.5 * (viewport[1] + viewport[3]),
        ];
        Some(self)
    }

    /// Screen position `(x, y)` in sample pixels (`y` down) and depth (distance along
    /// `forward`; smaller is nearer) of the world point `p`.
    #[inline]
    pub fn project(&self, p: [f64; 3]) -> [f64; 3] {
        let q = sub(p, self.center);
        [
            self.screen_center[0] + self.scale * dot(q, self.right),
            self.screen_center[1] - self.scale * dot(q, self.up),
            dot(q, self.forward),
        ]
    }
}

/// The principal axes of the points (eigenvectors of their covariance), largest variance
/// first; the identity for fewer than two points.
pub fn principal_axes(points: &[[f64; 3]]) -> [[f64; 3]; 3] {
    let n = points.len() as f64;
    if points.len() < 2 {
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    let mut mean = [0.0; 3];
    for p in points {
        for k in 0..3 {
            mean[k] += p[k] / n;
        }
    }
    let mut c = [[0.0; 3]; 3];
    for p in points {
        let q = sub(*p, mean);
        for i in 0..3 {
            for j in 0..3 {
                c[i][j] += q[i] * q[j] / n;
            }
        }
    }
    let (values, vectors) = jacobi_eigen(c);
    let mut order = [0usize, 1, 2];
    order.sort_by(|&a, &b| values[b].total_cmp(&values[a]));
    order.map(|k| [vectors[0][k], vectors[1][k], vectors[2][k]])
}

/// Cyclic Jacobi sweeps that diagonalize a symmetric 3×3 matrix: sweeps until the
/// off-diagonal part is below `1e-15` of the norm; at most 32 (each sweep squares the
/// error, so a handful suffices). Returns the eigenvalues and the eigenvectors as columns.
fn jacobi_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    const SWEEPS: usize = 32;
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let norm: f64 = a.iter().flatten().map(|x| x * x).sum::<f64>().sqrt();
    for _ in 0..SWEEPS {
        let off = (a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2]).sqrt();
        if !(off > 1e-15 * norm) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = c * akp - s * akq;
                a[k][q] = s * akp + c * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = c * apk - s * aqk;
                a[q][k] = s * apk + c * aqk;
            }
            for k in 0..3 {
                let (vkp, vkq) = (v[k][p], v[k][q]);
                v[k][p] = c * vkp - s * vkq;
                v[k][q] = s * vkp + c * vkq;
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn principal_axes_of_a_box_cloud() {
        // a flat cloud: long along x, medium along z, thin along y
        let mut pts = Vec::new();
        for i in 0..10 {
            for j in 0..5 {
                for k in 0..2 {
                    pts.push([i as f64 * 1.0, k as f64 * 0.1, j as f64 * 0.5]);
                }
            }
        }
        let axes = principal_axes(&pts);
        assert!(axes[0][0].abs() > 1.0 - 1e-12);
        assert!(axes[1][2].abs() > 1.0 - 1e-12);
        assert!(axes[2][1].abs() > 1.0 - 1e-12);
    }

    #[test]
    fn fit_puts_points_inside_the_viewport() {
        let pts = [[0.0, 0.0, 0.0], [2.0, 1.0, 0.0], [1.0, 3.0, 0.5]];
        let cam = Camera::looking([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], 0.0, 0.0)
            .fit(pts.iter(), [0.0, 0.0, 100.0, 200.0])
            .expect("extent");
        for p in pts {
            let s = cam.project(p);
            assert!(
                s[0] >= 3.9 && s[0] <= 96.1 && s[1] >= 3.9 && s[1] <= 196.1,
                "{s:?}"
            );
        }
        // x to the right, y up
        assert!(cam.project([2.0, 0.0, 0.0])[0] > cam.project([0.0, 0.0, 0.0])[0]);
        assert!(cam.project([0.0, 3.0, 0.0])[1] < cam.project([0.0, 0.0, 0.0])[1]);
    }

    #[test]
    fn azimuth_and_elevation_turn_the_frame() {
        let cam = Camera::looking([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], 90.0, 0.0);
        // turned a quarter to the right: now looks along −x
        assert!((cam.forward[0] + 1.0).abs() < 1e-12);
        let cam = Camera::looking([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], 0.0, 90.0);
        // from above: looks down −y
        assert!((cam.forward[1] + 1.0).abs() < 1e-12);
        assert!(dot(cam.forward, cam.up).abs() < 1e-12 && dot(cam.right, cam.up).abs() < 1e-12);
    }
}
