//! Where step solvers fail: one cell of a stability map (a solver on a scenario at a
//! time step, with its outcome, iterations, certificate, the step's convexity and, for
//! Newton, the spread of several starts), the solvers a map shows, and the map's
//! figure. The book's map (`stability`) and `evhi study stability` draw theirs with it.

use crate::output::plot::FONT;
use crate::output::plot::{GREY_LIGHT, okabe_ito as oi};
use crate::scenario::Scenario;

/// Cell colours of the map (Okabe–Ito, safe for colour-blind readers; a failed
/// cell also says "fail").
/// Convex and not convex differ in lightness (dark blue, pale grey), the two that
/// warn in hue and lightness (yellow, vermillion).
const CONVEX: RGBColor = oi::BLUE;
const NOT_CONVEX: RGBColor = GREY_LIGHT;
const SEVERAL: RGBColor = oi::YELLOW;
const FAILED: RGBColor = oi::VERMILLION;
/// The penalty converged but let u_nu pass g (Okabe–Ito bluish green).
const OVERSHOOT: RGBColor = oi::BLUISH_GREEN;
/// The outcome of a cell whose uncertified solver let u_nu pass g (measured).
const OVERSHOOTS_G: &str = "converged (overshoots g)";
use crate::output::plot::{Figure, e2s};
use crate::step::Status;
use crate::step::multistart::MultiStart;
use plotters::prelude::*;
use plotters::style::text_anchor::Pos;

/// One cell of a stability map: a solver's run of a scenario at one time step, and
/// how it went ([`map_cell`]).
pub struct Cell {
    /// The step solver, by its registry name or label.
    pub solver: &'static str,
    /// The number of time steps $N$.
    pub steps: usize,
    /// The scenario's softening slope $c_2$, as the caller records it (NaN where it
    /// does not).
    pub c2: f64,
    /// The outcome in words: `certified`, `several solutions`, `converged (…)` for an
    /// uncertified solver, `failed: …` or `error: …`.
    pub outcome: String,
    /// The step that failed (0 unless a step did).
    pub failed_step: u64,
    /// The step solver's outer iterations per step, on average; NaN where the run
    /// failed or did not start.
    pub mean_iterations: f64,
    /// The largest certificate over the steps, or the step solver's residual at the
    /// failed step; NaN where the run did not start.
    pub certificate: f64,
    /// The smallest curvature a step problem can have
    /// ([`crate::scheme::Run::hessian_min`]): positive when every step is strictly
    /// convex; NaN where the run failed or did not start.
    pub hessian_min: f64,
    /// With Newton: the largest relative distance between the answers from several
    /// starts ([`MultiStart::spread`]); NaN for every other solver.
    pub spread: f64,
}

/// One cell: `scn` (whose softening slope is `c2`, recorded with the cell) run with
/// `solver` at h = 1/n and `steps` steps.
pub fn map_cell(scn: &Scenario, c2: f64, n: usize, steps: usize, solver: &'static str) -> Cell {
    let entry = crate::step::solver(solver).expect("the map's solvers are registered");
    // An uncertified solver (the penalty overshoots g by design) is judged by its own
    // convergence.
    let sim = crate::simulation::Simulation::new(
        scn.clone(),
        crate::simulation::RunSettings::general(n, steps),
    );
    let (res, spread) = match sim {
        Err(e) => (Err(e.into()), f64::NAN),
        Ok(sim) if entry.name == crate::step::DEFAULT_SOLVER => {
            // Newton also from other starts: does the step have several solutions?
            let mut s = MultiStart {
                inner: entry.build(),
                spread: 0.0,
            };
            let r = sim.solve_with(&mut s, &mut ()).map(|s| s.run);
            (r, s.spread)
        }
        Ok(sim) => (
            sim.solve_with(entry.build().as_mut(), &mut ())
                .map(|s| s.run),
            f64::NAN,
        ),
    };
    match res {
        Ok(run) => Cell {
            solver,
            steps,
            c2,
            outcome: if spread > 1e-6 {
                "several solutions".into()
            } else if !entry.certified && crate::output::run::max_overshoot(&run.records) > 0.0 {
                // Measured: some step's u_nu passed g beyond rounding.
                OVERSHOOTS_G.into()
            } else if !entry.certified && scn.g.is_finite() {
                "converged (within g)".into()
            } else if !entry.certified {
                "converged (no limit)".into()
            } else {
                "certified".into()
            },
            failed_step: 0,
            mean_iterations: run.records.iter().map(|r| r.iterations as f64).sum::<f64>()
                / steps as f64,
            certificate: run
                .records
                .iter()
                .map(|r| r.certificate.max())
                .fold(0.0, f64::max),
            hessian_min: run.hessian_min,
            spread,
        },
        Err(crate::scheme::RunError::Step {
            step,
            status,
            residual,
            ..
        }) => Cell {
            solver,
            steps,
            c2,
            outcome: if status == Status::Converged {
                "failed: certificate over tolerance".to_string()
            } else {
                format!("failed: {}", status.label())
            },
            failed_step: step as u64,
            mean_iterations: f64::NAN,
            certificate: residual,
            hessian_min: f64::NAN,
            spread,
        },
        Err(e) => Cell {
            solver,
            steps,
            c2,
            outcome: format!("error: {e}"),
            failed_step: 0,
            mean_iterations: f64::NAN,
            certificate: f64::NAN,
            hessian_min: f64::NAN,
            spread,
        },
    }
}

