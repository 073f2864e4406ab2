//! The time discretisation error at a fixed mesh: backward Euler's error
//! $\max_n \|u^{h}(t_n) - u^{hk}_n\|_E$ and $\|u^h(T) - u^{hk}_N\|_E$ for $k = T/N$,
//! measured against the same mesh run with a much finer step $k_{\text{ref}}$, for
//! several load histories (see [`crate::history`]).
//!
//! Why it matters: the paper's constants give $\mathcal C = 0.07\,\mathcal G$, so away
//! from contact every mode relaxes with the one time constant $\tau = 0.07$. A load
//! applied in full at $t = 0$ (incompatible data: H(f) and H(0) fail) starts an
//! initial layer $u(t) \approx (1 - e^{-t/\tau})\,u_\infty$ that backward Euler cannot
//! follow until $k \lesssim \tau$. For each constant-load level the scalar model
//! $\tau \dot y + y = 1$, $y(0) = 0$, solved by backward Euler,
//! $y_n = 1 - (1 + k/\tau)^{-n}$, predicts the relative error without any mesh; the
//! table carries it beside the measurement.

use super::plot::{Figure, both, circle_legend, dashed_legend, e2s, legend};
use super::{Ctx, ExpError, col_f64, col_str, read_csv};
use crate::history::History;
use crate::norms::energy_norm;
use crate::output::csv::Table;
use crate::scenario::Scenario;
use crate::scheme::{Discretisation, Settings};
use plotters::prelude::*;

/// The load scenarios of the study.
pub const SCENARIOS: [&str; 2] = ["figure", "literal"];

