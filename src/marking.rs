//! Dörfler's bulk criterion: which of a set of indicators to refine. The space loop
//! ([`crate::adapt`]) marks triangles by it, the time grid's search
//! ([`crate::time_adapt`]) steps.

// ANCHOR: dorfler
/// The smallest set of indices whose `eta_sq` sum to at least `theta` of the total
/// (Dörfler's bulk criterion), largest first; none if the total is zero.
pub fn dorfler(eta_sq: &[f64], theta: f64) -> Vec<usize> {
    let total: f64 = eta_sq.iter().sum();
    if total <= 0.0 || total.is_nan() {
        return vec![];
    }
    let mut order: Vec<usize> = (0..eta_sq.len()).collect();
    order.sort_by(|&a, &b| eta_sq[b].total_cmp(&eta_sq[a]).then(a.cmp(&b)));
    let goal = theta * total;
    let mut sum = 0.0;
    let mut out = vec![];
    for i in order {
        if sum >= goal {
            break;
        }
        sum += eta_sq[i];
        out.push(i);
    }
    out
}
// ANCHOR_END: dorfler

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dorfler_takes_the_fewest_largest() {
        // Total 10: half is 5, reached by 4 + 1 (the two largest are 4 and 3: 7 >= 5).
        let eta = [1.0, 4.0, 0.5, 3.0, 1.5];
        assert_eq!(dorfler(&eta, 0.5), vec![1, 3]);
        // 0.4 of 10 is 4: the largest alone.
        assert_eq!(dorfler(&eta, 0.4), vec![1]);
        assert_eq!(dorfler(&eta, 1.0).len(), 5);
        assert!(dorfler(&[0.0, 0.0], 0.5).is_empty());
    }
}
