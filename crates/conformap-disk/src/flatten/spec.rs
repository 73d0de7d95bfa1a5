//! The command-line spellings of the boundary targets (`free`, `circle`, `rectangle`,
//! `scale:FILE`, `angles:FILE`, `polygon:FILE`) and the boundary files
//! (`<0-based vertex> <value>` per line). The crate reads no file: the caller reads `FILE`
//! and hands its text to [`BoundarySpec::into_boundary`].

use std::path::PathBuf;

use super::target::FlattenBoundary;
use crate::DiskError;

/// A boundary target as spelled on the command line, before its file is read.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum BoundarySpec {
    /// `free`.
    Free,
    /// `circle`.
    Circle,
    /// `rectangle` (corners and aspect come from their own options).
    Rectangle,
    /// `scale:FILE`: `<vertex> <u>` per line, every boundary vertex.
    Scale(PathBuf),
    /// `angles:FILE`: `<vertex> <exterior angle in degrees>` per line, every boundary vertex.
    Angles(PathBuf),
    /// `polygon:FILE`: `<vertex> <exterior angle in degrees>` per corner, in boundary order.
    Polygon(PathBuf),
}

impl BoundarySpec {
    /// Parses a spelling.
    ///
    /// # Errors
    /// [`DiskError::UnknownBoundary`] for any other spelling (or a file-taking mode without
    /// a file).
    ///
    /// # Examples
    /// ```
    /// use conformap_disk::BoundarySpec;
    /// assert_eq!(BoundarySpec::parse("free")?, BoundarySpec::Free);
    /// assert_eq!(BoundarySpec::parse("polygon:l.txt")?, BoundarySpec::Polygon("l.txt".into()));
    /// assert!(BoundarySpec::parse("square").is_err());
    /// assert!(BoundarySpec::parse("scale:").is_err());
    /// # Ok::<(), conformap_disk::DiskError>(())
    /// ```
    pub fn parse(s: &str) -> Result<Self, DiskError> {
        let unknown = || DiskError::UnknownBoundary {
            spelling: s.to_string(),
        };
        let (mode, file) = match s.split_once(':') {
            Some((m, f)) if !f.is_empty() => (m, Some(PathBuf::from(f))),
            Some(_) => return Err(unknown()),
            None => (s, None),
        };
        Ok(match (mode, file) {
            ("free", None) => Self::Free,
            ("circle", None) => Self::Circle,
            ("rectangle", None) => Self::Rectangle,
            ("scale", Some(f)) => Self::Scale(f),
            ("angles", Some(f)) => Self::Angles(f),
            ("polygon", Some(f)) => Self::Polygon(f),
            _ => return Err(unknown()),
        })
    }

    /// The file the caller must read and pass to [`Self::into_boundary`], if any.
    pub fn file(&self) -> Option<&std::path::Path> {
        match self {
            Self::Scale(f) | Self::Angles(f) | Self::Polygon(f) => Some(f),
            _ => None,
        }
    }

    /// The target, with the text of [`Self::file`] (angles in degrees are converted to
    /// radians) and the rectangle's options (ignored by the other modes).
    ///
    /// # Errors
    /// [`DiskError::BoundaryFile`] for a malformed line (naming the file and line);
    /// [`DiskError::InvalidOption`] when a file-taking mode gets no text.
    ///
    /// # Examples
    /// ```
    /// use conformap_disk::{BoundarySpec, FlattenBoundary};
    /// let spec = BoundarySpec::parse("polygon:tri.txt")?;
    /// let target = spec.into_boundary(Some("0 120\n# a comment\n5 120\n9 120\n"), None, None)?;
    /// let FlattenBoundary::Polygon(c) = target else { unreachable!() };
    /// assert_eq!(c.len(), 3);
    /// assert!((c[1].1 - 2.0 * std::f64::consts::PI / 3.0).abs() < 1e-15);
    /// # Ok::<(), conformap_disk::DiskError>(())
    /// ```
    pub fn into_boundary(
        self,
        text: Option<&str>,
        corners: Option<[u32; 4]>,
        aspect: Option<f64>,
    ) -> Result<FlattenBoundary, DiskError> {
        let read = |f: &PathBuf, degrees: bool| {
            let text = text.ok_or(DiskError::InvalidOption {
                name: "boundary",
                reason: "this boundary mode needs the text of its file",
            })?;
            parse_boundary_values(text, &f.display().to_string(), degrees)
        };
        Ok(match &self {
            Self::Free => FlattenBoundary::Free,
            Self::Circle => FlattenBoundary::Circle,
            Self::Rectangle => FlattenBoundary::Rectangle { corners, aspect },
            Self::Scale(f) => FlattenBoundary::Scale(read(f, false)?),
            Self::Angles(f) => FlattenBoundary::Angles(read(f, true)?),
            Self::Polygon(f) => FlattenBoundary::Polygon(read(f, true)?),
        })
    }
}

impl std::str::FromStr for BoundarySpec {
    type Err = DiskError;

    /// [`BoundarySpec::parse`].
    fn from_str(s: &str) -> Result<Self, DiskError> {
        Self::parse(s)
    }
}

/// Parses a boundary file: one `<0-based vertex> <value>` per line, blank lines and lines
/// starting with `#` skipped; `degrees` converts the values to radians. `source` names the
/// file in errors.
///
/// # Errors
/// [`DiskError::BoundaryFile`] naming `source` and the 1-based line: a line without two
/// fields, a vertex that is not a non-negative integer, a value that is not a finite number,
/// or extra fields.
///
/// # Examples
/// ```
/// use conformap_disk::parse_boundary_values;
/// let v = parse_boundary_values("3 0.5\n7 -0.25\n", "u.txt", false)?;
/// assert_eq!(v, vec![(3, 0.5), (7, -0.25)]);
/// let e = parse_boundary_values("3 0.5\n7 x\n", "u.txt", false).unwrap_err();
/// assert!(e.to_string().contains("u.txt:2") && e.to_string().contains("hint:"));
/// # Ok::<(), conformap_disk::DiskError>(())
/// ```
pub fn parse_boundary_values(
    text: &str,
    source: &str,
    degrees: bool,
) -> Result<Vec<(u32, f64)>, DiskError> {
    let mut out = Vec::new();
    for (n, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let bad = |reason: String| DiskError::BoundaryFile {
            file: source.to_string(),
            line: n + 1,
            reason,
        };
        let mut fields = line.split_whitespace();
        let (Some(v), Some(x)) = (fields.next(), fields.next()) else {
            return Err(bad(format!("expected two fields, found {line:?}")));
        };
        if let Some(extra) = fields.next() {
            return Err(bad(format!("unexpected third field {extra:?}")));
        }
        let vertex: u32 = v
            .parse()
            .map_err(|_| bad(format!("{v:?} is not a 0-based vertex index")))?;
        let value: f64 = x
            .parse()
            .ok()
            .filter(|x: &f64| x.is_finite())
            .ok_or_else(|| bad(format!("{x:?} is not a finite number")))?;
        out.push((vertex, if degrees { value.to_radians() } else { value }));
    }
    Ok(out)
}
