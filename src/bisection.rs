//! Newest-vertex bisection of the paper's structured mesh: nested families of
//! conforming meshes, uniform or graded towards chosen points.
//!
//! Every triangle ever made lives in one [`Forest`]. A triangle $[a, b, c]$ is cut at
//! the midpoint $m$ of its refinement edge $bc$ (the edge opposite its newest vertex
//! $a$) into $[m, a, b]$ and $[m, c, a]$, whose refinement edges are the two old
//! edges. In the initial mesh each square cell's diagonal is the refinement edge of
//! both its triangles, a compatible labelling, so refining a triangle whose
//! neighbour across that edge has another refinement edge first refines the
//! neighbour, and the recursion ends (Mitchell 1991; Binev, Dahmen, DeVore 2004).
//! A mesh is a set of leaves of the forest. Two meshes of the forest are nested when
//! every triangle of the finer one descends from one of the coarser, and then a P1
//! field of the coarse mesh is P1 on the fine one: [`Forest::interpolation`] locates
//! each fine node by descending the forest, so the embedding is exact.

use crate::element::twice_area;
use crate::error::InputError;
use crate::geometry::{Geometry, Side};
use crate::mesh::{Interpolation, MAX_N, Mesh, Pattern, check_n};
use std::collections::HashMap;

/// All triangles of a bisection family, and their nodes.
#[derive(Debug, Clone)]
pub struct Forest {
    /// Every node made so far; a mesh uses a subset.
    pub nodes: Vec<[f64; 2]>,
    /// Triangles $[a, b, c]$, counter-clockwise, refinement edge $bc$.
    tris: Vec<[usize; 3]>,
    children: Vec<Option<[usize; 2]>>,
    /// Depth in the forest (0 for the initial triangles).
    depth: Vec<u32>,
    midpoints: HashMap<(usize, usize), usize>,
    /// The initial grid, for a forest grown from one ([`Forest::new`]); `None` for one
    /// grown from a triangulation ([`Forest::from_triangles`]).
    grid: Option<Grid>,
}

/// The structured grid a forest grew from: $n_0$ segments on the bottom, $n_{y,0}$
/// rows, cells `cell` wide and tall, on `geometry`.
#[derive(Debug, Clone)]
struct Grid {
    n0: usize,
    ny0: usize,
    cell: [f64; 2],
    geometry: Geometry,
}

/// A conforming mesh of the forest: its triangles (sorted ids).
#[derive(Debug, Clone, PartialEq)]
pub struct Leaves(pub Vec<usize>);

fn key(a: usize, b: usize) -> (usize, usize) {
    (a.min(b), a.max(b))
}

impl Forest {
    /// The structured mesh with $n_0$ segments on `geometry` as the forest's roots.
    pub fn new(n0: usize, geometry: &Geometry) -> Result<(Forest, Leaves), InputError> {
        check_n(n0)?;
        let base = Mesh::build(n0, geometry, Pattern::Diagonal)?;
        let (ny0, cell) = (base.ny, [base.dx(), base.dy()]);
        // Rotate each triangle so that its vertex opposite the diagonal comes first.
        let tris: Vec<[usize; 3]> = base
            .triangles
            .iter()
            .map(|t| {
                // Diagonal pattern: [ll, lr, ur] -> [lr, ur, ll]; [ll, ur, ul] -> [ul, ll, ur].
                let (p0, p2) = (base.nodes[t[0]], base.nodes[t[2]]);
                if p2[1] > p0[1] && p2[0] > p0[0] {
                    [t[1], t[2], t[0]]
                } else {
                    [t[2], t[0], t[1]]
                }
            })
            .collect();
        let count = tris.len();
        Ok((
            Forest {
                nodes: base.nodes,
                children: vec![None; count],
                depth: vec![0; count],
                tris,
                midpoints: HashMap::new(),
                grid: Some(Grid {
                    n0,
                    ny0,
                    cell,
                    geometry: geometry.clone(),
                }),
            },
            Leaves((0..count).collect()),
        ))
    }