// ANCHOR: histories
/// The load histories of the study: (a) the shipped constant load; (b) a compatible
/// ramp over the whole interval, $\varphi(t) = t$; (c) a compatible ramp to full load
/// at $t = 1/4$, during which `figure`'s contact nodes reach the limit $g$.
pub fn histories() -> [(&'static str, History); 3] {
    [
        ("a_constant", History::Constant),
        ("b_ramp1", History::Ramp { t_r: 1.0 }),
        ("c_ramp0.25", History::Ramp { t_r: 0.25 }),
    ]
}
// ANCHOR_END: histories

/// Mesh, step levels and reference of a study.
#[derive(Debug, Clone)]
pub struct Plan {
    pub n: usize,
    pub levels: Vec<usize>,
    pub n_ref: usize,
}

pub fn plan(quick: bool) -> Plan {
    if quick {
        Plan {
            n: 16,
            levels: vec![4, 8, 16, 32, 64, 128, 256],
            n_ref: 16384,
        }
    } else {
        Plan {
            n: 32,
            levels: vec![4, 8, 16, 32, 64, 128, 256, 512, 1024],
            n_ref: 32768,
        }
    }
}

// ANCHOR: scalar_model
/// The scalar model of the layer: $\tau\dot y + y = \varphi(t)$, $y(0) = 0$, by backward
/// Euler with $N$ steps on $[0, T]$, $y_n = (\tau y_{n-1} + k\varphi(t_n))/(\tau + k)$,
/// against the same model with $N_{\text{ref}}$ steps, measured as the study measures
/// the field: (max over the level's times of the error) / (max of the reference there),
/// and the error at $T$ over $y_{\text{ref}}(T)$.
pub fn scalar_model(tau: f64, history: &History, t_end: f64, n: usize, n_ref: usize) -> (f64, f64) {
    let path = |steps: usize| -> Vec<f64> {
        let k = t_end / steps as f64;
        let mut y = vec![0.0; steps + 1];
        for i in 1..=steps {
            y[i] = (tau * y[i - 1] + k * history.phi(i as f64 * k)) / (tau + k);
        }
        y
    };
    let (yk, yr) = (path(n), path(n_ref));
    let ratio = n_ref / n;
    let (mut e_max, mut y_max) = (0.0f64, 0.0f64);
    for i in 1..=n {
        e_max = e_max.max((yk[i] - yr[i * ratio]).abs());
        y_max = y_max.max(yr[i * ratio].abs());
    }
    (e_max / y_max, (yk[n] - yr[n_ref]).abs() / yr[n_ref].abs())
}
// ANCHOR_END: scalar_model

/// One row of the study.
#[derive(Debug, Clone)]
pub struct Row {
    pub scenario: String,
    pub history: String,
    pub steps: usize,
    pub err_max: f64,
    pub err_t: f64,
    pub model_max: f64,
    pub model_t: f64,
    /// First time at which a contact node of the reference run sits at the limit $g$.
    pub t_first_limit: f64,
    /// The level's time $t_n$ where the error is largest.
    pub t_err_max: f64,
    /// The relaxation time $\tau$ and the limit $g$ of the run.
    pub tau: f64,
    pub g: f64,
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let plan = plan(ctx.quick);
    let rows = study(&plan, ctx)?;
    let path = write_rows(ctx, &plan, &rows, "time_study.csv", "history")?;
    write_markdown(ctx, &path, &plan)?;
    draw(ctx, &path)?;
    // One batch per material: a batch shares its step matrix.
    let all = controls()?;
    let mut rows = vec![];
    let mut materials: Vec<(f64, f64)> = vec![];
    for c in &all {
        if !materials.contains(&(c.2.alpha, c.2.beta)) {
            materials.push((c.2.alpha, c.2.beta));
        }
    }
    for m in materials {
        let group: Vec<_> = all
            .iter()
            .filter(|c| (c.2.alpha, c.2.beta) == m)
            .cloned()
            .collect();
        rows.extend(study_of(&plan, ctx, &group)?);
    }
    let path = write_rows(ctx, &plan, &rows, "time_controls.csv", "variant")?;
    draw_controls(ctx, &path)
}

/// Writes the rows of a study as `file`; `label` names the column of the row's label.
fn write_rows(
    ctx: &Ctx,
    plan: &Plan,
    rows: &[Row],
    file: &str,
    label: &str,
) -> Result<std::path::PathBuf, ExpError> {
    let params = format!(
        "fixed mesh n = 1/h = {}; k = T/N for N in {:?}; reference N_ref = {} on the same mesh; solver newton; \
         errors in the energy norm relative to the reference: max over the level's times t_n of ||u_ref(t_n) - u_n||_E \
         / max there of ||u_ref(t_n)||_E, and at t = T; model_*: the scalar backward-Euler model of the layer \
         (tau = C/G of the row), same measure; t_of_err_max: the level's time where the error is largest; \
         t_first_limit: first reference time with a contact node at u_nu = g (NaN: never){}",
        plan.n,
        plan.levels,
        plan.n_ref,
        if label == "variant" {
            "; variants: alpha and beta scaled by 0.1 and 10 (tau = C/G scaled, E kept; constant load), and figure with g = 1 (no node lands) under the constant load and the ramp to t = 1"
        } else {
            ""
        },
    );
    let order = |v: &[f64], i: usize| -> f64 {
        if i == 0
            || rows[i - 1].scenario != rows[i].scenario
            || rows[i - 1].history != rows[i].history
        {
            f64::NAN
        } else {
            (v[i - 1] / v[i]).log2()
        }
    };
    let em: Vec<f64> = rows.iter().map(|r| r.err_max).collect();
    let et: Vec<f64> = rows.iter().map(|r| r.err_t).collect();
    let t = Table::new()
        .str(
            "scenario",
            rows.iter().map(|r| r.scenario.clone()).collect(),
        )
        .str(label, rows.iter().map(|r| r.history.clone()).collect())
        .f64("tau", rows.iter().map(|r| r.tau).collect())
        .f64("g", rows.iter().map(|r| r.g).collect())
        .u64("steps", rows.iter().map(|r| r.steps as u64).collect())
        .f64("k", rows.iter().map(|r| 1.0 / r.steps as f64).collect())
        .f64(
            "k_over_tau",
            rows.iter().map(|r| 1.0 / r.steps as f64 / r.tau).collect(),
        )
        .f64(
            "rel_err_max_percent",
            em.iter().map(|e| 100.0 * e).collect(),
        )
        .f64(
            "order_max",
            (0..rows.len()).map(|i| order(&em, i)).collect(),
        )
        .f64("rel_err_T_percent", et.iter().map(|e| 100.0 * e).collect())
        .f64("order_T", (0..rows.len()).map(|i| order(&et, i)).collect())
        .f64(
            "model_max_percent",
            rows.iter().map(|r| 100.0 * r.model_max).collect(),
        )
        .f64(
            "model_T_percent",
            rows.iter().map(|r| 100.0 * r.model_t).collect(),
        )
        .f64("t_of_err_max", rows.iter().map(|r| r.t_err_max).collect())
        .f64(
            "t_first_limit",
            rows.iter().map(|r| r.t_first_limit).collect(),
        );
    ctx.write(file, &t, "time", &params)
}

/// `x` to three significant digits, plain where that reads well.
pub fn sig3(x: f64) -> String {
    if !x.is_finite() {
        return "–".into();
    }
    let a = x.abs();
    if a == 0.0 {
        "0".into()
    } else if (0.01..1000.0).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.2e}")
    }
}

