//! The lines of an OBJ text, and its split into chunks for parallel parsing.
//!
//! - `\n`, `\r\n` and a lone `\r` (classic Mac OS) each end a line.
//! - A `\` as the last non-blank character of a line continues the statement on the next
//!   line (OBJ specification, "Line continuation"); the logical line carries the number of
//!   its first physical line. A comment line never continues: a Windows path ending in `\`
//!   in a comment must not swallow the next statement.
//! - Lines are bytes: only the statements the reader parses must be text (see `parse`), so
//!   a comment or an object name in Latin-1 is fine.

use std::borrow::Cow;

use memchr::{memchr2, memrchr2};

/// One logical line: its physical line number (0-based within the chunk), the byte offset
/// of its start within the chunk, and its text (continuations joined by a space, line ends
/// removed; borrowed from the chunk at that offset unless joined).
pub(crate) struct Line<'a> {
    pub(crate) index: usize,
    pub(crate) start: usize,
    pub(crate) text: Cow<'a, [u8]>,
}

/// The logical lines of a chunk; [`Self::physical`] counts the physical ones read.
pub(crate) struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    physical: usize,
}

impl<'a> Lines<'a> {
    pub(crate) fn new(bytes: &'a [u8]) -> Self {
        Self {
            bytes,
            pos: 0,
            physical: 0,
        }
    }

    /// Physical lines read so far (all of them once the iterator is done).
    pub(crate) fn physical(&self) -> usize {
        self.physical
    }

    /// The next physical line's text, advancing past its line end.
    fn next_physical(&mut self) -> Option<&'a [u8]> {
        let (start, end, next) = physical_line(self.bytes, self.pos)?;
        self.pos = next;
        self.physical += 1;
        Some(&self.bytes[start..end])
    }
}

impl<'a> Iterator for Lines<'a> {
    type Item = Line<'a>;

    fn next(&mut self) -> Option<Line<'a>> {
        let index = self.physical;
        let start = self.pos;
        let first = self.next_physical()?;
        if !continues(first) {
            return Some(Line {
                index,
                start,
                text: Cow::Borrowed(first),
            });
        }
        let mut joined = Vec::with_capacity(2 * first.len());
        let mut cur = first;
        loop {
            if !continues(cur) {
                joined.extend_from_slice(cur);
                break;
            }
            let body = trim_end(cur);
            joined.extend_from_slice(&body[..body.len() - 1]);
            joined.push(b' ');
            match self.next_physical() {
                Some(next) => cur = next,
                None => break,
            }
        }
        Some(Line {
            index,
            start,
            text: Cow::Owned(joined),
        })
    }
}

/// `(start, end, next)` of the physical line at `pos`: its text is `start..end`, the next
/// line starts at `next`. `None` at the end of the bytes.
fn physical_line(bytes: &[u8], pos: usize) -> Option<(usize, usize, usize)> {
    if pos >= bytes.len() {
        return None;
    }
    Some(match memchr2(b'\n', b'\r', &bytes[pos..]) {
        Some(i) => {
            let end = pos + i;
            let crlf = bytes[end] == b'\r' && bytes.get(end + 1) == Some(&b'\n');
            (pos, end, end + 1 + usize::from(crlf))
        }
        None => (pos, bytes.len(), bytes.len()),
    })
}

/// ASCII blanks inside a line (`\r` and `\n` end lines before this is asked).
pub(crate) fn is_blank(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | 0x0b | 0x0c | b'\r' | b'\n')
}

fn trim_end(line: &[u8]) -> &[u8] {
    let end = line
        .iter()
        .rposition(|&b| !is_blank(b))
        .map_or(0, |i| i + 1);
    &line[..end]
}

/// Whether a physical line ends in a continuation `\` (and is not a comment).
fn continues(line: &[u8]) -> bool {
    let t = trim_end(line);
    t.last() == Some(&b'\\') && t.iter().find(|&&b| !is_blank(b)) != Some(&b'#')
}

/// Splits `bytes` into about `n` chunks, each ending just after a line end that no
/// continuation crosses, so every chunk holds whole logical lines. One chunk if `n ≤ 1`.
pub(crate) fn split_chunks(bytes: &[u8], n: usize) -> Vec<&[u8]> {
    let size = bytes.len() / n.max(1);
    let mut out = Vec::with_capacity(n.max(1));
    let mut start = 0;
    while start < bytes.len() {
        let mut at = start + size.max(1);
        if n <= 1 || at >= bytes.len() {
            out.push(&bytes[start..]);
            break;
        }
        // the first line end at or after `at` whose line does not continue
        loop {
            let Some(i) = memchr2(b'\n', b'\r', &bytes[at..]) else {
                at = bytes.len();
                break;
            };
            let end = at + i;
            let crlf = bytes[end] == b'\r' && bytes.get(end + 1) == Some(&b'\n');
            let line_start = memrchr2(b'\n', b'\r', &bytes[..end]).map_or(0, |k| k + 1);
            at = end + 1 + usize::from(crlf);
            if !continues(&bytes[line_start.max(start)..end]) {
                break;
            }
        }
        out.push(&bytes[start..at]);
        start = at;
    }
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // tests: a failed unwrap is a failed test
mod tests {
    use super::*;

    fn texts(bytes: &[u8]) -> Vec<(usize, String)> {
        Lines::new(bytes)
            .map(|l| (l.index, String::from_utf8_lossy(&l.text).into_owned()))
            .collect()
    }

    #[test]
    fn line_ends_of_every_kind() {
        let t = texts(b"a\nb\r\nc\rd\r\re");
        let want = [(0, "a"), (1, "b"), (2, "c"), (3, "d"), (4, ""), (5, "e")];
        let want: Vec<(usize, String)> = want.iter().map(|&(i, s)| (i, s.into())).collect();
        assert_eq!(t, want);
    }

    #[test]
    fn continuations_join_but_comments_do_not() {
        let mut lines = Lines::new(b"f 1 2 \\\n  3\n# C:\\dir\\\nv 0 0 0\n");
        let l = lines.next().unwrap();
        assert_eq!((l.index, &*l.text), (0, &b"f 1 2    3"[..]));
        assert_eq!(lines.next().unwrap().index, 2);
        assert_eq!(lines.next().unwrap().index, 3);
        assert!(lines.next().is_none());
        assert_eq!(lines.physical(), 4);
    }

    #[test]
    fn chunks_hold_whole_logical_lines() {
        let text: Vec<u8> = (0..500)
            .flat_map(|i| match i % 3 {
                0 => b"v 1 2 \\\r\n3\r\n".to_vec(),
                1 => b"vt 0 0\r".to_vec(),
                _ => b"# x\\\n".to_vec(),
            })
            .collect();
        for n in [1, 2, 7, 64] {
            let chunks = split_chunks(&text, n);
            assert_eq!(chunks.concat(), text);
            let per_chunk: Vec<(usize, String)> = chunks
                .iter()
                .flat_map(|c| texts(c).into_iter().map(|(_, s)| (0, s)))
                .collect();
            let whole: Vec<(usize, String)> =
                texts(&text).into_iter().map(|(_, s)| (0, s)).collect();
            assert_eq!(per_chunk, whole, "{n} chunks");
        }
    }
}
