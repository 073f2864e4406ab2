//! The structured, nested P1 triangulation of the scene's rectangle
//! $(0, W) \times (0, H)$ ([`crate::geometry`]; the paper's $(0,2)\times(0,1)$, MODEL.md):
//! $n$ segments on the bottom, $n$ columns and $n_y = nH/W$ (rounded) rows of cells,
//! each cut by its lower-left–upper-right diagonal. On the paper's scene $h = 1/n$ and
//! the cells are squares of side $2h$. The supports fix the components of the
//! boundary nodes they hold; $\Gamma_3$'s nodes whose normal component is free are
//! the contact nodes; the boundary edges carry their side (tractions act there).

use crate::error::InputError;
use crate::geometry::{Geometry, Side};

pub use crate::geometry::Pattern;

/// A P1 triangulation: the structured mesh of the scene's rectangle, or the mesh of a
/// mesh scene's body ([`Mesh::from_body`]), with the components its supports hold,
/// its contact nodes and their gaps, and its boundary edges.
#[derive(Debug, Clone)]
pub struct Mesh {
    /// Number of segments on the bottom, $n = 1/h$ on the paper's scene.
    pub n: usize,
    /// Rows of cells of the structured mesh of level $n$ ($n/2$ on the paper's scene).
    pub ny: usize,
    /// The rectangle's width $W$ (a body's: its bounding box's).
    pub width: f64,
    /// The rectangle's height $H$ (a body's: its bounding box's).
    pub height: f64,
    /// How the cells are cut.
    pub pattern: Pattern,
    /// Node coordinates.
    pub nodes: Vec<[f64; 2]>,
    /// Triangles, counter-clockwise node triples.
    pub triangles: Vec<[usize; 3]>,
    /// Fixed components of each node (x, y).
    pub fixed: Vec<[bool; 2]>,
    /// The nodes of $\Gamma_3$ ordered by $x$, its ends included.
    pub gamma3: Vec<usize>,
    /// The contact nodes: those of $\Gamma_3$ whose normal component is free (all of
    /// them unless a clamp or roller ends on $\Gamma_3$'s end).
    pub contact: Vec<usize>,
    /// The gap of each contact node (in `contact` order) that its contact variable is
    /// measured from: the contact acts on $u\cdot n_f - \text{gap}_i$. It is the node's
    /// initial gap $g_{0,i}$ less the normal component of a prescribed displacement
    /// ([`crate::body::Body::shift`]); zero on the rectangle, whose $\Gamma_3$ lies on
    /// the foundation.
    pub gap: Vec<f64>,
    /// The foundation's outward unit normal $n_f$ (the paper's $(0, -1)$ unless a mesh
    /// scene says otherwise). With another, the nodes of $\Gamma_3$ carry their dofs in
    /// the contact frame of [`crate::frame`], and `fixed` gives their held components in it.
    pub normal: [f64; 2],
    /// The rigid translation $d$ added to the computed field to give the body's
    /// displacement ([`crate::body::Body::shift`]); zero unless a mesh scene prescribes a
    /// displacement.
    pub shift: [f64; 2],
    /// The boundary edges and their sides, each ordered along its side.
    pub boundary: Vec<([usize; 2], Side)>,
    /// The boundary edges whose support adds a term $k_s\int_e u\cdot v\,ds$ to the
    /// elasticity operator, with its $k_s$ ([`crate::support::Hold::stiffness`]).
    pub boundary_terms: Vec<([usize; 2], f64)>,
    /// The nodes in coordinate-dissection order, found once per mesh (by
    /// [`crate::ordering::Ordering::coordinate_dissection`], which the run's
    /// factorisation and the smallness check's both order by).
    pub(crate) dissection: std::sync::OnceLock<NodeOrder>,
}

/// A mesh's nodes in nested-dissection order: the first half's nodes (ending at
/// `na`), the second's (ending at `nb`), then the separator between them. It depends
/// on the mesh alone, not on which dofs are free, so the mesh keeps it for every
/// factorisation on it (the ordering module finds it).
#[derive(Debug, Clone)]
pub(crate) struct NodeOrder {
    pub(crate) nodes: Vec<usize>,
    pub(crate) na: usize,
    pub(crate) nb: usize,
}

/// The most segments a structured mesh may have on the bottom (some 17 million
/// unknowns on the paper's rectangle).
pub const MAX_N: usize = 4096;

