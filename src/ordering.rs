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
//! - [`Ordering::coordinate_dissection`]: nested dissection of any triangle mesh by
//!   recursive coordinate bisection. A node set is split at the median of its
//!   coordinate along the longer side of its bounding box into $A$ and $B$; the
//!   nodes of one side with a triangle edge to the other side form the separator
//!   $S$ (the smaller of the two such sets), and the order is $A \setminus S$,
//!   $B \setminus S$ (each dissected the same way), then $S$. No matrix entry
//!   couples $A \setminus S$ with $B \setminus S$, so the first cut again gives two
//!   independent subtrees.
//!
//! All are written as `fwd[new] = old`.

use crate::assembly::SpMat;
use crate::error::FactorError;
use crate::mesh::{Dofs, Mesh, NodeOrder};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::amd;

/// The nodes from which a file mesh is ordered by coordinate dissection by default
/// (below, AMD): the run's factorisation and the trace constant's alike.
pub const MIN_NODES_TO_DISSECT: usize = 100_000;

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

    // ANCHOR: coordinate_dissection
    /// Nested dissection of any `mesh` by recursive coordinate bisection of its
    /// nodes, then `last` at the end.
    pub fn coordinate_dissection(mesh: &Mesh, dofs: &Dofs, last: &[usize]) -> Ordering {
        let NodeOrder { nodes, na, nb } = mesh.dissection.get_or_init(|| dissect_nodes(mesh));
        let (na, nb) = (*na, *nb);
        let is_last = mark(dofs.count, last);
        let mut fwd = Vec::with_capacity(dofs.count);
        let mut ends = [0; 2];
        for (k, &v) in nodes.iter().enumerate() {
            fwd.extend((0..2).filter_map(|c| dofs.of(v, c).filter(|&d| !is_last[d])));
            if k + 1 == na {
                ends[0] = fwd.len();
            }
            if k + 1 == nb {
                ends[1] = fwd.len();
            }
        }
        fwd.extend_from_slice(last);
        let halves = (ends[0] > 0 && ends[1] > ends[0]).then_some((ends[0], ends[1] - ends[0]));
        Ordering {
            fwd,
            m: last.len(),
            halves,
        }
    }
    // ANCHOR_END: coordinate_dissection

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

/// The nodes that share a triangle edge with each node (compressed rows).
/// A mesh's nodes in nested-dissection order by recursive coordinate bisection (the
/// mesh keeps it: [`NodeOrder`]).
fn dissect_nodes(mesh: &Mesh) -> NodeOrder {
    let graph = NodeGraph::new(mesh);
    let mut cut = Bisector {
        mesh,
        graph: &graph,
        stamp: vec![0; mesh.nodes.len()],
        side: vec![0; mesh.nodes.len()],
        level: 0,
    };
    let mut nodes = Vec::with_capacity(mesh.nodes.len());
    let all: Vec<usize> = (0..mesh.nodes.len()).collect();
    // Top level by hand, to record where the halves end.
    let (a, b, sep) = cut.split(all);
    cut.order(a, &mut nodes);
    let na = nodes.len();
    cut.order(b, &mut nodes);
    let nb = nodes.len();
    nodes.extend_from_slice(&sep);
    NodeOrder { nodes, na, nb }
}

struct NodeGraph {
    start: Vec<usize>,
    adj: Vec<usize>,
}

