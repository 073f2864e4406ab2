//! `evhi study stability`: where step solvers fail on the scenario's own law.

use super::map::NAN_COLUMNS;
use super::{bar, coarsest, write_scenario};
use crate::output::csv::Table;
use crate::output::rundir::RunDir;
use crate::scenario::Scenario;
use std::fmt::Write as _;

/// What each outcome of a cell means (the CSV's legend and the summary's).
const OUTCOMES: &str = "certified (every step certified), several solutions (Newton from other starts \
     ends more than 1e-6 away), converged (overshoots g) (a solver without a certificate, the penalty, \
     converged and some step's u_nu passed the limit g beyond rounding, measured), converged (within g) \
     (the same, u_nu never past g), converged (no limit) (the same where g is infinite: the penalty is \
     then the law itself), failed: <status> or failed: certificate over tolerance (at the step in \
     failed_step), error: <message> (the run did not start)";

/// What the hypotheses' columns mean (the summary's legend).
const CURVATURE: &str = "smallest step curvature: lambda_min(S + k diag(w) c_min), the smallest \
     eigenvalue of the step Hessian where the law's slope is at its steepest descent c_min, a lower \
     bound between the law's jumps (positive and no downward jump: every step is strictly convex, \
     so its minimiser is unique)";

/// Which step solver fails where on the scenario's own law: every registered
/// solver of the stability map at each mesh level n and time step k (certified;
/// several solutions from Newton's other starts; for the penalty, which has no
/// certificate, converged with u_nu past g, within g, or without a limit; failed
/// at which step; error where the run did not start; with mean iterations), and
/// per (n, k) the paper's smallness condition H(s) and the step convexity.
/// Writes stability.csv, hypotheses.csv, stability.md and stability.png/svg.
///
/// Example: evhi study stability --scenario data/scenarios/examples/cantilever.toml --quick --out runs/stab
#[derive(clap::Parser)]
pub struct StabilityArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long, value_parser = crate::scenario::arg_parser())]
    pub scenario: String,
    /// Levels n0, 2 n0 and steps 1, 8 (seconds); without it n0, 2 n0, 4 n0 and steps
    /// 1, 2, 4, …, 64 (a steady problem always takes one step). n0 is the coarsest
    /// n (4, 8, 16, …) that resolves the scene, but at least 8: 8 on the paper's
    /// scene.
    #[arg(long)]
    pub quick: bool,
    /// Map this step solver only (any of the registry; default: every solver the
    /// book's map runs).
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(crate::step::solver_values()))]
    pub solver: Option<String>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: std::path::PathBuf,
}

/// Runs the study from its parsed command line (its [`super::StudyEntry::run`]).
pub(super) fn from_matches(
    m: &clap::ArgMatches,
    command: &str,
    announce: bool,
) -> Result<String, Box<dyn std::error::Error>> {
    let args = <StabilityArgs as clap::FromArgMatches>::from_arg_matches(m)?;
    let _ = announce;
    run(args, command)
}

