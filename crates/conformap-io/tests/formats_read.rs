//! PLY, STL, OFF, GIfTI and FreeSurfer: hand-made files in every encoding and byte order,
//! files converted from the OBJ fixtures (read back as the OBJ's mesh), and round trips
//! through the writers (write → read → the same numbers).
#![allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test

mod common;

use common::{fixture, out_dir, planar_uv};
use conformap_io::{
    read_mesh, read_mesh_from_bytes, write_flat, write_flat_like, write_mesh_with_corner_uv,
    write_mesh_with_uv, CornerUv, Format, SPHERE_RADIUS,
};

/// A unit square (two triangles) as a PLY header and body for the given format line,
/// with an extra `red` property and an `edge` element that must be skipped.
fn square_ply(format: &str, vertex_type: &str, index_types: &str, body: &[u8]) -> Vec<u8> {
    let mut out = format!(
        "ply\nformat {format} 1.0\ncomment made by hand\nelement vertex 4\n\
         property {vertex_type} x\nproperty uchar red\nproperty {vertex_type} y\n\
         property {vertex_type} z\nelement face 1\nproperty list {index_types} vertex_index\n\
         element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n"
    )
    .into_bytes();
    out.extend_from_slice(body);
    out
}

const SQUARE: [[f64; 3]; 4] = [
    [0.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 0.0],
];

#[test]
fn ply_ascii_and_binary_in_both_byte_orders() {
    let ascii = square_ply(
        "ascii",
        "float",
        "uchar int",
        b"0 7 0 0\n1 7 0 0\n1 7 1 0\n0 7 1 0\n4 0 1 2 3\n0 1\n",
    );
    for big in [false, true] {
        // x, red, y, z as double / uchar; the quad as ushort count, uint indices
        let mut body = Vec::new();
        for p in SQUARE {
            let (x, y, z) = (p[0], p[1], p[2]);
            for (k, v) in [x, 7.0, y, z].into_iter().enumerate() {
                if k == 1 {
                    body.push(7u8);
                } else if big {
                    body.extend_from_slice(&v.to_be_bytes());
                } else {
                    body.extend_from_slice(&v.to_le_bytes());
                }
            }
        }
        let words: Vec<[u8; 4]> = [0u32, 1, 2, 3, 0, 1]
            .iter()
            .map(|i| {
                if big {
                    i.to_be_bytes()
                } else {
                    i.to_le_bytes()
                }
            })
            .collect();
        body.extend_from_slice(&if big {
            4u16.to_be_bytes()
        } else {
            4u16.to_le_bytes()
        });
        // four indices, then the edge's two ints
        words.iter().for_each(|w| body.extend_from_slice(w));
        let format = if big {
            "binary_big_endian"
        } else {
            "binary_little_endian"
        };
        let ply = square_ply(format, "double", "ushort uint", &body);
        let loaded = read_mesh_from_bytes(&ply, Format::Ply).unwrap();
        assert_eq!(loaded.mesh.positions(), &SQUARE, "{format}");
        assert_eq!(loaded.mesh.faces(), &[[0, 1, 2], [0, 2, 3]], "{format}");
        assert!(loaded.source.notes.iter().any(|n| n.contains("edge")));
    }
    let loaded = read_mesh_from_bytes(&ascii, Format::Ply).unwrap();
    assert_eq!(loaded.mesh.positions(), &SQUARE);
    assert_eq!(loaded.mesh.faces(), &[[0, 1, 2], [0, 2, 3]]);
}

#[test]
fn ply_round_trips_per_vertex_and_per_corner_maps_exactly() {
    let dir = out_dir("ply_round_trip");
    let obj = read_mesh(fixture("woody.obj")).unwrap();
    let uv = planar_uv(obj.mesh.positions());
    let out = dir.join("woody.ply");
    write_mesh_with_uv(&out, &obj.mesh, &uv, None).unwrap();
    let back = read_mesh(&out).unwrap();
    assert_eq!(back.mesh.positions(), obj.mesh.positions());
    assert_eq!(back.mesh.faces(), obj.mesh.faces());
    assert_eq!(back.per_vertex_uv().unwrap(), uv.as_slice());
    // a seamed map: every face's corners get their own coordinates
    let corner = CornerUv {
        texcoords: (0..3 * obj.mesh.num_faces())
            .map(|c| [c as f64 / 7.0, 1.0 / (c as f64 + 1.0)])
            .collect(),
        faces: (0..obj.mesh.num_faces() as u32)
            .map(|f| [3 * f, 3 * f + 1, 3 * f + 2])
            .collect(),
    };
    let seamed = dir.join("seamed.ply");
    write_mesh_with_corner_uv(&seamed, &obj.mesh, &corner).unwrap();
    let back = read_mesh(&seamed).unwrap();
    assert_eq!(back.mesh.positions(), obj.mesh.positions());
    assert_eq!(back.corner_uv.as_ref(), Some(&corner));
}

