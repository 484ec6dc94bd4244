//! The exact method against what needs no solver: the closed forms of free rocking, free
//! vibration and a sine's steady state; a multiprecision evaluation written apart from the Rust
//! code (validation/exact/, Python with mpmath at 40 digits); grazing uplifts found by bisection
//! on the amplitude; and the hardening cases of the other methods (records, random models).

use crate::common;

use flexrock_core::integrate::solution::Solution;
use flexrock_core::model::{Model, Overrides};
use flexrock_core::physics::automaton::{EventKind, Mode};

fn exact(text: &str) -> Solution {
    let model = common::model(text);
    flexrock_core::simulate::simulate(&model).expect("the exact method solves")
}

fn with_exact(text: &str) -> String {
    format!("{text}\n[solver]\nmethod = \"exact\"\noutput_dt = 0.001\n")
}

/// Free undamped rocking from rest at q0 > s_n: while rocking x = q - q_topple obeys
/// x'' = mu^2 x (mu^2 = -nu2 F'/Me), so x = x0 cosh(mu t), and the body lands when
/// cosh(mu t) = (q_topple - s_n)/(q_topple - q0); before uplift q = R cos(omega t + theta), and it
/// swings from s_n to -s_n in (pi - 2 theta)/omega; rocking the other way from the guard with
/// q' = v0 it lands again after 2 atanh(|v0|/(mu x0))/mu. Every event of the chain, from these
/// formulas alone, to 1e-13 relative.
#[test]
fn free_undamped_rocking_is_the_chain_of_cosh_and_arccos() {
    let text = with_exact(
        "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\
         damping_ratio = 0.0\ngravity = 9.81\n[excitation]\nkind = \"free\"\n\
         [simulation]\nduration = 6.0\nq0 = 0.4\nqdot0 = 0.0",
    );
    let model = common::model(&text);
    let c = &model.constants;
    let mu = (-c.nu2 * c.rocking_stiffness / c.generalised_mass).sqrt();
    let omega = (c.generalised_stiffness / c.generalised_mass).sqrt();
    let (s_n, topple) = (c.uplift_displacement, c.topple_displacement);
    let x0 = topple - s_n;
    // The chain: landing from the release, then swings and rocking episodes.
    let mut expected = Vec::new();
    let mut t = ((topple - s_n) / (topple - 0.4)).acosh() / mu;
    let mut v = -(topple - 0.4) * mu * (mu * t).sinh();
    expected.push((t, EventKind::Landing, v));
    while t < model.duration {
        v /= c.zeta_landing;
        let theta = (v.abs() / omega).atan2(s_n);
        t += (std::f64::consts::PI - 2.0 * theta) / omega;
        expected.push((t, EventKind::Uplift, v));
        v *= c.zeta_uplift;
        let ratio = v.abs() / (mu * x0);
        assert!(ratio < 1.0, "the chain overturns: choose a smaller release");
        t += 2.0 * ratio.atanh() / mu;
        v = -v;
        expected.push((t, EventKind::Landing, v));
    }
    let sol = exact(&text);
    let expected: Vec<_> = expected
        .into_iter()
        .filter(|e| e.0 <= model.duration)
        .collect();
    assert_eq!(sol.events.len(), expected.len(), "{:#?}", sol.events);
    for (event, (t, kind, v)) in sol.events.iter().zip(&expected) {
        assert_eq!(event.kind, *kind);
        assert!(
            (event.t - t).abs() <= 1e-13 * t,
            "{event:?} against t = {t}"
        );
        assert!(
            (event.qdot_before - v).abs() <= 1e-13 * v.abs(),
            "{event:?} against q' = {v}"
        );
    }
    assert!(sol.events.len() >= 9, "a chain of several episodes");
}

/// Free damped vibration below uplift: q = e^(-h w t) (q0 cos(wd t) + (v0 + h w q0)/wd sin(wd t)),
/// every sample of the history to 1e-13 of the amplitude.
#[test]
fn free_damped_vibration_is_the_damped_cosine() {
    let text = with_exact(
        "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\
         damping_ratio = 0.05\ngravity = 9.81\n[excitation]\nkind = \"free\"\n\
         [simulation]\nduration = 20.0\nq0 = 0.1\nqdot0 = -0.2",
    );
    let model = common::model(&text);
    let c = &model.constants;
    let omega = (c.generalised_stiffness / c.generalised_mass).sqrt();
    // c q' term: (gamma/E) Ke / Me = 2 h omega.
    let h = c.damping_coefficient * c.generalised_stiffness / c.generalised_mass / (2.0 * omega);
    let wd = omega * (1.0 - h * h).sqrt();
    let (q0, v0) = (0.1, -0.2);
    let sol = exact(&text);
    assert!(sol.events.is_empty());
    assert_eq!(sol.samples.len(), 20_001);
    for s in &sol.samples {
        let e = (-h * omega * s.t).exp();
        let q = e * (q0 * (wd * s.t).cos() + (v0 + h * omega * q0) / wd * (wd * s.t).sin());
        assert!(
            (s.q - q).abs() <= 1e-13 * 0.1,
            "t = {}: {} against {q}",
            s.t,
            s.q
        );
    }
}

