//! Parsing one chunk of an OBJ text: statements checked, numbers parsed (correctly rounded,
//! `fast-float2`), face indices resolved and polygons fan-triangulated, each element with
//! its line.
//!
//! Positive indices may refer forward and negative ones count back from the elements so
//! far, so a chunk needs the counts before it and in the whole file: [`count`] gives them
//! per chunk (a cheap first pass), [`parse_chunk`] does the rest.

use super::lines::{is_blank, Lines};
use crate::error::ObjProblem;

/// Marks a face corner without a texture coordinate.
pub(crate) const NO_UV: u32 = u32::MAX;

/// Marks a vertex whose numbers cannot be copied from the file's text (a homogeneous `w`,
/// colours after the position, a continued line): the writer formats it.
pub(crate) const NO_SPAN: (usize, usize) = (usize::MAX, 0);

/// Statements that are valid OBJ but carry nothing this reader uses.
const IGNORED: &[&[u8]] = &[
    b"o",
    b"g",
    b"s",
    b"mg",
    b"usemtl",
    b"mtllib",
    b"usemap",
    b"maplib",
    b"lod",
    b"bevel",
    b"c_interp",
    b"d_interp",
    b"shadow_obj",
    b"trace_obj",
    b"vp",
];
/// Free-form geometry and point/line elements: valid OBJ, ignored with a note.
const IGNORED_NOTED: &[&[u8]] = &[
    b"p", b"l", b"cstype", b"deg", b"bmat", b"step", b"curv", b"curv2", b"surf", b"parm", b"trim",
    b"hole", b"scrv", b"sp", b"end", b"con", b"ctech", b"stech",
];

/// Lines, `v`/`vt`/`vn` statements and the triangles of the `f` statements (corners − 2
/// each) of a chunk, or, summed, of the text before it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(crate) struct Counts {
    pub(crate) lines: usize,
    pub(crate) v: usize,
    pub(crate) vt: usize,
    pub(crate) vn: usize,
    pub(crate) tri: usize,
}

impl Counts {
    pub(crate) fn add(self, o: Self) -> Self {
        Self {
            lines: self.lines + o.lines,
            v: self.v + o.v,
            vt: self.vt + o.vt,
            vn: self.vn + o.vn,
            tri: self.tri + o.tri,
        }
    }
}

/// What a text yields; line numbers are the file's (1-based).
#[derive(Debug, Default)]
pub(crate) struct Parsed {
    pub(crate) positions: Vec<[f64; 3]>,
    pub(crate) vertex_lines: Vec<usize>,
    /// Per vertex, the byte range `(start, len)` in the text of its three numbers as
    /// written (`x y z`, parsed by the fast path), or [`NO_SPAN`].
    pub(crate) vertex_spans: Vec<(usize, usize)>,
    pub(crate) texcoords: Vec<[f64; 2]>,
    /// Triangles, 0-based global vertex indices.
    pub(crate) faces: Vec<[u32; 3]>,
    /// 0-based global `vt` index of each triangle corner, [`NO_UV`] if none; empty when the
    /// text has no `vt` at all.
    pub(crate) face_uv: Vec<[u32; 3]>,
    pub(crate) face_lines: Vec<usize>,
    /// Point, line and free-form statements ignored.
    pub(crate) noted: usize,
    /// The first offending line; parsing stops there.
    pub(crate) error: Option<(usize, ObjProblem)>,
}

impl Parsed {
    /// Room for exactly what `total` counts (the parse fills it in place, no growth and no
    /// concatenation of per-chunk pieces).
    pub(crate) fn with_counts(total: Counts) -> Self {
        Self {
            positions: vec![[0.0; 3]; total.v],
            vertex_lines: vec![0; total.v],
            vertex_spans: vec![NO_SPAN; total.v],
            texcoords: vec![[0.0; 2]; total.vt],
            faces: vec![[0; 3]; total.tri],
            face_uv: if total.vt > 0 {
                vec![[NO_UV; 3]; total.tri]
            } else {
                Vec::new()
            },
            face_lines: vec![0; total.tri],
            noted: 0,
            error: None,
        }
    }

