//! The studies on scenes of one's own: levels chosen so that every mesh the study
//! builds resolves the scene.

mod common;
use common::{Csv, evhi, ok, scratch, written};

/// A 3 x 1 scene whose supports end at y = 0.4 and 0.6 and whose contact zone starts at
/// 0.375 (issue 41, item 8): the coarsest power-of-two grid that resolves it at one
/// level, n = 16 (5 rows), misses y = 0.4 at 2n = 32 (11 rows), and the study used to
/// refuse it naming an n it does not take. It now starts from the coarsest n0 whose
/// every level resolves the scene (120: 40 rows, then 80).
#[test]
fn a_study_picks_levels_that_all_resolve_the_scene() {
    let dir = scratch("study-levels");
    let scene = written(
        dir.join("k2.toml"),
        "name = \"K2\"\nT = 1.0\ng = 0.05\n[geometry]\nwidth = 3.0\nheight = 1.0\n\
         contact = [0.375, 2.25]\n[geometry.supports]\n\
         left = [{ from = 0.0, to = 0.4, kind = \"rollers\" }, { from = 0.6, to = 1.0, kind = \"clamped\" }]\n\
         bottom = [{ from = 2.25, to = 3.0, kind = \"rollers\" }]\n\
         [material]\nE = 1000.0\nkappa = 0.3\nalpha = 50.0\nbeta = 30.0\n\
         [loads]\nf0 = [0.5, -4.0]\nf2 = [0.0, -20.0]\nhistory = { ramp = 0.3 }\n\
         [law]\nbreakpoints = [0.0, 0.02, 0.04]\nslopes = [0.0, 400.0, -100.0, 300.0]\n",
    );
    let out = dir.join("stab");
    ok(&evhi()
        .args(["study", "stability", "--quick", "--scenario"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap());
    let table = Csv::read(out.join("stability.csv"));
    let mut levels: Vec<f64> = table.column_f64("n");
    levels.dedup();
    assert_eq!(levels, vec![120.0, 240.0]);
    assert!(table.column_str("outcome").contains(&"certified"));
}

/// The convergence study lists an end of Γ3 inside the bottom as a singular point with no
/// predicted exponent, and its graded family refines towards it (issue 41, item 16).
#[test]
fn the_convergence_study_knows_the_ends_of_gamma_3() {
    let dir = scratch("study-contact-end");
    let scene = written(
        dir.join("block.toml"),
        "name = \"block\"\nT = 1.0\ng = 0.05\n[geometry]\nwidth = 2.0\nheight = 0.5\n\
         supports = { left = \"clamped\" }\ncontact = [0.5, 2.0]\n\
         [material]\nE = 1000.0\nkappa = 0.25\nalpha = 40.0\nbeta = 80.0\n\
         [loads]\nf0 = [0.0, -5.0]\nf2 = [0.0, -20.0]\nhistory = { ramp = 0.25 }\n\
         [law]\nbreakpoints = [0.0, 0.02, 0.04]\nslopes = [0.0, 500.0, -5.0, 300.0]\n",
    );
    let out = dir.join("conv");
    ok(&evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap());
    let sing = Csv::read(out.join("singular.csv"));
    let kinds = sing.column_str("kind");
    let at = kinds
        .iter()
        .position(|k| *k == "contact end")
        .expect("a contact end");
    assert_eq!(sing.f64(at, "x"), 0.5);
    assert!(sing.f64(at, "predicted_exponent").is_nan());
    let md = std::fs::read_to_string(out.join("convergence.md")).unwrap();
    assert!(md.contains("an end of Gamma_3 inside the bottom"), "{md}");
}

/// The convergence study says what it will cost before it starts (issue 41, item 15):
/// on a 3 x 1 scene whose coarsest resolving level is 12, quick mode's full plan has its
/// reference at n = 384, about 27 s of work, beyond quick mode's budget of 10 s (issue
/// 47, item 16), so it drops a level: reference at n = 192, about 3 s. The first line
/// says both before any work (the run is stopped there).
#[test]
fn the_convergence_study_says_its_cost_first() {
    use std::io::BufRead;
    let dir = scratch("study-cost");
    let scene = written(
        dir.join("k3.toml"),
        "name = \"k3\"\nT = 1.0\ng = 0.05\n[geometry]\nwidth = 3.0\nheight = 1.0\n\
         [geometry.supports]\nleft = [{ from = 0.0, to = 0.5, kind = \"clamped\" }]\n\
         [material]\nE = 1000.0\nkappa = 0.3\nalpha = 50.0\nbeta = 30.0\n\
         [loads]\nf0 = [0.0, -4.0]\nf2 = [0.0, -20.0]\nhistory = { ramp = 0.3 }\n\
         [law]\nbreakpoints = [0.0, 0.02, 0.04]\nslopes = [0.0, 400.0, -100.0, 300.0]\n",
    );
    let mut child = evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&scene)
        .arg("--out")
        .arg(dir.join("conv"))
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    std::io::BufReader::new(child.stderr.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    let _ = child.kill();
    let _ = child.wait();
    assert!(
        first.starts_with("study convergence (quick): uniform levels n = 12 to 48")
            && first.contains(
                "reference at n = 192 with about 6.5e4 unknowns and 192 step(s): about 3 s \
                 of work, estimated for a two-core AMD EPYC"
            )
            && first.contains(
                "cut by 1 level(s) to quick mode's budget of 10 s from uniform levels n = \
                 12 to 96"
            )
            && first.contains(
                "reference at n = 384 with about 2.6e5 unknowns and 384 step(s): about 27 s \
                 of work"
            ),
        "{first}"
    );
}

/// A smooth softening law on which the default Newton stalls (issue 41, item 5): the
/// convergence study fails naming `--solver`, which the studies now take, and with
/// `--solver newton-no-line-search` it runs; an uncertified solver is refused by name.
#[test]
fn every_study_takes_a_solver() {
    let dir = scratch("study-solver");
    let scene = written(
        dir.join("cs.toml"),
        "name = \"cs\"\nT = 1.0\ng = \"none\"\nproblem = \"steady\"\n[geometry]\nwidth = 2.0\n\
         height = 0.5\npattern = \"diagonal\"\n[geometry.supports]\nleft = \"clamped\"\n\
         [material]\nE = 1000.0\nkappa = 0.3\n[loads]\nf0 = [0.0, -5.0]\nf2 = [0.0, 0.0]\n\
         [[loads.traction]]\nside = \"top\"\nfrom = 1.0\nto = 2.0\nf = [0.0, -20.0]\n\
         [law]\nkind = \"softening\"\nstiffness = 900.0\nlength = 0.01\n",
    );
    let study = |kind: &str, extra: &[&str], out: &str| {
        evhi()
            .args(["study", kind, "--quick", "--scenario"])
            .arg(&scene)
            .args(extra)
            .arg("--out")
            .arg(dir.join(out))
            .output()
            .unwrap()
    };
    let failed = study("convergence", &[], "plain");
    assert!(!failed.status.success());
    let err = String::from_utf8_lossy(&failed.stderr);
    // The advice names what a study takes: --solver, not the --steps of `solve`.
    assert!(
        err.contains("`--solver proxgrad`") && !err.contains("more `--steps`"),
        "{err}"
    );
    ok(&study(
        "convergence",
        &["--solver", "newton-no-line-search"],
        "nnls",
    ));
    let table = Csv::read(dir.join("nnls/convergence.csv"));
    assert!(table.column_f64("n").len() >= 8);
    // The stability map runs the one solver asked for.
    ok(&study("stability", &["--solver", "proxgrad"], "stab"));
    let map = Csv::read(dir.join("stab/stability.csv"));
    assert!(map.column_str("solver").iter().all(|s| *s == "proxgrad"));
    // The time study takes certified solvers only.
    let refused = evhi()
        .args([
            "study",
            "time",
            "--quick",
            "--scenario",
            "figure",
            "--solver",
            "penalty",
        ])
        .arg("--out")
        .arg(dir.join("time"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&refused.stderr);
    assert!(
        !refused.status.success() && err.contains("`solver`") && err.contains("certified"),
        "{err}"
    );
    assert!(!dir.join("time").exists());
}

/// The convergence study warns when grading gains nothing (issue 41, item 16): a body
/// held by rollers whose top is clamped on [0.5, 1.5] under its own weight excites the
/// clamp's ends (the only singular points) so weakly that the uniform family already
/// converges at order 1; the graded family's last order is then no better, and the
/// study says so on stderr and in convergence.md.
#[test]
fn the_convergence_study_warns_when_grading_gains_nothing() {
    let dir = scratch("study-no-gain");
    let scene = written(
        dir.join("e.toml"),
        "name = \"e\"\nT = 1.0\ng = 0.05\nproblem = \"steady\"\n[geometry]\nwidth = 2.0\n\
         height = 1.0\n[geometry.supports]\nleft = \"rollers\"\nright = \"rollers\"\n\
         top = [{ from = 0.0, to = 0.5, kind = \"rollers\" }, { from = 0.5, to = 1.5, kind = \
         \"clamped\" }, { from = 1.5, to = 2.0, kind = \"rollers\" }]\n[material]\nE = 1000.0\n\
         kappa = 0.3\n[loads]\nf0 = [0.0, -20.0]\nf2 = [0.0, 0.0]\n[law]\nbreakpoints = [0.0]\n\
         slopes = [0.0, 500.0]\n",
    );
    let out = dir.join("conv");
    let o = evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&scene)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("warning: the graded family's last order") && err.contains("no better"),
        "{err}"
    );
    let md = std::fs::read_to_string(out.join("convergence.md")).unwrap();
    assert!(
        md.contains("Warning: the graded family's last order"),
        "{md}"
    );
    // And the numbers behind it: both families' last orders near 1, graded within
    // 0.05 of uniform or below.
    let t = Csv::read(out.join("convergence.csv"));
    let (fam, order) = (t.column_str("family"), t.column_f64("order_dofs"));
    let last = |f: &str| {
        (0..fam.len())
            .filter(|&i| fam[i] == f && order[i].is_finite())
            .map(|i| order[i])
            .next_back()
            .unwrap()
    };
    let (g, u) = (last("graded"), last("uniform"));
    assert!(g <= u + 0.05 && u > 0.95, "{g} {u}");
}

/// A 64 x 1 strip clamped at both ends under the paper's loads (issue 41, item 6): its
/// free sag is tens of thousands of times g, and the displacement recovered from a
/// solved condensed step misses the full system by far more than the certificate
/// allows. The run is refused with that cause, naming the free response against g, not
/// with a solver failure and its advice to change solvers.
#[test]
fn a_strip_too_long_for_its_loads_is_refused_with_the_cause() {
    let dir = scratch("strip");
    let scene = written(
        dir.join("inv.toml"),
        "name = \"inv\"\nT = 1.0\ng = 0.1\n[geometry]\nwidth = 64.0\nheight = 1.0\n\
         [geometry.supports]\nleft = \"clamped\"\nright = \"clamped\"\n[material]\nE = 1000.0\n\
         kappa = 0.4\nalpha = 100.0\nbeta = 50.0\n[loads]\nf0 = [0.0, -5.0]\nf2 = [0.0, -75.0]\n\
         [law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n",
    );
    // The default (reduced) loop and the general one.
    for path in ["reduced", "general"] {
        let o = evhi()
            .args([
                "solve",
                "--n",
                "64",
                "--steps",
                "16",
                "--path",
                path,
                "--scenario",
            ])
            .arg(&scene)
            .arg("--out")
            .arg(dir.join(path))
            .output()
            .unwrap();
        assert!(!o.status.success());
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            err.contains("Without contact the load would move the contact nodes by up to")
                && err.contains("times g = 1e-1")
                && err.contains("too long or too thin for its loads")
                && !err.contains("another step solver"),
            "{path}: {err}"
        );
        if path == "reduced" {
            assert!(err.contains("5.7e4 times g"), "{err}");
        }
        assert!(!dir.join(path).exists());
    }
}

