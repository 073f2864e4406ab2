//! The time grid $0 = t_0 < t_1 < \dots < t_M = T$ of a run.
//!
//! The scheme allows any grid: step $n$ solves with $k_n = t_n - t_{n-1}$. Two are
//! offered.
//!
//! - **Uniform**, $k = T/N$, $t_n = n k$: the paper's, and the default.
//! - **Into the initial layer.** A load applied in full at $t = 0$ starts a layer
//!   $u(t) \approx (1 - e^{-t/\tau})\,u_\infty$ of the relaxation time $\tau$ (the book's
//!   time chapter). Backward Euler's local error there is about
//!   $\tfrac12 k_n^2 |\ddot u| \sim \tfrac12 (k_n/\tau)^2 e^{-t_n/\tau}$, so the step may grow
//!   as the layer decays: from $k_0 = (T/N)/2^J$ each step proposes
//!   $$k^\ast_{n+1} = k^\ast_n\,(1 + k^\ast_n/(2\tau)),$$
//!   until $k^\ast$ reaches $T/N$. Each step takes the largest $(T/N)/2^j$ not above
//!   $k^\ast$ at which the time already reached is a multiple of it. So the grid has
//!   at most $J + 1$ distinct steps (the general loop factorises once per distinct
//!   step, and its steps only grow), every $t_n$ is a multiple of $(T/N)/2^J$ (a
//!   uniform reference with a multiple of $N 2^J$ steps has a step at each), and the
//!   last steps are $T/N$ long.
//!
//! The growth $1/(2\tau)$ rather than $1/\tau$ (the rate at which the layer's
//! local error falls): rounded down to powers of two, the faster growth jumps to
//! steps the layer cannot take yet. The time study (`data/adaptive_time.csv`)
//! measures what the grid saves.

use crate::error::InputError;
use crate::scenario::Scenario;

/// The shortest relaxation time of `scn`'s viscosity against its elasticity: the
/// smaller of $\mathcal C$'s and $\mathcal G$'s ratios on each Lamé part (with
/// proportional damping, both are the one $\tau$); 0 without viscosity.
pub fn fastest_relaxation(scn: &Scenario) -> f64 {
    if !scn.problem.viscous() {
        return 0.0;
    }
    let (g, c) = (scn.elasticity(), scn.viscosity());
    [c.a / g.a, c.b / g.b]
        .into_iter()
        .filter(|t| t.is_finite() && *t > 0.0)
        .fold(f64::INFINITY, f64::min)
}

/// The most halvings $J$ of the first step: $2^{30}$ smaller than $T/N$.
pub const MAX_HALVINGS: u32 = 30;

/// A run's time grid: the times $t_1, \dots, t_M = T$ and each step's length.
#[derive(Debug, Clone, PartialEq)]
pub struct TimeGrid {
    t_end: f64,
    /// $N$: the longest step is $T/N$.
    n: usize,
    /// $J$: the first step is $(T/N)/2^J$; 0 for the uniform grid.
    halvings: u32,
    /// Per step, the exponent $e$ of its length $2^e$ units of $(T/N)/2^J$ (empty for
    /// the uniform grid, whose every step is $T/N$).
    exponents: Vec<u32>,
    /// Per step, $t_n$ in those units.
    ends: Vec<u64>,
}

impl TimeGrid {
    /// $N$ steps of $T/N$.
    pub fn uniform(t_end: f64, n: usize) -> TimeGrid {
        TimeGrid {
            t_end,
            n,
            halvings: 0,
            exponents: vec![],
            ends: vec![],
        }
    }

    /// The grid into the initial layer of relaxation time `tau` (see the module): first
    /// step $(T/N)/2^J$, longest $T/N$. $J = 0$ is the uniform grid.
    pub fn layer(t_end: f64, n: usize, halvings: u32, tau: f64) -> Result<TimeGrid, InputError> {
        if halvings == 0 {
            return Ok(TimeGrid::uniform(t_end, n));
        }
        if halvings > MAX_HALVINGS {
            return Err(InputError::field(
                "time_layer",
                halvings,
                format!("a number of halvings of the first step from 0 to {MAX_HALVINGS}"),
            ));
        }
        if !(tau.is_finite() && tau > 0.0) {
            return Err(InputError::field(
                "time_layer",
                halvings,
                format!(
                    "0 here: a grid into the initial layer follows the relaxation time tau \
                     of a viscous scene with proportional damping, and this scene has tau = \
                     {tau}"
                ),
            ));
        }
        let per = 1u64 << halvings;
        let total = (n as u64).checked_mul(per).filter(|&t| t < 1 << 52);
        let Some(total) = total else {
            return Err(InputError::field(
                "time_layer",
                halvings,
                format!(
                    "at most {} halvings with {n} steps: the grid counts time in units of \
                     T/(N 2^J), and N 2^J must stay below 2^52",
                    (52 - (n as f64).log2().ceil() as u32).saturating_sub(1)
                ),
            ));
        };
        // ANCHOR: layer_grid
        let unit = t_end / total as f64;
        let (mut exponents, mut ends) = (vec![], vec![]);
        let (mut at, mut ideal) = (0u64, unit);
        while at < total {
            // The largest 2^e units within the proposal (at least one unit, at most
            // T/N) at which `at` is aligned.
            let within = ((ideal / unit).floor() as u64).clamp(1, per);
            let mut e = 63 - within.leading_zeros();
            while at % (1u64 << e) != 0 {
                e -= 1;
            }
            let size = 1u64 << e;
            at += size;
            exponents.push(e);
            ends.push(at);
            let k = ideal.max(size as f64 * unit);
            ideal = k * (1.0 + k / (2.0 * tau));
        }
        // ANCHOR_END: layer_grid
        Ok(TimeGrid {
            t_end,
            n,
            halvings,
            exponents,
            ends,
        })
    }

