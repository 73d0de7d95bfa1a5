//! Given cones (`--cones FILE`, the Python package's list): reading the file and checking
//! the cones against the mesh, every refusal naming its line (or list entry), the bad value
//! and what would be right.

use std::collections::HashMap;
use std::f64::consts::TAU;
use std::path::Path;

use conformap_atlas::cones::MAX_CONE_ANGLE;
use conformap_atlas::split_components;
use conformap_mesh::TriMesh;

use crate::failure::Failure;

/// How far, in degrees per cone, the curvatures `360° − angle` of a closed genus-0
/// component's cones may miss `360°·χ = 720°` and still be taken (the miss then shared
/// evenly among them): 1e-4°, what angles written with four decimals can miss by. A
/// report's angles (full precision) miss by about 1e-12°.
pub const GAUSS_BONNET_TOLERANCE_DEG: f64 = 1e-4;

/// One given cone.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GivenCone {
    /// Where it was given, for messages: `FILE:3` (line 3 of a file), `cones[2]` (an entry
    /// of a list).
    pub place: String,
    /// The vertex (0-based, the order of the mesh's `v` lines).
    pub vertex: u64,
    /// The cone angle, degrees (360: no cone; below: a convex tip; above: a saddle).
    pub angle_deg: f64,
}

/// Cones given by the user, not checked against a mesh yet.
#[derive(Debug, Clone, PartialEq, Default)]
#[non_exhaustive]
pub struct GivenCones {
    /// Where they come from, for messages: the file, or `cones`.
    pub origin: String,
    /// The cones in the order given.
    pub cones: Vec<GivenCone>,
}

impl GivenCones {
    /// Cones from `(vertex, angle in degrees)` pairs (the Python package's array), named
    /// `cones[i]` in messages.
    pub fn from_pairs(pairs: &[(u64, f64)]) -> Self {
        Self {
            origin: "cones".into(),
            cones: pairs
                .iter()
                .enumerate()
                .map(|(i, &(vertex, angle_deg))| GivenCone {
                    place: format!("cones[{i}]"),
                    vertex,
                    angle_deg,
                })
                .collect(),
        }
    }

    fn refuse(&self, place: &str, what: String, hint: &str) -> Failure {
        Failure::BadInput(format!("{place}: {what}"), Some(hint.to_string()))
    }

    /// The cones as the atlas takes them (vertex, defect `2π − angle` in radians), after checking them
    /// against `mesh`: every vertex in range, used by a face, not on the boundary, given
    /// once; every angle finite, above 0° and at most 720°; on every closed genus-0
    /// component the curvatures summing to 720° (Gauss–Bonnet, within
    /// [`GAUSS_BONNET_TOLERANCE_DEG`] per cone). Components of genus ≥ 1 and with
    /// boundary have no sum to meet: their handle cuts and boundary take up the rest.
    ///
    /// On a mesh split at its non-manifold vertices, `copies` is the input vertex of each
    /// vertex added (after the input's): a cone cannot sit on a vertex that was split.
    ///
    /// # Errors
    /// [`Failure::BadInput`] naming the first bad cone (its line or entry, the value), or
    /// the component whose cones break Gauss–Bonnet (their sum and the one needed).
    pub fn check(&self, mesh: &TriMesh, copies: &[u32]) -> Result<Vec<(u32, f64)>, Failure> {
        let n = mesh.num_vertices();
        let n_input = n - copies.len();
        let mut on_boundary = vec![false; n];
        for &v in mesh.boundary_loops().iter().flatten() {
            on_boundary[v as usize] = true;
        }
        let mut used = vec![false; n];
        for &v in mesh.faces().iter().flatten() {
            used[v as usize] = true;
        }
        let max_deg = MAX_CONE_ANGLE.to_degrees();
        let mut first: HashMap<u64, &str> = HashMap::new();
        for c in &self.cones {
            let place = c.place.as_str();
            if c.vertex >= n_input as u64 {
                return Err(self.refuse(
                    place,
                    format!(
                        "vertex {} is out of range: the mesh has {n_input} vertices (0 to {})",
                        c.vertex,
                        n_input.saturating_sub(1)
                    ),
                    "vertices are 0-based, in the order of the mesh's `v` lines (the `vertex` \
                     of each entry of the report's atlas.cone_list)",
                ));
            }
            if !(c.angle_deg.is_finite() && c.angle_deg > 0.0 && c.angle_deg <= max_deg) {
                return Err(self.refuse(
                    place,
                    format!(
                        "cone angle {}° at vertex {} is not a cone angle: it must be a finite \
                         number of degrees above 0 and at most {max_deg}",
                        c.angle_deg, c.vertex
                    ),
                    "give the total angle around the vertex in the flattened layout, in degrees: \
                     below 360 for a tip (90 for a cube corner), above 360 for a saddle; past \
                     720° the layout wraps round the cone more than twice and overlaps itself",
                ));
            }
            if copies.contains(&(c.vertex as u32)) {
                return Err(self.refuse(
                    place,
                    format!(
                        "vertex {} is non-manifold: the atlas splits it into one vertex per \
                         fan of faces",
                        c.vertex
                    ),
                    "a cone must sit on a manifold vertex; choose a vertex next to it",
                ));
            }
            if !used[c.vertex as usize] {
                return Err(self.refuse(
                    place,
                    format!("vertex {} is used by no face", c.vertex),
                    "a cone must sit on a vertex of the surface",
                ));
            }
            if on_boundary[c.vertex as usize] {
                return Err(self.refuse(
                    place,
                    format!("vertex {} lies on the boundary", c.vertex),
                    "a cone must be an interior vertex: the boundary of a chart is free and \
                     takes up curvature without cones; remove this line",
                ));
            }
            if let Some(before) = first.insert(c.vertex, place) {
                return Err(self.refuse(
                    place,
                    format!("vertex {} already has a cone ({before})", c.vertex),
                    "give each vertex at most one cone angle",
                ));
            }
        }
        let mut cones: Vec<(u32, f64)> = self
            .cones
            .iter()
            .map(|c| (c.vertex as u32, TAU - c.angle_deg.to_radians()))
            .collect();
        // Gauss–Bonnet on the closed genus-0 components
        let mut cones_at: HashMap<u32, usize> = HashMap::new();
        for (i, c) in cones.iter().enumerate() {
            cones_at.insert(c.0, i);
        }
        for (index, faces) in split_components(n, mesh.faces()).iter().enumerate() {
            let Some(chi) = closed_euler_characteristic(mesh, faces, &on_boundary) else {
                continue;
            };
            if chi != 2 {
                continue;
            }
            let mut verts: Vec<u32> = faces
                .iter()
                .flat_map(|&f| mesh.faces()[f as usize])
                .collect();
            verts.sort_unstable();
            verts.dedup();
            let mine: Vec<usize> = verts
                .iter()
                .filter_map(|v| cones_at.get(v))
                .copied()
                .collect();
            let sum_deg: f64 = mine.iter().map(|&i| cones[i].1.to_degrees()).sum();
            let need = 360.0 * chi as f64;
            let miss = need - sum_deg;
            if miss.abs() > GAUSS_BONNET_TOLERANCE_DEG * mine.len().max(1) as f64 {
                return Err(Failure::BadInput(
                    format!(
                        "{}: the {} cone(s) on component {index} (a closed surface of genus 0, \
                         χ = 2) carry a curvature Σ (360° − angle) = {sum_deg:.6}°; \
                         Gauss–Bonnet needs 360°·χ = {need}°",
                        self.origin,
                        mine.len(),
                    ),
                    Some(format!(
                        "change the angles of that component's cones so that their curvatures \
                         360° − angle add up to {need}° (off by {miss:+.6}° now), e.g. 8 cones of \
                         270°; or let the atlas place them: --cones 8 or --cones auto"
                    )),
                ));
            }
            for &i in &mine {
                cones[i].1 += miss.to_radians() / mine.len() as f64;
            }
        }
        Ok(cones)
    }
}