    /// Any conforming triangulation (`triangles` counter-clockwise on `nodes`) as the
    /// forest's roots. Each triangle's refinement edge is its longest, ties broken by
    /// the edge's node numbers, so that every edge has one rank in a strict order:
    /// refining a triangle first refines its neighbour across that edge only when the
    /// neighbour's own refinement edge ranks higher, and the conforming closure ends.
    /// Such a forest refines and interpolates as one from a grid does; its leaves
    /// become a mesh by [`Forest::leaf_triangles`] (the scene's boundary parts are
    /// not carried over).
    pub fn from_triangles(
        nodes: Vec<[f64; 2]>,
        triangles: &[[usize; 3]],
    ) -> Result<(Forest, Leaves), InputError> {
        let len = |a: usize, b: usize| {
            let (p, q) = (nodes[a], nodes[b]);
            (p[0] - q[0]).hypot(p[1] - q[1])
        };
        let mut tris = Vec::with_capacity(triangles.len());
        for (i, t) in triangles.iter().enumerate() {
            if t.iter().any(|&v| v >= nodes.len()) || twice_area(t.map(|v| nodes[v])) <= 0.0 {
                return Err(InputError::field(
                    "triangles",
                    format!("triangle {i} {t:?}"),
                    format!(
                        "three of the {} nodes, counter-clockwise, with a positive area",
                        nodes.len()
                    ),
                ));
            }
            // Rotate so that the top-ranked edge is the last, bc (opposite the first).
            let rank = |e: usize| {
                let (a, b) = (t[(e + 1) % 3], t[(e + 2) % 3]);
                (len(a, b), a.min(b), a.max(b))
            };
            let first = (0..3)
                .max_by(|&x, &y| rank(x).partial_cmp(&rank(y)).expect("finite lengths"))
                .expect("three edges");
            tris.push([t[first], t[(first + 1) % 3], t[(first + 2) % 3]]);
        }
        let count = tris.len();
        Ok((
            Forest {
                nodes,
                children: vec![None; count],
                depth: vec![0; count],
                tris,
                midpoints: HashMap::new(),
                grid: None,
            },
            Leaves((0..count).collect()),
        ))
    }

    /// The nodes and triangles (counter-clockwise) of `leaves`, the nodes renumbered
    /// in the forest's order: the mesh of a forest grown from any triangulation.
    pub fn leaf_triangles(&self, leaves: &Leaves) -> (Vec<[f64; 2]>, Vec<[usize; 3]>) {
        let (_, nodes, tris) = self.numbered(leaves);
        (nodes, tris)
    }

    /// [`Forest::leaf_triangles`] with each node's new number (`usize::MAX` off the mesh).
    fn numbered(&self, leaves: &Leaves) -> (Vec<usize>, Vec<[f64; 2]>, Vec<[usize; 3]>) {
        let mut local = vec![usize::MAX; self.nodes.len()];
        for &t in &leaves.0 {
            for v in self.tris[t] {
                local[v] = 0;
            }
        }
        let mut nodes = vec![];
        for (g, l) in local.iter_mut().enumerate() {
            if *l == 0 {
                *l = nodes.len();
                nodes.push(self.nodes[g]);
            }
        }
        let tris = leaves
            .0
            .iter()
            .map(|&t| self.tris[t].map(|v| local[v]))
            .collect();
        (local, nodes, tris)
    }

