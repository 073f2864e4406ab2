//! The corner exponents of the static control, checked against classical values, and
//! the control's observed orders against them.

use evhi::study::corners::{Edge, clamp_end_exponent, wedge_exponents};
use std::f64::consts::PI;

#[test]
fn wedge_exponents_match_classical_values() {
    // A crack (free-free, opening 2 pi): 1/2, whatever the material.
    for kappa_m in [1.4, 1.8, 2.2] {
        let r = wedge_exponents(2.0 * PI, kappa_m, [Edge::Free, Edge::Free]);
        assert!((r[0] - 0.5).abs() < 1e-9, "{r:?}");
    }
    // The L-shaped domain's re-entrant corner (free-free, 3 pi / 2): modes I and II,
    // 0.544484 and 0.908529 (Williams 1952), independent of Poisson's ratio.
    let r = wedge_exponents(1.5 * PI, 1.4, [Edge::Free, Edge::Free]);
    assert!((r[0] - 0.544484).abs() < 1e-6, "{r:?}");
    assert!((r[1] - 0.908529).abs() < 1e-6, "{r:?}");
    // The clamp ending on a straight edge has no real exponent below 1 (it is complex,
    // 1/2 + i ln(3 - 4 nu)/(2 pi)) ...
    assert!(wedge_exponents(PI, 1.4, [Edge::Clamped, Edge::Free]).is_empty());
    let (re, im) = clamp_end_exponent(1.4);
    assert_eq!(re, 0.5);
    assert!((im - 1.4f64.ln() / (2.0 * PI)).abs() < 1e-15);
    // ... and the clamped top corner (clamped-free, pi / 2) is milder than 1/2.
    let r = wedge_exponents(0.5 * PI, 1.4, [Edge::Clamped, Edge::Free]);
    assert!(r[0] > 0.6 && r[0] < 0.7, "{r:?}");
    // Swapping the edges changes nothing.
    let s = wedge_exponents(0.5 * PI, 1.4, [Edge::Free, Edge::Clamped]);
    assert!((r[0] - s[0]).abs() < 1e-9);
}