/// `data/time_study.md`: the study as tables for the book (three significant digits).
fn write_markdown(ctx: &Ctx, path: &std::path::Path, plan: &Plan) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, hi) = (col_str(&df, "scenario")?, col_str(&df, "history")?);
    let steps = col_f64(&df, "steps")?;
    let (em, om, mm) = (
        col_f64(&df, "rel_err_max_percent")?,
        col_f64(&df, "order_max")?,
        col_f64(&df, "model_max_percent")?,
    );
    let (et, ot) = (col_f64(&df, "rel_err_T_percent")?, col_f64(&df, "order_T")?);
    let row = |s: &str, h: &str, n: usize| {
        (0..sc.len())
            .find(|&i| sc[i] == s && hi[i] == h && steps[i] as usize == n)
            .expect("every scenario, history and level")
    };
    let with_order = |e: f64, o: f64| {
        if o.is_finite() {
            format!("{} ({:.2})", sig3(e), o)
        } else {
            sig3(e)
        }
    };
    let tau = Scenario::load("figure")?
        .relaxation_time()
        .unwrap_or(f64::NAN);
    let hist = histories();
    let mut md = format!(
        "<!-- {} -->\n\n",
        ctx.provenance("time", &format!("n = {}, N_ref = {}", plan.n, plan.n_ref))
            .join(" ")
    );
    for s in SCENARIOS {
        md += &format!(
            "**`{s}`, maximum over time.** Relative error in percent (observed order), \
             and the scalar model's prediction, for (a) the constant load, (b) the ramp to \
             t = 1, (c) the ramp to t = 1/4; h = 1/{}, reference N = {}.\n\n\
             | k | k/τ | (a) | model | (b) | model | (c) | model |\n\
             |---|---|---|---|---|---|---|---|\n",
            plan.n, plan.n_ref
        );
        for &n in &plan.levels {
            md += &format!("| 1/{n} | {} |", sig3(1.0 / n as f64 / tau));
            for (h, _) in &hist {
                let i = row(s, h, n);
                md += &format!(" {} | {} |", with_order(em[i], om[i]), sig3(mm[i]));
            }
            md += "\n";
        }
        md += "\n";
    }
    md += &format!(
        "**At t = T.** Relative error in percent (observed order); h = 1/{}.\n\n\
         | k | `literal` (a) | (b) | (c) | `figure` (a) | (b) | (c) |\n\
         |---|---|---|---|---|---|---|\n",
        plan.n
    );
    for &n in &plan.levels {
        md += &format!("| 1/{n} |");
        for s in SCENARIOS.iter().rev() {
            for (h, _) in &hist {
                let i = row(s, h, n);
                md += &format!(" {} |", with_order(et[i], ot[i]));
            }
        }
        md += "\n";
    }
    // The scalar model against Table 1's own k-family reference (N_ref = 512).
    md += "\n**The scalar model against N_ref = 512**, the reference of Table 1's k family \
           (constant load, maximum over time, percent).\n\n| N | 4 | 8 | 16 | 32 | 64 | 128 |\n\
           |---|---|---|---|---|---|---|\n| model |";
    for n in [4, 8, 16, 32, 64, 128] {
        md += &format!(
            " {} |",
            sig3(100.0 * scalar_model(tau, &History::Constant, 1.0, n, 512).0)
        );
    }
    md += "\n";
    ctx.write_file(&ctx.data_path("time_study.md"), md.as_bytes())
}

