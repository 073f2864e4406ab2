//! `evhi study`: the book's studies on any scenario, each written as a self-describing
//! directory like a run (the scenario, provenance lines, CSV, Markdown, figures).
//!
//! `convergence` is the graded study of chapter "Beyond the paper" on the scenario's
//! own scene: nested uniform and graded families of bisection meshes, $k = T/n$,
//! reference-free increments to the next level with their fitted exponents, errors
//! against a finer graded reference, and the corner exponents the supports predict.

use crate::experiments::graded;
use crate::experiments::singular::{Edge, clamp_end_exponent, wedge_exponents};
use crate::geometry::Hold;
use crate::output::csv::Table;
use crate::output::rundir::RunDir;
use crate::scenario::Scenario;
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;
use std::path::PathBuf;

#[derive(clap::Subcommand)]
pub enum Study {
    /// Convergence in space and time on the scenario's own scene: a uniform and a
    /// graded family of nested meshes (newest-vertex bisection of the coarsest grid
    /// that resolves the scene; the graded one refined towards the singular points
    /// `evhi show` lists, exponent 0.4), h and k = T/n refined together. Writes
    /// convergence.csv (per level: unknowns, error at T against a finer graded
    /// reference, increments ||u_n - u_2n||_E / ||u_2n||_E at T and their maximum over
    /// time, observed orders in N_dof^(-1/2)), convergence.md (the table, the fitted
    /// exponents, the reference's own error estimate), singular.csv (each singular
    /// point, its kind and the corner exponent it predicts) and convergence.png/svg.
    ///
    /// Example: evhi study convergence --scenario data/scenarios/examples/cantilever.toml --quick --out runs/conv
    Convergence(ConvergenceArgs),
    /// The time error at a fixed mesh: backward Euler at k = T/N for N = 4, 8, …
    /// against the same mesh with a far finer step, the maximum over time and at T,
    /// orders, where the error peaks, and, where the damping is proportional
    /// (C = tau G), the scalar model of the relaxation layer beside it. Writes
    /// time_study.csv, time_study.md and time_study.png/svg.
    ///
    /// Example: evhi study time --scenario data/scenarios/examples/five_branch.toml --quick --out runs/time
    Time(TimeArgs),
    /// Which step solver fails where on the scenario's own law: every registered
    /// solver of the stability map at each mesh level n and time step k (certified,
    /// several solutions from Newton's other starts, failed, with its mean iterations),
    /// and per (n, k) the paper's smallness condition H(s) and the step convexity.
    /// Writes stability.csv, hypotheses.csv, stability.md and stability.png/svg.
    ///
    /// Example: evhi study stability --scenario data/scenarios/examples/cantilever.toml --quick --out runs/stab
    Stability(StabilityArgs),
}

#[derive(clap::Args)]
pub struct TimeArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long)]
    pub scenario: String,
    /// Mesh n = 16, N up to 256 and a reference with 16384 steps (seconds); without
    /// it n = 32, N up to 1024 and 32768 reference steps.
    #[arg(long)]
    pub quick: bool,
    /// Override the mesh level n (a multiple of 4 on which the scene resolves).
    #[arg(long)]
    pub n: Option<usize>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(clap::Args)]
pub struct StabilityArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long)]
    pub scenario: String,
    /// Levels n = 8, 16 and steps 1, 8 (seconds); without it n = 8, 16, 32 and steps
    /// 1, 2, 4, …, 64 (a steady problem always takes one step).
    #[arg(long)]
    pub quick: bool,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

#[derive(clap::Args)]
pub struct ConvergenceArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long)]
    pub scenario: String,
    /// Four levels per family and a reference at 32 times the coarsest n (seconds);
    /// without it six uniform and five graded levels and a reference at 64 times (a
    /// few minutes on the paper's scene).
    #[arg(long)]
    pub quick: bool,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: PathBuf,
}

pub fn run(study: Study) -> Result<(), Box<dyn std::error::Error>> {
    match study {
        Study::Convergence(args) => convergence(args),
        Study::Time(args) => time(args),
        Study::Stability(args) => stability(args),
    }
}

/// The coarsest n (4, 8, 16, …) whose grid resolves the scene.
fn coarsest(scn: &Scenario) -> Result<usize, crate::error::InputError> {
    let mut n = 4;
    loop {
        match scn.mesh(n) {
            Ok(_) => return Ok(n),
            Err(e) if n >= 256 => return Err(e),
            Err(_) => n *= 2,
        }
    }
}

