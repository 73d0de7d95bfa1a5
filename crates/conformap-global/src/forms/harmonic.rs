//! Harmonic projection of the cohomology basis: `h_i = ω_i + d f_i` with `δ h_i = 0`, i.e.
//! `L f_i = div ω_i` for the cotangent Laplacian `L`, one vertex pinned. One symbolic
//! analysis and one numeric factorization serve all `2g` right-hand sides (one blocked
//! solve); on a symmetric double covering, two factorizations of half the size (the
//! Neumann and Dirichlet problems of one copy, [`HarmonicFactor::mirrored`]).

use std::time::Instant;

use conformap_mesh::{HomologyBasis, TriMesh};
use conformap_operators::{
    cotan_laplacian, cotan_laplacian_part, Cholesky, CholeskyOptions, FactorStats, LaplacianBlocks,
    Ordering, Partition,
};
use rayon::prelude::*;

use crate::forms::cohomology::{Cochain, SparseCochain};
use crate::GlobalError;

/// What the harmonic projection did and cost.
#[derive(Debug, Clone)]
pub struct HarmonicSolve {
    /// The harmonic forms, one per cohomology form, same order.
    pub forms: Vec<Cochain>,
    /// Largest `‖δ h_i‖∞ / ‖div ω_i‖∞` after the projection (rounding level when the
    /// solve is accurate).
    pub codifferential_residual: f64,
    /// The factorization's sizes and timings.
    pub factor: FactorStats,
    /// Milliseconds assembling `L` and its reduced block.
    pub assemble_ms: f64,
    /// Milliseconds for the blocked solve and the update of the forms.
    pub solve_ms: f64,
}

/// The vertices `(from, to)` of each edge's reference half-edge, looked up once for all
/// the forms of a projection.
fn edge_ends(mesh: &TriMesh, basis: &HomologyBasis) -> Vec<(u32, u32)> {
    basis
        .edges
        .halfedge
        .iter()
        .map(|&h| mesh.halfedge_vertices(h as usize))
        .collect()
}

/// `(div ω)_v = Σ_{edges v → u} w_vu ω(v → u)` of a form given by its nonzero values, with
/// `ends` each edge's reference half-edge's vertices ([`edge_ends`]).
fn divergence(
    vertices: usize,
    ends: &[(u32, u32)],
    weights: &[f64],
    support: &[(u32, f64)],
) -> Vec<f64> {
    let mut div = vec![0.0; vertices];
    for &(e, x) in support {
        let (a, b) = ends[e as usize];
        let flux = weights[e as usize] * x;
        div[a as usize] += flux;
        div[b as usize] -= flux;
    }
    div
}

/// `options` with the elimination order of `part`'s interior vertices by ascending
/// `rank` (ties by vertex; vertices beyond `rank` last): an order inherited from a related
/// surface instead of a fresh one (see [`HarmonicFactor::mirrored`]).
fn inherited(part: &Partition, rank: &[u64], options: &CholeskyOptions) -> CholeskyOptions {
    let key = |p: usize| {
        let v = part.interior[p] as usize;
        (rank.get(v).copied().unwrap_or(u64::MAX), v)
    };
    let mut perm: Vec<usize> = (0..part.interior.len()).collect();
    perm.sort_by_key(|&p| key(p));
    options.clone().with_ordering(Ordering::Custom(perm))
}

/// The reduced cotangent Laplacian of a closed surface (one vertex pinned), assembled and
/// factored once. It depends on the surface alone, not on its homology, so
/// [`crate::global_map`] factors it while the tree–cotree and the cut run on the other core.
///
/// On a symmetric double covering ([`HarmonicFactor::mirrored`]) the Laplacian `L`
/// commutes with the mirror, so with the first copy's interior `I`, the boundary `B` and
/// `f = (f_I, f_B, f_I')` the system `L f = d` splits into the symmetric part
/// `s = (f_I + f_I')/2`, `f_B`, which solves the Neumann problem of one copy
/// `L₁ (s, f_B) = ((d_I + d_I')/2, d_B/2)` (`L₁` the copy's own cotangent Laplacian: `L`'s
/// first-copy block with the boundary–boundary entries halved, a boundary edge having a
/// face in each copy), and the antisymmetric part `a = (f_I − f_I')/2`, which solves the
/// Dirichlet problem `L_II a = (d_I − d_I')/2`: two factorizations of one copy's size
/// instead of one of twice the size (the fill grows faster than the dimension: measured in
/// docs/benchmarks.md, issue 23). The potentials agree with the whole solve up to a
/// constant, which no form sees.
pub struct HarmonicFactor {
    kind: Kind,
    /// Milliseconds assembling `L` and its reduced block(s).
    pub assemble_ms: f64,
}

