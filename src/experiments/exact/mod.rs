//! The exact-solution study: Corollary 4.1 and the Céa inequality (4.16) observed
//! against manufactured solutions ([`evhi::manufactured`]), every error measured
//! against the truth.
//!
//! For each solution and family of levels $(n, N)$, $h = 1/n$, $k = T/N$, the relative
//! energy errors $\max_n\|u(t_n) - u^{hk}_n\|_E / \max_n\|u(t_n)\|_E$, at $t = T$, and in the
//! discrete $L^2(0, T; E)$ norm, with observed orders $\log_2(e_{\text{coarse}}/e_{\text{fine}})$
//! between successive levels (each halves $h$, $k$ or both); the step $t_n$ where the
//! maximum is reached and how many contact nodes of $u^{hk}_n$ are at $g$ there (whether
//! the maximum sees the unilateral limit); and the observed constant
//! of (4.24): its left side in $\|\cdot\|_V$ over $h^2 + k^2$. For (b) and (d) on
//! $h = k$: each term of the right side of (4.16) with its order; for (b) the same
//! runs with the compliance integral computed exactly (the variational crime); the
//! regime counts per step; the quadrature's own error; the residual estimator's
//! efficiency on every solution.

mod adaptive;
mod estimator;
mod figure;
mod hold;

use super::{Ctx, ExpError};
use evhi::manufactured::run::{ExactRun, REGIMES, Rule, run, run_rules};
use evhi::manufactured::{Data, Solution, load_vector};
use evhi::output::csv::Table;
use evhi::scenario::Scenario;

/// One family of levels of one solution: (n, N) pairs.
pub struct Family {
    pub sol: Solution,
    /// `h=k`, `h` ($N$ fixed) or `k` ($n$ fixed, $N$ powers of two); `k_on_step`: $n$
    /// fixed, $N = 5\cdot 2^m$, so that $t = 0.4$ (where (g) lands) is a time step.
    pub kind: &'static str,
    pub levels: Vec<(usize, usize)>,
}

/// The families of the study.
pub fn families(quick: bool) -> Vec<Family> {
    use Solution::*;
    let hk = |ns: &[usize]| ns.iter().map(|&n| (n, n)).collect::<Vec<_>>();
    let h = |ns: &[usize], steps: usize| ns.iter().map(|&n| (n, steps)).collect::<Vec<_>>();
    let k = |n: usize, ss: &[usize]| ss.iter().map(|&s| (n, s)).collect::<Vec<_>>();
    let fam = |sol, kind, levels| Family { sol, kind, levels };
    if quick {
        let ns = [8, 16, 32];
        vec![
            fam(Branch1, "h=k", hk(&ns)),
            fam(Regimes, "h=k", hk(&ns)),
            fam(Regimes, "h", h(&ns, 32)),
            fam(Regimes, "k", k(32, &[2, 4, 8])),
            fam(Steady, "h", h(&[8, 16, 32, 64], 1)),
            fam(Moving, "h=k", hk(&ns)),
            fam(P1, "k", k(16, &[4, 8, 16, 32])),
            fam(P1, "h", h(&ns, 16)),
            fam(P1Limit, "k", k(16, &[4, 8, 16, 32])),
            fam(P1Limit, "h=k", hk(&ns)),
            fam(Landing, "k", k(16, &[4, 8, 16, 32])),
            fam(Landing, "k_on_step", k(16, &[5, 10, 20, 40])),
            fam(Landing, "h=k", hk(&ns)),
            fam(OffNode, "h=k", hk(&ns)),
        ]
    } else {
        let ns = [8, 16, 32, 64, 128];
        vec![
            fam(Branch1, "h=k", hk(&ns)),
            fam(Regimes, "h=k", hk(&ns)),
            fam(Regimes, "h", h(&ns, 256)),
            fam(Regimes, "k", k(256, &[4, 8, 16, 32, 64, 128])),
            fam(Steady, "h", h(&[8, 16, 32, 64, 128, 256], 1)),
            fam(Moving, "h=k", hk(&ns)),
            fam(P1, "k", k(64, &[4, 8, 16, 32, 64, 128, 256, 512])),
            fam(P1, "h", h(&ns, 64)),
            fam(P1Limit, "k", k(64, &[4, 8, 16, 32, 64, 128, 256, 512])),
            fam(P1Limit, "h=k", hk(&ns)),
            fam(Landing, "k", k(64, &[4, 8, 16, 32, 64, 128, 256, 512])),
            fam(
                Landing,
                "k_on_step",
                k(64, &[5, 10, 20, 40, 80, 160, 320, 640]),
            ),
            fam(Landing, "h=k", hk(&ns)),
            fam(OffNode, "h=k", hk(&ns)),
        ]
    }
}

