//! Our own pass over an OBJ text: line numbers, statement checks, face indices.
//!
//! `tobj` parses the numbers but reports no line numbers, compacts vertices per object in
//! first-use order, and trusts face indices (an out-of-range texture index can overflow its
//! index arithmetic). So before `tobj` sees the text, this pass checks every statement and
//! every face index, resolves negative (relative) indices, fan-triangulates polygons while
//! remembering each triangle's line, and prepares the text `tobj` is given (see
//! [`Scan::tobj_text`]). Run again with `check_numbers` after `tobj` rejects a number, it
//! finds the first offending line.

use std::fmt::Write as _;
use std::num::FpCategory;

use crate::error::ObjProblem;

/// Marks a face corner without a texture coordinate.
pub(crate) const NO_UV: u32 = u32::MAX;

/// Statements that are valid OBJ but carry nothing this reader uses.
const IGNORED: &[&str] = &[
    "o",
    "g",
    "s",
    "mg",
    "usemtl",
    "mtllib",
    "usemap",
    "maplib",
    "lod",
    "bevel",
    "c_interp",
    "d_interp",
    "shadow_obj",
    "trace_obj",
    "vp",
];
/// Free-form geometry and point/line elements: valid OBJ, ignored with a note.
const IGNORED_NOTED: &[&str] = &[
    "p", "l", "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole",
    "scrv", "sp", "end", "con", "ctech", "stech",
];

/// Result of [`scan`].
#[derive(Debug, Default)]
pub(crate) struct Scan {
    /// 1-based line of each `v`.
    pub vertex_lines: Vec<usize>,
    /// Triangles, 0-based global vertex indices (polygons fan-triangulated).
    pub faces: Vec<[u32; 3]>,
    /// 0-based global `vt` index of each triangle corner, [`NO_UV`] if none.
    pub face_uv: Vec<[u32; 3]>,
    /// 1-based line of each triangle.
    pub face_lines: Vec<usize>,
    /// Ignored statements worth telling the user about.
    pub notes: Vec<String>,
    /// What `tobj` parses: first one synthetic polygon `f 1 2 … N` that makes `tobj`
    /// number the vertices in file order (it numbers them by first use), then the file's
    /// `v` (colours dropped), `vt` and `f` lines in order. Normals, groups, objects and
    /// materials are left out, so `tobj` returns a single model.
    pub tobj_text: String,
    /// Number of triangles the synthetic polygon yields (`max(N, 3) − 2`, 0 if N = 0).
    pub synthetic_triangles: usize,
}

/// Scans `text` (UTF-8, BOM already removed). With `check_numbers`, also parses every value
/// of `v`/`vt`/`vn` lines, so the first line `tobj` would reject is found.
///
/// # Errors
/// The first offending 1-based line and what is wrong with it.
pub(crate) fn scan(text: &str, check_numbers: bool) -> Result<Scan, (usize, ObjProblem)> {
    let (nv, nvt, nvn) = count_elements(text);
    let mut s = Scan::default();
    s.tobj_text.reserve(text.len() + 16 * nv);
    if nv > 0 {
        s.tobj_text.push('f');
        for k in 1..=nv.max(3) {
            let _ = write!(s.tobj_text, " {}", k.min(nv));
        }
        s.tobj_text.push('\n');
        s.synthetic_triangles = nv.max(3) - 2;
    }
    let (mut seen_v, mut seen_vt, mut seen_vn) = (0usize, 0usize, 0usize);
    let mut noted = 0usize;
    let mut corners: Vec<(u32, u32)> = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let lineno = i + 1;
        let mut words = line.split_whitespace();
        let Some(keyword) = words.next() else {
            continue;
        };
        let values: Vec<&str> = match keyword {
            "v" | "vt" | "vn" => words.by_ref().collect(),
            _ => Vec::new(),
        };
        match keyword {
            "v" => {
                check_values("v", &values, &[3, 4, 6], check_numbers).map_err(|p| (lineno, p))?;
                if check_numbers && values.len() == 4 && is_zero(values[3]) {
                    return Err((lineno, bad_number("v")));
                }
                // colours (x y z r g b) are dropped: tobj fails on files mixing both forms
                let kept = if values.len() == 6 { 3 } else { values.len() };
                s.tobj_text.push('v');
                for v in &values[..kept] {
                    s.tobj_text.push(' ');
                    s.tobj_text.push_str(v);
                }
                s.tobj_text.push('\n');
                s.vertex_lines.push(lineno);
                seen_v += 1;
            }
            "vt" => {
                check_values("vt", &values, &[2, 3], check_numbers).map_err(|p| (lineno, p))?;
                s.tobj_text.push_str(line.trim());
                s.tobj_text.push('\n');
                seen_vt += 1;
            }
            "vn" => {
                check_values("vn", &values, &[3], check_numbers).map_err(|p| (lineno, p))?;
                seen_vn += 1;
            }
            "f" => {
                corners.clear();
                for token in words {
                    let c = parse_corner(token, (seen_v, nv), (seen_vt, nvt), (seen_vn, nvn))
                        .map_err(|p| (lineno, p))?;
                    corners.push(c);
                }
                if corners.len() < 3 {
                    return Err((
                        lineno,
                        ObjProblem::TooFewCorners {
                            found: corners.len(),
                        },
                    ));
                }
                for w in 1..corners.len() - 1 {
                    let (a, b, c) = (corners[0], corners[w], corners[w + 1]);
                    s.faces.push([a.0, b.0, c.0]);
                    s.face_uv.push([a.1, b.1, c.1]);
                    s.face_lines.push(lineno);
                }
                s.tobj_text.push_str(line.trim());
                s.tobj_text.push('\n');
            }
            k if k.starts_with('#') || IGNORED.contains(&k) => {}
            k if IGNORED_NOTED.contains(&k) => noted += 1,
            k => {
                return Err((
                    lineno,
                    ObjProblem::UnknownStatement {
                        keyword: k.chars().take(40).collect(),
                    },
                ))
            }
        }
    }
    if noted > 0 {
        s.notes.push(format!(
            "{noted} point, line or free-form statement(s) ignored (only faces are read)"
        ));
    }
    Ok(s)
}

