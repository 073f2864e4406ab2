//! Sparse Cholesky factorisation $K = LL^\top$ of the step matrix $K = A + kB$,
//! with the contact normal dofs ordered last: faer analyses and factorises
//! (supernodal, sequential: on two cores `Par::Seq` was as fast as rayon, see
//! NOTES-toolchain); the triangular solves, which a run repeats once per step,
//! are our own.
//!
//! Ordering ([`crate::ordering`]): nested dissection or AMD, with the $m$ contact
//! dofs then moved to the end. Writing $K$ and $L$ in blocks (interior $I$, contact $C$),
//! $$K = \begin{pmatrix} K_{II} & K_{IC} \\ K_{CI} & K_{CC}\end{pmatrix},\qquad
//! L = \begin{pmatrix} L_{II} & 0 \\ L_{CI} & L_{CC}\end{pmatrix},$$
//! the Schur complement is $K_{CC} - K_{CI}K_{II}^{-1}K_{IC} = L_{CC}L_{CC}^\top$: the
//! condensed stiffness comes with the factor, at no extra solve. And since
//! $(K^{-1}b)_C = L_{CC}^{-\top}(L^{-1}b)_C$, a forward solve yields the contact values
//! of $K^{-1}b$; the backward solve is needed only once the contact forces are known.
//!
//! Why our own triangular solves: a step's cost is two sweeps over the 28 M
//! values of $L$ at $h = 1/512$, repeated at every step. Four things make them
//! about twice as fast as faer's general solve: (1) with nested dissection the
//! supernodes of the two halves of the domain are independent, so two threads
//! sweep them at once (each collecting its updates of the shared tail rows in a
//! buffer of its own); (2) the transposed sweep visits the supernodes from last
//! to first, against the hardware prefetcher, so it prefetches in software; (3)
//! most supernodes hold one or two columns, where plain loops beat calls into
//! dense kernels; (4) several right-hand sides share one sweep. `evhi bench
//! --sweeps` measures each; the sweeps run at about half the machine's
//! streaming rate, bound by per-supernode work and latency, not bandwidth.

#![warn(missing_docs)]

use crate::assembly::SpMat;
use crate::ordering::Ordering;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::perm::PermRef;
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::supernodal::SupernodalLltRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::{Mat, MatMut, Par, Side};

pub use crate::error::FactorError;

/// A supernodal Cholesky factor of $K$ with the contact dofs last.
pub struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// `fwd[new] = old`.
    fwd: Vec<usize>,
    /// The trailing $m \times m$ block $L_{CC}$ (lower triangular), rows and
    /// columns in the order of the contact dofs given to [`Cholesky::factor`].
    l_cc: Mat<f64>,
    /// Where the two independent halves end, if solves run them in parallel.
    split: Option<Split>,
    nodes: Nodes,
    /// Whether the backward sweep prefetches in software (on by default).
    prefetch: bool,
    /// The first supernode holding a contact column (the last $m$ columns).
    contact_supernode: usize,
}

/// Which sweep over $L$.
#[derive(Debug, Clone, Copy)]
enum Sweep {
    Forward,
    /// Forward, for right-hand sides that vanish off the contact dofs.
    ForwardContact,
    Backward,
}

/// Right-hand sides per sweep over $L$.
pub const MAX_BATCH: usize = 4;

/// Supernodes `0..a` hold the columns `0..n1` (first half), `a..b` the columns
/// `n1..tail` (second half), `b..` the rest.
#[derive(Debug, Clone, Copy)]
struct Split {
    supernodes: [usize; 2],
    rows: [usize; 2],
}

impl Split {
    /// `x` cut into its first half, second half and tail rows.
    fn cut<T>(self, x: &mut [T]) -> (&mut [T], &mut [T], &mut [T]) {
        let [n1, tail] = self.rows;
        let (halves, rest) = x.split_at_mut(tail);
        let (left, right) = halves.split_at_mut(n1);
        (left, right, rest)
    }
}

/// One supernode of $L$: columns `start..start + size`, stored column-major from
/// `val` with `size + rows.len()` rows (the dense diagonal block, then the rows
/// of `rows`).
#[derive(Debug, Clone)]
struct Node {
    start: usize,
    size: usize,
    val: usize,
    rows: std::ops::Range<usize>,
}

