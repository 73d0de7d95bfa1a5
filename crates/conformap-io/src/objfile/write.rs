//! OBJ writing. Numbers use Rust's shortest round-trip formatting (`{:?}` on `f64`), so
//! reading the file back gives the same bits.

use std::fmt::Write as _;

/// `v` lines and 1-based `f a b c` lines.
pub(crate) fn encode_obj(points: &[[f64; 3]], faces: &[[u32; 3]]) -> Vec<u8> {
    let mut s = String::with_capacity(40 * points.len() + 24 * faces.len() + 64);
    let _ = writeln!(
        s,
        "# conformap-io: {} vertices, {} faces",
        points.len(),
        faces.len()
    );
    push_vertices(&mut s, points);
    for f in faces {
        let _ = writeln!(s, "f {} {} {}", f[0] + 1, f[1] + 1, f[2] + 1);
    }
    s.into_bytes()
}

/// `v` lines, one `vt` per vertex (same order), and `f a/a b/b c/c` lines.
pub(crate) fn encode_obj_with_uv(
    points: &[[f64; 3]],
    uv: &[[f64; 2]],
    faces: &[[u32; 3]],
) -> Vec<u8> {
    let mut s = String::with_capacity(70 * points.len() + 40 * faces.len() + 64);
    let _ = writeln!(
        s,
        "# conformap-io: {} vertices, {} faces, one vt per vertex (vt k belongs to v k)",
        points.len(),
        faces.len()
    );
    push_vertices(&mut s, points);
    for t in uv {
        let _ = writeln!(s, "vt {:?} {:?}", t[0], t[1]);
    }
    for f in faces {
        let (a, b, c) = (f[0] + 1, f[1] + 1, f[2] + 1);
        let _ = writeln!(s, "f {a}/{a} {b}/{b} {c}/{c}");
    }
    s.into_bytes()
}

fn push_vertices(s: &mut String, points: &[[f64; 3]]) {
    for p in points {
        let _ = writeln!(s, "v {:?} {:?} {:?}", p[0], p[1], p[2]);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    #[test]
    fn shortest_round_trip_formatting() {
        let text = encode_obj(&[[0.1, -0.0, 1e-300], [1e300, 3.0, 2.5e-7]], &[]);
        let text = String::from_utf8(text).unwrap_or_default();
        assert!(text.contains("v 0.1 -0.0 1e-300\n"), "{text}");
        assert!(text.contains("v 1e300 3.0 2.5e-7\n"), "{text}");
    }
}
