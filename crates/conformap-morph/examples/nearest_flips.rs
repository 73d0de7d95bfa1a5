//! An independent count of the key frames' flipped faces (issue 37): a face of a key frame
//! counts when its normal points against the normal of the key surface's triangle nearest
//! (in 3D) to the face's centroid — no disk, no point location, nothing the morph computed
//! but the frame itself. Prints, per key surface, that count and its largest patch for
//! the morph, and for the exact correspondence when the meshes have one:
//!
//! ```text
//! cargo build --release --workspace --examples
//! target/release/examples/nearest_flips [--hard] [--no-creases] [--no-refine] [--list] \
//!     [S1.obj S1.landmarks.txt S2.obj S2.landmarks.txt ...]
//! ```
//!
//! `--list`: also every counted face of the morph (index, vertices, centroid on S1).
//! `--no-refine`: without the key frames' refinement (which moves vertices of faces that
//! this very count flags: with it, the count is no longer independent of the morph, and
//! the distance to the exact correspondence below is the independent check).
//!
//! With an exact correspondence it also prints how far the morph's key-frame vertices
//! lie from their exact counterparts, in mean edge lengths of the key surface: the mean,
//! the largest, and the sum over all covered vertices (a refinement that moves a few
//! vertices changes the sum by their moves towards or away from the exact places).
//!
//! Without surfaces it reads `../shared/morph/ict_{neutral,wry,pout}`.
//!
//! The exact correspondence: the ICT crops keep the source model's vertex order, so S1's
//! vertex `i` is the key surface's next vertex in order, except S1 vertices that the key's
//! crop dropped (`ict_wry` drops the top of the forehead): an S1 vertex above `y =
//! EXACT_DROP_ABOVE_Y` farther than `EXACT_SAME_POINT` from the key's next vertex is
//! skipped. The alignment counts only when every landmark lands on its counterpart; otherwise the exact count is not printed. It is counted on
//! the S1 faces whose three vertices have a counterpart (on wry, all but the top of the
//! forehead).

use conformap_mesh::TriMesh;
use conformap_morph::quality::{face_normal, largest_patch, point_triangle_distance};
use conformap_morph::{morph, Landmarks, MorphOptions, Surface};

/// S1 vertices above this height (`7.0`, model units) may be missing from a key surface
/// (the `ict_wry` crop removes polygons whose centroid has `y > 7.6`).
const EXACT_DROP_ABOVE_Y: f64 = 7.0;

