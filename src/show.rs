//! What a scenario is, and what it asks of the paper's theory: the text `evhi show`
//! prints. Every hypothesis the code can decide is checked, and each that fails is
//! a `warning:` line (a warning, not an error: the discrete problem may still be
//! solved and certified).

use crate::scenario::Scenario;
use std::fmt::Write;

/// The two sides of H(s), $\beta_B > m\|\iota_h\|^2$, for a run with $n$ segments: $\beta_B$
/// the coercivity of $\mathcal G$, $m = \max(0, -\min_b c_b)$, and the trace constant of the
/// run's own mesh. It grows with $n$ (the spaces are nested: `data/hypotheses.csv`), so a
/// coarser mesh would understate it; above [`TRACE_EXACT_MAX`] segments it is
/// extrapolated upward from the meshes of 128, 256 and 512 segments, and where the
/// scene has no such meshes (ends that only the run's own level resolves) it is
/// computed on the run's own mesh if that has at most [`TRACE_EXACT_NODES`] nodes.
#[derive(Debug, Clone, Copy)]
pub struct Smallness {
    /// $\beta_B$, the coercivity constant of $\mathcal G$: the left side.
    pub beta_b: f64,
    /// $m = \max(0, -\inf p')$, from the law's curvature lower bound.
    pub m: f64,
    /// The discrete trace constant $\|\iota_h\|^2$ ([`crate::norms::trace_norm_sq`]); NaN
    /// where unknown ([`Smallness::unknown`]).
    pub trace_sq: f64,
    /// The run's mesh.
    pub n: usize,
    /// Whether `trace_sq` is extrapolated (n above [`TRACE_EXACT_MAX`]).
    pub extrapolated: bool,
}

/// The largest mesh on which H(s) uses the trace constant computed exactly (its
/// factorisation and eigenvalues take well under a second there).
pub const TRACE_EXACT_MAX: usize = 512;

/// The most nodes of a mesh above [`TRACE_EXACT_MAX`] segments on which the trace
/// constant is computed exactly when it cannot be extrapolated: those of the paper's
/// mesh at 512 segments, whose exact constant the extrapolation computes anyway.
pub const TRACE_EXACT_NODES: usize = 513 * 257;

impl Smallness {
    /// The sides for a run of `scn` with `n` segments, the trace constant computed
    /// (or, above [`TRACE_EXACT_MAX`] segments, extrapolated) as the type says; an
    /// error where the trace constant cannot be computed.
    pub fn of(scn: &Scenario, n: usize) -> Result<Smallness, String> {
        Smallness::of_run(scn, n, None)
    }

    /// [`Smallness::of`] for a run on `mesh`, the scene's uniform mesh of `n` segments
    /// or its file's: where the constant is computed on that mesh, it is computed on
    /// this one (not built again, and its ordering found once for the run and the check).
    pub fn of_run(
        scn: &Scenario,
        n: usize,
        mesh: Option<&crate::mesh::Mesh>,
    ) -> Result<Smallness, String> {
        let trace = |level: usize| match mesh {
            Some(mesh) if level == n => crate::norms::trace_norm_sq_on(mesh),
            _ => crate::norms::trace_norm_sq(scn, level),
        };
        // A mesh scene has one mesh, whatever n: its constant is computed on it, once
        // (the extrapolation from levels 128, 256 and 512 factorised it three times).
        let (trace_sq, extrapolated) = if n <= TRACE_EXACT_MAX || scn.body().is_some() {
            (trace(n)?, false)
        } else {
            // A geometric tail from the last two increments, doubled: an estimate
            // from above of the limit the constant approaches.
            let extrapolated = || -> Result<f64, String> {
                let (a, b, c) = (trace(128)?, trace(256)?, trace(512)?);
                let r = if b > a {
                    ((c - b) / (b - a)).clamp(0.0, 0.9)
                } else {
                    0.9
                };
                Ok(c + 2.0 * (c - b).max(0.0) * r / (1.0 - r))
            };
            let nodes = (n + 1) * (crate::mesh::rows(n, &scn.geometry) + 1);
            match extrapolated() {
                Ok(v) => (v, true),
                Err(_) if nodes <= TRACE_EXACT_NODES => (trace(n)?, false),
                Err(e) => return Err(e),
            }
        };
        Ok(Smallness {
            beta_b: scn.elasticity().coercivity(),
            m: (-scn.law.curvature_min()).max(0.0),
            trace_sq,
            n,
            extrapolated,
        })
    }
    /// The sides with the trace constant unknown (NaN), when it cannot be computed.
    pub fn unknown(scn: &Scenario, n: usize) -> Smallness {
        Smallness {
            beta_b: scn.elasticity().coercivity(),
            m: (-scn.law.curvature_min()).max(0.0),
            trace_sq: f64::NAN,
            n,
            extrapolated: false,
        }
    }
    /// $m\|\iota_h\|^2$.
    pub fn rhs(&self) -> f64 {
        self.m * self.trace_sq
    }
    /// Whether H(s) holds: $m\|\iota_h\|^2 < \beta_B$ (false with the trace constant unknown).
    pub fn holds(&self) -> bool {
        self.rhs() < self.beta_b
    }
}