    /// Disjoint writers, one per chunk of `own` counts, in order.
    pub(crate) fn sinks(&mut self, own: &[Counts]) -> Vec<Sink<'_>> {
        let mut out = Vec::with_capacity(own.len());
        let has_uv = !self.face_uv.is_empty();
        let (mut pos, mut vl, mut tc) = (
            &mut self.positions[..],
            &mut self.vertex_lines[..],
            &mut self.texcoords[..],
        );
        let mut sp = &mut self.vertex_spans[..];
        let (mut fc, mut fu, mut fl) = (
            &mut self.faces[..],
            &mut self.face_uv[..],
            &mut self.face_lines[..],
        );
        for c in own {
            let (a, rest) = std::mem::take(&mut pos).split_at_mut(c.v);
            pos = rest;
            let (b, rest) = std::mem::take(&mut vl).split_at_mut(c.v);
            vl = rest;
            let (spans, rest) = std::mem::take(&mut sp).split_at_mut(c.v);
            sp = rest;
            let (t, rest) = std::mem::take(&mut tc).split_at_mut(c.vt);
            tc = rest;
            let (f, rest) = std::mem::take(&mut fc).split_at_mut(c.tri);
            fc = rest;
            let (u, rest) = std::mem::take(&mut fu).split_at_mut(if has_uv { c.tri } else { 0 });
            fu = rest;
            let (l, rest) = std::mem::take(&mut fl).split_at_mut(c.tri);
            fl = rest;
            out.push(Sink {
                positions: a,
                vertex_lines: b,
                vertex_spans: spans,
                texcoords: t,
                faces: f,
                face_uv: u,
                face_lines: l,
                nv: 0,
                nvt: 0,
                nf: 0,
                noted: 0,
            });
        }
        out
    }
}

/// Where one chunk's elements go: its slices of the whole text's arrays.
pub(crate) struct Sink<'a> {
    positions: &'a mut [[f64; 3]],
    vertex_lines: &'a mut [usize],
    vertex_spans: &'a mut [(usize, usize)],
    texcoords: &'a mut [[f64; 2]],
    faces: &'a mut [[u32; 3]],
    face_uv: &'a mut [[u32; 3]],
    face_lines: &'a mut [usize],
    nv: usize,
    nvt: usize,
    nf: usize,
    /// Point, line and free-form statements ignored.
    noted: usize,
}

impl Sink<'_> {
    fn vertex(&mut self, p: [f64; 3], line: usize, span: (usize, usize)) -> Result<(), ObjProblem> {
        let (Some(slot), Some(l), Some(sp)) = (
            self.positions.get_mut(self.nv),
            self.vertex_lines.get_mut(self.nv),
            self.vertex_spans.get_mut(self.nv),
        ) else {
            return Err(ObjProblem::Miscounted);
        };
        (*slot, *l, *sp) = (p, line, span);
        self.nv += 1;
        Ok(())
    }

    fn texcoord(&mut self, t: [f64; 2]) -> Result<(), ObjProblem> {
        let slot = self
            .texcoords
            .get_mut(self.nvt)
            .ok_or(ObjProblem::Miscounted)?;
        *slot = t;
        self.nvt += 1;
        Ok(())
    }

    fn triangle(&mut self, v: [u32; 3], t: [u32; 3], line: usize) -> Result<(), ObjProblem> {
        let (Some(f), Some(l)) = (
            self.faces.get_mut(self.nf),
            self.face_lines.get_mut(self.nf),
        ) else {
            return Err(ObjProblem::Miscounted);
        };
        (*f, *l) = (v, line);
        match self.face_uv.get_mut(self.nf) {
            Some(u) => *u = t,
            // no `vt` in the text: every corner is NO_UV (an index would have failed)
            None if t == [NO_UV; 3] => {}
            None => return Err(ObjProblem::Miscounted),
        }
        self.nf += 1;
        Ok(())
    }
}

/// A chunk's outcome beyond the elements it wrote.
#[derive(Debug, Default)]
pub(crate) struct ChunkOutcome {
    /// Point, line and free-form statements ignored.
    pub(crate) noted: usize,
    /// Triangles written.
    pub(crate) triangles: usize,
    /// The chunk's first offending line; parsing stops there.
    pub(crate) error: Option<(usize, ObjProblem)>,
}

/// The first word of a line and the rest.
fn split_keyword(line: &[u8]) -> Option<(&[u8], &[u8])> {
    let start = line.iter().position(|&b| !is_blank(b))?;
    let rest = &line[start..];
    let end = rest.iter().position(|&b| is_blank(b)).unwrap_or(rest.len());
    Some((&rest[..end], &rest[end..]))
}

/// The next blank-separated word of `s`, advancing `s` past it.
fn next_word<'a>(s: &mut &'a [u8]) -> Option<&'a [u8]> {
    let start = s.iter().position(|&b| !is_blank(b))?;
    let rest = &s[start..];
    let end = rest.iter().position(|&b| is_blank(b)).unwrap_or(rest.len());
    *s = &rest[end..];
    Some(&rest[..end])
}

/// The first pass: lines and element counts of a chunk.
///
/// With `exact` false, an `f` line of a chunk without continued lines counts as one
/// triangle without reading its corners (a guess, right for triangle meshes): the parse
/// of a line with more corners then finds its chunk's room too small
/// ([`ObjProblem::Miscounted`]) and the reader counts again, exactly (see
/// [`super::read`]).
pub(crate) fn count(chunk: &[u8], exact: bool) -> Counts {
    count_plain(chunk, exact).unwrap_or_else(|| count_general(chunk))
}

