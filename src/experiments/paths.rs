//! Both time loops on the same runs: the general loop of [`evhi::scheme`] (a
//! forward and a backward sweep with the factor of $A + kB$ per step) and the
//! reduced loop of [`evhi::reduced`] (the contact problem alone per step, for
//! proportional damping). For the three scenes and a load history at
//! $h = k = 1/n$: the largest gap between the two in the contact unknowns over all
//! steps, in the energy norms over all steps and in the field at $T$, each relative
//! to the general loop's largest value, and both loops' largest certificate.
//! `data/paths.csv`.

use super::{Ctx, ExpError};
use evhi::certificate::ContactState;
use evhi::output::csv::Table;
use evhi::scenario::Scenario;
use evhi::scheme::Run;
use evhi::simulation::{Loop, OnStep, RunSettings, Simulation};
use evhi::step::newton::Newton;

/// $\max|a - b| / \max|a|$.
fn gap(a: &[f64], b: &[f64]) -> f64 {
    let scale = evhi::dense::inf_norm(a).max(f64::MIN_POSITIVE);
    let diff = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
    diff / scale
}

/// One run of a loop: the contact unknowns of every step, the run.
type Traced = (Vec<f64>, Run);

/// The general loop on scenarios that share the step matrix, in one batch: one
/// factorisation of $A + kB$ serves them all, and each sweep over it several
/// columns, each column's arithmetic as in a run alone (`tests/linalg.rs`).
fn general(scns: &[&Scenario], n: usize) -> Result<Vec<Traced>, ExpError> {
    let owned: Vec<Scenario> = scns.iter().map(|s| (*s).clone()).collect();
    let mut r = vec![vec![]; scns.len()];
    let runs = super::run_newton_batch_states(&owned, n, n, &mut |i, _, _, _, c| {
        r[i].extend(c.iter().map(|c| c.u_nu))
    })?;
    Ok(r.into_iter().zip(runs).collect())
}

fn reduced(scn: &Scenario, n: usize) -> Result<Traced, ExpError> {
    let mut r = vec![];
    let settings = RunSettings::general(n, n).with_path(Loop::Reduced);
    let sim = Simulation::new(scn.clone(), settings)?;
    let mut observer =
        OnStep::new(|_, _, _, c: &[ContactState]| r.extend(c.iter().map(|c| c.u_nu)));
    let run = sim.solve_with(&mut Newton::default(), &mut observer)?.run;
    Ok((r, run))
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    // Every scene up to 1/256; `figure` alone at 1/512 (its general run takes 16 s).
    let (levels, finest): (Vec<usize>, usize) = if ctx.quick {
        (vec![8, 16], 16)
    } else {
        (vec![16, 32, 64, 128, 256], 512)
    };
    let ramp = Scenario::load("figure")?.with_ramp(0.25)?;
    let scenes: Vec<(String, Scenario)> = ["literal", "figure", "smooth"]
        .iter()
        .map(|name| Ok((name.to_string(), Scenario::load(name)?)))
        .chain([Ok(("figure-ramp".to_string(), ramp))])
        .collect::<Result<_, ExpError>>()?;
    let mut jobs: Vec<(usize, usize)> = (0..scenes.len())
        .flat_map(|s| levels.iter().map(move |&n| (s, n)))
        .collect();
    if finest > *levels.last().expect("levels") {
        jobs.push((1, finest));
    }
    ctx.add_units(jobs.len());
    // The general runs of each level, batched by step matrix.
    let mut generals: std::collections::BTreeMap<(usize, usize), Traced> = Default::default();
    let mut rows = vec![];
    for (s, n) in jobs {
        let (name, scn) = &scenes[s];
        if !generals.contains_key(&(s, n)) {
            let group: Vec<usize> = (0..scenes.len())
                .filter(|&o| scenes[o].1.same_operator(scn) && (o == s || levels.contains(&n)))
                .collect();
            let batch = general(&group.iter().map(|&o| &scenes[o].1).collect::<Vec<_>>(), n)?;
            for (o, traced) in group.into_iter().zip(batch) {
                generals.insert((o, n), traced);
            }
        }
        let (rg, g) = generals.remove(&(s, n)).expect("run above");
        let (rr, r) = reduced(scn, n)?;
        let energy =
            |run: &Run| -> Vec<f64> { run.records.iter().map(|s| s.energy_norm).collect() };
        let cert = |run: &Run| {
            (run.records.iter())
                .map(|s| s.certificate.max())
                .fold(0.0, f64::max)
        };
        rows.push((
            name.clone(),
            n,
            gap(&rg, &rr),
            gap(&energy(&g), &energy(&r)),
            gap(&g.u, &r.u),
            cert(&g),
            cert(&r),
        ));
        ctx.log(&format!("{name}: h = k = 1/{n}"));
    }
    let t = Table::new()
        .str("scenario", rows.iter().map(|r| r.0.clone()).collect())
        .u64("n", rows.iter().map(|r| r.1 as u64).collect())
        .u64("steps", rows.iter().map(|r| r.1 as u64).collect())
        .f64("contact_gap", rows.iter().map(|r| r.2).collect())
        .f64("energy_gap", rows.iter().map(|r| r.3).collect())
        .f64("field_gap_T", rows.iter().map(|r| r.4).collect())
        .f64(
            "general_max_certificate",
            rows.iter().map(|r| r.5).collect(),
        )
        .f64(
            "reduced_max_certificate",
            rows.iter().map(|r| r.6).collect(),
        );
    ctx.write(
        "paths.csv",
        &t,
        "h = k = 1/n; gaps between the general and the reduced time loop, each max |general - reduced| / max |general| over all steps (contact unknowns u_nu, energy norms) or over the dofs at T (field); certificates: the largest of each loop (the reduced loop's are on the condensed problem where no field is formed); solver newton",
    )?;
    Ok(())
}
