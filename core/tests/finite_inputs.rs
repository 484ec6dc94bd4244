//! No finite input makes a number that is not one: every numeric key of a model file (one body,
//! every excitation kind and solver; a row under either contact law), set to an extreme finite
//! value, is either refused with a message that names it, or gives a solution in which every
//! number is finite (or a run that stops at one of the caps every run has, saying so: a column
//! 1e20 m deep beside one 1 m deep chatters against it as against a wall).

use flexrock_core::model::{Model, Overrides, RowModel, Setting};
use proptest::prelude::*;

/// The body of every single-body model: the paper's.
const BODY: &str = "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\n\
                    youngs_modulus = 5e6\ndamping_ratio = 0.05\ngravity = 9.81\n";

/// The excitations, each with a duration: every kind (a record is made in memory elsewhere;
/// its keys are those of its file, read by the same rules).
const EXCITATIONS: [&str; 5] = [
    "[excitation]\nkind = \"paper-sine\"\namplitude = 5.0\nperiod = 1.0\nramp = 0.412\n\
     [simulation]\nduration = 2.0\n",
    "[excitation]\nkind = \"harmonic\"\namplitude = 5.0\nperiod = 1.0\n\
     [simulation]\nduration = 2.0\n",
    "[excitation]\nkind = \"sine-pulse\"\namplitude = 5.0\nperiod = 1.0\ncycles = 1.0\n\
     tail = 1.0\n",
    "[excitation]\nkind = \"ricker\"\namplitude = 5.0\nperiod = 1.0\ncenter = 1.0\n\
     [simulation]\nduration = 2.0\n",
    "[excitation]\nkind = \"free\"\n[simulation]\nduration = 2.0\nq0 = 0.05\n",
];

/// The numeric keys of a single body's file, each with the excitations (by index) that take it
/// and the solver methods it is read with.
const KEYS: [(&str, &[usize], &[&str]); 25] = {
    const ALL: &[usize] = &[0, 1, 2, 3, 4];
    const SOLVERS: &[&str] = &["exact", "tsit45", "bdf", "newmark"];
    [
        ("body.height", ALL, SOLVERS),
        ("body.width", ALL, SOLVERS),
        ("body.depth", ALL, SOLVERS),
        ("body.density", ALL, SOLVERS),
        ("body.youngs_modulus", ALL, SOLVERS),
        ("body.damping_ratio", ALL, SOLVERS),
        ("body.gravity", ALL, SOLVERS),
        ("body.poisson_ratio", ALL, SOLVERS),
        ("excitation.amplitude", &[0, 1, 2, 3], SOLVERS),
        ("excitation.period", &[0, 1, 2, 3], SOLVERS),
        ("excitation.ramp", &[0], SOLVERS),
        ("excitation.cycles", &[2], SOLVERS),
        ("excitation.tail", &[2], SOLVERS),
        ("excitation.center", &[3], SOLVERS),
        ("simulation.duration", ALL, SOLVERS),
        ("simulation.q0", ALL, SOLVERS),
        ("simulation.qdot0", ALL, SOLVERS),
        ("solver.output_dt", ALL, SOLVERS),
        (
            "solver.rtol",
            ALL,
            &["tsit45", "bdf", "esdirk34", "tr-bdf2"],
        ),
        (
            "solver.atol",
            ALL,
            &["tsit45", "bdf", "esdirk34", "tr-bdf2"],
        ),
        ("solver.dt", ALL, &["newmark"]),
        ("solver.newmark_beta", ALL, &["newmark"]),
        ("solver.newmark_gamma", ALL, &["newmark"]),
        ("body.mass", ALL, SOLVERS),
        ("body.period", ALL, SOLVERS),
    ]
};