    // ANCHOR: leaf_msh
    /// The mesh of `leaves` as a file mesh ([`Forest::leaf_triangles`]) with the named
    /// groups of `roots`, the triangulation the forest grew from
    /// ([`Forest::from_triangles`], its nodes numbered as the forest's first): a group's
    /// edge whose midpoint is a node of the mesh is carried as its two halves, each in
    /// turn the same way, so every boundary part keeps its role, oriented as it was.
    pub fn leaf_msh(&self, leaves: &Leaves, roots: &crate::msh::MshMesh) -> crate::msh::MshMesh {
        let (local, nodes, triangles) = self.numbered(leaves);
        let mut groups = roots.groups.clone();
        for g in &mut groups {
            let mut edges = Vec::with_capacity(g.edges.len());
            let mut todo: Vec<[usize; 2]> = g.edges.iter().rev().copied().collect();
            while let Some([a, b]) = todo.pop() {
                match self.midpoints.get(&key(a, b)) {
                    Some(&m) if local[m] != usize::MAX => todo.extend([[m, b], [a, m]]),
                    _ => edges.push([local[a], local[b]]),
                }
            }
            g.edges = edges;
        }
        crate::msh::MshMesh {
            file: roots.file.clone(),
            nodes,
            triangles,
            groups,
        }
    }
    // ANCHOR_END: leaf_msh

    /// The vertices of triangle `t`.
    pub fn triangle(&self, t: usize) -> [[f64; 2]; 3] {
        self.tris[t].map(|v| self.nodes[v])
    }

    /// The length of triangle `t`'s longest edge.
    pub fn diameter(&self, t: usize) -> f64 {
        let p = self.triangle(t);
        let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        d(p[0], p[1]).max(d(p[1], p[2])).max(d(p[2], p[0]))
    }

    /// How many triangles the forest holds (every level's, leaves or not): the ids
    /// are `0..triangle_count()`.
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// Depth of triangle `t` in the forest.
    pub fn depth(&self, t: usize) -> u32 {
        self.depth[t]
    }

    /// The two halves of `t`, made on first use.
    fn bisect(&mut self, t: usize) -> [usize; 2] {
        if let Some(c) = self.children[t] {
            return c;
        }
        let [a, b, c] = self.tris[t];
        let m = *self.midpoints.entry(key(b, c)).or_insert_with(|| {
            let (p, q) = (self.nodes[b], self.nodes[c]);
            self.nodes.push([0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]);
            self.nodes.len() - 1
        });
        let first = self.tris.len();
        self.tris.push([m, a, b]);
        self.tris.push([m, c, a]);
        self.children.push(None);
        self.children.push(None);
        let d = self.depth[t] + 1;
        self.depth.push(d);
        self.depth.push(d);
        let kids = [first, first + 1];
        self.children[t] = Some(kids);
        kids
    }

    /// Refines `mesh` until no triangle is `marked`, keeping it conforming.
    pub fn refine(&mut self, mesh: &Leaves, marked: impl Fn(&Forest, usize) -> bool) -> Leaves {
        self.refine_within(mesh, marked, usize::MAX)
            .expect("no bound on the nodes")
    }

    /// [`Forest::refine`], but giving up (`None`) once the forest holds more than
    /// `max_nodes` nodes: a marking that asks for more than memory or double
    /// precision allows stops there instead of growing without end.
    pub fn refine_within(
        &mut self,
        mesh: &Leaves,
        marked: impl Fn(&Forest, usize) -> bool,
        max_nodes: usize,
    ) -> Option<Leaves> {
        let mut state = State::new(self, mesh);
        loop {
            if self.nodes.len() > max_nodes {
                return None;
            }
            let todo: Vec<usize> = state
                .alive
                .iter()
                .enumerate()
                .filter(|&(t, &a)| a && marked(self, t))
                .map(|(t, _)| t)
                .collect();
            if todo.is_empty() {
                break;
            }
            for t in todo {
                if self.nodes.len() > max_nodes {
                    return None;
                }
                if state.alive.get(t).copied().unwrap_or(false) {
                    state.refine(self, t);
                }
            }
        }
        Some(Leaves(
            state
                .alive
                .iter()
                .enumerate()
                .filter(|&(_, &a)| a)
                .map(|(t, _)| t)
                .collect(),
        ))
    }

