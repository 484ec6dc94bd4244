//! Rows of columns under the compliant contact law (book/src/row.md §4a), checked against what
//! does not depend on its code: gaps that never close give each column alone (to the
//! integrator's tolerance); a stiffer and stiffer contact tends to Newton's law (the impact
//! law's row, itself checked against closed forms), its error falling as k^-1/2; an isolated
//! contact restitutes e, lasts and dissipates what the two-mass oscillator written out here says;
//! each column's energy books close with the contact's work; bad `[row]` keys are refused by
//! name.

use flexrock_core::bodies::row::{
    solve_row, solve_row_compliant, ColumnSpec, CompliantSettings, Row,
};
use flexrock_core::floor::{Free, PaperSine, PulseShape, SinePulse};
use flexrock_core::integrate::solution::Solution;
use flexrock_core::integrate::{History, InitialState};
use flexrock_core::model::RowModel;
use flexrock_core::physics::automaton::{EventKind, Mode};

use crate::common;
use crate::row::{alone, at_rest, body, mass_and_frequency, mode_shape, sigma, L, SETTINGS};

const TIGHT: CompliantSettings = CompliantSettings {
    rtol: 1e-10,
    atol: 1e-10,
    output_dt: 0.01,
};

/// Each column's events and peaks against its run alone, to `tol` (s and m).
fn close_to_alone(row: &Solution, single: &Solution, tol: f64, what: &str) {
    assert_eq!(row.events.len(), single.events.len(), "{what}: events");
    for (a, b) in row.events.iter().zip(&single.events) {
        assert_eq!((a.kind, a.from, a.to), (b.kind, b.from, b.to), "{what}");
        assert!(
            (a.t - b.t).abs() < tol,
            "{what}: event at {} vs {}",
            a.t,
            b.t
        );
    }
    for (a, b) in [(row.max_q, single.max_q), (row.min_q, single.min_q)] {
        assert!(
            (a.value - b.value).abs() < tol * b.value.abs().max(1e-3),
            "{what}: peak {a:?} vs {b:?}"
        );
    }
}

#[test]
fn gaps_that_never_close_give_each_column_alone() {
    let specs = [
        at_rest(body(4.0, 0.7, 600.0, 5e6, 0.05)),
        at_rest(body(3.0, 0.8, 500.0, 2e7, 0.03)),
        ColumnSpec {
            body: body(2.5, 0.9, 700.0, 1e8, 0.02),
            initial: InitialState {
                q: 0.01,
                qdot: -0.05,
            },
        },
    ];
    let floor = PaperSine::new(4.0, 1.0, 0.412);
    let impact = Row::new(&specs, &[10.0, 10.0], 0.5).unwrap();
    let compliant = impact.clone().compliant(1e7).unwrap();
    let by_impact = solve_row(&impact, &floor, 6.0, &SETTINGS, History::Sampled).unwrap();
    let by_spring = solve_row_compliant(&compliant, &floor, 6.0, &TIGHT, History::Sampled).unwrap();
    assert!(by_spring.contacts.is_empty() && by_spring.impacts.is_empty());
    let rocked: usize = by_spring
        .columns
        .iter()
        .map(|c| c.count(EventKind::Uplift))
        .sum();
    assert!(rocked >= 2, "the case should rock: {rocked} uplifts");
    for (i, spec) in specs.iter().enumerate() {
        let single = alone(spec, &floor, 6.0);
        assert_eq!(by_impact.columns[i].events, single.events);
        close_to_alone(&by_spring.columns[i], &single, 1e-7, &format!("column {i}"));
        assert_eq!(by_spring.columns[i].samples.len(), single.samples.len());
    }
}