/// A row under each contact law: two columns of the paper's size.
fn row_text(compliant: bool, key: &str, value: f64) -> String {
    let value = format!("{value:e}");
    let mut row = vec![
        ("gaps", "[0.003]".to_string()),
        ("restitution", "0.5".to_string()),
    ];
    if compliant {
        row.push(("contact", "\"compliant\"".to_string()));
        row.push(("stiffness", "1e9".to_string()));
        row.push(("friction", "0.5".to_string()));
    }
    let column = |youngs_modulus: &str| {
        vec![
            ("height", "4.0".to_string()),
            ("width", "0.7".to_string()),
            ("depth", "1.0".to_string()),
            ("density", "600.0".to_string()),
            ("youngs_modulus", youngs_modulus.to_string()),
            ("damping_ratio", "0.05".to_string()),
        ]
    };
    let mut columns = [column("5e8"), column("5e6")];
    let mut simulation = vec![("duration", "1.5".to_string())];
    let mut solver = vec![("output_dt", "0.01".to_string())];
    let mut excitation = vec![
        ("kind", "\"sine-pulse\"".to_string()),
        ("amplitude", "2.0".to_string()),
        ("period", "1.0".to_string()),
    ];
    let set = |table: &mut Vec<(&str, String)>, name: &'static str| {
        table.retain(|(k, _)| *k != name);
        table.push((name, value.clone()));
    };
    match key.split_once('.').expect("section.name") {
        ("row", "gaps") => {
            row.retain(|(k, _)| *k != "gaps");
            row.push(("gaps", format!("[{value}]")));
        }
        ("row", name) => set(&mut row, leak(name)),
        ("column", name) => set(&mut columns[0], leak(name)),
        ("simulation", name) => set(&mut simulation, leak(name)),
        ("solver", name) => set(&mut solver, leak(name)),
        ("excitation", name) => set(&mut excitation, leak(name)),
        other => panic!("{other:?}"),
    }
    let table = |name: &str, pairs: &[(&str, String)]| {
        let mut text = format!("{name}\n");
        for (k, v) in pairs {
            text.push_str(&format!("{k} = {v}\n"));
        }
        text
    };
    let mut text = table("[row]", &row);
    for column in &columns {
        text.push_str(&table("[[column]]", column));
    }
    text.push_str(&table("[excitation]", &excitation));
    text.push_str(&table("[simulation]", &simulation));
    text.push_str(&table("[solver]", &solver));
    text
}

fn leak(name: &str) -> &'static str {
    Box::leak(name.to_string().into_boxed_str())
}

/// The numeric keys of a row's file, and whether they belong to the compliant law only.
const ROW_KEYS: [(&str, bool); 14] = [
    ("row.gaps", false),
    ("row.restitution", false),
    ("row.stiffness", true),
    ("row.friction", true),
    ("column.height", false),
    ("column.width", false),
    ("column.depth", false),
    ("column.density", false),
    ("column.youngs_modulus", false),
    ("column.damping_ratio", false),
    ("column.q0", false),
    ("column.qdot0", false),
    ("excitation.amplitude", false),
    ("simulation.duration", false),
];

/// Extreme finite values: the ends of the range, the squares' overflow and underflow, a
/// subnormal, both zeros, and a power of ten drawn far from 1.
fn extreme() -> impl Strategy<Value = f64> {
    let fixed = prop::sample::select(vec![
        f64::MAX,
        -f64::MAX,
        1e300,
        -1e300,
        1e154,
        -1e154,
        1e-154,
        -1e-154,
        1e-300,
        f64::MIN_POSITIVE,
        f64::MIN_POSITIVE / 4.0,
        5e-324,
        0.0,
        -0.0,
    ]);
    let drawn =
        (prop::bool::ANY, 20i32..=307, prop::bool::ANY).prop_map(|(negative, exponent, small)| {
            let x = 10f64.powi(if small { -exponent } else { exponent });
            if negative {
                -x
            } else {
                x
            }
        });
    prop_oneof![fixed, drawn]
}

/// The first number of `text` (a Debug print of a solution) that is not finite, if any.
fn not_finite(text: &str) -> Option<&str> {
    text.split(|c: char| !(c.is_ascii_alphanumeric() || c == '-' || c == '.'))
        .find(|word| matches!(*word, "NaN" | "inf" | "-inf"))
}

/// Whether a run stopped at one of the caps of the events or steps every run has (book: Exit
/// codes, limits and warnings, "Every run ends"), which its message names.
fn stopped_at_a_cap(e: &flexrock_core::Error) -> bool {
    let message = e.to_string();
    matches!(e, flexrock_core::Error::Solver { .. })
        && (message.contains("over the cap of") || message.contains("a cascade of"))
}

