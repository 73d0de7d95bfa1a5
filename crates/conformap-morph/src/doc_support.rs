//! Analytic test surfaces for the doctests and tests (not part of the API): one bumpy
//! "face" sampled on two different polar grids, the second deformed like a change of
//! expression, with the same named landmarks on both.

use std::f64::consts::TAU;

use conformap_mesh::TriMesh;

use crate::Landmarks;

/// The material points of the landmarks (in the undeformed parameter plane) and their
/// names: the top of the main bump first (the centre of the normalization), then a
/// direction.
pub const MATERIAL_LANDMARKS: [([f64; 2], &str); 5] = [
    ([0.0, 0.0], "top"),
    ([0.45, 0.0], "east"),
    ([0.0, 0.45], "north"),
    ([-0.35, -0.3], "south_west"),
    ([0.3, -0.4], "dimple"),
];

/// The height of the surface over material point `(x, y)`: a main bump and a dimple.
pub fn height(x: f64, y: f64) -> f64 {
    0.5 * (-(x * x + y * y) / 0.15).exp()
        - 0.15 * (-((x - 0.3).powi(2) + (y + 0.4).powi(2)) / 0.03).exp()
}

/// A polar grid of `rings` rings, ring `k` with `sectors · k` vertices, boundary radius
/// `radius(θ)`, vertex 0 the centre; material points and faces (counter-clockwise).
pub fn polar_grid(
    rings: usize,
    sectors: usize,
    phase: f64,
    radius: impl Fn(f64) -> f64,
) -> (Vec<[f64; 2]>, Vec<[u32; 3]>) {
    let mut pts = vec![[0.0, 0.0]];
    let mut ring_start = vec![0usize];
    let mut ring_len = vec![1usize];
    for k in 1..=rings {
        let n = sectors * k;
        ring_start.push(pts.len());
        ring_len.push(n);
        for j in 0..n {
            let t = phase + TAU * j as f64 / n as f64;
            let r = radius(t) * k as f64 / rings as f64;
            pts.push([r * t.cos(), r * t.sin()]);
        }
    }
    let mut faces = Vec::new();
    let n1 = ring_len[1];
    for j in 0..n1 {
        faces.push([0, (1 + j) as u32, (1 + (j + 1) % n1) as u32]);
    }
    for k in 1..rings {
        let (si, ni) = (ring_start[k], ring_len[k]);
        let (so, no) = (ring_start[k + 1], ring_len[k + 1]);
        let (mut i, mut j) = (0usize, 0usize);
        while i < ni || j < no {
            // advance on the ring whose next vertex comes first in angle
            let ai = (i + 1) as f64 / ni as f64;
            let aj = (j + 1) as f64 / no as f64;
            let inner = |x: usize| (si + x % ni) as u32;
            let outer = |x: usize| (so + x % no) as u32;
            if j < no && (i >= ni || aj <= ai) {
                faces.push([inner(i), outer(j), outer(j + 1)]);
                j += 1;
            } else {
                faces.push([inner(i), outer(j), inner(i + 1)]);
                i += 1;
            }
        }
    }
    (pts, faces)
}

/// The "expression" deformation of the plane applied to the second surface.
pub fn deform(p: [f64; 2]) -> [f64; 2] {
    let [x, y] = p;
    [
        x + 0.08 * x * y + 0.03 * (3.0 * y).sin(),
        1.05 * y + 0.06 * (2.0 * x).sin(),
    ]
}

fn lift(pts: &[[f64; 2]], deformed: bool) -> Vec<[f64; 3]> {
    pts.iter()
        .map(|&p| {
            let h = height(p[0], p[1]);
            if deformed {
                let q = deform(p);
                [q[0], q[1], 1.2 * h + 0.05 * p[0]]
            } else {
                [p[0], p[1], h]
            }
        })
        .collect()
}

/// Vertex of `pts` nearest to each material landmark.
fn nearest(pts: &[[f64; 2]]) -> Vec<u32> {
    MATERIAL_LANDMARKS
        .iter()
        .map(|(m, _)| {
            let d = |p: &[f64; 2]| (p[0] - m[0]).powi(2) + (p[1] - m[1]).powi(2);
            (0..pts.len())
                .min_by(|&a, &b| d(&pts[a]).total_cmp(&d(&pts[b])))
                .unwrap_or(0) as u32
        })
        .collect()
}

/// A surface of the bump family with its landmarks: `rings`, `sectors`, grid `phase`,
/// boundary `radius(θ)`, deformed or not.
pub fn bump_surface(
    rings: usize,
    sectors: usize,
    phase: f64,
    radius: impl Fn(f64) -> f64,
    deformed: bool,
) -> (TriMesh, Landmarks) {
    let (pts, faces) = polar_grid(rings, sectors, phase, radius);
    let lm = nearest(&pts);
    let mesh = match TriMesh::try_new(lift(&pts, deformed), faces) {
        Ok(m) => m,
        Err(e) => panic!("doc_support: bad analytic mesh: {e}"),
    };
    let pairs = lm
        .into_iter()
        .zip(MATERIAL_LANDMARKS.iter().map(|(_, n)| n.to_string()))
        .collect();
    match Landmarks::new(pairs) {
        Ok(l) => (mesh, l),
        Err(e) => panic!("doc_support: {e}"),
    }
}

/// Two bump surfaces with their landmarks: a round one on 16 rings × 6 sectors, and the
/// deformed one on a rotated 13 × 7 grid with a wavy boundary (different vertex counts and
/// boundaries).
pub fn two_bumps_with_landmarks() -> ((TriMesh, Landmarks), (TriMesh, Landmarks)) {
    (
        bump_surface(16, 6, 0.0, |_| 1.0, false),
        bump_surface(13, 7, 0.2, |t| 0.95 + 0.05 * (3.0 * t).sin(), true),
    )
}
