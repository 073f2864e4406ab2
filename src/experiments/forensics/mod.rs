//! Table 1 forensics: which reading of the paper, if any, gives its six errors
//! (24.099 % at $h = k = 1/4$ down to 0.741 % at $1/128$, order about 1)?
//!
//! A *candidate* fixes every choice the paper leaves open or might have made
//! differently from us, and yields a six-level error sequence; its distance to the
//! paper is $\max_\text{levels} |\ln(\text{ours}/\text{paper})|$. The choices:
//! - the load: `literal` (as printed), `literal_vertical` (the top traction turned
//!   vertical, $f_2 = (0, -1.5\cdot10^{-3})$), `figure` (the loads of Figs. 3–4);
//! - the material: `plane_strain` (ours, the printed $\lambda$) or `plane_stress`;
//! - the mesh: `diagonal` (ours, cells of side $2h$), `cells_h` (cells of side $h$:
//!   the mesh with $2n$ segments and $k = 1/n$), `antidiagonal`, `crisscross`;
//! - the norm: `energy` ($\|v\|_E$), `energy_squared` (its square, in percent),
//!   `l2` ($L^2(\Omega)$), `h1_seminorm`, `max` (largest nodal $|v|$),
//!   `gamma3_u_nu` ($L^2(\Gamma_3)$ of $v_\nu$), `gamma3_sigma_nu` ($L^2(\Gamma_3)$ of the
//!   contact stress $\sigma_\nu$, the nodal values interpolated linearly);
//! - the time: `T`, `max_t` ($\max_n \|e_n\| / \max_n \|u_n\|$ over the level's own time
//!   steps) or `l2_t` ($(\sum_n \|e_n\|^2 / \sum_n \|u_n\|^2)^{1/2}$ over them);
//! - what the error is measured against: `reference` (the $h = k = 1/512$ solution,
//!   the coarse field embedded exactly), `next_finer` ($\|u_h - u_{h/2}\| / \|u_{h/2}\|$),
//!   `injected` ($\|u_h - I_h u_{ref}\| / \|I_h u_{ref}\|$ on the coarse mesh, with
//!   $I_h$ the nodal interpolant; measuring against the interpolant on the fine
//!   mesh gives the same numbers, since the embedding is exact), or
//!   `interpolation` ($\|u_{ref} - I_h u_{ref}\| / \|u_{ref}\|$: the interpolation
//!   error of the reference itself, no $u_h$).
//!
//! Every candidate that varies the norm, the time and the comparison is computed
//! for the paper's reading of the rest; the loads, material and meshes are varied
//! with the reference comparison and every norm and time. Each variant of the
//! operator has its own reference on its own mesh pattern, except `cells_h` (cells of
//! side $h$), which is measured against the common $1/512$ diagonal reference: its
//! cells have side $1/256$ there, one halving finer than its finest level.
//!
//! The fields of the reduced runs are formed at the kept steps only (every fourth
//! reference step), a batch of four columns per sweep over the factor; their contact
//! stresses are those of each step's condensed certificate, and the last step is also
//! certified on the full system. (Until the session that batched them, each kept
//! step was certified on the full system too, with $u_{n-1}$ formed for it, and took
//! its $\sigma_\nu$ from that certificate: the `gamma3_sigma_nu` readings over time
//! moved by at most $4\cdot10^{-11}$ relative, every other value not at all.)
//!
//! The same runs give the reference-free estimates of the uniform family: the
//! increments $d_n = \|u_n - u_{2n}\|_E / \|u_{2n}\|_E$ at $t = T$ up to $n = 256$,
//! their fitted exponent, and from it an estimate of the reference's own error.

use super::{Ctx, ExpError};
use evhi::certificate::ContactState;
use evhi::mesh::{Interpolation, Mesh, Pattern};
use evhi::norms::{FieldNorms, NormGeometry, gamma_l2_sq};
use evhi::output::csv::Table;
use evhi::scenario::Scenario;
use std::collections::BTreeMap;

mod table;
use table::{write_candidates, write_reference_free};

/// The paper's Table 1, percent, by $n$ ($h = k = 1/n$).
use super::convergence::PAPER;

/// The raw measures of one comparison: squared norms (and the max norm) of the
/// error and of the field compared with, in the order of [`RAW`].
type Raw = [f64; 6];

