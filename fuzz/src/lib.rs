//! What the fuzz targets run, as functions: each target in `fuzz_targets/` calls one of
//! them on the fuzzer's bytes. They return normally on any input, valid or not; they panic
//! only when conformap breaks a promise (a panic inside conformap, or an `Ok` result that
//! is inconsistent or not finite), which libFuzzer then reports as a crash.

use conformap_disk::{run_disk_method, DiskMethod, DiskOptions, DiskProblem};
use conformap_io::{read_mesh_from_bytes, read_raw_mesh_from_bytes, Format, IoError};
use conformap_mesh::{repair, MeshError, RepairOptions, TriMesh, DROPPED};
use conformap_metrics::{planar_map_metrics, MetricsOptions};
use num_complex::Complex64;

/// Meshes larger than this are read but not repaired or mapped (keeps runs fast).
const MAX_FACES: usize = 4000;

/// Reads `data` as `format` both validated and raw, checks that the two agree, then
/// repairs the raw read and validates the result.
pub fn read(data: &[u8], format: Format) {
    let validated = read_mesh_from_bytes(data, format);
    let raw = match read_raw_mesh_from_bytes(data, format) {
        Ok(raw) => raw,
        Err(e) => {
            // every error of the raw read is one of the validated read
            assert!(
                validated.is_err(),
                "raw read failed, validated did not: {e}"
            );
            return;
        }
    };
    let n = raw.positions.len();
    assert!(raw.faces.iter().flatten().all(|&i| (i as usize) < n));
    if let Some(uv) = &raw.uv {
        assert_eq!(uv.len(), n);
    }
    if let Some(lines) = &raw.source.face_lines {
        assert_eq!(lines.len(), raw.faces.len());
    }
    match &validated {
        Ok(loaded) => {
            assert_eq!(loaded.mesh.positions(), raw.positions.as_slice());
            assert_eq!(loaded.mesh.faces(), raw.faces.as_slice());
            if let Some(uv) = &loaded.uv {
                assert_eq!(uv.len(), loaded.mesh.num_vertices());
            }
        }
        Err(IoError::InvalidMesh { source, .. }) => {
            // the raw mesh fails validation with the same error (as text: NaN != NaN)
            let again = TriMesh::try_new(raw.positions.clone(), raw.faces.clone());
            let again = again.err().map(|e| e.to_string());
            assert_eq!(again, Some(source.to_string()));
        }
        Err(_) => {}
    }
    if raw.faces.len() <= MAX_FACES {
        check_repair(&raw.positions, &raw.faces, |e| {
            let _ = raw.invalid_mesh(e).to_string();
        });
    }
}

/// Repairs, checks the log's promises, validates; `on_error` gets a remaining validation
/// error in input numbering.
fn check_repair(positions: &[[f64; 3]], faces: &[[u32; 3]], on_error: impl Fn(MeshError)) {
    let Ok(fixed) = repair(positions, faces, &RepairOptions::DEFAULT) else {
        return;
    };
    let log = &fixed.log;
    assert_eq!(log.vertex_to_input.len(), fixed.positions.len());
    assert_eq!(log.face_to_input.len(), fixed.faces.len());
    assert_eq!(log.input_to_vertex.len(), positions.len());
    for (k, &v) in log.vertex_to_input.iter().enumerate() {
        assert_eq!(log.input_to_vertex[v as usize], k as u32);
    }
    let kept = log
        .input_to_vertex
        .iter()
        .filter(|&&k| k != DROPPED)
        .count();
    assert_eq!(kept, fixed.positions.len());
    let dropped_faces = log.duplicate_faces + log.component_faces_dropped;
    assert_eq!(fixed.faces.len() + dropped_faces, faces.len());
    match TriMesh::try_new(fixed.positions.clone(), fixed.faces.clone()) {
        Ok(mesh) => assert_eq!(mesh.num_components(), 1),
        Err(e) => {
            // what the repairs fix cannot remain
            assert!(
                !matches!(
                    e,
                    MeshError::DuplicateFace { .. }
                        | MeshError::UnreferencedVertex { .. }
                        | MeshError::InconsistentOrientation { .. }
                ),
                "repair left {e:?}"
            );
            on_error(log.to_input_error(e));
        }
    }
}

/// Reads a little-endian byte stream, giving zeros once it runs out.
struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        match self.0.split_first() {
            Some((&b, rest)) => {
                self.0 = rest;
                b
            }
            None => 0,
        }
    }

    /// A value in `[-1, 1]`.
    fn unit(&mut self) -> f64 {
        f64::from(self.byte() as i8) / 127.0
    }
}

/// A perturbed grid disk from bytes: `n × n` squares, vertices jittered in the plane and
/// lifted, some faces flipped or left out (so any topology can come out).
fn grid_from_bytes(mode: u8, b: &mut Bytes<'_>) -> (Vec<[f64; 3]>, Vec<[u32; 3]>) {
    let n = 1 + u32::from(b.byte() % 12);
    let h = 1.0 / f64::from(n);
    // mode bits 4-5: jitter within the cell, up to a cell, wild, or none
    let amp = h * [0.3, 1.0, 4.0, 0.0][usize::from((mode >> 4) & 3)];
    let mut p = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let (x, y) = (f64::from(i) * h, f64::from(j) * h);
            p.push([x + amp * b.unit(), y + amp * b.unit(), 0.3 * b.unit()]);
        }
    }
    let id = |i: u32, j: u32| j * (n + 1) + i;
    let mut f = Vec::new();
    for j in 0..n {
        for i in 0..n {
            let (a, bb, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            let tris = if (i + j) % 2 == 0 {
                [[a, bb, c], [a, c, d]]
            } else {
                [[a, bb, d], [bb, c, d]]
            };
            for mut t in tris {
                // mode bit 6: let the bytes drop and flip faces
                let cmd = if mode & 64 != 0 { b.byte() } else { 0 };
                if cmd % 16 == 1 {
                    continue;
                }
                if cmd % 16 == 2 {
                    t.swap(1, 2);
                }
                f.push(t);
            }
        }
    }
    (p, f)
}

