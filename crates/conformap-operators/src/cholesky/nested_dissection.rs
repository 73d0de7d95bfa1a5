//! A nested-dissection fill-reducing ordering for the graphs of surface-mesh Laplacians.
//!
//! George's automatic nested dissection: a breadth-first level structure from a
//! pseudo-peripheral vertex, a level near the middle as the vertex separator (the smallest
//! level among those that leave both sides at least [`BALANCE`] of the vertices), trimmed
//! of vertices with no neighbour on one side; both sides ordered recursively, the separator
//! last. Pieces of at most [`LEAF_SIZE`] vertices are ordered by approximate minimum degree.
//! On the graph of a triangulated surface a level is a closed or open curve of about
//! `√n` vertices, so the orders of the factor's fill and work are those of planar nested
//! dissection (`n log n` and `n^{3/2}`), with a constant well below AMD's on large meshes
//! (see `docs/benchmarks.md`), and the ordering itself costs a few breadth-first searches
//! per level of the recursion instead of AMD's minimum-degree bookkeeping.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;
use faer::sparse::SymbolicSparseColMatRef;

/// Pieces of at most this many vertices are not dissected further but ordered by AMD: the
/// separators of small pieces save less than they cost (measured: 64–256 within 2% in
/// factor time on the generated squares).
pub(super) const LEAF_SIZE: usize = 128;

/// Smallest fraction of a piece's vertices each side of a separator must keep: among the
/// levels that satisfy it the smallest is the separator.
pub(super) const BALANCE: f64 = 0.3;

/// Breadth-first sweeps from successive farthest vertices when looking for a
/// pseudo-peripheral vertex.
const PERIPHERAL_SWEEPS: usize = 3;

/// The adjacency of a symmetric pattern without its diagonal.
struct Graph {
    ptr: Vec<usize>,
    adj: Vec<u32>,
}

impl Graph {
    fn neighbours(&self, v: usize) -> &[u32] {
        &self.adj[self.ptr[v]..self.ptr[v + 1]]
    }
}

/// Scratch shared by the whole dissection.
struct Work {
    /// The piece each vertex belongs to now.
    piece: Vec<u32>,
    /// BFS level (valid for the vertices of the last search).
    level: Vec<u32>,
    /// Local index of a vertex within a leaf.
    local: Vec<u32>,
    queue: Vec<u32>,
    next_piece: u32,
}

impl Work {
    /// Breadth-first search from `root` within piece `id`: fills `self.queue` with the
    /// vertices reached, in order, and their levels. Returns the number of levels.
    fn bfs(&mut self, g: &Graph, root: u32, id: u32) -> usize {
        // levels are reset by the caller's marking: mark unvisited with u32::MAX
        self.queue.clear();
        self.queue.push(root);
        self.level[root as usize] = 0;
        let mut head = 0;
        let mut depth = 0;
        while head < self.queue.len() {
            let v = self.queue[head] as usize;
            head += 1;
            let lv = self.level[v];
            depth = depth.max(lv as usize + 1);
            for &w in g.neighbours(v) {
                let w = w as usize;
                if self.piece[w] == id && self.level[w] == u32::MAX {
                    self.level[w] = lv + 1;
                    self.queue.push(w as u32);
                }
            }
        }
        depth
    }

    fn reset_levels(&mut self, verts: &[u32]) {
        for &v in verts {
            self.level[v as usize] = u32::MAX;
        }
    }
}

