//! Figs. 3 and 4: the deformed body at $t = T$ (true scale) and the interface
//! forces on $\Gamma_3$, nodes coloured by their regime, for the `figure` scenario
//! ($h = k = 1/128$); Fig. 4 repeats it for several $g$.

use super::{Ctx, ExpError};
use evhi::certificate::ContactState;
use evhi::mesh::{Dofs, Mesh};
use evhi::output::csv::Table;
use evhi::output::plot::{REGIMES, both};
use evhi::output::scene::{Panel, SceneFigure};
use evhi::scenario::Scenario;

/// The state at $t = T$ of one scene.
pub struct Scene {
    pub mesh: Mesh,
    pub disp: Vec<[f64; 2]>,
    pub contact: Vec<ContactState>,
    pub regimes: Vec<String>,
}

/// Solves the `figure` scenario with limit `g` at $h = k = 1/n$.
pub fn solve_scene(n: usize, g: f64) -> Result<Scene, ExpError> {
    solve(&Scenario::load("figure")?.with_g(g)?, n)
}

/// Solves a scenario at $h = k = 1/n$ and classifies its contact nodes at $t = T$.
pub fn solve(scn: &Scenario, n: usize) -> Result<Scene, ExpError> {
    let res = super::run_newton(scn, n, n)?;
    scene(scn, n, res)
}

/// [`solve`] for scenarios that share the step matrix, in one batched run.
pub fn solve_all(scns: &[Scenario], n: usize) -> Result<Vec<Scene>, ExpError> {
    let runs = super::run_newton_batch(scns, n, n)?;
    scns.iter().zip(runs).map(|(s, r)| scene(s, n, r)).collect()
}

fn scene(scn: &Scenario, n: usize, res: evhi::scheme::Run) -> Result<Scene, ExpError> {
    debug_assert_eq!(res.mesh.n, n);
    let mesh = (*res.mesh).clone();
    let disp = Dofs::new(&mesh, true).expand(&res.u);
    let regimes = res
        .contact
        .iter()
        .map(|c| c.regime(scn.law(), scn.g()))
        .collect();
    Ok(Scene {
        mesh,
        disp,
        contact: res.contact,
        regimes,
    })
}

fn scene_n(ctx: &Ctx) -> usize {
    if ctx.quick { 16 } else { 128 }
}

/// Regime counts in `REGIMES` order.
pub fn counts(regimes: &[String]) -> Vec<u64> {
    REGIMES
        .iter()
        .map(|r| regimes.iter().filter(|x| x == r).count() as u64)
        .collect()
}

fn contact_table(scenes: &[(f64, &Scene)]) -> Table {
    let mut g = vec![];
    let (mut x, mut un, mut s1, mut s2, mut reg) = (vec![], vec![], vec![], vec![], vec![]);
    for (gv, sc) in scenes {
        for (i, &v) in sc.mesh.contact.iter().enumerate() {
            g.push(*gv);
            x.push(sc.mesh.nodes[v][0]);
            un.push(sc.contact[i].u_nu);
            s1.push(sc.contact[i].sigma_nu1);
            s2.push(sc.contact[i].sigma_nu2);
            reg.push(sc.regimes[i].clone());
        }
    }
    Table::new()
        .f64("g", g)
        .f64("x", x)
        .f64("u_nu", un)
        .f64("sigma_nu1", s1)
        .f64("sigma_nu2", s2)
        .str("regime", reg)
}

/// Nodes of the lattice with spacing `stride` (in mesh cells), with their displacement.
fn nodes_table(scenes: &[(f64, &Scene)], stride: usize) -> Table {
    let (mut g, mut x, mut y, mut ux, mut uy) = (vec![], vec![], vec![], vec![], vec![]);
    for (gv, sc) in scenes {
        let n = sc.mesh.n;
        for j in (0..=sc.mesh.ny).step_by(stride) {
            for i in (0..=n).step_by(stride) {
                let v = j * (n + 1) + i;
                g.push(*gv);
                x.push(sc.mesh.nodes[v][0]);
                y.push(sc.mesh.nodes[v][1]);
                ux.push(sc.disp[v][0]);
                uy.push(sc.disp[v][1]);
            }
        }
    }
    Table::new()
        .f64("g", g)
        .f64("x", x)
        .f64("y", y)
        .f64("ux", ux)
        .f64("uy", uy)
}

pub fn run_fig3(ctx: &Ctx) -> Result<(), ExpError> {
    let n = scene_n(ctx);
    let g = 0.1;
    ctx.add_units(1);
    ctx.log(&format!("fig3: figure scenario, h = k = 1/{n}, g = {g}"));
    let sc = solve_scene(n, g)?;
    let params = format!("scenario figure, h = k = 1/{n}, g = {g}, solver newton, t = T = 1");
    let cp = ctx.write("fig3_contact.csv", &contact_table(&[(g, &sc)]), &params)?;
    let np = ctx.write("fig3_nodes.csv", &nodes_table(&[(g, &sc)], 1), &params)?;
    let panels = vec![Panel::from_csv(&cp, &np, g, n)?];
    Ok(both(
        &ctx.figures,
        "fig3_deformed",
        (1000, 980),
        &SceneFigure {
            paper_law: true,
            panels,
            title: format!(
                "Fig. 3: deformed body at t = T (true scale), forces on Γ3; h = k = 1/{n}"
            ),
            columns: 1,
        },
    )?)
}

pub fn fig4_gs() -> [f64; 4] {
    [0.1, 0.09, 0.08, 0.07]
}

pub fn run_fig4(ctx: &Ctx) -> Result<(), ExpError> {
    let n = scene_n(ctx);
    let gs = fig4_gs();
    // The four limits share the step matrix: one batched run.
    ctx.add_units(1);
    ctx.log(&format!("fig4: figure scenario, h = k = 1/{n}, g = {gs:?}"));
    let scns = gs
        .iter()
        .map(|&g| Scenario::load("figure")?.with_g(g))
        .collect::<Result<Vec<_>, _>>()?;
    let scenes: Vec<(f64, Scene)> = gs.iter().copied().zip(solve_all(&scns, n)?).collect();
    let refs: Vec<(f64, &Scene)> = scenes.iter().map(|(g, s)| (*g, s)).collect();
    let params = format!("scenario figure, h = k = 1/{n}, g in {gs:?}, solver newton, t = T = 1");
    let cp = ctx.write("fig4_contact.csv", &contact_table(&refs), &params)?;
    let stride = (n / 32).max(1);
    let np = ctx.write(
        "fig4_nodes.csv",
        &nodes_table(&refs, stride),
        &format!("{params}; nodes every {stride} cells"),
    )?;
    let mut t = Table::new().f64("g", gs.to_vec());
    for (k, r) in REGIMES.iter().enumerate() {
        t = t.u64(
            r,
            scenes.iter().map(|(_, s)| counts(&s.regimes)[k]).collect(),
        );
    }
    ctx.write("fig4_counts.csv", &t, &params)?;
    let mut panels = vec![];
    for &g in &gs {
        panels.push(Panel::from_csv(&cp, &np, g, n / stride)?);
    }
    Ok(both(
        &ctx.figures,
        "fig4_several_g",
        (1000, 1180),
        &SceneFigure {
            paper_law: true,
            panels,
            title: format!(
                "Fig. 4: several g, deformed mesh (true scale) and forces, h = k = 1/{n} \
                 (mesh lines every {stride} cells)"
            ),
            columns: 2,
        },
    )?)
}
