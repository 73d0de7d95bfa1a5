//! Making a finished disk map flip-free: the boundary put back in cyclic order on the
//! circle, and the interior re-solved by the guarded harmonic extension.
//!
//! Folds of a disk map have two causes, and each has its fix:
//! - **The boundary is out of order** (CEM on igea_open: boundary vertices step backwards
//!   past their neighbours; the faces between them fold). Fix: the nearest angles, in the
//!   least-squares sense, whose consecutive gaps are all at least a floor (an isotonic
//!   regression along the loop), then the harmonic extension. A convex boundary makes the
//!   extension an embedding when the weights are non-negative.
//! - **Negative cotangent weights** fold the interior of a harmonic map even with the
//!   boundary in order. Fix: [`DiskProblem::guarded_extension`] re-solves the interior
//!   with the intrinsic Delaunay Laplacian (no negative interior weight) and, if input
//!   faces still fold, with Floater's mean value weights (positive on the input
//!   triangulation: one-to-one for a boundary in convex position).
//!
//! What neither fixes is crowding below f64: on long corridors (maze.obj) the conformal
//! map needs boundary gaps far below what an angle near `2π` resolves (`ulp(2π) ≈ 9e-16`),
//! and the harmonic extension of such a boundary folds in rounding. The floor is then
//! raised ×[`GAP_FLOOR_STEP`] up to [`GAP_FLOOR_MAX`] (or a tenth of the mean gap), as CCEM
//! does; beyond that the map is refused with [`DiskError::Folded`].

use std::f64::consts::{PI, TAU};

use num_complex::Complex64;

use crate::angles::{largest_gap, project_to_floor};
use crate::angles::{GAP_FLOOR_MAX, GAP_FLOOR_STEP, UNFOLD_MIN_GAP};
use crate::laplacian_choice::{count_flipped, InteriorOperator, LaplacianKind};
use crate::problem::DiskProblem;
use crate::DiskError;

/// What [`unfold_disk_map`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct Unfolded {
    /// The map: the input if it did not fold, else the repaired one.
    pub map: Vec<Complex64>,
    /// Faces the input folded.
    pub flipped_before: usize,
    /// Faces the returned map folds (0 unless the input did and could not be repaired
    /// without changing it: never returned, see the errors).
    pub flipped_after: usize,
    /// Boundary gaps of the input below the floor (backward steps included) that the
    /// ordering changed; 0 if the boundary was kept.
    pub repaired_gaps: usize,
    /// The floor of the ordered boundary, radians (0 if the boundary was kept).
    pub gap_floor: f64,
    /// The operator the returned interior solves.
    pub operator: InteriorOperator,
}

impl Unfolded {
    /// A line for a solver report, or `None` if nothing was changed.
    pub fn note(&self) -> Option<String> {
        if self.flipped_before == 0 {
            return None;
        }
        let how = match self.repaired_gaps {
            0 => format!(
                "the interior re-solved with the {} operator",
                self.operator.name()
            ),
            k => format!(
                "the boundary put back in order ({k} gaps below {:.0e} rad repaired), the \
                 interior solved with the {} operator",
                self.gap_floor,
                self.operator.name()
            ),
        };
        Some(format!(
            "the map folded {} faces: {how}; 0 folded faces now",
            self.flipped_before
        ))
    }
}

