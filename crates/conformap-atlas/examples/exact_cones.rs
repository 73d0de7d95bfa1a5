//! A measurement tool (issue 36): the exact discrete conformal metric
//! ([`exact::ExactMetric`], Springborn–Schröder–Pinkall, the mesh's connectivity kept) of
//! the automatically placed 8 cones against their linear cone metric (`ConeMetric`, one
//! Poisson solve), on the closed genus-0 meshes of `../shared/meshes` (or the meshes
//! given): the area spread of each (sd over faces of the log area scale), Newton steps,
//! the angle residual, triangles whose new lengths break a triangle inequality (the metric
//! then needs intrinsic flips to exist on this triangulation), and with `--angles` the
//! exact spread after re-optimizing the cone angles (positions kept) by projected gradient
//! descent. Results: docs/benchmarks.md, "Exact cone metric on spot".
//!
//! ```sh
//! cargo build --release --workspace --examples
//! target/release/examples/exact_cones [--angles] [MESH...]
//! ```

use std::f64::consts::{PI, TAU};
use std::time::Instant;

use conformap_atlas::{place_cones, ConeMetric, ConeOptions};
use conformap_mesh::TriMesh;
use exact::{ExactMetric, ExactOptions};

/// Gradient steps of the cone-angle re-optimization: 60, each a finite-difference
/// gradient (one exact solve per cone) and a line search of at most 8 halvings (spot:
/// 0.8322 after 20 steps, 0.8321 after 60, 45 s).
const ANGLE_STEPS: usize = 60;

/// Margin added to the least feasible blend toward equal defects: 0.02 of the way.
const BLEND_MARGIN: f64 = 0.02;

/// Finite-difference step of the angle gradient, radians of defect: 1e-4 (the exact
/// solve converges to 1e-10, so the difference quotient is good to about 1e-6).
const FD_STEP: f64 = 1e-4;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let angles = args.iter().any(|a| a == "--angles");
    args.retain(|a| a != "--angles");
    let shared = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/meshes");
    let meshes: Vec<String> = if args.is_empty() {
        ["spot", "armadillo", "brain", "david_head"]
            .iter()
            .map(|m| format!("{shared}/{m}.obj"))
            .collect()
    } else {
        args
    };
    println!("| mesh | faces | linear spread | exact spread | exact, valid faces only | Newton steps | residual rad | degenerate triangles | shortened steps | exact ms | exact, angles re-optimized |");
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for path in meshes {
        let mesh = conformap_io::read_mesh(&path)?.mesh;
        let name = std::path::Path::new(&path)
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let metric = ConeMetric::new(&mesh)?;
        let set = place_cones(&metric, 8, &ConeOptions::default());
        let cones: Vec<(u32, f64)> = set.cones.iter().map(|c| (c.vertex, c.defect)).collect();
        let t = Instant::now();
        let exact = ExactMetric::new(&mesh, &cones, &ExactOptions::DEFAULT);
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let Some(exact) = exact else {
            println!(
                "| {name} | {} | {:.4} | Newton failed | | | | | | {ms:.0} | |",
                mesh.num_faces(),
                set.area_spread
            );
            continue;
        };
        let (best, optimized) = if angles {
            let (s, c) = reoptimize(&mesh, &cones);
            (format!("{s:.4}"), c)
        } else {
            ("–".to_string(), cones.clone())
        };
        let bad = degenerate_near(&mesh, &exact, &cones);
        println!(
            "| {name} | {} | {:.4} | {} | {:.4} | {} | {:.1e} | {} | {} | {ms:.0} | {best} |",
            mesh.num_faces(),
            set.area_spread,
            if exact.degenerate == 0 {
                format!("{:.4}", exact.area_spread)
            } else {
                "– (degenerate)".to_string()
            },
            spread_valid(&mesh, &exact),
            exact.iterations,
            exact.residual,
            exact.degenerate,
            exact.shortened,
        );
        let before: Vec<String> = cones
            .iter()
            .map(|&(v, k)| format!("{v}:{:.1}°", (TAU - k).to_degrees()))
            .collect();
        let after: Vec<String> = optimized
            .iter()
            .map(|&(v, k)| format!("{v}:{:.1}°", (TAU - k).to_degrees()))
            .collect();
        eprintln!("{name}: placed {}", before.join(" "));
        if !bad.is_empty() {
            let bad: Vec<String> = bad
                .iter()
                .map(|(r, a)| format!("{r} rings from a cone of {a:.1}°"))
                .collect();
            eprintln!("{name}: degenerate faces: {}", bad.join(", "));
        }
        if angles {
            eprintln!("{name}: re-optimized {}", after.join(" "));
        }
    }
    Ok(())
}

