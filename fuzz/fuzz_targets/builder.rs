//! Arbitrary bytes as a sequence of the scene's checked builders (`with_g`,
//! `without_limit`, `with_loads`, `with_elasticity`, `with_viscosity`, `with_ramp`,
//! `with_history`, `with_problem`, `with_law`, `with_name`, `with_description`,
//! `with_pattern`) applied to the paper's scene, each with values read from the bytes
//! (any bit pattern: NaN, infinities, subnormals). No builder may panic; a refusal
//! must name its field; a scene that is accepted must solve on a small mesh without a
//! panic (a failure to converge is an error, not a crash).
#![no_main]
use evhi::geometry::Pattern;
use evhi::history::History;
use evhi::law::Law;
use evhi::scenario::{Problem, Scenario};
use evhi::simulation::{RunSettings, Simulation};
use libfuzzer_sys::fuzz_target;

fn take(data: &mut &[u8]) -> Option<f64> {
    let (head, rest) = data.split_first_chunk::<8>()?;
    *data = rest;
    Some(f64::from_le_bytes(*head))
}

fuzz_target!(|bytes: &[u8]| {
    let mut data = bytes;
    let mut scene = Scenario::load("figure").expect("the built-in scene");
    while let Some((&op, rest)) = data.split_first() {
        data = rest;
        let (Some(a), Some(b)) = (take(&mut data), take(&mut data)) else {
            break;
        };
        let next = match op % 12 {
            0 => scene.clone().with_g(a),
            1 => scene.clone().with_loads(Some([a, b]), Some([0.0, b])),
            2 => scene.clone().with_elasticity(a, b),
            3 => scene.clone().with_viscosity(a, b),
            4 => scene.clone().with_ramp(a),
            5 => match Law::new(&[0.0, a.abs()], &[0.0, b, 300.0], &[0.0, a], 0.0) {
                Ok(law) => scene.clone().with_law(law),
                Err(e) => Err(e),
            },
            6 => scene
                .clone()
                .with_name(&String::from_utf8_lossy(&a.to_le_bytes())),
            7 => scene.clone().without_limit(),
            8 => scene.clone().with_history(History::Table {
                points: vec![(0.0, a), (b, 1.0)],
            }),
            9 => scene.clone().with_problem(
                [Problem::Viscoelastic, Problem::Elastic, Problem::Steady]
                    [(a.to_bits() % 3) as usize],
            ),
            10 => scene
                .clone()
                .with_description(&String::from_utf8_lossy(&b.to_le_bytes())),
            _ => Ok(scene.clone().with_pattern(if a.to_bits() % 2 == 0 {
                Pattern::Diagonal
            } else {
                Pattern::CrissCross
            })),
        };
        match next {
            Ok(s) => scene = s,
            Err(e) => assert!(e.field_name().is_some() || !e.to_string().is_empty()),
        }
    }
    let settings = RunSettings::default().with_n(4).with_steps(2);
    if let Ok(sim) = Simulation::new(scene, settings) {
        let _ = sim.solve(&mut ());
    }
});
