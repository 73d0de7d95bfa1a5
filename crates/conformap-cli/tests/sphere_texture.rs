//! The texture `conformap sphere -o` writes: equirectangular, one `vt` per face corner split
//! along the seam meridian, poles treated. Measured on the written files: no face spans
//! more than a quarter of the texture, every `vt` names its vertex's sphere point, and a
//! latitude-longitude checker drawn through the file (a small rasterizer interpolating
//! `vt` across each face, as a GPU does, with `REPEAT` wrapping) matches the checker of the
//! sphere points themselves everywhere but along the checker's own edges: no band.

mod support;

use std::path::Path;

use conformap_io::{read_mesh, read_raw_mesh, CornerUv};
use conformap_sphere::from_equirectangular_uv;
use support::{conformap_ok, fixture, s, shared, tmpdir};

/// Largest share of the texture a face may span in `u` or `v`.
const MAX_FACE_SPAN: f64 = 0.25;

/// Checker cells: 16 in longitude, 8 in latitude.
const CHECKER: [f64; 2] = [16.0, 8.0];

/// The corner texture of a written file (per-vertex `vt` read as per corner).
fn corner_uv(path: &Path) -> (conformap_mesh::TriMesh, CornerUv) {
    let loaded = read_mesh(path).expect("readable output");
    let uv = match (&loaded.corner_uv, &loaded.uv) {
        (Some(c), _) => c.clone(),
        (None, Some(uv)) => CornerUv::per_vertex(uv, loaded.mesh.faces()),
        (None, None) => panic!("{}: no texture coordinates", path.display()),
    };
    (loaded.mesh, uv)
}

/// The largest span in `u` and in `v` of any face.
fn max_spans(uv: &CornerUv) -> [f64; 2] {
    let mut worst = [0.0f64; 2];
    for f in 0..uv.faces.len() {
        for (i, w) in worst.iter_mut().enumerate() {
            let x = [0, 1, 2].map(|k| uv.corner(f, k)[i]);
            let span = x.iter().cloned().fold(f64::MIN, f64::max)
                - x.iter().cloned().fold(f64::MAX, f64::min);
            *w = w.max(span);
        }
    }
    worst
}

/// Checker parity of texture coordinates (`REPEAT` wrapping in `u`).
fn parity(uv: [f64; 2]) -> bool {
    let a = (uv[0].rem_euclid(1.0) * CHECKER[0]).floor() as i64;
    let b = (uv[1].clamp(0.0, 1.0 - 1e-12) * CHECKER[1]).floor() as i64;
    (a + b) % 2 == 0
}