/// A 64 x 1 strip under the paper's loads, its supports the paper's (issue 47, item 10):
/// its quick convergence study used to work for minutes and then fail at the graded
/// reference with a solver's failure and advice to take more `--steps`, which a study
/// does not take. It now solves its coarsest level first, as `solve` would, and is
/// refused in a moment with the time loop's own cause, the cancellation in recovering
/// the displacement, and what to change in the scene; so is the strip clamped at both
/// ends (coarsest level 32 against 128). No directory is made.
#[test]
fn a_study_refuses_a_strip_too_long_for_its_loads_at_once() {
    let dir = scratch("study-strip");
    for (name, supports, n0) in [
        ("paper", "", "n = 128 with 128 step(s)"),
        (
            "clamped",
            "[geometry.supports]\nleft = \"clamped\"\nright = \"clamped\"\n",
            "n = 32 with 32 step(s)",
        ),
    ] {
        let scene = written(
            dir.join(format!("{name}.toml")),
            format!(
                "name = \"{name}\"\nT = 1.0\ng = 0.1\n[geometry]\nwidth = 64.0\nheight = 1.0\n\
                 {supports}[material]\nE = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0\n\
                 [loads]\nf0 = [0.0, -5.0]\nf2 = [0.0, -75.0]\n\
                 [law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n"
            ),
        );
        let out = dir.join(name);
        let clock = std::time::Instant::now();
        let o = evhi()
            .args(["study", "convergence", "--quick", "--scenario"])
            .arg(&scene)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap();
        let secs = clock.elapsed().as_secs_f64();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{name}: {err}");
        assert!(
            err.contains(&format!(
                "the study's coarsest level, {n0}, solved first as a check of the scene"
            )) && err.contains("step 1 ")
                && err.contains("Without contact the load would move the contact nodes by up to")
                && err.contains("times g = 1e-1")
                && err.contains("too long or too thin for its loads")
                && !err.contains("--steps")
                && !err.contains("another step solver"),
            "{name}: {err}"
        );
        assert!(secs < 10.0, "{name}: {secs} s");
        assert!(!out.exists());
    }
}

