//! Time steps chosen by the solution: backward Euler's local error estimated from a
//! linear predictor, and a time grid refined where it is large.
//!
//! **The indicator.** Backward Euler's local error at step $n$ is about
//! $\tfrac12 k_n^2\,\ddot u(t_n)$. The divided difference of the two last velocities,
//! $\ddot u \approx 2\,(\delta u_n/k_n - \delta u_{n-1}/k_{n-1})/(k_n + k_{n-1})$ with
//! $\delta u_n = u_n - u_{n-1}$, turns it into
//! $$\eta_n = \frac{k_n}{k_n + k_{n-1}}\,\big\|u_n - \hat u_n\big\|_E, \qquad
//! \hat u_n = u_{n-1} + \frac{k_n}{k_{n-1}}\,\delta u_{n-1},$$
//! the distance of the step's result from the linear extrapolation of the two states
//! before it (a predictor exact for motions linear in time). The first step has no two states before it,
//! and the velocity before $t = 0$ says nothing: a load applied in full at $t = 0$
//! makes $\dot u$ jump there, yet the solution is smooth on $(0, T]$ and the first
//! step's local error is $\tfrac12 k_1^2\ddot u$ like any other's. So it takes the
//! second step's divided difference, which spans $t_0, t_1, t_2$:
//! $\eta_1 = (k_1/k_2)^2\,\eta_2$. (Taking the body at rest before $t = 0$ instead,
//! $\eta_1 = \tfrac12\|u_1\|_E$, is of order $k_1$, not $k_1^2$: under that load it
//! overstated the first step by $\tau/k_1$ and spent the whole halving budget there.)
//!
//! **The estimate.** On the linear viscoelastic part each step shrinks the error it
//! carries by at least $1/(1 + k_n\lambda)$, $\lambda$ the body's slowest relaxation rate
//! ([`crate::material::slowest_rate`]), so the error at $t_n$ is about at most the
//! local errors made before it, each damped by the steps since:
//! $$\mathcal E = \max_n E_n \Big/ \max_n \|u_n\|_E, \qquad
//! E_n = \frac{E_{n-1}}{1 + k_n\lambda} + \eta_n$$
//! ([`transported`]). It is no bound: $\eta_n$ is asymptotic in $k_n/\tau$, and the
//! nonmonotone law may take some damping away. [`Level::sum`] keeps the plain sum
//! ($\lambda = 0$), which counts an error of the initial layer at full weight long after
//! it has decayed.
//!
//! **The bound.** Where the body has viscosity, each solve also measures the residual
//! of the steps joined by straight lines in time ([`crate::reconstruction`]): each
//! step's $\theta_n$, propagated at the same rate ([`propagated`]), bounds the error over
//! time without contact. Then the loop marks on the $\theta_n$ and stops on that bound
//! ([`Level::bound`]); $\eta_n$ and $\mathcal E$ are still reported, and drive a body
//! without viscosity.
//!
//! **The refinement.** Dörfler's bulk criterion on the $\theta_n$, or the $\eta_n$
//! without them (summed, not squared: the estimates add them), marks the fewest largest
//! steps that carry the fraction $\theta$ of their sum, and each marked step is cut into
//! two halves. A halved
//! step's local error falls by 4 and it becomes two steps, so its share of the sum
//! halves. Every step is a power of two of the finest unit $(T/N)/2^J$ and starts at
//! a multiple of its length ([`TimeGrid::from_exponents`]): the grid's times lie on
//! a uniform reference of $N 2^J$ steps, and the distinct lengths are at most
//! $J + 1$ (the reduced loop only rescales at a change of length; the general loop
//! keeps the operators of lengths it will need again, so it factorises each length
//! about once).

use crate::error::InputError;
use crate::marking::dorfler;
use crate::reduced::{Load, Reduced, State, Stepped};
use crate::time_grid::TimeGrid;

/// The predictor of step `step` (from 1): its ratio $k_n/k_{n-1}$ and the local
/// error's weight $k_n/(k_n + k_{n-1})$, with $k_0 = k_1$.
// ANCHOR: predictor
pub fn predictor(grid: &TimeGrid, step: usize) -> (f64, f64) {
    let k = grid.k(step);
    let k_prev = if step > 1 { grid.k(step - 1) } else { k };
    (k / k_prev, k / (k + k_prev))
}
// ANCHOR_END: predictor