/// A sine below uplift from rest: the steady state X e^(i W t), X = F / (k - W^2 + i c W), plus
/// the free motion that starts the body at rest (the shared closed form of the tests),
/// every sample to 1e-13 of the amplitude.
#[test]
fn a_sine_below_uplift_is_its_steady_state_plus_the_transient() {
    let text = with_exact(&common::reference_body(
        "[excitation]\nkind = \"harmonic\"\namplitude = 0.8\nperiod = 0.7\n\
         [simulation]\nduration = 10.0",
    ));
    let model = common::model(&text);
    let c = &model.constants;
    let omega = (c.generalised_stiffness / c.generalised_mass).sqrt();
    let sol = exact(&text);
    assert!(sol.events.is_empty(), "the sine stays below uplift");
    let peak = sol.max_q.value.max(-sol.min_q.value);
    let response = common::damped_oscillator_response(omega, 0.05, c.beta1, 0.8, 0.7);
    for s in &sol.samples {
        let q = response(s.t);
        assert!(
            (s.q - q).abs() <= 1e-13 * peak,
            "t = {}: {} against {q}",
            s.t,
            s.q
        );
    }
}

/// Before uplift the motion from rest is linear in the amplitude, so the amplitude at which a
/// sine first touches s_n is s_n over the peak of the unit response. A billionth above it the
/// body must lift off (an excursion beyond s_n of about a billionth of s_n, lasting microseconds,
/// far shorter than any sample), a billionth below it must not, and neither may storm.
#[test]
fn a_grazing_uplift_a_billionth_above_the_threshold_is_found() {
    let run = |amplitude: f64| {
        exact(&with_exact(&common::reference_body(&format!(
            "[excitation]\nkind = \"harmonic\"\namplitude = {amplitude}\nperiod = 0.6\n\
             [simulation]\nduration = 3.0"
        ))))
    };
    let unit = run(0.01);
    assert!(unit.events.is_empty());
    let model = common::model(&with_exact(&common::reference_body(
        "[excitation]\nkind = \"harmonic\"\namplitude = 1.0\nperiod = 0.6\n[simulation]\nduration = 3.0",
    )));
    let s_n = model.constants.uplift_displacement;
    let peak = unit.max_q.value.max(-unit.min_q.value) / 0.01;
    let threshold = s_n / peak;
    for (share, lifts) in [(1e-9, true), (-1e-9, false), (1e-6, true), (-1e-6, false)] {
        let sol = run(threshold * (1.0 + share));
        let uplifts = sol.count(EventKind::Uplift);
        assert_eq!(
            uplifts > 0,
            lifts,
            "amplitude threshold x (1 + {share:e}): {uplifts} uplifts"
        );
        if lifts {
            // One graze: an uplift and the landing right after it, then the same again at most
            // once per cycle of the sine.
            assert!(sol.events.len() <= 12, "{} events", sol.events.len());
            assert_eq!(sol.events[0].kind, EventKind::Uplift);
            assert_eq!(sol.events[1].kind, EventKind::Landing);
            assert!(sol.events[1].t - sol.events[0].t < 1e-3);
        }
    }
}

