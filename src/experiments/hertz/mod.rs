//! Hertz's contact of an elastic cylinder with a rigid plane, against the formula.
//!
//! A cylinder of radius $R$ (plane strain, $E$, $\nu$) pressed onto a rigid plane by a
//! force $P$ per unit thickness touches it on $|x| \le a$ with
//! $$a = 2\sqrt{\frac{P R}{\pi E^*}}, \qquad p(x) = \frac{2P}{\pi a^2}\sqrt{a^2 - x^2},
//! \qquad E^* = \frac{E}{1 - \nu^2},$$
//! so $p_0 = p(0) = 2P/(\pi a)$. The scene (`data/scenarios/examples/hertz.toml`) is
//! the right half of a half-cylinder: rollers on the axis $x = 0$, its flat face pressed
//! down by a prescribed displacement (the body is held vertically by the contact alone
//! otherwise, and the step operator $A + kB$ must be positive definite), frictionless
//! unilateral contact (`law = "none"`) on the arc near the origin. $P$ is then an
//! output: twice the half model's contact force $\sum_i w_i \mu_i$, checked against
//! the flat face's reaction from the assembled stiffness. The computed pressure is the
//! nodal force over the node's share of the $x$ axis (Hertz's $p$ is per unit of $x$).
//!
//! The half-width is read off the computed pressure at the edge of contact: near it
//! any smooth contact has $p \propto \sqrt{a - x}$, so $p^2$ is extrapolated linearly to
//! zero through the last two nodes in contact.
//!
//! The main table presses to $a/R \approx 0.05$; beside it, [`reading`] measures how the
//! error of $a$ depends on where the edge falls between two nodes and what the reading
//! itself adds, [`offset`] the finite body's share at $a/R$ = 0.05, 0.1 and 0.2 with the
//! circle's gaps and Hertz's parabola, and [`relax`] the same body with the paper's
//! viscosity on a compliant layer.

mod offset;
mod reading;
mod relax;

use super::{Ctx, ExpError, col_f64, read_csv};
use evhi::assembly::{matvec, stiffness};
use evhi::mesh::{Dofs, Mesh};
use evhi::output::csv::Table;
use evhi::output::plot::{Figure, both, e2s, legend};
use evhi::scenario::Scenario;
use evhi::simulation::{RunSettings, Simulation};
use plotters::prelude::*;
use std::f64::consts::PI;

/// The scene's file, as shipped.
const SCENE: &str = include_str!("../../../data/scenarios/examples/hertz.toml");
const SCENE_PATH: &str = "data/scenarios/examples/hertz.toml";
/// The radius of the meshes of `tools/meshes/hertz.py`.
pub const R: f64 = 1.0;

/// The meshes of `hertz.csv`, by their elements across $0.1R$ (half as many across
/// its $a \approx 0.05R$).
pub fn meshes(quick: bool) -> Vec<usize> {
    if quick {
        vec![25, 50]
    } else {
        vec![25, 50, 100, 200]
    }
}

/// The shipped scene's press of the flat face (downwards), $a \approx 0.1R$.
const SCENE_PRESS: f64 = 0.0161;

/// The prescribed displacement of the flat face (downwards) of `hertz.csv`, which
/// makes $a \approx 0.05R$ (from a first run; any value serves, Hertz is compared at the
/// computed force). At $a/R = 0.1$ the finite body alone shortens $a$ by about a
/// quarter of a percent (`hertz_offset.csv`); at 0.05 by a quarter of that.
pub const PRESS: f64 = 0.0050;

/// The initial gaps of the contact nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Gap {
    /// The circle's, $R - \sqrt{R^2 - x^2}$: the nodes' distances from the foundation.
    Circle,
    /// Hertz's parabola $x^2 / (2R)$ at the same nodes.
    Parabola,
}

impl Gap {
    pub fn name(self) -> &'static str {
        match self {
            Gap::Circle => "circle",
            Gap::Parabola => "parabola",
        }
    }
}

