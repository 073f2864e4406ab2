//! Scenario files: the built-ins parse, bad values are rejected with the field named.

use evhi::scenario::Scenario;

const GOOD: &str = include_str!("../data/scenarios/figure.toml");

fn with(from: &str, to: &str) -> String {
    assert!(GOOD.contains(from), "fixture lacks `{from}`");
    GOOD.replacen(from, to, 1)
}

#[test]
fn builtins_parse() {
    for name in ["literal", "figure"] {
        let s = Scenario::load(name).unwrap();
        assert_eq!(s.name(), name);
        assert_eq!(s.g(), 0.1);
        assert_eq!(*s.law(), evhi::law::paper_law());
    }
}

#[test]
fn bad_values_name_the_field() {
    let cases = [
        (with("T = 1.0", "T = -1.0"), "T"),
        (with("g = 0.1", "g = 0.0"), "g"),
        (with("g = 0.1", "g = nan"), "g"),
        (with("E = 1000.0", "E = -5.0"), "material.E"),
        (with("kappa = 0.4", "kappa = 0.5"), "material.kappa"),
        (with("beta = 50.0", "beta = 0.0"), "material.beta"),
        (with("alpha = 100.0", "alpha = -30.0"), "material.alpha"),
        (with("f2 = [0.0, -75.0]", "f2 = [0.0, inf]"), "loads.f2[1]"),
        (
            with(
                "breakpoints = [0.0, 0.05, 0.075]",
                "breakpoints = [0.0, 0.075, 0.05]",
            ),
            "law.breakpoints[2]",
        ),
        (
            with(
                "slopes = [0.0, 200.0, -100.0, 300.0]",
                "slopes = [0.0, 200.0]",
            ),
            "law.slopes",
        ),
    ];
    for (text, field) in cases {
        let err = Scenario::from_toml(&text, "test").unwrap_err();
        assert_eq!(err.field_name(), Some(field), "{err}");
        assert!(err.to_string().contains(field));
    }
}

#[test]
fn unknown_keys_and_syntax_errors_are_rejected() {
    let err = Scenario::from_toml(&with("g = 0.1", "g = 0.1\ngap = 3"), "test").unwrap_err();
    assert!(err.to_string().contains("gap"), "{err}");
    let err = Scenario::from_toml(&with("[material]", "[material]\nnu = 0.3"), "test").unwrap_err();
    assert!(err.to_string().contains("nu"), "{err}");
    assert!(Scenario::from_toml("T = ", "test").is_err());
    let err = Scenario::load("no-such-scenario").unwrap_err();
    assert_eq!(err.field_name(), Some("scenario"));
}

#[test]
fn overrides_are_validated() {
    let s = Scenario::load("figure").unwrap();
    assert_eq!(s.clone().with_g(-1.0).unwrap_err().field_name(), Some("g"));
    assert_eq!(
        s.clone()
            .with_loads(Some([f64::NAN, 0.0]), None)
            .unwrap_err()
            .field_name(),
        Some("loads.f0[0]")
    );
    assert_eq!(s.with_g(0.07).unwrap().g(), 0.07);
}

/// A traction on the clamped top (supports = "rollers") cannot act: it is refused by
/// name, in a file and as an override, instead of being recorded and silently dropped.
#[test]
fn a_traction_on_a_clamped_top_is_refused_by_name() {
    let smooth = evhi::scenario::Scenario::load("smooth").unwrap();
    let e = smooth
        .clone()
        .with_loads(None, Some([0.0, -1e6]))
        .unwrap_err();
    assert_eq!(e.field_name(), Some("loads.f2"), "{e}");
    assert!(e.to_string().contains("rollers"), "{e}");
    // A zero traction stays allowed, and the paper's supports take any.
    assert!(smooth.with_loads(None, Some([0.0, 0.0])).is_ok());
    let figure = evhi::scenario::Scenario::load("figure").unwrap();
    assert!(figure.with_loads(None, Some([0.0, -1e6])).is_ok());
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenarios/smooth.toml"
    ))
    .unwrap()
    .replace("f2 = [0.0, 0.0]", "f2 = [0.0, -75.0]");
    let e = evhi::scenario::Scenario::from_toml(&text, "smooth-with-f2").unwrap_err();
    assert_eq!(e.field_name(), Some("loads.f2"), "{e}");
}

