//! A whole atlas of a file with several components of every topology (a disk, a closed
//! genus 0, a genus 2, a holed disk, a genus 1 with boundary): every face kept, every uv in
//! the unit square, nothing flipped, no texel covered twice at 1024², seams equal.

use conformap_atlas::{build_atlas, AtlasOptions};

fn soup(names: &[&str]) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let (mut p, mut f) = (Vec::new(), Vec::new());
    for (i, name) in names.iter().enumerate() {
        let path = format!("{}/../../fixtures/{name}.obj", env!("CARGO_MANIFEST_DIR"));
        let mesh = conformap_io::read_mesh(path).expect("fixture reads").mesh;
        let base = p.len() as u32;
        // side by side in space (the atlas must not care)
        p.extend(
            mesh.positions()
                .iter()
                .map(|q| [q[0] + 1000.0 * i as f64, q[1], q[2]]),
        );
        f.extend(mesh.faces().iter().map(|t| t.map(|v| v + base)));
    }
    (p, f)
}

#[test]
fn five_components_of_every_topology_share_the_square_without_overlap() {
    let names = ["woody", "spot", "eightsim", "halftunnel", "punctured_torus"];
    let (p, f) = soup(&names);
    let atlas = build_atlas(&p, &f, &AtlasOptions::default()).expect("atlas");
    let r = &atlas.report;
    assert_eq!(r.components, 5);
    assert_eq!(atlas.uv.len(), 3 * f.len());
    assert!(atlas
        .uv
        .iter()
        .all(|q| (0.0..=1.0).contains(&q[0]) && (0.0..=1.0).contains(&q[1])));
    assert_eq!(r.flipped, 0, "{r:?}");
    assert_eq!(r.overlap.covered_twice, 0, "{r:?}");
    // seams agree to rounding, those of charts split because they overlapped too
    assert!(r.seam_log_ratio_max < 1e-10, "{r:?}");
    // spot and eightsim overlapped themselves in one piece each and were split
    assert!(r.charts > 5, "{r:?}");
    // 8 cones on spot, eightsim and the punctured torus, none on the two planar domains
    assert_eq!(r.cones, 24);
    assert!(r.packing_efficiency > 0.2, "{r:?}");
    // one texel density: every chart scaled alike
    assert!(atlas
        .packing
        .charts
        .iter()
        .all(|c| c.scale == atlas.packing.scale));
    // and every component given the same texture area per 3D area (before the layouts
    // were brought to their surfaces' area the five differed 29-fold: spot 9× woody's,
    // halftunnel 0.3×)
    let density: Vec<f64> = atlas
        .charts
        .iter()
        .map(|c| {
            let (mut uv_area, mut area) = (0.0, 0.0);
            for &face in &c.faces {
                let q = |k: usize| atlas.uv[3 * face as usize + k];
                let (a, b, d) = (q(0), q(1), q(2));
                uv_area +=
                    0.5 * ((b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0])).abs();
                let t = f[face as usize].map(|v| p[v as usize]);
                area += conformap_mesh::triangle_area(t[0], t[1], t[2]);
            }
            uv_area / area
        })
        .collect();
    for d in &density {
        assert!((d / density[0] - 1.0).abs() < 1e-9, "{density:?}");
    }
}

/// A flat 4 × 1 strip is one chart that fills a third of its smallest square (5/√2 on the
/// diagonal: 4 / 12.5 = 0.32); cut at its neck, the middle, its two halves stack into a
/// 2 × 2 square. Every seam, the new one too, keeps its lengths exactly.
#[test]
fn a_long_strip_is_cut_at_its_middle_and_its_halves_stacked() {
    let (nx, ny) = (32u32, 8u32);
    let mut p = Vec::new();
    for j in 0..=ny {
        for i in 0..=nx {
            // interior vertices nudged off the grid (a grid packed to whole texels would
            // put vertices on texel centres, where the raster's fill rule is ambiguous)
            let inner = i > 0 && i < nx && j > 0 && j < ny;
            let nudge = if inner {
                0.01 * ((i * 7 + j * 3) % 5) as f64
            } else {
                0.0
            };
            p.push([
                (4.0 * i as f64 + nudge) / nx as f64,
                (j as f64 + nudge) / ny as f64,
                0.0,
            ]);
        }
    }
    let at = |i: u32, j: u32| j * (nx + 1) + i;
    let mut f = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            f.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            f.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let atlas = build_atlas(&p, &f, &AtlasOptions::default()).expect("atlas");
    let r = &atlas.report;
    assert_eq!(r.charts, 2, "{r:?}");
    assert!(r.packing_efficiency > 0.85, "{r:?}");
    assert_eq!(r.overlap.covered_twice, 0, "{r:?}");
    assert_eq!(r.flipped, 0, "{r:?}");
    assert!(r.seam_log_ratio_max < 1e-12, "{r:?}");
    // the halves hold half of the strip each
    let halves: Vec<usize> = atlas.charts[0]
        .pieces
        .iter()
        .map(|q| q.faces.len())
        .collect();
    assert_eq!(halves.iter().sum::<usize>(), f.len());
    assert!(
        halves
            .iter()
            .all(|&n| n.abs_diff(f.len() / 2) <= f.len() / 16),
        "{halves:?}"
    );
}

