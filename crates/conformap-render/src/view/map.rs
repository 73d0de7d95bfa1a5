//! The map view: the flat map (or an orthographic view of a sphere map) with its mesh
//! edges where they are resolvable, faces coloured by a distortion or a texture, folded
//! faces flagged, and a colour bar.

use conformap_mesh::TriMesh;
use rayon::prelude::*;

use super::Canvas;
use super::{clamp_barycentric, colorbar, interpolate, FaceTex, TexMap};
use crate::camera::Camera;
use crate::error::RenderError;
use crate::faces::{chart_colors, distortions, face_field};
use crate::image::Image;
use crate::options::{ColorBy, RenderOptions};
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

/// What the map view draws: the map's points, where they land on the screen, and how
/// strongly each face's edges show.
struct MapScene<'a> {
    /// The mesh's faces.
    faces: &'a [[u32; 3]],
    /// The drawn points: the map's image of every vertex, or of every corner for a seamed
    /// map (where a vertex has several images).
    points: Vec<[f64; 3]>,
    /// Whether `points` holds one point per corner (`3 f + k`).
    per_corner: bool,
    /// `points` on the screen (sample pixels and depth).
    screen: Vec<[f64; 3]>,
    /// Whether the map is a sphere map (shaded by a light).
    sphere: bool,
    /// Whether faces are coloured by a quantity (rather than a texture).
    quantity: bool,
    /// Per face: its altitudes in samples and the opacity of its edges.
    edges: Vec<([f32; 3], f32)>,
    /// Half an edge's width, in samples.
    half: f64,
    /// Direction of the sphere's light (unit).
    light: [f64; 3],
}

impl MapScene<'_> {
    /// The indices into `points` of triangle `t`.
    fn tri_index(&self, t: usize) -> [u32; 3] {
        if self.per_corner {
            let b = 3 * t as u32;
            [b, b + 1, b + 2]
        } else {
            self.faces[t]
        }
    }

    /// Face `f` on the screen.
    fn tri(&self, f: usize) -> [[f64; 3]; 3] {
        self.tri_index(f).map(|i| self.screen[i as usize])
    }

    /// Face `f`'s map points.
    fn corners_of(&self, f: usize) -> [[f64; 3]; 3] {
        self.tri_index(f).map(|i| self.points[i as usize])
    }

    /// Colour `c` at barycentric coordinates `b` of face `f`, darkened towards the edge
    /// colour within half an edge's width of an edge.
    fn with_edge(&self, f: usize, b: [f64; 3], c: [f32; 3]) -> [f32; 3] {
        let (h, alpha) = self.edges[f];
        if alpha <= 0.0 {
            return c;
        }
        let d = (b[0] * h[0] as f64)
            .min(b[1] * h[1] as f64)
            .min(b[2] * h[2] as f64);
        if d < self.half {
            [0, 1, 2].map(|k| c[k] + alpha * (EDGE_COLOR[k] - c[k]))
        } else {
            c
        }
    }

    /// The light at map point `p` (1 for a planar map).
    fn shading(&self, p: [f64; 3]) -> f32 {
        if self.sphere {
            AMBIENT + DIFFUSE * dot(normalize(p), self.light).max(0.0) as f32
        } else {
            1.0
        }
    }

    /// Face `f` prepared for shading: its barycentric frame (not needed for a flat colour
    /// without edges).
    fn prepare(&self, f: u32) -> MapFace {
        let fi = f as usize;
        let needed = !self.quantity || self.sphere || self.edges[fi].1 > 0.0;
        MapFace {
            face: f,
            frame: needed.then(|| Barycentric::new(self.tri(fi))).flatten(),
        }
    }

    /// The sphere's light, once per face and pixel (at the centre of the face's samples).
    fn light_at(&self, face: &MapFace, points: &[[f64; 2]]) -> f32 {
        if self.sphere {
            let b = bary(&face.frame, centroid(points));
            self.shading(interpolate(b, self.corners_of(face.face as usize)))
        } else {
            1.0
        }
    }
}

/// Barycentric coordinates of screen point `p` in `frame` (the centre without one).
fn bary(frame: &Option<Barycentric>, p: [f64; 2]) -> [f64; 3] {
    frame.map_or([1.0 / 3.0; 3], |b| clamp_barycentric(b.at(p[0], p[1])))
}

/// The drawn points (see [`MapScene::points`]) and whether they are per corner.
fn map_points(mesh: &TriMesh, coords: &MapCoords<'_>) -> (Vec<[f64; 3]>, bool) {
    match coords.vertex_points() {
        Some(points) => (points, false),
        None => (
            (0..mesh.num_faces())
                .into_par_iter()
                .flat_map_iter(|f| coords.face(mesh, f))
                .collect::<Vec<_>>(),
            true,
        ),
    }
}

