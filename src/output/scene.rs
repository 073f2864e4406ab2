//! The picture of a solved scene: the deformed body at true scale with its mesh, and
//! the interface forces on $\Gamma_3$ with each node coloured by its regime, drawn from
//! the tables a run writes (`contact.csv`, `nodes.csv`, and `triangles.csv` for a
//! mesh that is no lattice). `evhi solve` and `evhi plot` draw a run's `deformed`
//! figure with it, and Figs. 3 and 4 of the paper's experiments their panels.

use super::FileError;
use super::csv::{Text, col_f64, col_str, read_csv};
use super::rows::{TriangleRow, column};
use crate::certificate::regime_order;
use crate::output::plot::FONT;
use crate::output::plot::{Figure, both, e2s, fit_title, legend, regime_colour, regime_label};
use crate::output::plot::{GREY, GREY_DARK, okabe_ito as oi};
use crate::scenario::Scenario;
use plotters::prelude::*;

/// The deformed body and interface forces of one run directory (`contact.csv` and
/// `nodes.csv` as `evhi solve` writes them) into `dir/deformed.{png,svg}`.
pub fn draw_run(
    dir: &std::path::Path,
    g: f64,
    cells: usize,
    title: String,
    written: Option<Written>,
) -> Result<(), FileError> {
    let tri = dir.join("triangles.csv");
    let every_node = tri.exists();
    let held = written.filter(|w| every_node && w.nodes.len() == w.disp.len());
    let contact = dir.join("contact.csv");
    let mut panel = match held {
        Some(w) => {
            let col = |v: &[[f64; 2]], c: usize| v.iter().map(|p| p[c]).collect();
            let nodes = [
                col(w.nodes, 0),
                col(w.nodes, 1),
                col(w.disp, 0),
                col(w.disp, 1),
            ];
            Panel::with_nodes(&contact, g, cells, nodes)?
        }
        None => Panel::from_csv(&contact, &dir.join("nodes.csv"), g, cells)?,
    };
    if let (true, Some(w)) = (every_node, written) {
        // The triangles this process wrote to triangles.csv.
        let nodes = panel.x.len();
        if let Some(bad) = w.triangles.iter().find(|t| t.iter().any(|&k| k >= nodes)) {
            return Err(FileError::Table {
                path: tri.display().to_string(),
                message: format!(
                    "the triangle {bad:?} names a node beyond the {nodes} of nodes.csv"
                ),
            });
        }
        panel.set_triangles(w.triangles.to_vec());
        panel.body = body_view(dir, &panel, Some(w.scene))?;
    } else if every_node {
        // Read as numbers, so that a row of NaN, -5 or 1.5 is refused as a triangle.
        let text = Text::read(&tri)?;
        let corners = (TriangleRow::COLUMNS.iter())
            .map(|c| column::<f64>(&text, c, &[]))
            .collect::<Result<Vec<_>, _>>()?;
        let nodes = panel.x.len();
        let mut list = Vec::with_capacity(text.rows.len());
        for (i, (line, _)) in text.rows.iter().enumerate() {
            let raw = [corners[0][i], corners[1][i], corners[2][i]];
            if !raw
                .iter()
                .all(|&k| k >= 0.0 && k.fract() == 0.0 && k < nodes as f64)
            {
                return Err(FileError::Table {
                    path: format!("{}:{line}", tri.display()),
                    message: format!(
                        "the row holds {raw:?}, not three node numbers in 0..{nodes} (the \
                         nodes of nodes.csv)"
                    ),
                });
            }
            list.push(raw.map(|x| x as usize));
        }
        panel.set_triangles(list);
        panel.body = body_view(dir, &panel, None)?;
    } else {
        panel.check_lattice(&dir.join("nodes.csv"))?;
    }
    panel.contact = run_contact(dir, &panel);
    let panels = vec![panel];
    both(
        dir,
        "deformed",
        (1000, 980),
        &SceneFigure {
            panels,
            title,
            paper_law: false,
            columns: 1,
        },
    )
}

