//! OBJ reading: the text split into chunks at line ends, each chunk counted, then parsed in
//! parallel (see [`super::parse`]) straight into its own slices of the file's arrays, sized
//! exactly by the counts (nothing grows, nothing is concatenated).

use std::path::Path;

use conformap_mesh::MeshError;
use rayon::prelude::*;

use super::lines::split_chunks;
use super::parse::{count, parse_into, ChunkOutcome, Counts, Parsed, Sink, NO_UV};
use crate::corner_uv::CornerUv;
use crate::error::{IoError, ObjProblem, Origin, UvProblem};
use crate::loaded::{Format, SourceInfo};
use crate::raw::RawMesh;

/// Texts shorter than this are parsed in one piece on the calling thread: below it, waking
/// the thread pool costs more than it saves (a 1 MiB OBJ parses in about 3 ms).
const PARALLEL_MIN_BYTES: usize = 1 << 20;
/// Chunks per thread: more than one, so that a thread that finishes early (a chunk of
/// comments, the other tenant of the core) takes another.
const CHUNKS_PER_THREAD: usize = 8;

/// Reads an OBJ file's bytes without validating the mesh. `path` only names the file in
/// errors. Also returns the span of each vertex's numbers in `bytes` (see [`VertexText`]).
pub(crate) fn read_obj_raw(
    bytes: &[u8],
    path: &Path,
) -> Result<(RawMesh, Vec<(usize, usize)>), IoError> {
    let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let bom = bytes.len() - text.len();
    let n = if text.len() < PARALLEL_MIN_BYTES {
        1
    } else {
        CHUNKS_PER_THREAD * rayon::current_num_threads()
    };
    let chunks = split_chunks(text, n);
    // each chunk's byte offset in `bytes` (the chunks tile the text in order)
    let offsets: Vec<usize> = chunks
        .iter()
        .scan(bom, |at, c| {
            let start = *at;
            *at += c.len();
            Some(start)
        })
        .collect();
    // first with every `f` line guessed a triangle; exactly if a chunk met a polygon
    let (mut whole, mut outcomes) = parse_chunks(&chunks, &offsets, false);
    if !outcomes.iter().all(|o| o.counted_right) {
        (whole, outcomes) = parse_chunks(&chunks, &offsets, true);
    }
    // each chunk stops at its first bad line, so the first chunk with one has the file's
    whole.error = outcomes.iter().find_map(|o| o.chunk.error.clone());
    if let Some((line, problem)) = whole.error.take() {
        return Err(IoError::ObjSyntax {
            path: path.to_path_buf(),
            line,
            problem,
        });
    }
    whole.noted = outcomes.iter().map(|o| o.chunk.noted).sum();
    if whole.positions.is_empty() {
        return Err(IoError::InvalidMesh {
            path: path.to_path_buf(),
            origin: None,
            source: MeshError::NoVertices,
        });
    }
    let uv = per_vertex_uv(&whole);
    let corner_uv = corner_uv(&whole);
    let mut source = SourceInfo::new(path.to_path_buf(), Format::Obj);
    source.file_vertex_count = whole.positions.len();
    if whole.noted > 0 {
        source.notes.push(format!(
            "{} point, line or free-form statement(s) ignored (only faces are read)",
            whole.noted
        ));
    }
    source.vertex_lines = Some(whole.vertex_lines);
    source.face_lines = Some(whole.face_lines);
    let raw = RawMesh::new(whole.positions, whole.faces, uv, source, None);
    Ok((raw.with_corner_uv(corner_uv), whole.vertex_spans))
}

/// A chunk's outcome, and whether its count was right (the guess of [`count`] can be
/// short).
struct Outcome {
    chunk: ChunkOutcome,
    counted_right: bool,
}

/// One chunk to parse: its text and byte offset, the counts before it and its own, and
/// its room in the text's arrays.
struct Job<'t, 's> {
    chunk: &'t [u8],
    at: usize,
    before: Counts,
    own: Counts,
    sink: Sink<'s>,
}

/// Counts (`exact`: see [`count`]) and parses the chunks, each straight into its slices of
/// the text's arrays.
fn parse_chunks(chunks: &[&[u8]], offsets: &[usize], exact: bool) -> (Parsed, Vec<Outcome>) {
    let counts: Vec<Counts> = if chunks.len() > 1 {
        chunks.par_iter().map(|c| count(c, exact)).collect()
    } else {
        chunks.iter().map(|c| count(c, exact)).collect()
    };
    let total = counts.iter().fold(Counts::default(), |a, &c| a.add(c));
    let mut before = Vec::with_capacity(counts.len());
    let mut acc = Counts::default();
    for &c in &counts {
        before.push(acc);
        acc = acc.add(c);
    }
    let mut whole = Parsed::with_counts(total);
    let outcomes = {
        let sinks = whole.sinks(&counts);
        let jobs = sinks.into_iter().enumerate().map(|(k, sink)| Job {
            chunk: chunks[k],
            at: offsets[k],
            before: before[k],
            own: counts[k],
            sink,
        });
        let parse = |mut job: Job<'_, '_>| {
            let chunk = parse_into(job.chunk, job.at, job.before, total, &mut job.sink);
            // a short guess overflows its room; a chunk that ends early has an error
            let counted_right = match &chunk.error {
                Some((_, problem)) => *problem != ObjProblem::Miscounted,
                None => chunk.triangles == job.own.tri,
            };
            Outcome {
                chunk,
                counted_right: exact || counted_right,
            }
        };
        if counts.len() > 1 {
            jobs.collect::<Vec<_>>()
                .into_par_iter()
                .map(parse)
                .collect()
        } else {
            jobs.map(parse).collect()
        }
    };
    (whole, outcomes)
}