/// The measures of a field: energy², L²², H¹², max, ‖v_ν‖²_Γ3, ‖σ_ν‖²_Γ3.
const RAW: [&str; 6] = [
    "energy",
    "l2",
    "h1_seminorm",
    "max",
    "gamma3_u_nu",
    "gamma3_sigma_nu",
];

fn raw(n: FieldNorms, sigma_sq: f64) -> Raw {
    [n.energy_sq, n.l2_sq, n.h1_sq, n.max, n.gamma_sq, sigma_sq]
}

/// A field at one time: nodal displacement and the contact stress at each contact node.
#[derive(Clone)]
struct Field {
    u: Vec<[f64; 2]>,
    sigma: Vec<f64>,
}

/// The running measures of one comparison over time.
#[derive(Default, Clone)]
struct Acc {
    at_t: Option<(Raw, Raw)>,
    max_e: Raw,
    max_u: Raw,
    sum_e: Raw,
    sum_u: Raw,
}

impl Acc {
    fn add(&mut self, e: Raw, u: Raw, last: bool) {
        for q in 0..RAW.len() {
            // The max norm is not squared: its "sum" is of squares all the same.
            let (es, us) = if q == 3 {
                (e[q] * e[q], u[q] * u[q])
            } else {
                (e[q], u[q])
            };
            self.max_e[q] = self.max_e[q].max(es);
            self.max_u[q] = self.max_u[q].max(us);
            self.sum_e[q] += es;
            self.sum_u[q] += us;
        }
        if last {
            self.at_t = Some((e, u));
        }
    }

    /// The relative error for measure `q` and time reading `time` (0: T, 1: max, 2: L²).
    fn relative(&self, q: usize, time: usize) -> f64 {
        let sq = |e: f64, u: f64| (e / u).sqrt();
        match time {
            0 => match self.at_t {
                Some((e, u)) if q == 3 => e[q] / u[q],
                Some((e, u)) => sq(e[q], u[q]),
                None => f64::NAN,
            },
            1 => sq(self.max_e[q], self.max_u[q]),
            _ => sq(self.sum_e[q], self.sum_u[q]),
        }
    }
}

/// Measures fields on the study's meshes with the elasticity tensor `g`. Each
/// mesh's triangle geometry is built on first use and kept for the group's
/// thousands of evaluations; meshes are told apart by (n, pattern, triangle
/// count), which within one study identifies them.
struct Meter {
    g: evhi::material::Isotropic,
    geometry: std::cell::RefCell<Vec<(MeshKey, std::rc::Rc<NormGeometry>)>>,
}

/// (n, pattern, triangle count) of a mesh of the study.
type MeshKey = (usize, Pattern, usize);

impl Meter {
    fn new(g: evhi::material::Isotropic) -> Meter {
        Meter {
            g,
            geometry: Default::default(),
        }
    }

    /// The measures of `v` (with contact stress `s`) on `mesh`.
    fn measures(&self, mesh: &Mesh, v: &[[f64; 2]], s: &[f64]) -> Raw {
        let id = (mesh.n, mesh.pattern, mesh.triangles.len());
        let found = self
            .geometry
            .borrow()
            .iter()
            .find(|(k, _)| *k == id)
            .map(|(_, g)| g.clone());
        let geo = found.unwrap_or_else(|| {
            let geo = std::rc::Rc::new(NormGeometry::new(mesh));
            self.geometry.borrow_mut().push((id, geo.clone()));
            geo
        });
        raw(geo.norms(mesh, &self.g, v), gamma_l2_sq(mesh, s))
    }

    /// The measures of the difference `a - b` on `mesh`.
    fn diff(&self, mesh: &Mesh, a: &Field, b_u: &[[f64; 2]], b_s: &[f64]) -> Raw {
        let du: Vec<[f64; 2]> =
            a.u.iter()
                .zip(b_u)
                .map(|(x, y)| [x[0] - y[0], x[1] - y[1]])
                .collect();
        let ds: Vec<f64> = a.sigma.iter().zip(b_s).map(|(x, y)| x - y).collect();
        self.measures(mesh, &du, &ds)
    }
}

/// Interpolates a contact vector of `coarse` to the contact nodes of `fine`.
fn contact_interp(coarse: &Mesh, fine: &Mesh, interp: &Interpolation, s: &[f64]) -> Vec<f64> {
    let mut nodal = vec![[0.0; 2]; coarse.nodes.len()];
    for (&c, &v) in coarse.contact.iter().zip(s) {
        nodal[c][0] = v;
    }
    fine.contact
        .iter()
        .map(|&c| {
            interp.weights[c]
                .iter()
                .map(|&(node, w)| w * nodal[node][0])
                .sum()
        })
        .collect()
}

