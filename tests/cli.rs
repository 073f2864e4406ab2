//! The command line: outputs, headers, and readable errors.

mod common;

use common::*;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const FIGURE: &str = "data/scenarios/figure.toml";
const FIVE: &str = "data/scenarios/examples/five_branch.toml";
const CANTILEVER: &str = "data/scenarios/examples/cantilever.toml";
/// The law of `figure`, which several tests replace.
const SLOPES: &str = "slopes = [0.0, 200.0, -100.0, 300.0]";

/// `evhi solve --scenario SCENARIO WORDS... --out OUT`.
fn solve(scenario: impl AsRef<OsStr>, words: &str, out: &Path) -> Command {
    let mut cmd = evhi_with("solve --scenario");
    cmd.arg(scenario)
        .args(words.split_whitespace())
        .arg("--out")
        .arg(out);
    cmd
}

/// `evhi solve --scenario figure --n 8 --steps 2 --out OUT`: the smallest run, for the
/// tests of outputs and messages.
fn small_solve(out: &Path) -> Command {
    solve("figure", "--n 8 --steps 2", out)
}

/// `evhi study STUDY --quick --scenario SCENARIO --out OUT`.
fn study(name: &str, scenario: impl AsRef<OsStr>, out: &Path) -> Command {
    let mut cmd = evhi_with(&format!("study {name} --quick --scenario"));
    cmd.arg(scenario).arg("--out").arg(out);
    cmd
}

/// `evhi reproduce WORDS... --data DATA --figures FIGURES`.
fn reproduce_into(words: &str, data: &Path, figures: &Path) -> Command {
    let mut cmd = evhi_with(&format!("reproduce {words} --data"));
    cmd.arg(data).arg("--figures").arg(figures);
    cmd
}

/// `evhi reproduce WORDS... --data DIR/data --figures DIR/figures`.
fn reproduce(words: &str, dir: &Path) -> Command {
    reproduce_into(words, &dir.join("data"), &dir.join("figures"))
}

/// `evhi show SCENARIO WORDS...`, run.
fn show(scenario: impl AsRef<OsStr>, words: &str) -> Output {
    let mut cmd = evhi_with("show");
    cmd.arg(scenario).args(words.split_whitespace());
    cmd.output().unwrap()
}

/// `evhi plot DIR`, run.
fn plot(dir: &Path) -> Output {
    evhi().arg("plot").arg(dir).output().unwrap()
}

/// A scenario file: `figure` with each `from` replaced by its `to`, in turn.
fn figure_file(dir: &Path, name: &str, edits: &[(&str, &str)]) -> PathBuf {
    let mut text = read(FIGURE);
    for (from, to) in edits {
        assert!(text.contains(from));
        text = text.replace(from, to);
    }
    written(dir.join(name), text)
}

/// The cantilever example as a `problem` (steady or elastic): without its viscosity.
fn cantilever_as(problem: &str) -> String {
    let text = read(CANTILEVER);
    let kept: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with("alpha") && !l.starts_with("beta"))
        .collect();
    let to = format!("problem = \"{problem}\"");
    kept.join("\n").replace("problem = \"viscoelastic\"", &to)
}

/// Asserts that each of `files` exists in `dir`.
fn assert_files(dir: &Path, label: &str, files: &[&str]) {
    for f in files {
        assert!(dir.join(f).exists(), "{label}: no {f}");
    }
}

/// Whether this checkout's .gitignore has the line `line`.
fn ignored(line: &str) -> bool {
    let ignore = read(concat!(env!("CARGO_MANIFEST_DIR"), "/.gitignore"));
    ignore.lines().any(|l| l.trim() == line)
}

#[test]
fn solve_writes_all_outputs() {
    let dir = scratch("cli");
    succeed(&mut solve("figure", "--n 16 --steps 8", &dir));
    // Every CSV opens with two provenance lines: the command, then the data solved.
    let body = |f: &str| -> String {
        let text = read(dir.join(f));
        let mut lines = text.lines();
        let first = lines.next().unwrap();
        assert!(first.starts_with("# produced by evhi"), "{f}");
        let data = lines.next().unwrap();
        assert!(
            data.starts_with("# scenario figure;") && data.contains("load history: constant"),
            "{f}: {data}"
        );
        lines.map(|l| format!("{l}\n")).collect()
    };
    let contact = body("contact.csv");
    assert!(contact.starts_with("x,u_nu,sigma_nu1,sigma_nu2,regime,y,s\n"));
    assert_eq!(contact.lines().count(), 1 + 17);
    let summary = body("summary.csv");
    assert!(summary.starts_with("n,steps,dofs,energy_norm_T,max_certificate,wall_s,"));
    assert!(summary.contains(",load_history,compatible_data,"));
    assert!(summary.contains(",constant,false,"));
    assert_eq!(body("steps.csv").lines().count(), 1 + 8);
    let vtu = read(dir.join("solution.vtu"));
    assert!(vtu.contains("NumberOfPoints=\"153\"") && vtu.contains("NumberOfCells=\"256\""));
    // No temporary files are left behind: the only hidden file is the run marker.
    let hidden: Vec<String> = names(&dir)
        .into_iter()
        .filter(|n| n.starts_with('.'))
        .collect();
    assert_eq!(hidden, vec![".evhi-run".to_string()]);
}

/// A load history from the command line (`--ramp`) or the scenario file gives the same
/// run; compatible data print no warning, constant loads print one naming H(f).
#[test]
fn load_histories_from_the_cli_and_the_file() {
    let base = scratch("cli-hist");
    let ramp = "[loads]\nhistory = { ramp = 0.25 }\n";
    let toml = figure_file(&base, "ramp.toml", &[("[loads]\n", ramp)]);
    let run = |scenario: &str, extra: &str, out: &str| -> (String, String) {
        let dir = base.join(out);
        let words = format!("--n 16 --steps 16 {extra}");
        let err = ok(&solve(scenario, &words, &dir).output().unwrap());
        (read(dir.join("summary.csv")), err)
    };
    let (from_file, warn_file) = run(toml.to_str().unwrap(), "", "file");
    let (from_cli, warn_cli) = run("figure", "--ramp 0.25", "cli");
    let (constant, warn_constant) = run("figure", "", "constant");
    assert!(
        !warn_file.contains("warning") && !warn_cli.contains("warning"),
        "{warn_cli}"
    );
    assert_contains(&warn_constant, &["warning", "H(f)"]);
    let energy = |s: &str| Csv::parse(s).f64(0, "energy_norm_T");
    assert_eq!(energy(&from_file), energy(&from_cli));
    assert!(from_cli.contains("ramp t_r = 0.25") && from_cli.contains(",true,"));
    // The ramp has reached the full load by t = 0.25, yet the body lags behind it.
    assert!(energy(&from_cli) < energy(&constant));
    // A bad ramp names the option.
    let o = evhi_with("solve --ramp -1 --out")
        .arg(base.join("bad"))
        .output()
        .unwrap();
    assert!(failed(&o).contains("`ramp`"));
}