enum Kind {
    /// One factorization of the whole surface, `pinned` fixed (boxed like the other).
    Whole(Box<(Partition, Cholesky, u32)>),
    /// The Neumann and Dirichlet halves of a double covering (boxed: two factorizations).
    Mirrored(Box<MirroredHalves>),
}

/// The two half-size factorizations of [`Kind::Mirrored`].
struct MirroredHalves {
    mirror: Vec<u32>,
    copy_vertices: usize,
    neumann: Partition,
    dirichlet: Partition,
    chol_n: Cholesky,
    chol_d: Cholesky,
}

impl HarmonicFactor {
    /// Assembles and factors the cotangent Laplacian of `mesh` with vertex `pinned` fixed.
    ///
    /// # Errors
    /// [`GlobalError::Operator`] when the reduced Laplacian is not positive definite
    /// (strongly negative cotangent weights).
    pub fn new(
        mesh: &TriMesh,
        pinned: u32,
        options: &CholeskyOptions,
    ) -> Result<Self, GlobalError> {
        let t0 = Instant::now();
        let l = cotan_laplacian(mesh);
        let part = Partition::new(mesh.num_vertices(), &[pinned]);
        let blocks = LaplacianBlocks::new(&l, &part);
        let assemble_ms = ms(t0);
        let chol = Cholesky::factor_with(&blocks.ii, options)?;
        Ok(Self {
            kind: Kind::Whole(Box::new((part, chol, pinned))),
            assemble_ms,
        })
    }

    /// The two half-size factorizations of a symmetric double covering `mesh` (see the type's
    /// docs): `mirror` gives each vertex's mirror image (boundary vertices are their own),
    /// the first `copy_vertices` vertices are the first copy and the boundary. With `rank`
    /// (per vertex of the first copy, e.g. from the unslit input's ordering, see
    /// `topology_opt`), both halves are eliminated in that order instead of a fresh
    /// fill-reducing ordering of each: the Dirichlet half of a slit surface is a principal
    /// submatrix of the input's Laplacian (the slit vertices removed), which keeps the
    /// order's fill, and the Neumann half differs by the slits' copies, ranked next to
    /// their originals.
    ///
    /// # Errors
    /// As [`HarmonicFactor::new`].
    pub fn mirrored(
        mesh: &TriMesh,
        mirror: &[u32],
        copy_vertices: usize,
        options: &CholeskyOptions,
        rank: Option<&[u64]>,
    ) -> Result<Self, GlobalError> {
        let t0 = Instant::now();
        let n1 = copy_vertices;
        let on_boundary = |v: usize| mirror[v] as usize == v;
        // the first copy's own Laplacian (its faces are the covering's first half): the
        // covering's rows of that copy with the shared boundary's entries halved, without
        // assembling the covering's matrix
        let l1 = cotan_laplacian_part(mesh, mesh.num_faces() / 2, n1);
        let boundary: Vec<u32> = (0..n1 as u32)
            .filter(|&v| on_boundary(v as usize))
            .collect();
        // Neumann: one boundary vertex pinned (the potentials are defined up to a constant)
        let neumann = Partition::new(n1, &boundary[..1.min(boundary.len())]);
        let dirichlet = Partition::new(n1, &boundary);
        let (bn, bd) = (
            LaplacianBlocks::new(&l1, &neumann),
            LaplacianBlocks::new(&l1, &dirichlet),
        );
        let assemble_ms = ms(t0);
        let (on, od) = match rank {
            Some(r) => (
                inherited(&neumann, r, options),
                inherited(&dirichlet, r, options),
            ),
            None => (options.clone(), options.clone()),
        };
        let chol_n = Cholesky::factor_with(&bn.ii, &on)?;
        let chol_d = Cholesky::factor_with(&bd.ii, &od)?;
        Ok(Self {
            kind: Kind::Mirrored(Box::new(MirroredHalves {
                mirror: mirror.to_vec(),
                copy_vertices,
                neumann,
                dirichlet,
                chol_n,
                chol_d,
            })),
            assemble_ms,
        })
    }