/// The supernodes as flat arrays, read by the hand-written triangular solves:
/// one right-hand side makes every dense operation a vector one, and most
/// supernodes hold one or two columns, where a plain loop beats a call into a
/// dense kernel.
#[derive(Debug, Clone, Default)]
struct Nodes {
    nodes: Vec<Node>,
    /// Row indices below the diagonal blocks.
    rows: Vec<u32>,
}

/// $\sum_i a_i b_i$ for `R` right-hand sides at once ($b_i \in \mathbb R^R$), with
/// four partial sums so that the compiler vectorises it.
#[inline]
fn dot<const R: usize>(a: &[f64], b: &[[f64; R]]) -> [f64; R] {
    let mut s = [[0.0; R]; 4];
    let (ca, cb) = (a.chunks_exact(4), b.chunks_exact(4));
    let mut out = [0.0; R];
    for (x, y) in ca.remainder().iter().zip(cb.remainder()) {
        for j in 0..R {
            out[j] += x * y[j];
        }
    }
    for (x, y) in ca.zip(cb) {
        for l in 0..4 {
            for j in 0..R {
                s[l][j] += x[l] * y[l][j];
            }
        }
    }
    for j in 0..R {
        out[j] += (s[0][j] + s[1][j]) + (s[2][j] + s[3][j]);
    }
    out
}

/// Software prefetch for a backward sweep through `values`: hardware prefetchers
/// follow ascending addresses well and descending ones badly, and the transposed
/// solve visits the supernodes from the last to the first.
struct Prefetch<'a> {
    values: &'a [f64],
    /// Everything from here on has been asked for.
    next: usize,
    on: bool,
}

/// How far below the current supernode to prefetch, in values (64 KiB).
const PREFETCH_AHEAD: usize = 8192;

impl<'a> Prefetch<'a> {
    fn new(values: &'a [f64], from: usize, on: bool) -> Self {
        Prefetch {
            values,
            next: from,
            on,
        }
    }

    /// Asks for the cache lines down to `PREFETCH_AHEAD` values below `at`.
    #[inline]
    fn below(&mut self, at: usize) {
        let target = at.saturating_sub(PREFETCH_AHEAD);
        while self.on && self.next > target {
            self.next = self.next.saturating_sub(8);
            #[cfg(target_arch = "x86_64")]
            // SAFETY: `next` is in bounds, and a prefetch never faults or writes.
            unsafe {
                use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
                _mm_prefetch::<_MM_HINT_T0>(self.values.as_ptr().add(self.next).cast());
            }
        }
    }
}

/// $X \leftarrow L^{-1} X$ over the supernodes `range` for `R` right-hand sides
/// (row $i$ of $X$ is `x[i]`), where `own` holds the rows from `lo` on and rows
/// from `tail` on live in `tail_x` (pass `tail = n` when `own` is all of $X$).
fn lower_solve<const R: usize>(
    nodes: &Nodes,
    values: &[f64],
    range: std::ops::Range<usize>,
    own: &mut [[f64; R]],
    lo: usize,
    tail_x: &mut [[f64; R]],
    tail: usize,
) {
    let mut tmp = Vec::new();
    for node in &nodes.nodes[range] {
        let (size, rows) = (node.size, &nodes.rows[node.rows.clone()]);
        let nr = size + rows.len();
        let v = &values[node.val..node.val + nr * size];
        let start = node.start - lo;
        tmp.clear();
        tmp.resize(rows.len(), [0.0; R]);
        for c in 0..size {
            let col = &v[c * nr..(c + 1) * nr];
            let xc = own[start + c].map(|x| x / col[c]);
            own[start + c] = xc;
            for (x, l) in own[start + c + 1..start + size]
                .iter_mut()
                .zip(&col[c + 1..size])
            {
                for j in 0..R {
                    x[j] -= l * xc[j];
                }
            }
            for (t, l) in tmp.iter_mut().zip(&col[size..]) {
                for j in 0..R {
                    t[j] += l * xc[j];
                }
            }
        }
        for (&r, t) in rows.iter().zip(&tmp) {
            let r = r as usize;
            let x = if r >= tail {
                &mut tail_x[r - tail]
            } else {
                &mut own[r - lo]
            };
            for j in 0..R {
                x[j] -= t[j];
            }
        }
    }
}