#[test]
fn bad_arguments_fail_with_the_field_named() {
    for (args, needle) in [
        ("--n 10", "`--n`"),
        ("--g -0.1", "`--g`"),
        ("--steps 0", "`--steps`"),
        ("--scenario nope", "`scenario`"),
        // issue 12: negative counts name their option; absurd tolerances are refused
        ("--n -4", "--n"),
        ("--steps -1", "--steps"),
        ("--certificate-tol inf", "`--certificate-tol`"),
        ("--certificate-tol 1e300", "`--certificate-tol`"),
        ("--certificate-tol 1e-20", "`--certificate-tol`"),
        ("--g 1e308", "`--g`"),
        ("--n 4096", "needs about"),
        ("--ramp 1e-300", "`ramp`"),
    ] {
        let out = evhi_with(&format!("solve --out /tmp/evhi-never {args}"))
            .output()
            .unwrap();
        let err = failed(&out);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    let out = evhi_with("solve --out /tmp/x --f0 1,two").output().unwrap();
    assert!(failed(&out).contains("two"));
}

#[test]
fn bench_sweeps_writes_every_variant() {
    let dir = scratch("sweeps");
    succeed(evhi_with("bench --sweeps --sweeps-n 16 --data").arg(&dir));
    let text = read(dir.join("bench_sweeps.csv"));
    let csv = Csv::parse(&text);
    let header = csv.header.join(",");
    assert!(header.starts_with("variant,ordering,threads,prefetch,columns,nnz_l,"));
    // faer, seven of ours, two streaming rates.
    assert_eq!(csv.len(), 10, "{text}");
    for (row, total) in csv.rows().iter().zip(csv.column_f64("total_ms")) {
        assert!(total > 0.0 && total.is_finite(), "{row:?}");
    }
    // A level the mesh does not allow is refused with the field named.
    let o = evhi_with("bench --sweeps --sweeps-n 10 --data")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(failed(&o).contains("`n`"));
}

/// `bench --mesh-read`: the paper mesh refined to the level, written, read back into
/// a body and its mesh, timed; a level that is no refinement of it is refused.
#[test]
fn bench_mesh_read_times_the_refined_paper_mesh() {
    let dir = scratch("bench-mesh");
    succeed(evhi_with("bench --mesh-read --mesh-read-levels 32,64 --repeat 1 --data").arg(&dir));
    // Its provenance names the command as run, with its flags.
    let first = read(dir.join("bench_mesh.csv"))
        .lines()
        .next()
        .unwrap_or("")
        .to_string();
    assert_contains(
        &first,
        &["`evhi bench --mesh-read --mesh-read-levels 32,64 --repeat 1 --data"],
    );
    let csv = Csv::read(dir.join("bench_mesh.csv"));
    assert_eq!(csv.column_f64("triangles"), [1024.0, 4096.0]);
    assert_eq!(csv.column_f64("nodes"), [561.0, 2145.0]);
    for t in csv.column_f64("total_s") {
        assert!(t > 0.0 && t < 10.0, "{t}");
    }
    let o = evhi_with("bench --mesh-read --mesh-read-levels 48 --data")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(failed(&o).contains("--mesh-read-levels"));
    // A table the bench cannot have written is refused by --from-csv.
    let data = dir.join("copy/data");
    std::fs::create_dir_all(&data).unwrap();
    for f in BENCH_TABLES.iter().chain([&".evhi-outputs"]) {
        std::fs::copy(Path::new("data").join(f), data.join(f)).unwrap();
    }
    let text = read(data.join("bench_mesh.csv"));
    std::fs::write(
        data.join("bench_mesh.csv"),
        text.replace(",262144,", ",262143,"),
    )
    .unwrap();
    let o = from_csv(&dir.join("copy"));
    let e = failed(&o);
    assert!(e.contains("bench_mesh.csv") && e.contains("262144"), "{e}");
}

/// `bench --mesh-solve`: the built-in scene and the same triangulation read from a
/// file, each solved in a child process on both loops, the same unknowns on both, the
/// built-in row the ratios' unit; a table whose built-in ratio is not 1 is refused.
/// `bench --estimator` times each level plainly and estimating every step, on both
/// loops; the estimator's phase is part of the estimating solve.
#[test]
fn bench_estimator_times_the_phase_on_both_loops() {
    let dir = scratch("bench-estimator");
    succeed(
        evhi_with(
            "bench --estimator --estimator-levels 8,16 --estimator-steps 4 --repeat 1 --data",
        )
        .arg(&dir),
    );
    let csv = Csv::read(dir.join("bench_estimator.csv"));
    assert_eq!(
        csv.column_str("path"),
        ["reduced", "reduced", "general", "general"]
    );
    assert_eq!(csv.column_f64("n"), [8.0, 16.0, 8.0, 16.0]);
    let (solve, estimating, est) = (
        csv.column_f64("solve_s"),
        csv.column_f64("estimating_s"),
        csv.column_f64("estimator_s"),
    );
    let percent = csv.column_f64("estimator_percent");
    for i in 0..4 {
        assert!(
            est[i] > 0.0 && est[i] < estimating[i],
            "{est:?} {estimating:?}"
        );
        assert!(
            (percent[i] - 100.0 * est[i] / solve[i]).abs() < 1e-9,
            "{percent:?}"
        );
    }
}

#[test]
fn bench_mesh_solve_times_both_scenes_on_both_loops() {
    let dir = scratch("bench-mesh-solve");
    succeed(
        evhi_with("bench --mesh-solve --mesh-solve-n 32 --mesh-solve-steps 4 --repeat 1 --data")
            .arg(&dir),
    );
    let csv = Csv::read(dir.join("bench_mesh_solve.csv"));
    assert_eq!(
        csv.column_str("path"),
        ["reduced", "reduced", "general", "general"]
    );
    assert_eq!(
        csv.column_str("scene"),
        ["built-in", "mesh", "built-in", "mesh"]
    );
    // n = 32: 33 x 17 nodes, the 33 of the clamped sides' ends held.
    let dofs = csv.column_f64("dofs");
    assert!(dofs.iter().all(|&d| d == dofs[0] && d > 1000.0), "{dofs:?}");
    let (solve, ratio) = (csv.column_f64("solve_s"), csv.column_f64("solve_ratio"));
    assert_eq!((ratio[0], ratio[2]), (1.0, 1.0));
    assert!((ratio[1] - solve[1] / solve[0]).abs() < 1e-12, "{ratio:?}");
    let o = evhi_with("bench --mesh-solve --mesh-solve-n 48 --data")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(failed(&o).contains("--mesh-solve-n"));
    // A built-in row whose ratio is not 1 is refused by --from-csv.
    let data = dir.join("copy/data");
    std::fs::create_dir_all(&data).unwrap();
    for f in BENCH_TABLES.iter().chain([&".evhi-outputs"]) {
        std::fs::copy(Path::new("data").join(f), data.join(f)).unwrap();
    }
    let text = read(data.join("bench_mesh_solve.csv"));
    let broken: Vec<String> = text
        .lines()
        .map(|l| match l.strip_suffix(",1.0,1.0") {
            Some(head) if l.starts_with("reduced,built-in") => format!("{head},1.5,1.0"),
            _ => l.to_string(),
        })
        .collect();
    std::fs::write(data.join("bench_mesh_solve.csv"), broken.join("\n") + "\n").unwrap();
    let e = failed(&from_csv(&dir.join("copy")));
    assert!(
        e.contains("bench_mesh_solve.csv") && e.contains("built-in row"),
        "{e}"
    );
}

/// Issue 12's cases that used to look right and were not, or were refused though valid.
#[test]
fn hostile_but_valid_input_is_solved_and_hostile_invalid_input_is_named() {
    let dir = scratch("cli-hostile");
    let run = |scenario: &Path, extra: &str| {
        let words = format!("--n 32 --steps 32 {extra}");
        solve(scenario, &words, &dir.join("out")).output().unwrap()
    };
    let figure = Path::new("figure");
    // An upward jump: nodes sit on the breakpoint up to rounding; it certifies.
    let up = format!("{SLOPES}\njumps = [0.0, 5.0, 0.0]");
    ok(&run(&figure_file(&dir, "jump.toml", &[(SLOPES, &up)]), ""));
    // A very thin layer: nodes at g(1 - 1e-8) are on the limit, not on branch 1.
    ok(&run(figure, "--g 1e-9"));
    let contact = read(dir.join("out/contact.csv"));
    assert!(
        contact.lines().filter(|l| l.contains(",limit,")).count() > 16,
        "{contact}"
    );
    // A certificate stricter than rounding: the refusal says what refused.
    let o = run(figure, "--certificate-tol 1e-15");
    let err = stderr(&o);
    if !o.status.success() {
        assert_contains(&err, &["reported convergence", "independent certificate"]);
        assert!(!err.contains("ended with Converged"), "{err}");
    }
    // A strongly softening law: the step can be nonconvex; solve warns and reports it.
    let soft = "slopes = [0.0, 200.0, -100000.0, 300.0]";
    let o = run(&figure_file(&dir, "soft.toml", &[(SLOPES, soft)]), "");
    let err = stderr(&o);
    assert!(err.contains("not convex") || !o.status.success(), "{err}");
    if o.status.success() {
        assert!(read(dir.join("out/summary.csv")).contains("step_curvature_min"));
    }
    // A very soft material breaks H(s): solve says so.
    let o = run(
        &figure_file(&dir, "soft_e.toml", &[("E = 1000.0", "E = 1e-3")]),
        "",
    );
    let err = stderr(&o);
    assert!(o.status.success() && err.contains("H(s) fails"), "{err}");
    assert!(read(dir.join("out/summary.csv")).contains(",beta_B,m_trace_norm_sq,"));
    // Values that overflow the solve are refused by name, echoed in exponent form.
    let huge = figure_file(&dir, "huge.toml", &[("T = 1.0", "T = 1e300")]);
    let err = stderr(&run(&huge, ""));
    assert!(
        err.contains("`T`") && err.contains("1e300") && err.len() < 400,
        "{err}"
    );
    let kappa = figure_file(&dir, "kappa.toml", &[("kappa = 0.4", "kappa = 1e308")]);
    let err = stderr(&run(&kappa, ""));
    assert!(
        err.contains("`material.kappa`") && err.contains("1e308") && err.len() < 400,
        "{err}"
    );
    // A 10 MB line with a parse error is echoed in part; a file over 1 MiB is refused.
    let long = written(
        dir.join("long.toml"),
        format!("name = \"{}", "x".repeat(900_000)),
    );
    let err = stderr(&run(&long, ""));
    assert!(err.len() < 2000, "{} bytes of error", err.len());
    let big = written(dir.join("big.toml"), "#".repeat(2 << 20));
    let err = stderr(&run(&big, ""));
    assert_contains(&err, &["`scenario`", "at most"]);
}

/// The evolution for ParaView: one VTU per written step and a .pvd with their times;
/// the last VTU's point fields equal contact.csv at the contact nodes.
#[test]
fn vtk_time_series_matches_the_contact_table() {
    let dir = scratch("cli-pvd");
    succeed(&mut solve("figure", "--n 16 --steps 8 --vtk-every 3", &dir));
    // Steps 3, 6 and the last, 8.
    let pvd = read(dir.join("solution.pvd"));
    let sets: Vec<(f64, String)> = pvd
        .lines()
        .filter(|l| l.starts_with("<DataSet"))
        .map(|l| {
            let attr = |name: &str| {
                let start = l.find(&format!("{name}=\"")).unwrap() + name.len() + 2;
                l[start..].split('"').next().unwrap().to_string()
            };
            (attr("timestep").parse().unwrap(), attr("file"))
        })
        .collect();
    assert_eq!(sets.len(), 3, "{pvd}");
    assert_eq!(
        sets.iter().map(|s| s.0).collect::<Vec<_>>(),
        vec![0.375, 0.75, 1.0]
    );
    for (_, f) in &sets {
        assert!(dir.join(f).exists(), "{f}");
    }
    // The last dataset against contact.csv (the contact nodes are the first 17 points).
    let vtu = read(dir.join(&sets[2].1));
    let array = |name: &str| -> Vec<f64> {
        let start = vtu.find(&format!("Name=\"{name}\"")).unwrap();
        let body = &vtu[start..];
        let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
        body.split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect()
    };
    let (sigma1, regime) = (array("sigma_nu1"), array("regime"));
    let contact = Csv::read(dir.join("contact.csv"));
    assert_eq!(contact.len(), 17);
    let mut limit = 0;
    for (i, r) in contact.column_str("regime").into_iter().enumerate() {
        assert_eq!(sigma1[i], contact.f64(i, "sigma_nu1"), "node {i}");
        let code = match r {
            "no_contact" => 0.0,
            "limit" => {
                limit += 1;
                4.0
            }
            b => b.trim_start_matches("branch").parse().unwrap(),
        };
        assert_eq!(regime[i], code, "node {i}: {r}");
    }
    assert!(limit > 0, "figure has nodes at the limit at T");
    // Off the contact boundary the regime is -1; the run directory describes itself.
    assert_eq!(regime[17], -1.0);
    let toml = read(dir.join("scenario.toml"));
    assert!(toml.contains("--vtk-every 3") && toml.contains("name = \"figure\""));
}

/// `evhi scenarios` lists the built-ins; `evhi show` prints a scenario and warns where
/// a hypothesis of the paper fails.
#[test]
fn scenarios_and_show() {
    let o = evhi().arg("scenarios").output().unwrap();
    let out = stdout(&o);
    assert!(o.status.success());
    for name in ["literal", "figure", "smooth"] {
        assert!(out.lines().any(|l| l.starts_with(name)), "{out}");
    }
    let o = show("figure", "");
    let (out, err) = (stdout(&o), stderr(&o));
    assert!(o.status.success(), "{err}");
    assert_contains(&out, &["H(s): beta_B", ": holds"]);
    assert_contains(&out, &["step convexity", "tau = 0.07"]);
    assert!(
        out.contains("warning: at t = 0") && err.contains("2 warning(s)"),
        "{out}{err}"
    );
    // A downward jump breaks H(j); a ramp makes the data compatible.
    let dir = scratch("cli-show");
    let down = format!("{SLOPES}\njumps = [0.0, -5.0, 0.0]");
    let ramp = ("[loads]\n", "[loads]\nhistory = { ramp = 0.5 }\n");
    let jump = figure_file(&dir, "down.toml", &[(SLOPES, &down), ramp]);
    let out = stdout(&show(&jump, "--n 16 --steps 16"));
    assert_contains(&out, &["warning: H(j) fails", "(a jump)"]);
    assert!(out.contains("H(f), H(0) at t = 0: hold"), "{out}");
    // solve warns about the downward jump too.
    let o = solve(&jump, "--n 16 --steps 16", &dir.join("out"))
        .output()
        .unwrap();
    let err = stderr(&o);
    assert!(err.contains("warning: H(j) fails"), "{err}");
    // A bad mesh is an error naming the option.
    assert!(failed(&show("figure", "--n 10")).contains("`--n`"));
}

/// A user scenario with a five-branch law and a jump, end to end: solve writes its
/// tables and figures, and `evhi plot` redraws the figures from the tables alone.
#[test]
fn a_user_scenario_runs_and_draws() {
    let dir = scratch("cli-five");
    let err = ok(&solve(FIVE, "--n 32 --steps 32", &dir).output().unwrap());
    assert!(
        !err.contains("warning"),
        "compatible data, H(s) holds: {err}"
    );
    let contact = read(dir.join("contact.csv"));
    assert_contains(&contact, &[",branch4,", ",limit,"]);
    let regimes = read(dir.join("regimes.csv"));
    assert!(
        regimes.contains("step,t,branch1,branch2,branch3,branch4,limit")
            || regimes.contains(",branch4,"),
        "{regimes}"
    );
    assert_eq!(Csv::read(dir.join("evolution.csv")).len(), 5 * 32);
    let size = |f: &str| std::fs::metadata(dir.join(f)).map(|m| m.len()).unwrap_or(0);
    let figures = [
        "deformed.png",
        "deformed.svg",
        "evolution.png",
        "evolution.svg",
    ];
    for f in figures {
        assert!(size(f) > 10_000, "{f}: {} bytes", size(f));
        std::fs::remove_file(dir.join(f)).unwrap();
    }
    ok(&plot(&dir));
    for f in figures {
        assert!(size(f) > 10_000, "redrawn {f}");
    }
    let o = plot(Path::new("/nonexistent-run"));
    assert!(failed(&o).contains("/nonexistent-run"));
}

/// `reproduce -q` prints nothing on success.
#[test]
fn reproduce_quiet_prints_nothing() {
    let dir = scratch("cli-quiet");
    let o = reproduce("fig2 loads --quick -q", &dir).output().unwrap();
    assert!(o.status.success());
    assert!(o.stderr.is_empty() && o.stdout.is_empty(), "{}", stderr(&o));
    assert!(dir.join("data/loads_search.csv").exists());
}

/// Every registered step solver is reachable from the command line; the penalty
/// method, which overshoots g by design, runs with a note that it is not certified.
#[test]
fn every_registered_solver_runs_from_the_command_line() {
    for entry in evhi::step::SOLVERS.iter() {
        let dir = scratch(&format!("solver-{}", entry.name));
        let mut cmd = solve("figure", "--n 8 --steps 4", &dir);
        let out = cmd.args(["--solver", entry.name]).output().unwrap();
        let err = stderr(&out);
        assert!(out.status.success(), "{}: {err}", entry.name);
        let uncertified = err.contains("is not certified");
        assert_eq!(uncertified, !entry.certified, "{}: {err}", entry.name);
        assert!(dir.join("summary.csv").exists(), "{}", entry.name);
    }
    let out = evhi_with("solve --solver gradient-descent --out /tmp/never")
        .output()
        .unwrap();
    let err = failed(&out);
    assert!(err.contains("newton") && err.contains("penalty"), "{err}");
}

/// `--path auto` takes the reduced loop where the damping is proportional and the
/// general one where it is not; steps.csv says which certificate each step got;
/// `--path reduced` on the non-proportional scene is refused by name.
#[test]
fn the_time_loop_follows_the_damping() {
    for (scenario, path, checks) in [
        ("figure", "reduced", ["condensed", "full"]),
        ("nonproportional", "general", ["full", "full"]),
    ] {
        let dir = scratch(&format!("path-{scenario}"));
        succeed(&mut solve(scenario, "--n 8 --steps 8", &dir));
        assert_eq!(summary(&dir).path, path);
        let check: Vec<String> = steps(&dir).into_iter().map(|s| s.check).collect();
        assert_eq!(check.len(), 8);
        assert_eq!([check[0].as_str(), check[7].as_str()], checks, "{scenario}");
    }
    let dir = scratch("path-refused");
    let words = "--n 8 --steps 4 --path reduced";
    let err = failed(&solve("nonproportional", words, &dir).output().unwrap());
    assert_contains(&err, &["material", "proportional"]);
}

/// A finer reference for Table 1 that cannot serve is refused by name, before
/// any run: not a multiple of the finest level, or too large for memory.
#[test]
fn a_bad_table1_reference_is_refused() {
    let dir = scratch("bad-reference");
    for bad in ["100", "1048576"] {
        let words = format!("table1 --quick --quiet --reference {bad}");
        let out = reproduce(&words, &dir).output().unwrap();
        assert!(!out.status.success(), "--reference {bad} must fail");
        let err = stderr(&out);
        assert!(err.contains(bad), "--reference {bad}: {err}");
    }
}

/// `reproduce --log` reports each finished unit as a line with its time and its
/// experiment instead of progress bars, and refuses to be quiet at the same time.
#[test]
fn reproduce_logs_lines_with_times() {
    let dir = scratch("log");
    let err = ok(&reproduce("static --quick --log", &dir).output().unwrap());
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| l.contains("] static: static control: "))
        .collect();
    // Three scenes on six quick levels, each line "  [   t.t s] static: ...".
    assert_eq!(lines.len(), 18, "{err}");
    for l in &lines {
        let secs = l
            .trim_start()
            .strip_prefix('[')
            .and_then(|r| r.split(" s]").next());
        let secs: f64 = secs.unwrap_or("x").trim().parse().expect(l);
        assert!(secs >= 0.0, "{l}");
    }
    let both = evhi_with("reproduce fig2 --log -q").output().unwrap();
    assert!(failed(&both).contains("--quiet"));
}