/// [`count`] of a chunk without line continuations, one scan of each line's ends and
/// first bytes (and, if `exact`, of an `f` line's corners); `None` when a line
/// continues, for [`count_general`] to count.
fn count_plain(chunk: &[u8], exact: bool) -> Option<Counts> {
    let mut c = Counts::default();
    let mut pos = 0;
    while pos < chunk.len() {
        let rest = &chunk[pos..];
        let (line, next) = match memchr::memchr2(b'\n', b'\r', rest) {
            Some(i) => {
                let crlf = rest[i] == b'\r' && rest.get(i + 1) == Some(&b'\n');
                (&rest[..i], i + 1 + usize::from(crlf))
            }
            None => (rest, rest.len()),
        };
        pos += next;
        c.lines += 1;
        // a `\` as the last non-blank character may continue the line
        if line.iter().rev().find(|&&b| !is_blank(b)) == Some(&b'\\') {
            return None;
        }
        let Some((keyword, rest)) = split_keyword(line) else {
            continue;
        };
        match keyword {
            b"v" => c.v += 1,
            b"vt" => c.vt += 1,
            b"vn" => c.vn += 1,
            b"f" if exact => c.tri += words(rest).saturating_sub(2),
            b"f" => c.tri += 1,
            _ => {}
        }
    }
    Some(c)
}

/// [`count`] through the logical lines (continuations joined).
fn count_general(chunk: &[u8]) -> Counts {
    let mut c = Counts::default();
    let mut lines = Lines::new(chunk);
    for line in lines.by_ref() {
        match split_keyword(&line.text) {
            Some((b"v", _)) => c.v += 1,
            Some((b"vt", _)) => c.vt += 1,
            Some((b"vn", _)) => c.vn += 1,
            Some((b"f", rest)) => c.tri += words(rest).saturating_sub(2),
            _ => {}
        }
    }
    c.lines = lines.physical();
    c
}

/// `s` without a trailing comment: from a `#` that starts a word (`v 1 2 3 # note`). A
/// `#` inside a word (`usemtl mat#1`) is kept; statements other than `v`/`vt`/`vn`/`f`
/// are not cut.
pub(crate) fn strip_comment(s: &[u8]) -> &[u8] {
    let mut prev_blank = true;
    for (i, &b) in s.iter().enumerate() {
        if b == b'#' && prev_blank {
            return &s[..i];
        }
        prev_blank = is_blank(b);
    }
    s
}

/// Blank-separated words of `s` (the corners of an `f` statement) before a comment.
fn words(s: &[u8]) -> usize {
    let s = strip_comment(s);
    // a word starts at a non-blank byte after a blank one (or at the start)
    let first = s.first().is_some_and(|&b| !is_blank(b));
    let later = s
        .windows(2)
        .filter(|w| is_blank(w[0]) && !is_blank(w[1]))
        .count();
    usize::from(first) + later
}

/// Parses a chunk into `sink` (room for exactly its elements: [`Parsed::sinks`] with the
/// chunk's [`count`]). `offset`: the chunk's byte offset in the text (for the vertex
/// spans); `before`: lines and elements before it; `total`: in the whole file.
pub(crate) fn parse_into(
    chunk: &[u8],
    offset: usize,
    before: Counts,
    total: Counts,
    sink: &mut Sink<'_>,
) -> ChunkOutcome {
    let mut out = ChunkOutcome::default();
    let mut seen = before;
    let mut corners: Vec<(u32, u32)> = Vec::new();
    for line in Lines::new(chunk) {
        let lineno = before.lines + line.index + 1;
        // where the line's text sits in the whole text (a joined line has no place)
        let at = match line.text {
            std::borrow::Cow::Borrowed(_) => Some(offset + line.start),
            std::borrow::Cow::Owned(_) => None,
        };
        if let Err(problem) =
            statement(&line.text, at, lineno, &mut seen, total, sink, &mut corners)
        {
            let problem = if std::str::from_utf8(&line.text).is_err() {
                ObjProblem::NotUtf8
            } else {
                problem
            };
            out.error = Some((lineno, problem));
            break;
        }
    }
    out.noted = sink.noted;
    out.triangles = sink.nf;
    out
}

/// Parses a whole text in one piece (counted first): the reference the tests compare the
/// chunked reader with.
#[cfg(test)]
pub(crate) fn parse_text(text: &[u8]) -> Parsed {
    let total = count(text, true);
    let mut whole = Parsed::with_counts(total);
    let outcome = {
        let mut sinks = whole.sinks(&[total]);
        parse_into(text, 0, Counts::default(), total, &mut sinks[0])
    };
    whole.noted = outcome.noted;
    whole.error = outcome.error;
    whole
}