/// The references of validation/exact/: for each case the exact method gives the same event
/// sequence; every event time within 1e-13 s and every peak within 1e-13 m of the 40-digit
/// evaluation, and each run's own error estimate at least its true error. The consistent
/// self-weight variant's constants come from a Ritz solution good to about 1e-11, and the
/// ill-conditioned cases (`ill-*`: an uplift that grazes s_n by 8e-11 m, a landing at 3e-5 m/s)
/// move picoseconds for a rounding of q by a few ulps, so these are held to 1e-8 and to their
/// estimate. The cases include a long chain of shallow uplifts of a near-rigid body
/// (free-rocking-stiff, 267 events), uplifts right after a slow approach to s_n under a sine
/// near resonance (harmonic-uplifts), where a state's rounding is most amplified, and a narrow
/// Ricker wavelet under a near-rigid body (ricker-narrow-stiff), whose later events carry the
/// errors of the earlier ones.
#[test]
fn the_multiprecision_references_to_1e_13() {
    let dir = common::workspace_file("validation/exact/reference");
    let mut cases = 0;
    for entry in std::fs::read_dir(&dir).expect("validation/exact/reference") {
        let case = entry.expect("entry").path();
        let name = case.file_name().unwrap().to_string_lossy().to_string();
        let file = common::workspace_file(&format!("validation/exact/cases/{name}.toml"));
        let overrides = Overrides {
            method: Some("exact".to_string()),
            ..Overrides::default()
        };
        let model = Model::load(&file, &overrides).expect("the case loads");
        let sol = flexrock_core::simulate::simulate(&model).expect("solves");
        let estimate = sol
            .rounding
            .as_ref()
            .expect("the exact method estimates its error");
        let reference = read_events(&case.join("events.csv"));
        let peaks: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(case.join("peaks.json")).unwrap())
                .unwrap();
        let to_estimate = name.contains("consistent") || name.starts_with("ill-");
        let tolerance: f64 = if to_estimate { 1e-8 } else { 1e-13 };
        assert_eq!(sol.events.len(), reference.len(), "{name}");
        for ((event, (t, kind, to)), error) in
            sol.events.iter().zip(&reference).zip(&estimate.event_time)
        {
            assert_eq!(event.kind.name(), kind, "{name}");
            assert_eq!(event.to.name(), to, "{name}");
            let true_error = (event.t - t).abs();
            // The paper's variant to 1e-13 s whatever the estimate; the consistent one and the
            // ill-conditioned cases to their estimate where that is larger.
            let limit = if to_estimate {
                tolerance.max(*error)
            } else {
                tolerance
            };
            assert!(
                true_error <= limit,
                "{name}: event {} off by {true_error:e} s",
                event.index
            );
            assert!(
                *error >= true_error,
                "{name}: event {} estimate {error:e} below {true_error:e}",
                event.index
            );
        }
        let number = |key: &str| peaks[key].as_f64().expect(key);
        for (value, reference, error) in [
            (sol.max_q.value, number("max_q"), estimate.max_q),
            (sol.min_q.value, number("min_q"), estimate.min_q),
        ] {
            let true_error = (value - reference).abs();
            assert!(
                true_error <= tolerance,
                "{name}: peak off by {true_error:e} m"
            );
            assert!(
                error >= true_error,
                "{name}: peak estimate {error:e} below {true_error:e}"
            );
        }
        for (value, reference, error) in [
            (sol.max_q.t, number("t_max_q"), estimate.t_max_q),
            (sol.min_q.t, number("t_min_q"), estimate.t_min_q),
        ] {
            let true_error = (value - reference).abs();
            assert!(
                error >= true_error,
                "{name}: peak time estimate {error:e} below {true_error:e}"
            );
        }
        assert_eq!(
            sol.overturned,
            peaks["overturned"].as_bool().unwrap(),
            "{name}"
        );
        // None of these grazes within its rounding: the closest, ill-graze-uplift, by 8e-11 m.
        assert!(
            estimate.grazes.is_empty() && estimate.uncertain_from.is_none(),
            "{name}: {:?}",
            estimate.grazes
        );
        cases += 1;
    }
    assert!(cases >= 19, "{cases} cases");
}

