//! What the time grid into the initial layer ([`crate::time_grid`]) and the time grid
//! chosen by the solution ([`crate::time_adapt`]) save: for each
//! scene of a time study, the error of the layer grids with longest step $T/N$ and
//! first step $(T/N)/2^J$, $J = 1, 2, \dots$, measured as [`super::time_error`]
//! measures the uniform levels (the largest error over the grid's times against a
//! much finer uniform reference on the same mesh, and the error at $T$), and then
//! how many steps each family needs to reach a target error.
//!
//! The reference has $N_{ref}$ uniform steps; a layer grid's times are multiples of
//! $(T/N)/2^J$, so $N 2^J$ must divide $N_{ref}$, and every time of the grid is a
//! reference time. Runs on the reduced loop (proportional damping, as every scene of
//! the book's time study has): one factorisation of $B$ serves the reference and
//! every grid, and each error is the energy norm of a difference of reduced states.

use super::time_error::{Plan, Row};
use super::{Ctx, ExpError};
use crate::output::csv::Table;
use crate::scenario::Scenario;
use crate::time_grid::TimeGrid;

/// One layer grid's measure for one scene.
#[derive(Debug, Clone)]
pub struct LayerRow {
    /// The scene (as in the time study's rows).
    pub scenario: String,
    /// The scene's load history label (as in the time study's rows).
    pub history: String,
    /// $N$: the longest step is $T/N$.
    pub n: usize,
    /// $J$: the first step is $(T/N)/2^J$.
    pub halvings: u32,
    /// The grid's steps.
    pub steps: usize,
    /// The first step.
    pub k_first: f64,
    /// The reconstruction's bound ([`crate::time_adapt::Level::bound`]) on this grid.
    pub bound: f64,
    /// $\min_n F_n / \|u_{ref}(t_n) - u_n\|_E$ over the steps: the bound against the error
    /// at each step, in absolute terms.
    pub bound_margin: f64,
    /// Largest error over the grid's times relative to the reference's largest norm
    /// there.
    pub err_max: f64,
    /// The relative error at $T$.
    pub err_t: f64,
}

/// One level of the adaptive choice of the time grid ([`crate::time_adapt`]) for one
/// scene, measured as the layer grids are.
#[derive(Debug, Clone)]
pub struct AdaptiveRow {
    /// The scene (as in the time study's rows).
    pub scenario: String,
    /// The scene's load history label (as in the time study's rows).
    pub history: String,
    /// The level, from 0 (the uniform grid of $N_0$ steps).
    pub level: usize,
    /// The grid's steps.
    pub steps: usize,
    /// $J$: the shortest step is $(T/N_0)/2^J$.
    pub halvings: u32,
    /// The shortest step.
    pub k_min: f64,
    /// The estimate: the local errors carried forward and damped
    /// ([`crate::time_adapt::transported`]) over $\max_n\|u_n\|_E$.
    pub estimate: f64,
    /// The plain sum $\sum_n\eta_n / \max_n\|u_n\|_E$.
    pub sum: f64,
    /// The reconstruction's bound ([`crate::time_adapt::Level::bound`]).
    pub bound: f64,
    /// As [`LayerRow::bound_margin`].
    pub bound_margin: f64,
    /// Largest error over the grid's times relative to the reference's largest norm
    /// there.
    pub err_max: f64,
    /// The relative error at $T$.
    pub err_t: f64,
}

/// What a time study of grids returns: the layer grids' rows and the adaptive levels.
pub struct Grids {
    /// The layer grids' rows, per scene by $J$.
    pub layer: Vec<LayerRow>,
    /// The adaptive levels' rows, per scene by level.
    pub adaptive: Vec<AdaptiveRow>,
}

