//! The simulator against closed forms: the linear oscillator before uplift, Housner's rigid block
//! in the rigid limit, and the event logic (no missed events, grazing starts, overturning).

use crate::common;

use flexrock_core::physics::automaton::{EventKind, Mode};

fn free_body(e_factor: f64, damping: f64, q0: f64, qdot0: f64, duration: f64) -> String {
    format!(
        "[body]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = {}\n\
         damping_ratio = {damping}\n\n[excitation]\nkind = \"free\"\n\n\
         [simulation]\nduration = {duration}\nq0 = {q0}\nqdot0 = {qdot0}\n\n\
         [solver]\nrtol = 1e-11\natol = 1e-13\noutput_dt = 0.01\n",
        5.0e6 * e_factor
    )
}

#[test]
fn weak_harmonic_matches_the_damped_oscillator() {
    let text = common::reference_body(
        "[excitation]\nkind = \"harmonic\"\namplitude = 0.3\nperiod = 1.0\n\
         [simulation]\nduration = 6.0\n[solver]\nrtol = 1e-10\natol = 1e-12\noutput_dt = 0.01\n",
    );
    let model = common::model(&text);
    let sol = flexrock_core::simulate::simulate(&model).unwrap();
    assert!(sol.events.is_empty(), "too weak to uplift");

    // q'' + 2 h w q' + w^2 q = -beta1 A sin(W t), q(0) = q'(0) = 0: closed form.
    let c = &model.constants;
    let exact = common::damped_oscillator_response(c.omega, 0.05, c.beta1, 0.3, 1.0);
    let mut worst: f64 = 0.0;
    for s in &sol.samples {
        worst = worst.max((s.q - exact(s.t)).abs());
        assert_eq!(s.mode, Mode::PreUplift);
    }
    assert!(worst < 1e-8, "max |q - closed form| = {worst:e} m");
}

#[test]
fn rigid_limit_free_rocking_lands_when_housner_says() {
    // E x 1e5, no damping, free rocking from theta0 = alpha/2, i.e. q0 = H theta0 = B/2.
    let text = free_body(1e5, 0.0, 0.35, 0.0, 0.7);
    let sol = common::solve(&text);
    let landing = sol
        .events
        .iter()
        .find(|e| e.kind == EventKind::Landing)
        .expect("the block lands");
    // book/src/model.md §7 (rigid limit):
    // t = (1/p) acosh(1 / (1 - theta0/alpha)), p = sqrt(3 g / (2 H)).
    let p = (3.0 * 9.81 / (2.0 * 4.0_f64)).sqrt();
    let housner = (1.0_f64 / (1.0 - 0.5)).acosh() / p;
    assert!(
        (landing.t - housner).abs() < 1e-5,
        "landing at {} s, Housner {} s",
        landing.t,
        housner
    );
    assert_eq!(landing.from, Mode::RockRight);
    // Velocity ratio across landing then uplift equals Housner's restitution on theta.
    let (h, b) = (4.0_f64, 0.7_f64);
    let housner_r = (2.0 * h * h - b * b) / (2.0 * (h * h + b * b));
    let next_uplift = sol
        .events
        .iter()
        .find(|e| e.kind == EventKind::Uplift && e.t >= landing.t)
        .expect("rocks on to the other toe");
    // In the rigid limit the pre-uplift phase is instantaneous, so the two jumps compose.
    let ratio = next_uplift.qdot_after / landing.qdot_before;
    assert!(
        (ratio - housner_r).abs() < 2e-3,
        "velocity ratio {ratio}, Housner {housner_r}"
    );
}

#[test]
fn rigid_limit_overturns_when_the_closed_form_says() {
    // In the rigid limit with no damping, u = B - q obeys u'' = p^2 u, so from q0 with an outward
    // velocity qdot0 > p (B - q0) the block reaches q = B at t = atanh(p u0 / qdot0) / p.
    let p = (3.0 * 9.81 / (2.0 * 4.0_f64)).sqrt();
    let u0 = 0.35;
    let qdot0 = 1.2 * p * u0;
    let sol = common::solve(&free_body(1e5, 0.0, 0.35, qdot0, 3.0));
    assert!(sol.overturned);
    let t_over = sol.t_overturn.unwrap();
    let expected = (1.0_f64 / 1.2).atanh() / p;
    assert!((t_over - expected).abs() < 1e-5, "{t_over} vs {expected}");
    let last = sol.events.last().unwrap();
    assert_eq!(last.kind, EventKind::Overturn);
    assert_eq!(last.to, Mode::Overturned);
    assert_eq!(last.q, 0.7);
    assert_eq!(sol.max_q.value, 0.7);
    assert_eq!(sol.final_mode, Mode::Overturned);
}