/// The exponent a singular point predicts (the smallest real part in $(0, 1)$), or
/// NaN where the wedge analysis does not cover its holds (rollers).
fn predicted(s: &crate::geometry::Singularity, kappa: f64) -> f64 {
    let kappa_m = 3.0 - 4.0 * kappa;
    let edge = |h: Hold| match h {
        Hold::Clamped => Some(Edge::Clamped),
        Hold::Free => Some(Edge::Free),
        Hold::Rollers => None,
    };
    let (Some(a), Some(b)) = (edge(s.holds[0]), edge(s.holds[1])) else {
        return f64::NAN;
    };
    if !s.corner {
        return clamp_end_exponent(kappa_m).0;
    }
    wedge_exponents(std::f64::consts::FRAC_PI_2, kappa_m, [a, b])
        .first()
        .copied()
        .unwrap_or(f64::NAN)
}

/// Least-squares slope of $-2\,\ln v$ against $\ln N$ over the finite points.
fn fitted(dofs: &[f64], v: &[f64]) -> f64 {
    let pts: Vec<(f64, f64)> = dofs
        .iter()
        .zip(v)
        .filter(|(_, y)| y.is_finite() && **y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if pts.len() < 2 {
        return f64::NAN;
    }
    let m = pts.len() as f64;
    let (sx, sy) = pts.iter().fold((0.0, 0.0), |a, p| (a.0 + p.0, a.1 + p.1));
    let (mx, my) = (sx / m, sy / m);
    let (num, den) = pts.iter().fold((0.0, 0.0), |a, p| {
        (a.0 + (p.0 - mx) * (p.1 - my), a.1 + (p.0 - mx).powi(2))
    });
    -2.0 * num / den
}

fn convergence(args: ConvergenceArgs) -> Result<(), Box<dyn std::error::Error>> {
    let scn = Scenario::load(&args.scenario)?;
    let n0 = coarsest(&scn)?;
    let levels = |k: usize| (0..k).map(|j| n0 << j).collect::<Vec<_>>();
    let plan = if args.quick {
        graded::Plan {
            uniform: levels(4),
            graded: levels(4),
            n_ref: n0 * 32,
        }
    } else {
        graded::Plan {
            uniform: levels(6),
            graded: levels(5),
            n_ref: n0 * 64,
        }
    };
    let sing = scn.geometry.singularities();
    let points = scn.geometry.singular_points();
    let mut families = vec![("uniform".to_string(), vec![])];
    if !points.is_empty() {
        families.push(("graded".to_string(), points.clone()));
    }
    let out = RunDir::open(&args.out)?;
    let bar = ProgressBar::new(graded::units(&plan, families.len()) as u64).with_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:30}] {pos}/{len} {elapsed}")
            .expect("valid template")
            .progress_chars("=> "),
    );
    let log = |m: &str| {
        bar.set_message(m.to_string());
        bar.inc(1);
    };
    let (table, ref_dofs) =
        graded::compute(std::slice::from_ref(&scn), &families, &plan, &points, &log)?;
    bar.finish_and_clear();
    let command = crate::output::run::quote_args(std::env::args().skip(1));
    let header = format!(
        "produced by evhi {} `evhi {}`\n# scenario {}; families: {}; levels uniform {:?}, graded {:?}; k = T/n; reference: the graded family refined to n = {} ({} unknowns), k = T/{}; grading exponent {}; errors and increments relative, energy norm; orders in N_dof^(-1/2) (1 = order 1 in h on a uniform mesh)",
        env!("CARGO_PKG_VERSION"),
        crate::output::run::one_line(&command),
        scn.name,
        families
            .iter()
            .map(|f| f.0.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        plan.uniform,
        plan.graded,
        plan.n_ref,
        ref_dofs,
        plan.n_ref,
        graded::MU
    );
    let lines: Vec<String> = header.split("\n# ").map(str::to_string).collect();
    out.write_table("convergence.csv", &table, &lines)?;
    let kappa = scn.kappa;
    let sing_table = Table::new()
        .f64("x", sing.iter().map(|s| s.point[0]).collect())
        .f64("y", sing.iter().map(|s| s.point[1]).collect())
        .str(
            "kind",
            sing.iter()
                .map(|s| {
                    format!(
                        "{} {}-{}",
                        if s.corner { "corner" } else { "side" },
                        s.holds[0].name(),
                        s.holds[1].name()
                    )
                })
                .collect(),
        )
        .f64(
            "predicted_exponent",
            sing.iter().map(|s| predicted(s, kappa)).collect(),
        );
    out.write_table("singular.csv", &sing_table, &lines)?;
    // The Markdown summary, read back from the table just written.
    let df = crate::experiments::read_csv(&out.path("convergence.csv"))?;
    let fam = crate::experiments::col_str(&df, "family")?;
    let col = |c: &str| crate::experiments::col_f64(&df, c);
    let (n, dofs, err, inc, inc_max) = (
        col("n")?,
        col("dofs")?,
        col("rel_err_T_percent")?,
        col("increment_T_percent")?,
        col("increment_max_percent")?,
    );
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Convergence of `{}` ({})\n\n{}\n\n| family | n | unknowns | error at T, % | increment at T, % | max increment over t, % |\n|---|---|---|---|---|---|",
        scn.name,
        if args.quick { "quick" } else { "full" },
        lines.join(". ")
    );
    for i in 0..fam.len() {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.4} | {:.4} | {:.4} |",
            fam[i], n[i], dofs[i], err[i], inc[i], inc_max[i]
        );
    }
    let _ = writeln!(
        md,
        "\nFitted exponents (least squares of -2 ln v against ln N_dof over each family's levels):\n"
    );
    for (f, _) in &families {
        let rows: Vec<usize> = (0..fam.len()).filter(|&i| fam[i] == *f).collect();
        let pick = |v: &[f64]| rows.iter().map(|&i| v[i]).collect::<Vec<_>>();
        let d = pick(&dofs);
        let _ = writeln!(
            md,
            "- {f}: error at T {:.3}, increment at T {:.3}, max increment over t {:.3}",
            fitted(&d, &pick(&err)),
            fitted(&d, &pick(&inc)),
            fitted(&d, &pick(&inc_max))
        );
    }
    // The reference's own error, from the last family's increments.
    let last_family = &families.last().expect("a family").0;
    let rows: Vec<usize> = (0..fam.len()).filter(|&i| fam[i] == *last_family).collect();
    let d: Vec<f64> = rows.iter().map(|&i| dofs[i]).collect();
    let incs: Vec<f64> = rows.iter().map(|&i| inc[i]).collect();
    let p = fitted(&d, &incs);
    // The increment at level n is ||u_n - u_2n||: from it, one factor 2^-p per level
    // up to the reference, then the geometric sum of the increments beyond it.
    let (n_last, last_inc) = rows
        .iter()
        .rev()
        .map(|&i| (n[i], inc[i]))
        .find(|x| x.1.is_finite())
        .unwrap_or((f64::NAN, f64::NAN));
    let levels_on = (plan.n_ref as f64 / n_last).log2();
    let ref_estimate = last_inc * 2f64.powf(-p * levels_on) / (1.0 - 2f64.powf(-p)).max(1e-3);
    let _ = writeln!(
        md,
        "\nThe reference's own error at T, estimated from the {last_family} family's last increment ({last_inc:.4} %) \
         carried on at the fitted rate {p:.3} to n = {}: about {ref_estimate:.4} % (a geometric tail; \
         errors of that size or below are not resolved).\n",
        plan.n_ref
    );
    let _ = writeln!(
        md,
        "Singular points of the scene and the exponent each predicts (plane strain, Poisson ratio {kappa}; \
         NaN where rollers meet, which the wedge analysis here does not cover):\n"
    );
    if sing.is_empty() {
        let _ = writeln!(
            md,
            "- none: the supports leave no corner singularity, so order 1 is expected on uniform meshes"
        );
    }
    for s in &sing {
        let _ = writeln!(
            md,
            "- ({}, {}): {} {} meeting {}: exponent {:.4}",
            s.point[0],
            s.point[1],
            if s.corner {
                "corner,"
            } else {
                "inside a side,"
            },
            s.holds[0].name(),
            s.holds[1].name(),
            predicted(s, kappa)
        );
    }
    out.write("convergence.md", md.as_bytes())?;
    let toml = match crate::scenario::BUILTIN
        .iter()
        .find(|b| b.0 == args.scenario)
    {
        Some((_, text)) => text.to_string(),
        None => std::fs::read_to_string(&args.scenario)?,
    };
    out.write(
        "scenario.toml",
        format!(
            "# The scenario of this study, as read.\n# evhi {}\n{toml}",
            crate::output::run::one_line(&command)
        )
        .as_bytes(),
    )?;
    graded::draw(
        &out.path(""),
        "convergence",
        &out.path("convergence.csv"),
        std::slice::from_ref(&scn.name),
        &families.iter().map(|f| f.0.clone()).collect::<Vec<_>>(),
    )?;
    out.publish()?;
    eprint!("{md}");
    Ok(())
}