/// Draws the sphere map (`points`, the mesh's faces) seen from `eye` (orthographic, with a
/// depth buffer), each pixel coloured by the checker through the interpolated `vt`;
/// returns the image and the share of covered pixels whose colour differs from the
/// checker of the interpolated sphere point itself.
fn rasterize(
    faces: &[[u32; 3]],
    points: &[[f64; 3]],
    uv: &CornerUv,
    eye: [f64; 3],
    size: usize,
) -> (Vec<u8>, f64) {
    let e = conformap_operators::vec3::normalize(eye);
    let up = if e[2].abs() < 0.9 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let right = conformap_operators::vec3::normalize(conformap_operators::vec3::cross(up, e));
    let up = conformap_operators::vec3::cross(e, right);
    let dot = conformap_operators::vec3::dot;
    let mut depth = vec![f64::NEG_INFINITY; size * size];
    let mut image = vec![255u8; size * size * 3];
    let (mut covered, mut wrong) = (0usize, 0usize);
    let px = |p: [f64; 3]| {
        [
            (dot(p, right) + 1.05) / 2.1 * size as f64,
            (1.05 - dot(p, up)) / 2.1 * size as f64,
        ]
    };
    let mut hit = vec![None; size * size];
    for (f, t) in faces.iter().enumerate() {
        let q = t.map(|v| points[v as usize]);
        let c = q.map(px);
        let area =
            (c[1][0] - c[0][0]) * (c[2][1] - c[0][1]) - (c[2][0] - c[0][0]) * (c[1][1] - c[0][1]);
        if area >= 0.0 {
            continue; // facing away (the image's y axis points down)
        }
        let lo = [0, 1].map(|i| c.iter().map(|p| p[i]).fold(f64::MAX, f64::min).max(0.0) as usize);
        let hi = [0, 1]
            .map(|i| (c.iter().map(|p| p[i]).fold(f64::MIN, f64::max).ceil() as usize).min(size));
        for y in lo[1]..hi[1] {
            for x in lo[0]..hi[0] {
                let p = [x as f64 + 0.5, y as f64 + 0.5];
                let w: [f64; 3] = std::array::from_fn(|k| {
                    let (a, b) = (c[(k + 1) % 3], c[(k + 2) % 3]);
                    ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])) / area
                });
                if w.iter().any(|&x| x < 0.0) {
                    continue;
                }
                let z: f64 = (0..3).map(|k| w[k] * dot(q[k], e)).sum();
                if z > depth[y * size + x] {
                    depth[y * size + x] = z;
                    hit[y * size + x] = Some((f, w));
                }
            }
        }
    }
    for (i, h) in hit.iter().enumerate() {
        let Some((f, w)) = *h else { continue };
        let t: [f64; 2] = std::array::from_fn(|i| (0..3).map(|k| w[k] * uv.corner(f, k)[i]).sum());
        let q = faces[f].map(|v| points[v as usize]);
        let p: [f64; 3] = std::array::from_fn(|i| (0..3).map(|k| w[k] * q[k][i]).sum());
        let truth = parity(conformap_sphere::equirectangular_uv(
            conformap_operators::vec3::normalize(p),
        ));
        let drawn = parity(t);
        covered += 1;
        if drawn != truth {
            wrong += 1;
        }
        let tone = if drawn { 40 } else { 215 };
        image[3 * i..3 * i + 3].copy_from_slice(&[tone, tone, if drawn { 120 } else { 235 }]);
    }
    (image, wrong as f64 / covered.max(1) as f64)
}

