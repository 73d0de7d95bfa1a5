//! The surface view: the 3D mesh seen by the principal-axis camera, Lambert-shaded,
//! coloured through its map per sample.

use conformap_mesh::TriMesh;
use rayon::prelude::*;

use super::Canvas;
use super::{clamp_barycentric, colorbar, FaceTex, TexMap};
use crate::camera::Camera;
use crate::error::RenderError;
use crate::faces::{chart_colors, distortions, face_field};
use crate::image::Image;
use crate::options::{ColorBy, RenderOptions};
use crate::param::MapCoords;
use crate::raster::{self, centroid, Barycentric};
use crate::textures::texture;
use conformap_operators::vec3::{cross, dot, normalize, sub};

/// Share of the light that reaches every lit point regardless of its normal: 0.3 (keeps
/// the texture readable on faces turned away from the light).
pub const AMBIENT: f32 = 0.3;
/// Share of the light from the head-light, times `|n · l|` (two-sided): 0.7.
pub const DIFFUSE: f32 = 0.7;
/// Faces whose screen area is at most this many output pixels take the light
/// interpolated from their corners' (computed once per vertex) rather than the light of
/// their interpolated normal: 1 pixel. Across a face that small the two differ by a small
/// fraction of a grey level, and the normalization per face and pixel made a third of the
/// shading time of a 1M-face picture, whose faces are nearly all that small.
pub const SMALL_FACE_PX: f64 = 1.0;
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
        let n = cross(sub(b, a), sub(c, a));
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

/// A face prepared for shading (see `raster::draw`).
#[derive(Debug, Clone, Copy, Default)]
struct LitFace {
    /// The face.
    face: u32,
    /// Its barycentric coordinates on the screen (`None`: zero screen area).
    frame: Option<Barycentric>,
    /// The light at its corners, on a face of at most [`SMALL_FACE_PX`]; `None` on larger
    /// faces (lit through their interpolated normal).
    corner_light: Option<[f32; 3]>,
}

/// Draws the surface view.
pub(crate) fn render_surface(
    mesh: &TriMesh,
    coords: &MapCoords<'_>,
    options: &RenderOptions,
) -> Result<Image, RenderError> {
    let Canvas {
        ss,
        side,
        quantity,
        bar,
    } = Canvas::new(options);
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

    // head-light from the upper left of the camera
    let light = normalize([
        -camera.forward[0] + 0.35 * camera.up[0] - 0.25 * camera.right[0],
        -camera.forward[1] + 0.35 * camera.up[1] - 0.25 * camera.right[1],
        -camera.forward[2] + 0.35 * camera.up[2] - 0.25 * camera.right[2],
    ]);
    // Lambert, two-sided, darker on the back
    let light_of = |n: [f64; 3]| -> f32 {
        let i = AMBIENT + DIFFUSE * dot(n, light).abs() as f32;
        if dot(n, camera.forward) > 0.0 {
            i * BACK_SIDE
        } else {
            i
        }
    };
    let vertex_light: Vec<f32> = vertex_normals
        .par_iter()
        .map(|n| light_of(n.map(f64::from)))
        .collect();
    let small_area2 = 2.0 * (ss * ss) as f64 * SMALL_FACE_PX;
    // a face's barycentric frame, and its corners' light if it is small
    let prepare_lit = |f: u32| -> LitFace {
        let t = faces[f as usize];
        let frame = Barycentric::new(t.map(|v| screen[v as usize]));
        let small = frame.is_none_or(|fr| fr.area2() <= small_area2);
        LitFace {
            face: f,
            frame,
            corner_light: small.then(|| t.map(|v| vertex_light[v as usize])),
        }
    };
    // the light at the barycentric coordinates b: interpolated from the corners' light on a
    // small face, else the light of the interpolated normal
    let lighting = |lit: &LitFace, b: [f64; 3]| -> f32 {
        if let Some(l) = lit.corner_light {
            return (b[0] * l[0] as f64 + b[1] * l[1] as f64 + b[2] * l[2] as f64) as f32;
        }
        let t = faces[lit.face as usize];
        let mut n = [0.0f64; 3];
        for k in 0..3 {
            let m = vertex_normals[t[k] as usize];
            for c in 0..3 {
                n[c] += b[k] * m[c] as f64;
            }
        }
        light_of(normalize(n))
    };
    // the barycentric coordinates of a face at a sample point, clamped into the face
    let bary = |frame: &Option<Barycentric>, p: [f64; 2]| {
        frame.map_or([1.0 / 3.0; 3], |b| clamp_barycentric(b.at(p[0], p[1])))
    };
    let size = options.size as usize;
    let tri = |t: usize| faces[t];
    let (n, bg) = (faces.len(), options.background);

    // the light varies slowly: it is evaluated once per face and pixel (at the centre of
    // the face's samples there), the colour at every sample
    let image = if quantity {
        // charts: their colours, no bar; a distortion: its colours and its bar
        let (colors, field) = if options.color == ColorBy::Chart {
            (chart_colors(mesh, coords), None)
        } else {
            let field = face_field(&distortions(mesh, coords), options.color);
            (field.colors(), Some(field))
        };
        let shade = |lit: &LitFace, points: &[[f64; 2]]| {
            let i = lighting(lit, bary(&lit.frame, centroid(points))) * points.len() as f32;
            colors[lit.face as usize].map(|c| c * i)
        };
        let mut image = raster::draw(size, ss, &screen, n, tri, bg, prepare_lit, shade);
        if let Some(field) = &field {
            colorbar::draw(&mut image, field);
        }
        image
    } else {
        let tex = TexMap::new(mesh, coords, options.texture_cells);
        let prepare = |f: u32| (prepare_lit(f), tex.face(coords.face(mesh, f as usize)));
        let shade = |(lit, face_tex): &(LitFace, FaceTex), points: &[[f64; 2]]| {
            let i = lighting(lit, bary(&lit.frame, centroid(points)));
            let mut acc = [0.0f32; 3];
            for &p in points {
                let (s, t) = face_tex.at(bary(&lit.frame, p));
                let c = texture(options.color, s, t);
                acc = [acc[0] + c[0], acc[1] + c[1], acc[2] + c[2]];
            }
            acc.map(|c| c * i)
        };
        raster::draw(size, ss, &screen, n, tri, bg, prepare, shade)
    };
    Ok(image)
}