/// What a mesh scene's panel draws beyond a lattice's: the foundation line (from the
/// run's `scenario.toml`), each contact node's arc length and deformed position
/// (matched to `nodes.csv` by its coordinates); `None` for a run that is no mesh scene
/// (or whose scenario does not read).
fn body_view(
    dir: &std::path::Path,
    panel: &Panel,
    scene: Option<&Scenario>,
) -> Result<Option<BodyView>, FileError> {
    let of = |scn: &Scenario| {
        scn.body()
            .map(|b| (b.foundation.point, b.foundation.normal))
    };
    // The run's own scene when the caller holds it (`evhi solve`), so that its mesh
    // is not read and built a second time; else the run's scenario.toml.
    let foundation = match scene {
        Some(scn) => of(scn),
        None => Scenario::load(&dir.join("scenario.toml").display().to_string())
            .ok()
            .and_then(|scn| of(&scn)),
    };
    let Some(foundation) = foundation else {
        // A graded rectangle, or a run without its scenario: drawn as the rectangle.
        return Ok(None);
    };
    let contact = dir.join("contact.csv");
    let c = read_csv(&contact)?;
    let arc = col_f64(&c, "s")?;
    let cy = col_f64(&c, "y")?;
    let key = |x: f64, y: f64| (x.to_bits(), y.to_bits());
    let at: std::collections::HashMap<(u64, u64), usize> = (0..panel.x.len())
        .map(|v| (key(panel.x[v], panel.y[v]), v))
        .collect();
    let mut moved = Vec::with_capacity(panel.cx.len());
    for (i, (&x, &y)) in panel.cx.iter().zip(&cy).enumerate() {
        let Some(&v) = at.get(&key(x, y)) else {
            return Err(FileError::Table {
                path: format!("{}:{}", contact.display(), i + 2),
                message: format!(
                    "the contact node at ({x}, {y}) is no node of nodes.csv; the tables were \
                     not written by one run"
                ),
            });
        };
        moved.push((x + panel.ux[v], y + panel.uy[v]));
    }
    Ok(Some(BodyView {
        foundation,
        arc,
        moved,
    }))
}

/// A mesh scene's extra panel data, read by `body_view`.
pub struct BodyView {
    /// The foundation's point and outward normal $n_f$.
    foundation: ([f64; 2], [f64; 2]),
    /// Each contact node's arc length along $\Gamma_3$.
    arc: Vec<f64>,
    /// Each contact node's deformed position.
    moved: Vec<(f64, f64)>,
}

/// $\Gamma_3$ of a run directory where it is a part of the bottom: from the run's
/// `scenario.toml`, or where that does not read, the span of its contact nodes.
fn run_contact(dir: &std::path::Path, panel: &Panel) -> Option<[f64; 2]> {
    let from_file = std::fs::read_to_string(dir.join("scenario.toml"))
        .ok()
        .and_then(|text| Scenario::from_toml(&text, "scenario.toml").ok())
        .map(|scn| scn.geometry.contact);
    let span = || {
        let lo = panel.cx.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = panel.cx.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        (lo < hi).then_some([lo, hi])
    };
    let contact = from_file.or_else(span)?;
    let whole = contact[0] <= 0.0 && contact[1] >= panel.width();
    (!whole).then_some(contact)
}

/// The entries of `v` whose row's `g` (in `gg`) is `g`.
fn pick_g(v: Vec<f64>, gg: &[f64], g: f64) -> Vec<f64> {
    v.into_iter()
        .zip(gg)
        .filter(|(_, x)| **x == g)
        .map(|(a, _)| a)
        .collect()
}

/// One panel's data, read back from the CSVs.
pub struct Panel {
    g: f64,
    /// lattice cells per side in x
    cells: usize,
    x: Vec<f64>,
    y: Vec<f64>,
    ux: Vec<f64>,
    uy: Vec<f64>,
    cx: Vec<f64>,
    s1: Vec<f64>,
    s2: Vec<f64>,
    regime: Vec<String>,
    u_nu: Vec<f64>,
    /// A mesh that is no lattice (graded): its triangles, node indices into `x`.
    triangles: Option<Vec<[usize; 3]>>,
    /// Their edges as [`mesh_edges`] gives them: found once, drawn by each figure.
    edges: Option<(Vec<[usize; 2]>, bool)>,
    /// $\Gamma_3$ as `[from, to]` on the bottom where it is not the whole bottom: the
    /// layer and foundation are drawn under it only.
    contact: Option<[f64; 2]>,
    /// A mesh scene's foundation, arc lengths and deformed contact nodes.
    body: Option<BodyView>,
}

