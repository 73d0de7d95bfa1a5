//! A skyline packer: rectangles placed one by one at the lowest spot of a bin of fixed width
//! (bottom-left rule), the bin's filled outline kept as a list of horizontal segments.

/// One horizontal piece of the skyline: `[x, x + width)` is filled up to `y`.
#[derive(Debug, Clone, Copy)]
struct Segment {
    x: f64,
    y: f64,
    width: f64,
}

/// Where a rectangle went.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Spot {
    /// Lower-left corner.
    pub x: f64,
    /// Lower-left corner.
    pub y: f64,
    /// Whether the rectangle was turned a quarter (its width and height swapped).
    pub turned: bool,
}

/// Places `sizes` (width, height; in the given order) in a bin of width `bin_width`, each at
/// the spot where its top ends lowest (ties: leftmost), turned a quarter when `turn` and
/// that ends lower. Returns the spots and the height used; `None` when a rectangle is wider
/// than the bin in every allowed orientation.
pub(crate) fn pack(sizes: &[[f64; 2]], bin_width: f64, turn: bool) -> Option<(Vec<Spot>, f64)> {
    let mut sky = vec![Segment {
        x: 0.0,
        y: 0.0,
        width: bin_width,
    }];
    let mut spots = Vec::with_capacity(sizes.len());
    let mut height: f64 = 0.0;
    for &[w, h] in sizes {
        let mut best: Option<(f64, f64, f64, usize, bool)> = None; // top, x, y, segment, turned
        for (turned, (ww, hh)) in [(false, (w, h)), (true, (h, w))] {
            if turned && (!turn || w == h) {
                continue;
            }
            for i in 0..sky.len() {
                if let Some(y) = fits(&sky, i, ww, bin_width) {
                    let top = y + hh;
                    let better = match best {
                        None => true,
                        Some((bt, bx, ..)) => top < bt || (top == bt && sky[i].x < bx),
                    };
                    if better {
                        best = Some((top, sky[i].x, y, i, turned));
                    }
                }
            }
        }
        // the bottom is kept as found (top − height would round differently)
        let (top, x, y, i, turned) = best?;
        let ww = if turned { h } else { w };
        place(&mut sky, i, x, top, ww);
        spots.push(Spot { x, y, turned });
        height = height.max(top);
    }
    Some((spots, height))
}

/// The height at which a rectangle of width `w` rests when its left side is at segment
/// `i`'s start, or `None` when it runs past the bin.
fn fits(sky: &[Segment], i: usize, w: f64, bin_width: f64) -> Option<f64> {
    let x = sky[i].x;
    if x + w > bin_width * (1.0 + 1e-12) {
        return None;
    }
    let mut y: f64 = 0.0;
    let mut covered = 0.0;
    for s in &sky[i..] {
        y = y.max(s.y);
        covered += s.width;
        if covered >= w {
            break;
        }
    }
    Some(y)
}

/// Puts a rectangle of width `w` with its top at `top` on the skyline at segment `i`.
fn place(sky: &mut Vec<Segment>, i: usize, x: f64, top: f64, w: f64) {
    let end = x + w;
    let mut j = i;
    // segments under the rectangle are cut away (the last one may keep its right part)
    while j < sky.len() && sky[j].x < end {
        let s_end = sky[j].x + sky[j].width;
        if s_end > end {
            sky[j].width = s_end - end;
            sky[j].x = end;
            break;
        }
        j += 1;
    }
    sky.splice(
        i..j,
        [Segment {
            x,
            y: top,
            width: w,
        }],
    );
    // neighbours at the same height merge
    let mut k = 0;
    while k + 1 < sky.len() {
        if sky[k].y == sky[k + 1].y {
            sky[k].width += sky[k + 1].width;
            sky.remove(k + 1);
        } else {
            k += 1;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn disjoint(sizes: &[[f64; 2]], spots: &[Spot]) -> bool {
        let rect = |k: usize| {
            let [w, h] = sizes[k];
            let (w, h) = if spots[k].turned { (h, w) } else { (w, h) };
            (spots[k].x, spots[k].y, spots[k].x + w, spots[k].y + h)
        };
        (0..sizes.len()).all(|a| {
            (a + 1..sizes.len()).all(|b| {
                let (p, q) = (rect(a), rect(b));
                p.2 <= q.0 || q.2 <= p.0 || p.3 <= q.1 || q.3 <= p.1
            })
        })
    }

    #[test]
    fn four_squares_fill_a_bin_exactly() {
        let sizes = [[1.0, 1.0]; 4];
        let (spots, h) = pack(&sizes, 2.0, true).expect("fits");
        assert_eq!(h, 2.0);
        assert!(disjoint(&sizes, &spots));
    }

    #[test]
    fn many_rectangles_do_not_overlap_and_fill_well() {
        // a deterministic spread of sizes, sorted by height as the packer's caller does
        let mut sizes: Vec<[f64; 2]> = (0..200)
            .map(|k| {
                let a = ((k * 7919) % 97) as f64 / 97.0;
                let b = ((k * 104729) % 89) as f64 / 89.0;
                [1.0 + 9.0 * a, 1.0 + 4.0 * b]
            })
            .collect();
        sizes.sort_by(|a, b| b[1].total_cmp(&a[1]));
        let (spots, h) = pack(&sizes, 60.0, true).expect("fits");
        assert!(disjoint(&sizes, &spots));
        let area: f64 = sizes.iter().map(|s| s[0] * s[1]).sum();
        assert!(area / (60.0 * h) > 0.8, "fill {}", area / (60.0 * h));
        assert!(pack(&[[70.0, 80.0]], 60.0, true).is_none());
        assert!(pack(&[[70.0, 50.0]], 60.0, true).expect("turned").0[0].turned);
    }
}