fn statement(
    line: &[u8],
    at: Option<usize>,
    lineno: usize,
    seen: &mut Counts,
    total: Counts,
    p: &mut Sink<'_>,
    corners: &mut Vec<(u32, u32)>,
) -> Result<(), ObjProblem> {
    let Some((keyword, rest)) = split_keyword(line) else {
        return Ok(());
    };
    // where `rest` starts in `line` (cutting a comment only shortens its end)
    let rest_at = line.len() - rest.len();
    let mut rest = match keyword {
        b"v" | b"vt" | b"vn" | b"f" => strip_comment(rest),
        _ => rest,
    };
    match keyword {
        b"v" => {
            if let Some((pos, (start, end))) = fast_floats::<3>(rest) {
                // `rest` is the end of `line`: the numbers' place in the whole text
                let span = at.map_or(NO_SPAN, |a| (a + rest_at + start, end - start));
                p.vertex(pos, lineno, span)?;
                seen.v += 1;
                return Ok(());
            }
            let mut x = [0.0; 6];
            let n = numbers("v", &mut rest, &mut x, &[3, 4, 6])?;
            let mut pos = [x[0], x[1], x[2]];
            if n == 4 {
                // homogeneous `x y z w`: the point is (x, y, z) / w
                if x[3] == 0.0 {
                    return Err(ObjProblem::ZeroW);
                }
                pos = pos.map(|c| c / x[3]);
            }
            p.vertex(pos, lineno, NO_SPAN)?;
            seen.v += 1;
        }
        b"vt" => {
            if let Some((t, _)) = fast_floats::<2>(rest) {
                p.texcoord(t)?;
                seen.vt += 1;
                return Ok(());
            }
            let mut x = [0.0; 3];
            numbers("vt", &mut rest, &mut x, &[2, 3])?;
            p.texcoord([x[0], x[1]])?;
            seen.vt += 1;
        }
        b"vn" => {
            if fast_floats::<3>(rest).is_some() {
                seen.vn += 1;
                return Ok(());
            }
            let mut x = [0.0; 3];
            numbers("vn", &mut rest, &mut x, &[3])?;
            seen.vn += 1;
        }
        b"f" => {
            if let Some(f) = fast_triangle(rest, total.v) {
                return p.triangle(f, [NO_UV; 3], lineno);
            }
            corners.clear();
            if !fast_corners(rest, *seen, total, corners)? {
                corners.clear();
                while let Some(token) = next_word(&mut rest) {
                    corners.push(parse_corner(token, *seen, total)?);
                }
            }
            if corners.len() < 3 {
                return Err(ObjProblem::TooFewCorners {
                    found: corners.len(),
                });
            }
            for w in 1..corners.len() - 1 {
                let (a, b, c) = (corners[0], corners[w], corners[w + 1]);
                p.triangle([a.0, b.0, c.0], [a.1, b.1, c.1], lineno)?;
            }
        }
        k if k.first() == Some(&b'#') || IGNORED.contains(&k) => {}
        k if IGNORED_NOTED.contains(&k) => p.noted += 1,
        k => {
            let keyword = std::str::from_utf8(k).map_err(|_| ObjProblem::NotUtf8)?;
            return Err(ObjProblem::UnknownStatement {
                keyword: keyword.chars().take(40).collect(),
            });
        }
    }
    Ok(())
}

/// The error for the value `token` of a `keyword` line that is not a finite number: not
/// a number at all, or a number too large for f64 (`1e400`; `inf` as written is left for
/// validation to name).
fn number_problem(keyword: &str, token: &[u8]) -> Option<ObjProblem> {
    let (keyword, text) = (
        keyword.to_owned(),
        String::from_utf8_lossy(token).chars().take(40).collect(),
    );
    match fast_float2::parse::<f64, _>(token) {
        Err(_) => Some(ObjProblem::BadNumber { keyword, text }),
        Ok(x) if x.is_infinite() && token.iter().any(u8::is_ascii_digit) => {
            Some(ObjProblem::NumberOverflow { keyword, text })
        }
        Ok(_) => None,
    }
}

/// Parses every value of a `v`/`vt`/`vn` line into `out` (its length is the most values
/// allowed); returns how many there are. The count is checked before the numbers, as
/// [`ObjProblem::WrongValueCount`] is the more useful message for a short line.
fn numbers(
    keyword: &str,
    rest: &mut &[u8],
    out: &mut [f64],
    allowed: &[usize],
) -> Result<usize, ObjProblem> {
    let mut n = 0;
    let mut bad = None;
    while let Some(token) = next_word(rest) {
        if let Some(slot) = out.get_mut(n) {
            match number_problem(keyword, token) {
                None => *slot = fast_float2::parse::<f64, _>(token).unwrap_or(f64::NAN),
                Some(problem) => {
                    bad.get_or_insert(problem);
                }
            }
        }
        n += 1;
    }
    if !allowed.contains(&n) {
        return Err(ObjProblem::WrongValueCount {
            keyword: keyword.to_owned(),
            found: n,
        });
    }
    if let Some(problem) = bad {
        return Err(problem);
    }
    Ok(n)
}

/// `s` past its leading blanks.
fn skip_blanks(s: &[u8]) -> &[u8] {
    let start = s.iter().position(|&b| !is_blank(b)).unwrap_or(s.len());
    &s[start..]
}