impl Panel {
    /// The panel of limit `g` from a contact and a nodes table (rows of every `g`
    /// when they have a `g` column), drawn as a lattice of `cells` cells across.
    pub fn from_csv(
        cp: &std::path::Path,
        np: &std::path::Path,
        g: f64,
        cells: usize,
    ) -> Result<Panel, FileError> {
        let nd = read_csv(np)?;
        // A run directory's tables have no `g` column: every row is this panel's.
        let ng = col_f64(&nd, "g").unwrap_or_else(|_| vec![g; nd.height()]);
        let pick =
            |c: &str| -> Result<Vec<f64>, FileError> { Ok(pick_g(col_f64(&nd, c)?, &ng, g)) };
        let nodes = [pick("x")?, pick("y")?, pick("ux")?, pick("uy")?];
        Panel::with_nodes(cp, g, cells, nodes)
    }

    /// [`Panel::from_csv`] with the nodes' columns `[x, y, ux, uy]` at hand.
    fn with_nodes(
        cp: &std::path::Path,
        g: f64,
        cells: usize,
        [x, y, ux, uy]: [Vec<f64>; 4],
    ) -> Result<Panel, FileError> {
        let c = read_csv(cp)?;
        let cg = col_f64(&c, "g").unwrap_or_else(|_| vec![g; c.height()]);
        let regime = col_str(&c, "regime")?
            .into_iter()
            .zip(&cg)
            .filter(|(_, x)| **x == g)
            .map(|(a, _)| a)
            .collect();
        Ok(Panel {
            g,
            cells,
            x,
            y,
            ux,
            uy,
            cx: pick_g(col_f64(&c, "x")?, &cg, g),
            s1: pick_g(col_f64(&c, "sigma_nu1")?, &cg, g),
            s2: pick_g(col_f64(&c, "sigma_nu2")?, &cg, g),
            u_nu: pick_g(col_f64(&c, "u_nu")?, &cg, g),
            regime,
            triangles: None,
            edges: None,
            contact: None,
            body: None,
        })
    }

    /// Draws the mesh as these triangles, not as a lattice.
    fn set_triangles(&mut self, list: Vec<[usize; 3]>) {
        self.edges = Some(mesh_edges(&list));
        self.triangles = Some(list);
    }
}

impl Panel {
    /// Refuses nodes that are not the lattice of `cells + 1` columns the figure draws
    /// (at least two rows, each column at one x, each row at one y): a nodes table cut
    /// short, or a summary whose n does not match it, would be misdrawn or index past
    /// the end.
    fn check_lattice(&self, path: &std::path::Path) -> Result<(), FileError> {
        let (cols, nodes) = (self.cells + 1, self.x.len());
        let rows = nodes / cols;
        let lattice = nodes.is_multiple_of(cols)
            && rows >= 2
            && (0..nodes).all(|v| {
                let (i, j) = (v % cols, v / cols);
                self.x[v] == self.x[i] && self.y[v] == self.y[j * cols]
            })
            && (1..cols).all(|i| self.x[i] > self.x[i - 1])
            && (1..rows).all(|j| self.y[j * cols] > self.y[(j - 1) * cols]);
        if lattice {
            Ok(())
        } else {
            Err(FileError::Table {
                path: path.display().to_string(),
                message: format!(
                    "its {nodes} node(s) are not a lattice of rows of {cols} (the n of \
                     summary.csv, drawn every few cells); the table was not written by \
                     this run"
                ),
            })
        }
    }

    /// The top of the force axis: a tenth above the largest total force (at least 1).
    fn force_top(&self) -> f64 {
        let total = self.s1.iter().zip(&self.s2).map(|(a, b)| -(a + b));
        total.fold(1.0f64, f64::max) * 1.1
    }