/// The pair of the impact law's one-impact test (the left column, shorter, swaying at v0 onto
/// the right one at rest, free of any floor motion), with a stiffer and stiffer spring: the
/// velocities of both columns at a time after the contact converge to the impact law's, with
/// an error falling as k^-1/2 (the contact lasts ~ (m_red/k)^1/2, over which the columns' own
/// restoring forces act).
#[test]
fn a_stiffer_and_stiffer_contact_tends_to_newtons_law() {
    let left = body(3.0, 0.7, 600.0, 5e6, 0.0);
    let right = body(4.0, 0.7, 900.0, 8e6, 0.0);
    let (v0, gap, e) = (0.05, 0.002, 0.6);
    let specs = [
        ColumnSpec {
            body: left,
            initial: InitialState { q: 0.0, qdot: v0 },
        },
        at_rest(right),
    ];
    let settings = CompliantSettings {
        rtol: 1e-11,
        atol: 1e-13,
        output_dt: 0.01,
    };
    let row = Row::new(&specs, &[gap], e).unwrap();
    let newton = solve_row(&row, &Free, 0.2, &SETTINGS, History::Sampled).unwrap();
    assert_eq!(newton.impacts.len(), 1);
    let at = |s: &Solution, t: f64| s.samples.iter().find(|x| x.t == t).unwrap().qdot;
    let t_after = 0.15;
    let mut errors = Vec::new();
    for k in [1e7, 1e8, 1e9, 1e10, 1e11] {
        let compliant = row.clone().compliant(k).unwrap();
        let solved =
            solve_row_compliant(&compliant, &Free, 0.2, &settings, History::Sampled).unwrap();
        assert_eq!(solved.contacts.len(), 1, "k = {k}: {:?}", solved.contacts);
        let stretch = solved.contacts[0];
        assert!(stretch.t_end.unwrap() < t_after, "k = {k}: {stretch:?}");
        let error = (0..2)
            .map(|i| (at(&solved.columns[i], t_after) - at(&newton.columns[i], t_after)).abs())
            .fold(0.0, f64::max)
            / v0;
        errors.push((k, error));
    }
    eprintln!("velocity error against Newton's law at t = {t_after} s: {errors:?}");
    for pair in errors.windows(2) {
        let ((k0, e0), (k1, e1)) = (pair[0], pair[1]);
        let rate = (e1 / e0).log10() / (k1 / k0).log10();
        assert!(
            (-0.6..=-0.4).contains(&rate),
            "from k = {k0} to {k1} the error falls from {e0} to {e1}: k^{rate}"
        );
    }
    assert!(errors.last().unwrap().1 < 5e-4, "{errors:?}");
}

/// The reduced mass of the contact points of a column of height `h_left` at its top against
/// one of height 4 m at xi = h_left / 4: M/4 over Phi^2 of each (int U^2 = 1/4).
fn reduced_mass(
    left: &flexrock_core::physics::body::Body,
    right: &flexrock_core::physics::body::Body,
) -> f64 {
    let u = mode_shape(left.height / right.height);
    let (ml, mr) = (left.mass / 4.0, right.mass / 4.0 / (u * u));
    ml * mr / (ml + mr)
}

