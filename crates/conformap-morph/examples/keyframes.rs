//! Pictures of a morph's key frames: every key frame of the shared faces (or of the
//! surfaces given) drawn with `conformap-render`, S1's disk map as a checkerboard (so a
//! tear or a fold shows as broken cells), and a close-up of the eyes and mouth coloured
//! by the angle distortion of that map with the faces flipped against the key surface
//! flagged magenta. `--no-creases`: without carrying S1's crease loops (the hole-fill
//! rims) onto the key surfaces', for comparison. `--around V1,V2,... --radius R`: also a
//! close-up of the faces of S1 within `R` (of the diagonal) of S1's vertices `V1, V2, …`
//! (e.g. the mouth corners), seen from `--azimuth A --elevation E` degrees.
//!
//! ```text
//! cargo run --release -p conformap-morph --example keyframes -- [--hard] [--no-creases] \
//!     [--around V1,V2 --radius R [--azimuth A] [--elevation E]] [OUT_DIR]
//! ```
//!
//! Writes `OUT_DIR/key_K.png`, `OUT_DIR/key_K_closeup.png` and, with `--around`,
//! `OUT_DIR/key_K_around.png` (default `target/morph`).

use std::path::PathBuf;

use conformap_mesh::TriMesh;
use conformap_morph::quality::flipped_against_key;
use conformap_morph::{morph, Landmarks, MorphOptions, Surface};
use conformap_render::{render, ColorBy, MapCoords, RenderOptions, UvValues};
use num_complex::Complex64;

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

fn main() -> Result<()> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let mut options = MorphOptions::DEFAULT;
    if let Some(k) = args.iter().position(|a| a == "--hard") {
        args.remove(k);
        options = options.with_hard_landmarks();
    }
    if let Some(k) = args.iter().position(|a| a == "--no-creases") {
        args.remove(k);
        options = options.with_crease_matching(false);
    }
    let mut value = |flag: &str| -> Option<String> {
        let k = args.iter().position(|a| a == flag)?;
        args.remove(k);
        (k < args.len()).then(|| args.remove(k))
    };
    let around: Vec<u32> = match value("--around") {
        Some(list) => list
            .split(',')
            .map(str::parse)
            .collect::<std::result::Result<_, _>>()?,
        None => Vec::new(),
    };
    let around_radius: f64 = value("--radius").map_or(Ok(0.03), |r| r.parse())?;
    let azimuth: f64 = value("--azimuth").map_or(Ok(0.0), |r| r.parse())?;
    let elevation: f64 = value("--elevation").map_or(Ok(0.0), |r| r.parse())?;
    let out = PathBuf::from(args.pop().unwrap_or_else(|| "target/morph".into()));
    std::fs::create_dir_all(&out)?;
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/morph");
    let mut surfaces = Vec::new();
    for name in ["ict_neutral", "ict_wry", "ict_pout"] {
        let mesh = conformap_io::read_mesh(format!("{dir}/{name}.obj"))?.mesh;
        let text = std::fs::read_to_string(format!("{dir}/{name}.landmarks.txt"))?;
        surfaces.push(Surface::new(mesh, Landmarks::parse(&text)?));
    }
    let m = morph(&surfaces, &options)?;
    let s1 = &surfaces[0].mesh;
    let disk = conformap_disk::compute_disk_map(
        s1,
        conformap_disk::DiskMethod::CcemQn,
        &conformap_disk::DiskOptions::DEFAULT,
    )?
    .map;
    for k in 0..surfaces.len() {
        let key = TriMesh::try_new(m.keys()[k].clone(), s1.faces().to_vec())?;
        let picture = render(
            &key,
            &MapCoords::Planar(UvValues::PerVertex(&disk)),
            &RenderOptions::DEFAULT.with_size(480),
        )?;
        picture.save_png(&out.join(format!("key_{k}.png")))?;
        if k == 0 {
            continue;
        }
        let flips = flipped_against_key(
            &m.keys()[k],
            s1.faces(),
            surfaces[k].mesh.positions(),
            surfaces[k].mesh.faces(),
            &m.landings()[k],
        );
        // the close-up: faces of S1 within a radius of the eye and mouth landmarks, the
        // flipped ones with two corners swapped (a folded face, flagged by the renderer)
        let view = RenderOptions::DEFAULT
            .with_size(480)
            .with_color(ColorBy::Angle);
        let lm: Vec<u32> = surfaces[0].landmarks.vertices()[1..].to_vec();
        let radius = 0.12 * s1.bbox_diagonal();
        closeup(&m.keys()[k], s1, &disk, &flips, &lm, radius, &view)?
            .save_png(&out.join(format!("key_{k}_closeup.png")))?;
        if !around.is_empty() {
            let view = view
                .with_size(720)
                .with_azimuth_deg(azimuth)
                .with_elevation_deg(elevation);
            let radius = around_radius * s1.bbox_diagonal();
            closeup(&m.keys()[k], s1, &disk, &flips, &around, radius, &view)?
                .save_png(&out.join(format!("key_{k}_around.png")))?;
        }
        println!(
            "key {k}: {} flipped faces (magenta in the close-up): {:?}",
            flips.len(),
            flips.iter().map(|&f| s1.faces()[f]).collect::<Vec<_>>()
        );
    }
    Ok(())
}