    /// The rectangle's width and height: the lattice's extent (from its lower-left
    /// corner, [`Self::origin`]).
    fn width(&self) -> f64 {
        self.x.iter().copied().fold(f64::NEG_INFINITY, f64::max) - self.origin()[0]
    }
    fn height(&self) -> f64 {
        self.y.iter().copied().fold(f64::NEG_INFINITY, f64::max) - self.origin()[1]
    }
    /// The lower-left corner of the undeformed nodes' box: the origin on a lattice, the
    /// box's corner on a mesh scene below or left of it.
    fn origin(&self) -> [f64; 2] {
        [
            self.x.iter().copied().fold(f64::INFINITY, f64::min),
            self.y.iter().copied().fold(f64::INFINITY, f64::min),
        ]
    }
    /// Whether the foundation is not the paper's line under the body.
    fn slanted(&self) -> bool {
        self.body
            .as_ref()
            .is_some_and(|b| b.foundation.1 != crate::frame::PAPER_NORMAL)
    }
    /// Where the force panel places each contact node: its arc length on a mesh scene,
    /// its x on the rectangle.
    fn along(&self) -> &[f64] {
        self.body.as_ref().map_or(&self.cx, |b| &b.arc)
    }
    /// The x span the mesh panel shows, and the y span it must show.
    fn x_span(&self) -> f64 {
        self.width() + 0.1
    }
    fn y_span(&self) -> f64 {
        self.height() + 0.18
    }
}

/// A figure of one or more solved scenes: each [`Panel`] the deformed body with its
/// mesh and the interface forces on $\Gamma_3$, under one title.
pub struct SceneFigure {
    /// The panels, row by row.
    pub panels: Vec<Panel>,
    /// The figure's title, above all panels.
    pub title: String,
    /// Label the branches with the paper's law (5.1); otherwise "branch b".
    pub paper_law: bool,
    /// Panels side by side in a row (1: one under the other, each with its own force
    /// axis and legend; more: a grid whose force axes share one range, under one
    /// legend for all).
    pub columns: usize,
}

impl Figure for SceneFigure {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let root = fit_title(root, &self.title, 24)?;
        let columns = self.columns.max(1);
        let grid = columns > 1;
        let (root, key) = if grid {
            let (key, rest) = root.split_vertically(KEY_HEIGHT);
            (rest, Some(key))
        } else {
            (root, None)
        };
        // One force range for every panel of a grid, so that their bars compare.
        let shared = grid.then(|| self.panels.iter().map(Panel::force_top).fold(1.0, f64::max));
        let rows = root.split_evenly((self.panels.len().div_ceil(columns), columns));
        for (p, area) in self.panels.iter().zip(rows.iter()) {
            // The mesh panel tall enough to show x in [-0.05, W + 0.05] and y in
            // [-0.16, H + 0.02] at true aspect (plus its caption and labels); the
            // forces get the rest.
            let (w, h) = area.dim_in_pixel();
            let plot_w = w.saturating_sub(MESH_FRAME.0) as f64;
            let need = (plot_w * p.y_span() / p.x_span()) as u32 + MESH_FRAME.1;
            let (top, bottom) = area.split_vertically(need.min(h * 3 / 4));
            draw_mesh(p, &top, grid)?;
            draw_forces(p, &bottom, self.paper_law, shared)?;
        }
        if let Some(key) = key {
            let mut regimes: Vec<String> = self
                .panels
                .iter()
                .flat_map(|p| p.regime.iter().cloned())
                .collect();
            regimes.sort();
            regimes.dedup();
            let mut entries: Vec<(String, RGBColor)> = regime_order(&regimes)
                .into_iter()
                .map(|r| {
                    let label = format!("-σν¹: {}", regime_label(&r));
                    (label, regime_colour(&r))
                })
                .collect();
            entries.push(("-σν²: unilateral part".into(), UNILATERAL));
            key_row(&key, &entries, 17)?;
        }
        Ok(())
    }
}

/// The height of a grid's legend rows under its title, pixels (three rows: a
/// 1000 px grid holds two entries a row).
const KEY_HEIGHT: u32 = 92;

/// The colour of the unilateral part of the force.
const UNILATERAL: RGBColor = oi::REDDISH_PURPLE;

