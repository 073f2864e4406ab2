//! `evhi study convergence`: the graded study on the scenario's own scene.

use super::coarsest;
use crate::experiments::graded;
use crate::experiments::singular::{Edge, clamp_end_exponent, wedge_exponents};
use crate::geometry::Hold;
use crate::output::csv::Table;
use crate::output::rundir::RunDir;
use crate::scenario::Scenario;
use indicatif::{ProgressBar, ProgressStyle};
use std::fmt::Write as _;

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

pub(super) fn run(
    args: super::ConvergenceArgs,
    command: &str,
) -> Result<String, Box<dyn std::error::Error>> {
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
    let command = command.to_string();
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
    super::write_scenario(&out, &args.scenario, &command)?;
    graded::draw(
        &out.path(""),
        "convergence",
        &out.path("convergence.csv"),
        std::slice::from_ref(&scn.name),
        &families.iter().map(|f| f.0.clone()).collect::<Vec<_>>(),
    )?;
    out.publish()?;
    Ok(md)
}
