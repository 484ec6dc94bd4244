//! Random rows of two to four columns under the shipped records at random scales, gaps and
//! restitutions: every run ends (at its duration, or where a column overturns), every impact
//! carries an impulse (in a chain one may also fall on a contact that is not closing, pushed by
//! its neighbour's) and strikes its instant once, held stretches end after they begin, and
//! every column's energy books close. Catches chatter and stuck contact logic in corners no
//! case names (the three- and four-column cases of `row.rs` were found this way). The same for
//! compliant rows with friction: every run ends, friction never exceeds mu times the contact
//! force nor gives energy, stuck stretches end after they begin, and the books close. And
//! rows made to strike at one instant (two bodies in turn, gaps down to 1e-12 m, under records
//! and pulses, both laws, friction or none): at no sample do two faces stand overlapping
//! without a contact between them.

use proptest::prelude::*;

const RECORDS: [&str; 5] = [
    "A-ELC180.AT2",
    "ANLA196.AT2",
    "HEN-E.AT2",
    "PBFEAS.AT2",
    "elCentro.AT2",
];

/// A drawn column: height (m), slenderness B/H, log10 of the gravity parameter, damping ratio,
/// consistent self-weight.
type Drawn = (f64, f64, f64, f64, bool);

/// Two to four drawn columns.
fn drawn_columns() -> impl Strategy<Value = Vec<Drawn>> {
    proptest::collection::vec(
        (
            2.5f64..5.5,
            0.1f64..0.22,
            -2.0f64..0.4,
            0.0f64..0.06,
            proptest::bool::ANY,
        ),
        2..=4,
    )
}

/// The `[[column]]` tables of the drawn columns. Young's modulus comes from the gravity
/// parameter M g H^2 / EI = 12 rho g H / (E s^2) (from 0.01, near rigid, to 2.5, a quarter of
/// the way to buckling from the top), so that nearly every body drawn is one the model accepts.
fn column_tables(columns: &[Drawn]) -> String {
    let mut text = String::new();
    for &(height, slenderness, log_gravity, damping, consistent) in columns {
        let width = height * slenderness;
        let youngs =
            12.0 * 600.0 * 9.81 * height / (10f64.powf(log_gravity) * slenderness * slenderness);
        text.push_str(&format!(
            "[[column]]\nheight = {height}\nwidth = {width}\ndensity = 600.0\n\
             youngs_modulus = {youngs:e}\ndamping_ratio = {damping}\nself_weight = \"{}\"\n",
            if consistent { "consistent" } else { "paper" },
        ));
    }
    text
}

/// The `[excitation]` (record `record` of [`RECORDS`] times `scale`) and `[solver]` tables,
/// the solver's with `solver` before its `output_dt`.
fn floor_and_solver(record: usize, scale: f64, solver: &str) -> String {
    let records = concat!(env!("CARGO_MANIFEST_DIR"), "/../validation/records");
    format!(
        "[excitation]\nkind = \"record\"\npath = \"{records}/{}\"\nformat = \"peer-at2\"\n\
         units = \"g\"\nscale = {scale}\n[solver]\n{solver}output_dt = 0.02\n",
        RECORDS[record],
    )
}

/// Duration of every random row's run, s.
const DURATION: f64 = 12.0;