/// Runs every scenario and history at every level (one batched run per level).
pub fn study(plan: &Plan, ctx: &Ctx) -> Result<Vec<Row>, ExpError> {
    let mut scns = vec![];
    for name in SCENARIOS {
        for (label, h) in histories() {
            let mut s = Scenario::load(name)?.with_history(h)?;
            s.name = format!("{name}/{label}");
            scns.push((name.to_string(), label.to_string(), s));
        }
    }
    study_of(plan, ctx, &scns)
}

// ANCHOR: controls
/// The controls of the layer, all under the constant load: the relaxation time
/// $\tau = \mathcal C/\mathcal G$ scaled by 0.1 and 10 (the viscosity $\alpha, \beta$
/// scaled, the elasticity kept) for `literal` and `figure`, with the shipped $\tau$ as
/// the baseline, and `figure` with $g = 1$, ten times the shipped limit, so that no
/// contact node lands on it, under the constant load and under the ramp to $t = 1$.
pub fn controls() -> Result<Vec<(String, String, Scenario)>, ExpError> {
    let mut out = vec![];
    for name in SCENARIOS {
        for scale in [0.1, 1.0, 10.0] {
            let mut s = Scenario::load(name)?;
            s.alpha *= scale;
            s.beta *= scale;
            let tau = s.relaxation_time().unwrap_or(f64::NAN);
            let label = format!("tau = {}", sig3(tau));
            s.name = format!("{name}/{label}");
            out.push((name.to_string(), label, s));
        }
    }
    for (label, history) in [
        ("no landing (g = 1)", History::Constant),
        (
            "no landing (g = 1) under the ramp to 1",
            History::Ramp { t_r: 1.0 },
        ),
    ] {
        let mut s = Scenario::load("figure")?
            .with_g(1.0)?
            .with_history(history)?;
        s.name = format!("figure/{label}");
        out.push(("figure".into(), label.into(), s));
    }
    Ok(out)
}
// ANCHOR_END: controls