/// Measures the layer grids of longest step $T/N$ (`n`) and each $J$ in `halvings`,
/// and the levels of the adaptive choice of the grid with settings `adapt` (its $J$
/// capped where $N_0 2^J$ still divides the reference's steps), for the scenes `scns`
/// (name, history label, scene) on `plan`'s mesh and reference.
pub fn study(
    plan: &Plan,
    ctx: &Ctx,
    scns: &[(String, String, Scenario)],
    n: usize,
    halvings: &[u32],
    adapt: &crate::time_adapt::Settings,
) -> Result<Grids, ExpError> {
    let mut out = Grids {
        layer: vec![],
        adaptive: vec![],
    };
    let Some(first) = scns.first() else {
        return Ok(out);
    };
    if let Some(&j) = halvings
        .iter()
        .find(|&&j| j > 30 || !plan.n_ref.is_multiple_of(n << j))
    {
        return Err(crate::error::InputError::field(
            "time layer halvings",
            j,
            format!(
                "a J with N 2^J dividing the reference's {} steps (N = {n})",
                plan.n_ref
            ),
        )
        .into());
    }
    let adapt = crate::time_adapt::Settings {
        max_halvings: (0..=adapt.max_halvings)
            .rev()
            .find(|&j| plan.n_ref.is_multiple_of(adapt.n0 << j))
            .unwrap_or(0),
        ..*adapt
    };
    if !plan.n_ref.is_multiple_of(adapt.n0) {
        return Err(crate::error::InputError::field(
            "n0",
            adapt.n0,
            format!("a number of steps dividing the reference's {}", plan.n_ref),
        )
        .into());
    }
    let sim = super::runs::simulation(&first.2, plan.n, plan.n_ref)?;
    let disc = sim.discretisation();
    if crate::reduced::proportional(&first.2, &disc).is_none() {
        return Err(crate::error::InputError::field(
            "scenario",
            &first.0,
            "a scene with proportional damping: the layer study runs on the reduced loop",
        )
        .into());
    }
    let mut timings = crate::scheme::Timings::default();
    let op = sim.reduced_operator(&disc, &mut timings)?;
    let tol = crate::scheme::CERTIFICATE_TOL;
    ctx.add_units(scns.len());
    for (name, label, scn) in scns {
        let load = op.load_of(scn);
        // The reference's state and norm at every one of its steps.
        let mut refs = Vec::with_capacity(plan.n_ref);
        op.march(
            scn,
            &load,
            plan.n_ref,
            plan.solver.build().as_mut(),
            tol,
            &|_| false,
            &mut timings,
            &mut |s| refs.push((s.state.clone(), op.energy(&load, s.state))),
        )?;
        let rate = scn.slowest_rate().unwrap_or(0.0);
        // ANCHOR: measure_grid
        // One grid's errors against the reference at its own times, and each step's
        // distance from the linear predictor (crate::time_adapt).
        let mut measure = |grid: &TimeGrid| -> Result<Measured, ExpError> {
            let stride = plan.n_ref / (grid.n() << grid.halvings());
            let last = grid.len();
            let (mut err_max, mut ref_max, mut err_t) = (0.0f64, 0.0f64, f64::NAN);
            let mut errs = Vec::with_capacity(grid.len());
            let solver = &mut *plan.solver.build();
            let solved = crate::time_adapt::march_reduced(
                &op,
                scn,
                &load,
                grid,
                (solver, tol),
                &mut timings,
                &mut |s| {
                    let at = grid.units(s.step) as usize * stride - 1;
                    let (st_ref, r) = &refs[at];
                    let e = op.energy_diff(&load, st_ref, s.state);
                    errs.push(e);
                    err_max = err_max.max(e);
                    ref_max = ref_max.max(*r);
                    if s.step == last {
                        err_t = e / r;
                    }
                },
            )?;
            let each = crate::time_adapt::propagated_each(grid, &solved.theta, rate);
            let bound = each.iter().copied().fold(0.0, f64::max) / solved.norm_max;
            let bound_margin = crate::time_adapt::least_margin(&each, &errs);
            Ok(Measured {
                err_max,
                ref_max,
                err_t,
                gaps: solved.gaps,
                theta: solved.theta,
                bound,
                bound_margin,
                norm_max: solved.norm_max,
            })
        };
        // ANCHOR_END: measure_grid
        for &j in halvings {
            let grid = TimeGrid::of(scn, n, j)?;
            let m = measure(&grid)?;
            out.layer.push(LayerRow {
                scenario: name.clone(),
                history: label.clone(),
                n,
                halvings: j,
                steps: grid.len(),
                k_first: grid.k(1),
                bound: m.bound,
                bound_margin: m.bound_margin,
                err_max: m.err_max / m.ref_max,
                err_t: m.err_t,
            });
        }
        let (levels, _) = crate::time_adapt::adapt_time(
            scn.t_end,
            &adapt,
            scn.slowest_rate().unwrap_or(0.0),
            |grid| {
                let m = measure(grid)?;
                Ok::<_, ExpError>(crate::time_adapt::Solved {
                    gaps: m.gaps.clone(),
                    theta: m.theta.clone(),
                    norm_max: m.norm_max,
                    out: m,
                })
            },
            |_| {},
        )?;
        for (level, l) in levels.into_iter().enumerate() {
            out.adaptive.push(AdaptiveRow {
                scenario: name.clone(),
                history: label.clone(),
                level,
                steps: l.grid.len(),
                halvings: l.grid.halvings(),
                k_min: l.grid.k_min(),
                estimate: l.estimate,
                sum: l.sum,
                bound: l.out.bound,
                bound_margin: l.out.bound_margin,
                err_max: l.out.err_max / l.out.ref_max,
                err_t: l.out.err_t,
            });
        }
        ctx.log(&format!("time layer: {name} {label}"));
    }
    Ok(out)
}