/// A scenario path that is not a regular file is refused by name, without reading it
/// (issue 27, case 9: `show /dev/zero` grew without bound, a FIFO blocked).
#[test]
fn a_scenario_that_is_not_a_regular_file_is_refused() {
    for path in ["/dev/zero", "/tmp"] {
        let e = evhi::scenario::Scenario::load(path).unwrap_err();
        assert_eq!(e.field_name(), Some("scenario"), "{path}: {e}");
        assert!(e.to_string().contains("regular"), "{e}");
    }
    let fifo = std::env::temp_dir().join(format!("evhi-fifo-{}.toml", std::process::id()));
    let _ = std::fs::remove_file(&fifo);
    if std::process::Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        let e = evhi::scenario::Scenario::load(fifo.to_str().unwrap()).unwrap_err();
        assert!(e.to_string().contains("regular"), "{e}");
        let _ = std::fs::remove_file(&fifo);
    }
}

#[test]
fn refused_numbers_are_echoed_as_read_and_bounds_as_written() {
    let cases = [
        // A tiny value in exponent notation, not 0.00000000000000000001.
        ("E = 1e-20", "got 1e-20, expected a number in [1e-12, 1e12]"),
        // Beyond 2^53 the digits written are not the digits read: say so.
        (
            "E = 9007199254740993",
            "got 9.007199254740992e15 (the double nearest to the number written)",
        ),
    ];
    for (to, expect) in cases {
        let err = Scenario::from_toml(&with("E = 1000.0", to), "test").unwrap_err();
        assert!(err.to_string().contains(expect), "{err}");
    }
}

#[test]
fn the_law_table_takes_one_family_and_names_the_other_s_keys() {
    let soft = GOOD.replace(
        "breakpoints = [0.0, 0.05, 0.075]\nslopes = [0.0, 200.0, -100.0, 300.0]",
        "kind = \"softening\"\nstiffness = 900.0\nlength = 0.03",
    );
    assert_ne!(soft, GOOD, "fixture changed");
    let s = Scenario::from_toml(&soft, "test").unwrap();
    assert_eq!(s.law().kind(), "softening");
    let cases = [
        (
            soft.replace("length = 0.03", "length = 0.03\nslopes = [1.0]"),
            "law.slopes",
        ),
        (
            soft.replace("stiffness = 900.0", "stiffness = -1.0"),
            "law.stiffness",
        ),
        (soft.replace("length = 0.03", ""), "law.length"),
        (soft.replace("\"softening\"", "\"smooth\""), "law.kind"),
        (
            with(
                "slopes = [0.0, 200.0, -100.0, 300.0]",
                "slopes = [0.0, 200.0, -100.0, 300.0]\nlength = 1.0",
            ),
            "law.length",
        ),
    ];
    for (text, field) in cases {
        let err = Scenario::from_toml(&text, "test").unwrap_err();
        assert_eq!(err.field_name(), Some(field), "{err}");
    }
}

