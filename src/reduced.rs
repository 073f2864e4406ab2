//! The reduced time loop for proportional damping (issue "Speed"; first part).
//!
//! When $\mathcal C = c\,\mathcal G$, so $A = cB$ and $K = A + kB = (c + k)B$, one step
//! of the scheme needs no sparse solve at all. With $a = c/(c+k)$,
//! $\beta_n = k\varphi(t_n)/(c+k)$ and $q = -E_C B^{-1} f$ (the load's contact response,
//! one solve), $K^{-1}A = a\,I$ gives
//! $$K^{-1} b_n = a\,u_{n-1} + \beta_n B^{-1} f, \qquad r_{0,n} = a\,r_{n-1} + \beta_n q,$$
//! so each step is only the condensed contact problem of [`crate::step`], from
//! $r_{0,n}$, and the field is a sum
//! $$u_n = Y_n\,B^{-1} f + K^{-1}E_C^\top Z_n, \qquad Y_n = a Y_{n-1} + \beta_n, \quad
//! Z_n = a Z_{n-1} + z_n, \quad z_n = S(r_{0,n} - r_n),$$
//! formed with one solve only where it is wanted. This module runs that loop for
//! one scenario and gives the contact unknowns at every step and the field at the
//! steps asked for; `tests/reduced.rs` checks it against [`crate::scheme`] to
//! $10^{-12}$. It is not yet wired into the experiments or `solve` (see the book's
//! speed section for what is left).

use crate::error::InputError;
use crate::scenario::Scenario;
use crate::scheme::{Discretisation, Options, RunError, StepOperator, Timings};
use crate::step::{Status, StepProblem, StepSolver};

/// The result of a reduced run.
pub struct ReducedRun {
    /// $r_n$ (contact normal displacements $u_\nu$) at every step $n = 1 \dots N$.
    pub r: Vec<Vec<f64>>,
    /// $(n, u_n)$ at the steps asked for.
    pub fields: Vec<(usize, Vec<f64>)>,
    pub timings: Timings,
}

/// Whether the scenario's damping is proportional on the assembled matrices:
/// its relaxation time $c$ when $\max|A - cB| \le 10^{-12} \max|A|$.
pub fn proportional(scn: &Scenario, disc: &Discretisation) -> Option<f64> {
    let c = scn.relaxation_time()?;
    let (a, b) = (disc.a.val(), disc.b.val());
    if a.len() != b.len() || disc.a.col_ptr() != disc.b.col_ptr() {
        return None;
    }
    let scale = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let gap = a
        .iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - c * y).abs()));
    (gap <= 1e-12 * scale).then_some(c)
}

/// Runs the scheme by the reduced loop; `outputs` are the steps whose full field is
/// formed. A scenario without proportional damping is refused by name.
pub fn run_reduced(
    scn: &Scenario,
    opt: &Options,
    solver: &mut dyn StepSolver,
    outputs: &[usize],
) -> Result<ReducedRun, RunError> {
    crate::scheme::check_steps(opt)?;
    crate::scheme::check_memory(opt.n)?;
    let mut timings = Timings::default();
    let (disc, _) = crate::timing::timed(&mut timings.assembly, || {
        crate::scheme::discretise(std::slice::from_ref(scn), opt)
    })?;
    let Some(c) = proportional(scn, &disc) else {
        return Err(InputError::field(
            "material",
            format!("alpha = {}, beta = {}", scn.alpha, scn.beta),
            "proportional damping, C = c G (alpha/beta as the elastic a/b), for the reduced loop",
        )
        .into());
    };
    let k = scn.t_end / opt.steps as f64;
    let op = StepOperator::new(
        &disc,
        k,
        opt.ordering,
        opt.parallel,
        scn.law.min_slope(),
        &mut timings,
    )?;
    let (a, ck) = (c / (c + k), c + k);
    // B^{-1} f = (c + k) K^{-1} f, and q = -E_C B^{-1} f.
    let binv_f: Vec<f64> = op.chol.solve(&disc.f).iter().map(|x| ck * x).collect();
    let q: Vec<f64> = disc.contact_dofs.iter().map(|&d| -binv_f[d]).collect();
    let m = q.len();
    let (mut r, mut zsum, mut y) = (vec![0.0; m], vec![0.0; m], 0.0);
    let mut out = ReducedRun {
        r: Vec::with_capacity(opt.steps),
        fields: vec![],
        timings: Timings::default(),
    };
    let clock = std::time::Instant::now();
    for step in 1..=opt.steps {
        let t = step as f64 * k;
        let beta = k * scn.history.phi(t) / ck;
        let r0: Vec<f64> = r
            .iter()
            .zip(&q)
            .map(|(rp, qi)| a * rp + beta * qi)
            .collect();
        let prob = StepProblem {
            s: op.s.as_ref(),
            r0: &r0,
            kw: &op.kw,
            law: &scn.law,
            g: scn.g,
            lipschitz: op.lambda_max,
            curvature_min: op.hessian_min,
        };
        let info = crate::timing::timed(&mut timings.step_solver, || solver.solve(&prob, &mut r));
        if info.status != Status::Converged {
            return Err(RunError::Step {
                scenario: scn.name.clone(),
                step,
                t,
                solver: solver.name().to_string(),
                status: info.status,
                iterations: info.iterations,
                residual: info.residual,
                certificate: f64::NAN,
                tol: opt.certificate_tol,
            });
        }
        let diff: Vec<f64> = r0.iter().zip(&r).map(|(x, y)| x - y).collect();
        let z = crate::dense::sym_matvec(op.s.as_ref(), &diff);
        for (zs, zi) in zsum.iter_mut().zip(&z) {
            *zs = a * *zs + zi;
        }
        y = a * y + beta;
        out.r.push(r.clone());
        if outputs.contains(&step) {
            let mut rhs = vec![0.0; disc.dofs.count];
            for (&d, zs) in disc.contact_dofs.iter().zip(&zsum) {
                rhs[d] = *zs;
            }
            let w = op.chol.solve(&rhs);
            let u: Vec<f64> = w.iter().zip(&binv_f).map(|(w, g)| y * g + w).collect();
            out.fields.push((step, u));
        }
    }
    timings.steps = clock.elapsed().as_secs_f64();
    out.timings = timings;
    Ok(out)
}
