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
/// on a 3 x 1 scene whose coarsest resolving level is 12, quick mode's reference is at
/// n = 384, about 18 times the work of the paper's scene in the same mode, and the
/// first line says so before any work (the run is stopped there).
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
        first.starts_with("study convergence (quick): uniform levels n = 12 to 96")
            && first.contains("reference at n = 384 with at least 99330 unknowns and 384 step(s)")
            && first.contains("about 18 times the work of the paper's scene"),
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