/// $\log_2(a / b)$ between successive levels (NaN for the first).
fn orders(v: &[f64]) -> Vec<f64> {
    (0..v.len())
        .map(|i| {
            if i == 0 {
                f64::NAN
            } else {
                (v[i - 1] / v[i]).log2()
            }
        })
        .collect()
}

/// The study's rows, kept to write its tables.
struct Study {
    scn: Scenario,
    /// (family index, run) in the order of [`families`].
    runs: Vec<(usize, ExactRun)>,
    /// (b) on h = k with the exact rule, and the nodal–exact distance per level.
    crime: Vec<(ExactRun, f64)>,
}

pub fn run_study(ctx: &Ctx) -> Result<(), ExpError> {
    let scn = Scenario::load("literal")?;
    if scn.g() != evhi::manufactured::G {
        return Err(evhi::error::InputError::field(
            "g",
            scn.g(),
            format!(
                "the g = {} the manufactured solutions are built for",
                evhi::manufactured::G
            ),
        )
        .into());
    }
    let fams = families(ctx.quick);
    ctx.add_units(fams.iter().map(|f| f.levels.len()).sum());
    let mut study = Study {
        scn: scn.clone(),
        runs: vec![],
        crime: vec![],
    };
    for (fi, fam) in fams.iter().enumerate() {
        for &(n, steps) in &fam.levels {
            // (b) on h = k also runs with the exact compliance integral, in lockstep.
            if fam.sol == Solution::Regimes && fam.kind == "h=k" {
                let (mut runs, diffs) =
                    run_rules(fam.sol, &scn, n, steps, &[Rule::Nodal, Rule::Exact])?;
                let exact = runs.pop().expect("two rules");
                let nodal = runs.pop().expect("two rules");
                let umax = nodal.rows.iter().map(|r| r.exact_e).fold(0.0, f64::max);
                let dmax = diffs.iter().copied().fold(0.0, f64::max);
                study.crime.push((exact, dmax / umax));
                study.runs.push((fi, nodal));
            } else {
                study.runs.push((fi, run(fam.sol, &scn, n, steps)?));
            }
            ctx.log(&format!(
                "exact {} {} n = {n}, N = {steps}",
                fam.sol.name(),
                fam.kind
            ));
        }
    }
    let grid = run_grid(ctx, &scn, &study.runs)?;
    let conv = write_convergence(ctx, &fams, &study)?;
    let cea = write_cea(ctx, &fams, &study)?;
    write_crime(ctx, &fams, &study)?;
    let regimes = write_regimes(ctx, &fams, &study)?;
    write_quadrature(ctx, &scn)?;
    write_quadrature_effect(ctx, &scn)?;
    let hold = hold::write_hold(ctx, &scn)?;
    estimator::write_estimator(ctx, &scn)?;
    adaptive::write_adaptive(ctx, &scn)?;
    let grid = write_grid(ctx, &grid)?;
    figure::draw_all(ctx, &conv, &cea, &regimes, &hold)?;
    figure::draw_grid(ctx, &grid)
}

/// The solutions and levels of the $(h, k)$ grid: every pair of $n$ and $N$ from one
/// list, for (b) and (f).
pub fn grid(quick: bool) -> (Vec<Solution>, Vec<usize>) {
    let levels = if quick {
        vec![8, 16, 32]
    } else {
        vec![8, 16, 32, 64, 128]
    };
    (vec![Solution::Regimes, Solution::P1Limit], levels)
}