/// Solves the row model `text` (written into the test directory `name`) over `duration`, and
/// checks that the run ended at its duration or where a column overturned. None for a body the
/// model refuses (s_n beyond B under the consistent self-weight).
fn solve_to_its_end(
    text: &str,
    name: &str,
    duration: f64,
) -> Result<Option<flexrock_core::bodies::row::RowSolution>, TestCaseError> {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::create_dir_all(&dir).expect("temporary directory");
    let path = dir.join("row.toml");
    std::fs::write(&path, text).expect("model file written");
    let model = match flexrock_core::model::RowModel::load(&path, Some(duration)) {
        Ok(model) => model,
        Err(e) if e.to_string().contains("unstable under its own weight") => return Ok(None),
        Err(e) => return Err(TestCaseError::fail(format!("refused: {e}\n{text}"))),
    };
    let solution = flexrock_core::simulate::simulate_row(&model)
        .map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
    match solution.overturned {
        Some((_, t)) => prop_assert_eq!(solution.final_time, t, "{}", text),
        None => prop_assert_eq!(solution.final_time, duration, "{}", text),
    }
    Ok(Some(solution))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 48,
        failure_persistence: None,
        rng_seed: crate::common::proptest_seed(20_261_126),
        ..ProptestConfig::default()
    })]

    #[test]
    fn random_rows_under_records_end_normally(
        columns in drawn_columns(),
        log_gaps in proptest::collection::vec(-3.5f64..-1.3, 3),
        restitution in 0.0f64..=1.0,
        record in 0usize..5,
        scale in 0.5f64..4.0,
    ) {
        let n = columns.len();
        let gaps: Vec<String> = log_gaps[..n - 1].iter().map(|g| format!("{:e}", 10f64.powf(*g))).collect();
        let mut text = format!("[row]\ngaps = [{}]\nrestitution = {restitution}\n", gaps.join(", "));
        text.push_str(&column_tables(&columns));
        text.push_str(&floor_and_solver(record, scale, ""));
        let Some(solution) = solve_to_its_end(&text, "random-rows", DURATION)? else {
            return Ok(());
        };
        let mut struck: Vec<(usize, f64)> = Vec::new();
        for impact in &solution.impacts {
            prop_assert!(impact.impulse > 0.0, "impact without impulse {:?}\n{}", impact, text);
            prop_assert!(!struck.contains(&(impact.contact, impact.t)), "instant struck twice {:?}\n{}", impact, text);
            struck.push((impact.contact, impact.t));
        }
        for held in &solution.held {
            if let Some(end) = held.t_end {
                prop_assert!(end > held.t_start, "{:?}\n{}", held, text);
            }
        }
        for (i, column) in solution.columns.iter().enumerate() {
            // An impact right after a column's own event is booked after it, not an ulp before.
            prop_assert!(column.events.windows(2).all(|w| w[0].t <= w[1].t), "column {}: events out of order\n{}", i, text);
            let share = column.energy_residual_share();
            prop_assert!(share < 1e-8, "column {}: energy residual {} of its scale\n{}", i, share, text);
        }
    }

    #[test]
    fn random_compliant_rows_with_friction_end_normally(
        columns in drawn_columns(),
        log_gaps in proptest::collection::vec(-3.5f64..-1.3, 3),
        restitution in 0.05f64..=1.0,
        log_stiffness in 6.0f64..9.0,
        friction in 0.0f64..3.0,
        record in 0usize..5,
        scale in 0.5f64..4.0,
    ) {
        let n = columns.len();
        let gaps: Vec<String> = log_gaps[..n - 1].iter().map(|g| format!("{:e}", 10f64.powf(*g))).collect();
        let mut text = format!(
            "[row]\ngaps = [{}]\nrestitution = {restitution}\ncontact = \"compliant\"\n\
             stiffness = {:e}\nfriction = {friction}\n",
            gaps.join(", "),
            10f64.powf(log_stiffness),
        );
        text.push_str(&column_tables(&columns));
        text.push_str(&floor_and_solver(record, scale, "method = \"tsit45\"\n"));
        let Some(solution) = solve_to_its_end(&text, "random-rough-rows", DURATION)? else {
            return Ok(());
        };
        for s in &solution.contacts {
            prop_assert!(s.friction_dissipated >= -1e-9 * s.energy_dissipated.abs().max(1.0), "{:?}\n{}", s, text);
            prop_assert!(s.peak_friction_force <= friction * s.peak_force * (1.0 + 1e-9), "{:?}\n{}", s, text);
        }
        for c in &solution.contact_history {
            let (p, f) = (c.force.unwrap_or(0.0), c.friction_force.unwrap_or(0.0));
            prop_assert!(f.abs() <= friction * p.max(0.0) * (1.0 + 1e-9) + 1e-9, "{:?}\n{}", c, text);
        }
        for stuck in &solution.sticking {
            if let Some(end) = stuck.t_end {
                prop_assert!(end >= stuck.t_start, "{:?}\n{}", stuck, text);
            }
        }
        for (i, column) in solution.columns.iter().enumerate() {
            prop_assert!(column.events.windows(2).all(|w| w[0].t <= w[1].t), "column {}: events out of order\n{}", i, text);
            // The compliant law's books are quadratures of its integration at rtol 1e-10: over
            // these rows they close to 6e-7 of their scale at worst (frictionless rows alike).
            let share = column.energy_residual_share();
            prop_assert!(share < 2e-6, "column {}: energy residual {} of its scale\n{}", i, share, text);
        }
    }
}