/// The knife-edge grazes of validation/exact/grazes/: models whose hump of q reaches within
/// 1e-18 to 1e-12 m of s_n, or beyond it by as little (among them the paper's
/// body under a 2 s sine of 0.47223579741960314 m/s^2, which the 40-digit solution lifts off by
/// 1.7e-17 m for 9 ns, where the run ends on s_n to the bit), sine pulses and a record scaled
/// to such a graze, pulses and speeds that just overturn the body or just fail to, and a
/// rocking body that just lands or just does not. Against each one's 40-digit solution:
///
/// - every event the run is sure of (its estimate below the duration) is the reference's, at a
///   time within its estimate; where the sequences part, the run says its sequence is
///   uncertain from no later than there, and the estimate of each later event is the duration;
/// - both peaks and their times are within their estimates;
/// - the run warns of a graze wherever the true margin is within 1e-15 m of the guard (the
///   run's own rounding of q there is some 1e-14 m), and nowhere it is 1e-12 m or more away;
///   near the overturning point, within 1e-8 m and 5e-7 m.
#[test]
fn every_knife_edge_graze_is_told_and_within_its_estimate() {
    let dir = common::workspace_file("validation/exact/grazes/reference");
    let margins: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(common::workspace_file(
            "validation/exact/grazes/margins.json",
        ))
        .expect("margins.json"),
    )
    .expect("margins.json reads");
    let (mut cases, mut warned) = (0, 0);
    for entry in std::fs::read_dir(&dir).expect("validation/exact/grazes/reference") {
        let case = entry.expect("entry").path();
        let name = case.file_name().unwrap().to_string_lossy().to_string();
        let file = common::workspace_file(&format!("validation/exact/grazes/cases/{name}.toml"));
        let model = Model::load(&file, &Overrides::default()).expect("the case loads");
        let sol = flexrock_core::simulate::simulate(&model).expect("solves");
        let estimate = sol.rounding.as_ref().expect("an estimate");
        let reference = read_events(&case.join("events.csv"));
        let peaks: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(case.join("peaks.json")).unwrap())
                .unwrap();
        // The events up to where the sequences part.
        let same = sol
            .events
            .iter()
            .zip(&reference)
            .take_while(|(e, (_, kind, to))| e.kind.name() == kind && e.to.name() == to)
            .count();
        for ((event, (t, _, _)), error) in sol
            .events
            .iter()
            .zip(&reference)
            .zip(&estimate.event_time)
            .take(same)
        {
            let true_error = (event.t - t).abs();
            assert!(
                *error >= true_error,
                "{name}: event {} estimate {error:e} below {true_error:e}",
                event.index
            );
        }
        if same < sol.events.len().max(reference.len()) {
            let parted = [
                sol.events.get(same).map(|e| e.t),
                reference.get(same).map(|r| r.0),
            ]
            .into_iter()
            .flatten()
            .fold(f64::INFINITY, f64::min);
            let from = estimate.uncertain_from;
            assert!(
                from.is_some_and(|from| from <= parted),
                "{name}: the sequences part at {parted} s, the run is uncertain from {from:?}"
            );
            assert!(
                estimate.event_time[same..]
                    .iter()
                    .all(|&e| e == model.duration),
                "{name}: {:?}",
                &estimate.event_time[same..]
            );
        }
        let number = |key: &str| peaks[key].as_f64().expect(key);
        for (key, value, error) in [
            ("max_q", sol.max_q.value, estimate.max_q),
            ("t_max_q", sol.max_q.t, estimate.t_max_q),
            ("min_q", sol.min_q.value, estimate.min_q),
            ("t_min_q", sol.min_q.t, estimate.t_min_q),
        ] {
            let true_error = (value - number(key)).abs();
            assert!(
                error >= true_error,
                "{name}: {key} estimate {error:e} below {true_error:e}"
            );
        }
        // The warning, exactly where the run's arithmetic does not decide.
        let warning = flexrock_core::simulate::warnings(&model, &sol)
            .into_iter()
            .any(|w| w.starts_with("a graze") || w.contains("another sequence of events"));
        assert_eq!(warning, estimate.uncertain_from.is_some(), "{name}");
        // Near the overturning point, the rocking mode's saddle, the margin goes as the square
        // root of a change of the model's numbers: their rounding moves it by some 1e-7 m.
        let (close, far) = match margins[&name]["guard"].as_str() {
            Some("overturn") => (1e-8, 5e-7),
            _ => (1e-15, 1e-12),
        };
        if let Some(margin) = margins[&name]["margin"].as_str() {
            let margin: f64 = margin.parse().expect("a margin");
            if margin.abs() <= close {
                assert!(warning, "{name}: no warning {margin:e} m from the guard");
            }
            if margin.abs() >= far {
                assert!(!warning, "{name}: a warning {margin:e} m from the guard");
            }
        }
        warned += usize::from(warning);
        cases += 1;
    }
    assert!(cases >= 70, "{cases} cases");
    assert!(warned >= 20, "{warned} warned");
}

/// Undamped free vibration below uplift, q = q0 cos(omega t), tops at q0 at t = 0 and every
/// period after it, all equal: the time of the largest q is any of them, and the run's estimate
/// of it reaches the farthest (where it was the time of the one top the run's rounding picked).
#[test]
fn equal_tops_make_the_time_of_the_largest_q_any_of_theirs() {
    let text = with_exact(
        "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\
         damping_ratio = 0.0\ngravity = 9.81\n[excitation]\nkind = \"free\"\n\
         [simulation]\nduration = 10.0\nq0 = 0.1\nqdot0 = 0.0",
    );
    let model = common::model(&text);
    let c = &model.constants;
    let period = 2.0 * std::f64::consts::PI / (c.generalised_stiffness / c.generalised_mass).sqrt();
    let sol = exact(&text);
    assert!(sol.events.is_empty());
    let estimate = sol.rounding.as_ref().expect("an estimate");
    let last = (model.duration / period).floor() * period;
    let farthest = sol.max_q.t.max(last - sol.max_q.t);
    assert!(
        estimate.t_max_q >= farthest,
        "t_max_q = {} s, estimate {:e} s, tops from 0 to {last} s",
        sol.max_q.t,
        estimate.t_max_q
    );
    // The smallest q, -q0 half a period on and every period after it, likewise.
    let last = ((model.duration - 0.5 * period) / period).floor() * period + 0.5 * period;
    let farthest = (sol.min_q.t - 0.5 * period).max(last - sol.min_q.t);
    assert!(
        estimate.t_min_q >= farthest,
        "t_min_q estimate {:e} s",
        estimate.t_min_q
    );
}

