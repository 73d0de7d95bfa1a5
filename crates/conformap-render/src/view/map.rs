//! The map view: the flat map (or an orthographic view of a sphere map) with its mesh
//! edges where they are resolvable, faces coloured by a distortion or a texture, folded
//! faces flagged, and a colour bar.

use conformap_mesh::TriMesh;
use rayon::prelude::*;

use super::{clamp_barycentric, colorbar, interpolate, FaceTex, TexMap};
use crate::camera::Camera;
use crate::error::RenderError;
use crate::faces::{distortions, face_field};
use crate::image::Image;
use crate::options::RenderOptions;
use crate::param::{Domain, MapCoords};
use crate::raster::{self, centroid, Barycentric};
use crate::textures::texture;
use crate::view::surface::{AMBIENT, DIFFUSE};
use conformap_operators::vec3::{dot, normalize};

/// Width of a mesh edge in output pixels: 1.
pub const EDGE_WIDTH_PX: f64 = 1.0;
/// Smallest altitude (output pixels) of a face whose edges are drawn at all: 2. Below it
/// the edges would merge into a solid dark area.
pub const EDGE_FADE_START_PX: f64 = 2.0;
/// Altitude (output pixels) from which a face's edges are drawn at full strength: 6.
/// Between the two the edges fade in, so dense regions of a map stay readable.
pub const EDGE_FADE_FULL_PX: f64 = 6.0;
/// Colour of mesh edges: dark grey.
const EDGE_COLOR: [f32; 3] = [0.12, 0.12, 0.12];
/// Opacity of a fully drawn edge: 0.75.
const EDGE_OPACITY: f32 = 0.75;

/// A face prepared for shading (see `raster::draw`).
#[derive(Debug, Clone, Copy, Default)]
struct MapFace {
    /// The face.
    face: u32,
    /// Its barycentric coordinates on the screen (`None`: zero screen area, or not needed).
    frame: Option<Barycentric>,
}