/// The exact spread of `cones` with their defects moved by projected gradient descent
/// (defects summing to `2πχ`, cone angles in [90°, 720°]; a metric with a degenerate
/// triangle counts as infinite spread); the best spread and cones. When the placed
/// angles give degenerate triangles, the start is the least blend toward equal defects
/// (bisection, 20 steps) that gives none.
fn reoptimize(mesh: &TriMesh, cones: &[(u32, f64)]) -> (f64, Vec<(u32, f64)>) {
    let spread = |c: &[(u32, f64)]| {
        ExactMetric::new(mesh, c, &ExactOptions::DEFAULT)
            .filter(|e| e.degenerate == 0)
            .map_or(f64::INFINITY, |e| e.area_spread)
    };
    // defect = 2π − angle: angle 720° is defect −2π, angle 90° is defect 3π/2
    let clamp = |k: f64| k.clamp(-TAU, 1.5 * PI);
    let total: f64 = cones.iter().map(|c| c.1).sum();
    let equal = total / cones.len() as f64;
    let blend = |s: f64| -> Vec<(u32, f64)> {
        cones
            .iter()
            .map(|&(v, k)| (v, (1.0 - s) * k + s * equal))
            .collect()
    };
    let mut value = spread(cones);
    let mut best = cones.to_vec();
    if !value.is_finite() {
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..20 {
            let mid = 0.5 * (lo + hi);
            if spread(&blend(mid)).is_finite() {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        // a margin inside the feasible set, so the finite differences stay feasible
        let s = (hi + BLEND_MARGIN).min(1.0);
        best = blend(s);
        value = spread(&best);
        eprintln!("start: blend {s:.4} toward equal defects (least feasible {hi:.4}): exact spread {value:.4}");
    }
    let mut step = 0.1;
    for _ in 0..ANGLE_STEPS {
        let mut grad: Vec<f64> = (0..best.len())
            .map(|i| {
                let mut c = best.clone();
                c[i].1 += FD_STEP;
                // keep the sum: spread the change over the others
                let share = FD_STEP / (best.len() - 1) as f64;
                for (j, x) in c.iter_mut().enumerate() {
                    if j != i {
                        x.1 -= share;
                    }
                }
                let g = (spread(&c) - value) / FD_STEP;
                // a step out of the feasible set: no move along this cone
                if g.is_finite() {
                    g
                } else {
                    0.0
                }
            })
            .collect();
        let mean = grad.iter().sum::<f64>() / grad.len() as f64;
        grad.iter_mut().for_each(|g| *g -= mean);
        let norm = grad.iter().map(|g| g * g).sum::<f64>().sqrt();
        if norm < 1e-9 {
            break;
        }
        let mut improved = false;
        for _ in 0..8 {
            let mut c: Vec<(u32, f64)> = best
                .iter()
                .zip(&grad)
                .map(|(&(v, k), g)| (v, clamp(k - step * g / norm)))
                .collect();
            // re-centre after clamping so the sum stays 2πχ
            let drift: f64 =
                c.iter().map(|x| x.1).sum::<f64>() - best.iter().map(|x| x.1).sum::<f64>();
            let len = c.len() as f64;
            c.iter_mut().for_each(|x| x.1 -= drift / len);
            let s = spread(&c);
            if s < value {
                (best, value) = (c, s);
                improved = true;
                step *= 1.5;
                break;
            }
            step *= 0.5;
        }
        if !improved {
            break;
        }
        eprintln!("angle step: exact spread {value:.4}");
    }
    // which cones sit at the edge of the feasible set: 1° more angle there (taken
    // evenly from the others) breaks a triangle inequality
    let degree = 1f64.to_radians();
    let share = degree / (best.len() - 1) as f64;
    let edge: Vec<String> = (0..best.len())
        .filter(|&i| {
            let c: Vec<(u32, f64)> = best
                .iter()
                .enumerate()
                .map(|(j, &(v, k))| (v, if j == i { k - degree } else { k + share }))
                .collect();
            !spread(&c).is_finite()
        })
        .map(|i| format!("{}", best[i].0))
        .collect();
    eprintln!("cones at the edge of the feasible set (1° more breaks a triangle): {edge:?}");
    (value, best)
}

/// The exact metric's area spread over the faces whose triangle inequalities hold (a
/// degenerate face's log area is −∞): a hint of what the metric with intrinsic flips
/// would give, not a realizable spread.
fn spread_valid(mesh: &TriMesh, exact: &ExactMetric) -> f64 {
    let p = mesh.positions();
    let logs: Vec<f64> = mesh
        .faces()
        .iter()
        .zip(&exact.lengths)
        .filter_map(|(f, l)| {
            let d = |a: u32, b: u32| {
                let (x, y) = (p[a as usize], p[b as usize]);
                ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
            };
            let a3 = heron([d(f[0], f[1]), d(f[1], f[2]), d(f[2], f[0])]);
            let a2 = heron(*l);
            (a2 > 0.0 && a3 > 0.0).then(|| (a2 / a3).ln())
        })
        .collect();
    let n = logs.len().max(1) as f64;
    let mean = logs.iter().sum::<f64>() / n;
    (logs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n).sqrt()
}

/// Heron's area of side lengths `l` (0 when a triangle inequality fails).
fn heron(l: [f64; 3]) -> f64 {
    let s = 0.5 * (l[0] + l[1] + l[2]);
    (s * (s - l[0]) * (s - l[1]) * (s - l[2])).max(0.0).sqrt()
}

/// Each degenerate face of `exact`: its rings (breadth first over edges) from the nearest
/// cone and that cone's angle, degrees.
fn degenerate_near(mesh: &TriMesh, exact: &ExactMetric, cones: &[(u32, f64)]) -> Vec<(usize, f64)> {
    let n = mesh.num_vertices();
    let mut ring = vec![usize::MAX; n];
    let mut owner = vec![0usize; n];
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); n];
    for f in mesh.faces() {
        for k in 0..3 {
            adj[f[k] as usize].push(f[(k + 1) % 3]);
            adj[f[(k + 1) % 3] as usize].push(f[k]);
        }
    }
    let mut queue = std::collections::VecDeque::new();
    for (i, &(v, _)) in cones.iter().enumerate() {
        ring[v as usize] = 0;
        owner[v as usize] = i;
        queue.push_back(v);
    }
    while let Some(v) = queue.pop_front() {
        for &w in &adj[v as usize] {
            if ring[w as usize] == usize::MAX {
                ring[w as usize] = ring[v as usize] + 1;
                owner[w as usize] = owner[v as usize];
                queue.push_back(w);
            }
        }
    }
    mesh.faces()
        .iter()
        .zip(&exact.lengths)
        .filter(|(_, l)| heron(**l) <= 0.0)
        .map(|(f, _)| {
            let v = *f.iter().min_by_key(|&&v| ring[v as usize]).unwrap_or(&f[0]);
            let c = owner[v as usize];
            (ring[v as usize], (TAU - cones[c].1).to_degrees())
        })
        .collect()
}