    /// Whether [`Self::project`] may take a homology basis rooted at `root` (the whole
    /// factorization pins the root; the mirrored one any vertex).
    pub fn fits_root(&self, root: u32) -> bool {
        match &self.kind {
            Kind::Whole(w) => w.2 == root,
            Kind::Mirrored(_) => true,
        }
    }

    /// The factorizations' sizes and timings (the mirrored halves added up).
    pub fn stats(&self) -> FactorStats {
        match &self.kind {
            Kind::Whole(w) => w.1.stats().clone(),
            Kind::Mirrored(h) => {
                let (chol_n, chol_d) = (&h.chol_n, &h.chol_d);
                let (a, b) = (chol_n.stats(), chol_d.stats());
                FactorStats {
                    n: a.n + b.n,
                    nnz_matrix: a.nnz_matrix + b.nnz_matrix,
                    nnz_factor: a.nnz_factor + b.nnz_factor,
                    supernodal: a.supernodal || b.supernodal,
                    analyse_ms: a.analyse_ms + b.analyse_ms,
                    factor_ms: a.factor_ms + b.factor_ms,
                    ordering: a.ordering,
                }
            }
        }
    }

    /// Solves `L f_i = div_i` for every divergence of `divs` (one blocked solve per
    /// factorization): the solution columns, read per form by [`Self::potential`].
    fn solve(&self, divs: &[Vec<f64>]) -> Solution {
        let k = divs.len();
        match &self.kind {
            Kind::Whole(w) => {
                let (part, chol, _) = &**w;
                let mut rhs = Vec::with_capacity(part.interior.len() * k);
                for d in divs {
                    rhs.extend(part.interior.iter().map(|&v| d[v as usize]));
                }
                chol.solve_in_place(&mut rhs, k);
                Solution::Whole(rhs)
            }
            Kind::Mirrored(h) => {
                let MirroredHalves {
                    mirror,
                    neumann,
                    dirichlet,
                    chol_n,
                    chol_d,
                    ..
                } = &**h;
                let on_boundary = |v: usize| mirror[v] as usize == v;
                let (nn, nd) = (neumann.interior.len(), dirichlet.interior.len());
                let (mut rn, mut rd) = (Vec::with_capacity(nn * k), Vec::with_capacity(nd * k));
                for d in divs {
                    rn.extend(neumann.interior.iter().map(|&v| {
                        let (v, w) = (v as usize, mirror[v as usize] as usize);
                        if on_boundary(v) {
                            0.5 * d[v]
                        } else {
                            0.5 * (d[v] + d[w])
                        }
                    }));
                    rd.extend(dirichlet.interior.iter().map(|&v| {
                        let (v, w) = (v as usize, mirror[v as usize] as usize);
                        0.5 * (d[v] - d[w])
                    }));
                }
                // the two halves are independent: one core each (each solve is sequential)
                rayon::join(
                    || chol_n.solve_in_place(&mut rn, k),
                    || chol_d.solve_in_place(&mut rd, k),
                );
                Solution::Mirrored(rn, rd)
            }
        }
    }

    /// The potential `f_i` of form `i` on every vertex of the surface, from the solution
    /// columns (pinned and mirror-fixed values 0): the sum of the symmetric (Neumann) and
    /// antisymmetric (Dirichlet) parts on the first copy, their difference on the second.
    fn potential(&self, solution: &Solution, i: usize) -> Vec<f64> {
        match (&self.kind, solution) {
            (Kind::Whole(w), Solution::Whole(x)) => {
                let part = &w.0;
                let ni = part.interior.len();
                part.assemble(&x[i * ni..(i + 1) * ni], &[0.0])
            }
            (Kind::Mirrored(h), Solution::Mirrored(rn, rd)) => {
                let MirroredHalves {
                    mirror,
                    copy_vertices,
                    neumann,
                    dirichlet,
                    ..
                } = &**h;
                let (nn, nd) = (neumann.interior.len(), dirichlet.interior.len());
                let (sym, anti) = (&rn[i * nn..(i + 1) * nn], &rd[i * nd..(i + 1) * nd]);
                let mut f = vec![0.0; mirror.len()];
                for v in 0..*copy_vertices {
                    let s = if neumann.is_interior[v] {
                        sym[neumann.local[v] as usize]
                    } else {
                        0.0
                    };
                    let a = if dirichlet.is_interior[v] {
                        anti[dirichlet.local[v] as usize]
                    } else {
                        0.0
                    };
                    f[v] = s + a;
                    let w = mirror[v] as usize;
                    if w != v {
                        f[w] = s - a;
                    }
                }
                f
            }
            _ => unreachable!("a solution comes from its own factorization"),
        }
    }