/// Two columns meeting with a gap of a micrometre and a very stiff spring: the contact is over
/// long before the columns' own forces matter, so the contact points are the isolated two-mass
/// oscillator delta'' + 2 zeta w delta' + w^2 delta = 0, let go where the force k delta + c
/// delta' vanishes (delta'' = 0): they leave at e times the speed they met at, after
/// 2 acos(zeta) / (w sqrt(1 - zeta^2)) (2 acosh(zeta) / (w sqrt(zeta^2 - 1)) when zeta > 1), and
/// the contact takes (1 - e^2) m_red w^2 / 2.
#[test]
fn an_isolated_contact_restitutes_e() {
    let left = body(3.0, 0.7, 600.0, 5e6, 0.0);
    let right = body(4.0, 0.7, 900.0, 8e6, 0.0);
    let (v0, gap, k) = (0.05, 1e-6, 1e12);
    let settings = CompliantSettings {
        rtol: 1e-12,
        atol: 1e-15,
        output_dt: 1e-3,
    };
    let m_red = reduced_mass(&left, &right);
    let omega = (k / m_red).sqrt();
    for e in [0.05, 0.3, 0.6, 0.9, 1.0] {
        let specs = [
            ColumnSpec {
                body: left.clone(),
                initial: InitialState { q: 0.0, qdot: v0 },
            },
            at_rest(right.clone()),
        ];
        let row = Row::new(&specs, &[gap], e).unwrap().compliant(k).unwrap();
        let solved = solve_row_compliant(&row, &Free, 2e-3, &settings, History::Sampled)
            .unwrap_or_else(|err| panic!("e = {e}: {err}"));
        assert_eq!(solved.contacts.len(), 1, "e = {e}: {:?}", solved.contacts);
        let s = solved.contacts[0];
        assert!(
            (s.reduced_mass - m_red).abs() < 1e-12 * m_red,
            "e = {e}: m_red {} vs {m_red}",
            s.reduced_mass
        );
        let w = s.closing_velocity;
        let restitution = s.separating_velocity.unwrap() / w;
        eprintln!(
            "isolated contact, e = {e}: restitutes {restitution}, lasts {} s, takes {} J",
            s.t_end.unwrap() - s.t_start,
            s.energy_dissipated
        );
        assert!(
            (restitution - e).abs() < 5e-8,
            "e = {e}: restitutes {restitution}"
        );
        // The dashpot's damping ratio, and the contact's length from it.
        let zeta = s.damping / (2.0 * (k * m_red).sqrt());
        let duration = if zeta < 1.0 {
            2.0 * zeta.acos() / (omega * (1.0 - zeta * zeta).sqrt())
        } else {
            2.0 * zeta.acosh() / (omega * (zeta * zeta - 1.0).sqrt())
        };
        let lasted = s.t_end.unwrap() - s.t_start;
        assert!(
            (lasted - duration).abs() < 1e-5 * duration,
            "e = {e}: lasted {lasted} s, the oscillator {duration} s"
        );
        let taken = (1.0 - e * e) * m_red * w * w / 2.0;
        assert!(
            (s.energy_dissipated - taken).abs() < 1e-5 * m_red * w * w,
            "e = {e}: took {} J, the oscillator {taken} J",
            s.energy_dissipated
        );
        // The largest force: at the start for a dashpot that strong (zeta >= 1/2: delta'' falls
        // from its start), else k delta + c delta' at the zero of its rate.
        assert!(
            s.peak_force >= s.damping * w * (1.0 - 1e-9),
            "e = {e}: {s:?}"
        );
        // Both columns log the start and the end, q' unchanged there.
        for c in &solved.columns {
            let kinds: Vec<EventKind> = c.events.iter().map(|ev| ev.kind).collect();
            assert_eq!(kinds, [EventKind::ContactStart, EventKind::ContactEnd]);
            assert!(c.events.iter().all(|ev| ev.qdot_after == ev.qdot_before));
            assert_eq!(c.final_mode, Mode::PreUplift);
        }
    }
}

/// The pair of models/row-compliant.toml: a soft and a stiff column of the reference size,
/// 2 cm apart, at rest, under the compliant law (k = 1e7 N/m).
pub(crate) fn pair_of_row_compliant_toml() -> Row {
    let specs = [
        at_rest(body(4.0, 0.7, 600.0, 5e6, 0.05)),
        at_rest(body(4.0, 0.7, 600.0, 5e7, 0.05)),
    ];
    Row::new(&specs, &[0.02], 0.5)
        .unwrap()
        .compliant(1e7)
        .unwrap()
}

/// Each column's energy books close with the work of the contact forces on it, through many
/// contacts under the paper's sine (the pair of models/row-compliant.toml), and through
/// uplifts and landings while in contact (a soft column leaning on a stiff one under a slow
/// pulse, let go near where the quasi-static leans of the two differ by the gap).
#[test]
fn energy_books_close_with_the_contact_work() {
    let row = pair_of_row_compliant_toml();
    let floor = PaperSine::new(4.0, 1.0, 0.412);
    let solved = solve_row_compliant(&row, &floor, 6.0, &TIGHT, History::Sampled).unwrap();
    assert!(solved.contacts.len() >= 3, "{:?}", solved.contacts);
    let taken: f64 = solved.contacts.iter().map(|s| s.energy_dissipated).sum();
    eprintln!("paper's sine: contacts took {taken} J");
    common::row_books_close("paper's sine", &solved, 2e-8);
    for c in &solved.columns {
        // The contact work matters: leaving it out would not close the books.
        assert!(
            taken > 1e-3 * c.energy_scale,
            "{taken} J of {}",
            c.energy_scale
        );
    }
    for s in &solved.contacts {
        assert!(s.energy_dissipated > 0.0 && s.peak_force > 0.0, "{s:?}");
    }

    // Leaning under a slow pulse (the impact law's persistent-contact case).
    let soft = body(4.0, 0.7, 600.0, 5e6, 0.05);
    let stiff = body(4.0, 0.7, 600.0, 5e8, 0.05);
    let specs = [at_rest(stiff.clone()), at_rest(soft.clone())];
    let (gap, amplitude, period) = (0.003, 0.8, 20.0);
    let beta1 = 4.0 * sigma() / L;
    let omega2 = |b: &flexrock_core::physics::body::Body| {
        let (_, w) = mass_and_frequency(b);
        w * w
    };
    let a_release = gap / (beta1 * (1.0 / omega2(&soft) - 1.0 / omega2(&stiff)));
    let t_release =
        period / 2.0 - (a_release / amplitude).asin() * period / (2.0 * std::f64::consts::PI);
    let row = Row::new(&specs, &[gap], 0.5)
        .unwrap()
        .compliant(1e9)
        .unwrap();
    let floor = SinePulse::new(amplitude, period, 1.0, PulseShape::Antisymmetric);
    let solved = solve_row_compliant(&row, &floor, 12.0, &TIGHT, History::Sampled).unwrap();
    let longest = common::longest(&solved.contacts, |s| (s.t_start, s.t_end)).expect("contacts");
    let end = longest.t_end.unwrap();
    eprintln!(
        "leaning: in contact from {} s to {end} s, quasi-statically let go at {t_release} s",
        longest.t_start
    );
    // The spring's static compression (P / k, a fraction of a millimetre) moves the release a little.
    assert!(
        (end - t_release).abs() < 5e-3,
        "let go at {end} s, quasi-statically at {t_release} s"
    );
    common::row_books_close("leaning", &solved, 2e-8);
}