    /// The coarsest conforming mesh of the forest that refines both `mesh` and `other`:
    /// `mesh` refined wherever one of its triangles is a strict ancestor of a
    /// triangle of `other` (and wherever conformity then asks). Two meshes of one
    /// forest then both embed in it exactly ([`Forest::interpolation`]).
    pub fn refine_to_contain(&mut self, mesh: &Leaves, other: &Leaves) -> Leaves {
        let mut parent = vec![usize::MAX; self.tris.len()];
        for (t, c) in self.children.iter().enumerate() {
            if let Some([a, b]) = c {
                parent[*a] = t;
                parent[*b] = t;
            }
        }
        let mut above = vec![false; self.tris.len()];
        for &t in &other.0 {
            let mut p = parent[t];
            while p != usize::MAX && !above[p] {
                above[p] = true;
                p = parent[p];
            }
        }
        self.refine(mesh, |_, t| above.get(t) == Some(&true))
    }

    /// The mesh of `leaves` for the solver: its nodes renumbered in the order of
    /// the forest's (so coarser meshes' nodes come first), boundary parts from
    /// the coordinates. `n` names the level (the uniform mesh it refines).
    ///
    /// The forest must have grown from a grid ([`Forest::new`]); one grown from a
    /// triangulation gives its leaves by [`Forest::leaf_triangles`].
    pub fn mesh(&self, leaves: &Leaves, n: usize) -> Mesh {
        let grid = self
            .grid
            .as_ref()
            .expect("Forest::mesh is for a forest grown from a grid");
        let mut used = vec![false; self.nodes.len()];
        for &t in &leaves.0 {
            for v in self.tris[t] {
                used[v] = true;
            }
        }
        let mut local = vec![usize::MAX; self.nodes.len()];
        let mut nodes = vec![];
        for (g, &u) in used.iter().enumerate() {
            if u {
                local[g] = nodes.len();
                nodes.push(self.nodes[g]);
            }
        }
        // Counter-clockwise with the refinement edge last is already counter-clockwise.
        let triangles: Vec<[usize; 3]> = leaves
            .0
            .iter()
            .map(|&t| self.tris[t].map(|v| local[v]))
            .collect();
        let geo = &grid.geometry;
        let fixed = nodes.iter().map(|&p| geo.fixed_at(p)).collect();
        // The boundary edges: both ends on one side, ordered along it (the load takes
        // an edge's length as the difference of its coordinates along the side).
        let mut boundary = vec![];
        for t in &triangles {
            for e in 0..3 {
                let (a, b) = (t[e], t[(e + 1) % 3]);
                for side in Side::ALL {
                    if geo.on(side, nodes[a]) && geo.on(side, nodes[b]) {
                        let (pa, pb) = (side.along(nodes[a]), side.along(nodes[b]));
                        boundary.push((if pa < pb { [a, b] } else { [b, a] }, side));
                    }
                }
            }
        }
        boundary.sort_by(|x, y| {
            (Side::ALL.iter().position(|s| *s == x.1))
                .cmp(&Side::ALL.iter().position(|s| *s == y.1))
                .then(
                    x.1.along(nodes[x.0[0]])
                        .total_cmp(&y.1.along(nodes[y.0[0]])),
                )
        });
        // The rows of the uniform level n this mesh stands for (a label: its nodes are
        // the forest's).
        let ny = if n.is_multiple_of(grid.n0) {
            n / grid.n0 * grid.ny0
        } else {
            crate::mesh::rows(n, geo)
        };
        Mesh::finish(
            n,
            ny,
            geo,
            Pattern::Bisected,
            nodes,
            triangles,
            fixed,
            boundary,
        )
    }

