//! OFF (Object File Format) text: `OFF` (or `COFF`, `NOFF`, `CNOFF`, `STOFF`, `STCNOFF`...),
//! the counts `V F E`, `V` vertex lines (`x y z`, then normals, colours or texture
//! coordinates, ignored), `F` face lines (`n i1 … in`, then an optional colour, ignored).
//! Polygons are fan-triangulated as for OBJ; `#` starts a comment anywhere. Vertex `k` is
//! the file's `k`-th vertex line. 4D (`4OFF`), `nOFF` and binary OFF are refused.

use std::path::Path;

use crate::cursor::{malformed, numbered_lines, parse_f64, quote, CORRUPT_HINT, TRUNCATED_HINT};
use crate::error::{IoError, Place, UvProblem};
use crate::loaded::{Format, SourceInfo};
use crate::off_keyword::keyword_prefixes;
use crate::raw::{ElementOrigins, RawMesh};

/// The non-comment words of each line, with its number; empty lines left out.
fn content_lines(bytes: &[u8]) -> impl Iterator<Item = (usize, Vec<&[u8]>)> {
    numbered_lines(bytes, 1).filter_map(|(line, text)| {
        let body = text.split(|&b| b == b'#').next().unwrap_or_default();
        let w: Vec<&[u8]> = crate::cursor::words(body).collect();
        (!w.is_empty()).then_some((line, w))
    })
}

/// Reads an OFF file's bytes without validating the mesh.
pub(crate) fn read_off_raw(bytes: &[u8], path: &Path) -> Result<RawMesh, IoError> {
    let bad = |line: usize, problem: String, hint| {
        malformed(path, Format::Off, Place::Line(line), problem, hint)
    };
    let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let mut lines = content_lines(text);
    let (line, mut head) = lines
        .next()
        .ok_or_else(|| bad(1, "the file is empty".into(), TRUNCATED_HINT))?;
    let prefix = keyword_prefixes(head[0]).ok_or_else(|| {
        bad(
            line,
            format!("`{}` is not an OFF header", quote(head[0])),
            CORRUPT_HINT,
        )
    })?;
    if prefix.contains(&b'4') || prefix.contains(&b'n') || head.get(1) == Some(&&b"BINARY"[..]) {
        let problem = format!(
            "`{}` files (4D, n-D or binary OFF) are not read",
            quote(head[0])
        );
        return Err(bad(
            line,
            problem,
            "convert the file to 3D ASCII OFF, PLY or OBJ",
        ));
    }
    // the counts follow on the same line or on the next
    head.remove(0);
    let (line, counts) = if head.is_empty() {
        lines.next().ok_or_else(|| {
            bad(
                line,
                "the file ends before the counts".into(),
                TRUNCATED_HINT,
            )
        })?
    } else {
        (line, head)
    };
    let count = |k: usize| {
        counts
            .get(k)
            .and_then(|w| std::str::from_utf8(w).ok()?.parse::<usize>().ok())
    };
    let (Some(nv), Some(nf)) = (count(0), count(1)) else {
        return Err(bad(
            line,
            "expected the counts `vertices faces edges`".into(),
            CORRUPT_HINT,
        ));
    };
    // memory estimate before allocating: a vertex line takes at least 6 bytes, a face 8
    let room = bytes.len() as u64 / 6;
    if nv as u64 > room || nf as u64 > bytes.len() as u64 / 8 {
        let problem = format!(
            "the counts declare {nv} vertices and {nf} faces, more than the file's {} bytes \
             can hold",
            bytes.len()
        );
        return Err(bad(line, problem, TRUNCATED_HINT));
    }
    let mut positions = Vec::with_capacity(nv);
    let mut faces = Vec::with_capacity(nf);
    let mut face_of = Vec::with_capacity(nf);
    let mut last = line;
    for k in 0..nv + nf {
        let Some((line, w)) = lines.next() else {
            let what = if k < nv { "vertex" } else { "face" };
            let index = if k < nv { k } else { k - nv };
            let problem =
                format!("the file ends before {what} {index} (of {nv} vertices, {nf} faces)");
            return Err(bad(last, problem, TRUNCATED_HINT));
        };
        last = line;
        if k < nv {
            positions
                .push(vertex(&w).map_err(|p| bad(line, format!("vertex {k}: {p}"), CORRUPT_HINT))?);
        } else {
            let f = k - nv;
            let corners =
                face(&w, nv).map_err(|p| bad(line, format!("face {f}: {p}"), CORRUPT_HINT))?;
            for i in 1..corners.len() - 1 {
                faces.push([corners[0], corners[i], corners[i + 1]]);
                face_of.push(f);
            }
        }
    }
    if positions.is_empty() {
        return Err(IoError::InvalidMesh {
            path: path.to_path_buf(),
            origin: None,
            source: conformap_mesh::MeshError::NoVertices,
        });
    }
    let mut source = SourceInfo::new(path.to_path_buf(), Format::Off);
    source.file_vertex_count = nv;
    let elements = ElementOrigins {
        vertex: "vertex",
        face: "face",
        vertex_of: Vec::new(),
        face_of,
    };
    let raw = RawMesh::new(positions, faces, Err(UvProblem::Absent), source, None);
    Ok(raw.with_elements(elements))
}

/// `x y z` from the start of a vertex line.
fn vertex(w: &[&[u8]]) -> Result<[f64; 3], String> {
    if w.len() < 3 {
        return Err(format!("{} value(s); a vertex needs x y z", w.len()));
    }
    let mut p = [0.0; 3];
    for (slot, word) in p.iter_mut().zip(w) {
        *slot = parse_f64(word).ok_or_else(|| format!("`{}` is not a number", quote(word)))?;
    }
    Ok(p)
}

/// The corners of a face line `n i1 … in [colour]`.
fn face(w: &[&[u8]], nv: usize) -> Result<Vec<u32>, String> {
    let int = |word: &[u8]| std::str::from_utf8(word).ok()?.parse::<u64>().ok();
    let n = int(w[0]).ok_or_else(|| format!("`{}` is not a corner count", quote(w[0])))?;
    if n < 3 {
        return Err(format!("{n} corner(s); a face needs at least 3"));
    }
    if (w.len() as u64) < n + 1 {
        return Err(format!("{} index(es) for {n} corners", w.len() - 1));
    }
    w[1..=n as usize]
        .iter()
        .map(|word| match int(word) {
            Some(i) if i < nv as u64 => Ok(i as u32),
            Some(i) => Err(format!(
                "vertex index {i} is out of range ({nv} vertices; OFF counts from 0)"
            )),
            None => Err(format!("`{}` is not a vertex index", quote(word))),
        })
        .collect()
}
