//! Hand-made GIfTI files in every encoding, and truncated or corrupt PLY, STL, OFF, GIfTI
//! and FreeSurfer files: each gives `IoError::Malformed` naming the place, with a hint,
//! never a panic.
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use std::io::Write;

use base64::Engine;
use conformap_io::{read_mesh_from_bytes, write_flat, Format, IoError, Place};

const SQUARE: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

/// One data array: intent, data type, dims, encoding, endian, order, data text.
struct Array<'a>(
    &'a str,
    &'a str,
    &'a [usize],
    &'a str,
    &'a str,
    &'a str,
    String,
);

fn gifti(arrays: &[Array<'_>]) -> Vec<u8> {
    let mut s = format!(
        "<?xml version=\"1.0\"?>\n<GIFTI Version=\"1.0\" NumberOfDataArrays=\"{}\">\n",
        arrays.len()
    );
    for Array(intent, ty, dims, enc, endian, order, data) in arrays {
        let d: String = dims
            .iter()
            .enumerate()
            .map(|(k, d)| format!(" Dim{k}=\"{d}\""))
            .collect();
        s.push_str(&format!(
            "<DataArray Intent=\"{intent}\" DataType=\"{ty}\" ArrayIndexingOrder=\"{order}\" \
             Dimensionality=\"{}\"{d} Encoding=\"{enc}\" Endian=\"{endian}\">\n\
             <CoordinateSystemTransformMatrix><DataSpace><![CDATA[NIFTI_XFORM_UNKNOWN]]></DataSpace>\
             <TransformedSpace><![CDATA[NIFTI_XFORM_TALAIRACH]]></TransformedSpace>\
             <MatrixData>1 0 0 10 0 1 0 20 0 0 1 30 0 0 0 1</MatrixData></CoordinateSystemTransformMatrix>\n\
             <Data>{data}</Data></DataArray>\n",
            dims.len()
        ));
    }
    s.push_str("</GIFTI>\n");
    s.into_bytes()
}

fn b64(bytes: &[u8], gzip: bool) -> String {
    let bytes = if gzip {
        let mut z = flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::default());
        z.write_all(bytes).unwrap();
        z.finish().unwrap()
    } else {
        bytes.to_vec()
    };
    base64::engine::general_purpose::STANDARD.encode(bytes)
}

/// The square's points and triangles as GIfTI arrays in the given encoding.
fn square_arrays(enc: &str, big: bool, column_major: bool) -> Vec<Array<'static>> {
    let endian = if big { "BigEndian" } else { "LittleEndian" };
    let order = if column_major {
        "ColumnMajorOrder"
    } else {
        "RowMajorOrder"
    };
    let tri = [[0i32, 1, 2], [0, 2, 3]];
    let points: Vec<f64> = if column_major {
        (0..3)
            .flat_map(|c| SQUARE.iter().map(move |p| p[c]))
            .collect()
    } else {
        SQUARE.iter().flatten().copied().collect()
    };
    let faces: Vec<i32> = if column_major {
        (0..3).flat_map(|c| tri.iter().map(move |t| t[c])).collect()
    } else {
        tri.iter().flatten().copied().collect()
    };
    let (p, f) = if enc == "ASCII" {
        let p: Vec<String> = points.iter().map(|x| x.to_string()).collect();
        let f: Vec<String> = faces.iter().map(|x| x.to_string()).collect();
        (p.join(" "), f.join("\n"))
    } else {
        let gz = enc == "GZipBase64Binary";
        let pb: Vec<u8> = points
            .iter()
            .flat_map(|&x| {
                if big {
                    (x as f32).to_be_bytes()
                } else {
                    (x as f32).to_le_bytes()
                }
            })
            .collect();
        let fb: Vec<u8> = faces
            .iter()
            .flat_map(|&x| {
                if big {
                    x.to_be_bytes()
                } else {
                    x.to_le_bytes()
                }
            })
            .collect();
        (b64(&pb, gz), b64(&fb, gz))
    };
    vec![
        Array(
            "NIFTI_INTENT_POINTSET",
            "NIFTI_TYPE_FLOAT32",
            &[4, 3],
            enc_static(enc),
            endian,
            order,
            p,
        ),
        Array(
            "NIFTI_INTENT_TRIANGLE",
            "NIFTI_TYPE_INT32",
            &[2, 3],
            enc_static(enc),
            endian,
            order,
            f,
        ),
    ]
}

fn enc_static(enc: &str) -> &'static str {
    match enc {
        "ASCII" => "ASCII",
        "Base64Binary" => "Base64Binary",
        _ => "GZipBase64Binary",
    }
}