/// An S1 vertex in the dropped region is the key's next vertex when within this distance:
/// `0.01` (the forehead does not move with the expressions; the nearest other vertex is
/// about 0.2 away).
const EXACT_SAME_POINT: f64 = 0.01;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut options = MorphOptions::DEFAULT;
    let mut list = false;
    while let Some(k) = args.iter().position(|a| a.starts_with("--")) {
        match args.remove(k).as_str() {
            "--hard" => options = options.with_hard_landmarks(),
            "--no-creases" => options = options.with_crease_matching(false),
            "--no-refine" => options = options.with_key_frame_refinement(false),
            "--list" => list = true,
            other => return Err(format!("unknown flag {other}").into()),
        }
    }
    if args.is_empty() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/morph");
        for name in ["ict_neutral", "ict_wry", "ict_pout"] {
            args.push(format!("{dir}/{name}.obj"));
            args.push(format!("{dir}/{name}.landmarks.txt"));
        }
    }
    if args.len() < 4 || args.len() % 2 != 0 {
        return Err(
            "usage: nearest_flips [--hard] [--no-creases] S1.obj S1.lm S2.obj S2.lm ...".into(),
        );
    }
    let mut surfaces = Vec::new();
    let mut names = Vec::new();
    for pair in args.chunks(2) {
        let mesh = conformap_io::read_mesh(&pair[0])?.mesh;
        let landmarks = Landmarks::parse(&std::fs::read_to_string(&pair[1])?)?;
        surfaces.push(Surface::new(mesh, landmarks));
        names.push(pair[0].rsplit('/').next().unwrap_or(&pair[0]).to_string());
    }
    let m = morph(&surfaces, &options)?;
    // the same morph without the refinement, to compare the vertices it moved
    let unrefined = if options.refine_key_frames {
        Some(morph(
            &surfaces,
            &options.clone().with_key_frame_refinement(false),
        )?)
    } else {
        None
    };
    let s1 = &surfaces[0];
    for (k, sk) in surfaces.iter().enumerate().skip(1) {
        let near = NearestTriangle::new(&sk.mesh);
        let (flipped, patch) = count(&near, &m.keys()[k], m.faces());
        let n = flipped.len();
        if list {
            for &f in &flipped {
                let tri = m.faces()[f];
                let c = centroid(s1.mesh.positions(), &tri);
                println!(
                    "  {}: face {f} {tri:?}, on S1 at ({:.3}, {:.3}, {:.3})",
                    names[k], c[0], c[1], c[2]
                );
            }
        }
        let r = &m.report.keys[k];
        print!(
            "{}: morph {n} faces against the nearest key triangle (largest patch {patch}); \
             the morph's own count {} ({})",
            names[k], r.key_frame_flipped_faces, r.key_frame_largest_flip_patch
        );
        if let Some(rf) = &r.refine {
            print!(
                "; refined: {} -> {} disagreeing, {} moves (largest {:.3} mean edges), {:.1} ms",
                rf.disagreeing_before,
                rf.disagreeing_after,
                rf.moves,
                rf.largest_move_edges,
                rf.wall_ms
            );
        }
        match exact(s1, sk) {
            Some(map) => {
                // S1's faces whose three vertices have a counterpart
                let faces: Vec<[u32; 3]> = m
                    .faces()
                    .iter()
                    .filter(|f| f.iter().all(|&v| map[v as usize] != u32::MAX))
                    .copied()
                    .collect();
                let frame: Vec<[f64; 3]> = map
                    .iter()
                    .map(|&j| {
                        let p = sk.mesh.positions();
                        p.get(j as usize).copied().unwrap_or([0.0; 3])
                    })
                    .collect();
                let (e, ep) = count(&near, &frame, &faces);
                println!(
                    "; exact correspondence {} (largest patch {ep}) of the {} faces it covers",
                    e.len(),
                    faces.len()
                );
                let edge = mean_edge(&sk.mesh);
                let off: Vec<f64> = map
                    .iter()
                    .enumerate()
                    .filter(|&(_, &j)| j != u32::MAX)
                    .map(|(v, _)| distance(m.keys()[k][v], frame[v]) / edge)
                    .collect();
                let sum: f64 = off.iter().sum();
                println!(
                    "  off the exact correspondence (mean edges of {}): mean {:.4}, max {:.3}, sum {:.2} over {} vertices",
                    names[k],
                    sum / off.len().max(1) as f64,
                    off.iter().copied().fold(0.0, f64::max),
                    sum,
                    off.len()
                );
                if let Some(u) = &unrefined {
                    // the vertices the refinement moved: nearer to or farther from their
                    // exact places than without it
                    let (mut nearer, mut farther, mut change) = (0, 0, 0.0);
                    for (v, &j) in map.iter().enumerate() {
                        let (a, b) = (u.keys()[k][v], m.keys()[k][v]);
                        if j == u32::MAX || a == b {
                            continue;
                        }
                        let (da, db) = (distance(a, frame[v]) / edge, distance(b, frame[v]) / edge);
                        nearer += usize::from(db < da);
                        farther += usize::from(db > da);
                        change += db - da;
                    }
                    println!(
                        "  against the morph without the refinement: {} vertices differ, {nearer} nearer to their exact places, {farther} farther, sum {change:+.3} mean edges",
                        nearer + farther
                    );
                }
            }
            None => println!("; no exact correspondence"),
        }
    }
    Ok(())
}