fn write_png(path: &Path, rgb: &[u8], size: usize) {
    let file = std::fs::File::create(path).expect("png file");
    let mut enc = png::Encoder::new(std::io::BufWriter::new(file), size as u32, size as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    let mut w = enc.write_header().expect("png header");
    w.write_image_data(rgb).expect("png data");
}

/// Maps `mesh` with `sphere`, writes OBJ, GLB and PLY, and checks the texture of each;
/// returns the largest spans and the checker mismatch of the OBJ.
fn check_mesh(mesh: &Path, tag: &str) -> ([f64; 2], f64) {
    let d = tmpdir(tag);
    let flat = d.join("sphere.obj");
    let outs = ["uv.obj", "uv.glb", "uv.ply"].map(|n| d.join(n));
    for out in &outs {
        conformap_ok(&["sphere", s(mesh), "-o", s(out), "--flat", s(&flat)]);
    }
    // the unit-sphere points, read without the mesh checks: a sphere map of a mesh with
    // thin features (armadillo) has faces far below read_mesh's zero-area threshold
    let points = read_raw_mesh(&flat).expect("flat").positions;
    let (m, uv) = corner_uv(&outs[0]);
    // the OBJ keeps the input's vertices and faces, in order
    let input = read_mesh(mesh).expect("input").mesh;
    assert_eq!(m.positions(), input.positions(), "{tag}");
    assert_eq!(m.faces(), input.faces(), "{tag}");
    // every corner's vt is its vertex's sphere point: its latitude always, its longitude
    // away from the poles (near them a corner may take its face's mean u)
    for (f, t) in m.faces().iter().enumerate() {
        for k in 0..3 {
            let q = from_equirectangular_uv(uv.corner(f, k));
            let p = points[t[k] as usize];
            let d = (0..3).map(|i| (p[i] - q[i]).powi(2)).sum::<f64>().sqrt();
            let polar = p[0].hypot(p[1]) <= conformap_sphere::SPHERE_POLAR_READ;
            assert!(
                (p[2] - q[2]).abs() < 1e-9,
                "{tag}: face {f} corner {k}: latitude"
            );
            assert!(
                polar || d < 1e-9,
                "{tag}: face {f} corner {k} off its point by {d}"
            );
        }
    }
    // and the file reads back as the sphere map (render and mobius take it)
    let back = conformap_sphere::sphere_points_from_corner_uv(&m, &uv.texcoords, &uv.faces)
        .expect("a sphere texture");
    let off = back
        .iter()
        .zip(&points)
        .map(|(a, b)| (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max);
    eprintln!("{tag}: points read back from the texture within {off:.2e}");
    let spans = max_spans(&uv);
    for out in &outs[1..] {
        let (_, other) = corner_uv(out);
        let s = max_spans(&other);
        assert!(
            s[0] <= MAX_FACE_SPAN && s[1] <= MAX_FACE_SPAN,
            "{}: {s:?}",
            out.display()
        );
    }
    let mut worst = 0.0f64;
    for (k, eye) in [
        [1.0, 0.0, 0.3],
        [-1.0, 0.05, 0.2],
        [0.1, 0.2, 1.0],
        [0.2, -0.1, -1.0],
    ]
    .iter()
    .enumerate()
    {
        let (img, wrong) = rasterize(m.faces(), &points, &uv, *eye, 400);
        write_png(&d.join(format!("checker_{k}.png")), &img, 400);
        worst = worst.max(wrong);
    }
    // the per-vertex texture this replaced: its seam faces span the texture
    let old_uv: Vec<[f64; 2]> = points
        .iter()
        .map(|&p| conformap_sphere::equirectangular_uv(p))
        .collect();
    let old = CornerUv::per_vertex(&old_uv, m.faces());
    let (img, old_wrong) = rasterize(m.faces(), &points, &old, [-1.0, 0.05, 0.2], 400);
    write_png(&d.join("checker_per_vertex.png"), &img, 400);
    eprintln!(
        "{tag}: spans {spans:?} (per vertex {:?}), checker mismatch {worst:.4} (per vertex, \
         seam side: {old_wrong:.4}), pictures in {}",
        max_spans(&old),
        d.display()
    );
    assert!(
        max_spans(&old)[0] > 0.5 && old_wrong > worst,
        "{tag}: the test must see a band"
    );
    (spans, worst)
}

/// Checker pixels drawn through the texture may differ from the sphere's own checker only
/// where the linear interpolation of a face crosses a cell edge, and in the small faces
/// pinched at the poles: measured 3.03 % of the covered pixels on spot in the worst of four
/// views (the view looking down a pole); the per-vertex texture, with its band along the
/// seam, 3.74 % in the view of the seam alone.
const MAX_CHECKER_MISMATCH: f64 = 0.035;

#[test]
fn spot_sphere_texture_has_no_seam_band() {
    let (spans, wrong) = check_mesh(&fixture("spot.obj"), "spot-texture");
    assert!(
        spans[0] <= MAX_FACE_SPAN && spans[1] <= MAX_FACE_SPAN,
        "{spans:?}"
    );
    assert!(wrong < MAX_CHECKER_MISMATCH, "{wrong}");
}

#[test]
#[ignore = "maps every closed genus-0 shared mesh (~1 min)"]
fn shared_closed_meshes_sphere_textures_have_no_seam_band() {
    for name in ["spot.obj", "david_head.obj", "armadillo.obj", "brain.obj"] {
        let Some(path) = shared(name) else {
            continue;
        };
        let (spans, wrong) = check_mesh(&path, name.trim_end_matches(".obj"));
        assert!(
            spans[0] <= MAX_FACE_SPAN && spans[1] <= MAX_FACE_SPAN,
            "{name}: {spans:?}"
        );
        assert!(wrong < MAX_CHECKER_MISMATCH, "{name}: {wrong}");
    }
}
