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
//!
//! The two sides of a separator are independent, so pieces of at least
//! [`PARALLEL_PIECE`] vertices dissect their sides as two rayon tasks; and each side
//! starts its search for a pseudo-peripheral vertex where its parent's ended (the root
//! of the parent's last sweep lies on one side, its farthest vertex on the other), which
//! usually saves one of the sweeps. The order is deterministic.

use std::sync::atomic::AtomicU32;
use std::sync::atomic::Ordering::Relaxed;

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

/// Pieces of at least this many vertices have their two sides dissected in parallel
/// (rayon tasks); smaller ones in the calling task.
const PARALLEL_PIECE: usize = 16_384;

/// Per-vertex scratch shared by all tasks of the dissection. Every piece owns its
/// vertices' entries (pieces are disjoint), so concurrent tasks never write the same
/// entry; they do read the `piece` of neighbours in other pieces, hence atomics
/// (relaxed: plain loads and stores on x86-64 and AArch64). Piece ids are unique across
/// tasks (`next_piece`), so a vertex of another piece never looks like one's own.
struct Shared {
    /// The piece each vertex belongs to now.
    piece: Vec<AtomicU32>,
    /// BFS level (valid for the vertices of the owning piece's last search).
    level: Vec<AtomicU32>,
    /// Local index of a vertex within a leaf.
    local: Vec<AtomicU32>,
    next_piece: AtomicU32,
}

impl Shared {
    fn piece(&self, v: usize) -> u32 {
        self.piece[v].load(Relaxed)
    }

    fn set_piece(&self, v: usize, id: u32) {
        self.piece[v].store(id, Relaxed);
    }

    fn level(&self, v: usize) -> u32 {
        self.level[v].load(Relaxed)
    }

    /// Whether `v` has a neighbour in piece `id`.
    fn touches(&self, g: &Graph, v: u32, id: u32) -> bool {
        g.neighbours(v as usize)
            .iter()
            .any(|&w| self.piece(w as usize) == id)
    }

    /// `k` fresh piece ids.
    fn ids(&self, k: u32) -> u32 {
        self.next_piece.fetch_add(k, Relaxed)
    }

    /// Breadth-first search from `root` within piece `id`, the levels of `verts` (the
    /// piece) reset first: fills `queue` with the vertices reached, in order. Returns the
    /// number of levels.
    fn bfs(&self, g: &Graph, verts: &[u32], root: u32, id: u32, queue: &mut Vec<u32>) -> usize {
        for &v in verts {
            self.level[v as usize].store(u32::MAX, Relaxed);
        }
        queue.clear();
        queue.push(root);
        self.level[root as usize].store(0, Relaxed);
        let mut head = 0;
        let mut depth = 0;
        while head < queue.len() {
            let v = queue[head] as usize;
            head += 1;
            let lv = self.level(v);
            depth = depth.max(lv as usize + 1);
            for &w in g.neighbours(v) {
                let w = w as usize;
                if self.piece(w) == id && self.level(w) == u32::MAX {
                    self.level[w].store(lv + 1, Relaxed);
                    queue.push(w as u32);
                }
            }
        }
        depth
    }
}

/// The nested-dissection order of the symmetric pattern `a` (both triangles stored, or
/// either: the pattern is symmetrized): `perm[k]` is the row eliminated at step `k`.
/// Deterministic: the order depends on the pattern only, not on the tasks' timing.
pub(super) fn nested_dissection(a: SymbolicSparseColMatRef<'_, usize>) -> Vec<usize> {
    let n = a.nrows();
    let g = symmetric_graph(a);
    let atomics = |value: u32| (0..n).map(|_| AtomicU32::new(value)).collect::<Vec<_>>();
    let shared = Shared {
        piece: atomics(0),
        level: atomics(u32::MAX),
        local: atomics(0),
        next_piece: AtomicU32::new(1),
    };
    let mut perm = vec![0usize; n];
    dissect(&g, &shared, (0..n as u32).collect(), 0, None, &mut perm);
    perm
}