/// $X \leftarrow L^{-\top} X$ over the supernodes `range` (taken in reverse), with
/// `own` and `tail_x` as in [`lower_solve`]; the tail is only read.
#[allow(clippy::too_many_arguments)]
fn upper_solve<const R: usize>(
    prefetch: bool,
    nodes: &Nodes,
    values: &[f64],
    range: std::ops::Range<usize>,
    own: &mut [[f64; R]],
    lo: usize,
    tail_x: &[[f64; R]],
    tail: usize,
) {
    let mut tmp = Vec::new();
    let mut ahead = Prefetch::new(
        values,
        nodes.nodes[range.clone()].last().map_or(0, |n| n.val),
        prefetch,
    );
    for node in nodes.nodes[range].iter().rev() {
        let (size, rows) = (node.size, &nodes.rows[node.rows.clone()]);
        let nr = size + rows.len();
        let v = &values[node.val..node.val + nr * size];
        ahead.below(node.val);
        tmp.clear();
        tmp.extend(rows.iter().map(|&r| {
            let r = r as usize;
            if r >= tail {
                tail_x[r - tail]
            } else {
                own[r - lo]
            }
        }));
        let start = node.start - lo;
        let x = &mut own[start..start + size];
        // The rows below the diagonal block first, reading the columns forwards
        // (the memory prefetcher follows ascending addresses), then the block.
        for (c, x) in x.iter_mut().enumerate() {
            let s = dot(&v[c * nr + size..(c + 1) * nr], &tmp);
            for j in 0..R {
                x[j] -= s[j];
            }
        }
        for c in (0..size).rev() {
            let col = &v[c * nr..c * nr + size];
            let (head, done) = x.split_at_mut(c + 1);
            let s = dot(&col[c + 1..], done);
            for j in 0..R {
                head[c][j] = (head[c][j] - s[j]) / col[c];
            }
        }
    }
}

fn other<E: std::fmt::Debug>(e: E) -> FactorError {
    FactorError::Other(format!("{e:?}"))
}

