//! Named landmarks: parsing `<0-based vertex index> <name>` lines and the checks that make
//! a set of landmark lists usable (range, repeats, the same names in the same order).

use crate::MorphError;

/// The landmarks of one surface: vertex indices with their names, in file order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Landmarks {
    vertices: Vec<u32>,
    names: Vec<String>,
}

impl Landmarks {
    /// Landmarks from `(vertex, name)` pairs, in order. Nothing is checked here beyond the
    /// count (see [`Self::check_against`] for the checks against a mesh).
    ///
    /// # Errors
    /// [`MorphError::TooFewLandmarks`] for fewer than two.
    pub fn new(pairs: Vec<(u32, String)>) -> Result<Self, MorphError> {
        if pairs.len() < 2 {
            return Err(MorphError::TooFewLandmarks { found: pairs.len() });
        }
        let (vertices, names) = pairs.into_iter().unzip();
        Ok(Self { vertices, names })
    }

    /// Parses the text of a landmark file: one `<0-based vertex index> <name>` per line
    /// (the name is the rest of the line, trimmed; it may not be empty). Blank lines and
    /// lines starting with `#` are skipped.
    ///
    /// # Errors
    /// [`MorphError::LandmarkSyntax`] naming the 1-based line; [`MorphError::TooFewLandmarks`].
    ///
    /// # Examples
    /// ```
    /// use conformap_morph::Landmarks;
    /// let l = Landmarks::parse("# face\n4857 nose_tip\n3742 left_eye_inner\n")?;
    /// assert_eq!(l.vertices(), &[4857, 3742]);
    /// assert_eq!(l.names()[1], "left_eye_inner");
    /// assert!(Landmarks::parse("12 nose\nx eye\n").is_err()); // line 2: not an index
    /// # Ok::<(), conformap_morph::MorphError>(())
    /// ```
    pub fn parse(text: &str) -> Result<Self, MorphError> {
        let mut pairs = Vec::new();
        for (k, raw) in text.lines().enumerate() {
            let line = raw.trim();
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let syntax = |reason: String| MorphError::LandmarkSyntax {
                line: k + 1,
                reason,
            };
            let (index, name) = line
                .split_once(char::is_whitespace)
                .ok_or_else(|| syntax(format!("expected `<vertex> <name>`, found {line:?}")))?;
            let vertex: u64 = index.parse().map_err(|_| {
                syntax(format!(
                    "{index:?} is not a 0-based vertex index (a non-negative integer)"
                ))
            })?;
            let vertex = u32::try_from(vertex)
                .map_err(|_| syntax(format!("vertex index {vertex} is too large")))?;
            pairs.push((vertex, name.trim().to_string()));
        }
        Self::new(pairs)
    }

    /// The vertex indices, in order.
    pub fn vertices(&self) -> &[u32] {
        &self.vertices
    }

    /// The names, in order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Number of landmarks.
    pub fn len(&self) -> usize {
        self.vertices.len()
    }

    /// Always `false` (a landmark list holds at least two).
    pub fn is_empty(&self) -> bool {
        self.vertices.is_empty()
    }

    /// Checks the landmarks of surface `surface` against its vertex count: every index in
    /// range, no vertex and no name twice.
    ///
    /// # Errors
    /// [`MorphError::LandmarkOutOfRange`], [`MorphError::RepeatedLandmark`].
    pub fn check_against(&self, surface: usize, vertices: usize) -> Result<(), MorphError> {
        for (j, &v) in self.vertices.iter().enumerate() {
            if v as usize >= vertices {
                return Err(MorphError::LandmarkOutOfRange {
                    surface,
                    name: self.names[j].clone(),
                    vertex: u64::from(v),
                    vertices,
                });
            }
        }
        if let Some((first, second)) = first_repeat(&self.vertices) {
            return Err(MorphError::RepeatedLandmark {
                surface,
                first,
                second,
                what: "same vertex",
            });
        }
        if let Some((first, second)) = first_repeat(&self.names) {
            return Err(MorphError::RepeatedLandmark {
                surface,
                first,
                second,
                what: "same name",
            });
        }
        Ok(())
    }

