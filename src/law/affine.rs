//! The piecewise-affine family: a piecewise-linear, possibly discontinuous
//! function $p$, its potential $j(s) = \int_0^s p$ and the Clarke subdifferential
//! $\partial_{Cl} j(s)$ (paper §4, (4.5); the paper's instance is (5.1)).
//!
//! The real line is cut by breakpoints $s_1 < \dots < s_K$ into branches
//! $b = 0, \dots, K$: branch 0 is $(-\infty, s_1]$, branch $b$ is $(s_b, s_{b+1}]$,
//! branch $K$ is $(s_K, \infty)$. On branch $b$, $p$ is affine with slope $c_b$.
//! At $s_b$ the law may jump by $d_b = p(s_b^+) - p(s_b^-)$.
//!
//! Because $p$ is locally bounded and piecewise continuous, Clarke's generalised
//! gradient of $j$ at $s$ is the closed convex hull of the one-sided limits:
//! $\partial_{Cl} j(s) = [\min(p(s^-), p(s^+)), \max(p(s^-), p(s^+))]$, a single
//! point wherever $p$ is continuous.
//!
//! Branch indices, slopes and `p_on` stay in this room: the rest of the code asks
//! [`super::Law`] for what the mathematics needs.

use super::{Interval, Regime};
use crate::error::{InputError, bounded};

/// A piecewise-linear normal compliance law, validated on construction.
#[derive(Debug, Clone, PartialEq)]
pub struct Affine {
    /// Breakpoints $s_1 < \dots < s_K$.
    breaks: Vec<f64>,
    /// The jump of $p$ at each breakpoint, as given.
    jump_sizes: Vec<f64>,
    /// Slopes $c_0, \dots, c_K$, one per branch.
    slopes: Vec<f64>,
    /// Value of $p$ at the left end of each branch: $p(s_1^-)$ for branch 0
    /// (anchored at $s_1$, or at 0 when there are no breakpoints), $p(s_b^+)$ for
    /// branch $b \ge 1$.
    start: Vec<f64>,
    /// Value of the antiderivative (normalised to vanish at the anchor of branch 0)
    /// at the left end of each branch.
    prim_start: Vec<f64>,
    /// $j(s) = P(s) - P(0)$ with $P$ the antiderivative above.
    prim_zero: f64,
}

/// The paper's law (5.1): $p = 0$ for $s \le 0$, slope $c_1 = 200$ up to
/// $u_1 = 0.05$, slope $c_2 = -100$ up to $u_2 = 0.075$, slope $c_3 = 300$ beyond.
// ANCHOR: law_paper
pub fn paper_law() -> super::Law {
    super::Law::new(
        &[0.0, 0.05, 0.075],
        &[0.0, 200.0, -100.0, 300.0],
        &[0.0; 3],
        0.0,
    )
    .expect("the paper's law is valid")
}
// ANCHOR_END: law_paper

impl Affine {
    /// Builds a law from its breakpoints, the slope on each branch, the jump
    /// at each breakpoint and the value `p_left` $= p(s_1^-)$ (or $p(0)$ when there
    /// are no breakpoints). Every input is checked; an error names the field.
    pub fn new(
        breaks: &[f64],
        slopes: &[f64],
        jumps: &[f64],
        p_left: f64,
    ) -> Result<Affine, InputError> {
        for (i, &s) in breaks.iter().enumerate() {
            bounded(&format!("law.breakpoints[{i}]"), s, f64::MAX)?;
            if i > 0 && s <= breaks[i - 1] {
                return Err(InputError::field(
                    format!("law.breakpoints[{i}]"),
                    s,
                    format!(
                        "a value above law.breakpoints[{}] = {} (breakpoints strictly increase)",
                        i - 1,
                        breaks[i - 1]
                    ),
                ));
            }
        }
        if slopes.len() != breaks.len() + 1 {
            return Err(InputError::field(
                "law.slopes",
                format!("{} entries", slopes.len()),
                format!(
                    "{} entries, one per branch (one more than law.breakpoints)",
                    breaks.len() + 1
                ),
            ));
        }
        if jumps.len() != breaks.len() {
            return Err(InputError::field(
                "law.jumps",
                format!("{} entries", jumps.len()),
                format!("{} entries, one per breakpoint", breaks.len()),
            ));
        }
        for (i, &c) in slopes.iter().enumerate() {
            bounded(&format!("law.slopes[{i}]"), c, f64::MAX)?;
        }
        for (i, &d) in jumps.iter().enumerate() {
            bounded(&format!("law.jumps[{i}]"), d, f64::MAX)?;
        }
        bounded("law.p_left", p_left, f64::MAX)?;
        let nb = slopes.len();
        let mut start = vec![p_left; nb];
        let mut prim_start = vec![0.0; nb];
        for b in 1..nb {
            let len = if b == 1 {
                0.0
            } else {
                breaks[b - 1] - breaks[b - 2]
            };
            let end_val = start[b - 1] + slopes[b - 1] * len;
            prim_start[b] =
                prim_start[b - 1] + start[b - 1] * len + 0.5 * slopes[b - 1] * len * len;
            start[b] = end_val + jumps[b - 1];
        }
        let mut law = Affine {
            breaks: breaks.to_vec(),
            jump_sizes: jumps.to_vec(),
            slopes: slopes.to_vec(),
            start,
            prim_start,
            prim_zero: 0.0,
        };
        law.prim_zero = law.prim(0.0);
        Ok(law)
    }