    /// The grid of a run of `scn` with longest step $T/N$ (`steps` $= N$) and `halvings`
    /// $= J$ (0: uniform), into the layer of the scene's fastest relaxation time
    /// ([`fastest_relaxation`]).
    pub fn of(scn: &Scenario, steps: usize, halvings: u32) -> Result<TimeGrid, InputError> {
        if halvings == 0 {
            return Ok(TimeGrid::uniform(scn.t_end, steps));
        }
        TimeGrid::layer(scn.t_end, steps, halvings, fastest_relaxation(scn))
    }

    /// The grid of steps of $2^{e_i}$ units of $(T/N)/2^J$ (`exponents` $= e_1, e_2,
    /// \dots$), each starting at a multiple of its own length, together $N 2^J$ units.
    /// The shortest step is made one unit ($J$ lowered by its exponent), so the grid
    /// of steps all $T/N$ is the uniform one.
    pub fn from_exponents(
        t_end: f64,
        n: usize,
        halvings: u32,
        exponents: &[u32],
    ) -> Result<TimeGrid, InputError> {
        let bad = |what: String| InputError::field("time grid", format!("{exponents:?}"), what);
        if halvings > MAX_HALVINGS {
            return Err(bad(format!(
                "at most {MAX_HALVINGS} halvings, not {halvings}"
            )));
        }
        let total = (n as u64)
            .checked_mul(1u64 << halvings)
            .filter(|&t| t < 1 << 52)
            .ok_or_else(|| bad(format!("N 2^J below 2^52 (N = {n}, J = {halvings})")))?;
        let shift = exponents.iter().copied().min().unwrap_or(0).min(halvings);
        let (mut at, mut ends, mut exps) = (0u64, vec![], vec![]);
        for (i, &e) in exponents.iter().enumerate() {
            if e > halvings || at % (1u64 << e) != 0 {
                return Err(bad(format!(
                    "steps of at most T/N, each starting at a multiple of its length \
                     (step {} does not)",
                    i + 1
                )));
            }
            at += 1u64 << e;
            ends.push(at >> shift);
            exps.push(e - shift);
        }
        if at != total {
            return Err(bad(format!(
                "steps that add up to T ({at} of {total} units)"
            )));
        }
        let halvings = halvings - shift;
        if halvings == 0 {
            return Ok(TimeGrid::uniform(t_end, n));
        }
        Ok(TimeGrid {
            t_end,
            n,
            halvings,
            exponents: exps,
            ends,
        })
    }

    /// Refuses, by name, a grid with no step or one that does not end at `t_end` (a
    /// scene's $T$), to rounding.
    pub fn check_ends_at(&self, t_end: f64) -> Result<(), InputError> {
        let end = if self.is_empty() {
            0.0
        } else {
            self.t(self.len())
        };
        if self.is_empty() || (end - t_end).abs() > 1e-12 * t_end.abs().max(1.0) {
            return Err(InputError::field(
                "time grid",
                format!("a grid ending at t = {end}"),
                format!("a grid of at least one step ending at the scene's T = {t_end}"),
            ));
        }
        Ok(())
    }

    /// Each step's exponent $e$: its length is $2^e$ units of $(T/N)/2^J$.
    pub fn exponents(&self) -> Vec<u32> {
        if self.halvings == 0 {
            vec![0; self.n]
        } else {
            self.exponents.clone()
        }
    }

    /// The grid with each step of `marked` (indices from 0) cut into two halves.
    pub fn bisect(&self, marked: &[usize]) -> Result<TimeGrid, InputError> {
        let mut exps = self.exponents();
        let mut halvings = self.halvings;
        if marked.iter().any(|&i| exps.get(i) == Some(&0)) {
            halvings += 1;
            exps.iter_mut().for_each(|e| *e += 1);
        }
        let mut cut = vec![false; exps.len()];
        for &i in marked {
            if let Some(c) = cut.get_mut(i) {
                *c = true;
            }
        }
        let mut out = Vec::with_capacity(exps.len() + marked.len());
        for (e, c) in exps.into_iter().zip(cut) {
            if c {
                out.extend([e - 1, e - 1]);
            } else {
                out.push(e);
            }
        }
        TimeGrid::from_exponents(self.t_end, self.n, halvings, &out)
    }

