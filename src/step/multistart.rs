//! A wrapper that tests a step for several solutions: the stability map uses it to
//! tell a nonconvex step with one stationary point from one with several.

use super::{Info, Status, StepProblem, StepSolver, inf_norm};

/// Runs a solver, and also solves every step again from other starting points
/// (zero, $g$, $r_0$), recording the largest relative distance between answers:
/// a nonzero spread means the step has several stationary points.
pub struct MultiStart {
    /// The solver run from each starting point.
    pub inner: Box<dyn StepSolver>,
    /// The largest relative distance between answers so far.
    pub spread: f64,
}

impl StepSolver for MultiStart {
    fn validate(&self) -> Result<(), crate::error::InputError> {
        self.inner.validate()
    }

    fn name(&self) -> &'static str {
        self.inner.name()
    }
    fn certified(&self) -> bool {
        self.inner.certified()
    }
    fn solve(&mut self, p: &StepProblem, r: &mut Vec<f64>) -> Info {
        let info = self.inner.solve(p, r);
        if info.status != Status::Converged {
            return info;
        }
        let m = p.m();
        for start in [
            vec![0.0; m],
            vec![p.g.min(1e3); m],
            p.r0.iter().map(|&x| x.min(p.g)).collect(),
        ] {
            let mut x = start;
            if self.inner.solve(p, &mut x).status == Status::Converged {
                let d: Vec<f64> = x.iter().zip(r.iter()).map(|(a, b)| a - b).collect();
                self.spread = self.spread.max(inf_norm(&d) / inf_norm(r).max(1e-300));
            }
        }
        info
    }
}
