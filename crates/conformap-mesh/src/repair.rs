//! Safe, standard repairs of a raw triangle list, applied before validation and only when a
//! caller asks for them (the CLI's `--repair`): never silently.
//!
//! [`repair`] works on the positions and faces as a file gave them and returns new arrays
//! plus a [`RepairLog`] of what changed, with the vertex and face maps that relate the
//! repaired mesh to the input. The repairs, in the order applied:
//!
//! 1. drop exact duplicate faces (same three vertices in any order), keeping the first;
//! 2. keep the largest connected component (most faces; ties: the one holding the lowest
//!    face index);
//! 3. re-orient faces consistently: a breadth-first walk over manifold edges flips faces to
//!    agree with their neighbours, and each edge-connected patch keeps the orientation of
//!    the majority of its faces (ties: that of its lowest face). A surface on which no
//!    choice agrees everywhere (a Möbius strip) is a [`MeshError::NonOrientable`];
//! 4. drop vertices that no remaining face uses; the others keep their relative order, so
//!    repaired vertex `k` is the `k`-th kept input vertex.
//!
//! What is not repaired, because no repair is both safe and standard: out-of-range indices,
//! non-finite coordinates, degenerate faces, non-manifold edges and vertices. Those still
//! fail validation ([`crate::TriMesh::try_new`]) after the repair;
//! [`RepairLog::to_input_error`] renames the elements of that error back to input numbering.

use std::collections::VecDeque;

use crate::MeshError;

/// Marks a dropped input vertex in [`RepairLog::input_to_vertex`].
pub const DROPPED: u32 = u32::MAX;

/// Which repairs [`repair`] applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[non_exhaustive]
pub struct RepairOptions {
    /// Drop faces with the same vertex set as an earlier face (whatever the order or
    /// orientation), keeping the first. Default: `true`.
    pub drop_duplicate_faces: bool,
    /// Keep only the connected component (faces sharing vertices) with the most faces; on a
    /// tie, the one holding the lowest face index. Default: `true`.
    pub keep_largest_component: bool,
    /// Flip faces so that neighbours across every manifold edge agree. Default: `true`.
    pub orient: bool,
    /// Drop vertices no (remaining) face uses. Default: `true`.
    pub drop_unreferenced_vertices: bool,
}

impl RepairOptions {
    /// Every repair, as a constant (the default).
    pub const DEFAULT: Self = Self {
        drop_duplicate_faces: true,
        keep_largest_component: true,
        orient: true,
        drop_unreferenced_vertices: true,
    };

    /// No repair at all: [`repair`] then only renumbers nothing and reports the components.
    pub const NONE: Self = Self {
        drop_duplicate_faces: false,
        keep_largest_component: false,
        orient: false,
        drop_unreferenced_vertices: false,
    };

    /// Sets [`Self::drop_duplicate_faces`].
    #[must_use]
    pub fn with_drop_duplicate_faces(mut self, on: bool) -> Self {
        self.drop_duplicate_faces = on;
        self
    }

    /// Sets [`Self::keep_largest_component`].
    #[must_use]
    pub fn with_keep_largest_component(mut self, on: bool) -> Self {
        self.keep_largest_component = on;
        self
    }

    /// Sets [`Self::orient`].
    #[must_use]
    pub fn with_orient(mut self, on: bool) -> Self {
        self.orient = on;
        self
    }

    /// Sets [`Self::drop_unreferenced_vertices`].
    #[must_use]
    pub fn with_drop_unreferenced_vertices(mut self, on: bool) -> Self {
        self.drop_unreferenced_vertices = on;
        self
    }
}

impl Default for RepairOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What [`repair`] did, and how the repaired mesh relates to the input.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub struct RepairLog {
    /// Vertices of the input.
    pub input_vertices: usize,
    /// Faces of the input.
    pub input_faces: usize,
    /// Duplicate faces dropped.
    pub duplicate_faces: usize,
    /// Connected components of the input (after dropping duplicates).
    pub components: usize,
    /// Faces dropped with the smaller components.
    pub component_faces_dropped: usize,
    /// Vertices dropped with the smaller components (used by none of the kept faces).
    pub component_vertices_dropped: usize,
    /// Faces flipped to agree with their neighbours.
    pub flipped_faces: usize,
    /// Vertices merged into an earlier one at a bit-identical position before the repairs
    /// (an OBJ triangle soup or seam-split export; set by the caller that welded, 0 here).
    pub coincident_welded: usize,
    /// Vertices of the input that no face uses, dropped.
    pub unreferenced_vertices: usize,
    /// For each repaired vertex, the input vertex it is (`vt` index `k` of an output belongs
    /// to input vertex `vertex_to_input[k]`).
    pub vertex_to_input: Vec<u32>,
    /// For each input vertex, its repaired vertex, or [`DROPPED`].
    pub input_to_vertex: Vec<u32>,
    /// For each repaired face, the input face it is (possibly flipped).
    pub face_to_input: Vec<u32>,
}