/// Runs the $(h, k)$ grid of [`grid`], row by row, taking a pair the families already
/// ran (`done`) from there.
fn run_grid(
    ctx: &Ctx,
    scn: &Scenario,
    done: &[(usize, ExactRun)],
) -> Result<Vec<ExactRun>, ExpError> {
    let (sols, levels) = grid(ctx.quick);
    ctx.add_units(sols.len() * levels.len() * levels.len());
    let mut out = vec![];
    for sol in sols {
        for &n in &levels {
            for &steps in &levels {
                let same =
                    |r: &&(usize, ExactRun)| r.1.sol == sol && r.1.n == n && r.1.steps == steps;
                match done.iter().find(same) {
                    Some((_, r)) => out.push(r.clone()),
                    None => out.push(run(sol, scn, n, steps)?),
                }
                ctx.log(&format!("exact grid {} n = {n}, N = {steps}", sol.name()));
            }
        }
    }
    Ok(out)
}

fn write_grid(ctx: &Ctx, runs: &[ExactRun]) -> Result<std::path::PathBuf, ExpError> {
    let mut t = Cols::default();
    for r in runs {
        let (h, k, lhs) = (r.h, r.k, r.lhs());
        let terms = r.cea_terms();
        t.s("letter", r.sol.letter());
        t.s("solution", r.sol.name());
        t.u("n", r.n);
        t.u("steps", r.steps);
        t.f("h", h);
        t.f("k", k);
        t.f("lhs", lhs);
        t.f("lhs_over_h2_plus_k2", lhs / (h * h + k * k));
        t.f("lhs_over_h_plus_k_sq", lhs / ((h + k) * (h + k)));
        t.f("max_u_v_sq", r.max_exact_v_sq());
        t.f(
            "rel_lhs_over_h2_plus_k2",
            lhs / r.max_exact_v_sq() / (h * h + k * k),
        );
        t.f("rel_err_max_percent", 100.0 * r.rel_max());
        for (name, v) in CEA_TERMS.iter().zip(terms) {
            t.f(name, v);
        }
        t.f("lhs_over_terms", lhs / terms.iter().sum::<f64>());
        t.f("limit_share_percent", 100.0 * r.limit_share());
        t.f("max_certificate", r.max_certificate());
    }
    let params = format!(
        "{}; solutions (b) and (f) on every pair (n, N) of the levels, h = 1/n (the paper's h: Gamma_3 in 1/h segments, the cells have side 2h), k = T/N; lhs = max_n ||e_n||_V^2 + k sum ||e_n||_V^2, the left side of (4.24); max_u_v_sq = max_n ||u(t_n)||_V^2; rel_lhs_over_h2_plus_k2 = lhs / max_u_v_sq / (h^2 + k^2), the constant with the size of u divided out; the right side of (4.16) with v_n = Pi^h u_n as in exact_cea.csv (interp_max, dinterp_sum, gamma_sum, r_sum, delta_sum) and lhs_over_terms = lhs / their sum, the observed constant of (4.16); limit_share as in exact_convergence.csv; letter = the book's name of the solution",
        params()
    );
    ctx.write("exact_grid.csv", &t.table(), &params)
}

/// The columns of the terms of the right side of (4.16), in the order of
/// [`ExactRun::cea_terms`].
const CEA_TERMS: [&str; 5] = [
    "interp_max",
    "dinterp_sum",
    "gamma_sum",
    "r_sum",
    "delta_sum",
];

