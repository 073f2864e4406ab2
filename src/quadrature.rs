//! Quadrature for data that vary in space: the loads and norms of a manufactured
//! solution ([`crate::manufactured`]). The scheme itself needs none (its loads are
//! constant per element and its contact rule is nodal).
//!
//! - On a segment $[a, b]$: Gauss–Legendre with 5 points, exact for polynomials of
//!   degree 9: $\int_a^b f \approx \tfrac{b-a}{2}\sum_q w_q f(\tfrac{a+b}{2} + \tfrac{b-a}{2}\xi_q)$.
//! - On a triangle $T$: the 7-point rule of degree 5 (Strang–Fix, Dunavant's table):
//!   $\int_T f \approx |T| \sum_q w_q f(\sum_a \lambda^q_a x_a)$, barycentric points
//!   $\lambda^q$, $\sum_q w_q = 1$.
//! - Where the integrand is smooth only piecewise, the domain is cut first: a
//!   triangle along vertical lines $x = c$ ([`clip_vertical`]), a segment at given
//!   points, so that every rule acts on one smooth piece and keeps its degree.

/// Gauss–Legendre on $[-1, 1]$: 5 (node, weight) pairs, exact to degree 9.
pub const GAUSS5: [(f64, f64); 5] = [
    (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.0, 0.568_888_888_888_888_9),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_5),
    (0.906_179_845_938_664, 0.236_926_885_056_189_1),
];

/// The 7-point triangle rule of degree 5: barycentric point and weight (weights sum to 1).
pub const TRI7: [([f64; 3], f64); 7] = {
    const A1: f64 = 0.059_715_871_789_770;
    const B1: f64 = 0.470_142_064_105_115;
    const W1: f64 = 0.132_394_152_788_506;
    const A2: f64 = 0.797_426_985_353_087;
    const B2: f64 = 0.101_286_507_323_456;
    const W2: f64 = 0.125_939_180_544_827;
    [
        ([1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0], 0.225),
        ([A1, B1, B1], W1),
        ([B1, A1, B1], W1),
        ([B1, B1, A1], W1),
        ([A2, B2, B2], W2),
        ([B2, A2, B2], W2),
        ([B2, B2, A2], W2),
    ]
};

/// $\int_a^b f$ by [`GAUSS5`] on each piece between `a`, the `cuts` inside
/// $(a, b)$ (in any order) and `b`.
pub fn segment(a: f64, b: f64, cuts: &[f64], mut f: impl FnMut(f64) -> f64) -> f64 {
    let mut pts: Vec<f64> = cuts.iter().copied().filter(|&c| c > a && c < b).collect();
    pts.push(a);
    pts.push(b);
    pts.sort_by(f64::total_cmp);
    pts.windows(2)
        .map(|w| {
            let (mid, half) = (0.5 * (w[0] + w[1]), 0.5 * (w[1] - w[0]));
            half * GAUSS5
                .iter()
                .map(|&(xi, wq)| wq * f(mid + half * xi))
                .sum::<f64>()
        })
        .sum()
}

/// The points and weights of [`TRI7`] on the triangle `p` cut along the vertical
/// lines $x = c$ for each `c` of `cuts`: every piece (a triangle, or a quadrilateral
/// split into two) gets its own 7 points, so a function smooth on each side of
/// every cut is integrated to degree 5. Weights include the area.
pub fn triangle_points(p: [[f64; 2]; 3], cuts: &[f64]) -> Vec<([f64; 2], f64)> {
    let mut out = Vec::with_capacity(7);
    for piece in clip_vertical(p, cuts) {
        let area = 0.5 * crate::element::twice_area(piece).abs();
        if area <= 0.0 {
            continue;
        }
        for (l, w) in TRI7 {
            let x = l[0] * piece[0][0] + l[1] * piece[1][0] + l[2] * piece[2][0];
            let y = l[0] * piece[0][1] + l[1] * piece[1][1] + l[2] * piece[2][1];
            out.push(([x, y], w * area));
        }
    }
    out
}