impl RepairLog {
    /// Whether any repair changed the mesh (dropped or flipped anything).
    pub fn changed(&self) -> bool {
        self.duplicate_faces
            + self.component_faces_dropped
            + self.flipped_faces
            + self.vertex_to_input.len().abs_diff(self.input_vertices)
            > 0
    }

    /// One phrase per repair that changed something, for a person, e.g. `1 duplicate face
    /// dropped` (empty if none did).
    pub fn actions(&self) -> Vec<String> {
        let plural =
            |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
        let mut out = Vec::new();
        if self.coincident_welded > 0 {
            let what = plural(
                self.coincident_welded,
                "coincident vertex",
                "coincident vertices",
            );
            out.push(format!("{what} welded into an earlier one"));
        }
        if self.duplicate_faces > 0 {
            let what = plural(self.duplicate_faces, "duplicate face", "duplicate faces");
            out.push(format!("{what} dropped"));
        }
        if self.component_faces_dropped > 0 {
            out.push(format!(
                "largest of {} components kept ({} and {} dropped)",
                self.components,
                plural(self.component_faces_dropped, "face", "faces"),
                plural(self.component_vertices_dropped, "vertex", "vertices"),
            ));
        }
        if self.flipped_faces > 0 {
            let what = plural(self.flipped_faces, "face", "faces");
            out.push(format!("{what} flipped to agree with the neighbours"));
        }
        if self.unreferenced_vertices > 0 {
            let what = plural(
                self.unreferenced_vertices,
                "unreferenced vertex",
                "unreferenced vertices",
            );
            out.push(format!("{what} dropped"));
        }
        out
    }

    /// Renames the vertices and faces a [`MeshError`] about the repaired mesh names to their
    /// input numbers, so the error points into the input file. Indices outside the maps are
    /// left as they are.
    pub fn to_input_error(&self, error: MeshError) -> MeshError {
        let vi = |v: u32| self.vertex_to_input.get(v as usize).copied().unwrap_or(v);
        let v = |v: usize| self.vertex_to_input.get(v).map_or(v, |&i| i as usize);
        let f = |f: usize| self.face_to_input.get(f).map_or(f, |&i| i as usize);
        use MeshError as E;
        match error {
            E::NoVertices
            | E::NoFaces { .. }
            | E::TooManyVertices { .. }
            | E::NotClosedSurface { .. }
            // the repair reports it in input numbering already
            | E::NonOrientable { .. } => error,
            E::NonFiniteCoordinate {
                vertex,
                axis,
                value,
            } => E::NonFiniteCoordinate {
                vertex: v(vertex),
                axis,
                value,
            },
            E::IndexOutOfRange {
                face,
                index,
                vertex_count,
            } => E::IndexOutOfRange {
                face: f(face),
                index,
                vertex_count,
            },
            E::RepeatedVertexInFace { face, vertex } => E::RepeatedVertexInFace {
                face: f(face),
                vertex: vi(vertex),
            },
            E::ZeroAreaFace {
                face,
                area,
                threshold,
            } => E::ZeroAreaFace {
                face: f(face),
                area,
                threshold,
            },
            E::DuplicateFace { face, first } => E::DuplicateFace {
                face: f(face),
                first: f(first),
            },
            E::UnreferencedVertex { vertex, count } => E::UnreferencedVertex {
                vertex: v(vertex),
                count,
            },
            E::NonManifoldEdge { a, b, count, faces } => E::NonManifoldEdge {
                a: vi(a),
                b: vi(b),
                count,
                faces: faces.into_iter().map(f).collect(),
            },
            E::InconsistentOrientation { face, other, a, b } => E::InconsistentOrientation {
                face: f(face),
                other: f(other),
                a: vi(a),
                b: vi(b),
            },
            E::NonManifoldVertex { vertex, faces } => E::NonManifoldVertex {
                vertex: v(vertex),
                faces,
            },
            E::InvalidSlit {
                slit,
                vertex,
                reason,
            } => E::InvalidSlit {
                slit,
                vertex: vi(vertex),
                reason,
            },
        }
    }
}