#[test]
fn the_elasticity_by_young_or_lame_in_plane_strain_or_stress() {
    let g = |text: String| Scenario::from_toml(&text, "test").unwrap().elasticity();
    let base = g(GOOD.to_string());
    // Plane strain by Lame: a = lambda, b = 2 mu, the same tensor as E = 1000, kappa = 0.4.
    let (lambda, mu) = (base.a, base.b / 2.0);
    let lame = g(with(
        "E = 1000.0\nkappa = 0.4",
        &format!("lambda = {lambda:e}\nmu = {mu:e}"),
    ));
    assert!((lame.a - base.a).abs() < 1e-9 * base.a && (lame.b - base.b).abs() < 1e-9 * base.b);
    // Plane stress by E and nu: a = E nu / (1 - nu^2), b = E / (1 + nu).
    let ps = g(with("kappa = 0.4", "kappa = 0.4\nplane = \"stress\""));
    let (e, nu) = (1000.0, 0.4);
    assert!((ps.a - e * nu / (1.0 - nu * nu)).abs() < 1e-9 * ps.a);
    assert!((ps.b - e / (1.0 + nu)).abs() < 1e-9 * ps.b);
    // Plane stress by Lame: a = 2 lambda mu / (lambda + 2 mu), b = 2 mu.
    let psl = g(with(
        "E = 1000.0\nkappa = 0.4",
        &format!("lambda = {lambda:e}\nmu = {mu:e}\nplane = \"stress\""),
    ));
    assert!((psl.a - 2.0 * lambda * mu / (lambda + 2.0 * mu)).abs() < 1e-9 * psl.a);
    assert!((psl.b - 2.0 * mu).abs() < 1e-9 * psl.b);
    // Refused by name: a mix, a missing constant, a bad plane, a non-positive mu.
    let cases = [
        (with("kappa = 0.4", "kappa = 0.4\nmu = 300.0"), "material.E"),
        (
            with("E = 1000.0\nkappa = 0.4", "mu = 300.0"),
            "material.lambda",
        ),
        (
            with("kappa = 0.4", "kappa = 0.4\nplane = \"axisymmetric\""),
            "material.plane",
        ),
        (
            with("E = 1000.0\nkappa = 0.4", "lambda = 1.0\nmu = 0.0"),
            "material.mu",
        ),
        (
            with("E = 1000.0\nkappa = 0.4", "lambda = -5.0\nmu = 1.0"),
            "material.lambda",
        ),
        (with("kappa = 0.4", ""), "material.kappa"),
    ];
    for (text, field) in cases {
        let err = Scenario::from_toml(&text, "test").unwrap_err();
        assert_eq!(err.field_name(), Some(field), "{err}");
    }
}

/// A Poisson ratio of 0 zeroes the first coefficient of G: the damping is then
/// proportional only if C's first coefficient is zero too (it used to divide by zero,
/// call a non-proportional scene proportional with tau = inf, and send `solve` by
/// default to a loop that refused it), and the paper's ratio is kept.
#[test]
fn a_zero_poisson_ratio_is_classified_by_both_coefficients() {
    let zero = with("kappa = 0.4", "kappa = 0.0");
    let scn = Scenario::from_toml(&zero, "test").unwrap();
    assert_eq!(scn.relaxation_time(), None);
    let both = zero.replacen("alpha = 100.0", "alpha = 0.0", 1);
    let scn = Scenario::from_toml(&both, "test").unwrap();
    let tau = scn.relaxation_time().expect("C = tau G");
    assert_eq!(tau, scn.viscosity().b / scn.elasticity().b);
    assert!(tau.is_finite() && tau > 0.0);
    let paper = Scenario::load("figure").unwrap();
    let tau = paper.relaxation_time().unwrap();
    assert!((tau - 0.07).abs() < 1e-12, "{tau}");
}

/// Loads that are not all zero but tiny throughout are refused by name, in a file and
/// as overrides (they used to fail the first step with a certificate of order one);
/// all-zero loads, loads at the bound, and one tiny component beside a normal one pass.
#[test]
fn loads_too_small_to_certify_are_refused_by_name() {
    let tiny = with("f0 = [0.0, -5.0]", "f0 = [0.0, 0.0]").replacen(
        "f2 = [0.0, -75.0]",
        "f2 = [0.0, -1e-200]",
        1,
    );
    let err = Scenario::from_toml(&tiny, "test").unwrap_err();
    assert_eq!(err.field_name(), Some("[loads]"), "{err}");
    assert!(err.to_string().contains("1e-200"), "{err}");
    let fig = Scenario::load("figure").unwrap();
    let err = fig
        .clone()
        .with_loads(Some([0.0, 0.0]), Some([1e-300, 0.0]))
        .unwrap_err();
    assert_eq!(err.field_name(), Some("[loads]"), "{err}");
    for (f0, f2) in [
        ([0.0, 0.0], [0.0, 0.0]),
        ([0.0, 0.0], [0.0, -1e-100]),
        ([1e-300, -5.0], [0.0, -75.0]),
    ] {
        fig.clone().with_loads(Some(f0), Some(f2)).unwrap();
    }
}