/// One grid's measure: the largest error and reference norm over its times, the
/// relative error at $T$, each step's predictor distance and the largest norm.
struct Measured {
    err_max: f64,
    ref_max: f64,
    err_t: f64,
    gaps: Vec<f64>,
    theta: Vec<f64>,
    bound: f64,
    bound_margin: f64,
    norm_max: f64,
}

/// The steps a family of runs needs to reach `target` (relative): the family's
/// `(steps, error)` sorted by steps, the first that reaches it, and between it and the
/// one before, the count at which the log–log line through the two crosses the
/// target. `None` where no run reaches it; the first run's count where it already
/// does (then the true need is at most that).
pub fn steps_to(family: &[(usize, f64)], target: f64) -> Option<(f64, &'static str)> {
    let mut f: Vec<(usize, f64)> = family.to_vec();
    f.sort_by_key(|p| p.0);
    let i = f.iter().position(|p| p.1 <= target)?;
    if i == 0 {
        return Some((f[0].0 as f64, "at most"));
    }
    let ((s0, e0), (s1, e1)) = (f[i - 1], f[i]);
    let (ls0, ls1) = ((s0 as f64).ln(), (s1 as f64).ln());
    let (le0, le1) = (e0.ln(), e1.ln());
    if le1 == le0 {
        return Some((s1 as f64, "interpolated"));
    }
    let ls = ls0 + (target.ln() - le0) * (ls1 - ls0) / (le1 - le0);
    Some((ls.exp().clamp(s0 as f64, s1 as f64), "interpolated"))
}

/// The targets of [`savings`], relative: 1 % and 0.1 %.
pub const TARGETS: [f64; 2] = [0.01, 0.001];

/// Per scene and history, per measure (largest over time, at $T$) and target: the
/// steps the uniform levels `uniform`, the layer grids and the adaptive levels of
/// `grids` need, and each ratio to the uniform count.
pub fn savings(uniform: &[Row], grids: &Grids) -> Table {
    let mut keys: Vec<(String, String)> = (grids.layer.iter())
        .map(|r| (r.scenario.clone(), r.history.clone()))
        .collect();
    keys.dedup();
    let mut cols: (Vec<String>, Vec<String>, Vec<String>, Vec<f64>) = Default::default();
    let mut need: [(Vec<f64>, Vec<String>); 3] = Default::default();
    let mut ratio: [Vec<f64>; 2] = Default::default();
    // The adaptive levels' steps summed through the first at or below the target:
    // each level solves from t = 0.
    let mut summed = vec![];
    for (scn, hist) in &keys {
        let of = |a: &str, b: &str| a == scn && b == hist;
        for measure in ["max", "T"] {
            let pick = |max: f64, t: f64| if measure == "max" { max } else { t };
            let families: [Vec<(usize, f64)>; 3] = [
                (uniform.iter())
                    .filter(|r| of(&r.scenario, &r.history))
                    .map(|r| (r.steps, pick(r.err_max, r.err_t)))
                    .collect(),
                (grids.layer.iter())
                    .filter(|r| of(&r.scenario, &r.history))
                    .map(|r| (r.steps, pick(r.err_max, r.err_t)))
                    .collect(),
                (grids.adaptive.iter())
                    .filter(|r| of(&r.scenario, &r.history))
                    .map(|r| (r.steps, pick(r.err_max, r.err_t)))
                    .collect(),
            ];
            for target in TARGETS {
                cols.0.push(scn.clone());
                cols.1.push(hist.clone());
                cols.2.push(measure.into());
                cols.3.push(100.0 * target);
                let mut counts = [f64::NAN; 3];
                for (k, fam) in families.iter().enumerate() {
                    let (s, how) = steps_to(fam, target).unwrap_or((f64::NAN, "not reached"));
                    need[k].0.push(s);
                    need[k].1.push(how.into());
                    counts[k] = s;
                }
                ratio[0].push(counts[1] / counts[0]);
                ratio[1].push(counts[2] / counts[0]);
                let fam = &families[2];
                summed.push(match fam.iter().position(|p| p.1 <= target) {
                    Some(i) => fam[..=i].iter().map(|p| p.0 as f64).sum(),
                    None => f64::NAN,
                });
            }
        }
    }
    let [(u, uh), (l, lh), (a, ah)] = need;
    let [rl, ra] = ratio;
    Table::new()
        .str("scenario", cols.0)
        .str("history", cols.1)
        .str("measure", cols.2)
        .f64("target_percent", cols.3)
        .f64("uniform_steps", u)
        .str("uniform_how", uh)
        .f64("layer_steps", l)
        .str("layer_how", lh)
        .f64("layer_over_uniform", rl)
        .f64("adaptive_steps", a)
        .str("adaptive_how", ah)
        .f64("adaptive_over_uniform", ra)
        .f64("adaptive_levels_steps", summed)
}