/// The main job changes no committed file with its own wall times: a full run keeps
/// them in the git-ignored `local/` of the data directory, and only `--record-times`
/// writes the table the book quotes.
#[test]
fn reproduce_keeps_its_times_local_unless_recorded() {
    let dir = scratch("times");
    let data = dir.join("data");
    let run = |extra: &str| succeed(&mut reproduce(&format!("fig2 -q {extra}"), &dir));
    run("");
    assert!(data.join("fig2_law.csv").exists());
    assert!(!data.join("reproduce_times.csv").exists());
    let local = read(data.join("local/reproduce_times.csv"));
    assert!(local.contains("\nfig2,fig2,"), "{local}");
    run("--record-times");
    let recorded = read(data.join("reproduce_times.csv"));
    let first = recorded.lines().next().unwrap();
    assert!(
        first.contains("`evhi reproduce fig2 --record-times --data "),
        "{first}"
    );
    assert!(recorded.contains("machine: "), "{recorded}");
    // The git-ignored directory is the one this checkout ignores.
    assert!(ignored("/data/local/"));
}

/// `solve --scenario smooth --f2 0,-1e6` (the top is clamped there) is refused naming
/// `f2`, before any work.
#[test]
fn solve_refuses_a_traction_on_a_clamped_top() {
    let dir = scratch("clamped-f2");
    let words = "--n 8 --steps 2 --f2 0,-1e6";
    let err = failed(&solve("smooth", words, &dir.join("run")).output().unwrap());
    assert!(err.contains("f2") && err.contains("rollers"), "{err}");
    assert!(!dir.join("run").join("summary.csv").exists());
}

/// The certificate judges the limit on its own scale: runs whose displacements dwarf
/// g (or the law's breakpoint gaps) so far that double precision cannot tell u_nu
/// from g are refused, naming the scale, on both time loops; none is certified. The
/// cases of the hostile run that were certified before (u_nu = -1.5 g labelled
/// `limit`; nodes 0.23 g below the limit labelled `limit`; 1.6e-4 g off).
#[test]
fn displacements_that_dwarf_g_are_refused_not_certified() {
    let dir = scratch("unresolvable");
    let cases = [
        // E = 1e-6 with huge loads, g = 1, a two-branch law.
        "name = \"tiny-E\"\nT = 1.0\ng = 1.0\n[material]\nE = 1e-6\nkappa = 0.4\nalpha = 2e-7\nbeta = 1e-7\n\
         [loads]\nf0 = [0.0, -1e9]\nf2 = [0.0, -1e10]\n[law]\nbreakpoints = [0.0]\nslopes = [0.0, 200.0]\n",
        // The paper's material and law with g = 1e-12 and large loads.
        "name = \"thin-layer\"\nT = 1.0\ng = 1e-12\n[material]\nE = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0\n\
         [loads]\nf0 = [0.0, -5e4]\nf2 = [0.0, -1e6]\n[law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n",
        // E = 1, g = 1e-3, f2 = -1e8.
        "name = \"soft\"\nT = 1.0\ng = 1e-3\n[material]\nE = 1.0\nkappa = 0.4\nalpha = 0.1\nbeta = 0.05\n\
         [loads]\nf0 = [0.0, 0.0]\nf2 = [0.0, -1e8]\n[law]\nbreakpoints = [0.0]\nslopes = [0.0, 200.0]\n",
    ];
    for (i, text) in cases.iter().enumerate() {
        for path in ["general", "auto"] {
            let extra = ["--n", "16", "--steps", "4", "--path", path];
            let (out, _) = solve_text(&dir, &format!("case{i}-{path}"), text, &extra);
            let err = stderr(&out);
            assert!(!out.status.success(), "case {i} ({path}) was certified");
            assert!(
                err.contains("resolved in double precision") && err.contains("g = "),
                "case {i} ({path}): {err}"
            );
        }
    }
}

/// Re-running `solve` into an earlier run directory that also holds the user's own
/// files is refused, naming them, and leaves them (and the earlier run) in place.
#[test]
fn solve_keeps_the_users_files_in_an_earlier_run_directory() {
    let dir = scratch("user-files");
    let out = dir.join("run");
    let solve = || small_solve(&out).output().unwrap();
    assert!(solve().status.success());
    // A rerun of a clean run directory is allowed.
    assert!(solve().status.success());
    std::fs::write(out.join("my_notes.txt"), "mine").unwrap();
    std::fs::create_dir(out.join("analysis")).unwrap();
    refused(&solve(), &["`my_notes.txt`", "`analysis/`"]);
    assert_eq!(read(out.join("my_notes.txt")), "mine");
    assert!(out.join("analysis").is_dir() && out.join("summary.csv").exists());
}

/// `reproduce --quick` without `--data`/`--figures` writes its coarse levels into the
/// git-ignored `data/local/quick/` and `figures/local/quick/`, never over the committed
/// full-level outputs.
#[test]
fn reproduce_quick_never_overwrites_the_committed_outputs() {
    let dir = scratch("quick-default");
    succeed(evhi_with("reproduce fig2 --quick -q").current_dir(&dir));
    assert!(dir.join("data/local/quick/fig2_law.csv").exists());
    assert!(dir.join("figures/local/quick/fig2_law.png").exists());
    assert!(!dir.join("data/fig2_law.csv").exists());
    assert!(!dir.join("figures/fig2_law.png").exists());
    assert!(ignored("/figures/local/"));
}

/// A line feed or carriage return cannot break out of a provenance line: refused in a
/// scenario's name, escaped in a path on the command line (issue 27, case 4).
#[test]
fn control_characters_stay_out_of_the_provenance_lines() {
    let dir = scratch("control-chars");
    let file = figure_file(
        &dir,
        "nl.toml",
        &[("name = \"figure\"", "name = \"fig\\nure\"")],
    );
    failed_with(&show(&file, ""), "`name`");
    for bad in ["cr\rrun", "lf\nrun"] {
        let out = dir.join(bad);
        succeed(&mut small_solve(&out));
        let contact = read(out.join("contact.csv"));
        let lines: Vec<&str> = contact.lines().collect();
        assert!(lines[0].starts_with("# produced by evhi") && lines[1].starts_with("# scenario"));
        assert_eq!(
            lines[2], "x,u_nu,sigma_nu1,sigma_nu2,regime,y,s",
            "{contact}"
        );
        let escaped = lines[0].contains("\\r") || lines[0].contains("\\n");
        assert!(escaped, "{}", lines[0]);
    }
}

