//! The adaptive loop on scenes nobody graded: the cantilever, clamped along its left
//! side, whose singular points no preset names (and whose law jumps down), and the
//! five-branch scene, the paper's body with a law whose upward jump falls where the
//! solution puts it, and the contact-zone scene, the paper's body pressed on half its
//! top and pulled on the other half, whose contact zone and limit stretch end inside
//! $\Gamma_3$; each from the coarsest grid that resolves it.
//! Per scene, the uniform family (every triangle bisected to the next level's size)
//! and the adaptive family (Dörfler marking on the estimator's maximum over time), to
//! the same budget of unknowns, against a reference that nobody graded either: the
//! adaptive loop continued to [`REFERENCE_FACTOR`] times the budget, refined to hold
//! both families' last meshes, so that every mesh embeds in it exactly.

use super::adaptive::{Collect, FAMILIES, Fields, Keep, Lev, Reference, Row, level};
use super::{Ctx, ExpError};
use evhi::adapt::{AdaptSettings, adapt_from, initial_forest, solve_estimating};
use evhi::mesh::Dofs;
use evhi::scenario::Scenario;
use evhi::simulation::{Observer, RunSettings, Simulation};
use std::sync::Arc;

/// The scenes: name, TOML (compiled in), its path.
const SCENES: [(&str, &str); 3] = [
    (
        include_str!("../../data/scenarios/examples/cantilever.toml"),
        "data/scenarios/examples/cantilever.toml",
    ),
    (
        include_str!("../../data/scenarios/examples/five_branch.toml"),
        "data/scenarios/examples/five_branch.toml",
    ),
    (
        include_str!("../../data/scenarios/examples/contact_zone.toml"),
        "data/scenarios/examples/contact_zone.toml",
    ),
];

/// The experiment that adapts meshes: the user scenes, with a quarter of the paper
/// scenes' budget and their steps, then the paper's scenes ([`super::adaptive::run`]),
/// which write every row.
pub fn run_all(ctx: &Ctx) -> Result<(), ExpError> {
    let plan = super::adaptive::plan(ctx.quick);
    let (user, what) = rows(ctx, plan.steps, plan.max_dofs / 4)?;
    super::adaptive::run(ctx, user, &what)
}

/// The reference's budget over the families'.
pub const REFERENCE_FACTOR: usize = 16;

/// Runs the scenes (`steps` steps, a budget of `budget` unknowns): their rows of
/// `adaptive_convergence.csv`, and what the table's header says of them.
pub(super) fn rows(ctx: &Ctx, steps: usize, budget: usize) -> Result<(Vec<Row>, String), ExpError> {
    let mut out = vec![];
    let mut refs = vec![];
    ctx.add_units(SCENES.len());
    for (i, (toml, path)) in SCENES.iter().enumerate() {
        let scn = Scenario::from_toml(toml, path)?;
        let (mut forest, root, n0) = initial_forest(&scn)?;
        let settings = RunSettings::default().with_n(n0).with_steps(steps);
        let geo = scn.geometry().clone();
        let mut levs: Vec<Lev> = vec![];
        // The uniform family: the grid's cells halved level by level.
        let (mut leaves, mut n) = (root.clone(), n0);
        loop {
            let mesh = Arc::new(forest.mesh(&leaves, n));
            let dofs = Dofs::new(&mesh, true).count;
            if dofs > budget {
                break;
            }
            let clock = std::time::Instant::now();
            let sim = Simulation::on_mesh(scn.clone(), settings.clone(), mesh.clone())?;
            let est = solve_estimating(&sim, evhi::adapt::Aggregate::Max, &mut Keep)?;
            let total: f64 = est.eta_sq.iter().sum();
            levs.push(Lev {
                family: FAMILIES[0], // uniform
                scene: i,
                level: levs.len(),
                leaves: leaves.clone(),
                dofs,
                fields: est.fields,
                estimate: (total / est.norm_sq).sqrt(),
                wall_s: clock.elapsed().as_secs_f64(),
            });
            n *= 2;
            leaves = level(&mut forest, &geo, &leaves, n, &[]);
        }
        let uniform_last = levs
            .last()
            .map(|l| l.leaves.clone())
            .unwrap_or(root.clone());
        // The adaptive family, in the same forest.
        let adapt = AdaptSettings::default().with_tol(1e-6);
        let mut collect = Collect {
            family: FAMILIES[2], // adaptive
            scene: i,
            levels: vec![],
        };
        let a = adapt_from(
            forest,
            root.clone(),
            &scn,
            &settings,
            &adapt.clone().with_max_dofs(budget),
            &mut collect,
        )?;
        forest = a.forest;
        let adaptive_last = a.leaves;
        levs.extend(collect.levels);
        // The reference: the adaptive loop continued, then holding both families.
        let r = adapt_from(
            forest,
            root,
            &scn,
            &settings,
            &adapt.with_max_dofs(REFERENCE_FACTOR * budget),
            &mut (),
        )?;
        forest = r.forest;
        let mut reference = r.leaves;
        for last in [&uniform_last, &adaptive_last] {
            reference = forest.refine_to_contain(&reference, last);
        }
        let ref_mesh = Arc::new(forest.mesh(&reference, n0));
        let ref_dofs = Dofs::new(&ref_mesh, true);
        let sim = Simulation::on_mesh(scn.clone(), settings.clone(), ref_mesh.clone())?;
        let mut keep = Fields(vec![], ref_dofs.count);
        keep.restart();
        sim.solve(&mut keep)?;
        let ref_fields: Vec<Vec<[f64; 2]>> = keep.0.iter().map(|u| ref_dofs.expand(u)).collect();
        refs.push(format!("{}: {} dofs", scn.name(), ref_dofs.count));
        ctx.log(&format!(
            "user scene {}: {} levels, reference {} dofs",
            scn.name(),
            levs.len(),
            ref_dofs.count
        ));
        // Errors: each level carried to the reference exactly.
        let g = scn.elasticity();
        let norm_geo = evhi::norms::NormGeometry::new(&ref_mesh);
        let ref_norms: Vec<f64> = (ref_fields.iter())
            .map(|u| norm_geo.norms(&ref_mesh, &g, u).energy_sq)
            .collect();
        let reference = Reference {
            mesh: &ref_mesh,
            norm_geo: &norm_geo,
            g: &g,
        };
        for lev in &levs {
            let (at_t, max) = reference.error(&forest, lev, n0, &ref_fields, &ref_norms);
            out.push(Row {
                scenario: scn.name().to_string(),
                family: lev.family,
                level: lev.level,
                dofs: lev.dofs,
                steps,
                err_t: at_t,
                err_max: max,
                estimate: lev.estimate,
                wall_s: lev.wall_s,
            });
        }
    }
    let what = format!(
        "the user scenes (data/scenarios/examples/cantilever.toml, five_branch.toml, contact_zone.toml), each from the coarsest grid that resolves it; uniform: every longest edge within level n's bound, n doubling from that grid's; adaptive: evhi::adapt, theta 0.5, indicators at their maximum over the steps (told nothing of the singular points); both until the next mesh would pass {budget} dofs; N = {steps} steps; reference: the adaptive loop continued to {} dofs, refined to hold both families' last meshes ({}); the other columns as above",
        REFERENCE_FACTOR * budget,
        refs.join("; ")
    );
    Ok((out, what))
}