mod exact {
    //! The exact discrete conformal metric of a set of cones (Springborn, Schröder,
    //! Pinkall 2008, "Conformal equivalence of triangle meshes").
    //!
    //! The new edge lengths are `l̃_ij = e^{(u_i + u_j)/2} l_ij`; `u` minimizes their
    //! convex energy, whose gradient is `Θ_v − Σ angles at v` (the target angle sum
    //! `Θ_v = 2π` everywhere but at the cones, `2π − k_c` there) and whose Hessian is the
    //! cotangent Laplacian of the current lengths. Newton's method with that Hessian (one
    //! symbolic analysis, a numeric refactorization per step), `u = 0` at one pinned
    //! vertex (the energy does not change with a constant), the step cut to the minimum
    //! of the energy along it when the full step overshoots.
    //!
    //! The mesh's connectivity is kept (no intrinsic flips): a triangle breaking an
    //! inequality gets angles 0, 0 and π (the extension that keeps the energy convex and
    //! Newton converging) and is counted in [`ExactMetric::degenerate`]; such a metric
    //! would need intrinsic edge flips to be laid out.

    use conformap_mesh::TriMesh;
    use conformap_operators::{cotan_laplacian, Cholesky, LaplacianBlocks, Partition};
    use sprs::CsMat;

