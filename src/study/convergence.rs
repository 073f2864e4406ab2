//! `evhi study convergence`: the graded study on the scenario's own scene.

use super::corners::{Edge, clamp_end_exponent, wedge_exponents};
use super::graded;
use super::{ExpError, coarsest, pct, study_ctx};
use crate::output::csv::Table;
use crate::output::rundir::RunDir;
use crate::scenario::Scenario;
use crate::support::Hold;
use std::fmt::Write as _;

/// The exponent a singular point predicts (the smallest real part in $(0, 1)$), or
/// NaN where the wedge analysis does not cover its holds (rollers).
fn predicted(s: &crate::geometry::Singularity, kappa: f64) -> f64 {
    let kappa_m = 3.0 - 4.0 * kappa;
    let edge = |h: Hold| match h {
        Hold::Clamped => Some(Edge::Clamped),
        Hold::Free => Some(Edge::Free),
        _ => None,
    };
    let (Some(a), Some(b)) = (edge(s.holds[0]), edge(s.holds[1])) else {
        return f64::NAN;
    };
    // No exponent is known in general where Gamma_3 ends inside the bottom.
    if s.contact_end {
        return f64::NAN;
    }
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

/// The holds' names at a singular point, a free hold on $\Gamma_3$ called `contact`
/// (its exponent is computed as for a free edge).
fn holds_named(s: &crate::geometry::Singularity, geo: &crate::geometry::Geometry) -> [String; 2] {
    let on_contact = s.point[1] == 0.0 && (geo.contact[0]..=geo.contact[1]).contains(&s.point[0]);
    s.holds.map(|h| match h {
        Hold::Free if on_contact => "contact (as free)".to_string(),
        h => h.name().to_string(),
    })
}

/// The reference's own error, from a family's increments $v_l = \|u_{n_l} - u_{2 n_l}\|$:
/// the Galerkin errors of nested spaces are orthogonal in the energy norm, so the
/// increments beyond the reference add in quadrature,
/// $\|u - u_{ref}\|^2 = \sum_{m \ge 0} v(n_{ref} 2^m)^2 = v(n_{ref})^2 / (1 - r^2)$, with
/// $r$ the ratio of one increment to the previous one. The exponent is the smaller of
/// the observed orders of the family's last two increment pairs (one if there is only
/// one): the slower decay, so that the estimate errs large, a rough bound rather than
/// a fit; `None` where it is not positive (no decay to carry on).
fn reference_error(n: &[f64], dofs: &[f64], inc: &[f64], n_ref: f64) -> Option<(f64, f64, f64)> {
    let pts: Vec<usize> = (0..inc.len())
        .filter(|&i| inc[i].is_finite() && inc[i] > 0.0)
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let order = |a: usize, b: usize| -2.0 * (inc[b] / inc[a]).ln() / (dofs[b] / dofs[a]).ln();
    let fine = &pts[pts.len().saturating_sub(3)..];
    let p = fine
        .windows(2)
        .map(|w| order(w[0], w[1]))
        .fold(f64::INFINITY, f64::min);
    if p.is_nan() || p <= 0.0 {
        return None;
    }
    let (a, b) = (fine[fine.len() - 2], fine[fine.len() - 1]);
    // One level's ratio of unknowns (about 4), hence of increments.
    let r = (dofs[b] / dofs[a]).powf(-p / 2.0);
    let levels_on = (n_ref / n[b]).log2();
    let at_ref = inc[b] * r.powf(levels_on);
    Some((p, inc[b], at_ref / (1.0 - r * r).sqrt()))
}

/// How the last observed uniform orders move against the limit the corners predict.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Trend {
    /// Each below the one before by more than 0.005, the last still above the limit
    /// by more than 0.1.
    Falling,
    /// The last within 0.1 of the limit, either side.
    Within,
    /// The last below the limit by more than 0.1.
    Below,
    /// The last two within 0.05 of each other, above the limit by more than 0.1.
    Level,
    /// None of these (or fewer than two orders).
    Unclear,
}

fn uniform_trend(last: &[f64], limit: f64) -> Trend {
    match last {
        [.., x] if (x - limit).abs() <= 0.1 => Trend::Within,
        [.., x] if *x < limit - 0.1 => Trend::Below,
        [_, _, ..] if last.windows(2).all(|w| w[1] < w[0] - 0.005) => Trend::Falling,
        [.., a, b] if (a - b).abs() <= 0.05 => Trend::Level,
        _ => Trend::Unclear,
    }
}

/// What the max increment over time is, and why no exponent is fitted to it.
const MAX_INCREMENT: &str = "The max increment over t is the largest over the level's steps t_j of \
     ||u_n(t_j) - u_2n(t_j)||_E / ||u_2n(t_j)||_E, each step relative to its own solution's norm, and \
     \"at t\" is where it occurs. From n to 2n both h and k = T/n halve, so the increment holds a time \
     part too: in the first steps, while k is not well below the material's relaxation time (the \
     initial layer of the book's chapter \"Time\"), that part can dominate, and the maximum then sits \
     at the first step and falls more slowly than h. No exponent is fitted to it.";

/// [`MAX_INCREMENT`] for a problem without viscosity: no time part.
const MAX_INCREMENT_STATIC: &str = "The max increment over t is the largest over the level's steps \
     t_j of ||u_n(t_j) - u_2n(t_j)||_E / ||u_2n(t_j)||_E, each step relative to its own solution's \
     norm, and \"at t\" is where it occurs. Without viscosity each step is the static problem at its \
     load (one solve at T for a steady problem), so the increment is the mesh's alone. No exponent is \
     fitted to it.";

/// Below this multiple of the reference's own error a measured error is not
/// resolved, where the two are orthogonal and add in quadrature (nested meshes):
/// $\sqrt{1 + 1/2.18^2} = 1.100$, so the reference's error moves the measured one by 10 %.
const RESOLVED: f64 = 2.18;

/// The same where nothing is assumed of the errors' directions (the split, whose time
/// errors subtract): by the triangle inequality the reference's error moves the
/// measured one by at most a tenth when it is a tenth of it.
const RESOLVED_ANY: f64 = 10.0;

/// Whether an error `e` is resolved against a reference whose own error is about `r`
/// (NaN: not estimated), at the multiple `threshold` of it.
fn resolved_word(e: f64, r: f64, threshold: f64) -> &'static str {
    if !r.is_finite() {
        "unknown"
    } else if e < threshold * r {
        "no"
    } else {
        "yes"
    }
}