/// Makes `map` (a disk map of `problem`'s mesh, boundary on the unit circle) flip-free:
/// unchanged if no face folds; else the interior re-solved by
/// [`DiskProblem::guarded_extension`]; if faces still fold, the boundary angles replaced
/// by the nearest ones (least squares) in cyclic order with every gap at least
/// `1e-13` rad, raising that floor ×1000 while faces fold, up to
/// `1e-4` rad or a tenth of the mean gap `2π / n_B`.
///
/// # Errors
/// [`DiskError::Folded`] if no floor gives a flip-free map (or the boundary does not wind
/// once counter-clockwise around the centre); [`DiskError::Operator`] if the intrinsic
/// Laplacian cannot be factored.
pub fn unfold_disk_map(
    problem: &DiskProblem<'_>,
    map: &[Complex64],
) -> Result<Unfolded, DiskError> {
    let (flips, first) = count_flipped(problem.mesh(), map);
    let mut out = Unfolded {
        map: map.to_vec(),
        flipped_before: flips,
        flipped_after: flips,
        repaired_gaps: 0,
        gap_floor: 0.0,
        operator: match problem.laplacian_kind() {
            LaplacianKind::IntrinsicDelaunay => InteriorOperator::IntrinsicDelaunay,
            _ => InteriorOperator::Cotan,
        },
    };
    if flips == 0 {
        return Ok(out);
    }
    let fb = problem.partition().boundary_values(map);
    let y = unwrapped_angles(&fb);
    let n = y.len();
    let mut folded = DiskError::Folded {
        flipped_faces: flips,
        face: first.unwrap_or(0),
        held_gaps: 0,
        floor: 0.0,
    };
    // a boundary vertex that stepped backwards past its neighbour folds the face on that
    // boundary edge whatever the interior operator: re-solving the interior with the
    // reserve operators first could not help, and costs their factorizations (igea_open
    // with CEM: 470 MiB and 1.4 s for the intrinsic and mean-value solves, then the
    // reordering below fixed it)
    let backwards =
        n >= 2 && (y.windows(2).any(|w| w[1] - w[0] <= 0.0) || (fb[0] / fb[n - 1]).arg() <= 0.0);
    if !backwards {
        let g = problem.guarded_extension(&fb)?;
        if g.flipped_faces == 0 {
            out.map = g.map;
            out.flipped_after = 0;
            out.operator = g.operator;
            return Ok(out);
        }
        folded = DiskError::Folded {
            flipped_faces: g.flipped_faces,
            face: g.first_flipped.or(first).unwrap_or(0),
            held_gaps: 0,
            floor: 0.0,
        };
    }
    if n < 3 {
        return Err(folded);
    }
    // one counter-clockwise turn: the unwrapped steps, the closing one included, sum to 2π
    let winding = y[n - 1] - y[0] + (fb[0] / fb[n - 1]).arg();
    if !((winding - TAU).abs() < PI) {
        return Err(folded);
    }
    let cut = largest_gap(&y);
    let floor_max = GAP_FLOOR_MAX.min(0.1 * TAU / n as f64);
    let mut floor = UNFOLD_MIN_GAP;
    while floor <= floor_max {
        let Some(theta) = project_to_floor(&y, floor, cut) else {
            break;
        };
        let repaired = (0..n)
            .filter(|&k| {
                let next = if k + 1 < n { y[k + 1] } else { y[0] + TAU };
                next - y[k] < floor
            })
            .count();
        let fb: Vec<Complex64> = theta
            .iter()
            .map(|&t| Complex64::from_polar(1.0, t))
            .collect();
        let g = problem.guarded_extension(&fb)?;
        if g.flipped_faces == 0 {
            out.map = g.map;
            out.flipped_after = 0;
            out.repaired_gaps = repaired;
            out.gap_floor = floor;
            out.operator = g.operator;
            return Ok(out);
        }
        folded = DiskError::Folded {
            flipped_faces: g.flipped_faces,
            face: g.first_flipped.unwrap_or(0),
            held_gaps: repaired,
            floor,
        };
        floor *= GAP_FLOOR_STEP;
    }
    Err(folded)
}

/// Angles of `fb` unwrapped along the loop: each step the principal value of
/// `arg(f_{k+1} / f_k)` in `(−π, π]`, so a backward step is a negative gap.
fn unwrapped_angles(fb: &[Complex64]) -> Vec<f64> {
    let mut y = Vec::with_capacity(fb.len());
    let mut t = fb.first().map_or(0.0, |z| z.arg());
    for (k, z) in fb.iter().enumerate() {
        if k > 0 {
            t += (z / fb[k - 1]).arg();
        }
        y.push(t);
    }
    y
}