/// The disk pipeline on a small mesh from `data`: the first byte chooses how to build the
/// mesh (even: an OBJ in the rest; odd: a perturbed grid), whether to repair it first
/// (bit 1) and the method (bits 2-3: CEM, harmonic, CCEM-QN, CCEM; iterations capped);
/// then validation, `DiskProblem`, the map and its metrics. An `Ok` map and `Ok` metrics
/// must be finite.
pub fn disk(data: &[u8]) {
    let Some((&mode, rest)) = data.split_first() else {
        return;
    };
    let (positions, faces) = if mode % 2 == 0 {
        match read_raw_mesh_from_bytes(rest, Format::Obj) {
            Ok(raw) if raw.faces.len() <= MAX_FACES => (raw.positions, raw.faces),
            _ => return,
        }
    } else {
        grid_from_bytes(mode, &mut Bytes(rest))
    };
    let mesh = if mode & 2 != 0 {
        check_repair(&positions, &faces, |_| {});
        match repair(&positions, &faces, &RepairOptions::DEFAULT) {
            Ok(r) => TriMesh::try_new(r.positions, r.faces),
            Err(_) => return,
        }
    } else {
        TriMesh::try_new(positions, faces)
    };
    let Ok(mesh) = mesh else { return };
    let Ok(mut problem) = DiskProblem::new(&mesh) else {
        return;
    };
    let (method, cap) = match (mode >> 2) & 3 {
        0 => (DiskMethod::Cem, 5),
        1 => (DiskMethod::Harmonic, 1),
        2 => (DiskMethod::CcemQn, 30),
        _ => (DiskMethod::Ccem, 30),
    };
    let options = DiskOptions::DEFAULT.with_max_iter(Some(cap));
    let Ok(out) = run_disk_method(&mut problem, method, &options) else {
        return;
    };
    assert_eq!(out.map.len(), mesh.num_vertices());
    if let Some(v) = out.map.iter().position(|z| !z.is_finite()) {
        panic!("an Ok disk map is not finite at vertex {v}: {}", out.map[v]);
    }
    check_metrics(&mesh, &out.map);
}

fn check_metrics(mesh: &TriMesh, map: &[Complex64]) {
    let Ok(m) = planar_map_metrics(mesh, map, &MetricsOptions::default()) else {
        return;
    };
    let values = [
        ("conformal_energy", m.conformal_energy),
        ("dirichlet_energy", m.dirichlet_energy),
        ("image_area", m.image_area),
        ("angle mean", m.angle_distortion_deg.mean),
        ("angle max", m.angle_distortion_deg.max),
        ("circle residual", m.circle_residual_max),
    ];
    for (name, v) in values {
        assert!(v.is_finite(), "metric {name} is {v} for a finite map");
    }
}

/// The map file (`PARAM`) reader of `metrics` and `mobius`, against a fixed 7-vertex
/// hexagonal disk: on success the map has the mesh's vertex count (and one texture
/// coordinate per vertex if any); on failure the error is bad input with a hint.
pub fn param(data: &[u8]) {
    use conformap::jobs::param::read_map_file;
    use std::sync::OnceLock;
    static MESH: OnceLock<TriMesh> = OnceLock::new();
    let mesh = MESH.get_or_init(|| {
        let mut positions = vec![[0.0, 0.0, 0.0]];
        positions.extend((0..6).map(|k| {
            let a = f64::from(k) * std::f64::consts::FRAC_PI_3;
            [a.cos(), a.sin(), 0.0]
        }));
        let faces = (0..6u32).map(|k| [0, 1 + k, 1 + (k + 1) % 6]).collect();
        TriMesh::try_new(positions, faces).expect("the hexagon is a valid mesh")
    });
    let path = std::env::temp_dir().join(format!("conformap-fuzz-param-{}.obj", std::process::id()));
    if std::fs::write(&path, data).is_err() {
        return;
    }
    let result = read_map_file(&path, std::path::Path::new("hexagon.obj"), mesh);
    match result {
        Ok(map) => {
            assert_eq!(map.positions.len(), mesh.num_vertices());
            if let Some(uv) = &map.uv {
                assert_eq!(uv.len(), mesh.num_vertices());
            }
            use conformap::jobs::param::PlanarMap;
            match map.planar_map().0 {
                PlanarMap::PerVertex(p) => assert_eq!(p.len(), mesh.num_vertices()),
                PlanarMap::PerCorner(c) => assert_eq!(c.len(), 3 * mesh.num_faces()),
            }
            // a seamed map is refused where one value per vertex is needed, with a hint
            if let Err(failure) = map.planar() {
                assert!(failure.hint().is_some_and(|h| !h.is_empty()), "no hint: {failure}");
            }
        }
        Err(failure) => {
            assert_eq!(failure.exit_code(), 1, "{failure}");
            assert!(failure.hint().is_some_and(|h| !h.is_empty()), "no hint: {failure}");
            assert!(!failure.to_string().contains("panicked"));
        }
    }
}