/// Checks a number of contact segments: a positive multiple of 4, so that $y = 1/2$
/// is a mesh line.
pub fn check_n(n: usize) -> Result<(), InputError> {
    if n == 0 || !n.is_multiple_of(4) {
        return Err(InputError::field(
            "n",
            n,
            "a positive multiple of 4 (on the paper's scene y = 0.5 is then a mesh line; on \
             any scene the levels n, 2n, ... nest)",
        ));
    }
    Ok(())
}

/// The rows of cells of the structured mesh of level `n` on `geo`: near-square cells,
/// $n H / W$ rounded ($n/2$ on the paper's scene).
pub fn rows(n: usize, geo: &Geometry) -> usize {
    ((n as f64 * geo.height / geo.width).round() as usize).max(1)
}

/// The width and height of a cell of the structured mesh of level `n` on `geo`: square
/// cells when the rows fit exactly (the paper's scene), else cells of height $H / n_y$.
pub fn spacing(n: usize, geo: &Geometry) -> [f64; 2] {
    let side = geo.width / n as f64;
    let ny = rows(n, geo);
    if ny as f64 * side == geo.height {
        [side, side]
    } else {
        [side, geo.height / ny as f64]
    }
}

/// Refuses a segment of `side` (a support's or a traction's, `field`) whose ends
/// `[from, to]` miss the nodes, spaced `d` along the side on the mesh with `n`.
pub(crate) fn check_ends(
    field: &str,
    side: Side,
    ends: [f64; 2],
    d: f64,
    n: usize,
) -> Result<(), InputError> {
    for (end, v) in [("from", ends[0]), ("to", ends[1])] {
        if !on_line(v, d) {
            return Err(InputError::field(
                end_key(field, side, end),
                v,
                format!(
                    "a mesh line of the mesh with n = {n}, where the {} side has a node \
                     every {d}: choose n so that every segment's ends are nodes",
                    side.name()
                ),
            ));
        }
    }
    Ok(())
}

/// The key of a segment's end `end` (`from` or `to`): `FIELD.from` for a segment
/// the file spells out; for a preset's (whose field is `geometry.supports = "NAME"`),
/// the preset and the side, since the file has no key of the end itself.
fn end_key(field: &str, side: Side, end: &str) -> String {
    if field.contains(" = ") {
        format!(
            "{field} (its {} side's clamp or rollers, `{end}`)",
            side.name()
        )
    } else {
        format!("{field}.{end}")
    }
}

/// Refuses a level `n` whose structured grid on `geo` would not be a mesh of the scene:
/// cells far from square, or a support's or $\Gamma_3$'s end off the grid lines. Builds
/// nothing, so a study can ask it of levels it will build later.
pub fn check_grid(n: usize, geo: &Geometry) -> Result<(), InputError> {
    check_n(n)?;
    let [side, dy] = spacing(n, geo);
    if !(0.5..=2.0).contains(&(dy / side)) {
        return Err(InputError::field(
            "n",
            n,
            format!(
                "a mesh whose cells are near squares: n = {n} gives cells {side:e} wide \
                     and {dy:e} tall on the {} x {} rectangle; take a larger n",
                geo.width, geo.height
            ),
        ));
    }
    for s in &geo.supports {
        let d = if s.side.normal() == 0 { dy } else { side };
        check_ends(&s.field, s.side, [s.from, s.to], d, n)?;
    }
    for v in geo.contact {
        if !on_line(v, side) {
            return Err(InputError::field(
                "geometry.contact",
                v,
                format!(
                    "a mesh line of the mesh with n = {n} (a node every {side} on the \
                         bottom): choose n so that Gamma_3's ends are nodes"
                ),
            ));
        }
    }
    Ok(())
}

/// The grids, by segments on the bottom, in the order a coarsest grid that resolves a
/// scene is sought: 4, 8, 16, … up to `max` first (levels that double from them nest
/// with the uniform meshes), then every other multiple of 4 up to `max`.
pub fn grid_candidates(max: usize) -> impl Iterator<Item = usize> {
    let powers =
        std::iter::successors(Some(4usize), |m| Some(2 * m)).take_while(move |&m| m <= max);
    let others = (4..=max).step_by(4).filter(|m| !m.is_power_of_two());
    powers.chain(others)
}

/// Whether `v` lies on a mesh line of spacing `d` (within rounding).
pub(crate) fn on_line(v: f64, d: f64) -> bool {
    let q = v / d;
    (q - q.round()).abs() <= 1e-9 * q.abs().max(1.0)
}

