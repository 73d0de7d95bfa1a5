//! STL, ASCII and binary: facets of three positions each, welded into a mesh.
//!
//! STL repeats every position in each facet that uses it. Bit-identical positions are
//! welded (`-0.0` = `0.0`); mesh vertices are numbered in order of first appearance
//! (facet by facet, corner by corner), and [`SourceInfo::weld_map`] gives the mesh vertex
//! of each facet corner `3 f + k`. Facet normals are ignored (the winding gives the
//! orientation), and so are binary attribute bytes.

use std::path::Path;

use crate::coincident::classes;
use crate::cursor::{malformed, numbered_lines, parse_f64, quote, words, Cursor, CORRUPT_HINT};
use crate::error::{IoError, Place, UvProblem};
use crate::loaded::{Format, SourceInfo};
use crate::raw::{ElementOrigins, RawMesh};

/// Bytes of a binary STL header (80) and facet count (4).
const BINARY_HEADER: usize = 84;
/// Bytes of a binary facet: normal, three corners (f32 × 12) and a 2-byte attribute.
const BINARY_FACET: usize = 50;

/// Whether `bytes` are a binary STL: the size its facet count gives, or a file that does
/// not start with `solid` (binary files may start with it; ASCII ones must).
fn is_binary(bytes: &[u8]) -> bool {
    let sized = bytes.get(80..84).is_some_and(|n| {
        let n = u32::from_le_bytes([n[0], n[1], n[2], n[3]]) as u64;
        BINARY_HEADER as u64 + BINARY_FACET as u64 * n == bytes.len() as u64
    });
    let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let ascii = text
        .iter()
        .position(|b| !b.is_ascii_whitespace())
        .is_some_and(|i| text[i..].starts_with(b"solid"));
    sized || !ascii
}

/// Reads an STL file's bytes without validating the mesh.
pub(crate) fn read_stl_raw(bytes: &[u8], path: &Path) -> Result<RawMesh, IoError> {
    let (corners, ascii) = if is_binary(bytes) {
        (binary_corners(bytes, path)?, false)
    } else {
        (ascii_corners(bytes, path)?, true)
    };
    if corners.is_empty() {
        return Err(IoError::InvalidMesh {
            path: path.to_path_buf(),
            origin: None,
            source: conformap_mesh::MeshError::NoVertices,
        });
    }
    let (map, first) = classes(&corners, None);
    let positions: Vec<[f64; 3]> = first.iter().map(|&c| corners[c]).collect();
    let faces: Vec<[u32; 3]> = map.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let mut source = SourceInfo::new(path.to_path_buf(), Format::Stl);
    source.file_vertex_count = corners.len();
    source.notes.push(format!(
        "{} STL: {} facet corners welded into {} vertices ({} welded)",
        if ascii { "ASCII" } else { "binary" },
        corners.len(),
        positions.len(),
        corners.len() - positions.len()
    ));
    source.weld_map = Some(map);
    let elements = ElementOrigins {
        vertex: "vertex of facet",
        face: "facet",
        vertex_of: first.iter().map(|&c| c / 3).collect(),
        face_of: Vec::new(),
    };
    let raw = RawMesh::new(positions, faces, Err(UvProblem::Absent), source, None);
    Ok(raw.with_elements(elements))
}

/// The three corners of every facet of a binary STL, in order.
fn binary_corners(bytes: &[u8], path: &Path) -> Result<Vec<[f64; 3]>, IoError> {
    let mut c = Cursor::new(bytes, path, Format::Stl, false);
    c.take(80, String::new)?;
    let n = c.i32(String::new)? as u32 as u64;
    c.check_count(n, BINARY_FACET as u64, "facets")?;
    let body = &bytes[BINARY_HEADER..BINARY_HEADER + BINARY_FACET * n as usize];
    let mut corners = Vec::with_capacity(3 * n as usize);
    for facet in body.chunks_exact(BINARY_FACET) {
        for k in 0..3 {
            let at = 12 + 12 * k;
            corners.push(std::array::from_fn(|i| {
                let b = &facet[at + 4 * i..at + 4 * i + 4];
                f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            }));
        }
    }
    Ok(corners)
}

/// The corners of every facet of an ASCII STL (`solid` … `facet normal` … `outer loop`,
/// three `vertex x y z`, `endloop`, `endfacet` … `endsolid`); several solids are joined.
fn ascii_corners(bytes: &[u8], path: &Path) -> Result<Vec<[f64; 3]>, IoError> {
    let bad = |line: usize, problem: String| {
        malformed(path, Format::Stl, Place::Line(line), problem, CORRUPT_HINT)
    };
    let mut corners = Vec::new();
    // corners of the facet being read, and the line it started on
    let mut open: Option<(usize, usize)> = None;
    for (line, text) in numbered_lines(bytes, 1) {
        let mut w = words(text);
        match w.next() {
            Some(b"vertex") => {
                let Some((_, n)) = &mut open else {
                    return Err(bad(line, "`vertex` outside a facet".into()));
                };
                let xyz: Vec<&[u8]> = w.collect();
                let parsed: Option<Vec<f64>> = xyz.iter().map(|t| parse_f64(t)).collect();
                match parsed {
                    Some(p) if p.len() == 3 => corners.push([p[0], p[1], p[2]]),
                    Some(p) => {
                        return Err(bad(line, format!("`vertex` has {} values, not 3", p.len())))
                    }
                    None => {
                        let word = xyz.iter().find(|t| parse_f64(t).is_none()).copied();
                        let problem =
                            format!("`{}` is not a number", quote(word.unwrap_or_default()));
                        return Err(bad(line, problem));
                    }
                }
                *n += 1;
            }
            Some(b"facet") => {
                if open.is_some() {
                    return Err(bad(line, "`facet` inside a facet (no `endfacet`)".into()));
                }
                open = Some((line, 0));
            }
            Some(b"endfacet") => match open.take() {
                Some((_, 3)) => {}
                Some((start, n)) => {
                    return Err(bad(
                        start,
                        format!("the facet has {n} vertices; STL facets have 3"),
                    ))
                }
                None => return Err(bad(line, "`endfacet` without `facet`".into())),
            },
            Some(b"solid" | b"endsolid" | b"outer" | b"endloop") | None => {}
            Some(other) => {
                return Err(bad(
                    line,
                    format!("`{}` is not an STL keyword", quote(other)),
                ))
            }
        }
    }
    if let Some((start, _)) = open {
        return Err(malformed(
            path,
            Format::Stl,
            Place::Line(start),
            "the file ends inside this facet",
            crate::cursor::TRUNCATED_HINT,
        ));
    }
    Ok(corners)
}