/// What the NaN of a stability table means, column by column.
pub const NAN_COLUMNS: &str = "NaN: multistart_spread for every solver but newton (only newton is \
     restarted), mean_iterations where the run failed or did not start (hessian_min too, in \
     the map's table), max_certificate_or_residual where it did not start";

/// The map's solvers: the registry's entries marked `mapped`, in registry order.
pub fn solvers() -> Vec<&'static str> {
    crate::step::SOLVERS
        .iter()
        .filter(|e| e.mapped)
        .map(|e| e.label)
        .collect()
}

/// A map: per cell (solver, k, row value, outcome, mean iterations, hessian_min); the
/// rows are the distinct row values ascending, labelled by `row_label`.
pub struct MapFigure {
    /// The cells: (solver, $k$, row value, outcome, mean iterations, hessian_min); one
    /// panel per solver, in the order they first appear.
    pub cells: Vec<(String, f64, f64, String, f64, f64)>,
    /// The figure's title.
    pub title: String,
    /// The description of the row axis.
    pub row_desc: String,
    /// The label of a row value on its axis.
    pub row_label: fn(f64) -> String,
}

impl Figure for MapFigure {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let root = root.titled(&self.title, (FONT, 21)).map_err(e2s)?;
        let mut ks: Vec<f64> = self.cells.iter().map(|c| c.1).collect();
        ks.sort_by(f64::total_cmp);
        ks.dedup();
        let mut cs: Vec<f64> = self.cells.iter().map(|c| c.2).collect();
        cs.sort_by(f64::total_cmp);
        cs.dedup();
        let band = 100;
        let (top, _legend_band) = root.split_vertically(root.dim_in_pixel().1 - band);
        let mut solvers: Vec<&str> = vec![];
        for c in &self.cells {
            if !solvers.contains(&c.0.as_str()) {
                solvers.push(&c.0);
            }
        }
        let panels = top.split_evenly((solvers.len().div_ceil(2), 2));
        for (solver, area) in solvers.iter().zip(panels.iter()) {
            let mut chart = ChartBuilder::on(area)
                .caption(*solver, (FONT, 20))
                .margin(10)
                .x_label_area_size(45)
                .y_label_area_size(70)
                .build_cartesian_2d(-0.5..ks.len() as f64 - 0.5, -0.5..cs.len() as f64 - 0.5)
                .map_err(e2s)?;
            let (kl, cl, rl) = (ks.clone(), cs.clone(), self.row_label);
            chart
                .configure_mesh()
                .disable_mesh()
                .x_labels(ks.len())
                .y_labels(cs.len())
                .x_label_formatter(&move |x| {
                    let i = x.round();
                    if (x - i).abs() > 1e-9 || i < 0.0 {
                        return String::new();
                    }
                    kl.get(i as usize)
                        .map_or(String::new(), |k| format!("1/{}", (1.0 / k).round()))
                })
                .y_label_formatter(&move |y| {
                    let i = y.round();
                    if (y - i).abs() > 1e-9 || i < 0.0 {
                        return String::new();
                    }
                    cl.get(i as usize).map_or(String::new(), |c| rl(*c))
                })
                .x_desc("time step k")
                .y_desc(&self.row_desc)
                .label_style((FONT, 18))
                .axis_desc_style((FONT, 18))
                .draw()
                .map_err(e2s)?;
            for c in self.cells.iter().filter(|c| c.0 == *solver) {
                let x = ks.iter().position(|&k| k == c.1).unwrap_or(0) as f64;
                let y = cs.iter().position(|&v| v == c.2).unwrap_or(0) as f64;
                let colour = if c.3.starts_with("failed") || c.3.starts_with("error") {
                    FAILED
                } else if c.3 == "several solutions" {
                    SEVERAL
                } else if c.3 == OVERSHOOTS_G {
                    OVERSHOOT
                } else if c.5 > 0.0 {
                    CONVEX
                } else {
                    NOT_CONVEX
                };
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(x - 0.46, y - 0.46), (x + 0.46, y + 0.46)],
                        colour.filled(),
                    )))
                    .map_err(e2s)?;
                let label = if c.4.is_finite() {
                    format!("{:.1}", c.4)
                } else {
                    "fail".into()
                };
                // Centred in the cell; white on the dark cells.
                let ink = if colour == CONVEX || colour == OVERSHOOT {
                    WHITE
                } else {
                    BLACK
                };
                let style = (FONT, 18).into_font().color(&ink).pos(Pos::new(
                    plotters::style::text_anchor::HPos::Center,
                    plotters::style::text_anchor::VPos::Center,
                ));
                chart
                    .draw_series(std::iter::once(Text::new(label, (x, y), style)))
                    .map_err(e2s)?;
            }
        }
        let legend = [
            (
                "certified (penalty: never past g), every step convex",
                CONVEX,
            ),
            (
                "certified (penalty: never past g), steps not convex",
                NOT_CONVEX,
            ),
            ("several solutions (multistart)", SEVERAL),
            ("failed", FAILED),
            ("penalty converged, uν past g (no certificate)", OVERSHOOT),
        ];
        // Legend rows of two entries under the panels.
        let y0 = root.dim_in_pixel().1 as i32 - band as i32 + 8;
        for (i, (text, colour)) in legend.iter().enumerate() {
            let (x, y) = (20 + 540 * (i % 2) as i32, y0 + 30 * (i / 2) as i32);
            root.draw(&Rectangle::new([(x, y), (x + 18, y + 18)], colour.filled()))
                .map_err(e2s)?;
            root.draw(&Text::new(*text, (x + 26, y + 1), (FONT, 18)))
                .map_err(e2s)?;
        }
        Ok(())
    }
}