evhi::row! {
    /// One row of `hertz.csv`: one mesh against Hertz's formula at the computed force.
    pub struct HertzRow {
        /// Elements across the nominal half-width 0.1 R (the mesh's name).
        mesh: u64 => "mesh",
        /// The shortest segment of Gamma_3.
        h_min: f64 => "h_min",
        dofs: u64 => "dofs",
        a_fem: f64 => "a_fem",
        a_hertz: f64 => "a_hertz",
        p0_fem: f64 => "p0_fem",
        p0_hertz: f64 => "p0_hertz",
        rel_err_a: f64 => "rel_err_a",
        rel_err_p0: f64 => "rel_err_p0",
        /// The pressure's relative L2 error over the contact.
        rel_err_p_l2: f64 => "rel_err_p_l2",
        /// |contact force + flat face's reaction| / |reaction| (equilibrium).
        total_force_rel_err: f64 => "total_force_rel_err",
        /// P, the force on the whole body (twice the half model's).
        force: f64 => "P",
        /// The largest (u_nu - g0) - g over the contact nodes, relative to g.
        penetration: f64 => "penetration_over_g",
        /// Elements across the computed half-width.
        elements_across: f64 => "elements_across",
    }
}

/// One solved mesh: the nodes of $\Gamma_3$ in contact order with their pressure.
pub struct Solved {
    pub row: HertzRow,
    /// $x$ and the computed pressure of each contact node.
    pub x: Vec<f64>,
    pub p: Vec<f64>,
}

/// The scene on `data/meshes/{mesh}.msh` (`hertz_50`, `hertz_wide_25`) with the flat
/// face pressed by `press` and the contact nodes' initial gaps `gap`.
pub fn scene(mesh: &str, press: f64, gap: Gap) -> Result<Scenario, ExpError> {
    let text = SCENE
        .replace("hertz_25.msh", &format!("{mesh}.msh"))
        .replace(
            &format!("u = [0.0, -{SCENE_PRESS}]"),
            &format!("u = [0.0, {:e}]", -press),
        );
    let scn = Scenario::from_toml(&text, SCENE_PATH)?;
    Ok(match gap {
        Gap::Circle => scn,
        Gap::Parabola => {
            let body = scn.body().expect("a mesh scene");
            let g0 = (body.gamma3.iter())
                .map(|&v| body.mesh.nodes[v][0].powi(2) / (2.0 * R))
                .collect();
            scn.with_contact_gaps(g0)?
        }
    })
}

