//! Local untangling of a planar map: the free vertices of folded faces are moved into the
//! kernel of their one-ring polygon, as little as possible.
//!
//! The constraint that vertex `v` at `x` keeps face `(v, a, b)` of its one ring
//! positively oriented is linear in `x`: the signed distance of `x` from the line through
//! `a` and `b`, `d(x) = σ (a × b + (b − a) × x) / |b − a|`, must be positive. The
//! intersection of those half-planes is the kernel of the one-ring polygon; when it is
//! not empty, `v` goes to the point nearest its current position among those at distance
//! at least [`UNTANGLE_MARGIN`] × ρ* from every line (ρ*: the radius of the largest
//! circle in the kernel, its Chebyshev radius), so its faces are not slivers. Both are
//! found by enumeration (a one ring has 3–12 lines): the Chebyshev centre lies where
//! three of the lines are at equal distance, the nearest point is the current position,
//! a projection onto one shrunk line or the crossing of two.
//!
//! A round treats the free vertices of the folded faces, grown by one more ring of
//! neighbours after every round that did not reduce the folded faces (a vertex whose
//! kernel is empty waits for its neighbours to move), in ascending order (Gauss–Seidel,
//! deterministic). Vertices that are not free never move.

use num_complex::Complex64;

/// Untangling rounds at most: `32`. A round costs a pass over the faces; on the shared
/// faces the rim moves of wry fold 12 faces of S1's disk, which one round untangles.
pub const UNTANGLE_MAX_ROUNDS: usize = 32;

/// The margin a moved vertex keeps from the lines of its one ring, as a fraction of the
/// ring kernel's Chebyshev radius: `0.5`. `0` would put it on the kernel's edge (a
/// degenerate face), `1` at the Chebyshev centre whatever its position was; a half keeps
/// every face of the ring at least half as tall as the fattest placement allows while
/// moving the vertex little.
pub const UNTANGLE_MARGIN: f64 = 0.5;

/// For every vertex, the edges `(a, b)` opposite it in its faces, oriented as the faces
/// (`[v, a, b]` is a cyclic rotation of the face): the lines of its ring kernel.
#[derive(Debug, Clone)]
pub(crate) struct Rings {
    offsets: Vec<usize>,
    edges: Vec<[u32; 2]>,
}

impl Rings {
    /// The rings of the `n` vertices of `faces`.
    pub fn new(faces: &[[u32; 3]], n: usize) -> Self {
        let mut count = vec![0usize; n + 1];
        for f in faces {
            for &v in f {
                count[v as usize + 1] += 1;
            }
        }
        for i in 0..n {
            count[i + 1] += count[i];
        }
        let offsets = count.clone();
        let mut edges = vec![[0u32; 2]; offsets[n]];
        let mut next = count;
        for f in faces {
            for c in 0..3 {
                let v = f[c] as usize;
                edges[next[v]] = [f[(c + 1) % 3], f[(c + 2) % 3]];
                next[v] += 1;
            }
        }
        Self { offsets, edges }
    }

    /// The edges opposite vertex `v`.
    pub fn of(&self, v: usize) -> &[[u32; 2]] {
        &self.edges[self.offsets[v]..self.offsets[v + 1]]
    }
}

/// What an untangling did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Untangled {
    /// Rounds run.
    pub rounds: usize,
    /// Distinct vertices moved.
    pub moved: usize,
    /// Faces still folded at the end.
    pub folded_left: usize,
}

/// `a × b` (the z component of the cross product).
fn cross(a: Complex64, b: Complex64) -> f64 {
    a.re * b.im - a.im * b.re
}

/// A line `n · x + c = d(x)` (unit `n`): `d` is the signed distance from the line.
#[derive(Debug, Clone, Copy)]
struct Line {
    n: Complex64,
    c: f64,
}

impl Line {
    fn dist(&self, x: Complex64) -> f64 {
        self.n.re * x.re + self.n.im * x.im + self.c
    }
}