/// The elasticity's documented ranges are the validator's, and each refusal names the
/// constant the user gave and its bound in their terms: Lamé's lambda just above
/// -2 mu/3 (plane strain) or -mu/2 (plane stress) passes and just below is refused as
/// `material.lambda`; a plane-stress Poisson ratio passes above -1/2 and is refused
/// below it as `material.kappa` (both used to be refused through the plane-strain
/// Poisson ratio they imply, though the book allowed them).
#[test]
fn elasticity_ranges_are_the_documented_ones() {
    let lame = |lambda: f64, plane: &str| {
        with(
            "E = 1000.0\nkappa = 0.4",
            &format!("lambda = {lambda:e}\nmu = 300.0{plane}"),
        )
    };
    for (lambda, plane, ok) in [
        (-199.0, "", true),
        (-201.0, "", false),
        (-149.0, "\nplane = \"stress\"", true),
        (-151.0, "\nplane = \"stress\"", false),
    ] {
        match Scenario::from_toml(&lame(lambda, plane), "test") {
            Ok(_) => assert!(ok, "lambda = {lambda}{plane} accepted"),
            Err(e) => {
                assert!(!ok, "lambda = {lambda}{plane}: {e}");
                assert_eq!(e.field_name(), Some("material.lambda"), "{e}");
                assert!(e.to_string().contains("mu"), "{e}");
            }
        }
    }
    let stress = |kappa: &str| {
        with(
            "kappa = 0.4",
            &format!("kappa = {kappa}\nplane = \"stress\""),
        )
    };
    Scenario::from_toml(&stress("-0.49"), "test").unwrap();
    // Inside and outside the plane-strain range alike, the refusal names the
    // plane-stress one.
    for bad in ["-0.6", "-1.0", "0.6"] {
        let err = Scenario::from_toml(&stress(bad), "test").unwrap_err();
        assert_eq!(err.field_name(), Some("material.kappa"), "{err}");
        assert!(err.to_string().contains("(-1/2, 1/2)"), "{err}");
    }
}

/// A scene built through the library cannot hold what the file reader refuses: each
/// checked builder refuses the same value with the same words as the file (issue 48,
/// item 1; `scene.g = -1.0` used to solve, "certified", with u_nu = -1).
#[test]
fn the_builders_refuse_what_the_file_refuses_in_the_same_words() {
    use evhi::law::Law;
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenarios/figure.toml"
    ))
    .unwrap();
    let figure = Scenario::load("figure").unwrap();
    let smooth = Scenario::load("smooth").unwrap();
    let smooth_text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/data/scenarios/smooth.toml"
    ))
    .unwrap();
    let law =
        |slopes: &[f64], jumps: &[f64]| Law::new(&[0.0, 0.05, 0.075], slopes, jumps, 0.0).unwrap();
    type Build = Box<dyn Fn() -> Result<Scenario, evhi::error::InputError>>;
    let cases: Vec<(String, Build)> = vec![
        (
            text.replace("g = 0.1", "g = -1.0"),
            Box::new({
                let s = figure.clone();
                move || s.clone().with_g(-1.0)
            }),
        ),
        (
            text.replace("f0 = [0.0, -5.0]", "f0 = [nan, -5.0]"),
            Box::new({
                let s = figure.clone();
                move || s.clone().with_loads(Some([f64::NAN, -5.0]), None)
            }),
        ),
        (
            text.replace("f2 = [0.0, -75.0]", "f2 = [0.0, 1e300]"),
            Box::new({
                let s = figure.clone();
                move || s.clone().with_loads(None, Some([0.0, 1e300]))
            }),
        ),
        (
            smooth_text.replace("f2 = [0.0, 0.0]", "f2 = [0.0, -75.0]"),
            Box::new({
                let s = smooth.clone();
                move || s.clone().with_loads(None, Some([0.0, -75.0]))
            }),
        ),
        (
            text.replace("E = 1000.0", "E = -1.0"),
            Box::new({
                let s = figure.clone();
                move || s.clone().with_elasticity(-1.0, 0.4)
            }),
        ),
        (
            text.replace("kappa = 0.4", "kappa = 0.5"),
            Box::new({
                let s = figure.clone();
                move || s.clone().with_elasticity(1000.0, 0.5)
            }),
        ),
        (
            text.replace("alpha = 100.0", "alpha = -30.0"),
            Box::new({
                let s = figure.clone();
                move || s.clone().with_viscosity(-30.0, 50.0)
            }),
        ),
        (
            text.replace("beta = 50.0", "beta = 0.0"),
            Box::new({
                let s = figure.clone();
                move || s.clone().with_viscosity(100.0, 0.0)
            }),
        ),
        (
            text.replace(
                "slopes = [0.0, 200.0, -100.0, 300.0]",
                "slopes = [0.0, 200.0, -1e12, 300.0]",
            ),
            Box::new({
                let s = figure.clone();
                move || {
                    s.clone()
                        .with_law(law(&[0.0, 200.0, -1e12, 300.0], &[0.0; 3]))
                }
            }),
        ),
        (
            text.replace(
                "slopes = [0.0, 200.0, -100.0, 300.0]",
                "slopes = [0.0, 200.0, -100.0, 300.0]\njumps = [0.0, -1e9, 0.0]",
            ),
            Box::new({
                let s = figure.clone();
                move || {
                    s.clone()
                        .with_law(law(&[0.0, 200.0, -100.0, 300.0], &[0.0, -1e9, 0.0]))
                }
            }),
        ),
        (
            text.replace("name = \"figure\"", "name = \"  \""),
            Box::new({
                let s = figure.clone();
                move || s.clone().with_name("  ")
            }),
        ),
    ];
    for (file, build) in cases {
        let from_file = Scenario::from_toml(&file, "test").unwrap_err();
        let from_code = build().unwrap_err();
        assert_eq!(from_file.to_string(), from_code.to_string());
        assert!(from_code.field_name().is_some(), "{from_code}");
    }
    // An elastic scene takes no viscosity, as its file may give none.
    let elastic = figure
        .clone()
        .with_problem(evhi::scenario::Problem::Elastic)
        .unwrap();
    let e = elastic.with_viscosity(100.0, 50.0).unwrap_err();
    assert_eq!(e.field_name(), Some("material.alpha"), "{e}");
    // What is accepted is what the accessors give back.
    let s = figure
        .with_viscosity(60.0, 30.0)
        .unwrap()
        .with_g(0.2)
        .unwrap();
    assert_eq!((s.alpha(), s.beta(), s.g()), (60.0, 30.0, 0.2));
}