/// A 64 x 1 strip under light loads (issue 47, item 11): the split's structured meshes
/// have n H / W rows of cells, rounded and at least 1, so 1 row at n = 32 and 4 at its
/// reference's n = 256; a level is not embedded in the reference, and the split used to
/// fail with "got 32 to 512, expected a fine n that is a multiple of the coarse n". The
/// study now runs without the split and says why, naming the rows, before any work (the
/// run is stopped there); on a 3 x 1 strip (1 row at n = 4, 21 at 64) the whole quick
/// study runs, its summary saying the same. The library's embedding names the rows too.
#[test]
fn a_study_without_nested_uniform_meshes_runs_without_the_split() {
    use std::io::BufRead;
    let dir = scratch("study-rows");
    let strip = |name: &str, width: f64, f0: &str, f2: &str| {
        written(
            dir.join(format!("{name}.toml")),
            format!(
                "name = \"{name}\"\nT = 1.0\ng = 0.1\n[geometry]\nwidth = {width:?}\nheight = 1.0\n\
                 [geometry.supports]\nleft = \"clamped\"\nright = \"clamped\"\n[material]\n\
                 E = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0\n\
                 [loads]\nf0 = [0.0, {f0}]\nf2 = [0.0, {f2}]\n\
                 [law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n"
            ),
        )
    };
    let long = strip("long", 64.0, "-1e-6", "-1e-5");
    let mut child = evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&long)
        .arg("--out")
        .arg(dir.join("long"))
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut lines = std::io::BufReader::new(child.stderr.take().unwrap()).lines();
    let (first, second) = (
        lines.next().unwrap().unwrap(),
        lines.next().unwrap().unwrap(),
    );
    let _ = child.kill();
    let _ = child.wait();
    assert!(first.starts_with("study convergence (quick)"), "{first}");
    assert!(
        second.starts_with(
            "study convergence: no h and k parts: the split's uniform meshes do not nest"
        ) && second.contains(
            "the 64 x 1 rectangle has 1 row(s) of cells at n = 32 and 4 at its reference's n = 256"
        ),
        "{second}"
    );
    // The 3 x 1 strip, whole.
    let short = strip("short", 3.0, "-5.0", "-75.0");
    let out = dir.join("short");
    ok(&evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&short)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap());
    let md = std::fs::read_to_string(out.join("convergence.md")).unwrap();
    assert!(
        md.contains("No h and k parts: the split's uniform meshes do not nest: the 3 x 1 rectangle has 1 row(s) of cells at n = 4 and 21 at its reference's n = 64"),
        "{md}"
    );
    assert!(!out.join("split.csv").exists());
    assert_eq!(Csv::read(out.join("convergence.csv")).len(), 8);
    // The embedding between the two meshes the split used to try.
    let scn = evhi::scenario::Scenario::read(long.to_str().unwrap())
        .unwrap()
        .0;
    let err = evhi::mesh::Interpolation::nested(&scn.mesh(32).unwrap(), &scn.mesh(512).unwrap())
        .err()
        .unwrap()
        .to_string();
    assert!(
        err.contains("got 32 to 512, whose meshes have 1 to 8 row(s) of cells")
            && err.contains("nested meshes, whose rows grow as n does (16 times)"),
        "{err}"
    );
}