/// The pair of [`pair_of_row_compliant_toml`] as a row model file, under the impact law, for
/// 1 s of the paper's sine.
pub(crate) const ROW: &str = "[row]\ngaps = [0.02]\nrestitution = 0.5\n\
    [[column]]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5e6\ndamping_ratio = 0.05\n\
    [[column]]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5e7\ndamping_ratio = 0.05\n\
    [excitation]\nkind = \"paper-sine\"\namplitude = 4.0\nperiod = 1.0\nramp = 0.412\n\
    [simulation]\nduration = 1.0\n";

#[test]
fn bad_contact_keys_are_refused_by_name() {
    let with = |row_keys: &str| {
        ROW.replacen(
            "restitution = 0.5\n",
            &format!("restitution = 0.5\n{row_keys}"),
            1,
        )
    };
    let message = |text: &str| match RowModel::from_toml_str(text) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    };
    for (keys, expected) in [
        ("contact = \"compliant\"\n", "row.stiffness = (missing)"),
        (
            "contact = \"compliant\"\nstiffness = 0.0\n",
            "row.stiffness = 0: must be",
        ),
        (
            "contact = \"compliant\"\nstiffness = -1e7\n",
            "row.stiffness = -1e7: must be",
        ),
        (
            "stiffness = 1e7\n",
            "row.stiffness = 1e7: is a key of the compliant law",
        ),
        (
            "contact = \"impact\"\nstiffness = 1e7\n",
            "row.stiffness = 1e7: is a key",
        ),
        ("contact = \"springy\"\n", "row.contact = \"springy\""),
    ] {
        let m = message(&with(keys));
        assert!(m.contains(expected), "{keys}: {m}");
    }
    let m = message(
        &with("contact = \"compliant\"\nstiffness = 1e7\n")
            .replace("restitution = 0.5", "restitution = 0.0"),
    );
    assert!(m.contains("row.restitution = 0"), "{m}");
    let m = message(&format!(
        "{}[solver]\nmethod = \"exact\"\n",
        with("contact = \"compliant\"\nstiffness = 1e7\n")
    ));
    assert!(m.contains("solver.method"), "{m}");
    let m = message(&format!(
        "{}[solver]\nrtol = 1.0\n",
        with("contact = \"compliant\"\nstiffness = 1e7\n")
    ));
    assert!(m.contains("solver.rtol = 1"), "{m}");
    // Good ones: the impact law as before (its table keeps no new keys), the compliant one
    // with its tolerances.
    let impact = RowModel::from_toml_str(ROW).unwrap();
    assert!(impact.compliant.is_none());
    let good = format!(
        "{}[solver]\nrtol = 1e-9\natol = 1e-9\n",
        with("contact = \"compliant\"\nstiffness = 1e7\n")
    );
    let compliant = RowModel::from_toml_str(&good).unwrap();
    let settings = compliant.compliant.unwrap();
    assert_eq!((settings.rtol, settings.atol), (1e-9, 1e-9));
}

