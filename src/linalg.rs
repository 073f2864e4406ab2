//! Sparse Cholesky factorisation $K = LL^\top$ of the step matrix $K = A + kB$,
//! with the contact normal dofs ordered last (faer, supernodal, sequential: on
//! two cores `Par::Seq` was as fast as rayon, see NOTES-toolchain).
//!
//! Ordering: faer's approximate minimum degree on $K$, with the $m$ contact dofs
//! then moved to the end. Writing $K$ and $L$ in blocks (interior $I$, contact $C$),
//! $$K = \begin{pmatrix} K_{II} & K_{IC} \\ K_{CI} & K_{CC}\end{pmatrix},\qquad
//! L = \begin{pmatrix} L_{II} & 0 \\ L_{CI} & L_{CC}\end{pmatrix},$$
//! the Schur complement is $K_{CC} - K_{CI}K_{II}^{-1}K_{IC} = L_{CC}L_{CC}^\top$: the
//! condensed stiffness comes with the factor, at no extra solve. And since
//! $(K^{-1}b)_C = L_{CC}^{-\top}(L^{-1}b)_C$, a forward solve yields the contact values
//! of $K^{-1}b$; the backward solve is needed only once the contact forces are known.

use crate::assembly::SpMat;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::perm::PermRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::{Conj, Mat, MatMut, Par, Side};

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

/// A supernodal Cholesky factor of $K$ with the contact dofs last.
pub struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// `fwd[new] = old`.
    fwd: Vec<usize>,
    /// The trailing $m \times m$ block $L_{CC}$ (lower triangular), rows and
    /// columns in the order of the contact dofs given to [`Cholesky::factor`].
    l_cc: Mat<f64>,
}

fn other<E: std::fmt::Debug>(e: E) -> FactorError {
    FactorError::Other(format!("{e:?}"))
}