/// The README's own scene is shipped as the file its commands run
/// (`data/scenarios/examples/block.toml`), and the README shows that file's TOML: the
/// two cannot drift apart, and the file reads as a scene.
#[test]
fn the_readme_scene_is_the_shipped_file() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let shown = readme
        .split("```toml\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("a TOML block in the README");
    let path = root.join("data/scenarios/examples/block.toml");
    let file = std::fs::read_to_string(&path).unwrap();
    let body: String = file
        .lines()
        .skip_while(|l| l.starts_with('#'))
        .map(|l| format!("{l}\n"))
        .collect();
    assert_eq!(
        body, shown,
        "the README's TOML is not the shipped block.toml"
    );
    assert!(readme.contains("--scenario data/scenarios/examples/block.toml"));
    let scene = evhi::scenario::Scenario::load(&path.display().to_string()).unwrap();
    assert_eq!(scene.name(), "block");
}

/// The README's library snippet is abridged from `examples/solve_a_scene.rs`, which
/// is built and is the crate's doc-tested front page: every code line the README shows
/// (its trailing comment set aside) is a line of that example, so the snippet cannot
/// stop compiling without the test failing.
#[test]
fn the_readme_snippet_is_the_front_page_example() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let shown = readme
        .split("```rust\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("a Rust block in the README");
    let example = std::fs::read_to_string(root.join("examples/solve_a_scene.rs")).unwrap();
    let code = |l: &str| l.split(" //").next().unwrap_or("").trim().to_string();
    let lines: Vec<String> = example.lines().map(code).collect();
    let mut shown_lines = 0;
    for l in shown.lines().map(code).filter(|l| !l.is_empty()) {
        assert!(lines.contains(&l), "README line not in the example: {l}");
        shown_lines += 1;
    }
    assert!(
        shown_lines >= 4,
        "the README's snippet has {shown_lines} lines"
    );
}