    /// The breakpoints $s_1 < \dots < s_K$.
    pub fn breakpoints(&self) -> &[f64] {
        &self.breaks
    }
    /// The jump $p(s_i^+) - p(s_i^-)$ at each breakpoint, as given to [`Affine::new`].
    pub fn jump_sizes(&self) -> &[f64] {
        &self.jump_sizes
    }
    /// $p(s_1^-)$ (or $p(0)$ when there are no breakpoints), as given to [`Affine::new`].
    pub fn p_left(&self) -> f64 {
        self.start[0]
    }
    /// The slopes $c_0, \dots, c_K$, one per branch.
    pub fn slopes(&self) -> &[f64] {
        &self.slopes
    }
    /// The number of branches, $K + 1$.
    pub fn n_branches(&self) -> usize {
        self.slopes.len()
    }

    /// The branch holding `s`: the number of breakpoints strictly below `s`
    /// (branches are closed on the right).
    pub fn branch(&self, s: f64) -> usize {
        self.breaks.partition_point(|&b| b < s)
    }

    /// Left end (anchor) of branch `b`.
    pub fn anchor(&self, b: usize) -> f64 {
        match b {
            0 => self.breaks.first().copied().unwrap_or(0.0),
            _ => self.breaks[b - 1],
        }
    }

    /// $p$ on branch `b`, extended affinely to all of $\mathbb{R}$.
    pub fn p_on(&self, b: usize, s: f64) -> f64 {
        self.start[b] + self.slopes[b] * (s - self.anchor(b))
    }

    /// The one-sided limits $p(s^-)$, $p(s^+)$.
    pub fn p_sides(&self, s: f64) -> (f64, f64) {
        let left = self.branch(s);
        let right = self.breaks.partition_point(|&b| b <= s);
        (self.p_on(left, s), self.p_on(right, s))
    }

    /// $p(s)$ where $p$ is continuous; at a jump, the left limit.
    pub fn p(&self, s: f64) -> f64 {
        self.p_on(self.branch(s), s)
    }

    /// Clarke's subdifferential $\partial_{Cl} j(s)$: the interval spanned by the
    /// one-sided limits of $p$ at $s$ (a point where $p$ is continuous).
    // ANCHOR: clarke
    pub fn clarke(&self, s: f64) -> Interval {
        let (a, b) = self.p_sides(s);
        Interval {
            lo: a.min(b),
            hi: a.max(b),
        }
    }
    // ANCHOR_END: clarke

    /// [`crate::law::Law::clarke`] widened by the breakpoints within `delta` of `s`: the hull of
    /// $\partial_{Cl} j(s)$ and $\partial_{Cl} j(s_b)$ for every $|s_b - s| \le \delta$. A node that
    /// a solver put exactly on a kink comes back from the recovery solve a few units of
    /// rounding away from it; this is the subdifferential it was solved with.
    pub fn clarke_near(&self, s: f64, delta: f64) -> Interval {
        let mut out = self.clarke(s);
        let from = self.breaks.partition_point(|&b| b < s - delta);
        for &b in self.breaks[from..].iter().take_while(|&&b| b <= s + delta) {
            let c = self.clarke(b);
            out.lo = out.lo.min(c.lo);
            out.hi = out.hi.max(c.hi);
        }
        out
    }

