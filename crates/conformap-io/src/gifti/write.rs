//! Writing GIfTI: a surface (`NIFTI_INTENT_POINTSET` float32 + `NIFTI_INTENT_TRIANGLE`
//! int32) and per-vertex data arrays (`.shape.gii`/`.func.gii`), each array
//! `GZipBase64Binary`, little-endian, row-major, as nibabel and Connectome Workbench write
//! them.

use std::fmt::Write as _;
use std::io::Write as _;

use base64::Engine;

use crate::loaded::{CoordinateTransform, SurfaceMetadata};

/// Escapes `<`, `>`, `&` and `"` for XML text and attributes.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// zlib-compressed, base64-encoded `bytes`.
fn gzip_base64(bytes: &[u8]) -> String {
    let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::new(6));
    // writing to a Vec cannot fail
    let packed = z
        .write_all(bytes)
        .and_then(|()| z.finish())
        .unwrap_or_default();
    base64::engine::general_purpose::STANDARD.encode(packed)
}

/// One `<DataArray>` of little-endian `bytes` with the given attributes and inner XML.
fn data_array(
    out: &mut String,
    intent: &str,
    data_type: &str,
    dims: &[usize],
    inner: &str,
    bytes: &[u8],
) {
    let _ = write!(
        out,
        "<DataArray Intent=\"{intent}\" DataType=\"{data_type}\" \
         ArrayIndexingOrder=\"RowMajorOrder\" Dimensionality=\"{}\"",
        dims.len()
    );
    for (k, d) in dims.iter().enumerate() {
        let _ = write!(out, " Dim{k}=\"{d}\"");
    }
    let _ = write!(
        out,
        " Encoding=\"GZipBase64Binary\" Endian=\"LittleEndian\" ExternalFileName=\"\" \
         ExternalFileOffset=\"\">\n{inner}<Data>{}</Data>\n</DataArray>\n",
        gzip_base64(bytes)
    );
}

/// The transform's XML. The matrix is written one row per line, as nibabel and gifticlib
/// write it: nibabel reads a one-line `MatrixData` as a vector of 16 numbers, not 4 × 4.
fn transform_xml(t: &CoordinateTransform) -> String {
    let numbers: Vec<String> = t
        .matrix
        .iter()
        .map(|row| {
            row.iter()
                .map(|x| format!("{x:?}"))
                .collect::<Vec<_>>()
                .join(" ")
        })
        .collect();
    format!(
        "<CoordinateSystemTransformMatrix><DataSpace><![CDATA[{}]]></DataSpace>\
         <TransformedSpace><![CDATA[{}]]></TransformedSpace><MatrixData>{}</MatrixData>\
         </CoordinateSystemTransformMatrix>\n",
        t.data_space.replace("]]>", ""),
        t.transformed_space.replace("]]>", ""),
        numbers.join("\n")
    )
}

fn document(arrays: usize, body: &str) -> Vec<u8> {
    format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<GIFTI Version=\"1.0\" \
         NumberOfDataArrays=\"{arrays}\">\n<MetaData/>\n<LabelTable/>\n{body}</GIFTI>\n"
    )
    .into_bytes()
}

/// A GIfTI surface: points as float32, triangles as int32; `meta` gives the point set's
/// coordinate transforms to keep (else an identity `NIFTI_XFORM_UNKNOWN` one).
pub(crate) fn encode_gifti_surface(
    points: &[[f64; 3]],
    faces: &[[u32; 3]],
    meta: Option<&SurfaceMetadata>,
) -> Vec<u8> {
    let identity = CoordinateTransform {
        data_space: "NIFTI_XFORM_UNKNOWN".into(),
        transformed_space: "NIFTI_XFORM_UNKNOWN".into(),
        matrix: std::array::from_fn(|r| std::array::from_fn(|c| f64::from(u8::from(r == c)))),
    };
    let kept = meta.map(|m| m.transforms.as_slice()).unwrap_or_default();
    let transforms: String = if kept.is_empty() {
        transform_xml(&identity)
    } else {
        kept.iter().map(transform_xml).collect()
    };
    let p: Vec<u8> = points
        .iter()
        .flatten()
        .flat_map(|&x| (x as f32).to_le_bytes())
        .collect();
    let f: Vec<u8> = faces
        .iter()
        .flatten()
        .flat_map(|&i| (i as i32).to_le_bytes())
        .collect();
    let mut body = String::new();
    data_array(
        &mut body,
        "NIFTI_INTENT_POINTSET",
        "NIFTI_TYPE_FLOAT32",
        &[points.len(), 3],
        &transforms,
        &p,
    );
    data_array(
        &mut body,
        "NIFTI_INTENT_TRIANGLE",
        "NIFTI_TYPE_INT32",
        &[faces.len(), 3],
        "",
        &f,
    );
    document(2, &body)
}

/// A GIfTI data file: one float32 array per column, each named in its metadata.
pub(crate) fn encode_gifti_data(columns: &[(&str, &[f64])]) -> Vec<u8> {
    let mut body = String::new();
    for (name, values) in columns {
        let meta = format!(
            "<MetaData><MD><Name><![CDATA[Name]]></Name><Value><![CDATA[{}]]></Value></MD>\
             </MetaData>\n",
            escape(name).replace("]]>", "")
        );
        let bytes: Vec<u8> = values
            .iter()
            .flat_map(|&x| (x as f32).to_le_bytes())
            .collect();
        data_array(
            &mut body,
            "NIFTI_INTENT_NONE",
            "NIFTI_TYPE_FLOAT32",
            &[values.len()],
            &meta,
            &bytes,
        );
    }
    document(columns.len(), &body)
}