/// Orders the piece `verts` (id `id`) into `perm` (its positions only, `verts.len()`
/// long): both sides recursively, the separator last. `hint` is a vertex known to lie
/// far out in the piece (the parent's BFS root or its farthest vertex), where the search
/// for a pseudo-peripheral vertex starts.
fn dissect(
    g: &Graph,
    sh: &Shared,
    verts: Vec<u32>,
    id: u32,
    hint: Option<u32>,
    perm: &mut [usize],
) {
    if verts.len() <= LEAF_SIZE {
        order_leaf(g, sh, &verts, perm);
        return;
    }
    let mut queue = Vec::with_capacity(verts.len());
    // pseudo-peripheral root: repeatedly the last vertex of a sweep
    let mut root = hint.unwrap_or(verts[0]);
    let mut depth = sh.bfs(g, &verts, root, id, &mut queue);
    if queue.len() < verts.len() {
        // disconnected: the component reached and the rest are independent
        let reached = std::mem::take(&mut queue);
        let a_id = sh.ids(2);
        let b_id = a_id + 1;
        for &v in &verts {
            sh.set_piece(v as usize, b_id);
        }
        for &v in &reached {
            sh.set_piece(v as usize, a_id);
        }
        let rest: Vec<u32> = verts
            .iter()
            .copied()
            .filter(|&v| sh.piece(v as usize) == b_id)
            .collect();
        let (pa, pb) = perm.split_at_mut(reached.len());
        two(
            verts.len(),
            || dissect(g, sh, reached, a_id, None, pa),
            || dissect(g, sh, rest, b_id, None, pb),
        );
        return;
    }
    for _ in 0..PERIPHERAL_SWEEPS {
        let far = *queue.last().unwrap_or(&root);
        if far == root {
            break;
        }
        let d = sh.bfs(g, &verts, far, id, &mut queue);
        root = far;
        // no longer getting farther: keep this sweep
        let settled = d <= depth;
        depth = d;
        if settled {
            break;
        }
    }
    let farthest = *queue.last().unwrap_or(&root);
    // level sizes and the separator level
    let mut count = vec![0usize; depth];
    for &v in &queue {
        count[sh.level(v as usize) as usize] += 1;
    }
    drop(queue);
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
        order_leaf(g, sh, &verts, perm);
        return;
    }
    // trim the separator: a vertex with no neighbour beyond it joins the near side,
    // then one with no neighbour on the near side joins the far side
    let a_id = sh.ids(3);
    let (b_id, s_id) = (a_id + 1, a_id + 2);
    for &v in &verts {
        let l = sh.level(v as usize);
        sh.set_piece(
            v as usize,
            match l.cmp(&sep_level) {
                std::cmp::Ordering::Less => a_id,
                std::cmp::Ordering::Greater => b_id,
                std::cmp::Ordering::Equal => s_id,
            },
        );
    }
    let sep: Vec<u32> = verts
        .iter()
        .copied()
        .filter(|&v| sh.piece(v as usize) == s_id)
        .collect();
    for &v in &sep {
        if !sh.touches(g, v, b_id) {
            sh.set_piece(v as usize, a_id);
        }
    }
    for &v in &sep {
        if sh.piece(v as usize) == s_id && !sh.touches(g, v, a_id) {
            sh.set_piece(v as usize, b_id);
        }
    }
    let mut part_a = Vec::new();
    let mut part_b = Vec::new();
    let mut part_s = Vec::new();
    for &v in &verts {
        let p = sh.piece(v as usize);
        if p == a_id {
            part_a.push(v);
        } else if p == b_id {
            part_b.push(v);
        } else {
            part_s.push(v);
        }
    }
    if part_a.is_empty() || part_b.is_empty() {
        order_leaf(g, sh, &verts, perm);
        return;
    }
    drop(verts);
    let (pa, rest) = perm.split_at_mut(part_a.len());
    let (pb, ps) = rest.split_at_mut(part_b.len());
    for (slot, &v) in ps.iter_mut().zip(&part_s) {
        *slot = v as usize;
    }
    // the root lies on side A (level 0), the farthest vertex on side B: each starts its
    // side's search for a peripheral vertex
    let hint_a = (sh.piece(root as usize) == a_id).then_some(root);
    let hint_b = (sh.piece(farthest as usize) == b_id).then_some(farthest);
    two(
        total,
        || dissect(g, sh, part_a, a_id, hint_a, pa),
        || dissect(g, sh, part_b, b_id, hint_b, pb),
    );
}