/// The share of $\Gamma_3 \times (0, T)$ where $u_\nu = g$: a midpoint sum on a
/// $20000 \times 200$ grid (cells of $10^{-4}$ in $x$ and $0.005$ in $t$). Its lines
/// hold the hold's ends and the plateau's ends of (b), (f), (g) and (i), so it is exact
/// for them; for (d), whose ends move, and (h), whose ends sit on no line, it meets
/// the closed forms the book gives to $10^{-4}$ of the share (a test compares them).
pub(super) fn exact_share(sol: Solution, scn: &Scenario) -> f64 {
    let data = Data::new(sol, scn);
    let (nx, nt) = (20_000, 200);
    let t_end = scn.t_end();
    let mut at = 0usize;
    for j in 0..nt {
        let t = (j as f64 + 0.5) / nt as f64 * t_end;
        for i in 0..nx {
            let x = (i as f64 + 0.5) / nx as f64 * 2.0;
            if data.u_nu(x, t) >= scn.g() - 1e-12 {
                at += 1;
            }
        }
    }
    at as f64 / (nx * nt) as f64
}

/// The provenance every table of the study shares.
fn params() -> String {
    format!("{PARAMS}; {}", evhi::manufactured::parameters())
}

const PARAMS: &str = "manufactured solutions of evhi::manufactured on the paper's domain, supports, material (E = 1000, kappa = 0.4, alpha = 100, beta = 50), law (5.1) and g = 0.1, T = 1; loads derived from u (weak form, 7-point rule per triangle and 5-point Gauss per contact segment, cut where the data are piecewise); Newton with the full certificate every step";

fn write_convergence(
    ctx: &Ctx,
    fams: &[Family],
    s: &Study,
) -> Result<std::path::PathBuf, ExpError> {
    let limit = REGIMES
        .iter()
        .position(|r| *r == "limit")
        .expect("a regime");
    let mut t = Cols::default();
    // The exact share, once per solution.
    let mut shares = std::collections::HashMap::new();
    for (fi, fam) in fams.iter().enumerate() {
        let runs: Vec<&ExactRun> = s.runs.iter().filter(|r| r.0 == fi).map(|r| &r.1).collect();
        let max: Vec<f64> = runs.iter().map(|r| r.rel_max()).collect();
        let fin: Vec<f64> = runs.iter().map(|r| r.rel_final()).collect();
        let l2: Vec<f64> = runs.iter().map(|r| r.rel_l2()).collect();
        let (om, of, ol) = (orders(&max), orders(&fin), orders(&l2));
        let share_exact = *shares
            .entry(fam.sol.name())
            .or_insert_with(|| exact_share(fam.sol, &s.scn));
        for (i, r) in runs.iter().enumerate() {
            t.s("letter", fam.sol.letter());
            t.s("solution", fam.sol.name());
            t.s("family", fam.kind);
            t.u("n", r.n);
            t.u("steps", r.steps);
            t.f("rel_err_max_percent", 100.0 * max[i]);
            t.f("order_max", om[i]);
            t.f("rel_err_T_percent", 100.0 * fin[i]);
            t.f("order_T", of[i]);
            t.f("rel_err_l2_percent", 100.0 * l2[i]);
            t.f("order_l2", ol[i]);
            t.f("lhs_over_h2_plus_k2", r.constant());
            t.f("landing_gap", landing_gap(fam.sol, r.k));
            let at_max = r.max_row();
            t.f("t_at_max", at_max.t);
            t.u("limit_nodes_at_max", at_max.regimes[limit]);
            t.f("limit_share_exact_percent", 100.0 * share_exact);
            t.f("limit_share_percent", 100.0 * r.limit_share());
            t.f("max_certificate", r.max_certificate());
        }
    }
    let params = format!(
        "{}; rel_err_max = max_n ||u(t_n) - u_n||_E / max_n ||u(t_n)||_E, rel_err_T at t = T, rel_err_l2 = (k sum ||e_n||_E^2)^(1/2) / (k sum ||u(t_n)||_E^2)^(1/2); order = log2 of the ratio to the previous level of the family; lhs_over_h2_plus_k2 = (max_n ||e_n||_V^2 + k sum ||e_n||_V^2) / (h^2 + k^2) with h = 1/n, k = T/N (the observed constant of (4.24)); landing_gap (g only) = T1 - t_m, t_m the last step before the landing time T1 = 0.4; t_at_max = the t_n where max_n ||u(t_n) - u_n||_E is reached (the first, on a tie), limit_nodes_at_max = the contact nodes of the discrete solution at g at that step (regime limit: within 1e-8 g, as in exact_regimes.csv); limit_share_exact = the share of Gamma_3 x (0, T) where u_nu = g (midpoint sum on a 20000 x 200 grid), limit_share = that of the discrete solution: the contact nodes at g after each step, each weighted by its 2h of Gamma_3 and each step by k (count / (n N)); letter = the book's name of the solution; steady: the static problem, one solve, and ||e||_V^2 / h^2 in that column",
        params()
    );
    ctx.write("exact_convergence.csv", &t.table(), &params)
}