/// A column that overturns ends the row's run there, as under the impact law: the pair of
/// models/row-compliant.toml under the paper's sine at 9 m/s^2.
#[test]
fn an_overturning_column_ends_the_run() {
    let row = pair_of_row_compliant_toml();
    let floor = PaperSine::new(9.0, 1.0, 0.412);
    let solved = solve_row_compliant(&row, &floor, 6.0, &TIGHT, History::Sampled).unwrap();
    let (i, t) = solved.overturned.expect("a column overturns");
    assert!(!solved.contacts.is_empty());
    assert_eq!(solved.final_time, t);
    assert!(solved.columns[i].overturned);
    assert_eq!(solved.columns[i].t_overturn, Some(t));
    for c in &solved.columns {
        assert_eq!(c.final_time, t);
        assert!(c.samples.iter().all(|s| s.t <= t));
    }
}

/// The pair of models/row-compliant.toml beside a copy of itself, 1 m away: the two pairs' first
/// contacts close at the same instant, and each pair moves as the pair alone (to the
/// integrator's tolerance: the four columns share its steps). Of two contacts closing at one
/// instant only the first found was started, and the second pair passed through each other,
/// its gap down to -0.25 m with its contact open, in 2 contacts instead of 6.
#[test]
fn a_pair_beside_its_copy_moves_as_the_pair_alone() {
    let floor = PaperSine::new(4.0, 1.0, 0.412);
    let pair = pair_of_row_compliant_toml();
    let alone = solve_row_compliant(&pair, &floor, 6.0, &TIGHT, History::Sampled).unwrap();
    let specs = [
        at_rest(body(4.0, 0.7, 600.0, 5e6, 0.05)),
        at_rest(body(4.0, 0.7, 600.0, 5e7, 0.05)),
    ];
    let four = [specs.clone(), specs].concat();
    let row = Row::new(&four, &[0.02, 1.0, 0.02], 0.5)
        .unwrap()
        .compliant(1e7)
        .unwrap();
    let solved = solve_row_compliant(&row, &floor, 6.0, &TIGHT, History::Sampled).unwrap();
    assert_eq!(common::faces_passing(&solved), None);
    for (c, own) in [(0, 0), (2, 0)] {
        let mine: Vec<_> = solved.contacts.iter().filter(|s| s.contact == c).collect();
        assert_eq!(mine.len(), alone.contacts.len(), "contact {c}: {mine:?}");
        for (a, b) in mine
            .iter()
            .zip(alone.contacts.iter().filter(|s| s.contact == own))
        {
            assert!((a.t_start - b.t_start).abs() < 1e-7, "{a:?} vs {b:?}");
        }
    }
    assert!(solved.contacts.iter().all(|s| s.contact != 1));
    for (i, column) in solved.columns.iter().enumerate() {
        close_to_alone(column, &alone.columns[i % 2], 1e-7, &format!("column {i}"));
    }
}

/// Rows of four to six columns, soft and stiff in turn 2 mm apart under El Centro with
/// k = 1e8 N/m: contacts close at one instant, and reset by a column's landing while parting;
/// at no sample do two faces stand overlapping without a contact. (Faces passed through each
/// other there, open contacts at gaps down to -8 cm.)
#[test]
fn faces_never_stand_overlapping_without_a_contact() {
    let records = concat!(env!("CARGO_MANIFEST_DIR"), "/../validation/records");
    for n in 4..=6 {
        let mut text = format!(
            "[row]\ngaps = [{}]\nrestitution = 0.5\ncontact = \"compliant\"\nstiffness = 1e8\n",
            vec!["0.002"; n - 1].join(", ")
        );
        for i in 0..n {
            text.push_str(&format!(
                "[[column]]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = {}\n\
                 damping_ratio = 0.05\n",
                if i % 2 == 0 { "5e6" } else { "5e7" }
            ));
        }
        text.push_str(&format!(
            "[excitation]\nkind = \"record\"\npath = \"{records}/elCentro.AT2\"\n\
             format = \"peer-at2\"\nunits = \"g\"\nscale = 1.0\n\
             [simulation]\nduration = 20.0\n[solver]\nmethod = \"tsit45\"\noutput_dt = 0.005\n"
        ));
        let model = RowModel::from_toml_str(&text).unwrap();
        let solved = flexrock_core::simulate::simulate_row(&model)
            .unwrap_or_else(|e| panic!("{n} columns: {e}"));
        assert!(
            solved.contacts.len() > 10,
            "{n} columns: {:?}",
            solved.contacts
        );
        assert_eq!(common::faces_passing(&solved), None, "{n} columns");
    }
}

