//! Decoding a GIfTI data array: ASCII, `Base64Binary` or `GZipBase64Binary` (zlib), any
//! byte order, row- or column-major, into f64 values in row-major order.

use std::io::Read;
use std::path::Path;

use base64::Engine;

use crate::cursor::{malformed, CORRUPT_HINT};
use crate::error::{IoError, Place};
use crate::loaded::Format;

/// The most a GIfTI array may inflate per compressed byte. Deflate allows 1032:1, but
/// float32 points and int32 triangles of real surfaces compress about 1.5–4:1; an array
/// that claims more is refused before inflating (a gzip bomb, or wrong dimensions), which
/// bounds what a file can make the reader allocate.
const MAX_INFLATE_RATIO: usize = 64;

/// A `<DataArray>` as the XML gives it.
#[derive(Debug, Clone, Default)]
pub(crate) struct DataArray {
    /// 0-based, in file order.
    pub(crate) index: usize,
    pub(crate) intent: String,
    pub(crate) data_type: String,
    pub(crate) order: String,
    pub(crate) dimensionality: Option<usize>,
    pub(crate) dims: Vec<Option<usize>>,
    pub(crate) encoding: String,
    pub(crate) endian: String,
    pub(crate) external: String,
    /// The text of `<Data>`.
    pub(crate) data: Vec<u8>,
    /// `(DataSpace, TransformedSpace, MatrixData)` texts.
    pub(crate) transforms: Vec<(String, String, String)>,
}

/// Reads one value from its little-endian bytes.
type ReadValue = fn(&[u8]) -> f64;

/// Bytes of a value of a NIfTI data type, and how to read one (little-endian bytes).
fn data_type(name: &str) -> Option<(usize, ReadValue)> {
    Some(match name {
        "NIFTI_TYPE_FLOAT32" => (4, |b| {
            f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        }),
        "NIFTI_TYPE_FLOAT64" => (8, |b| {
            f64::from_le_bytes([b[0], b[1], b[2], b[3], b[4], b[5], b[6], b[7]])
        }),
        "NIFTI_TYPE_INT32" => (4, |b| {
            f64::from(i32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        }),
        "NIFTI_TYPE_UINT32" => (4, |b| {
            f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        }),
        "NIFTI_TYPE_INT16" => (2, |b| f64::from(i16::from_le_bytes([b[0], b[1]]))),
        "NIFTI_TYPE_UINT16" => (2, |b| f64::from(u16::from_le_bytes([b[0], b[1]]))),
        "NIFTI_TYPE_INT8" => (1, |b| f64::from(b[0] as i8)),
        "NIFTI_TYPE_UINT8" => (1, |b| f64::from(b[0])),
        _ => return None,
    })
}

/// The values of an `n × columns` array, row-major.
pub(crate) fn decode_values(
    a: &DataArray,
    columns: usize,
    path: &Path,
) -> Result<Vec<f64>, IoError> {
    let bad = |problem: String, hint: &'static str| {
        malformed(
            path,
            Format::Gifti,
            Place::DataArray(a.index),
            problem,
            hint,
        )
    };
    let rows = check_dims(a, columns).map_err(|p| bad(p, CORRUPT_HINT))?;
    let too_large = || {
        bad(
            format!("dimensions ({rows}, {columns}) are too large"),
            CORRUPT_HINT,
        )
    };
    let count = rows.checked_mul(columns).ok_or_else(too_large)?;
    let values = match encoding(&a.encoding) {
        "ASCII" => ascii(&a.data, count).map_err(|p| bad(p, CORRUPT_HINT))?,
        "Base64Binary" | "GZipBase64Binary" => {
            let (size, read) = data_type(&a.data_type).ok_or_else(|| {
                bad(
                    format!("data type `{}` is not supported", a.data_type),
                    CORRUPT_HINT,
                )
            })?;
            let len = count.checked_mul(size).ok_or_else(too_large)?;
            let bytes = binary(a, len).map_err(|p| bad(p, CORRUPT_HINT))?;
            let big = matches!(a.endian.as_str(), "BigEndian" | "GIFTI_ENDIAN_BIG");
            bytes
                .chunks_exact(size)
                .map(|c| {
                    let mut w = [0u8; 8];
                    w[..size].copy_from_slice(c);
                    if big {
                        w[..size].reverse();
                    }
                    read(&w)
                })
                .collect()
        }
        "ExternalFileBinary" => {
            return Err(bad(
                format!("the data is in an external file (`{}`)", a.external),
                "write the surface with its data inside the .gii (e.g. with nibabel, \
                 GZipBase64Binary encoding)",
            ))
        }
        other => return Err(bad(format!("unknown encoding `{other}`"), CORRUPT_HINT)),
    };
    Ok(if a.order == "ColumnMajorOrder" {
        (0..count)
            .map(|k| values[(k % columns) * rows + k / columns])
            .collect()
    } else {
        values
    })
}

