//! The reduced time loop for proportional damping.
//!
//! When $\mathcal C = c\,\mathcal G$, so $A = cB$ and $K = A + kB = (c + k)B$, a step of
//! the scheme needs no sparse solve at all. With $a = c/(c+k)$,
//! $\beta_n = k\varphi(t_n)/(c+k)$ and $q = -E_C B^{-1} f$ (the load's contact
//! response, one solve), $K^{-1}A = a\,I$ gives
//! $$K^{-1} b_n = a\,u_{n-1} + \beta_n B^{-1} f, \qquad r_{0,n} = a\,r_{n-1} + \beta_n q,$$
//! so each step is only the condensed contact problem of [`crate::step`] with
//! $S_K = (c+k) S_B$, from $r_{0,n}$. The field is
//! $$u_n = B^{-1}\big(Y_n f + E_C^\top W_n\big), \qquad Y_n = a Y_{n-1} + \beta_n, \quad
//! W_n = a W_{n-1} + z_n/(c+k), \quad z_n = S_K(r_{0,n} - r_n),$$
//! formed with one solve only where it is wanted ([`Reduced::field`]). Its energy
//! norm $\|u_n\|_E^2 = \tfrac12 u_n^\top B u_n$ needs none: $B u_n = Y_n f + E_C^\top W_n$
//! and $E_C u_n = -r_n$ give
//! $$u_n^\top B u_n = Y_n^2\, f^\top B^{-1} f - Y_n\, W_n^\top q - W_n^\top r_n,$$
//! and the same for the difference of two runs on one mesh ([`Reduced::energy_diff`]).
//!
//! One factorisation of $B$ (and one condensation) serves every $k$: Table 1's
//! reference and its $k$ family share it. Every step is certified on its
//! condensed problem ([`crate::certificate::certify_condensed`]); every step whose
//! field is formed also on the full, uncondensed system with the assembled $A$ and
//! $B$ ([`crate::certificate::certify`]), which checks the reduction itself.
//! `tests/reduced.rs` compares the loop with [`crate::scheme`].

use crate::assembly::{abs_matvec_norm, matvec};
use crate::certificate::{Certificate, ContactState, certify, certify_condensed};
use crate::error::InputError;
use crate::linalg::Cholesky;
use crate::scenario::Scenario;
use crate::scheme::{
    Check, Discretisation, OrderingKind, Partial, Run, RunError, Settings, StepRecord, Timings,
};
use crate::step::{Status, StepProblem, StepSolver};
use crate::timing::timed;
use faer::Mat;
use std::time::Instant;

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

/// $B$ factorised with the contact dofs last and condensed onto them: the
/// operator of every reduced run on one mesh, whatever $k$.
pub struct Reduced<'d> {
    /// The mesh's discretisation: the assembled $A$ and $B$, dofs, contact dofs,
    /// weights and gaps.
    pub disc: &'d Discretisation,
    /// The relaxation time $c$ ($A = cB$).
    pub c: f64,
    /// The Cholesky factor of $B$, contact dofs last.
    pub chol: Cholesky,
    /// $S_B$, the Schur complement of $B$ on the contact normal dofs.
    pub s_b: Mat<f64>,
    /// The smallest eigenvalue of $S_B$.
    pub lambda_min: f64,
    /// The largest eigenvalue of $S_B$.
    pub lambda_max: f64,
}

/// A load on the mesh and what the loop needs of it.
pub struct Load {
    /// The load vector $f$ (at $\varphi = 1$).
    pub f: Vec<f64>,
    /// $B^{-1} f$.
    pub binv_f: Vec<f64>,
    /// $q = -E_C B^{-1} f$.
    pub q: Vec<f64>,
    /// $f^\top B^{-1} f$.
    pub ff: f64,
}

/// The state after a step in reduced coordinates: $u_n = B^{-1}(Y f + E_C^\top W)$
/// and $r = -E_C u_n$.
#[derive(Debug, Clone)]
pub struct State {
    /// $Y_n$, the load's coefficient.
    pub y: f64,
    /// $W_n$, the accumulated contact reactions, one per contact node.
    pub w: Vec<f64>,
    /// $r_n = -E_C u_n$, the normal displacement $u_\nu$ of each contact node.
    pub r: Vec<f64>,
}