/// The energy books of the exact method close: on every case of the multiprecision references
/// (sines, pulses, the ramp's cubic, a Ricker wavelet, a record, free motion, grazing), the
/// energy at each sample equals the initial energy plus the floor's work minus the damping's
/// and the impacts' losses to 1e-13 of the run's energy scale. The work integrals are summed
/// from Taylor series of the motion about each sample, apart from the closed form the energy is
/// evaluated from, so a wrong or truncated series shows here.
#[test]
fn the_energy_books_close_to_1e_13_on_every_reference_case() {
    let dir = common::workspace_file("validation/exact/reference");
    let mut cases = 0;
    for entry in std::fs::read_dir(&dir).expect("validation/exact/reference") {
        let name = entry
            .expect("entry")
            .file_name()
            .to_string_lossy()
            .to_string();
        let file = common::workspace_file(&format!("validation/exact/cases/{name}.toml"));
        let overrides = Overrides {
            method: Some("exact".to_string()),
            ..Overrides::default()
        };
        let model = Model::load(&file, &overrides).expect("the case loads");
        let sol = flexrock_core::simulate::simulate(&model).expect("solves");
        assert!(sol.energy_scale > 0.0, "{name}: no energy booked");
        let share = sol.max_energy_residual / sol.energy_scale;
        assert!(
            share < 1e-13,
            "{name}: energy residual {share:e} of the scale"
        );
        cases += 1;
    }
    assert!(cases >= 10, "only {cases} reference cases");
}

/// (t, kind, to) of each row of a reference events.csv.
fn read_events(path: &std::path::Path) -> Vec<(f64, String, String)> {
    let text = std::fs::read_to_string(path).expect("reference events");
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("index,t,kind,from,to,q,qdot_before,qdot_after")
    );
    lines
        .map(|line| {
            let f: Vec<&str> = line.split(',').collect();
            (f[1].parse().unwrap(), f[2].to_string(), f[4].to_string())
        })
        .collect()
}

