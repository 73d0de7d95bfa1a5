//! Reading a PLY body: the `vertex` element's `x y z` (and texture coordinates), the
//! `face` element's index lists (fan-triangulated, with a per-corner `texcoord` list if
//! there is one); every other element and property skipped.

use std::path::Path;

use super::header::{parse_header, Element, Encoding, Header, Kind, Scalar};
use crate::corner_uv::CornerUv;
use crate::cursor::{malformed, parse_f64, quote, Cursor, CORRUPT_HINT, TRUNCATED_HINT};
use crate::error::{IoError, Place, UvProblem};
use crate::loaded::{Format, SourceInfo};
use crate::raw::{ElementOrigins, RawMesh};

/// Names of per-vertex texture coordinates, in the order they are looked for.
const UV_NAMES: [(&str, &str); 4] = [
    ("texture_u", "texture_v"),
    ("u", "v"),
    ("s", "t"),
    ("texture_s", "texture_t"),
];

/// Where an element's values come from: binary bytes or ASCII words.
enum Body<'a> {
    Binary(Cursor<'a>),
    Ascii(Words<'a>),
}

/// The words of an ASCII body, with their line.
struct Words<'a> {
    text: &'a [u8],
    pos: usize,
    line: usize,
    path: &'a Path,
}

impl<'a> Words<'a> {
    fn next(&mut self) -> Option<&'a [u8]> {
        while let Some(&b) = self.text.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            // `\r\n` counts once
            if b == b'\n' || (b == b'\r' && self.text.get(self.pos + 1) != Some(&b'\n')) {
                self.line += 1;
            }
            self.pos += 1;
        }
        let start = self.pos;
        while self
            .text
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        (self.pos > start).then(|| &self.text[start..self.pos])
    }
}

impl Body<'_> {
    /// The next value of type `s`, inside `element` (for messages).
    fn value(&mut self, s: Scalar, element: &dyn Fn() -> String) -> Result<f64, IoError> {
        match self {
            Self::Binary(c) => {
                let b = c.take(s.size(), element)?;
                Ok(s.value(b, c.big_endian))
            }
            Self::Ascii(w) => {
                let Some(word) = w.next() else {
                    return Err(malformed(
                        w.path,
                        Format::Ply,
                        Place::Line(w.line),
                        format!("the file ends inside {}", element()),
                        TRUNCATED_HINT,
                    ));
                };
                parse_f64(word).ok_or_else(|| {
                    malformed(
                        w.path,
                        Format::Ply,
                        Place::Line(w.line),
                        format!("{}: `{}` is not a number", element(), quote(word)),
                        CORRUPT_HINT,
                    )
                })
            }
        }
    }

    /// An error at the current place.
    fn error(&self, problem: String, element: String) -> IoError {
        match self {
            Self::Binary(c) => c.error(element, problem, CORRUPT_HINT),
            Self::Ascii(w) => malformed(
                w.path,
                Format::Ply,
                Place::Line(w.line),
                format!("{element}: {problem}"),
                CORRUPT_HINT,
            ),
        }
    }

    /// Checks that `count` instances of `e` can fit in what is left (the memory estimate
    /// before allocating for them): binary by their fewest bytes, ASCII by two bytes a value.
    fn check_count(&self, e: &Element) -> Result<(), IoError> {
        let what = format!("`{}` elements", e.name);
        match self {
            Self::Binary(c) => c.check_count(e.count as u64, e.min_bytes() as u64, &what),
            Self::Ascii(w) => {
                let left = w.text.len().saturating_sub(w.pos) as u64;
                let room = left / (2 * e.props.len().max(1) as u64);
                if e.count as u64 > room {
                    return Err(malformed(
                        w.path,
                        Format::Ply,
                        Place::Line(w.line),
                        format!(
                            "the header declares {} {what}, but the {left} byte(s) left hold at \
                             most {room}",
                            e.count
                        ),
                        TRUNCATED_HINT,
                    ));
                }
                Ok(())
            }
        }
    }

    /// The next integer of type `s` that is a count or an index (≥ 0, integral).
    fn index(&mut self, s: Scalar, element: &dyn Fn() -> String) -> Result<u32, IoError> {
        let x = self.value(s, element)?;
        if x >= 0.0 && x.fract() == 0.0 && x <= f64::from(u32::MAX - 1) {
            Ok(x as u32)
        } else {
            Err(self.error(format!("{x} is not a valid index or count"), element()))
        }
    }
}