/// For (g): $T_1 - t_m$, how long before the landing time $T_1$ the last step
/// $t_m < T_1$ falls (in $(0, k]$; $k$ when $T_1$ is a step); NaN for the others.
fn landing_gap(sol: Solution, k: f64) -> f64 {
    sol.landing_time().map_or(f64::NAN, |t1| {
        let m = (t1 / k - 1e-9).ceil() - 1.0;
        t1 - m * k
    })
}

fn write_cea(ctx: &Ctx, fams: &[Family], s: &Study) -> Result<std::path::PathBuf, ExpError> {
    let mut t = Cols::default();
    const TERMS: [&str; 5] = CEA_TERMS;
    for (fi, fam) in fams.iter().enumerate() {
        if fam.kind != "h=k"
            || !matches!(
                fam.sol,
                Solution::Regimes | Solution::Moving | Solution::OffNode
            )
        {
            continue;
        }
        let runs: Vec<&ExactRun> = s.runs.iter().filter(|r| r.0 == fi).map(|r| &r.1).collect();
        let terms: Vec<[f64; 5]> = runs.iter().map(|r| r.cea_terms()).collect();
        let lhs: Vec<f64> = runs.iter().map(|r| r.lhs()).collect();
        let per: Vec<Vec<f64>> = (0..5)
            .map(|j| orders(&terms.iter().map(|x| x[j]).collect::<Vec<_>>()))
            .collect();
        let ol = orders(&lhs);
        for (i, r) in runs.iter().enumerate() {
            t.s("letter", fam.sol.letter());
            t.s("solution", fam.sol.name());
            t.u("n", r.n);
            t.u("steps", r.steps);
            for (j, name) in TERMS.iter().enumerate() {
                t.f(name, terms[i][j]);
                t.f(&format!("order_{name}"), per[j][i]);
            }
            t.f("lhs", lhs[i]);
            t.f("order_lhs", ol[i]);
            t.f("lhs_over_terms", lhs[i] / terms[i].iter().sum::<f64>());
            t.f("r_share", terms[i][3] / terms[i].iter().sum::<f64>());
            t.f(
                "r_sum_predicted",
                fam.sol
                    .predicted_r_sum(r.n, r.steps, r.k * r.steps as f64)
                    .unwrap_or(f64::NAN),
            );
            t.f("lhs_over_h2_plus_k2", lhs[i] / (r.h * r.h + r.k * r.k));
        }
    }
    let params = format!(
        "{}; the right side of (4.16) with v_n = Pi^h u_n (nodal interpolant), h = k = 1/n: interp_max = max_n ||u_n - Pi u_n||_V^2, dinterp_sum = k sum ||delta(u_n - Pi u_n)||_V^2, gamma_sum = k sum ||u_n,nu - Pi u_n,nu||_L2(Gamma3), r_sum = k sum |R_n(Pi u_n)|, delta_sum = k sum ||delta u_n - u'(t_n)||_V^2; predicted orders (4.20)-(4.23): 2 each (h^2 or k^2); lhs = max_n ||e_n||_V^2 + k sum ||e_n||_V^2, predicted 2; lhs_over_terms = lhs / (the sum of the five terms), the observed constant of (4.16); r_share = r_sum / (the sum of the five terms); r_sum_predicted: (h)'s k sum |R_n| in closed form (Solution::predicted_r_sum), NaN for the others; lhs_over_h2_plus_k2 that of (4.24)",
        params()
    );
    ctx.write("exact_cea.csv", &t.table(), &params)
}