/// Two `reproduce` into one output set cannot mix: the second fails at once while the
/// first holds the set's lock; and the temporaries of a killed run are removed by the
/// next one (issue 27, cases 5 and 6).
#[test]
fn reproduce_locks_its_outputs_and_cleans_a_killed_runs_temporaries() {
    let dir = scratch("reproduce-lock");
    let (data, figures) = (dir.join("data"), dir.join("figures"));
    std::fs::create_dir_all(&data).unwrap();
    std::fs::create_dir_all(&figures).unwrap();
    // A killed run's leftovers (no process has this id: above Linux's pid_max).
    let stale = [
        written(data.join(".fig2_law.csv.tmp-999999999"), "partial"),
        written(figures.join(".fig2_law.tmp-999999999.png"), "partial"),
    ];
    let run = || reproduce("fig2 --quick -q", &dir).output().unwrap();
    let lock = std::fs::File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(data.join(".reproduce.lock"))
        .unwrap();
    lock.try_lock().unwrap();
    failed_with(&run(), "another `evhi reproduce`");
    let untouched = stale.iter().all(|s| s.exists());
    assert!(untouched, "a refused run must touch nothing");
    drop(lock);
    ok(&run());
    assert!(stale.iter().all(|s| !s.exists()), "stale temporaries left");
    assert!(data.join("fig2_law.csv").exists());
}

/// H(s) is judged with the trace constant of the run's own mesh, which grows with n:
/// slopes [0, 200, -290, 300] pass on the 1/64 mesh's constant but fail on 1/256's
/// (issue 27, case 12: the 1/64 constant used to be taken for every n).
#[test]
fn smallness_uses_the_runs_own_trace_constant() {
    let dir = scratch("hs-trace");
    let soft = "slopes = [0.0, 200.0, -290.0, 300.0]";
    let file = figure_file(&dir, "soft.toml", &[(SLOPES, soft)]);
    let shown = |n: &str| {
        let o = show(&file, &format!("--n {n}"));
        stdout(&o) + &stderr(&o)
    };
    let line = |text: &str| {
        text.lines()
            .find(|l| l.starts_with("H(s)"))
            .unwrap()
            .to_string()
    };
    assert!(line(&shown("64")).ends_with("holds"), "{}", shown("64"));
    let at256 = line(&shown("256"));
    assert!(
        at256.contains("(n = 256)") && at256.ends_with("fails"),
        "{at256}"
    );
}

/// `plot RUN_DIR` takes the run directory's lock: it cannot redraw while a `solve`
/// writes there (issue 27, case 8).
#[test]
fn plot_waits_for_no_one_and_mixes_nothing() {
    let dir = scratch("plot-lock");
    let out = dir.join("run");
    succeed(&mut small_solve(&out));
    // Another process's lock, as a run holds it.
    let lock = evhi::output::try_lock_file(&dir.join(".run.lock"))
        .unwrap()
        .unwrap();
    failed_with(&plot(&out), "another evhi run");
    drop(lock);
    ok(&plot(&out));
}

/// The memory guard also reads the address-space limit: under `ulimit -v 3000000` a
/// mesh that cannot fit is refused before any work, with the estimate, instead of
/// aborting in an allocation (issue 27, case 11).
#[test]
fn the_memory_guard_reads_the_address_space_limit() {
    let dir = scratch("ulimit");
    let o = Command::new("bash")
        .arg("-c")
        .arg(format!(
            "ulimit -v 3000000; exec '{}' solve --scenario figure --n 2048 --steps 1 --out '{}'",
            env!("CARGO_BIN_EXE_evhi"),
            dir.join("run").display()
        ))
        .output()
        .unwrap();
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(
        err.contains("fits in memory") && !err.contains("backtrace"),
        "{err}"
    );
    assert!(!dir.join("run").exists());
}

