//! What a run directory and `evhi show` say about the data solved (issue 41, item 11):
//! the `#` provenance lines name every load, the further tractions among them;
//! `summary.csv` records the material the solver used; `show` says when E and kappa
//! are converted from the file's plane-stress or Lamé constants, and from what.

mod common;

use common::*;

/// The paper's scene with `figure`'s material and law; `loads` is its `[loads]` table.
fn scene(loads: &str) -> String {
    format!(
        "name = \"same_load\"\nT = 1.0\ng = 0.1\n\n\
         [material]\nE = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0\n\n\
         [loads]\n{loads}\n\
         [law]\nbreakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]\n"
    )
}

/// `figure`'s loads, `f2` on the whole top.
const AS_F2: &str = "f0 = [0.0, -5.0]\nf2 = [0.0, -75.0]\n";

/// A `[material]` table in each form the file may give (`figure`'s is plane strain).
const PLANE_STRESS: &str =
    "E = 1000.0\nkappa = 0.3\nplane = \"stress\"\nalpha = 100.0\nbeta = 50.0";
const LAME: &str = "lambda = 600.0\nmu = 400.0\nalpha = 100.0\nbeta = 50.0";
const PLANE_STRAIN: &str = "E = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0";

fn with_material(material: &str) -> String {
    scene(AS_F2).replace(
        "E = 1000.0\nkappa = 0.4\nalpha = 100.0\nbeta = 50.0",
        material,
    )
}

#[test]
fn show_says_when_e_and_kappa_are_converted_and_from_what() {
    let dir = scratch("prov-show");
    let show = |name: &str, material: &str| -> String {
        let file = written(dir.join(format!("{name}.toml")), with_material(material));
        stdout(&succeed(evhi_with("show --n 16").arg(file)))
    };
    // Plane stress E_s = 1000, nu_s = 0.3: kappa = nu_s/(1 + nu_s), E = E_s(1 + 2 nu_s)/(1 + nu_s)^2.
    let text = show("stress", PLANE_STRESS);
    let scn = evhi::scenario::Scenario::from_toml(&with_material(PLANE_STRESS), "stress").unwrap();
    assert!(
        (scn.kappa() - 0.3 / 1.3).abs() < 1e-14 && (scn.e() - 1000.0 * 1.6 / 1.69).abs() < 1e-9
    );
    assert_contains(
        &text,
        &[&format!(
            "material: E = {}, kappa = {} (plane strain, converted from the file's plane-stress \
             E = 1000, nu = 0.3), alpha = 100, beta = 50",
            scn.e(),
            scn.kappa()
        )],
    );
    assert_contains(
        &show("lame", LAME),
        &["(plane strain, converted from the file's plane-strain Lame lambda = 600, mu = 400)"],
    );
    let stress_lame = format!("{LAME}\nplane = \"stress\"");
    assert_contains(
        &show("stress_lame", &stress_lame),
        &["converted from the file's plane-stress Lame lambda = 600, mu = 400"],
    );
    // Plane strain by E and kappa is solved as given: the line says nothing more.
    let plain = show("strain", PLANE_STRAIN);
    assert_contains(
        &plain,
        &["material: E = 1000, kappa = 0.4, alpha = 100, beta = 50\n"],
    );
    assert!(!plain.contains("converted"), "{plain}");
}

#[test]
fn summary_records_the_material_the_solver_used_after_the_old_columns() {
    let dir = scratch("prov-material");
    for (name, material) in [
        ("strain", PLANE_STRAIN),
        ("stress", PLANE_STRESS),
        ("lame", LAME),
    ] {
        let text = with_material(material);
        let scn = evhi::scenario::Scenario::from_toml(&text, name).unwrap();
        let (o, run) = solve_text(&dir, name, &text, &["--n", "8", "--steps", "2"]);
        ok(&o);
        let row = common::summary(&run);
        for (col, got, want) in [
            ("E", row.e, scn.e()),
            ("kappa", row.kappa, scn.kappa()),
            ("alpha", row.alpha, scn.alpha()),
            ("beta", row.beta, scn.beta()),
        ] {
            assert_eq!(got, want, "{name}: {col}");
        }
        let s = Csv::read(run.join("summary.csv"));
        // Appended: the columns before them keep their places, `version` last of them.
        let tail: Vec<&str> = s
            .header
            .iter()
            .rev()
            .take(6)
            .rev()
            .map(|h| h.as_str())
            .collect();
        assert_eq!(
            tail,
            ["version", "E", "kappa", "alpha", "beta", "tractions"]
        );
        assert_eq!(s.header[..4], ["n", "steps", "dofs", "energy_norm_T"]);
    }
    // An elastic problem has no viscosity: 0 and 0 are what the solver used.
    let elastic = with_material("E = 1000.0\nkappa = 0.4")
        .replace("g = 0.1", "g = 0.1\nproblem = \"elastic\"");
    let (o, run) = solve_text(&dir, "elastic", &elastic, &["--n", "8", "--steps", "2"]);
    ok(&o);
    let s = common::summary(&run);
    assert_eq!((s.alpha, s.beta), (0.0, 0.0));
    assert_eq!((s.e, s.kappa), (1000.0, 0.4));
}

