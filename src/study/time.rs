//! `evhi study time`: the time error at a fixed mesh on the scenario's own history.

use super::{bar, pct, study_ctx, write_scenario};
use crate::output::plot::okabe_ito as oi;
use crate::output::rundir::RunDir;
use crate::scenario::Scenario;
use std::fmt::Write as _;

/// The time error at a fixed mesh: backward Euler at k = T/N for N = 4, 8, …
/// against the same mesh with a far finer step, the maximum over time and at T,
/// orders, where the error peaks, and, where the damping is proportional
/// (C = tau G), the scalar model of the relaxation layer beside it. Writes
/// time_study.csv, time_study.md and time_study.png/svg. Viscoelastic scenarios
/// only: an elastic or steady one has no time error and is refused.
///
/// Example: evhi study time --scenario data/scenarios/examples/five_branch.toml --quick --out runs/time
#[derive(clap::Parser)]
pub struct TimeArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long, value_parser = crate::scenario::arg_parser())]
    pub scenario: String,
    /// Mesh n = 16, N up to 256 and a reference with 16384 steps (seconds); without
    /// it n = 32, N up to 1024 and 32768 reference steps.
    #[arg(long)]
    pub quick: bool,
    /// Override the mesh level n (a multiple of 4 on which the scene resolves).
    #[arg(long)]
    pub n: Option<usize>,
    /// The step solver of every run of the study (default newton), a certified one:
    /// the study compares runs whose every step is certified.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(crate::step::solver_values()))]
    pub solver: Option<String>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: std::path::PathBuf,
}

/// Runs the study from its parsed command line (its [`super::StudyEntry::run`]).
pub(super) fn from_matches(
    m: &clap::ArgMatches,
    command: &str,
    announce: bool,
) -> Result<String, Box<dyn std::error::Error>> {
    let args = <TimeArgs as clap::FromArgMatches>::from_arg_matches(m)?;
    let _ = announce;
    run(args, command)
}

pub(super) fn run(args: TimeArgs, command: &str) -> Result<String, Box<dyn std::error::Error>> {
    use super::time_error as time;
    let (scn, text) = Scenario::read(&args.scenario)?;
    if scn.problem != crate::scenario::Problem::Viscoelastic {
        return Err(crate::error::InputError::field(
            "scenario",
            &scn.name,
            format!(
                "a viscoelastic scenario: this one is {} ({}, so backward Euler has no time \
                 error to study)",
                scn.problem.name(),
                if scn.problem == crate::scenario::Problem::Steady {
                    "one solve at T"
                } else {
                    "each step solves the static problem with f(t_n)"
                }
            ),
        )
        .into());
    }
    let mut plan = time::plan(args.quick);
    if let Some(n) = args.n {
        scn.refuse_level_on_mesh(n)
            .map_err(|e| e.for_flag("n", "--n"))?;
    }
    match (args.n, scn.body_mesh()) {
        // A mesh scene's mesh is its file's: n is its count of contact segments.
        (_, Some(mesh)) => plan.n = mesh.n,
        (Some(n), None) => plan.n = n,
        (None, None) => {}
    }
    plan.solver = super::study_solver(args.solver.as_deref())?;
    if scn.body().is_none() {
        scn.mesh(plan.n)?;
    }
    let out = RunDir::open(&args.out)?;
    let progress = bar(0);
    let ctx = study_ctx(&out, args.quick, &progress, command);
    let rows = time::study_of(
        &plan,
        &ctx,
        &[(scn.name.clone(), scn.history.to_string(), scn.clone())],
    )?;
    progress.finish_and_clear();
    time::write_rows(&ctx, &plan, &rows, "time_study.csv", "history")?;
    let mut md = format!(
        "# Time error of `{}` at n = {} ({})\n\nproduced by evhi {} `evhi {command}`\n\nReference: {} steps on the same mesh. Errors relative, energy norm: \
         \"max over t\" is max_n ||e_n|| / max_n ||u_ref,n|| over the level's steps, \"at T\" is ||e(T)|| / ||u_ref(T)||; \
         orders are orders in k (log2 of the ratio to the previous row, k halved); \"t of max\" is where ||e_n|| peaks.\n\n\
         | N | k | max over t, % | order in k | at T, % | order in k | model max, % | model T, % | t of max |\n|---|---|---|---|---|---|---|---|---|\n",
        scn.name,
        plan.n,
        if args.quick { "quick" } else { "full" },
        env!("CARGO_PKG_VERSION"),
        plan.n_ref
    );
    for (i, r) in rows.iter().enumerate() {
        let order = |a: f64, b: f64| if i == 0 { f64::NAN } else { (b / a).log2() };
        let _ = writeln!(
            md,
            "| {} | {:.4e} | {} | {:.3} | {} | {:.3} | {} | {} | {:.4} |",
            r.steps,
            r.t_end / r.steps as f64,
            pct(100.0 * r.err_max),
            order(
                r.err_max,
                if i > 0 { rows[i - 1].err_max } else { f64::NAN }
            ),
            pct(100.0 * r.err_t),
            order(r.err_t, if i > 0 { rows[i - 1].err_t } else { f64::NAN }),
            pct(100.0 * r.model_max),
            pct(100.0 * r.model_t),
            r.t_err_max
        );
    }
    let _ = writeln!(
        md,
        "\n{}",
        match scn.relaxation_time() {
            Some(0.0) => "No viscosity: the model columns are the load history alone.".to_string(),
            Some(tau) => format!(
                "Proportional damping, tau = {tau:.6}: the model is the scalar layer tau y' + y = phi(t) by backward Euler; \
                 backward Euler resolves the layer only once k is well below tau."
            ),
            None => "The damping is not proportional (several relaxation times): no scalar model."
                .to_string(),
        }
    );
    out.write("time_study.md", md.as_bytes())?;
    draw_time(&out.path(""), &rows, plan.n)?;
    write_scenario(&out, &text, command)?;
    out.publish()?;
    Ok(md)
}

