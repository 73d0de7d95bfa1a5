//! Checks of a morph's frames: flipped faces against the key surface, fold patches,
//! degenerate faces, and the size of frame-to-frame steps.

use std::collections::HashMap;

use conformap_operators::vec3::{cross, dot, norm, sub};

use crate::Location;

/// A face counts as degenerate when its area is below this fraction of the squared
/// bounding-box diagonal: `1e-14` (rounding of the area of a unit triangle is 1e-16;
/// the smallest face of the shared faces is about 1e-6 of the squared diagonal).
pub const DEGENERATE_AREA_REL: f64 = 1e-14;

/// Two faces sharing an edge make a crease when their normals turn by more than this
/// many degrees: `90` (the normals oppose each other; the zipped hole fills of the
/// shared faces are pleated like that, about 170 edges per face, while the skin has no
/// such edge).
pub const CREASE_ANGLE_DEG: f64 = 90.0;

/// Twice the area vector of triangle `f` of `positions`.
pub fn face_normal(positions: &[[f64; 3]], f: &[u32; 3]) -> [f64; 3] {
    let [a, b, c] = f.map(|v| positions[v as usize]);
    cross(sub(b, a), sub(c, a))
}

/// Faces of `frame` (with connectivity `faces`) whose normal points against the normal of
/// the key surface (`key_positions`, `key_faces`) where the face lands: `landing[f]`, the
/// key surface's face under face `f` (the location of the image of its centroid, through
/// the same correspondence that carried its vertices). Returns the flipped faces,
/// ascending.
///
/// This is the key surface's normal *at the face*: a frame face is compared with the key
/// face its own interior lies on. At a crease of the key surface (where its normal jumps,
/// e.g. the rims of the shared faces' hole fills, 127–178°) the faces holding a vertex
/// disagree, so the normals at the vertices ([`flipped_at_vertices`]) do not say which
/// side a face is on.
pub fn flipped_against_key(
    frame: &[[f64; 3]],
    faces: &[[u32; 3]],
    key_positions: &[[f64; 3]],
    key_faces: &[[u32; 3]],
    landing: &[Location],
) -> Vec<usize> {
    faces
        .iter()
        .zip(landing)
        .enumerate()
        .filter(|(_, (f, at))| {
            let reference = face_normal(key_positions, &key_faces[at.face as usize]);
            !(dot(face_normal(frame, f), reference) > 0.0)
        })
        .map(|(k, _)| k)
        .collect()
}

/// Faces of `frame` whose normal points against the sum of the unit normals of the key
/// faces its three vertices were located in (`locations`, one per vertex): the measure
/// of earlier versions, kept for comparison. A vertex on a crease of the key surface is
/// located in any one of the faces around it, so a face along a crease can count as
/// flipped although it lies on the key surface (on the shared faces, S1 morphed onto
/// itself flags faces along the hole-fill rims); [`flipped_against_key`] does not.
pub fn flipped_at_vertices(
    frame: &[[f64; 3]],
    faces: &[[u32; 3]],
    key_positions: &[[f64; 3]],
    key_faces: &[[u32; 3]],
    locations: &[Location],
) -> Vec<usize> {
    let unit = |n: [f64; 3]| {
        let l = norm(n);
        if l > 0.0 {
            [n[0] / l, n[1] / l, n[2] / l]
        } else {
            n
        }
    };
    faces
        .iter()
        .enumerate()
        .filter(|(_, f)| {
            let mut reference = [0.0; 3];
            for &v in f.iter() {
                let kf = &key_faces[locations[v as usize].face as usize];
                let n = unit(face_normal(key_positions, kf));
                reference = [
                    reference[0] + n[0],
                    reference[1] + n[1],
                    reference[2] + n[2],
                ];
            }
            !(dot(face_normal(frame, f), reference) > 0.0)
        })
        .map(|(k, _)| k)
        .collect()
}

/// The crease edges of a mesh: interior edges `(a, b)`, `a < b`, whose two faces' normals
/// turn by more than `angle_deg` degrees, sorted.
pub fn crease_edges(positions: &[[f64; 3]], faces: &[[u32; 3]], angle_deg: f64) -> Vec<(u32, u32)> {
    let cos = angle_deg.to_radians().cos();
    let unit: Vec<[f64; 3]> = faces
        .iter()
        .map(|f| {
            let n = face_normal(positions, f);
            let l = norm(n);
            if l > 0.0 {
                [n[0] / l, n[1] / l, n[2] / l]
            } else {
                n
            }
        })
        .collect();
    let mut edge_faces: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (k, t) in faces.iter().enumerate() {
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            edge_faces.entry((a.min(b), a.max(b))).or_default().push(k);
        }
    }
    let mut out: Vec<(u32, u32)> = edge_faces
        .into_iter()
        .filter_map(|(edge, list)| match list[..] {
            [f, g] if dot(unit[f], unit[g]) < cos => Some(edge),
            _ => None,
        })
        .collect();
    out.sort_unstable();
    out
}