/// Each step's $\eta_n$ from its distance `gaps[n-1]` $= \|u_n - \hat u_n\|_E$ from the
/// predictor; the first step's from the second's (see the module).
// ANCHOR: indicators
pub fn indicators(grid: &TimeGrid, gaps: &[f64]) -> Vec<f64> {
    let mut eta: Vec<f64> = (gaps.iter().enumerate())
        .map(|(i, g)| predictor(grid, i + 1).1 * g)
        .collect();
    if eta.len() > 1 {
        eta[0] = (grid.k(1) / grid.k(2)).powi(2) * eta[1];
    }
    eta
}
// ANCHOR_END: indicators

/// The local errors `eta[n-1]` $= \eta_n$ carried forward to later times and damped
/// there at the slowest rate `rate` $= \lambda$ ([`crate::material::slowest_rate`]),
/// $E_n = E_{n-1}/(1 + k_n\lambda) + \eta_n$, $E_0 = 0$: the largest $E_n$. Without contact
/// it bounds the error over time up to the local errors' own accuracy (each step
/// shrinks what came before by at least $1/(1 + k_n\lambda)$); the contact terms are not
/// in it: a monotone law only damps more, the nonmonotone branch may damp less.
// ANCHOR: transported
pub fn transported(grid: &TimeGrid, eta: &[f64], rate: f64) -> f64 {
    let mut carried = 0.0f64;
    let mut top = 0.0f64;
    for (i, e) in eta.iter().enumerate() {
        carried = carried / (1.0 + grid.k(i + 1) * rate) + e;
        top = top.max(carried);
    }
    top
}
// ANCHOR_END: transported

/// $E_n = e^{-k_n\lambda}E_{n-1} + \theta_n$, $E_0 = 0$: the largest $E_n$, where each
/// $\theta_n$ is already damped to its own $t_n$ (as
/// [`crate::manufactured::run::StepRow::theta`] is). For $A\dot e + Be = R$ the
/// propagator $e^{-tA^{-1}B}$ shrinks the energy norm by $e^{-\lambda t}$ at least
/// ($A^{-1}B$ is self-adjoint in $B$'s inner product, its least eigenvalue $\lambda$), so
/// with $\theta_n = \int_{t_{n-1}}^{t_n} e^{-\lambda(t_n - s)}\|A^{-1}R(s)\|_E\,ds$ this is a
/// bound of $\max_n\|e(t_n)\|_E$ from $e(0) = 0$. The exact factor, not
/// [`transported`]'s $1/(1 + k_n\lambda)$: that one follows backward Euler's own
/// damping of a defect, this one the continuous problem's damping of a residual.
// ANCHOR: propagated
pub fn propagated(grid: &TimeGrid, theta: &[f64], rate: f64) -> f64 {
    propagated_each(grid, theta, rate)
        .into_iter()
        .fold(0.0, f64::max)
}

/// Every $F_n$ of [`propagated`], in order: the bound at each $t_n$.
pub fn propagated_each(grid: &TimeGrid, theta: &[f64], rate: f64) -> Vec<f64> {
    let mut carried = 0.0f64;
    (theta.iter().enumerate())
        .map(|(i, th)| {
            carried = carried * (-grid.k(i + 1) * rate).exp() + th;
            carried
        })
        .collect()
}
// ANCHOR_END: propagated

/// $\min_n F_n / e_n$ over the steps with $e_n > 0$: the bounds `each` ([`propagated_each`])
/// against the errors `err` at the same steps (above 1 where the bound held at every
/// step); $+\infty$ where no error is positive.
pub fn least_margin(each: &[f64], err: &[f64]) -> f64 {
    (each.iter().zip(err))
        .filter(|(_, e)| **e > 0.0)
        .map(|(f, e)| f / e)
        .fold(f64::INFINITY, f64::min)
}

/// The settings of an adaptive choice of the time grid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Settings {
    /// $N_0$: the first grid has $N_0$ steps of $T/N_0$, the longest any step gets.
    pub n0: usize,
    /// Dörfler's fraction $\theta$ in $(0, 1]$.
    pub theta: f64,
    /// Stop when the bound [`Level::bound`] (or, without one, the estimate
    /// [`Level::estimate`]) is at most this.
    pub tol: f64,
    /// Stop before a grid of more steps than this.
    pub max_steps: usize,
    /// Stop before a grid whose shortest step is $(T/N_0)/2^J$ with $J$ above this.
    pub max_halvings: u32,
}

impl Default for Settings {
    /// $N_0 = 4$, $\theta = 0.8$, no tolerance, 4096 steps, $J \le 13$. The time
    /// study measured $\theta = 0.5$ (the space loop's) against 0.8: the final grids
    /// that reach its targets are of about the same size, and 0.8 takes fewer
    /// levels to get there.
    fn default() -> Self {
        Settings {
            n0: 4,
            theta: 0.8,
            tol: 0.0,
            max_steps: 4096,
            max_halvings: 13,
        }
    }
}