/// Runs the scenarios `scns` (scenario name, label, scenario) at every level.
pub fn study_of(
    plan: &Plan,
    ctx: &Ctx,
    scns: &[(String, String, Scenario)],
) -> Result<Vec<Row>, ExpError> {
    let batch: Vec<Scenario> = scns.iter().map(|s| s.2.clone()).collect();
    let disc = Discretisation::new(&batch[0], plan.n)?;
    let n_max = *plan.levels.iter().max().expect("levels");
    if !plan.n_ref.is_multiple_of(n_max) || plan.levels.iter().any(|l| !n_max.is_multiple_of(*l)) {
        return Err(crate::error::InputError::field(
            "time study levels",
            format!("{:?} / {}", plan.levels, plan.n_ref),
            "levels that divide the finest, which divides the reference",
        )
        .into());
    }
    // The reference at the times of the finest level, and when nodes first reach g.
    ctx.add_units(1 + plan.levels.len());
    ctx.log(&format!(
        "time study: reference N = {} at n = {}",
        plan.n_ref, plan.n
    ));
    let stride = plan.n_ref / n_max;
    let nb = batch.len();
    let mut refs: Vec<Vec<Vec<f64>>> = vec![vec![vec![0.0; disc.dofs.count]]; nb];
    let mut first_limit = vec![f64::NAN; nb];
    let opt = Settings::new(plan.n, plan.n_ref);
    super::run_newton_batch_with(&batch, &opt, &mut |i, step, t, u| {
        if step % stride == 0 {
            refs[i].push(u.to_vec());
        }
        let g = batch[i].g;
        if first_limit[i].is_nan() && disc.contact_dofs.iter().any(|&d| g - (-u[d]) <= 1e-8 * g) {
            first_limit[i] = t;
        }
    })?;
    let ref_norms: Vec<Vec<f64>> = refs
        .iter()
        .map(|r| r.iter().map(|u| energy_norm(&disc.b, u)).collect())
        .collect();
    let mut rows = vec![];
    for &steps in &plan.levels {
        ctx.log(&format!("time study: N = {steps}"));
        let ratio = n_max / steps;
        let mut e_max = vec![0.0f64; nb];
        let mut r_max = vec![0.0f64; nb];
        let mut e_t = vec![0.0f64; nb];
        let mut t_max = vec![f64::NAN; nb];
        let opt = Settings::new(plan.n, steps);
        super::run_newton_batch_with(&batch, &opt, &mut |i, step, t, u| {
            let j = step * ratio;
            let diff: Vec<f64> = u.iter().zip(&refs[i][j]).map(|(a, b)| a - b).collect();
            let e = energy_norm(&disc.b, &diff);
            if e > e_max[i] {
                (e_max[i], t_max[i]) = (e, t);
            }
            r_max[i] = r_max[i].max(ref_norms[i][j]);
            if step == steps {
                e_t[i] = e / ref_norms[i][j];
            }
        })?;
        for (i, (name, label, s)) in scns.iter().enumerate() {
            let (model_max, model_t) = match s.relaxation_time() {
                Some(tau) => scalar_model(tau, &s.history, s.t_end, steps, plan.n_ref),
                None => (f64::NAN, f64::NAN),
            };
            rows.push(Row {
                scenario: name.clone(),
                history: label.clone(),
                steps,
                err_max: e_max[i] / r_max[i],
                err_t: e_t[i],
                model_max,
                model_t,
                t_first_limit: first_limit[i],
                t_err_max: t_max[i],
                tau: s.relaxation_time().unwrap_or(f64::NAN),
                g: s.g,
            });
        }
    }
    // Group by scenario and history, levels ascending within each.
    rows.sort_by(|a, b| {
        (a.scenario.as_str(), a.history.as_str(), a.steps).cmp(&(
            b.scenario.as_str(),
            b.history.as_str(),
            b.steps,
        ))
    });
    Ok(rows)
}

/// Okabe–Ito colours (safe for colour-blind readers), one per history.
const COLOURS: [RGBColor; 3] = [
    RGBColor(213, 94, 0),
    RGBColor(0, 114, 178),
    RGBColor(0, 158, 115),
];

/// A plotted series: label, points, colour index (the history), marker (0 circle for
/// `figure`, 1 triangle for `literal`) and whether it is the dashed scalar model.
type Series = (String, Vec<(f64, f64)>, usize, usize, bool);

struct TimeFig {
    series: Vec<Series>,
    title: String,
    levels: Vec<f64>,
    /// Room above the data for the legend, as a factor on the largest value.
    headroom: f64,
}

