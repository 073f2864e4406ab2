//! Sparse Cholesky factorisation $K = LL^\top$ of the step matrix $K = A + kB$
//! (faer, fill-reducing AMD ordering, sequential: on two cores `Par::Seq` was
//! as fast as rayon, see NOTES-toolchain).

use crate::assembly::SpMat;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::{Conj, MatMut, Par, Side};

/// Why a factorisation failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FactorError {
    #[error(
        "the step matrix A + kB is not positive definite (pivot {index}); check the material constants"
    )]
    NotPositiveDefinite { index: usize },
    #[error("sparse factorisation failed: {0}")]
    Other(String),
}

/// A numeric sparse Cholesky factor with its symbolic analysis.
pub struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
}

impl Cholesky {
    /// Symbolic analysis (AMD) and numeric factorisation of the lower triangle of `k`.
    pub fn factor(k: &SpMat) -> Result<Cholesky, FactorError> {
        let symbolic = factorize_symbolic_cholesky(
            k.symbolic(),
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams::default(),
        )
        .map_err(|e| FactorError::Other(format!("{e:?}")))?;
        let mut values = vec![0.0; symbolic.len_val()];
        let par = Par::Seq;
        let mut mem =
            MemBuffer::new(symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()));
        symbolic
            .factorize_numeric_llt(
                &mut values,
                k.as_ref(),
                Side::Lower,
                Default::default(),
                par,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| match e {
                faer::linalg::solvers::LltError::NonPositivePivot { index } => {
                    FactorError::NotPositiveDefinite { index }
                }
            })?;
        Ok(Cholesky { symbolic, values })
    }

    /// Number of stored entries of $L$.
    pub fn nnz_l(&self) -> usize {
        self.values.len()
    }

    pub fn dim(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Solves $K X = R$ in place for a block of right-hand sides.
    pub fn solve_block(&self, rhs: MatMut<'_, f64>) {
        let par = Par::Seq;
        let mut mem = MemBuffer::new(
            self.symbolic
                .solve_in_place_scratch::<f64>(rhs.ncols(), par),
        );
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            par,
            MemStack::new(&mut mem),
        );
    }

    /// Solves $K x = b$ in place.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let n = b.len();
        self.solve_block(MatMut::from_column_major_slice_mut(b, n, 1));
    }
}
