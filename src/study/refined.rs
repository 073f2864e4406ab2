//! `evhi study convergence` on a mesh scene: the uniform family of its body, each
//! level the one before refined uniformly ([`crate::refine`]: each triangle into four
//! at its edges' midpoints), with $k = T/N_l$, $N_l = N_0 2^l$, so that $h$ and $k$
//! halve together. Each level's $u(T)$ is embedded exactly in the reference (the
//! family refined once more, with twice the steps) and its relative error
//! $\|u_{\text{ref}}(T) - u_l(T)\|_E / \|u_{\text{ref}}(T)\|_E$ is measured there, with
//! the observed order in $h$, $\log_2(e_{l-1}/e_l)$.
//!
//! The boundary's new nodes are midpoints of the coarse boundary edges: every level
//! solves on the coarse mesh's polygon, so the study measures the convergence to the
//! solution on that polygon, and the geometry stays at the coarse mesh's resolution.
//! The graded family and the $h$/$k$ split need the rectangle's structured meshes
//! (bisection towards its corners, meshes of any level $n$): the report says so.

use super::{ExpError, bar, pct, study_ctx, write_scenario};
use crate::output::rundir::RunDir;
use crate::refine::Refinement;
use crate::scenario::Scenario;
use std::fmt::Write as _;
use std::sync::Arc;

crate::row! {
    /// One row of a mesh scene's `convergence.csv`: a level of the uniform family.
    pub struct LevelRow {
        /// The level: 0 for the file's mesh, one more per uniform refinement.
        level: u64 => "level",
        /// The level's triangles.
        triangles: u64 => "triangles" if crate::output::rows::AT_LEAST_ONE,
        /// Its displacement unknowns.
        dofs: u64 => "dofs" if crate::output::rows::AT_LEAST_ONE,
        /// Its longest edge.
        h_max: f64 => "h_max" if crate::output::rows::POSITIVE,
        /// Its time steps.
        steps: u64 => "steps" if crate::output::rows::AT_LEAST_ONE,
        /// The relative error in the energy norm at $T$ against the reference, in percent.
        rel_err_t_percent: f64 => "rel_err_T_percent",
        /// The observed order in $h$ from the level before (NaN at the first).
        order_h: f64 => "order_h",
    }
}

/// The largest reference the study builds, in triangles.
pub const MAX_REFERENCE_TRIANGLES: usize = 1 << 20;

/// The levels below the reference: three with `--quick`, else four.
pub fn levels(quick: bool) -> usize {
    if quick { 3 } else { 4 }
}

/// The steps $N_0$ of the coarsest level: 4 with `--quick`, else 8 (1 for a steady
/// scene, solved once at $T$).
fn first_steps(scn: &Scenario, quick: bool) -> usize {
    match (scn.problem, quick) {
        (crate::scenario::Problem::Steady, _) => 1,
        (_, true) => 4,
        (_, false) => 8,
    }
}

/// The longest edge of `mesh`.
fn h_max(mesh: &crate::mesh::Mesh) -> f64 {
    let len = |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]).hypot(b[1] - a[1]);
    (mesh.triangles.iter())
        .flat_map(|t| (0..3).map(move |i| (t[i], t[(i + 1) % 3])))
        .map(|(a, b)| len(mesh.nodes[a], mesh.nodes[b]))
        .fold(0.0, f64::max)
}