/// The standard name of an encoding: GIfTI's C library (gifticlib) and files written
/// through it spell the encodings by their code names (`GIFTI_ENCODING_B64BIN`), which
/// nibabel reads as well.
fn encoding(name: &str) -> &str {
    match name {
        "GIFTI_ENCODING_ASCII" => "ASCII",
        "GIFTI_ENCODING_B64BIN" => "Base64Binary",
        "GIFTI_ENCODING_B64GZ" => "GZipBase64Binary",
        "GIFTI_ENCODING_EXTBIN" => "ExternalFileBinary",
        other => other,
    }
}

/// The row count of an `n × columns` array, or what is wrong with its dimensions.
fn check_dims(a: &DataArray, columns: usize) -> Result<usize, String> {
    let dims: Vec<usize> = a.dims.iter().map(|d| d.unwrap_or(0)).collect();
    let ok = a.dimensionality.unwrap_or(dims.len()) == 2 && dims.len() == 2 && dims[1] == columns;
    if !ok {
        return Err(format!(
            "{}: dimensions {:?}, expected 2 dimensions (n, {columns})",
            a.intent, dims
        ));
    }
    Ok(dims[0])
}

/// `count` numbers of an ASCII array.
fn ascii(text: &[u8], count: usize) -> Result<Vec<f64>, String> {
    let words = text
        .split(|b| b.is_ascii_whitespace())
        .filter(|w| !w.is_empty());
    let mut out = Vec::with_capacity(count.min(text.len() / 2 + 1));
    for w in words {
        let x = crate::cursor::parse_f64(w)
            .ok_or_else(|| format!("`{}` is not a number", crate::cursor::quote(w)))?;
        out.push(x);
    }
    if out.len() != count {
        return Err(format!(
            "{} values, but the dimensions need {count}",
            out.len()
        ));
    }
    Ok(out)
}

/// The `len` bytes of a base64 (and perhaps zlib) array; allocations are bounded by what
/// the text can hold, checked before decoding.
fn binary(a: &DataArray, len: usize) -> Result<Vec<u8>, String> {
    let text: Vec<u8> = a
        .data
        .iter()
        .copied()
        .filter(|b| !b.is_ascii_whitespace())
        .collect();
    let most = text.len() / 4 * 3;
    let gzip = encoding(&a.encoding) == "GZipBase64Binary";
    let room = if gzip {
        most.saturating_mul(MAX_INFLATE_RATIO)
    } else {
        most
    };
    if len > room {
        return Err(format!(
            "the dimensions need {len} bytes, more than the {} base64 characters can hold",
            text.len()
        ));
    }
    let raw = base64::engine::general_purpose::STANDARD
        .decode(&text)
        .map_err(|e| format!("the data is not valid base64 ({e})"))?;
    let bytes = if gzip {
        let mut out = Vec::with_capacity(len.min(raw.len().saturating_mul(8)));
        flate2::read::ZlibDecoder::new(raw.as_slice())
            .take(len as u64 + 1)
            .read_to_end(&mut out)
            .map_err(|e| format!("the data does not inflate (zlib: {e})"))?;
        out
    } else {
        raw
    };
    if bytes.len() != len {
        return Err(format!(
            "{} bytes of data, but the dimensions and data type need {len}",
            bytes.len()
        ));
    }
    Ok(bytes)
}
