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

/// How [`round_mouth`] purses a mouth: the opening's half-width and half-height as
/// fractions of the mouth's half-width (corner to corner / 2), how far forward the rim
/// goes (the same fraction), and the radius (the same fraction) beyond which nothing
/// moves.
#[derive(Debug, Clone, Copy)]
pub struct Pucker {
    /// Half-width of the round opening: `0.7` of the mouth's half-width (narrower
    /// openings crush the mouth corners into extra crease lines that cut the rim's
    /// crease loop: 0.5 and 0.3 did).
    pub half_width: f64,
    /// Half-height: `0.75` (a slightly tall "O", so that its two vertices farthest apart
    /// are the top and the bottom of the opening, not the mouth corners).
    pub half_height: f64,
    /// Forward push of the rim (along +z, the face's view direction): `0.3`.
    pub push: f64,
    /// Vertices farther than this from the mouth's centre stay: `2.5`.
    pub reach: f64,
    /// Rings of vertices around the rim that move with it (the lips' roll into the
    /// mouth, which makes the rim a crease): `2`.
    pub rigid_rings: usize,
    /// Passes of smoothing of the moves off the rim (each vertex halfway to the mean of
    /// its neighbours' moves): `1`. Without it the edge of the rings that move with the
    /// rim leaves extra crease lines beside the opening (16 + 9 + 3 vertices on each
    /// side, against 14 with one pass); 10 passes flatten the lips' roll so much that
    /// the rim is no longer a crease loop.
    pub smoothing: usize,
}

impl Pucker {
    /// The values documented on the fields.
    pub const DEFAULT: Self = Self {
        half_width: 0.7,
        half_height: 0.75,
        push: 0.3,
        reach: 2.5,
        rigid_rings: 2,
        smoothing: 1,
    };
}

/// Gauss–Seidel sweeps of [`round_mouth`]'s harmonic extension: at most `20000`, stopped
/// when no vertex moves by more than `1e-12` of the mouth's half-width in a sweep (the
/// region holds a few hundred vertices; it converges in a few thousand sweeps).
const PUCKER_SWEEPS: usize = 20_000;