#[test]
fn gifti_every_encoding_byte_order_and_layout() {
    for enc in ["ASCII", "Base64Binary", "GZipBase64Binary"] {
        for big in [false, true] {
            for column_major in [false, true] {
                let bytes = gifti(&square_arrays(enc, big, column_major));
                let loaded = read_mesh_from_bytes(&bytes, Format::Gifti)
                    .unwrap_or_else(|e| panic!("{enc} big={big} col={column_major}: {e}"));
                assert_eq!(
                    loaded.mesh.positions(),
                    &SQUARE,
                    "{enc} {big} {column_major}"
                );
                assert_eq!(loaded.mesh.faces(), &[[0, 1, 2], [0, 2, 3]]);
                let t = &loaded.source.surface.as_ref().unwrap().transforms[0];
                assert_eq!(t.transformed_space, "NIFTI_XFORM_TALAIRACH");
                assert_eq!(t.matrix[1][3], 20.0);
            }
        }
    }
}

/// The error of reading `bytes` as `format`, which must be `Malformed`.
fn malformed(bytes: &[u8], format: Format) -> (Place, String, &'static str) {
    match read_mesh_from_bytes(bytes, format) {
        Err(e @ IoError::Malformed { .. }) => {
            let (msg, hint) = (e.to_string(), e.hint());
            assert!(msg.starts_with("<memory>: "), "{msg}");
            assert!(hint.len() > 30, "{hint}");
            let IoError::Malformed { place, .. } = e else {
                unreachable!()
            };
            (place, msg, hint)
        }
        other => panic!("expected Malformed, got {other:?}"),
    }
}

#[test]
fn corrupt_gifti_names_the_array() {
    let mut arrays = square_arrays("Base64Binary", false, false);
    arrays[0].6 = "not*base64!".repeat(10);
    let (place, msg, _) = malformed(&gifti(&arrays), Format::Gifti);
    assert_eq!(place, Place::DataArray(0));
    assert!(msg.contains("not valid base64"), "{msg}");

    let mut arrays = square_arrays("GZipBase64Binary", false, false);
    arrays[1].2 = &[2, 4];
    let (place, msg, _) = malformed(&gifti(&arrays), Format::Gifti);
    assert_eq!(place, Place::DataArray(1));
    assert!(msg.contains("dimensions"), "{msg}");

    // the dimensions claim more data than the text holds
    let mut arrays = square_arrays("GZipBase64Binary", false, false);
    arrays[0].2 = &[5, 3];
    let (place, msg, _) = malformed(&gifti(&arrays), Format::Gifti);
    assert_eq!(place, Place::DataArray(0));
    assert!(msg.contains("bytes"), "{msg}");

    // a gzip array claiming far more than its text can inflate to is refused unread
    let mut arrays = square_arrays("GZipBase64Binary", false, false);
    arrays[0].2 = &[1_000_000_000, 3];
    let (place, msg, _) = malformed(&gifti(&arrays), Format::Gifti);
    assert_eq!(place, Place::DataArray(0));
    assert!(msg.contains("more than the"), "{msg}");

    let arrays = square_arrays("ASCII", false, false);
    let (place, msg, hint) = malformed(&gifti(&arrays[..1]), Format::Gifti);
    assert_eq!(place, Place::File);
    assert!(msg.contains("NIFTI_INTENT_TRIANGLE"), "{msg}");
    assert!(hint.contains(".surf.gii"), "{hint}");

    let (place, _, _) = malformed(b"<?xml version=\"1.0\"?><GIFTI><DataArray", Format::Gifti);
    assert!(
        matches!(place, Place::Byte { .. } | Place::File),
        "{place:?}"
    );
}

