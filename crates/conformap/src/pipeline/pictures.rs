//! `--png PREFIX`: the surface and map pictures of a command's result, staged with its
//! other outputs (`PREFIX_surface.png`, `PREFIX_map.png`).

use std::path::Path;

use conformap_mesh::TriMesh;
use conformap_render::{render, ColorBy, MapCoords, RenderOptions, UvValues, View};
use num_complex::Complex64;

use crate::failure::{render_failure, Failure};
use crate::pipeline::outputs::{png_paths, Staged};
use crate::pipeline::solved::{PictureDomain, Solved, TexCoords};

/// Side of the `--png` pictures in pixels: 1024 (the render crate's default size).
pub const PNG_SIZE: u32 = RenderOptions::DEFAULT.size;

/// Renders the surface (checkerboard) and map (angle distortion) pictures of `solved` and
/// stages them under `prefix`.
pub fn stage_pictures(
    staged: &mut Staged,
    prefix: &Path,
    mesh: &TriMesh,
    solved: &Solved,
    domain: PictureDomain,
) -> Result<(), Failure> {
    let planar: Vec<Complex64>;
    let corners: Vec<[Complex64; 3]>;
    let mut mesh = mesh;
    let coords = match (domain, &solved.uv) {
        (PictureDomain::Sphere, _) => MapCoords::Sphere(&solved.flat.0),
        (PictureDomain::Plane, TexCoords::PerVertex(uv)) => {
            planar = uv.iter().map(|t| Complex64::new(t[0], t[1])).collect();
            MapCoords::Planar(UvValues::PerVertex(&planar))
        }
        (PictureDomain::Plane, TexCoords::PerCorner(uv) | TexCoords::Refined { uv, .. }) => {
            if let TexCoords::Refined { mesh: refined, .. } = &solved.uv {
                mesh = refined;
            }
            corners = (0..uv.faces.len())
                .map(|f| {
                    std::array::from_fn(|k| {
                        let t = uv.corner(f, k);
                        Complex64::new(t[0], t[1])
                    })
                })
                .collect();
            MapCoords::Planar(UvValues::PerCorner(&corners))
        }
    };
    let options = RenderOptions::DEFAULT.with_size(PNG_SIZE);
    let views = [
        options,
        options.with_view(View::Map).with_color(ColorBy::Angle),
    ];
    for (path, view) in png_paths(prefix).iter().zip(views) {
        let image = render(mesh, &coords, &view).map_err(|e| render_failure(e, path))?;
        staged.png(path, &image)?;
    }
    Ok(())
}
