//! Table 1 and Fig. 5: relative energy-norm errors $\|u_{ref} - u^{hk}\|_E / \|u_{ref}\|_E$
//! against a reference solution ($h = k = 1/512$), for $h = k = 1/4, \dots, 1/128$,
//! for the `literal` and the `figure` scenarios. Beyond the paper: the error split
//! into its $h$ part ($k$ at the reference value) and its $k$ part ($h$ at the
//! reference value), and where in $\Omega$ the error sits. The paper does not say at
//! which time it measures; we report $t = T$ and the maximum over the time levels
//! shared with the reference. The computation is [`evhi::study::split`].

use super::{Ctx, ExpError, col_f64, col_str, read_csv};
use evhi::output::csv::Table;
use evhi::output::plot::both;
use evhi::scenario::Scenario;
use evhi::study::split::figure::{COLOURS, Fig5};
pub use evhi::study::split::{Plan, Regions, compute, draw_split, plan};
use plotters::prelude::*;

mod table;
use table::{write_markdown, write_shift};

#[cfg(test)]
mod tests;

/// The paper's Table 1 (percent), keyed by $n$ with $h = k = 1/n$ ($h + k = 2/n$).
pub const PAPER: [(usize, f64); 6] = [
    (4, 24.099),
    (8, 12.835),
    (16, 6.407),
    (32, 3.153),
    (64, 1.540),
    (128, 0.741),
];

/// The scenarios of the study: the paper's data as printed, the loads of Figs. 3-4,
/// and the smooth scene that satisfies the corollary's regularity hypotheses.
pub const SCENARIOS: [&str; 3] = ["literal", "figure", "smooth"];

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let mut plan = plan(ctx.quick);
    let grid = *plan.levels.last().expect("levels");
    let own = plan.n_ref;
    let suffix = match ctx.reference {
        Some(r) => {
            if r <= own || !r.is_multiple_of(grid) {
                return Err(evhi::error::InputError::field(
                    "reference",
                    r,
                    format!(
                        "a multiple of {grid} (the finest level) above {own}, Table 1's own \
                         reference (which `reproduce table1` alone writes), e.g. {}",
                        2 * own
                    ),
                )
                .into());
            }
            evhi::scheme::check_memory(r, r / 2)?;
            // The shift compares with table1.csv: it must be there before the work.
            table::check_base(ctx)?;
            plan.n_ref = r;
            format!("_ref{r}")
        }
        None => String::new(),
    };
    let scenarios = SCENARIOS
        .iter()
        .map(|name| Scenario::load(name))
        .collect::<Result<Vec<_>, _>>()?;
    let (t, params) = compute(&scenarios, &plan, ctx, &Regions::paper(), Some(&PAPER))?;
    if !suffix.is_empty() {
        let command = format!("{} --reference {}", ctx.experiment, plan.n_ref);
        let path = ctx.write_as(&format!("table1{suffix}.csv"), &t, &command, &params)?;
        return write_shift(ctx, &path, &suffix, own);
    }
    let path = ctx.write("table1.csv", &t, &params)?;
    write_markdown(ctx, &path, &params)?;
    draw(ctx, &path)
}

fn draw(ctx: &Ctx, path: &std::path::Path) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, fam) = (col_str(&df, "scenario")?, col_str(&df, "family")?);
    let (n, steps) = (col_f64(&df, "n")?, col_f64(&df, "steps")?);
    let (et, em, pp) = (
        col_f64(&df, "rel_err_T_percent")?,
        col_f64(&df, "rel_err_max_percent")?,
        col_f64(&df, "paper_percent")?,
    );
    // x: h = k = 1/n for the h = k family; the varying h = 1/n or k = 1/N for the split.
    let x_of = |i: usize| match fam[i].as_str() {
        "k" => 1.0 / steps[i],
        _ => 1.0 / n[i],
    };
    let pick = |s: &str, f: &str, v: &[f64]| -> Vec<(f64, f64)> {
        (0..sc.len())
            .filter(|&i| sc[i] == s && fam[i] == f && v[i].is_finite())
            .map(|i| (x_of(i), v[i]))
            .collect()
    };
    let mut main = vec![(
        "paper, Table 1".to_string(),
        pick("literal", "h=k", &pp),
        BLACK,
        false,
    )];
    for (name, colour) in SCENARIOS.iter().zip(COLOURS) {
        main.push((
            format!("{name}, t = T"),
            pick(name, "h=k", &et),
            colour,
            false,
        ));
        main.push((
            format!("{name}, max over t"),
            pick(name, "h=k", &em),
            colour,
            true,
        ));
    }
    both(
        &ctx.figures,
        "fig5_errors",
        (1000, 750),
        &Fig5 {
            title: "Fig. 5: relative error in energy norm, h = k".into(),
            x_desc: "h = k = 1/n".into(),
            series: main,
        },
    )?;
    let names = SCENARIOS.map(str::to_string);
    draw_split(
        &ctx.figures,
        "fig5_split",
        path,
        &names,
        "h (h part, k as the reference's) or k (k part, h as the reference's)",
    )
}