/// [`triangle_points`] on the $4^{\rm depth}$ children of `p` by repeated midpoint
/// refinement (to measure the quadrature's own error).
pub fn triangle_points_refined(
    p: [[f64; 2]; 3],
    cuts: &[f64],
    depth: usize,
) -> Vec<([f64; 2], f64)> {
    if depth == 0 {
        return triangle_points(p, cuts);
    }
    let mid = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    let (m01, m12, m20) = (mid(p[0], p[1]), mid(p[1], p[2]), mid(p[2], p[0]));
    [
        [p[0], m01, m20],
        [m01, p[1], m12],
        [m20, m12, p[2]],
        [m01, m12, m20],
    ]
    .into_iter()
    .flat_map(|c| triangle_points_refined(c, cuts, depth - 1))
    .collect()
}

/// The triangle `p` cut along the vertical lines $x = c$ (`cuts` that cross its
/// interior), as triangles: each cut splits a convex polygon in two, and each
/// polygon is fanned from its first vertex.
pub fn clip_vertical(p: [[f64; 2]; 3], cuts: &[f64]) -> Vec<[[f64; 2]; 3]> {
    let mut polys: Vec<Vec<[f64; 2]>> = vec![p.to_vec()];
    for &c in cuts {
        let mut next = Vec::with_capacity(polys.len() + 1);
        for poly in polys {
            let (lo, hi) = poly
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), q| {
                    (l.min(q[0]), h.max(q[0]))
                });
            if c <= lo || c >= hi {
                next.push(poly);
                continue;
            }
            let (mut left, mut right) = (vec![], vec![]);
            for i in 0..poly.len() {
                let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
                if a[0] <= c {
                    left.push(a);
                }
                if a[0] >= c {
                    right.push(a);
                }
                if (a[0] - c) * (b[0] - c) < 0.0 {
                    let s = (c - a[0]) / (b[0] - a[0]);
                    let q = [c, a[1] + s * (b[1] - a[1])];
                    left.push(q);
                    right.push(q);
                }
            }
            next.push(left);
            next.push(right);
        }
        polys = next;
    }
    polys
        .into_iter()
        .filter(|poly| poly.len() >= 3)
        .flat_map(|poly| (1..poly.len() - 1).map(move |i| [poly[0], poly[i], poly[i + 1]]))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rules_are_exact_to_their_degree() {
        // Gauss 5 on [0, 2]: x^9 integrates to 2^10 / 10.
        let v = segment(0.0, 2.0, &[], |x| x.powi(9));
        assert!((v - 102.4).abs() < 1e-11, "{v}");
        // The triangle rule on the unit triangle: x^a y^b integrates to a! b! / (a+b+2)!.
        let p = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        let fact = |n: u32| (1..=n).product::<u32>().max(1) as f64;
        for (a, b) in [(5, 0), (2, 3), (1, 4), (0, 0)] {
            let exact = fact(a) * fact(b) / fact(a + b + 2);
            let v: f64 = triangle_points(p, &[])
                .iter()
                .map(|(x, w)| w * x[0].powi(a as i32) * x[1].powi(b as i32))
                .sum();
            assert!((v - exact).abs() < 1e-14, "{a} {b}: {v} {exact}");
        }
    }

    #[test]
    fn cuts_keep_the_area_and_integrate_kinks_exactly() {
        let p = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]];
        let pts = triangle_points(p, &[0.3, 0.7, 2.0]);
        let area: f64 = pts.iter().map(|x| x.1).sum();
        assert!((area - 0.5).abs() < 1e-15);
        // |x - 0.3| y: piecewise polynomial, exact with the cut; its exact integral
        // over {0 < y < x < 1} is int_0^1 |x - 0.3| x^2 / 2 dx.
        let exact = {
            let f = |x: f64| (x - 0.3).abs() * x * x / 2.0;
            segment(0.0, 1.0, &[0.3], f)
        };
        let v: f64 = pts.iter().map(|(x, w)| w * (x[0] - 0.3).abs() * x[1]).sum();
        assert!((v - exact).abs() < 1e-15, "{v} {exact}");
    }
}