    /// The harmonic representatives `h_i = ω_i + d f_i` of the closed forms `closed`, given
    /// by their nonzero values (same cohomology class: `h − ω = d f` is exact, so every
    /// period is kept), written over `storage` (one [`storage`] vector per form). `basis`
    /// must be a homology basis of the factored mesh, rooted at the pinned vertex for a
    /// whole factorization ([`Self::fits_root`]).
    ///
    /// # Errors
    /// [`GlobalError::NonFinite`] if a solve produces a non-finite value.
    ///
    /// # Panics
    /// If `storage` does not hold one vector per form, each one value per edge.
    pub fn project(
        &self,
        mesh: &TriMesh,
        basis: &HomologyBasis,
        weights: &[f64],
        closed: &[SparseCochain],
        mut storage: Vec<Cochain>,
    ) -> Result<HarmonicSolve, GlobalError> {
        assert_eq!(storage.len(), closed.len(), "one storage vector per form");
        assert!(storage.iter().all(|h| h.len() == basis.edges.len()));
        let t1 = Instant::now();
        let ends = edge_ends(mesh, basis);
        let nv = mesh.num_vertices();
        let divs: Vec<Vec<f64>> = closed
            .par_iter()
            .map(|w| divergence(nv, &ends, weights, w))
            .collect();
        let solution = self.solve(&divs);
        // the forms are independent: one per thread, each with its own potential. h is
        // written over its storage in edge order, with its divergence on the same pass:
        // the relative residual
        let residuals: Vec<Result<f64, usize>> = storage
            .par_iter_mut()
            .zip(closed)
            .zip(&divs)
            .enumerate()
            .map(|(i, ((h, omega), div))| {
                let f = self.potential(&solution, i);
                if let Some(v) = f.iter().position(|x| !x.is_finite()) {
                    return Err(v);
                }
                let mut after = vec![0.0; nv];
                let mut next = omega.iter().peekable();
                for (e, ((out, &(a, b)), &w)) in h.iter_mut().zip(&ends).zip(weights).enumerate() {
                    let x = match next.next_if(|&&(k, _)| k as usize == e) {
                        Some(&(_, x)) => x,
                        None => 0.0,
                    };
                    let value = (x + f[b as usize]) - f[a as usize];
                    *out = value;
                    // the divergence of h, as `divergence` sums it
                    let flux = w * value;
                    after[a as usize] += flux;
                    after[b as usize] -= flux;
                }
                let scale = div.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                let res = after.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                Ok(if scale > 0.0 { res / scale } else { 0.0 })
            })
            .collect();
        let mut codifferential_residual = 0.0f64;
        for r in residuals {
            match r {
                Ok(r) => codifferential_residual = codifferential_residual.max(r),
                Err(vertex) => {
                    return Err(GlobalError::NonFinite {
                        vertex,
                        stage: "harmonic projection",
                    })
                }
            }
        }
        Ok(HarmonicSolve {
            forms: storage,
            codifferential_residual,
            factor: self.stats(),
            assemble_ms: self.assemble_ms,
            solve_ms: ms(t1),
        })
    }
}

/// Storage for `forms` harmonic forms of `edges` values each, for
/// [`HarmonicFactor::project`]: filled with NaN, so every page is faulted in here — on a
/// core that would otherwise wait for the factorization — and a value the projection failed
/// to write could not pass for a number (62 MB of fresh pages at genus 15 on armadillo's
/// covering: about 35 ms of page faults off the projection's critical path).
pub fn storage(forms: usize, edges: usize) -> Vec<Cochain> {
    (0..forms).map(|_| vec![f64::NAN; edges]).collect()
}

/// The solution columns of [`HarmonicFactor::solve`], form by form (column-major).
enum Solution {
    /// One system: `interior × k`.
    Whole(Vec<f64>),
    /// The Neumann and Dirichlet systems of one copy.
    Mirrored(Vec<f64>, Vec<f64>),
}

/// Milliseconds since `t`.
pub(crate) fn ms(t: Instant) -> f64 {
    t.elapsed().as_secs_f64() * 1e3
}
