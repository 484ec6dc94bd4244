//! Whatever the text of a model file, reading it gives a model or an error, never a panic.

use flexrock_core::model::{Model, Overrides};
use proptest::prelude::*;

const REFERENCE: &str = include_str!("../../models/ichinose1986.toml");

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 2000,
        failure_persistence: None,
        rng_seed: crate::common::proptest_seed(20_261_129),
        ..ProptestConfig::default()
    })]

    #[test]
    fn arbitrary_text_never_panics(text in ".{0,400}") {
        let _ = Model::from_toml_str(&text, &Overrides::default());
    }

    #[test]
    fn edited_reference_never_panics(
        edits in proptest::collection::vec((0usize..2000, "[-0-9.eE+a-z=\"\\n\\[\\] ]{0,6}"), 0..6)
    ) {
        let mut text = REFERENCE.to_string();
        for (at, insert) in edits {
            let mut at = at % (text.len() + 1);
            while !text.is_char_boundary(at) {
                at -= 1;
            }
            let end = (at + insert.len()).min(text.len());
            let end = (end..=text.len()).find(|&e| text.is_char_boundary(e)).unwrap_or(text.len());
            text.replace_range(at..end, &insert);
        }
        if let Ok(model) = Model::from_toml_str(&text, &Overrides::default()) {
            // A model that passes validation has a body the model means something for.
            prop_assert!(model.constants.uplift_displacement < model.body.width);
            prop_assert!(model.constants.zeta_landing < 1.0);
            prop_assert!(model.duration > 0.0);
        }
    }
}

/// The reference body with `extra` appended (TOML sections), read as a model.
fn reference_with(extra: &str, overrides: &Overrides) -> flexrock_core::error::Result<Model> {
    let text = format!("[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\n{extra}");
    Model::from_toml_str(&text, overrides)
}

const PULSE: &str =
    "[simulation]\nduration = 0.9\n[excitation]\nkind = \"sine-pulse\"\nperiod = 0.8\n";

#[test]
fn documented_inclusive_limits_accept_their_exact_values() {
    let none = Overrides::default();
    let accepted = |extra: &str| {
        reference_with(extra, &none).unwrap_or_else(|e| panic!("{extra}: refused: {e}"));
    };
    // atol <= 0.01 B: 0.01 * 0.7 rounds to 0.006999999999999999.
    accepted(&format!(
        "youngs_modulus = 5e6\n{PULSE}amplitude = 1.0\n[solver]\natol = 0.007\n"
    ));
    // A peak floor acceleration of 20 g = 20 x 9.80665 = 196.133 m/s^2 (rounds to ...2998).
    accepted(&format!(
        "youngs_modulus = 5e6\n{PULSE}amplitude = 196.133\n"
    ));
    // A pre-uplift period of 1e-4 s, in both variants.
    accepted(&format!("period = 1e-4\n{PULSE}amplitude = 1.0\n"));
    accepted(&format!(
        "period = 1e-4\nself_weight = \"consistent\"\n{PULSE}amplitude = 1.0\n"
    ));
    // 1e6 history rows and 1e8 Newmark steps: 0.9/9e-7 and 0.9/9e-9 round above them.
    accepted(&format!(
        "youngs_modulus = 5e6\n{PULSE}amplitude = 1.0\n[solver]\noutput_dt = 9e-7\n"
    ));
    accepted(&format!(
        "youngs_modulus = 5e6\n{PULSE}amplitude = 1.0\n[solver]\nmethod = \"newmark\"\ndt = 9e-9\n"
    ));
    // 1e6 FEM steps: 0.9 / 9e-7.
    flexrock_core::bodies::fem::check_run_size(2, 5, 9e-7, 0.9).expect("1e6 steps");

    // Beyond the limits, the message prints the limit as written.
    let refused = |extra: &str| match reference_with(extra, &none) {
        Ok(_) => panic!("{extra}: accepted"),
        Err(e) => e.to_string(),
    };
    let atol = refused(&format!(
        "youngs_modulus = 5e6\n{PULSE}amplitude = 1.0\n[solver]\natol = 0.0070001\n"
    ));
    assert!(atol.contains("[7e-19, 0.007]"), "{atol}");
    let peak = refused(&format!(
        "youngs_modulus = 5e6\n{PULSE}amplitude = 196.1331\n"
    ));
    assert!(peak.contains("limit of 196.133 m/s^2 (20 g)"), "{peak}");
    let period = refused(&format!("period = 0.9999e-4\n{PULSE}amplitude = 1.0\n"));
    assert!(period.contains("at least 1e-4 s"), "{period}");
}

