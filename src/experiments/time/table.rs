//! The time study's tables: the CSV of a study's rows and the rendering for the book.

#[allow(unused_imports)]
use super::*;

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