/// A row of `n` columns, two bodies in turn: each (height, slenderness, log10 of the gravity
/// parameter), damping 0.05, the paper's self-weight.
fn alternating_columns(n: usize, bodies: [(f64, f64, f64); 2]) -> String {
    column_tables(
        &(0..n)
            .map(|i| {
                let (height, slenderness, log_gravity) = bodies[i % 2];
                (height, slenderness, log_gravity, 0.05, false)
            })
            .collect::<Vec<_>>(),
    )
}

/// A drawn floor motion: a shipped record at a scale (8 s of it), a one-sine pulse or a Ricker
/// wavelet (4 s), as its `[excitation]` table and the run's duration.
fn drawn_floor() -> impl Strategy<Value = (String, f64)> {
    let records = concat!(env!("CARGO_MANIFEST_DIR"), "/../validation/records");
    prop_oneof![
        (0usize..5, 0.5f64..3.0).prop_map(move |(record, scale)| (
            format!(
                "[excitation]\nkind = \"record\"\npath = \"{records}/{}\"\nformat = \"peer-at2\"\n\
                 units = \"g\"\nscale = {scale}\n",
                RECORDS[record]
            ),
            8.0
        )),
        (1.0f64..6.0, 0.3f64..1.5).prop_map(|(amplitude, period)| (
            format!(
                "[excitation]\nkind = \"sine-pulse\"\namplitude = {amplitude}\nperiod = {period}\n\
                 cycles = 1\nshape = \"antisymmetric\"\n"
            ),
            4.0
        )),
        (1.0f64..8.0, 0.3f64..1.5).prop_map(|(amplitude, period)| (
            format!(
                "[excitation]\nkind = \"ricker\"\namplitude = {amplitude}\nperiod = {period}\n\
                 center = 1.0\n"
            ),
            4.0
        )),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 40,
        failure_persistence: None,
        rng_seed: crate::common::proptest_seed(20_261_207),
        ..ProptestConfig::default()
    })]

    #[test]
    fn faces_never_stand_overlapping_without_a_contact(
        n in 2usize..=6,
        soft in (2.5f64..5.5, 0.1f64..0.22, -0.5f64..0.4),
        stiff in (2.5f64..5.5, 0.1f64..0.22, -2.0f64..-0.5),
        equal_heights in proptest::bool::ANY,
        log_gap in -12.0f64..-2.0,
        restitution in 0.05f64..=1.0,
        compliant in proptest::bool::ANY,
        log_stiffness in 6.0f64..9.0,
        friction in prop_oneof![Just(0.0), 0.1f64..1.0],
        (floor, duration) in drawn_floor(),
    ) {
        let stiff = if equal_heights { (soft.0, stiff.1, stiff.2) } else { stiff };
        let gap = format!("{:e}", 10f64.powf(log_gap));
        let mut text = format!(
            "[row]\ngaps = [{}]\nrestitution = {restitution}\n",
            vec![gap; n - 1].join(", ")
        );
        if compliant {
            text.push_str(&format!(
                "contact = \"compliant\"\nstiffness = {:e}\nfriction = {friction}\n",
                10f64.powf(log_stiffness)
            ));
        }
        text.push_str(&alternating_columns(n, [soft, stiff]));
        text.push_str(&floor);
        text.push_str(&format!(
            "[simulation]\nduration = {duration}\n[solver]\n{}output_dt = 0.005\n",
            if compliant { "method = \"tsit45\"\n" } else { "" }
        ));
        let Some(solution) = solve_to_its_end(&text, "random-alternating-rows", duration)? else {
            return Ok(());
        };
        prop_assert_eq!(crate::common::faces_passing(&solution), None, "{}", text);
    }
}