/// Every refusal of the file reader that a builder can reach: the scene the builder
/// would make, written as a file, is refused with the builder's own words (its first
/// line; the file adds where the value stood) and by the same field.
#[test]
fn the_builders_refuse_what_the_file_refuses() {
    use evhi::law::Law;
    use evhi::scenario::Problem;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let figure_text = std::fs::read_to_string(root.join("data/scenarios/figure.toml")).unwrap();
    let figure = || Scenario::from_toml(&figure_text, "figure").unwrap();
    let elastic_text = figure_text.replace("alpha = 100.0\nbeta = 50.0\n", "");
    let elastic_text = elastic_text.replace("g = 0.1\n", "g = 0.1\nproblem = \"elastic\"\n");
    let elastic = || Scenario::from_toml(&elastic_text, "figure").unwrap();
    let edit = |text: &str, from: &str, to: &str| {
        assert!(text.contains(from), "no `{from}`");
        text.replacen(from, to, 1)
    };
    let f = figure_text.as_str();
    type Built = Result<Scenario, evhi::error::InputError>;
    let big = evhi::scenario::MAX_LAW * 10.0;
    let cases: Vec<(String, Built)> = vec![
        (edit(f, "g = 0.1", "g = -1.0"), figure().with_g(-1.0)),
        (edit(f, "g = 0.1", "g = 0.0"), figure().with_g(0.0)),
        (edit(f, "g = 0.1", "g = nan"), figure().with_g(f64::NAN)),
        (
            edit(f, "f0 = [0.0, -5.0]", "f0 = [nan, -5.0]"),
            figure().with_loads(Some([f64::NAN, -5.0]), None),
        ),
        (
            edit(f, "f2 = [0.0, -75.0]", "f2 = [0.0, 1e300]"),
            figure().with_loads(None, Some([0.0, 1e300])),
        ),
        (
            edit(f, "E = 1000.0", "E = -1.0"),
            figure().with_elasticity(-1.0, 0.4),
        ),
        (
            edit(f, "kappa = 0.4", "kappa = 0.5"),
            figure().with_elasticity(1000.0, 0.5),
        ),
        (
            edit(f, "alpha = 100.0", "alpha = inf"),
            figure().with_viscosity(f64::INFINITY, 50.0),
        ),
        (
            edit(f, "beta = 50.0", "beta = 0.0"),
            figure().with_viscosity(100.0, 0.0),
        ),
        (
            edit(f, "alpha = 100.0", "alpha = -100.0"),
            figure().with_viscosity(-100.0, 50.0),
        ),
        (
            edit(
                &elastic_text,
                "kappa = 0.4\n",
                "kappa = 0.4\nalpha = 1.0\nbeta = 2.0\n",
            ),
            elastic().with_viscosity(1.0, 2.0),
        ),
        (
            edit(
                &elastic_text,
                "problem = \"elastic\"",
                "problem = \"viscoelastic\"",
            ),
            elastic().with_problem(Problem::Viscoelastic),
        ),
        (
            edit(
                f,
                "slopes = [0.0, 200.0, -100.0, 300.0]",
                &format!("slopes = [0.0, {big:e}, -100.0, 300.0]"),
            ),
            figure().with_law(
                Law::new(
                    &[0.0, 0.05, 0.075],
                    &[0.0, big, -100.0, 300.0],
                    &[0.0; 3],
                    0.0,
                )
                .unwrap(),
            ),
        ),
        (
            edit(f, "name = \"figure\"", "name = \" \""),
            figure().with_name(" "),
        ),
        (
            edit(f, "name = \"figure\"", "name = \"a\\nb\""),
            figure().with_name("a\nb"),
        ),
        (
            edit(
                f,
                "description = \"vertical loads f0 = (0, -5), f2 = (0, -75) on the top; \
                 paper's material and law\"",
                "description = \"two\\nlines\"",
            ),
            figure().with_description("two\nlines"),
        ),
    ];
    for (text, built) in cases {
        let file = Scenario::from_toml(&text, "figure").expect_err(&text);
        let built = built.expect_err(&text);
        let file_msg = file.to_string();
        let built_msg = built.to_string();
        let first = file_msg.lines().next().unwrap_or_default();
        assert_eq!(first, built_msg, "file: {file_msg}");
        assert_eq!(file.field_name(), built.field_name(), "{file_msg}");
        assert!(built.field_name().is_some(), "{built_msg}");
    }
}