/// The report of a scenario, for a run with `n` segments and `steps` time steps.
/// Returns the text and the number of warnings.
pub fn report(scn: &Scenario, n: usize, steps: usize) -> (String, usize) {
    let mut s = String::new();
    let mut warnings = 0;
    let mut warn = |s: &mut String, msg: String| {
        warnings += 1;
        let _ = writeln!(s, "warning: {msg}");
    };
    let _ = writeln!(s, "scenario `{}`: {}", scn.name, scn.description);
    // A preset scene unchanged keeps the one-line form; any other is spelled out.
    let geo = &scn.geometry;
    let preset = match geo.preset {
        Some("paper") if *geo == crate::geometry::Geometry::paper() => Some("Paper"),
        Some("rollers") if *geo == crate::geometry::Geometry::rollers() => Some("Rollers"),
        _ => None,
    };
    let _ = writeln!(
        s,
        "  T = {}, g = {}, supports: {}",
        scn.t_end,
        if scn.g.is_finite() {
            scn.g.to_string()
        } else {
            "none (no unilateral limit: pure normal compliance)".to_string()
        },
        preset.unwrap_or("as below")
    );
    if let Some(body) = &scn.body {
        for line in body.describe() {
            let _ = writeln!(s, "{line}");
        }
    } else if preset.is_none() {
        for line in geo.describe() {
            let _ = writeln!(s, "{line}");
        }
    }
    if !scn.problem.viscous() {
        let _ = writeln!(
            s,
            "  problem: {} (no viscosity: {})",
            scn.problem.name(),
            if scn.problem == crate::scenario::Problem::Steady {
                "one solve of the static problem with the loads at t = T"
            } else {
                "each time step the static problem with the loads at t_n"
            }
        );
    }
    for t in &scn.tractions {
        let _ = writeln!(
            s,
            "  traction {}: [{}, {}] on the {} side over [{}, {}]",
            t.field,
            t.f[0],
            t.f[1],
            t.side.name(),
            t.from,
            t.to
        );
    }
    let (g_t, c_t) = (scn.elasticity(), scn.viscosity());
    let _ = writeln!(
        s,
        "material: {}, alpha = {}, beta = {}\n  elasticity G: a = {:.6e}, b = {:.6e} (coercivity {:.6e}); viscosity C: a = {}, b = {} (coercivity {:.6e})",
        scn.material_form.describe(scn.e, scn.kappa),
        scn.alpha,
        scn.beta,
        g_t.a,
        g_t.b,
        g_t.coercivity(),
        c_t.a,
        c_t.b,
        c_t.coercivity()
    );
    let springs: Vec<String> = (scn.supports_with_stiffness().into_iter())
        .map(|(field, _)| field)
        .collect();
    match scn.relaxation_time() {
        Some(_) if !scn.problem.viscous() => {
            let _ = writeln!(
                s,
                "  C = 0: no viscosity; A = 0, so the reduced time loop applies with c = 0 (each \
                 step is the static contact problem alone)"
            );
        }
        Some(tau) if scn.proportional_damping().is_none() => {
            let _ = writeln!(
                s,
                "  C = {tau:.6} G, but the spring support ({}) adds stiffness to B alone: A = C is \
                 not a multiple of B + B_s, so the damping is not proportional and the general \
                 time loop runs",
                springs.join(", ")
            );
        }
        Some(tau) => {
            let _ = writeln!(
                s,
                "  C = {tau:.6} G: proportional damping, one relaxation time tau = {tau:.6} s (backward \
                 Euler resolves the initial layer only for k well below tau; k = {})",
                scn.t_end / steps as f64
            );
        }
        None => {
            let _ = writeln!(s, "  C is not a multiple of G: several relaxation times");
        }
    }
    let law = &scn.law;
    for line in law.describe() {
        let _ = writeln!(s, "{line}");
    }
    let m = (-law.curvature_min()).max(0.0);
    if law.down_jumps().is_empty() {
        let _ = writeln!(
            s,
            "  H(j): constant m = max(0, -inf p') = {m} (relaxed monotonicity)"
        );
    }
    for (at, jump) in law.down_jumps() {
        warn(
            &mut s,
            format!(
                "H(j) fails: p jumps down by {} at s = {at}, so no finite m makes j relaxed monotone",
                -jump
            ),
        );
    }
    let _ = writeln!(
        s,
        "loads: f0 = ({}, {}), f2 = ({}, {}), f0_modulation = {}, history: {}",
        scn.f0[0], scn.f0[1], scn.f2[0], scn.f2[1], scn.f0_modulation, scn.history
    );
    let jumps_down = !law.down_jumps().is_empty();
    match Smallness::of(scn, n) {
        Ok(_) if jumps_down => {
            let _ = writeln!(
                s,
                "H(s): does not apply: H(j) fails (a downward jump), so no finite m exists for it"
            );
        }
        Ok(h) => {
            let holds = h.holds();
            let _ = writeln!(
                s,
                "H(s): beta_B = {:.6e} {} m ||iota_h||^2 = {m} * {:.6e} = {:.6e} (n = {}{}): {}",
                h.beta_b,
                if holds { ">" } else { "<=" },
                h.trace_sq,
                h.rhs(),
                h.n,
                if h.extrapolated {
                    ", the trace constant extrapolated upward from n = 128, 256, 512"
                } else {
                    ""
                },
                if holds { "holds" } else { "fails" }
            );
            if !holds {
                warn(
                    &mut s,
                    "H(s) fails: the paper's existence and error theory assume it".into(),
                );
            }
        }
        Err(e) => warn(
            &mut s,
            format!("the trace constant could not be computed: {e}"),
        ),
    }
    match crate::scheme::step_curvature(scn, n, steps) {
        Ok(c) => {
            let _ = writeln!(
                s,
                "step convexity (n = {n}, steps = {steps}): smallest step curvature {c:.6e}"
            );
            if c <= 0.0 {
                warn(
                    &mut s,
                    format!(
                        "a step can be nonconvex at n = {n}, steps = {steps}: a certified step is then \
                         a stationary point, not necessarily the minimiser"
                    ),
                );
            }
        }
        Err(e) => warn(
            &mut s,
            format!("the step curvature could not be computed: {e}"),
        ),
    }
    let h = scn.time_hypotheses();
    if scn.problem != crate::scenario::Problem::Viscoelastic {
        let _ = writeln!(
            s,
            "H(f), H(0) at t = 0: not asked (a {} problem has no evolution from u0 = 0)",
            scn.problem.name()
        );
        return (s, warnings);
    }
    if h.h_0() {
        let _ = writeln!(s, "H(f), H(0) at t = 0: hold (f(0) = {} (f0, f2))", h.phi0);
    }
    for why in h.failures() {
        warn(&mut s, format!("at t = 0: {why}"));
    }
    (s, warnings)
}