fn draw(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, hi) = (col_str(&df, "scenario")?, col_str(&df, "history")?);
    let k = col_f64(&df, "k")?;
    let mut levels: Vec<f64> = k.clone();
    levels.sort_by(f64::total_cmp);
    levels.dedup();
    for (which, col, model) in [
        ("max", "rel_err_max_percent", "model_max_percent"),
        ("T", "rel_err_T_percent", "model_T_percent"),
    ] {
        let (e, m) = (col_f64(&df, col)?, col_f64(&df, model)?);
        let mut series = vec![];
        for (si, s) in SCENARIOS.iter().enumerate() {
            for (hi_i, (label, _)) in histories().iter().enumerate() {
                let pts: Vec<(f64, f64)> = (0..k.len())
                    .filter(|&i| sc[i] == *s && hi[i] == *label && e[i] > 0.0)
                    .map(|i| (k[i], e[i]))
                    .collect();
                series.push((
                    format!("{s}, {}", label.replace('_', ") ")),
                    pts,
                    hi_i,
                    si,
                    false,
                ));
            }
        }
        for (hi_i, (label, _)) in histories().iter().enumerate() {
            let pts: Vec<(f64, f64)> = (0..k.len())
                .filter(|&i| sc[i] == "literal" && hi[i] == *label && m[i] > 0.0)
                .map(|i| (k[i], m[i]))
                .collect();
            let name = if hi_i == 0 {
                "scalar model (dashed), tau = 0.07".to_string()
            } else {
                String::new()
            };
            series.push((name, pts, hi_i, 9, true));
        }
        let title = if which == "max" {
            "Time error at fixed h: max over t"
        } else {
            "Time error at fixed h: at t = T"
        };
        let fig = TimeFig {
            series,
            title: title.into(),
            levels: levels.clone(),
            headroom: if which == "max" { 40.0 } else { 1000.0 },
        };
        both(
            &ctx.figures,
            &format!("time_study_{which}"),
            (900, 700),
            &fig,
        )?;
    }
    Ok(())
}

impl Figure for TimeFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        let ys: Vec<f64> = self
            .series
            .iter()
            .flat_map(|s| s.1.iter().map(|p| p.1))
            .collect();
        let ymin = ys.iter().copied().fold(f64::INFINITY, f64::min);
        let ymax = ys.iter().copied().fold(0.0, f64::max);
        let (xmin, xmax) = (self.levels[0], self.levels[self.levels.len() - 1]);
        let levels = self.levels.clone();
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 28))
            .margin(15)
            .x_label_area_size(60)
            .y_label_area_size(90)
            .build_cartesian_2d(
                (xmin / 1.4..xmax * 1.4).log_scale().with_key_points(levels),
                (ymin / 3.0..ymax * self.headroom).log_scale(),
            )
            .map_err(e2s)?;
        chart
            .configure_mesh()
            .x_desc("time step k")
            .y_desc("relative error in energy norm [%]")
            .x_label_formatter(&|x| format!("1/{}", (1.0 / x).round()))
            .y_label_formatter(&|y| {
                if (1e-3..1e3).contains(y) {
                    format!("{}", (y * 1e6).round() / 1e6)
                } else {
                    format!("{y:.0e}")
                }
            })
            .label_style(("sans-serif", 20))
            .axis_desc_style(("sans-serif", 22))
            .draw()
            .map_err(e2s)?;
        for (label, pts, ci, marker, dashed) in &self.series {
            if pts.is_empty() {
                continue;
            }
            let c = COLOURS[*ci];
            let width = if *dashed {
                2
            } else if *marker == 0 {
                3
            } else {
                1
            };
            let style = c.stroke_width(width);
            let m = *marker;
            if *dashed {
                let drawn = chart
                    .draw_series(DashedLineSeries::new(pts.clone(), 8, 6, style))
                    .map_err(e2s)?;
                if !label.is_empty() {
                    let grey = RGBColor(60, 60, 60).stroke_width(2);
                    drawn.label(label.clone()).legend(move |(x, y)| {
                        EmptyElement::at((x, y))
                            + PathElement::new(vec![(0, 0), (10, 0)], grey)
                            + PathElement::new(vec![(16, 0), (24, 0)], grey)
                    });
                }
                continue;
            }
            chart
                .draw_series(LineSeries::new(pts.clone(), style))
                .map_err(e2s)?;
            if m == 0 {
                chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 6, c.filled())))
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |xy| circle_legend(xy, 12, style, 6, c));
            } else {
                chart
                    .draw_series(
                        pts.iter()
                            .map(|&p| TriangleMarker::new(p, 7, c.stroke_width(2))),
                    )
                    .map_err(e2s)?
                    .label(label.clone())
                    .legend(move |(x, y)| {
                        EmptyElement::at((x + 12, y))
                            + PathElement::new(vec![(-12, 0), (12, 0)], style)
                            + TriangleMarker::new((0, 0), 7, c.stroke_width(2))
                    });
            }
        }
        // The relaxation time: backward Euler follows the layer only for k well below it.
        let tau = 0.07;
        let (y0, y1) = (ymin / 3.0, ymax * self.headroom);
        chart
            .draw_series(DashedLineSeries::new(
                vec![(tau, y0), (tau, y1)],
                4,
                4,
                RGBColor(150, 150, 150).stroke_width(1),
            ))
            .map_err(e2s)?;
        chart
            .draw_series(std::iter::once(Text::new(
                "k = tau",
                (tau * 1.05, y0 * 1.6),
                ("sans-serif", 18).into_font().color(&RGBColor(90, 90, 90)),
            )))
            .map_err(e2s)?;
        // Slope-1 guide through the last point of the first compatible series.
        if let Some(&(x0, y0)) = self.series.get(1).and_then(|s| s.1.last()) {
            let guide = vec![(x0, y0 / 2.5), (x0 * 16.0, y0 / 2.5 * 16.0)];
            chart
                .draw_series(DashedLineSeries::new(
                    guide,
                    3,
                    5,
                    RGBColor(90, 90, 90).stroke_width(1),
                ))
                .map_err(e2s)?
                .label("slope 1")
                .legend(|xy| dashed_legend(xy, 3, 5, RGBColor(90, 90, 90).stroke_width(1)));
        }
        legend(&mut chart, SeriesLabelPosition::UpperLeft, 18, 0.9)?;
        Ok(())
    }
}

