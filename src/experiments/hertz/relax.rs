//! The viscoelastic Hertz: the cylinder with the paper's Kelvin–Voigt viscosity on a
//! compliant layer, relaxing towards its elastic answer.
//!
//! The body is `hertz.csv`'s (`hertz_50`, $E = 1000$, $\nu = 0.3$, flat face pressed by
//! $d$ = [`PRESS`]) with the paper's viscosity $\alpha = 100$, $\beta = 50$
//! ($\mathcal C\varepsilon = \alpha\,\mathrm{tr}\,\varepsilon\,I + \beta\,\varepsilon$
//! in the paper's notation), so that it solves
//! $\mathcal C\varepsilon(\dot u) + \mathcal G\varepsilon(u)$ in equilibrium with the
//! contact, and on $\Gamma_3$ the paper's normal compliance law with its limit, scaled to
//! this contact. The paper's law has breakpoints $0, 0.05, 0.075$, slopes
//! $0, 200, -100, 300$ and the limit $g = 0.1$, on a body of unit size whose contact
//! stresses are of the order of its load, 75. Here lengths are scaled by
//! $\lambda_L = d / 0.1 = 0.05$, so that the limit is the press ($g = d$: the centre
//! starts at the limit), and stresses by $\lambda_S = 2$, so that the law at its
//! limit, $2 \cdot 15 = 30$, is near Hertz's peak pressure at this press (27.7,
//! `hertz.csv`); the slopes scale by $\lambda_S/\lambda_L = 40$.
//!
//! The prescribed displacement is a rigid shift present from $t = 0$ (`src/body.rs`):
//! at the start the undeformed body sinks into the layer by $d - g_{0,i}$, the law
//! pushes back, and the viscosity lets the body yield only gradually. Each step's
//! contact force $P(t)$ (twice the half model's), the pressure at the axis $p_0(t)$ and
//! the contact half-width $a(t)$ (where the penetration $u_\nu - g_0$ crosses zero,
//! linear between the nodes around it; the layer's pressure vanishes there with it)
//! are recorded against the same three of the steady elastic solution with the same
//! law and limit.

use super::{PRESS, R, SCENE, SCENE_PATH, SCENE_PRESS, x_shares};
use crate::experiments::{Ctx, ExpError, col_f64, read_csv};
use evhi::certificate::ContactState;
use evhi::mesh::Mesh;
use evhi::output::csv::Table;
use evhi::output::plot::{Figure, both, e2s, legend};
use evhi::scenario::{Problem, Scenario};
use evhi::simulation::{OnStep, RunSettings, Simulation};
use plotters::prelude::*;

/// The mesh.
pub const MESH: &str = "hertz_50";
/// Time steps over $T = 1$ (quick: a quarter).
pub fn steps(quick: bool) -> usize {
    if quick { 32 } else { 128 }
}

/// The paper's law scaled: lengths by $\lambda_L = 0.05$, stresses by $\lambda_S = 2$.
pub const LAW: &str =
    "[law]\nbreakpoints = [0.0, 0.0025, 0.00375]\nslopes = [0.0, 8000.0, -4000.0, 12000.0]\n";
/// The limit $g = \lambda_L \cdot 0.1$, the press.
pub const G: f64 = 0.005;

/// The viscoelastic scene.
pub fn scene() -> Result<Scenario, ExpError> {
    let text = SCENE
        .replace("hertz_25.msh", &format!("{MESH}.msh"))
        .replace(
            &format!("u = [0.0, -{SCENE_PRESS}]"),
            &format!("u = [0.0, {:e}]", -PRESS),
        )
        .replace("problem = \"steady\"\n", "")
        .replace("law = \"none\"\n", "")
        .replace("g = 1e-4", &format!("g = {G}"))
        .replace("kappa = 0.3\n", "kappa = 0.3\nalpha = 100.0\nbeta = 50.0\n")
        .replace("name = \"hertz\"", "name = \"hertz-viscoelastic\"");
    Ok(Scenario::from_toml(&format!("{text}\n{LAW}"), SCENE_PATH)?)
}