/// Solves the mesh `name` pressed by `press` with the gaps `gap` and compares with Hertz at the
/// computed force.
pub fn solve(name: &str, press: f64, gap: Gap) -> Result<Solved, ExpError> {
    let scn = scene(name, press, gap)?;
    let sim = Simulation::new(scn.clone(), RunSettings::default())?;
    let sol = sim.solve(&mut ())?;
    let run = &sol.run;
    let mesh: &Mesh = &run.mesh;
    let x: Vec<f64> = mesh.contact.iter().map(|&v| mesh.nodes[v][0]).collect();
    let w = mesh.contact_weights();
    let m = x.len();
    let wx = x_shares(&x);
    // Nodal forces: the contact stress -sigma_nu = xi + mu per unit length of Gamma_3.
    let force: Vec<f64> = (run.contact.iter().zip(&w))
        .map(|(c, wi)| -(c.sigma_nu1 + c.sigma_nu2) * wi)
        .collect();
    let p: Vec<f64> = force.iter().zip(&wx).map(|(f, l)| f / l).collect();
    let half = force.iter().sum::<f64>();
    let big_p = 2.0 * half;
    // The flat face's reaction from the assembled stiffness on every dof.
    let all = Dofs::new(mesh, false);
    let b = stiffness(mesh, &all, &scn.elasticity());
    let dofs = Dofs::new(mesh, true);
    let u_all = all.gather(&mesh.displacement(&dofs, &run.u));
    let reaction = matvec(&b, &u_all);
    let body = scn.body().expect("a mesh scene");
    let flat = body
        .mesh
        .group("flat")
        .expect("the mesh names its flat face");
    let mut on_flat: Vec<usize> = flat.edges.iter().flatten().copied().collect();
    on_flat.sort_unstable();
    on_flat.dedup();
    let flat_force: f64 = on_flat
        .iter()
        .map(|&v| reaction[all.of(v, 1).expect("every dof kept")])
        .sum();
    // The support pulls the face down by what the contact pushes it up: they cancel.
    let total_force_rel_err = (half + flat_force).abs() / flat_force.abs();
    let e_star = scn.e() / (1.0 - scn.kappa() * scn.kappa());
    let a_h = 2.0 * (big_p * R / (PI * e_star)).sqrt();
    let p0_h = 2.0 * big_p / (PI * a_h);
    let (a_fem, last) = edge(&x, &p);
    let p0_fem = p[0];
    let hertz = |t: f64| {
        if t.abs() < a_h {
            p0_h * (1.0 - (t / a_h).powi(2)).sqrt()
        } else {
            0.0
        }
    };
    let first_out = x.get(last + 1).copied().unwrap_or(x[m - 1]);
    let rel_err_p_l2 = l2_error(&x, &p, &hertz, a_h.max(first_out));
    let g = scn.g();
    let penetration = (run.contact.iter())
        .map(|c| (c.u_nu - g) / g)
        .fold(f64::NEG_INFINITY, f64::max);
    let h_min = (0..m - 1)
        .map(|i| {
            let (p, q) = (mesh.nodes[mesh.contact[i]], mesh.nodes[mesh.contact[i + 1]]);
            (q[0] - p[0]).hypot(q[1] - p[1])
        })
        .fold(f64::INFINITY, f64::min);
    let row = HertzRow {
        mesh: mesh_number(name),
        h_min,
        dofs: run.dofs as u64,
        a_fem,
        a_hertz: a_h,
        p0_fem,
        p0_hertz: p0_h,
        rel_err_a: (a_fem - a_h) / a_h,
        rel_err_p0: (p0_fem - p0_h) / p0_h,
        rel_err_p_l2,
        total_force_rel_err,
        force: big_p,
        penetration,
        elements_across: a_fem / h_min,
    };
    Ok(Solved { row, x, p })
}

/// The number a mesh's name ends with (`hertz_wide_25`: 25).
fn mesh_number(mesh: &str) -> u64 {
    (mesh.rsplit('_').next())
        .and_then(|n| n.parse().ok())
        .expect("a mesh named hertz_N or hertz_wide_N")
}

/// The edge of contact from the nodal pressures `p` at `x`: $p^2$ through the last two
/// nodes in contact, extrapolated to zero ($p \propto \sqrt{a - x}$ there); with the
/// index of the last node in contact.
pub fn edge(x: &[f64], p: &[f64]) -> (f64, usize) {
    let last = p.iter().rposition(|&v| v > 0.0).unwrap_or(0);
    let a = if last >= 1 {
        let (x1, x2) = (x[last - 1], x[last]);
        let (q1, q2) = (p[last - 1].powi(2), p[last].powi(2));
        if q1 > q2 {
            x2 + q2 * (x2 - x1) / (q1 - q2)
        } else {
            x2
        }
    } else {
        f64::NAN
    };
    (a, last)
}

/// The nodes' shares of the $x$ axis: half the $x$-extent of the segments beside each.
pub fn x_shares(x: &[f64]) -> Vec<f64> {
    let m = x.len();
    (0..m)
        .map(|i| {
            let l = if i > 0 { x[i] - x[i - 1] } else { 0.0 };
            let r = if i + 1 < m { x[i + 1] - x[i] } else { 0.0 };
            0.5 * (l.abs() + r.abs())
        })
        .collect()
}