/// Counts `v`, `vt`, `vn` lines (positive indices may refer forward, as `tobj` allows).
fn count_elements(text: &str) -> (usize, usize, usize) {
    let (mut v, mut vt, mut vn) = (0, 0, 0);
    for line in text.lines() {
        match line.split_whitespace().next() {
            Some("v") => v += 1,
            Some("vt") => vt += 1,
            Some("vn") => vn += 1,
            _ => {}
        }
    }
    (v, vt, vn)
}

fn bad_number(keyword: &str) -> ObjProblem {
    ObjProblem::BadNumber {
        keyword: keyword.to_owned(),
    }
}

fn check_values(
    keyword: &str,
    values: &[&str],
    allowed: &[usize],
    check_numbers: bool,
) -> Result<(), ObjProblem> {
    if !allowed.contains(&values.len()) {
        return Err(ObjProblem::WrongValueCount {
            keyword: keyword.to_owned(),
            found: values.len(),
        });
    }
    if check_numbers && values.iter().any(|v| v.parse::<f64>().is_err()) {
        return Err(bad_number(keyword));
    }
    Ok(())
}

fn is_zero(token: &str) -> bool {
    token
        .parse::<f64>()
        .is_ok_and(|w| w.classify() == FpCategory::Zero)
}

/// Parses `v`, `v/vt`, `v//vn` or `v/vt/vn`; returns the 0-based vertex and `vt` indices.
/// Each `(seen, total)` pair: elements defined before this line, and in the whole file.
fn parse_corner(
    token: &str,
    v: (usize, usize),
    vt: (usize, usize),
    vn: (usize, usize),
) -> Result<(u32, u32), ObjProblem> {
    let bad = || ObjProblem::BadCorner {
        token: token.chars().take(40).collect(),
    };
    let mut parts = token.split('/');
    let pv = parts.next().filter(|p| !p.is_empty()).ok_or_else(bad)?;
    let pvt = parts.next().filter(|p| !p.is_empty());
    let pvn = parts.next().filter(|p| !p.is_empty());
    if parts.next().is_some() {
        return Err(bad());
    }
    let parse = |p: &str| p.parse::<i64>().map_err(|_| bad());
    let vi = resolve(parse(pv)?, v, "vertex")?;
    let ti = match pvt {
        Some(p) => resolve(parse(p)?, vt, "texture coordinate")?,
        None => NO_UV,
    };
    if let Some(p) = pvn {
        resolve(parse(p)?, vn, "normal")?;
    }
    Ok((vi, ti))
}

/// Resolves a 1-based or negative (relative) OBJ index to a 0-based one.
fn resolve(
    index: i64,
    (seen, total): (usize, usize),
    what: &'static str,
) -> Result<u32, ObjProblem> {
    let out = |count| ObjProblem::IndexOutOfRange { what, index, count };
    let zero_based = match index {
        0 => return Err(ObjProblem::IndexZero { what }),
        i if i > 0 => {
            let k = (i - 1).unsigned_abs();
            if k >= total as u64 {
                return Err(out(total));
            }
            k
        }
        i => {
            let back = i.unsigned_abs();
            if back > seen as u64 {
                return Err(out(seen));
            }
            seen as u64 - back
        }
    };
    // NO_UV (u32::MAX) stays free: no real file has 2^32 - 1 elements
    u32::try_from(zero_based)
        .ok()
        .filter(|&k| k != NO_UV)
        .ok_or_else(|| out(total))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    #[test]
    fn negative_indices_and_fans() {
        let s = scan("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n", true).unwrap();
        assert_eq!(s.faces, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(s.face_lines, vec![5, 5]);
        assert!(s.tobj_text.starts_with("f 1 2 3 4\n"));
        assert_eq!(s.synthetic_triangles, 2);
    }

    #[test]
    fn corner_forms() {
        let text = "v 0 0 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 1//1 1/1\n";
        let s = scan(text, false).unwrap();
        assert_eq!(s.face_uv, vec![[0, NO_UV, 0]]);
        let err = scan("v 0 0 0\nf 1/1/1/1 1 1\n", false).unwrap_err();
        assert!(matches!(err, (2, ObjProblem::BadCorner { .. })));
        let err = scan("v 0 0 0\nf 1/ 1 x\n", false).unwrap_err();
        assert!(matches!(err, (2, ObjProblem::BadCorner { .. })));
    }

    #[test]
    fn hostile_indices_are_errors() {
        for idx in [
            "9223372036854775807",
            "-9223372036854775808",
            "99999999999999999999",
        ] {
            let text = format!("v 0 0 0\nvt 0 0\nf 1/{idx} 1/1 1/1\n");
            assert!(scan(&text, false).is_err(), "{idx}");
        }
    }

    #[test]
    fn numbers_checked_only_on_request() {
        let text = "v 0 0 zero\n";
        assert!(scan(text, false).is_ok());
        assert!(matches!(
            scan(text, true),
            Err((1, ObjProblem::BadNumber { .. }))
        ));
        assert!(matches!(
            scan("v 1 2 3 0\n", true),
            Err((1, ObjProblem::BadNumber { .. }))
        ));
    }
}