impl Settings {
    /// Refuses settings that cannot run, by field.
    pub fn check(&self) -> Result<(), InputError> {
        if self.n0 == 0 {
            return Err(InputError::field("n0", self.n0, "at least 1 step"));
        }
        if !(self.theta > 0.0 && self.theta <= 1.0) {
            return Err(InputError::field(
                "theta",
                self.theta,
                "a fraction in (0, 1]",
            ));
        }
        if self.tol.is_nan() || self.tol < 0.0 {
            return Err(InputError::field(
                "tol",
                self.tol,
                "a relative error, 0 or more",
            ));
        }
        if self.max_steps < self.n0 {
            return Err(InputError::field(
                "max_steps",
                self.max_steps,
                format!("at least the first grid's {} steps", self.n0),
            ));
        }
        if self.max_halvings > crate::time_grid::MAX_HALVINGS {
            return Err(InputError::field(
                "max_halvings",
                self.max_halvings,
                format!("from 0 to {}", crate::time_grid::MAX_HALVINGS),
            ));
        }
        Ok(())
    }
}

/// One grid of an adaptive run and what its solve showed.
#[derive(Debug, Clone)]
pub struct Level<T> {
    /// The grid.
    pub grid: TimeGrid,
    /// Each step's $\eta_n$.
    pub eta: Vec<f64>,
    /// Each step's $\theta_n$ ([`Solved::theta`]), or empty.
    pub theta: Vec<f64>,
    /// The estimated relative error over time: the local errors carried forward and
    /// damped at the body's slowest rate ([`transported`]) over $\max_n\|u_n\|_E$.
    pub estimate: f64,
    /// The plain sum $\sum_n\eta_n / \max_n\|u_n\|_E$ (the estimate without damping).
    pub sum: f64,
    /// The reconstruction's bound ([`crate::reconstruction`]): the steps' $\theta_n$
    /// propagated at the slowest rate ([`propagated`]) over $\max_n\|u_n\|_E$; a bound of
    /// the relative error over time without contact, an estimate with it. `None` where
    /// the solve formed no $\theta_n$.
    pub bound: Option<f64>,
    /// Anything else the solve returns.
    pub out: T,
}

/// Why an adaptive run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// The bound ([`Level::bound`]), or without one the estimate, reached the tolerance.
    Tolerance,
    /// The next grid would have had more steps than allowed.
    Steps,
    /// The next grid would have needed a shorter step than allowed.
    Halvings,
}

/// What one solve on a grid reports: each step's $\|u_n - \hat u_n\|_E$ (see
/// [`predictor`]), the largest $\|u_n\|_E$, and anything else.
pub struct Solved<T> {
    /// Per step, $\|u_n - \hat u_n\|_E$.
    pub gaps: Vec<f64>,
    /// Per step, the reconstruction's $\theta_n$ ([`crate::reconstruction`]), or empty.
    pub theta: Vec<f64>,
    /// $\max_n \|u_n\|_E$.
    pub norm_max: f64,
    /// Anything else the solve returns.
    pub out: T,
}

/// Solves on $N_0$ uniform steps, estimates, refines the marked steps and solves
/// again from $t = 0$, until the bound (where the solve measured $\theta_n$; else the
/// estimate) is within `s.tol` or the next grid would leave the step or halving
/// budget. `rate` is the body's slowest relaxation rate
/// ([`crate::material::slowest_rate`]; 0 sums the local errors without damping).
/// `solve` runs one grid; `on_level` sees each level as it is done.
pub fn adapt_time<T, E: From<InputError>>(
    t_end: f64,
    s: &Settings,
    rate: f64,
    solve: impl FnMut(&TimeGrid) -> Result<Solved<T>, E>,
    on_level: impl FnMut(&Level<T>),
) -> Result<(Vec<Level<T>>, Stop), E> {
    adapt_time_from(TimeGrid::uniform(t_end, s.n0), s, rate, solve, on_level)
}