pub(super) fn run(
    args: StabilityArgs,
    command: &str,
) -> Result<String, Box<dyn std::error::Error>> {
    use super::map::{MapFigure, map_cell, solvers};
    let (scn, text) = Scenario::read(&args.scenario)?;
    let steady = scn.problem == crate::scenario::Problem::Steady;
    let multiples: &[usize] = if args.quick { &[1, 2] } else { &[1, 2, 4] };
    // Each level's scene: the rectangle's at n0 times the multiples, or a mesh
    // scene's body refined uniformly once per doubling (its n is then its count of
    // contact segments).
    let scenes: Vec<(usize, Scenario)> = match scn.body_mesh() {
        None => {
            let n0 = coarsest(&scn, multiples, 8)?;
            multiples.iter().map(|m| (m * n0, scn.clone())).collect()
        }
        Some(mesh) => {
            let mut out = vec![(mesh.n, scn.clone())];
            while out.len() < multiples.len() {
                let (fine, _) = out.last().expect("one").1.refined()?;
                let n = fine.body_mesh().expect("a mesh scene").n;
                out.push((n, fine));
            }
            out
        }
    };
    let levels: Vec<usize> = scenes.iter().map(|s| s.0).collect();
    let steps: Vec<usize> = if steady {
        vec![1]
    } else if args.quick {
        vec![1, 8]
    } else {
        vec![1, 2, 4, 8, 16, 32, 64]
    };
    let solvers = match &args.solver {
        Some(name) => vec![crate::step::solver(name)?.label],
        None => solvers(),
    };
    // A downward jump breaks both hypotheses at once: H(j) fails, so H(s) has no
    // finite m to test, and the step energy is not convex whatever its curvature
    // bound between the jumps says.
    let jumps_down = !scn.law.down_jumps().is_empty();
    let h_s_word = |h: &crate::show::Smallness| {
        if jumps_down {
            "n/a (H(j) fails)"
        } else if h.holds() {
            "holds"
        } else {
            "fails"
        }
    };
    let convex_word = |curv: f64| {
        if jumps_down {
            "no (downward jump)"
        } else if curv > 0.0 {
            "yes"
        } else {
            "no"
        }
    };
    let out = RunDir::open(&args.out)?;
    let progress = bar((levels.len() * steps.len() * (solvers.len() + 1)) as u64);
    let mut cells = vec![];
    let mut hyp = vec![];
    for (n, scn) in &scenes {
        let n = *n;
        for &st in &steps {
            let h_s = crate::show::Smallness::of(scn, n)?;
            let curvature = crate::scheme::step_curvature(scn, n, st)?;
            hyp.push((n, st, h_s, curvature));
            progress.inc(1);
            for &solver in &solvers {
                progress.set_message(format!("n = {n}, steps = {st}, {solver}"));
                cells.push((n, map_cell(scn, f64::NAN, n, st, solver)));
                progress.inc(1);
            }
        }
    }
    progress.finish_and_clear();
    let lines = vec![
        format!(
            "produced by evhi {} `evhi {command}`",
            env!("CARGO_PKG_VERSION")
        ),
        format!(
            "scenario {}; levels n = {levels:?}, steps {steps:?}, T = {}; outcome: {OUTCOMES}; step_curvature_min = lambda_min(S + k diag(w) c_min), the step Hessian's worst case between the law's jumps (> 0 and no downward jump: every step strictly convex); H_s is n/a and steps_convex no where the law jumps down (H(j) fails); {NAN_COLUMNS}",
            scn.name, scn.t_end
        ),
    ];
    let t = Table::new()
        .u64("n", cells.iter().map(|c| c.0 as u64).collect())
        .str(
            "solver",
            cells.iter().map(|c| c.1.solver.to_string()).collect(),
        )
        .u64("steps", cells.iter().map(|c| c.1.steps as u64).collect())
        .f64(
            "k",
            cells.iter().map(|c| scn.t_end / c.1.steps as f64).collect(),
        )
        .str(
            "outcome",
            cells.iter().map(|c| c.1.outcome.clone()).collect(),
        )
        .u64(
            "failed_step",
            cells.iter().map(|c| c.1.failed_step).collect(),
        )
        .f64(
            "mean_iterations",
            cells.iter().map(|c| c.1.mean_iterations).collect(),
        )
        .f64(
            "max_certificate_or_residual",
            cells.iter().map(|c| c.1.certificate).collect(),
        )
        .f64(
            "multistart_spread",
            cells.iter().map(|c| c.1.spread).collect(),
        );
    out.write_table("stability.csv", &t, &lines)?;
    let h = Table::new()
        .u64("n", hyp.iter().map(|r| r.0 as u64).collect())
        .u64("steps", hyp.iter().map(|r| r.1 as u64).collect())
        .f64("beta_B", hyp.iter().map(|r| r.2.beta_b).collect())
        // No finite m_J where the law jumps down: NaN, not the 0 of a law without one.
        .f64(
            "m_trace_norm_sq",
            hyp.iter()
                .map(|r| if jumps_down { f64::NAN } else { r.2.rhs() })
                .collect(),
        )
        .str(
            "H_s",
            hyp.iter().map(|r| h_s_word(&r.2).to_string()).collect(),
        )
        .f64("step_curvature_min", hyp.iter().map(|r| r.3).collect())
        .str(
            "steps_convex",
            hyp.iter().map(|r| convex_word(r.3).to_string()).collect(),
        );
    out.write_table("hypotheses.csv", &h, &lines)?;
    let mut md = format!(
        "# Step solvers on `{}` ({})\n\n{}\n\nOutcomes: {}.\n\nColumns: H(s) is the paper's smallness condition at the level's trace constant; {CURVATURE}.\n\n| n | steps | H(s) | smallest step curvature | steps convex | {} |\n|---|---|---|---|---|{}\n",
        scn.name,
        if args.quick { "quick" } else { "full" },
        lines[0],
        // Markdown would read the placeholders as HTML tags and drop them.
        OUTCOMES
            .replace("<status>", "`<status>`")
            .replace("<message>", "`<message>`"),
        solvers.join(" | "),
        "---|".repeat(solvers.len())
    );
    for (n, st, h_s, curv) in &hyp {
        let outcomes: Vec<String> = solvers
            .iter()
            .map(|s| {
                cells
                    .iter()
                    .find(|c| c.0 == *n && c.1.steps == *st && c.1.solver == *s)
                    .map_or(String::new(), |c| c.1.outcome.clone())
            })
            .collect();
        let _ = writeln!(
            md,
            "| {n} | {st} | {} | {curv:.4e} | {} | {} |",
            h_s_word(h_s),
            convex_word(*curv),
            outcomes.join(" | ")
        );
    }
    for (at, jump) in scn.law.down_jumps() {
        let _ = writeln!(md, "\nH(j) fails: p jumps down by {} at s = {at}.", -jump);
    }
    out.write("stability.md", md.as_bytes())?;
    // The map: one panel per solver, k across, n down.
    let fig = MapFigure {
        cells: cells
            .iter()
            .map(|(n, c)| {
                (
                    c.solver.to_string(),
                    scn.t_end / c.steps as f64,
                    *n as f64,
                    c.outcome.clone(),
                    c.mean_iterations,
                    // The colour reads convexity from this value: no step is convex
                    // where the law jumps down, whatever the bound between the jumps.
                    if jumps_down {
                        f64::NEG_INFINITY
                    } else {
                        hyp.iter()
                            .find(|r| r.0 == *n && r.1 == c.steps)
                            .map_or(f64::NAN, |r| r.3)
                    },
                )
            })
            .collect(),
        title: format!(
            "Where step solvers fail on {}, by time step k and mesh n (numbers: mean iterations per step)",
            scn.name
        ),
        row_desc: "mesh: segments n".into(),
        row_label: |n| format!("{n:.0}"),
    };
    crate::output::plot::both(&out.path(""), "stability", (1100, 1150), &fig)?;
    write_scenario(&out, &text, command)?;
    out.publish()?;
    Ok(md)
}