/// Runs `a` and `b`, as two rayon tasks when the piece has at least
/// [`PARALLEL_PIECE`] vertices.
fn two(size: usize, a: impl FnOnce() + Send, b: impl FnOnce() + Send) {
    if size >= PARALLEL_PIECE {
        rayon::join(a, b);
    } else {
        a();
        b();
    }
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

/// Orders the piece `verts` by AMD on its induced subgraph into `perm` (its positions,
/// `verts.len()` long).
fn order_leaf(g: &Graph, sh: &Shared, verts: &[u32], perm: &mut [usize]) {
    let m = verts.len();
    if m <= 2 {
        for (slot, &v) in perm.iter_mut().zip(verts) {
            *slot = v as usize;
        }
        return;
    }
    let id = sh.ids(1);
    for (k, &v) in verts.iter().enumerate() {
        sh.set_piece(v as usize, id);
        sh.local[v as usize].store(k as u32, Relaxed);
    }
    let mut col_ptr = Vec::with_capacity(m + 1);
    let mut row_idx = Vec::new();
    col_ptr.push(0usize);
    for &v in verts {
        let start = row_idx.len();
        for &w in g.neighbours(v as usize) {
            if sh.piece(w as usize) == id {
                row_idx.push(sh.local[w as usize].load(Relaxed) as usize);
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
    for (k, slot) in perm.iter_mut().enumerate() {
        let local = if ordered { fwd[k] } else { k };
        *slot = verts[local] as usize;
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

    /// The pattern of a `w × h` grid with diagonals (both triangles and the diagonal).
    fn grid_pattern(w: usize, h: usize) -> (Vec<usize>, Vec<usize>) {
        let n = w * h;
        let mut cols: Vec<Vec<usize>> = (0..n).map(|j| vec![j]).collect();
        for y in 0..h {
            for x in 0..w {
                let v = y * w + x;
                let mut nb = Vec::new();
                if x + 1 < w {
                    nb.push(v + 1);
                }
                if y + 1 < h {
                    nb.push(v + w);
                    if x + 1 < w {
                        nb.push(v + w + 1);
                    }
                }
                for u in nb {
                    cols[v].push(u);
                    cols[u].push(v);
                }
            }
        }
        let mut ptr = vec![0usize];
        let mut idx = Vec::new();
        for c in &mut cols {
            c.sort_unstable();
            idx.extend_from_slice(c);
            ptr.push(idx.len());
        }
        (ptr, idx)
    }

    #[test]
    fn parallel_dissection_is_deterministic() {
        // 200 × 180: pieces above PARALLEL_PIECE at the top levels, dissected as tasks
        let (w, h) = (200usize, 180usize);
        let (ptr, idx) = grid_pattern(w, h);
        let a = SymbolicSparseColMatRef::new_checked(w * h, w * h, &ptr, None, &idx);
        let pool = |threads| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
        };
        let one = pool(1).install(|| nested_dissection(a));
        for _ in 0..3 {
            assert_eq!(pool(2).install(|| nested_dissection(a)), one);
        }
        // and the top separator is a short cut across the grid, not a long diagonal: the
        // last min(w, h) positions hold a separator of at most 1.5 × the shorter side
        let mut pos = vec![0usize; w * h];
        for (k, &v) in one.iter().enumerate() {
            pos[v] = k;
        }
        let removed_after = |sep_len: usize| {
            // vertices eliminated in the last sep_len steps separate the rest
            let cut = w * h - sep_len;
            let mut comp = vec![usize::MAX; w * h];
            let mut count = 0;
            for s in 0..w * h {
                if pos[s] >= cut || comp[s] != usize::MAX {
                    continue;
                }
                let mut stack = vec![s];
                comp[s] = count;
                while let Some(v) = stack.pop() {
                    for &u in &idx[ptr[v]..ptr[v + 1]] {
                        if pos[u] < cut && comp[u] == usize::MAX {
                            comp[u] = count;
                            stack.push(u);
                        }
                    }
                }
                count += 1;
            }
            count
        };
        assert!(
            removed_after(h * 3 / 2) >= 2,
            "no separator within 1.5 × {h}"
        );
    }
}
