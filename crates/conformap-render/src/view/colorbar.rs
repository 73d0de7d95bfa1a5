//! The colour bar of a per-face quantity: the colour ramp with its range, what it shows,
//! and the count of folded faces in the flag colour.

use crate::colormap::FLAG_COLOR;
use crate::faces::FaceField;
use crate::font::{draw_text, format_value, text_width, GLYPH_H};
use crate::image::Image;

/// Share of the picture's width kept for the colour bar at its right: 0.16.
const BAR_SHARE: f64 = 0.16;
/// Colour of the bar's frame and text.
const INK: [u8; 3] = [20, 20, 20];

/// Width in pixels of the strip a colour bar needs in a picture of `size` pixels.
pub(crate) fn width(size: u32) -> u32 {
    ((size as f64 * BAR_SHARE) as u32).max(40)
}

fn to_u8(c: [f32; 3]) -> [u8; 3] {
    c.map(|x| (x * 255.0 + 0.5).clamp(0.0, 255.0) as u8)
}

/// Draws the colour bar of `field` into the right strip of `image`.
pub(crate) fn draw(image: &mut Image, field: &FaceField) {
    let (w, h) = (image.width() as i64, image.height() as i64);
    let bar_w = width(image.width()) as i64;
    let left = w - bar_w;
    let strip_x0 = left + bar_w / 12;
    let strip_x1 = strip_x0 + (bar_w * 2 / 9).max(6);
    let (y0, y1) = (h * 3 / 20, h * 17 / 20);
    let s = field.scale;
    let hi_label = format!(
        "{}{}{}",
        if field.clipped_hi { ">" } else { "" },
        format_value(s.hi),
        field.unit
    );
    let lo_label = format!(
        "{}{}{}",
        if field.clipped_lo { "<" } else { "" },
        format_value(s.lo),
        field.unit
    );
    let mid_label = format!("{}{}", format_value(0.5 * (s.lo + s.hi)), field.unit);
    let room = w - strip_x1 - bar_w / 16 - 2;
    let longest = [&hi_label, &lo_label, &mid_label]
        .iter()
        .map(|t| text_width(t, 1))
        .max()
        .unwrap_or(1)
        .max(text_width(field.title, 1))
        .max(text_width("folded", 1));
    let k = (room / longest.max(1)).clamp(1, (h / 300).max(1));

    // the ramp, top = hi
    for y in y0..y1 {
        let t = (y1 - 1 - y) as f64 / (y1 - 1 - y0).max(1) as f64;
        let c = to_u8(s.color(s.lo + t * (s.hi - s.lo)));
        image.fill_rect(strip_x0, y, strip_x1, y + 1, c);
    }
    // frame
    image.fill_rect(strip_x0 - 1, y0 - 1, strip_x1 + 1, y0, INK);
    image.fill_rect(strip_x0 - 1, y1, strip_x1 + 1, y1 + 1, INK);
    image.fill_rect(strip_x0 - 1, y0 - 1, strip_x0, y1 + 1, INK);
    image.fill_rect(strip_x1, y0 - 1, strip_x1 + 1, y1 + 1, INK);
    // labels at the top, middle and bottom, with ticks
    let tx = strip_x1 + bar_w / 16;
    let half = GLYPH_H * k / 2;
    for (y, text) in [
        (y0, &hi_label),
        ((y0 + y1) / 2, &mid_label),
        (y1 - 1, &lo_label),
    ] {
        image.fill_rect(strip_x1, y, tx - 2, y + 1, INK);
        draw_text(image, tx, y - half, text, k, INK);
    }
    // title above
    draw_text(image, strip_x0, y0 - GLYPH_H * k * 2, field.title, k, INK);
    // folded faces in the flag colour
    if field.flagged > 0 {
        let y = y1 + GLYPH_H * k;
        let box_side = GLYPH_H * k;
        image.fill_rect(
            strip_x0,
            y,
            strip_x0 + box_side,
            y + box_side,
            to_u8(FLAG_COLOR),
        );
        draw_text(image, strip_x0 + box_side + 2 * k, y, "folded", k, INK);
        draw_text(
            image,
            strip_x0,
            y + box_side + 2 * k,
            &field.flagged.to_string(),
            k,
            INK,
        );
    }
}