/// The fast path of a `v`/`vt`/`vn` line: exactly `N` numbers, each read where it starts
/// (`parse_partial` finds its end, so the bytes are scanned once) and ended by a blank or
/// the line's end, and the byte range `(start, end)` in `s` from the first number's start
/// to the last one's end. `None` for anything else (another count, a bad number), which
/// the general path then reads or reports; on the lines it accepts both paths give the
/// same bits, `parse_partial` being `parse` of the longest number at the start.
fn fast_floats<const N: usize>(s: &[u8]) -> Option<([f64; N], (usize, usize))> {
    let mut out = [0.0; N];
    let mut rest = s;
    let mut start = None;
    for slot in &mut out {
        rest = skip_blanks(rest);
        start.get_or_insert(s.len() - rest.len());
        let (x, len) = match decimal(rest) {
            Some(read) => read,
            None => fast_float2::parse_partial::<f64, _>(rest).ok()?,
        };
        // an overflow (or `inf`) is the general path's to judge
        if x.is_infinite() {
            return None;
        }
        rest = &rest[len..];
        if rest.first().is_some_and(|&b| !is_blank(b)) {
            return None;
        }
        *slot = x;
    }
    let end = s.len() - rest.len();
    rest.iter()
        .all(|&b| is_blank(b))
        .then_some((out, (start.unwrap_or(end), end)))
}

/// Powers of ten exactly representable as f64.
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16,
    1e17, 1e18, 1e19, 1e20, 1e21, 1e22,
];

/// The common number of a mesh file, `[-]digits[.digits]` of at most 15 significant
/// digits, at the start of `s`: its value and length, `None` for anything else (an
/// exponent, more digits, `inf`...) or when the number goes on (`fast-float2` then reads
/// it). Correctly rounded: the digits form an integer below 2^53 and the divisor is a power
/// of ten below 10^23, both exact in f64, and one IEEE division rounds correctly
/// (Clinger's fast path, as `fast-float2` takes it too, without its general set-up).
pub(crate) fn decimal(s: &[u8]) -> Option<(f64, usize)> {
    let (negative, mut rest) = match s {
        [b'-', tail @ ..] => (true, tail),
        _ => (false, s),
    };
    let mut m: u64 = 0;
    // wrapping: a value of more than 15 digits is refused below
    let mut digits = 0usize;
    while let [d @ b'0'..=b'9', tail @ ..] = rest {
        m = m.wrapping_mul(10).wrapping_add(u64::from(d - b'0'));
        digits += 1;
        rest = tail;
    }
    if digits == 0 {
        return None;
    }
    let mut scale = 0usize;
    if let [b'.', tail @ ..] = rest {
        rest = tail;
        while let [d @ b'0'..=b'9', tail @ ..] = rest {
            m = m.wrapping_mul(10).wrapping_add(u64::from(d - b'0'));
            scale += 1;
            rest = tail;
        }
    }
    // 15 digits keep m below 10^15 < 2^53 (leading zeros count too: a safe bound)
    if digits + scale > 15 || rest.first().is_some_and(|&b| !is_blank(b)) {
        return None;
    }
    let x = m as f64 / EXACT_POWERS_OF_TEN[scale];
    Some((if negative { -x } else { x }, s.len() - rest.len()))
}

/// An optionally signed decimal integer at the start of `s`: its value and length, `None`
/// without digits or on overflow (the general path then reports the token).
fn leading_int(s: &[u8]) -> Option<(i64, usize)> {
    let negative = s.first() == Some(&b'-');
    let start = usize::from(negative || s.first() == Some(&b'+'));
    // up to 18 digits cannot overflow an i64; longer runs take the checked path
    let mut x: i64 = 0;
    let mut len = start;
    while let Some(&d) = s.get(len) {
        if !d.is_ascii_digit() || len - start == 18 {
            break;
        }
        x = 10 * x + i64::from(d - b'0');
        len += 1;
    }
    if s.get(len).is_some_and(u8::is_ascii_digit) {
        let digits = s[start..].iter().take_while(|b| b.is_ascii_digit()).count();
        return Some((parse_int(&s[..start + digits])?, start + digits));
    }
    if len == start {
        return None;
    }
    Some((if negative { -x } else { x }, len))
}

/// The fastest path of an `f` line: exactly three positive vertex indices within the
/// file's `total_v` vertices (`f 1 2 3`: no sign, no `/`), spaces or tabs before each and
/// after the last; 0-based. `None` for anything else, which [`fast_corners`] or the
/// general path then reads or reports; on the lines it accepts all give the same.
fn fast_triangle(s: &[u8], total_v: usize) -> Option<[u32; 3]> {
    let blank = |b: u8| b == b' ' || b == b'\t';
    let mut out = [0u32; 3];
    let mut i = 0;
    for slot in &mut out {
        if !blank(*s.get(i)?) {
            return None;
        }
        while s.get(i).is_some_and(|&b| blank(b)) {
            i += 1;
        }
        let start = i;
        let mut x: u64 = 0;
        // ten digits at most here (more than any u32 index); an eleventh steps aside
        while let Some(&d) = s.get(i).filter(|d| d.is_ascii_digit() && i - start < 10) {
            x = 10 * x + u64::from(d - b'0');
            i += 1;
        }
        if i == start || s.get(i).is_some_and(|&b| !blank(b)) || x == 0 || x > total_v as u64 {
            return None;
        }
        *slot = u32::try_from(x - 1).ok()?;
    }
    s[i..].iter().all(|&b| blank(b)).then_some(out)
}

