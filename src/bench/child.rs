//! One `evhi solve` in a child process, started afresh as a user's run is: the numbers
//! of its summary row and the iteration totals of its steps.

/// What a child run solves: a scenario by name or file, and its level where the
/// scene has levels (a mesh scene's mesh is its file's).
pub struct Scene {
    /// `--scenario`.
    pub scenario: String,
    /// `--n`, or none for a mesh scene.
    pub n: Option<usize>,
}

impl Scene {
    /// The built-in `figure` scene at level `n`.
    pub fn figure(n: usize) -> Scene {
        Scene {
            scenario: "figure".into(),
            n: Some(n),
        }
    }
}

/// `evhi solve` of `scene` in a child process, into `dir`.
pub fn solve_into(
    dir: &std::path::Path,
    scene: &Scene,
    steps: usize,
    solver: &str,
    path: &str,
) -> Result<(), String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut cmd = std::process::Command::new(exe);
    cmd.args(["solve", "--scenario", &scene.scenario, "--solver", solver])
        .args(["--path", path, "--steps"])
        .arg(steps.to_string())
        .arg("--out")
        .arg(dir);
    if let Some(n) = scene.n {
        cmd.args(["--n", &n.to_string()]);
    }
    let out = cmd.output().map_err(|e| e.to_string())?;
    if !out.status.success() {
        return Err(format!(
            "{}{}, steps = {steps}, {solver}, {path} path: {}",
            scene.scenario,
            scene.n.map_or(String::new(), |n| format!(", n = {n}")),
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    Ok(())
}

/// One configuration run in a child process; returns the numeric columns of its
/// summary row (and the iteration totals of steps.csv) as name -> value.
pub fn run(
    scene: &Scene,
    steps: usize,
    solver: &str,
    path: &str,
) -> Result<std::collections::HashMap<String, f64>, String> {
    let dir = std::env::temp_dir().join(format!(
        "evhi-bench-{}-{}-{}-{steps}-{solver}-{path}",
        std::process::id(),
        std::path::Path::new(&scene.scenario)
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy()),
        scene.n.unwrap_or(0),
    ));
    solve_into(&dir, scene, steps, solver, path)?;
    // Both files through their row types (the project's own CSV reader, polars); string
    // columns are skipped.
    use evhi::output::rows::{StepRow, SummaryRow};
    let read = || -> Result<std::collections::HashMap<String, f64>, evhi::output::FileError> {
        let summary = SummaryRow::read(&dir.join("summary.csv"))?;
        let mut row: std::collections::HashMap<String, f64> = (summary.first().iter())
            .flat_map(|s| s.numbers())
            .map(|(name, x)| (name.to_string(), x))
            .collect();
        let steps = StepRow::read(&dir.join("steps.csv"))?;
        let total = |f: fn(&StepRow) -> u64| steps.iter().map(|s| f(s) as f64).sum::<f64>();
        row.insert("iterations_total".into(), total(|s| s.iterations));
        row.insert(
            "inner_iterations_total".into(),
            total(|s| s.inner_iterations),
        );
        Ok(row)
    };
    let row = read().map_err(|e| e.to_string());
    let _ = std::fs::remove_dir_all(&dir);
    row
}