/// The lines of `v`'s ring kernel at the current positions (skipping zero-length edges).
fn kernel_lines(rings: &Rings, v: usize, map: &[Complex64], sigma: f64) -> Vec<Line> {
    rings
        .of(v)
        .iter()
        .filter_map(|&[a, b]| {
            let (a, b) = (map[a as usize], map[b as usize]);
            let e = b - a;
            let len = e.norm();
            // σ (a × b + e × x) / |e|, with e × x = e.re x.im − e.im x.re
            (len > 0.0).then(|| Line {
                n: Complex64::new(-e.im, e.re) * (sigma / len),
                c: sigma * cross(a, b) / len,
            })
        })
        .collect()
}

/// The point where `d_i − t`, `d_j − t`, `d_k − t` vanish: `(x, t)`, if the 3 × 3 system
/// is regular.
fn equidistant(l: [&Line; 3]) -> Option<(Complex64, f64)> {
    // rows [n.re, n.im, −1] · (x, y, t) = −c
    let m = l.map(|q| [q.n.re, q.n.im, -1.0]);
    let r = l.map(|q| -q.c);
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(m);
    if d.abs() < 1e-12 {
        return None;
    }
    let solve = |col: usize| {
        let mut mc = m;
        for row in 0..3 {
            mc[row][col] = r[row];
        }
        det(mc) / d
    };
    Some((Complex64::new(solve(0), solve(1)), solve(2)))
}

/// The Chebyshev radius of the kernel (the largest `t` with `d_i(x) ≥ t` for all `i`):
/// `None` when the lines bound no region (fewer than three, or parallel).
fn chebyshev_radius(lines: &[Line]) -> Option<f64> {
    let n = lines.len();
    let mut best: Option<f64> = None;
    for i in 0..n {
        for j in i + 1..n {
            for k in j + 1..n {
                let Some((x, t)) = equidistant([&lines[i], &lines[j], &lines[k]]) else {
                    continue;
                };
                // feasible: every line at least t away (up to rounding)
                let slack = 1e-12 * (1.0 + t.abs());
                if lines.iter().all(|q| q.dist(x) >= t - slack) && best.is_none_or(|b| t > b) {
                    best = Some(t);
                }
            }
        }
    }
    best
}

/// The point nearest `x0` with `d_i(x) ≥ margin` for every line (the region is not empty:
/// `margin` is below the Chebyshev radius).
fn nearest_inside(lines: &[Line], x0: Complex64, margin: f64) -> Option<Complex64> {
    let feasible = |x: Complex64| lines.iter().all(|q| q.dist(x) >= margin * (1.0 - 1e-9));
    if feasible(x0) {
        return Some(x0);
    }
    let mut candidates = Vec::new();
    for (i, p) in lines.iter().enumerate() {
        // projection of x0 onto the shrunk line d_i = margin
        candidates.push(x0 - p.n * (p.dist(x0) - margin));
        for q in &lines[i + 1..] {
            let det = p.n.re * q.n.im - p.n.im * q.n.re;
            if det.abs() < 1e-12 {
                continue;
            }
            // n_p · x = margin − c_p, n_q · x = margin − c_q
            let (rp, rq) = (margin - p.c, margin - q.c);
            candidates.push(Complex64::new(
                (rp * q.n.im - rq * p.n.im) / det,
                (p.n.re * rq - q.n.re * rp) / det,
            ));
        }
    }
    candidates
        .into_iter()
        .filter(|&x| feasible(x))
        .min_by(|a, b| (a - x0).norm_sqr().total_cmp(&(b - x0).norm_sqr()))
}

/// The faces of `map` folded or degenerate against the orientation `sigma`.
pub(crate) fn folded(faces: &[[u32; 3]], map: &[Complex64], sigma: f64) -> Vec<usize> {
    faces
        .iter()
        .enumerate()
        .filter(|(_, f)| {
            let [a, b, c] = f.map(|v| map[v as usize]);
            !(sigma * cross(b - a, c - a) > 0.0)
        })
        .map(|(k, _)| k)
        .collect()
}

