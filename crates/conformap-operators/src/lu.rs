//! Sparse LU for small symmetric systems that need not be positive definite (e.g. the
//! boundary block `L_BB` of a non-Delaunay mesh).

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Lu;
use faer::sparse::linalg::LuError;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::MatMut;
use num_complex::Complex64;
use sprs::CsMat;

use crate::OperatorError;

/// A sparse LU factorization with partial pivoting (faer), factor once and solve many.
#[derive(Debug)]
pub struct LuSolver {
    lu: Lu<usize, f64>,
    n: usize,
}

impl LuSolver {
    /// Factors the square CSC matrix `a`.
    ///
    /// # Errors
    /// [`OperatorError::StructurallySingular`] if `a` is singular, [`OperatorError::OutOfMemory`] if memory runs out, and
    /// [`OperatorError::NotSquareCsc`] for a non-square or non-CSC matrix.
    pub fn factor(a: &CsMat<f64>) -> Result<Self, OperatorError> {
        let (rows, cols) = (a.rows(), a.cols());
        if !a.is_csc() || rows != cols {
            return Err(OperatorError::NotSquareCsc { rows, cols });
        }
        let (col_ptr, indices, data) = a.view().into_raw_storage();
        if col_ptr.first() != Some(&0) {
            return Err(OperatorError::NotSquareCsc { rows, cols });
        }
        let symbolic = SymbolicSparseColMatRef::new_checked(rows, cols, col_ptr, None, indices);
        let lu = SparseColMatRef::new(symbolic, data)
            .sp_lu()
            .map_err(|e| match e {
                LuError::SymbolicSingular { index } => {
                    OperatorError::StructurallySingular { index }
                }
                LuError::Generic(e) => OperatorError::from_faer(e, "the sparse LU"),
            })?;
        Ok(Self { lu, n: rows })
    }

    /// Solves `A z = b` for complex `b`.
    pub fn solve_complex(&self, b: &[Complex64]) -> Vec<Complex64> {
        let n = self.n;
        let mut buf = Vec::with_capacity(2 * n);
        buf.extend(b.iter().map(|z| z.re));
        buf.extend(b.iter().map(|z| z.im));
        self.lu
            .solve_in_place(MatMut::from_column_major_slice_mut(&mut buf, n, 2));
        (0..n).map(|i| Complex64::new(buf[i], buf[n + i])).collect()
    }
}
