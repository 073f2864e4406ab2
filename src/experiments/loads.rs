//! The search for the `figure` loads (MODEL.md): the printed loads cannot bend the
//! body onto the law's branches, so vertical loads $f_0 = (0, -q_0)$, $f_2 = (0, -q_2)$
//! are chosen by computation. On a grid of round values we solve to $t = T$
//! ($g = 0.1$) and record where the contact nodes end up. A load qualifies when a
//! body force acts ($q_0 > 0$: the paper says constant vertical body forces act), the
//! centre of $\Gamma_3$ sits at the limit and every branch of the law and the limit
//! hold nodes; among those we take the one whose least-populated regime is largest
//! (the most even spread), the smaller load on ties.

use super::scenes::counts;
use super::{Ctx, ExpError};
use evhi::output::csv::Table;
use evhi::output::plot::REGIMES;
use evhi::scenario::Scenario;

/// The grid searched: $q_0$ (volume, N/m²) and $q_2$ (top, N/m).
pub fn grid() -> (Vec<f64>, Vec<f64>) {
    (
        vec![0.0, 5.0, 10.0],
        vec![25.0, 50.0, 75.0, 100.0, 125.0, 150.0],
    )
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let n = if ctx.quick { 16 } else { 64 };
    let base = Scenario::load("figure")?;
    let (q0s, q2s) = grid();
    let mut rows: Vec<(f64, f64, Vec<u64>, f64, String, f64)> = vec![];
    for &q0 in &q0s {
        for &q2 in &q2s {
            let scn = base
                .clone()
                .with_loads(Some([0.0, -q0]), Some([0.0, -q2]))?;
            let scene = super::scenes::solve(&scn, n)?;
            let regimes = scene.regimes;
            let c = counts(&regimes);
            let centre = scene.contact.len() / 2;
            let m = regimes.len() as f64;
            // least share over branch1..3 and limit
            let spread = c[1..]
                .iter()
                .map(|&k| k as f64 / m)
                .fold(f64::INFINITY, f64::min);
            rows.push((
                q0,
                q2,
                c,
                scene.contact[centre].u_nu,
                regimes[centre].clone(),
                spread,
            ));
        }
    }
    let qualifies = |r: &(f64, f64, Vec<u64>, f64, String, f64)| {
        r.0 > 0.0 && r.4 == "limit" && r.2[1..].iter().all(|&k| k > 0)
    };
    let best = rows
        .iter()
        .enumerate()
        .filter(|(_, r)| qualifies(r))
        .max_by(|(_, a), (_, b)| {
            a.5.total_cmp(&b.5)
                .then((b.0 + b.1).total_cmp(&(a.0 + a.1)))
        })
        .map(|(i, _)| i);
    let mut t = Table::new()
        .f64("q0", rows.iter().map(|r| r.0).collect())
        .f64("q2", rows.iter().map(|r| r.1).collect());
    for (k, name) in REGIMES.iter().enumerate() {
        t = t.u64(name, rows.iter().map(|r| r.2[k]).collect());
    }
    t = t
        .f64("u_nu_centre", rows.iter().map(|r| r.3).collect())
        .str("centre_regime", rows.iter().map(|r| r.4.clone()).collect())
        .f64("least_share", rows.iter().map(|r| r.5).collect())
        .str(
            "qualifies",
            rows.iter().map(|r| qualifies(r).to_string()).collect(),
        )
        .str(
            "chosen",
            (0..rows.len())
                .map(|i| (Some(i) == best).to_string())
                .collect(),
        );
    let params = format!(
        "scenario figure with f0 = (0,-q0), f2 = (0,-q2); g = {}, h = k = 1/{n}, t = T; chosen = qualifies (q0 > 0, centre at the limit, every branch populated) with the largest least_share",
        base.g()
    );
    ctx.write("loads_search.csv", &t, &params)?;
    if let Some(i) = best {
        ctx.add_units(1);
        ctx.log(&format!(
            "loads: chosen q0 = {}, q2 = {} (scenario figure has q0 = {}, q2 = {})",
            rows[i].0,
            rows[i].1,
            -base.f0()[1],
            -base.f2()[1]
        ));
    }
    Ok(())
}