/// `positions` and `faces` as ASCII and binary STL (float32, as STL stores them).
fn stl_files(p: &[[f64; 3]], f: &[[u32; 3]]) -> (Vec<u8>, Vec<u8>) {
    let mut binary = b"solid but binary: the size decides".to_vec();
    binary.resize(80, b' ');
    binary.extend_from_slice(&(f.len() as u32).to_le_bytes());
    let mut ascii = String::from("solid fixture\n");
    for t in f {
        binary.extend_from_slice(&[0u8; 12]);
        ascii.push_str("  facet normal 0 0 1\n    outer loop\n");
        for &i in t {
            let q = p[i as usize].map(|x| x as f32);
            q.iter()
                .for_each(|x| binary.extend_from_slice(&x.to_le_bytes()));
            ascii.push_str(&format!("      vertex {:e} {:e} {:e}\n", q[0], q[1], q[2]));
        }
        binary.extend_from_slice(&[0, 0]);
        ascii.push_str("    endloop\n  endfacet\n");
    }
    ascii.push_str("endsolid fixture\n");
    (ascii.into_bytes(), binary)
}

#[test]
fn stl_welds_into_the_obj_mesh_in_order_of_first_appearance() {
    let obj = read_mesh(fixture("woody.obj")).unwrap();
    let (ascii, binary) = stl_files(obj.mesh.positions(), obj.mesh.faces());
    // the order of first appearance over the faces
    let mut order = vec![u32::MAX; obj.mesh.num_vertices()];
    let mut seen = Vec::new();
    for &v in obj.mesh.faces().iter().flatten() {
        if order[v as usize] == u32::MAX {
            order[v as usize] = seen.len() as u32;
            seen.push(v as usize);
        }
    }
    for (bytes, is_ascii) in [(ascii, true), (binary, false)] {
        let stl = read_mesh_from_bytes(&bytes, Format::Stl).unwrap();
        assert_eq!(stl.mesh.num_vertices(), obj.mesh.num_vertices());
        for (k, &v) in seen.iter().enumerate() {
            // ASCII holds the f32's decimal text, read as f64; binary the f32 itself
            let want = obj.mesh.positions()[v].map(|x| match is_ascii {
                true => format!("{:e}", x as f32).parse().unwrap(),
                false => f64::from(x as f32),
            });
            assert_eq!(stl.mesh.positions()[k], want);
        }
        let want: Vec<[u32; 3]> = obj
            .mesh
            .faces()
            .iter()
            .map(|f| f.map(|v| order[v as usize]))
            .collect();
        assert_eq!(stl.mesh.faces(), want.as_slice());
        let map = stl.source.weld_map.as_ref().unwrap();
        assert_eq!(map.len(), 3 * obj.mesh.num_faces());
        let welded = 3 * obj.mesh.num_faces() - obj.mesh.num_vertices();
        assert!(
            stl.source.notes[0].contains(&format!("({welded} welded)")),
            "{:?}",
            stl.source.notes
        );
    }
}

#[test]
fn off_headers_comments_and_polygons() {
    let text = b"# a comment\nCOFF 4 1 0\n0 0 0 255 0 0 255\n1 0 0 255 0 0 255 # red\n\n\
                 1 1 0 1 1 1 1\n0 1 0 1 1 1 1\n4 0 1 2 3 255 255 255\n";
    let loaded = read_mesh_from_bytes(text, Format::Off).unwrap();
    assert_eq!(loaded.mesh.positions(), &SQUARE);
    assert_eq!(loaded.mesh.faces(), &[[0, 1, 2], [0, 2, 3]]);
    for header in [
        "OFF\n4 1 0\n",
        "NOFF\n4 1 0\n",
        "STOFF 4 1 0\n",
        "CNOFF\n4 1 0\n",
    ] {
        let text = format!("{header}0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n");
        let loaded = read_mesh_from_bytes(text.as_bytes(), Format::Off);
        // vertex 3 is unused: the raw read works, validation names it
        assert!(
            matches!(&loaded, Err(conformap_io::IoError::InvalidMesh { origin: Some(o), .. }) if o.to_string() == "vertex 3"),
            "{header}: {loaded:?}"
        );
    }
    // the OBJ fixture written as OFF reads as the OBJ's mesh, bit for bit
    let obj = read_mesh(fixture("woody.obj")).unwrap();
    let mut off = format!(
        "OFF\n{} {} 0\n",
        obj.mesh.num_vertices(),
        obj.mesh.num_faces()
    );
    obj.mesh
        .positions()
        .iter()
        .for_each(|p| off.push_str(&format!("{:?} {:?} {:?}\n", p[0], p[1], p[2])));
    obj.mesh
        .faces()
        .iter()
        .for_each(|f| off.push_str(&format!("3 {} {} {}\n", f[0], f[1], f[2])));
    let back = read_mesh_from_bytes(off.as_bytes(), Format::Off).unwrap();
    assert_eq!(back.mesh.positions(), obj.mesh.positions());
    assert_eq!(back.mesh.faces(), obj.mesh.faces());
}