fn write_crime(ctx: &Ctx, fams: &[Family], s: &Study) -> Result<(), ExpError> {
    let fi = fams
        .iter()
        .position(|f| f.sol == Solution::Regimes && f.kind == "h=k")
        .expect("the family (b) h=k");
    let nodal: Vec<&ExactRun> = s.runs.iter().filter(|r| r.0 == fi).map(|r| &r.1).collect();
    let crime: Vec<f64> = s.crime.iter().map(|c| c.1).collect();
    let oc = orders(&crime);
    let mut t = Cols::default();
    for (i, (nod, (ex, c))) in nodal.iter().zip(&s.crime).enumerate() {
        t.u("n", nod.n);
        t.u("steps", nod.steps);
        t.f("rel_err_nodal_percent", 100.0 * nod.rel_max());
        t.f("rel_err_exact_percent", 100.0 * ex.rel_max());
        t.f("crime_percent", 100.0 * c);
        t.f("order_crime", oc[i]);
        t.f("crime_share", c / nod.rel_max());
        t.f("max_kkt_exact", ex.max_certificate());
    }
    let params = format!(
        "{}; solution (b) on h = k = 1/n, the same loads solved with the scheme's nodal (trapezoidal) compliance rule and with the exact integral of j(u_h) on Gamma_3 (evhi::manufactured::exact_rule, projected Newton, KKT residual max_kkt_exact); rel_err = max_n ||u(t_n) - u_n||_E / max_n ||u(t_n)||_E; crime = max_n ||u_n(nodal) - u_n(exact)||_E / max_n ||u(t_n)||_E; crime_share = crime / rel_err_nodal",
        params()
    );
    ctx.write("exact_crime.csv", &t.table(), &params)?;
    Ok(())
}

fn write_regimes(ctx: &Ctx, fams: &[Family], s: &Study) -> Result<std::path::PathBuf, ExpError> {
    let mut t = Cols::default();
    for (fi, fam) in fams.iter().enumerate() {
        if fam.kind != "h=k" {
            continue;
        }
        for (_, r) in s.runs.iter().filter(|r| r.0 == fi) {
            for row in &r.rows {
                t.s("solution", fam.sol.name());
                t.u("n", r.n);
                t.u("steps", r.steps);
                t.u("step", row.step);
                t.f("t", row.t);
                for (j, name) in REGIMES.iter().enumerate() {
                    t.u(name, row.regimes[j]);
                }
                t.u("iterations", row.iterations);
            }
        }
    }
    let params = format!(
        "{}; every solution with an h = k family ((a), (b), (d), (f), (g), (h)) on h = k = 1/n: the number of contact nodes (n + 1) in each regime of the discrete solution after every step, and Newton's iterations",
        params()
    );
    ctx.write("exact_regimes.csv", &t.table(), &params)
}

/// The quadrature's own error: the load vector of every solution at three times
/// (the static one at its only time) by the study's rules against the same rules on
/// each triangle's 16 children and each contact segment's 4 quarters.
fn write_quadrature(ctx: &Ctx, scn: &Scenario) -> Result<(), ExpError> {
    let levels: &[usize] = if ctx.quick {
        &[8, 16, 32]
    } else {
        &[8, 16, 32, 64, 128]
    };
    let mut t = Cols::default();
    for sol in evhi::manufactured::SOLUTIONS {
        let data = Data::new(sol, scn);
        let times: &[f64] = if sol.is_static() {
            &[0.0]
        } else {
            &[0.3, 0.55, 0.9]
        };
        for &n in levels {
            let mesh = scn.mesh(n)?;
            let dofs = evhi::mesh::Dofs::new(&mesh, true);
            for &time in times {
                let f = load_vector(&data, &mesh, &dofs, time, 0);
                let fine = load_vector(&data, &mesh, &dofs, time, 2);
                let num = f
                    .iter()
                    .zip(&fine)
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max);
                let den = fine.iter().map(|b| b.abs()).fold(0.0, f64::max);
                t.s("solution", sol.name());
                t.u("n", n);
                t.f("t", time);
                t.f("load_rel_diff", num / den);
            }
        }
    }
    let params = format!(
        "{}; every solution at t = 0.3, 0.55, 0.9 (the static one at its only time): load_rel_diff = ||F - F_fine||_inf / ||F_fine||_inf between the load vector by the study's rules and by the same rules on each triangle's 16 children (two midpoint refinements) and each contact segment's 4 quarters",
        params()
    );
    ctx.write("exact_quadrature.csv", &t.table(), &params)?;
    Ok(())
}

