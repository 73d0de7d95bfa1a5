//! Pictures of global conformal parameterizations (holomorphic 1-forms) of the higher-genus
//! meshes: the surface with a checkerboard through the seamed layout, and the layout (the
//! fundamental domain) coloured by angle distortion.
//!
//! `cargo run --release -p conformap-render --example global_gallery -- [OUT_DIR] [NAME...]`
//! (default `target/gallery`, names: eight kitten_10k fertility punctured_torus). Meshes of
//! `../shared/meshes/` are skipped when absent.

use std::path::PathBuf;
use std::time::Instant;

use conformap_global::{global_map, GlobalMapOptions};
use conformap_render::{render, ColorBy, MapCoords, RenderOptions, UvValues, View};
use conformap_testkit::{read_plain_obj, real_mesh_or_skip};
use num_complex::Complex64;

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().unwrap_or_else(|| "target/gallery".into()));
    let mut names: Vec<String> = args.collect();
    if names.is_empty() {
        names = ["eight", "kitten_10k", "fertility", "punctured_torus"]
            .map(String::from)
            .to_vec();
    }
    std::fs::create_dir_all(&out)?;
    for name in &names {
        let Some(path) = real_mesh_or_skip(&format!("{name}.obj"), "global_gallery") else {
            continue;
        };
        let mesh = read_plain_obj(&path)?;
        let t = Instant::now();
        let map = global_map(&mesh, &GlobalMapOptions::DEFAULT)?;
        println!(
            "{name}: genus {}, form {}, {} zeros, in {:.2} s",
            map.genus,
            map.form_index,
            map.input_zeros().count(),
            t.elapsed().as_secs_f64()
        );
        // the input's faces (the first copy of a double covering)
        let corners: Vec<[Complex64; 3]> = map
            .input_corner_uv()
            .chunks_exact(3)
            .map(|c| [c[0], c[1], c[2]])
            .collect();
        let coords = MapCoords::Planar(UvValues::PerCorner(&corners));
        let shown = if map.split_edges == 0 && map.input_faces == mesh.num_faces() {
            mesh.clone()
        } else {
            conformap_mesh::TriMesh::try_new(
                map.surface.positions()[..map.input_vertices].to_vec(),
                map.surface.faces()[..map.input_faces].to_vec(),
            )?
        };
        let base = RenderOptions::DEFAULT.with_size(800);
        for (what, options) in [
            ("global_surface", base),
            (
                "global_layout",
                base.with_view(View::Map).with_color(ColorBy::Angle),
            ),
        ] {
            let image = render(&shown, &coords, &options)?;
            let file = out.join(format!("{name}_{what}.png"));
            image.save_png(&file)?;
            println!("  {}", file.display());
        }
    }
    Ok(())
}
