//! Options and errors of [`crate::koebe`], each option with its default and why.

use crate::options::{at_least_one, finite_non_negative, finite_positive, with_setters};
use crate::{CemOptions, DiskError};

/// Options of [`crate::koebe`].
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub struct KoebeOptions {
    /// Boundary loop (index into `mesh.boundary_loops()`) that becomes the unit circle.
    /// Default: `None`, the longest loop (ties: the first), as `conformap disk` chooses.
    pub outer: Option<usize>,
    /// Stop the sweeps once the worst circle residual after a sweep is at most this.
    /// Default: `1e-4`: the polish that follows puts every loop on its circle to rounding
    /// and needs only a start near its minimizer (its result is the same from `1e-2` or
    /// `1e-8`, measured on the class-b meshes); the iteration converges linearly, so each
    /// further decade costs about one more sweep. With the polish off, use
    /// [`KoebeOptions::TOL_WITHOUT_POLISH`]. The residual is the worst
    /// `max ||f − c| − r| / r` over every loop's vertices, against its best-fit circle.
    pub tol: f64,
    /// Sweep cap (one sweep maps once with each loop open). Default: 200. The iteration
    /// converges linearly at a rate set by how close the holes are to each other (Zeng et
    /// al.); the test meshes need far fewer, so the cap only ends a stalled run, which the
    /// report then marks as not converged.
    pub max_sweeps: usize,
    /// Newton iteration cap per step. Default: 50. Steps after the first sweep start next
    /// to their minimizer and take 1–4 iterations; the first ones, from a rough start, up
    /// to about 15.
    pub newton_max_iter: usize,
    /// Newton step tolerance, radians: a step ends once a full Newton step moves no
    /// boundary angle by more than this. Default: `1e-11` (quadratic convergence leaves an
    /// error far below that, and `1e-11` is about `1e5` units in the last place of `2π`).
    pub newton_step_tol: f64,
    /// CEM options of the first map (CEM Algorithm 2, step 3: the surface with every hole
    /// filled, on [`crate::DiskProblem::new`]). Default: [`CemOptions::DEFAULT`] (the
    /// paper's 20 iterations).
    pub initial: CemOptions,
    /// End with the circle-domain energy minimization (see [`crate::koebe`], step 5).
    /// Default: `true`.
    pub polish: bool,
}

impl KoebeOptions {
    /// The tolerance to use with [`KoebeOptions::polish`] off: `1e-8`, a hundred times
    /// below the `1e-6` the maps are judged by, so the final normalization (which moves the
    /// holes) leaves the residual well inside it.
    pub const TOL_WITHOUT_POLISH: f64 = 1e-8;

    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        outer: None,
        tol: 1e-4,
        max_sweeps: 200,
        newton_max_iter: 50,
        newton_step_tol: 1e-11,
        initial: CemOptions::DEFAULT,
        polish: true,
    };

    with_setters! {
        with_outer(outer: Option<usize>);
        with_tol(tol: f64);
        with_max_sweeps(max_sweeps: usize);
    }

    /// Sets [`Self::newton_max_iter`] and [`Self::newton_step_tol`].
    #[must_use]
    pub fn with_newton(mut self, max_iter: usize, step_tol: f64) -> Self {
        self.newton_max_iter = max_iter;
        self.newton_step_tol = step_tol;
        self
    }

    with_setters! {
        with_initial(initial: CemOptions);
        with_polish(polish: bool);
    }

    /// Checks the ranges: `tol ≥ 0` and finite, `max_sweeps ≥ 1`, `newton_max_iter ≥ 1`,
    /// `newton_step_tol > 0` and finite.
    ///
    /// # Errors
    /// [`DiskError::InvalidOption`] naming the option.
    pub fn validate(&self) -> Result<(), DiskError> {
        finite_non_negative("tol", self.tol)?;
        at_least_one("max_sweeps", self.max_sweeps)?;
        at_least_one("newton_max_iter", self.newton_max_iter)?;
        finite_positive("newton_step_tol", self.newton_step_tol)
    }
}

impl Default for KoebeOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
