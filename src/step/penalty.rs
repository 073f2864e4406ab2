//! The penalty treatment of the unilateral limit, the common alternative to the
//! exact bound: $u_\nu \le g$ is dropped and the law gains a stiff branch beyond $g$,
//! $p(s) \mathrel{+}= \varepsilon^{-1}(s - g)^+$, so the foundation pushes back in
//! proportion to the overshoot. The modified, unconstrained step is solved by the
//! Newton solver. The answer violates $u_\nu \le g$ by about $\varepsilon\,\sigma_\nu$, and the
//! step matrix grows as stiff as $\varepsilon^{-1}$: the price of avoiding the bound.
//!
//! A fixed $\varepsilon^{-1}$ means nothing across problems: multiply the material and
//! the loads by $10^6$ and the same overshoot needs a stiffness $10^6$ times larger.
//! So the registered solver states it *relative to the step*: the penalty's curvature
//! on the weakest contact node, $k w_{\min}\,\varepsilon^{-1}$, is $\rho$ times the
//! bound $\bar\lambda \ge \lambda_{\max}(S)$ on the condensed stiffness (the step's
//! `lipschitz`), $$\varepsilon^{-1} = \rho\,\bar\lambda / (k\,w_{\min}).$$
//! Then the overshoot relative to the step's own displacements is about $1/\rho$ on
//! every scale and mesh, and the condensed matrix's condition grows like $\rho$.

use super::newton::Newton;
use super::{Info, StepProblem, StepSolver};
use crate::law::Law;

/// How the penalty stiffness $\varepsilon^{-1}$ is given.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Stiffness {
    /// $\varepsilon^{-1}$ itself, pressure per metre of overshoot (the stiffness
    /// study of the book sweeps it on one scene).
    Absolute(f64),
    /// $\rho$ in $\varepsilon^{-1} = \rho\,\lambda_{\max}(S)/(k w_{\min})$: the same
    /// relative overshoot whatever the units, mesh or step.
    Relative(f64),
}

/// The registered solver's $\rho$: the penalty's curvature $10^3$ times the
/// body's stiffest condensed mode, an overshoot of about $10^{-3}$ of the step's
/// displacement change and a condition number about $10^3$ times that of $S$.
pub const RELATIVE_STIFFNESS: f64 = 1e3;

/// Newton on the penalised law.
#[derive(Debug, Clone)]
pub struct Penalty {
    /// The penalty stiffness $\varepsilon^{-1}$, absolute or relative to the step.
    pub stiffness: Stiffness,
    /// The Newton solver of the penalised, unconstrained step.
    pub inner: Newton,
    cache: Option<(Law, f64, f64, Law)>,
}

impl Penalty {
    /// A penalty of absolute stiffness $\varepsilon^{-1}$ = `stiffness`.
    pub fn new(stiffness: f64) -> Self {
        Self::with(Stiffness::Absolute(stiffness))
    }

    /// A penalty of relative stiffness $\rho$ (see the module's header).
    pub fn relative(rho: f64) -> Self {
        Self::with(Stiffness::Relative(rho))
    }

    fn with(stiffness: Stiffness) -> Self {
        Penalty {
            stiffness,
            inner: Newton::default(),
            cache: None,
        }
    }

    /// $\varepsilon^{-1}$ on the step `p`.
    pub fn stiffness_on(&self, p: &StepProblem) -> f64 {
        match self.stiffness {
            Stiffness::Absolute(s) => s,
            Stiffness::Relative(rho) => {
                let kw_min = p.kw.iter().copied().fold(f64::INFINITY, f64::min);
                rho * p.lipschitz / kw_min
            }
        }
    }

    /// The law with the penalty branch added at `g` (see [`Law::penalised`]), or
    /// `None` for a family without one.
    pub fn penalised(law: &Law, g: f64, stiffness: f64) -> Option<Law> {
        law.penalised(g, stiffness)
    }
}

/// Why the penalty cannot take a law: the penalty is an affine branch beyond g.
fn declined(law: &Law) -> String {
    format!(
        "solver `penalty` needs a piecewise-affine law (the penalty is an affine branch beyond \
         g); the scenario's law is `{}`: use `newton` or `proxgrad`",
        law.kind()
    )
}

impl StepSolver for Penalty {
    fn name(&self) -> &'static str {
        "penalty"
    }

    /// The penalised answer overshoots $g$ by design.
    fn certified(&self) -> bool {
        false
    }

    fn declines(&self, law: &Law, g: f64) -> Option<String> {
        law.penalised(g, 1.0).is_none().then(|| declined(law))
    }

    fn validate(&self) -> Result<(), crate::error::InputError> {
        // The stiffness is the penalty's one setting; the inner Newton has its own.
        match self.stiffness {
            Stiffness::Absolute(s) => super::setting("penalty", "stiffness", s, 1e-12, 1e15)?,
            Stiffness::Relative(rho) => {
                super::setting("penalty", "relative_stiffness", rho, 1e-6, 1e8)?
            }
        }
        self.inner.settings.validate()
    }

    fn solve(&mut self, p: &StepProblem, r: &mut Vec<f64>) -> Info {
        if let Err(e) = self.validate() {
            return Info::refused(e.to_string());
        }
        let stiffness = self.stiffness_on(p);
        if !(stiffness.is_finite() && stiffness > 0.0) {
            return Info::refused(format!(
                "penalty: the stiffness {stiffness:e} derived from the step (lambda_max(S) = {:e}) \
                 is not a positive number",
                p.lipschitz
            ));
        }
        let fresh = !matches!(&self.cache, Some((l, g, s, _)) if l == p.law && *g == p.g && *s == stiffness);
        if fresh {
            let Some(law) = Self::penalised(p.law, p.g, stiffness) else {
                return Info::refused(declined(p.law));
            };
            self.cache = Some((p.law.clone(), p.g, stiffness, law));
        }
        let law = &self.cache.as_ref().expect("cached").3;
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
