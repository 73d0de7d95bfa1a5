//! The PLY header: format line, elements and their properties, up to `end_header`.

use std::path::Path;

use crate::cursor::{malformed, numbered_lines, quote, words, CORRUPT_HINT, TRUNCATED_HINT};
use crate::error::{IoError, Place};
use crate::loaded::Format;

/// A PLY scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    /// The type named `word` (both the classic and the sized names).
    fn parse(word: &[u8]) -> Option<Self> {
        Some(match word {
            b"char" | b"int8" => Self::I8,
            b"uchar" | b"uint8" => Self::U8,
            b"short" | b"int16" => Self::I16,
            b"ushort" | b"uint16" => Self::U16,
            b"int" | b"int32" => Self::I32,
            b"uint" | b"uint32" => Self::U32,
            b"float" | b"float32" => Self::F32,
            b"double" | b"float64" => Self::F64,
            _ => return None,
        })
    }

    /// Bytes in binary files.
    pub(crate) fn size(self) -> usize {
        match self {
            Self::I8 | Self::U8 => 1,
            Self::I16 | Self::U16 => 2,
            Self::I32 | Self::U32 | Self::F32 => 4,
            Self::F64 => 8,
        }
    }

    /// Whether the type is an integer (list counts and indices must be).
    pub(crate) fn is_integer(self) -> bool {
        !matches!(self, Self::F32 | Self::F64)
    }

    /// The value of the first `size()` bytes of `b` (the caller checked the length).
    pub(crate) fn value(self, b: &[u8], big_endian: bool) -> f64 {
        let mut w = [0u8; 8];
        let n = self.size();
        w[..n].copy_from_slice(&b[..n]);
        if big_endian {
            w[..n].reverse();
        }
        match self {
            Self::I8 => f64::from(w[0] as i8),
            Self::U8 => f64::from(w[0]),
            Self::I16 => f64::from(i16::from_le_bytes([w[0], w[1]])),
            Self::U16 => f64::from(u16::from_le_bytes([w[0], w[1]])),
            Self::I32 => f64::from(i32::from_le_bytes([w[0], w[1], w[2], w[3]])),
            Self::U32 => f64::from(u32::from_le_bytes([w[0], w[1], w[2], w[3]])),
            Self::F32 => f64::from(f32::from_le_bytes([w[0], w[1], w[2], w[3]])),
            Self::F64 => f64::from_le_bytes(w),
        }
    }
}

/// A property: a scalar, or a list (count type, item type).
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum Kind {
    Scalar(Scalar),
    List(Scalar, Scalar),
}

/// One `property` line.
#[derive(Debug, Clone)]
pub(crate) struct Property {
    pub(crate) name: String,
    pub(crate) kind: Kind,
}

/// One `element` line and its properties.
#[derive(Debug, Clone)]
pub(crate) struct Element {
    pub(crate) name: String,
    pub(crate) count: usize,
    pub(crate) props: Vec<Property>,
}

impl Element {
    /// The index of the property named any of `names`.
    pub(crate) fn find(&self, names: &[&str]) -> Option<usize> {
        self.props
            .iter()
            .position(|p| names.contains(&p.name.as_str()))
    }

    /// Bytes per instance when every property is a scalar (a fixed stride).
    pub(crate) fn stride(&self) -> Option<usize> {
        self.props
            .iter()
            .map(|p| match p.kind {
                Kind::Scalar(s) => Some(s.size()),
                Kind::List(..) => None,
            })
            .sum()
    }

    /// The fewest bytes (binary) one instance takes: scalars, and list counts.
    pub(crate) fn min_bytes(&self) -> usize {
        self.props
            .iter()
            .map(|p| match p.kind {
                Kind::Scalar(s) | Kind::List(s, _) => s.size(),
            })
            .sum()
    }
}

/// How the body is stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Encoding {
    Ascii,
    Binary { big_endian: bool },
}

/// The parsed header.
#[derive(Debug, Clone)]
pub(crate) struct Header {
    pub(crate) encoding: Encoding,
    pub(crate) elements: Vec<Element>,
    /// Byte offset of the body.
    pub(crate) body: usize,
    /// Lines in the header (the body's first line is `lines + 1`).
    pub(crate) lines: usize,
}