/// Draws the map view.
pub(crate) fn render_map(
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
    let n_faces = mesh.num_faces();
    let faces = mesh.faces();
    // the drawn mesh: the map's image of every vertex, or of every corner for a seamed map
    // (where a vertex has several images)
    let (points, per_corner) = match coords.vertex_points() {
        Some(points) => (points, false),
        None => (
            (0..n_faces)
                .into_par_iter()
                .flat_map_iter(|f| coords.face(mesh, f))
                .collect::<Vec<_>>(),
            true,
        ),
    };
    let sphere = coords.domain() == Domain::Sphere;
    let camera = if sphere {
        Camera::looking(
            [0.0, 0.0, -1.0],
            [0.0, 1.0, 0.0],
            options.azimuth_deg,
            options.elevation_deg,
        )
    } else {
        Camera::looking([0.0, 0.0, -1.0], [0.0, 1.0, 0.0], 0.0, 0.0)
    };
    let camera = camera
        .fit(points.iter(), [0.0, 0.0, side as f64 - bar, side as f64])
        .ok_or(RenderError::Collapsed)?;
    let screen: Vec<[f64; 3]> = points.par_iter().map(|&p| camera.project(p)).collect();
    let tri_index = |t: usize| {
        if per_corner {
            let b = 3 * t as u32;
            [b, b + 1, b + 2]
        } else {
            faces[t]
        }
    };
    let tri = |f: usize| tri_index(f).map(|i| screen[i as usize]);
    let corners_of = |f: usize| tri_index(f).map(|i| points[i as usize]);

    // altitudes in samples, and how strongly each face's edges show
    let half = 0.5 * EDGE_WIDTH_PX * ss as f64;
    let edges: Vec<([f32; 3], f32)> = (0..n_faces)
        .into_par_iter()
        .map(|f| {
            let t = tri(f);
            let area2 = ((t[1][0] - t[0][0]) * (t[2][1] - t[0][1])
                - (t[1][1] - t[0][1]) * (t[2][0] - t[0][0]))
                .abs();
            let mut h = [0.0f32; 3];
            for k in 0..3 {
                let (a, b) = (t[(k + 1) % 3], t[(k + 2) % 3]);
                // screen lengths are at most 2¹⁷ samples: no overflow without `hypot`
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let len = (dx * dx + dy * dy).sqrt();
                h[k] = if len > 0.0 { (area2 / len) as f32 } else { 0.0 };
            }
            let h_min = h[0].min(h[1]).min(h[2]) as f64 / ss as f64;
            let fade = ((h_min - EDGE_FADE_START_PX) / (EDGE_FADE_FULL_PX - EDGE_FADE_START_PX))
                .clamp(0.0, 1.0);
            (h, fade as f32 * EDGE_OPACITY)
        })
        .collect();
    let with_edge = |f: usize, b: [f64; 3], c: [f32; 3]| -> [f32; 3] {
        let (h, alpha) = edges[f];
        if alpha <= 0.0 {
            return c;
        }
        let d = (b[0] * h[0] as f64)
            .min(b[1] * h[1] as f64)
            .min(b[2] * h[2] as f64);
        if d < half {
            [0, 1, 2].map(|k| c[k] + alpha * (EDGE_COLOR[k] - c[k]))
        } else {
            c
        }
    };
    let light = normalize([-0.25, 0.35, 1.0]);
    let shading = |p: [f64; 3]| -> f32 {
        if sphere {
            AMBIENT + DIFFUSE * dot(normalize(p), light).max(0.0) as f32
        } else {
            1.0
        }
    };

    let bary = |frame: &Option<Barycentric>, p: [f64; 2]| {
        frame.map_or([1.0 / 3.0; 3], |b| clamp_barycentric(b.at(p[0], p[1])))
    };
    // a face's barycentric frame (not needed for a flat colour without edges)
    let prepare = |f: u32| -> MapFace {
        let fi = f as usize;
        let needed = !quantity || sphere || edges[fi].1 > 0.0;
        MapFace {
            face: f,
            frame: needed.then(|| Barycentric::new(tri(fi))).flatten(),
        }
    };
    // the sphere's light, once per face and pixel (at the centre of the face's samples)
    let light_at = |face: &MapFace, points: &[[f64; 2]]| {
        if sphere {
            let b = bary(&face.frame, centroid(points));
            shading(interpolate(b, corners_of(face.face as usize)))
        } else {
            1.0
        }
    };
    let size = options.size as usize;
    let (bg, n) = (options.background, n_faces);

    let image = if quantity {
        let field = face_field(&distortions(mesh, coords), options.color);
        let colors = field.colors();
        let shade = |face: &MapFace, points: &[[f64; 2]]| {
            let f = face.face as usize;
            let c = colors[f].map(|c| c * light_at(face, points));
            if edges[f].1 <= 0.0 {
                return c.map(|c| c * points.len() as f32);
            }
            let mut acc = [0.0f32; 3];
            for &p in points {
                let e = with_edge(f, bary(&face.frame, p), c);
                acc = [acc[0] + e[0], acc[1] + e[1], acc[2] + e[2]];
            }
            acc
        };
        let mut image = raster::draw(size, ss, &screen, n, tri_index, bg, prepare, shade);
        colorbar::draw(&mut image, &field);
        image
    } else {
        let tex = TexMap::new(mesh, coords, options.texture_cells);
        let prepare = |f: u32| {
            let face = prepare(f);
            (face, tex.face(corners_of(f as usize)))
        };
        let shade = |(face, face_tex): &(MapFace, FaceTex), points: &[[f64; 2]]| {
            let f = face.face as usize;
            let i = light_at(face, points);
            let mut acc = [0.0f32; 3];
            for &p in points {
                let b = bary(&face.frame, p);
                let (s, t) = face_tex.at(b);
                let e = with_edge(f, b, texture(options.color, s, t).map(|c| c * i));
                acc = [acc[0] + e[0], acc[1] + e[1], acc[2] + e[2]];
            }
            acc
        };
        raster::draw(size, ss, &screen, n, tri_index, bg, prepare, shade)
    };
    Ok(image)
}
