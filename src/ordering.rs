//! Fill-reducing orderings of the free dofs, with the contact normal dofs last
//! (so that their Schur complement falls out of the factor, see [`crate::linalg`]).
//!
//! Two are offered:
//! - [`Ordering::amd`]: faer's approximate minimum degree on the matrix graph, for any
//!   mesh;
//! - [`Ordering::nested_dissection`]: geometric nested dissection of the structured
//!   grid. A vertical or horizontal grid line separates the grid (no triangle
//!   crosses it, the diagonals stay inside their cells), so the grid is cut in
//!   two by its middle line across the longer side, each half is ordered the same
//!   way, and the line comes after both halves. On a 2D grid this is the classical
//!   near-optimal order (George 1973), and the first cut, the line $x = 1$, splits
//!   the factor into two independent subtrees that two threads solve at once.
//!
//! Both are written as `fwd[new] = old`.

use crate::assembly::SpMat;
use crate::error::FactorError;
use crate::mesh::{Dofs, Mesh};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;

/// A symmetric permutation of the dofs with `m` given dofs last.
#[derive(Debug, Clone)]
pub struct Ordering {
    /// `fwd[new] = old`.
    pub fwd: Vec<usize>,
    /// The number of trailing dofs (the contact normal dofs, in the order given).
    pub m: usize,
    /// With nested dissection: the lengths $(n_1, n_2)$ of the two halves that
    /// come first, positions $[0, n_1)$ and $[n_1, n_1 + n_2)$. No entry of the
    /// matrix couples them, so neither does the factor.
    pub halves: Option<(usize, usize)>,
}

fn other<E: std::fmt::Debug>(e: E) -> FactorError {
    FactorError::Other(format!("{e:?}"))
}

impl Ordering {
    /// AMD on the pattern of `k`, then `last` moved to the end.
    pub fn amd(k: &SpMat, last: &[usize]) -> Result<Ordering, FactorError> {
        let n = k.nrows();
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
        let is_last = mark(n, last);
        let mut fwd: Vec<usize> = amd_fwd.into_iter().filter(|&d| !is_last[d]).collect();
        fwd.extend_from_slice(last);
        Ok(Ordering {
            fwd,
            m: last.len(),
            halves: None,
        })
    }

    // ANCHOR: nested_dissection
    /// Geometric nested dissection of the structured `mesh`, then `last` at the end.
    pub fn nested_dissection(mesh: &Mesh, dofs: &Dofs, last: &[usize]) -> Ordering {
        let (nx, ny) = (mesh.n, mesh.ny);
        let is_last = mark(dofs.count, last);
        let mut fwd = Vec::with_capacity(dofs.count);
        let mut emit = |fwd: &mut Vec<usize>, i: usize, j: usize| {
            let node = j * (nx + 1) + i;
            for c in 0..2 {
                if let Some(d) = dofs.of(node, c).filter(|&d| !is_last[d]) {
                    fwd.push(d);
                }
            }
        };
        // Criss-cross cells have a centre node coupled only to the cell's corners:
        // eliminated first, each makes its cell a clique, which no grid line crosses.
        // The centres of the cells left of x = 1 go with the left half, the others
        // with the right.
        let grid = (nx + 1) * (ny + 1);
        let centres = |fwd: &mut Vec<usize>, cols: std::ops::Range<usize>| {
            if mesh.pattern != crate::mesh::Pattern::CrissCross {
                return;
            }
            for j in 0..ny {
                for i in cols.clone() {
                    let node = grid + j * nx + i;
                    fwd.extend((0..2).filter_map(|c| dofs.of(node, c)));
                }
            }
        };
        // Top level by hand, to record where the halves end: the middle column
        // i = nx/2 (the line x = 1) separates left from right.
        let mid = nx / 2;
        centres(&mut fwd, 0..mid);
        dissect(&mut fwd, &mut emit, (0, mid - 1), (0, ny));
        let n1 = fwd.len();
        centres(&mut fwd, mid..nx);
        dissect(&mut fwd, &mut emit, (mid + 1, nx), (0, ny));
        let n2 = fwd.len() - n1;
        for j in 0..=ny {
            emit(&mut fwd, mid, j);
        }
        fwd.extend_from_slice(last);
        Ordering {
            fwd,
            m: last.len(),
            halves: Some((n1, n2)),
        }
    }
    // ANCHOR_END: nested_dissection

    /// `inv[old] = new`.
    pub fn inverse(&self) -> Vec<usize> {
        let mut inv = vec![0usize; self.fwd.len()];
        for (new, &old) in self.fwd.iter().enumerate() {
            inv[old] = new;
        }
        inv
    }
}

fn mark(n: usize, dofs: &[usize]) -> Vec<bool> {
    let mut is = vec![false; n];
    for &d in dofs {
        is[d] = true;
    }
    is
}

/// Boxes of at most this many nodes are numbered row by row.
const LEAF: usize = 16;

/// Orders the nodes of the box `i0..=i1` × `j0..=j1`: both halves, then the
/// middle line across the longer side.
fn dissect(
    fwd: &mut Vec<usize>,
    emit: &mut impl FnMut(&mut Vec<usize>, usize, usize),
    (i0, i1): (usize, usize),
    (j0, j1): (usize, usize),
) {
    let (w, h) = (i1 + 1 - i0, j1 + 1 - j0);
    if w * h <= LEAF || w.max(h) < 3 {
        for j in j0..=j1 {
            for i in i0..=i1 {
                emit(fwd, i, j);
            }
        }
    } else if w >= h {
        let s = (i0 + i1) / 2;
        dissect(fwd, emit, (i0, s - 1), (j0, j1));
        dissect(fwd, emit, (s + 1, i1), (j0, j1));
        for j in j0..=j1 {
            emit(fwd, s, j);
        }
    } else {
        let s = (j0 + j1) / 2;
        dissect(fwd, emit, (i0, i1), (j0, s - 1));
        dissect(fwd, emit, (i0, i1), (s + 1, j1));
        for i in i0..=i1 {
            emit(fwd, i, s);
        }
    }
}