/// A series of the controls' figure: label, (k/τ, error) points, colour, marker
/// (0 circle for `figure`, 1 triangle for `literal`), dashed (the scalar model).
type ControlSeries = (String, Vec<(f64, f64)>, RGBColor, usize, bool);

struct ControlFig {
    panels: Vec<(String, Vec<ControlSeries>)>,
}

/// `figures/time_controls.png`: the errors of the controls against k/τ, the maximum
/// over time. If the layer sets the error, the τ curves fall on one another.
fn draw_controls(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, va) = (col_str(&df, "scenario")?, col_str(&df, "variant")?);
    let x = col_f64(&df, "k_over_tau")?;
    let mut variants: Vec<String> = va.clone();
    variants.sort();
    variants.dedup();
    // The constant load only: the ramp's errors are another story (chapter "Time").
    variants.retain(|v| !v.contains("ramp"));
    // Okabe–Ito: the three relaxation times, then the no-landing control.
    let colour = |v: &str, i: usize| {
        if v.starts_with("no landing") {
            RGBColor(0, 0, 0)
        } else {
            [
                RGBColor(0, 114, 178),
                RGBColor(213, 94, 0),
                RGBColor(0, 158, 115),
            ][i % 3]
        }
    };
    let mut panels = vec![];
    // The maximum over time only: at T the short relaxation times leave errors at
    // the reference's rounding, which say nothing of the layer.
    for (title, col, model) in [("max over t", "rel_err_max_percent", "model_max_percent")] {
        let (e, m) = (col_f64(&df, col)?, col_f64(&df, model)?);
        let mut series = vec![];
        for (vi, v) in variants.iter().enumerate() {
            for (si, s) in ["figure", "literal"].iter().enumerate() {
                let pts: Vec<(f64, f64)> = (0..x.len())
                    .filter(|&i| sc[i] == *s && va[i] == *v && e[i] > 0.0)
                    .map(|i| (x[i], e[i]))
                    .collect();
                if !pts.is_empty() {
                    series.push((format!("{s}, {v}"), pts, colour(v, vi), si, false));
                }
            }
            let pts: Vec<(f64, f64)> = (0..x.len())
                .filter(|&i| sc[i] == "figure" && va[i] == *v && m[i] > 0.0)
                .map(|i| (x[i], m[i]))
                .collect();
            if !v.starts_with("no landing") {
                series.push((String::new(), pts, colour(v, vi), 9, true));
            }
        }
        panels.push((title.to_string(), series));
    }
    both(
        &ctx.figures,
        "time_controls",
        (900, 700),
        &ControlFig { panels },
    )
}

