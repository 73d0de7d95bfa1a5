//! FreeSurfer binary triangle surfaces (`lh.white`, `lh.pial`, `lh.sphere`...), big-endian:
//! the magic `FF FF FE`, a `created by …` line ended by two line ends, the vertex and face
//! counts (`i32`), `f32 x y z` per vertex, `i32` corners per triangle, and an optional
//! volume-geometry footer (the tag `2 0 20` or `20`, then `key = value` lines), which is
//! kept byte for byte ([`SurfaceMetadata::volume_info`]).

use std::path::Path;

use crate::cursor::{Cursor, CORRUPT_HINT};
use crate::error::{IoError, UvProblem, WriteProblem};
use crate::loaded::{Format, SourceInfo, SurfaceMetadata, FREESURFER_MAGIC};
use crate::raw::{ElementOrigins, RawMesh};

/// FreeSurfer's quad-file magic (`FF FF FF`), which this reader refuses.
const QUAD_MAGIC: [u8; 3] = [0xff, 0xff, 0xff];
/// The created-by line is at most this long (FreeSurfer writes about 60 bytes).
const MAX_STAMP: usize = 4096;

/// Reads a FreeSurfer surface's bytes without validating the mesh.
pub(crate) fn read_freesurfer_raw(bytes: &[u8], path: &Path) -> Result<RawMesh, IoError> {
    let mut c = Cursor::new(bytes, path, Format::FreeSurfer, true);
    let magic = c.take(3, String::new)?;
    if magic != FREESURFER_MAGIC {
        c.pos = 0;
        let (problem, hint) = if magic == QUAD_MAGIC {
            (
                "a quad surface (magic FF FF FF); only triangle surfaces are read",
                "convert it to a triangle surface: mris_convert lh.orig lh.orig.tri",
            )
        } else {
            (
                "not a FreeSurfer triangle surface (its first bytes are not FF FF FE)",
                "check the file: FreeSurfer surfaces (lh.white, lh.pial...) start with FF FF FE; \
                 a file of another format needs its extension (.obj, .ply, .gii...)",
            )
        };
        return Err(c.error("", problem, hint));
    }
    let created_by = stamp(&mut c)?;
    let nv = c.i32(String::new)?;
    let nf = c.i32(String::new)?;
    if nv <= 0 || nf < 0 {
        c.pos -= 8;
        return Err(c.error("", format!("{nv} vertices and {nf} faces"), CORRUPT_HINT));
    }
    let (nv, nf) = (nv as usize, nf as usize);
    c.check_count(
        nv as u64 * 12 + nf as u64 * 12,
        1,
        "bytes of vertices and faces",
    )?;
    let mut positions = Vec::with_capacity(nv);
    for k in 0..nv {
        let name = || format!("vertex {k}");
        positions.push([c.f32(name)?, c.f32(name)?, c.f32(name)?]);
    }
    let mut faces = Vec::with_capacity(nf);
    for k in 0..nf {
        let name = || format!("triangle {k}");
        let mut tri = [0u32; 3];
        for slot in &mut tri {
            let i = c.i32(name)?;
            if i < 0 || i as usize >= nv {
                c.pos -= 4;
                let problem = format!("vertex index {i} is out of range ({nv} vertices)");
                return Err(c.error(name(), problem, CORRUPT_HINT));
            }
            *slot = i as u32;
        }
        faces.push(tri);
    }
    let volume_info = (c.remaining() > 0).then(|| bytes[c.pos..].to_vec());
    let mut source = SourceInfo::new(path.to_path_buf(), Format::FreeSurfer);
    source.file_vertex_count = nv;
    source.surface = Some(SurfaceMetadata {
        created_by: Some(created_by),
        volume_info,
        transforms: Vec::new(),
    });
    let raw = RawMesh::new(positions, faces, Err(UvProblem::Absent), source, None);
    Ok(raw.with_elements(ElementOrigins::identity("vertex", "triangle")))
}

/// The `created by …` line and the empty line after it.
fn stamp(c: &mut Cursor<'_>) -> Result<String, IoError> {
    let rest = &c.bytes[c.pos..];
    let Some(end) = memchr::memchr(b'\n', &rest[..rest.len().min(MAX_STAMP)]) else {
        return Err(c.error(
            "",
            "no end to the `created by` line",
            crate::cursor::TRUNCATED_HINT,
        ));
    };
    let text = String::from_utf8_lossy(&rest[..end]).into_owned();
    c.pos += end + 1;
    // FreeSurfer ends the line with "\n\n"; some writers put only one
    if c.bytes.get(c.pos) == Some(&b'\n') {
        c.pos += 1;
    }
    Ok(text)
}

/// The bytes of a FreeSurfer triangle surface; `meta` gives the created-by line and the
/// volume-geometry footer to keep (else `created by conformap` and no footer).
pub(crate) fn encode_freesurfer(
    points: &[[f64; 3]],
    faces: &[[u32; 3]],
    meta: Option<&SurfaceMetadata>,
) -> Result<Vec<u8>, WriteProblem> {
    let (Ok(nv), Ok(nf)) = (i32::try_from(points.len()), i32::try_from(faces.len())) else {
        return Err(WriteProblem::TooLarge);
    };
    let mut out = Vec::with_capacity(100 + 12 * (points.len() + faces.len()));
    out.extend_from_slice(&FREESURFER_MAGIC);
    out.extend_from_slice(b"created by conformap\n\n");
    out.extend_from_slice(&nv.to_be_bytes());
    out.extend_from_slice(&nf.to_be_bytes());
    for p in points {
        for &x in p {
            out.extend_from_slice(&(x as f32).to_be_bytes());
        }
    }
    for f in faces {
        for &i in f {
            out.extend_from_slice(&(i as i32).to_be_bytes());
        }
    }
    if let Some(footer) = meta.and_then(|m| m.volume_info.as_ref()) {
        out.extend_from_slice(footer);
    }
    Ok(out)
}