/// The camera: straight onto the plane, or turned by the options' azimuth and elevation
/// around a sphere; fitted into the picture left of the colour bar (`bar` samples wide).
fn map_camera(
    sphere: bool,
    options: &RenderOptions,
    points: &[[f64; 3]],
    side: f64,
    bar: f64,
) -> Result<Camera, RenderError> {
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
    camera
        .fit(points.iter(), [0.0, 0.0, side - bar, side])
        .ok_or(RenderError::Collapsed)
}

/// Per face: its altitudes in samples, and how strongly its edges show (fading in between
/// [`EDGE_FADE_START_PX`] and [`EDGE_FADE_FULL_PX`] of its smallest altitude).
fn edge_strengths(scene: &MapScene<'_>, n_faces: usize, ss: usize) -> Vec<([f32; 3], f32)> {
    (0..n_faces)
        .into_par_iter()
        .map(|f| {
            let t = scene.tri(f);
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
        .collect()
}

/// Draws the map view.
pub(crate) fn render_map(
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
    let (points, per_corner) = map_points(mesh, coords);
    let sphere = coords.domain() == Domain::Sphere;
    let camera = map_camera(sphere, options, &points, side as f64, bar)?;
    let screen: Vec<[f64; 3]> = points.par_iter().map(|&p| camera.project(p)).collect();
    let mut scene = MapScene {
        faces: mesh.faces(),
        points,
        per_corner,
        screen,
        sphere,
        quantity,
        edges: Vec::new(),
        half: 0.5 * EDGE_WIDTH_PX * ss as f64,
        light: normalize([-0.25, 0.35, 1.0]),
    };
    scene.edges = edge_strengths(&scene, mesh.num_faces(), ss);
    Ok(if quantity {
        draw_quantity(&scene, mesh, coords, options)
    } else {
        draw_texture(&scene, mesh, coords, options)
    })
}

/// The map coloured by the distortion of [`RenderOptions::color`], with its colour bar.
fn draw_quantity(
    scene: &MapScene<'_>,
    mesh: &TriMesh,
    coords: &MapCoords<'_>,
    options: &RenderOptions,
) -> Image {
    // charts: their colours, no bar; a distortion: its colours and its bar
    let (colors, field) = if options.color == ColorBy::Chart {
        (chart_colors(mesh, coords), None)
    } else {
        let field = face_field(&distortions(mesh, coords), options.color);
        (field.colors(), Some(field))
    };
    let shade = |face: &MapFace, points: &[[f64; 2]]| {
        let f = face.face as usize;
        let c = colors[f].map(|c| c * scene.light_at(face, points));
        if scene.edges[f].1 <= 0.0 {
            return c.map(|c| c * points.len() as f32);
        }
        let mut acc = [0.0f32; 3];
        for &p in points {
            let e = scene.with_edge(f, bary(&face.frame, p), c);
            acc = [acc[0] + e[0], acc[1] + e[1], acc[2] + e[2]];
        }
        acc
    };
    let mut image = raster::draw(
        options.size as usize,
        options.supersample as usize,
        &scene.screen,
        mesh.num_faces(),
        |t| scene.tri_index(t),
        options.background,
        |f| scene.prepare(f),
        shade,
    );
    if let Some(field) = &field {
        colorbar::draw(&mut image, field);
    }
    image
}

/// The map with the texture of [`RenderOptions::color`] through it.
fn draw_texture(
    scene: &MapScene<'_>,
    mesh: &TriMesh,
    coords: &MapCoords<'_>,
    options: &RenderOptions,
) -> Image {
    let tex = TexMap::new(mesh, coords, options.texture_cells);
    let prepare = |f: u32| (scene.prepare(f), tex.face(scene.corners_of(f as usize)));
    let shade = |(face, face_tex): &(MapFace, FaceTex), points: &[[f64; 2]]| {
        let f = face.face as usize;
        let i = scene.light_at(face, points);
        let mut acc = [0.0f32; 3];
        for &p in points {
            let b = bary(&face.frame, p);
            let (s, t) = face_tex.at(b);
            let e = scene.with_edge(f, b, texture(options.color, s, t).map(|c| c * i));
            acc = [acc[0] + e[0], acc[1] + e[1], acc[2] + e[2]];
        }
        acc
    };
    raster::draw(
        options.size as usize,
        options.supersample as usize,
        &scene.screen,
        mesh.num_faces(),
        |t| scene.tri_index(t),
        options.background,
        prepare,
        shade,
    )
}
