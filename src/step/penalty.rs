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

    /// The law with the penalty branch added at `g` (see [`Law::penalised`]).
    pub fn penalised(law: &Law, g: f64, stiffness: f64) -> Law {
        law.penalised(g, stiffness)
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