/// Faces of `frame` (connectivity `faces`) whose normal points against the nearest key
/// triangle's, and the largest patch of them.
fn count(
    near: &NearestTriangle<'_>,
    frame: &[[f64; 3]],
    faces: &[[u32; 3]],
) -> (Vec<usize>, usize) {
    let key = near.mesh;
    let flipped: Vec<usize> = faces
        .iter()
        .enumerate()
        .filter(|(_, f)| {
            let c = centroid(frame, f);
            let t = near.nearest(c);
            let a = face_normal(frame, f);
            let b = face_normal(key.positions(), &key.faces()[t]);
            !(a[0] * b[0] + a[1] * b[1] + a[2] * b[2] > 0.0)
        })
        .map(|(k, _)| k)
        .collect();
    let patch = largest_patch(faces, &flipped);
    (flipped, patch)
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The mean edge length of a mesh (every face's three edges).
fn mean_edge(mesh: &TriMesh) -> f64 {
    let p = mesh.positions();
    let total: f64 = mesh
        .faces()
        .iter()
        .flat_map(|f| (0..3).map(move |e| distance(p[f[e] as usize], p[f[(e + 1) % 3] as usize])))
        .sum();
    total / (3 * mesh.faces().len()).max(1) as f64
}

fn centroid(p: &[[f64; 3]], f: &[u32; 3]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for &v in f {
        for i in 0..3 {
            c[i] += p[v as usize][i] / 3.0;
        }
    }
    c
}

/// The exact correspondence of the module docs: for every S1 vertex its key vertex.
fn exact(s1: &Surface, sk: &Surface) -> Option<Vec<u32>> {
    let (p1, pk) = (s1.mesh.positions(), sk.mesh.positions());
    let mut map = Vec::with_capacity(p1.len());
    let mut j = 0usize;
    for p in p1 {
        let Some(&q) = pk.get(j) else {
            // past the key's last vertex: S1 vertices its crop dropped
            map.push(u32::MAX);
            continue;
        };
        let d = ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
        if p[1] > EXACT_DROP_ABOVE_Y && d > EXACT_SAME_POINT {
            // dropped by the key's crop: S1 vertex without a counterpart
            map.push(u32::MAX);
            continue;
        }
        map.push(j as u32);
        j += 1;
    }
    let landmarks_agree = s1
        .landmarks
        .vertices()
        .iter()
        .zip(sk.landmarks.vertices())
        .all(|(&a, &b)| map[a as usize] == b);
    landmarks_agree.then_some(map)
}

/// Nearest triangle of a mesh to a point: a uniform grid of cells (side twice the mean
/// edge length) listing the triangles whose bounding box meets them, searched in growing
/// shells of cells.
struct NearestTriangle<'m> {
    mesh: &'m TriMesh,
    lo: [f64; 3],
    h: f64,
    dims: [usize; 3],
    cells: Vec<Vec<u32>>,
}

impl<'m> NearestTriangle<'m> {
    fn new(mesh: &'m TriMesh) -> Self {
        let p = mesh.positions();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for q in p {
            for i in 0..3 {
                lo[i] = lo[i].min(q[i]);
                hi[i] = hi[i].max(q[i]);
            }
        }
        let mut total = 0.0;
        for f in mesh.faces() {
            for e in 0..3 {
                let (a, b) = (p[f[e] as usize], p[f[(e + 1) % 3] as usize]);
                total +=
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
            }
        }
        let h = 2.0 * total / (3 * mesh.faces().len()).max(1) as f64;
        let dims = [0, 1, 2].map(|i| (((hi[i] - lo[i]) / h).floor() as usize) + 1);
        let mut cells = vec![Vec::new(); dims[0] * dims[1] * dims[2]];
        let grid = Self {
            mesh,
            lo,
            h,
            dims,
            cells: Vec::new(),
        };
        for (t, f) in mesh.faces().iter().enumerate() {
            let mut a = [usize::MAX; 3];
            let mut b = [0usize; 3];
            for &v in f {
                let c = grid.cell(p[v as usize]);
                for i in 0..3 {
                    a[i] = a[i].min(c[i]);
                    b[i] = b[i].max(c[i]);
                }
            }
            for x in a[0]..=b[0] {
                for y in a[1]..=b[1] {
                    for z in a[2]..=b[2] {
                        cells[(x * dims[1] + y) * dims[2] + z].push(t as u32);
                    }
                }
            }
        }
        Self { cells, ..grid }
    }

    fn cell(&self, q: [f64; 3]) -> [usize; 3] {
        [0, 1, 2].map(|i| (((q[i] - self.lo[i]) / self.h).max(0.0) as usize).min(self.dims[i] - 1))
    }

    fn nearest(&self, q: [f64; 3]) -> usize {
        let c = self.cell(q);
        let (p, f) = (self.mesh.positions(), self.mesh.faces());
        let mut best = (f64::INFINITY, 0usize);
        let reach = self.dims.iter().copied().max().unwrap_or(1);
        for r in 0..=reach {
            let range = |i: usize| c[i].saturating_sub(r)..=(c[i] + r).min(self.dims[i] - 1);
            for x in range(0) {
                for y in range(1) {
                    for z in range(2) {
                        let shell = [x, y, z].iter().zip(&c).any(|(&a, &b)| a.abs_diff(b) == r);
                        if !shell {
                            continue;
                        }
                        for &t in &self.cells[(x * self.dims[1] + y) * self.dims[2] + z] {
                            let tri = f[t as usize].map(|v| p[v as usize]);
                            let d = point_triangle_distance(q, tri);
                            if d < best.0 {
                                best = (d, t as usize);
                            }
                        }
                    }
                }
            }
            // every cell not searched yet is at least r·h away
            if best.0 <= r as f64 * self.h {
                break;
            }
        }
        best.1
    }
}