/// The face `mesh` with its mouth pursed into a round "O" pushed forward: the crease
/// loop nearest to both mouth corners `corners = (right, left)` (the rim of the zipped
/// mouth fill of the shared faces, y up, looking along +z; cut at its two vertices
/// farthest apart, the ends of the fill's zip) goes onto an ellipse
/// ([`Pucker`]) around the corners' midpoint, each side of the rim by its share of 3D
/// arc length (the upper side over the top, corner to corner), and every other vertex
/// within `reach` follows by the harmonic extension of the rim's moves (uniform graph
/// Laplacian; vertices beyond `reach` are held). Vertex order and faces are `mesh`'s.
///
/// # Panics
/// If the mesh has no crease loop.
pub fn round_mouth(mesh: &TriMesh, corners: (u32, u32), pucker: &Pucker) -> TriMesh {
    use std::f64::consts::PI;
    let p = mesh.positions();
    let loops = crate::creases::crease_loops(p, mesh.faces(), crate::quality::CREASE_ANGLE_DEG);
    let dist = |a: [f64; 3], b: [f64; 3]| {
        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
    };
    // the loop nearest to the corners, and its vertices nearest to each (the mouth
    // corners of the shared faces lie a ring of faces off the rim)
    let nearest = |lp: &[u32], v: u32| {
        lp.iter()
            .copied()
            .min_by(|&a, &b| {
                dist(p[a as usize], p[v as usize]).total_cmp(&dist(p[b as usize], p[v as usize]))
            })
            .unwrap_or(v)
    };
    let off = |lp: &[u32]| {
        dist(p[nearest(lp, corners.0) as usize], p[corners.0 as usize])
            + dist(p[nearest(lp, corners.1) as usize], p[corners.1 as usize])
    };
    let rim = loops
        .iter()
        .min_by(|a, b| off(a).total_cmp(&off(b)))
        .unwrap_or_else(|| panic!("doc_support: no crease loop"));
    // the rim's two vertices farthest apart (the ends of the fill's zip), the one nearer
    // to the right mouth corner first
    let mut ends = (rim[0], rim[0], -1.0);
    for (i, &a) in rim.iter().enumerate() {
        for &b in &rim[i + 1..] {
            let d = dist(p[a as usize], p[b as usize]);
            if d > ends.2 {
                ends = (a, b, d);
            }
        }
    }
    let to_right = |v: u32| dist(p[v as usize], p[corners.0 as usize]);
    let (right, left) = if to_right(ends.0) <= to_right(ends.1) {
        (ends.0, ends.1)
    } else {
        (ends.1, ends.0)
    };
    let n = rim.len();
    let start = rim.iter().position(|&v| v == right).unwrap_or(0);
    let rim: Vec<u32> = (0..n).map(|i| rim[(start + i) % n]).collect();
    let mid = rim.iter().position(|&v| v == left).unwrap_or(n / 2);
    let (pr, pl) = (p[right as usize], p[left as usize]);
    let centre = [
        0.5 * (pr[0] + pl[0]),
        0.5 * (pr[1] + pl[1]),
        0.5 * (pr[2] + pl[2]),
    ];
    let half = 0.5 * dist(pr, pl);
    // the two sides, each from the right corner to the left one
    let side_a: Vec<u32> = rim[..=mid].to_vec();
    let side_b: Vec<u32> = std::iter::once(right)
        .chain(rim[mid..].iter().rev().copied())
        .collect();
    let mean_y = |s: &[u32]| s.iter().map(|&v| p[v as usize][1]).sum::<f64>() / s.len() as f64;
    let mut target: Vec<Option<[f64; 3]>> = vec![None; p.len()];
    for side in [&side_a, &side_b] {
        let upper = mean_y(side) >= mean_y(if side == &side_a { &side_b } else { &side_a });
        let mut s = vec![0.0];
        for w in side.windows(2) {
            s.push(s[s.len() - 1] + dist(p[w[0] as usize], p[w[1] as usize]));
        }
        let total = s[s.len() - 1];
        for (&v, &si) in side.iter().zip(&s) {
            let share = si / total;
            let theta = if upper {
                PI * (1.0 - share)
            } else {
                PI * (1.0 + share)
            };
            target[v as usize] = Some([
                centre[0] + pucker.half_width * half * theta.cos(),
                centre[1] + pucker.half_height * half * theta.sin(),
                centre[2] + pucker.push * half,
            ]);
        }
    }
    // neighbours (graph of the edges)
    let mut nb: Vec<Vec<u32>> = vec![Vec::new(); p.len()];
    for f in mesh.faces() {
        for e in 0..3 {
            let (a, b) = (f[e], f[(e + 1) % 3]);
            if !nb[a as usize].contains(&b) {
                nb[a as usize].push(b);
                nb[b as usize].push(a);
            }
        }
    }
    let mut d: Vec<[f64; 3]> = vec![[0.0; 3]; p.len()];
    let mut held = vec![false; p.len()];
    let mut front = Vec::new();
    for (v, q) in p.iter().enumerate() {
        if let Some(t) = target[v] {
            d[v] = [t[0] - q[0], t[1] - q[1], t[2] - q[2]];
            held[v] = true;
            front.push(v);
        }
    }
    // the lips' roll next to the rim moves with it: each vertex within `rigid_rings`
    // rings turns (about z) and moves with the rim vertex it is reached from first, by
    // the turn of the rim's tangent there and that vertex's move
    let mut source: Vec<u32> = (0..p.len() as u32).collect();
    for _ in 0..pucker.rigid_rings {
        let mut next = Vec::new();
        for &v in &front {
            for &w in &nb[v] {
                if !held[w as usize] {
                    held[w as usize] = true;
                    source[w as usize] = source[v];
                    next.push(w as usize);
                }
            }
        }
        front = next;
    }
    let mut turn = vec![(1.0, 0.0); p.len()];
    for i in 0..n {
        let (a, r, b) = (rim[(i + n - 1) % n], rim[i], rim[(i + 1) % n]);
        let (ta, tb) = (target[a as usize], target[b as usize]);
        if let (Some(ta), Some(tb)) = (ta, tb) {
            let (pa, pb) = (p[a as usize], p[b as usize]);
            let before = (pb[1] - pa[1]).atan2(pb[0] - pa[0]);
            let after = (tb[1] - ta[1]).atan2(tb[0] - ta[0]);
            turn[r as usize] = ((after - before).cos(), (after - before).sin());
        }
    }
    for v in 0..p.len() {
        let r = source[v] as usize;
        if held[v] && r != v {
            let (c, s) = turn[r];
            let (x, y) = (p[v][0] - p[r][0], p[v][1] - p[r][1]);
            let to = [
                p[r][0] + d[r][0] + c * x - s * y,
                p[r][1] + d[r][1] + s * x + c * y,
                p[v][2] + d[r][2],
            ];
            d[v] = [to[0] - p[v][0], to[1] - p[v][1], to[2] - p[v][2]];
        }
    }
    let free: Vec<usize> = (0..p.len())
        .filter(|&v| !held[v] && dist(p[v], centre) < pucker.reach * half)
        .collect();
    for _ in 0..PUCKER_SWEEPS {
        let mut change = 0.0f64;
        for &v in &free {
            let k = nb[v].len() as f64;
            let mut m = [0.0; 3];
            for &w in &nb[v] {
                for c in 0..3 {
                    m[c] += d[w as usize][c] / k;
                }
            }
            change = change.max(dist(m, d[v]));
            d[v] = m;
        }
        if change <= 1e-12 * half {
            break;
        }
    }
    // smoothing of the moves (not the positions) off the rim, so that the rings that
    // move with the rim blend into the harmonic part
    let near: Vec<usize> = (0..p.len())
        .filter(|&v| target[v].is_none() && dist(p[v], centre) < pucker.reach * half)
        .collect();
    for _ in 0..pucker.smoothing {
        let before = d.clone();
        for &v in &near {
            let k = nb[v].len() as f64;
            for c in 0..3 {
                let mean = nb[v].iter().map(|&w| before[w as usize][c]).sum::<f64>() / k;
                d[v][c] = 0.5 * before[v][c] + 0.5 * mean;
            }
        }
    }
    let moved = p
        .iter()
        .zip(&d)
        .map(|(q, m)| [q[0] + m[0], q[1] + m[1], q[2] + m[2]])
        .collect();
    match TriMesh::try_new(moved, mesh.faces().to_vec()) {
        Ok(m) => m,
        Err(e) => panic!("doc_support: the pursed mouth is not a mesh: {e}"),
    }
}