/// Legend entries (a filled square and its label) left to right in rows across
/// `area`, a new row where the next would not fit.
fn key_row<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    entries: &[(String, RGBColor)],
    font: u32,
) -> Result<(), String> {
    let (width, _) = area.dim_in_pixel();
    let style = TextStyle::from((FONT, font).into_font());
    let (mut x, mut y) = (20i32, 6i32);
    for (label, colour) in entries {
        let w = area.estimate_text_size(label, &style).map_err(e2s)?.0 as i32 + 52;
        if x + w > width as i32 && x > 20 {
            (x, y) = (20, y + 28);
        }
        area.draw(&Rectangle::new([(x, y), (x + 16, y + 16)], colour.filled()))
            .map_err(e2s)?;
        area.draw(&plotters::element::Text::new(
            label.clone(),
            (x + 24, y),
            style.clone(),
        ))
        .map_err(e2s)?;
        x += w;
    }
    Ok(())
}

/// The mesh panel's x span, the y span it must show, and its frame (pixels
/// outside the plotting area: y labels and margins across; caption, x labels
/// and margins down).
const MESH_FRAME: (u32, u32) = (66, 92);

fn draw_mesh<DB: DrawingBackend>(
    p: &Panel,
    area: &DrawingArea<DB, plotters::coord::Shift>,
    compact: bool,
) -> Result<(), String> {
    let limit = if p.g.is_finite() {
        format!("g = {}", p.g)
    } else {
        "no limit".to_string()
    };
    let edges = &p.edges;
    // A grid's panel is half the width: its caption names the limit only (the counts
    // per regime are the table beside the grid).
    let caption = if compact {
        limit
    } else {
        format!(
            "{limit}: {}contact nodes: {}",
            match edges {
                Some((_, true)) => format!(
                    "deformed body (true scale; its {} triangles drawn by the outline); ",
                    p.triangles.as_ref().map_or(0, Vec::len)
                ),
                _ => "deformed mesh (true scale); ".to_string(),
            },
            regime_order(&p.regime)
                .iter()
                .map(|r| format!("{r} {}", p.regime.iter().filter(|x| *x == r).count()))
                .collect::<Vec<_>>()
                .join(", ")
        )
    };
    let o = p.origin();
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, if compact { 17 } else { 18 }))
        .margin(8)
        .x_label_area_size(48)
        .y_label_area_size(50)
        // True aspect: as many metres per pixel down as across.
        .build_cartesian_2d(
            o[0] - 0.05..o[0] + p.width() + 0.05,
            o[1] - 0.16..o[1] - 0.16 + aspect_span(p, area),
        )
        .map_err(e2s)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc("x [m]")
        .y_desc("y [m]")
        .label_style((FONT, 16))
        .draw()
        .map_err(e2s)?;
    // Foundation: layer top (y = 0, undeformed obstacle) and rigid base (y = -g;
    // none without a limit, the layer then fills the panel's foot), under Gamma_3 only.
    let [left, right] = p.contact.unwrap_or([o[0] - 0.05, o[0] + p.width() + 0.05]);
    let base = p.g.min(0.16);
    if p.slanted() {
        let (x0, x1) = (o[0] - 0.05, o[0] + p.width() + 0.05);
        let (y0, y1) = (o[1] - 0.16, o[1] - 0.16 + aspect_span(p, area));
        draw_slanted_foundation(&mut chart, p, [x0, x1, y0, y1])?;
    } else if p.g.is_finite() {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(left, -0.16), (right, -p.g)],
                GREY.mix(0.5).filled(),
            )))
            .map_err(e2s)?;
    }
    if !p.slanted() {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [
                    (left, if p.g.is_finite() { -p.g } else { -base }),
                    (right, 0.0),
                ],
                oi::YELLOW.mix(0.4).filled(),
            )))
            .map_err(e2s)?;
    }
    let nx = p.cells;
    let ny = (p.x.len() / (nx + 1)).saturating_sub(1);
    let at = |i: usize, j: usize| {
        let v = j * (nx + 1) + i;
        (p.x[v] + p.ux[v], p.y[v] + p.uy[v])
    };
    let style = GREY_DARK.stroke_width(1);
    let mut segs = vec![];
    let moved = |v: usize| (p.x[v] + p.ux[v], p.y[v] + p.uy[v]);
    if let Some((edges, _)) = edges {
        segs.extend(edges.iter().map(|&[a, b]| [moved(a), moved(b)]));
    }
    for j in (0..=ny).filter(|_| p.triangles.is_none()) {
        for i in 0..=nx {
            if i < nx {
                segs.push([at(i, j), at(i + 1, j)]);
            }
            if j < ny {
                segs.push([at(i, j), at(i, j + 1)]);
            }
            if i < nx && j < ny {
                segs.push([at(i, j), at(i + 1, j + 1)]);
            }
        }
    }
    chart
        .draw_series(
            segs.into_iter()
                .map(|s| PathElement::new(s.to_vec(), style)),
        )
        .map_err(e2s)?;
    let dots: Vec<(f64, f64)> = match &p.body {
        Some(b) => b.moved.clone(),
        None => p.cx.iter().zip(&p.u_nu).map(|(&x, &u)| (x, -u)).collect(),
    };
    chart
        .draw_series(
            dots.into_iter()
                .zip(&p.regime)
                .map(|(at, r)| Circle::new(at, 3, regime_colour(r).filled())),
        )
        .map_err(e2s)?;
    Ok(())
}