    /// The exact P1 embedding of the mesh `coarse` (a mesh of this forest) into
    /// the nodes of `fine`, any mesh of the forest that refines it.
    pub fn interpolation(&self, coarse: &Leaves, fine: &Mesh) -> Interpolation {
        let mut in_coarse = vec![false; self.tris.len()];
        for &t in &coarse.0 {
            in_coarse[t] = true;
        }
        let mut local = HashMap::new();
        {
            let mut used: Vec<usize> = coarse.0.iter().flat_map(|&t| self.tris[t]).collect();
            used.sort_unstable();
            used.dedup();
            for (i, g) in used.into_iter().enumerate() {
                local.insert(g, i);
            }
        }
        let roots = self.depth.iter().take_while(|&&d| d == 0).count();
        let weights = fine
            .nodes
            .iter()
            .map(|&p| {
                let bary = |t: usize| {
                    let q = self.triangle(t);
                    let det = twice_area(q);
                    let l1 = twice_area([q[0], p, q[2]]) / det;
                    let l2 = twice_area([q[0], q[1], p]) / det;
                    [1.0 - l1 - l2, l1, l2]
                };
                let worst = |l: [f64; 3]| l[0].min(l[1]).min(l[2]);
                let mut t = match &self.grid {
                    Some(g) => {
                        let (nx, ny) = (g.n0, g.ny0);
                        let [side, dy] = g.cell;
                        let i = ((p[0] / side).floor() as usize).min(nx - 1);
                        let j = ((p[1] / dy).floor() as usize).min(ny - 1);
                        let cell = j * nx + i;
                        if worst(bary(2 * cell)) >= worst(bary(2 * cell + 1)) {
                            2 * cell
                        } else {
                            2 * cell + 1
                        }
                    }
                    // Any triangulation: the root that holds p best.
                    None => (0..roots)
                        .max_by(|&a, &b| worst(bary(a)).total_cmp(&worst(bary(b))))
                        .expect("a root"),
                };
                while !in_coarse[t] {
                    let [c0, c1] = self.children[t].expect("the fine mesh refines the coarse one");
                    t = if worst(bary(c0)) >= worst(bary(c1)) {
                        c0
                    } else {
                        c1
                    };
                }
                let l = bary(t);
                let v = self.tris[t];
                [
                    (local[&v[0]], l[0]),
                    (local[&v[1]], l[1]),
                    (local[&v[2]], l[2]),
                ]
            })
            .collect();
        Interpolation { weights }
    }
}

/// A mesh being refined: which triangles are in it, and the triangles on each edge.
struct State {
    alive: Vec<bool>,
    edges: HashMap<(usize, usize), [Option<usize>; 2]>,
}

impl State {
    fn new(forest: &Forest, mesh: &Leaves) -> State {
        let mut s = State {
            alive: vec![false; forest.tris.len()],
            edges: HashMap::new(),
        };
        for &t in &mesh.0 {
            s.add(forest, t);
        }
        s
    }

    fn add(&mut self, forest: &Forest, t: usize) {
        if self.alive.len() <= t {
            self.alive.resize(t + 1, false);
        }
        self.alive[t] = true;
        let v = forest.tris[t];
        for e in 0..3 {
            let slot = self
                .edges
                .entry(key(v[e], v[(e + 1) % 3]))
                .or_insert([None; 2]);
            if slot[0].is_none() {
                slot[0] = Some(t);
            } else {
                slot[1] = Some(t);
            }
        }
    }

    fn remove(&mut self, forest: &Forest, t: usize) {
        self.alive[t] = false;
        let v = forest.tris[t];
        for e in 0..3 {
            let k = key(v[e], v[(e + 1) % 3]);
            let slot = self.edges.get_mut(&k).expect("edge of a live triangle");
            if slot[0] == Some(t) {
                slot[0] = slot[1].take();
            } else {
                slot[1] = None;
            }
            if slot[0].is_none() {
                self.edges.remove(&k);
            }
        }
    }

    /// The other live triangle on edge `(b, c)` of `t`.
    fn across(&self, t: usize, b: usize, c: usize) -> Option<usize> {
        let slot = self.edges.get(&key(b, c))?;
        slot.iter().flatten().copied().find(|&o| o != t)
    }

    fn split(&mut self, forest: &mut Forest, t: usize) {
        self.remove(forest, t);
        for c in forest.bisect(t) {
            self.add(forest, c);
        }
    }

