//! The interior of boundary first flattening (Sawhney & Crane 2017, §4.4): the harmonic
//! extension of the boundary curve's `x` and `y` (two Dirichlet solves with the problem's
//! factor of `L_II`, guarded against folds), or of `x` with `y` as its discrete conjugate
//! (a Neumann solve with the pinned Laplacian).

use num_complex::Complex64;

use super::boundary::PinnedLaplacian;
use crate::laplacian_choice::{count_flipped_where, InteriorOperator};
use crate::{DiskError, DiskProblem};

/// How the interior of the flattening is computed from its boundary curve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[non_exhaustive]
pub enum FlattenInterior {
    /// `x` and `y` both harmonic with the boundary curve as Dirichlet data (the boundary is
    /// met exactly). If faces fold, the interior is re-solved with the intrinsic Delaunay
    /// Laplacian and then Floater's mean value weights
    /// ([`crate::DiskProblem::guarded_extension`]). The default: on the shared meshes it
    /// never folded and its angle distortion was at most the conjugate's.
    #[default]
    Harmonic,
    /// `x` harmonic, `y` its conjugate: the minimizer of the conformal energy `E_D − A` over
    /// `y` with `x` fixed, `L y = b` with `b_k = ½ (x_{k−1} − x_{k+1})` at boundary vertex
    /// `k` (the gradient of the signed image area) and 0 inside; the boundary's `y` then
    /// follows the interior instead of the curve (the paper's variant). Falls back to
    /// [`Self::Harmonic`] where it folds more faces.
    Conjugate,
}

impl FlattenInterior {
    /// The name used in reports: `harmonic` or `conjugate`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Harmonic => "harmonic",
            Self::Conjugate => "conjugate",
        }
    }
}

/// The interior map and what it took.
#[derive(Debug, Clone)]
pub(crate) struct Extension {
    pub map: Vec<Complex64>,
    pub flipped_faces: usize,
    /// Folded faces of the first solve, before any fallback.
    pub flipped_before: usize,
    pub operator: InteriorOperator,
    /// Which variant produced `map`.
    pub variant: FlattenInterior,
}

/// Extends `boundary` (problem boundary order) into the interior.
///
/// # Errors
/// [`DiskError::Operator`] if an operator cannot be factored.
pub(crate) fn extend(
    problem: &DiskProblem<'_>,
    boundary: &[Complex64],
    variant: FlattenInterior,
    pinned: Option<&PinnedLaplacian>,
    ears: &[bool],
    fallback: bool,
) -> Result<Extension, DiskError> {
    if variant == FlattenInterior::Conjugate {
        let map = conjugate(problem, boundary, pinned)?;
        let flips = count_folds(&map, problem, ears);
        if flips == 0 {
            return Ok(Extension {
                map,
                flipped_faces: 0,
                flipped_before: 0,
                operator: InteriorOperator::Cotan,
                variant,
            });
        }
        let mut h = harmonic(problem, boundary, ears, fallback)?;
        h.flipped_before = flips;
        if h.flipped_faces >= flips {
            h.map = map;
            h.flipped_faces = flips;
            h.operator = InteriorOperator::Cotan;
            h.variant = variant;
        }
        return Ok(h);
    }
    harmonic(problem, boundary, ears, fallback)
}

/// Faces with non-positive image area, not counting the `ears` (see [`straight_ears`]).
pub(crate) fn count_folds(map: &[Complex64], problem: &DiskProblem<'_>, ears: &[bool]) -> usize {
    count_flipped_where(problem.mesh(), map, |f| !ears[f])
}

/// Faces whose three vertices are consecutive on the boundary loop with a middle vertex of
/// target curvature exactly 0 (inside a straight side of a rectangle or polygon): their
/// image is a segment by construction — degenerate, not folded, and no interior operator
/// changes it.
pub(crate) fn straight_ears(problem: &DiskProblem<'_>, kappa: &[f64]) -> Vec<bool> {
    let partition = problem.partition();
    let lp = &partition.boundary;
    let m = lp.len();
    problem
        .mesh()
        .faces()
        .iter()
        .map(|t| {
            t.iter().all(|&v| !partition.is_interior[v as usize])
                && t.iter().any(|&b| {
                    let k = partition.local[b as usize] as usize;
                    let (a, c) = (lp[(k + m - 1) % m], lp[(k + 1) % m]);
                    kappa[k] == 0.0 && t.contains(&a) && t.contains(&c)
                })
        })
        .collect()
}

/// The harmonic interior; where it folds and `fallback` is set, the guarded one.
fn harmonic(
    problem: &DiskProblem<'_>,
    boundary: &[Complex64],
    ears: &[bool],
    fallback: bool,
) -> Result<Extension, DiskError> {
    let map = problem.harmonic_extension(boundary);
    let before = count_folds(&map, problem, ears);
    if before == 0 || !fallback {
        return Ok(Extension {
            map,
            flipped_faces: before,
            flipped_before: before,
            operator: InteriorOperator::Cotan,
            variant: FlattenInterior::Harmonic,
        });
    }
    let g = problem.guarded_extension(boundary)?;
    Ok(Extension {
        flipped_faces: count_folds(&g.map, problem, ears),
        map: g.map,
        flipped_before: before,
        operator: g.operator,
        variant: FlattenInterior::Harmonic,
    })
}

/// `x` harmonic with the curve's `x` on the boundary; `y` its conjugate (see
/// [`FlattenInterior::Conjugate`]), shifted so its boundary mean is the curve's.
fn conjugate(
    problem: &DiskProblem<'_>,
    boundary: &[Complex64],
    pinned: Option<&PinnedLaplacian>,
) -> Result<Vec<Complex64>, DiskError> {
    let own;
    let pinned = match pinned {
        Some(p) => p,
        None => {
            own = PinnedLaplacian::new(problem, problem.partition().boundary[0])?;
            &own
        }
    };
    let partition = problem.partition();
    let xb: Vec<Complex64> = boundary.iter().map(|z| Complex64::new(z.re, 0.0)).collect();
    let x = problem.harmonic_extension(&xb);
    let m = boundary.len();
    let mut b = vec![0.0; x.len()];
    for k in 0..m {
        let prev = boundary[(k + m - 1) % m].re;
        let next = boundary[(k + 1) % m].re;
        b[partition.boundary[k] as usize] = 0.5 * (prev - next);
    }
    let y = pinned.solve(&b);
    let shift = boundary.iter().map(|z| z.im).sum::<f64>() / m as f64
        - partition
            .boundary
            .iter()
            .map(|&v| y[v as usize])
            .sum::<f64>()
            / m as f64;
    Ok(x.iter()
        .zip(&y)
        .map(|(xv, yv)| Complex64::new(xv.re, yv + shift))
        .collect())
}