/// The scenario file's text (a built-in's compiled-in text).
fn scenario_text(name: &str) -> Result<String, std::io::Error> {
    match crate::scenario::BUILTIN.iter().find(|b| b.0 == name) {
        Some((_, text)) => Ok(text.to_string()),
        None => std::fs::read_to_string(name),
    }
}

/// A progress bar of `len` units.
fn bar(len: u64) -> ProgressBar {
    ProgressBar::new(len).with_style(
        ProgressStyle::with_template("{spinner} {msg} [{bar:30}] {pos}/{len} {elapsed}")
            .expect("valid template")
            .progress_chars("=> "),
    )
}

/// The experiments' context writing into the study's staged directory, its
/// provenance naming the study's command line.
fn study_ctx(out: &RunDir, quick: bool, progress: &ProgressBar) -> crate::experiments::Ctx {
    crate::experiments::Ctx {
        quick,
        data: out.path(""),
        figures: out.path(""),
        verbose: false,
        progress: Some(progress.clone()),
        reference: None,
        command: Some(crate::output::run::one_line(
            &crate::output::run::quote_args(std::env::args().skip(1)),
        )),
        experiment: "",
    }
}

/// Writes the scenario as read into the study's directory.
fn write_scenario(out: &RunDir, name: &str) -> Result<(), Box<dyn std::error::Error>> {
    let command = crate::output::run::quote_args(std::env::args().skip(1));
    out.write(
        "scenario.toml",
        format!(
            "# The scenario of this study, as read.\n# evhi {}\n{}",
            crate::output::run::one_line(&command),
            scenario_text(name)?
        )
        .as_bytes(),
    )?;
    Ok(())
}