#[test]
fn gifti_and_freesurfer_round_trips_keep_order_and_float32_values() {
    let dir = out_dir("surface_round_trip");
    let obj = read_mesh(fixture("woody.obj")).unwrap();
    let as_f32 = |p: &[[f64; 3]]| -> Vec<[f64; 3]> {
        p.iter().map(|q| q.map(|x| f64::from(x as f32))).collect()
    };
    let want = as_f32(obj.mesh.positions());
    // a flat map is written as it is given (z = 0 stays 0)
    for name in ["woody.surf.gii", "lh.woody.white"] {
        let out = dir.join(name);
        write_flat(&out, obj.mesh.positions(), obj.mesh.faces()).unwrap();
        let back = read_mesh(&out).unwrap();
        assert_eq!(back.mesh.positions(), want.as_slice(), "{name}");
        assert_eq!(back.mesh.faces(), obj.mesh.faces(), "{name}");
    }
    // a FreeSurfer surface without a known extension is found by its magic
    let fs = dir.join("lh.woody.white");
    let bare = dir.join("lh.woody");
    std::fs::copy(&fs, &bare).unwrap();
    let back = read_mesh(&bare).unwrap();
    assert_eq!(back.source.format, Format::FreeSurfer);
    assert_eq!(
        back.source.surface.as_ref().unwrap().created_by.as_deref(),
        Some("created by conformap")
    );
    // a volume-geometry footer is kept by write_flat_like
    let mut with_footer = std::fs::read(&fs).unwrap();
    let footer =
        b"\x00\x00\x00\x02\x00\x00\x00\x00\x00\x00\x00\x14valid = 1  # volume info valid\n";
    with_footer.extend_from_slice(footer);
    std::fs::write(&bare, &with_footer).unwrap();
    let read = read_mesh(&bare).unwrap();
    assert_eq!(
        read.source.surface.as_ref().unwrap().volume_info.as_deref(),
        Some(&footer[..])
    );
    let again = dir.join("rh.again.white");
    write_flat_like(
        &again,
        read.mesh.positions(),
        read.mesh.faces(),
        Some(&read.source),
    )
    .unwrap();
    assert_eq!(std::fs::read(&again).unwrap(), with_footer);
}

#[test]
fn sphere_maps_are_written_at_radius_100() {
    let dir = out_dir("sphere_radius");
    // an octahedron on the unit sphere
    let p = [
        [1.0, 0.0, 0.0],
        [-1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, -1.0, 0.0],
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
    ];
    let f = [
        [0, 2, 4],
        [2, 1, 4],
        [1, 3, 4],
        [3, 0, 4],
        [2, 0, 5],
        [1, 2, 5],
        [3, 1, 5],
        [0, 3, 5],
    ];
    for name in ["s.surf.gii", "lh.s.sphere"] {
        let out = dir.join(name);
        write_flat(&out, &p, &f).unwrap();
        let back = read_mesh(&out).unwrap();
        for (a, b) in back.mesh.positions().iter().zip(&p) {
            assert_eq!(*a, b.map(|x| x * SPHERE_RADIUS), "{name}");
        }
        assert_eq!(back.mesh.faces(), &f);
    }
    // OBJ keeps the unit sphere
    let out = dir.join("s.obj");
    write_flat(&out, &p, &f).unwrap();
    assert_eq!(read_mesh(&out).unwrap().mesh.positions(), &p);
}