/// The force $P$ (whole body), the pressure at the axis and the half-width of one
/// contact state on `mesh`.
fn measures(mesh: &Mesh, contact: &[ContactState]) -> (f64, f64, f64) {
    debug_assert_eq!(mesh.contact.len(), contact.len());
    let x: Vec<f64> = mesh.contact.iter().map(|&v| mesh.nodes[v][0]).collect();
    let w = mesh.contact_weights();
    let force: Vec<f64> = (contact.iter().zip(&w))
        .map(|(c, wi)| -(c.sigma_nu1 + c.sigma_nu2) * wi)
        .collect();
    let shares = x_shares(&x);
    let p0 = force[0] / shares[0];
    let a = match contact.iter().position(|c| c.u_nu <= 0.0) {
        Some(0) => 0.0,
        Some(i) => {
            let (s1, s2) = (contact[i - 1].u_nu, contact[i].u_nu);
            x[i - 1] + (x[i] - x[i - 1]) * s1 / (s1 - s2)
        }
        None => x[x.len() - 1],
    };
    (2.0 * force.iter().sum::<f64>(), p0, a)
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    ctx.add_units(2);
    let visco = scene()?;
    let steady = visco.clone().with_problem(Problem::Steady)?;
    let sim = Simulation::new(steady, RunSettings::default())?;
    let sol = sim.solve(&mut ())?;
    let (p_el, p0_el, a_el) = measures(&sol.run.mesh, &sol.run.contact);
    ctx.log(&format!(
        "hertz: the steady elastic answer on the layer, P = {p_el:.4}, a = {a_el:.5}"
    ));
    let n = steps(ctx.quick);
    let sim = Simulation::new(visco, RunSettings::default().with_steps(n))?;
    let mesh = sim.mesh().clone();
    // Each step's t, P, p0, a and s0.
    let mut rec: Vec<[f64; 5]> = vec![];
    let sol = {
        let mut obs = OnStep::new(|_: usize, t: f64, _: Option<&[f64]>, c: &[ContactState]| {
            let (p, p0, a) = measures(&mesh, c);
            rec.push([t, p, p0, a, c[0].u_nu]);
        });
        sim.solve(&mut obs)?
    };
    ctx.log("hertz: the viscoelastic body relaxed");
    let certificate = sol.max_certificate();
    let col = |i: usize, by: f64| rec.iter().map(|r| r[i] / by).collect::<Vec<f64>>();
    let m = rec.len();
    let table = Table::new()
        .f64("t", col(0, 1.0))
        .f64("P", col(1, 1.0))
        .f64("p0", col(2, 1.0))
        .f64("a", col(3, 1.0))
        .f64("s0", col(4, 1.0))
        .f64("P_over_steady", col(1, p_el))
        .f64("p0_over_steady", col(2, p0_el))
        .f64("a_over_steady", col(3, a_el))
        .f64("P_steady", vec![p_el; m])
        .f64("p0_steady", vec![p0_el; m])
        .f64("a_steady", vec![a_el; m]);
    let path = ctx.write(
        "hertz_relax.csv",
        &table,
        &format!(
            "the viscoelastic Hertz: data/scenarios/examples/hertz.toml on data/meshes/{MESH}.msh (R = {R}), flat face pressed by {PRESS} from t = 0, with the paper's viscosity alpha = 100, beta = 50 and its law scaled (lengths by 0.05, stresses by 2: {}, g = {G}); T = 1, {n} steps of backward Euler, largest certificate {certificate:.1e}; P the force on the whole body, p0 the pressure at the axis, a where u_nu - g0 crosses 0, s0 = u_nu - g0 at the axis (the law's argument there); *_steady the steady elastic solution with the same law and limit",
            LAW.replace('\n', " ").trim()
        ),
    )?;
    let df = read_csv(&path)?;
    let fig = RelaxFig {
        t: col_f64(&df, "t")?,
        series: [
            col_f64(&df, "P_over_steady")?,
            col_f64(&df, "p0_over_steady")?,
            col_f64(&df, "a_over_steady")?,
        ],
    };
    Ok(both(&ctx.figures, "hertz_relax", (900, 600), &fig)?)
}

/// The three measures over $t$, each over its steady elastic value.
struct RelaxFig {
    t: Vec<f64>,
    series: [Vec<f64>; 3],
}

impl Figure for RelaxFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let hi = (self.series.iter().flatten())
            .fold(1.0f64, |m, v| m.max(*v))
            .min(5.0);
        let lo = (self.series.iter().flatten())
            .fold(1.0f64, |m, v| m.min(*v))
            .max(0.0);
        let pad = 0.05 * (hi - lo);
        let mut chart = ChartBuilder::on(root)
            .caption(
                "Viscoelastic Hertz on a compliant layer: relaxing to the elastic answer",
                (evhi::output::plot::FONT, 24),
            )
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..1.0, (lo - pad)..(hi + pad))
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("t")
            .y_desc("over the steady elastic value (same law)")
            .draw()
            .map_err(e2s)?;
        chart
            .draw_series(LineSeries::new(
                vec![(0.0, 1.0), (1.0, 1.0)],
                BLACK.stroke_width(2),
            ))
            .map_err(e2s)?
            .label("steady elastic solution")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
        // Okabe–Ito, as the regimes' colours.
        let styles = [
            (evhi::output::plot::okabe_ito::BLUE, "contact force P(t)"),
            (
                evhi::output::plot::okabe_ito::VERMILLION,
                "peak pressure p0(t)",
            ),
            (
                evhi::output::plot::okabe_ito::BLUISH_GREEN,
                "half-width a(t)",
            ),
        ];
        for (s, (colour, label)) in self.series.iter().zip(styles) {
            let pts: Vec<(f64, f64)> = self.t.iter().copied().zip(s.iter().copied()).collect();
            chart
                .draw_series(LineSeries::new(pts, colour.stroke_width(2)))
                .map_err(e2s)?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight, 16, 0.9)
    }
}