fn time(args: TimeArgs) -> Result<(), Box<dyn std::error::Error>> {
    use crate::experiments::time;
    let scn = Scenario::load(&args.scenario)?;
    if scn.problem == crate::scenario::Problem::Steady {
        return Err(crate::error::InputError::field(
            "scenario",
            &scn.name,
            "a scenario with a time evolution (problem = \"steady\" is one solve: no time error)",
        )
        .into());
    }
    let mut plan = time::plan(args.quick);
    if let Some(n) = args.n {
        plan.n = n;
    }
    scn.mesh(plan.n)?;
    let out = RunDir::open(&args.out)?;
    let progress = bar(0);
    let ctx = study_ctx(&out, args.quick, &progress);
    let rows = time::study_of(
        &plan,
        &ctx,
        &[(scn.name.clone(), scn.history.to_string(), scn.clone())],
    )?;
    progress.finish_and_clear();
    time::write_rows(&ctx, &plan, &rows, "time_study.csv", "history")?;
    let mut md = format!(
        "# Time error of `{}` at n = {} ({})\n\nReference: {} steps on the same mesh. Errors relative, energy norm.\n\n\
         | N | k | max over t, % | order | at T, % | order | model max, % | model T, % | t of max |\n|---|---|---|---|---|---|---|---|---|\n",
        scn.name,
        plan.n,
        if args.quick { "quick" } else { "full" },
        plan.n_ref
    );
    for (i, r) in rows.iter().enumerate() {
        let order = |a: f64, b: f64| if i == 0 { f64::NAN } else { (b / a).log2() };
        let _ = writeln!(
            md,
            "| {} | {:.4e} | {:.4} | {:.3} | {:.4} | {:.3} | {:.4} | {:.4} | {:.4} |",
            r.steps,
            r.t_end / r.steps as f64,
            100.0 * r.err_max,
            order(
                r.err_max,
                if i > 0 { rows[i - 1].err_max } else { f64::NAN }
            ),
            100.0 * r.err_t,
            order(r.err_t, if i > 0 { rows[i - 1].err_t } else { f64::NAN }),
            100.0 * r.model_max,
            100.0 * r.model_t,
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
    write_scenario(&out, &args.scenario)?;
    out.publish()?;
    eprint!("{md}");
    Ok(())
}

/// The time study's figure: the error (max over t and at T) against N, with the
/// scalar model dashed where there is one.
/// A curve: label, (N, error %) points, colour, dashed (the model).
type Curve = (String, Vec<(f64, f64)>, plotters::style::RGBColor, bool);

struct TimeFig {
    series: Vec<Curve>,
    title: String,
}

impl crate::experiments::plot::Figure for TimeFig {
    fn draw<DB: plotters::prelude::DrawingBackend>(
        &self,
        root: &plotters::prelude::DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        use crate::experiments::plot::{e2s, legend};
        use plotters::prelude::*;
        let pts: Vec<(f64, f64)> = self.series.iter().flat_map(|s| s.1.clone()).collect();
        let (x0, x1) = pts
            .iter()
            .fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.0), a.1.max(p.0)));
        let (y0, y1) = pts
            .iter()
            .fold((f64::INFINITY, 0.0f64), |a, p| (a.0.min(p.1), a.1.max(p.1)));
        if pts.is_empty() {
            return Err("no positive error to draw".into());
        }
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(45)
            .y_label_area_size(80)
            .build_cartesian_2d(
                (x0 / 1.5..x1 * 1.5).log_scale(),
                (y0 / 3.0..y1 * 3.0).log_scale(),
            )
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("time steps N")
            .y_desc("relative energy error, %")
            .label_style(("sans-serif", 17))
            .draw()
            .map_err(e2s)?;
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
    rows: &[crate::experiments::time::Row],
    n: usize,
) -> Result<(), crate::experiments::ExpError> {
    use plotters::style::RGBColor;
    let pick = |f: &dyn Fn(&crate::experiments::time::Row) -> f64| -> Vec<(f64, f64)> {
        rows.iter()
            .map(|r| (r.steps as f64, 100.0 * f(r)))
            .filter(|p| p.1.is_finite() && p.1 > 0.0)
            .collect()
    };
    let (blue, red) = (RGBColor(0, 114, 178), RGBColor(213, 94, 0));
    let mut series = vec![
        ("max over t".to_string(), pick(&|r| r.err_max), blue, false),
        ("at T".to_string(), pick(&|r| r.err_t), red, false),
    ];
    for (label, f, c) in [
        (
            "model, max over t",
            (|r: &crate::experiments::time::Row| r.model_max) as fn(&_) -> f64,
            blue,
        ),
        (
            "model, at T",
            |r: &crate::experiments::time::Row| r.model_t,
            red,
        ),
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
    crate::experiments::plot::both(dir, "time_study", (900, 650), &TimeFig { series, title })
}

fn stability(args: StabilityArgs) -> Result<(), Box<dyn std::error::Error>> {
    use crate::experiments::stability::map::{MapFigure, map_cell, solvers};
    let scn = Scenario::load(&args.scenario)?;
    let steady = scn.problem == crate::scenario::Problem::Steady;
    let n0 = coarsest(&scn)?.max(8);
    let levels: Vec<usize> = if args.quick {
        vec![n0, 2 * n0]
    } else {
        vec![n0, 2 * n0, 4 * n0]
    };
    let steps: Vec<usize> = if steady {
        vec![1]
    } else if args.quick {
        vec![1, 8]
    } else {
        vec![1, 2, 4, 8, 16, 32, 64]
    };
    let solvers = solvers();
    let out = RunDir::open(&args.out)?;
    let progress = bar((levels.len() * steps.len() * (solvers.len() + 1)) as u64);
    let mut cells = vec![];
    let mut hyp = vec![];
    for &n in &levels {
        for &st in &steps {
            let h_s = crate::show::Smallness::of(&scn, n)?;
            let curvature = crate::scheme::step_curvature(&scn, n, st)?;
            hyp.push((n, st, h_s, curvature));
            progress.inc(1);
            for &solver in &solvers {
                progress.set_message(format!("n = {n}, steps = {st}, {solver}"));
                cells.push((n, map_cell(&scn, f64::NAN, n, st, solver)));
                progress.inc(1);
            }
        }
    }
    progress.finish_and_clear();
    let command =
        crate::output::run::one_line(&crate::output::run::quote_args(std::env::args().skip(1)));
    let lines = vec![
        format!(
            "produced by evhi {} `evhi {command}`",
            env!("CARGO_PKG_VERSION")
        ),
        format!(
            "scenario {}; levels n = {levels:?}, steps {steps:?}, T = {}; outcome: certified (every step), several solutions (newton from other starts differs by > 1e-6), converged (overshoots g) for the uncertified penalty, failed (with the step); hessian_min = lambda_min(S + k diag(w) c_min) (> 0: every step strictly convex)",
            scn.name, scn.t_end
        ),
    ];
    let t = Table::new()
        .u64("n", cells.iter().map(|c| c.0 as u64).collect())
        .str(
            "solver",
            cells.iter().map(|c| c.1.solver.to_string()).collect(),
        )
        .u64("steps", cells.iter().map(|c| c.1.steps as u64).collect())
        .f64(
            "k",
            cells.iter().map(|c| scn.t_end / c.1.steps as f64).collect(),
        )
        .str(
            "outcome",
            cells.iter().map(|c| c.1.outcome.clone()).collect(),
        )
        .u64(
            "failed_step",
            cells.iter().map(|c| c.1.failed_step).collect(),
        )
        .f64(
            "mean_iterations",
            cells.iter().map(|c| c.1.mean_iterations).collect(),
        )
        .f64(
            "max_certificate_or_residual",
            cells.iter().map(|c| c.1.certificate).collect(),
        )
        .f64(
            "multistart_spread",
            cells.iter().map(|c| c.1.spread).collect(),
        );
    out.write_table("stability.csv", &t, &lines)?;
    let h = Table::new()
        .u64("n", hyp.iter().map(|r| r.0 as u64).collect())
        .u64("steps", hyp.iter().map(|r| r.1 as u64).collect())
        .f64("beta_B", hyp.iter().map(|r| r.2.beta_b).collect())
        .f64("m_trace_norm_sq", hyp.iter().map(|r| r.2.rhs()).collect())
        .str(
            "H_s",
            hyp.iter()
                .map(|r| (if r.2.holds() { "holds" } else { "fails" }).to_string())
                .collect(),
        )
        .f64("step_curvature_min", hyp.iter().map(|r| r.3).collect())
        .str(
            "steps_convex",
            hyp.iter()
                .map(|r| (if r.3 > 0.0 { "yes" } else { "no" }).to_string())
                .collect(),
        );
    out.write_table("hypotheses.csv", &h, &lines)?;
    let mut md = format!(
        "# Step solvers on `{}` ({})\n\n| n | steps | H(s) | smallest step curvature | {} |\n|---|---|---|---|{}\n",
        scn.name,
        if args.quick { "quick" } else { "full" },
        solvers.join(" | "),
        "---|".repeat(solvers.len())
    );
    for (n, st, h_s, curv) in &hyp {
        let outcomes: Vec<String> = solvers
            .iter()
            .map(|s| {
                cells
                    .iter()
                    .find(|c| c.0 == *n && c.1.steps == *st && c.1.solver == *s)
                    .map_or(String::new(), |c| c.1.outcome.clone())
            })
            .collect();
        let _ = writeln!(
            md,
            "| {n} | {st} | {} | {curv:.4e} | {} |",
            if h_s.holds() { "holds" } else { "fails" },
            outcomes.join(" | ")
        );
    }
    for (at, jump) in scn.law.down_jumps() {
        let _ = writeln!(md, "\nH(j) fails: p jumps down by {} at s = {at}.", -jump);
    }
    out.write("stability.md", md.as_bytes())?;
    // The map: one panel per solver, k across, n down.
    let fig = MapFigure {
        cells: cells
            .iter()
            .map(|(n, c)| {
                (
                    c.solver.to_string(),
                    scn.t_end / c.steps as f64,
                    *n as f64,
                    c.outcome.clone(),
                    c.mean_iterations,
                    hyp.iter()
                        .find(|r| r.0 == *n && r.1 == c.steps)
                        .map_or(f64::NAN, |r| r.3),
                )
            })
            .collect(),
        title: format!(
            "Where step solvers fail on {}, by time step k and mesh n (numbers: mean iterations per step)",
            scn.name
        ),
        row_desc: "mesh: segments n".into(),
        row_label: |n| format!("{n:.0}"),
    };
    crate::experiments::plot::both(&out.path(""), "stability", (1100, 1150), &fig)?;
    write_scenario(&out, &args.scenario)?;
    out.publish()?;
    eprint!("{md}");
    Ok(())
}