    /// Bisects `t` and whatever conformity then requires.
    fn refine(&mut self, forest: &mut Forest, t: usize) {
        let [_, b, c] = forest.tris[t];
        if let Some(mut nb) = self.across(t, b, c) {
            let [_, nb_b, nb_c] = forest.tris[nb];
            if key(nb_b, nb_c) != key(b, c) {
                self.refine(forest, nb);
                nb = self
                    .across(t, b, c)
                    .expect("the neighbour's half keeps the edge");
            }
            self.split(forest, t);
            self.split(forest, nb);
        } else {
            self.split(forest, t);
        }
    }
}

/// The largest longest edge allowed at `x` on a mesh of uniform size `d` (the
/// longest edge of its cells) graded towards `points` with exponent $\mu$:
/// $d \min(1, \max(r, d^{1/\mu})^{1-\mu})$, $r$ the distance to the nearest point. A
/// function $r^\lambda$ with $\lambda > \mu$ is then approximated at the rate of a smooth
/// one (Babuška, Kellogg, Pitkäranta 1979).
pub fn graded_size(d: f64, x: [f64; 2], points: &[[f64; 2]], mu: f64) -> f64 {
    let r = points
        .iter()
        .map(|p| (x[0] - p[0]).hypot(x[1] - p[1]))
        .fold(f64::INFINITY, f64::min);
    d * r.max(d.powf(1.0 / mu)).powf(1.0 - mu).min(1.0)
}

/// The centroid of triangle `t`.
pub fn centroid(f: &Forest, t: usize) -> [f64; 2] {
    let p = f.triangle(t);
    [
        (p[0][0] + p[1][0] + p[2][0]) / 3.0,
        (p[0][1] + p[1][1] + p[2][1]) / 3.0,
    ]
}

/// The mesh of level `n` on `geo` graded towards its singular points
/// ([`Geometry::singular_points`]) with exponent `mu` in $(0, 1)$: newest-vertex
/// bisection of the coarsest structured mesh that resolves the scene (4, 8, …
/// segments) until every triangle's longest edge is at most [`graded_size`], with
/// lengths measured in units of $\min(W, H)$ and $d$ the diagonal of a cell of the
/// uniform mesh of level $n$. A scene without singular points gets the uniform mesh
/// of level $n$ by bisection.
pub fn graded_mesh(geo: &Geometry, n: usize, mu: f64) -> Result<Mesh, InputError> {
    graded_mesh_resolving(geo, n, mu, &|_| Ok(()))
}

