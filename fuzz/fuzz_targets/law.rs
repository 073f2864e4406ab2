//! Arbitrary numbers as a law: construction must never panic; a valid law must
//! evaluate to finite values with a Clarke interval holding both one-sided limits.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let nums: Vec<f64> = data
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap()))
        .collect();
    if nums.len() < 3 {
        return;
    }
    let k = (nums.len() - 2) / 3;
    let (breaks, rest) = nums.split_at(k);
    let (slopes, rest) = rest.split_at(k + 1);
    let (jumps, rest) = rest.split_at(k.min(rest.len()));
    let p_left = rest.first().copied().unwrap_or(0.0);
    match evhi::law::Law::new(breaks, slopes, jumps, p_left) {
        Ok(law) => {
            for &s in breaks.iter().chain([0.0, -1.0, 1.0].iter()) {
                let c = law.clarke(s);
                let (a, b) = law.p_sides(s);
                assert!(c.lo <= a.min(b) && a.max(b) <= c.hi || !(a.is_finite() && b.is_finite()));
            }
        }
        Err(e) => assert!(e.field_name().is_some_and(|f| f.starts_with("law."))),
    }
});
