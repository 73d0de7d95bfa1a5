//! Renders the pictures of `docs/images/`: disk maps of spothead, hand and igea_open, spot's
//! sphere map, a disk with holes, each as surface (checker), map (angle or area) and
//! histogram.
//!
//! `cargo run --release -p conformap-render --example gallery -- [OUT_DIR] [NAME...]`
//! (default `target/gallery`, all names: spothead hand igea_open spot alex_3holes
//! halftunnel). Meshes of `../shared/meshes/` are skipped when absent.

use std::path::{Path, PathBuf};
use std::time::Instant;

use conformap_disk::{compute_disk_map, koebe, DiskMethod, DiskOptions, KoebeOptions};
use conformap_mesh::TriMesh;
use conformap_render::{
    angle_histogram, histogram_svg, render, ColorBy, MapCoords, RenderOptions, UvValues, View,
};
use conformap_sphere::{sphere_map, SphereOptions};
use conformap_testkit::{read_plain_obj, real_mesh_or_skip};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().unwrap_or_else(|| "target/gallery".into()));
    let mut names: Vec<String> = args.collect();
    if names.is_empty() {
        names = [
            "spothead",
            "hand",
            "igea_open",
            "spot",
            "alex_3holes",
            "halftunnel",
        ]
        .map(String::from)
        .to_vec();
    }
    std::fs::create_dir_all(&out)?;
    for name in &names {
        let Some(path) = real_mesh_or_skip(&format!("{name}.obj"), "gallery") else {
            continue;
        };
        let mesh = read_plain_obj(&path)?;
        let t = Instant::now();
        let loops = mesh.boundary_loops().len();
        if loops == 0 {
            let map = sphere_map(&mesh, &SphereOptions::DEFAULT)?;
            println!("{name}: sphere map in {:.2} s", t.elapsed().as_secs_f64());
            let coords = MapCoords::Sphere(&map.points);
            pictures(&mesh, &coords, &out, name)?;
        } else if loops == 1 {
            let map = compute_disk_map(&mesh, DiskMethod::CcemQn, &DiskOptions::DEFAULT)?;
            println!("{name}: disk map in {:.2} s", t.elapsed().as_secs_f64());
            let coords = MapCoords::Planar(UvValues::PerVertex(&map.map));
            pictures(&mesh, &coords, &out, name)?;
        } else {
            let map = koebe(&mesh, &KoebeOptions::DEFAULT)?;
            println!("{name}: Koebe map in {:.2} s", t.elapsed().as_secs_f64());
            let coords = MapCoords::Planar(UvValues::PerVertex(&map.map));
            pictures(&mesh, &coords, &out, name)?;
        }
    }
    Ok(())
}

fn pictures(mesh: &TriMesh, coords: &MapCoords<'_>, out: &Path, name: &str) -> Result<()> {
    let base = RenderOptions::DEFAULT.with_size(800);
    let jobs = [
        ("surface", base),
        ("map", base.with_view(View::Map)),
        (
            "angle",
            base.with_view(View::Map).with_color(ColorBy::Angle),
        ),
        ("area", base.with_view(View::Map).with_color(ColorBy::Area)),
        ("histogram", base.with_view(View::Histogram)),
    ];
    for (what, options) in jobs {
        let t = Instant::now();
        let image = render(mesh, coords, &options)?;
        let ms = t.elapsed().as_secs_f64() * 1e3;
        let file = out.join(format!("{name}_{what}.png"));
        image.save_png(&file)?;
        let kb = std::fs::metadata(&file)?.len() / 1024;
        println!("  {} ({ms:.0} ms, {kb} KiB)", file.display());
    }
    let hist = angle_histogram(mesh, coords, base.histogram_bins)?;
    std::fs::write(
        out.join(format!("{name}_histogram.svg")),
        histogram_svg(&hist, 800),
    )?;
    Ok(())
}