/// A repaired triangle list, not yet validated.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Repaired {
    /// Positions of the kept vertices, in input order.
    pub positions: Vec<[f64; 3]>,
    /// The kept faces, in input order, some flipped, in repaired vertex numbering.
    pub faces: Vec<[u32; 3]>,
    /// What changed, and the maps back to the input.
    pub log: RepairLog,
}

/// Applies the repairs `options` asks for to a raw triangle list (see the module docs for
/// what each does and in which order). The result still needs [`crate::TriMesh::try_new`]:
/// defects no repair touches (degenerate faces, non-manifold elements, non-finite
/// coordinates) are left for validation to report.
///
/// # Errors
/// The [`MeshError`] of a defect no repair touches and that keeps the repairs from running:
/// no vertices or faces, too many vertices, an index out of range or a face using a vertex
/// twice (input numbering);
/// [`MeshError::NonOrientable`] when orienting and the surface has a twist.
///
/// # Examples
/// ```
/// use conformap_mesh::{repair, RepairOptions, TriMesh};
/// // a square with a flipped second face, a duplicate of the first, and a stray vertex
/// let positions = vec![
///     [0.0, 0.0, 0.0], [9.0, 9.0, 9.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0],
/// ];
/// let faces = vec![[0, 2, 3], [0, 4, 3], [3, 0, 2]];
/// assert!(TriMesh::try_new(positions.clone(), faces.clone()).is_err());
/// let fixed = repair(&positions, &faces, &RepairOptions::DEFAULT)?;
/// assert_eq!(fixed.log.actions().len(), 3);
/// assert_eq!(fixed.log.vertex_to_input, vec![0, 2, 3, 4]); // vertex 1 dropped
/// assert_eq!(fixed.faces, vec![[0, 1, 2], [0, 2, 3]]);
/// let mesh = TriMesh::try_new(fixed.positions, fixed.faces)?;
/// assert_eq!(mesh.boundary_loops().len(), 1);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn repair(
    positions: &[[f64; 3]],
    faces: &[[u32; 3]],
    options: &RepairOptions,
) -> Result<Repaired, MeshError> {
    check_preconditions(positions.len(), faces)?;
    let n = positions.len();
    let mut keep = vec![true; faces.len()];
    let duplicate_faces = if options.drop_duplicate_faces {
        mark_duplicates(faces, &mut keep)
    } else {
        0
    };
    let (component_of, sizes) = face_components(n, faces, &keep);
    let components = sizes.len();
    let mut component_faces_dropped = 0;
    if options.keep_largest_component && components > 1 {
        let best = largest(&sizes);
        for (k, c) in keep.iter_mut().zip(&component_of) {
            if *k && *c != best {
                *k = false;
                component_faces_dropped += 1;
            }
        }
    }
    let face_to_input: Vec<u32> = (0..faces.len() as u32)
        .filter(|&f| keep[f as usize])
        .collect();
    let mut kept: Vec<[u32; 3]> = face_to_input.iter().map(|&f| faces[f as usize]).collect();
    let flipped_faces = if options.orient {
        orient(&mut kept).map_err(|e| match e {
            MeshError::NonOrientable { face, other, a, b } => MeshError::NonOrientable {
                face: face_to_input[face] as usize,
                other: face_to_input[other] as usize,
                a,
                b,
            },
            other => other,
        })?
    } else {
        0
    };
    // referenced by the input (all faces) and by the kept faces
    let mut in_input = vec![false; n];
    faces
        .iter()
        .flatten()
        .for_each(|&v| in_input[v as usize] = true);
    let mut in_kept = vec![false; n];
    kept.iter()
        .flatten()
        .for_each(|&v| in_kept[v as usize] = true);
    let unreferenced_vertices = in_input.iter().filter(|r| !**r).count();
    let component_vertices_dropped = in_input
        .iter()
        .zip(&in_kept)
        .filter(|(i, k)| **i && !**k)
        .count();
    let keep_vertex = |v: usize| in_kept[v] || !options.drop_unreferenced_vertices;
    let vertex_to_input: Vec<u32> = (0..n as u32).filter(|&v| keep_vertex(v as usize)).collect();
    let mut input_to_vertex = vec![DROPPED; n];
    for (k, &v) in vertex_to_input.iter().enumerate() {
        input_to_vertex[v as usize] = k as u32;
    }
    let out_faces = kept
        .iter()
        .map(|f| f.map(|v| input_to_vertex[v as usize]))
        .collect();
    let out_positions = vertex_to_input
        .iter()
        .map(|&v| positions[v as usize])
        .collect();
    let dropped = options.drop_unreferenced_vertices;
    Ok(Repaired {
        positions: out_positions,
        faces: out_faces,
        log: RepairLog {
            input_vertices: n,
            input_faces: faces.len(),
            duplicate_faces,
            components,
            component_faces_dropped,
            component_vertices_dropped: if dropped {
                component_vertices_dropped
            } else {
                0
            },
            flipped_faces,
            unreferenced_vertices: if dropped { unreferenced_vertices } else { 0 },
            coincident_welded: 0,
            vertex_to_input,
            input_to_vertex,
            face_to_input,
        },
    })
}