/// [`adapt_time`] from the grid `start` in place of $N_0$ uniform steps: a grid an
/// earlier search chose (its $N$ is $N_0$, within the budgets), so that a search on a
/// refined mesh goes on from the coarser mesh's grid instead of again from $N_0$. The
/// grid's $T$ is the caller's to check (`solve` runs it as it is; [`choose_from`]
/// refuses a grid that does not end at the scene's $T$).
// ANCHOR: adapt_time
pub fn adapt_time_from<T, E: From<InputError>>(
    start: TimeGrid,
    s: &Settings,
    rate: f64,
    mut solve: impl FnMut(&TimeGrid) -> Result<Solved<T>, E>,
    mut on_level: impl FnMut(&Level<T>),
) -> Result<(Vec<Level<T>>, Stop), E> {
    s.check()?;
    check_start(&start, s)?;
    let mut grid = start;
    let mut levels = vec![];
    loop {
        let solved = solve(&grid)?;
        let eta = indicators(&grid, &solved.gaps);
        let sum = eta.iter().sum::<f64>() / solved.norm_max;
        let estimate = transported(&grid, &eta, rate) / solved.norm_max;
        let bound = (solved.theta.len() == grid.len())
            .then(|| propagated(&grid, &solved.theta, rate) / solved.norm_max);
        if let Some(b) = bound.filter(|b| !b.is_finite()) {
            return Err(InputError::field(
                "time bound",
                b,
                "a finite bound over a positive largest norm (the solve returned a NaN \
                 residual or a zero norm)",
            )
            .into());
        }
        if !(estimate.is_finite() && sum.is_finite()) {
            return Err(InputError::field(
                "time indicator",
                sum,
                "a finite sum of the steps' local errors over a positive largest norm \
                 (the solve returned a NaN or a zero norm)",
            )
            .into());
        }
        let level = Level {
            grid,
            eta,
            theta: solved.theta,
            estimate,
            sum,
            bound,
            out: solved.out,
        };
        on_level(&level);
        // ANCHOR: mark_and_stop
        // The bound where the solve measured it, else the predictor's indicators. A
        // zero sum marks nothing: then the estimate is 0, within any tolerance.
        let (marks, stop_on) = match bound {
            Some(b) => (&level.theta, b),
            None => (&level.eta, estimate),
        };
        let marked = dorfler(marks, s.theta);
        // ANCHOR_END: mark_and_stop
        let grid_now = &level.grid;
        let exps = grid_now.exponents();
        let next = if stop_on <= s.tol || marked.is_empty() {
            Err(Stop::Tolerance)
        } else if marked.iter().any(|&i| exps[i] == 0) && grid_now.halvings() >= s.max_halvings {
            // Halving a step of one unit needs J + 1: past the budget (checked before
            // the grid is formed, so that J never passes its bound).
            Err(Stop::Halvings)
        } else {
            let next = grid_now.bisect(&marked)?;
            if next.len() > s.max_steps {
                Err(Stop::Steps)
            } else {
                Ok(next)
            }
        };
        levels.push(level);
        match next {
            Ok(next) => grid = next,
            Err(stop) => return Ok((levels, stop)),
        }
    }
}
// ANCHOR_END: adapt_time

/// Refuses, by name, a start grid no search with settings `s` could have chosen: one
/// with no step, whose longest step is not $T/N_0$, or past the budgets.
fn check_start(start: &TimeGrid, s: &Settings) -> Result<(), InputError> {
    if start.is_empty()
        || start.n() != s.n0
        || start.halvings() > s.max_halvings
        || start.len() > s.max_steps
    {
        return Err(InputError::field(
            "start",
            format!(
                "a grid of {} steps, longest T/{}, {} halvings",
                start.len(),
                start.n(),
                start.halvings()
            ),
            format!(
                "a grid whose longest step is T/N0 = T/{}, with at most {} halvings and at \
                 most {} steps (one an earlier search with these settings chose)",
                s.n0, s.max_halvings, s.max_steps
            ),
        ));
    }
    Ok(())
}

/// What [`choose`] found: every level, why it stopped, and the seconds the search
/// took (every level's solve, the indicators with them).
#[derive(Debug, Clone)]
pub struct Chosen {
    /// The levels, the last one's grid the chosen one.
    pub levels: Vec<Level<()>>,
    /// Why the search stopped.
    pub stop: Stop,
    /// The search's wall seconds.
    pub search_s: f64,
}

impl Chosen {
    /// The last level's grid.
    pub fn grid(&self) -> &TimeGrid {
        &self.levels.last().expect("a search has a level").grid
    }
}

impl Stop {
    /// Why the search stopped, in words.
    pub fn describe(self) -> &'static str {
        match self {
            Stop::Tolerance => {
                "the bound (or, without viscosity, the estimate) is within the tolerance"
            }
            Stop::Steps => "the next grid would have more steps than allowed",
            Stop::Halvings => "the next grid would need a shorter step than allowed",
        }
    }
}