impl Cholesky {
    /// Analyses and factorises `k` in the given `ordering` (its last `m` dofs are
    /// the contact dofs). With [`Ordering::halves`] set and checked against the
    /// supernodes, triangular solves run the two halves on two threads.
    pub fn factor(k: &SpMat, ordering: &Ordering) -> Result<Cholesky, FactorError> {
        let n = k.nrows();
        let m = ordering.m;
        let fwd = ordering.fwd.clone();
        if fwd.len() != n || m > n {
            return Err(FactorError::Other(format!(
                "ordering of {} dofs ({} last) for a matrix of {} rows",
                fwd.len(),
                m,
                n
            )));
        }
        let inv = ordering.inverse();
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
            split: None,
            nodes: Nodes::default(),
            prefetch: true,
            contact_supernode: 0,
        };
        chol.nodes = chol.flat_nodes()?;
        chol.contact_supernode = (chol.nodes.nodes.iter())
            .position(|nd| nd.start + nd.size > n - m)
            .unwrap_or(chol.nodes.nodes.len());
        chol.l_cc = chol.trailing_block(m)?;
        chol.split = ordering.halves.and_then(|h| chol.split_at(h));
        Ok(chol)
    }

    /// The supernode ranges of the two halves, if every supernode of the first
    /// $n_1$ columns touches only rows of that half or of the tail, and likewise for
    /// the next $n_2$; otherwise `None` (the solves then run on one thread).
    fn split_at(&self, (n1, n2): (usize, usize)) -> Option<Split> {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            return None;
        };
        let (begin, end) = (sym.supernode_begin(), sym.supernode_end());
        let tail = n1 + n2;
        let a = begin.iter().position(|&b| b >= n1)?;
        let b = begin.iter().position(|&b| b >= tail).unwrap_or(begin.len());
        // No supernode may straddle the end of the first half; one may straddle
        // the end of the second (it then belongs to the tail, solved after both).
        let b = if b > a && end[b - 1] > tail { b - 1 } else { b };
        if a == 0 || b <= a || end[a - 1] > n1 {
            return None;
        }
        let sn = self.supernodal().ok()?;
        let inside = |range: std::ops::Range<usize>, lo: usize, hi: usize| {
            range.into_iter().all(|s| {
                sn.supernode(s)
                    .pattern()
                    .iter()
                    .all(|&r| (lo..hi).contains(&r) || r >= tail)
            })
        };
        (inside(0..a, 0, n1) && inside(a..b, n1, tail)).then_some(Split {
            supernodes: [a, b],
            rows: [n1, tail],
        })
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

    /// Order $n$ of the factored matrix: its number of rows, the length of a right-hand side.
    pub fn dim(&self) -> usize {
        self.symbolic.nrows()
    }

    /// The trailing block $L_{CC}$.
    pub fn l_cc(&self) -> &Mat<f64> {
        &self.l_cc
    }

    fn n_supernodes(&self) -> usize {
        self.nodes.nodes.len()
    }

    fn flat_nodes(&self) -> Result<Nodes, FactorError> {
        let SymbolicCholeskyRaw::Supernodal(sym) = self.symbolic.raw() else {
            return Err(FactorError::Other("expected a supernodal factor".into()));
        };
        if self.dim() > u32::MAX as usize {
            return Err(FactorError::Other(format!(
                "{} rows exceed u32",
                self.dim()
            )));
        }
        let mut flat = Nodes::default();
        for s in 0..sym.n_supernodes() {
            let node = sym.supernode(s);
            let size = sym.supernode_end()[s] - sym.supernode_begin()[s];
            let first = flat.rows.len();
            flat.rows.extend(node.pattern().iter().map(|&r| r as u32));
            flat.nodes.push(Node {
                start: node.start(),
                size,
                val: sym.col_ptr_for_val()[s],
                rows: first..flat.rows.len(),
            });
        }
        Ok(flat)
    }

    /// Whether triangular solves run the two halves on two threads.
    pub fn is_parallel(&self) -> bool {
        self.split.is_some()
    }

    /// Turns the software prefetch of the backward sweep on or off (to measure it).
    pub fn set_prefetch(&mut self, on: bool) {
        self.prefetch = on;
    }

    /// Makes every later triangular solve run on the calling thread alone (for
    /// callers that already keep both cores busy).
    pub fn sequential(&mut self) {
        self.split = None;
    }

    /// Forward solve $x = L^{-1}\Pi b$ ($\Pi$ the fill-reducing permutation).
    // ANCHOR: forward
    pub fn forward(&self, b: &[f64]) -> Vec<f64> {
        self.forward_many(&[b]).pop().expect("one column")
    }

    /// Forward solves of several right-hand sides: one sweep over L per group of
    /// up to four (the sweep costs memory traffic, which the columns share).
    pub fn forward_many(&self, bs: &[&[f64]]) -> Vec<Vec<f64>> {
        self.forward_groups(bs, Sweep::Forward)
    }

    /// [`Cholesky::forward_many`] for right-hand sides that vanish off the contact
    /// dofs (the last m rows of the ordering), as a field's contact reactions do:
    /// the sweep starts at the first supernode that holds a contact column. Every
    /// supernode before it only divides and multiplies zeros (its values stay +0)
    /// and subtracts +0 from the rows it updates, which leaves their values as they
    /// are: the result is [`Cholesky::forward_many`]'s, to the bit but for the sign
    /// of a zero entry of the right-hand side (the full sweep's split halves add
    /// +0 to it), for the cost of the separator's supernodes (`tests/linalg.rs`).
    pub fn forward_many_contact(&self, bs: &[&[f64]]) -> Vec<Vec<f64>> {
        debug_assert!(bs.iter().all(|b| {
            let first = self.dim() - self.l_cc.nrows();
            (self.fwd[..first].iter()).all(|&old| b[old] == 0.0)
        }));
        self.forward_groups(bs, Sweep::ForwardContact)
    }

    fn forward_groups(&self, bs: &[&[f64]], how: Sweep) -> Vec<Vec<f64>> {
        let mut out = Vec::with_capacity(bs.len());
        for group in bs.chunks(MAX_BATCH) {
            // Permuted and interleaved: row i of the group is x[i*r..(i+1)*r].
            let r = group.len();
            let mut x = vec![0.0; self.dim() * r];
            for (row, &old) in x.chunks_exact_mut(r).zip(&self.fwd) {
                for (v, b) in row.iter_mut().zip(group) {
                    *v = b[old];
                }
            }
            self.sweep(&mut x, r, how);
            if r == 1 {
                out.push(x);
            } else {
                out.extend((0..r).map(|j| x.iter().skip(j).step_by(r).copied().collect()));
            }
        }
        out
    }

    /// One sweep over the `r` interleaved columns of `x`.
    fn sweep(&self, x: &mut [f64], r: usize, how: Sweep) {
        fn run<const R: usize>(c: &Cholesky, x: &mut [f64], how: Sweep) {
            let rows = x.as_chunks_mut::<R>().0;
            match how {
                Sweep::Forward => c.sweep_forward(rows),
                Sweep::ForwardContact => {
                    let (n, all) = (c.dim(), c.contact_supernode..c.n_supernodes());
                    lower_solve(&c.nodes, &c.values, all, rows, 0, &mut [], n)
                }
                Sweep::Backward => c.sweep_backward(rows),
            }
        }
        match r {
            1 => run::<1>(self, x, how),
            2 => run::<2>(self, x, how),
            3 => run::<3>(self, x, how),
            _ => run::<4>(self, x, how),
        }
    }

    fn sweep_forward<const R: usize>(&self, x: &mut [[f64; R]]) {
        let n = self.dim();
        let mut first = 0;
        if let Some(split) = self.split {
            let ([a, b], [n1, tail]) = (split.supernodes, split.rows);
            // The halves are independent; each collects its updates of the
            // tail rows in its own buffer, added once both are done.
            let (left, right, rest) = split.cut(x);
            let (mut buf_l, mut buf_r) = (vec![[0.0; R]; n - tail], vec![[0.0; R]; n - tail]);
            std::thread::scope(|scope| {
                scope.spawn(|| {
                    lower_solve(&self.nodes, &self.values, a..b, right, n1, &mut buf_r, tail)
                });
                lower_solve(&self.nodes, &self.values, 0..a, left, 0, &mut buf_l, tail);
            });
            for ((x, l), r) in rest.iter_mut().zip(&buf_l).zip(&buf_r) {
                for j in 0..R {
                    x[j] += l[j] + r[j];
                }
            }
            first = b;
        }
        let all = first..self.n_supernodes();
        lower_solve(&self.nodes, &self.values, all, x, 0, &mut [], n);
    }
    // ANCHOR_END: forward

    fn sweep_backward<const R: usize>(&self, x: &mut [[f64; R]]) {
        let n = self.dim();
        let first = self.split.map_or(0, |s| s.supernodes[1]);
        let all = first..self.n_supernodes();
        upper_solve(self.prefetch, &self.nodes, &self.values, all, x, 0, &[], n);
        if let Some(split) = self.split {
            let ([a, b], [n1, tail]) = (split.supernodes, split.rows);
            // The tail is known; the halves only read it.
            let (left, right, rest) = split.cut(x);
            let rest = &*rest;
            std::thread::scope(|scope| {
                scope.spawn(|| {
                    upper_solve(
                        self.prefetch,
                        &self.nodes,
                        &self.values,
                        a..b,
                        right,
                        n1,
                        rest,
                        tail,
                    )
                });
                upper_solve(
                    self.prefetch,
                    &self.nodes,
                    &self.values,
                    0..a,
                    left,
                    0,
                    rest,
                    tail,
                );
            });
        }
    }

    /// Backward solve: returns $\Pi^\top L^{-\top} x$ (so `backward(forward(b))` $= K^{-1}b$).
    pub fn backward(&self, x: Vec<f64>) -> Vec<f64> {
        self.backward_many(vec![x]).pop().expect("one column")
    }

    /// Backward solves of several columns, see [`Cholesky::forward_many`].
    pub fn backward_many(&self, xs: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
        let n = self.dim();
        let mut out = Vec::with_capacity(xs.len());
        let mut xs = xs.into_iter().peekable();
        while xs.peek().is_some() {
            let group: Vec<Vec<f64>> = xs.by_ref().take(MAX_BATCH).collect();
            let r = group.len();
            let mut x = if r == 1 {
                group.into_iter().next().expect("one column")
            } else {
                let mut x = vec![0.0; n * r];
                for (i, row) in x.chunks_exact_mut(r).enumerate() {
                    for (v, col) in row.iter_mut().zip(&group) {
                        *v = col[i];
                    }
                }
                x
            };
            self.sweep(&mut x, r, Sweep::Backward);
            for j in 0..r {
                let mut u = vec![0.0; n];
                for (row, &old) in x.chunks_exact(r).zip(&self.fwd) {
                    u[old] = row[j];
                }
                out.push(u);
            }
        }
        out
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