/// The plan of the h, k and h = k split on uniform meshes, the reference four times
/// finer than the finest level in both modes: on the paper's scene (coarsest n 4)
/// the full plan is Table 1's ([`super::split::plan`]).
pub fn split_plan(n0: usize, quick: bool) -> super::split::Plan {
    split_plan_of(n0, if quick { 3 } else { 6 })
}

/// The split's `levels` levels from `n0` and its reference four times finer than the
/// finest.
fn split_plan_of(n0: usize, levels: usize) -> super::split::Plan {
    super::split::Plan {
        levels: (0..levels).map(|j| n0 << j).collect(),
        n_ref: n0 << (levels + 1),
        solver: crate::step::DEFAULT_SOLVER_ENTRY,
    }
}

/// The split reference's own error in one family, in % like the errors: the finest
/// level's error carried on to the reference at the family's smallest positive
/// observed order, capped at 1 (the scheme's order in h and in k: a larger observed
/// order is pre-asymptotic, or inflated by the reference's own error), so that the
/// estimate errs large where the orders fall towards 1. NaN where no order is
/// positive.
fn split_reference_error(err: &[f64], order: &[f64], param: &[f64], param_ref: f64) -> f64 {
    let p = order
        .iter()
        .copied()
        .filter(|o| o.is_finite() && *o > 0.0)
        .reduce(f64::min)
        .map(|p| p.min(1.0));
    match (err.last(), param.last(), p) {
        (Some(&e), Some(&x), Some(p)) => e * (x / param_ref).powf(p),
        _ => f64::NAN,
    }
}

/// Convergence in space and time on the scenario's own scene: a uniform and a
/// graded family of nested meshes (newest-vertex bisection of the coarsest grid
/// that resolves the scene; the graded one refined, exponent 0.4, towards the
/// scene's singular points, where the supports change along the boundary, listed
/// in singular.csv), h and k = T/n refined together. Writes convergence.csv (per
/// level: unknowns, error at T against a finer graded reference, increments
/// ||u_n - u_2n||_E / ||u_2n||_E at T and their maximum over time, observed orders
/// in N_dof^(-1/2)), convergence.md (the table; the fitted exponents; a rough
/// estimate of the reference's own error and which rows it leaves unresolved; a
/// note where uniform orders exceed what the corners predict, with their trend),
/// singular.csv (each singular point, its kind and the corner exponent it predicts)
/// and convergence.png/svg; for a viscoelastic scenario with proportional damping
/// also split.csv and split.png/svg, Table 1's h = k, h-only and k-only families on
/// uniform meshes against a reference four times finer, with their own rough
/// reference-error estimate and resolved flags in the summary, where those meshes
/// nest (the summary says why they are absent otherwise: on a 64 x 1 strip the rows
/// of cells go from 1 at n = 32 to 4 at n = 256, and a level is not embedded in the
/// reference).
///
/// Example: evhi study convergence --scenario data/scenarios/examples/cantilever.toml --quick --out runs/conv
#[derive(clap::Parser)]
pub struct ConvergenceArgs {
    /// A built-in scenario or the path of a scenario TOML file.
    #[arg(long, value_parser = crate::scenario::arg_parser())]
    pub scenario: String,
    /// Four levels per family and a reference at 32 times the coarsest n, the split
    /// on three levels against 16 times, within a budget of about 10 s of work (the
    /// paper's scene's quick study is estimated at 3 s and takes under 1 s, on the
    /// reduced loop): where the estimate is larger,
    /// the plan drops a level at a time, its references with it, down to two levels per
    /// family, and a scene still above the budget is refused before any work, with what
    /// it would take. Without
    /// it six uniform and five graded levels and a reference at 64 times, the split on
    /// six levels against 128 times, Table 1's plan on the paper's scene (about 8 s
    /// there on a two-core AMD EPYC: median of three whole runs, 7.7 to 8.8 s). Before
    /// any work the study says what it will cost (its levels, its reference's size and
    /// steps, and the seconds of work they take at the rate measured on that machine)
    /// and solves its coarsest level as `solve` would, so that a scene the time loop
    /// refuses is refused at once, with the loop's cause.
    #[arg(long)]
    pub quick: bool,
    /// The step solver of every run of the study (default newton), a certified one:
    /// the study compares runs whose every step is certified.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(crate::step::solver_values()))]
    pub solver: Option<String>,
    /// Output directory (created if missing).
    #[arg(long)]
    pub out: std::path::PathBuf,
    /// Print the cost notice before any work (the command line does; a study run from
    /// the library stays quiet).
    #[arg(skip)]
    pub announce: bool,
}

/// Runs the study from its parsed command line (its [`super::StudyEntry::run`]).
pub(super) fn from_matches(
    m: &clap::ArgMatches,
    command: &str,
    announce: bool,
) -> Result<String, Box<dyn std::error::Error>> {
    let args = <ConvergenceArgs as clap::FromArgMatches>::from_arg_matches(m)?;
    let args = ConvergenceArgs { announce, ..args };
    run(args, command)
}