/// Issue 41's 3 x 1 scene `K2` (six singular points, three tractions, a tabulated history,
/// plane stress): its quick convergence study took 84 to 88 s and 2.4 GB on an idle
/// two-core machine (issue 47, item 16; 155 s when the rates were re-fitted on a quiet
/// machine). Quick mode now keeps to a budget of about 10 s of work: the study says
/// first that it drops two levels (reference at n = 128 instead of 512, about 3 min of
/// work; the run is stopped there). A 3 x 1 scene whose coarsest level
/// is 12 runs its cut plan whole (three levels per family), its summary saying why. A
/// 64 x 1 strip whose coarsest resolving level is 128 is over the budget even cut to two
/// levels, and is refused before any work with what each plan would take (its full
/// study's reference would exceed the largest mesh, which the message says, so the
/// remedy is the scene's).
#[test]
fn quick_mode_keeps_to_its_budget() {
    use std::io::BufRead;
    let dir = scratch("study-budget");
    let k2 = written(
        dir.join("k2.toml"),
        "name = \"K2\"\nT = 1.0\ng = 0.05\n[geometry]\nwidth = 3.0\nheight = 1.0\n\
         contact = [0.375, 2.25]\npattern = \"diagonal\"\n[geometry.supports]\n\
         left = [{ from = 0.0, to = 0.4, kind = \"rollers\" }, { from = 0.6, to = 1.0, kind = \"clamped\" }]\n\
         bottom = [{ from = 2.25, to = 3.0, kind = \"rollers\" }]\n\
         top = [{ from = 2.25, to = 3.0, kind = \"rollers\" }]\n\
         [material]\nlambda = 600.0\nmu = 350.0\nalpha = 50.0\nbeta = 30.0\nplane = \"stress\"\n\
         [loads]\nf0 = [0.5, -4.0]\nf2 = [1.0, 0.0]\n\
         history = { table = [[0, 0], [0.3, 1.0], [0.6, 0.5], [1.0, 1.2]] }\n\
         [[loads.traction]]\nside = \"top\"\nfrom = 0.75\nto = 2.25\nf = [2.0, -80.0]\n\
         [[loads.traction]]\nside = \"right\"\nfrom = 0.2\nto = 1.0\nf = [-5.0, 2.0]\n\
         [[loads.traction]]\nside = \"bottom\"\nfrom = 0.0\nto = 0.375\nf = [1.0, 3.0]\n\
         [law]\nbreakpoints = [0.0, 0.02, 0.04]\nslopes = [0.0, 400.0, -100.0, 300.0]\n\
         jumps = [0.0, 1.0, -0.5]\n",
    );
    let clock = std::time::Instant::now();
    let mut child = evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&k2)
        .arg("--out")
        .arg(dir.join("k2"))
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = String::new();
    std::io::BufReader::new(child.stderr.take().unwrap())
        .read_line(&mut first)
        .unwrap();
    let secs = clock.elapsed().as_secs_f64();
    let _ = child.kill();
    let _ = child.wait();
    assert!(
        first.starts_with(
            "study convergence (quick): uniform levels n = 16 to 32, graded n = 16 to 32, \
             reference at n = 128 with about 7.0e4 unknowns and 128 step(s): about 2 s of work"
        ) && first.contains(
            "cut by 2 level(s) to quick mode's budget of 10 s from uniform levels n = 16 to \
             128, graded n = 16 to 128, reference at n = 512 with about 1.1e6 unknowns and \
             512 step(s): about 3 min of work"
        ),
        "{first}"
    );
    assert!(secs < 10.0, "the plan took {secs} s to say");
    // A 3 x 1 scene whose quick plan drops a level, run whole.
    let block = written(
        dir.join("block.toml"),
        "name = \"block\"\nT = 1.0\ng = 0.05\n[geometry]\nwidth = 3.0\nheight = 1.0\n\
         [geometry.supports]\nleft = [{ from = 0.0, to = 0.5, kind = \"clamped\" }]\n\
         [material]\nE = 1000.0\nkappa = 0.3\nalpha = 50.0\nbeta = 30.0\n\
         [loads]\nf0 = [0.0, -4.0]\nf2 = [0.0, -20.0]\nhistory = { ramp = 0.3 }\n\
         [law]\nbreakpoints = [0.0, 0.02, 0.04]\nslopes = [0.0, 400.0, 100.0, 300.0]\n",
    );
    let out = dir.join("block");
    let err = ok(&evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&block)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap());
    assert!(err.contains("cut by 1 level(s)"), "{err}");
    let table = Csv::read(out.join("convergence.csv"));
    assert_eq!(table.column_f64("n"), [12.0, 24.0, 48.0, 12.0, 24.0, 48.0]);
    let md = std::fs::read_to_string(out.join("convergence.md")).unwrap();
    assert!(
        md.contains(
            "Quick mode's budget, about 10 s of work, cut this plan by 1 level(s) per family, \
             and its reference with them: its full quick plan has uniform levels n = 12 to 96"
        ),
        "{md}"
    );
    // The strip: refused at once.
    let strip = written(
        dir.join("strip.toml"),
        "name = \"strip\"\nT = 1.0\ng = 0.1\n[geometry]\nwidth = 64.0\nheight = 1.0\n\
         [material]\nE = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0\n\
         [loads]\nf0 = [0.0, -1e-3]\nf2 = [0.0, -1e-2]\n\
         [law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n",
    );
    let out = dir.join("strip");
    let clock = std::time::Instant::now();
    let o = evhi()
        .args(["study", "convergence", "--quick", "--scenario"])
        .arg(&strip)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let secs = clock.elapsed().as_secs_f64();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{err}");
    assert!(
        err.contains("fits quick mode's budget of about 10 s of work")
            && err.contains(
                "even cut to 2 levels per family it has uniform levels n = 128 to 256, graded \
                 n = 128 to 256, reference at n = 1024 with about 4.5e4 unknowns and 1024 \
                 step(s): about 53 s of work"
            )
            && err.contains(
                "Without --quick the reference would be at n = 8192, beyond the 4096 a mesh \
                 may have. Change the scene so that a coarser grid resolves it"
            )
            && err.contains("here n = 128"),
        "{err}"
    );
    assert!(secs < 10.0, "{secs} s");
    assert!(!out.exists());
}
