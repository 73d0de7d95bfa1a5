//! OBJ files of one set of triangles at many vertex positions (the frames of a morph):
//! the face lines are formatted once and every frame is one buffered write.

use std::path::Path;

use crate::api::check_finite;
use crate::atomic::write_atomically;
use crate::objfile::{face_lines, obj_header, vertex_lines};
use crate::{IoError, WriteProblem};

/// The frames of a morph as OBJ files: `faces` formatted once, each frame's file its
/// header and `v` lines followed by that text, written with one `write` (through a
/// temporary sibling, renamed into place, like every writer of this crate). The bytes are
/// exactly those of [`crate::write_flat`] with the same points and faces.
///
/// # Examples
/// ```
/// use conformap_io::{read_mesh, ObjFrames};
/// let dir = std::env::temp_dir().join(format!("conformap-io-frames-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// let frames = ObjFrames::new(&[[0, 1, 2]]);
/// for (i, z) in [0.0, 0.5].into_iter().enumerate() {
///     let path = dir.join(format!("frame_{i}.obj"));
///     frames.write(&path, &[[0.0, 0.0, z], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])?;
///     assert_eq!(read_mesh(&path)?.mesh.positions()[0], [0.0, 0.0, z]);
/// }
/// # std::fs::remove_dir_all(&dir)?;
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct ObjFrames {
    /// The `f` lines.
    face_text: Vec<u8>,
    face_count: usize,
    /// The face holding the largest vertex index, and that index.
    largest: Option<(usize, u32)>,
}

impl ObjFrames {
    /// Formats the `f` lines of `faces` (0-based indices, written 1-based).
    pub fn new(faces: &[[u32; 3]]) -> Self {
        let largest = faces
            .iter()
            .enumerate()
            .map(|(k, f)| (k, f[0].max(f[1]).max(f[2])))
            .fold(None, |best: Option<(usize, u32)>, (k, i)| match best {
                Some((_, j)) if j >= i => best,
                _ => Some((k, i)),
            });
        Self {
            face_text: face_lines(faces).concat(),
            face_count: faces.len(),
            largest,
        }
    }

    /// The bytes of the frame with vertex positions `points`.
    ///
    /// # Errors
    /// [`WriteProblem::FaceIndex`] if a face refers to a vertex beyond `points`;
    /// [`WriteProblem::NonFinite`] for a NaN or infinite coordinate.
    pub fn encode(&self, points: &[[f64; 3]]) -> Result<Vec<u8>, WriteProblem> {
        if let Some((face, index)) = self.largest.filter(|&(_, i)| i as usize >= points.len()) {
            return Err(WriteProblem::FaceIndex {
                face,
                index,
                vertex_count: points.len(),
            });
        }
        check_finite(points.iter().map(|p| p.as_slice()))?;
        let header = obj_header(points.len(), self.face_count);
        let vertices = vertex_lines(points).parts();
        let size =
            header.len() + vertices.iter().map(Vec::len).sum::<usize>() + self.face_text.len();
        let mut out = Vec::with_capacity(size);
        out.extend_from_slice(header.as_bytes());
        for part in &vertices {
            out.extend_from_slice(part);
        }
        out.extend_from_slice(&self.face_text);
        Ok(out)
    }

    /// Writes the frame with vertex positions `points` to `path` as OBJ text, whatever
    /// the file's name says (name it `.obj`).
    ///
    /// # Errors
    /// [`IoError::BadWriteInput`] for the problems of [`Self::encode`];
    /// [`IoError::Write`] if the file cannot be written.
    pub fn write(&self, path: impl AsRef<Path>, points: &[[f64; 3]]) -> Result<(), IoError> {
        let path = path.as_ref();
        let bytes = self
            .encode(points)
            .map_err(|problem| IoError::BadWriteInput {
                path: path.to_path_buf(),
                problem,
            })?;
        write_atomically(path, &bytes)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;
    use crate::objfile::encode_obj;

    #[test]
    fn bytes_equal_those_of_write_flat_and_bad_input_is_refused() {
        let points = [[0.1, -0.0, 1e-300], [1e300, 3.0, 2.5e-7], [1.0, 2.0, 3.0]];
        let faces = [[0, 1, 2], [2, 1, 0]];
        let frames = ObjFrames::new(&faces);
        assert_eq!(
            frames.encode(&points).unwrap(),
            encode_obj(&points, &faces).concat()
        );
        assert!(matches!(
            frames.encode(&points[..2]),
            Err(WriteProblem::FaceIndex {
                face: 0,
                index: 2,
                vertex_count: 2
            })
        ));
        let mut nan = points;
        nan[1][2] = f64::NAN;
        assert!(matches!(
            frames.encode(&nan),
            Err(WriteProblem::NonFinite { vertex: 1, .. })
        ));
    }
}