/// Whether an error message names `key` (by its name in the section) or the derived quantity
/// that it made break a rule.
fn names(message: &str, key: &str) -> bool {
    let name = key.rsplit('.').next().unwrap_or(key);
    message.contains(name) || message.contains("derived ")
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        failure_persistence: None,
        rng_seed: crate::common::proptest_seed(20_261_207),
        ..ProptestConfig::default()
    })]

    #[test]
    fn an_extreme_value_of_a_key_is_refused_by_name_or_solved_finite(
        (key, excitation, method) in (0..KEYS.len()).prop_flat_map(|k| {
            let (_, kinds, methods) = KEYS[k];
            (Just(k), prop::sample::select(kinds.to_vec()), prop::sample::select(methods.to_vec()))
        }),
        value in extreme(),
    ) {
        let (key, _, _) = KEYS[key];
        let mut text = format!("{BODY}{}", EXCITATIONS[excitation]);
        if key == "body.mass" {
            text = text.replace("density = 600.0\n", "");
        }
        if key == "body.period" {
            text = text.replace("youngs_modulus = 5e6\n", "");
        }
        let overrides = Overrides {
            settings: vec![Setting::text("solver.method", method), Setting::number(key, value)],
            ..Overrides::default()
        };
        let context = format!("{key} = {value:e}, method {method}, excitation {excitation}");
        let model = match Model::from_toml_str(&text, &overrides) {
            Ok(model) => model,
            Err(e) => {
                let message = e.to_string();
                prop_assert!(names(&message, key), "{context}: refused without naming it: {message}");
                return Ok(());
            }
        };
        let solution = match flexrock_core::simulate::simulate(&model) {
            Ok(solution) => solution,
            Err(e) => {
                prop_assert!(stopped_at_a_cap(&e), "{context}: accepted, then the run failed: {e}");
                return Ok(());
            }
        };
        let printed = format!("{:?} {:?} {:?}", solution.samples, solution.events, solution.max_q);
        let printed = format!(
            "{printed} {:?} {:?} {} {}",
            solution.min_q, solution.episodes, solution.max_energy_residual, solution.energy_scale
        );
        prop_assert!(not_finite(&printed).is_none(), "{context}: a number that is not finite");
    }

    #[test]
    fn an_extreme_value_of_a_row_key_is_refused_by_name_or_solved_finite(
        (key, compliant) in (0..ROW_KEYS.len()).prop_flat_map(|k| {
            let (_, compliant_only) = ROW_KEYS[k];
            (Just(k), if compliant_only { Just(true).boxed() } else { prop::bool::ANY.boxed() })
        }),
        value in extreme(),
    ) {
        let (key, _) = ROW_KEYS[key];
        let text = row_text(compliant, key, value);
        let context = format!("{key} = {value:e}, compliant {compliant}");
        let model = match RowModel::from_toml_str(&text) {
            Ok(model) => model,
            Err(e) => {
                let message = e.to_string();
                prop_assert!(names(&message, key), "{context}: refused without naming it: {message}");
                return Ok(());
            }
        };
        let solution = match flexrock_core::simulate::simulate_row(&model) {
            Ok(solution) => solution,
            Err(e) => {
                prop_assert!(stopped_at_a_cap(&e), "{context}: accepted, then the run failed: {e}");
                return Ok(());
            }
        };
        let mut printed = String::new();
        for column in &solution.columns {
            printed.push_str(&format!(
                "{:?} {:?} {:?} {:?} {}",
                column.samples, column.events, column.max_q, column.min_q, column.max_energy_residual
            ));
        }
        printed.push_str(&format!(
            "{:?} {:?} {:?} {:?}",
            solution.impacts, solution.contacts, solution.contact_history, solution.sticking
        ));
        prop_assert!(not_finite(&printed).is_none(), "{context}: a number that is not finite");
    }
}

/// The body's keys set one at a time to their extreme values give no number that is not finite,
/// and the excitation keys found by the audit among them: a Ricker wavelet centred at 1e154 s
/// and beyond (its floor acceleration was NaN at every sample), a friction of 1e200 between a
/// row's faces (histories of NaN from 0.38 s on, and the friction's work -inf J).
#[test]
fn the_audits_inputs_give_finite_numbers_or_a_refusal() {
    for center in [1e154, -1e154, 1e300, -1e300, f64::MAX] {
        for method in ["exact", "tsit45", "bdf", "newmark"] {
            let overrides = Overrides {
                settings: vec![
                    Setting::text("solver.method", method),
                    Setting::number("excitation.center", center),
                ],
                ..Overrides::default()
            };
            let text = format!("{BODY}{}", EXCITATIONS[3]);
            let model = Model::from_toml_str(&text, &overrides).expect("a wavelet far away");
            let solution = flexrock_core::simulate::simulate(&model)
                .unwrap_or_else(|e| panic!("center {center:e}, {method}: {e}"));
            for sample in &solution.samples {
                assert_eq!(sample.floor_acc, 0.0, "center {center:e}, {method}");
                assert_eq!(sample.q, 0.0, "center {center:e}, {method}");
            }
        }
    }
    let message = RowModel::from_toml_str(&row_text(true, "row.friction", 1e200))
        .err()
        .expect("refused")
        .to_string();
    assert!(
        message.contains("row.friction = 1e200") && message.contains("at most 10"),
        "{message}"
    );
}