/// What the elements give.
#[derive(Default)]
struct Parts {
    positions: Vec<[f64; 3]>,
    uv: Option<Vec<Option<[f64; 2]>>>,
    faces: Vec<[u32; 3]>,
    face_of: Vec<usize>,
    corner_uv: Option<CornerUv>,
    polygons: bool,
    skipped: Vec<String>,
}

/// Reads a PLY file's bytes without validating the mesh.
pub(crate) fn read_ply_raw(bytes: &[u8], path: &Path) -> Result<RawMesh, IoError> {
    let header = parse_header(bytes, path)?;
    let body = &bytes[header.body.min(bytes.len())..];
    let mut source = match header.encoding {
        Encoding::Ascii => Body::Ascii(Words {
            text: body,
            pos: 0,
            line: header.lines + 1,
            path,
        }),
        Encoding::Binary { big_endian } => {
            let mut c = Cursor::new(bytes, path, Format::Ply, big_endian);
            c.pos = header.body;
            Body::Binary(c)
        }
    };
    let parts = read_elements(&header, &mut source, path)?;
    finish(parts, path)
}

fn read_elements(header: &Header, body: &mut Body<'_>, path: &Path) -> Result<Parts, IoError> {
    let mut parts = Parts::default();
    for e in &header.elements {
        body.check_count(e)?;
        match e.name.as_str() {
            "vertex" if parts.positions.is_empty() => read_vertices(e, body, &mut parts, path)?,
            "face" if parts.faces.is_empty() => read_faces(e, body, &mut parts)?,
            _ => {
                skip(e, body)?;
                parts.skipped.push(e.name.clone());
            }
        }
    }
    Ok(parts)
}

/// Skips the instances of an element nothing is read from.
fn skip(e: &Element, body: &mut Body<'_>) -> Result<(), IoError> {
    if let (Body::Binary(c), Some(stride)) = (&mut *body, e.stride()) {
        let name = || format!("{} element", e.name);
        let n = e
            .count
            .checked_mul(stride)
            .ok_or_else(|| c.error(name(), "too large", TRUNCATED_HINT))?;
        c.take(n, name)?;
        return Ok(());
    }
    for k in 0..e.count {
        let name = || format!("{} {k}", e.name);
        for p in &e.props {
            match p.kind {
                Kind::Scalar(s) => {
                    body.value(s, &name)?;
                }
                Kind::List(cs, is) => {
                    let n = body.index(cs, &name)?;
                    for _ in 0..n {
                        body.value(is, &name)?;
                    }
                }
            }
        }
    }
    Ok(())
}

fn read_vertices(
    e: &Element,
    body: &mut Body<'_>,
    parts: &mut Parts,
    path: &Path,
) -> Result<(), IoError> {
    let scalar_at = |name: &str| {
        e.find(&[name])
            .filter(|&i| matches!(e.props[i].kind, Kind::Scalar(_)))
    };
    let (Some(x), Some(y), Some(z)) = (scalar_at("x"), scalar_at("y"), scalar_at("z")) else {
        return Err(malformed(
            path,
            Format::Ply,
            Place::File,
            "the `vertex` element has no scalar `x`, `y` and `z` properties",
            CORRUPT_HINT,
        ));
    };
    let uv = UV_NAMES
        .iter()
        .find_map(|(u, v)| Some((scalar_at(u)?, scalar_at(v)?)));
    if let (Body::Binary(c), Some(stride)) = (&mut *body, e.stride()) {
        fixed_vertices(e, c, stride, [x, y, z], uv, parts)?;
        return Ok(());
    }
    let mut positions = Vec::with_capacity(e.count);
    let mut uvs = uv.map(|_| Vec::with_capacity(e.count));
    let mut row = vec![0.0; e.props.len()];
    for k in 0..e.count {
        let name = || format!("vertex {k}");
        for (i, p) in e.props.iter().enumerate() {
            match p.kind {
                Kind::Scalar(s) => row[i] = body.value(s, &name)?,
                Kind::List(cs, is) => {
                    let n = body.index(cs, &name)?;
                    for _ in 0..n {
                        body.value(is, &name)?;
                    }
                }
            }
        }
        positions.push([row[x], row[y], row[z]]);
        if let (Some(list), Some((u, v))) = (&mut uvs, uv) {
            list.push(Some([row[u], row[v]]));
        }
    }
    parts.positions = positions;
    parts.uv = uvs;
    Ok(())
}