    /// Newton's tolerance and cap. `Default` is [`ExactOptions::DEFAULT`].
    #[derive(Debug, Clone, Copy, PartialEq)]
    #[non_exhaustive]
    pub(crate) struct ExactOptions {
        /// Converged when the largest angle-sum error over the vertices is below this,
        /// radians. Default: 1e-10 (Newton converges quadratically: on spot the step before
        /// is at 1e-6, the one after at round-off; 1e-10 rad is 6e-9 degrees).
        pub(crate) tolerance: f64,
        /// Newton steps at most. Default: 30 (spot, armadillo, brain and david_head need 4–7
        /// from `u = 0`; a step halved 30 times counts as a failure).
        pub(crate) max_iterations: usize,
    }

    impl ExactOptions {
        /// The defaults, as a constant.
        pub(crate) const DEFAULT: Self = Self {
            tolerance: 1e-10,
            max_iterations: 30,
        };
    }

    /// Bisections of the line search for the minimum along a Newton direction: 30 (the step
    /// then known to 1e-9 of the full step).
    const LINE_SEARCH_BISECTIONS: usize = 30;

    impl Default for ExactOptions {
        fn default() -> Self {
            Self::DEFAULT
        }
    }

    /// The exact conformal metric of a closed surface with cones.
    #[derive(Debug, Clone, PartialEq)]
    #[non_exhaustive]
    pub(crate) struct ExactMetric {
        /// The scale factor per vertex (`u = 0` at the pinned vertex, the last).
        pub(crate) u: Vec<f64>,
        /// Per face, the new length of the edge from corner `k` to corner `k + 1`.
        pub(crate) lengths: Vec<[f64; 3]>,
        /// Newton steps taken.
        pub(crate) iterations: usize,
        /// Largest angle-sum error over the vertices at the end, radians.
        pub(crate) residual: f64,
        /// Newton steps shortened by the line search.
        pub(crate) shortened: usize,
        /// Triangles whose new lengths break a triangle inequality (angles 0, 0 and π in
        /// the energy's extension): the metric then needs intrinsic edge flips, which this
        /// solver does not make, and the cut disk cannot be laid out.
        pub(crate) degenerate: usize,
        /// The area spread: sd over faces of `log(new area / 3D area)`.
        pub(crate) area_spread: f64,
    }

