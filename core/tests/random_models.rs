//! Random bodies, excitations, initial states, methods and tolerances: every run ends normally
//! (or with a typed error), its events alternate as the automaton allows, and its history stays
//! inside the model's relations. Catches panics and stuck event logic in corners no case names.

use crate::common;

use flexrock_core::model::{Model, Overrides};
use flexrock_core::physics::automaton::{EventKind, Mode};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 1000,
        failure_persistence: None,
        rng_seed: common::proptest_seed(20_261_128),
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_runs_end_normally(
        height in 2.0f64..8.0,
        slenderness in 0.08f64..0.3,
        log_e in 6.0f64..9.0,
        damping in 0.0f64..0.1,
        amplitude in 0.0f64..6.0,
        period in 0.3f64..3.0,
        kind in 0usize..4,
        q0_fraction in -0.9f64..0.9,
        qdot0 in -0.5f64..0.5,
        method in 0usize..6,
        log_rtol in -10.0f64..-3.0,
        consistent in proptest::bool::ANY,
    ) {
        let width = height * slenderness;
        let excitation = match kind {
            0 => format!("kind = \"harmonic\"\namplitude = {amplitude}\nperiod = {period}"),
            1 => format!("kind = \"paper-sine\"\namplitude = {amplitude}\nperiod = {period}\nramp = {}", 0.412 * period),
            2 => format!("kind = \"sine-pulse\"\namplitude = {amplitude}\nperiod = {period}"),
            _ => "kind = \"free\"".to_string(),
        };
        let method = ["bdf", "esdirk34", "tr-bdf2", "tsit45", "newmark", "exact"][method];
        let tolerances = if method == "newmark" {
            "dt = 0.002".to_string()
        } else if method == "exact" {
            String::new()
        } else {
            format!("rtol = {}\natol = {}", 10f64.powf(log_rtol), 10f64.powf(log_rtol - 2.0))
        };
        let text = format!(
            "[body]\nheight = {height}\nwidth = {width}\ndensity = 600.0\nyoungs_modulus = {}\n\
             damping_ratio = {damping}\nself_weight = \"{}\"\n[excitation]\n{excitation}\n[simulation]\nduration = 4.0\n\
             q0 = {}\nqdot0 = {qdot0}\n[solver]\nmethod = \"{method}\"\n{tolerances}\noutput_dt = 0.01\n",
            10f64.powf(log_e),
            if consistent { "consistent" } else { "paper" },
            q0_fraction * width,
        );
        let Ok(model) = Model::from_toml_str(&text, &Overrides::default()) else {
            // Bodies the model refuses (unstable, too squat, Newmark beyond its limit) are fine.
            return Ok(());
        };
        let sol = flexrock_core::simulate::simulate(&model).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        let s_n = model.constants.uplift_displacement;
        // The overturning guard: B in the paper's model, where F = 0 in the consistent one.
        let b = model.constants.topple_displacement;
        // Events chain: each starts in the mode the previous one ended in.
        for pair in sol.events.windows(2) {
            prop_assert_eq!(pair[0].to, pair[1].from, "{}", text);
        }
        // Newmark with compensation logs an event where it detects it, past the guard.
        if method != "newmark" {
            // Uplifts and overturns move away from the floor, landings back towards it.
            let wrong = common::event_against_its_direction(&sol);
            prop_assert!(wrong.is_none(), "{:?}\n{}", wrong, text);
            for e in &sol.events {
                let level = match e.kind { EventKind::Overturn => b, _ => s_n };
                prop_assert!((e.q.abs() - level).abs() < 1e-12);
            }
            for s in &sol.samples {
                prop_assert!(s.q.abs() <= b * (1.0 + 1e-9));
                match s.mode {
                    Mode::PreUplift => prop_assert!(s.q.abs() <= s_n * (1.0 + 1e-6) + 1e-9, "{} {}", s.t, s.q),
                    Mode::RockRight => prop_assert!(s.q >= s_n * (1.0 - 1e-6) - 1e-9, "{} {}", s.t, s.q),
                    Mode::RockLeft => prop_assert!(s.q <= -s_n * (1.0 - 1e-6) + 1e-9, "{} {}", s.t, s.q),
                    Mode::Overturned => {}
                }
            }
        }
        prop_assert!(sol.final_time <= model.duration * (1.0 + 1e-12));
    }
}