/// The vertices of a binary element of scalars only: one slice, read row by row.
fn fixed_vertices(
    e: &Element,
    c: &mut Cursor<'_>,
    stride: usize,
    xyz: [usize; 3],
    uv: Option<(usize, usize)>,
    parts: &mut Parts,
) -> Result<(), IoError> {
    // each property's byte offset in a row, and its type
    let mut at = Vec::with_capacity(e.props.len());
    let mut offset = 0;
    for p in &e.props {
        if let Kind::Scalar(s) = p.kind {
            at.push((offset, s));
            offset += s.size();
        }
    }
    let len = e.count.saturating_mul(stride);
    let data = c.take(len, || "vertex element".to_string())?;
    let big = c.big_endian;
    let get = |row: &[u8], i: usize| {
        let (o, s) = at[i];
        s.value(&row[o..], big)
    };
    parts.positions = data
        .chunks_exact(stride.max(1))
        .map(|row| xyz.map(|i| get(row, i)))
        .collect();
    parts.uv = uv.map(|(u, v)| {
        data.chunks_exact(stride.max(1))
            .map(|row| Some([get(row, u), get(row, v)]))
            .collect()
    });
    Ok(())
}

/// The faces of a binary element whose only property is the index list: read straight
/// from the bytes.
fn list_only_faces(
    e: &Element,
    c: &mut Cursor<'_>,
    (count_type, index_type): (Scalar, Scalar),
    parts: &mut Parts,
) -> Result<(), IoError> {
    let start = match (count_type, index_type) {
        (Scalar::U8, Scalar::I32) => triangle_run(e.count, c, i32::MAX as u32, parts),
        (Scalar::U8, Scalar::U32) => triangle_run(e.count, c, u32::MAX - 1, parts),
        _ => 0,
    };
    let (cs, is) = (count_type.size(), index_type.size());
    let big = c.big_endian;
    let valid = |x: f64| x >= 0.0 && x.fract() == 0.0 && x <= f64::from(u32::MAX - 1);
    for k in start..e.count {
        let name = || format!("face {k}");
        let n = count_type.value(c.take(cs, name)?, big);
        if !(valid(n) && n >= 3.0) {
            c.pos -= cs;
            let problem = format!("{n} corner(s); a face needs at least 3");
            return Err(c.error(name(), problem, CORRUPT_HINT));
        }
        let n = n as usize;
        let bytes = c.take(n.saturating_mul(is), name)?;
        let mut corners = bytes.chunks_exact(is).map(|b| index_type.value(b, big));
        let index = |x: f64| valid(x).then_some(x as u32);
        let mut bad = None;
        let mut next = || {
            let x = corners.next().unwrap_or(f64::NAN);
            index(x).unwrap_or_else(|| {
                bad.get_or_insert(x);
                0
            })
        };
        let (first, mut prev) = (next(), next());
        for _ in 2..n {
            let cur = next();
            parts.faces.push([first, prev, cur]);
            parts.face_of.push(k);
            prev = cur;
        }
        if let Some(x) = bad {
            return Err(c.error(name(), format!("{x} is not a vertex index"), CORRUPT_HINT));
        }
        parts.polygons |= n > 3;
    }
    Ok(())
}

/// Reads the leading run of triangles in the layout nearly every tool writes (`uchar`
/// count, 4-byte indices) straight from the bytes, 13 bytes a face, with no per-value type
/// dispatch: binary PLY reads twice as fast (a 1M-face height field: 70 → 35 ms). It stops
/// at the first face that is not a triangle, has an index above `max_index` (a negative
/// `int` reads as one) or is not whole in the file, and returns how many faces it read: the
/// general loop reads on from there and reports what is wrong, as it always did.
fn triangle_run(count: usize, c: &mut Cursor<'_>, max_index: u32, parts: &mut Parts) -> usize {
    let big = c.big_endian;
    let word = |b: &[u8]| {
        let w = [b[0], b[1], b[2], b[3]];
        if big {
            u32::from_be_bytes(w)
        } else {
            u32::from_le_bytes(w)
        }
    };
    let body = c.bytes.get(c.pos..).unwrap_or_default();
    let mut read = 0;
    for face in body.chunks_exact(13).take(count) {
        let t = [word(&face[1..5]), word(&face[5..9]), word(&face[9..13])];
        if face[0] != 3 || t.iter().any(|&i| i > max_index) {
            break;
        }
        parts.faces.push(t);
        parts.face_of.push(read);
        read += 1;
    }
    c.pos += 13 * read;
    read
}

