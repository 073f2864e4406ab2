//! The softening family: a smooth, nonmonotone law of a crushable foundation,
//! $$p(s) = c\,s\,e^{-s/a} \quad (s > 0), \qquad p(s) = 0 \quad (s \le 0),$$
//! with a stiffness $c > 0$ and a length $a > 0$. The foundation resists in
//! proportion to the penetration at first (slope $c$ at $s = 0^+$), most at $s = a$
//! (where $p = c\,a/e$), and less beyond: it softens, as a layer that gives way.
//!
//! - Potential: $j(s) = c\,a^2\,\big(1 - e^{-x}(1 + x)\big)$, $x = s/a$, for $s > 0$; 0 else.
//! - $p$ is continuous, so Clarke's subdifferential is the single value $p(s)$; $p'$
//!   jumps at $0$ (from 0 to $c$), the one kink.
//! - $p'(s) = c\,e^{-s/a}(1 - s/a)$, smallest at $s = 2a$: $\inf p' = -c\,e^{-2}$. So
//!   $j$ is relaxed monotone with H(j)'s constant $m = c\,e^{-2}$, and there is no
//!   downward jump.
//! - Regimes: `branch1` while $p$ rises ($0 < s \le a$), `branch2` once it softens.
//!
//! Not piecewise affine: the convexification and the penalty, whose models are
//! built from affine pieces, decline it by name; Newton and proximal gradient solve it
//! with the prox below.

use super::{Prox, Regime, Tangent};
use crate::error::{InputError, bounded};

/// The regimes other than no contact and the limit: rising, softening.
pub const BRANCHES: usize = 3;

/// $p(s) = c\,s\,e^{-s/a}$ for $s > 0$, validated on construction.
#[derive(Debug, Clone, PartialEq)]
pub struct Softening {
    c: f64,
    a: f64,
}

impl Softening {
    /// The law with stiffness `c` and length `a`, both positive and finite; an error
    /// names the field.
    pub fn new(c: f64, a: f64) -> Result<Softening, InputError> {
        for (field, v) in [("law.stiffness", c), ("law.length", a)] {
            bounded(field, v, f64::MAX)?;
            if v <= 0.0 {
                return Err(InputError::field(field, v, "a positive number"));
            }
        }
        Ok(Softening { c, a })
    }

    /// The stiffness $c$: the slope of $p$ at $s = 0^+$.
    pub fn stiffness(&self) -> f64 {
        self.c
    }

    /// The length $a$, where $p$ is largest.
    pub fn length(&self) -> f64 {
        self.a
    }

    /// $p(s) = c\,s\,e^{-s/a}$ for $s > 0$, 0 for $s \le 0$.
    pub fn p(&self, s: f64) -> f64 {
        if s > 0.0 {
            self.c * s * (-s / self.a).exp()
        } else {
            0.0
        }
    }

    /// $p'(s)$, the right derivative at the kink $s = 0$ taken from the left (0).
    pub fn dp(&self, s: f64) -> f64 {
        if s > 0.0 {
            self.c * (-s / self.a).exp() * (1.0 - s / self.a)
        } else {
            0.0
        }
    }

    /// $j(s) = c\,a^2 (1 - e^{-x}(1 + x))$, by its series for small $x$ (where the
    /// closed form cancels).
    pub fn j(&self, s: f64) -> f64 {
        if s <= 0.0 {
            return 0.0;
        }
        let x = s / self.a;
        let f = if x < 1e-3 {
            // sum_{n >= 2} (-1)^n (n - 1) x^n / n!
            x * x * (0.5 - x / 3.0 + x * x / 8.0 - x * x * x / 30.0)
        } else {
            -(-x).exp_m1() - x * (-x).exp()
        };
        self.c * self.a * self.a * f
    }

    /// $\inf p' = -c\,e^{-2}$, at $s = 2a$.
    pub fn curvature_min(&self) -> f64 {
        -self.c * (-2.0f64).exp()
    }