#[test]
fn no_missed_events_at_loose_tolerance() {
    let loose = common::reference_body(
        "[excitation]\nkind = \"paper-sine\"\namplitude = 5.0\nperiod = 1.0\nramp = 0.412\n\
         [simulation]\nduration = 6.0\n[solver]\nrtol = 1e-4\natol = 1e-6\n",
    );
    let tight = loose.replace("rtol = 1e-4\natol = 1e-6", "rtol = 1e-10\natol = 1e-12");
    let (a, b) = (common::solve(&loose), common::solve(&tight));
    let seq = |s: &flexrock_core::integrate::solution::Solution| {
        s.events
            .iter()
            .map(|e| (e.kind, e.from, e.to))
            .collect::<Vec<_>>()
    };
    assert!(b.events.len() >= 10);
    assert_eq!(seq(&a), seq(&b));
    for (ea, eb) in a.events.iter().zip(&b.events) {
        assert!((ea.t - eb.t).abs() < 1e-2, "{} vs {}", ea.t, eb.t);
    }
}

#[test]
fn grazing_start_on_the_guard_does_not_trigger_it() {
    // q0 = s_n exactly, at rest: the body moves back into pre-uplift and never reaches s_n again.
    let probe = common::model(&free_body(1.0, 0.05, 0.0, 0.0, 1.0));
    let s_n = probe.constants.uplift_displacement;
    for q0 in [s_n, -s_n] {
        let sol = common::solve(&free_body(1.0, 0.05, q0, 0.0, 4.0));
        assert!(sol.events.is_empty(), "q0 = {q0}: {:?}", sol.events);
        assert!(sol.samples.iter().all(|s| s.mode == Mode::PreUplift));
        assert!(sol.max_q.value <= s_n && sol.min_q.value >= -s_n);
    }
}

#[test]
fn start_on_the_guard_moving_out_uplifts_at_once() {
    let probe = common::model(&free_body(1.0, 0.05, 0.0, 0.0, 1.0));
    let c = &probe.constants;
    let s_n = c.uplift_displacement;
    for (q0, v0, to) in [(s_n, 0.5, Mode::RockRight), (-s_n, -0.5, Mode::RockLeft)] {
        let sol = common::solve(&free_body(1.0, 0.05, q0, v0, 2.0));
        let first = &sol.events[0];
        assert_eq!(first.t, 0.0);
        assert_eq!(first.kind, EventKind::Uplift);
        assert_eq!(first.to, to);
        assert!((first.qdot_after - c.zeta_uplift * v0).abs() < 1e-15);
        // It then comes back and lands: the guard of the new mode is not re-triggered at t = 0.
        assert_eq!(sol.events[1].kind, EventKind::Landing);
        assert!(sol.events[1].t > 0.05);
    }
}

#[test]
fn resets_follow_the_zetas() {
    let text = common::reference_body(
        "[excitation]\nkind = \"paper-sine\"\namplitude = 5.0\nperiod = 1.0\nramp = 0.412\n\
         [simulation]\nduration = 6.0\n",
    );
    let model = common::model(&text);
    let sol = flexrock_core::simulate::simulate(&model).unwrap();
    let c = &model.constants;
    for e in &sol.events {
        let expected = match e.kind {
            EventKind::Uplift => c.zeta_uplift * e.qdot_before,
            EventKind::Landing => e.qdot_before / c.zeta_landing,
            EventKind::Overturn => e.qdot_before,
            EventKind::Impact
            | EventKind::ContactStart
            | EventKind::ContactEnd
            | EventKind::FrictionStick
            | EventKind::FrictionSlip => {
                panic!("a body alone is struck at t = {}", e.t)
            }
        };
        assert!((e.qdot_after - expected).abs() < 1e-14);
        assert_eq!(e.q.abs(), c.uplift_displacement);
    }
    // Modes alternate sensibly: every landing follows an uplift on the same side.
    for pair in sol.events.windows(2) {
        if pair[1].kind == EventKind::Landing {
            assert_eq!(pair[0].to, pair[1].from);
        }
    }
    // History obeys the model's relations: r = 0 whenever |q| <= s_n, |s| <= s_n always.
    for s in &sol.samples {
        assert!(s.s.abs() <= c.uplift_displacement * (1.0 + 1e-12));
        if s.mode == Mode::PreUplift {
            assert_eq!(s.r, 0.0);
        }
    }
}

