//! The contact law: values, potential and Clarke subdifferential at and between breakpoints.

use evhi::law::{Law, paper_law};

const TOL: f64 = 1e-14;

#[test]
fn paper_law_values_between_breakpoints() {
    let law = paper_law();
    // (5.1): 0 below 0, 200 s up to 0.05, 10 - 100 (s - 0.05) up to 0.075, 7.5 + 300 (s - 0.075) beyond.
    for (s, p) in [
        (-1.0, 0.0),
        (-1e-9, 0.0),
        (0.01, 2.0),
        (0.04, 8.0),
        (0.06, 9.0),
        (0.07, 8.0),
        (0.09, 12.0),
        (0.1, 15.0),
    ] {
        assert!(
            (law.p(s) - p).abs() < TOL,
            "p({s}) = {} expected {p}",
            law.p(s)
        );
        let c = law.clarke(s);
        assert!(
            (c.lo - p).abs() < TOL && (c.hi - p).abs() < TOL,
            "clarke({s}) = {c:?}"
        );
    }
}

#[test]
fn paper_law_is_continuous_at_breakpoints() {
    let law = paper_law();
    for (s, p) in [(0.0, 0.0), (0.05, 10.0), (0.075, 7.5)] {
        let c = law.clarke(s);
        assert!(
            (c.lo - p).abs() < TOL && (c.hi - p).abs() < TOL,
            "clarke({s}) = {c:?}, expected {{{p}}}"
        );
    }
}

#[test]
fn potential_integrates_the_law() {
    let law = paper_law();
    // j(s) = ∫_0^s p: 100 s² up to 0.05 (0.25 there), then 0.25 + 10 d - 50 d², d = s - 0.05.
    assert!((law.j(-0.3)).abs() < TOL);
    assert!((law.j(0.03) - 100.0 * 0.03 * 0.03).abs() < TOL);
    let d: f64 = 0.025;
    let j075 = 0.25 + 10.0 * d - 50.0 * d * d;
    assert!((law.j(0.075) - j075).abs() < 1e-13);
    let e: f64 = 0.025;
    assert!((law.j(0.1) - (j075 + 7.5 * e + 150.0 * e * e)).abs() < 1e-13);
    // A central difference of j reproduces p away from breakpoints.
    for s in [0.02, 0.06, 0.09] {
        let fd = (law.j(s + 1e-6) - law.j(s - 1e-6)) / 2e-6;
        assert!((fd - law.p(s)).abs() < 1e-6);
    }
}

#[test]
fn jumps_give_an_interval() {
    // p = 0 below 0, jumps up by 5 at 0, slope 10, jumps down by 3 at 1.
    let law = Law::new(&[0.0, 1.0], &[0.0, 10.0, 0.0], &[5.0, -3.0], 0.0).unwrap();
    let c0 = law.clarke(0.0);
    assert_eq!((c0.lo, c0.hi), (0.0, 5.0));
    let c1 = law.clarke(1.0);
    assert!(
        (c1.lo - 12.0).abs() < TOL && (c1.hi - 15.0).abs() < TOL,
        "{c1:?}"
    );
    assert!((law.p(0.5) - 10.0).abs() < TOL);
    assert!((law.p(2.0) - 12.0).abs() < TOL);
    assert_eq!(law.down_jumps(), vec![(1.0, -3.0)]);
    // j stays continuous across a jump of p.
    assert!((law.j(1.0 + 1e-12) - law.j(1.0 - 1e-12)).abs() < 1e-10);
    assert!((law.j(1.0) - (5.0 + 5.0)).abs() < TOL);
    // Interval helpers.
    assert_eq!(c0.dist(-1.0), 1.0);
    assert_eq!(c0.dist(2.0), 0.0);
    assert_eq!(c0.clamp(7.0), 5.0);
}

#[test]
fn bad_laws_name_the_field() {
    type Case<'a> = (&'a [f64], &'a [f64], &'a [f64], &'a str);
    let cases: [Case; 5] = [
        (
            &[0.0, 0.0],
            &[0.0, 1.0, 2.0],
            &[0.0, 0.0],
            "law.breakpoints[1]",
        ),
        (&[0.0], &[0.0], &[0.0], "law.slopes"),
        (&[0.0], &[0.0, 1.0], &[], "law.jumps"),
        (&[f64::NAN], &[0.0, 1.0], &[0.0], "law.breakpoints[0]"),
        (&[0.0], &[0.0, f64::INFINITY], &[0.0], "law.slopes[1]"),
    ];
    for (b, s, j, field) in cases {
        let err = Law::new(b, s, j, 0.0).unwrap_err();
        assert_eq!(err.field_name(), Some(field), "{err}");
    }
}
