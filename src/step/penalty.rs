//! The penalty treatment of the unilateral limit, the common alternative to the
//! exact bound: $u_\nu \le g$ is dropped and the law gains a stiff branch beyond $g$,
//! $p(s) \mathrel{+}= \varepsilon^{-1}(s - g)^+$, so the foundation pushes back in
//! proportion to the overshoot. The modified, unconstrained step is solved by the
//! Newton solver. The answer violates $u_\nu \le g$ by about $\varepsilon\,\sigma^2_\nu$, and the
//! step matrix grows as stiff as $\varepsilon^{-1}$: the price of avoiding the bound.

use super::newton::Newton;
use super::{Info, StepProblem, StepSolver};
use crate::law::Law;

/// Newton on the penalised law.
#[derive(Debug, Clone)]
pub struct Penalty {
    /// The penalty stiffness $\varepsilon^{-1}$ (pressure per metre of overshoot).
    pub stiffness: f64,
    pub inner: Newton,
    cache: Option<(Law, f64, Law)>,
}

impl Penalty {
    pub fn new(stiffness: f64) -> Self {
        Penalty {
            stiffness,
            inner: Newton::default(),
            cache: None,
        }
    }

    /// The law with the penalty branch added at `g`.
    pub fn penalised(law: &Law, g: f64, stiffness: f64) -> Law {
        let mut breaks: Vec<f64> = law
            .breakpoints()
            .iter()
            .copied()
            .filter(|&s| s < g)
            .collect();
        let mut slopes: Vec<f64> = law.slopes()[..=breaks.len()].to_vec();
        let jumps_below: Vec<f64> = breaks
            .iter()
            .map(|&s| {
                let (a, b) = law.p_sides(s);
                b - a
            })
            .collect();
        // Beyond g: the law's own slope there plus the penalty; p stays continuous at g.
        let beyond = law.slopes()[law.branch(g)];
        breaks.push(g);
        slopes.push(beyond + stiffness);
        let mut jumps = jumps_below;
        jumps.push(0.0);
        let p_left = law.p_sides(breaks[0]).0;
        Law::new(&breaks, &slopes, &jumps, p_left)
            .expect("a valid law stays valid with a penalty branch")
    }
}

impl StepSolver for Penalty {
    fn name(&self) -> &'static str {
        "penalty"
    }

    fn solve(&mut self, p: &StepProblem, r: &mut Vec<f64>) -> Info {
        // The stiffness is the penalty's one setting (the inner Newton checks its own).
        if let Err(e) = super::setting("penalty", "stiffness", self.stiffness, 1e-12, 1e15) {
            return Info::refused(e.to_string());
        }
        let fresh = !matches!(&self.cache, Some((l, g, _)) if l == p.law && *g == p.g);
        if fresh {
            self.cache = Some((
                p.law.clone(),
                p.g,
                Self::penalised(p.law, p.g, self.stiffness),
            ));
        }
        let law = &self.cache.as_ref().expect("cached").2;
        let q = StepProblem {
            s: p.s,
            r0: p.r0,
            kw: p.kw,
            law,
            g: f64::INFINITY,
            lipschitz: p.lipschitz,
            curvature_min: p.curvature_min,
        };
        self.inner.solve(&q, r)
    }
}