/// `figure`'s load as a `[[loads.traction]]` on the whole top with `f2 = (0, 0)`:
/// the same load vector as [`AS_F2`], so the same results; the `#` lines used to say
/// only `f2 = (0, 0)`, as if the top were free.
const AS_TRACTION: &str = "f0 = [0.0, -5.0]\nf2 = [0.0, 0.0]\n\n\
    [[loads.traction]]\nside = \"top\"\nfrom = 0.0\nto = 2.0\nf = [0.0, -75.0]\n";

/// The data line of a run's `#` lines (the second, after the command).
fn data_line(run: &std::path::Path, file: &str) -> String {
    let csv = Csv::read(run.join(file));
    assert_eq!(csv.provenance.len(), 2, "{:?}", csv.provenance);
    csv.provenance[1].clone()
}

#[test]
fn the_same_load_as_f2_or_as_a_traction_solves_alike_and_each_header_names_it() {
    let dir = scratch("prov-same-load");
    let words = ["--n", "16", "--steps", "8"];
    let (o, f2_run) = solve_text(&dir, "f2", &scene(AS_F2), &words);
    ok(&o);
    let (o, traction_run) = solve_text(&dir, "traction", &scene(AS_TRACTION), &words);
    ok(&o);
    let (a, b) = (common::summary(&f2_run), common::summary(&traction_run));
    let (ea, eb) = (a.energy_norm_t, b.energy_norm_t);
    assert!(
        ea > 0.0 && (ea - eb).abs() <= 1e-12 * ea,
        "{ea} against {eb}"
    );
    assert_eq!(a.path, b.path);
    // The results agree; the headers differ, each naming the load it was given.
    let (la, lb) = (
        data_line(&f2_run, "summary.csv"),
        data_line(&traction_run, "summary.csv"),
    );
    assert_ne!(la, lb);
    assert_contains(&la, &["f2 = (0, -75)", "f0 = (0, -5)", "f0_modulation = 0"]);
    assert!(!la.contains("loads.traction"), "{la}");
    assert_contains(
        &lb,
        &[
            "f2 = (0, 0)",
            "loads.traction[0] = (0, -75) on the top side over [0, 2]",
        ],
    );
    // Every table of the run opens with the same lines.
    for f in [
        "contact.csv",
        "steps.csv",
        "nodes.csv",
        "evolution.csv",
        "regimes.csv",
    ] {
        assert_eq!(data_line(&traction_run, f), lb, "{f}");
    }
    // summary.csv counts the further tractions.
    assert_eq!(a.tractions, 0);
    assert_eq!(b.tractions, 1);
}

/// The `#` line names the material the solver used, and for a plane-stress file the
/// constants it was converted from: two runs that differ only in the material no longer
/// carry the same header.
#[test]
fn the_provenance_line_names_the_material() {
    let dir = scratch("prov-header-material");
    let (o, strain) = solve_text(
        &dir,
        "strain",
        &with_material(PLANE_STRAIN),
        &["--n", "8", "--steps", "2"],
    );
    ok(&o);
    let (o, stress) = solve_text(
        &dir,
        "stress",
        &with_material(PLANE_STRESS),
        &["--n", "8", "--steps", "2"],
    );
    ok(&o);
    let a = data_line(&strain, "contact.csv");
    let b = data_line(&stress, "contact.csv");
    assert!(
        a.contains("material: E = 1000, kappa = 0.4, alpha = 100, beta = 50"),
        "{a}"
    );
    assert!(
        b.contains("converted from the file's plane-stress E = 1000, nu = 0.3"),
        "{b}"
    );
}
