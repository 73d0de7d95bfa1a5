//! Options of [`crate::global_map`].

use conformap_operators::CholeskyOptions;

use crate::forms::conjugate::ConjugateMethod;
use crate::forms::optimal::{FormSearchOptions, Objective};

/// Options of [`crate::global_map`].
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct GlobalMapOptions {
    /// Which holomorphic basis form `φ_k = ω_k + i *ω_k` (`0 ≤ k < 2g`) to lay out,
    /// overriding [`Self::objective`]. Default `None`: the objective decides.
    pub form: Option<usize>,
    /// Which combination of the basis forms to lay out. Default [`Objective::Uniform`].
    pub objective: Objective,
    /// The multistart of the uniform / least-uniform search. Default
    /// [`FormSearchOptions::DEFAULT`].
    pub search: FormSearchOptions,
    /// The conjugate forms. Default [`ConjugateMethod::NearestComplexStructure`].
    pub conjugate: ConjugateMethod,
    /// Root vertex of the shortest-path tree (also the vertex pinned in the harmonic
    /// projection). Default `None`: vertex 0.
    pub root: Option<usize>,
    /// The sparse Cholesky of the cotangent Laplacian. Default [`CholeskyOptions::DEFAULT`].
    pub cholesky: CholeskyOptions,
}

impl GlobalMapOptions {
    /// The defaults, as a constant.
    pub const DEFAULT: Self = Self {
        form: None,
        objective: Objective::Uniform,
        search: FormSearchOptions::DEFAULT,
        conjugate: ConjugateMethod::NearestComplexStructure,
        root: None,
        cholesky: CholeskyOptions::DEFAULT,
    };

    /// Sets [`Self::form`].
    #[must_use]
    pub fn with_form(mut self, form: Option<usize>) -> Self {
        self.form = form;
        self
    }

    /// Sets [`Self::objective`].
    #[must_use]
    pub fn with_objective(mut self, objective: Objective) -> Self {
        self.objective = objective;
        self
    }

    /// Sets [`Self::search`].
    #[must_use]
    pub fn with_search(mut self, search: FormSearchOptions) -> Self {
        self.search = search;
        self
    }

    /// Sets [`Self::conjugate`].
    #[must_use]
    pub fn with_conjugate(mut self, conjugate: ConjugateMethod) -> Self {
        self.conjugate = conjugate;
        self
    }

    /// Sets [`Self::root`].
    #[must_use]
    pub fn with_root(mut self, root: Option<usize>) -> Self {
        self.root = root;
        self
    }

    /// Sets [`Self::cholesky`].
    #[must_use]
    pub fn with_cholesky(mut self, cholesky: CholeskyOptions) -> Self {
        self.cholesky = cholesky;
        self
    }
}

impl Default for GlobalMapOptions {
    fn default() -> Self {
        Self::DEFAULT
    }
}
