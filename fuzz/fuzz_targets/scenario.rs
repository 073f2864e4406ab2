//! Arbitrary bytes as a scenario file: parsing must never panic, and a rejection
//! of a value must name its field.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        match evhi::scenario::Scenario::from_toml(text, "fuzz") {
            Ok(s) => assert!(s.t_end() > 0.0 && s.g() > 0.0 && s.kappa() < 0.5),
            Err(e) => assert!(!e.to_string().is_empty()),
        }
    }
});