/// [`graded_mesh`] whose initial grid of $n_0$ segments must also pass `resolves(n0)`
/// (a scene's tractions, say, whose ends must be nodes): the first of 4, 8, 16, … segments up to `n` whose
/// grid resolves the scene, failing that the first multiple of 4 up to `n` (the
/// uniform level `n` itself at the latest). Bisection only adds nodes, so every end
/// the initial grid resolves is a node of the graded mesh.
pub fn graded_mesh_resolving(
    geo: &Geometry,
    n: usize,
    mu: f64,
    resolves: &dyn Fn(usize) -> Result<(), InputError>,
) -> Result<Mesh, InputError> {
    if !(0.05..=0.95).contains(&mu) {
        return Err(InputError::field(
            "grading",
            mu,
            "a number in [0.05, 0.95] (the exponent mu of the grading: near 1 almost \
             uniform, smaller grades more strongly towards the singular points)",
        ));
    }
    check_n(n)?;
    let uniform = Mesh::build(n, geo, Pattern::Diagonal)?;
    resolves(n)?;
    let (mut forest, root) = crate::mesh::grid_candidates(n)
        .find_map(|n0| resolves(n0).ok().and_then(|_| Forest::new(n0, geo).ok()))
        .map_or_else(|| Forest::new(n, geo), Ok)?;
    let unit = geo.width.min(geo.height);
    let d = cell_diagonal(geo, uniform.n) / unit;
    let points: Vec<[f64; 2]> = geo
        .singular_points()
        .iter()
        .map(|p| [p[0] / unit, p[1] / unit])
        .collect();
    // The bound's smallest value, d^(1/mu), is the size the triangles at a singular
    // point approach: it must stay where coordinates can still tell their vertices apart.
    let smallest = d.powf(1.0 / mu);
    if !points.is_empty() && smallest < MIN_GRADED_SIZE {
        // d^(1/mu) >= s  <=>  mu >= ln d / ln s (both logarithms negative).
        let least = (d.ln() / MIN_GRADED_SIZE.ln() * 1000.0).ceil() / 1000.0;
        return Err(InputError::field(
            "grading",
            mu,
            format!(
                "at least {least} at n = {n}: grading {mu} asks for triangles of about \
                 {smallest:.1e} of min(W, H) at the singular points, below the \
                 {MIN_GRADED_SIZE:e} that double-precision coordinates resolve; take a \
                 larger grading or a smaller n"
            ),
        ));
    }
    // The nodes a run could hold in memory (the memory guard's rule, two dofs a
    // node), and never more than the largest uniform mesh's.
    let largest = (MAX_N + 1) * (MAX_N / 2 + 1);
    let max_nodes = crate::memory::max_dofs().map_or(largest, |d| (d / 2).min(largest));
    // A hair of slack so that a triangle exactly at the bound is not cut.
    let slack = 1.0 + 1e-12;
    let leaves = forest.refine_within(
        &root,
        |f, t| {
            let c = centroid(f, t);
            let bound = if points.is_empty() {
                d
            } else {
                graded_size(d, [c[0] / unit, c[1] / unit], &points, mu)
            };
            f.diameter(t) / unit > slack * bound
        },
        max_nodes,
    );
    match leaves {
        Some(leaves) => Ok(forest.mesh(&leaves, n)),
        None => Err(InputError::field(
            "grading",
            mu,
            format!(
                "a graded mesh that fits in memory: at n = {n} the refinement passed \
                 {max_nodes} nodes, more than a run can hold here; take a larger grading \
                 or a smaller n"
            ),
        )),
    }
}

/// The smallest triangle a grading may ask for, in units of $\min(W, H)$: coordinates
/// in double precision are exact to about $10^{-16}$ of the body, so below this a
/// triangle's shape keeps fewer than four digits (and bisection near $10^{-16}$ stops
/// making smaller triangles at all).
pub const MIN_GRADED_SIZE: f64 = 1e-12;

/// The diagonal of a cell of the structured mesh of level `n` on `geo`: $2\sqrt2/n$ on
/// the paper's scene.
pub fn cell_diagonal(geo: &Geometry, n: usize) -> f64 {
    let dx = geo.width / n as f64;
    let ny = crate::mesh::rows(n, geo);
    if ny as f64 * dx == geo.height {
        std::f64::consts::SQRT_2 * dx
    } else {
        dx.hypot(geo.height / ny as f64)
    }
}

/// A scenario's graded meshes.
impl crate::scenario::Scenario {
    /// The mesh of level $n$ graded towards the scene's singular points with exponent
    /// `mu` ([`crate::bisection::graded_mesh_resolving`]). Bisection starts from the
    /// coarsest grid whose nodes hold every end of the supports, the tractions and
    /// $\Gamma_3$ (a grid of 4, 8, 16, … segments where one does, else of any multiple of
    /// 4 up to $n$), so those ends are nodes of the graded mesh; the mesh built is then
    /// checked for each of them, and an end it misses is refused by its key. The graded
    /// mesh cuts the cells by the paper's diagonal only.
    pub fn graded_mesh(&self, n: usize, mu: f64) -> Result<Mesh, InputError> {
        if self.pattern != Pattern::Diagonal {
            return Err(InputError::field(
                "geometry.pattern",
                self.pattern.name(),
                "\"diagonal\" with a graded mesh (bisection starts from the paper's diagonal cut)",
            ));
        }
        // The uniform level's checks, without building it (graded_mesh_resolving builds it).
        self.check_grid(n)?;
        let mesh = crate::bisection::graded_mesh_resolving(&self.geometry, n, mu, &|n0| {
            self.check_traction_ends(n0)
        })?;
        self.check_ends_on(&mesh)?;
        Ok(mesh)
    }
}