    impl ExactMetric {
        /// Solves for the exact metric of closed `mesh` with the angle defect `k` at each cone
        /// `(vertex, k)` (the defects must sum to `2πχ`). `None` when Newton does not reach
        /// `options.tolerance` within `options.max_iterations` steps, or the Laplacian does
        /// not factor (a triangle near degenerate).
        pub(crate) fn new(
            mesh: &TriMesh,
            cones: &[(u32, f64)],
            options: &ExactOptions,
        ) -> Option<Self> {
            let n = mesh.num_vertices();
            if n < 4 || !mesh.boundary_loops().is_empty() {
                return None;
            }
            let faces = mesh.faces();
            let p = mesh.positions();
            let dist = |a: u32, b: u32| {
                let (x, y) = (p[a as usize], p[b as usize]);
                ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
            };
            let base: Vec<[f64; 3]> = faces
                .iter()
                .map(|f| [dist(f[0], f[1]), dist(f[1], f[2]), dist(f[2], f[0])])
                .collect();
            let mut target = vec![std::f64::consts::TAU; n];
            for &(v, k) in cones {
                target[v as usize] -= k;
            }
            // the Laplacian's pattern, and where each face's entries go in it
            let mut lap = cotan_laplacian(mesh);
            let slots = Slots::new(&lap, faces);
            let part = Partition::new(n, &[(n - 1) as u32]);
            let mut u = vec![0.0; n];
            let mut lengths = scaled(&base, faces, &u);
            let mut chol: Option<Cholesky> = None;
            let mut iterations = 0;
            let mut shortened = 0;
            let mut error = angle_error(faces, &lengths, &target);
            let mut residual = max_abs(&error);
            while residual > options.tolerance {
                if iterations == options.max_iterations {
                    return None;
                }
                iterations += 1;
                slots.fill(&mut lap, &lengths);
                let ii = LaplacianBlocks::new(&lap, &part).ii;
                match chol.as_mut() {
                    Some(c) => c.refactor(&ii).ok()?,
                    None => chol = Some(Cholesky::factor(&ii).ok()?),
                }
                // the energy's gradient is the angle error Θ − Σ angles and its Hessian L:
                // the Newton direction d solves L d = −(Θ − Σ angles)
                let mut d = part.interior_values(&error.iter().map(|e| -e).collect::<Vec<_>>());
                chol.as_ref()?.solve_in_place(&mut d, 1);
                let d = part.assemble(&d, &[0.0]);
                // the energy along u + t d is convex: its slope φ'(t) = error(u + t d) · d
                // rises with t; the full step if the energy still falls there, else bisection
                // for φ'(t) = 0 (the exact minimum along the line)
                let at = |t: f64| {
                    let trial: Vec<f64> = u.iter().zip(&d).map(|(a, x)| a + t * x).collect();
                    let l = scaled(&base, faces, &trial);
                    let e = angle_error(faces, &l, &target);
                    let slope: f64 = e.iter().zip(&d).map(|(a, b)| a * b).sum();
                    (trial, l, e, slope)
                };
                let mut step = at(1.0);
                if step.3 > 0.0 && max_abs(&step.2) > residual {
                    shortened += 1;
                    let (mut lo, mut hi) = (0.0, 1.0);
                    for _ in 0..LINE_SEARCH_BISECTIONS {
                        let mid = 0.5 * (lo + hi);
                        let s = at(mid);
                        if s.3 > 0.0 {
                            hi = mid;
                        } else {
                            lo = mid;
                            step = s;
                        }
                    }
                    if lo == 0.0 {
                        return None;
                    }
                }
                (u, lengths, error) = (step.0, step.1, step.2);
                residual = max_abs(&error);
            }
            let degenerate = lengths.iter().filter(|l| degenerate(**l)).count();
            let area_spread = area_spread(&base, &lengths);
            Some(Self {
                u,
                lengths,
                iterations,
                residual,
                shortened,
                degenerate,
                area_spread,
            })
        }
    }

    /// Where each face's cotangent weights go in the Laplacian's values: for corner `k` of
    /// face `f`, the off-diagonal entries of its opposite edge (both orders) and the two
    /// diagonal entries of that edge's ends.
    struct Slots {
        /// Per face and corner: `[(a, b), (b, a), (a, a), (b, b)]` for the edge `a b`
        /// opposite the corner.
        at: Vec<[[usize; 4]; 3]>,
    }

    impl Slots {
        fn new(lap: &CsMat<f64>, faces: &[[u32; 3]]) -> Self {
            let indptr = lap.indptr();
            let indptr = indptr.raw_storage();
            let indices = lap.indices();
            let find = |row: u32, col: u32| {
                let (s, e) = (indptr[col as usize], indptr[col as usize + 1]);
                s + indices[s..e]
                    .iter()
                    .position(|&r| r == row as usize)
                    .expect("the cotangent Laplacian's pattern holds every edge")
            };
            let at = faces
                .iter()
                .map(|f| {
                    std::array::from_fn(|k| {
                        let (a, b) = (f[(k + 1) % 3], f[(k + 2) % 3]);
                        [find(a, b), find(b, a), find(a, a), find(b, b)]
                    })
                })
                .collect();
            Self { at }
        }