#[test]
fn energy_residual_is_small_and_shrinks_with_the_tolerance() {
    let base = common::reference_body(
        "[excitation]\nkind = \"paper-sine\"\namplitude = 5.0\nperiod = 1.0\nramp = 0.412\n\
         [simulation]\nduration = 6.0\n[solver]\nrtol = RTOL\natol = 1e-13\n",
    );
    let loose = common::solve(&base.replace("RTOL", "1e-6"));
    let tight = common::solve(&base.replace("RTOL", "1e-11"));
    // The energy scale of the run: Me q'^2/2 with q' ~ 1.8 m/s is about 1 kJ.
    assert!(
        tight.max_energy_residual < 1e-4,
        "{}",
        tight.max_energy_residual
    );
    assert!(tight.max_energy_residual < loose.max_energy_residual / 100.0);
}

#[test]
fn all_methods_agree() {
    let base = common::reference_body(
        "[excitation]\nkind = \"paper-sine\"\namplitude = 5.0\nperiod = 1.0\nramp = 0.412\n\
         [simulation]\nduration = 6.0\n[solver]\nmethod = \"METHOD\"\nrtol = 1e-9\natol = 1e-11\n",
    );
    let reference = common::solve(&base.replace("METHOD", "bdf"));
    for method in ["esdirk34", "tr-bdf2", "tsit45"] {
        let other = common::solve(&base.replace("METHOD", method));
        assert_eq!(other.events.len(), reference.events.len(), "{method}");
        for (a, b) in other.events.iter().zip(&reference.events) {
            assert_eq!(a.kind, b.kind);
            assert!((a.t - b.t).abs() < 1e-5, "{method}: {} vs {}", a.t, b.t);
        }
        assert!((other.max_q.value - reference.max_q.value).abs() < 1e-5);
    }
}

/// Undamped free rocking of a stiff body never stops: it loses speed only at impacts. Between
/// them both branches conserve |q'| from guard to guard (h = 0), so every uplift starts with
/// ζU/ζL times the speed of the one before. The run has about 70 events: every method must
/// carry it to its end (diffsol counts Newton failures over a whole run, and each mode
/// switch used to cost one, so implicit methods gave up after 50 events).
#[test]
fn undamped_free_rocking_loses_speed_only_at_impacts_through_many_events() {
    let text = free_body(200.0, 0.0, 0.0, 0.3, 4.0);
    let constants = common::model(&text).constants;
    let ratio = constants.zeta_uplift / constants.zeta_landing;
    for method in ["bdf", "esdirk34", "tr-bdf2", "tsit45"] {
        let text = text
            .replace(
                "rtol = 1e-11",
                &format!("method = \"{method}\"\nrtol = 1e-9"),
            )
            .replace("atol = 1e-13", "atol = 1e-8");
        let sol = common::solve(&text);
        assert_eq!(sol.final_time, 4.0, "{method}");
        let uplifts: Vec<f64> = sol
            .events
            .iter()
            .filter(|e| e.kind == EventKind::Uplift)
            .map(|e| e.qdot_before.abs())
            .collect();
        assert!(uplifts.len() > 30, "{method}: {} uplifts", uplifts.len());
        for pair in uplifts.windows(2).take(30) {
            let r = pair[1] / pair[0];
            assert!(
                (r / ratio - 1.0).abs() < 1e-4,
                "{method}: {r} against {ratio}"
            );
        }
    }
}

/// A crossing found inside the step that reaches a stop time moves the solver back before it;
/// the run must still stop there. This body grazes its guards at ever smaller speeds, so at a
/// loose tolerance such crossings come often (before the fix, a run to 2.5 s went on forever).
#[test]
fn runs_end_at_their_stop_time_after_crossings_in_the_last_step() {
    for k in 0..=20 {
        let duration = 2.0 + 0.1 * k as f64;
        let text = format!(
            "[body]\nheight = 2\nwidth = 0.46748874965162096\ndensity = 600.0\n\
             youngs_modulus = 943268295.7622077\ndamping_ratio = 0\n\
             [excitation]\nkind = \"free\"\n\
             [simulation]\nduration = {duration}\nq0 = 0\nqdot0 = 0.33511040563962013\n\
             [solver]\nmethod = \"tsit45\"\nrtol = 0.001\natol = 0.00001\noutput_dt = 0.01\n"
        );
        let model = common::model(&text);
        let sol = flexrock_core::simulate::simulate(&model)
            .unwrap_or_else(|e| panic!("duration {duration}: {e}"));
        assert!((sol.final_time - duration).abs() < 1e-9, "{duration}");
        assert!((sol.samples.last().unwrap().t - duration).abs() < 1e-9);
    }
}