/// What the quadrature does to the reported errors: every solution on $h = k$ (the
/// static one at $N = 1$) at the coarsest levels, run with the study's rules and with
/// every rule of the loads and of the error norm refined once (each triangle into its
/// 4 children, each contact segment into 2 halves).
fn write_quadrature_effect(ctx: &Ctx, scn: &Scenario) -> Result<(), ExpError> {
    let levels: &[usize] = if ctx.quick { &[8] } else { &[8, 16] };
    ctx.add_units(evhi::manufactured::SOLUTIONS.len() * levels.len());
    let mut t = Cols::default();
    for sol in evhi::manufactured::SOLUTIONS {
        for &n in levels {
            let steps = if sol.is_static() { 1 } else { n };
            let plain = evhi::manufactured::run::run_refined(sol, scn, n, steps, 0)?;
            let fine = evhi::manufactured::run::run_refined(sol, scn, n, steps, 1)?;
            let (a, b) = (plain.rel_max(), fine.rel_max());
            t.s("solution", sol.name());
            t.u("n", n);
            t.u("steps", steps);
            t.f("rel_err_max_percent", 100.0 * a);
            t.f("rel_err_max_refined_percent", 100.0 * b);
            t.f("rel_change", (a - b).abs() / b);
            ctx.log(&format!("exact quadrature effect {} n = {n}", sol.name()));
        }
    }
    let params = format!(
        "{}; every solution on h = k = 1/n (the static one at N = 1): rel_err_max = max_n ||u(t_n) - u_n||_E / max_n ||u(t_n)||_E with the study's rules, and refined: the loads and the error norms with each rule on the 4 children of every triangle and the 2 halves of every contact segment; rel_change = |plain - refined| / refined",
        params()
    );
    ctx.write("exact_quadrature_effect.csv", &t.table(), &params)?;
    Ok(())
}

/// Columns filled row by row.
#[derive(Default)]
struct Cols {
    names: Vec<String>,
    cols: Vec<Col>,
}

enum Col {
    F(Vec<f64>),
    U(Vec<u64>),
    S(Vec<String>),
}

impl Cols {
    fn slot(&mut self, name: &str, make: impl FnOnce() -> Col) -> &mut Col {
        let i = match self.names.iter().position(|n| n == name) {
            Some(i) => i,
            None => {
                self.names.push(name.to_string());
                self.cols.push(make());
                self.cols.len() - 1
            }
        };
        &mut self.cols[i]
    }
    fn f(&mut self, name: &str, v: f64) {
        if let Col::F(c) = self.slot(name, || Col::F(vec![])) {
            c.push(v)
        }
    }
    fn u(&mut self, name: &str, v: usize) {
        if let Col::U(c) = self.slot(name, || Col::U(vec![])) {
            c.push(v as u64)
        }
    }
    fn s(&mut self, name: &str, v: &str) {
        if let Col::S(c) = self.slot(name, || Col::S(vec![])) {
            c.push(v.to_string())
        }
    }
    fn table(self) -> Table {
        self.names
            .into_iter()
            .zip(self.cols)
            .fold(Table::new(), |t, (n, c)| match c {
                Col::F(v) => t.f64(&n, v),
                Col::U(v) => t.u64(&n, v),
                Col::S(v) => t.str(&n, v),
            })
    }
}