/// Armadillo (thin limbs, obtuse triangles; its cones at π/4 folded 34 faces): no flipped
/// face, nothing overlaps and every seam keeps its length; the atlas issue's bars against BFF's 8 cones
/// (area spread 2.51, angle 1.47°, packing 0.40).
#[test]
#[ignore = "reads the 86k-face armadillo from ../shared/meshes"]
fn armadillo_has_no_flipped_face_and_no_overlap() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/meshes/armadillo.obj"
    );
    let mesh = conformap_io::read_mesh(path).expect("armadillo").mesh;
    let atlas =
        build_atlas(mesh.positions(), mesh.faces(), &AtlasOptions::default()).expect("atlas");
    let r = &atlas.report;
    assert_eq!(r.flipped, 0, "{r:?}");
    assert_eq!(r.overlap.covered_twice, 0, "{r:?}");
    assert!(
        r.seam_log_ratio_mean < 1e-3 && r.seam_log_ratio_max < 1e-6,
        "{r:?}"
    );
}

/// `--cones auto` on armadillo at the default bound (area spread 1.0): the first count
/// whose layout is within the bound, 18 cones, left 1 face flipped after the atlas's
/// repairs; the search goes on to a count that leaves none (19).
#[test]
#[ignore = "reads the 86k-face armadillo from ../shared/meshes; minutes in debug, 8 s in release"]
fn armadillo_auto_cones_leave_no_flipped_face() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../../shared/meshes/armadillo.obj"
    );
    let mesh = conformap_io::read_mesh(path).expect("armadillo").mesh;
    let mut options = AtlasOptions::default();
    options.max_area_spread = Some(1.0);
    let atlas = build_atlas(mesh.positions(), mesh.faces(), &options).expect("atlas");
    let r = &atlas.report;
    assert_eq!(r.flipped, 0, "{r:?}");
    assert_eq!(r.overlap.covered_twice, 0, "{r:?}");
    assert!(r.area_spread <= 1.0, "{r:?}");
}

/// eightsim (173 vertices) at 32 cones is cut into strips one face wide whose boundary
/// crosses itself where no interior path can separate the crossing: such a piece is grown
/// again into regions without overlap (1,602 texels covered twice before, 0 now), every
/// face keeping its layout.
#[test]
fn pieces_no_path_can_split_are_regrown_without_overlap() {
    let (p, f) = soup(&["eightsim"]);
    let atlas = build_atlas(&p, &f, &AtlasOptions::default().with_cones(32)).expect("atlas");
    let r = &atlas.report;
    assert_eq!(r.cones, 32);
    assert_eq!(r.flipped, 0, "{r:?}");
    assert_eq!(r.overlap.covered_twice, 0, "{r:?}");
    assert!(r.seam_log_ratio_max < 1e-10, "{r:?}");
    assert_eq!(atlas.uv.len(), 3 * f.len());
}

/// The overlap splits cut one crossing at a time and leave slivers; pieces that share a
/// path of edges in the chart's layout are merged back where the union overlaps nothing
/// (`chart/merge.rs`): spot 9 → 4 charts, eightsim 13 → 6 and at 32 cones 38 → 14, each
/// still without a flipped face or a texel covered twice, seams of equal length.
#[test]
fn slivers_of_the_overlap_splits_are_merged_back() {
    for (mesh, cones, most) in [("spot", 8, 4), ("eightsim", 8, 6), ("eightsim", 32, 14)] {
        let (p, f) = soup(&[mesh]);
        let atlas = build_atlas(&p, &f, &AtlasOptions::default().with_cones(cones)).expect("atlas");
        let r = &atlas.report;
        assert!(r.charts <= most, "{mesh} at {cones} cones: {r:?}");
        assert_eq!(r.flipped, 0, "{mesh}: {r:?}");
        assert_eq!(r.overlap.covered_twice, 0, "{mesh}: {r:?}");
        assert!(r.seam_log_ratio_max < 1e-10, "{mesh}: {r:?}");
        assert_eq!(atlas.uv.len(), 3 * f.len());
    }
}