/// The defects that keep the repairs from running at all, as [`crate::TriMesh::try_new`]
/// names them.
fn check_preconditions(n: usize, faces: &[[u32; 3]]) -> Result<(), MeshError> {
    if n == 0 {
        return Err(MeshError::NoVertices);
    }
    if faces.is_empty() {
        return Err(MeshError::NoFaces { vertices: n });
    }
    if n >= u32::MAX as usize || faces.len() * 3 >= u32::MAX as usize {
        return Err(MeshError::TooManyVertices { vertices: n });
    }
    for (face, f) in faces.iter().enumerate() {
        if let Some(&index) = f.iter().find(|&&i| i as usize >= n) {
            return Err(MeshError::IndexOutOfRange {
                face,
                index,
                vertex_count: n,
            });
        }
        if f[0] == f[1] || f[0] == f[2] {
            return Err(MeshError::RepeatedVertexInFace { face, vertex: f[0] });
        }
        if f[1] == f[2] {
            return Err(MeshError::RepeatedVertexInFace { face, vertex: f[1] });
        }
    }
    Ok(())
}

/// Clears `keep` for every face whose vertex set an earlier face has; returns how many.
fn mark_duplicates(faces: &[[u32; 3]], keep: &mut [bool]) -> usize {
    let mut keyed: Vec<([u32; 3], u32)> = faces
        .iter()
        .enumerate()
        .map(|(i, f)| {
            let mut k = *f;
            k.sort_unstable();
            (k, i as u32)
        })
        .collect();
    keyed.sort_unstable();
    let mut dropped = 0;
    for w in keyed.windows(2) {
        if w[0].0 == w[1].0 {
            keep[w[1].1 as usize] = false;
            dropped += 1;
        }
    }
    dropped
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[x as usize];
        parent[x as usize] = parent[p as usize];
        x = p;
    }
    x
}

/// Component (numbered by first face, in face order) of every kept face, and each
/// component's face count. Faces sharing a vertex are connected, as in
/// [`crate::TriMesh::num_components`]. Dropped faces get `u32::MAX`.
fn face_components(n: usize, faces: &[[u32; 3]], keep: &[bool]) -> (Vec<u32>, Vec<usize>) {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    for (f, _) in faces.iter().zip(keep).filter(|(_, k)| **k) {
        for k in 1..3 {
            let (a, b) = (find(&mut parent, f[0]), find(&mut parent, f[k]));
            if a != b {
                parent[a.max(b) as usize] = a.min(b);
            }
        }
    }
    let mut number = vec![u32::MAX; n];
    let mut sizes: Vec<usize> = Vec::new();
    let mut of = vec![u32::MAX; faces.len()];
    for (i, f) in faces.iter().enumerate() {
        if !keep[i] {
            continue;
        }
        let root = find(&mut parent, f[0]) as usize;
        if number[root] == u32::MAX {
            number[root] = sizes.len() as u32;
            sizes.push(0);
        }
        of[i] = number[root];
        sizes[number[root] as usize] += 1;
    }
    (of, sizes)
}