/// Faces at a crease: every face with a vertex on an edge whose two faces' normals turn
/// by more than `angle_deg` degrees (e.g. [`CREASE_ANGLE_DEG`]). One flag per face.
pub fn crease_faces(positions: &[[f64; 3]], faces: &[[u32; 3]], angle_deg: f64) -> Vec<bool> {
    let nv = faces
        .iter()
        .flat_map(|f| f.iter())
        .map(|&v| v as usize + 1)
        .max()
        .unwrap_or(0);
    let mut on_crease = vec![false; nv];
    for (a, b) in crease_edges(positions, faces, angle_deg) {
        on_crease[a as usize] = true;
        on_crease[b as usize] = true;
    }
    faces
        .iter()
        .map(|f| f.iter().any(|&v| on_crease[v as usize]))
        .collect()
}

/// The size of the largest group of `marked` faces connected through shared edges.
pub fn largest_patch(faces: &[[u32; 3]], marked: &[usize]) -> usize {
    if marked.is_empty() {
        return 0;
    }
    let mut edge_faces: HashMap<(u32, u32), Vec<usize>> = HashMap::new();
    for (k, &f) in marked.iter().enumerate() {
        let t = faces[f];
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            edge_faces.entry((a.min(b), a.max(b))).or_default().push(k);
        }
    }
    // union–find over the marked faces
    let mut parent: Vec<usize> = (0..marked.len()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for list in edge_faces.values() {
        for w in list.windows(2) {
            let (a, b) = (find(&mut parent, w[0]), find(&mut parent, w[1]));
            parent[a] = b;
        }
    }
    let mut size = vec![0usize; marked.len()];
    for k in 0..marked.len() {
        let r = find(&mut parent, k);
        size[r] += 1;
    }
    size.into_iter().max().unwrap_or(0)
}

/// Faces of `positions` whose area is at most `rel` times the squared diagonal `diag`.
pub fn degenerate_faces(positions: &[[f64; 3]], faces: &[[u32; 3]], diag: f64, rel: f64) -> usize {
    let floor = rel * diag * diag;
    faces
        .iter()
        .filter(|f| !(0.5 * norm(face_normal(positions, f)) > floor))
        .count()
}

/// The largest distance a vertex moves from `a` to `b`.
pub fn max_step(a: &[[f64; 3]], b: &[[f64; 3]]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(p, q)| norm(sub(*p, *q)))
        .fold(0.0, f64::max)
}

/// Distance from point `p` to triangle `t` (3D).
pub fn point_triangle_distance(p: [f64; 3], t: [[f64; 3]; 3]) -> f64 {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let nn = dot(n, n);
    if nn > 0.0 {
        // inside the prism over the triangle: the distance to its plane
        let inside = (0..3).all(|k| {
            let e = sub(t[(k + 1) % 3], t[k]);
            dot(cross(e, sub(p, t[k])), n) >= 0.0
        });
        if inside {
            return dot(sub(p, t[0]), n).abs() / nn.sqrt();
        }
    }
    (0..3)
        .map(|k| {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = sub(b, a);
            let ee = dot(e, e);
            let s = if ee > 0.0 {
                (dot(sub(p, a), e) / ee).clamp(0.0, 1.0)
            } else {
                0.0
            };
            norm(sub(p, [a[0] + s * e[0], a[1] + s * e[1], a[2] + s * e[2]]))
        })
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles on the edge (0, 1) along x, the second turned about that edge by
    /// `turn` degrees from the first's plane, plus a third triangle away from the edge.
    fn hinge(turn: f64) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
        let t = turn.to_radians();
        let pos = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 1.0, 0.0],
            [0.5, -t.cos(), t.sin()],
            [1.5, 1.0, 0.0],
            [2.5, 1.0, 0.0],
            [2.0, 2.0, 0.0],
        ];
        (pos, vec![[0, 1, 2], [1, 0, 3], [4, 5, 6]])
    }

    #[test]
    fn creases_are_edges_whose_normals_turn_more_than_the_angle() {
        // turned by 60°: the normals turn by 60°, no crease
        let (p, f) = hinge(60.0);
        assert_eq!(crease_faces(&p, &f, CREASE_ANGLE_DEG), vec![false; 3]);
        // turned by 120° (a sharp fold): both hinge faces, not the far one
        let (p, f) = hinge(120.0);
        assert_eq!(
            crease_faces(&p, &f, CREASE_ANGLE_DEG),
            vec![true, true, false]
        );
        // the angle is a parameter
        assert_eq!(crease_faces(&p, &f, 150.0), vec![false; 3]);
    }
}