/// A GIfTI surface whose arrays spell their encoding and byte order by gifticlib's code
/// names (`GIFTI_ENCODING_B64BIN`, `GIFTI_ENDIAN_BIG`), as nibabel's own test file
/// `base64bin.gii` does; nibabel reads such files, so must we.
#[test]
fn gifti_encodings_by_their_code_names() {
    use base64::Engine as _;
    let b64 = |bytes: Vec<u8>| base64::engine::general_purpose::STANDARD.encode(bytes);
    let points: [f32; 12] = [0., 0., 0., 1., 0., 0., 1., 1., 0., 0., 1., 0.];
    let array = |intent: &str, ty: &str, dim0: usize, encoding: &str, endian: &str, data: &str| {
        format!(
            "<DataArray Intent=\"{intent}\" DataType=\"{ty}\" ArrayIndexingOrder=\"RowMajorOrder\" \
             Dimensionality=\"2\" Dim0=\"{dim0}\" Dim1=\"3\" Encoding=\"{encoding}\" \
             Endian=\"{endian}\" ExternalFileName=\"\" ExternalFileOffset=\"\">\
             <MetaData/><Data>{data}</Data></DataArray>"
        )
    };
    let big: Vec<u8> = points.iter().flat_map(|x| x.to_be_bytes()).collect();
    let text = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<GIFTI Version=\"1.0\" NumberOfDataArrays=\"2\">\
         <MetaData/>{}{}</GIFTI>\n",
        array("NIFTI_INTENT_POINTSET", "NIFTI_TYPE_FLOAT32", 4, "GIFTI_ENCODING_B64BIN",
              "GIFTI_ENDIAN_BIG", &b64(big)),
        array("NIFTI_INTENT_TRIANGLE", "NIFTI_TYPE_INT32", 2, "GIFTI_ENCODING_ASCII",
              "GIFTI_ENDIAN_LITTLE", "0 1 2 0 2 3"),
    );
    let mesh = read_mesh_from_bytes(text.as_bytes(), Format::Gifti)
        .unwrap()
        .mesh;
    assert_eq!(mesh.positions()[2], [1.0, 1.0, 0.0]);
    assert_eq!(mesh.faces(), &[[0, 1, 2], [0, 2, 3]]);
}

/// A binary PLY of the unit square's corners and `faces` (uchar counts, `index_type` 4-byte
/// indices written from `i64`s), in either byte order.
fn ply_faces(big: bool, index_type: &str, faces: &[&[i64]]) -> Vec<u8> {
    let format = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut out = format!(
        "ply\nformat {format} 1.0\nelement vertex 4\nproperty float x\nproperty float y\n\
         property float z\nelement face {}\nproperty list uchar {index_type} vertex_indices\n\
         end_header\n",
        faces.len()
    )
    .into_bytes();
    for p in SQUARE {
        for v in p {
            let v = v as f32;
            out.extend_from_slice(&if big {
                v.to_be_bytes()
            } else {
                v.to_le_bytes()
            });
        }
    }
    for f in faces {
        out.push(f.len() as u8);
        for &i in *f {
            let w = i as u32;
            out.extend_from_slice(&if big {
                w.to_be_bytes()
            } else {
                w.to_le_bytes()
            });
        }
    }
    out
}

#[test]
fn ply_triangle_runs_hand_over_to_the_general_reader() {
    for big in [false, true] {
        for index_type in ["int", "uint"] {
            // triangles, then a quad (fanned), then triangles again
            let ply = ply_faces(big, index_type, &[&[0, 1, 2], &[0, 1, 2, 3], &[3, 2, 1]]);
            let raw = conformap_io::read_raw_mesh_from_bytes(&ply, Format::Ply).unwrap();
            assert_eq!(
                raw.faces,
                vec![[0, 1, 2], [0, 1, 2], [0, 2, 3], [3, 2, 1]],
                "{index_type} big={big}"
            );
            // an index no vertex has, after a run of triangles: named by its face
            let ply = ply_faces(big, index_type, &[&[0, 1, 2], &[0, 1, 2], &[0, -1, 2]]);
            let e = conformap_io::read_raw_mesh_from_bytes(&ply, Format::Ply)
                .unwrap_err()
                .to_string();
            assert!(e.contains("face 2"), "{e}");
            // a file cut inside its last triangle
            let ply = ply_faces(big, index_type, &[&[0, 1, 2], &[0, 2, 3]]);
            let e = conformap_io::read_raw_mesh_from_bytes(&ply[..ply.len() - 2], Format::Ply)
                .unwrap_err()
                .to_string();
            assert!(e.contains("face 1"), "{e}");
        }
    }
}