/// Chooses the time grid of `sim`'s scene ([`adapt_time`] from $N_0$ uniform steps):
/// each level is a run of `sim` on its grid with its solver, and each step's
/// predictor distance is measured in the energy norm, from the reduced loop's states
/// where `sim` runs it (no field formed), else from the general loop's fields. Each
/// level runs `sim`'s solver as it is (no fallback: a stalled step stops the search
/// with its error). The search only chooses: the caller solves on [`Chosen::grid`]
/// ([`crate::simulation::Simulation::on_time_grid`]).
pub fn choose(
    sim: &crate::simulation::Simulation,
    s: &Settings,
    on_level: &mut dyn FnMut(&Level<()>),
) -> Result<Chosen, crate::scheme::RunError> {
    let start = TimeGrid::uniform(sim.scenario().t_end, s.n0);
    choose_from(sim, s, start, on_level)
}

/// [`choose`] from the grid `start` ([`adapt_time_from`]): the adaptive mesh loop
/// starts each level's search from the grid the level before chose.
pub fn choose_from(
    sim: &crate::simulation::Simulation,
    s: &Settings,
    start: TimeGrid,
    on_level: &mut dyn FnMut(&Level<()>),
) -> Result<Chosen, crate::scheme::RunError> {
    let clock = std::time::Instant::now();
    // The settings and the start grid before any work.
    s.check()?;
    check_start(&start, s)?;
    start.check_ends_at(sim.scenario().t_end)?;
    let scn = sim.scenario();
    let disc = sim.discretisation();
    let tol = sim.settings().certificate_tol;
    let rate = scn.slowest_rate().unwrap_or(0.0);
    let (levels, stop) = if sim.reduced() {
        let mut timings = crate::scheme::Timings::default();
        let op = sim.reduced_operator(&disc, &mut timings)?;
        let load = op.load_of(scn);
        adapt_time_from(
            start,
            s,
            rate,
            |grid| {
                let solver = &mut *sim.solver().build();
                march_reduced(
                    &op,
                    scn,
                    &load,
                    grid,
                    (solver, tol),
                    &mut timings,
                    &mut |_| {},
                )
            },
            &mut *on_level,
        )?
    } else {
        // The reconstruction needs A's factor (one per search) and the load; a body
        // without viscosity has neither a rate nor a residual to measure.
        let a_factor = match scn.slowest_rate() {
            Some(_) => Some(
                crate::scheme::factorise(
                    &disc,
                    &disc.a,
                    crate::scheme::OrderingKind::NestedDissection,
                    true,
                )?
                .0,
            ),
            None => None,
        };
        let f = scn.load_vector(&disc.mesh, &disc.dofs);
        adapt_time_from(
            start,
            s,
            rate,
            |grid| {
                let level = sim.on_time_grid(grid.clone())?;
                let fields = a_factor.as_ref().map(|a| crate::reconstruction::OnFields {
                    a,
                    b: &disc.b,
                    contact_dofs: &disc.contact_dofs,
                    weights: &disc.weights,
                    law: &scn.law,
                });
                let mut obs = Gaps {
                    b: &disc.b,
                    grid,
                    last: [vec![], vec![]],
                    gaps: Vec::with_capacity(grid.len()),
                    norm_max: 0.0,
                    rebuilt: fields.map(|fields| Rebuilt {
                        fields,
                        f: &f,
                        scn,
                        rate,
                        breaks: scn.history.breaks(),
                        before: crate::reconstruction::Before::at_rest(&disc.gap),
                        gap: &disc.gap,
                        theta: Vec::with_capacity(grid.len()),
                    }),
                };
                // Run as it is, as on the reduced loop: a stalled step stops the search.
                level.solve_with(sim.solver().build().as_mut(), &mut obs)?;
                Ok::<_, crate::scheme::RunError>(Solved {
                    gaps: obs.gaps,
                    theta: obs.rebuilt.map_or(vec![], |r| r.theta),
                    norm_max: obs.norm_max,
                    out: (),
                })
            },
            &mut *on_level,
        )?
    };
    Ok(Chosen {
        levels,
        stop,
        search_s: clock.elapsed().as_secs_f64(),
    })
}

