//! The prepared disk problem: Laplacian, interior/boundary blocks and their factorizations,
//! built once and shared by every disk method.

use std::time::Instant;

use conformap_mesh::{Topology, TriMesh};
use conformap_operators::{
    cotan_laplacian, quadratic_form, Cholesky, LaplacianBlocks, LuSolver, Partition,
};
use num_complex::Complex64;
use sprs::CsMat;

use crate::DiskError;

/// Everything a disk method needs about a mesh with one boundary loop, factored once.
///
/// The boundary vertices are ordered along the boundary loop (counter-clockwise for an
/// orientation-preserving map).
#[derive(Debug)]
pub struct DiskProblem<'m> {
    mesh: &'m TriMesh,
    laplacian: CsMat<f64>,
    partition: Partition,
    blocks: LaplacianBlocks,
    interior_factor: Cholesky,
    boundary_solver: Option<LuSolver>,
    /// Milliseconds spent assembling `L` and its blocks.
    pub assemble_ms: f64,
    /// Milliseconds spent factoring `L_II` (symbolic + numeric).
    pub factor_ms: f64,
}

impl<'m> DiskProblem<'m> {
    /// Checks the topology, assembles the cotangent Laplacian (CEM Eq. 6), splits it into
    /// the blocks of CEM Eq. 9 and factors `L_II` with a sparse Cholesky.
    ///
    /// # Errors
    /// [`DiskError::WrongTopology`] unless the mesh is a disk; [`DiskError::NoInteriorVertex`];
    /// [`DiskError::Operator`] if `L_II` is not positive definite.
    pub fn new(mesh: &'m TriMesh) -> Result<Self, DiskError> {
        let found = mesh.topology();
        if found != Topology::Disk {
            return Err(DiskError::WrongTopology { found });
        }
        let t0 = Instant::now();
        let laplacian = cotan_laplacian(mesh);
        let boundary = mesh.boundary_loops()[0].clone();
        let partition = Partition::new(mesh.num_vertices(), &boundary);
        if partition.interior.is_empty() {
            return Err(DiskError::NoInteriorVertex);
        }
        let blocks = LaplacianBlocks::new(&laplacian, &partition);
        let assemble_ms = t0.elapsed().as_secs_f64() * 1e3;
        let t1 = Instant::now();
        let interior_factor = Cholesky::factor(&blocks.ii)?;
        let factor_ms = t1.elapsed().as_secs_f64() * 1e3;
        Ok(Self {
            mesh,
            laplacian,
            partition,
            blocks,
            interior_factor,
            boundary_solver: None,
            assemble_ms,
            factor_ms,
        })
    }

    /// The mesh.
    pub fn mesh(&self) -> &'m TriMesh {
        self.mesh
    }

    /// The full cotangent Laplacian `L`.
    pub fn laplacian(&self) -> &CsMat<f64> {
        &self.laplacian
    }

    /// The interior/boundary partition (boundary in loop order).
    pub fn partition(&self) -> &Partition {
        &self.partition
    }

    /// The blocks `L_II`, `L_IB`, `L_BB`.
    pub fn blocks(&self) -> &LaplacianBlocks {
        &self.blocks
    }

    /// The Cholesky factor of `L_II`.
    pub fn interior_factor(&self) -> &Cholesky {
        &self.interior_factor
    }

    /// Number of boundary vertices.
    pub fn num_boundary(&self) -> usize {
        self.partition.boundary.len()
    }

    /// Harmonic extension: solves `L_II f_I = −L_IB f_B` (CEM Eq. 10) and returns the whole
    /// map in vertex order.
    pub fn harmonic_extension(&self, boundary: &[Complex64]) -> Vec<Complex64> {
        let interior = self.interior_solution(boundary);
        self.partition.assemble(&interior, boundary)
    }

    /// Interior values of the harmonic extension of `boundary` (interior order).
    pub fn interior_solution(&self, boundary: &[Complex64]) -> Vec<Complex64> {
        let mut rhs = self.blocks.ib_mul(boundary);
        for z in &mut rhs {
            *z = -*z;
        }
        self.interior_factor.solve_complex(&rhs)
    }

    /// Solves `L_BB x = b` (factoring `L_BB` on first use, sparse LU: `L_BB` need not be
    /// positive definite on a non-Delaunay mesh).
    ///
    /// # Errors
    /// [`DiskError::Operator`] if `L_BB` is singular.
    pub fn solve_boundary_block(&mut self, b: &[Complex64]) -> Result<Vec<Complex64>, DiskError> {
        if self.boundary_solver.is_none() {
            self.boundary_solver = Some(LuSolver::factor(&self.blocks.bb)?);
        }
        match &self.boundary_solver {
            Some(s) => Ok(s.solve_complex(b)),
            None => unreachable!("factored above"),
        }
    }

    /// Dirichlet energy `½ fᴴ L f` (CEM Eq. 5).
    pub fn dirichlet_energy(&self, f: &[Complex64]) -> f64 {
        quadratic_form(&self.laplacian, f)
    }

    /// Image area of CEM Eq. 8 along the boundary loop.
    pub fn image_area(&self, f: &[Complex64]) -> f64 {
        polygon_area_of(&self.partition.boundary, f)
    }

    /// Conformal energy `E_C = E_D − A` (CEM Eq. 7).
    pub fn conformal_energy(&self, f: &[Complex64]) -> f64 {
        self.dirichlet_energy(f) - self.image_area(f)
    }
}

/// Signed area of the polygon through `f[loop[0]], f[loop[1]], …` (CEM Eq. 8).
pub fn polygon_area_of(lp: &[u32], f: &[Complex64]) -> f64 {
    let m = lp.len();
    let mut a = 0.0;
    for k in 0..m {
        let p = f[lp[k] as usize];
        let q = f[lp[(k + 1) % m] as usize];
        a += p.re * q.im - q.re * p.im;
    }
    0.5 * a
}

/// Signed area of the polygon through the points `z` in order.
pub fn polygon_area(z: &[Complex64]) -> f64 {
    let m = z.len();
    let mut a = 0.0;
    for k in 0..m {
        let (p, q) = (z[k], z[(k + 1) % m]);
        a += p.re * q.im - q.re * p.im;
    }
    0.5 * a
}