/// Fifty columns, soft and stiff in turn 2 cm apart: the 25 soft ones lift off at one instant,
/// and the 25 contacts with a soft column on the left close at one instant, each as the pair
/// alone's first contact. (The run stopped there: "endless chain of events at one instant",
/// the cap on events at one instant not counting the row's columns.)
#[test]
fn fifty_columns_whose_contacts_close_at_one_instant_run() {
    let floor = PaperSine::new(4.0, 1.0, 0.412);
    let alone = solve_row_compliant(
        &pair_of_row_compliant_toml(),
        &floor,
        0.5,
        &TIGHT,
        History::Sampled,
    )
    .unwrap();
    let first = alone.contacts[0];
    let specs: Vec<ColumnSpec> = (0..50)
        .map(|i| {
            at_rest(body(
                4.0,
                0.7,
                600.0,
                if i % 2 == 0 { 5e6 } else { 5e7 },
                0.05,
            ))
        })
        .collect();
    let row = Row::new(&specs, &[0.02; 49], 0.5)
        .unwrap()
        .compliant(1e7)
        .unwrap();
    let solved = solve_row_compliant(&row, &floor, 0.5, &TIGHT, History::Sampled).unwrap();
    assert_eq!(solved.final_time, 0.5);
    assert_eq!(common::faces_passing(&solved), None);
    for c in (0..49).step_by(2) {
        let s = solved
            .contacts
            .iter()
            .find(|s| s.contact == c)
            .expect("a contact");
        assert!(
            (s.t_start - first.t_start).abs() < 1e-7,
            "{s:?} vs {first:?}"
        );
    }
}

/// The limit of a stiff contact on the pair of models/row-compliant.toml beside a copy of itself
/// (the case of [`a_pair_beside_its_copy_moves_as_the_pair_alone`]): after the first contacts of
/// both pairs, closing at one instant, every column's velocity tends to the impact law's as
/// k^-1/2.
#[test]
fn two_pairs_struck_at_one_instant_tend_to_newtons_law() {
    let floor = PaperSine::new(4.0, 1.0, 0.412);
    let specs = [
        at_rest(body(4.0, 0.7, 600.0, 5e6, 0.05)),
        at_rest(body(4.0, 0.7, 600.0, 5e7, 0.05)),
    ];
    let four = [specs.clone(), specs].concat();
    let row = Row::new(&four, &[0.02, 1.0, 0.02], 0.5).unwrap();
    let settings = CompliantSettings {
        rtol: 1e-11,
        atol: 1e-13,
        output_dt: 0.01,
    };
    let duration = 0.4;
    let newton = solve_row(&row, &floor, duration, &SETTINGS, History::Sampled).unwrap();
    let at = |s: &Solution, t: f64| s.samples.iter().find(|x| x.t == t).unwrap().qdot;
    let t_after = 0.3;
    let scale = newton.impacts[0].closing_velocity;
    let mut errors = Vec::new();
    for k in [1e7, 1e8, 1e9, 1e10, 1e11] {
        let compliant = row.clone().compliant(k).unwrap();
        let solved =
            solve_row_compliant(&compliant, &floor, duration, &settings, History::Sampled).unwrap();
        let error = (0..4)
            .map(|i| (at(&solved.columns[i], t_after) - at(&newton.columns[i], t_after)).abs())
            .fold(0.0, f64::max)
            / scale;
        errors.push((k, error));
    }
    eprintln!("velocity error against Newton's law at t = {t_after} s: {errors:?}");
    for pair in errors.windows(2) {
        let ((k0, e0), (k1, e1)) = (pair[0], pair[1]);
        let rate = (e1 / e0).log10() / (k1 / k0).log10();
        assert!(
            (-0.6..=-0.4).contains(&rate),
            "from k = {k0} to {k1} the error falls from {e0} to {e1}: k^{rate}"
        );
    }
}