    fn prim(&self, s: f64) -> f64 {
        let b = self.branch(s);
        let d = s - self.anchor(b);
        self.prim_start[b] + self.start[b] * d + 0.5 * self.slopes[b] * d * d
    }

    /// The potential $j(s) = \int_0^s p(t)\,dt$ (nonconvex when a slope or a jump is negative).
    pub fn j(&self, s: f64) -> f64 {
        self.prim(s) - self.prim_zero
    }

    /// The most negative curvature of $j$, $\min(0, \min_b c_b)$: the constant
    /// $m$ of hypothesis H(j) when the law has no downward jump.
    pub fn min_slope(&self) -> f64 {
        self.slopes.iter().copied().fold(0.0, f64::min)
    }

    /// Breakpoints with a downward jump, with the jump (negative).
    pub fn down_jumps(&self) -> Vec<(f64, f64)> {
        (0..self.breaks.len())
            .filter_map(|i| {
                let s = self.breaks[i];
                let (a, b) = self.p_sides(s);
                (b < a).then_some((s, b - a))
            })
            .collect()
    }

    /// The slope of $p$ on branch `b`: the curvature of $j$ there.
    pub fn slope(&self, b: usize) -> f64 {
        self.slopes[b]
    }

    /// The breakpoints where $p$ jumps (up or down): a node there is pinned.
    pub fn jumps(&self) -> Vec<f64> {
        self.breaks
            .iter()
            .copied()
            .filter(|&s| {
                let i = self.clarke(s);
                i.hi > i.lo
            })
            .collect()
    }

    /// Whether `s` lies within `tol` of a breakpoint (on the boundary of two branches).
    pub fn near_breakpoint(&self, s: f64, tol: f64) -> bool {
        self.breaks.iter().any(|&b| (s - b).abs() <= tol)
    }

    /// The convex part $j_\cup$ of the convex–concave split $j = j_\cup + j_\cap$
    /// below the limit $g$, with $j_\cap(s) = \tfrac12 c_{\min} s^2$ plus the downward
    /// jumps of $p$ (so that $j_\cup'' = c_b - c_{\min} \ge 0$ on every branch):
    /// the anchor $a$ (the first breakpoint below $g$) and, from it, the runs of
    /// $j_\cup$ on which a node's cost is linear plus quadratic.
    // ANCHOR: convex_split
    pub fn convex_runs(&self, g: f64) -> (f64, Vec<ConvexRun>) {
        let cmin = self.min_slope();
        let down = self.down_jumps();
        // p_cup = p - (j_cap)': the downward jumps at or below `upto` are removed.
        let p_cup = |b: usize, s: f64, upto: f64| {
            self.p_on(b, s)
                - cmin * s
                - down
                    .iter()
                    .filter(|(sb, _)| *sb <= upto)
                    .map(|(_, d)| d)
                    .sum::<f64>()
        };
        let bps: Vec<f64> = self.breaks.iter().copied().filter(|&s| s < g).collect();
        let a = bps.first().copied().unwrap_or(g);
        // Left of the anchor: no breakpoint is passed (f64::MIN keeps the sum empty).
        let mut out = vec![ConvexRun {
            dir: -1.0,
            len: f64::INFINITY,
            lin: -p_cup(0, a, f64::MIN),
            quad: self.slope(0) - cmin,
        }];
        for (idx, &s) in bps.iter().enumerate() {
            let b = idx + 1;
            let end = bps.get(idx + 1).copied().unwrap_or(g);
            out.push(ConvexRun {
                dir: 1.0,
                len: end - s,
                lin: p_cup(b, s, s),
                quad: self.slope(b) - cmin,
            });
        }
        (a, out)
    }

    /// A supergradient of j∩ at s.
    pub fn concave_slope(&self, s: f64) -> f64 {
        self.min_slope() * s
            + self
                .down_jumps()
                .iter()
                .filter(|(sb, _)| s > *sb)
                .map(|(_, d)| d)
                .sum::<f64>()
    }
    // ANCHOR_END: convex_split
}

