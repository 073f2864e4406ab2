//! The time discretisation error at a fixed mesh: a study's plan, its runs against a
//! much finer step on the same mesh, the scalar layer model beside them, and its
//! table. The book's time study (`time`) and `evhi study time` both run it.
//!
//! What it measures: backward Euler's error
//! $\max_n \|u^{h}(t_n) - u^{hk}_n\|_E$ and $\|u^h(T) - u^{hk}_N\|_E$ for $k = T/N$,
//! against the same mesh run with a much finer step $k_{\text{ref}}$, for several load
//! histories (see [`crate::history`]).
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

use super::{Ctx, ExpError};
use crate::history::History;
use crate::norms::energy_norm;
use crate::output::csv::Table;
use crate::scenario::Scenario;
use crate::scheme::Discretisation;

/// Mesh, step levels and reference of a study.
#[derive(Debug, Clone)]
pub struct Plan {
    /// The mesh level $n$ of every run, $h = 1/n$.
    pub n: usize,
    /// The levels' numbers of steps $N$, $k = T/N$: each divides the largest.
    pub levels: Vec<usize>,
    /// The reference's number of steps $N_{\text{ref}}$ on the same mesh, a multiple of
    /// the largest level.
    pub n_ref: usize,
    /// The step solver of every run (the registry's; `newton` in the book's study).
    pub solver: &'static crate::step::SolverEntry,
}

/// The plan of the study: with `quick`, $n = 16$ and $N$ from 4 to 256 against
/// $N_{\text{ref}} = 16384$; else $n = 32$ and $N$ from 4 to 1024 against 32768; the
/// default step solver.
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

/// The scalar model of the layer: $\tau\dot y + y = \varphi(t)$, $y(0) = 0$, by backward
/// Euler with $N$ steps on $[0, T]$, $y_n = (\tau y_{n-1} + k\varphi(t_n))/(\tau + k)$,
/// against the same model with $N_{\text{ref}}$ steps, measured as the study measures
/// the field: (max over the level's times of the error) / (max of the reference there),
/// and the error at $T$ over $y_{\text{ref}}(T)$.
// ANCHOR: scalar_model
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
    /// The scenario's name.
    pub scenario: String,
    /// The row's label (its load history, or the variant of the scene).
    pub history: String,
    /// The level's number of steps $N$.
    pub steps: usize,
    /// $\max_n \|u_{ref}(t_n) - u_n\|_E / \max_n \|u_{ref}(t_n)\|_E$ over the level's times.
    pub err_max: f64,
    /// $\|u_{ref}(T) - u_N\|_E / \|u_{ref}(T)\|_E$.
    pub err_t: f64,
    /// The scalar model's error over time, measured as `err_max` ([`scalar_model`]);
    /// NaN without a relaxation time.
    pub model_max: f64,
    /// The scalar model's error at $T$, measured as `err_t`; NaN without a relaxation
    /// time.
    pub model_t: f64,
    /// First time at which a contact node of the reference run sits at the limit $g$.
    pub t_first_limit: f64,
    /// The level's time $t_n$ where the error is largest.
    pub t_err_max: f64,
    /// The relaxation time $\tau$ of the run, $\mathcal C = \tau\mathcal G$ (NaN where the
    /// tensors are not proportional).
    pub tau: f64,
    /// The limit $g$ of the run.
    pub g: f64,
    /// The final time $T$ of the run.
    pub t_end: f64,
}

/// Runs the scenarios `scns` (scenario name, label, scenario) at every level.
pub fn study_of(
    plan: &Plan,
    ctx: &Ctx,
    scns: &[(String, String, Scenario)],
) -> Result<Vec<Row>, ExpError> {
    let batch: Vec<Scenario> = scns.iter().map(|s| s.2.clone()).collect();
    let sim = super::runs::simulation(&batch[0], plan.n, plan.n_ref)?;
    let disc = sim.discretisation();
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
    let measured = match reduced_measures(plan, &batch, (&sim, &disc), ctx)? {
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
    (sim, disc): (&crate::simulation::Simulation, &Discretisation),
    ctx: &Ctx,
) -> Result<Option<Measures>, ExpError> {
    if crate::reduced::proportional(&batch[0], disc).is_none() {
        return Ok(None);
    }
    let n_max = *plan.levels.iter().max().expect("levels");
    let stride = plan.n_ref / n_max;
    let mut timings = crate::scheme::Timings::default();
    let op = sim.reduced_operator(disc, &mut timings)?;
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
    let sim = super::runs::simulation(&batch[0], plan.n, plan.n_ref)?;
    super::runs::run_batch_with(&sim, batch, plan.solver, &mut |i, step, t, u| {
        if step % stride == 0 {
            refs[i].push(u.to_vec());
        }
        if first_limit[i].is_nan()
            && (disc.contact_dofs.iter().zip(&disc.gap))
                .any(|(&d, gap)| at_limit(batch[i].g, -u[d] - gap))
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
        let sim = super::runs::simulation(&batch[0], plan.n, steps)?;
        super::runs::run_batch_with(&sim, batch, plan.solver, &mut |i, step, t, u| {
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

/// Writes the rows of a study as `file`; `label` names the column of the row's label.
pub fn write_rows(
    ctx: &Ctx,
    plan: &Plan,
    rows: &[Row],
    file: &str,
    label: &str,
) -> Result<std::path::PathBuf, ExpError> {
    let params = format!(
        "fixed mesh n = 1/h = {}; k = T/N for N in {:?}; reference N_ref = {} on the same mesh; solver {}; \
         errors in the energy norm relative to the reference: max over the level's times t_n of ||u_ref(t_n) - u_n||_E \
         / max there of ||u_ref(t_n)||_E, and at t = T; model_*: the scalar backward-Euler model of the layer \
         (tau = C/G of the row), same measure; t_of_err_max: the level's time where the error is largest; \
         t_first_limit: first reference time with a contact node at u_nu = g (NaN: never){}{}{}",
        plan.n,
        plan.levels,
        plan.n_ref,
        plan.solver.name,
        if label == "variant" {
            "; variants: alpha and beta scaled by 0.1 and 10 (tau = C/G scaled, E kept; constant load), and figure with g = 1 (no node lands) under the constant load and the ramp to t = 1"
        } else {
            ""
        },
        // Conventions that only some scenes need, said where they occur.
        if rows.iter().any(|r| !r.tau.is_finite()) {
            "; tau, k_over_tau and model_*: NaN where C is not a multiple of G (no single \
             relaxation time, so no scalar model)"
        } else {
            ""
        },
        if rows.iter().any(|r| r.g.is_infinite()) {
            "; g = inf: no limit"
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
        .f64("k", rows.iter().map(|r| r.t_end / r.steps as f64).collect())
        .f64(
            "k_over_tau",
            rows.iter()
                .map(|r| r.t_end / r.steps as f64 / r.tau)
                .collect(),
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
    ctx.write(file, &t, &params)
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