/// The Euler characteristic `V − E + F` of the component of `faces` when it is closed
/// (none of its vertices on the boundary); `None` otherwise.
fn closed_euler_characteristic(mesh: &TriMesh, faces: &[u32], on_boundary: &[bool]) -> Option<i64> {
    let mut verts: Vec<u32> = Vec::with_capacity(3 * faces.len());
    for &f in faces {
        for v in mesh.faces()[f as usize] {
            if on_boundary[v as usize] {
                return None;
            }
            verts.push(v);
        }
    }
    verts.sort_unstable();
    verts.dedup();
    // closed: every edge has two faces
    let edges = 3 * faces.len() / 2;
    Some(verts.len() as i64 - edges as i64 + faces.len() as i64)
}

/// Reads a cone file: one `<vertex> <cone angle in degrees>` per line (0-based vertex
/// indices), `#` starting a comment, blank lines skipped.
///
/// # Errors
/// [`Failure::BadInput`] for an unreadable file or a line that is not two numbers (its
/// path and line, what it holds, a hint).
pub fn parse_cone_file(path: &Path) -> Result<GivenCones, Failure> {
    let shown = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| {
        Failure::BadInput(
            format!("{shown}: cannot read the cone file: {e}"),
            Some(
                "--cones takes a count, `auto` or a file of `<vertex> <angle in degrees>` lines"
                    .into(),
            ),
        )
    })?;
    let mut cones = Vec::new();
    let hint = "each line holds `<vertex> <cone angle in degrees>`: a 0-based vertex index \
                and a number, e.g. `123 270`; `#` starts a comment";
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let place = format!("{shown}:{}", i + 1);
        let bad = |what: String| {
            Failure::BadInput(format!("{shown}:{}: {what}", i + 1), Some(hint.to_string()))
        };
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() != 2 {
            return Err(bad(format!(
                "`{line}` has {} field(s), not 2 (vertex and angle)",
                fields.len()
            )));
        }
        let vertex: u64 = fields[0].parse().map_err(|_| {
            bad(format!(
                "vertex `{}` is not a vertex index (a whole number, 0 or more)",
                fields[0]
            ))
        })?;
        let angle_deg: f64 = fields[1]
            .parse()
            .map_err(|_| bad(format!("angle `{}` is not a number", fields[1])))?;
        cones.push(GivenCone {
            place,
            vertex,
            angle_deg,
        });
    }
    Ok(GivenCones {
        origin: shown,
        cones,
    })
}