impl Figure for ControlFig {
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<(), String> {
        for (k, (title, series)) in self.panels.iter().enumerate() {
            let area = root;
            let pts: Vec<(f64, f64)> = series.iter().flat_map(|s| s.1.clone()).collect();
            let (xmin, xmax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
                (a.min(p.0), b.max(p.0))
            });
            let (ymin, ymax) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
                (a.min(p.1), b.max(p.1))
            });
            let (xr, yr) = ((xmin / 1.5, xmax * 1.5), (ymin / 3.0, ymax * 30.0));
            let keys: Vec<f64> = (-4..=3)
                .map(|e| 10f64.powi(e))
                .filter(|v| *v >= xr.0 && *v <= xr.1)
                .collect();
            let ykeys: Vec<f64> = (-8..=3)
                .map(|e| 10f64.powi(e))
                .filter(|v| *v >= yr.0 && *v <= yr.1)
                .collect();
            let mut chart = ChartBuilder::on(area)
                .caption(
                    format!("Time error against k/tau: {title}"),
                    ("sans-serif", 22),
                )
                .margin(15)
                .x_label_area_size(60)
                .y_label_area_size(80)
                .build_cartesian_2d(
                    (xr.0..xr.1).log_scale().with_key_points(keys),
                    (yr.0..yr.1).log_scale().with_key_points(ykeys),
                )
                .map_err(e2s)?;
            chart
                .configure_mesh()
                .x_desc("k / tau")
                .y_desc("relative error in energy norm, %")
                .x_label_formatter(&|x| format!("{x:e}"))
                .y_label_formatter(&|y| format!("{y:e}"))
                .label_style(("sans-serif", 17))
                .axis_desc_style(("sans-serif", 19))
                .draw()
                .map_err(e2s)?;
            for (label, pts, c, marker, dashed) in series {
                let (c, m) = (*c, *marker);
                if *dashed {
                    chart
                        .draw_series(DashedLineSeries::new(pts.clone(), 8, 6, c.stroke_width(2)))
                        .map_err(e2s)?;
                    continue;
                }
                let style = c.stroke_width(if m == 0 { 3 } else { 1 });
                chart
                    .draw_series(LineSeries::new(pts.clone(), style))
                    .map_err(e2s)?;
                let drawn = if m == 0 {
                    chart
                        .draw_series(pts.iter().map(|&p| Circle::new(p, 6, c.filled())))
                        .map_err(e2s)?
                } else {
                    chart
                        .draw_series(pts.iter().map(|&p| Circle::new(p, 4, c.stroke_width(2))))
                        .map_err(e2s)?
                };
                if k == 0 {
                    let r = if m == 0 { 6 } else { 4 };
                    let st = if m == 0 {
                        c.filled()
                    } else {
                        c.stroke_width(2)
                    };
                    drawn.label(label.clone()).legend(move |(x, y)| {
                        EmptyElement::at((x + 12, y))
                            + PathElement::new(vec![(-12, 0), (12, 0)], style)
                            + Circle::new((0, 0), r, st)
                    });
                }
            }
            if k == 0 {
                let grey = RGBColor(60, 60, 60).stroke_width(2);
                chart
                    .draw_series(std::iter::once(PathElement::new(vec![], grey)))
                    .map_err(e2s)?
                    .label("scalar model (dashed), figure")
                    .legend(move |(x, y)| {
                        EmptyElement::at((x, y))
                            + PathElement::new(vec![(0, 0), (10, 0)], grey)
                            + PathElement::new(vec![(16, 0), (24, 0)], grey)
                    });
            }
            legend(&mut chart, SeriesLabelPosition::UpperLeft, 15, 0.9)?;
        }
        Ok(())
    }
}
