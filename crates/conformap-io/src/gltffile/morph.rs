//! GLB with morph targets and an animation of their weights: a morph (a base mesh and
//! per-target displacements) that any glTF 2.0 viewer plays.
//!
//! One mesh, one triangle primitive (`POSITION`, `u32` indices) with one morph target
//! (`POSITION` displacements) per key, a node, and one animation whose channel drives the
//! node's `weights` with a `LINEAR` sampler (one keyframe per frame). Target names go to
//! `mesh.extras.targetNames` (the convention three.js and Blender read). Values are
//! stored as f32 (relative error ≤ 2⁻²⁴).

use std::io;
use std::path::Path;

use serde_json::json;

use crate::atomic::write_atomically;
use crate::error::{IoError, WriteProblem};

use super::container::encode_glb;
use super::write::{f32_of, push_vec3, ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER, FLOAT, UNSIGNED_INT};

/// A morph to write: base mesh, displacement targets, and the weights over time.
#[derive(Debug, Clone, Copy)]
pub struct MorphGlb<'a> {
    /// Base positions (the first frame).
    pub positions: &'a [[f64; 3]],
    /// Triangles, 0-based into `positions`.
    pub faces: &'a [[u32; 3]],
    /// One displacement per position for every target.
    pub targets: &'a [Vec<[f64; 3]>],
    /// One name per target.
    pub target_names: &'a [String],
    /// Keyframe times in seconds, strictly increasing.
    pub times: &'a [f64],
    /// For every keyframe, one weight per target.
    pub weights: &'a [Vec<f64>],
}

/// Writes `morph` as a `.glb` at `path` (complete or not at all).
///
/// # Errors
/// [`IoError::BadWriteInput`] for no vertex or face, a face index out of range or a
/// non-finite value; [`IoError::Write`] (kind `InvalidInput`) for inconsistent shapes
/// (a target or a weight row of the wrong length, a name missing, times not increasing),
/// or when the file cannot be written.
///
/// # Examples
/// ```
/// use conformap_io::{write_morph_glb, MorphGlb};
/// let dir = std::env::temp_dir().join(format!("conformap-io-morph-doc-{}", std::process::id()));
/// std::fs::create_dir_all(&dir).unwrap();
/// let path = dir.join("m.glb");
/// let up = vec![[0.0, 0.0, 1.0]; 3];
/// write_morph_glb(&path, &MorphGlb {
///     positions: &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
///     faces: &[[0, 1, 2]],
///     targets: &[up],
///     target_names: &["lifted".to_string()],
///     times: &[0.0, 1.0],
///     weights: &[vec![0.0], vec![1.0]],
/// })?;
/// assert!(std::fs::metadata(&path).unwrap().len() > 0);
/// # std::fs::remove_dir_all(&dir).unwrap();
/// # Ok::<(), conformap_io::IoError>(())
/// ```
pub fn write_morph_glb(path: impl AsRef<Path>, morph: &MorphGlb<'_>) -> Result<(), IoError> {
    let path = path.as_ref();
    let shape = |message: String| IoError::Write {
        path: path.to_path_buf(),
        source: io::Error::new(io::ErrorKind::InvalidInput, message),
    };
    check_shapes(morph).map_err(shape)?;
    let bytes = encode_morph_glb(morph).map_err(|problem| IoError::BadWriteInput {
        path: path.to_path_buf(),
        problem,
    })?;
    write_atomically(path, &bytes)
}

fn check_shapes(m: &MorphGlb<'_>) -> Result<(), String> {
    let n = m.positions.len();
    if let Some((k, t)) = m.targets.iter().enumerate().find(|(_, t)| t.len() != n) {
        return Err(format!(
            "morph target {k} has {} values for {n} vertices",
            t.len()
        ));
    }
    if m.target_names.len() != m.targets.len() {
        return Err(format!(
            "{} target names for {} targets",
            m.target_names.len(),
            m.targets.len()
        ));
    }
    if m.weights.len() != m.times.len() {
        return Err(format!(
            "{} weight rows for {} times",
            m.weights.len(),
            m.times.len()
        ));
    }
    if let Some((k, w)) = m
        .weights
        .iter()
        .enumerate()
        .find(|(_, w)| w.len() != m.targets.len())
    {
        return Err(format!(
            "weight row {k} has {} values for {} targets",
            w.len(),
            m.targets.len()
        ));
    }
    if m.times.is_empty() || m.times.windows(2).any(|w| !(w[1] > w[0])) || !m.times[0].is_finite() {
        return Err("animation times must be finite and strictly increasing (at least one)".into());
    }
    Ok(())
}