/// Marches `grid` on the reduced loop ([`Reduced::march_on`] with `solver` and the
/// certificate tolerance beside it) and measures each step's distance from the
/// predictor on the states, with no field formed, and the largest norm; `observe`
/// sees every step too. The search of [`choose`] and the time study both march so.
pub fn march_reduced(
    op: &Reduced<'_>,
    scn: &crate::scenario::Scenario,
    load: &Load,
    grid: &TimeGrid,
    (solver, tol): (&mut dyn crate::step::StepSolver, f64),
    timings: &mut crate::scheme::Timings,
    observe: &mut dyn FnMut(&Stepped<'_>),
) -> Result<Solved<()>, crate::scheme::RunError> {
    let zero = State {
        y: 0.0,
        w: vec![0.0; load.q.len()],
        r: vec![0.0; load.q.len()],
    };
    let (mut u1, mut u2) = (zero.clone(), zero);
    let (mut gaps, mut norm_max) = (Vec::with_capacity(grid.len()), 0.0f64);
    // The reconstruction's residual: the contact variables of the step before (u_0 = 0)
    // and the load's kinks in time; A = cB, so the slowest rate is 1/c.
    let mut theta = Vec::with_capacity(grid.len());
    let mut before = crate::reconstruction::Before::at_rest(&op.disc.gap);
    let breaks = scn.history.breaks();
    let phi = |t: f64| scn.history.phi(t);
    op.march_on(
        scn,
        load,
        grid,
        solver,
        tol,
        &|_| false,
        timings,
        &mut |st| {
            let (ratio, _) = predictor(grid, st.step);
            gaps.push(op.predictor_gap(load, (st.state, &u1, &u2), ratio));
            let k = grid.k(st.step);
            let points = crate::reconstruction::time_points(&breaks, st.t - k, st.t);
            theta.push(crate::reconstruction::on_states(
                op,
                load,
                (&u1, st.state),
                (&before, st.contact),
                (st.t, k),
                &scn.law,
                &phi,
                (1.0 / op.c, &points),
            ));
            before = crate::reconstruction::Before::of(st.contact);
            norm_max = norm_max.max(st.record.energy_norm);
            observe(&st);
            u2 = std::mem::replace(&mut u1, st.state.clone());
        },
    )?;
    Ok(Solved {
        gaps,
        theta,
        norm_max,
        out: (),
    })
}

/// The general loop's observer of [`choose`]: each step's predictor distance from
/// the fields, and the largest norm.
struct Gaps<'a> {
    b: &'a crate::assembly::SpMat,
    grid: &'a TimeGrid,
    /// $u_{n-1}$ and $u_{n-2}$ (empty before the first and second steps: zero).
    last: [Vec<f64>; 2],
    gaps: Vec<f64>,
    norm_max: f64,
    /// The reconstruction's residual, where the body has viscosity.
    rebuilt: Option<Rebuilt<'a>>,
}

/// What [`Gaps`] needs for each step's $\theta_n$ ([`crate::reconstruction::OnFields`]).
struct Rebuilt<'a> {
    fields: crate::reconstruction::OnFields<'a>,
    /// The load vector at $\varphi = 1$.
    f: &'a [f64],
    scn: &'a crate::scenario::Scenario,
    rate: f64,
    /// The load history's kinks in time.
    breaks: Vec<f64>,
    /// The contact nodes at the step before.
    before: crate::reconstruction::Before,
    /// The contact gaps, for the state at $u_0 = 0$ after a restart.
    gap: &'a [f64],
    theta: Vec<f64>,
}