/// Untangles `map` in place (see the module docs): only vertices with `free[v]` move.
pub(crate) fn untangle(
    map: &mut [Complex64],
    faces: &[[u32; 3]],
    rings: &Rings,
    free: &[bool],
    sigma: f64,
) -> Untangled {
    let n = map.len();
    let mut out = Untangled::default();
    let mut ever_moved = vec![false; n];
    let mut bad = folded(faces, map, sigma);
    let mut grow = 0;
    while !bad.is_empty() && out.rounds < UNTANGLE_MAX_ROUNDS {
        out.rounds += 1;
        // the vertices of the folded faces, grown by `grow` rings
        let mut active = vec![false; n];
        for &f in &bad {
            for &v in &faces[f] {
                active[v as usize] = true;
            }
        }
        for _ in 0..grow {
            let current: Vec<usize> = (0..n).filter(|&v| active[v]).collect();
            for v in current {
                for &[a, b] in rings.of(v) {
                    active[a as usize] = true;
                    active[b as usize] = true;
                }
            }
        }
        for v in (0..n).filter(|&v| active[v] && free[v]) {
            let lines = kernel_lines(rings, v, map, sigma);
            let Some(rho) = chebyshev_radius(&lines).filter(|&r| r > 0.0) else {
                continue;
            };
            if let Some(x) = nearest_inside(&lines, map[v], UNTANGLE_MARGIN * rho) {
                if x != map[v] {
                    map[v] = x;
                    ever_moved[v] = true;
                }
            }
        }
        let next = folded(faces, map, sigma);
        if next.len() >= bad.len() {
            grow += 1;
        }
        bad = next;
    }
    out.moved = ever_moved.iter().filter(|&&m| m).count();
    out.folded_left = bad.len();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A hexagon around a centre vertex 0, counter-clockwise.
    fn hexagon() -> (Vec<Complex64>, Vec<[u32; 3]>) {
        let mut p = vec![Complex64::new(0.0, 0.0)];
        for k in 0..6 {
            p.push(Complex64::from_polar(
                1.0,
                std::f64::consts::TAU * k as f64 / 6.0,
            ));
        }
        let f = (0..6u32).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        (p, f)
    }

    #[test]
    fn the_chebyshev_radius_of_a_regular_hexagon_is_its_inradius() {
        let (p, f) = hexagon();
        let rings = Rings::new(&f, p.len());
        let lines = kernel_lines(&rings, 0, &p, 1.0);
        assert_eq!(lines.len(), 6);
        let r = chebyshev_radius(&lines).unwrap_or(f64::NAN);
        assert!((r - 3f64.sqrt() / 2.0).abs() < 1e-12, "{r}");
    }

    #[test]
    fn a_centre_pushed_outside_its_ring_comes_back_nearest_inside() {
        let (mut p, f) = hexagon();
        // the centre beyond the edge (1, 2): three faces fold
        p[0] = Complex64::new(1.2, 1.0);
        assert!(!folded(&f, &p, 1.0).is_empty());
        let rings = Rings::new(&f, p.len());
        let mut free = vec![false; p.len()];
        free[0] = true;
        let before: Vec<Complex64> = p.clone();
        let u = untangle(&mut p, &f, &rings, &free, 1.0);
        assert_eq!((u.rounds, u.moved, u.folded_left), (1, 1, 0), "{u:?}");
        assert!(folded(&f, &p, 1.0).is_empty());
        // the ring did not move, and the centre keeps half the inradius from every edge
        assert_eq!(p[1..], before[1..]);
        let lines = kernel_lines(&rings, 0, &p, 1.0);
        let d = lines
            .iter()
            .map(|l| l.dist(p[0]))
            .fold(f64::INFINITY, f64::min);
        assert!((d - 0.5 * 3f64.sqrt() / 2.0).abs() < 1e-12, "{d}");
    }

    #[test]
    fn a_vertex_already_inside_stays_and_held_vertices_never_move() {
        let (mut p, f) = hexagon();
        p[0] = Complex64::new(0.1, -0.05);
        let rings = Rings::new(&f, p.len());
        let before = p.clone();
        let u = untangle(&mut p, &f, &rings, &[true; 7], 1.0);
        assert_eq!((u.rounds, u.moved), (0, 0));
        assert_eq!(p, before);
        p[0] = Complex64::new(3.0, 0.0);
        let u = untangle(&mut p, &f, &rings, &[false; 7], 1.0);
        assert_eq!((u.rounds, u.moved), (UNTANGLE_MAX_ROUNDS, 0));
        assert_eq!(u.folded_left, folded(&f, &p, 1.0).len());
        assert!(u.folded_left > 0);
    }
}