#[test]
fn truncated_and_corrupt_binary_files_name_the_byte() {
    let dir = common::out_dir("formats_bad");
    let p = SQUARE;
    let f = [[0, 1, 2], [0, 2, 3]];
    let ply = dir.join("sq.ply");
    write_flat(&ply, &p, &f).unwrap();
    let bytes = std::fs::read(&ply).unwrap();
    let header = bytes
        .windows(11)
        .position(|w| w == b"end_header\n")
        .unwrap()
        + 11;
    // cut inside vertex data, inside face data
    let (place, msg, _) = malformed(&bytes[..header + 30], Format::Ply);
    assert!(
        matches!(place, Place::Byte { offset, .. } if offset == header as u64),
        "{place:?} {msg}"
    );
    let cut = bytes.len() - 5;
    let (place, msg, _) = malformed(&bytes[..cut], Format::Ply);
    assert!(
        matches!(&place, Place::Byte { element, .. } if element == "face 1"),
        "{place:?} {msg}"
    );
    // a header that claims a billion vertices is refused before allocating
    let huge = String::from_utf8_lossy(&bytes[..header])
        .replace("element vertex 4", "element vertex 1000000000");
    let mut big = huge.into_bytes();
    big.extend_from_slice(&bytes[header..]);
    let (_, msg, _) = malformed(&big, Format::Ply);
    assert!(msg.contains("declares 1000000000"), "{msg}");
    // a face index past the vertices
    let mut bad = bytes.clone();
    let last = bad.len() - 4;
    bad[last..].copy_from_slice(&9i32.to_le_bytes());
    let (_, msg, _) = malformed(&bad, Format::Ply);
    assert!(msg.contains("face 1 refers to vertex 9"), "{msg}");
    let (place, _, _) = malformed(
        b"ply\nformat binary_middle_endian 1.0\nend_header\n",
        Format::Ply,
    );
    assert_eq!(place, Place::Line(2));

    // FreeSurfer: bad magic, truncated triangles
    let fs = dir.join("lh.sq.white");
    write_flat(&fs, &p, &f).unwrap();
    let bytes = std::fs::read(&fs).unwrap();
    let mut wrong = bytes.clone();
    wrong[2] = 0xfd;
    let (place, msg, hint) = malformed(&wrong, Format::FreeSurfer);
    assert_eq!(
        place,
        Place::Byte {
            offset: 0,
            element: String::new()
        }
    );
    assert!(
        msg.contains("FF FF FE") && hint.contains("FF FF FE"),
        "{msg}"
    );
    // the counts are held against the bytes present before anything is allocated
    let (place, msg, _) = malformed(&bytes[..bytes.len() - 2], Format::FreeSurfer);
    assert!(matches!(place, Place::Byte { offset: 33, .. }), "{place:?}");
    assert!(msg.contains("declares 72 bytes"), "{msg}");
    // a triangle index past the vertices
    let mut bad = bytes.clone();
    let at = bytes.len() - 4;
    bad[at..].copy_from_slice(&7i32.to_be_bytes());
    let (place, msg, _) = malformed(&bad, Format::FreeSurfer);
    assert!(
        matches!(&place, Place::Byte { element, offset } if element == "triangle 1" && *offset == at as u64),
        "{place:?}"
    );
    assert!(msg.contains("index 7"), "{msg}");

    // STL: a binary file whose count claims more facets than it holds (and no `solid`)
    let mut stl = vec![0u8; 80];
    stl.extend_from_slice(&1000u32.to_le_bytes());
    stl.extend_from_slice(&[0u8; 50]);
    let (_, msg, _) = malformed(&stl, Format::Stl);
    assert!(msg.contains("declares 1000 facets"), "{msg}");
    let ascii =
        b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\n";
    let (place, msg, _) = malformed(ascii, Format::Stl);
    assert_eq!(place, Place::Line(2));
    assert!(msg.contains("2 vertices"), "{msg}");
    let (place, _, _) = malformed(
        b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n",
        Format::Stl,
    );
    assert_eq!(place, Place::Line(4));

    // OFF: fewer lines than counted, an index out of range
    let (place, msg, _) = malformed(b"OFF\n3 1 0\n0 0 0\n1 0 0\n", Format::Off);
    assert_eq!(place, Place::Line(4));
    assert!(msg.contains("vertex 2"), "{msg}");
    let (place, msg, _) = malformed(b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", Format::Off);
    assert_eq!(place, Place::Line(6));
    assert!(msg.contains("out of range"), "{msg}");
}

#[test]
fn gifti_data_arrays_are_not_surfaces() {
    let dir = common::out_dir("gifti_data");
    let out = dir.join("q.shape.gii");
    conformap_io::write_vertex_data(&out, &[("angle", &[1.0, 2.0]), ("area", &[0.5, -0.5])])
        .unwrap();
    let text = std::fs::read_to_string(&out).unwrap();
    assert_eq!(text.matches("<DataArray").count(), 2);
    let err = conformap_io::read_mesh(&out).unwrap_err();
    assert!(
        err.to_string().contains("no NIFTI_INTENT_POINTSET"),
        "{err}"
    );
    // columns of different lengths write nothing
    let bad = dir.join("bad.func.gii");
    assert!(conformap_io::write_vertex_data(&bad, &[("a", &[1.0]), ("b", &[])]).is_err());
    assert!(!bad.exists());
}