impl crate::simulation::Observer for Gaps<'_> {
    fn step(
        &mut self,
        n: usize,
        _t: f64,
        u: Option<&[f64]>,
        c: &[crate::certificate::ContactState],
    ) {
        let Some(u) = u else { return };
        let (ratio, _) = predictor(self.grid, n);
        if let Some(r) = self.rebuilt.as_mut() {
            let k = self.grid.k(n);
            let t = self.grid.t(n);
            // u_0 = 0 before the first step.
            let zero;
            let u_prev = if self.last[0].is_empty() {
                zero = vec![0.0; u.len()];
                &zero
            } else {
                &self.last[0]
            };
            let phi_n = r.scn.history.phi(t);
            let points: Vec<(f64, f64, Vec<f64>)> =
                crate::reconstruction::time_points(&r.breaks, t - k, t)
                    .into_iter()
                    .map(|(s, w)| {
                        let dphi = r.scn.history.phi(s) - phi_n;
                        (s, w, r.f.iter().map(|f| dphi * f).collect())
                    })
                    .collect();
            let step = crate::reconstruction::StepFields {
                t,
                k,
                u_prev,
                u,
                before: &r.before,
                contact: c,
            };
            r.theta.push(r.fields.theta(&step, r.rate, &points));
            r.before = crate::reconstruction::Before::of(c);
        }
        let at = |v: &Vec<f64>, i: usize| v.get(i).copied().unwrap_or(0.0);
        let d: Vec<f64> = (u.iter().enumerate())
            .map(|(i, x)| x - (1.0 + ratio) * at(&self.last[0], i) + ratio * at(&self.last[1], i))
            .collect();
        self.gaps.push(crate::norms::energy_norm(self.b, &d));
        self.norm_max = self.norm_max.max(crate::norms::energy_norm(self.b, u));
        self.last.swap(0, 1);
        self.last[0] = u.to_vec();
    }

    fn restart(&mut self) {
        self.last = [vec![], vec![]];
        self.gaps.clear();
        self.norm_max = 0.0;
        if let Some(r) = self.rebuilt.as_mut() {
            r.theta.clear();
            r.before = crate::reconstruction::Before::at_rest(r.gap);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn transported_errors_decay_at_the_slowest_rate() {
        // One local error of 1 at the first of four steps of 1/4 at rate 4: it halves
        // at each later step; a second error of 1 at step 3 adds to a quarter.
        let g = TimeGrid::uniform(1.0, 4);
        assert_eq!(transported(&g, &[1.0, 0.0, 0.0, 0.0], 4.0), 1.0);
        assert_eq!(transported(&g, &[1.0, 0.0, 1.0, 0.0], 4.0), 1.25);
        // No damping: the plain sum; the rate never lets the estimate pass it.
        let eta = [0.3, 0.1, 0.4, 0.2];
        assert!((transported(&g, &eta, 0.0) - 1.0).abs() < 1e-15);
        assert!(transported(&g, &eta, 4.0) < 1.0);
        // The body's slowest rate: 1/tau when C = tau G, else the smaller ratio.
        let elast = crate::material::Isotropic { a: 2.0, b: 3.0 };
        let visc = crate::material::Isotropic { a: 0.2, b: 0.3 };
        assert_eq!(crate::material::slowest_rate(&visc, &elast), Some(10.0));
        let stiff_shear = crate::material::Isotropic { a: 0.2, b: 0.1 };
        // deviatoric 3/0.1 = 30, spherical (4 + 3)/(0.4 + 0.1) = 14
        assert_eq!(
            crate::material::slowest_rate(&stiff_shear, &elast),
            Some(14.0)
        );
        let none = crate::material::Isotropic { a: 0.0, b: 0.0 };
        assert_eq!(crate::material::slowest_rate(&none, &elast), None);
    }

    #[test]
    fn propagated_residuals_bound_the_relaxation_from_above() {
        // A residual of 1 at the first of four steps of 1/4, damped to half per step.
        let g = TimeGrid::uniform(1.0, 4);
        let rate = 4.0 * std::f64::consts::LN_2;
        assert!((propagated(&g, &[1.0, 0.0, 0.0, 0.0], rate) - 1.0).abs() < 1e-15);
        assert!((propagated(&g, &[1.0, 0.0, 1.0, 0.0], rate) - 1.25).abs() < 1e-15);
        // tau u' + u = 1, u(0) = 0, by backward Euler: the reconstruction's residual is
        // R(s) = (t_n - s)/k (u_n - u_{n-1}), and A^{-1} R = R / tau. Its damped integral
        // over a step is exact here, and R never changes sign, so the triangle
        // inequality behind the bound is an equality: the propagated bound is the true
        // largest error, to rounding, on every grid.
        let tau = 0.07;
        let rate = 1.0 / tau;
        for n in [4usize, 16, 64, 256] {
            let g = TimeGrid::uniform(1.0, n);
            let k = 1.0 / n as f64;
            let (mut u, mut theta, mut err) = (0.0f64, vec![], 0.0f64);
            let weight = (1.0 - (-rate * k).exp() * (1.0 + rate * k)) / (rate * rate * k);
            for i in 1..=n {
                let next = (tau * u / k + 1.0) / (tau / k + 1.0);
                theta.push(weight * (next - u).abs() / tau);
                u = next;
                err = err.max((1.0 - (-(i as f64) * k / tau).exp() - u).abs());
            }
            let bound = propagated(&g, &theta, rate);
            assert!(
                (bound - err).abs() <= 1e-13 * err,
                "n = {n}: {bound} vs {err}"
            );
        }
    }

    #[test]
    fn the_predictor_weighs_half_on_equal_steps() {
        let g = TimeGrid::uniform(1.0, 8);
        assert_eq!(predictor(&g, 1), (1.0, 0.5));
        assert_eq!(predictor(&g, 5), (1.0, 0.5));
        let g = g.bisect(&[2]).unwrap();
        // steps: 1/8, 1/8, 1/16, 1/16, 1/8 ...
        assert_eq!(predictor(&g, 3), (0.5, 1.0 / 3.0));
        assert_eq!(predictor(&g, 5), (2.0, 2.0 / 3.0));
    }

    #[test]
    fn a_linear_motion_has_no_local_error_and_stops_at_once() {
        // u(t) = t is integrated exactly: every gap is 0 past the first step.
        let s = Settings {
            tol: 1e-12,
            ..Settings::default()
        };
        let (levels, stop) = adapt_time(
            1.0,
            &s,
            0.0,
            |g| {
                let gaps = (1..=g.len()).map(|_| 0.0).collect();
                Ok::<_, InputError>(Solved {
                    gaps,
                    theta: vec![],
                    norm_max: 1.0,
                    out: (),
                })
            },
            |_| {},
        )
        .unwrap();
        assert_eq!((levels.len(), stop), (1, Stop::Tolerance));
    }

    #[test]
    fn the_first_step_takes_the_second_steps_curvature() {
        let g = TimeGrid::uniform(1.0, 4).bisect(&[0]).unwrap();
        // steps 1/8, 1/8, 1/4, 1/4, 1/4: eta_2 = gap_2 / 2, eta_1 = eta_2, eta_3 = 2 gap_3 / 3.
        let eta = indicators(&g, &[7.0, 2.0, 3.0, 0.0, 0.0]);
        assert_eq!(eta[..3], [1.0, 1.0, 2.0]);
        let g = TimeGrid::uniform(1.0, 4).bisect(&[1]).unwrap();
        // steps 1/4, 1/8, ...: eta_2 = gap_2 / 3, eta_1 = 4 eta_2.
        let eta = indicators(&g, &[7.0, 3.0, 0.0, 0.0, 0.0]);
        assert!((eta[0] - 4.0).abs() < 1e-15 && (eta[1] - 1.0).abs() < 1e-15);
        assert_eq!(indicators(&TimeGrid::uniform(1.0, 1), &[2.0]), [1.0]);
    }

    #[test]
    fn a_layer_is_refined_at_its_start_until_the_budget() {
        // u = 1 - exp(-t/tau): gaps from the exact solution on the grid.
        let tau = 0.07;
        let u = |t: f64| 1.0 - (-t / tau).exp();
        let s = Settings {
            max_steps: 200,
            ..Settings::default()
        };
        let (levels, stop) = adapt_time(
            1.0,
            &s,
            1.0 / tau,
            |g| {
                let mut gaps = vec![];
                for n in 1..=g.len() {
                    let (r, _) = predictor(g, n);
                    let (u1, u0) = (u(g.t(n - 1)), if n > 1 { u(g.t(n - 2)) } else { 0.0 });
                    let pred = if n > 1 { u1 + r * (u1 - u0) } else { 0.0 };
                    gaps.push((u(g.t(n)) - pred).abs());
                }
                Ok::<_, InputError>(Solved {
                    gaps,
                    theta: vec![],
                    norm_max: 1.0,
                    out: (),
                })
            },
            |_| {},
        )
        .unwrap();
        assert_eq!(stop, Stop::Steps);
        let last = &levels.last().unwrap().grid;
        // Short steps first, long steps late.
        assert!(last.k(1) < last.k(last.len()) / 8.0, "{last:?}");
        let first = levels[0].estimate;
        assert!(levels.last().unwrap().estimate < first / 4.0);
        // The damped estimate never passes the plain sum; over the true largest error
        // of backward Euler on u' = (1 - u)/tau it stays above 1 and falls towards it
        // level by level (3.02 on the first grid, k/tau = 3.6; 1.04 on the last).
        let mut ratios = vec![];
        for l in &levels {
            assert!(l.estimate <= l.sum, "{} {}", l.estimate, l.sum);
            let (mut v, mut err) = (0.0f64, 0.0f64);
            for n in 1..=l.grid.len() {
                let k = l.grid.k(n);
                v = (v + k / tau) / (1.0 + k / tau);
                err = err.max((u(l.grid.t(n)) - v).abs());
            }
            let ratio = l.estimate / err;
            ratios.push(ratio);
        }
        assert!(ratios.iter().all(|&r| r > 1.0), "{ratios:?}");
        assert!(ratios.windows(2).all(|w| w[1] < w[0]), "{ratios:?}");
        assert!(*ratios.last().unwrap() < 1.05, "{ratios:?}");
        assert!(Settings { theta: 0.0, ..s }.check().is_err());
    }
}