/// The fast path of an `f` line: corners `v`, `v/vt`, `v//vn` or `v/vt/vn` read in one
/// scan into `corners`. `Ok(false)` when a token has another shape, for the general path
/// to read or report; index errors are the general path's errors.
fn fast_corners(
    mut s: &[u8],
    seen: Counts,
    total: Counts,
    corners: &mut Vec<(u32, u32)>,
) -> Result<bool, ObjProblem> {
    loop {
        s = skip_blanks(s);
        if s.is_empty() {
            return Ok(true);
        }
        let Some((v, len)) = leading_int(s) else {
            return Ok(false);
        };
        s = &s[len..];
        let mut vt = None;
        let mut vn = None;
        if s.first() == Some(&b'/') {
            s = &s[1..];
            if let Some((t, len)) = leading_int(s) {
                vt = Some(t);
                s = &s[len..];
            }
            if s.first() == Some(&b'/') {
                s = &s[1..];
                let Some((nrm, len)) = leading_int(s) else {
                    return Ok(false);
                };
                vn = Some(nrm);
                s = &s[len..];
            } else if vt.is_none() {
                return Ok(false); // `v/` alone
            }
        }
        if s.first().is_some_and(|&b| !is_blank(b)) {
            return Ok(false);
        }
        let vi = resolve(v, (seen.v, total.v), "vertex")?;
        let ti = match vt {
            Some(t) => resolve(t, (seen.vt, total.vt), "texture coordinate")?,
            None => NO_UV,
        };
        // normals are never used: without `vn` lines, `f 1//1` is accepted
        if let Some(nrm) = vn.filter(|_| total.vn > 0) {
            resolve(nrm, (seen.vn, total.vn), "normal")?;
        }
        corners.push((vi, ti));
    }
}

/// Parses `v`, `v/vt`, `v//vn` or `v/vt/vn`; returns the 0-based vertex and `vt` indices.
fn parse_corner(token: &[u8], seen: Counts, total: Counts) -> Result<(u32, u32), ObjProblem> {
    let bad = || ObjProblem::BadCorner {
        token: String::from_utf8_lossy(token).chars().take(40).collect(),
    };
    let mut parts = token.split(|&b| b == b'/');
    let pv = parts.next().filter(|p| !p.is_empty()).ok_or_else(bad)?;
    let pvt = parts.next().filter(|p| !p.is_empty());
    let pvn = parts.next().filter(|p| !p.is_empty());
    if parts.next().is_some() {
        return Err(bad());
    }
    let vi = resolve(parse_int(pv).ok_or_else(bad)?, (seen.v, total.v), "vertex")?;
    let ti = match pvt {
        Some(p) => resolve(
            parse_int(p).ok_or_else(bad)?,
            (seen.vt, total.vt),
            "texture coordinate",
        )?,
        None => NO_UV,
    };
    if let Some(p) = pvn {
        let nrm = parse_int(p).ok_or_else(bad)?;
        // normals are never used: without `vn` lines, `f 1//1` is accepted
        if total.vn > 0 {
            resolve(nrm, (seen.vn, total.vn), "normal")?;
        }
    }
    Ok((vi, ti))
}

