//! Topology of closed surfaces: homology generators by tree–cotree decomposition, the cut
//! graph, and the cut mesh (the surface opened into one disk).
//!
//! - [`EdgeIndex`] (`edges.rs`): undirected edges with a reference orientation, the index
//!   space of 1-forms.
//! - [`homology_basis`] → [`HomologyBasis`] (`tree_cotree.rs`): shortest-path tree, maximum
//!   dual spanning tree weighted by loop length, the `2g` [`Generator`] loops.
//! - [`cut_graph`], [`cut_mesh`] → [`CutMesh`] (`cut.rs`): the pruned cut graph and the
//!   fundamental domain with its map from cut vertices back to input vertices.

mod cut;
mod edges;
mod tree_cotree;

pub use cut::{cut_graph, cut_mesh, cut_mesh_along, CutMesh};
pub use edges::EdgeIndex;
pub(crate) use tree_cotree::UnionFind;
pub use tree_cotree::{homology_basis, Generator, HomologyBasis};

use crate::trimesh::TriMesh;

/// A small torus of revolution (`n × m` grid, radii 2 and 1) for the examples.
#[doc(hidden)]
pub fn doc_torus() -> TriMesh {
    grid_torus(8, 6, 2.0, 1.0)
}

/// A torus of revolution on an `n × m` grid (test and example support).
pub(crate) fn grid_torus(n: usize, m: usize, major: f64, minor: f64) -> TriMesh {
    let id = |i: usize, j: usize| ((j % m) * n + i % n) as u32;
    let mut positions = Vec::with_capacity(n * m);
    for j in 0..m {
        let t = j as f64 * std::f64::consts::TAU / m as f64;
        for i in 0..n {
            let p = i as f64 * std::f64::consts::TAU / n as f64;
            let rho = major + minor * t.cos();
            positions.push([rho * p.cos(), rho * p.sin(), minor * t.sin()]);
        }
    }
    let mut faces = Vec::with_capacity(2 * n * m);
    for j in 0..m {
        for i in 0..n {
            faces.push([id(i, j), id(i + 1, j), id(i + 1, j + 1)]);
            faces.push([id(i, j), id(i + 1, j + 1), id(i, j + 1)]);
        }
    }
    match TriMesh::try_new(positions, faces) {
        Ok(mesh) => mesh,
        // a grid torus with n, m ≥ 3 is always valid
        Err(e) => unreachable!("grid torus invalid: {e}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{MeshError, Topology};

    /// Checks the decomposition, the generator loops and the cut mesh of a genus-`genus`
    /// closed mesh.
    fn check_basis(mesh: &TriMesh, genus: usize) {
        let basis = homology_basis(mesh, None).expect("closed");
        assert_eq!(basis.generators.len(), 2 * genus);
        let opp = mesh.opposite_halfedges();
        for g in &basis.generators {
            // a closed path of half-edges
            for w in 0..g.halfedges.len() {
                let h = g.halfedges[w] as usize;
                let next = g.halfedges[(w + 1) % g.halfedges.len()] as usize;
                assert_eq!(mesh.halfedge_vertices(h).1, mesh.halfedge_vertices(next).0);
                // no immediate backtracking
                assert_ne!(opp[h] as usize, next);
            }
            assert!(g.length > 0.0);
            assert!(!basis.in_tree[g.edge as usize] && !basis.in_cotree[g.edge as usize]);
        }
        // cotree is a spanning tree of the F faces, tree of the V vertices
        assert_eq!(
            basis.in_tree.iter().filter(|&&t| t).count(),
            mesh.num_vertices() - 1
        );
        assert_eq!(
            basis.in_cotree.iter().filter(|&&t| t).count(),
            mesh.num_faces() - 1
        );
        let on_cut = cut_graph(mesh, &basis);
        let cut = cut_mesh(mesh, &basis, on_cut).expect("valid cut");
        assert_eq!(cut.mesh.topology(), Topology::Disk);
        assert_eq!(cut.mesh.num_faces(), mesh.num_faces());
        for (c, &v) in cut.original.iter().enumerate() {
            assert_eq!(cut.mesh.positions()[c], mesh.positions()[v as usize]);
        }
        for (f, t) in mesh.faces().iter().enumerate() {
            for k in 0..3 {
                assert_eq!(cut.original[cut.mesh.faces()[f][k] as usize], t[k]);
            }
        }
        // every seam edge carries a generator loop or lies on one: the pruned graph has no
        // leaves
        let mut degree = vec![0; mesh.num_vertices()];
        for (e, &c) in cut.on_cut.iter().enumerate() {
            if c {
                let (a, b) = mesh.halfedge_vertices(basis.edges.halfedge[e] as usize);
                degree[a as usize] += 1;
                degree[b as usize] += 1;
            }
        }
        assert!(degree.iter().all(|&d| d != 1));
        // the opened mesh is the one a fresh validation of its arrays gives, also with an
        // extra flagged edge away from the cut (its sides keep both ends: it stays matched)
        let same_as_fresh = |cut: &CutMesh| {
            let fresh = TriMesh::try_new(cut.mesh.positions().to_vec(), cut.mesh.faces().to_vec())
                .expect("valid");
            assert_eq!(cut.mesh.opposite_halfedges(), fresh.opposite_halfedges());
            assert_eq!(cut.mesh.boundary_loops(), fresh.boundary_loops());
            assert_eq!(cut.mesh.boundary_flags(), fresh.boundary_flags());
            assert_eq!(cut.mesh.num_edges(), fresh.num_edges());
            assert_eq!(cut.mesh.num_components(), fresh.num_components());
        };
        same_as_fresh(&cut);
        let away = (0..basis.edges.len()).find(|&e| {
            let (a, b) = mesh.halfedge_vertices(basis.edges.halfedge[e] as usize);
            degree[a as usize] == 0 && degree[b as usize] == 0
        });
        // (the 3 × 3 torus has none: every vertex is on the cut)
        assert!(
            away.is_some() || mesh.num_faces() < 50,
            "an edge away from the cut"
        );
        if let Some(e) = away {
            let mut on_cut = cut.on_cut.clone();
            on_cut[e] = true;
            let extra = cut_mesh(mesh, &basis, on_cut).expect("valid cut");
            let h = basis.edges.halfedge[e] as usize;
            assert_ne!(extra.mesh.opposite_halfedges()[h], crate::NO_HALFEDGE);
            same_as_fresh(&extra);
        }
    }

    #[test]
    fn torus_has_two_generators_and_cuts_to_a_disk() {
        check_basis(&grid_torus(12, 7, 3.0, 1.0), 1);
        check_basis(&grid_torus(3, 3, 3.0, 1.0), 1);
    }

    #[test]
    fn torus_generators_are_the_two_circles() {
        // on a 20 × 10 torus with radii 3 and 1 the shortest loops are a meridian (length
        // ≈ 2π·1) and a loop around the hole (≈ 2π·2 along the inner equator)
        let mesh = grid_torus(20, 10, 3.0, 1.0);
        let basis = homology_basis(&mesh, None).expect("closed");
        let lens: Vec<f64> = basis.generators.iter().map(|g| g.length).collect();
        assert!((lens[0] - 6.18).abs() < 0.15, "{lens:?}"); // meridian, 10 chords of radius 1
        assert!(lens[1] < 2.0 * std::f64::consts::PI * 4.0, "{lens:?}");
    }

    #[test]
    fn open_meshes_are_refused() {
        let square = TriMesh::try_new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            vec![[0, 1, 2], [0, 2, 3]],
        )
        .expect("valid");
        assert_eq!(
            homology_basis(&square, None).err(),
            Some(MeshError::NotClosedSurface {
                components: 1,
                boundaries: 1
            })
        );
    }

    #[test]
    fn eightsim_genus_two() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/eightsim.obj");
        let text = std::fs::read_to_string(path).expect("fixture");
        let (mut p, mut f) = (Vec::new(), Vec::new());
        for line in text.lines() {
            let w: Vec<&str> = line.split_whitespace().collect();
            match w.first() {
                Some(&"v") => p.push([1, 2, 3].map(|i| w[i].parse::<f64>().expect("x"))),
                Some(&"f") => f.push([1, 2, 3].map(|i| w[i].parse::<u32>().expect("i") - 1)),
                _ => {}
            }
        }
        let mesh = TriMesh::try_new(p, f).expect("valid");
        check_basis(&mesh, 2);
    }
}