    /// Checks that surface `surface`'s landmarks have the names of `reference` (surface
    /// 0's) in the same order.
    ///
    /// # Errors
    /// [`MorphError::LandmarkMismatch`] at the first position that differs.
    pub fn check_same_names(&self, surface: usize, reference: &Self) -> Result<(), MorphError> {
        let n = self.len().max(reference.len());
        for index in 0..n {
            let expected = reference.names.get(index);
            let found = self.names.get(index);
            if expected != found {
                let show = |s: Option<&String>| s.cloned().unwrap_or_else(|| "<none>".into());
                return Err(MorphError::LandmarkMismatch {
                    surface,
                    index,
                    expected: show(expected),
                    found: show(found),
                });
            }
        }
        Ok(())
    }
}

/// The first pair of positions `(i, j)`, `i < j`, holding equal items (smallest `j`).
fn first_repeat<T: Ord>(items: &[T]) -> Option<(usize, usize)> {
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by(|&a, &b| items[a].cmp(&items[b]).then(a.cmp(&b)));
    order
        .windows(2)
        .filter(|w| items[w[0]] == items[w[1]])
        .map(|w| (w[0], w[1]))
        .min_by_key(|&(_, j)| j)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parsed(text: &str) -> Landmarks {
        match Landmarks::parse(text) {
            Ok(l) => l,
            Err(e) => panic!("{e}"),
        }
    }

    #[test]
    fn syntax_errors_name_the_line() {
        let cases = [
            ("1 a\n\n-3 b\n", 3),
            ("1 a\n2\n", 2),
            ("1 a\n99999999999 b\n", 2),
            ("# c\n1.5 a\n2 b\n", 2),
        ];
        for (text, line) in cases {
            match Landmarks::parse(text) {
                Err(MorphError::LandmarkSyntax { line: l, .. }) => assert_eq!(l, line, "{text:?}"),
                other => panic!("{text:?}: {other:?}"),
            }
        }
        assert_eq!(
            Landmarks::parse("5 nose\n"),
            Err(MorphError::TooFewLandmarks { found: 1 })
        );
    }

    #[test]
    fn range_and_repeats_are_refused() {
        let l = parsed("0 a\n7 b\n3 c\n");
        assert!(l.check_against(0, 8).is_ok());
        assert!(matches!(
            l.check_against(2, 7),
            Err(MorphError::LandmarkOutOfRange {
                surface: 2,
                vertex: 7,
                vertices: 7,
                ..
            })
        ));
        let twice = parsed("4 a\n1 b\n4 c\n");
        assert_eq!(
            twice.check_against(1, 10),
            Err(MorphError::RepeatedLandmark {
                surface: 1,
                first: 0,
                second: 2,
                what: "same vertex"
            })
        );
        let named = parsed("4 a\n1 b\n5 b\n");
        assert!(matches!(
            named.check_against(0, 10),
            Err(MorphError::RepeatedLandmark {
                first: 1,
                second: 2,
                what: "same name",
                ..
            })
        ));
    }

    #[test]
    fn names_must_match_in_order() {
        let a = parsed("0 nose\n1 eye\n2 chin\n");
        assert!(parsed("9 nose\n8 eye\n7 chin\n")
            .check_same_names(1, &a)
            .is_ok());
        assert!(matches!(
            parsed("9 nose\n7 chin\n8 eye\n").check_same_names(1, &a),
            Err(MorphError::LandmarkMismatch { index: 1, .. })
        ));
        match parsed("9 nose\n8 eye\n").check_same_names(2, &a) {
            Err(MorphError::LandmarkMismatch {
                surface: 2,
                index: 2,
                found,
                ..
            }) => assert_eq!(found, "<none>"),
            other => panic!("{other:?}"),
        }
    }
}