/// The most edges a mesh panel draws; a finer mesh is drawn by its outline only (an
/// SVG of every edge of a 260 000-triangle mesh is some 75 MB, and no edge of it is
/// wider than a pixel apart at this size).
const MAX_DRAWN_EDGES: usize = 60_000;

/// The edges of `tris`, each once: all of them up to [`MAX_DRAWN_EDGES`], the boundary
/// (edges of one triangle) beyond.
fn mesh_edges(tris: &[[usize; 3]]) -> (Vec<[usize; 2]>, bool) {
    // Each triangle's edges by their lower end (a counting sort), each end's list
    // sorted: an interior edge then appears twice in a row, a boundary edge once.
    // Some five times faster than one sort of all pairs (paper_n512: 786 k pairs),
    // which was ten times faster than a hash map.
    let n = tris.iter().flatten().max().map_or(0, |&v| v + 1);
    let mut start = vec![0usize; n + 1];
    for t in tris {
        for e in 0..3 {
            start[t[e].min(t[(e + 1) % 3]) + 1] += 1;
        }
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut high = vec![0usize; start[n]];
    for t in tris {
        for e in 0..3 {
            let (a, b) = (t[e], t[(e + 1) % 3]);
            let lo = a.min(b);
            high[fill[lo]] = a.max(b);
            fill[lo] += 1;
        }
    }
    let mut edges: Vec<[usize; 2]> = Vec::with_capacity(high.len() / 2 + 1);
    let mut once: Vec<[usize; 2]> = Vec::new();
    for lo in 0..n {
        let list = &mut high[start[lo]..start[lo + 1]];
        list.sort_unstable();
        let mut i = 0;
        while i < list.len() {
            let mut j = i + 1;
            while j < list.len() && list[j] == list[i] {
                j += 1;
            }
            edges.push([lo, list[i]]);
            if j - i == 1 {
                once.push([lo, list[i]]);
            }
            i = j;
        }
    }
    let outline = edges.len() > MAX_DRAWN_EDGES;
    (if outline { once } else { edges }, outline)
}

/// A slanted foundation: its layer between the line through the foundation's point
/// and the limit's line $g$ beyond it along $n_f$, and the rigid base beyond that,
/// each cut to the plotting box `[x0, x1, y0, y1]`.
fn draw_slanted_foundation<DB: DrawingBackend>(
    chart: &mut ChartContext<
        '_,
        DB,
        Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
    >,
    p: &Panel,
    [x0, x1, y0, y1]: [f64; 4],
) -> Result<(), String> {
    let Some(body) = &p.body else { return Ok(()) };
    let (pt, n) = body.foundation;
    let tau = [-n[1], n[0]];
    let far = 10.0 * ((x1 - x0).hypot(y1 - y0));
    let band = |from: f64, to: f64| -> Vec<(f64, f64)> {
        let at = |d: f64, t: f64| (pt[0] + d * n[0] + t * tau[0], pt[1] + d * n[1] + t * tau[1]);
        clip_box(
            &[at(from, -far), at(from, far), at(to, far), at(to, -far)],
            [x0, x1, y0, y1],
        )
    };
    let depth = if p.g.is_finite() { p.g } else { 0.16 };
    let layer = band(0.0, depth);
    if p.g.is_finite() {
        let rigid = band(p.g, far);
        if rigid.len() >= 3 {
            chart
                .draw_series(std::iter::once(Polygon::new(rigid, GREY.mix(0.5).filled())))
                .map_err(e2s)?;
        }
    }
    if layer.len() >= 3 {
        chart
            .draw_series(std::iter::once(Polygon::new(
                layer,
                oi::YELLOW.mix(0.4).filled(),
            )))
            .map_err(e2s)?;
    }
    Ok(())
}

/// The convex polygon `poly` cut to the box `[x0, x1, y0, y1]` (Sutherland–Hodgman).
fn clip_box(poly: &[(f64, f64)], [x0, x1, y0, y1]: [f64; 4]) -> Vec<(f64, f64)> {
    let mut out = poly.to_vec();
    // Each edge of the box as "inside when f(p) >= 0".
    let sides: [&dyn Fn((f64, f64)) -> f64; 4] =
        [&|q| q.0 - x0, &|q| x1 - q.0, &|q| q.1 - y0, &|q| y1 - q.1];
    for f in sides {
        let input = std::mem::take(&mut out);
        for (i, &a) in input.iter().enumerate() {
            let b = input[(i + 1) % input.len()];
            let (fa, fb) = (f(a), f(b));
            if fa >= 0.0 {
                out.push(a);
            }
            if (fa >= 0.0) != (fb >= 0.0) {
                let t = fa / (fa - fb);
                out.push((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            }
        }
    }
    out
}

/// The y span that the area's plotting region shows at true aspect.
fn aspect_span<DB: DrawingBackend>(
    p: &Panel,
    area: &DrawingArea<DB, plotters::coord::Shift>,
) -> f64 {
    let (w, h) = area.dim_in_pixel();
    let plot_w = w.saturating_sub(MESH_FRAME.0).max(1) as f64;
    let plot_h = h.saturating_sub(MESH_FRAME.1).max(1) as f64;
    (p.x_span() * plot_h / plot_w).max(p.y_span())
}

/// The force panel of `p`, its axis up to `shared` (a grid's common top) or its own
/// top; its own legend only without a shared top (a grid has one for all).
fn draw_forces<DB: DrawingBackend>(
    p: &Panel,
    area: &DrawingArea<DB, plotters::coord::Shift>,
    paper_law: bool,
    shared: Option<f64>,
) -> Result<(), String> {
    let ymax = shared.unwrap_or_else(|| p.force_top());
    let caption = if shared.is_some() {
        "interface force -σν = -σν¹ - σν² on Γ3"
    } else {
        "interface force -σν on Γ3: compliance part -σν¹ (regime colour), unilateral part -σν² (reddish purple)"
    };
    let along = p.along();
    let (lo, hi) = match &p.body {
        Some(_) => (
            along.iter().copied().fold(f64::INFINITY, f64::min),
            along.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        ),
        None => (p.origin()[0], p.origin()[0] + p.width()),
    };
    let mut chart = ChartBuilder::on(area)
        .caption(caption, (FONT, 17))
        .margin(8)
        .x_label_area_size(48)
        .y_label_area_size(62)
        .build_cartesian_2d(lo - 0.05..hi + 0.05, 0.0..ymax)
        .map_err(e2s)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_desc(if p.body.is_some() {
            "arc length s along Γ3 [m]"
        } else {
            "x [m]"
        })
        .y_desc("-σν [N/m]")
        .x_label_formatter(&crate::output::plot::plain)
        .y_label_formatter(&crate::output::plot::plain)
        .label_style((FONT, 16))
        .draw()
        .map_err(e2s)?;
    let w = if along.len() > 1 {
        (along[1] - along[0]).abs() * 0.35
    } else {
        0.01
    };
    for (k, &x) in along.iter().enumerate() {
        let a = -p.s1[k];
        let b = -(p.s1[k] + p.s2[k]);
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x - w, 0.0), (x + w, a)],
                regime_colour(&p.regime[k]).filled(),
            )))
            .map_err(e2s)?;
        if b > a {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(x - w, a), (x + w, b)],
                    UNILATERAL.filled(),
                )))
                .map_err(e2s)?;
        }
    }
    if shared.is_some() {
        return Ok(());
    }
    for r in regime_order(&p.regime) {
        {
            let label = match (paper_law, r.as_str()) {
                (true, _) | (false, "limit" | "no_contact") => regime_label(&r).to_string(),
                _ => r.replace("branch", "branch "),
            };
            let colour = regime_colour(&r);
            chart
                .draw_series(std::iter::once(Circle::new(
                    (-10.0, -10.0),
                    0,
                    colour.filled(),
                )))
                .map_err(e2s)?
                .label(label)
                .legend(move |(x, y)| {
                    Rectangle::new([(x, y - 5), (x + 14, y + 5)], colour.filled())
                });
        }
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight, 15, 0.85)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mesh_edges_are_each_drawn_once_and_a_fine_mesh_by_its_outline() {
        // Two triangles sharing an edge: five edges, the shared one once.
        assert_eq!(
            mesh_edges(&[[0, 1, 2], [1, 3, 2]]),
            (vec![[0, 1], [0, 2], [1, 2], [1, 3], [2, 3]], false)
        );
        // A strip of m squares cut in two: 4m + 1 edges in all, 2m + 2 on its outline.
        let m = MAX_DRAWN_EDGES / 4 + 1;
        let tris: Vec<[usize; 3]> = (0..m)
            .flat_map(|i| {
                let (a, b, c, d) = (2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1);
                [[a, b, c], [a, c, d]]
            })
            .collect();
        let (outline, thinned) = mesh_edges(&tris);
        assert_eq!((outline.len(), thinned), (2 * m + 2, true));
        assert_eq!(mesh_edges(&tris[..2 * (m - 2)]).0.len(), 4 * (m - 2) + 1);
    }

    #[test]
    fn a_band_is_cut_to_the_box() {
        let inside = clip_box(&[(0.2, 0.2), (0.8, 0.2), (0.8, 0.8)], [0.0, 1.0, 0.0, 1.0]);
        assert_eq!(inside, vec![(0.2, 0.2), (0.8, 0.2), (0.8, 0.8)]);
        let cut = clip_box(
            &[(-1.0, 0.5), (2.0, 0.5), (2.0, -1.0), (-1.0, -1.0)],
            [0.0, 1.0, 0.0, 1.0],
        );
        let area: f64 = (0..cut.len())
            .map(|i| {
                let (a, b) = (cut[i], cut[(i + 1) % cut.len()]);
                a.0 * b.1 - b.0 * a.1
            })
            .sum::<f64>()
            .abs()
            / 2.0;
        assert!(
            (area - 0.5).abs() < 1e-15,
            "the lower half of the box: {area}"
        );
    }
}

/// What the process that has just written a run directory still holds of the run,
/// so that drawing its figures need not read it back.
#[derive(Clone, Copy)]
pub struct Written<'a> {
    /// The scene solved (read back, a mesh scene's mesh would be parsed and built
    /// again from the run's scenario.toml).
    pub scene: &'a crate::scenario::Scenario,
    /// The mesh's triangles, as triangles.csv holds them.
    pub triangles: &'a [[usize; 3]],
    /// The mesh's nodes and their displacement at $T$, as nodes.csv holds them when
    /// it holds every node (a mesh that is no lattice): reading 131 k rows back took
    /// 0.3 s of a 3 s run (paper_n512).
    pub nodes: &'a [[f64; 2]],
    /// The displacement of each of `nodes`; empty when nodes.csv is a lattice (the
    /// figure then reads it, as it does for a run drawn by `evhi plot`).
    pub disp: &'a [[f64; 2]],
}