/// The GLB bytes of `morph` (shapes assumed consistent: see [`write_morph_glb`]).
///
/// # Errors
/// [`WriteProblem::Empty`], [`WriteProblem::FaceIndex`], [`WriteProblem::NonFinite`],
/// [`WriteProblem::TooLarge`].
pub fn encode_morph_glb(m: &MorphGlb<'_>) -> Result<Vec<u8>, WriteProblem> {
    let n = m.positions.len();
    if n == 0 || m.faces.is_empty() {
        return Err(WriteProblem::Empty);
    }
    for (face, f) in m.faces.iter().enumerate() {
        if let Some(&index) = f.iter().find(|&&i| i as usize >= n) {
            return Err(WriteProblem::FaceIndex {
                face,
                index,
                vertex_count: n,
            });
        }
    }
    let mut bin = Vec::with_capacity(12 * n * (1 + m.targets.len()) + 12 * m.faces.len());
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut view = |bin: &Vec<u8>, start: usize, target: Option<u32>| {
        let mut v = json!({ "buffer": 0, "byteOffset": start, "byteLength": bin.len() - start });
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        views.push(v);
        views.len() - 1
    };
    let start = bin.len();
    let (lo, hi) = push_vec3(&mut bin, m.positions)?;
    let v = view(&bin, start, Some(ARRAY_BUFFER));
    accessors.push(json!({ "bufferView": v, "componentType": FLOAT, "count": n, "type": "VEC3", "min": lo, "max": hi }));
    let mut targets = Vec::new();
    for t in m.targets {
        let start = bin.len();
        let (lo, hi) = push_vec3(&mut bin, t)?;
        let v = view(&bin, start, Some(ARRAY_BUFFER));
        accessors.push(json!({ "bufferView": v, "componentType": FLOAT, "count": n, "type": "VEC3", "min": lo, "max": hi }));
        targets.push(json!({ "POSITION": accessors.len() - 1 }));
    }
    let start = bin.len();
    for &i in m.faces.iter().flatten() {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    let v = view(&bin, start, Some(ELEMENT_ARRAY_BUFFER));
    accessors.push(json!({ "bufferView": v, "componentType": UNSIGNED_INT, "count": 3 * m.faces.len(), "type": "SCALAR" }));
    let indices = accessors.len() - 1;
    let start = bin.len();
    for (k, &t) in m.times.iter().enumerate() {
        bin.extend_from_slice(&f32_of(t, k)?.to_le_bytes());
    }
    let v = view(&bin, start, None);
    let (t0, t1) = (m.times[0] as f32, m.times[m.times.len() - 1] as f32);
    accessors.push(json!({ "bufferView": v, "componentType": FLOAT, "count": m.times.len(), "type": "SCALAR", "min": [t0], "max": [t1] }));
    let input = accessors.len() - 1;
    let start = bin.len();
    for (k, row) in m.weights.iter().enumerate() {
        for &w in row {
            bin.extend_from_slice(&f32_of(w, k)?.to_le_bytes());
        }
    }
    let v = view(&bin, start, None);
    accessors.push(json!({ "bufferView": v, "componentType": FLOAT, "count": m.times.len() * m.targets.len(), "type": "SCALAR" }));
    let output = accessors.len() - 1;
    if u32::try_from(bin.len() + (1 << 20)).is_err() {
        return Err(WriteProblem::TooLarge);
    }
    let first: Vec<f32> = m.weights[0].iter().map(|&w| w as f32).collect();
    let doc = json!({
        "asset": { "version": "2.0", "generator": "conformap-io (morph)" },
        "scene": 0,
        "scenes": [{ "nodes": [0] }],
        "nodes": [{ "mesh": 0, "name": "morph" }],
        "meshes": [{
            "primitives": [{ "attributes": { "POSITION": 0 }, "indices": indices, "mode": 4, "targets": targets }],
            "weights": first,
            "extras": { "targetNames": m.target_names },
        }],
        "animations": [{
            "name": "morph",
            "channels": [{ "sampler": 0, "target": { "node": 0, "path": "weights" } }],
            "samplers": [{ "input": input, "output": output, "interpolation": "LINEAR" }],
        }],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{ "byteLength": bin.len() }],
    });
    encode_glb(doc.to_string().into_bytes(), bin)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;
    use gltf::animation::util::ReadOutputs;

    #[test]
    fn a_standard_reader_loads_targets_and_animation() {
        // a 2 × 2 quad, two targets (lift, shear), three keyframes
        let positions = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let faces = [[0, 1, 2], [0, 2, 3]];
        let lift = vec![[0.0, 0.0, 0.5]; 4];
        let shear: Vec<[f64; 3]> = positions.iter().map(|p| [0.25 * p[1], 0.0, 0.0]).collect();
        let targets = [lift.clone(), shear.clone()];
        let names = ["lift".to_string(), "shear".to_string()];
        let times = [0.0, 0.5, 1.0];
        let weights = [vec![0.0, 0.0], vec![0.7, 0.3], vec![0.0, 1.0]];
        let m = MorphGlb {
            positions: &positions,
            faces: &faces,
            targets: &targets,
            target_names: &names,
            times: &times,
            weights: &weights,
        };
        let bytes = encode_morph_glb(&m).unwrap();
        let (doc, buffers, _) = gltf::import_slice(&bytes).unwrap();
        let mesh = doc.meshes().next().unwrap();
        let prim = mesh.primitives().next().unwrap();
        let reader = prim.reader(|b| Some(&buffers[b.index()]));
        let base: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
        assert_eq!(base.len(), 4);
        let read: Vec<Vec<[f32; 3]>> = reader
            .read_morph_targets()
            .map(|(p, _, _)| p.unwrap().collect())
            .collect();
        assert_eq!(read.len(), 2);
        for (got, want) in read.iter().zip(&targets) {
            for (g, w) in got.iter().zip(want) {
                for k in 0..3 {
                    assert_eq!(f64::from(g[k]), w[k]);
                }
            }
        }
        assert_eq!(mesh.weights(), Some(&[0.0f32, 0.0][..]));
        let anim = doc.animations().next().unwrap();
        let channel = anim.channels().next().unwrap();
        assert_eq!(channel.target().node().index(), 0);
        assert_eq!(
            channel.target().property(),
            gltf::animation::Property::MorphTargetWeights
        );
        assert_eq!(
            channel.sampler().interpolation(),
            gltf::animation::Interpolation::Linear
        );
        let r = channel.reader(|b| Some(&buffers[b.index()]));
        let inputs: Vec<f32> = r.read_inputs().unwrap().collect();
        assert_eq!(inputs, vec![0.0, 0.5, 1.0]);
        let Some(ReadOutputs::MorphTargetWeights(w)) = r.read_outputs() else {
            panic!("no weights output");
        };
        let w: Vec<f32> = w.into_f32().collect();
        assert_eq!(w, vec![0.0, 0.0, 0.7, 0.3, 0.0, 1.0]);
    }

    #[test]
    fn bad_shapes_and_values_are_refused() {
        let positions = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let short = vec![vec![[0.0; 3]; 2]];
        let names = ["a".to_string()];
        let m = MorphGlb {
            positions: &positions,
            faces: &[[0, 1, 2]],
            targets: &short,
            target_names: &names,
            times: &[0.0],
            weights: &[vec![1.0]],
        };
        assert!(check_shapes(&m)
            .unwrap_err()
            .contains("morph target 0 has 2 values"));
        let bad = vec![vec![[0.0, f64::NAN, 0.0]; 3]];
        let m = MorphGlb { targets: &bad, ..m };
        assert!(check_shapes(&m).is_ok());
        assert!(matches!(
            encode_morph_glb(&m),
            Err(WriteProblem::NonFinite { vertex: 0, .. })
        ));
        let m = MorphGlb {
            faces: &[[0, 1, 3]],
            ..m
        };
        assert!(matches!(
            encode_morph_glb(&m),
            Err(WriteProblem::FaceIndex {
                face: 0,
                index: 3,
                ..
            })
        ));
    }
}