fn read_faces(e: &Element, body: &mut Body<'_>, parts: &mut Parts) -> Result<(), IoError> {
    let list_at = |names: &[&str]| {
        e.find(names)
            .filter(|&i| matches!(e.props[i].kind, Kind::List(..)))
    };
    let Some(indices) = list_at(&["vertex_indices", "vertex_index"]) else {
        let what = || "face element".to_string();
        return Err(body.error(
            "has no `vertex_indices` (or `vertex_index`) list property".into(),
            what(),
        ));
    };
    let texcoord = list_at(&["texcoord"]);
    parts.faces.reserve(e.count);
    parts.face_of.reserve(e.count);
    if let (Body::Binary(c), [only]) = (&mut *body, e.props.as_slice()) {
        if let Kind::List(cs, is) = only.kind {
            return list_only_faces(e, c, (cs, is), parts);
        }
    }
    let mut corners: Vec<u32> = Vec::new();
    let mut tex: Vec<f64> = Vec::new();
    let mut uv = texcoord.map(|_| CornerUv::default());
    for k in 0..e.count {
        let name = || format!("face {k}");
        corners.clear();
        tex.clear();
        for (i, p) in e.props.iter().enumerate() {
            match p.kind {
                Kind::Scalar(s) => {
                    body.value(s, &name)?;
                }
                Kind::List(cs, is) => {
                    let n = body.index(cs, &name)?;
                    for _ in 0..n {
                        if i == indices {
                            corners.push(body.index(is, &name)?);
                        } else if Some(i) == texcoord {
                            tex.push(body.value(is, &name)?);
                        } else {
                            body.value(is, &name)?;
                        }
                    }
                }
            }
        }
        if corners.len() < 3 {
            let problem = format!("{} corner(s); a face needs at least 3", corners.len());
            return Err(body.error(problem, name()));
        }
        parts.polygons |= corners.len() > 3;
        for w in 1..corners.len() - 1 {
            parts.faces.push([corners[0], corners[w], corners[w + 1]]);
            parts.face_of.push(k);
        }
        if let Some(uv) = &mut uv {
            if tex.len() != 2 * corners.len() {
                let problem = format!(
                    "its `texcoord` list has {} values for {} corners (need 2 per corner)",
                    tex.len(),
                    corners.len()
                );
                return Err(body.error(problem, name()));
            }
            let base = uv.texcoords.len() as u32;
            uv.texcoords
                .extend(tex.chunks_exact(2).map(|t| [t[0], t[1]]));
            for w in 1..corners.len() as u32 - 1 {
                uv.faces.push([base, base + w, base + w + 1]);
            }
        }
    }
    parts.corner_uv = uv;
    Ok(())
}

/// Checks the indices and builds the raw mesh.
fn finish(parts: Parts, path: &Path) -> Result<RawMesh, IoError> {
    let nv = parts.positions.len();
    if nv == 0 {
        return Err(IoError::InvalidMesh {
            path: path.to_path_buf(),
            origin: None,
            source: conformap_mesh::MeshError::NoVertices,
        });
    }
    for (f, tri) in parts.faces.iter().enumerate() {
        if let Some(&i) = tri.iter().find(|&&i| i as usize >= nv) {
            return Err(malformed(
                path,
                Format::Ply,
                Place::File,
                format!(
                    "face {} refers to vertex {i}, but there are only {nv} vertices",
                    parts.face_of[f]
                ),
                "the face list refers past the vertex list: the file is damaged; export it \
                 again",
            ));
        }
    }
    let mut source = SourceInfo::new(path.to_path_buf(), Format::Ply);
    source.file_vertex_count = nv;
    if !parts.skipped.is_empty() {
        source.notes.push(format!(
            "PLY elements not read: {}",
            parts.skipped.join(", ")
        ));
    }
    let uv = match parts.uv {
        Some(uv) => Ok(uv),
        None => Err(UvProblem::Absent),
    };
    let elements = ElementOrigins {
        vertex: "vertex",
        face: "face",
        vertex_of: Vec::new(),
        face_of: if parts.polygons {
            parts.face_of
        } else {
            Vec::new()
        },
    };
    let raw = RawMesh::new(parts.positions, parts.faces, uv, source, None);
    Ok(raw.with_elements(elements).with_corner_uv(parts.corner_uv))
}