/// Small messages of issue 27, case 16: `show` prints m = 0 (not -0) for a monotone
/// law and caps --steps as `solve` does; a symbolic link as --out is named as one.
#[test]
fn show_and_out_messages_say_what_is_wrong() {
    let dir = scratch("messages");
    let mono = "slopes = [0.0, 200.0, 100.0, 300.0]";
    let text = stdout(&show(figure_file(&dir, "mono.toml", &[(SLOPES, mono)]), ""));
    assert!(
        text.contains("= 0 (relaxed monotonicity)") && !text.contains("-0"),
        "{text}"
    );
    failed_with(&show("figure", "--steps 2000000"), "`--steps`");
    std::fs::create_dir(dir.join("real")).unwrap();
    std::os::unix::fs::symlink(dir.join("real"), dir.join("link")).unwrap();
    failed_with(
        &small_solve(&dir.join("link")).output().unwrap(),
        "symbolic link",
    );
    // A last component too long for the staging directory beside it is refused
    // before anything (lock included) is written.
    let o = small_solve(&dir.join("a".repeat(245))).output().unwrap();
    failed_with(&o, "245 bytes long; at most 235");
    let left: Vec<_> = names(&dir).into_iter().filter(|n| n.len() > 200).collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

/// `--vtk-every` is bounded by the volume it would write: 1e6 steps at n = 128 with a
/// snapshot every step (about 1 TB) is refused before any work, naming the option and
/// the estimate (issue 27, case 10).
#[test]
fn a_vtk_series_that_cannot_fit_is_refused() {
    let dir = scratch("vtk-volume");
    let words = "--n 128 --steps 1000000 --vtk-every 1";
    let err = failed(&solve("figure", words, &dir.join("run")).output().unwrap());
    assert_contains(&err, &["`vtk-every`", "TB in all"]);
    assert!(!dir.join("run/summary.csv").exists());
}

/// `plot` refuses a tampered table, naming file, line and column, instead of drawing
/// text as 0, an empty table, NaN or 1e300 (issue 27, case 15).
#[test]
fn plot_refuses_tampered_tables() {
    let dir = scratch("tampered");
    let out = dir.join("run");
    succeed(&mut small_solve(&out));
    let contact = read(out.join("contact.csv"));
    let lines: Vec<&str> = contact.lines().collect();
    let first = lines[3]; // after two provenance lines and the header
    let cells: Vec<&str> = first.split(',').collect();
    for (bad, expect) in [("abc", "`abc`"), ("NaN", "`NaN`"), ("1e300", "`1e300`")] {
        let row = format!("{},{bad},{}", cells[0], cells[2..].join(","));
        std::fs::write(out.join("contact.csv"), contact.replacen(first, &row, 1)).unwrap();
        let o = plot(&out);
        let err = stderr(&o);
        assert!(!o.status.success(), "{bad} drawn");
        assert_contains(&err, &["contact.csv:4", "`u_nu`", expect]);
    }
    let header_only: String = lines[..3].iter().map(|l| format!("{l}\n")).collect();
    std::fs::write(out.join("contact.csv"), header_only).unwrap();
    assert!(stderr(&plot(&out)).contains("no data row"));
    std::fs::write(out.join("contact.csv"), contact).unwrap();
    ok(&plot(&out));
}

#[test]
fn two_threads_with_amd_are_refused_and_amd_alone_runs_on_one() {
    let dir = scratch("threads-amd");
    let mut cmd = small_solve(&dir.join("run"));
    let out = cmd
        .args(["--threads", "2", "--ordering", "amd"])
        .output()
        .unwrap();
    let err = failed(&out);
    assert_contains(&err, &["`--threads`", "the AMD ordering"]);
    assert!(!dir.join("run").exists(), "refused before any work");
    succeed(small_solve(&dir.join("run")).args(["--ordering", "amd"]));
    assert!(read(dir.join("run/summary.csv")).contains("amd"));
}

/// Issue 25's scene from the command line: the cantilever example on a uniform and on a
/// graded mesh, viscoelastic and steady. The VTK file and the figures follow the
/// rectangle (2 x 0.5, every node inside it, the clamped corner no contact node), the
/// graded run writes its triangles, and the options that do not fit are refused by name.
#[test]
fn a_new_scene_solves_draws_and_writes_vtk_from_the_cli() {
    let dir = scratch("scene");
    let steady = written(dir.join("steady.toml"), cantilever_as("steady"));
    let file = Path::new(CANTILEVER);
    for (name, scenario, extra) in [
        ("uniform", file, "--steps 16"),
        ("graded", file, "--steps 16 --mesh graded"),
        ("steady", steady.as_path(), ""),
        (
            "steady-graded",
            steady.as_path(),
            "--mesh graded --grading 0.3",
        ),
    ] {
        let out = dir.join(name);
        succeed(&mut solve(scenario, &format!("--n 16 {extra}"), &out));
        let figures = [
            "deformed.png",
            "deformed.svg",
            "evolution.png",
            "solution.vtu",
        ];
        assert_files(&out, name, &figures);
        assert_eq!(out.join("triangles.csv").exists(), name.contains("graded"));
        let vtu = read(out.join("solution.vtu"));
        let points = vtu
            .split("NumberOfPoints=\"")
            .nth(1)
            .and_then(|s| s.split('"').next());
        let points: usize = points.unwrap().parse().unwrap();
        let nodes = Csv::read(out.join("nodes.csv"));
        let rows: Vec<Vec<f64>> = nodes
            .rows()
            .iter()
            .map(|r| r.iter().map(|x| x.parse().unwrap()).collect())
            .collect();
        let xmax = rows.iter().map(|r| r[0]).fold(0.0, f64::max);
        let ymax = rows.iter().map(|r| r[1]).fold(0.0, f64::max);
        assert_eq!(
            (xmax, ymax),
            (2.0, 0.5),
            "{name}: the lattice spans the rectangle"
        );
        if name.contains("graded") {
            assert_eq!(
                points,
                rows.len(),
                "{name}: VTK and nodes.csv hold every node"
            );
        } else {
            assert_eq!(points, 17 * 5, "{name}: 17 x 5 grid nodes");
        }
        // The clamped corner (0, 0) is no contact node.
        let first_x = Csv::read(out.join("contact.csv")).f64(0, "x");
        assert!(first_x > 0.0, "{name}: the clamped corner in contact.csv");
    }
    // The options that do not fit, each named.
    for (args, field) in [
        ("--steps 4", "steps"),
        ("--grading 0.3", "grading"),
        ("--mesh graded --grading 1.5", "grading"),
        ("--n 10", "n"),
    ] {
        let o = solve(&steady, args, &dir.join("refused")).output().unwrap();
        let err = stderr(&o);
        assert!(!o.status.success(), "{args:?} accepted");
        assert!(err.contains(&format!("`--{field}`")), "{args:?}: {err}");
    }
}

/// `evhi study convergence --quick` on user scenario files (the five-branch example on
/// the paper's scene, the cantilever on its own): each writes its directory, the
/// orders are finite, the figures exist, and the singular points are the scene's.
#[test]
fn the_convergence_study_runs_on_user_scenarios() {
    let dir = scratch("study");
    for (name, file, singular) in [("five", FIVE, 4), ("cantilever", CANTILEVER, 2)] {
        let out = dir.join(name);
        succeed(&mut study("convergence", file, &out));
        let files = ["convergence.csv", "convergence.md", "convergence.png"];
        assert_files(&out, name, &files);
        assert_files(
            &out,
            name,
            &["convergence.svg", "singular.csv", "scenario.toml"],
        );
        let conv = Csv::read(out.join("convergence.csv"));
        assert_eq!(conv.len(), 8, "{name}: two families of four levels");
        for (i, r) in conv.rows().iter().enumerate() {
            let n: usize = conv.get(i, "n").parse().unwrap();
            let err = conv.f64(i, "rel_err_T_percent");
            assert!(err.is_finite() && err > 0.0, "{name}: {r:?}");
            let order = conv.f64(i, "order_dofs");
            assert_eq!(order.is_finite(), n > 4, "{name}: order at n = {n}: {r:?}");
            let inc = conv.f64(i, "increment_T_percent");
            assert_eq!(inc.is_finite(), n < 32, "{name}: increment at n = {n}");
        }
        let sing = Csv::read(out.join("singular.csv"));
        assert_eq!(sing.len(), singular, "{name}: {:?}", sing.rows());
        // The h and k parts where the damping is proportional (the five-branch
        // example), else a sentence saying why not (the cantilever's is not).
        let md = read(out.join("convergence.md"));
        if name == "five" {
            let split = Csv::read(out.join("split.csv"));
            assert_eq!(split.len(), 9, "three families of three levels");
            for (i, r) in split.rows().iter().enumerate() {
                let e = split.f64(i, "rel_err_T_percent");
                let m = split.f64(i, "rel_err_max_percent");
                assert!(e > 0.0 && m >= e * (1.0 - 1e-12), "{r:?}");
                let o = split.f64(i, "order_T");
                // An order from the second level of each family on (the k family
                // varies the steps).
                let first = if split.get(i, "family") == "k" {
                    split.get(i, "steps") == "4"
                } else {
                    split.get(i, "n") == "4"
                };
                assert_eq!(o.is_finite(), !first, "{r:?}");
            }
            assert!(out.join("split.png").exists() && md.contains("**The h and k parts"));
        } else {
            assert!(!out.join("split.csv").exists());
            let why = "No h and k parts: the damping is not proportional";
            assert!(md.contains(why), "{md}");
        }
    }
    // A steady and an elastic copy of the cantilever: the h = k families only, the
    // steady one in one step per level.
    for problem in ["steady", "elastic"] {
        let file = written(dir.join(format!("{problem}.toml")), cantilever_as(problem));
        let out = dir.join(problem);
        succeed(&mut study("convergence", &file, &out));
        let md = read(out.join("convergence.md"));
        let why = format!("No h and k parts: the problem is {problem}");
        assert!(md.contains(&why), "{md}");
        assert_eq!(md.contains("one step (steady)"), problem == "steady");
    }
    // `evhi --help` points to `evhi study --help`, which lists every study of the
    // registry, and each study explains its options.
    let help = stdout(&evhi_with("--help").output().unwrap());
    assert_contains(&help, &["evhi study --help"]);
    let help = stdout(&evhi_with("study --help").output().unwrap());
    for entry in &evhi::study::STUDIES {
        assert!(help.contains(entry.name), "lacks {}: {help}", entry.name);
    }
    let help = stdout(&evhi_with("study convergence --help").output().unwrap());
    assert_contains(&help, &["--quick", "singular"]);
}

/// `evhi study time` and `evhi study stability --quick` on user scenario files: each
/// writes its directory with finite errors and orders, the map's outcomes, and the
/// hypotheses per level; a steady scenario has no time study.
#[test]
fn the_time_and_stability_studies_run_on_user_scenarios() {
    let dir = scratch("studies");
    for (name, file) in [("five", FIVE), ("cantilever", CANTILEVER)] {
        let out = dir.join(format!("time-{name}"));
        succeed(&mut study("time", file, &out));
        let files = ["time_study.csv", "time_study.md", "time_study.png"];
        assert_files(&out, name, &files);
        assert_files(&out, name, &["time_study.svg", "scenario.toml"]);
        let time = Csv::read(out.join("time_study.csv"));
        assert_eq!(time.len(), 7, "{name}: N = 4 … 256");
        for (i, r) in time.rows().iter().enumerate() {
            let e = time.f64(i, "rel_err_max_percent");
            assert!(e.is_finite() && e > 0.0, "{name}: {r:?}");
            assert_eq!(time.f64(i, "order_T").is_finite(), i > 0, "{name}: {r:?}");
        }
        let out = dir.join(format!("stab-{name}"));
        succeed(&mut study("stability", file, &out));
        let files = ["stability.csv", "hypotheses.csv", "stability.md"];
        assert_files(&out, name, &files);
        assert_files(&out, name, &["stability.png", "scenario.toml"]);
        let stab = Csv::read(out.join("stability.csv"));
        assert!(!stab.is_empty());
        // Newton, the default, is certified on both examples at every cell.
        for (i, r) in stab.rows().iter().enumerate() {
            if stab.get(i, "solver") == "newton" {
                assert_eq!(stab.get(i, "outcome"), "certified", "{name}: {r:?}");
            }
        }
        // A study's directory is a run directory: rerunning into it replaces its set,
        // while a file of the user's in it is refused by name and kept.
        let rerun = || study("stability", file, &out).output().unwrap();
        if name == "cantilever" {
            ok(&rerun());
            std::fs::write(out.join("my_notes.txt"), "mine").unwrap();
            failed_with(&rerun(), "`my_notes.txt`");
            assert!(out.join("my_notes.txt").exists() && out.join("stability.csv").exists());
        }
        let hyp = Csv::read(out.join("hypotheses.csv"));
        assert_eq!(hyp.len(), 4, "{name}: two levels, two step counts");
        // The cantilever's law jumps down: H(j) fails, so H(s) does not apply and
        // the steps are not convex whatever the curvature between the jumps.
        for (i, r) in hyp.rows().iter().enumerate() {
            let (hs, convex) = (hyp.get(i, "H_s"), hyp.get(i, "steps_convex"));
            if name == "cantilever" {
                assert_eq!((hs, convex), ("n/a (H(j) fails)", "no (downward jump)"));
            } else {
                assert!(hs == "holds" || hs == "fails", "{r:?}");
                assert!(convex == "yes" || convex == "no", "{r:?}");
            }
        }
    }
    let steady = written(dir.join("steady.toml"), cantilever_as("steady"));
    let o = study("time", &steady, &dir.join("refused"))
        .output()
        .unwrap();
    refused(&o, &["`scenario`", "one solve at T"]);
    // An elastic scenario has no time error either: refused by name.
    let elastic = written(dir.join("elastic.toml"), cantilever_as("elastic"));
    let o = study("time", &elastic, &dir.join("refused-elastic"))
        .output()
        .unwrap();
    let err = failed(&o);
    assert_contains(&err, &["`scenario`", "elastic", "no time error", "f(t_n)"]);
}

/// `reproduce --jobs N` gives the same files whatever N: one worker, and more workers
/// than experiments, write byte-identical tables and figures (quick mode, a set
/// whose experiments run threads of their own, table1 among them); `--jobs 0` is
/// refused by name.
#[test]
fn reproduce_writes_the_same_files_whatever_the_jobs() {
    let dir = scratch("jobs");
    let experiments = "hypotheses fig2 fig3 table1 graded time";
    // The same relative directories, so that the provenance lines, which name them,
    // are the same too.
    for jobs in ["1", "8"] {
        std::fs::create_dir_all(dir.join(jobs)).unwrap();
        let words = format!("--quick -q --jobs {jobs} {experiments}");
        succeed(
            reproduce_into(&words, Path::new("data"), Path::new("figures"))
                .current_dir(dir.join(jobs)),
        );
    }
    let mut compared = 0;
    for sub in ["data", "figures"] {
        let mut files = names(&dir.join("1").join(sub));
        files.sort();
        for f in files {
            let a = std::fs::read(dir.join("1").join(sub).join(&f)).unwrap();
            let b = std::fs::read(dir.join("8").join(sub).join(&f))
                .unwrap_or_else(|e| panic!("{f:?} with --jobs 8: {e}"));
            assert!(a == b, "{sub}/{f:?} differs between --jobs 1 and --jobs 8");
            compared += 1;
        }
    }
    assert!(compared > 20, "only {compared} files compared");
    let o = evhi_with("reproduce fig2 --quick --jobs 0 --data")
        .arg(dir.join("zero"))
        .output();
    assert!(failed(&o.unwrap()).contains("`jobs`"));
}

/// A grading whose smallest triangles double precision cannot resolve is refused by
/// name, with the least grading the level allows, before any mesh is built (it used to
/// refine until memory ran out); a grading at that bound runs.
#[test]
fn a_grading_finer_than_double_precision_is_refused_by_name() {
    let dir = scratch("grading");
    let run = |mu: &str| {
        let words = format!("--mesh graded --grading {mu} --n 32 --steps 2");
        solve("figure", &words, &dir.join(format!("g{mu}")))
            .output()
            .unwrap()
    };
    refused(&run("0.05"), &["`--grading`", "at least 0.088 at n = 32"]);
    assert!(!dir.join("g0.05").exists());
    ok(&run("0.088"));
}

/// A Gamma_3 whose nodes the supports all hold (at this n) is refused by name, with the
/// nodes and what to change; it used to panic while setting up the output. One level
/// finer, a free node appears and the run goes.
#[test]
fn a_gamma3_without_a_free_node_is_refused_by_name() {
    let dir = scratch("gamma3-held");
    let text = format!(
        "{}\n[geometry]\ncontact = [1.0, 1.25]\n[geometry.supports]\nbottom = [\
         {{from = 0.0, to = 1.0, kind = \"clamped\"}}, \
         {{from = 1.25, to = 2.0, kind = \"clamped\"}}]\n",
        read(FIGURE)
    );
    let run = |n: &str| solve_text(&dir, &format!("run{n}"), &text, &["--n", n, "--steps", "2"]).0;
    refused(
        &run("8"),
        &["`geometry.contact`", "(x = 1, 1.25) are all held"],
    );
    ok(&run("16"));
}

/// A step count out of range is refused before anything is sized by it (a table of
/// 4e12 flags used to be allocated first: the process was killed, without a word).
#[test]
fn a_huge_step_count_is_refused_before_any_allocation() {
    let dir = scratch("huge-steps");
    let o = solve("figure", "--n 4 --steps 4000000000000", &dir.join("run")).output();
    refused(&o.unwrap(), &["`--steps`", "an integer in 1..=1000000"]);
}

/// `plot` refuses a summary or a nodes table that does not describe the run (g NaN,
/// n NaN or not matching the nodes, the nodes cut short) by name, and leaves no
/// temporary figure behind; each used to panic in a drawing thread, or to draw the
/// wrong mesh. A graded run's triangles must name nodes of its nodes table.
#[test]
fn plot_refuses_a_summary_or_lattice_that_does_not_fit() {
    let dir = scratch("plot-summary");
    let out = dir.join("run");
    succeed(&mut small_solve(&out));
    let edit = |file: &str, column: &str, value: &str| {
        let text = read(out.join(file));
        let lines: Vec<&str> = text.lines().collect();
        let cols: Vec<&str> = lines[2].split(',').collect();
        let at = cols.iter().position(|c| *c == column).unwrap();
        let mut row: Vec<&str> = lines[3].split(',').collect();
        row[at] = value;
        let mut all: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        all[3] = row.join(",");
        all.join("\n") + "\n"
    };
    let summary = read(out.join("summary.csv"));
    let nodes = read(out.join("nodes.csv"));
    let cut: String = nodes.lines().take(4).map(|l| format!("{l}\n")).collect();
    for (file, text, expect) in [
        (
            "summary.csv",
            edit("summary.csv", "g", "NaN"),
            "column `g` holds `NaN`",
        ),
        (
            "summary.csv",
            edit("summary.csv", "n", "NaN"),
            "column `n` holds `NaN`",
        ),
        (
            "summary.csv",
            edit("summary.csv", "n", "16"),
            "not a lattice of rows of 17",
        ),
        ("nodes.csv", cut, "1 node(s) are not a lattice"),
    ] {
        std::fs::write(out.join(file), &text).unwrap();
        let o = plot(&out);
        let err = stderr(&o);
        assert!(!o.status.success(), "{expect}: drawn");
        assert!(err.contains(expect) && !err.contains("panicked"), "{err}");
        let leftovers: Vec<String> = names(&out)
            .into_iter()
            .filter(|f| f.contains(".tmp-"))
            .collect();
        assert!(leftovers.is_empty(), "{leftovers:?}");
        std::fs::write(out.join("summary.csv"), &summary).unwrap();
        std::fs::write(out.join("nodes.csv"), &nodes).unwrap();
    }
    ok(&plot(&out));

    let graded = dir.join("graded");
    succeed(small_solve(&graded).args(["--mesh", "graded"]));
    let tri = read(graded.join("triangles.csv"));
    let lines: Vec<&str> = tri.lines().collect();
    let data = lines.iter().position(|l| !l.starts_with('#')).unwrap() + 1;
    for bad in ["NaN", "-5", "1.5"] {
        let mut row: Vec<&str> = lines[data].split(',').collect();
        row[0] = bad;
        let mut all: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        all[data] = row.join(",");
        std::fs::write(graded.join("triangles.csv"), all.join("\n") + "\n").unwrap();
        let o = plot(&graded);
        let err = stderr(&o);
        assert!(!o.status.success(), "{bad}: drawn");
        assert!(err.contains("not three node numbers"), "{err}");
    }
}

/// `text`, a table as evhi writes it, with the row at `line` (from 1, as an error
/// names it) holding `value` in `column`, for each of `edits`.
fn with_cells(text: &str, line: usize, edits: &[(&str, &str)]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let header = lines.iter().find(|l| !l.starts_with('#')).unwrap().clone();
    let cols: Vec<&str> = header.split(',').collect();
    let mut row: Vec<String> = lines[line - 1].split(',').map(str::to_string).collect();
    for (column, value) in edits {
        let at = cols.iter().position(|c| c == column).unwrap();
        row[at] = value.to_string();
    }
    lines[line - 1] = row.join(",");
    lines.join("\n") + "\n"
}

/// `text` without its column `column`.
fn without_column(text: &str, column: &str) -> String {
    let header = text.lines().find(|l| !l.starts_with('#')).unwrap();
    let at = header.split(',').position(|c| c == column).unwrap();
    let lines: Vec<String> = (text.lines())
        .map(|l| {
            if l.starts_with('#') {
                return l.to_string();
            }
            let mut f: Vec<&str> = l.split(',').collect();
            f.remove(at);
            f.join(",")
        })
        .collect();
    lines.join("\n") + "\n"
}

/// What the table library advises its Python users, which no message of ours repeats.
const POLARS_ADVICE: [&str; 4] = [
    "truncate_ragged_lines",
    "infer_schema_length",
    "ignore_errors",
    "schema_overrides",
];

/// `plot` checks what its titles claim against the run's own tables: a summary that
/// says n = 128 (and h = 1/128) on a run of n = 64 drew it titled "h = 1/128"; n, h and
/// steps are now checked against the contact nodes, the body's width and the steps
/// recorded, and the figures are left as they were (issue 47, case 7). A graded run's
/// nodes do not give its n: its h and steps are checked.
#[test]
fn plot_refuses_a_summary_that_the_runs_tables_contradict() {
    let dir = scratch("plot-claims");
    let out = dir.join("run");
    succeed(&mut solve("figure", "--n 64 --steps 2", &out));
    let summary = read(out.join("summary.csv"));
    let before = snapshot(&out);
    for (edits, needles) in [
        (
            &[("n", "128"), ("h", "0.0078125")][..],
            &["summary.csv:4", "column `n` holds `128`", "makes n = 64"][..],
        ),
        (
            &[("n", "32"), ("h", "0.03125")][..],
            &["summary.csv:4", "column `n` holds `32`", "makes n = 64"][..],
        ),
        (
            &[("h", "0.0078125")][..],
            &["column `h` holds `0.0078125`", "h = W/(2n) = 0.015625"][..],
        ),
        (
            &[("steps", "3")][..],
            &["column `steps` holds `3`", "regimes.csv records 2 step(s)"][..],
        ),
        // The limit line of evolution.png (round four's re-run drew it where the
        // edited summary said).
        (
            &[("g", "0.2")][..],
            &[
                "column `g` holds `0.2`",
                "contact.csv, written by the same run, states g = 0.1",
            ][..],
        ),
        (
            &[("g", "inf")][..],
            &["column `g` holds `inf`", "states g = 0.1"][..],
        ),
    ] {
        std::fs::write(out.join("summary.csv"), with_cells(&summary, 4, edits)).unwrap();
        refused(&plot(&out), needles);
        std::fs::write(out.join("summary.csv"), &summary).unwrap();
        assert!(
            snapshot(&out) == before,
            "{edits:?}: the run directory changed"
        );
    }
    ok(&plot(&out));
    // Without the stated g, the contact nodes still bound it from below.
    let contact = read(out.join("contact.csv"));
    let unstated = contact.replace("; g = 0.1;", ";");
    assert_ne!(unstated, contact);
    std::fs::write(out.join("contact.csv"), unstated).unwrap();
    let low = with_cells(&summary, 4, &[("g", "0.001")]);
    std::fs::write(out.join("summary.csv"), low).unwrap();
    refused(&plot(&out), &["column `g` holds `0.001`", "above it"]);
    std::fs::write(out.join("summary.csv"), &summary).unwrap();
    std::fs::write(out.join("contact.csv"), contact).unwrap();
    ok(&plot(&out));

    // A graded run of a level that is no power of two: its nodes do not give n, and
    // what they give is not refused.
    let graded = dir.join("graded");
    succeed(solve("figure", "--n 24 --steps 2", &graded).args(["--mesh", "graded"]));
    ok(&plot(&graded));
    // But its n and h edited together (round five: drawn) are refused: the scene's
    // graded mesh of that n has other nodes.
    let summary = read(graded.join("summary.csv"));
    let h: f64 = Csv::parse(&summary).column_f64("h")[0];
    let h2 = (h / 2.0).to_string();
    let edited = with_cells(&summary, 4, &[("n", "48"), ("h", &h2)]);
    std::fs::write(graded.join("summary.csv"), edited).unwrap();
    refused(&plot(&graded), &["column `n` holds `48`", "nodes.csv has"]);
    std::fs::write(graded.join("summary.csv"), &summary).unwrap();
    ok(&plot(&graded));
}

/// `plot` of what is not a run directory says so, and names no flag it does not have
/// (round four's re-run: `plot .` gave a raw "i/o on ./contact.csv"); the staging
/// directory of a `solve` at work is refused, for it is under that run's lock, not its
/// own (1 in 184 plots during a solve wrote into it).
#[test]
fn plot_says_what_is_not_a_run_directory() {
    let dir = scratch("plot-not-a-run");
    let file = written(dir.join("file.txt"), "x");
    let staging = dir.join(".run.staging-4242");
    std::fs::create_dir_all(&staging).unwrap();
    for (path, needles) in [
        (
            dir.to_path_buf(),
            &["not a run directory: it has no summary.csv"][..],
        ),
        (dir.join("missing"), &["no such directory"][..]),
        (file, &["not a directory"][..]),
        (
            staging,
            &["the staging directory of a `solve` writing `run`"][..],
        ),
    ] {
        let err = refused(&plot(&path), needles);
        assert!(!err.contains("--out"), "{err}");
        assert!(!err.contains("i/o on"), "{err}");
    }
}

/// An edited table is refused in our words, by file, line and column: a ragged
/// `summary.csv` passed on the table library's advice to its Python users (issue 47,
/// case 12), and a missing column named the column where the file should stand
/// ("table a: not found", case 13).
#[test]
fn plot_names_the_file_line_and_column_of_an_edited_table() {
    let dir = scratch("plot-ragged");
    let out = dir.join("run");
    succeed(&mut small_solve(&out));
    let summary = read(out.join("summary.csv"));
    let lines: Vec<&str> = summary.lines().collect();
    let cols = lines[2].split(',').count();
    let last = lines[2].split(',').next_back().unwrap();
    let longer = format!("{},extra\n", lines[..4].join("\n"));
    let shorter = format!("{}\n", lines[..4].join("\n").rsplit_once(',').unwrap().0);
    let before = snapshot(&out);
    for (text, needles) in [
        (
            longer,
            vec![
                "summary.csv:4".to_string(),
                format!("{} fields where the header (line 3) has {cols}", cols + 1),
                "`extra`, has no column".into(),
            ],
        ),
        (
            shorter,
            vec![
                "summary.csv:4".to_string(),
                format!("{} fields where the header (line 3) has {cols}", cols - 1),
                format!("column `{last}` (field {cols}) has no value"),
            ],
        ),
    ] {
        std::fs::write(out.join("summary.csv"), text).unwrap();
        let needles: Vec<&str> = needles.iter().map(String::as_str).collect();
        let err = refused(&plot(&out), &needles);
        for advice in POLARS_ADVICE {
            assert!(!err.contains(advice), "{err}");
        }
    }
    std::fs::write(out.join("summary.csv"), &summary).unwrap();
    assert!(snapshot(&out) == before, "the run directory changed");

    let graded = dir.join("graded");
    succeed(small_solve(&graded).args(["--mesh", "graded"]));
    let triangles = read(graded.join("triangles.csv"));
    std::fs::write(
        graded.join("triangles.csv"),
        without_column(&triangles, "a"),
    )
    .unwrap();
    let err = refused(
        &plot(&graded),
        &[
            "triangles.csv:3",
            "no column `a`",
            "the header has `b`, `c`",
        ],
    );
    assert!(!err.contains("table a:"), "{err}");
}

/// The bench's tables `bench --from-csv` reads, as committed.
const BENCH_TABLES: [&str; 9] = [
    "bench.csv",
    "bench_mesh.csv",
    "bench_mesh_solve.csv",
    "work_precision.csv",
    "bench_solvers.csv",
    "bench_scipy.csv",
    "bench_sweeps.csv",
    "bench_vs_paper.csv",
    "table1_reference_error.csv",
];

/// `evhi bench --from-csv --data DIR/data --figures DIR/figures`, run with a time limit.
fn from_csv(dir: &Path) -> Output {
    let mut cmd = evhi_with("bench --from-csv --data");
    cmd.arg(dir.join("data"))
        .arg("--figures")
        .arg(dir.join("figures"));
    output_within(&mut cmd, 120)
}

/// `bench --from-csv` trusted its tables: a time of 0 spun for ten minutes and NaN
/// allocated until the kernel killed it (issue 47, case 3); NaN, 0 or negative times
/// became NaN, inf or -133 in bench_vs_paper.csv, negative dofs 0, n = 128.4 counted
/// as 128, an unknown loop and a repeated row passed, and garbage was rendered into
/// Markdown (case 5); a ragged table passed on the table library's advice (case 12)
/// and a missing column was named where the file should be (case 13). Each is now
/// refused by file, line, column and value, at once, with nothing written; the
/// committed tables still render byte for byte.
#[test]
fn bench_from_csv_refuses_tables_the_bench_cannot_have_written() {
    let dir = scratch("bench-from-csv");
    let data = dir.join("data");
    std::fs::create_dir_all(&data).unwrap();
    for f in BENCH_TABLES.iter().chain([&".evhi-outputs"]) {
        std::fs::copy(Path::new("data").join(f), data.join(f)).unwrap();
    }
    ok(&from_csv(&dir));
    for f in [
        "bench_vs_paper.csv",
        "bench_vs_paper.md",
        "bench.md",
        "bench_solvers.md",
    ] {
        assert_eq!(read(data.join(f)), read(Path::new("data").join(f)), "{f}");
    }
    let before = snapshot(&dir);
    let wp = read(data.join("work_precision.csv"));
    let bench = read(data.join("bench.csv"));
    let lines: Vec<&str> = bench.lines().collect();
    let repeated = format!("{}\n{}\n", lines[..8].join("\n"), lines[7..].join("\n"));
    let cell = |file: &str, line: usize, column: &str, value: &str| {
        let text = if file == "bench.csv" { &bench } else { &wp };
        with_cells(text, line, &[(column, value)]).into_bytes()
    };
    // Each case: the file, its text, and what the refusal says.
    let mut cases: Vec<(&str, Vec<u8>, Vec<String>)> = vec![];
    for (file, line, column, value, allowed) in [
        (
            "work_precision.csv",
            4,
            "wall_s",
            "0",
            "a time in seconds from 1e-9 to 1e6",
        ),
        (
            "work_precision.csv",
            5,
            "wall_s",
            "NaN",
            "a time in seconds from 1e-9 to 1e6",
        ),
        // A subnormal time spun for hours in the chart's axis (round four's re-run).
        (
            "work_precision.csv",
            4,
            "wall_s",
            "1e-310",
            "a time in seconds from 1e-9 to 1e6",
        ),
        (
            "work_precision.csv",
            6,
            "rel_err_max_percent",
            "1e-310",
            "at least 2.2e-308",
        ),
        (
            "work_precision.csv",
            6,
            "rel_err_max_percent",
            "-1",
            "a finite number > 0",
        ),
        (
            "work_precision.csv",
            5,
            "steps",
            "256",
            "the family `h` has steps = 512",
        ),
        (
            "bench.csv",
            8,
            "wall_s",
            "0",
            "a time in seconds from 1e-9 to 1e6",
        ),
        (
            "bench.csv",
            8,
            "wall_s",
            "NaN",
            "a time in seconds from 1e-9 to 1e6",
        ),
        (
            "bench.csv",
            9,
            "wall_s",
            "-0.005",
            "a time in seconds from 1e-9 to 1e6",
        ),
        (
            "bench.csv",
            8,
            "wall_s",
            "1e-310",
            "a time in seconds from 1e-9 to 1e6",
        ),
        (
            "bench.csv",
            8,
            "wall_s",
            "1e308",
            "a time in seconds from 1e-9 to 1e6",
        ),
        ("bench.csv", 8, "dofs", "16000", "has 16638 free unknowns"),
        ("bench.csv", 8, "dofs", "-16638", "a whole number >= 1"),
        ("bench.csv", 8, "n", "128.4", "a whole number >= 1"),
        ("bench.csv", 8, "path", "sideways", "`general` or `reduced`"),
    ] {
        let at = format!("{file}:{line}");
        let holds = format!("column `{column}` holds `{value}`");
        let text = cell(file, line, column, value);
        cases.push((file, text, vec![at, holds, allowed.into()]));
    }
    let garbage = b"n,solver,wall_s\n16,new\0ton\x01,0.1\n".to_vec();
    let header_only = |text: &str| -> Vec<u8> {
        let header = text.lines().take_while(|l| l.starts_with('#')).count() + 1;
        let kept: Vec<&str> = text.lines().take(header).collect();
        (kept.join("\n") + "\n").into_bytes()
    };
    let solvers = read(data.join("bench_solvers.csv"));
    let mut ragged = wp.lines().map(str::to_string).collect::<Vec<_>>();
    ragged[5].push_str(",7");
    for (file, text, needles) in [
        (
            "bench.csv",
            repeated.into_bytes(),
            vec!["bench.csv:9", "line 8 has it"],
        ),
        (
            "bench_solvers.csv",
            garbage,
            vec!["bench_solvers.csv:2", "U+0000"],
        ),
        (
            "bench.csv",
            header_only(&bench),
            vec!["bench.csv", "a header and no data row"],
        ),
        (
            "bench_solvers.csv",
            header_only(&solvers),
            vec!["bench_solvers.csv", "a header and no data row"],
        ),
        (
            "bench_solvers.csv",
            b"\xff\xfe\x00garbage\n".to_vec(),
            vec!["bench_solvers.csv:1", "not UTF-8"],
        ),
        (
            "work_precision.csv",
            (ragged.join("\n") + "\n").into_bytes(),
            vec![
                "work_precision.csv:6",
                "7 fields where the header (line 3) has 6",
            ],
        ),
        (
            "work_precision.csv",
            without_column(&wp, "wall_s").into_bytes(),
            vec!["work_precision.csv:3", "no column `wall_s`"],
        ),
        (
            "bench.csv",
            without_column(&bench, "dofs").into_bytes(),
            vec!["bench.csv:3", "no column `dofs`"],
        ),
    ] {
        cases.push((
            file,
            text,
            needles.into_iter().map(str::to_string).collect(),
        ));
    }
    // The mesh's own error, which the work-precision chart draws as a floor, is a
    // percentage: 1e300 was accepted and drawn (round five).
    let refe = read(data.join("table1_reference_error.csv"));
    let figure_line = 1 + refe.lines().position(|l| l.starts_with("figure,")).unwrap();
    for value in ["1e300", "150", "0"] {
        cases.push((
            "table1_reference_error.csv",
            with_cells(
                &refe,
                figure_line,
                &[("reference_error_orthogonal_percent", value)],
            )
            .into_bytes(),
            vec![
                format!("table1_reference_error.csv:{figure_line}"),
                format!("column `reference_error_orthogonal_percent` holds `{value}`"),
                "a percentage > 0 and at most 100".into(),
            ],
        ));
    }
    for (file, text, needles) in cases {
        let original = std::fs::read(data.join(file)).unwrap();
        std::fs::write(data.join(file), &text).unwrap();
        let needles: Vec<&str> = needles.iter().map(String::as_str).collect();
        let err = refused(&from_csv(&dir), &needles);
        for advice in POLARS_ADVICE {
            assert!(!err.contains(advice), "{err}");
        }
        std::fs::write(data.join(file), original).unwrap();
        assert!(
            snapshot(&dir) == before,
            "{needles:?}: a file was written or changed"
        );
    }
    ok(&from_csv(&dir));
}

/// `bench` writes its tables and figures under fixed names into --data and
/// --figures: a directory holding files evhi did not write is refused before
/// anything is read or written, as `reproduce` refuses it (round four's re-run found
/// `bench --from-csv --figures DIR` replacing a user's `work_precision.png`).
#[test]
fn bench_refuses_a_foreign_output_directory() {
    let dir = scratch("bench-foreign");
    let data = dir.join("data");
    let figures = dir.join("figures");
    std::fs::create_dir_all(&data).unwrap();
    std::fs::create_dir_all(&figures).unwrap();
    for f in BENCH_TABLES.iter().chain([&".evhi-outputs"]) {
        std::fs::copy(Path::new("data").join(f), data.join(f)).unwrap();
    }
    std::fs::write(figures.join("work_precision.png"), "the user's own").unwrap();
    let before = snapshot(&dir);
    refused(
        &from_csv(&dir),
        &[
            "figures",
            "holds files evhi did not write",
            "work_precision.png",
        ],
    );
    assert!(snapshot(&dir) == before, "a file was written or changed");
    // Without the mark, the data directory is refused as well.
    std::fs::remove_file(figures.join("work_precision.png")).unwrap();
    std::fs::remove_file(data.join(".evhi-outputs")).unwrap();
    let before = snapshot(&dir);
    refused(
        &from_csv(&dir),
        &["`--data`", "holds files evhi did not write"],
    );
    assert!(snapshot(&dir) == before, "a file was written or changed");
}

/// An absurd n is refused by the memory guard (the integer count of unknowns used to
/// wrap and let n = 5643117386039700 pass `show`), with the need in readable units.
#[test]
fn an_absurd_n_is_refused_by_the_memory_guard() {
    for cmd in [
        "show figure --n 5643117386039700",
        "show figure --n 4294967296",
    ] {
        let o = evhi_with(cmd).output().unwrap();
        let err = stderr(&o);
        assert!(!o.status.success(), "{cmd:?} passed");
        assert_contains(&err, &["`--n`", "fits in memory", "e"]);
    }
}

/// Smaller messages the audit found wrong: `plot .` inside a run directory draws (it
/// was refused as `--out .`); a negative `--certificate-tol` reaches the range check
/// (clap took it for a flag); `show` checks a steady scenario at its one step, as
/// `solve` runs it, and refuses more; and a law that jumps down has no finite m, so
/// the summary writes NaN (not 0) and `show` prints no value for it.
#[test]
fn the_audits_smaller_messages_say_what_holds() {
    let dir = scratch("audit-messages");
    let out = dir.join("run");
    succeed(&mut small_solve(&out));
    succeed(evhi().arg("plot").arg(".").current_dir(&out));
    let mut cmd = small_solve(&dir.join("neg"));
    let err = stderr(&cmd.args(["--certificate-tol", "-1e-10"]).output().unwrap());
    assert_contains(&err, &["`--certificate-tol`", "[1e-15, 1e-4]"]);

    let steady: String = read(FIGURE)
        .lines()
        .filter(|l| !l.starts_with("alpha") && !l.starts_with("beta"))
        .map(|l| {
            if l.starts_with("g = ") {
                format!("{l}\nproblem = \"steady\"\n")
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    let file = written(dir.join("steady.toml"), steady);
    let o = show(&file, "--n 8");
    ok(&o);
    assert!(stdout(&o).contains("steps = 1)"));
    assert!(failed(&show(&file, "--n 8 --steps 4")).contains("`--steps`"));

    let shown = stdout(&show(CANTILEVER, ""));
    assert!(!shown.contains("H(j): constant m"), "{shown}");
    let run = dir.join("cantilever");
    succeed(&mut solve(CANTILEVER, "--n 8 --steps 2", &run));
    assert!(summary(&run).m_trace_norm_sq.is_nan());
}

/// What the second audit found in the studies and `reproduce`, each refused by name
/// before any work or output: a scene whose study reference would exceed the largest
/// mesh (it refined until an allocation failed), a scene with no load (its tables were
/// all NaN with exit 0), another cell pattern (ignored, or failing late), a scene no
/// level up to 256 resolves (the advice named an n the study does not take).
#[test]
fn studies_refuse_what_they_cannot_measure() {
    let dir = scratch("study-refusals");
    let cantilever = read(CANTILEVER);
    let figure = read(FIGURE);
    let zero = figure
        .replacen("f0 = [0.0, -5.0]", "f0 = [0.0, 0.0]", 1)
        .replacen("f2 = [0.0, -75.0]", "f2 = [0.0, 0.0]", 1);
    let cases = [
        (
            "fine.toml",
            cantilever.replacen("from = 1.0", "from = 1.0078125", 1),
            "convergence",
            "the reference would be at n = 8192",
        ),
        (
            "third.toml",
            // 0.3 would do now (a grid of 20 resolves it): no grid up to 256 has a
            // node at 0.3333333.
            cantilever.replacen("from = 1.0", "from = 0.3333333", 1),
            "convergence",
            "it takes no --n",
        ),
        ("zero.toml", zero.clone(), "convergence", "is not zero"),
        ("zero.toml", zero, "time", "is not zero"),
        (
            "criss.toml",
            format!("{figure}\n[geometry]\npattern = \"crisscross\"\n"),
            "convergence",
            "`geometry.pattern`",
        ),
    ];
    for (i, (file, text, kind, expect)) in cases.iter().enumerate() {
        let path = written(dir.join(format!("{i}-{file}")), text);
        let out = dir.join(format!("out{i}"));
        let o = study(kind, &path, &out).output().unwrap();
        let err = stderr(&o);
        assert!(!o.status.success(), "{file} {kind} passed");
        assert!(err.contains(expect) && !err.contains("panicked"), "{err}");
        assert!(!out.join("convergence.csv").exists() && !out.join("time_study.csv").exists());
    }
}

/// `reproduce` refuses what it would ignore or fail on late, before it makes a
/// directory: `--jobs 0`, `--record-times --quick`, `--reference` without Table 1, a
/// `--data` or `--figures` path that is a file (named by its option), and a finer
/// reference with no table1.csv to compare with (it used to compute and write
/// table1_ref64.csv first). The finer reference's shift names the reference it
/// shifts from (the quick one is 1/32, not the paper's 1/512).
#[test]
fn reproduce_refuses_before_it_writes() {
    let dir = scratch("reproduce-refusals");
    let (data, figures) = (dir.join("data"), dir.join("figures"));
    let file = written(dir.join("a-file"), "x");
    let run = |extra: &str, data: &Path, figures: &Path| {
        let words = format!("--quick -q {extra}");
        reproduce_into(&words, data, figures).output().unwrap()
    };
    for (extra, expect) in [
        ("fig2 --jobs 0", "`jobs`"),
        ("fig2 --record-times", "`record-times`"),
        ("fig2 --reference 64", "`reference`"),
    ] {
        let o = run(extra, &data, &figures);
        let err = stderr(&o);
        assert!(
            !o.status.success() && err.contains(expect),
            "{extra:?}: {err}"
        );
        assert!(
            !data.exists() && !figures.exists(),
            "{extra:?} made a directory"
        );
    }
    for (d, f, expect) in [(&file, &figures, "`--data`"), (&data, &file, "`--figures`")] {
        failed_with(&run("fig2", d, f), expect);
    }
    let _ = std::fs::remove_dir_all(&data);
    failed_with(&run("table1 --reference 64", &data, &figures), "missing");
    assert!(!data.join("table1_ref64.csv").exists());
    ok(&run("table1", &data, &figures));
    ok(&run("table1 --reference 64", &data, &figures));
    let shift = read(data.join("table1_reference_shift_ref64.csv"));
    assert!(
        shift.contains("(reference h = k = 1/32)") && shift.contains("rel_err_T_percent_ref32")
    );
}

/// The worked example runs from any working directory (its studies read the compiled-in
/// scenario, not a path relative to the repository), and removes its scratch directory
/// and the locks beside its run directories when done.
#[test]
fn the_example_runs_anywhere_and_leaves_nothing_in_tmp() {
    let dir = scratch("example-anywhere");
    let child = reproduce("--quick -q example", &dir)
        .current_dir(&dir)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id().to_string();
    ok(&child.wait_with_output().unwrap());
    assert!(dir.join("data/example_study_convergence.md").exists());
    let left: Vec<String> = names(&std::env::temp_dir())
        .into_iter()
        .filter(|f| f.contains("evhi-example") && f.contains(&pid))
        .collect();
    assert!(left.is_empty(), "{left:?}");
}

/// A solver that cannot take the scenario's law is refused by name before any step
/// (`solve`), and the stability study lists it as a run that did not start (`error:`,
/// as its legend says) instead of a failed first step with a debug dump of the status.
/// A scene without singular points has no graded family, and its convergence table
/// says so (its header used to list graded levels and a graded reference).
#[test]
fn declined_solvers_and_absent_families_are_said_as_they_are() {
    let dir = scratch("declined");
    let softening = "data/scenarios/examples/softening.toml";
    let words = "--solver convexify --n 8 --steps 2";
    let o = solve(softening, words, &dir.join("run")).output().unwrap();
    refused(&o, &["`solver`", "piecewise-affine"]);
    let out = dir.join("stability");
    succeed(&mut study("stability", softening, &out));
    let table = read(out.join("stability.csv"));
    assert!(!table.contains("Failed("), "{table}");
    let rows: Vec<&str> = table
        .lines()
        .filter(|l| l.contains(",convexify,") || l.contains(",penalty,"))
        .collect();
    assert!(!rows.is_empty());
    assert!(rows.iter().all(|r| r.contains("\"error: ")), "{rows:?}");

    let smooth = dir.join("smooth");
    succeed(&mut study("convergence", "smooth", &smooth));
    let csv = read(smooth.join("convergence.csv"));
    let header: String = csv.lines().take(2).collect();
    assert!(
        header.contains("families: uniform;")
            && header.contains("reference: the uniform family")
            && !header.contains("graded"),
        "{header}"
    );
}

/// The step records count against memory too: a million steps (about 4 GB of records)
/// under a 3 GB address-space limit are refused by name, where the run used to abort
/// in an allocation.
#[test]
fn step_records_that_cannot_fit_are_refused() {
    let dir = scratch("step-records");
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 3000000 && exec '{}' solve --scenario figure --n 4 --steps 1000000 --out '{}'",
            env!("CARGO_BIN_EXE_evhi"),
            dir.join("run").display()
        ))
        .output()
        .unwrap();
    refused(&o, &["`--steps`", "records fit in memory"]);
}

/// The time study's table says what its NaN and inf mean where a scene has them (the
/// cantilever: no single relaxation time, no limit g), and the convergence summary of
/// a scene whose singular points all lack a computed exponent calls the limit of the
/// uniform orders unknown instead of 1.
#[test]
fn tables_say_what_their_nan_and_inf_mean() {
    let dir = scratch("nan-legends");
    let out = dir.join("time");
    succeed(&mut study("time", CANTILEVER, &out));
    let csv = read(out.join("time_study.csv"));
    let legend = csv.lines().nth(1).unwrap();
    assert_contains(
        legend,
        &["NaN where C is not a multiple of G", "g = inf: no limit"],
    );
    // Rollers on the upper halves of both sides and on the top: the singular points
    // are where rollers end, whose exponent the wedge analysis does not give.
    let text = read(FIGURE).replacen("f2 = [0.0, -75.0]", "f2 = [0.0, 0.0]", 1);
    let text = format!(
        "{text}\n[geometry.supports]\nleft = [{{from = 0.5, to = 1.0, kind = \"rollers\"}}]\n\
         right = [{{from = 0.5, to = 1.0, kind = \"rollers\"}}]\ntop = \"rollers\"\n"
    );
    let file = written(dir.join("rollers.toml"), text);
    let out = dir.join("conv");
    ok(&study("convergence", &file, &out).output().unwrap());
    let md = read(out.join("convergence.md"));
    assert!(md.contains("(not known here:"), "{md}");
}

/// What a third audit (the docs against the outputs) found wrong in the run
/// directory: `h` in summary.csv is the book's W/(2n) (it was 1/n whatever the
/// width), and a uniform run's lattice in nodes.csv keeps the mesh's last column and
/// row whatever n (a stride of n/32 alone left them out for n = 100), and is drawn.
#[test]
fn the_run_directory_holds_what_the_book_says() {
    let dir = scratch("run-as-documented");
    let wide = format!("{}\n[geometry]\nwidth = 4.0\n", read(FIGURE));
    let (o, out) = solve_text(&dir, "wide", &wide, &["--n", "16", "--steps", "2"]);
    ok(&o);
    assert_eq!(summary(&out).h, 4.0 / 32.0);

    let out = dir.join("n100");
    succeed(&mut solve("figure", "--n 100 --steps 2", &out));
    let nodes = Csv::read(out.join("nodes.csv"));
    let (x, y) = (nodes.column_f64("x"), nodes.column_f64("y"));
    let top = |v: &[f64]| v.iter().copied().fold(f64::MIN, f64::max);
    assert_eq!((top(&x), top(&y)), (2.0, 1.0));
    ok(&plot(&out));
}

/// The H(f) warning names the traction that breaks it (it blamed `f2` when f2 = (0, 0)
/// and only a `[[loads.traction]]` was loaded), and a steady or elastic problem, which
/// has no evolution from u0 = 0, prints none (issue 41, items 10 and 13).
#[test]
fn the_h_f_warning_names_its_traction_and_only_for_an_evolution() {
    let base = scratch("cli-hf");
    let scene = |problem: &str| {
        format!(
            "name = \"pulled\"\nT = 1.0\ng = \"none\"\nproblem = \"{problem}\"\n\
             [geometry]\nwidth = 3.0\nheight = 1.0\n[geometry.supports]\nleft = \"clamped\"\n\
             [material]\nE = 1000.0\nkappa = 0.3\n{}\
             [loads]\nf0 = [0.0, 0.0]\nf2 = [0.0, 0.0]\n\
             [[loads.traction]]\nside = \"top\"\nfrom = 2.25\nto = 3.0\nf = [0.0, 10.0]\n\
             [law]\nbreakpoints = [0.0]\nslopes = [0.0, 500.0]\n",
            if problem == "viscoelastic" {
                "alpha = 10.0\nbeta = 5.0\n"
            } else {
                ""
            }
        )
    };
    for (problem, warns) in [
        ("viscoelastic", true),
        ("elastic", false),
        ("steady", false),
    ] {
        let (o, _) = solve_text(&base, problem, &scene(problem), &["--n", "12"]);
        let err = stderr(&o);
        assert!(o.status.success(), "{problem}: {err}");
        assert_eq!(err.contains("H(f)"), warns, "{problem}: {err}");
        if warns {
            assert!(
                err.contains("`loads.traction[0]`") && !err.contains("f2"),
                "{err}"
            );
        }
        let out = stdout(&show(base.join(format!("{problem}.toml")), ""));
        assert_eq!(out.contains("not asked"), !warns, "{problem}: {out}");
    }
}

/// `bench` refuses at once what it used to refuse or fail on after minutes of
/// measurement (round four's re-run): a level given twice, a level that is no level
/// of the paper's scene, no repeat, and a --data without the table1.csv its chart
/// draws. Nothing is measured or written.
#[test]
fn bench_refuses_its_arguments_before_measuring() {
    let dir = scratch("bench-args");
    let data = dir.join("data");
    let figures = dir.join("figures");
    std::fs::create_dir_all(&data).unwrap();
    std::fs::copy("data/.evhi-outputs", data.join(".evhi-outputs")).unwrap();
    let bench = |extra: &str| {
        let mut cmd = evhi_with(&format!("bench {extra} --data"));
        cmd.arg(&data).arg("--figures").arg(&figures);
        output_within(&mut cmd, 60)
    };
    let before = snapshot(&dir);
    for (extra, needles) in [
        ("--levels 8,8", &["`--levels`", "each level once"][..]),
        (
            "--levels 5",
            &["`--levels`", "a positive multiple of 4"][..],
        ),
        (
            "--solver-levels 0",
            &["`--solver-levels`", "a positive multiple of 4"][..],
        ),
        ("--repeat 0", &["`--repeat`", ">= 1"][..]),
        (
            "--levels 8",
            &["`--data`", "table1.csv", "reproduce table1"][..],
        ),
    ] {
        let start = std::time::Instant::now();
        refused(&bench(extra), needles);
        assert!(
            start.elapsed().as_secs() < 20,
            "{extra}: refused after work"
        );
        assert!(snapshot(&dir) == before, "{extra}: a file was written");
    }
}