/// What the observer of a reduced run sees after each step.
pub struct Stepped<'a> {
    /// The step's number $n$, from 1.
    pub step: usize,
    /// The time $t_n$ at the end of the step.
    pub t: f64,
    /// The state after the step.
    pub state: &'a State,
    /// The step's record: solver status, iterations, certificate, energy norm, time.
    pub record: &'a StepRecord,
    /// The contact nodes' states, from the full certificate where the step was
    /// certified on the full system, from the condensed one elsewhere (also where the
    /// field was formed but not certified on the full system, see
    /// [`crate::simulation::Observer::certifies_field`]; the two differ by rounding).
    pub contact: &'a [ContactState],
    /// $u_n$, at the steps whose field was asked for.
    pub field: Option<&'a [f64]>,
}

/// The operator of one step length $k$: $S_K = (c+k)S_B$, the weights and bounds.
struct AtK {
    k: f64,
    s: Mat<f64>,
    kw: Vec<f64>,
    lambda_max: f64,
    hessian_min: f64,
}

impl<'d> Reduced<'d> {
    /// Factorises and condenses $B$; a scenario whose damping is not proportional
    /// on `disc` is refused by name.
    pub fn new(
        scn: &Scenario,
        disc: &'d Discretisation,
        ordering: OrderingKind,
        parallel: bool,
        timings: &mut Timings,
    ) -> Result<Reduced<'d>, RunError> {
        // Without viscosity A = 0 = 0 (B + B_s): the loop takes the term in B.
        let springs = scn.supports_with_stiffness();
        if let Some((field, hold)) = springs.into_iter().find(|_| scn.problem.viscous()) {
            return Err(InputError::field(
                field,
                hold,
                "a support without a boundary stiffness for the reduced loop, which needs \
                 A = cB: this support adds its term to the elasticity B alone (it has no \
                 dashpot), so the general loop solves the scene",
            )
            .into());
        }
        let Some(c) = proportional(scn, disc) else {
            return Err(InputError::field(
                "material",
                format!("alpha = {}, beta = {}", scn.alpha, scn.beta),
                "proportional damping, C = c G (alpha/beta as the elastic a/b), for the reduced loop",
            )
            .into());
        };
        timings.factorisations += 1;
        let (chol, _) = timed(&mut timings.factorisation, || {
            crate::scheme::factorise(disc, &disc.b, ordering, parallel)
        })?;
        let cond = timed(&mut timings.condensation, || {
            crate::condense::condense(&chol).map_err(RunError::Condense)
        })?;
        Ok(Reduced {
            disc,
            c,
            chol,
            s_b: cond.s,
            lambda_min: cond.lambda_min,
            lambda_max: cond.lambda_max,
        })
    }

    /// The load response of `f` (one solve).
    pub fn load(&self, f: Vec<f64>) -> Load {
        let binv_f = self.chol.solve(&f);
        let q = self.disc.contact_dofs.iter().map(|&d| -binv_f[d]).collect();
        let ff = f.iter().zip(&binv_f).map(|(a, b)| a * b).sum();
        Load { f, binv_f, q, ff }
    }

    /// The load response of a scenario that shares the mesh (its own $f_0$, $f_2$).
    pub fn load_of(&self, scn: &Scenario) -> Load {
        let d = self.disc;
        self.load(scn.load_vector(&d.mesh, &d.dofs))
    }

    /// $u = B^{-1}(Y f + E_C^\top W)$: one solve ([`Reduced::fields`] of one state).
    pub fn field(&self, load: &Load, st: &State) -> Vec<f64> {
        self.fields(load, &[st]).pop().expect("one field")
    }

    /// The fields of several states under one load, their solves batched (one
    /// sweep over the factor serves them all; [`Reduced::field`] for one).
    pub fn fields(&self, load: &Load, states: &[&State]) -> Vec<Vec<f64>> {
        let rhs: Vec<Vec<f64>> = states.iter().map(|st| self.contact_rhs(st)).collect();
        let cols: Vec<&[f64]> = rhs.iter().map(Vec::as_slice).collect();
        let v = self
            .chol
            .backward_many(self.chol.forward_many_contact(&cols));
        (v.into_iter().zip(states))
            .map(|(v, st)| self.with_load(load, st, v))
            .collect()
    }

    /// $E_C^\top W$: the state's contact reactions as a right-hand side.
    fn contact_rhs(&self, st: &State) -> Vec<f64> {
        let mut rhs = vec![0.0; self.disc.dofs.count];
        for (&d, w) in self.disc.contact_dofs.iter().zip(&st.w) {
            rhs[d] = *w;
        }
        rhs
    }

    /// $Y B^{-1} f + v$, with $v = B^{-1} E_C^\top W$ solved.
    fn with_load(&self, load: &Load, st: &State, v: Vec<f64>) -> Vec<f64> {
        v.iter()
            .zip(&load.binv_f)
            .map(|(v, b)| st.y * b + v)
            .collect()
    }

    /// $u^\top B u$ of a state, without a solve.
    pub fn quad(&self, load: &Load, st: &State) -> f64 {
        let wq: f64 = st.w.iter().zip(&load.q).map(|(a, b)| a * b).sum();
        let wr: f64 = st.w.iter().zip(&st.r).map(|(a, b)| a * b).sum();
        st.y * st.y * load.ff - st.y * wq - wr
    }

    /// $\|u\|_E = \sqrt{u^\top B u / 2}$ of a state (the norm of [`crate::norms`]).
    pub fn energy(&self, load: &Load, st: &State) -> f64 {
        (0.5 * self.quad(load, st)).max(0.0).sqrt()
    }

    /// $\|u_a - u_b\|_E$ of two states on this mesh under one load, without a solve
    /// (the formula of [`Reduced::quad`] for the difference, which is formed first).
    pub fn energy_diff(&self, load: &Load, a: &State, b: &State) -> f64 {
        let d = State {
            y: a.y - b.y,
            w: a.w.iter().zip(&b.w).map(|(x, y)| x - y).collect(),
            r: a.r.iter().zip(&b.r).map(|(x, y)| x - y).collect(),
        };
        self.energy(load, &d)
    }

    /// $\|u_n - \hat u_n\|_E$ with the linear predictor $\hat u_n = u_{n-1} +
    /// r\,(u_{n-1} - u_{n-2})$ ([`crate::time_adapt`]), of the states $u_n$, $u_{n-1}$,
    /// $u_{n-2}$, without a solve.
    pub fn predictor_gap(&self, load: &Load, (u, u1, u2): (&State, &State, &State), r: f64) -> f64 {
        let c = |a: f64, b: f64, c: f64| a - (1.0 + r) * b + r * c;
        let d = State {
            y: c(u.y, u1.y, u2.y),
            w: (u.w.iter().zip(&u1.w).zip(&u2.w))
                .map(|((a, b), e)| c(*a, *b, *e))
                .collect(),
            r: (u.r.iter().zip(&u1.r).zip(&u2.r))
                .map(|((a, b), e)| c(*a, *b, *e))
                .collect(),
        };
        self.energy(load, &d)
    }

    fn at(&self, k: f64, cmin: f64) -> Result<AtK, RunError> {
        let ck = self.c + k;
        let s = Mat::from_fn(self.s_b.nrows(), self.s_b.ncols(), |i, j| {
            ck * self.s_b[(i, j)]
        });
        let kw: Vec<f64> = self.disc.weights.iter().map(|w| k * w).collect();
        let hessian_min =
            crate::scheme::step_hessian_min(s.as_ref(), &kw, cmin, ck * self.lambda_min)?;
        Ok(AtK {
            k,
            s,
            kw,
            lambda_max: ck * self.lambda_max,
            hessian_min,
        })
    }

    /// The full certificate of $u_n$ (formed) against $K u_n = A u_{n-1} + k\varphi(t_n) f$
    /// with the assembled $A$ and $B$.
    fn certify_full(
        &self,
        at: &AtK,
        scn: &Scenario,
        load: &Load,
        (u_prev, u, s): (&[f64], &[f64], &[f64]),
        t: f64,
    ) -> (Certificate, Vec<ContactState>) {
        let d = self.disc;
        let (au, bu) = (matvec(&d.a, u), matvec(&d.b, u));
        let ku: Vec<f64> = au.iter().zip(&bu).map(|(a, b)| a + at.k * b).collect();
        let kphi = at.k * scn.history.phi(t);
        let b: Vec<f64> = (matvec(&d.a, u_prev).iter().zip(&load.f))
            .map(|(a, f)| a + kphi * f)
            .collect();
        // |K| = (c + k)|B| on a proportional pattern.
        let ku_abs = (self.c + at.k) * abs_matvec_norm(&d.b, u);
        certify(
            &ku,
            ku_abs,
            &b,
            u,
            s,
            &d.contact_dofs,
            &d.gap,
            &at.kw,
            &scn.law,
            scn.g,
        )
    }

    /// [`Reduced::march`] with Newton's method at the certificate tolerance of every
    /// run, [`crate::scheme::CERTIFICATE_TOL`] (what the experiments use).
    pub fn march_newton(
        &self,
        scn: &Scenario,
        load: &Load,
        steps: usize,
        want_field: &dyn Fn(usize) -> bool,
        timings: &mut Timings,
        observe: &mut dyn FnMut(Stepped<'_>),
    ) -> Result<March, RunError> {
        self.march(
            scn,
            load,
            steps,
            &mut crate::step::newton::Newton::default(),
            crate::scheme::CERTIFICATE_TOL,
            want_field,
            timings,
            observe,
        )
    }

    /// Runs `steps` steps of length $T/\text{steps}$ for `scn` under `load`. The
    /// field is formed (one solve, and a full certificate) at the steps for which
    /// `want_field` is true; every step gets the condensed certificate and fails
    /// the run when it exceeds `tol`. `observe` sees every step.
    #[allow(clippy::too_many_arguments)]
    pub fn march(
        &self,
        scn: &Scenario,
        load: &Load,
        steps: usize,
        solver: &mut dyn StepSolver,
        tol: f64,
        want_field: &dyn Fn(usize) -> bool,
        timings: &mut Timings,
        observe: &mut dyn FnMut(Stepped<'_>),
    ) -> Result<March, RunError> {
        self.march_on(
            scn,
            load,
            &crate::time_grid::TimeGrid::uniform(scn.t_end, steps),
            solver,
            tol,
            want_field,
            timings,
            observe,
        )
    }

    /// [`Reduced::march`] on any time grid: each step's $a$, $\beta_n$ and $S_K$ are
    /// those of its own $k_n$ (the operator of a new $k$ is $S_B$ scaled, no solve).
    #[allow(clippy::too_many_arguments)]
    pub fn march_on(
        &self,
        scn: &Scenario,
        load: &Load,
        grid: &crate::time_grid::TimeGrid,
        solver: &mut dyn StepSolver,
        tol: f64,
        want_field: &dyn Fn(usize) -> bool,
        timings: &mut Timings,
        observe: &mut dyn FnMut(Stepped<'_>),
    ) -> Result<March, RunError> {
        let fields = FieldSteps {
            form: want_field,
            certify: want_field,
        };
        self.march_fields(scn, load, grid, solver, tol, &fields, timings, observe)
    }

    /// [`Reduced::march_on`] with the steps that form their field and those of them
    /// that certify it on the full system told apart (`fields`).
    #[allow(clippy::too_many_arguments)]
    fn march_fields(
        &self,
        scn: &Scenario,
        load: &Load,
        grid: &crate::time_grid::TimeGrid,
        solver: &mut dyn StepSolver,
        tol: f64,
        fields: &FieldSteps<'_>,
        timings: &mut Timings,
        observe: &mut dyn FnMut(Stepped<'_>),
    ) -> Result<March, RunError> {
        let want_field = fields.form;
        let steps = grid.len();
        let cmin = scn.law.curvature_min();
        let mut at = timed(&mut timings.condensation, || self.at(grid.k(1), cmin))?;
        let mut hessian_min = at.hessian_min;
        let m = load.q.len();
        let mut st = State {
            y: 0.0,
            w: vec![0.0; m],
            r: vec![0.0; m],
        };
        let mut records = Vec::with_capacity(steps);
        // The last field formed, kept while the next step may need it as u_{n-1}.
        let mut last: Option<(usize, Vec<f64>)> = None;
        // The contact states after the last completed step, for a failure's report.
        let mut last_contact = vec![];
        let clock = Instant::now();
        let mut rescale_s = 0.0;
        for step in 1..=steps {
            let (t, k) = (grid.t(step), grid.k(step));
            if k != at.k {
                let clock = Instant::now();
                at = timed(&mut timings.condensation, || self.at(k, cmin))?;
                hessian_min = hessian_min.min(at.hessian_min);
                rescale_s += clock.elapsed().as_secs_f64();
            }
            let (ck, a) = (self.c + k, self.c / (self.c + k));
            let t0 = Instant::now();
            // ANCHOR: reduced_step
            // r_0 = a r_{n-1} + beta_n q: no solve.
            let beta = k * scn.history.phi(t) / ck;
            let r0: Vec<f64> = (st.r.iter().zip(&load.q))
                .map(|(rp, qi)| a * rp + beta * qi)
                .collect();
            // The step problem is posed in the contact variables s = r - gap.
            let gap = &self.disc.gap;
            let shift = |v: &[f64]| -> Vec<f64> { v.iter().zip(gap).map(|(x, g)| x - g).collect() };
            let s0 = shift(&r0);
            let mut s = shift(&st.r);
            let prob = StepProblem {
                s: at.s.as_ref(),
                r0: &s0,
                kw: &at.kw,
                law: &scn.law,
                g: scn.g,
                lipschitz: at.lambda_max,
                curvature_min: at.hessian_min,
            };
            let prev = want_field(step).then(|| st.clone());
            let mut info = timed(&mut timings.step_solver, || solver.solve(&prob, &mut s));
            for ((r, si), g) in st.r.iter_mut().zip(&s).zip(gap) {
                *r = si + g;
            }
            info.time_s = t0.elapsed().as_secs_f64();
            // The contact reactions z = S_K (r_0 - r) enter W; Y follows the load.
            let diff: Vec<f64> = r0.iter().zip(&st.r).map(|(x, y)| x - y).collect();
            let z = crate::dense::sym_matvec(at.s.as_ref(), &diff);
            for (w, zi) in st.w.iter_mut().zip(&z) {
                *w = a * *w + zi / ck;
            }
            st.y = a * st.y + beta;
            // ANCHOR_END: reduced_step
            let ((mut certificate, mut contact), field) = timed(&mut timings.certificates, || {
                let cond = certify_condensed(at.s.as_ref(), &s0, &s, &at.kw, &scn.law, scn.g);
                let field = prev.map(|p| match last.take() {
                    // u_{n-1} was formed at the step before: one solve.
                    Some((n, u_prev)) if n + 1 == step => (u_prev, self.field(load, &st)),
                    _ => {
                        let mut pair = self.fields(load, &[&p, &st]).into_iter();
                        (pair.next().expect("two"), pair.next().expect("two"))
                    }
                });
                (cond, field)
            });
            let mut check = Check::Condensed;
            if let Some((u_prev, u)) = field.as_ref().filter(|_| (fields.certify)(step)) {
                let full = timed(&mut timings.certificates, || {
                    self.certify_full(&at, scn, load, (u_prev, u, &s), t)
                });
                // The full certificate checks every equation, the contact conditions
                // among them, on the assembled system: it replaces the condensed one.
                (certificate, contact) = full;
                check = Check::Full;
            }
            let rec = StepRecord {
                step,
                t,
                status: info.status.clone(),
                iterations: info.iterations,
                inner_iterations: info.inner_iterations,
                solver_residual: info.residual,
                certificate,
                energy_norm: self.energy(load, &st),
                time_s: info.time_s,
                check,
            };
            // A failure keeps the steps done: records, the last field formed (u_{n-1}
            // where this step formed it beside its own) and the contact states.
            let done = |e: RunError| {
                let formed = match &field {
                    Some((u_prev, _)) if step > 1 => Some((step - 1, u_prev.clone())),
                    Some(_) => None,
                    None => last.clone(),
                };
                e.with_partial(Partial {
                    records: records.clone(),
                    field: formed,
                    contact: last_contact.clone(),
                })
            };
            crate::scheme::check_resolution(&certificate, scn, step).map_err(done)?;
            let failed = info.status != Status::Converged
                || certificate.max().is_nan()
                || certificate.max() > tol;
            // A converged condensed step whose full certificate fails, on a load whose
            // free response dwarfs g: the recovery's cancellation, said as such.
            if failed && info.status == Status::Converged {
                let free =
                    || crate::dense::inf_norm(&load.q) * st.y.abs().max(scn.history.phi(t).abs());
                let failure = (step, t, solver.name(), info.residual);
                if let Some(e) =
                    crate::scheme::cancellation(scn, failure, certificate.max(), tol, free)
                {
                    return Err(done(e));
                }
            }
            if failed {
                return Err(done(RunError::Step {
                    scenario: scn.name.as_str().into(),
                    step,
                    t,
                    solver: solver.name().into(),
                    status: info.status,
                    iterations: info.iterations,
                    residual: info.residual,
                    certificate: certificate.max(),
                    tol,
                    partial: Box::default(),
                }));
            }
            observe(Stepped {
                step,
                t,
                state: &st,
                record: &rec,
                contact: &contact,
                field: field.as_ref().map(|(_, u)| u.as_slice()),
            });
            records.push(rec);
            last = field.map(|(_, u)| (step, u));
            last_contact = contact;
        }
        timings.steps += clock.elapsed().as_secs_f64() - rescale_s;
        let k_min = grid.k_min();
        let k_top = (1..=steps).map(|s| grid.k(s)).fold(k_min, f64::max);
        Ok(March {
            records,
            hessian_min,
            s_eigen: (
                (self.c + k_min) * self.lambda_min,
                (self.c + k_top) * self.lambda_max,
            ),
        })
    }
}

/// `observe(n, t_n, u_n, contact_n)` of a reduced run: `u_n` where it was formed.
pub type FieldObserver<'a> = dyn FnMut(usize, f64, Option<&[f64]>, &[ContactState]) + 'a;

/// What [`Reduced::march`] returns besides what it showed the observer.
pub struct March {
    /// The record of every step, in order.
    pub records: Vec<StepRecord>,
    /// The step operator's curvature bound (see [`Run::hessian_min`]).
    pub hessian_min: f64,
    /// The extreme eigenvalues of $S_K$.
    pub s_eigen: (f64, f64),
}

/// Which steps of a march form their field $u_n$ (one solve), and which of those
/// also certify it on the full system (a product with $A$ and $B$ each); every step
/// gets the condensed certificate.
struct FieldSteps<'a> {
    form: &'a dyn Fn(usize) -> bool,
    certify: &'a dyn Fn(usize) -> bool,
}

/// Runs one scenario by the reduced loop, with the result the general loop gives
/// (the time loop of [`crate::scheme`]): the field is formed, and the step
/// certified on the full system, at the last step and at a sample of three more (a
/// quarter, half and three quarters of the way); elsewhere the field is formed where
/// `want_field` asks, and certified on the full system where `certify_field` asks as
/// well; `observe(n, t_n, u_n, contact_n)` gets the field where it was formed.
pub(crate) fn run(
    scn: &Scenario,
    opt: &Settings,
    solver: &mut dyn StepSolver,
    (want_field, certify_field): (&dyn Fn(usize) -> bool, &dyn Fn(usize) -> bool),
    observe: &mut FieldObserver<'_>,
) -> Result<Run, RunError> {
    crate::scheme::check_steps(Some(scn), opt)?;
    crate::scheme::check_memory(opt.n, crate::mesh::rows(opt.n, &scn.geometry))?;
    solver.validate()?;
    crate::step::check_takes(solver, scn)?;
    let mut timings = Timings::default();
    let (disc, _) = timed(&mut timings.assembly, || {
        crate::scheme::discretise(std::slice::from_ref(scn), opt)
    })?;
    let op = Reduced::new(scn, &disc, opt.ordering, opt.parallel, &mut timings)?;
    // The load's solve is the one solve of the run before the steps: its time is
    // the floor's unit (`one_solve_s`).
    let load = crate::timing::timed(&mut timings.one_solve, || op.load(disc.f.clone()));
    let grid = opt.time_grid(scn)?;
    let last = grid.len();
    let quarter = (last / 4).max(1);
    let sample = |n: usize| n.is_multiple_of(quarter) || n == last;
    let fields = FieldSteps {
        form: &|n| sample(n) || want_field(n),
        certify: &|n| sample(n) || (want_field(n) && certify_field(n)),
    };
    let (mut u, mut contact) = (vec![], vec![]);
    let march = op.march_fields(
        scn,
        &load,
        &grid,
        solver,
        opt.certificate_tol,
        &fields,
        &mut timings,
        &mut |s| {
            observe(s.step, s.t, s.field, s.contact);
            if s.step == last {
                u = s.field.expect("the last field is formed").to_vec();
                contact = s.contact.to_vec();
            }
        },
    )?;
    Ok(Run::finished(
        opt,
        &disc,
        scn.t_end,
        (op.chol.nnz_l(), if op.chol.is_parallel() { 2 } else { 1 }),
        u,
        march.records,
        contact,
        timings,
        (march.s_eigen, march.hessian_min),
    ))
}