/// The hardening cases of the adaptive methods: every record of validation/records/ at three
/// scales, and random bodies under sines and pulses. The exact method logs the same events as
/// tsit45 at rtol 1e-12 (outside grazes, where that one may itself be wrong), never storms, and
/// its events alternate as the automaton allows.
#[test]
fn the_hardening_cases_log_the_events_of_a_tight_run() {
    let tight = |text: &str| {
        let model = Model::from_toml_str(
            &format!("{text}\n[solver]\nmethod = \"tsit45\"\nrtol = 1e-12\natol = 1e-14\n"),
            &Overrides::default(),
        )
        .unwrap();
        flexrock_core::simulate::simulate_peaks(&model).unwrap()
    };
    let mut texts = Vec::new();
    for record in [
        "elCentro.AT2",
        "ANLA196.AT2",
        "A-ELC180.AT2",
        "PBFEAS.AT2",
        "HEN-E.AT2",
    ] {
        for scale in [1.0, 3.0, 5.0] {
            texts.push(common::reference_body(&format!(
                "[excitation]\nkind = \"record\"\npath = \"{}\"\nscale = {scale}\ntail = 2.0\n",
                common::workspace_file(&format!("validation/records/{record}")).display()
            )));
        }
    }
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut random = |lo: f64, hi: f64| {
        seed ^= seed >> 12;
        seed ^= seed << 25;
        seed ^= seed >> 27;
        lo + (hi - lo)
            * ((seed.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64)
    };
    while texts.len() < 15 + 60 {
        let height = random(2.0, 8.0);
        let width = height * random(0.08, 0.3);
        let kind = ["harmonic", "sine-pulse", "paper-sine"][random(0.0, 2.999) as usize];
        let period = random(0.3, 3.0);
        let ramp = if kind == "paper-sine" {
            format!("ramp = {}\n", 0.412 * period)
        } else {
            String::new()
        };
        let text = format!(
            "[body]\nheight = {height}\nwidth = {width}\ndensity = 600.0\nyoungs_modulus = {}\n\
             damping_ratio = {}\n[excitation]\nkind = \"{kind}\"\namplitude = {}\nperiod = {period}\n\
             {ramp}[simulation]\nduration = 4.0\nq0 = {}\n",
            10f64.powf(random(6.0, 9.0)),
            random(0.0, 0.1),
            random(0.5, 6.0),
            random(-0.5, 0.5) * width,
        );
        if Model::from_toml_str(&text, &Overrides::default()).is_ok() {
            texts.push(text);
        }
    }
    let (mut identical, mut grazes) = (0, 0);
    for text in &texts {
        let exact = {
            let model = Model::from_toml_str(
                &format!("{text}\n[solver]\nmethod = \"exact\"\n"),
                &Overrides::default(),
            )
            .unwrap();
            flexrock_core::simulate::simulate_peaks(&model).unwrap()
        };
        assert!(
            common::event_against_its_direction(&exact).is_none(),
            "{text}"
        );
        let tight = tight(text);
        let kinds = |s: &Solution| {
            s.events
                .iter()
                .map(|e| (e.kind, e.to))
                .collect::<Vec<(EventKind, Mode)>>()
        };
        if kinds(&exact) == kinds(&tight) {
            identical += 1;
            for (a, b) in exact.events.iter().zip(&tight.events) {
                assert!((a.t - b.t).abs() < 1e-8, "{text}: {a:?} against {b:?}");
            }
        } else {
            // They may part only where tsit45 itself is unsure: at a graze (an event whose
            // speed across the guard is tiny) within the tight run's own accuracy.
            let i = (0..)
                .find(|&i| kinds(&exact).get(i) != kinds(&tight).get(i))
                .unwrap();
            let slow = |s: &Solution| s.events.get(i).is_some_and(|e| e.qdot_before.abs() < 1e-3);
            assert!(
                slow(&exact) || slow(&tight),
                "{text}: the logs part at event {i} without a graze"
            );
            grazes += 1;
        }
    }
    eprintln!(
        "{identical} identical, {grazes} parting at a graze, of {}",
        texts.len()
    );
    assert!(identical * 100 >= texts.len() * 95);
}

/// A body at rest on a floor at rest stays there: q is 0 at every sample, no event, and the
/// solver proves it at once (a value equal to the extreme recorded is no new peak), where it
/// used to halve the first interval until it gave up. From rest under a one-sine pulse, whose
/// floor acceleration also starts at zero, the start is a double root of q' (q' = q'' = 0): the
/// test on q''' settles it in a few halvings.
#[test]
fn a_body_at_rest_stays_at_rest_and_a_start_from_rest_is_cheap() {
    let rest = exact(&with_exact(&common::reference_body(
        "[excitation]\nkind = \"free\"\n[simulation]\nduration = 5.0",
    )));
    assert!(rest.events.is_empty());
    assert!(rest.samples.iter().all(|s| s.q == 0.0 && s.qdot == 0.0));
    assert!(
        rest.stats.rhs_evaluations < 10,
        "{}",
        rest.stats.rhs_evaluations
    );
    let pulse = exact(&with_exact(&common::reference_body(
        "[excitation]\nkind = \"sine-pulse\"\namplitude = 1.0\nperiod = 0.8\n[simulation]\nduration = 0.001",
    )));
    assert!(pulse.events.is_empty());
    assert!(
        pulse.stats.crossing_retries == 0,
        "no interval left unresolved"
    );
    assert!(
        pulse.stats.rhs_evaluations < 40,
        "{}",
        pulse.stats.rhs_evaluations
    );
}

/// A stiff body (E = 5 GPa, T = 0.049 s) at rest under a slow one-sine pulse (20 s): its
/// quasi-static lean is hundreds of times its free motion. The search must not cut the motion
/// into pieces as short as the body's own period times that ratio (it took 1.8 million
/// evaluations of the closed form over 12 s, and gave up over 20 s). The largest lean is the
/// damped steady state's amplitude, beta1 A / ((omega^2 - Omega^2)^2 + (2 h omega Omega)^2)^(1/2),
/// at the middle of the pulse's second half, from the body's closed forms alone.
#[test]
fn a_stiff_body_under_a_slow_floor_is_searched_in_long_pieces() {
    let text = "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\n\
        youngs_modulus = 5.0e9\ndamping_ratio = 0.05\n\
        [excitation]\nkind = \"sine-pulse\"\namplitude = 0.8\nperiod = 20.0\n\
        [simulation]\nduration = 20.0\n";
    let s = exact(&with_exact(text));
    assert!(
        s.stats.rhs_evaluations < 20_000,
        "{} evaluations",
        s.stats.rhs_evaluations
    );
    let l: f64 = 1.875_104_068_711_961;
    let sigma = (l.cosh() + l.cos()) / (l.sinh() + l.sin());
    let beta1 = 4.0 * sigma / l;
    let (m, ei) = (600.0 * 4.0 * 0.7, 5.0e9 * 0.7_f64.powi(3) / 12.0);
    let omega2 = l.powi(4) * ei / (m * 4.0_f64.powi(3));
    let big_omega = 2.0 * std::f64::consts::PI / 20.0;
    let cross = 2.0 * 0.05 * omega2.sqrt() * big_omega;
    let lean = beta1 * 0.8 / ((omega2 - big_omega * big_omega).powi(2) + cross * cross).sqrt();
    assert!(
        (s.max_q.value / lean - 1.0).abs() < 1e-3,
        "max q {} against the steady lean {lean}",
        s.max_q.value
    );
    assert!((s.max_q.t - 15.0).abs() < 0.1, "at {} s", s.max_q.t);
}

/// Every kind of floor motion's closed form is the motion: at 20,001 times over 10 s, the shape
/// of the stretch holding t gives a(t) to rounding (within the stated bound for the Ricker
/// wavelet's Taylor pieces), and the stretch holds t (it ends after it). Where the floor jumps
/// (the end of a record whose last sample is not zero) a(t) there is the side before the jump,
/// which the stretch ending at t gives: a single point, which no integral sees.
#[test]
fn every_closed_form_of_the_floor_is_the_floor_motion() {
    use flexrock_core::floor::{
        FloorMotion, Free, Harmonic, PaperSine, PulseShape, RecordedMotion, Ricker, SinePulse,
    };
    let record: Vec<f64> = (0..700)
        .map(|k| 3.0 * (0.37 * k as f64).sin() * (-0.004 * k as f64).exp())
        .collect();
    let motions: Vec<Box<dyn FloorMotion>> = vec![
        Box::new(Free),
        Box::new(Harmonic {
            amplitude: 2.5,
            period: 1.5,
        }),
        Box::new(PaperSine::new(5.0, 1.0, 0.412)),
        Box::new(SinePulse::new(3.0, 0.8, 2.0, PulseShape::Antisymmetric)),
        Box::new(SinePulse::new(3.0, 0.8, 1.0, PulseShape::Symmetric)),
        Box::new(Ricker {
            amplitude: 4.0,
            period: 1.0,
            center: 1.5,
        }),
        Box::new(RecordedMotion::new("made up".to_string(), 0.01, record)),
    ];
    for floor in &motions {
        let peak = floor.peak_acceleration().max(1.0);
        for i in 0..=20_000 {
            let t = i as f64 * 5e-4;
            let form = floor.closed_form(t);
            assert!(
                form.until > t,
                "{}: the stretch at t = {t} ends at {}",
                floor.kind(),
                form.until
            );
            let a = floor.acceleration(t);
            let mut difference = (form.shape.value(t) - a).abs();
            if t > 0.0 {
                let before = floor.closed_form(t - 5e-4);
                if before.until == t {
                    difference = difference.min((before.shape.value(t) - a).abs());
                }
            }
            assert!(
                difference <= form.error_bound + 1e-13 * peak,
                "{} at t = {t}: closed form off by {difference:e}",
                floor.kind()
            );
        }
    }
}

/// A flow under the Ricker wavelet re-plans at the end of each Taylor piece, where x = pi (t -
/// tc) / Tp computed from that time can round to just below the boundary: the closed form there
/// must be the next piece (its own expansion, within its stated bound over all of it), not the
/// piece before carried a whole width beyond its radius. The pieces used to be carried: on the
/// first wavelet below, the piece at x = 0.5 was the one about x = 0.35, off by 1e-12 of A
/// near its end, 1e5 times its stated bound, which moved that run's peaks by 1.5e-14 m.
#[test]
fn each_taylor_piece_of_the_ricker_wavelet_is_its_own_from_its_start() {
    use flexrock_core::floor::{FloorMotion, Ricker};
    for (amplitude, period, center) in [(6.0, 0.5, 0.6), (4.0, 1.0, 1.5), (-2.5, 0.37, 0.9)] {
        let floor = Ricker {
            amplitude,
            period,
            center,
        };
        let mut t: f64 = 0.0;
        let mut pieces = 0;
        while t.is_finite() && pieces < 100 {
            let form = floor.closed_form(t);
            assert!(
                form.until > t,
                "the stretch at t = {t} ends at {}",
                form.until
            );
            let end = if form.until.is_finite() {
                form.until
            } else {
                t + period
            };
            for k in 0..=64 {
                let s = t + (end - t) * k as f64 / 64.0;
                let difference = (form.shape.value(s) - floor.acceleration(s)).abs();
                assert!(
                    difference <= form.error_bound + 1e-14 * amplitude.abs(),
                    "A = {amplitude}, Tp = {period}: the piece taken at t = {t} is off by \
                     {difference:e} at {s} (stated bound {:e})",
                    form.error_bound
                );
            }
            t = form.until;
            pieces += 1;
        }
        assert!(pieces > 30, "the wavelet has {pieces} pieces");
    }
}

/// A run that starts at rest away from 0 has its smallest q at t = 0, before any flow: the
/// estimate of that peak is not zero (the initial q is the file's decimal rounded to a double,
/// and an independent solver finds t = 0 as a root of q' only to its own rounding), as every
/// other entry of the estimate is not.
#[test]
fn a_peak_at_the_initial_state_has_an_error_estimate() {
    let model = Model::from_toml_str(
        "[body]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\
         [excitation]\nkind = \"free\"\n[simulation]\nduration = 3.0\nq0 = -0.55\n\
         [solver]\nmethod = \"exact\"\n",
        &Overrides::default(),
    )
    .expect("the model reads");
    let sol = flexrock_core::simulate::simulate(&model).expect("solves");
    assert_eq!(sol.min_q.t, 0.0, "the smallest q is the initial one");
    let e = sol.rounding.as_ref().expect("an estimate");
    for (name, value) in [
        ("max_q", e.max_q),
        ("t_max_q", e.t_max_q),
        ("min_q", e.min_q),
        ("t_min_q", e.t_min_q),
    ] {
        assert!(value > 1e-30, "{name} estimate {value:e}");
    }
    assert!(e.event_time.iter().all(|&x| x > 0.0));
}

/// Each root of the paper's example (its 22 events and the extrema between them) is found in a
/// few Newton steps. Once a step falls below half an ulp of t the double found is the root; the
/// search used to halve the bracket from there down to two ulps, which took 1043 evaluations of
/// the closed form for the example's 27 flows (38 per flow, where now about 11).
#[test]
fn the_papers_example_needs_few_evaluations_per_flow() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../models/ichinose1986.toml");
    let overrides = Overrides {
        method: Some("exact".to_string()),
        ..Overrides::default()
    };
    let model = Model::load(&path, &overrides).expect("the model loads");
    let s = flexrock_core::simulate::simulate(&model).expect("solves");
    assert_eq!(s.events.len(), 22);
    assert!(
        s.stats.rhs_evaluations <= 15 * s.stats.steps,
        "{} evaluations for {} flows",
        s.stats.rhs_evaluations,
        s.stats.steps
    );
}

