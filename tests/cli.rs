//! The command line: outputs, headers, and readable errors.

use std::process::Command;

fn evhi() -> Command {
    Command::new(env!("CARGO_BIN_EXE_evhi"))
}

/// A fresh, empty scratch directory for one test.
fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("evhi-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    Scratch(dir)
}

/// A test's scratch directory, removed when the test ends unless it failed (then it
/// stays for a look): runs no longer leave a directory per test behind.
struct Scratch(std::path::PathBuf);

impl std::ops::Deref for Scratch {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        &self.0
    }
}

impl AsRef<std::path::Path> for Scratch {
    fn as_ref(&self) -> &std::path::Path {
        &self.0
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.as_os_str()
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// Runs `cmd`, which must succeed (its stderr is shown otherwise).
fn succeed(cmd: &mut Command) {
    let out = cmd.output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Asserts that a command was refused and that its stderr holds every one of
/// `needles` and no panic; returns the stderr.
fn refused(o: &std::process::Output, needles: &[&str]) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success(), "accepted: {err}");
    assert!(!err.contains("panicked"), "{err}");
    for n in needles {
        assert!(err.contains(n), "no `{n}` in: {err}");
    }
    err
}

/// `evhi solve --scenario figure --n 8 --steps 2 --out OUT`: the smallest run, for the
/// tests of outputs and messages.
fn small_solve(out: &std::path::Path) -> Command {
    let mut cmd = evhi();
    cmd.args([
        "solve",
        "--scenario",
        "figure",
        "--n",
        "8",
        "--steps",
        "2",
        "--out",
    ])
    .arg(out);
    cmd
}

#[test]
fn solve_writes_all_outputs() {
    let dir = scratch("cli");
    succeed(
        evhi()
            .args([
                "solve",
                "--scenario",
                "figure",
                "--n",
                "16",
                "--steps",
                "8",
                "--out",
            ])
            .arg(&dir),
    );
    // Every CSV opens with two provenance lines: the command, then the data solved.
    let body = |f: &str| -> String {
        let text = std::fs::read_to_string(dir.join(f)).unwrap();
        let mut lines = text.lines();
        assert!(
            lines.next().unwrap().starts_with("# produced by evhi"),
            "{f}"
        );
        let data = lines.next().unwrap();
        assert!(
            data.starts_with("# scenario figure;") && data.contains("load history: constant"),
            "{f}: {data}"
        );
        lines.map(|l| format!("{l}\n")).collect()
    };
    let contact = body("contact.csv");
    assert!(contact.starts_with("x,u_nu,sigma_nu1,sigma_nu2,regime\n"));
    assert_eq!(contact.lines().count(), 1 + 17);
    let summary = body("summary.csv");
    assert!(summary.starts_with("n,steps,dofs,energy_norm_T,max_certificate,wall_s,"));
    assert!(summary.contains(",load_history,compatible_data,"));
    assert!(summary.contains(",constant,false,"));
    let steps = body("steps.csv");
    assert_eq!(steps.lines().count(), 1 + 8);
    let vtu = std::fs::read_to_string(dir.join("solution.vtu")).unwrap();
    assert!(vtu.contains("NumberOfPoints=\"153\"") && vtu.contains("NumberOfCells=\"256\""));
    // No temporary files are left behind: the only hidden file is the run marker.
    let hidden: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert_eq!(hidden, vec![".evhi-run".to_string()]);
}

/// A load history from the command line (`--ramp`) or the scenario file gives the same
/// run; compatible data print no warning, constant loads print one naming H(f).
#[test]
fn load_histories_from_the_cli_and_the_file() {
    let base = scratch("cli-hist");
    let toml = base.join("ramp.toml");
    let text = std::fs::read_to_string("data/scenarios/figure.toml")
        .unwrap()
        .replace("[loads]\n", "[loads]\nhistory = { ramp = 0.25 }\n");
    std::fs::write(&toml, text).unwrap();
    let run = |scenario: &str, extra: &[&str], out: &str| -> (String, String) {
        let dir = base.join(out);
        let o = evhi()
            .args([
                "solve",
                "--scenario",
                scenario,
                "--n",
                "16",
                "--steps",
                "16",
            ])
            .args(extra)
            .arg("--out")
            .arg(&dir)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr).to_string();
        assert!(o.status.success(), "{err}");
        let summary = std::fs::read_to_string(dir.join("summary.csv")).unwrap();
        (summary, err)
    };
    let (from_file, warn_file) = run(toml.to_str().unwrap(), &[], "file");
    let (from_cli, warn_cli) = run("figure", &["--ramp", "0.25"], "cli");
    let (constant, warn_constant) = run("figure", &[], "constant");
    assert!(
        !warn_file.contains("warning") && !warn_cli.contains("warning"),
        "{warn_cli}"
    );
    assert!(
        warn_constant.contains("warning") && warn_constant.contains("H(f)"),
        "{warn_constant}"
    );
    let energy = |s: &str| -> f64 {
        let rows: Vec<&str> = s.lines().filter(|l| !l.starts_with('#')).collect();
        rows[1].split(',').nth(3).unwrap().parse().unwrap()
    };
    assert_eq!(energy(&from_file), energy(&from_cli));
    assert!(from_cli.contains("ramp t_r = 0.25") && from_cli.contains(",true,"));
    // The ramp has reached the full load by t = 0.25, yet the body lags behind it.
    assert!(energy(&from_cli) < energy(&constant));
    // A bad ramp names the option.
    let o = evhi()
        .args(["solve", "--ramp", "-1", "--out"])
        .arg(base.join("bad"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("`ramp`"));
}

#[test]
fn bad_arguments_fail_with_the_field_named() {
    for (args, needle) in [
        (vec!["--n", "10"], "`n`"),
        (vec!["--g", "-0.1"], "`g`"),
        (vec!["--steps", "0"], "`steps`"),
        (vec!["--scenario", "nope"], "`scenario`"),
        // issue 12: negative counts name their option; absurd tolerances are refused
        (vec!["--n", "-4"], "--n"),
        (vec!["--steps", "-1"], "--steps"),
        (vec!["--certificate-tol", "inf"], "`certificate-tol`"),
        (vec!["--certificate-tol", "1e300"], "`certificate-tol`"),
        (vec!["--certificate-tol", "1e-20"], "`certificate-tol`"),
        (vec!["--g", "1e308"], "`g`"),
        (vec!["--n", "4096"], "needs about"),
        (vec!["--ramp", "1e-300"], "`ramp`"),
    ] {
        let out = evhi()
            .args(["solve", "--out", "/tmp/evhi-never"])
            .args(&args)
            .output()
            .unwrap();
        assert!(!out.status.success());
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
    let out = evhi()
        .args(["solve", "--out", "/tmp/x", "--f0", "1,two"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("two"));
}

#[test]
fn bench_sweeps_writes_every_variant() {
    let dir = scratch("sweeps");
    succeed(
        evhi()
            .args(["bench", "--sweeps", "--sweeps-n", "16", "--data"])
            .arg(&dir),
    );
    let csv = std::fs::read_to_string(dir.join("bench_sweeps.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().filter(|l| !l.starts_with('#')).collect();
    assert!(rows[0].starts_with("variant,ordering,threads,prefetch,columns,nnz_l,"));
    // faer, seven of ours, two streaming rates.
    assert_eq!(rows.len(), 1 + 10, "{csv}");
    for row in &rows[1..] {
        let total: f64 = row.split(',').nth(8).unwrap().parse().unwrap();
        assert!(total > 0.0 && total.is_finite(), "{row}");
    }
    // A level the mesh does not allow is refused with the field named.
    let out = evhi()
        .args(["bench", "--sweeps", "--sweeps-n", "10", "--data"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("`n`"));
}

/// A scenario file: `figure` with `from` replaced by `to`.
fn figure_file(dir: &std::path::Path, name: &str, from: &str, to: &str) -> std::path::PathBuf {
    let text = std::fs::read_to_string("data/scenarios/figure.toml").unwrap();
    assert!(text.contains(from));
    let p = dir.join(name);
    std::fs::write(&p, text.replace(from, to)).unwrap();
    p
}

/// Issue 12's cases that used to look right and were not, or were refused though valid.
#[test]
fn hostile_but_valid_input_is_solved_and_hostile_invalid_input_is_named() {
    let dir = scratch("cli-hostile");
    let run = |scenario: &std::path::Path, extra: &[&str]| {
        evhi()
            .args(["solve", "--n", "32", "--steps", "32", "--scenario"])
            .arg(scenario)
            .args(extra)
            .arg("--out")
            .arg(dir.join("out"))
            .output()
            .unwrap()
    };
    let slopes = "slopes = [0.0, 200.0, -100.0, 300.0]";
    // An upward jump: nodes sit on the breakpoint up to rounding; it certifies.
    let jump = figure_file(
        &dir,
        "jump.toml",
        slopes,
        &format!("{slopes}\njumps = [0.0, 5.0, 0.0]"),
    );
    let o = run(&jump, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // A very thin layer: nodes at g(1 - 1e-8) are on the limit, not on branch 1.
    let o = run(&std::path::PathBuf::from("figure"), &["--g", "1e-9"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let contact = std::fs::read_to_string(dir.join("out/contact.csv")).unwrap();
    assert!(
        contact.lines().filter(|l| l.ends_with(",limit")).count() > 16,
        "{contact}"
    );
    // A certificate stricter than rounding: the refusal says what refused.
    let o = run(
        &std::path::PathBuf::from("figure"),
        &["--certificate-tol", "1e-15"],
    );
    let err = String::from_utf8_lossy(&o.stderr);
    if !o.status.success() {
        assert!(
            err.contains("reported convergence") && err.contains("independent certificate"),
            "{err}"
        );
        assert!(!err.contains("ended with Converged"), "{err}");
    }
    // A strongly softening law: the step can be nonconvex; solve warns and reports it.
    let soft = figure_file(
        &dir,
        "soft.toml",
        slopes,
        "slopes = [0.0, 200.0, -100000.0, 300.0]",
    );
    let o = run(&soft, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("not convex") || !o.status.success(), "{err}");
    if o.status.success() {
        let summary = std::fs::read_to_string(dir.join("out/summary.csv")).unwrap();
        assert!(summary.contains("step_curvature_min"));
    }
    // A very soft material breaks H(s): solve says so.
    let soft_e = figure_file(&dir, "soft_e.toml", "E = 1000.0", "E = 1e-3");
    let o = run(&soft_e, &[]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success() && err.contains("H(s) fails"), "{err}");
    let summary = std::fs::read_to_string(dir.join("out/summary.csv")).unwrap();
    assert!(summary.contains(",beta_B,m_trace_norm_sq,"));
    // Values that overflow the solve are refused by name, echoed in exponent form.
    let huge = figure_file(&dir, "huge.toml", "T = 1.0", "T = 1e300");
    let err = String::from_utf8_lossy(&run(&huge, &[]).stderr).to_string();
    assert!(
        err.contains("`T`") && err.contains("1e300") && err.len() < 400,
        "{err}"
    );
    let kappa = figure_file(&dir, "kappa.toml", "kappa = 0.4", "kappa = 1e308");
    let err = String::from_utf8_lossy(&run(&kappa, &[]).stderr).to_string();
    assert!(
        err.contains("`material.kappa`") && err.contains("1e308") && err.len() < 400,
        "{err}"
    );
    // A 10 MB line with a parse error is echoed in part; a file over 1 MiB is refused.
    let long = dir.join("long.toml");
    std::fs::write(&long, format!("name = \"{}", "x".repeat(900_000))).unwrap();
    let err = String::from_utf8_lossy(&run(&long, &[]).stderr).to_string();
    assert!(err.len() < 2000, "{} bytes of error", err.len());
    let big = dir.join("big.toml");
    std::fs::write(&big, "#".repeat(2 << 20)).unwrap();
    let err = String::from_utf8_lossy(&run(&big, &[]).stderr).to_string();
    assert!(
        err.contains("`scenario`") && err.contains("at most"),
        "{err}"
    );
}

/// The evolution for ParaView: one VTU per written step and a .pvd with their times;
/// the last VTU's point fields equal contact.csv at the contact nodes.
#[test]
fn vtk_time_series_matches_the_contact_table() {
    let dir = scratch("cli-pvd");
    let o = evhi()
        .args([
            "solve",
            "--scenario",
            "figure",
            "--n",
            "16",
            "--steps",
            "8",
            "--vtk-every",
            "3",
        ])
        .arg("--out")
        .arg(&dir)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Steps 3, 6 and the last, 8.
    let pvd = std::fs::read_to_string(dir.join("solution.pvd")).unwrap();
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
    let vtu = std::fs::read_to_string(dir.join(&sets[2].1)).unwrap();
    let array = |name: &str| -> Vec<f64> {
        let start = vtu.find(&format!("Name=\"{name}\"")).unwrap();
        let body = &vtu[start..];
        let body = &body[body.find('>').unwrap() + 1..body.find("</DataArray>").unwrap()];
        body.split_whitespace()
            .map(|x| x.parse().unwrap())
            .collect()
    };
    let (sigma1, regime) = (array("sigma_nu1"), array("regime"));
    let contact = std::fs::read_to_string(dir.join("contact.csv")).unwrap();
    let rows: Vec<Vec<String>> = contact
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    assert_eq!(rows.len(), 17);
    let mut limit = 0;
    for (i, r) in rows.iter().enumerate() {
        assert_eq!(sigma1[i], r[2].parse::<f64>().unwrap(), "node {i}");
        let code = match r[4].as_str() {
            "no_contact" => 0.0,
            "limit" => {
                limit += 1;
                4.0
            }
            b => b.trim_start_matches("branch").parse().unwrap(),
        };
        assert_eq!(regime[i], code, "node {i}: {}", r[4]);
    }
    assert!(limit > 0, "figure has nodes at the limit at T");
    // Off the contact boundary the regime is -1; the run directory describes itself.
    assert_eq!(regime[17], -1.0);
    let toml = std::fs::read_to_string(dir.join("scenario.toml")).unwrap();
    assert!(toml.contains("--vtk-every 3") && toml.contains("name = \"figure\""));
}

/// `evhi scenarios` lists the built-ins; `evhi show` prints a scenario and warns where
/// a hypothesis of the paper fails.
#[test]
fn scenarios_and_show() {
    let o = evhi().arg("scenarios").output().unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success());
    for name in ["literal", "figure", "smooth"] {
        assert!(out.lines().any(|l| l.starts_with(name)), "{out}");
    }
    let o = evhi().args(["show", "figure"]).output().unwrap();
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert!(o.status.success(), "{err}");
    assert!(
        out.contains("H(s): beta_B") && out.contains(": holds"),
        "{out}"
    );
    assert!(
        out.contains("step convexity") && out.contains("tau = 0.07"),
        "{out}"
    );
    assert!(
        out.contains("warning: at t = 0") && err.contains("2 warning(s)"),
        "{out}{err}"
    );
    // A downward jump breaks H(j); a ramp makes the data compatible.
    let dir = scratch("cli-show");
    let slopes = "slopes = [0.0, 200.0, -100.0, 300.0]";
    let jump = figure_file(
        &dir,
        "down.toml",
        slopes,
        &format!("{slopes}\njumps = [0.0, -5.0, 0.0]"),
    );
    let text = std::fs::read_to_string(&jump)
        .unwrap()
        .replace("[loads]\n", "[loads]\nhistory = { ramp = 0.5 }\n");
    std::fs::write(&jump, text).unwrap();
    let o = evhi()
        .arg("show")
        .arg(&jump)
        .args(["--n", "16", "--steps", "16"])
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(
        out.contains("warning: H(j) fails") && out.contains("(a jump)"),
        "{out}"
    );
    assert!(out.contains("H(f), H(0) at t = 0: hold"), "{out}");
    // solve warns about the downward jump too.
    let o = evhi()
        .arg("solve")
        .arg("--scenario")
        .arg(&jump)
        .args(["--n", "16", "--steps", "16", "--out"])
        .arg(dir.join("out"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("warning: H(j) fails"), "{err}");
    // A bad mesh is an error naming the option.
    let o = evhi()
        .args(["show", "figure", "--n", "10"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("`n`"));
}

/// A user scenario with a five-branch law and a jump, end to end: solve writes its
/// tables and figures, and `evhi plot` redraws the figures from the tables alone.
#[test]
fn a_user_scenario_runs_and_draws() {
    let dir = scratch("cli-five");
    let o = evhi()
        .args([
            "solve",
            "--scenario",
            "data/scenarios/examples/five_branch.toml",
        ])
        .args(["--n", "32", "--steps", "32", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    assert!(
        !err.contains("warning"),
        "compatible data, H(s) holds: {err}"
    );
    let contact = std::fs::read_to_string(dir.join("contact.csv")).unwrap();
    assert!(
        contact.contains(",branch4\n") && contact.contains(",limit\n"),
        "{contact}"
    );
    let regimes = std::fs::read_to_string(dir.join("regimes.csv")).unwrap();
    assert!(
        regimes.contains("step,t,branch1,branch2,branch3,branch4,limit")
            || regimes.contains(",branch4,"),
        "{regimes}"
    );
    let evolution = std::fs::read_to_string(dir.join("evolution.csv")).unwrap();
    assert_eq!(
        evolution.lines().filter(|l| !l.starts_with('#')).count(),
        1 + 5 * 32
    );
    let size = |f: &str| std::fs::metadata(dir.join(f)).map(|m| m.len()).unwrap_or(0);
    for f in [
        "deformed.png",
        "deformed.svg",
        "evolution.png",
        "evolution.svg",
    ] {
        assert!(size(f) > 10_000, "{f}: {} bytes", size(f));
        std::fs::remove_file(dir.join(f)).unwrap();
    }
    let o = evhi().arg("plot").arg(&dir).output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "deformed.png",
        "deformed.svg",
        "evolution.png",
        "evolution.svg",
    ] {
        assert!(size(f) > 10_000, "redrawn {f}");
    }
    let o = evhi().args(["plot", "/nonexistent-run"]).output().unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("/nonexistent-run"));
}

/// `reproduce -q` prints nothing on success.
#[test]
fn reproduce_quiet_prints_nothing() {
    let dir = scratch("cli-quiet");
    let o = evhi()
        .args(["reproduce", "fig2", "loads", "--quick", "-q", "--data"])
        .arg(dir.join("data"))
        .arg("--figures")
        .arg(dir.join("figures"))
        .output()
        .unwrap();
    assert!(o.status.success());
    assert!(
        o.stderr.is_empty() && o.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(dir.join("data/loads_search.csv").exists());
}

/// Every registered step solver is reachable from the command line; the penalty
/// method, which overshoots g by design, runs with a note that it is not certified.
#[test]
fn every_registered_solver_runs_from_the_command_line() {
    for entry in evhi::step::SOLVERS.iter() {
        let dir = scratch(&format!("solver-{}", entry.name));
        let out = evhi()
            .args(["solve", "--scenario", "figure", "--n", "8", "--steps", "4"])
            .args(["--solver", entry.name, "--out"])
            .arg(&dir)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{}: {stderr}", entry.name);
        assert_eq!(
            stderr.contains("is not certified"),
            !entry.certified,
            "{}: {stderr}",
            entry.name
        );
        assert!(dir.join("summary.csv").exists(), "{}", entry.name);
    }
    let out = evhi()
        .args([
            "solve",
            "--solver",
            "gradient-descent",
            "--out",
            "/tmp/never",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("newton") && stderr.contains("penalty"),
        "{stderr}"
    );
}

/// `--path auto` takes the reduced loop where the damping is proportional and the
/// general one where it is not; steps.csv says which certificate each step got;
/// `--path reduced` on the non-proportional scene is refused by name.
#[test]
fn the_time_loop_follows_the_damping() {
    let column = |dir: &std::path::Path, file: &str, name: &str| -> Vec<String> {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let mut lines = text.lines().filter(|l| !l.starts_with('#'));
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let at = header.iter().position(|h| *h == name).unwrap();
        lines
            .map(|l| l.split(',').nth(at).unwrap().to_string())
            .collect()
    };
    for (scenario, path, checks) in [
        ("figure", "reduced", ["condensed", "full"]),
        ("nonproportional", "general", ["full", "full"]),
    ] {
        let dir = scratch(&format!("path-{scenario}"));
        succeed(
            evhi()
                .args(["solve", "--scenario", scenario, "--n", "8", "--steps", "8"])
                .arg("--out")
                .arg(&dir),
        );
        assert_eq!(column(&dir, "summary.csv", "path"), vec![path.to_string()]);
        let check = column(&dir, "steps.csv", "check");
        assert_eq!(check.len(), 8);
        assert_eq!([check[0].as_str(), check[7].as_str()], checks, "{scenario}");
    }
    let dir = scratch("path-refused");
    let out = evhi()
        .args([
            "solve",
            "--scenario",
            "nonproportional",
            "--n",
            "8",
            "--steps",
            "4",
        ])
        .args(["--path", "reduced", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("material") && err.contains("proportional"),
        "{err}"
    );
}

/// A finer reference for Table 1 that cannot serve is refused by name, before
/// any run: not a multiple of the finest level, or too large for memory.
#[test]
fn a_bad_table1_reference_is_refused() {
    let dir = scratch("bad-reference");
    for bad in ["100", "1048576"] {
        let out = evhi()
            .args([
                "reproduce",
                "table1",
                "--quick",
                "--quiet",
                "--reference",
                bad,
            ])
            .arg("--data")
            .arg(dir.join("data"))
            .arg("--figures")
            .arg(dir.join("figures"))
            .output()
            .unwrap();
        assert!(!out.status.success(), "--reference {bad} must fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(bad), "--reference {bad}: {err}");
    }
}

/// `reproduce --log` reports each finished unit as a line with its time and its
/// experiment instead of progress bars, and refuses to be quiet at the same time.
#[test]
fn reproduce_logs_lines_with_times() {
    let dir = scratch("log");
    let out = evhi()
        .args(["reproduce", "static", "--quick", "--log", "--data"])
        .arg(dir.join("data"))
        .arg("--figures")
        .arg(dir.join("figures"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
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
    let both = evhi()
        .args(["reproduce", "fig2", "--log", "-q"])
        .output()
        .unwrap();
    assert!(!both.status.success());
    assert!(String::from_utf8_lossy(&both.stderr).contains("--quiet"));
}

/// The main job changes no committed file with its own wall times: a full run keeps
/// them in the git-ignored `local/` of the data directory, and only `--record-times`
/// writes the table the book quotes.
#[test]
fn reproduce_keeps_its_times_local_unless_recorded() {
    let dir = scratch("times");
    let (data, figures) = (dir.join("data"), dir.join("figures"));
    let run = |extra: &[&str]| {
        succeed(
            evhi()
                .args(["reproduce", "fig2", "-q"])
                .args(extra)
                .arg("--data")
                .arg(&data)
                .arg("--figures")
                .arg(&figures),
        )
    };
    run(&[]);
    assert!(data.join("fig2_law.csv").exists());
    assert!(!data.join("reproduce_times.csv").exists());
    let local = std::fs::read_to_string(data.join("local/reproduce_times.csv")).unwrap();
    assert!(local.contains("\nfig2,fig2,"), "{local}");
    run(&["--record-times"]);
    let recorded = std::fs::read_to_string(data.join("reproduce_times.csv")).unwrap();
    let first = recorded.lines().next().unwrap();
    assert!(
        first.contains("`evhi reproduce fig2 --record-times`"),
        "{first}"
    );
    assert!(recorded.contains("machine: "), "{recorded}");
    // The git-ignored directory is the one this checkout ignores.
    let ignore =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/.gitignore")).unwrap();
    assert!(ignore.lines().any(|l| l.trim() == "/data/local/"));
}

/// `solve --scenario smooth --f2 0,-1e6` (the top is clamped there) is refused naming
/// `f2`, before any work.
#[test]
fn solve_refuses_a_traction_on_a_clamped_top() {
    let dir = scratch("clamped-f2");
    let out = evhi()
        .args([
            "solve",
            "--scenario",
            "smooth",
            "--n",
            "8",
            "--steps",
            "2",
            "--f2",
            "0,-1e6",
            "--out",
        ])
        .arg(dir.join("run"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
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
        let file = dir.join(format!("case{i}.toml"));
        std::fs::write(&file, text).unwrap();
        for path in ["general", "auto"] {
            let out = evhi()
                .args([
                    "solve",
                    "--n",
                    "16",
                    "--steps",
                    "4",
                    "--path",
                    path,
                    "--scenario",
                ])
                .arg(&file)
                .arg("--out")
                .arg(dir.join(format!("run{i}-{path}")))
                .output()
                .unwrap();
            let err = String::from_utf8_lossy(&out.stderr);
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
    let o = solve();
    refused(&o, &["`my_notes.txt`", "`analysis/`"]);
    assert_eq!(
        std::fs::read_to_string(out.join("my_notes.txt")).unwrap(),
        "mine"
    );
    assert!(out.join("analysis").is_dir() && out.join("summary.csv").exists());
}

/// `reproduce --quick` without `--data`/`--figures` writes its coarse levels into the
/// git-ignored `data/local/quick/` and `figures/local/quick/`, never over the committed
/// full-level outputs.
#[test]
fn reproduce_quick_never_overwrites_the_committed_outputs() {
    let dir = scratch("quick-default");
    succeed(
        evhi()
            .current_dir(&dir)
            .args(["reproduce", "fig2", "--quick", "-q"]),
    );
    assert!(dir.join("data/local/quick/fig2_law.csv").exists());
    assert!(dir.join("figures/local/quick/fig2_law.png").exists());
    assert!(!dir.join("data/fig2_law.csv").exists());
    assert!(!dir.join("figures/fig2_law.png").exists());
    let ignore =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/.gitignore")).unwrap();
    assert!(ignore.lines().any(|l| l.trim() == "/figures/local/"));
}

/// A line feed or carriage return cannot break out of a provenance line: refused in a
/// scenario's name, escaped in a path on the command line (issue 27, case 4).
#[test]
fn control_characters_stay_out_of_the_provenance_lines() {
    let dir = scratch("control-chars");
    let text = std::fs::read_to_string("data/scenarios/figure.toml")
        .unwrap()
        .replace("name = \"figure\"", "name = \"fig\\nure\"");
    let file = dir.join("nl.toml");
    std::fs::write(&file, text).unwrap();
    let o = evhi().args(["show"]).arg(&file).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("`name`"), "{err}");
    for bad in ["cr\rrun", "lf\nrun"] {
        let out = dir.join(bad);
        succeed(&mut small_solve(&out));
        let contact = std::fs::read_to_string(out.join("contact.csv")).unwrap();
        let lines: Vec<&str> = contact.lines().collect();
        assert!(lines[0].starts_with("# produced by evhi") && lines[1].starts_with("# scenario"));
        assert_eq!(lines[2], "x,u_nu,sigma_nu1,sigma_nu2,regime", "{contact}");
        assert!(
            lines[0].contains("\\r") || lines[0].contains("\\n"),
            "{}",
            lines[0]
        );
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
        data.join(".fig2_law.csv.tmp-999999999"),
        figures.join(".fig2_law.tmp-999999999.png"),
    ];
    for s in &stale {
        std::fs::write(s, "partial").unwrap();
    }
    let run = || {
        evhi()
            .args(["reproduce", "fig2", "--quick", "-q", "--data"])
            .arg(&data)
            .arg("--figures")
            .arg(&figures)
            .output()
            .unwrap()
    };
    let lock = std::fs::File::options()
        .create(true)
        .truncate(false)
        .write(true)
        .open(data.join(".reproduce.lock"))
        .unwrap();
    lock.try_lock().unwrap();
    let o = run();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("another `evhi reproduce`"),
        "{err}"
    );
    assert!(
        stale.iter().all(|s| s.exists()),
        "a refused run must touch nothing"
    );
    drop(lock);
    let o = run();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stale.iter().all(|s| !s.exists()), "stale temporaries left");
    assert!(data.join("fig2_law.csv").exists());
}

/// H(s) is judged with the trace constant of the run's own mesh, which grows with n:
/// slopes [0, 200, -290, 300] pass on the 1/64 mesh's constant but fail on 1/256's
/// (issue 27, case 12: the 1/64 constant used to be taken for every n).
#[test]
fn smallness_uses_the_runs_own_trace_constant() {
    let dir = scratch("hs-trace");
    let file = figure_file(
        &dir,
        "soft.toml",
        "slopes = [0.0, 200.0, -100.0, 300.0]",
        "slopes = [0.0, 200.0, -290.0, 300.0]",
    );
    let show = |n: &str| {
        let o = evhi()
            .args(["show"])
            .arg(&file)
            .args(["--n", n])
            .output()
            .unwrap();
        String::from_utf8_lossy(&o.stdout).into_owned() + &String::from_utf8_lossy(&o.stderr)
    };
    let line = |text: &str| {
        text.lines()
            .find(|l| l.starts_with("H(s)"))
            .unwrap()
            .to_string()
    };
    assert!(line(&show("64")).ends_with("holds"), "{}", show("64"));
    let at256 = line(&show("256"));
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
    let lock = std::fs::File::options()
        .write(true)
        .open(dir.join(".run.lock"))
        .unwrap();
    lock.try_lock().unwrap();
    let o = evhi().arg("plot").arg(&out).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("another evhi run"),
        "{err}"
    );
    drop(lock);
    succeed(evhi().arg("plot").arg(&out));
}

/// The memory guard also reads the address-space limit: under `ulimit -v 3000000` a
/// mesh that cannot fit is refused before any work, with the estimate, instead of
/// aborting in an allocation (issue 27, case 11).
#[test]
fn the_memory_guard_reads_the_address_space_limit() {
    let dir = scratch("ulimit");
    let o = std::process::Command::new("bash")
        .arg("-c")
        .arg(format!(
            "ulimit -v 3000000; exec '{}' solve --scenario figure --n 2048 --steps 1 --out '{}'",
            env!("CARGO_BIN_EXE_evhi"),
            dir.join("run").display()
        ))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
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
    let mono = figure_file(
        &dir,
        "mono.toml",
        "slopes = [0.0, 200.0, -100.0, 300.0]",
        "slopes = [0.0, 200.0, 100.0, 300.0]",
    );
    let o = evhi().arg("show").arg(&mono).output().unwrap();
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(
        text.contains("= 0 (relaxed monotonicity)") && !text.contains("-0"),
        "{text}"
    );
    let o = evhi()
        .args(["show", "figure", "--steps", "2000000"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("`steps`"), "{err}");
    std::fs::create_dir(dir.join("real")).unwrap();
    std::os::unix::fs::symlink(dir.join("real"), dir.join("link")).unwrap();
    let o = small_solve(&dir.join("link")).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("symbolic link"),
        "{err}"
    );
    // A last component too long for the staging directory beside it is refused
    // before anything (lock included) is written.
    let long = dir.join("a".repeat(245));
    let o = small_solve(&long).output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("245 bytes long; at most 235"),
        "{err}"
    );
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().len() > 200)
        .collect();
    assert!(left.is_empty(), "left behind: {left:?}");
}

/// `--vtk-every` is bounded by the volume it would write: 1e6 steps at n = 128 with a
/// snapshot every step (about 1 TB) is refused before any work, naming the option and
/// the estimate (issue 27, case 10).
#[test]
fn a_vtk_series_that_cannot_fit_is_refused() {
    let dir = scratch("vtk-volume");
    let o = evhi()
        .args([
            "solve",
            "--scenario",
            "figure",
            "--n",
            "128",
            "--steps",
            "1000000",
            "--vtk-every",
            "1",
            "--out",
        ])
        .arg(dir.join("run"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("`vtk-every`") && err.contains("GB in all"),
        "{err}"
    );
    assert!(!dir.join("run/summary.csv").exists());
}

/// `plot` refuses a tampered table, naming file, line and column, instead of drawing
/// text as 0, an empty table, NaN or 1e300 (issue 27, case 15).
#[test]
fn plot_refuses_tampered_tables() {
    let dir = scratch("tampered");
    let out = dir.join("run");
    succeed(&mut small_solve(&out));
    let contact = std::fs::read_to_string(out.join("contact.csv")).unwrap();
    let lines: Vec<&str> = contact.lines().collect();
    let first = lines[3]; // after two provenance lines and the header
    let fields: Vec<&str> = first.split(',').collect();
    for (bad, expect) in [("abc", "`abc`"), ("NaN", "`NaN`"), ("1e300", "`1e300`")] {
        let row = format!("{},{bad},{}", fields[0], fields[2..].join(","));
        let text = contact.replacen(first, &row, 1);
        std::fs::write(out.join("contact.csv"), text).unwrap();
        let o = evhi().arg("plot").arg(&out).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{bad} drawn");
        assert!(
            err.contains("contact.csv:4") && err.contains("`u_nu`") && err.contains(expect),
            "{err}"
        );
    }
    let header_only: String = lines[..3].iter().map(|l| format!("{l}\n")).collect();
    std::fs::write(out.join("contact.csv"), header_only).unwrap();
    let o = evhi().arg("plot").arg(&out).output().unwrap();
    assert!(String::from_utf8_lossy(&o.stderr).contains("no data row"));
    std::fs::write(out.join("contact.csv"), contact).unwrap();
    succeed(evhi().arg("plot").arg(&out));
}

#[test]
fn two_threads_with_amd_are_refused_and_amd_alone_runs_on_one() {
    let dir = scratch("threads-amd");
    let out = small_solve(&dir.join("run"))
        .args(["--threads", "2", "--ordering", "amd"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("`threads`") && err.contains("--ordering amd"),
        "{err}"
    );
    assert!(!dir.join("run").exists(), "refused before any work");
    succeed(small_solve(&dir.join("run")).args(["--ordering", "amd"]));
    let summary = std::fs::read_to_string(dir.join("run/summary.csv")).unwrap();
    assert!(summary.contains("amd"));
}

/// Issue 25's scene from the command line: the cantilever example on a uniform and on a
/// graded mesh, viscoelastic and steady. The VTK file and the figures follow the
/// rectangle (2 x 0.5, every node inside it, the clamped corner no contact node), the
/// graded run writes its triangles, and the options that do not fit are refused by name.
#[test]
fn a_new_scene_solves_draws_and_writes_vtk_from_the_cli() {
    let dir = scratch("scene");
    let file = "data/scenarios/examples/cantilever.toml";
    let steady = dir.join("steady.toml");
    let text = std::fs::read_to_string(file).unwrap();
    let text: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with("alpha") && !l.starts_with("beta"))
        .collect();
    std::fs::write(
        &steady,
        text.join("\n")
            .replace("problem = \"viscoelastic\"", "problem = \"steady\""),
    )
    .unwrap();
    for (name, scenario, extra) in [
        (
            "uniform",
            std::path::PathBuf::from(file),
            vec!["--steps", "16"],
        ),
        (
            "graded",
            std::path::PathBuf::from(file),
            vec!["--steps", "16", "--mesh", "graded"],
        ),
        ("steady", steady.clone(), vec![]),
        (
            "steady-graded",
            steady.clone(),
            vec!["--mesh", "graded", "--grading", "0.3"],
        ),
    ] {
        let out = dir.join(name);
        succeed(
            evhi()
                .args(["solve", "--scenario"])
                .arg(&scenario)
                .args(["--n", "16", "--out"])
                .arg(&out)
                .args(&extra),
        );
        for f in [
            "deformed.png",
            "deformed.svg",
            "evolution.png",
            "solution.vtu",
        ] {
            assert!(out.join(f).exists(), "{name}: no {f}");
        }
        assert_eq!(out.join("triangles.csv").exists(), name.contains("graded"));
        let vtu = std::fs::read_to_string(out.join("solution.vtu")).unwrap();
        let points: usize = vtu
            .split("NumberOfPoints=\"")
            .nth(1)
            .and_then(|s| s.split('"').next())
            .unwrap()
            .parse()
            .unwrap();
        let nodes = std::fs::read_to_string(out.join("nodes.csv")).unwrap();
        let rows: Vec<Vec<f64>> = nodes
            .lines()
            .filter(|l| !l.starts_with('#'))
            .skip(1)
            .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
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
        let contact = std::fs::read_to_string(out.join("contact.csv")).unwrap();
        let first_x: f64 = contact
            .lines()
            .filter(|l| !l.starts_with('#'))
            .nth(1)
            .unwrap()
            .split(',')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(first_x > 0.0, "{name}: the clamped corner in contact.csv");
    }
    // The options that do not fit, each named.
    for (args, field) in [
        (vec!["--steps", "4"], "steps"),
        (vec!["--grading", "0.3"], "grading"),
        (vec!["--mesh", "graded", "--ordering", "nd"], "ordering"),
        (vec!["--mesh", "graded", "--grading", "1.5"], "grading"),
        (vec!["--n", "10"], "n"),
    ] {
        let o = evhi()
            .args(["solve", "--scenario"])
            .arg(&steady)
            .args(["--out"])
            .arg(dir.join("refused"))
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} accepted");
        assert!(err.contains(&format!("`{field}`")), "{args:?}: {err}");
    }
}

/// `evhi study convergence --quick` on user scenario files (the five-branch example on
/// the paper's scene, the cantilever on its own): each writes its directory, the
/// orders are finite, the figures exist, and the singular points are the scene's.
#[test]
fn the_convergence_study_runs_on_user_scenarios() {
    let dir = scratch("study");
    for (name, file, singular) in [
        ("five", "data/scenarios/examples/five_branch.toml", 4),
        ("cantilever", "data/scenarios/examples/cantilever.toml", 2),
    ] {
        let out = dir.join(name);
        succeed(
            evhi()
                .args([
                    "study",
                    "convergence",
                    "--quick",
                    "--scenario",
                    file,
                    "--out",
                ])
                .arg(&out),
        );
        for f in [
            "convergence.csv",
            "convergence.md",
            "convergence.png",
            "convergence.svg",
            "singular.csv",
            "scenario.toml",
        ] {
            assert!(out.join(f).exists(), "{name}: no {f}");
        }
        let text = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
        let mut lines = text.lines().filter(|l| !l.starts_with('#'));
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let col = |c: &str| header.iter().position(|h| *h == c).unwrap();
        let rows: Vec<Vec<String>> = lines
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect();
        assert_eq!(rows.len(), 8, "{name}: two families of four levels");
        for r in &rows {
            let n: usize = r[col("n")].parse().unwrap();
            let err: f64 = r[col("rel_err_T_percent")].parse().unwrap();
            assert!(err.is_finite() && err > 0.0, "{name}: {r:?}");
            let order: f64 = r[col("order_dofs")].parse().unwrap();
            assert_eq!(order.is_finite(), n > 4, "{name}: order at n = {n}: {r:?}");
            let inc: f64 = r[col("increment_T_percent")].parse().unwrap();
            assert_eq!(inc.is_finite(), n < 32, "{name}: increment at n = {n}");
        }
        let sing = std::fs::read_to_string(out.join("singular.csv")).unwrap();
        assert_eq!(
            sing.lines().filter(|l| !l.starts_with('#')).count(),
            1 + singular,
            "{name}: {sing}"
        );
        // The h and k parts where the damping is proportional (the five-branch
        // example), else a sentence saying why not (the cantilever's is not).
        let md = std::fs::read_to_string(out.join("convergence.md")).unwrap();
        if name == "five" {
            let text = std::fs::read_to_string(out.join("split.csv")).unwrap();
            let mut lines = text.lines().filter(|l| !l.starts_with('#'));
            let header: Vec<&str> = lines.next().unwrap().split(',').collect();
            let col = |c: &str| header.iter().position(|h| *h == c).unwrap();
            let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
            assert_eq!(rows.len(), 9, "three families of three levels");
            for r in &rows {
                let e: f64 = r[col("rel_err_T_percent")].parse().unwrap();
                let m: f64 = r[col("rel_err_max_percent")].parse().unwrap();
                assert!(e > 0.0 && m >= e * (1.0 - 1e-12), "{r:?}");
                let o: f64 = r[col("order_T")].parse().unwrap();
                // An order from the second level of each family on (the k family
                // varies the steps).
                let first = if r[col("family")] == "k" {
                    r[col("steps")] == "4"
                } else {
                    r[col("n")] == "4"
                };
                assert_eq!(o.is_finite(), !first, "{r:?}");
            }
            assert!(out.join("split.png").exists() && md.contains("**The h and k parts"));
        } else {
            assert!(!out.join("split.csv").exists());
            assert!(
                md.contains("No h and k parts: the damping is not proportional"),
                "{md}"
            );
        }
    }
    // A steady and an elastic copy of the cantilever: the h = k families only, the
    // steady one in one step per level.
    let text = std::fs::read_to_string("data/scenarios/examples/cantilever.toml").unwrap();
    for problem in ["steady", "elastic"] {
        let file = dir.join(format!("{problem}.toml"));
        let kept: Vec<&str> = text
            .lines()
            .filter(|l| !l.starts_with("alpha") && !l.starts_with("beta"))
            .collect();
        std::fs::write(
            &file,
            kept.join("\n").replace(
                "problem = \"viscoelastic\"",
                &format!("problem = \"{problem}\""),
            ),
        )
        .unwrap();
        let out = dir.join(problem);
        succeed(
            evhi()
                .args(["study", "convergence", "--quick", "--scenario"])
                .arg(&file)
                .arg("--out")
                .arg(&out),
        );
        let md = std::fs::read_to_string(out.join("convergence.md")).unwrap();
        assert!(
            md.contains(&format!("No h and k parts: the problem is {problem}")),
            "{md}"
        );
        assert_eq!(md.contains("one step (steady)"), problem == "steady");
    }
    // `evhi --help` and `evhi study --help` list the studies, and each study
    // explains its options.
    for args in [vec!["--help"], vec!["study", "--help"]] {
        let help = evhi().args(&args).output().unwrap();
        let help = String::from_utf8_lossy(&help.stdout);
        for study in ["convergence", "time", "stability"] {
            assert!(help.contains(study), "{args:?} lacks {study}: {help}");
        }
    }
    let help = evhi()
        .args(["study", "convergence", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8_lossy(&help.stdout);
    assert!(
        help.contains("--quick") && help.contains("singular"),
        "{help}"
    );
}

/// `evhi study time` and `evhi study stability --quick` on user scenario files: each
/// writes its directory with finite errors and orders, the map's outcomes, and the
/// hypotheses per level; a steady scenario has no time study.
#[test]
fn the_time_and_stability_studies_run_on_user_scenarios() {
    let dir = scratch("studies");
    let read = |path: std::path::PathBuf| -> (Vec<String>, Vec<Vec<String>>) {
        let text = std::fs::read_to_string(&path).unwrap();
        let mut lines = text.lines().filter(|l| !l.starts_with('#'));
        let header = lines
            .next()
            .unwrap()
            .split(',')
            .map(str::to_string)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect();
        (header, rows)
    };
    for (name, file) in [
        ("five", "data/scenarios/examples/five_branch.toml"),
        ("cantilever", "data/scenarios/examples/cantilever.toml"),
    ] {
        let out = dir.join(format!("time-{name}"));
        succeed(
            evhi()
                .args(["study", "time", "--quick", "--scenario", file, "--out"])
                .arg(&out),
        );
        for f in [
            "time_study.csv",
            "time_study.md",
            "time_study.png",
            "time_study.svg",
            "scenario.toml",
        ] {
            assert!(out.join(f).exists(), "{name}: no {f}");
        }
        let (h, rows) = read(out.join("time_study.csv"));
        let c = |n: &str| h.iter().position(|x| x == n).unwrap();
        assert_eq!(rows.len(), 7, "{name}: N = 4 … 256");
        for (i, r) in rows.iter().enumerate() {
            let e: f64 = r[c("rel_err_max_percent")].parse().unwrap();
            assert!(e.is_finite() && e > 0.0, "{name}: {r:?}");
            let o: f64 = r[c("order_T")].parse().unwrap();
            assert_eq!(o.is_finite(), i > 0, "{name}: {r:?}");
        }
        let out = dir.join(format!("stab-{name}"));
        succeed(
            evhi()
                .args(["study", "stability", "--quick", "--scenario", file, "--out"])
                .arg(&out),
        );
        for f in [
            "stability.csv",
            "hypotheses.csv",
            "stability.md",
            "stability.png",
            "scenario.toml",
        ] {
            assert!(out.join(f).exists(), "{name}: no {f}");
        }
        let (h, rows) = read(out.join("stability.csv"));
        let outcome = h.iter().position(|x| x == "outcome").unwrap();
        let solver = h.iter().position(|x| x == "solver").unwrap();
        assert!(!rows.is_empty());
        // Newton, the default, is certified on both examples at every cell.
        for r in rows.iter().filter(|r| r[solver] == "newton") {
            assert_eq!(r[outcome], "certified", "{name}: {r:?}");
        }
        // A study's directory is a run directory: rerunning into it replaces its set,
        // while a file of the user's in it is refused by name and kept.
        let rerun = || {
            evhi()
                .args(["study", "stability", "--quick", "--scenario", file, "--out"])
                .arg(&out)
                .output()
                .unwrap()
        };
        if name == "cantilever" {
            let o = rerun();
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
            std::fs::write(out.join("my_notes.txt"), "mine").unwrap();
            let o = rerun();
            let err = String::from_utf8_lossy(&o.stderr);
            assert!(
                !o.status.success() && err.contains("`my_notes.txt`"),
                "{err}"
            );
            assert!(out.join("my_notes.txt").exists() && out.join("stability.csv").exists());
        }
        let (h, rows) = read(out.join("hypotheses.csv"));
        assert_eq!(rows.len(), 4, "{name}: two levels, two step counts");
        let hs = h.iter().position(|x| x == "H_s").unwrap();
        let convex = h.iter().position(|x| x == "steps_convex").unwrap();
        // The cantilever's law jumps down: H(j) fails, so H(s) does not apply and
        // the steps are not convex whatever the curvature between the jumps.
        for r in &rows {
            if name == "cantilever" {
                assert_eq!(
                    (r[hs].as_str(), r[convex].as_str()),
                    ("n/a (H(j) fails)", "no (downward jump)")
                );
            } else {
                assert!(r[hs] == "holds" || r[hs] == "fails", "{r:?}");
                assert!(r[convex] == "yes" || r[convex] == "no", "{r:?}");
            }
        }
    }
    let steady = dir.join("steady.toml");
    let text = std::fs::read_to_string("data/scenarios/examples/cantilever.toml").unwrap();
    let text: Vec<&str> = text
        .lines()
        .filter(|l| !l.starts_with("alpha") && !l.starts_with("beta"))
        .collect();
    std::fs::write(
        &steady,
        text.join("\n")
            .replace("problem = \"viscoelastic\"", "problem = \"steady\""),
    )
    .unwrap();
    let o = evhi()
        .args(["study", "time", "--quick", "--scenario"])
        .arg(&steady)
        .arg("--out")
        .arg(dir.join("refused"))
        .output()
        .unwrap();
    refused(&o, &["`scenario`", "one solve at T"]);
    // An elastic scenario has no time error either: refused by name.
    let elastic = dir.join("elastic.toml");
    std::fs::write(
        &elastic,
        std::fs::read_to_string(&steady)
            .unwrap()
            .replace("problem = \"steady\"", "problem = \"elastic\""),
    )
    .unwrap();
    let o = evhi()
        .args(["study", "time", "--quick", "--scenario"])
        .arg(&elastic)
        .arg("--out")
        .arg(dir.join("refused-elastic"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(
        err.contains("`scenario`")
            && err.contains("elastic")
            && err.contains("no time error")
            && err.contains("f(t_n)"),
        "{err}"
    );
}

/// `reproduce --jobs N` gives the same files whatever N: one worker, and more workers
/// than experiments, write byte-identical tables and figures (quick mode, a set
/// whose experiments run threads of their own, table1 among them); `--jobs 0` is
/// refused by name.
#[test]
fn reproduce_writes_the_same_files_whatever_the_jobs() {
    let dir = scratch("jobs");
    let names = ["hypotheses", "fig2", "fig3", "table1", "graded", "time"];
    for jobs in ["1", "8"] {
        succeed(
            evhi()
                .args(["reproduce", "--quick", "-q", "--jobs", jobs])
                .args(names)
                .arg("--data")
                .arg(dir.join(jobs).join("data"))
                .arg("--figures")
                .arg(dir.join(jobs).join("figures")),
        );
    }
    let mut compared = 0;
    for sub in ["data", "figures"] {
        let mut files: Vec<_> = std::fs::read_dir(dir.join("1").join(sub))
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
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
    let o = evhi()
        .args(["reproduce", "fig2", "--quick", "--jobs", "0", "--data"])
        .arg(dir.join("zero"))
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("`jobs`"));
}

/// A grading whose smallest triangles double precision cannot resolve is refused by
/// name, with the least grading the level allows, before any mesh is built (it used to
/// refine until memory ran out); a grading at that bound runs.
#[test]
fn a_grading_finer_than_double_precision_is_refused_by_name() {
    let dir = scratch("grading");
    let run = |mu: &str| {
        evhi()
            .args([
                "solve",
                "--scenario",
                "figure",
                "--mesh",
                "graded",
                "--grading",
                mu,
            ])
            .args(["--n", "32", "--steps", "2", "--out"])
            .arg(dir.join(format!("g{mu}")))
            .output()
            .unwrap()
    };
    let o = run("0.05");
    refused(&o, &["`grading`", "at least 0.088 at n = 32"]);
    assert!(!dir.join("g0.05").exists());
    let o = run("0.088");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A Gamma_3 whose nodes the supports all hold (at this n) is refused by name, with the
/// nodes and what to change; it used to panic while setting up the output. One level
/// finer, a free node appears and the run goes.
#[test]
fn a_gamma3_without_a_free_node_is_refused_by_name() {
    let dir = scratch("gamma3-held");
    let text = std::fs::read_to_string("data/scenarios/figure.toml").unwrap();
    let file = dir.join("held.toml");
    std::fs::write(
        &file,
        format!(
            "{text}\n[geometry]\ncontact = [1.0, 1.25]\n[geometry.supports]\nbottom = [\
             {{from = 0.0, to = 1.0, kind = \"clamped\"}}, \
             {{from = 1.25, to = 2.0, kind = \"clamped\"}}]\n"
        ),
    )
    .unwrap();
    let run = |n: &str| {
        evhi()
            .args(["solve", "--scenario"])
            .arg(&file)
            .args(["--n", n, "--steps", "2", "--out"])
            .arg(dir.join(format!("run{n}")))
            .output()
            .unwrap()
    };
    let o = run("8");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("`geometry.contact`") && err.contains("(x = 1, 1.25) are all held"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
    let o = run("16");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A step count out of range is refused before anything is sized by it (a table of
/// 4e12 flags used to be allocated first: the process was killed, without a word).
#[test]
fn a_huge_step_count_is_refused_before_any_allocation() {
    let dir = scratch("huge-steps");
    let o = evhi()
        .args([
            "solve",
            "--scenario",
            "figure",
            "--n",
            "4",
            "--steps",
            "4000000000000",
        ])
        .arg("--out")
        .arg(dir.join("run"))
        .output()
        .unwrap();
    refused(&o, &["`steps`", "an integer in 1..=1000000"]);
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
        let text = std::fs::read_to_string(out.join(file)).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let cols: Vec<&str> = lines[2].split(',').collect();
        let at = cols.iter().position(|c| *c == column).unwrap();
        let mut row: Vec<&str> = lines[3].split(',').collect();
        row[at] = value;
        let mut all: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        all[3] = row.join(",");
        all.join("\n") + "\n"
    };
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let nodes = std::fs::read_to_string(out.join("nodes.csv")).unwrap();
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
        (
            "nodes.csv",
            nodes.lines().take(4).map(|l| format!("{l}\n")).collect(),
            "1 node(s) are not a lattice",
        ),
    ] {
        std::fs::write(out.join(file), &text).unwrap();
        let o = evhi().arg("plot").arg(&out).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{expect}: drawn");
        assert!(err.contains(expect) && !err.contains("panicked"), "{err}");
        let leftovers: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|f| f.contains(".tmp-"))
            .collect();
        assert!(leftovers.is_empty(), "{leftovers:?}");
        std::fs::write(out.join("summary.csv"), &summary).unwrap();
        std::fs::write(out.join("nodes.csv"), &nodes).unwrap();
    }
    succeed(evhi().arg("plot").arg(&out));

    let graded = dir.join("graded");
    succeed(small_solve(&graded).args(["--mesh", "graded"]));
    let tri = std::fs::read_to_string(graded.join("triangles.csv")).unwrap();
    let lines: Vec<&str> = tri.lines().collect();
    let data = lines.iter().position(|l| !l.starts_with('#')).unwrap() + 1;
    for bad in ["NaN", "-5", "1.5"] {
        let mut row: Vec<&str> = lines[data].split(',').collect();
        row[0] = bad;
        let mut all: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        all[data] = row.join(",");
        std::fs::write(graded.join("triangles.csv"), all.join("\n") + "\n").unwrap();
        let o = evhi().arg("plot").arg(&graded).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{bad}: drawn");
        assert!(err.contains("not three node numbers"), "{err}");
    }
}

/// An absurd n is refused by the memory guard (the integer count of unknowns used to
/// wrap and let n = 5643117386039700 pass `show`), with the need in readable units.
#[test]
fn an_absurd_n_is_refused_by_the_memory_guard() {
    for cmd in [
        vec!["show", "figure", "--n", "5643117386039700"],
        vec!["show", "figure", "--n", "4294967296"],
    ] {
        let o = evhi().args(&cmd).output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{cmd:?} passed");
        assert!(
            err.contains("`n`") && err.contains("fits in memory") && err.contains("e"),
            "{err}"
        );
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
    let o = small_solve(&dir.join("neg"))
        .args(["--certificate-tol", "-1e-10"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("`certificate-tol`") && err.contains("[1e-15, 1e-4]"),
        "{err}"
    );

    let text = std::fs::read_to_string("data/scenarios/figure.toml").unwrap();
    let steady: String = text
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
    let file = dir.join("steady.toml");
    std::fs::write(&file, steady).unwrap();
    let o = evhi()
        .arg("show")
        .arg(&file)
        .args(["--n", "8"])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("steps = 1)"));
    let o = evhi()
        .arg("show")
        .arg(&file)
        .args(["--n", "8", "--steps", "4"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("`steps`"));

    let cantilever = "data/scenarios/examples/cantilever.toml";
    let o = evhi().args(["show", cantilever]).output().unwrap();
    let shown = String::from_utf8_lossy(&o.stdout);
    assert!(!shown.contains("H(j): constant m"), "{shown}");
    let run = dir.join("cantilever");
    succeed(
        evhi()
            .args([
                "solve",
                "--scenario",
                cantilever,
                "--n",
                "8",
                "--steps",
                "2",
                "--out",
            ])
            .arg(&run),
    );
    let summary = std::fs::read_to_string(run.join("summary.csv")).unwrap();
    let lines: Vec<&str> = summary.lines().filter(|l| !l.starts_with('#')).collect();
    let at = lines[0]
        .split(',')
        .position(|c| c == "m_trace_norm_sq")
        .unwrap();
    assert_eq!(lines[1].split(',').nth(at), Some("NaN"));
}

/// What the second audit found in the studies and `reproduce`, each refused by name
/// before any work or output: a scene whose study reference would exceed the largest
/// mesh (it refined until an allocation failed), a scene with no load (its tables were
/// all NaN with exit 0), another cell pattern (ignored, or failing late), a scene no
/// level up to 256 resolves (the advice named an n the study does not take).
#[test]
fn studies_refuse_what_they_cannot_measure() {
    let dir = scratch("study-refusals");
    let cantilever = std::fs::read_to_string("data/scenarios/examples/cantilever.toml").unwrap();
    let figure = std::fs::read_to_string("data/scenarios/figure.toml").unwrap();
    let cases = [
        (
            "fine.toml",
            cantilever.replacen("from = 1.0", "from = 1.0078125", 1),
            "convergence",
            "the reference would be at n = 8192",
        ),
        (
            "third.toml",
            cantilever.replacen("from = 1.0", "from = 0.3", 1),
            "convergence",
            "it takes no --n",
        ),
        (
            "zero.toml",
            figure
                .replacen("f0 = [0.0, -5.0]", "f0 = [0.0, 0.0]", 1)
                .replacen("f2 = [0.0, -75.0]", "f2 = [0.0, 0.0]", 1),
            "convergence",
            "is not zero",
        ),
        (
            "zero.toml",
            figure
                .replacen("f0 = [0.0, -5.0]", "f0 = [0.0, 0.0]", 1)
                .replacen("f2 = [0.0, -75.0]", "f2 = [0.0, 0.0]", 1),
            "time",
            "is not zero",
        ),
        (
            "criss.toml",
            format!("{figure}\n[geometry]\npattern = \"crisscross\"\n"),
            "convergence",
            "`geometry.pattern`",
        ),
    ];
    for (i, (file, text, study, expect)) in cases.iter().enumerate() {
        let path = dir.join(format!("{i}-{file}"));
        std::fs::write(&path, text).unwrap();
        let out = dir.join(format!("out{i}"));
        let o = evhi()
            .args(["study", study, "--quick", "--scenario"])
            .arg(&path)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{file} {study} passed");
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
    let file = dir.join("a-file");
    std::fs::write(&file, "x").unwrap();
    let run = |extra: &[&str], data: &std::path::Path, figures: &std::path::Path| {
        evhi()
            .args(["reproduce", "--quick", "-q"])
            .args(extra)
            .arg("--data")
            .arg(data)
            .arg("--figures")
            .arg(figures)
            .output()
            .unwrap()
    };
    for (extra, expect) in [
        (&["fig2", "--jobs", "0"][..], "`jobs`"),
        (&["fig2", "--record-times"][..], "`record-times`"),
        (&["fig2", "--reference", "64"][..], "`reference`"),
    ] {
        let o = run(extra, &data, &figures);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains(expect),
            "{extra:?}: {err}"
        );
        assert!(
            !data.exists() && !figures.exists(),
            "{extra:?} made a directory"
        );
    }
    for (d, f, expect) in [(&file, &figures, "`data`"), (&data, &file, "`figures`")] {
        let o = run(&["fig2"], d, f);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success() && err.contains(expect), "{err}");
    }
    let _ = std::fs::remove_dir_all(&data);
    let o = run(&["table1", "--reference", "64"], &data, &figures);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success() && err.contains("missing"), "{err}");
    assert!(!data.join("table1_ref64.csv").exists());
    succeed(
        evhi()
            .args(["reproduce", "--quick", "-q", "table1", "--data"])
            .arg(&data)
            .arg("--figures")
            .arg(&figures),
    );
    let o = run(&["table1", "--reference", "64"], &data, &figures);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let shift = std::fs::read_to_string(data.join("table1_reference_shift_ref64.csv")).unwrap();
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
    let child = evhi()
        .args(["reproduce", "--quick", "-q", "example", "--data"])
        .arg(dir.join("data"))
        .arg("--figures")
        .arg(dir.join("figures"))
        .current_dir(&dir)
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let pid = child.id().to_string();
    let o = child.wait_with_output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(dir.join("data/example_study_convergence.md").exists());
    let left: Vec<String> = std::fs::read_dir(std::env::temp_dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
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
    let o = evhi()
        .args(["solve", "--scenario", softening, "--solver", "convexify"])
        .args(["--n", "8", "--steps", "2", "--out"])
        .arg(dir.join("run"))
        .output()
        .unwrap();
    refused(&o, &["`solver`", "piecewise-affine"]);
    let out = dir.join("stability");
    succeed(
        evhi()
            .args([
                "study",
                "stability",
                "--quick",
                "--scenario",
                softening,
                "--out",
            ])
            .arg(&out),
    );
    let table = std::fs::read_to_string(out.join("stability.csv")).unwrap();
    assert!(!table.contains("Failed("), "{table}");
    let rows: Vec<&str> = table
        .lines()
        .filter(|l| l.contains(",convexify,") || l.contains(",penalty,"))
        .collect();
    assert!(!rows.is_empty());
    assert!(rows.iter().all(|r| r.contains("\"error: ")), "{rows:?}");

    let smooth = dir.join("smooth");
    succeed(
        evhi()
            .args([
                "study",
                "convergence",
                "--quick",
                "--scenario",
                "smooth",
                "--out",
            ])
            .arg(&smooth),
    );
    let csv = std::fs::read_to_string(smooth.join("convergence.csv")).unwrap();
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
    let o = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 3000000 && exec '{}' solve --scenario figure --n 4 --steps 1000000 --out '{}'",
            env!("CARGO_BIN_EXE_evhi"),
            dir.join("run").display()
        ))
        .output()
        .unwrap();
    refused(&o, &["`steps`", "records fit in memory"]);
}

/// The time study's table says what its NaN and inf mean where a scene has them (the
/// cantilever: no single relaxation time, no limit g), and the convergence summary of
/// a scene whose singular points all lack a computed exponent calls the limit of the
/// uniform orders unknown instead of 1.
#[test]
fn tables_say_what_their_nan_and_inf_mean() {
    let dir = scratch("nan-legends");
    let out = dir.join("time");
    succeed(
        evhi()
            .args(["study", "time", "--quick", "--scenario"])
            .arg("data/scenarios/examples/cantilever.toml")
            .arg("--out")
            .arg(&out),
    );
    let csv = std::fs::read_to_string(out.join("time_study.csv")).unwrap();
    let legend = csv.lines().nth(1).unwrap();
    assert!(
        legend.contains("NaN where C is not a multiple of G")
            && legend.contains("g = inf: no limit"),
        "{legend}"
    );
    // Rollers on the upper halves of both sides and on the top: the singular points
    // are where rollers end, whose exponent the wedge analysis does not give.
    let text = std::fs::read_to_string("data/scenarios/figure.toml")
        .unwrap()
        .replacen("f2 = [0.0, -75.0]", "f2 = [0.0, 0.0]", 1);
    let file = dir.join("rollers.toml");
    std::fs::write(
        &file,
        format!(
            "{text}\n[geometry.supports]\nleft = [{{from = 0.5, to = 1.0, kind = \"rollers\"}}]\n\
             right = [{{from = 0.5, to = 1.0, kind = \"rollers\"}}]\ntop = \"rollers\"\n"
        ),
    )
    .unwrap();
    let out = dir.join("conv");
    let o = evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&file)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let md = std::fs::read_to_string(out.join("convergence.md")).unwrap();
    assert!(md.contains("(not known here:"), "{md}");
}

/// What a third audit (the docs against the outputs) found wrong in the run
/// directory: `h` in summary.csv is the book's W/(2n) (it was 1/n whatever the
/// width), and a uniform run's lattice in nodes.csv keeps the mesh's last column and
/// row whatever n (a stride of n/32 alone left them out for n = 100), and is drawn.
#[test]
fn the_run_directory_holds_what_the_book_says() {
    let dir = scratch("run-as-documented");
    let text = std::fs::read_to_string("data/scenarios/figure.toml").unwrap();
    let wide = dir.join("wide.toml");
    std::fs::write(&wide, format!("{text}\n[geometry]\nwidth = 4.0\n")).unwrap();
    let out = dir.join("wide");
    succeed(
        evhi()
            .args(["solve", "--scenario"])
            .arg(&wide)
            .args(["--n", "16", "--steps", "2", "--out"])
            .arg(&out),
    );
    let column = |file: &std::path::Path, name: &str| -> Vec<f64> {
        let text = std::fs::read_to_string(file).unwrap();
        let mut lines = text.lines().filter(|l| !l.starts_with('#'));
        let header: Vec<&str> = lines.next().unwrap().split(',').collect();
        let at = header.iter().position(|c| *c == name).unwrap();
        lines
            .map(|l| l.split(',').nth(at).unwrap().parse().unwrap())
            .collect()
    };
    assert_eq!(column(&out.join("summary.csv"), "h"), vec![4.0 / 32.0]);

    let out = dir.join("n100");
    succeed(
        evhi()
            .args([
                "solve",
                "--scenario",
                "figure",
                "--n",
                "100",
                "--steps",
                "2",
                "--out",
            ])
            .arg(&out),
    );
    let (x, y) = (
        column(&out.join("nodes.csv"), "x"),
        column(&out.join("nodes.csv"), "y"),
    );
    let top = |v: &[f64]| v.iter().copied().fold(f64::MIN, f64::max);
    assert_eq!((top(&x), top(&y)), (2.0, 1.0));
    succeed(evhi().arg("plot").arg(&out));
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
        let file = base.join(format!("{problem}.toml"));
        std::fs::write(&file, scene(problem)).unwrap();
        let o = evhi()
            .args(["solve", "--n", "12", "--scenario"])
            .arg(&file)
            .arg("--out")
            .arg(base.join(problem))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{problem}: {err}");
        assert_eq!(err.contains("H(f)"), warns, "{problem}: {err}");
        if warns {
            assert!(
                err.contains("`loads.traction[0]`") && !err.contains("f2"),
                "{err}"
            );
        }
        let shown = evhi().arg("show").arg(&file).output().unwrap();
        let out = String::from_utf8_lossy(&shown.stdout);
        assert_eq!(out.contains("not asked"), !warns, "{problem}: {out}");
    }
}
