//! The book's time study: the time discretisation error at a fixed mesh for the two
//! loads under three load histories (`time_study.csv`), and its controls, the
//! relaxation time scaled and the limit moved out of reach (`time_controls.csv`),
//! with their figures and the book's Markdown table. The computation, and why it
//! matters (the initial layer of relaxation time $\tau = 0.07$ under a load applied
//! in full at $t = 0$), is [`evhi::study::time_error`], which `evhi study time` runs
//! on any scenario.

use super::{Ctx, ExpError, col_f64, col_str, read_csv};
use evhi::history::History;
use evhi::output::plot::{Figure, both, circle_legend, dashed_legend, e2s, legend};
use evhi::scenario::Scenario;

use plotters::prelude::*;

mod figure;
mod grids;
mod table;
use figure::{draw, draw_controls, in_words};
use grids::draw_grids;
use table::write_markdown;

pub use evhi::study::time_error::{Plan, Row, plan, scalar_model, sig3, study_of, write_rows};

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

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let plan = plan(ctx.quick);
    let rows = study(&plan, ctx)?;
    let path = write_rows(ctx, &plan, &rows, "time_study.csv", "history")?;
    write_markdown(ctx, &path, &plan)?;
    draw(ctx, &path)?;
    layer(&plan, ctx, &rows)?;
    draw_grids(ctx)?;
    // One batch per material: a batch shares its step matrix.
    let all = controls()?;
    let mut rows = vec![];
    let mut materials: Vec<(f64, f64)> = vec![];
    for c in &all {
        if !materials.contains(&(c.2.alpha(), c.2.beta())) {
            materials.push((c.2.alpha(), c.2.beta()));
        }
    }
    for m in materials {
        let group: Vec<_> = all
            .iter()
            .filter(|c| (c.2.alpha(), c.2.beta()) == m)
            .cloned()
            .collect();
        rows.extend(study_of(&plan, ctx, &group)?);
    }
    let path = write_rows(ctx, &plan, &rows, "time_controls.csv", "variant")?;
    draw_controls(ctx, &path)
}

/// Runs every scenario and history at every level (one batched run per level).
pub fn study(plan: &Plan, ctx: &Ctx) -> Result<Vec<Row>, ExpError> {
    study_of(plan, ctx, &scenes()?)
}

/// The study's scenes: each load scenario under each history.
fn scenes() -> Result<Vec<(String, String, Scenario)>, ExpError> {
    let mut scns = vec![];
    for name in SCENARIOS {
        for (label, h) in histories() {
            let s = Scenario::load(name)?
                .with_history(h)?
                .with_name(&format!("{name}/{label}"))?;
            scns.push((name.to_string(), label.to_string(), s));
        }
    }
    Ok(scns)
}

/// The longest step $T/N$ of the layer grids: $N = 16$, $k = 0.89\tau$.
pub const LAYER_N: usize = 16;

/// The layer grids' halvings $J$: the first step from $T/32$ down to $T/(16 \cdot
/// 2^{J})$, as far as the reference's steps allow.
fn layer_halvings(plan: &Plan) -> Vec<u32> {
    (1..=11)
        .filter(|&j| plan.n_ref.is_multiple_of(LAYER_N << j))
        .collect()
}

/// What the layer and adaptive tables say of their bound columns.
const BOUND: &str = "bound_percent = max_n F_n / max_n ||u_n||_E, F_n = exp(-k_n lambda) F_(n-1) + theta_n, theta_n the reconstruction's residual of step n measured through A^(-1) and damped to t_n (evhi::reconstruction, evhi::time_adapt::propagated): a bound of the error over time without contact, an estimate with it; bound_margin = min_n F_n / ||u_ref(t_n) - u_n||_E, the bound against the error at each step in absolute terms (above 1 where the bound holds)";

// ANCHOR: layer
/// The time grid into the initial layer against the uniform levels `uniform` of the
/// same study, and the adaptive choice of the grid: `time_layer.csv` (each grid's
/// errors), `time_adaptive.csv` (each adaptive level's errors and estimate) and
/// `adaptive_time.csv` (the steps each family needs for 1 % and 0.1 %, largest over
/// time and at T).
fn layer(plan: &Plan, ctx: &Ctx, uniform: &[Row]) -> Result<(), ExpError> {
    use evhi::study::time_layer;
    let halvings = layer_halvings(plan);
    let adapt = evhi::time_adapt::Settings::default();
    let grids = time_layer::study(plan, ctx, &scenes()?, LAYER_N, &halvings, &adapt)?;
    let common = format!(
        "fixed mesh n = 1/h = {}, reference N_ref = {} uniform steps on the same mesh,          solver {}, errors measured as in time_study.csv over each grid's own times",
        plan.n, plan.n_ref, plan.solver.name
    );
    ctx.write(
        "time_layer.csv",
        &time_layer::table(&grids.layer),
        &format!(
            "{common}; time grids into the initial layer (evhi::time_grid): longest step              T/N with N = n_longest, first step k_first = (T/N)/2^J for J = halvings, each              step growing as k (1 + k/(2 tau)) rounded down to T/N over a power of two;              steps = the grid's count; {BOUND}"
        ),
    )?;
    ctx.write(
        "time_adaptive.csv",
        &time_layer::adaptive_table(&grids.adaptive),
        &format!(
            "{common}; the adaptive choice of the time grid (evhi::time_adapt): from N0 =              {} uniform steps, each level's steps marked by Doerfler's criterion (theta = {})              on the reconstruction's residuals theta_n (evhi::reconstruction) and halved, until more than {} steps or a              shortest step below the reference's; estimate = max_n E_n / max ||u_n||_E with E_n = E_(n-1) / (1 + k_n lambda) + eta_n, lambda the body's slowest relaxation rate (evhi::time_adapt::transported); sum = sum eta_n / max ||u_n||_E, the same without the damping; {BOUND}",
            adapt.n0, adapt.theta, adapt.max_steps
        ),
    )?;
    ctx.write(
        "adaptive_time.csv",
        &time_layer::savings(uniform, &grids),
        &format!(
            "{common}; per scene, history, measure (max: largest error over time; T: at t =              T) and target: the steps the uniform levels of time_study.csv (N = {:?}) and              the layer grids of time_layer.csv need, where the log-log line through the              first run at or below the target and the one before crosses it              (`interpolated`), the first run's count where it already is (`at most`), NaN              where none reaches it; the same for the adaptive levels of              time_adaptive.csv; layer_over_uniform and adaptive_over_uniform the ratios              to the uniform count; adaptive_levels_steps the adaptive levels' steps summed              through the first at or below the target (each level solves from t = 0)",
            plan.levels
        ),
    )?;
    Ok(())
}
// ANCHOR_END: layer

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
            let s = Scenario::load(name)?;
            let (alpha, beta) = (s.alpha() * scale, s.beta() * scale);
            let s = s.with_viscosity(alpha, beta)?;
            let tau = s.relaxation_time().unwrap_or(f64::NAN);
            // 0.007, 0.07, 0.7 (rounded: the product is 0.06999... in double precision)
            let label = format!("tau = {}", (tau * 1e6).round() / 1e6);
            let s = s.with_name(&format!("{name}/{label}"))?;
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
        let s = Scenario::load("figure")?
            .with_g(1.0)?
            .with_history(history)?
            .with_name(&format!("figure/{label}"))?;
        out.push(("figure".into(), label.into(), s));
    }
    Ok(out)
}
// ANCHOR_END: controls
