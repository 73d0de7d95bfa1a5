//! Pieces merged back after the repairs: the overlap splits cut along shortest paths, one
//! crossing at a time, and leave slivers of a few faces where a strip was cut more often
//! than the overlap needed (the 1-form layouts of `--seamless`: fertility 95 pieces).
//! Two pieces that share a path of edges in the chart's own layout (both keep the chart's
//! coordinates, so the shared edges sit at the same place on both sides) are one piece
//! again when the union stays a disk and no boundary edge of one crosses a boundary edge of
//! the other: a flip-free disk whose boundary does not cross itself is one-to-one (see
//! `conformap_metrics::boundary_crossings`), and each piece's own boundary already does
//! not cross itself. Faces keep their coordinates; the seams left are the ones that were.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use conformap_mesh::NO_HALFEDGE;
use conformap_metrics::segments_meet;

use super::piece::{sub_piece, Piece};
use crate::error::AtlasError;

/// Faces a piece may have to be merged into a neighbour: 5 % of the chart's faces (at
/// least 16). Larger pieces are the layout's real parts; merging them would only undo the
/// splits that were needed.
const MERGE_SHARE: f64 = 0.05;

/// `pieces` of the chart `whole` (the chart's faces, mesh and layout as one piece) with
/// every small piece merged into a neighbour where the union is a disk without overlap
/// (module docs). Pieces whose coordinates are not the chart's (a folded face detached as
/// its mirror image) are kept as they are. The order of the pieces is kept (a merged
/// piece takes the place of the larger of the two).
///
/// # Errors
/// [`AtlasError::Mesh`] should a merged piece fail validation (a disk by construction).
pub(crate) fn merge_pieces(whole: &Piece, pieces: Vec<Piece>) -> Result<Vec<Piece>, AtlasError> {
    if pieces.len() < 2 {
        return Ok(pieces);
    }
    let mesh = &whole.mesh;
    let tris = mesh.faces();
    // the whole's face of each component face (the whole lists them all, in order)
    let local: HashMap<u32, u32> = whole
        .faces
        .iter()
        .enumerate()
        .map(|(i, &f)| (f, i as u32))
        .collect();
    let n = pieces.len();
    let mut groups: Vec<Option<Vec<u32>>> = Vec::with_capacity(n);
    let mut consistent = vec![false; n];
    let mut owner = vec![usize::MAX; tris.len()];
    for (i, p) in pieces.iter().enumerate() {
        let faces: Option<Vec<u32>> = p.faces.iter().map(|f| local.get(f).copied()).collect();
        let same = faces.as_ref().is_some_and(|faces| {
            faces.iter().zip(p.mesh.faces()).all(|(&f, t)| {
                let w = tris[f as usize];
                (0..3).all(|k| p.uv[t[k] as usize] == whole.uv[w[k] as usize])
            })
        });
        if let Some(faces) = faces.filter(|_| same) {
            faces.iter().for_each(|&f| owner[f as usize] = i);
            groups.push(Some(faces));
            consistent[i] = true;
        } else {
            groups.push(None);
        }
    }
    let limit = ((MERGE_SHARE * tris.len() as f64) as usize).max(16);
    let graph = Graph { whole };
    // each group's boundary half-edges, kept up to date as groups merge
    let mut bnd: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (f, &g) in owner.iter().enumerate() {
        if g == usize::MAX {
            continue;
        }
        for h in 3 * f..3 * f + 3 {
            if graph.owner_across(&owner, h) != g {
                bnd[g].push(h as u32);
            }
        }
    }
    loop {
        let mut order: Vec<usize> = (0..n)
            .filter(|&i| groups[i].as_ref().is_some_and(|g| g.len() <= limit))
            .collect();
        order.sort_by_key(|&i| (groups[i].as_ref().map_or(0, |g| g.len()), i));
        let mut merged = false;
        for i in order {
            if groups[i].is_none() {
                continue;
            }
            // neighbours across the chart's own edges, most shared edges first
            let mut shared: HashMap<usize, usize> = HashMap::default();
            for &h in &bnd[i] {
                let j = graph.owner_across(&owner, h as usize);
                if j != usize::MAX && groups[j].is_some() {
                    *shared.entry(j).or_default() += 1;
                }
            }
            let mut near: Vec<(usize, usize)> = shared.into_iter().collect();
            near.sort_by_key(|&(j, c)| (std::cmp::Reverse(c), j));
            let small = groups[i].as_ref().expect("live");
            let found = near
                .into_iter()
                .map(|(j, _)| j)
                .find(|&j| graph.mergeable(&owner, small, &bnd[i], i, &bnd[j], j));
            if let Some(j) = found {
                // the union's boundary: both boundaries but the edges between them
                let mut union: Vec<u32> = bnd[j]
                    .iter()
                    .copied()
                    .filter(|&h| graph.owner_across(&owner, h as usize) != i)
                    .collect();
                union.extend(
                    bnd[i]
                        .iter()
                        .copied()
                        .filter(|&h| graph.owner_across(&owner, h as usize) != j),
                );
                bnd[j] = union;
                bnd[i].clear();
                let small = groups[i].take().expect("live");
                small.iter().for_each(|&f| owner[f as usize] = j);
                groups[j].as_mut().expect("live").extend(small);
                merged = true;
            }
        }
        if !merged {
            break;
        }
    }
    let mut out = Vec::with_capacity(n);
    for ((p, g), kept) in pieces.into_iter().zip(groups).zip(consistent) {
        match g {
            // merged ones cut from the whole; untouched pieces as they were
            Some(mut faces) if faces.len() != p.faces.len() => {
                faces.sort_unstable();
                out.push(sub_piece(whole, &faces)?);
            }
            Some(_) => out.push(p),
            // not in the chart's coordinates: as it was; else merged into another
            None if !kept => out.push(p),
            None => {}
        }
    }
    Ok(out)
}

