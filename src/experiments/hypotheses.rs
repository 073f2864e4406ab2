//! A numerical check of the hypotheses of §2 for the paper's data (§4–5):
//! H(A), H(B) with the constants of the tensors $\mathcal C$, $\mathcal G$ in the
//! norm $\|v\|_V^2 = (\varepsilon(v), \varepsilon(v))$; H(J)(iii) with $m$ the largest
//! negative slope of $p$; and the smallness condition H(s), $\beta > m\|\iota\|^2$.
//!
//! The trace constant $\|\iota\| = \sup_v \|v_\nu\|_{L^2(\Gamma_3)} / \|v\|_V$ is computed on
//! each mesh as a generalised eigenvalue: with $V$ the matrix of $(\varepsilon, \varepsilon)$,
//! $\|\iota_h\|^2 = \lambda_{\max}(W^{1/2} F_V W^{1/2})$, where $F_V = P V^{-1} P^\top$ is the
//! flexibility of $V$ on the contact normal dofs ($= (L_{CC}L_{CC}^\top)^{-1}$ of its
//! factor) and $W$ the trapezoidal weights. Trapezoidal quadrature of
//! $\int_{\Gamma_3} v_\nu^2$ is exact up to $O(h^2)$ for P1. The values grow with $n$ in
//! `data/hypotheses.csv`; with quadrature weights nothing guarantees that they bound
//! $\|\iota\|$ from below.

use super::{Ctx, ExpError};
use evhi::output::csv::Table;
use evhi::scenario::Scenario;

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let scn = Scenario::load("figure")?;
    let levels: Vec<usize> = if ctx.quick {
        vec![4, 8, 16]
    } else {
        vec![4, 8, 16, 32, 64, 128, 256]
    };
    let visc = scn.viscosity();
    let elas = scn.elasticity();
    let m = -scn.law().curvature_min();
    let mut rows = vec![];
    for &n in &levels {
        let trace_sq = evhi::norms::trace_norm_sq(&scn, n).map_err(|message| {
            ExpError::File(evhi::output::FileError::Table {
                path: format!("{} (trace constant at n = {n})", ctx.experiment),
                message,
            })
        })?;
        rows.push((n, trace_sq.sqrt(), m * trace_sq));
    }
    let beta = elas.coercivity();
    let t = Table::new()
        .u64("n", rows.iter().map(|r| r.0 as u64).collect())
        .f64("trace_norm", rows.iter().map(|r| r.1).collect())
        .f64("m_trace_norm_sq", rows.iter().map(|r| r.2).collect())
        .f64("alpha_A", vec![visc.coercivity(); rows.len()])
        .f64("beta_B", vec![beta; rows.len()])
        .f64("m", vec![m; rows.len()])
        .str(
            "smallness_holds",
            rows.iter().map(|r| (beta > r.2).to_string()).collect(),
        );
    ctx.write(
        "hypotheses.csv",
        &t,
        "material and law of the paper (E = 1000, kappa = 0.4, alpha = 100, beta = 50, c2 = -100); ||v||_V^2 = (eps(v), eps(v)); alpha_A, beta_B: coercivity of C and G; m = max(0, -min slope of p); paper's supports",
    )?;
    compatibility(ctx)
}

// ANCHOR: compat
/// H(f) and H(0) at $t = 0$ for every built-in scenario under the load histories of the
/// time study ([`super::time::histories`]).
pub fn compatibility(ctx: &Ctx) -> Result<(), ExpError> {
    let mut rows = vec![];
    for (name, _) in evhi::scenario::BUILTIN {
        for (label, h) in super::time::histories() {
            let scn = Scenario::load(name)?.with_history(h)?;
            rows.push((
                name,
                label,
                scn.history().to_string(),
                scn.time_hypotheses(),
            ));
        }
    }
    let t = Table::new()
        .str("scenario", rows.iter().map(|r| r.0.to_string()).collect())
        .str("history", rows.iter().map(|r| r.1.to_string()).collect())
        .str("phi", rows.iter().map(|r| r.2.clone()).collect())
        .f64("phi0", rows.iter().map(|r| r.3.phi0).collect())
        .str(
            "f2_0_zero",
            rows.iter().map(|r| r.3.f2_zero.to_string()).collect(),
        )
        .str(
            "f0_0_in_V",
            rows.iter().map(|r| r.3.f0_in_v.to_string()).collect(),
        )
        .str(
            "zero_in_clarke_j_0",
            rows.iter()
                .map(|r| r.3.zero_in_clarke.to_string())
                .collect(),
        )
        .str("H_f", rows.iter().map(|r| r.3.h_f().to_string()).collect())
        .str("H_0", rows.iter().map(|r| r.3.h_0().to_string()).collect());
    ctx.write(
        "hypotheses_compat.csv",
        &t,
        "H(f) at t = 0: f2(0) = 0 and f0(0) in V (f0(0) vanishes on every prescribed displacement component); \
         H(0) at u0 = 0: additionally 0 in the Clarke subdifferential of j at 0; f(t) = phi(t) (f0, f2)",
    )?;
    Ok(())
}
// ANCHOR_END: compat
