//! A built-in 5×7 bitmap font for the few labels of colour bars and histograms (digits,
//! signs and a handful of lower-case letters): no system fonts.

use crate::image::Image;

/// Glyph width in font pixels (plus one of spacing).
pub(crate) const GLYPH_W: i64 = 5;
/// Glyph height in font pixels.
pub(crate) const GLYPH_H: i64 = 7;

/// The glyph of `c`, seven rows of five columns (`#` set); `None` for characters the font
/// does not have (drawn as a blank).
fn glyph(c: char) -> Option<[&'static str; 7]> {
    Some(match c {
        '0' => [
            " ### ", "#   #", "#  ##", "# # #", "##  #", "#   #", " ### ",
        ],
        '1' => [
            "  #  ", " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        '2' => [
            " ### ", "#   #", "    #", "   # ", "  #  ", " #   ", "#####",
        ],
        '3' => [
            "#####", "   # ", "  #  ", "   # ", "    #", "#   #", " ### ",
        ],
        '4' => [
            "   # ", "  ## ", " # # ", "#  # ", "#####", "   # ", "   # ",
        ],
        '5' => [
            "#####", "#    ", "#### ", "    #", "    #", "#   #", " ### ",
        ],
        '6' => [
            "  ## ", " #   ", "#    ", "#### ", "#   #", "#   #", " ### ",
        ],
        '7' => [
            "#####", "    #", "   # ", "  #  ", " #   ", " #   ", " #   ",
        ],
        '8' => [
            " ### ", "#   #", "#   #", " ### ", "#   #", "#   #", " ### ",
        ],
        '9' => [
            " ### ", "#   #", "#   #", " ####", "    #", "   # ", " ##  ",
        ],
        '.' => [
            "     ", "     ", "     ", "     ", "     ", " ##  ", " ##  ",
        ],
        '-' => [
            "     ", "     ", "     ", "#####", "     ", "     ", "     ",
        ],
        '+' => [
            "     ", "  #  ", "  #  ", "#####", "  #  ", "  #  ", "     ",
        ],
        '>' => [
            "#    ", " #   ", "  #  ", "   # ", "  #  ", " #   ", "#    ",
        ],
        '<' => [
            "    #", "   # ", "  #  ", " #   ", "  #  ", "   # ", "    #",
        ],
        '°' => [
            " ##  ", "#  # ", "#  # ", " ##  ", "     ", "     ", "     ",
        ],
        '|' => [
            "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ",
        ],
        'a' => [
            "     ", "     ", " ### ", "    #", " ####", "#   #", " ####",
        ],
        'c' => [
            "     ", "     ", " ### ", "#    ", "#    ", "#   #", " ### ",
        ],
        'd' => [
            "    #", "    #", " ## #", "#  ##", "#   #", "#   #", " ####",
        ],
        'e' => [
            "     ", "     ", " ### ", "#   #", "#####", "#    ", " ### ",
        ],
        'f' => [
            "  ## ", " #  #", " #   ", "###  ", " #   ", " #   ", " #   ",
        ],
        'g' => [
            "     ", " ####", "#   #", "#   #", " ####", "    #", " ### ",
        ],
        'i' => [
            "  #  ", "     ", " ##  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        'l' => [
            " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        'm' => [
            "     ", "     ", "## # ", "# # #", "# # #", "#   #", "#   #",
        ],
        'n' => [
            "     ", "     ", "# ## ", "##  #", "#   #", "#   #", "#   #",
        ],
        'o' => [
            "     ", "     ", " ### ", "#   #", "#   #", "#   #", " ### ",
        ],
        'r' => [
            "     ", "     ", "# ## ", "##  #", "#    ", "#    ", "#    ",
        ],
        's' => [
            "     ", "     ", " ####", "#    ", " ### ", "    #", "#### ",
        ],
        't' => [
            " #   ", " #   ", "###  ", " #   ", " #   ", " #  #", "  ## ",
        ],
        'u' => [
            "     ", "     ", "#   #", "#   #", "#   #", "#  ##", " ## #",
        ],
        'x' => [
            "     ", "     ", "#   #", " # # ", "  #  ", " # # ", "#   #",
        ],
        'μ' => [
            "     ", "     ", "#   #", "#   #", "#   #", "## ##", "# ## ",
        ],
        ' ' => ["     "; 7],
        _ => return None,
    })
}

/// Width in picture pixels of `text` at font scale `scale`.
pub(crate) fn text_width(text: &str, scale: i64) -> i64 {
    let n = text.chars().count() as i64;
    if n == 0 {
        0
    } else {
        scale * (n * (GLYPH_W + 1) - 1)
    }
}

/// Draws `text` with its top-left corner at `(x, y)`, each font pixel a `scale × scale`
/// square of `color`.
pub(crate) fn draw_text(image: &mut Image, x: i64, y: i64, text: &str, scale: i64, color: [u8; 3]) {
    let mut cx = x;
    for c in text.chars() {
        if let Some(rows) = glyph(c) {
            for (r, row) in rows.iter().enumerate() {
                for (k, b) in row.chars().enumerate() {
                    if b == '#' {
                        let px = cx + k as i64 * scale;
                        let py = y + r as i64 * scale;
                        image.fill_rect(px, py, px + scale, py + scale, color);
                    }
                }
            }
        }
        cx += (GLYPH_W + 1) * scale;
    }
}

/// A number with three significant digits at most, no exponent, trailing zeros dropped
/// (`0`, `0.125`, `12.3`, `1250`).
pub(crate) fn format_value(x: f64) -> String {
    if !x.is_finite() {
        return "-".to_string();
    }
    let a = x.abs();
    let s = if a >= 100.0 {
        format!("{x:.0}")
    } else if a >= 10.0 {
        format!("{x:.1}")
    } else if a >= 1.0 {
        format!("{x:.2}")
    } else if a >= 0.001 {
        format!("{x:.3}")
    } else if a > 0.0 {
        format!("{x:.6}")
    } else {
        "0".to_string()
    };
    if s.contains('.') {
        let t = s.trim_end_matches('0').trim_end_matches('.');
        if t == "-0" {
            "0".to_string()
        } else {
            t.to_string()
        }
    } else {
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_glyph_is_five_by_seven() {
        for c in "0123456789.-+<>°|acdefgilmnorstuxμ ".chars() {
            let g = glyph(c).expect("glyph");
            assert!(g.iter().all(|r| r.chars().count() == 5), "{c}");
        }
    }

    #[test]
    fn numbers() {
        assert_eq!(format_value(0.0), "0");
        assert_eq!(format_value(12.34), "12.3");
        assert_eq!(format_value(0.1250), "0.125");
        assert_eq!(format_value(-2.5), "-2.5");
        assert_eq!(format_value(1234.0), "1234");
        assert_eq!(text_width("12", 2), 22);
    }

    #[test]
    fn text_is_drawn() {
        let mut img = Image::filled(40, 10, [255; 3]);
        draw_text(&mut img, 1, 1, "8", 1, [0; 3]);
        let dark = img.pixels().filter(|p| p[0] == 0).count();
        assert_eq!(dark, 17);
    }
}