/// The convergence study of a mesh scene (`evhi study convergence` on a scene whose body
/// is a mesh file): quick or full, with the named step solver, into `out`.
pub(super) fn run(
    (quick, solver, out): (bool, Option<&str>, &std::path::Path),
    scn: Scenario,
    text: String,
    command: &str,
) -> Result<String, Box<dyn std::error::Error>> {
    let body = scn.body().expect("a mesh scene");
    let solver = super::study_solver(solver)?;
    let count = levels(quick);
    let coarse = body.mesh.triangles.len();
    let reference = coarse << (2 * count);
    if reference > MAX_REFERENCE_TRIANGLES {
        return Err(crate::error::InputError::field(
            "geometry.mesh",
            &body.file,
            format!(
                "a mesh of at most {} triangles for {}`study convergence`: its reference \
                 refines it {count} times, {coarse} triangles to {reference}, beyond the \
                 {MAX_REFERENCE_TRIANGLES} the study builds; mesh the body coarser (the study \
                 refines it){}",
                MAX_REFERENCE_TRIANGLES >> (2 * count),
                if quick { "" } else { "a full " },
                if quick {
                    ""
                } else {
                    ", or take --quick (one level fewer)"
                }
            ),
        )
        .into());
    }
    // The family and its embeddings, before any solve (each level's parts checked
    // again as the scene's were).
    let mut scns = vec![scn.clone()];
    let mut embeds: Vec<Refinement> = vec![];
    for l in 0..count {
        let (fine, r) = scns[l]
            .refined()
            .map_err(|e| ExpError::from(e).at(format!("refinement {}", l + 1)))?;
        scns.push(fine);
        embeds.push(r);
    }
    let n0 = first_steps(&scn, quick);
    let steps = |l: usize| if n0 == 1 { 1 } else { n0 << l };
    let out = RunDir::open(out)?;
    let progress = bar(count as u64 + 1);
    let ctx = study_ctx(&out, quick, &progress, command);
    let g = scn.elasticity();
    // u(T) of each level, nodal, two components a node.
    let mut fields: Vec<(Arc<crate::mesh::Mesh>, usize, Vec<f64>)> = vec![];
    for (l, s) in scns.iter().enumerate() {
        let mesh = Arc::new(s.body_mesh().expect("a mesh scene"));
        ctx.log(&format!(
            "level {l}: {} triangles, {} steps",
            mesh.triangles.len(),
            steps(l)
        ));
        let u =
            super::graded::reference_at_t(std::slice::from_ref(s), &mesh, mesh.n, steps(l), solver)
                .map_err(|e| e.in_study().at(format!("level {l}")))?
                .pop()
                .expect("one scene");
        let dofs = crate::mesh::Dofs::new(&mesh, true);
        let nodal: Vec<f64> = dofs.expand(&u).into_iter().flatten().collect();
        fields.push((mesh, dofs.count, nodal));
    }
    progress.finish_and_clear();
    let (ref_mesh, ref_dofs, u_ref) = fields.last().expect("the reference");
    let geo = crate::norms::NormGeometry::new(ref_mesh);
    let pairs = |v: &[f64]| -> Vec<[f64; 2]> { v.chunks(2).map(|c| [c[0], c[1]]).collect() };
    let ref_sq = geo.norms(ref_mesh, &g, &pairs(u_ref)).energy_sq;
    let mut rows: Vec<LevelRow> = vec![];
    for (l, (mesh, dofs, u)) in fields[..count].iter().enumerate() {
        let mut v = u.clone();
        for r in &embeds[l..] {
            v = r.embed(&v);
        }
        let diff: Vec<f64> = u_ref.iter().zip(&v).map(|(a, b)| a - b).collect();
        let err = (geo.norms(ref_mesh, &g, &pairs(&diff)).energy_sq / ref_sq).sqrt();
        let order = match rows.last() {
            Some(prev) => (prev.rel_err_t_percent / (100.0 * err)).log2(),
            None => f64::NAN,
        };
        rows.push(LevelRow {
            level: l as u64,
            triangles: mesh.triangles.len() as u64,
            dofs: *dofs as u64,
            h_max: h_max(mesh),
            steps: steps(l) as u64,
            rel_err_t_percent: 100.0 * err,
            order_h: order,
        });
    }
    let lines = vec![
        format!(
            "produced by evhi {} `evhi {command}`",
            env!("CARGO_PKG_VERSION")
        ),
        format!(
            "scenario {} on the mesh {} ({coarse} triangles); uniform family: level l is the mesh refined l times (each triangle into four at its edges' midpoints; boundary midpoints stay on the coarse polygon), k = T/N with N = {n0}*2^l; reference: refined {count} times ({} triangles, {ref_dofs} unknowns) with N = {}; solver {}; error at T relative, energy norm, each level embedded exactly in the reference; order_h = log2 of the ratio to the previous level's error (h halves each level)",
            scn.name,
            body.file,
            ref_mesh.triangles.len(),
            steps(count),
            solver.name
        ),
    ];
    out.write_table("convergence.csv", &LevelRow::table(&rows), &lines)?;
    let mut md = format!(
        "# Convergence of `{}` on its mesh ({})\n\n{}\n\n{}\n\n\
         | level | triangles | unknowns | h_max | steps | error at T, % | order in h |\n\
         |---|---|---|---|---|---|---|\n",
        scn.name,
        if quick { "quick" } else { "full" },
        lines[0],
        lines[1]
    );
    for r in &rows {
        let _ = writeln!(
            md,
            "| {} | {} | {} | {:.4e} | {} | {} | {:.3} |",
            r.level,
            r.triangles,
            r.dofs,
            r.h_max,
            r.steps,
            pct(r.rel_err_t_percent),
            r.order_h
        );
    }
    let _ = writeln!(
        md,
        "\nThe geometry stays at the coarse mesh's resolution: a refined boundary edge's \
         midpoint lies on the coarse edge, not on the body's true outline, so these errors \
         are those of the problem on the coarse polygon. To resolve a curved outline \
         better, mesh it finer in Gmsh.\n\nNot run on a mesh scene: the graded family and \
         the h and k split, which need the rectangle's structured meshes (bisection graded \
         towards its corners, meshes of any level n)."
    );
    out.write("convergence.md", md.as_bytes())?;
    write_scenario(&out, &text, command)?;
    out.publish()?;
    Ok(md)
}