        /// The cotangent Laplacian of `lengths` (½ cot per corner on its opposite edge) into
        /// `lap`'s values.
        fn fill(&self, lap: &mut CsMat<f64>, lengths: &[[f64; 3]]) {
            let data = lap.data_mut();
            data.iter_mut().for_each(|x| *x = 0.0);
            for (f, slots) in self.at.iter().enumerate() {
                let cot = cotangents(lengths[f]);
                for k in 0..3 {
                    let w = 0.5 * cot[k];
                    let [ab, ba, aa, bb] = slots[k];
                    data[ab] -= w;
                    data[ba] -= w;
                    data[aa] += w;
                    data[bb] += w;
                }
            }
        }
    }

    /// Per face, `base` scaled by `e^{(u_a + u_b)/2}` per edge.
    fn scaled(base: &[[f64; 3]], faces: &[[u32; 3]], u: &[f64]) -> Vec<[f64; 3]> {
        faces
            .iter()
            .zip(base)
            .map(|(f, l)| {
                std::array::from_fn(|k| {
                    l[k] * (0.5 * (u[f[k] as usize] + u[f[(k + 1) % 3] as usize])).exp()
                })
            })
            .collect()
    }

    /// Whether side lengths `l` break a triangle inequality (or make a flat triangle).
    fn degenerate(s: [f64; 3]) -> bool {
        s[0] >= s[1] + s[2] || s[1] >= s[2] + s[0] || s[2] >= s[0] + s[1]
    }

    /// The corner angles of a triangle of edge lengths `l` (`l[k]` from corner `k` to
    /// `k + 1`): corner `k` is opposite `l[(k + 1) % 3]`. Half-angle formula, accurate for
    /// thin triangles; a triangle breaking an inequality gets π opposite its longest side and
    /// 0 elsewhere (the continuous extension that keeps the energy convex).
    fn angles(l: [f64; 3]) -> [f64; 3] {
        std::array::from_fn(|k| {
            let a = l[(k + 1) % 3];
            let (b, c) = (l[k], l[(k + 2) % 3]);
            if a >= b + c {
                return std::f64::consts::PI;
            }
            if b >= a + c || c >= a + b {
                return 0.0;
            }
            let num = (a - b + c) * (a + b - c);
            let den = (a + b + c) * (-a + b + c);
            2.0 * (num / den).max(0.0).sqrt().atan()
        })
    }

    /// The cotangents of [`angles`], from the lengths: `(b² + c² − a²) / 4A`; 0 for a
    /// degenerate triangle (the extended energy is flat there).
    fn cotangents(l: [f64; 3]) -> [f64; 3] {
        let area = heron(l);
        if degenerate(l) || area <= 0.0 {
            return [0.0; 3];
        }
        std::array::from_fn(|k| {
            let a = l[(k + 1) % 3];
            let (b, c) = (l[k], l[(k + 2) % 3]);
            (b * b + c * c - a * a) / (4.0 * area)
        })
    }

    /// The area of a triangle of side lengths `l` (Kahan's stable Heron).
    fn heron(l: [f64; 3]) -> f64 {
        let mut s = l;
        s.sort_by(|x, y| y.total_cmp(x));
        let [a, b, c] = s;
        0.25 * ((a + (b + c)) * (c - (a - b)) * (c + (a - b)) * (a + (b - c)))
            .max(0.0)
            .sqrt()
    }

    /// `Θ_v − Σ angles at v` per vertex.
    fn angle_error(faces: &[[u32; 3]], lengths: &[[f64; 3]], target: &[f64]) -> Vec<f64> {
        let mut e = target.to_vec();
        for (f, l) in faces.iter().zip(lengths) {
            let a = angles(*l);
            for k in 0..3 {
                e[f[k] as usize] -= a[k];
            }
        }
        e
    }

    fn max_abs(x: &[f64]) -> f64 {
        x.iter().fold(0.0, |m, v| m.max(v.abs()))
    }

    /// The sd over faces of `log(area of lengths / area of base)`.
    fn area_spread(base: &[[f64; 3]], lengths: &[[f64; 3]]) -> f64 {
        let logs: Vec<f64> = base
            .iter()
            .zip(lengths)
            .map(|(b, l)| (heron(*l) / heron(*b)).ln())
            .collect();
        let n = logs.len().max(1) as f64;
        let mean = logs.iter().sum::<f64>() / n;
        (logs.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / n).sqrt()
    }
}