#[test]
fn a_body_that_lifts_off_under_its_own_weight_is_refused() {
    // With the weight in the bending, E = 1.177 MPa is just short of buckling (M g H^2/EI =
    // 7.834 against 7.837) but s_n exceeds B = 0.7 m; E = 5 MPa stands (s_n = 0.189 m).
    let extra = |e: f64| {
        format!("self_weight = \"consistent\"\nyoungs_modulus = {e}\n{PULSE}amplitude = 1.0\n")
    };
    let message = match reference_with(&extra(1177175.17), &Overrides::default()) {
        Ok(m) => panic!(
            "accepted with s_n = {} m, B = 0.7 m",
            m.constants.uplift_displacement
        ),
        Err(e) => e.to_string(),
    };
    for part in [
        "body.youngs_modulus = 1177175.17",
        "unstable under its own weight",
        "must be less than the width B = 0.7 m",
        "body.density",
        "body.height",
    ] {
        assert!(message.contains(part), "{part:?} not in: {message}");
    }
    let standing = reference_with(&extra(5e6), &Overrides::default()).unwrap();
    assert!(standing.constants.uplift_displacement < 0.7);
}

#[test]
fn an_overflowing_body_product_blames_the_key_that_was_set() {
    // M = density H B D overflows at H = 1e308: the message names body.height, not body.mass.
    let overrides = Overrides {
        settings: vec![flexrock_core::model::Setting::number("body.height", 1e308)],
        ..Overrides::default()
    };
    let text = format!(
        "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\nyoungs_modulus = 5e6\n\
         {PULSE}amplitude = 1.0\n"
    );
    let message = Model::from_toml_str(&text, &overrides)
        .err()
        .expect("refused")
        .to_string();
    assert!(message.contains("body.height = 1e308"), "{message}");
    assert!(!message.contains("body.mass"), "{message}");
    // EI = E D B^3/12 overflows at B = 1e103 (before B < H is checked).
    let text = text.replace("width = 0.7", "width = 1e103");
    let message = Model::from_toml_str(&text, &Overrides::default())
        .err()
        .expect("refused")
        .to_string();
    assert!(message.contains("body.width = 1e103"), "{message}");
}

/// A key the excitation's kind does not take is refused with the value it was given: a number as
/// typed, a text as written.
#[test]
fn a_key_of_another_kind_is_refused_with_its_value() {
    let harmonic =
        "youngs_modulus = 5e6\n[simulation]\nduration = 1.0\n[excitation]\nkind = \"harmonic\"\n\
                    amplitude = 1.0\nperiod = 0.5\n";
    for (extra, key, value) in [
        ("cycles = 2.5", "excitation.cycles", "2.5"),
        ("tail = 1e-7", "excitation.tail", "0.0000001"),
        ("shape = \"symmetric\"", "excitation.shape", "symmetric"),
    ] {
        let text = format!("{harmonic}{extra}\n");
        let message = reference_with(&text, &Overrides::default())
            .err()
            .unwrap_or_else(|| panic!("{extra} was read"))
            .to_string();
        assert!(
            message.contains(key)
                && message.contains(value)
                && message.contains("not a parameter of kind = \"harmonic\""),
            "{extra}: {message}"
        );
    }
}