/// $\|p_h - p\|_{L^2(0, L)} / \|p\|_{L^2(0, L)}$ with $p_h$ the piecewise-linear
/// interpolant of the nodal values `p` at `x` (zero beyond them), by 8-point
/// Gauss–Legendre on each segment and on the pieces of $[0, L]$ split at $a$.
fn l2_error(x: &[f64], p: &[f64], exact: &dyn Fn(f64) -> f64, len: f64) -> f64 {
    let ph = |t: f64| match x.windows(2).position(|w| w[0] <= t && t <= w[1]) {
        Some(i) => p[i] + (p[i + 1] - p[i]) * (t - x[i]) / (x[i + 1] - x[i]),
        None => 0.0,
    };
    // 8-point Gauss-Legendre nodes and weights on [-1, 1].
    const GL: [(f64, f64); 4] = [
        (0.183_434_642_495_649_8, 0.362_683_783_378_362),
        (0.525_532_409_916_329, 0.313_706_645_877_887_3),
        (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
        (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    ];
    let mut cuts: Vec<f64> = x.iter().copied().filter(|&t| t < len).collect();
    cuts.push(len);
    let (mut err, mut norm) = (0.0, 0.0);
    for w in cuts.windows(2) {
        // Each segment in 8 pieces: the exact pressure's square root at a.
        for k in 0..8 {
            let (lo, hi) = (
                w[0] + (w[1] - w[0]) * k as f64 / 8.0,
                w[0] + (w[1] - w[0]) * (k + 1) as f64 / 8.0,
            );
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            for (xi, wi) in GL {
                for t in [mid - half * xi, mid + half * xi] {
                    let (e, h) = (exact(t), ph(t));
                    err += wi * half * (h - e).powi(2);
                    norm += wi * half * e * e;
                }
            }
        }
    }
    (err / norm).sqrt()
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let levels = meshes(ctx.quick);
    ctx.add_units(levels.len());
    let mut rows = vec![];
    let mut profiles = vec![];
    for &n in &levels {
        let s = solve(&format!("hertz_{n}"), PRESS, Gap::Circle)?;
        ctx.log(&format!(
            "hertz: mesh {n}, a = {:.6} (Hertz {:.6})",
            s.row.a_fem, s.row.a_hertz
        ));
        rows.push(s.row.clone());
        profiles.push((n, s));
    }
    let params = format!(
        "Hertz's cylinder on a rigid plane, half model: data/scenarios/examples/hertz.toml on data/meshes/hertz_MESH.msh (tools/meshes/hertz.py; MESH elements across 0.1 R, half as many across a), R = {R}, flat face pressed by {PRESS} (a/R about 0.05); P = twice the half model's contact force; a_hertz, p0_hertz from P; a_fem from p^2 extrapolated to zero through the last two nodes in contact; p0_fem the pressure at x = 0; pressures per unit x (nodal force over the node's share of the x axis); rel_err_p_l2 over [0, max(a_hertz, first node out of contact)]; total_force_rel_err = |contact force + flat face's reaction| / |reaction| (the two balance); penetration_over_g = max(u_nu - g0 - g) / g"
    );
    ctx.write("hertz.csv", &HertzRow::table(&rows), &params)?;
    // The finest mesh's pressure (and the coarsest's) beside Hertz's.
    let mut t_mesh = vec![];
    let (mut t_x, mut t_p) = (vec![], vec![]);
    for (n, s) in [profiles.first(), profiles.last()].into_iter().flatten() {
        let a = s.row.a_hertz;
        for (x, p) in s.x.iter().zip(&s.p) {
            if *x <= 1.5 * a {
                t_mesh.push(*n as u64);
                t_x.push(x / a);
                t_p.push(p / s.row.p0_hertz);
            }
        }
    }
    let profile = Table::new()
        .u64("mesh", t_mesh)
        .f64("x_over_a_hertz", t_x)
        .f64("p_over_p0_hertz", t_p);
    let path = ctx.write(
        "hertz_pressure.csv",
        &profile,
        "the computed pressure at the contact nodes of the coarsest and finest meshes of hertz.csv, scaled by Hertz's a and p0 at the computed force",
    )?;
    let df = read_csv(&path)?;
    let fig = PressureFig {
        mesh: col_f64(&df, "mesh")?,
        x: col_f64(&df, "x_over_a_hertz")?,
        p: col_f64(&df, "p_over_p0_hertz")?,
    };
    both(&ctx.figures, "hertz_pressure", (900, 600), &fig)?;
    relax::run(ctx)?;
    if !ctx.quick {
        let edges = reading::run(ctx)?;
        let fits = offset::run(ctx)?;
        let finest = rows.last().expect("meshes");
        let mean = edges.last().expect("meshes").fem_mean;
        ctx.write(
            "hertz_finest_split.csv",
            &finest_split(finest, mean, &fits),
            "the finest mesh of hertz.csv (a/R about 0.05) split: finite_body = c (a_hertz/R)^2 with the circle's c at the finest count across a (hertz_offset_fit.csv), discretisation = rel_err - finite_body; a_mean: a's error over the edge's places (rel_err_a_mean of hertz_edge.csv)",
        )?;
    }
    Ok(())
}

evhi::row! {
    /// The finest mesh's error of a quantity split into the finite body's and the
    /// discretisation's parts.
    pub struct SplitRow {
        /// `a`, `a_mean` (over the edge's places) or `p0`.
        quantity: String => "quantity",
        rel_err: f64 => "rel_err",
        finite_body: f64 => "finite_body",
        discretisation: f64 => "discretisation",
    }
}

/// The split of the finest row's errors with the circle's finite-body coefficients
/// at the most elements across $a$, and `mean`, the mean error of $a$ over the places
/// of the edge.
fn finest_split(finest: &HertzRow, mean: f64, fits: &[offset::FitRow]) -> Table {
    let s2 = (finest.a_hertz / R).powi(2);
    let most = fits.iter().map(|f| f.across).max().expect("fits");
    let c = |q: &str| {
        (fits.iter())
            .find(|f| f.gap == Gap::Circle.name() && f.quantity == q && f.across == most)
            .expect("a fit")
            .coefficient
    };
    let (fa, fp) = (c("a") * s2, c("p0") * s2);
    let rows = [
        ("a", finest.rel_err_a, fa),
        ("a_mean", mean, fa),
        ("p0", finest.rel_err_p0, fp),
    ]
    .map(|(q, e, f)| SplitRow {
        quantity: q.into(),
        rel_err: e,
        finite_body: f,
        discretisation: e - f,
    });
    SplitRow::table(&rows)
}

/// The computed pressures against Hertz's ellipse, in Hertz's units.
struct PressureFig {
    mesh: Vec<f64>,
    x: Vec<f64>,
    p: Vec<f64>,
}

impl Figure for PressureFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Hertz: contact pressure of a cylinder on a rigid plane",
                (evhi::output::plot::FONT, 26),
            )
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..1.5, 0.0..1.15)
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("x / a (a Hertz's half-width at the computed force)")
            .y_desc("p / p0 (Hertz's peak)")
            .draw()
            .map_err(e2s)?;
        let curve: Vec<(f64, f64)> = (0..=400)
            .map(|i| {
                let t = 1.5 * i as f64 / 400.0;
                (t, if t < 1.0 { (1.0 - t * t).sqrt() } else { 0.0 })
            })
            .collect();
        chart
            .draw_series(LineSeries::new(curve, BLACK.stroke_width(2)))
            .map_err(e2s)?
            .label("Hertz")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
        let mut meshes: Vec<f64> = self.mesh.clone();
        meshes.dedup();
        // The finest first, small, and the coarsest over it, larger: both stay visible.
        for (k, m) in meshes.iter().enumerate().rev() {
            let (colour, r) = if k == 0 {
                (evhi::output::plot::okabe_ito::VERMILLION, 5)
            } else {
                (evhi::output::plot::okabe_ito::BLUE, 2)
            };
            let pts: Vec<(f64, f64)> = (0..self.x.len())
                .filter(|&i| self.mesh[i] == *m)
                .map(|i| (self.x[i], self.p[i]))
                .collect();
            chart
                .draw_series(
                    pts.iter()
                        .map(|&(x, y)| Circle::new((x, y), r, colour.filled())),
                )
                .map_err(e2s)?
                .label(format!("evhi, mesh {m} ({} nodes on Gamma_3)", pts.len()))
                .legend(move |(x, y)| Circle::new((x + 10, y), r, colour.filled()));
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight, 16, 0.9)
    }
}