impl Cholesky {
    /// Orders (AMD, then `last` at the end), analyses and factorises `k`.
    pub fn factor(k: &SpMat, last: &[usize]) -> Result<Cholesky, FactorError> {
        let n = k.nrows();
        let m = last.len();
        // AMD on the full pattern, then the contact dofs moved to the end.
        let (mut amd_fwd, mut amd_inv) = (vec![0usize; n], vec![0usize; n]);
        let mut mem =
            MemBuffer::try_new(amd::order_scratch::<usize>(n, k.compute_nnz())).map_err(other)?;
        amd::order(
            &mut amd_fwd,
            &mut amd_inv,
            k.symbolic(),
            Default::default(),
            MemStack::new(&mut mem),
        )
        .map_err(other)?;
        let mut is_last = vec![false; n];
        for &d in last {
            is_last[d] = true;
        }
        let mut fwd: Vec<usize> = amd_fwd.into_iter().filter(|&d| !is_last[d]).collect();
        fwd.extend_from_slice(last);
        let mut inv = vec![0usize; n];
        for (new, &old) in fwd.iter().enumerate() {
            inv[old] = new;
        }
        let perm = PermRef::new_checked(&fwd, &inv, n);
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
            ..Default::default()
        };
        let symbolic = factorize_symbolic_cholesky(
            k.symbolic(),
            Side::Lower,
            SymmetricOrdering::Custom(perm),
            params,
        )
        .map_err(other)?;
        let mut values = vec![0.0; symbolic.len_val()];
        let par = Par::Seq;
        let mut mem = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .map_err(other)?;
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
        let mut chol = Cholesky {
            symbolic,
            values,
            fwd,
            l_cc: Mat::zeros(m, m),
        };
        chol.l_cc = chol.trailing_block(m)?;
        Ok(chol)
    }

    fn supernodal(&self) -> Result<SupernodalLltRef<'_, usize, f64>, FactorError> {
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => Ok(SupernodalLltRef::new(s, &self.values)),
            SymbolicCholeskyRaw::Simplicial(_) => {
                Err(FactorError::Other("expected a supernodal factor".into()))
            }
        }
    }

    /// Reads the trailing $m \times m$ block of $L$ from the supernodes.
    fn trailing_block(&self, m: usize) -> Result<Mat<f64>, FactorError> {
        let n = self.dim();
        let first = n - m;
        let sn = self.supernodal()?;
        let sym = match self.symbolic.raw() {
            SymbolicCholeskyRaw::Supernodal(s) => s,
            SymbolicCholeskyRaw::Simplicial(_) => unreachable!(),
        };
        let mut l = Mat::<f64>::zeros(m, m);
        for s in 0..sym.n_supernodes() {
            let node = sn.supernode(s);
            let (start, val) = (node.start(), node.val());
            let size = val.ncols();
            if start + size <= first {
                continue;
            }
            for c in 0..size {
                let col = start + c;
                if col < first {
                    continue;
                }
                for r in c..size {
                    l[(start + r - first, col - first)] = val[(r, c)];
                }
                for (idx, &row) in node.pattern().iter().enumerate() {
                    l[(row - first, col - first)] = val[(size + idx, c)];
                }
            }
        }
        Ok(l)
    }

    /// Number of stored entries of $L$.
    pub fn nnz_l(&self) -> usize {
        self.values.len()
    }

    pub fn dim(&self) -> usize {
        self.symbolic.nrows()
    }

    /// The trailing block $L_{CC}$.
    pub fn l_cc(&self) -> &Mat<f64> {
        &self.l_cc
    }

    /// The supernodal factor and a scratch buffer for one right-hand side.
    /// (`factor` forces, and `trailing_block` checks, a supernodal factorisation.)
    fn solve_parts(&self) -> (SupernodalLltRef<'_, usize, f64>, MemBuffer) {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            unreachable!("Cholesky::factor builds a supernodal factor")
        };
        let mem = MemBuffer::new(sym.solve_in_place_scratch::<f64>(1, Par::Seq));
        (SupernodalLltRef::new(sym, &self.values), mem)
    }

    /// Forward solve $x = L^{-1}\Pi b$ ($\Pi$ the fill-reducing permutation).
    pub fn forward(&self, b: &[f64]) -> Vec<f64> {
        let n = self.dim();
        let mut x: Vec<f64> = self.fwd.iter().map(|&old| b[old]).collect();
        let (sn, mut mem) = self.solve_parts();
        let rhs = MatMut::from_column_major_slice_mut(&mut x, n, 1);
        sn.l_solve_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut mem));
        x
    }

    /// Backward solve: returns $\Pi^\top L^{-\top} x$ (so `backward(forward(b))` $= K^{-1}b$).
    pub fn backward(&self, mut x: Vec<f64>) -> Vec<f64> {
        let n = self.dim();
        let (sn, mut mem) = self.solve_parts();
        let rhs = MatMut::from_column_major_slice_mut(&mut x, n, 1);
        sn.l_transpose_solve_with_conj(Conj::No, rhs, Par::Seq, MemStack::new(&mut mem));
        let mut u = vec![0.0; n];
        for (new, &old) in self.fwd.iter().enumerate() {
            u[old] = x[new];
        }
        u
    }

    /// $K^{-1} b$.
    pub fn solve(&self, b: &[f64]) -> Vec<f64> {
        self.backward(self.forward(b))
    }

    /// $y_C = L_{CC}^{-\top} x_C$ in place (the contact part of a backward solve).
    pub fn contact_backward(&self, x_c: &mut [f64]) {
        let m = x_c.len();
        solve_upper_triangular_in_place(
            self.l_cc.transpose(),
            MatMut::from_column_major_slice_mut(x_c, m, 1),
            Par::Seq,
        );
    }

    /// $L_{CC}^{-1} z$ in place (the contact part of a forward solve).
    pub fn contact_forward(&self, z: &mut [f64]) {
        let m = z.len();
        solve_lower_triangular_in_place(
            self.l_cc.as_ref(),
            MatMut::from_column_major_slice_mut(z, m, 1),
            Par::Seq,
        );
    }
}