pub(super) fn run(
    args: ConvergenceArgs,
    command: &str,
) -> Result<String, Box<dyn std::error::Error>> {
    use super::split;
    let (scn, text) = Scenario::read(&args.scenario)?;
    if scn.body().is_some() {
        let how = (args.quick, args.solver.as_deref(), args.out.as_path());
        return super::refined::run(how, scn, text, command);
    }
    let solver = super::study_solver(args.solver.as_deref())?;
    let Plans {
        plan,
        split_plan,
        no_split,
        cut,
    } = plans(&scn, &args, solver)?;
    let viscous = no_split.is_none();
    let sing = scn.geometry.singularities();
    let points = scn.geometry.singular_points();
    let mut families = vec![("uniform".to_string(), vec![])];
    if !points.is_empty() {
        families.push(("graded".to_string(), points.clone()));
    }
    let out = RunDir::open(&args.out)?;
    let bar = super::bar(graded::units(&plan, families.len()) as u64);
    let ctx = study_ctx(&out, args.quick, &bar, command);
    let graded::Graded {
        table, ref_dofs, ..
    } = graded::compute(
        std::slice::from_ref(&scn),
        &families,
        &plan,
        &points,
        None,
        &|m| ctx.log(m),
    )?;
    let unit = scn.geometry.width.min(scn.geometry.height);
    let split_table = if viscous {
        let regions = split::Regions {
            points: points.clone(),
            radius: unit / 8.0,
            near: "singular_points",
        };
        Some(
            split::compute(
                std::slice::from_ref(&scn),
                &split_plan,
                &ctx,
                &regions,
                None,
            )?
            .0,
        )
    } else {
        None
    };
    bar.finish_and_clear();
    let command = command.to_string();
    let lines = provenance_lines(&scn, &command, &plan, &families, ref_dofs);
    out.write_table("convergence.csv", &table, &lines)?;
    let sing_table = singular_table(&scn, &sing);
    out.write_table("singular.csv", &sing_table, &lines)?;
    let mut md = graded_report(
        &out,
        &scn,
        (args.quick, cut.as_ref()),
        &lines,
        &families,
        &plan,
        &sing,
    )?;
    match &split_table {
        Some(t) => split_report(&out, &mut md, &command, &scn, &split_plan, t)?,
        None => {
            let _ = writeln!(
                md,
                "\nNo h and k parts: {}.",
                no_split.as_deref().unwrap_or("")
            );
        }
    }
    out.write("convergence.md", md.as_bytes())?;
    super::write_scenario(&out, &text, &command)?;
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

/// The plans of the study: the graded families' and, where the time error can be parted
/// (a viscoelastic scene with proportional damping and nested uniform meshes), the
/// split's; `no_split` says why not otherwise; `cut` says how many levels quick mode's
/// budget took off, and what the uncut plan would have cost.
struct Plans {
    plan: graded::Plan,
    split_plan: super::split::Plan,
    no_split: Option<String>,
    cut: Option<Cut>,
}

/// Levels a quick plan dropped to fit [`QUICK_BUDGET_S`], and what the full quick plan
/// would have cost.
struct Cut {
    levels: usize,
    uncut: String,
}

/// The plans of the study at `cut` levels fewer than its mode's (only quick mode is
/// cut), from the coarsest $n_0$ at which every structured level resolves the scene.
struct Candidate {
    n0: usize,
    plan: graded::Plan,
    split_plan: super::split::Plan,
    no_split: Option<String>,
}

impl Candidate {
    fn new(
        scn: &Scenario,
        quick: bool,
        cut: usize,
        solver: &'static crate::step::SolverEntry,
    ) -> Result<Candidate, crate::error::InputError> {
        // The split's uniform levels and its reference are structured meshes: each must
        // resolve the scene (the bisection families nest by construction).
        let split_levels = if quick {
            3usize.saturating_sub(cut).max(2)
        } else {
            6
        };
        let split_multiples: Vec<usize> =
            if scn.problem.viscous() && scn.relaxation_time().is_some() {
                (0..split_levels)
                    .map(|j| 1 << j)
                    .chain([1 << (split_levels + 1)])
                    .collect()
            } else {
                vec![1]
            };
        let n0 = coarsest(scn, &split_multiples, 4)?;
        let levels = |k: usize| (0..k).map(|j| n0 << j).collect::<Vec<_>>();
        let plan = if quick {
            graded::Plan {
                uniform: levels(4 - cut),
                graded: levels(4 - cut),
                n_ref: n0 * (32 >> cut),
                solver,
            }
        } else {
            graded::Plan {
                uniform: levels(6),
                graded: levels(5),
                n_ref: n0 * 64,
                solver,
            }
        };
        let split_plan = super::split::Plan {
            solver,
            ..split_plan_of(n0, split_levels)
        };
        let no_split = no_split(scn, &split_plan);
        Ok(Candidate {
            n0,
            plan,
            split_plan,
            no_split,
        })
    }

    /// What the plan will cost, roughly, before any work: every run's steps times the
    /// work of a step, [`SECONDS_PER_UNKNOWN_STEP`] per unknown and
    /// [`SECONDS_PER_CONTACT_CUBE`] per cube of the contact nodes (the step solver
    /// factors its dense condensed matrix). A uniform level's sizes are counted from its
    /// grid; a graded one's from the family's level $2 n_0$, built here, its unknowns
    /// times four and its contact nodes times two per halving of $h$ (on the paper's
    /// scene that gives the quick reference 89 600 unknowns against its 90 130), or,
    /// where that level is too large to build for an estimate, as the uniform mesh's (a
    /// lower bound).
    fn cost(&self, scn: &Scenario, points: &[[f64; 2]]) -> Result<Cost, ExpError> {
        let (plan, n0, geo) = (&self.plan, self.n0, &scn.geometry);
        let uniform = |n: usize| {
            let contact = (geo.contact[1] - geo.contact[0]) / geo.width * n as f64;
            (grid_unknowns(scn, n), contact.round() as usize + 1)
        };
        let built = if !points.is_empty() && grid_unknowns(scn, 2 * n0) <= ESTIMATE_BUILD_MAX {
            Some(graded::first_sizes(geo, n0, points)?)
        } else {
            None
        };
        let graded = |n: usize| match built {
            _ if points.is_empty() => uniform(n),
            Some([first, _]) if n == n0 => first,
            Some([_, (dofs, contact)]) => {
                let r = n / (2 * n0);
                (dofs * r * r, contact * r)
            }
            None => uniform(n),
        };
        let work = |n: usize, (unknowns, contact): (usize, usize)| {
            steps_of(scn, n) as f64
                * (unknowns as f64 * SECONDS_PER_UNKNOWN_STEP
                    + (contact as f64).powi(3) * SECONDS_PER_CONTACT_CUBE)
        };
        // The check of the coarsest level, the families and the reference.
        let mut total = work(n0, uniform(n0));
        total += (plan.uniform.iter())
            .map(|&n| work(n, uniform(n)))
            .sum::<f64>();
        if !points.is_empty() {
            total += (plan.graded.iter())
                .map(|&n| work(n, graded(n)))
                .sum::<f64>();
        }
        let reference = graded(plan.n_ref);
        total += work(plan.n_ref, reference);
        // The split: its reference, the k family on the reference's mesh, and the
        // h = k and h families on each level's.
        if self.no_split.is_none() {
            let sp = &self.split_plan;
            let r = sp.n_ref;
            total += work(r, uniform(r));
            for &n in &sp.levels {
                total += work(n, uniform(r)) + work(n, uniform(n)) + work(r, uniform(n));
            }
        }
        Ok(Cost {
            ref_unknowns: reference.0,
            lower_bound: built.is_none() && !points.is_empty(),
            seconds: total,
        })
    }

    /// The plan in words: its levels and its reference, with `cost`.
    fn words(&self, scn: &Scenario, cost: &Cost) -> String {
        let levels = |v: &[usize]| match (v.first(), v.last()) {
            (Some(a), Some(b)) => format!("{a} to {b}"),
            _ => "none".into(),
        };
        let steps = steps_of(scn, self.plan.n_ref);
        format!(
            "uniform levels n = {}, graded n = {}, reference at n = {} with {} {:.1e} \
             unknowns and {steps} step(s): {} of work",
            levels(&self.plan.uniform),
            levels(&self.plan.graded),
            self.plan.n_ref,
            if cost.lower_bound {
                "at least"
            } else {
                "about"
            },
            cost.ref_unknowns as f64,
            duration(cost.seconds),
        )
    }
}

/// A duration in words: under a second, seconds, minutes or hours.
fn duration(seconds: f64) -> String {
    match seconds {
        s if s < 1.0 => "under a second".to_string(),
        s if s < 120.0 => format!("about {s:.0} s"),
        s if s < 7200.0 => format!("about {:.0} min", s / 60.0),
        s => format!("about {:.0} h", s / 3600.0),
    }
}

/// What a plan will cost, estimated before any work ([`Candidate::cost`]).
struct Cost {
    /// The reference's unknowns.
    ref_unknowns: usize,
    /// Whether `ref_unknowns` is only a lower bound (the uniform mesh's).
    lower_bound: bool,
    /// Seconds of work, at [`SECONDS_PER_UNKNOWN_STEP`].
    seconds: f64,
}

/// Quick mode's budget, seconds of work as [`Candidate::cost`] estimates it: a quick
/// plan above it is cut a level at a time, the reference and the split with it, down
/// to two levels per family (one observed order each); a scene whose smallest quick
/// plan is still above it is refused before any work.
const QUICK_BUDGET_S: f64 = 10.0;

/// The most levels quick mode drops to fit [`QUICK_BUDGET_S`]: four levels per family
/// become two.
const QUICK_CUTS: usize = 2;

/// The rates of [`Candidate::cost`] on a two-core AMD EPYC: seconds per unknown and
/// time step, and (below) per cube of a step's contact nodes. Fitted on a quiet machine
/// (load under 0.3) to two whole quick studies of issue 47's `K2` scene (a 3 x 1
/// rectangle, six singular points, the general loop), whose cost is almost all the
/// reference's: the plan cut to a reference at n = 256 (260 339 unknowns, 256 steps)
/// took 19.5 s of CPU, and the uncut plan, reference at n = 512 (1 042 695 unknowns,
/// 512 steps), 154 s. The two points fit a linear rate that covers the step's two
/// triangular solves, the certificate and the factorisation, with a contact term too
/// small to measure at these sizes (the fit gives 9e-12 s per cube). A `solve --timings`
/// of the n = 256 reference spends 13.1 s in its steps, 2.0e-7 s per unknown and step.
/// The rate errs large on the reduced loop, which the paper's scene's quick study runs.
const SECONDS_PER_UNKNOWN_STEP: f64 = 2.6e-7;

/// The rate of [`Candidate::cost`] per cube of a step's contact nodes (see
/// [`SECONDS_PER_UNKNOWN_STEP`]).
const SECONDS_PER_CONTACT_CUBE: f64 = 1.0e-11;

/// The largest uniform mesh, in unknowns, at level $2 n_0$ whose graded counterpart
/// [`Candidate::cost`] builds for its estimate (a fraction of a second).
const ESTIMATE_BUILD_MAX: usize = 200_000;

/// Why the split of `plan` does not run on `scn`, or `None` where it does: a steady or
/// elastic problem has no time error to part, the reduced loop it runs on needs
/// proportional damping, and its errors need every level embedded in the reference,
/// which structured meshes are only where the rows grow with $n$.
fn no_split(scn: &Scenario, plan: &super::split::Plan) -> Option<String> {
    match scn.problem {
        crate::scenario::Problem::Steady => {
            return Some(
                "the problem is steady (one solve at T), so there is no time error to part"
                    .to_string(),
            );
        }
        crate::scenario::Problem::Elastic => {
            return Some(
                "the problem is elastic (each step is the static problem with f(t_n)), so \
                 there is no time error to part"
                    .to_string(),
            );
        }
        crate::scenario::Problem::Viscoelastic => {}
    }
    if scn.relaxation_time().is_none() {
        return Some(
            "the damping is not proportional (C is not a multiple of G), and the split runs \
             on the reduced time loop, which needs it; the h = k families above carry both \
             parts"
                .to_string(),
        );
    }
    // A structured mesh has n H / W rows, rounded and at least 1: where rounding
    // moves them, a level's mesh is not a refinement of the reference's.
    let geo = &scn.geometry;
    let rows = |n: usize| crate::mesh::rows(n, geo);
    let r = plan.n_ref;
    plan.levels
        .iter()
        .find(|&&n| rows(n) * r != rows(r) * n)
        .map(|&n| {
            format!(
                "the split's uniform meshes do not nest: the {} x {} rectangle has {} row(s) \
                 of cells at n = {n} and {} at its reference's n = {r} (n H / W rounded, at \
                 least 1), not {r}/{n} times as many, so a level is not embedded in the \
                 reference, which the split's errors need; the graded families above nest \
                 by bisection and carry both parts",
                geo.width,
                geo.height,
                rows(n),
                rows(r),
            )
        })
}

fn plans(
    scn: &Scenario,
    args: &ConvergenceArgs,
    solver: &'static crate::step::SolverEntry,
) -> Result<Plans, Box<dyn std::error::Error>> {
    // Every mesh of the study comes from bisection of the diagonal cut, as a graded
    // `solve` does: another pattern would be ignored (or fail late), so it is refused.
    if scn.pattern != crate::mesh::Pattern::Diagonal {
        return Err(crate::error::InputError::field(
            "geometry.pattern",
            scn.pattern.name(),
            "\"diagonal\" for the convergence study (its uniform and graded meshes come \
             from newest-vertex bisection of the paper's diagonal cut)",
        )
        .into());
    }
    let points = scn.geometry.singular_points();
    let first = Candidate::new(scn, args.quick, 0, solver)?;
    // The reference is the graded family refined to n_ref, at least the unknowns of
    // the uniform mesh there: refused by name before any work if it cannot be built
    // (it used to refine until an allocation failed).
    let most = crate::mesh::MAX_N;
    if first.plan.n_ref > most {
        let (n0, ratio) = (first.n0, first.plan.n_ref / first.n0);
        return Err(crate::error::InputError::field(
            "scenario",
            &args.scenario,
            format!(
                "a scene the study can afford: the coarsest mesh that resolves this one has \
                 n = {n0}, so the reference would be at n = {} ({ratio} times that), beyond \
                 the {most} a mesh may have; put the ends of its supports, tractions and \
                 Gamma_3 on the grid of n = {} or coarser",
                first.plan.n_ref,
                most / ratio
            ),
        )
        .into());
    }
    // Quick mode's plan, cut a level at a time until it fits its budget.
    let first_cost = first.cost(scn, &points)?;
    let mut chosen = (first, first_cost, 0);
    while args.quick && chosen.1.seconds > QUICK_BUDGET_S && chosen.2 < QUICK_CUTS {
        let cut = chosen.2 + 1;
        let next = Candidate::new(scn, true, cut, solver)?;
        let cost = next.cost(scn, &points)?;
        chosen = (next, cost, cut);
    }
    let (candidate, cost, cut) = chosen;
    let n0 = candidate.n0;
    let over = args.quick && cost.seconds > QUICK_BUDGET_S;
    if !over {
        crate::scheme::check_memory(
            candidate.plan.n_ref,
            crate::mesh::rows(candidate.plan.n_ref, &scn.geometry),
        )?;
        if candidate.no_split.is_none() {
            crate::scheme::check_memory(
                candidate.split_plan.n_ref,
                crate::mesh::rows(candidate.split_plan.n_ref, &scn.geometry),
            )?;
        }
    }
    let cut = (cut > 0).then(|| -> Result<Cut, ExpError> {
        let uncut = Candidate::new(scn, true, 0, solver)?;
        let uncut_cost = uncut.cost(scn, &points)?;
        Ok(Cut {
            levels: cut,
            uncut: uncut.words(scn, &uncut_cost),
        })
    });
    let cut = cut.transpose()?;
    if args.announce && !over {
        crate::diag!(
            "study convergence ({}): {}, estimated for a two-core AMD EPYC{}",
            if args.quick { "quick" } else { "full" },
            candidate.words(scn, &cost),
            match &cut {
                Some(c) => format!(
                    "; cut by {} level(s) to quick mode's budget of {QUICK_BUDGET_S} s from {}",
                    c.levels, c.uncut
                ),
                None => String::new(),
            }
        );
        if let Some(why) = &candidate.no_split {
            crate::diag!("study convergence: no h and k parts: {why}");
        }
    }
    // The coarsest level first, as `solve` runs it: a scene the time loop refuses is
    // refused now, with the loop's own cause, not after the reference.
    let check_s = (grid_unknowns(scn, n0) * steps_of(scn, n0)) as f64 * SECONDS_PER_UNKNOWN_STEP;
    if !over || check_s <= QUICK_BUDGET_S {
        check_scene(scn, n0, solver)?;
    }
    if over {
        // The full study, where its reference is a mesh the study may build.
        let full = match Candidate::new(scn, false, 0, solver) {
            Ok(c) if c.plan.n_ref > most => format!(
                "Without --quick the reference would be at n = {}, beyond the {most} a mesh \
                 may have. C",
                c.plan.n_ref
            ),
            Ok(c) => match c.cost(scn, &points) {
                Ok(k) => format!("Run it without --quick ({}), or c", c.words(scn, &k)),
                Err(_) => "Run it without --quick, or c".to_string(),
            },
            Err(_) => "C".to_string(),
        };
        return Err(crate::error::InputError::field(
            "scenario",
            &args.scenario,
            format!(
                "a scene whose quick convergence study fits quick mode's budget of about \
                 {QUICK_BUDGET_S} s of work: even cut to {} levels per family it has {}, \
                 estimated for a two-core AMD EPYC. {full}hange the scene so that a coarser grid resolves it: the study \
                 starts from the coarsest n whose cells are near squares and whose nodes \
                 hold the ends of the supports, tractions and Gamma_3, here n = {n0} (a \
                 long thin body needs many cells along it)",
                candidate.plan.uniform.len(),
                candidate.words(scn, &cost),
            ),
        )
        .into());
    }
    Ok(Plans {
        plan: candidate.plan,
        split_plan: candidate.split_plan,
        no_split: candidate.no_split,
        cut,
    })
}

/// The unknowns of the structured grid of level `n`, two per node (clamped ones
/// included).
fn grid_unknowns(scn: &Scenario, n: usize) -> usize {
    2 * (n + 1) * (crate::mesh::rows(n, &scn.geometry) + 1)
}

/// The steps of a study's level `n`: $k = T/n$, or one step for a steady problem.
fn steps_of(scn: &Scenario, n: usize) -> usize {
    if scn.problem == crate::scenario::Problem::Steady {
        1
    } else {
        n
    }
}

/// Solves the study's coarsest level `n0` as its uniform family's first level runs
/// (the structured mesh, $k = T/n_0$, the general loop, the study's solver), through
/// the same [`Simulation`](crate::simulation::Simulation) as `solve`, before any other
/// work: a scene whose steps the loop refuses, say one too long or too thin for its
/// loads ([`RunError::Cancellation`](crate::scheme::RunError::Cancellation)), is refused
/// at once with the loop's own cause instead of after the reference.
fn check_scene(
    scn: &Scenario,
    n0: usize,
    solver: &'static crate::step::SolverEntry,
) -> Result<(), ExpError> {
    let steps = steps_of(scn, n0);
    let context = || {
        format!(
            "the study's coarsest level, n = {n0} with {steps} step(s), solved first as a \
             check of the scene"
        )
    };
    let sim = super::runs::simulation(scn, n0, steps).map_err(|e| e.at(context()))?;
    sim.solve_with(solver.build().as_mut(), &mut ())
        .map(|_| ())
        .map_err(|e| ExpError::from(e).at(context()))
}

/// The `#` lines of `convergence.csv` and `singular.csv`: the command, the scene, the
/// families, the levels, the reference and what the columns mean.
fn provenance_lines(
    scn: &Scenario,
    command: &str,
    plan: &graded::Plan,
    families: &[(String, Vec<[f64; 2]>)],
    ref_dofs: usize,
) -> Vec<String> {
    let steps_word = match scn.problem {
        crate::scenario::Problem::Steady => "one step (steady)".to_string(),
        crate::scenario::Problem::Elastic => {
            "k = T/n (elastic: every step is the static problem, so k does not enter the error at T)"
                .to_string()
        }
        crate::scenario::Problem::Viscoelastic => "k = T/n".to_string(),
    };
    let graded_family = families.len() > 1;
    let header = format!(
        "produced by evhi {} `evhi {}`\n# scenario {} ({}); families: {}; levels uniform {:?}{}; {steps_word}; reference: the {} family refined to n = {} ({} unknowns), {}; {}errors and increments relative, energy norm; orders: observed between a level and the previous one of its family, in N_dof^(-1/2) (1 = order 1 in h on a uniform mesh); NaN: the first level's orders and the last level's increments (nothing to compare with)",
        env!("CARGO_PKG_VERSION"),
        crate::output::run::one_line(command),
        scn.name,
        scn.problem.name(),
        families
            .iter()
            .map(|f| f.0.as_str())
            .collect::<Vec<_>>()
            .join(", "),
        plan.uniform,
        // A scene without singular points has no graded family (see `families`).
        if graded_family {
            format!(", graded {:?}", plan.graded)
        } else {
            String::new()
        },
        if graded_family { "graded" } else { "uniform" },
        plan.n_ref,
        ref_dofs,
        match scn.problem {
            crate::scenario::Problem::Steady => "one step".to_string(),
            crate::scenario::Problem::Elastic => "the static problem at T".to_string(),
            crate::scenario::Problem::Viscoelastic => format!("k = T/{}", plan.n_ref),
        },
        if graded_family {
            format!("grading exponent {}; ", graded::MU)
        } else {
            String::new()
        }
    );
    header.split("\n# ").map(str::to_string).collect()
}

/// `singular.csv`: each singular point of the scene, its kind and the exponent it
/// predicts.
fn singular_table(scn: &Scenario, sing: &[crate::geometry::Singularity]) -> Table {
    let kappa = scn.kappa;
    Table::new()
        .f64("x", sing.iter().map(|s| s.point[0]).collect())
        .f64("y", sing.iter().map(|s| s.point[1]).collect())
        .str(
            "kind",
            sing.iter()
                .map(|s| {
                    let [a, b] = holds_named(s, &scn.geometry);
                    if s.contact_end {
                        "contact end".to_string()
                    } else {
                        format!("{} {a}-{b}", if s.corner { "corner" } else { "side" })
                    }
                })
                .collect(),
        )
        .f64(
            "predicted_exponent",
            sing.iter().map(|s| predicted(s, kappa)).collect(),
        )
}

/// The Markdown summary of the graded study, read back from `convergence.csv` as
/// written: the table with what is resolved, the fitted exponents, the reference's own
/// error, the asymptotics against the corner exponents, a graded family that gains
/// nothing (also a warning on stderr), and the singular points.
fn graded_report(
    out: &RunDir,
    scn: &Scenario,
    (quick, cut): (bool, Option<&Cut>),
    lines: &[String],
    families: &[(String, Vec<[f64; 2]>)],
    plan: &graded::Plan,
    sing: &[crate::geometry::Singularity],
) -> Result<String, Box<dyn std::error::Error>> {
    let kappa = scn.kappa;
    // The Markdown summary, read back from the table just written.
    let df = crate::output::csv::read_csv(&out.path("convergence.csv"))?;
    let fam = crate::output::csv::col_str(&df, "family")?;
    let col = |c: &str| crate::output::csv::col_f64(&df, c);
    let (n, dofs, err, order, inc, order_inc, inc_max, t_max) = (
        col("n")?,
        col("dofs")?,
        col("rel_err_T_percent")?,
        col("order_dofs")?,
        col("increment_T_percent")?,
        col("order_increment_dofs")?,
        col("increment_max_percent")?,
        col("t_of_increment_max")?,
    );
    // The reference's own error, from the last family's increments.
    let last_family = &families.last().expect("a family").0;
    let rows: Vec<usize> = (0..fam.len()).filter(|&i| fam[i] == *last_family).collect();
    let pick = |v: &[f64]| rows.iter().map(|&i| v[i]).collect::<Vec<_>>();
    let estimate = reference_error(&pick(&n), &pick(&dofs), &pick(&inc), plan.n_ref as f64);
    // The measured error and the reference's own add in quadrature: below RESOLVED
    // times the latter, the reference moves the measured error by more than 10 %.
    let reference = estimate.map_or(f64::NAN, |(_, _, r)| r);
    let resolved = |e: f64| resolved_word(e, reference, RESOLVED);
    let mut md = String::new();
    let _ = writeln!(
        md,
        "# Convergence of `{}` ({})\n\n{}\n\n{}\n\n| family | n | unknowns | error at T, % | order | resolved | increment at T, % | order | max increment over t, % | at t |\n|---|---|---|---|---|---|---|---|---|---|",
        scn.name,
        if quick { "quick" } else { "full" },
        lines.join(". "),
        if scn.problem.viscous() {
            MAX_INCREMENT
        } else {
            MAX_INCREMENT_STATIC
        }
    );
    if let Some(c) = cut {
        // After the table's header: a paragraph of its own before the table.
        let at = md.find("\n\n| family").expect("the table's header");
        md.insert_str(
            at,
            &format!(
                "\n\nQuick mode's budget, about {QUICK_BUDGET_S} s of work, cut this plan by {} \
                 level(s) per family, and its reference with them: its full quick plan has {}.",
                c.levels, c.uncut
            ),
        );
    }
    for i in 0..fam.len() {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.3} | {} | {} | {:.3} | {} | {:.4} |",
            fam[i],
            n[i],
            dofs[i],
            pct(err[i]),
            order[i],
            resolved(err[i]),
            pct(inc[i]),
            order_inc[i],
            pct(inc_max[i]),
            t_max[i]
        );
    }
    let _ = writeln!(
        md,
        "\nFitted exponents (least squares of -2 ln v against ln N_dof over each family's levels; none \
         for the max increment over t, see above):\n"
    );
    for (f, _) in families {
        let rows: Vec<usize> = (0..fam.len()).filter(|&i| fam[i] == *f).collect();
        let pick = |v: &[f64]| rows.iter().map(|&i| v[i]).collect::<Vec<_>>();
        let d = pick(&dofs);
        let _ = writeln!(
            md,
            "- {f}: error at T {:.3}, increment at T {:.3}",
            fitted(&d, &pick(&err)),
            fitted(&d, &pick(&inc)),
        );
    }
    match estimate {
        Some((p, last, e)) => {
            let _ = writeln!(
                md,
                "\nThe reference's own error at T, roughly: about {} %, from the {last_family} family's last increment \
                 ({} %) carried on to n = {} at the exponent {p:.3}, the smaller of the observed orders of its last \
                 two increment pairs (the slower decay, so that the estimate errs large unless the true order is \
                 lower still), the increments beyond \
                 adding in quadrature (Galerkin orthogonality of nested spaces in the energy norm: exact for the \
                 linear static problem, perturbed here by the contact terms and by the time step, which changes \
                 with the level). An error below {RESOLVED} times this is marked not \
                 resolved: adding in quadrature, the reference's own error then changes it by more than 10 %.",
                pct(e),
                pct(last),
                plan.n_ref
            );
        }
        None => {
            let _ = writeln!(
                md,
                "\nThe reference's own error at T is not estimable: the {last_family} family's increments do not \
                 decrease (observed order not positive), so nothing says how far the reference itself is from \
                 the exact solution, and the errors above measure the distance to the reference only."
            );
        }
    }
    let lambda = sing
        .iter()
        .map(|s| predicted(s, kappa))
        .filter(|x| x.is_finite())
        .fold(f64::INFINITY, f64::min);
    let uniform_rows: Vec<usize> = (0..fam.len()).filter(|&i| fam[i] == "uniform").collect();
    let expected = lambda.min(1.0);
    let above: Vec<String> = uniform_rows
        .iter()
        .filter(|&&i| order[i].is_finite() && order[i] > expected + 0.1)
        .map(|&i| format!("{:.3} at n = {}", order[i], n[i]))
        .collect();
    // The trend over the last three observed orders (two if there are only two).
    let finite: Vec<f64> = uniform_rows
        .iter()
        .map(|&i| order[i])
        .filter(|o| o.is_finite())
        .collect();
    let last: &[f64] = &finite[finite.len().saturating_sub(3)..];
    let shown = last
        .iter()
        .map(|o| format!("{o:.3}"))
        .collect::<Vec<_>>()
        .join(", ");
    let trend = uniform_trend(last, expected);
    let latest = last.last().copied().unwrap_or(f64::NAN);
    let finer = match (quick, cut) {
        (true, None) => " (the full run, without --quick, goes two levels finer)".to_string(),
        (true, Some(c)) => format!(
            " (the full run, without --quick, goes {} levels finer)",
            2 + c.levels
        ),
        (false, _) => String::new(),
    };
    let _ = writeln!(
        md,
        "\nAsymptotics: on uniform meshes the order in N_dof^(-1/2) tends to min(1, lambda), lambda the smallest exponent below{}.{}",
        if lambda.is_finite() {
            format!(" ({expected:.3} here)")
        } else if sing.is_empty() {
            " (1 here: the scene has no singular point)".to_string()
        } else {
            // Points whose exponent is not computed (NaN below): the limit is unknown,
            // and the orders are compared with 1, the most it can be.
            " (not known here: no exponent below is computed, so it may lie under 1; the orders \
             are compared with 1, the most it can be)"
                .to_string()
        },
        match (above.is_empty(), trend) {
            (true, _) => String::new(),
            (false, Trend::Falling) => format!(
                " The uniform orders {} exceed it by more than 0.1; the last ones, {shown}, fall towards \
                 it: the coarse levels are not yet in the asymptotic range.",
                above.join(", ")
            ),
            (false, Trend::Within) => format!(
                " The uniform orders {} exceed it by more than 0.1; the last, {:.3}, is within 0.1 of it \
                 (the last ones: {shown}), consistent with the coarser levels not yet being in the \
                 asymptotic range.",
                above.join(", "),
                latest
            ),
            (false, Trend::Below) => format!(
                " The uniform orders {} exceed it by more than 0.1, while the last, {:.3}, is below it by \
                 more than 0.1 (the last ones: {shown}): the orders are not settled on these levels, and \
                 an order below the limit may be the reference's own error showing{finer}.",
                above.join(", "),
                latest
            ),
            (false, Trend::Level) => format!(
                " The uniform orders {} exceed it by more than 0.1, and the last ones, {shown}, level off \
                 above it: either the levels are not yet asymptotic, or this load excites the singular mode \
                 only weakly (its coefficient small), so that its rate shows only on finer meshes; these \
                 levels cannot tell which{finer}.",
                above.join(", ")
            ),
            (false, Trend::Unclear) => format!(
                " The uniform orders {} exceed it by more than 0.1, and the last ones, {shown}, show no \
                 clear trend: these levels cannot tell whether they are not yet asymptotic or the load \
                 excites the singular mode only weakly{finer}.",
                above.join(", ")
            ),
        }
    );
    // A graded family no better than the uniform one has missed something: a singular
    // point the code does not know, or levels not yet asymptotic.
    let last_order = |family: &str| {
        (0..fam.len())
            .filter(|&i| fam[i] == family && order[i].is_finite())
            .map(|i| order[i])
            .next_back()
    };
    if let (Some(g), Some(u)) = (last_order("graded"), last_order("uniform"))
        && g <= u + 0.05
    {
        let why = if u >= 0.95 {
            "the uniform family is already near order 1, so the singular points are too weakly \
             excited for grading to matter"
        } else {
            "a singular point it does not refine towards, or levels not yet asymptotic"
        };
        let warning = format!(
            "the graded family's last order, {g:.3}, is no better than the uniform one's, {u:.3}: \
             the grading gains nothing on these levels ({why}){finer}"
        );
        crate::diag!("warning: {warning}");
        let _ = writeln!(md, "\nWarning: {warning}.");
    }
    let _ = writeln!(
        md,
        "\nSingular points of the scene and the exponent each predicts (plane strain, Poisson ratio {kappa}; \
         NaN where rollers meet, which the wedge analysis here does not cover):\n"
    );
    if sing.is_empty() {
        let _ = writeln!(
            md,
            "- none: the supports leave no corner singularity, so order 1 is expected on uniform meshes"
        );
    }
    for s in sing {
        let [a, b] = holds_named(s, &scn.geometry);
        if s.contact_end {
            let _ = writeln!(
                md,
                "- ({}, {}): an end of Gamma_3 inside the bottom, free meeting contact: no exponent \
                 known (graded towards all the same)",
                s.point[0], s.point[1]
            );
            continue;
        }
        let _ = writeln!(
            md,
            "- ({}, {}): {} {a} meeting {b}: exponent {:.4}",
            s.point[0],
            s.point[1],
            if s.corner {
                "corner,"
            } else {
                "inside a side,"
            },
            predicted(s, kappa)
        );
    }
    Ok(md)
}

