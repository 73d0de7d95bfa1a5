//! Reading a GIfTI surface: the XML's data arrays (with `quick-xml`), the point set and
//! the triangles decoded (see [`super::decode`]), the point set's coordinate transforms
//! kept.

use std::path::Path;

use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

use super::decode::{decode_values, DataArray};
use crate::cursor::{malformed, CORRUPT_HINT};
use crate::error::{IoError, Place, UvProblem};
use crate::loaded::{CoordinateTransform, Format, SourceInfo, SurfaceMetadata};
use crate::raw::{ElementOrigins, RawMesh};

/// The text element being read.
#[derive(Clone, Copy, PartialEq, Eq)]
enum In {
    Other,
    Data,
    DataSpace,
    TransformedSpace,
    MatrixData,
}

/// The data arrays of a GIfTI document, in file order.
pub(crate) fn parse_arrays(bytes: &[u8], path: &Path) -> Result<Vec<DataArray>, IoError> {
    let mut reader = Reader::from_reader(bytes);
    let mut arrays: Vec<DataArray> = Vec::new();
    let mut within = In::Other;
    let mut transform: Option<(String, String, String)> = None;
    let mut seen_root = false;
    loop {
        let event = reader.read_event().map_err(|e| {
            let place = Place::Byte {
                offset: reader.error_position(),
                element: String::new(),
            };
            malformed(
                path,
                Format::Gifti,
                place,
                format!("malformed XML: {e}"),
                CORRUPT_HINT,
            )
        })?;
        match event {
            Event::Start(e) | Event::Empty(e) => {
                let name = e.local_name();
                match name.as_ref() {
                    b"GIFTI" => seen_root = true,
                    b"DataArray" => arrays.push(array_of(&e, arrays.len())),
                    b"CoordinateSystemTransformMatrix" => {
                        transform = Some(Default::default());
                    }
                    b"Data" => within = In::Data,
                    b"DataSpace" => within = In::DataSpace,
                    b"TransformedSpace" => within = In::TransformedSpace,
                    b"MatrixData" => within = In::MatrixData,
                    _ => within = In::Other,
                }
            }
            Event::Text(t) => add_text(&t, within, &mut arrays, &mut transform),
            Event::CData(t) => add_text(&t, within, &mut arrays, &mut transform),
            Event::End(e) => {
                if e.local_name().as_ref() == b"CoordinateSystemTransformMatrix" {
                    if let (Some(t), Some(a)) = (transform.take(), arrays.last_mut()) {
                        a.transforms.push(t);
                    }
                }
                within = In::Other;
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if !seen_root {
        return Err(malformed(
            path,
            Format::Gifti,
            Place::File,
            "no <GIFTI> element: not a GIfTI file",
            CORRUPT_HINT,
        ));
    }
    Ok(arrays)
}

fn add_text(
    t: &[u8],
    within: In,
    arrays: &mut [DataArray],
    transform: &mut Option<(String, String, String)>,
) {
    let text = String::from_utf8_lossy(t);
    match (within, arrays.last_mut(), transform.as_mut()) {
        (In::Data, Some(a), _) => a.data.extend_from_slice(t),
        (In::DataSpace, _, Some(tr)) => tr.0.push_str(text.trim()),
        (In::TransformedSpace, _, Some(tr)) => tr.1.push_str(text.trim()),
        (In::MatrixData, _, Some(tr)) => {
            tr.2.push(' ');
            tr.2.push_str(&text);
        }
        _ => {}
    }
}

/// A data array from its attributes.
fn array_of(e: &BytesStart<'_>, index: usize) -> DataArray {
    let mut a = DataArray {
        index,
        ..DataArray::default()
    };
    for attr in e.attributes().flatten() {
        let value = String::from_utf8_lossy(&attr.value).trim().to_string();
        match attr.key.local_name().as_ref() {
            b"Intent" => a.intent = value,
            b"DataType" => a.data_type = value,
            b"ArrayIndexingOrder" => a.order = value,
            b"Dimensionality" => a.dimensionality = value.parse().ok(),
            b"Encoding" => a.encoding = value,
            b"Endian" => a.endian = value,
            b"ExternalFileName" => a.external = value,
            k if k.starts_with(b"Dim") => {
                let d: Option<usize> = std::str::from_utf8(&k[3..])
                    .ok()
                    .and_then(|s| s.parse().ok());
                if let Some(d) = d.filter(|&d| d < 8) {
                    if a.dims.len() <= d {
                        a.dims.resize(d + 1, None);
                    }
                    a.dims[d] = value.parse().ok();
                }
            }
            _ => {}
        }
    }
    a
}

/// Reads a GIfTI surface's bytes without validating the mesh: the first
/// `NIFTI_INTENT_POINTSET` array and the first `NIFTI_INTENT_TRIANGLE` array.
pub(crate) fn read_gifti_raw(bytes: &[u8], path: &Path) -> Result<RawMesh, IoError> {
    let arrays = parse_arrays(bytes, path)?;
    let find = |intent: &str| arrays.iter().find(|a| a.intent == intent);
    let missing = |what: &str| {
        malformed(
            path,
            Format::Gifti,
            Place::File,
            format!("no {what} data array"),
            "this GIfTI file is not a surface (a .shape.gii or .func.gii holds data for one): \
             pass the .surf.gii",
        )
    };
    let points = find("NIFTI_INTENT_POINTSET").ok_or_else(|| missing("NIFTI_INTENT_POINTSET"))?;
    let triangles =
        find("NIFTI_INTENT_TRIANGLE").ok_or_else(|| missing("NIFTI_INTENT_TRIANGLE"))?;
    let p = decode_values(points, 3, path)?;
    let t = decode_values(triangles, 3, path)?;
    let positions: Vec<[f64; 3]> = p.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
    let nv = positions.len();
    let mut faces = Vec::with_capacity(t.len() / 3);
    for (k, c) in t.chunks_exact(3).enumerate() {
        let mut tri = [0u32; 3];
        for (slot, &x) in tri.iter_mut().zip(c) {
            if !(x >= 0.0 && x.fract() == 0.0 && x < nv as f64) {
                return Err(malformed(
                    path,
                    Format::Gifti,
                    Place::DataArray(triangles.index),
                    format!("triangle {k} has vertex index {x}, out of range ({nv} points)"),
                    CORRUPT_HINT,
                ));
            }
            *slot = x as u32;
        }
        faces.push(tri);
    }
    if nv == 0 {
        return Err(IoError::InvalidMesh {
            path: path.to_path_buf(),
            origin: None,
            source: conformap_mesh::MeshError::NoVertices,
        });
    }
    let mut source = SourceInfo::new(path.to_path_buf(), Format::Gifti);
    source.file_vertex_count = nv;
    source.surface = Some(SurfaceMetadata {
        created_by: None,
        volume_info: None,
        transforms: points.transforms.iter().filter_map(transform_of).collect(),
    });
    let raw = RawMesh::new(positions, faces, Err(UvProblem::Absent), source, None);
    Ok(raw.with_elements(ElementOrigins::identity("point", "triangle")))
}

/// A transform from its three texts; `None` unless the matrix has 16 numbers.
fn transform_of(
    (data, transformed, matrix): &(String, String, String),
) -> Option<CoordinateTransform> {
    let numbers: Vec<f64> = matrix
        .split_ascii_whitespace()
        .map(|w| crate::cursor::parse_f64(w.as_bytes()))
        .collect::<Option<_>>()?;
    (numbers.len() == 16).then(|| CoordinateTransform {
        data_space: data.clone(),
        transformed_space: transformed.clone(),
        matrix: std::array::from_fn(|r| std::array::from_fn(|c| numbers[4 * r + c])),
    })
}