/// The component with most faces; components are numbered by first face, so the first
/// maximum is the one holding the lowest face index.
fn largest(sizes: &[usize]) -> u32 {
    let mut best = 0;
    for (c, &s) in sizes.iter().enumerate() {
        if s > sizes[best] {
            best = c;
        }
    }
    best as u32
}

/// Neighbour across each side of each face over a manifold edge: (face, same direction).
type Neighbours = Vec<[Option<(u32, bool)>; 3]>;

fn manifold_neighbours(faces: &[[u32; 3]]) -> Neighbours {
    let mut keys: Vec<(u64, u32)> = Vec::with_capacity(faces.len() * 3);
    for (f, t) in faces.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let key = (u64::from(a.min(b)) << 32) | u64::from(a.max(b));
            keys.push((key, (3 * f + k) as u32));
        }
    }
    keys.sort_unstable();
    let mut nb: Neighbours = vec![[None; 3]; faces.len()];
    let mut i = 0;
    while i < keys.len() {
        let mut j = i + 1;
        while j < keys.len() && keys[j].0 == keys[i].0 {
            j += 1;
        }
        if j - i == 2 {
            let (h0, h1) = (keys[i].1 as usize, keys[i + 1].1 as usize);
            let start = |h: usize| faces[h / 3][h % 3];
            let same = start(h0) == start(h1);
            nb[h0 / 3][h0 % 3] = Some(((h1 / 3) as u32, same));
            nb[h1 / 3][h1 % 3] = Some(((h0 / 3) as u32, same));
        }
        i = j;
    }
    nb
}

/// Flips faces so that neighbours over manifold edges agree (each patch keeps its majority
/// orientation); returns the number flipped. Face numbers in errors are indices of `faces`.
fn orient(faces: &mut [[u32; 3]]) -> Result<usize, MeshError> {
    let nb = manifold_neighbours(faces);
    let mut flip: Vec<Option<bool>> = vec![None; faces.len()];
    let mut queue = VecDeque::new();
    let mut patch = Vec::new();
    let mut flipped = 0;
    for seed in 0..faces.len() {
        if flip[seed].is_some() {
            continue;
        }
        flip[seed] = Some(false);
        queue.push_back(seed);
        patch.clear();
        while let Some(g) = queue.pop_front() {
            patch.push(g);
            let fg = flip[g].unwrap_or(false);
            for (k, side) in nb[g].iter().enumerate() {
                let Some((h, same)) = *side else { continue };
                let h = h as usize;
                let want = fg ^ same;
                match flip[h] {
                    None => {
                        flip[h] = Some(want);
                        queue.push_back(h);
                    }
                    Some(have) if have != want => {
                        return Err(MeshError::NonOrientable {
                            face: h,
                            other: g,
                            a: faces[g][k],
                            b: faces[g][(k + 1) % 3],
                        });
                    }
                    Some(_) => {}
                }
            }
        }
        let count = patch.iter().filter(|&&f| flip[f] == Some(true)).count();
        let invert = 2 * count > patch.len();
        for &f in &patch {
            let fl = flip[f] == Some(true);
            if fl != invert {
                faces[f].swap(1, 2);
                flipped += 1;
            }
        }
    }
    Ok(flipped)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    #[test]
    fn majority_orientation_wins() {
        // a fan of four triangles around vertex 0; only face 0 is flipped
        let p = vec![[0.0; 3]; 6];
        let f = vec![[0, 2, 1], [0, 2, 3], [0, 3, 4], [0, 4, 5]];
        let r = repair(&p, &f, &RepairOptions::DEFAULT).unwrap();
        assert_eq!(r.log.flipped_faces, 1);
        assert_eq!(r.faces[0], [0, 1, 2]);
        assert_eq!(&r.faces[1..], &f[1..]);
    }

    #[test]
    fn none_changes_nothing() {
        let p = vec![[0.0; 3]; 5];
        let f = vec![[0, 1, 2], [2, 1, 0]];
        let r = repair(&p, &f, &RepairOptions::NONE).unwrap();
        assert!(!r.log.changed());
        assert_eq!(r.faces, f);
        assert_eq!(r.positions.len(), 5);
        assert_eq!(r.log.components, 1);
    }
}
