//! The OFF keyword (`OFF`, `COFF`, `STOFF`, …), shared by
//! [`Format::sniff`](crate::Format::sniff) and the OFF reader.

/// Whether the first word of `text` is an OFF keyword (for
/// [`Format::sniff`](crate::Format::sniff)).
pub(crate) fn is_off_header(text: &[u8]) -> bool {
    let word = text
        .split(|b| b.is_ascii_whitespace())
        .find(|w| !w.is_empty())
        .unwrap_or_default();
    keyword_prefixes(word).is_some()
}

/// The prefixes of an OFF keyword (`ST`, `C`, `N`, `4`, `n` before `OFF`), `None` if the
/// word is not one.
pub(crate) fn keyword_prefixes(word: &[u8]) -> Option<&[u8]> {
    let prefix = word.strip_suffix(b"OFF")?;
    let allowed = [&b"ST"[..], b"C", b"N", b"4", b"n"];
    let mut rest = prefix;
    for a in allowed {
        rest = rest.strip_prefix(a).unwrap_or(rest);
    }
    rest.is_empty().then_some(prefix)
}