/// The h and k parts: writes `split.csv` and its figure, and adds their table and the
/// reference's own error per family to the summary `md`.
fn split_report(
    out: &RunDir,
    md: &mut String,
    command: &str,
    scn: &Scenario,
    split_plan: &super::split::Plan,
    t: &Table,
) -> Result<(), Box<dyn std::error::Error>> {
    use super::split;
    out.write_table("split.csv", t, &split_lines(command, scn, split_plan))?;
    let df = crate::output::csv::read_csv(&out.path("split.csv"))?;
    let f = crate::output::csv::col_str(&df, "family")?;
    let col = |c: &str| crate::output::csv::col_f64(&df, c);
    let (sn, st, et, ot, em, om) = (
        col("n")?,
        col("steps")?,
        col("rel_err_T_percent")?,
        col("order_T")?,
        col("rel_err_max_percent")?,
        col("order_max")?,
    );
    // The reference's own error per family and measure (at T, max over t).
    let families: Vec<String> = {
        let mut v: Vec<String> = vec![];
        for x in &f {
            if !v.contains(x) {
                v.push(x.clone());
            }
        }
        v
    };
    let estimate = |family: &str, e: &[f64], o: &[f64]| {
        let rows: Vec<usize> = (0..f.len()).filter(|&i| f[i] == family).collect();
        let pick = |v: &[f64]| rows.iter().map(|&i| v[i]).collect::<Vec<_>>();
        let param = if family == "k" { pick(&st) } else { pick(&sn) };
        split_reference_error(&pick(e), &pick(o), &param, split_plan.n_ref as f64)
    };
    let est: Vec<(String, f64, f64)> = families
        .iter()
        .map(|fam| {
            (
                fam.clone(),
                estimate(fam, &et, &ot),
                estimate(fam, &em, &om),
            )
        })
        .collect();
    let flag = |family: &str, e: f64, which: usize| {
        let r = est
            .iter()
            .find(|x| x.0 == family)
            .map_or(f64::NAN, |x| if which == 0 { x.1 } else { x.2 });
        resolved_word(e, r, RESOLVED_ANY)
    };
    let _ = writeln!(
        md,
        "\n**The h and k parts (uniform structured meshes).** {}\n\n| family | n | steps | error at T, % | order | resolved | max over t, % | order | resolved |\n|---|---|---|---|---|---|---|---|---|",
        split_lines(command, scn, split_plan)[1]
    );
    for i in 0..f.len() {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} | {:.3} | {} | {} | {:.3} | {} |",
            f[i],
            sn[i],
            st[i],
            pct(et[i]),
            ot[i],
            flag(&f[i], et[i], 0),
            pct(em[i]),
            om[i],
            flag(&f[i], em[i], 1)
        );
    }
    let _ = writeln!(
        md,
        "\nThe reference here is only four times finer than the finest level, so its own error is a \
         large part of the finest errors and inflates the finest orders. Its error, roughly, in each \
         family: the finest level's error carried on to n (or, for k, N) = {} at the family's smallest \
         positive observed order, capped at 1, the scheme's order in h and in k (the estimate errs large \
         unless the true order is lower still, as where the orders still fall): {}. The errors of the levels and of the reference are not \
         assumed to add in quadrature (the time errors subtract): a row whose error is below {RESOLVED_ANY} \
         times this is marked not resolved, since the reference's error may then move it by more than 10 %, \
         and its order is not a rate. The graded study above measures the orders without a reference: its \
         increments need none.",
        split_plan.n_ref,
        est.iter()
            .map(|(fam, t, m)| format!("{fam} {} % at T, {} % max over t", pct(*t), pct(*m)))
            .collect::<Vec<_>>()
            .join("; ")
    );
    split::draw_split(
        &out.path(""),
        "split",
        &out.path("split.csv"),
        std::slice::from_ref(&scn.name),
        "1/n (h part: h = W/(2n), k of the reference) or 1/N (k part: k = T/N, h of the reference)",
    )?;
    Ok(())
}

