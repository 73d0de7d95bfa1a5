//! `--png PREFIX`: the surface and map pictures of a command's result, staged with its
//! other outputs (`PREFIX_surface.png`, `PREFIX_map.png`), and the mapping of render errors
//! to failures (shared with `conformap render`).

use std::ffi::OsString;
use std::path::{Path, PathBuf};

use conformap_mesh::TriMesh;
use conformap_render::{
    render, ColorBy, Image, MapCoords, RenderError, RenderOptions, UvValues, View,
};
use num_complex::Complex64;

use crate::failure::Failure;
use crate::pipeline::{Solved, Staged, TexCoords};

/// Side of the `--png` pictures in pixels: 1024 (the render crate's default size).
pub const PNG_SIZE: u32 = RenderOptions::DEFAULT.size;

/// Where a command's map lands, for its pictures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PictureDomain {
    /// A planar map: the texture coordinates of [`Solved::uv`] (an affine image of the map,
    /// which the pictures fit to their frame anyway).
    Plane,
    /// A sphere map: the unit-sphere points of [`Solved::flat`].
    Sphere,
}

/// `PREFIX_surface.png` and `PREFIX_map.png`.
pub fn png_paths(prefix: &Path) -> [PathBuf; 2] {
    ["_surface.png", "_map.png"].map(|suffix| {
        let mut name = OsString::from(prefix.as_os_str());
        name.push(suffix);
        PathBuf::from(name)
    })
}

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

/// The failure of a render error for output `path`: options are usage errors (2), a map
/// that cannot be drawn is bad input (1).
pub fn render_failure(e: RenderError, path: &Path) -> Failure {
    let hint = match &e {
        RenderError::NotOnSphere { .. } => {
            "pass a sphere map (the --flat output of `sphere`), or --domain plane for a \
             planar map"
        }
        RenderError::Collapsed => "check the map: every vertex has the same image",
        RenderError::NonFiniteValue { .. } => "recompute the map: it holds NaN or infinity",
        RenderError::InvalidOption { name, reason } => {
            return Failure::Usage(format!(
                "invalid option {}: {reason}",
                crate::failure::option_flag(name)
            ))
        }
        _ => "check that the output's directory is writable",
    };
    Failure::BadInput(
        format!("cannot draw {}: {e}", path.display()),
        Some(hint.to_string()),
    )
}

/// Encodes `image` as PNG into `path` (used by [`Staged::png`]).
pub(crate) fn write_png(path: &Path, image: &Image) -> Result<(), Failure> {
    image.save_png(path).map_err(|e| render_failure(e, path))
}