/// One run of a node's convex part $j_\cup$: $t \ge 0$ (and $t \le$ `len` when
/// finite), cost `lin * t + 0.5 * quad * t^2`, entering $r$ with sign `dir`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConvexRun {
    /// The run's direction from the anchor: $-1$ for the run left of it, $+1$ for the
    /// runs right of it.
    pub dir: f64,
    /// The run's length (to the next breakpoint below $g$, or to $g$); $+\infty$ for
    /// the run left of the anchor.
    pub len: f64,
    /// The cost's linear coefficient: $p_\cup = p - j_\cap'$ at the run's start, in
    /// the run's direction.
    pub lin: f64,
    /// The cost's quadratic coefficient, $c_b - c_{\min} \ge 0$ on the run's branch.
    pub quad: f64,
}

impl Affine {
    /// The regime of a normal displacement `u_nu` not at the limit.
    pub fn regime(&self, u_nu: f64) -> Regime {
        let b = self.branch(u_nu);
        if b == 0 && self.slopes()[0] == 0.0 && self.p_on(0, u_nu) == 0.0 {
            Regime::NoContact
        } else {
            Regime::Branch(b)
        }
    }

    /// $p$ on the branch holding `s`, as $p(0\text{-extension}) + c_b\,s$.
    pub fn tangent(&self, s: f64) -> super::Tangent {
        let b = self.branch(s);
        super::Tangent {
            at_zero: self.p_on(b, 0.0),
            slope: self.slopes[b],
        }
    }

    /// The vertices of the law on $[lo, hi]$: `lo`, both sides of every breakpoint
    /// inside, and the left limit at `hi`.
    pub fn polyline(&self, lo: f64, hi: f64) -> Vec<(f64, f64)> {
        let mut out = vec![(lo, self.p(lo))];
        for &s in self.breaks.iter().filter(|&&s| s > lo && s < hi) {
            let (a, b) = self.p_sides(s);
            out.extend([(s, a), (s, b)]);
        }
        out.push((hi, self.p_sides(hi).0));
        out
    }

    /// The law in words: breakpoints, slopes, the values on both sides of each
    /// breakpoint.
    pub fn describe(&self) -> Vec<String> {
        let mut out = vec![format!(
            "law: breakpoints {:?}, slopes {:?}",
            self.breakpoints(),
            self.slopes()
        )];
        for &b in self.breakpoints() {
            let (l, r) = self.p_sides(b);
            out.push(format!(
                "  at s = {b}: p(s-) = {l}, p(s+) = {r}{}",
                if l == r { "" } else { " (a jump)" }
            ));
        }
        out
    }
}

impl Affine {
    /// $\operatorname{prox}$ of $\gamma\,kw\,j$ restricted to $s \le g$, at $v$: on each
    /// branch (cut at $g$) the objective $kw\, j(s) + (s - v)^2/(2\gamma)$ is a strictly
    /// convex quadratic; its minimiser clamped to the branch is the branch's best
    /// point, and the best branch wins. Returns the point, the slope of the prox
    /// there (0 when clamped to a branch end, i.e. pinned) and the branch.
    // ANCHOR: prox
    pub fn prox(&self, v: f64, gamma: f64, kw: f64, g: f64) -> super::Prox {
        let law = self;
        let bps = law.breakpoints();
        let mut best = (f64::INFINITY, 0.0, 0.0, 0usize);
        for b in 0..law.n_branches() {
            let lo = if b == 0 {
                f64::NEG_INFINITY
            } else {
                bps[b - 1]
            };
            if lo >= g {
                break;
            }
            let hi = bps.get(b).copied().unwrap_or(f64::INFINITY).min(g);
            let c = law.slopes()[b];
            let denom = 1.0 + gamma * kw * c;
            let stat = (v - gamma * kw * law.p_on(b, 0.0)) / denom;
            let s = stat.clamp(lo, hi);
            let obj = kw * law.j(s) + (s - v) * (s - v) / (2.0 * gamma);
            let slope = if s == stat && s < hi && s > lo {
                1.0 / denom
            } else {
                0.0
            };
            if obj < best.0 {
                best = (obj, s, slope, b);
            }
        }
        super::Prox {
            s: best.1,
            slope: best.2,
            curvature: self.slopes[best.3],
            piece: best.3,
        }
    }
    // ANCHOR_END: prox
}

impl Affine {
    /// The law with the penalty branch added at `g`.
    pub fn penalised(&self, g: f64, stiffness: f64) -> Affine {
        let law = self;
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
        Affine::new(&breaks, &slopes, &jumps, p_left)
            .expect("a valid law stays valid with a penalty branch")
    }
}