/// The provenance lines of `split.csv`.
fn split_lines(command: &str, scn: &Scenario, plan: &super::split::Plan) -> Vec<String> {
    vec![
        format!(
            "produced by evhi {} `evhi {}`",
            env!("CARGO_PKG_VERSION"),
            crate::output::run::one_line(command)
        ),
        format!(
            "scenario {}; uniform structured meshes n = {:?} against a reference at n = {} with N = {} steps; families: h=k (N = n steps), h (N = {} steps, the reference's k), k (the reference's mesh, N = n steps); rel_err_T at t = T, rel_err_max = max_j ||e_j||_E / max_j ||u_ref,j||_E over the level's steps; order_T and order_max are observed orders in 1/n (h=k, h) or in k (k); shares: the squared error within {} of a singular point, within it of y = 0, and the rest",
            scn.name,
            plan.levels,
            plan.n_ref,
            plan.n_ref,
            plan.n_ref,
            scn.geometry.width.min(scn.geometry.height) / 8.0
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::{Trend, uniform_trend};

    #[test]
    fn trends_of_the_reviewed_runs() {
        // `figure`, full: falling steadily into the band above ½.
        assert_eq!(uniform_trend(&[0.582, 0.572, 0.564], 0.5), Trend::Within);
        // the cantilever, quick: a drop, then flat at 1 above its 0.711.
        assert_eq!(uniform_trend(&[1.311, 1.004, 1.024], 0.711), Trend::Level);
        assert_eq!(uniform_trend(&[1.3, 1.1, 0.95], 0.711), Trend::Falling);
        assert_eq!(uniform_trend(&[0.9, 1.2, 1.0], 0.711), Trend::Unclear);
        assert_eq!(uniform_trend(&[], 0.711), Trend::Unclear);
        assert_eq!(uniform_trend(&[0.8, 0.3], 0.5), Trend::Below);
    }
}