/// The texture coordinate of every corner, when every corner has one.
fn corner_uv(s: &Parsed) -> Option<CornerUv> {
    let n = s.texcoords.len();
    let complete = s
        .face_uv
        .iter()
        .flatten()
        .all(|&t| t != NO_UV && (t as usize) < n);
    (complete && !s.face_uv.is_empty()).then(|| CornerUv {
        texcoords: s.texcoords.clone(),
        faces: s.face_uv.clone(),
    })
}

/// A texture coordinate per vertex (`None` for a vertex no face uses).
type VertexUv = Vec<Option<[f64; 2]>>;

/// One texture coordinate per vertex, or why there is not: every corner needs a `vt`, and
/// the corners of a vertex one value (the same value under two `vt` indices is fine).
fn per_vertex_uv(s: &Parsed) -> Result<VertexUv, UvProblem> {
    let corners = s.face_uv.iter().flatten();
    // no `vt` in the file leaves `face_uv` empty
    if corners.clone().all(|&t| t == NO_UV) {
        return Err(UvProblem::Absent);
    }
    // per vertex: (vt index, value, line) of its first corner
    let mut first: Vec<Option<(u32, [f64; 2], usize)>> = vec![None; s.positions.len()];
    for (c, &t) in corners.enumerate() {
        let (f, k) = (c / 3, c % 3);
        let line = s.face_lines[f];
        // the parser resolved every vt index against the file's count
        let Some(&uv) = s.texcoords.get(t as usize) else {
            return Err(UvProblem::Missing {
                origin: Origin::Line(line),
            });
        };
        let v = s.faces[f][k] as usize;
        match &mut first[v] {
            slot @ None => *slot = Some((t, uv, line)),
            Some((t0, uv0, line0)) => {
                let same = *t0 == t || uv0.map(f64::to_bits) == uv.map(f64::to_bits);
                if !same {
                    return Err(UvProblem::Seam {
                        vertex: v,
                        origin: Origin::Line(line),
                        first: Origin::Line(*line0),
                    });
                }
            }
        }
    }
    // a vertex no face uses has no texture coordinate
    Ok(first
        .into_iter()
        .map(|slot| slot.map(|(_, uv, _)| uv))
        .collect())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    /// `tobj` (this reader's backend until the parser became our own) numbered each
    /// object's vertices by first use; the file's numbering must survive several objects.
    #[test]
    fn several_objects_keep_file_order() {
        let text = b"o a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 3 1 2\no b\nv 5 5 5\nf 4 1 2\n";
        let raw = read_obj_raw(text, Path::new("t.obj")).unwrap().0;
        assert_eq!(raw.positions[2], [0.0, 1.0, 0.0]);
        assert_eq!(raw.faces, vec![[2, 0, 1], [3, 0, 1]]);
        // the faces share vertices 0, 1 and run edge 0-1 the same way, so validation
        // names face 1 on line 8
        let err = raw.validate().unwrap_err();
        assert!(err.to_string().starts_with("t.obj:8: "), "{err}");
    }

    /// A text large enough to be parsed in parallel chunks gives exactly what one chunk
    /// gives, errors included.
    #[test]
    fn parallel_chunks_agree_with_one() {
        let mut text = String::new();
        let n = 40_000;
        for i in 0..n {
            text.push_str(&format!("v {i} {}.25 -0.{i}\n", i % 7));
            if i % 5 == 0 {
                text.push_str(&format!("vt 0.{i} 1\n# comment {i}\n"));
            }
        }
        for i in 0..n - 2 {
            text.push_str(&format!(
                "f {} -2/1 {}\n",
                i + 1,
                -1 - i64::from(i % 3 != 0)
            ));
        }
        assert!(text.len() > PARALLEL_MIN_BYTES);
        let bytes = text.as_bytes();
        let one = super::super::parse::parse_text(bytes);
        let raw = read_obj_raw(bytes, Path::new("t.obj")).unwrap().0;
        assert_eq!(raw.positions, one.positions);
        assert_eq!(raw.faces, one.faces);
        assert_eq!(raw.source.vertex_lines.unwrap(), one.vertex_lines);
        assert_eq!(raw.source.face_lines.unwrap(), one.face_lines);
        // polygons far into the text: the triangle guess is short there, so the text is
        // counted again exactly, with the same result; and an error after a polygon is
        // still found on its line
        let mut polygons = text.clone();
        for i in 0..n - 3 {
            if i % 5000 == 4999 {
                polygons.push_str(&format!("f {} {} {} {}\n", i + 1, i + 2, i + 3, i + 4));
            }
        }
        let raw = read_obj_raw(polygons.as_bytes(), Path::new("t.obj"))
            .unwrap()
            .0;
        let one = super::super::parse::parse_text(polygons.as_bytes());
        assert_eq!(raw.faces.len(), n - 2 + 2 * ((n - 3) / 5000));
        assert_eq!(raw.faces, one.faces);
        assert_eq!(raw.source.face_lines.unwrap(), one.face_lines);
        let bad = format!("{polygons}f 1 2\n");
        let err = read_obj_raw(bad.as_bytes(), Path::new("t.obj")).unwrap_err();
        assert!(
            matches!(err, IoError::ObjSyntax { line, .. } if line == bad.lines().count()),
            "{err}"
        );
        // an error in the last part of the file is found on its line
        let bad = format!("{text}f 1 2 0\n");
        let lines = bad.lines().count();
        let err = read_obj_raw(bad.as_bytes(), Path::new("t.obj")).unwrap_err();
        assert!(
            matches!(err, IoError::ObjSyntax { line, .. } if line == lines),
            "{err}"
        );
    }
}