/// The chart's mesh and layout.
struct Graph<'a> {
    whole: &'a Piece,
}

impl Graph<'_> {
    /// The group of the face across half-edge `h` (`usize::MAX` on the chart's boundary).
    fn owner_across(&self, owner: &[usize], h: usize) -> usize {
        let o = self.whole.mesh.opposite_halfedges()[h];
        if o == NO_HALFEDGE {
            usize::MAX
        } else {
            owner[o as usize / 3]
        }
    }

    /// The ends of half-edge `h`.
    fn ends(&self, h: u32) -> [u32; 2] {
        let t = self.whole.mesh.faces()[h as usize / 3];
        let k = h as usize % 3;
        [t[k], t[(k + 1) % 3]]
    }

    /// Whether group `a` (id `ia`, boundary `ba`) and group `ib` (boundary `bb`) make one
    /// disk without overlap: they share one path of edges (as many shared vertices as
    /// shared edges plus one: no second path round a hole, no pinch at a lone vertex) and
    /// no boundary edge of one meets a boundary edge of the other away from it. Costs the
    /// small group's faces and the two boundaries, not the large group's faces.
    fn mergeable(
        &self,
        owner: &[usize],
        a: &[u32],
        ba: &[u32],
        ia: usize,
        bb: &[u32],
        ib: usize,
    ) -> bool {
        let tris = self.whole.mesh.faces();
        let shared_edges = ba
            .iter()
            .filter(|&&h| self.owner_across(owner, h as usize) == ib)
            .count();
        if shared_edges == 0 {
            return false;
        }
        // a vertex of `a` in a face of `b` lies on `b`'s boundary
        let verts: HashSet<u32> = a.iter().flat_map(|&f| tris[f as usize]).collect();
        let shared_vertices = bb
            .iter()
            .flat_map(|&h| self.ends(h))
            .filter(|v| verts.contains(v))
            .collect::<HashSet<u32>>()
            .len();
        if shared_vertices != shared_edges + 1 {
            return false;
        }
        let ea: Vec<[u32; 2]> = ba
            .iter()
            .filter(|&&h| self.owner_across(owner, h as usize) != ib)
            .map(|&h| self.ends(h))
            .collect();
        let eb: Vec<[u32; 2]> = bb
            .iter()
            .filter(|&&h| self.owner_across(owner, h as usize) != ia)
            .map(|&h| self.ends(h))
            .collect();
        !boundaries_meet(&self.whole.uv, &ea, &eb)
    }
}

/// Whether a segment of `ea` meets a segment of `eb` (vertex pairs into `uv`) other than
/// at a vertex they share ([`segments_meet`]); boxes first.
fn boundaries_meet(uv: &[num_complex::Complex64], ea: &[[u32; 2]], eb: &[[u32; 2]]) -> bool {
    let lo_hi = |e: &[u32; 2]| {
        let (p, q) = (uv[e[0] as usize], uv[e[1] as usize]);
        (
            p.re.min(q.re),
            p.re.max(q.re),
            p.im.min(q.im),
            p.im.max(q.im),
        )
    };
    let (small, large) = if ea.len() <= eb.len() {
        (ea, eb)
    } else {
        (eb, ea)
    };
    let boxes: Vec<_> = small.iter().map(lo_hi).collect();
    let (x0, x1, y0, y1) = boxes.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |m, b| (m.0.min(b.0), m.1.max(b.1), m.2.min(b.2), m.3.max(b.3)),
    );
    for e in large {
        let l = lo_hi(e);
        if l.1 < x0 || l.0 > x1 || l.3 < y0 || l.2 > y1 {
            continue;
        }
        for (s, bx) in small.iter().zip(&boxes) {
            if l.1 < bx.0 || l.0 > bx.1 || l.3 < bx.2 || l.2 > bx.3 {
                continue;
            }
            if segments_meet(
                uv[s[0] as usize],
                uv[s[1] as usize],
                uv[e[0] as usize],
                uv[e[1] as usize],
                *s,
                *e,
            ) {
                return true;
            }
        }
    }
    false
}
