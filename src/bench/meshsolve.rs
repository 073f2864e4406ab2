//! A mesh scene's solve against the built-in scene's (`evhi bench --mesh-solve`): the
//! paper's `figure` scene at level $n$, built in, and the same scene read from the paper
//! mesh refined to level $n$ (data/meshes/paper_n16.msh refined uniformly, written as
//! MSH 4.1 into a scratch directory, with data/scenarios/examples/paper_mesh.toml
//! pointed at it). Both are the same triangulation, so the two runs do the same
//! arithmetic up to the ordering (the grid's nested dissection against the file
//! mesh's coordinate dissection); what differs is reading the file, ordering a mesh
//! that is no grid, and writing a mesh scene's larger run directory.
//!
//! Each run is `evhi solve` in a fresh process, the two scenes in turn, on each time
//! loop; the phases are the run's own (`summary.csv`).

use super::child::{Scene, run as child};
use super::meshread::PAPER_N16;
use super::tables::MeshSolveRow;
use evhi::study::{Ctx, ExpError};
use evhi::timing::median;

/// The mesh scene of the paper's rectangle, whose mesh the bench replaces.
const PAPER_MESH_TOML: &str = include_str!("../../data/scenarios/examples/paper_mesh.toml");

/// Times both scenes at level `n` with `steps` steps, `repeat` runs each on each loop,
/// and writes `bench_mesh_solve.csv`.
pub fn run(
    ctx: &Ctx,
    n: usize,
    steps: usize,
    repeat: usize,
    machine: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    let io = |path: &std::path::Path, e: std::io::Error| {
        ExpError::File(evhi::output::FileError::Io {
            path: path.display().to_string(),
            source: e,
        })
    };
    let levels = super::meshread::check_level(n)?;
    let dir = std::env::temp_dir().join(format!("evhi-bench-mesh-solve-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| io(&dir, e))?;
    let mut mesh = evhi::msh::parse(PAPER_N16, "paper_n16.msh")?;
    for _ in 0..levels {
        mesh = evhi::refine::refine(&mesh).mesh;
    }
    let file = format!("paper_n{n}.msh");
    let msh = dir.join(&file);
    std::fs::write(&msh, evhi::msh::write(&mesh)).map_err(|e| io(&msh, e))?;
    let toml = PAPER_MESH_TOML.replace("../../meshes/paper_n16.msh", &file);
    let scene_path = dir.join("paper_mesh.toml");
    std::fs::write(&scene_path, toml).map_err(|e| io(&scene_path, e))?;
    let scenes = [
        ("built-in", Scene::figure(n)),
        (
            "mesh",
            Scene {
                scenario: scene_path.display().to_string(),
                n: None,
            },
        ),
    ];
    let mut rows = vec![];
    for path in ["reduced", "general"] {
        let mut runs: [Vec<std::collections::HashMap<String, f64>>; 2] = [vec![], vec![]];
        for r in 0..repeat {
            for (i, (name, scene)) in scenes.iter().enumerate() {
                evhi::diag!(
                    "  mesh solve: {name} scene, n = {n}, {path} loop, run {}",
                    r + 1
                );
                runs[i].push(child(scene, steps, evhi::step::DEFAULT_SOLVER, path)?);
            }
        }
        let med = |i: usize, k: &str| {
            median(
                runs[i]
                    .iter()
                    .map(|row| row.get(k).copied().unwrap_or(f64::NAN))
                    .collect(),
            )
        };
        // The solve: every phase of the loop, from assembly to the last step.
        let solve = |i: usize| {
            median(
                runs[i]
                    .iter()
                    .map(|row| {
                        ["assembly_s", "factorisation_s", "condensation_s", "steps_s"]
                            .iter()
                            .map(|k| row.get(*k).copied().unwrap_or(f64::NAN))
                            .sum()
                    })
                    .collect(),
            )
        };
        for (i, (name, _)) in scenes.iter().enumerate() {
            rows.push(MeshSolveRow {
                path: path.into(),
                scene: name.to_string(),
                n: n as u64,
                steps: steps as u64,
                dofs: med(i, "dofs"),
                assembly_s: med(i, "assembly_s"),
                factorisation_s: med(i, "factorisation_s"),
                condensation_s: med(i, "condensation_s"),
                steps_s: med(i, "steps_s"),
                solve_s: solve(i),
                wall_s: med(i, "wall_s"),
                solve_ratio: solve(i) / solve(0),
                wall_ratio: med(i, "wall_s") / med(0, "wall_s"),
            });
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    ctx.write_as(
        "bench_mesh_solve.csv",
        &MeshSolveRow::table(&rows),
        "bench --mesh-solve",
        &format!(
            "machine: {machine}; the figure scene at level n built in, and read from data/meshes/paper_n16.msh refined uniformly to level n (scenarios/examples/paper_mesh.toml); each run `evhi solve --steps {steps}` in a fresh process, the two scenes in turn; medians of {repeat} runs; solve_s = assembly + factorisation + condensation + steps (each run's sum, then the median); wall_s the run's wall time up to writing its run directory (summary.csv's: reading the scene included); the ratios are over the built-in scene's on the same loop"
        ),
    )?;
    Ok(())
}