/// Parses the header of `bytes`.
pub(crate) fn parse_header(bytes: &[u8], path: &Path) -> Result<Header, IoError> {
    let bad = |line: usize, problem: String| {
        malformed(path, Format::Ply, Place::Line(line), problem, CORRUPT_HINT)
    };
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut offset = 0;
    for (line, text) in numbered_lines(bytes, 1) {
        // the body starts after this line's end, whatever the line end is
        offset += text.len();
        offset += match bytes.get(offset) {
            Some(b'\r') if bytes.get(offset + 1) == Some(&b'\n') => 2,
            Some(_) => 1,
            None => 0,
        };
        let mut w = words(text);
        let keyword = w.next().unwrap_or(b"");
        match keyword {
            b"ply" if line == 1 => {}
            _ if line == 1 => {
                return Err(bad(1, "the file does not start with `ply`".into()));
            }
            b"format" => encoding = Some(parse_format(w.next(), line, &bad)?),
            b"comment" | b"obj_info" | b"" => {}
            b"element" => {
                let (name, count) = (w.next(), w.next().and_then(parse_usize));
                let (Some(name), Some(count)) = (name, count) else {
                    return Err(bad(line, "`element` needs a name and a count".into()));
                };
                elements.push(Element {
                    name: quote(name),
                    count,
                    props: Vec::new(),
                });
            }
            b"property" => {
                let prop = parse_property(w, line, &bad)?;
                let Some(element) = elements.last_mut() else {
                    return Err(bad(line, "`property` before any `element`".into()));
                };
                element.props.push(prop);
            }
            b"end_header" => {
                let Some(encoding) = encoding else {
                    return Err(bad(line, "the header has no `format` line".into()));
                };
                return Ok(Header {
                    encoding,
                    elements,
                    body: offset,
                    lines: line,
                });
            }
            other => {
                return Err(bad(
                    line,
                    format!("`{}` is not a PLY header keyword", quote(other)),
                ))
            }
        }
    }
    Err(malformed(
        path,
        Format::Ply,
        Place::File,
        "the header has no `end_header` line",
        TRUNCATED_HINT,
    ))
}

fn parse_usize(word: &[u8]) -> Option<usize> {
    std::str::from_utf8(word).ok()?.parse().ok()
}

fn parse_format(
    word: Option<&[u8]>,
    line: usize,
    bad: &impl Fn(usize, String) -> IoError,
) -> Result<Encoding, IoError> {
    match word {
        Some(b"ascii") => Ok(Encoding::Ascii),
        Some(b"binary_little_endian") => Ok(Encoding::Binary { big_endian: false }),
        Some(b"binary_big_endian") => Ok(Encoding::Binary { big_endian: true }),
        other => Err(bad(
            line,
            format!(
                "unknown PLY format `{}` (expected ascii, binary_little_endian or \
                 binary_big_endian)",
                quote(other.unwrap_or(b""))
            ),
        )),
    }
}

fn parse_property<'a>(
    mut w: impl Iterator<Item = &'a [u8]>,
    line: usize,
    bad: &impl Fn(usize, String) -> IoError,
) -> Result<Property, IoError> {
    let ty = |word: Option<&[u8]>| {
        let word = word.unwrap_or(b"");
        Scalar::parse(word).ok_or_else(|| {
            bad(
                line,
                format!("`{}` is not a PLY property type", quote(word)),
            )
        })
    };
    let first = w.next();
    let kind = if first == Some(b"list") {
        let count = ty(w.next())?;
        let item = ty(w.next())?;
        if !count.is_integer() {
            return Err(bad(
                line,
                "a list's count type must be an integer type".into(),
            ));
        }
        Kind::List(count, item)
    } else {
        Kind::Scalar(ty(first)?)
    };
    let Some(name) = w.next() else {
        return Err(bad(line, "`property` without a name".into()));
    };
    Ok(Property {
        name: quote(name),
        kind,
    })
}
