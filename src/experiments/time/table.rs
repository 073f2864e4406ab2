//! The time study's tables: the CSV of a study's rows and the rendering for the book.

#[allow(unused_imports)]
use super::*;

/// `data/time_study.md`: the study as tables for the book (three significant digits).
pub(super) fn write_markdown(
    ctx: &Ctx,
    path: &std::path::Path,
    plan: &Plan,
) -> Result<(), ExpError> {
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
        ctx.provenance(
            ctx.experiment,
            &format!("n = {}, N_ref = {}", plan.n, plan.n_ref)
        )
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