impl Mesh {
    /// The paper's mesh with $n$ contact segments; $n$ must be a positive multiple of 4
    /// so that $y = 1/2$ is a mesh line.
    pub fn structured(n: usize) -> Result<Mesh, InputError> {
        Mesh::build(n, &Geometry::paper(), Pattern::Diagonal)
    }

    /// The mesh with $n$ contact segments on the given geometry.
    pub fn with_supports(n: usize, geo: &Geometry) -> Result<Mesh, InputError> {
        Mesh::build(n, geo, Pattern::Diagonal)
    }

    /// The mesh with $n$ segments on the bottom, the given geometry and cell pattern.
    /// Every end of a support segment and of $\Gamma_3$ must fall on a mesh line.
    pub fn build(n: usize, geo: &Geometry, pattern: Pattern) -> Result<Mesh, InputError> {
        check_n(n)?;
        if !pattern.is_grid() {
            return Err(InputError::field(
                "pattern",
                pattern.name(),
                "a grid pattern (a bisected mesh comes from bisection, a file's from Mesh::from_body)",
            ));
        }
        if n > MAX_N {
            return Err(InputError::field(
                "n",
                n,
                format!("at most {MAX_N} (memory)"),
            ));
        }
        check_grid(n, geo)?;
        let (nx, ny) = (n, rows(n, geo));
        let [side, dy] = spacing(n, geo);
        let id = |i: usize, j: usize| j * (nx + 1) + i;
        let mut nodes = Vec::with_capacity((nx + 1) * (ny + 1));
        let mut fixed = Vec::with_capacity(nodes.capacity());
        for j in 0..=ny {
            for i in 0..=nx {
                let p = [i as f64 * side, j as f64 * dy];
                fixed.push(if i == 0 || i == nx || j == 0 || j == ny {
                    geo.fixed_at(p)
                } else {
                    [false; 2]
                });
                nodes.push(p);
            }
        }
        let grid = nodes.len();
        let mut triangles = Vec::with_capacity(4 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (ll, lr, ur, ul) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                match pattern {
                    Pattern::Diagonal => {
                        triangles.push([ll, lr, ur]);
                        triangles.push([ll, ur, ul]);
                    }
                    Pattern::Antidiagonal => {
                        triangles.push([ll, lr, ul]);
                        triangles.push([lr, ur, ul]);
                    }
                    Pattern::CrissCross | Pattern::Bisected | Pattern::File => {
                        let c = grid + j * nx + i;
                        triangles.push([ll, lr, c]);
                        triangles.push([lr, ur, c]);
                        triangles.push([ur, ul, c]);
                        triangles.push([ul, ll, c]);
                    }
                }
            }
        }
        if pattern == Pattern::CrissCross {
            for j in 0..ny {
                for i in 0..nx {
                    nodes.push([(i as f64 + 0.5) * side, (j as f64 + 0.5) * dy]);
                    fixed.push([false; 2]);
                }
            }
        }
        let mut boundary = vec![];
        boundary.extend((0..ny).map(|j| ([id(0, j), id(0, j + 1)], Side::Left)));
        boundary.extend((0..ny).map(|j| ([id(nx, j), id(nx, j + 1)], Side::Right)));
        boundary.extend((0..nx).map(|i| ([id(i, 0), id(i + 1, 0)], Side::Bottom)));
        boundary.extend((0..nx).map(|i| ([id(i, ny), id(i + 1, ny)], Side::Top)));
        let mesh = Mesh::finish(n, ny, geo, pattern, nodes, triangles, fixed, boundary);
        if mesh.contact.is_empty() {
            let xs: Vec<String> = (mesh.gamma3.iter())
                .map(|&v| format!("{}", mesh.nodes[v][0]))
                .collect();
            return Err(InputError::field(
                "geometry.contact",
                format!("[{}, {}]", geo.contact[0], geo.contact[1]),
                format!(
                    "a Gamma_3 with a node whose normal component is free: at n = {n} its \
                     nodes (x = {}) are all held by supports, so there is no contact to \
                     solve; take a larger n, or let the supports leave part of Gamma_3 free",
                    xs.join(", ")
                ),
            ));
        }
        Ok(mesh)
    }

    /// A mesh from its parts, $\Gamma_3$ and the contact nodes found from the
    /// coordinates.
    #[allow(clippy::too_many_arguments)]
    pub fn finish(
        n: usize,
        ny: usize,
        geo: &Geometry,
        pattern: Pattern,
        nodes: Vec<[f64; 2]>,
        triangles: Vec<[usize; 3]>,
        fixed: Vec<[bool; 2]>,
        boundary: Vec<([usize; 2], Side)>,
    ) -> Mesh {
        let tol = geo.tol();
        let [x0, x1] = geo.contact;
        let mut gamma3: Vec<usize> = (0..nodes.len())
            .filter(|&v| {
                let p = nodes[v];
                geo.on(Side::Bottom, p) && p[0] >= x0 - tol && p[0] <= x1 + tol
            })
            .collect();
        gamma3.sort_by(|&a, &b| nodes[a][0].total_cmp(&nodes[b][0]));
        let contact: Vec<usize> = gamma3.iter().copied().filter(|&v| !fixed[v][1]).collect();
        // The support inside each boundary edge (at its midpoint) says its term.
        let boundary_terms = (boundary.iter())
            .filter_map(|&(e, side)| {
                let mid = 0.5 * (side.along(nodes[e[0]]) + side.along(nodes[e[1]]));
                let k = geo.hold_at(side, mid).stiffness();
                (k > 0.0).then_some((e, k))
            })
            .collect();
        Mesh {
            n,
            ny,
            gap: vec![0.0; contact.len()],
            normal: crate::frame::PAPER_NORMAL,
            shift: [0.0; 2],
            width: geo.width,
            height: geo.height,
            pattern,
            nodes,
            triangles,
            fixed,
            gamma3,
            contact,
            boundary,
            boundary_terms,
            dissection: Default::default(),
        }
    }

    /// The mesh of a mesh scene's body: the file's nodes and triangles, the components
    /// its supports hold, $\Gamma_3$ the contact part's nodes in order along it. It has
    /// no sides (`boundary` is empty: the body's tractions act on its named parts);
    /// `n` is the number of contact segments and `width`, `height` the bounding box's,
    /// so that $h = W/(2n)$ labels it as it does a grid of the same contact segments.
    pub fn from_body(body: &crate::body::Body) -> Mesh {
        let ([width, height], _) = body.bounds();
        let mut fixed = body.fixed();
        let gamma3 = body.gamma3.clone();
        if let Some(frame) = crate::frame::Frame::of_normal(body.foundation.normal) {
            // Held components of Gamma_3's nodes in the frame (checked by the body).
            for &v in &gamma3 {
                let mut slots = [false; 2];
                for c in (0..2).filter(|&c| fixed[v][c]) {
                    match (frame.slot_of_axis(c), fixed[v]) {
                        (Some(k), _) => slots[k] = true,
                        (None, [true, true]) => slots = [true, true],
                        (None, _) => unreachable!("refused by Body::new"),
                    }
                }
                fixed[v] = slots;
            }
        }
        let contact: Vec<usize> = gamma3.iter().copied().filter(|&v| !fixed[v][1]).collect();
        let mut boundary_terms = vec![];
        for s in &body.supports {
            let k = s.hold.stiffness();
            if k > 0.0 {
                let g = body.mesh.group(&s.part).expect("checked when built");
                boundary_terms.extend(g.edges.iter().map(|&e| (e, k)));
            }
        }
        let gap = (body.gamma3.iter().zip(body.gap()))
            .filter(|&(&v, _)| !fixed[v][1])
            .map(|(_, g)| g)
            .collect();
        Mesh {
            n: body.gamma3.len() - 1,
            gap,
            normal: body.foundation.normal,
            shift: body.shift(),
            ny: 0,
            width,
            height,
            pattern: Pattern::File,
            nodes: body.mesh.nodes.clone(),
            triangles: body.mesh.triangles.clone(),
            fixed,
            gamma3,
            contact,
            boundary: vec![],
            boundary_terms,
            dissection: Default::default(),
        }
    }

    /// Refuses a segment of `side` (a support's, a traction's or $\Gamma_3$, `field`)
    /// whose ends are not nodes of this mesh: the check on the mesh a run solves on,
    /// whatever built it.
    pub fn check_nodes_at(
        &self,
        field: &str,
        side: Side,
        ends: [f64; 2],
    ) -> Result<(), InputError> {
        let tol = 1e-9 * self.width.max(self.height);
        for (end, v) in [("from", ends[0]), ("to", ends[1])] {
            let hit = self
                .boundary
                .iter()
                .filter(|(_, s)| *s == side)
                .any(|(e, _)| {
                    e.iter()
                        .any(|&a| (side.along(self.nodes[a]) - v).abs() <= tol)
                });
            if !hit {
                let key = if field == "geometry.contact" {
                    field.to_string()
                } else {
                    end_key(field, side, end)
                };
                return Err(InputError::field(
                    key,
                    v,
                    format!(
                        "a node of the {} side of the mesh solved on ({} mesh of level n = {}), \
                         which has none there: the load or support would act on a shifted \
                         segment; choose n so that the end is a node, or a uniform mesh",
                        side.name(),
                        self.pattern.name(),
                        self.n
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The mesh size $h = W/(2n)$, half a cell's width: $1/n$ on the paper's scene.
    pub fn h(&self) -> f64 {
        self.width / (2 * self.n) as f64
    }

    /// The width of a cell of the structured mesh, $2h$.
    pub fn dx(&self) -> f64 {
        self.width / self.n as f64
    }

    /// The height of a cell of the structured mesh.
    pub fn dy(&self) -> f64 {
        let side = self.dx();
        if self.ny as f64 * side == self.height {
            side
        } else {
            self.height / self.ny as f64
        }
    }

    /// The edges of the top side, where the paper's $f_2$ acts, left to right.
    pub fn top_edges(&self) -> Vec<[usize; 2]> {
        self.boundary
            .iter()
            .filter(|(_, s)| *s == Side::Top)
            .map(|(e, _)| *e)
            .collect()
    }

    /// The body's displacement at each node from the computed dofs `u`: `u` expanded
    /// by `dofs` plus the rigid [`Mesh::shift`] of a prescribed displacement.
    pub fn displacement(&self, dofs: &Dofs, u: &[f64]) -> Vec<[f64; 2]> {
        let [dx, dy] = self.shift;
        (dofs.expand(u).into_iter())
            .map(|[x, y]| [x + dx, y + dy])
            .collect()
    }

    /// The arc length $s$ along $\Gamma_3$ of each contact node, from $\Gamma_3$'s first
    /// node (its left end on the rectangle, where $s$ is $x$ less that end's).
    pub fn contact_arc_length(&self) -> Vec<f64> {
        let mut s = 0.0;
        let mut at = Vec::with_capacity(self.gamma3.len());
        for (i, &v) in self.gamma3.iter().enumerate() {
            if i > 0 {
                let (p, q) = (self.nodes[self.gamma3[i - 1]], self.nodes[v]);
                s += (q[0] - p[0]).hypot(q[1] - p[1]);
            }
            at.push(s);
        }
        (self.gamma3.iter().zip(at))
            .filter(|&(&v, _)| !self.fixed[v][1])
            .map(|(_, s)| s)
            .collect()
    }

    /// Trapezoidal weights of the contact nodes: half the length of the $\Gamma_3$
    /// segments beside each node ($2h$ inside $\Gamma_3$, $h$ at its ends on a grid).
    /// A node of $\Gamma_3$ whose normal component a support holds is no contact node:
    /// its term of the contact functional is a constant.
    // ANCHOR: weights
    pub fn contact_weights(&self) -> Vec<f64> {
        let m = self.gamma3.len();
        let x: Vec<f64> = self.gamma3.iter().map(|&c| self.nodes[c][0]).collect();
        let h = self.h();
        (0..m)
            .filter(|&i| !self.fixed[self.gamma3[i]][1])
            .map(|i| {
                if self.pattern == Pattern::File {
                    // Half the lengths of the segments beside the node, along the part.
                    let len = |a: usize, b: usize| {
                        let (p, q) = (self.nodes[self.gamma3[a]], self.nodes[self.gamma3[b]]);
                        (q[0] - p[0]).hypot(q[1] - p[1])
                    };
                    0.5 * (if i > 0 { len(i - 1, i) } else { 0.0 }
                        + if i + 1 < m { len(i, i + 1) } else { 0.0 })
                } else if self.pattern == Pattern::Bisected {
                    0.5 * (x[(i + 1).min(m - 1)] - x[i.saturating_sub(1)])
                } else if i == 0 || i == m - 1 {
                    h
                } else {
                    2.0 * h
                }
            })
            .collect()
    }
    // ANCHOR_END: weights
}

/// Degrees of freedom: two per node, clamped nodes removed (or kept, for tests). A
/// node of $\Gamma_3$ under a foundation whose normal is not the paper's carries its
/// pair in the contact frame ([`crate::frame`]); `expand` and `gather` convert.
#[derive(Debug, Clone)]
pub struct Dofs {
    /// `map[2 * node + c]` is the dof of component `c` of `node`, if free.
    pub map: Vec<Option<usize>>,
    /// The number of dofs (the free ones, or all with `clamp = false`).
    pub count: usize,
    /// The contact frame and which nodes carry it; `None` when every pair is Cartesian.
    frame: Option<(crate::frame::Frame, Vec<bool>)>,
}

impl Dofs {
    /// Numbers the free dofs node by node; with `clamp = false` every dof is free.
    pub fn new(mesh: &Mesh, clamp: bool) -> Dofs {
        let mut map = Vec::with_capacity(2 * mesh.nodes.len());
        let mut count = 0;
        for v in 0..mesh.nodes.len() {
            for c in 0..2 {
                if clamp && mesh.fixed[v][c] {
                    map.push(None);
                } else {
                    map.push(Some(count));
                    count += 1;
                }
            }
        }
        let frame = crate::frame::Frame::of_normal(mesh.normal).map(|f| {
            let mut on = vec![false; mesh.nodes.len()];
            for &v in &mesh.gamma3 {
                on[v] = true;
            }
            (f, on)
        });
        Dofs { map, count, frame }
    }
    /// The dof of component `c` (0 = x, 1 = y) of `node`: of the frame's
    /// (tangent, normal into the body) at a node that carries the contact frame.
    pub fn of(&self, node: usize, c: usize) -> Option<usize> {
        self.map[2 * node + c]
    }
    /// The contact frame of `node`, if it carries one.
    pub fn frame_at(&self, node: usize) -> Option<crate::frame::Frame> {
        self.frame
            .as_ref()
            .and_then(|(f, on)| on[node].then_some(*f))
    }
    /// Whether some node carries the contact frame.
    pub fn has_frame(&self) -> bool {
        self.frame.is_some()
    }
    /// Expands a vector of free dofs to one Cartesian value pair per node (zero where
    /// clamped).
    pub fn expand(&self, u: &[f64]) -> Vec<[f64; 2]> {
        let mut out = Vec::new();
        self.expand_into(u, &mut out);
        out
    }
    /// [`Dofs::expand`] into `out`, whose storage is reused.
    pub fn expand_into(&self, u: &[f64], out: &mut Vec<[f64; 2]>) {
        out.clear();
        out.extend(
            (self.map.chunks(2)).map(|d| [d[0].map_or(0.0, |i| u[i]), d[1].map_or(0.0, |i| u[i])]),
        );
        if let Some((f, on)) = &self.frame {
            for (val, _) in out.iter_mut().zip(on).filter(|(_, on)| **on) {
                *val = f.to_cartesian(*val);
            }
        }
    }
    /// Adds the Cartesian nodal force `val` at `node` into `f` on its free dofs.
    pub fn add_nodal(&self, f: &mut [f64], node: usize, val: [f64; 2]) {
        let val = self.frame_at(node).map_or(val, |fr| fr.to_frame(val));
        for (c, x) in val.iter().enumerate() {
            if let Some(i) = self.of(node, c) {
                f[i] += x;
            }
        }
    }
}

impl Dofs {
    /// Gathers one Cartesian value pair per node into a vector of free dofs.
    pub fn gather(&self, nodal: &[[f64; 2]]) -> Vec<f64> {
        let mut u = vec![0.0; self.count];
        for (v, val) in nodal.iter().enumerate() {
            let val = self.frame_at(v).map_or(*val, |fr| fr.to_frame(*val));
            for (c, x) in val.iter().enumerate() {
                if let Some(d) = self.of(v, c) {
                    u[d] = *x;
                }
            }
        }
        u
    }
}

/// The P1 interpolation from a coarse mesh to the nodes of a finer one of any
/// pattern: for each fine node, the coarse triangle that holds it and its
/// barycentric weights. When the spaces are nested this is the exact embedding of
/// the coarse P1 space in the fine one; for fields sampled at many times it is
/// built once.
#[derive(Debug, Clone)]
pub struct Interpolation {
    /// Per fine node: three (coarse node, weight) pairs.
    pub weights: Vec<[(usize, f64); 3]>,
}

impl Interpolation {
    /// The interpolation from `coarse` to the nodes of `fine`, by search: each fine
    /// node takes, among the coarse triangles whose centroids lie in its cell of the
    /// coarse grid or a neighbouring one, the triangle whose smallest barycentric
    /// weight is largest (the one that holds it, up to rounding).
    pub fn new(coarse: &Mesh, fine: &Mesh) -> Interpolation {
        // Bucket the coarse triangles by the cell of their centroid.
        let (nx, ny) = (coarse.n, coarse.ny);
        let (side, dy) = (coarse.dx(), coarse.dy());
        let mut cells: Vec<Vec<usize>> = vec![vec![]; nx * ny];
        let cell = |x: f64, y: f64| {
            let i = ((x / side).floor() as isize).clamp(0, nx as isize - 1) as usize;
            let j = ((y / dy).floor() as isize).clamp(0, ny as isize - 1) as usize;
            (i, j)
        };
        for (t, tri) in coarse.triangles.iter().enumerate() {
            let c = tri.iter().fold([0.0; 2], |a, &v| {
                [
                    a[0] + coarse.nodes[v][0] / 3.0,
                    a[1] + coarse.nodes[v][1] / 3.0,
                ]
            });
            let (i, j) = cell(c[0], c[1]);
            cells[j * nx + i].push(t);
        }
        let weights = fine
            .nodes
            .iter()
            .map(|&p| {
                let (i, j) = cell(p[0], p[1]);
                // A point on a cell edge may lie in the neighbour's triangles only
                // up to rounding: take the triangle whose smallest weight is largest.
                let mut best = ([(0, 0.0); 3], f64::NEG_INFINITY);
                const AROUND: [(isize, isize); 9] = [
                    (0, 0),
                    (-1, 0),
                    (1, 0),
                    (0, -1),
                    (0, 1),
                    (-1, -1),
                    (1, -1),
                    (-1, 1),
                    (1, 1),
                ];
                for (di, dj) in AROUND {
                    if best.1 >= -1e-12 {
                        break;
                    }
                    let (ci, cj) = (i as isize + di, j as isize + dj);
                    if ci < 0 || cj < 0 || ci >= nx as isize || cj >= ny as isize {
                        continue;
                    }
                    for &t in &cells[cj as usize * nx + ci as usize] {
                        let tri = coarse.triangles[t];
                        let q = tri.map(|v| coarse.nodes[v]);
                        let det = crate::element::twice_area(q);
                        let l1 = crate::element::twice_area([q[0], p, q[2]]) / det;
                        let l2 = crate::element::twice_area([q[0], q[1], p]) / det;
                        let l0 = 1.0 - l1 - l2;
                        let worst = l0.min(l1).min(l2);
                        if worst > best.1 {
                            best = ([(tri[0], l0), (tri[1], l1), (tri[2], l2)], worst);
                        }
                    }
                }
                best.0
            })
            .collect();
        Interpolation { weights }
    }

    /// The interpolation from a structured mesh of the paper's pattern to a
    /// uniform refinement of it (`fine.n` a multiple of `coarse.n`), in closed
    /// form: fine node $(i_f, j_f)$ lies at $(a, b)$ in the cell of coarse node
    /// $(i_c, j_c)$, in its lower-right triangle when $a \ge b$. The meshes are
    /// nested (each fine triangle lies in one coarse triangle), so this is the
    /// exact embedding of the coarse P1 space in the fine one.
    pub fn nested(coarse: &Mesh, fine: &Mesh) -> Result<Interpolation, InputError> {
        if coarse.pattern != Pattern::Diagonal || fine.pattern != Pattern::Diagonal {
            return Err(InputError::field(
                "pattern",
                format!("{} to {}", coarse.pattern.name(), fine.pattern.name()),
                "the paper's diagonal pattern on both meshes (else Interpolation::new)",
            ));
        }
        if !fine.n.is_multiple_of(coarse.n) {
            return Err(InputError::field(
                "n",
                format!("{} to {}", coarse.n, fine.n),
                "a fine n that is a multiple of the coarse n",
            ));
        }
        // The rows, n H / W rounded and at least 1, must grow as n does.
        if fine.ny * coarse.n != coarse.ny * fine.n {
            return Err(InputError::field(
                "n",
                format!(
                    "{} to {}, whose meshes have {} to {} row(s) of cells",
                    coarse.n, fine.n, coarse.ny, fine.ny
                ),
                format!(
                    "nested meshes, whose rows grow as n does ({} times): on this rectangle \
                     the rows, n H / W rounded and at least 1, do not",
                    fine.n / coarse.n
                ),
            ));
        }
        let r = fine.n / coarse.n;
        let (nxc, nxf) = (coarse.n, fine.n);
        let idc = |i: usize, j: usize| j * (nxc + 1) + i;
        // Coarse cell and position in it along one axis, the last cell closed.
        let locate = |f: usize, cells: usize| {
            let c = (f / r).min(cells - 1);
            (c, (f - c * r) as f64 / r as f64)
        };
        let mut weights = Vec::with_capacity(fine.nodes.len());
        for jf in 0..=fine.ny {
            for if_ in 0..=nxf {
                let ((ic, a), (jc, b)) = (locate(if_, nxc), locate(jf, coarse.ny));
                let (ll, lr, ur, ul) = (
                    idc(ic, jc),
                    idc(ic + 1, jc),
                    idc(ic + 1, jc + 1),
                    idc(ic, jc + 1),
                );
                weights.push(if a >= b {
                    [(ll, 1.0 - a), (lr, a - b), (ur, b)]
                } else {
                    [(ll, 1.0 - b), (ur, a), (ul, b - a)]
                });
            }
        }
        Ok(Interpolation { weights })
    }

    /// $P^\top v$: the transpose applied to one value pair per fine node, one
    /// pair per coarse node out (`coarse_nodes` of them).
    pub fn apply_transpose(&self, vals: &[[f64; 2]], coarse_nodes: usize) -> Vec<[f64; 2]> {
        let mut out = vec![[0.0; 2]; coarse_nodes];
        for (w, v) in self.weights.iter().zip(vals) {
            for &(node, wt) in w {
                out[node][0] += wt * v[0];
                out[node][1] += wt * v[1];
            }
        }
        out
    }

    /// The interpolated field at the fine nodes.
    pub fn apply(&self, vals: &[[f64; 2]]) -> Vec<[f64; 2]> {
        self.weights
            .iter()
            .map(|w| {
                let mut v = [0.0; 2];
                for &(node, wt) in w {
                    v[0] += wt * vals[node][0];
                    v[1] += wt * vals[node][1];
                }
                v
            })
            .collect()
    }
}

/// A scenario's structured meshes and the checks that its supports, tractions and
/// $\Gamma_3$ end on nodes.
impl crate::scenario::Scenario {
    /// A mesh scene's mesh (`None` on the rectangle, whose meshes have a level $n$).
    pub fn body_mesh(&self) -> Option<Mesh> {
        self.body().map(Mesh::from_body)
    }

    /// The mesh with $n$ segments on the bottom and this scenario's geometry and
    /// pattern; every traction's ends must be nodes too.
    pub fn mesh(&self, n: usize) -> Result<Mesh, InputError> {
        self.refuse_mesh_scene("a mesh of level n")?;
        let mesh = Mesh::build(n, &self.geometry, self.pattern)?;
        self.check_traction_ends(n)?;
        Ok(mesh)
    }

    /// Refuses a level `n` whose structured grid would not resolve this scene (its
    /// supports', tractions' and $\Gamma_3$'s ends on grid lines, cells near squares),
    /// without building the mesh.
    pub fn check_grid(&self, n: usize) -> Result<(), InputError> {
        self.refuse_mesh_scene("a mesh of level n")?;
        crate::mesh::check_grid(n, &self.geometry)?;
        self.check_traction_ends(n)
    }

    /// Refuses a traction whose ends are not nodes of the structured mesh of level `n`.
    pub(crate) fn check_traction_ends(&self, n: usize) -> Result<(), InputError> {
        let [dx, dy] = crate::mesh::spacing(n, &self.geometry);
        for t in &self.tractions {
            let d = if t.side.normal() == 0 { dy } else { dx };
            crate::mesh::check_ends(&t.field, t.side, [t.from, t.to], d, n)?;
        }
        Ok(())
    }

    /// Refuses `mesh` for this scene, by the key of the first end of a support, a
    /// traction or $\Gamma_3$ that is not one of its boundary nodes (where that load
    /// or support would act on a shifted segment).
    pub fn check_ends_on(&self, mesh: &Mesh) -> Result<(), InputError> {
        if let Some(body) = &self.body {
            if mesh.nodes != body.mesh.nodes || mesh.triangles != body.mesh.triangles {
                return Err(InputError::field(
                    "mesh",
                    format!("a mesh of {} nodes", mesh.nodes.len()),
                    format!(
                        "the mesh of the scene's file {} ({} nodes): a mesh scene solves on \
                         its own mesh",
                        body.file,
                        body.mesh.nodes.len()
                    ),
                ));
            }
            return Ok(());
        }
        let geo = &self.geometry;
        let supports = geo
            .supports
            .iter()
            .map(|s| (s.field.as_str(), s.side, [s.from, s.to]));
        let tractions = self
            .tractions
            .iter()
            .map(|t| (t.field.as_str(), t.side, [t.from, t.to]));
        let contact = std::iter::once(("geometry.contact", Side::Bottom, geo.contact));
        for (field, side, ends) in supports.chain(tractions).chain(contact) {
            mesh.check_nodes_at(field, side, ends)?;
        }
        Ok(())
    }
}