impl NodeGraph {
    /// Each triangle gives each of its corners the other two: the lists are counted,
    /// filled, then each sorted and rid of repeats in place (a counting sort by node;
    /// one sort of all 1.6 M pairs of paper_n512 took three times as long).
    fn new(mesh: &Mesh) -> NodeGraph {
        let n = mesh.nodes.len();
        let mut start = vec![0usize; n + 1];
        for t in &mesh.triangles {
            for &v in t {
                start[v + 1] += 2;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut adj = vec![0usize; start[n]];
        for t in &mesh.triangles {
            for i in 0..3 {
                let v = t[i];
                adj[fill[v]] = t[(i + 1) % 3];
                adj[fill[v] + 1] = t[(i + 2) % 3];
                fill[v] += 2;
            }
        }
        // Compacted in place: a node's unique neighbours are written no later than
        // where its own list began.
        let mut w = 0;
        for v in 0..n {
            let (a, b) = (start[v], start[v + 1]);
            adj[a..b].sort_unstable();
            start[v] = w;
            let mut last = usize::MAX;
            for k in a..b {
                if adj[k] != last {
                    last = adj[k];
                    adj[w] = last;
                    w += 1;
                }
            }
        }
        start[n] = w;
        adj.truncate(w);
        NodeGraph { start, adj }
    }
    fn of(&self, v: usize) -> &[usize] {
        &self.adj[self.start[v]..self.start[v + 1]]
    }
}

/// Node sets of at most this many nodes are not cut further.
const LEAF_NODES: usize = 16;

/// Recursive coordinate bisection with vertex separators.
struct Bisector<'a> {
    mesh: &'a Mesh,
    graph: &'a NodeGraph,
    /// `side[v]` (1 = A, 2 = B) is valid for the cut numbered `stamp[v]`.
    stamp: Vec<u32>,
    side: Vec<u8>,
    level: u32,
}

impl Bisector<'_> {
    /// Splits `set` into (A without S, B without S, S).
    fn split(&mut self, mut set: Vec<usize>) -> (Vec<usize>, Vec<usize>, Vec<usize>) {
        let nodes = &self.mesh.nodes;
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &v in &set {
            for c in 0..2 {
                lo[c] = lo[c].min(nodes[v][c]);
                hi[c] = hi[c].max(nodes[v][c]);
            }
        }
        let c = usize::from(hi[1] - lo[1] > hi[0] - lo[0]);
        let key = |v: usize| (nodes[v][c], v);
        let mid = set.len() / 2;
        set.select_nth_unstable_by(mid, |&p, &q| key(p).partial_cmp(&key(q)).unwrap());
        // Nodes on the median's coordinate all go to B, so that a grid line is cut
        // whole; if that leaves A empty, the cut is at the middle position.
        let pivot = nodes[set[mid]][c];
        let (mut a, mut b): (Vec<usize>, Vec<usize>) =
            set.iter().partition(|&&v| nodes[v][c] < pivot);
        if a.is_empty() {
            let (x, y) = set.split_at(mid);
            (a, b) = (x.to_vec(), y.to_vec());
        }
        self.level += 1;
        for (s, part) in [(1, &a), (2, &b)] {
            for &v in part.iter() {
                self.stamp[v] = self.level;
                self.side[v] = s;
            }
        }
        let touching = |me: &Vec<usize>, other: u8| -> Vec<bool> {
            me.iter()
                .map(|&v| {
                    self.graph
                        .of(v)
                        .iter()
                        .any(|&w| self.stamp[w] == self.level && self.side[w] == other)
                })
                .collect()
        };
        let (ta, tb) = (touching(&a, 2), touching(&b, 1));
        let (na, nb) = (
            ta.iter().filter(|&&t| t).count(),
            tb.iter().filter(|&&t| t).count(),
        );
        // (the part without its separator nodes, the separator)
        let take = |part: Vec<usize>, t: Vec<bool>| -> (Vec<usize>, Vec<usize>) {
            let (mut rest, mut s) = (Vec::with_capacity(part.len()), vec![]);
            for (v, on) in part.into_iter().zip(t) {
                if on { s.push(v) } else { rest.push(v) }
            }
            (rest, s)
        };
        if na <= nb {
            let (a, s) = take(a, ta);
            (a, b, s)
        } else {
            let (b, s) = take(b, tb);
            (a, b, s)
        }
    }

    /// Appends `set` in nested-dissection order to `out`.
    fn order(&mut self, set: Vec<usize>, out: &mut Vec<usize>) {
        if set.len() <= LEAF_NODES {
            out.extend_from_slice(&set);
            return;
        }
        let (a, b, s) = self.split(set);
        self.order(a, out);
        self.order(b, out);
        out.extend_from_slice(&s);
    }
}