/// The time study's figure: the error (max over t and at T) against N, with the
/// scalar model dashed where there is one.
/// A curve: label, (N, error %) points, colour, dashed (the model).
type Curve = (String, Vec<(f64, f64)>, plotters::style::RGBColor, bool);

struct TimeFig {
    series: Vec<Curve>,
    title: String,
}

impl crate::output::plot::Figure for TimeFig {
    fn draw<DB: plotters::prelude::DrawingBackend>(
        &self,
        root: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        use crate::output::plot::{LogLogChart, e2s, extent, legend};
        use plotters::prelude::*;
        let pts: Vec<(f64, f64)> = self.series.iter().flat_map(|s| s.1.clone()).collect();
        let ((x0, x1), (y0, y1)) = extent(&pts);
        if pts.is_empty() {
            return Err("no positive error to draw".into());
        }
        // A key at each N of the study, printed as the integer it is.
        let mut ns: Vec<f64> = pts.iter().map(|p| p.0).collect();
        ns.sort_by(f64::total_cmp);
        ns.dedup();
        let mut chart = LogLogChart {
            caption: (&self.title, 22),
            margin: 12,
            label_areas: (45, 80),
            desc: ("time steps N", "relative energy error, %"),
            format: (Some(&|x| format!("{x:.0}")), None),
            fonts: (17, None),
        }
        .build(
            root,
            (x0 / 1.5..x1 * 1.5).log_scale().with_key_points(ns),
            (y0 / 3.0..y1 * 3.0).log_scale(),
        )?;
        for (label, p, c, dashed) in &self.series {
            let c = *c;
            if *dashed {
                chart
                    .draw_series(DashedLineSeries::new(p.clone(), 6, 4, c.stroke_width(2)))
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |(x, y)| {
                        // a dashed key: two short strokes
                        EmptyElement::at((x, y))
                            + PathElement::new(vec![(0, 0), (9, 0)], c.stroke_width(2))
                            + PathElement::new(vec![(15, 0), (24, 0)], c.stroke_width(2))
                    });
            } else {
                chart
                    .draw_series(LineSeries::new(p.clone(), c.stroke_width(3)))
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 24, y)], c.stroke_width(3))
                    });
                chart
                    .draw_series(p.iter().map(|&q| Circle::new(q, 4, c.filled())))
                    .map_err(e2s)?;
            }
        }
        legend(&mut chart, SeriesLabelPosition::UpperRight, 16, 0.9)?;
        Ok(())
    }
}

fn draw_time(
    dir: &std::path::Path,
    rows: &[super::time_error::Row],
    n: usize,
) -> Result<(), super::ExpError> {
    let pick = |f: &dyn Fn(&super::time_error::Row) -> f64| -> Vec<(f64, f64)> {
        rows.iter()
            .map(|r| (r.steps as f64, 100.0 * f(r)))
            .filter(|p| p.1.is_finite() && p.1 > 0.0)
            .collect()
    };
    let (blue, red) = (oi::BLUE, oi::VERMILLION);
    let mut series = vec![
        ("max over t".to_string(), pick(&|r| r.err_max), blue, false),
        ("at T".to_string(), pick(&|r| r.err_t), red, false),
    ];
    for (label, f, c) in [
        (
            "model, max over t",
            (|r: &super::time_error::Row| r.model_max) as fn(&_) -> f64,
            blue,
        ),
        ("model, at T", |r: &super::time_error::Row| r.model_t, red),
    ] {
        let p = pick(&f);
        if !p.is_empty() {
            series.push((label.to_string(), p, c, true));
        }
    }
    series.retain(|s| !s.1.is_empty());
    let title = format!(
        "time error of {} at n = {n} against N",
        rows.first().map_or("", |r| r.scenario.as_str())
    );
    Ok(crate::output::plot::both(
        dir,
        "time_study",
        (900, 650),
        &TimeFig { series, title },
    )?)
}
