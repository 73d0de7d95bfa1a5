//! The surface view: the 3D mesh seen by the principal-axis camera, Lambert-shaded,
//! coloured through its map per sample.

use conformap_mesh::TriMesh;
use rayon::prelude::*;

use super::{clamp_barycentric, colorbar, interpolate, TexMap};
use crate::camera::{cross, dot, normalize, Camera};
use crate::error::RenderError;
use crate::faces::{distortions, face_field};
use crate::image::Image;
use crate::options::RenderOptions;
use crate::param::MapCoords;
use crate::raster::{barycentric, rasterize, resolve};
use crate::textures::texture;

/// Share of the light that reaches every lit point regardless of its normal: 0.3 (keeps
/// the texture readable on faces turned away from the light).
pub const AMBIENT: f32 = 0.3;
/// Share of the light from the head-light, times `|n · l|` (two-sided): 0.7.
pub const DIFFUSE: f32 = 0.7;
/// Factor darkening the back side of an open surface (seen through its boundary): 0.7.
pub const BACK_SIDE: f32 = 0.7;

/// The sum of the area-weighted normals of the mesh's faces (twice the vector area), and
/// the area-weighted vertex normals (unit; zero for an isolated vertex).
pub(crate) fn normals(mesh: &TriMesh) -> ([f64; 3], Vec<[f32; 3]>) {
    let p = mesh.positions();
    let mut acc = vec![[0.0f64; 3]; mesh.num_vertices()];
    let mut sum = [0.0; 3];
    for t in mesh.faces() {
        let [a, b, c] = t.map(|v| p[v as usize]);
        let n = cross(
            [b[0] - a[0], b[1] - a[1], b[2] - a[2]],
            [c[0] - a[0], c[1] - a[1], c[2] - a[2]],
        );
        for v in t {
            let x = &mut acc[*v as usize];
            x[0] += n[0];
            x[1] += n[1];
            x[2] += n[2];
        }
        sum = [sum[0] + n[0], sum[1] + n[1], sum[2] + n[2]];
    }
    let unit = acc
        .par_iter()
        .map(|&n| normalize(n).map(|x| x as f32))
        .collect();
    (sum, unit)
}

/// Draws the surface view.
pub(crate) fn render_surface(
    mesh: &TriMesh,
    coords: &MapCoords<'_>,
    options: &RenderOptions,
) -> Result<Image, RenderError> {
    let ss = options.supersample as usize;
    let side = options.size as usize * ss;
    let quantity = !options.color.is_texture();
    let bar = if quantity {
        colorbar::width(options.size) as f64 * ss as f64
    } else {
        0.0
    };
    let (normal_sum, vertex_normals) = normals(mesh);
    let camera = Camera::principal(
        mesh.positions(),
        normal_sum,
        options.azimuth_deg,
        options.elevation_deg,
    )
    .fit(
        mesh.positions().iter(),
        [0.0, 0.0, side as f64 - bar, side as f64],
    )
    .ok_or(RenderError::Collapsed)?;
    let screen: Vec<[f64; 3]> = mesh
        .positions()
        .par_iter()
        .map(|&p| camera.project(p))
        .collect();
    let faces = mesh.faces();
    let vis = rasterize(side, side, &screen, faces.len(), |t| faces[t]);

    // head-light from the upper left of the camera
    let light = normalize([
        -camera.forward[0] + 0.35 * camera.up[0] - 0.25 * camera.right[0],
        -camera.forward[1] + 0.35 * camera.up[1] - 0.25 * camera.right[1],
        -camera.forward[2] + 0.35 * camera.up[2] - 0.25 * camera.right[2],
    ]);
    let lighting = |f: usize, b: [f64; 3]| -> f32 {
        let t = faces[f];
        let mut n = [0.0f64; 3];
        for k in 0..3 {
            let m = vertex_normals[t[k] as usize];
            for c in 0..3 {
                n[c] += b[k] * m[c] as f64;
            }
        }
        let n = normalize(n);
        let back = dot(n, camera.forward) > 0.0;
        let i = AMBIENT + DIFFUSE * dot(n, light).abs() as f32;
        if back {
            i * BACK_SIDE
        } else {
            i
        }
    };
    let tri = |f: usize| faces[f].map(|v| screen[v as usize]);

    let image = if quantity {
        let field = face_field(&distortions(mesh, coords), options.color);
        let colors = field.colors();
        let mut image = resolve(&vis, ss, options.background, |f, x, y| {
            let f = f as usize;
            let b = clamp_barycentric(barycentric(tri(f), x, y).unwrap_or([1.0 / 3.0; 3]));
            let i = lighting(f, b);
            colors[f].map(|c| c * i)
        });
        colorbar::draw(&mut image, &field);
        image
    } else {
        let tex = TexMap::new(mesh, coords, options.texture_cells);
        resolve(&vis, ss, options.background, |f, x, y| {
            let f = f as usize;
            let b = clamp_barycentric(barycentric(tri(f), x, y).unwrap_or([1.0 / 3.0; 3]));
            let (s, t) = tex.at(interpolate(b, coords.face(mesh, f)));
            let i = lighting(f, b);
            texture(options.color, s, t).map(|c| c * i)
        })
    };
    Ok(image)
}