/// The adaptive levels' table.
pub fn adaptive_table(rows: &[AdaptiveRow]) -> Table {
    let head = Table::new()
        .str(
            "scenario",
            rows.iter().map(|r| r.scenario.clone()).collect(),
        )
        .str("history", rows.iter().map(|r| r.history.clone()).collect())
        .u64("level", rows.iter().map(|r| r.level as u64).collect())
        .u64("steps", rows.iter().map(|r| r.steps as u64).collect())
        .u64("halvings", rows.iter().map(|r| r.halvings as u64).collect())
        .f64("k_min", rows.iter().map(|r| r.k_min).collect())
        .f64(
            "estimate_percent",
            rows.iter().map(|r| 100.0 * r.estimate).collect(),
        )
        .f64("sum_percent", rows.iter().map(|r| 100.0 * r.sum).collect());
    with_bound(head, rows.iter().map(|r| (r.bound, r.bound_margin)))
        .f64(
            "rel_err_max_percent",
            rows.iter().map(|r| 100.0 * r.err_max).collect(),
        )
        .f64(
            "rel_err_T_percent",
            rows.iter().map(|r| 100.0 * r.err_t).collect(),
        )
}

/// `t` with the columns of the reconstruction's bound: `bound_percent` and
/// `bound_margin` from each row's `(bound, margin)`.
fn with_bound(t: Table, rows: impl Iterator<Item = (f64, f64)>) -> Table {
    let (bound, margin): (Vec<f64>, Vec<f64>) = rows.map(|(b, m)| (100.0 * b, m)).unzip();
    t.f64("bound_percent", bound).f64("bound_margin", margin)
}

/// The layer grids' table.
pub fn table(rows: &[LayerRow]) -> Table {
    let head = Table::new()
        .str(
            "scenario",
            rows.iter().map(|r| r.scenario.clone()).collect(),
        )
        .str("history", rows.iter().map(|r| r.history.clone()).collect())
        .u64("n_longest", rows.iter().map(|r| r.n as u64).collect())
        .u64("halvings", rows.iter().map(|r| r.halvings as u64).collect())
        .u64("steps", rows.iter().map(|r| r.steps as u64).collect())
        .f64("k_first", rows.iter().map(|r| r.k_first).collect());
    with_bound(head, rows.iter().map(|r| (r.bound, r.bound_margin)))
        .f64(
            "rel_err_max_percent",
            rows.iter().map(|r| 100.0 * r.err_max).collect(),
        )
        .f64(
            "rel_err_T_percent",
            rows.iter().map(|r| 100.0 * r.err_t).collect(),
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_to_a_target_cross_the_log_log_line() {
        let fam = [(4, 0.1), (8, 0.05), (16, 0.025)];
        assert_eq!(steps_to(&fam, 0.2), Some((4.0, "at most")));
        let (s, how) = steps_to(&fam, 0.04).unwrap();
        assert_eq!(how, "interpolated");
        // error ~ 0.4/N: 0.04 at N = 10
        assert!((s - 10.0).abs() < 1e-9, "{s}");
        assert_eq!(steps_to(&fam, 0.01), None);
    }
}