/// A record's samples inside its intervals come from the exact recurrence over their offset
/// where the grid has few samples an interval (here every 5 ms in El Centro's 20 ms), and from
/// the interval's Taylor series where it has many (every 1 ms): at the times both grids share,
/// the two agree to rounding, through the rocking episode and the free vibration after the
/// record.
#[test]
fn a_records_samples_by_the_recurrence_are_its_series_to_rounding() {
    let run = |output_dt: &str| {
        exact(&common::reference_body(&format!(
            "[excitation]\nkind = \"record\"\npath = \"{}\"\nunits = \"g\"\ntail = 2.0\n\n\
             [solver]\nmethod = \"exact\"\noutput_dt = {output_dt}\n",
            common::workspace_file("validation/records/elCentro.AT2").display()
        )))
    };
    let (coarse, fine) = (run("0.005"), run("0.001"));
    assert!(
        coarse.events.len() >= 2,
        "El Centro rocks the reference body"
    );
    let mut shared = 0;
    let mut fine_samples = fine.samples.iter().peekable();
    for sample in &coarse.samples {
        while fine_samples.peek().is_some_and(|f| f.t < sample.t) {
            fine_samples.next();
        }
        // (At an event both grids hold the state before and after it, in that order.)
        let Some(other) = fine_samples.next_if(|f| f.t == sample.t) else {
            continue;
        };
        shared += 1;
        assert!(
            (sample.q - other.q).abs() <= 1e-15 && (sample.qdot - other.qdot).abs() <= 1e-14,
            "t = {} s: q {} and q' {} by the recurrence, {} and {} by the series",
            sample.t,
            sample.q,
            sample.qdot,
            other.q,
            other.qdot
        );
    }
    assert!(shared > 6000, "{shared} shared times");
}
