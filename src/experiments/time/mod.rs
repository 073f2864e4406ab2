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
//!
//! With proportional damping (every built-in scenario) the study runs on the reduced
//! loop: one factorisation of $B$ serves the reference and every level, and each
//! error is the energy norm of a difference of reduced states, with no field formed
//! (`reduced_measures`). Until the session that moved it there, the study formed
//! every field by the general loop, whose solves leave a rounding of a few
//! $10^{-10}\,\|u_{ref}\|_E$ in each field: the errors moved by at most
//! $3.5\cdot10^{-10}$ relative to the reference's norm, which is below $10^{-5}$ of any
//! error above $10^{-5}$ and up to $10^{-3}$ of the smallest ones at $N = 1024$; the
//! rounding floors under the relaxed constant load ($\tau = 0.007$ at $T$) fell from
//! $8\cdot10^{-10}$ to $8\cdot10^{-12}$.

use super::{Ctx, ExpError, col_f64, col_str, read_csv};
use crate::history::History;
use crate::norms::energy_norm;
use crate::output::csv::Table;
use crate::output::plot::{Figure, both, circle_legend, dashed_legend, e2s, legend};
use crate::scenario::Scenario;
use crate::scheme::{Discretisation, Settings};
use plotters::prelude::*;

mod figure;
mod table;
use figure::{draw, draw_controls};
pub use table::sig3;
use table::write_markdown;
pub use table::write_rows;

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
    /// The step solver of every run (the registry's; `newton` in the book's study).
    pub solver: &'static crate::step::SolverEntry,
}