/// An `i64` as `str::parse` reads it (optional sign, decimal digits); `None` on overflow.
fn parse_int(s: &[u8]) -> Option<i64> {
    let (negative, digits) = match s {
        [b'-', rest @ ..] => (true, rest),
        [b'+', rest @ ..] => (false, rest),
        _ => (false, s),
    };
    if digits.is_empty() {
        return None;
    }
    let mut x: i64 = 0;
    for &d in digits {
        if !d.is_ascii_digit() {
            return None;
        }
        let d = i64::from(d - b'0');
        x = x.checked_mul(10)?;
        x = if negative {
            x.checked_sub(d)?
        } else {
            x.checked_add(d)?
        };
    }
    Some(x)
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

    fn one(text: &str) -> Parsed {
        parse_text(text.as_bytes())
    }

    #[test]
    fn negative_indices_and_fans() {
        let s = one("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf -4 -3 -2 -1\n");
        assert_eq!(s.faces, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(s.face_lines, vec![5, 5]);
        assert!(s.error.is_none());
    }

    #[test]
    fn corner_forms() {
        let s = one("v 0 0 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 1//1 1/1\n");
        assert_eq!(s.face_uv, vec![[0, NO_UV, 0]]);
        let s = one("v 0 0 0\nf 1/1/1/1 1 1\n");
        assert!(matches!(s.error, Some((2, ObjProblem::BadCorner { .. }))));
        let s = one("v 0 0 0\nf 1/ 1 x\n");
        assert!(matches!(s.error, Some((2, ObjProblem::BadCorner { .. }))));
    }

    #[test]
    fn hostile_indices_are_errors() {
        for idx in [
            "9223372036854775807",
            "-9223372036854775808",
            "99999999999999999999",
        ] {
            let s = one(&format!("v 0 0 0\nvt 0 0\nf 1/{idx} 1/1 1/1\n"));
            assert!(s.error.is_some(), "{idx}");
        }
    }

    #[test]
    fn integers_parse_as_str_parse_does() {
        for s in [
            "0",
            "+7",
            "-12",
            "9223372036854775807",
            "-9223372036854775808",
        ] {
            assert_eq!(parse_int(s.as_bytes()), s.parse().ok(), "{s}");
        }
        for s in ["", "-", "+", "1x", "9223372036854775808", " 1", "--1"] {
            assert_eq!(parse_int(s.as_bytes()), None, "{s}");
        }
    }

    #[test]
    fn numbers_and_homogeneous_w() {
        let s = one("v 1 2 3 2\nv 1 2 zero\n");
        // the first line parsed (the arrays are sized by the count; the error stops there)
        assert_eq!(s.positions[0], [0.5, 1.0, 1.5]);
        assert!(matches!(s.error, Some((2, ObjProblem::BadNumber { .. }))));
        let s = one("v 1 2 3 0\n");
        assert_eq!(s.error, Some((1, ObjProblem::ZeroW)));
        let s = one("v 1 2\n");
        assert!(matches!(
            s.error,
            Some((1, ObjProblem::WrongValueCount { found: 2, .. }))
        ));
    }

    #[test]
    fn correctly_rounded_like_the_standard_library() {
        let tokens = [
            "0.1",
            "2.2250738585072011e-308",
            "4.9e-324",
            "1.7976931348623157e308",
            "-0.0",
            "0.30000000000000004",
            "123456789012345678901234567890",
            "1e-400",
            "inf",
            "-Infinity",
            "7.",
            ".5",
            "+3E+2",
        ];
        for t in tokens {
            let ours = fast_float2::parse::<f64, _>(t).unwrap();
            let std: f64 = t.parse().unwrap();
            assert_eq!(ours.to_bits(), std.to_bits(), "{t}");
        }
        for t in ["1e", "e5", "--1", "1.2.3", "0x10", ""] {
            assert!(fast_float2::parse::<f64, _>(t).is_err(), "{t}");
            assert!(t.parse::<f64>().is_err(), "{t}");
        }
    }

    /// The decimal fast path gives the bits of the standard library's correctly rounded
    /// parse on every number it reads, and steps aside for the rest.
    #[test]
    fn decimals_round_like_the_standard_library() {
        let mut state = 0x2545_f491_4f6c_dd1du64;
        let mut next = |k: u64| {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state % k
        };
        let mut read = 0;
        for _ in 0..200_000 {
            let mut t = String::new();
            if next(2) == 0 {
                t.push('-');
            }
            for _ in 0..=next(9) {
                t.push(char::from(b'0' + next(10) as u8));
            }
            if next(4) != 0 {
                t.push('.');
                for _ in 0..next(18) {
                    t.push(char::from(b'0' + next(10) as u8));
                }
            }
            let want: f64 = t.parse().unwrap();
            if let Some((x, len)) = decimal(t.as_bytes()) {
                assert_eq!((x.to_bits(), len), (want.to_bits(), t.len()), "{t}");
                read += 1;
            }
            // the same number followed by a blank, or by more of a number
            let spaced = format!("{t} 1");
            if let Some((x, len)) = decimal(spaced.as_bytes()) {
                assert_eq!((x.to_bits(), len), (want.to_bits(), t.len()), "{t}");
            }
            assert!(decimal(format!("{t}e1").as_bytes()).is_none(), "{t}");
        }
        assert!(read > 100_000, "{read}");
        for t in [
            "9007199254740993",
            "0.1234567890123456",
            "1e5",
            "inf",
            ".5",
            "-",
            "+1",
            "x",
        ] {
            assert!(decimal(t.as_bytes()).is_none(), "{t}");
        }
        assert_eq!(
            decimal(b"-0.0").map(|(x, _)| x.to_bits()),
            Some((-0.0f64).to_bits())
        );
        assert_eq!(decimal(b"7."), Some((7.0, 2)));
    }

    /// The fast paths give exactly what the general path gives, or step aside: numbers and
    /// corners of every shape the general path accepts or rejects.
    #[test]
    fn fast_paths_agree_with_the_general_path() {
        let numbers_tokens = [
            "0",
            "-0.0",
            "1.5",
            "+3E+2",
            ".5",
            "7.",
            "1e-400",
            "inf",
            "-Infinity",
            "nan",
            "1e",
            "1.2.3",
            "0x10",
            "1,5",
            "2.2250738585072011e-308",
            "123456789012345678901",
        ];
        for a_tok in numbers_tokens {
            for b_tok in numbers_tokens {
                for sep in [" ", "\t", "  "] {
                    let line = format!("{sep}{a_tok}{sep}{b_tok}{sep}1.25{sep}");
                    let fast = fast_floats::<3>(line.as_bytes()).map(|(x, (a, b))| {
                        // the span holds exactly the three numbers
                        let text = &line[a..b];
                        assert_eq!(
                            text,
                            format!("{a_}{sep}{b_}{sep}1.25", a_ = a_tok, b_ = b_tok)
                        );
                        x
                    });
                    let mut rest = line.as_bytes();
                    let mut x = [0.0; 6];
                    let general = numbers("v", &mut rest, &mut x, &[3]);
                    match (fast, general) {
                        (Some(f), Ok(3)) => {
                            assert_eq!(
                                f.map(f64::to_bits),
                                [x[0], x[1], x[2]].map(f64::to_bits),
                                "{line}"
                            )
                        }
                        (Some(_), g) => panic!("fast accepted {line:?}, general gave {g:?}"),
                        (None, Ok(_)) => {} // stepping aside is always allowed
                        (None, Err(_)) => {}
                    }
                }
            }
        }
        let seen = Counts {
            v: 5,
            vt: 4,
            vn: 3,
            ..Counts::default()
        };
        let total = Counts {
            v: 9,
            vt: 9,
            vn: 9,
            ..Counts::default()
        };
        let corner_tokens = [
            "1",
            "-1",
            "+2",
            "9",
            "10",
            "0",
            "-6",
            "1/2",
            "1//3",
            "1/2/3",
            "1/",
            "1//",
            "1/2/",
            "/1",
            "1/x",
            "x",
            "1/2/3/4",
            "-1/-1/-1",
            "99999999999999999999",
            "1/-5",
        ];
        for a in corner_tokens {
            for b in corner_tokens {
                let line = format!(" {a} {b}\t3 ");
                let mut corners = Vec::new();
                let fast = fast_corners(line.as_bytes(), seen, total, &mut corners);
                let mut rest = line.as_bytes();
                let general: Result<Vec<_>, _> = std::iter::from_fn(|| next_word(&mut rest))
                    .map(|t| parse_corner(t, seen, total))
                    .collect();
                if let Some(f) = fast_triangle(line.as_bytes(), total.v) {
                    let want: Vec<_> = f.iter().map(|&v| (v, NO_UV)).collect();
                    assert_eq!(Ok(want), general, "{line}");
                }
                match fast {
                    Ok(true) => assert_eq!(Ok(corners), general, "{line}"),
                    Ok(false) => {}
                    Err(e) => assert_eq!(Err(e), general, "{line}"),
                }
            }
        }
    }

    /// The one-scan count agrees with the count through logical lines on every line
    /// shape, and steps aside for a continued line.
    #[test]
    fn plain_count_agrees_with_the_general_count() {
        let lines = [
            "v 1 2 3",
            "vt 0 1",
            "vn 0 0 1",
            "f 1 2 3",
            "f 1/1 2/2 3/3 4/4",
            "f\t1 2  3 ",
            "  v 1 2 3",
            "\tf 1 2 3 4 5",
            "f 1",
            "f",
            "v",
            "vt",
            "vp 1 2",
            "vertex 1 2 3",
            "fo 1 2 3",
            "# v 1 2 3",
            "o f",
            "g v",
            "",
            "   ",
            "usemtl x",
            "l 1 2",
            "#",
            "f 1 2 3 # tail",
        ];
        let ends = ["\n", "\r\n", "\r"];
        for (i, a) in lines.iter().enumerate() {
            for (j, b) in lines.iter().enumerate() {
                let text = format!("{a}{}{b}{}", ends[i % 3], ends[j % 3]);
                let bytes = text.as_bytes();
                assert_eq!(
                    count_plain(bytes, true),
                    Some(count_general(bytes)),
                    "{text:?}"
                );
                // without the last line end
                let cut = &bytes[..bytes.len() - ends[j % 3].len()];
                assert_eq!(count_plain(cut, true), Some(count_general(cut)), "{text:?}");
            }
        }
        let continued = b"f 1 2 \\\n3\n";
        assert_eq!(count_plain(continued, true), None);
        assert_eq!(count(continued, false).tri, 1);
        // a comment ending in `\` does not continue, but the plain count leaves it to
        // the general one all the same
        assert_eq!(count(b"# C:\\dir\\\nv 0 0 0\n", false).v, 1);
    }

    #[test]
    fn non_utf8_only_matters_in_statements() {
        let mut bytes = b"# caf\xe9\no caf\xe9\nv 0 0 0\n".to_vec();
        let s = parse_text(&bytes);
        assert!(s.error.is_none());
        bytes.extend_from_slice(b"v 1 \xe9 0\n");
        let s = parse_text(&bytes);
        assert!(matches!(s.error, Some((4, ObjProblem::NotUtf8))));
    }
}