    /// The number of steps $M$.
    pub fn len(&self) -> usize {
        if self.halvings == 0 {
            self.n
        } else {
            self.ends.len()
        }
    }

    /// Whether the grid has no step (never, for a grid that was built).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether every step is $T/N$.
    pub fn is_uniform(&self) -> bool {
        self.halvings == 0
    }

    /// $N$: the longest step is $T/N$.
    pub fn n(&self) -> usize {
        self.n
    }

    /// $J$: the first step is $(T/N)/2^J$.
    pub fn halvings(&self) -> u32 {
        self.halvings
    }

    /// The longest step, $T/N$.
    pub fn k_max(&self) -> f64 {
        self.t_end / self.n as f64
    }

    fn unit(&self) -> f64 {
        self.t_end / (self.n as u64 * (1u64 << self.halvings)) as f64
    }

    /// $t_n$ of step `step` in $0..=M$ (on the uniform grid $n\,(T/N)$, as every
    /// uniform run has computed it).
    pub fn t(&self, step: usize) -> f64 {
        if self.halvings == 0 || step == 0 {
            step as f64 * self.k_max()
        } else {
            self.ends[step - 1] as f64 * self.unit()
        }
    }

    /// $k_n = t_n - t_{n-1}$ of step `step` in $1..=M$ (exact: a power of two times
    /// the unit).
    pub fn k(&self, step: usize) -> f64 {
        if self.halvings == 0 {
            self.k_max()
        } else {
            (1u64 << self.exponents[step - 1]) as f64 * self.unit()
        }
    }

    /// The index of step `step`'s length among the powers of two from the shortest
    /// step up (0 on the uniform grid; a layer grid's lengths never shrink).
    pub fn size_index(&self, step: usize) -> usize {
        if self.halvings == 0 {
            0
        } else {
            self.exponents[step - 1] as usize
        }
    }

    /// The shortest step: $(T/N)/2^J$ (every grid has a step of one unit).
    pub fn k_min(&self) -> f64 {
        if self.halvings == 0 {
            self.k_max()
        } else {
            self.unit()
        }
    }

    /// The step's time in units of the finest $(T/N)/2^J$: where a uniform reference
    /// with $N 2^J$ steps (or a multiple) has the same time.
    pub fn units(&self, step: usize) -> u64 {
        if self.halvings == 0 {
            step as u64
        } else {
            self.ends[step - 1]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_uniform_grid_is_the_one_every_run_had() {
        let g = TimeGrid::uniform(1.0, 64);
        assert_eq!(g.len(), 64);
        for n in 1..=64 {
            assert_eq!(g.t(n).to_bits(), (n as f64 * (1.0 / 64.0)).to_bits());
            assert_eq!(g.k(n), 1.0 / 64.0);
        }
        assert_eq!(TimeGrid::layer(1.0, 64, 0, 0.07).unwrap(), g);
    }

    #[test]
    fn a_layer_grid_grows_by_aligned_powers_of_two_and_ends_at_t() {
        let (n, j, tau) = (16, 6, 0.07);
        let g = TimeGrid::layer(1.0, n, j, tau).unwrap();
        let m = g.len();
        assert_eq!(g.k(1), 1.0 / 16.0 / 64.0);
        assert_eq!(g.t(m), 1.0);
        assert_eq!(g.k(m), 1.0 / 16.0);
        let mut prev = 0.0;
        for s in 1..=m {
            let k = g.k(s);
            assert!((g.t(s) - prev - k).abs() < 1e-15, "step {s}");
            if s > 1 {
                assert!(k >= g.k(s - 1), "step {s} shrinks");
                assert!(k <= 2.0 * g.k(s - 1), "step {s} more than doubles");
            }
            assert_eq!(g.units(s) % (1 << (g.size_index(s) as u64)), 0);
            prev = g.t(s);
        }
        // Far fewer steps than the uniform grid of the first step's length, more than N.
        assert!(m > n && m < n * 64 / 4, "{m}");
        let distinct: std::collections::BTreeSet<u64> = (1..=m).map(|s| g.k(s).to_bits()).collect();
        assert_eq!(distinct.len(), j as usize + 1);
    }

    #[test]
    fn a_grid_must_end_at_the_scenes_t() {
        let g = TimeGrid::uniform(1.0, 4).bisect(&[0, 3]).unwrap();
        assert!(g.check_ends_at(1.0).is_ok());
        let e = g.check_ends_at(2.0).unwrap_err().to_string();
        assert!(e.contains("time grid") && e.contains("T = 2"), "{e}");
    }

    #[test]
    fn bad_layers_are_refused_by_name() {
        let e = TimeGrid::layer(1.0, 16, 31, 0.07).unwrap_err().to_string();
        assert!(
            e.contains("time_layer") && e.contains("from 0 to 30"),
            "{e}"
        );
        let e = TimeGrid::layer(1.0, 16, 4, 0.0).unwrap_err().to_string();
        assert!(e.contains("relaxation time"), "{e}");
        let e = TimeGrid::layer(1.0, 1 << 30, 30, 0.07)
            .unwrap_err()
            .to_string();
        assert!(e.contains("2^52"), "{e}");
    }
}