pub fn plan(quick: bool) -> Plan {
    if quick {
        Plan {
            n: 16,
            levels: vec![4, 8, 16, 32, 64, 128, 256],
            n_ref: 16384,
            solver: crate::step::DEFAULT_SOLVER_ENTRY,
        }
    } else {
        Plan {
            n: 32,
            levels: vec![4, 8, 16, 32, 64, 128, 256, 512, 1024],
            n_ref: 32768,
            solver: crate::step::DEFAULT_SOLVER_ENTRY,
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
    /// The relaxation time $\tau$ and the limit $g$ of the run, and its final time.
    pub tau: f64,
    pub g: f64,
    pub t_end: f64,
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
/// The controls of the layer. (1) Under the constant load, the relaxation time
/// tau = C/G scaled by 0.1 and 10 (the viscosity alpha, beta scaled, the elasticity
/// kept) for `literal` and `figure`, with the shipped tau = 0.07 as the baseline.
/// (2) `figure` with g = 1, ten times the shipped limit, so that no contact node lands
/// on it, under the constant load and under the ramp to t = 1.
pub fn controls() -> Result<Vec<(String, String, Scenario)>, ExpError> {
    let mut out = vec![];
    for name in SCENARIOS {
        for scale in [0.1, 1.0, 10.0] {
            let mut s = Scenario::load(name)?;
            s.alpha *= scale;
            s.beta *= scale;
            let tau = s.relaxation_time().unwrap_or(f64::NAN);
            // 0.007, 0.07, 0.7 (rounded: the product is 0.06999... in double precision)
            let label = format!("tau = {}", (tau * 1e6).round() / 1e6);
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
    let measured = match reduced_measures(plan, &batch, &disc, ctx)? {
        Some(m) => m,
        None => general_measures(plan, &batch, &disc, ctx)?,
    };
    // Errors are relative to the reference: a reference that is zero at every step
    // (no load) leaves them undefined, refused by name rather than written as NaN.
    for (i, (name, _, _)) in scns.iter().enumerate() {
        if measured
            .levels
            .iter()
            .any(|l| l[i].r_max.is_nan() || l[i].r_max <= 0.0)
        {
            return Err(crate::error::InputError::field(
                "scenario",
                name,
                "a scene whose solution is not zero: the reference's energy norm is 0 at \
                 every step (the loads vanish), so no relative time error is defined",
            )
            .into());
        }
    }
    let mut rows = vec![];
    for (l, &steps) in plan.levels.iter().enumerate() {
        for (i, (name, label, s)) in scns.iter().enumerate() {
            let (model_max, model_t) = match s.relaxation_time() {
                Some(tau) => scalar_model(tau, &s.history, s.t_end, steps, plan.n_ref),
                None => (f64::NAN, f64::NAN),
            };
            let m = &measured.levels[l][i];
            rows.push(Row {
                scenario: name.clone(),
                history: label.clone(),
                steps,
                err_max: m.e_max / m.r_max,
                err_t: m.e_t,
                model_max,
                model_t,
                t_first_limit: measured.first_limit[i],
                t_err_max: m.t_max,
                tau: s.relaxation_time().unwrap_or(f64::NAN),
                g: s.g,
                t_end: s.t_end,
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

/// What one level measures of one scenario: $\max_j \|e_j\|_E$, $\max_j \|u_{ref,j}\|_E$
/// over its steps, $\|e_N\|_E / \|u_{ref}(T)\|_E$, and the time of the largest error.
#[derive(Debug, Clone, Copy)]
struct LevelMeasure {
    e_max: f64,
    r_max: f64,
    e_t: f64,
    t_max: f64,
}

impl Default for LevelMeasure {
    fn default() -> Self {
        LevelMeasure {
            e_max: 0.0,
            r_max: 0.0,
            e_t: 0.0,
            t_max: f64::NAN,
        }
    }
}

impl LevelMeasure {
    /// Adds the error `e` at step `step` of `steps` (time `t`) against a reference of
    /// norm `r` there.
    fn add(&mut self, e: f64, r: f64, (step, steps, t): (usize, usize, f64)) {
        if e > self.e_max {
            (self.e_max, self.t_max) = (e, t);
        }
        self.r_max = self.r_max.max(r);
        if step == steps {
            self.e_t = e / r;
        }
    }
}

/// Per scenario the first time a node of the reference sits at $g$; per level and
/// scenario its [`LevelMeasure`].
struct Measures {
    first_limit: Vec<f64>,
    levels: Vec<Vec<LevelMeasure>>,
}

/// Whether contact value `s` (a penetration $u_\nu$) sits at the limit `g`.
fn at_limit(g: f64, s: f64) -> bool {
    g.is_finite() && g - s <= 1e-8 * g
}

/// The measures by the reduced loop, where the damping is proportional (`None`
/// otherwise): one factorisation of $B$ serves the reference and every level, and
/// the errors are energy norms of differences of reduced states
/// ([`crate::reduced::Reduced::energy_diff`]): no field is formed, and no step
/// solves with the factor. Every step is certified on its condensed problem.
fn reduced_measures(
    plan: &Plan,
    batch: &[Scenario],
    disc: &Discretisation,
    ctx: &Ctx,
) -> Result<Option<Measures>, ExpError> {
    if crate::reduced::proportional(&batch[0], disc).is_none() {
        return Ok(None);
    }
    let n_max = *plan.levels.iter().max().expect("levels");
    let stride = plan.n_ref / n_max;
    let mut timings = crate::scheme::Timings::default();
    let op = crate::reduced::Reduced::new(
        &batch[0],
        disc,
        crate::scheme::OrderingKind::NestedDissection,
        true,
        &mut timings,
    )?;
    let march = |scn: &Scenario,
                 load: &crate::reduced::Load,
                 steps: usize,
                 timings: &mut crate::scheme::Timings,
                 observe: &mut dyn FnMut(crate::reduced::Stepped)|
     -> Result<(), ExpError> {
        op.march(
            scn,
            load,
            steps,
            plan.solver.build().as_mut(),
            crate::scheme::CERTIFICATE_TOL,
            &|_| false,
            timings,
            observe,
        )?;
        Ok(())
    };
    let mut first_limit = vec![f64::NAN; batch.len()];
    let mut levels = vec![vec![LevelMeasure::default(); batch.len()]; plan.levels.len()];
    let mut refs = vec![];
    for (i, scn) in batch.iter().enumerate() {
        let load = op.load_of(scn);
        // The reference's states at the finest level's times t_j, j = 1, 2, ...
        refs.clear();
        march(scn, &load, plan.n_ref, &mut timings, &mut |s| {
            if s.step % stride == 0 {
                refs.push((s.state.clone(), op.energy(&load, s.state)));
            }
            if first_limit[i].is_nan() && s.state.r.iter().any(|&r| at_limit(scn.g, r)) {
                first_limit[i] = s.t;
            }
        })?;
        for (l, &steps) in plan.levels.iter().enumerate() {
            let ratio = n_max / steps;
            let m = &mut levels[l][i];
            march(scn, &load, steps, &mut timings, &mut |s| {
                let (st_ref, r) = &refs[s.step * ratio - 1];
                m.add(
                    op.energy_diff(&load, st_ref, s.state),
                    *r,
                    (s.step, steps, s.t),
                );
            })?;
        }
    }
    ctx.log(&format!(
        "time study: reference N = {} at n = {}",
        plan.n_ref, plan.n
    ));
    for &steps in &plan.levels {
        ctx.log(&format!("time study: N = {steps}"));
    }
    Ok(Some(Measures {
        first_limit,
        levels,
    }))
}

/// The measures by the general loop, the batch in one run per level: the reference
/// fields kept at the finest level's times, each level's field compared with them.
fn general_measures(
    plan: &Plan,
    batch: &[Scenario],
    disc: &Discretisation,
    ctx: &Ctx,
) -> Result<Measures, ExpError> {
    let n_max = *plan.levels.iter().max().expect("levels");
    let stride = plan.n_ref / n_max;
    let nb = batch.len();
    ctx.log(&format!(
        "time study: reference N = {} at n = {}",
        plan.n_ref, plan.n
    ));
    let mut refs: Vec<Vec<Vec<f64>>> = vec![vec![vec![0.0; disc.dofs.count]]; nb];
    let mut first_limit = vec![f64::NAN; nb];
    let opt = Settings::new(plan.n, plan.n_ref);
    super::run_batch_with(batch, &opt, plan.solver, &mut |i, step, t, u| {
        if step % stride == 0 {
            refs[i].push(u.to_vec());
        }
        if first_limit[i].is_nan()
            && disc
                .contact_dofs
                .iter()
                .any(|&d| at_limit(batch[i].g, -u[d]))
        {
            first_limit[i] = t;
        }
    })?;
    let ref_norms: Vec<Vec<f64>> = refs
        .iter()
        .map(|r| r.iter().map(|u| energy_norm(&disc.b, u)).collect())
        .collect();
    let mut levels = vec![];
    for &steps in &plan.levels {
        ctx.log(&format!("time study: N = {steps}"));
        let ratio = n_max / steps;
        let mut m = vec![LevelMeasure::default(); nb];
        let opt = Settings::new(plan.n, steps);
        super::run_batch_with(batch, &opt, plan.solver, &mut |i, step, t, u| {
            let j = step * ratio;
            let diff: Vec<f64> = u.iter().zip(&refs[i][j]).map(|(a, b)| a - b).collect();
            m[i].add(
                energy_norm(&disc.b, &diff),
                ref_norms[i][j],
                (step, steps, t),
            );
        })?;
        levels.push(m);
    }
    Ok(Measures {
        first_limit,
        levels,
    })
}
