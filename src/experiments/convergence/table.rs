//! Table 1's tables beyond the CSV: the shift of every entry against a finer reference
//! and the rendering of Table 1 for the book.

#[allow(unused_imports)]
use super::*;

/// `table1.csv`, which a finer reference's shift compares with: refused by name if
/// missing.
pub(super) fn check_base(ctx: &Ctx) -> Result<std::path::PathBuf, ExpError> {
    let base = ctx.data.join("table1.csv");
    if base.exists() {
        Ok(base)
    } else {
        Err(ExpError::File(evhi::output::FileError::Table {
            path: base.display().to_string(),
            message: format!(
                "missing: run `evhi reproduce table1{}` (with the same --data) before a finer \
                 reference",
                if ctx.quick { " --quick" } else { "" }
            ),
        }))
    }
}

/// How far each error of `table1.csv` (reference 1/512) moves with the finer
/// reference of `path`: both values and their ratio, at $T$ and over $t$.
pub(super) fn write_shift(
    ctx: &Ctx,
    path: &std::path::Path,
    suffix: &str,
    own: usize,
) -> Result<(), ExpError> {
    let base = check_base(ctx)?;
    let (old, new) = (read_csv(&base)?, read_csv(path)?);
    // A row is its scenario, family and level: n, or the steps in the k family.
    let key = |df: &evhi::output::csv::Frame| -> Result<Vec<String>, ExpError> {
        let (s, f) = (col_str(df, "scenario")?, col_str(df, "family")?);
        let (n, k) = (col_f64(df, "n")?, col_f64(df, "steps")?);
        Ok((0..s.len())
            .map(|i| {
                let level = if f[i] == "k" { k[i] } else { n[i] };
                format!("{} {} {level}", s[i], f[i])
            })
            .collect())
    };
    if key(&old)? != key(&new)? {
        return Err(ExpError::File(evhi::output::FileError::Table {
            path: base.display().to_string(),
            message: "its rows are not those of the finer reference's table (quick mode?)".into(),
        }));
    }
    let col = |df: &evhi::output::csv::Frame, c: &str| col_f64(df, c);
    let (t0, t1) = (
        col(&old, "rel_err_T_percent")?,
        col(&new, "rel_err_T_percent")?,
    );
    let (m0, m1) = (
        col(&old, "rel_err_max_percent")?,
        col(&new, "rel_err_max_percent")?,
    );
    let ratio = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| b / a).collect();
    let t = Table::new()
        .str("scenario", col_str(&new, "scenario")?)
        .str("family", col_str(&new, "family")?)
        .f64("n", col(&new, "n")?)
        .f64("steps", col(&new, "steps")?)
        .f64(&format!("rel_err_T_percent_ref{own}"), t0.clone())
        .f64(&format!("rel_err_T_percent{suffix}"), t1.clone())
        .f64("ratio_T", ratio(&t0, &t1))
        .f64(&format!("rel_err_max_percent_ref{own}"), m0.clone())
        .f64(&format!("rel_err_max_percent{suffix}"), m1.clone())
        .f64("ratio_max", ratio(&m0, &m1));
    let command = format!(
        "{} --reference {}",
        ctx.experiment,
        suffix.trim_start_matches("_ref")
    );
    ctx.write_as(
        &format!("table1_reference_shift{suffix}.csv"),
        &t,
        &command,
        &format!(
            "table1.csv (reference h = k = 1/{own}) against the finer reference; ratio = finer / {own}"
        ),
    )?;
    Ok(())
}

/// The Markdown Table 1, ours beside the paper's, from the CSV.
pub(super) fn write_markdown(
    ctx: &Ctx,
    path: &std::path::Path,
    params: &str,
) -> Result<(), ExpError> {
    let df = read_csv(path)?;
    let (sc, fam) = (col_str(&df, "scenario")?, col_str(&df, "family")?);
    let (n, hk) = (col_f64(&df, "n")?, col_f64(&df, "h_plus_k")?);
    let (et, em, ot, om, pp) = (
        col_f64(&df, "rel_err_T_percent")?,
        col_f64(&df, "rel_err_max_percent")?,
        col_f64(&df, "order_T")?,
        col_f64(&df, "order_max")?,
        col_f64(&df, "paper_percent")?,
    );
    let f = |x: f64| {
        if x.is_finite() {
            format!("{x:.3}")
        } else {
            "".into()
        }
    };
    let mut md = format!(
        "<!-- {} -->\n<!-- {} -->\n\n",
        ctx.provenance(ctx.experiment, "").join(" "),
        params
    );
    let rows: Vec<usize> = (0..sc.len())
        .filter(|&i| fam[i] == "h=k" && sc[i] == SCENARIOS[0])
        .collect();
    // Two narrow tables, at t = T and the maximum over t, each with the paper's column.
    for (title, err, ord) in [
        ("at t = T", &et, &ot),
        (
            "maximum over t (over the time levels shared with the reference)",
            &em,
            &om,
        ),
    ] {
        md += &format!(
            "Relative error in energy norm, h = k, in percent, {title}; order = observed order between successive rows.\n\n| h + k | paper |"
        );
        for name in SCENARIOS {
            md += &format!(" {name} | order |");
        }
        md += "\n|---|---|";
        md += &"---|---|".repeat(SCENARIOS.len());
        md += "\n";
        for &i in &rows {
            md += &format!("| 1/{} | {} |", (1.0 / hk[i]).round(), f(pp[i]));
            for name in SCENARIOS {
                let j = (0..sc.len())
                    .find(|&j| fam[j] == "h=k" && sc[j] == name && n[j] == n[i])
                    .expect("every scenario");
                md += &format!(" {} | {} |", f(err[j]), f(ord[j]));
            }
            md += "\n";
        }
        md += "\n";
    }
    ctx.write_file(&ctx.data_path("table1.md"), md.as_bytes())
}