/// The nested-dissection order of the symmetric pattern `a` (both triangles stored, or
/// either: the pattern is symmetrized): `perm[k]` is the row eliminated at step `k`.
pub(super) fn nested_dissection(a: SymbolicSparseColMatRef<'_, usize>) -> Vec<usize> {
    let n = a.nrows();
    let g = symmetric_graph(a);
    let mut work = Work {
        piece: vec![0; n],
        level: vec![u32::MAX; n],
        local: vec![0; n],
        queue: Vec::with_capacity(n),
        next_piece: 1,
    };
    let mut perm = vec![0usize; n];
    // (first position, vertices, id): the piece occupies positions first..first + len
    let mut stack: Vec<(usize, Vec<u32>, u32)> = vec![(0, (0..n as u32).collect(), 0)];
    while let Some((first, verts, id)) = stack.pop() {
        if verts.len() <= LEAF_SIZE {
            order_leaf(&g, &mut work, &verts, first, &mut perm);
            continue;
        }
        work.reset_levels(&verts);
        // pseudo-peripheral root: repeatedly the last vertex of a sweep
        let mut root = verts[0];
        let mut depth = work.bfs(&g, root, id);
        if work.queue.len() < verts.len() {
            // disconnected: the component reached and the rest are independent
            let reached = work.queue.clone();
            let (a_id, b_id) = (work.next_piece, work.next_piece + 1);
            work.next_piece += 2;
            for &v in &verts {
                work.piece[v as usize] = b_id;
            }
            for &v in &reached {
                work.piece[v as usize] = a_id;
            }
            let rest: Vec<u32> = verts
                .iter()
                .copied()
                .filter(|&v| work.piece[v as usize] == b_id)
                .collect();
            stack.push((first + reached.len(), rest, b_id));
            stack.push((first, reached, a_id));
            continue;
        }
        for _ in 0..PERIPHERAL_SWEEPS {
            let far = *work.queue.last().unwrap_or(&root);
            if far == root {
                break;
            }
            work.reset_levels(&verts);
            let d = work.bfs(&g, far, id);
            root = far;
            // no longer getting farther: keep this sweep
            let settled = d <= depth;
            depth = d;
            if settled {
                break;
            }
        }
        // level sizes and the separator level
        let mut count = vec![0usize; depth];
        for &v in &work.queue {
            count[work.level[v as usize] as usize] += 1;
        }
        let total = verts.len();
        let min_side = (BALANCE * total as f64) as usize;
        let mut below = 0usize;
        let mut best: Option<(usize, usize)> = None;
        let mut median = depth / 2;
        let mut median_found = false;
        for (m, &c) in count.iter().enumerate() {
            let above = total - below - c;
            if !median_found && below + c >= total / 2 {
                median = m;
                median_found = true;
            }
            if below >= min_side && above >= min_side && best.is_none_or(|(_, bc)| c < bc) {
                best = Some((m, c));
            }
            below += c;
        }
        let sep_level = best.map_or(median, |b| b.0) as u32;
        if depth < 3 || sep_level == 0 || sep_level as usize + 1 >= depth {
            // too shallow to dissect (a clique-like piece): a leaf
            order_leaf(&g, &mut work, &verts, first, &mut perm);
            continue;
        }
        // trim the separator: a vertex with no neighbour beyond it joins the near side,
        // then one with no neighbour on the near side joins the far side
        let (a_id, b_id, s_id) = (work.next_piece, work.next_piece + 1, work.next_piece + 2);
        work.next_piece += 3;
        for &v in &verts {
            let l = work.level[v as usize];
            work.piece[v as usize] = match l.cmp(&sep_level) {
                std::cmp::Ordering::Less => a_id,
                std::cmp::Ordering::Greater => b_id,
                std::cmp::Ordering::Equal => s_id,
            };
        }
        let sep: Vec<u32> = verts
            .iter()
            .copied()
            .filter(|&v| work.piece[v as usize] == s_id)
            .collect();
        for &v in &sep {
            let touches_b = g
                .neighbours(v as usize)
                .iter()
                .any(|&w| work.piece[w as usize] == b_id);
            if !touches_b {
                work.piece[v as usize] = a_id;
            }
        }
        for &v in &sep {
            if work.piece[v as usize] != s_id {
                continue;
            }
            let touches_a = g
                .neighbours(v as usize)
                .iter()
                .any(|&w| work.piece[w as usize] == a_id);
            if !touches_a {
                work.piece[v as usize] = b_id;
            }
        }
        let mut part_a = Vec::new();
        let mut part_b = Vec::new();
        let mut part_s = Vec::new();
        for &v in &verts {
            let p = work.piece[v as usize];
            if p == a_id {
                part_a.push(v);
            } else if p == b_id {
                part_b.push(v);
            } else {
                part_s.push(v);
            }
        }
        if part_a.is_empty() || part_b.is_empty() {
            order_leaf(&g, &mut work, &verts, first, &mut perm);
            continue;
        }
        let sep_first = first + part_a.len() + part_b.len();
        for (k, &v) in part_s.iter().enumerate() {
            perm[sep_first + k] = v as usize;
        }
        stack.push((first + part_a.len(), part_b, b_id));
        stack.push((first, part_a, a_id));
    }
    perm
}