/// One level run: its mesh and its fields by reference step $j$ ($t = j/n_{ref}$).
struct LevelRun {
    mesh: Mesh,
    fields: BTreeMap<usize, Field>,
}

/// A group of scenarios that share the step matrix: one batched run per level.
struct Group {
    material: &'static str,
    mesh: &'static str,
    /// (load label, scenario).
    loads: Vec<(&'static str, Scenario)>,
}

/// Runs the group's scenarios at $(n, N)$ and keeps every step whose time is on
/// the grid of stride `stride` reference steps. Proportional damping goes by the
/// reduced loop (one factorisation of $B$; a field formed, and certified on the
/// full system, only at the kept steps); other damping (plane stress keeps the
/// plane-strain viscosity) by the general loop, the group in one batch.
fn run_level(
    group: &Group,
    n: usize,
    steps: usize,
    n_ref: usize,
    stride: usize,
    mut keep: impl FnMut(usize, usize, Field),
) -> Result<Mesh, ExpError> {
    let scns: Vec<Scenario> = group.loads.iter().map(|(_, s)| s.clone()).collect();
    let sim = crate::experiments::runs::simulation(&scns[0], n, steps)?;
    let disc = sim.discretisation();
    let dofs = &disc.dofs;
    let per = n_ref / steps;
    let kept = |step: usize| (step * per).is_multiple_of(stride);
    let field = |u: &[f64], states: &[ContactState]| Field {
        u: dofs.expand(u),
        sigma: evhi::estimator::contact_stress(states),
    };
    if evhi::reduced::proportional(&scns[0], &disc).is_some() {
        let mut timings = evhi::scheme::Timings::default();
        let op = sim.reduced_operator(&disc, &mut timings)?;
        for (i, scn) in scns.iter().enumerate() {
            let load = op.load_of(scn);
            // The kept steps' states, their fields formed a batch at a time (one
            // sweep over the factor serves MAX_BATCH columns, each column's
            // arithmetic as alone), in step order. Every step is certified on its
            // condensed problem, whose contact states give sigma; the last step also
            // on the full system (the march's own field).
            let mut batch: Vec<(usize, evhi::reduced::State, Vec<f64>)> = vec![];
            let flush = |batch: &mut Vec<(usize, evhi::reduced::State, Vec<f64>)>,
                         keep: &mut dyn FnMut(usize, usize, Field)| {
                let states: Vec<&evhi::reduced::State> = batch.iter().map(|b| &b.1).collect();
                let fields = op.fields(&load, &states);
                for ((step, _, sigma), u) in batch.drain(..).zip(fields) {
                    keep(
                        i,
                        step * per,
                        Field {
                            u: dofs.expand(&u),
                            sigma,
                        },
                    );
                }
            };
            op.march_newton(
                scn,
                &load,
                steps,
                &|step| step == steps,
                &mut timings,
                &mut |s| {
                    if !kept(s.step) {
                        return;
                    }
                    match s.field {
                        Some(u) => {
                            flush(&mut batch, &mut keep);
                            keep(i, s.step * per, field(u, s.contact));
                        }
                        None => {
                            let sigma = s.contact.iter().map(|c| c.sigma_nu1 + c.sigma_nu2);
                            batch.push((s.step, s.state.clone(), sigma.collect()));
                            if batch.len() == evhi::linalg::MAX_BATCH {
                                flush(&mut batch, &mut keep);
                            }
                        }
                    }
                },
            )?;
            flush(&mut batch, &mut keep);
        }
    } else {
        super::run_newton_batch_states(
            &scns,
            n,
            steps,
            &mut |i, step, _, u, states: &[ContactState]| {
                if kept(step) {
                    keep(i, step * per, field(u, states));
                }
            },
        )?;
    }
    Ok((*disc.mesh).clone())
}

/// The levels and reference of the study: Table 1's.
pub use super::convergence::{Plan, plan};

/// One candidate's sequence over the levels.
struct Row {
    load: &'static str,
    material: &'static str,
    mesh: &'static str,
    norm: String,
    time: &'static str,
    against: &'static str,
    values: Vec<f64>,
}

const TIMES: [&str; 3] = ["T", "max_t", "l2_t"];

/// Rows for every norm and time from the accumulators of one (load, material,
/// mesh, comparison), one per level.
fn rows_of(
    load: &'static str,
    material: &'static str,
    mesh: &'static str,
    against: &'static str,
    accs: &[Acc],
) -> Vec<Row> {
    let mut out = vec![];
    for (q, name) in RAW.iter().enumerate() {
        for (t, time) in TIMES.iter().enumerate() {
            let values: Vec<f64> = accs.iter().map(|a| 100.0 * a.relative(q, t)).collect();
            if q == 0 {
                out.push(Row {
                    load,
                    material,
                    mesh,
                    norm: "energy_squared".into(),
                    time,
                    against,
                    values: values.iter().map(|v| v * v / 100.0).collect(),
                });
            }
            out.push(Row {
                load,
                material,
                mesh,
                norm: name.to_string(),
                time,
                against,
                values,
            });
        }
    }
    out
}

/// What the study computes for one group.
struct GroupResult {
    rows: Vec<Row>,
    /// Per load: the increments $d_n$ (energy, $t = T$, percent) by $n$.
    increments: Vec<(&'static str, Vec<(usize, f64)>)>,
}

/// Runs one group: its levels (and, for the paper's group, the extra families),
/// then its reference, comparing on the fly.
fn study_group(group: &Group, plan: &Plan, main: bool, ctx: &Ctx) -> Result<GroupResult, ExpError> {
    let levels = &plan.levels;
    let top = *levels.last().expect("levels");
    let n_ref = plan.n_ref;
    // Stored times: the grid of the finest level ($t = j/top$).
    let stride = n_ref / top;
    let meter = Meter::new(group.loads[0].1.elasticity());
    let nl = group.loads.len();
    // Runs by (load, kind, n): kind 0 = h = k, 1 = cells of side h.
    let mut runs: BTreeMap<(usize, usize, usize), LevelRun> = BTreeMap::new();
    let mut level_ns: Vec<usize> = levels.clone();
    if main && 2 * top < n_ref {
        level_ns.push(2 * top);
    }
    for &n in &level_ns {
        let clock = std::time::Instant::now();
        let mut fields: Vec<BTreeMap<usize, Field>> = vec![BTreeMap::new(); nl];
        let mesh = run_level(group, n, n, n_ref, stride, |i, j, f| {
            fields[i].insert(j, f);
        })?;
        for (i, f) in fields.into_iter().enumerate() {
            runs.insert(
                (i, 0, n),
                LevelRun {
                    mesh: mesh.clone(),
                    fields: f,
                },
            );
        }
        ctx.log(&format!(
            "forensics {} {}: h = k = 1/{n} ({:.1} s)",
            group.material,
            group.mesh,
            clock.elapsed().as_secs_f64()
        ));
    }
    if main {
        // Cells of side h: the mesh with 2n segments, k = 1/n; the paper's load only.
        let lit = Group {
            material: group.material,
            mesh: "cells_h",
            loads: vec![group.loads[0].clone()],
        };
        for &n in levels {
            let clock = std::time::Instant::now();
            let mut fields = BTreeMap::new();
            let mesh = run_level(&lit, 2 * n, n, n_ref, stride, |_, j, f| {
                fields.insert(j, f);
            })?;
            runs.insert((0, 1, n), LevelRun { mesh, fields });
            ctx.log(&format!(
                "forensics cells of side h: h = 1/{}, k = 1/{n} ({:.1} s)",
                2 * n,
                clock.elapsed().as_secs_f64()
            ));
        }
    }

    // Next-finer comparisons between stored levels (the finest pair waits for the
    // reference), at the coarser level's times.
    let mut next: BTreeMap<(usize, usize), Acc> = BTreeMap::new();
    for i in 0..nl {
        for &n in &level_ns {
            let Some(fine) = runs.get(&(i, 0, 2 * n)) else {
                continue;
            };
            let coarse = &runs[&(i, 0, n)];
            let interp = Interpolation::new(&coarse.mesh, &fine.mesh);
            let mut acc = Acc::default();
            for (&j, f) in &coarse.fields {
                let ff = &fine.fields[&j];
                let cu = interp.apply(&f.u);
                let cs = contact_interp(&coarse.mesh, &fine.mesh, &interp, &f.sigma);
                let e = meter.diff(&fine.mesh, ff, &cu, &cs);
                let u = meter.measures(&fine.mesh, &ff.u, &ff.sigma);
                acc.add(e, u, j == n_ref);
            }
            next.insert((i, n), acc);
        }
    }

    // The reference, compared with every stored run on the fly.
    let ref_mesh = group.loads[0].1.mesh(n_ref)?;
    let interps: BTreeMap<usize, Interpolation> = runs
        .values()
        .map(|r| r.mesh.n)
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .map(|n| {
            let m = runs.values().find(|r| r.mesh.n == n).expect("listed");
            (n, Interpolation::new(&m.mesh, &ref_mesh))
        })
        .collect();
    // Coarse node -> reference node (the meshes are nested, nodes coincide).
    let key = |p: [f64; 2]| {
        (
            (p[0] * n_ref as f64).round() as i64,
            (p[1] * n_ref as f64).round() as i64,
        )
    };
    let ref_index: std::collections::HashMap<(i64, i64), usize> = ref_mesh
        .nodes
        .iter()
        .enumerate()
        .map(|(i, &p)| (key(p), i))
        .collect();
    let injections: BTreeMap<usize, Vec<usize>> = interps
        .keys()
        .map(|&n| {
            let m = &runs.values().find(|r| r.mesh.n == n).expect("listed").mesh;
            let map = m.nodes.iter().map(|&p| ref_index[&key(p)]).collect();
            (n, map)
        })
        .collect();
    let ref_contact_pos: std::collections::HashMap<usize, usize> = ref_mesh
        .contact
        .iter()
        .enumerate()
        .map(|(k, &c)| (c, k))
        .collect();

    // Accumulators: (load, kind, n) against the reference; injected and
    // interpolation for the paper's reading.
    let mut vs_ref: BTreeMap<(usize, usize, usize), Acc> = BTreeMap::new();
    let mut injected: BTreeMap<(usize, usize), Acc> = BTreeMap::new();
    let mut interpolation: BTreeMap<(usize, usize), Acc> = BTreeMap::new();
    let clock = std::time::Instant::now();
    let ref_group = Group {
        material: group.material,
        mesh: group.mesh,
        loads: group.loads.clone(),
    };
    let mut failure: Option<ExpError> = None;
    run_level(&ref_group, n_ref, n_ref, n_ref, stride, |i, j, truth| {
        if failure.is_some() {
            return;
        }
        let u_meas = meter.measures(&ref_mesh, &truth.u, &truth.sigma);
        for (&(li, kind, n), run) in &runs {
            if li != i {
                continue;
            }
            let Some(f) = run.fields.get(&j) else {
                continue;
            };
            let last = j == n_ref;
            // What this comparison feeds: the table's rows against the reference,
            // the last increment (the finest stored level, whose other times no
            // row reads), the injected and interpolation readings.
            let against_ref = levels.contains(&n) || kind == 1;
            let increment = kind == 0 && 2 * n == n_ref && (last || levels.contains(&n));
            let injection = main && li == 0 && kind == 0 && levels.contains(&n);
            if !(against_ref || increment || injection) {
                continue;
            }
            let interp = &interps[&run.mesh.n];
            let pu = interp.apply(&f.u);
            let ps = contact_interp(&run.mesh, &ref_mesh, interp, &f.sigma);
            let e = meter.diff(&ref_mesh, &truth, &pu, &ps);
            if !e.iter().all(|x| x.is_finite()) {
                failure = Some(ExpError::File(evhi::output::FileError::Table {
                    path: "table1_forensics".into(),
                    message: format!("non-finite error at h = 1/{n}, t = {j}/{n_ref}"),
                }));
                return;
            }
            if against_ref {
                vs_ref
                    .entry((li, kind, n))
                    .or_default()
                    .add(e, u_meas, last);
            }
            // The finest stored level against the reference: the last increment,
            // needed at t = T only.
            if increment {
                next.entry((li, n)).or_default().add(e, u_meas, last);
            }
            if injection {
                // Injection: the reference's values at the coarse nodes.
                let inj = &injections[&run.mesh.n];
                let iu: Vec<[f64; 2]> = inj.iter().map(|&r| truth.u[r]).collect();
                let is: Vec<f64> = run
                    .mesh
                    .contact
                    .iter()
                    .map(|&c| truth.sigma[ref_contact_pos[&inj[c]]])
                    .collect();
                let ei = meter.diff(&run.mesh, f, &iu, &is);
                let ui = meter.measures(&run.mesh, &iu, &is);
                injected.entry((li, n)).or_default().add(ei, ui, last);
                let piu = interp.apply(&iu);
                let pis = contact_interp(&run.mesh, &ref_mesh, interp, &is);
                let ep = meter.diff(&ref_mesh, &truth, &piu, &pis);
                interpolation
                    .entry((li, n))
                    .or_default()
                    .add(ep, u_meas, last);
            }
        }
    })?;
    if let Some(e) = failure {
        return Err(e);
    }
    ctx.log(&format!(
        "forensics {} {}: reference h = k = 1/{n_ref} and comparisons ({:.1} s)",
        group.material,
        group.mesh,
        clock.elapsed().as_secs_f64()
    ));

    let mut rows = vec![];
    for (i, (load, _)) in group.loads.iter().enumerate() {
        let accs: Vec<Acc> = levels.iter().map(|&n| vs_ref[&(i, 0, n)].clone()).collect();
        rows.extend(rows_of(
            load,
            group.material,
            group.mesh,
            "reference",
            &accs,
        ));
        if main && i == 0 {
            let accs: Vec<Acc> = levels.iter().map(|&n| vs_ref[&(0, 1, n)].clone()).collect();
            rows.extend(rows_of(load, group.material, "cells_h", "reference", &accs));
            for (name, map) in [
                ("next_finer", &next),
                ("injected", &injected),
                ("interpolation", &interpolation),
            ] {
                let accs: Vec<Acc> = levels.iter().map(|&n| map[&(0, n)].clone()).collect();
                rows.extend(rows_of(load, group.material, group.mesh, name, &accs));
            }
        }
    }
    let increments = if main {
        group
            .loads
            .iter()
            .enumerate()
            .map(|(i, (load, _))| {
                let d = level_ns
                    .iter()
                    .filter_map(|&n| next.get(&(i, n)).map(|a| (n, 100.0 * a.relative(0, 0))))
                    .collect();
                (*load, d)
            })
            .collect()
    } else {
        vec![]
    };
    Ok(GroupResult { rows, increments })
}

/// Plane-strain constants $(E', \kappa')$ that give the plane-stress tensor of
/// $(E, \kappa)$: the same shear modulus and $\lambda' = E\kappa/(1 - \kappa^2)$.
pub fn plane_stress_equivalent(e: f64, kappa: f64) -> (f64, f64) {
    (
        e * (1.0 + 2.0 * kappa) / ((1.0 + kappa) * (1.0 + kappa)),
        kappa / (1.0 + kappa),
    )
}

/// The groups of the study; the first is the paper's reading.
fn groups() -> Result<Vec<Group>, ExpError> {
    let literal = Scenario::load("literal")?;
    let vertical = literal
        .clone()
        .with_loads(None, Some([0.0, literal.f2()[0]]))?;
    let figure = Scenario::load("figure")?;
    let (e, kappa) = plane_stress_equivalent(literal.e(), literal.kappa());
    Ok(vec![
        Group {
            material: "plane_strain",
            mesh: "diagonal",
            loads: vec![
                ("literal", literal.clone()),
                ("literal_vertical", vertical),
                ("figure", figure),
            ],
        },
        Group {
            material: "plane_stress",
            mesh: "diagonal",
            loads: vec![("literal", literal.clone().with_elasticity(e, kappa)?)],
        },
        Group {
            material: "plane_strain",
            mesh: "antidiagonal",
            loads: vec![(
                "literal",
                literal.clone().with_pattern(Pattern::Antidiagonal),
            )],
        },
        Group {
            material: "plane_strain",
            mesh: "crisscross",
            loads: vec![("literal", literal.with_pattern(Pattern::CrissCross))],
        },
    ])
}

pub fn run(ctx: &Ctx) -> Result<(), ExpError> {
    let plan = plan(ctx.quick);
    let groups = groups()?;
    let top = *plan.levels.last().expect("levels");
    let extra = usize::from(2 * top < plan.n_ref);
    ctx.add_units(groups.len() * (plan.levels.len() + 1) + extra + plan.levels.len());
    let mut rows = vec![];
    let mut increments = vec![];
    for (gi, group) in groups.iter().enumerate() {
        let r = study_group(group, &plan, gi == 0, ctx)?;
        rows.extend(r.rows);
        increments.extend(r.increments);
    }
    write_candidates(ctx, &plan, &rows)?;
    write_reference_free(ctx, &plan, &increments)
}