/// The faces of S1 (first vertex within `radius` of one of S1's vertices `centres`) at
/// the key frame's positions `key`, coloured through S1's disk map `disk`, the faces in
/// `flips` with two corners swapped (flagged magenta by the renderer).
fn closeup(
    key: &[[f64; 3]],
    s1: &TriMesh,
    disk: &[Complex64],
    flips: &[usize],
    centres: &[u32],
    radius: f64,
    view: &RenderOptions,
) -> Result<conformap_render::Image> {
    let near = |f: &[u32; 3]| {
        let p = s1.positions()[f[0] as usize];
        centres.iter().any(|&c| {
            let q = s1.positions()[c as usize];
            let d = [p[0] - q[0], p[1] - q[1], p[2] - q[2]];
            (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt() < radius
        })
    };
    let mut faces = Vec::new();
    let mut corners: Vec<[Complex64; 3]> = Vec::new();
    for (i, f) in s1.faces().iter().enumerate() {
        if !near(f) {
            continue;
        }
        let mut c = f.map(|v| disk[v as usize]);
        if flips.binary_search(&i).is_ok() {
            c.swap(1, 2);
        }
        faces.push(*f);
        corners.push(c);
    }
    let crop = submesh(key, faces, &mut corners)?;
    Ok(render(
        &crop,
        &MapCoords::Planar(UvValues::PerCorner(&corners)),
        view,
    )?)
}

/// The mesh of `faces` (indices into `points`) with only the vertices they use; a face at
/// a vertex where the selection touches itself (non-manifold) is dropped with its corners.
fn submesh(
    points: &[[f64; 3]],
    mut faces: Vec<[u32; 3]>,
    corners: &mut Vec<[Complex64; 3]>,
) -> Result<TriMesh> {
    loop {
        let mut index = vec![u32::MAX; points.len()];
        let mut kept = Vec::new();
        let local: Vec<[u32; 3]> = faces
            .iter()
            .map(|f| {
                f.map(|v| {
                    if index[v as usize] == u32::MAX {
                        index[v as usize] = kept.len() as u32;
                        kept.push(points[v as usize]);
                    }
                    index[v as usize]
                })
            })
            .collect();
        match TriMesh::try_new(kept, local.clone()) {
            Err(conformap_mesh::MeshError::NonManifoldVertex { vertex, .. }) => {
                let keep: Vec<bool> = local
                    .iter()
                    .map(|f| !f.contains(&(vertex as u32)))
                    .collect();
                let mut it = keep.iter();
                faces.retain(|_| *it.next().unwrap_or(&true));
                let mut it = keep.iter();
                corners.retain(|_| *it.next().unwrap_or(&true));
            }
            other => return Ok(other?),
        }
    }
}