/// The graph of `a + aᵀ` without the diagonal.
fn symmetric_graph(a: SymbolicSparseColMatRef<'_, usize>) -> Graph {
    let n = a.nrows();
    let mut deg = vec![0usize; n + 1];
    for j in 0..n {
        for &i in a.row_idx_of_col_raw(j) {
            if i != j {
                deg[i] += 1;
                deg[j] += 1;
            }
        }
    }
    let mut ptr = vec![0usize; n + 1];
    for v in 0..n {
        ptr[v + 1] = ptr[v] + deg[v];
    }
    let mut fill = ptr.clone();
    let mut adj = vec![0u32; ptr[n]];
    for j in 0..n {
        for &i in a.row_idx_of_col_raw(j) {
            if i != j {
                adj[fill[i]] = j as u32;
                fill[i] += 1;
                adj[fill[j]] = i as u32;
                fill[j] += 1;
            }
        }
    }
    // each edge may now appear twice (full storage): sort and dedup per vertex
    let mut out_ptr = vec![0usize; n + 1];
    let mut out = Vec::with_capacity(adj.len() / 2 + n);
    for v in 0..n {
        let s = &mut adj[ptr[v]..ptr[v + 1]];
        s.sort_unstable();
        let mut last = u32::MAX;
        for &w in s.iter() {
            if w != last {
                out.push(w);
                last = w;
            }
        }
        out_ptr[v + 1] = out.len();
    }
    Graph {
        ptr: out_ptr,
        adj: out,
    }
}

/// Orders the piece `verts` by AMD on its induced subgraph into positions
/// `first..first + verts.len()`.
fn order_leaf(g: &Graph, work: &mut Work, verts: &[u32], first: usize, perm: &mut [usize]) {
    let m = verts.len();
    if m <= 2 {
        for (k, &v) in verts.iter().enumerate() {
            perm[first + k] = v as usize;
        }
        return;
    }
    let id = work.next_piece;
    work.next_piece += 1;
    for (k, &v) in verts.iter().enumerate() {
        work.piece[v as usize] = id;
        work.local[v as usize] = k as u32;
    }
    let mut col_ptr = Vec::with_capacity(m + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0usize);
    for &v in verts {
        let start = row_idx.len();
        for &w in g.neighbours(v as usize) {
            if work.piece[w as usize] == id {
                row_idx.push(work.local[w as usize] as usize);
            }
        }
        row_idx[start..].sort_unstable();
        col_ptr.push(row_idx.len());
    }
    let pattern = SymbolicSparseColMatRef::new_checked(m, m, &col_ptr, None, &row_idx);
    let mut fwd = vec![0usize; m];
    let mut inv = vec![0usize; m];
    let ordered = MemBuffer::try_new(amd::order_scratch::<usize>(m, row_idx.len()))
        .ok()
        .and_then(|mut mem| {
            amd::order(
                &mut fwd,
                &mut inv,
                pattern,
                amd::Control::default(),
                MemStack::new(&mut mem),
            )
            .ok()
        })
        .is_some();
    for k in 0..m {
        let local = if ordered { fwd[k] } else { k };
        perm[first + k] = verts[local] as usize;
    }
}

#[cfg(test)]
mod tests {
    use faer::sparse::SymbolicSparseColMatRef;

    use super::nested_dissection;

    #[test]
    fn is_a_permutation_and_separates() {
        // a 40 × 30 grid with diagonals, plus a disconnected 3 × 3 grid
        let (w, h) = (40usize, 30usize);
        let n = w * h + 9;
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        let mut edge = |a: usize, b: usize| {
            cols[a].push(b);
            cols[b].push(a);
        };
        for y in 0..h {
            for x in 0..w {
                let v = y * w + x;
                if x + 1 < w {
                    edge(v, v + 1);
                }
                if y + 1 < h {
                    edge(v, v + w);
                }
                if x + 1 < w && y + 1 < h {
                    edge(v, v + w + 1);
                }
            }
        }
        for y in 0..3 {
            for x in 0..3 {
                let v = w * h + y * 3 + x;
                if x + 1 < 3 {
                    edge(v, v + 1);
                }
                if y + 1 < 3 {
                    edge(v, v + 3);
                }
            }
        }
        let mut ptr = vec![0usize];
        let mut idx = Vec::new();
        for (j, c) in cols.iter_mut().enumerate() {
            c.push(j);
            c.sort_unstable();
            c.dedup();
            idx.extend_from_slice(c);
            ptr.push(idx.len());
        }
        let a = SymbolicSparseColMatRef::new_checked(n, n, &ptr, None, &idx);
        let perm = nested_dissection(a);
        let mut seen = vec![false; n];
        for &p in &perm {
            assert!(!seen[p]);
            seen[p] = true;
        }
        assert!(seen.iter().all(|&s| s));
    }
}
