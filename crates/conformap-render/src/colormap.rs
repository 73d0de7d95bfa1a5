//! Colour maps: a sequential one for non-negative quantities, a diverging one for signed
//! ones, and the flag colour of folded faces.

/// Colour of flipped (folded) and degenerate faces: magenta, outside both colour maps.
pub const FLAG_COLOR: [f32; 3] = [1.0, 0.0, 1.0];

/// Colours of [`crate::ColorBy::Chart`]: 10 light, distinct hues (Tableau-like, lightened
/// so the shading and the mesh edges stay visible), none of them the flag colour.
pub const CHART_COLORS: [[f32; 3]; 10] = [
    [0.45, 0.62, 0.85],
    [1.00, 0.65, 0.35],
    [0.50, 0.80, 0.45],
    [0.95, 0.45, 0.45],
    [0.70, 0.58, 0.85],
    [0.72, 0.55, 0.45],
    [0.95, 0.65, 0.85],
    [0.65, 0.65, 0.65],
    [0.85, 0.85, 0.40],
    [0.40, 0.85, 0.85],
];

/// Sequential map (a viridis-like ramp, dark purple → blue → green → yellow), 9 stops.
const SEQUENTIAL: [[f32; 3]; 9] = [
    [0.267, 0.005, 0.329],
    [0.279, 0.175, 0.483],
    [0.230, 0.322, 0.546],
    [0.173, 0.449, 0.558],
    [0.128, 0.567, 0.551],
    [0.153, 0.683, 0.503],
    [0.369, 0.789, 0.383],
    [0.678, 0.864, 0.190],
    [0.993, 0.906, 0.144],
];

/// Diverging map (blue → white → red, like ColorBrewer's RdBu reversed), 7 stops.
const DIVERGING: [[f32; 3]; 7] = [
    [0.129, 0.400, 0.675],
    [0.404, 0.663, 0.812],
    [0.820, 0.898, 0.941],
    [0.969, 0.969, 0.969],
    [0.992, 0.859, 0.780],
    [0.937, 0.541, 0.384],
    [0.698, 0.094, 0.169],
];

fn ramp(stops: &[[f32; 3]], t: f64) -> [f32; 3] {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let x = t * (stops.len() - 1) as f64;
    let i = (x.floor() as usize).min(stops.len() - 2);
    let f = (x - i as f64) as f32;
    let (a, b) = (stops[i], stops[i + 1]);
    [
        a[0] + f * (b[0] - a[0]),
        a[1] + f * (b[1] - a[1]),
        a[2] + f * (b[2] - a[2]),
    ]
}

/// A colour scale: a map and the value range it spans (values outside are clamped).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Scale {
    /// Value at the low end.
    pub lo: f64,
    /// Value at the high end.
    pub hi: f64,
    /// Whether the diverging map is used (else the sequential one).
    pub diverging: bool,
}

impl Scale {
    /// The colour of `value`.
    #[inline]
    pub fn color(&self, value: f64) -> [f32; 3] {
        let t = if self.hi > self.lo {
            (value - self.lo) / (self.hi - self.lo)
        } else {
            0.0
        };
        if self.diverging {
            ramp(&DIVERGING, t)
        } else {
            ramp(&SEQUENTIAL, t)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn near(a: [f32; 3], b: [f32; 3]) -> bool {
        a.iter().zip(&b).all(|(x, y)| (x - y).abs() < 1e-5)
    }

    #[test]
    fn ends_and_clamping() {
        let s = Scale {
            lo: -1.0,
            hi: 1.0,
            diverging: true,
        };
        assert!(near(s.color(-5.0), DIVERGING[0]));
        assert!(near(s.color(1.0), DIVERGING[6]));
        assert!(near(s.color(0.0), DIVERGING[3]));
        let q = Scale {
            lo: 0.0,
            hi: 2.0,
            diverging: false,
        };
        assert!(near(q.color(f64::NAN), SEQUENTIAL[0]));
        assert!(near(q.color(2.0), SEQUENTIAL[8]));
    }
}
