//! What the PLY, STL, OFF, GIfTI and FreeSurfer readers share: a byte cursor whose errors
//! name the byte offset and the element read, the check of the counts a header declares
//! against the bytes the file holds (so that no reader allocates more than its file
//! can fill), and text tokens with their line.

use std::path::Path;

use crate::error::{IoError, Place};
use crate::loaded::Format;

/// The hint for a file that ends before what its header declares.
pub(crate) const TRUNCATED_HINT: &str = "the file is cut short (an interrupted copy or \
                                          download?): copy or export it again";
/// The hint for a file whose content is not what its format allows.
pub(crate) const CORRUPT_HINT: &str = "the file is damaged or not of the format its name \
                                        says: export it again, or check it in the program \
                                        that wrote it";

/// The [`IoError::Malformed`] of `path`.
pub(crate) fn malformed(
    path: &Path,
    format: Format,
    place: Place,
    problem: impl Into<String>,
    hint: &'static str,
) -> IoError {
    IoError::Malformed {
        path: path.to_path_buf(),
        format,
        place,
        problem: problem.into(),
        hint,
    }
}

/// Reads a binary file front to back; errors name the byte offset.
pub(crate) struct Cursor<'a> {
    pub(crate) bytes: &'a [u8],
    pub(crate) pos: usize,
    pub(crate) path: &'a Path,
    pub(crate) format: Format,
    /// Big-endian numbers (FreeSurfer, big-endian PLY).
    pub(crate) big_endian: bool,
}

impl<'a> Cursor<'a> {
    pub(crate) fn new(bytes: &'a [u8], path: &'a Path, format: Format, big_endian: bool) -> Self {
        Self {
            bytes,
            pos: 0,
            path,
            format,
            big_endian,
        }
    }

    /// Bytes left.
    pub(crate) fn remaining(&self) -> usize {
        self.bytes.len().saturating_sub(self.pos)
    }

    /// An error at the current offset, inside `element` (empty in a header).
    pub(crate) fn error(
        &self,
        element: impl Into<String>,
        problem: impl Into<String>,
        hint: &'static str,
    ) -> IoError {
        let place = Place::Byte {
            offset: self.pos as u64,
            element: element.into(),
        };
        malformed(self.path, self.format, place, problem, hint)
    }

    /// The next `n` bytes; a truncation error naming `element` if the file ends first.
    pub(crate) fn take(
        &mut self,
        n: usize,
        element: impl Fn() -> String,
    ) -> Result<&'a [u8], IoError> {
        match self
            .pos
            .checked_add(n)
            .and_then(|end| self.bytes.get(self.pos..end))
        {
            Some(s) => {
                self.pos += n;
                Ok(s)
            }
            None => Err(self.error(
                element(),
                format!(
                    "the file ends here, {} byte(s) short of what its header declares",
                    n - self.remaining().min(n)
                ),
                TRUNCATED_HINT,
            )),
        }
    }

    /// The next 4 bytes in the file's byte order.
    pub(crate) fn word(&mut self, element: impl Fn() -> String) -> Result<[u8; 4], IoError> {
        let s = self.take(4, element)?;
        let mut w = [s[0], s[1], s[2], s[3]];
        if self.big_endian {
            w.reverse();
        }
        Ok(w)
    }

    /// An `i32`.
    pub(crate) fn i32(&mut self, element: impl Fn() -> String) -> Result<i32, IoError> {
        Ok(i32::from_le_bytes(self.word(element)?))
    }

    /// An `f32` widened to f64.
    pub(crate) fn f32(&mut self, element: impl Fn() -> String) -> Result<f64, IoError> {
        Ok(f64::from(f32::from_le_bytes(self.word(element)?)))
    }

    /// Checks that `count` elements of at least `min_bytes` each fit in the bytes left: the
    /// reader's memory estimate before it allocates for them.
    pub(crate) fn check_count(
        &self,
        count: u64,
        min_bytes: u64,
        what: &str,
    ) -> Result<(), IoError> {
        let room = self.remaining() as u64 / min_bytes.max(1);
        if count > room {
            return Err(self.error(
                "",
                format!(
                    "the header declares {count} {what}, but the {} byte(s) left hold at most \
                     {room}",
                    self.remaining()
                ),
                TRUNCATED_HINT,
            ));
        }
        Ok(())
    }
}

/// The blank-separated words of a text line, each with its byte offset in the line.
pub(crate) fn words(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|w| !w.is_empty())
}

/// A word as text, shortened to 40 characters, for messages.
pub(crate) fn quote(word: &[u8]) -> String {
    String::from_utf8_lossy(word).chars().take(40).collect()
}

/// A decimal number as `str::parse::<f64>` reads it (correctly rounded).
pub(crate) fn parse_f64(word: &[u8]) -> Option<f64> {
    match crate::objfile::decimal(word) {
        Some((x, len)) if len == word.len() => Some(x),
        _ => fast_float2::parse::<f64, _>(word).ok(),
    }
}

/// The lines of a text with their 1-based numbers (`\n`, `\r\n` or `\r` ends), starting
/// at byte `start` whose line is `first_line`.
pub(crate) fn numbered_lines(
    text: &[u8],
    first_line: usize,
) -> impl Iterator<Item = (usize, &[u8])> {
    let mut pos = 0;
    let mut line = first_line;
    std::iter::from_fn(move || {
        if pos >= text.len() {
            return None;
        }
        let rest = &text[pos..];
        let (body, next) = match memchr::memchr2(b'\n', b'\r', rest) {
            Some(i) => {
                let crlf = rest[i] == b'\r' && rest.get(i + 1) == Some(&b'\n');
                (&rest[..i], i + 1 + usize::from(crlf))
            }
            None => (rest, rest.len()),
        };
        pos += next;
        line += 1;
        Some((line - 1, body))
    })
}