    /// The tangent of $p$ at `s`, the linearisation $p(s) + p'(s)(t - s)$ (slope
    /// [`Softening::dp`]).
    pub fn tangent(&self, s: f64) -> Tangent {
        let slope = self.dp(s);
        Tangent {
            at_zero: self.p(s) - slope * s,
            slope,
        }
    }

    /// The regime of `s` not at the limit: no contact for $s \le 0$, `Branch(1)` while
    /// $p$ rises ($0 < s \le a$), `Branch(2)` beyond.
    pub fn regime(&self, s: f64) -> Regime {
        if s <= 0.0 {
            Regime::NoContact
        } else if s <= self.a {
            Regime::Branch(1)
        } else {
            Regime::Branch(2)
        }
    }

    /// The prox: for $v \le 0$ the node stays at $v$ (no contact, $p = 0$); else the
    /// root in $(0, \min(v, g)]$ of $h(s) = s - v + \gamma\,kw\,p(s)$, increasing when
    /// $1 + \gamma\,kw\,\inf p' > 0$, by Newton's method safeguarded by bisection, or
    /// $g$ when the root lies beyond it (pinned).
    pub fn prox(&self, v: f64, gamma: f64, kw: f64, g: f64) -> Prox {
        let gk = gamma * kw;
        let done = |s: f64, pinned: bool| Prox {
            s,
            slope: if pinned {
                0.0
            } else {
                1.0 / (1.0 + gk * self.dp(s))
            },
            curvature: self.dp(s),
            piece: match self.regime(s) {
                Regime::Branch(b) => b,
                _ => 0,
            },
        };
        if v <= 0.0 {
            return if v <= g {
                done(v, false)
            } else {
                done(g, true)
            };
        }
        let h = |s: f64| s - v + gk * self.p(s);
        let hi0 = v.min(g);
        if h(hi0) < 0.0 {
            // The root lies beyond g: pinned there.
            return done(g, true);
        }
        let (mut lo, mut hi) = (0.0, hi0);
        let mut s = 0.5 * (lo + hi);
        for _ in 0..200 {
            let hs = h(s);
            if hs == 0.0 {
                break;
            }
            if hs < 0.0 {
                lo = s;
            } else {
                hi = s;
            }
            let d = 1.0 + gk * self.dp(s);
            let newton = s - hs / d;
            let next = if d > 0.0 && newton > lo && newton < hi {
                newton
            } else {
                0.5 * (lo + hi)
            };
            if (next - s).abs() <= 4.0 * f64::EPSILON * s.abs().max(f64::MIN_POSITIVE) {
                s = next;
                break;
            }
            s = next;
        }
        done(s, false)
    }

    /// Samples of the law on $[lo, hi]$, with the kink at 0 and the turn at $a$.
    pub fn polyline(&self, lo: f64, hi: f64) -> Vec<(f64, f64)> {
        let mut xs: Vec<f64> = (0..=200)
            .map(|i| lo + (hi - lo) * i as f64 / 200.0)
            .collect();
        xs.extend([0.0, self.a].into_iter().filter(|&x| x > lo && x < hi));
        xs.sort_by(f64::total_cmp);
        xs.dedup();
        xs.into_iter().map(|x| (x, self.p(x))).collect()
    }

    /// The law in words, one line each: the formula with $c$ and $a$, then the peak
    /// $p(a)$ and the steepest softening $p'(2a)$.
    pub fn describe(&self) -> Vec<String> {
        vec![
            format!(
                "law: softening p(s) = c s exp(-s/a) for s > 0, c = {}, a = {}",
                self.c, self.a
            ),
            format!(
                "  rises to p(a) = {:e} at s = a, softens beyond; steepest softening p'(2a) = {:e}",
                self.p(self.a),
                self.curvature_min()
            ),
        ]
    }
}
