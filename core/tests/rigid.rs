//! The rigid block (src/rigid.rs) against closed forms of Housner's slender block. In q = theta H
//! units, rocking right: q'' = k^2 (q - B) - (3/2) a, k^2 = 3 g/(2 H); with x = q - B and a
//! constant floor acceleration the motion is x = x_e + (x0 - x_e) cosh(k t) + (v0/k) sinh(k t),
//! x_e = 3 a/(2 k^2) = a H/g, from which every expected value below is derived.

use flexrock_core::bodies::rigid::{
    simulate_block, simulate_from, RigidBlock, RigidEventKind, RigidForm, RigidOutcome,
    RigidOverturning, RigidPhase, RigidSettings,
};
use flexrock_core::floor::{ClosedForm, FloorMotion, Free, Harmonic, PulseShape, SinePulse};
use flexrock_core::integrate::InitialState;

const H: f64 = 4.0;
const B: f64 = 0.7;
const G: f64 = 9.81;

fn housner() -> RigidBlock {
    RigidBlock::housner(H, B, G).unwrap()
}

fn elastic_limit() -> RigidBlock {
    RigidBlock::elastic_limit(H, B, G).unwrap()
}

fn k() -> f64 {
    (1.5 * G / H).sqrt()
}

/// The closed forms use their own k, e and g B/H, not the block's methods; this checks those too.
#[test]
fn block_quantities() {
    let b = housner();
    assert!((b.frequency() - k()).abs() < 1e-15);
    let alpha = (B / H).atan();
    // e = 1 - 1.5 sin^2(alpha) (book/src/model.md §7, eq. A7).
    assert!((b.restitution() - (1.0 - 1.5 * alpha.sin().powi(2))).abs() < 1e-15);
    assert!((b.restitution() - 0.955_427_531_837_477).abs() < 1e-14);
    assert!((b.uplift_acceleration() - G * B / H).abs() < 1e-15);
    let l = flexrock_core::physics::constants::MODE_ROOT;
    let sigma = (l.cosh() + l.cos()) / (l.sinh() + l.sin());
    let factor = l.powi(3) / (8.0 * sigma);
    assert!((elastic_limit().uplift_acceleration() - factor * G * B / H).abs() < 1e-14);
    assert!((b.overturning_velocity() - k() * B).abs() < 1e-15);
}

use crate::common::Constant;

fn from(block: &RigidBlock, floor: &dyn FloorMotion, q: f64, qdot: f64, t: f64) -> RigidOutcome {
    simulate_from(
        block,
        floor,
        InitialState { q, qdot },
        t,
        &RigidSettings::for_block(block),
    )
    .unwrap()
}

fn first(
    outcome: &RigidOutcome,
    kind: RigidEventKind,
) -> &flexrock_core::bodies::rigid::RigidEvent {
    outcome
        .events
        .iter()
        .find(|e| e.kind == kind)
        .unwrap_or_else(|| panic!("no {kind:?} in {:?}", outcome.events))
}

/// (1) Free rocking from q0 at rest reaches q = 0 at (1/k) acosh(1/(1 - q0/B))
/// (book/src/model.md §7, rigid limit),
/// (3) with |q'| = k sqrt(B^2 - (B - q0)^2) (energy: q'^2 = k^2 ((B - q)^2 - (B - q0)^2)), which
/// the impact multiplies by e. Tolerance: a run of N steps adds round-off of order N ulps, and
/// near the unstable position |q| = B (q0 = 0.69) it grows like cosh(k t) = 70: measured 1.1e-12 s
/// there (4e-13 relative) at 1 ms steps, 1.2e-11 s at 0.1 ms, 1.7e-13 s at 10 ms.
#[test]
fn free_rocking_reaches_the_floor_at_housners_time_and_loses_the_restitution() {
    let block = housner();
    for q0 in [0.05, 0.3, 0.69, -0.3] {
        let o = from(&block, &Free, q0, 0.0, 3.0);
        let impact = first(&o, RigidEventKind::Impact);
        let x0 = q0.abs();
        let t1 = (1.0 / (1.0 - x0 / B)).acosh() / k();
        let speed = k() * (B * B - (B - x0) * (B - x0)).sqrt();
        assert!(
            (impact.t - t1).abs() < 5e-12 * t1,
            "q0 = {q0}: impact at {} s, closed form {t1} s",
            impact.t
        );
        assert!(
            (impact.qdot_before + q0.signum() * speed).abs() < 1e-12 * speed,
            "q0 = {q0}: q' before impact {}, closed form {}",
            impact.qdot_before,
            -q0.signum() * speed
        );
        let e = (2.0 * H * H - B * B) / (2.0 * (H * H + B * B));
        assert!((impact.qdot_after - e * impact.qdot_before).abs() < 1e-15 * speed);
        let expected_side = if q0 > 0.0 {
            RigidPhase::RockLeft
        } else {
            RigidPhase::RockRight
        };
        assert_eq!(impact.to, expected_side);
        assert_eq!(impact.q, 0.0);
        assert_eq!(o.n_uplift, 0);
        assert!((o.max_abs_q - x0).abs() < 1e-15);
    }
}

/// (2) From upright with speed v0, x = -B cosh(k t) + (v0/k) sinh(k t): the block overturns iff
/// v0 > k B, at tanh(k t) = k B/v0; below, it turns at q = B - sqrt(B^2 - v0^2/k^2). Near the
/// critical speed the block creeps past the unstable position, which amplifies round-off: the
/// overturn time is off by 3e-12 s at 1 ms steps (1.4e-12 s at 10 ms, 2.8e-11 s at 0.1 ms).
#[test]
fn free_block_overturns_iff_its_speed_exceeds_k_b() {
    let block = housner();
    let critical = k() * B;
    for sign in [1.0, -1.0] {
        let v0 = 1.001 * critical;
        let o = from(&block, &Free, 0.0, sign * v0, 10.0);
        let t_ov = (critical / v0).atanh() / k();
        assert!(o.overturned);
        let t = o.t_overturn.unwrap();
        assert!((t - t_ov).abs() < 1e-11 * t_ov, "{t} against {t_ov}");
        assert_eq!(o.final_state.phase, RigidPhase::Overturned);
        assert_eq!(o.final_state.q, sign * B);
        assert_eq!(o.max_abs_q, B);
        assert_eq!(o.n_impact, 0);

        let v0 = 0.999 * critical;
        let o = from(&block, &Free, 0.0, sign * v0, 10.0);
        assert!(!o.overturned);
        let q_max = B - (B * B - v0 * v0 / (k() * k())).sqrt();
        let t_max = (v0 / critical).atanh() / k();
        assert!(
            (o.max_abs_q - q_max).abs() < 1e-11 * q_max,
            "{}",
            o.max_abs_q
        );
        assert!((o.t_max_abs_q - t_max).abs() < 1e-9, "{}", o.t_max_abs_q);
        // It comes back with the speed it left with, at twice the turning time.
        let impact = first(&o, RigidEventKind::Impact);
        assert!(
            (impact.t - 2.0 * t_max).abs() < 1e-11 * t_max,
            "{}",
            impact.t
        );
        assert!((impact.qdot_before + sign * v0).abs() < 1e-11 * v0);
    }
}

/// (4) A floor acceleration below a_up never lifts the block; one above lifts it at once, onto
/// the toe the floor pushes it towards (a < 0 rocks it right). A sine a = A sin(2 pi t/T) with
/// A above a_up lifts it to the left at T asin(a_up/A)/(2 pi).
#[test]
fn uplift_starts_at_the_uplift_acceleration() {
    for block in [housner(), elastic_limit()] {
        let a_up = block.uplift_acceleration();
        for sign in [1.0, -1.0] {
            let o = simulate_block(&block, &Constant(-sign * 0.999 * a_up), 5.0).unwrap();
            assert_eq!(o.n_uplift, 0);
            assert_eq!(o.final_state.phase, RigidPhase::Rest);
            assert_eq!(o.max_abs_q, 0.0);

            let o = simulate_block(&block, &Constant(-sign * 1.001 * a_up), 0.5).unwrap();
            assert_eq!(o.first_uplift, Some(0.0));
            let side = if sign > 0.0 {
                RigidPhase::RockRight
            } else {
                RigidPhase::RockLeft
            };
            assert_eq!(o.events[0].to, side);
            assert!(o.final_state.q * sign > 0.0);
        }
        let period = 1.0;
        let o = simulate_block(
            &block,
            &Harmonic {
                amplitude: 0.99 * a_up,
                period,
            },
            3.0,
        )
        .unwrap();
        assert_eq!(o.n_uplift, 0);
        let amplitude = 1.01 * a_up;
        let o = simulate_block(&block, &Harmonic { amplitude, period }, 0.5).unwrap();
        let expected = period * (a_up / amplitude).asin() / (2.0 * std::f64::consts::PI);
        let t = o.first_uplift.expect("lifts");
        assert!((t - expected).abs() < 1e-14, "{t} against {expected}");
        assert_eq!(o.events[0].to, RigidPhase::RockLeft);
    }
}

/// (5) Under a = -c (c > a_up) from t = 0 the block lifts at once and, with x0 = -B, v0 = 0,
/// x_e = -c H/g: q = (c H/g - B)(cosh(k t) - 1), q' = k (c H/g - B) sinh(k t); it overturns
/// (q = B) at cosh(k t) = c/(c - g B/H).
#[test]
fn a_constant_push_overturns_at_the_closed_form_time() {
    for block in [housner(), elastic_limit()] {
        for c in [1.5 * G * B / H, 3.0 * G * B / H] {
            let amplitude = c * H / G - B;
            let t_ov = (c / (c - G * B / H)).acosh() / k();
            let o = simulate_block(&block, &Constant(-c), 10.0).unwrap();
            let t = o.t_overturn.expect("overturns");
            assert!(
                (t - t_ov).abs() < 1e-12 * t_ov,
                "c = {c}: {t} against {t_ov}"
            );
            assert_eq!(o.n_uplift, 1);
            assert_eq!(o.n_impact, 0);

            let t = 0.7 * t_ov;
            let o = simulate_block(&block, &Constant(-c), t).unwrap();
            let q = amplitude * ((k() * t).cosh() - 1.0);
            let v = k() * amplitude * (k() * t).sinh();
            assert!(
                (o.final_state.q - q).abs() < 1e-13 * q,
                "{} against {q}",
                o.final_state.q
            );
            assert!((o.final_state.qdot - v).abs() < 1e-13 * v);
            assert_eq!(o.final_state.t, t);
        }
    }
}

/// Free rocking decays through impacts that shrink by e and accumulate in finite time. A flight
/// that leaves q = 0 with speed v < k B lasts 2 atanh(v/(k B))/k, so from rest at q0 the impacts
/// end at t1 + sum_n 2 atanh(e^n v1/(k B))/k, v1 = e k sqrt(B^2 - (B - q0)^2). The block is put at
/// rest when the rest of that sequence would take less than ZENO_TIME (by the module's bound
/// 2 v/((3/2)(g B/H)(1 - e)), which the true flights, slower near q = 0 than the bound assumes
/// only by O(v^2), meet).
#[test]
fn chatter_ends_at_the_accumulation_point() {
    let block = housner();
    let e = block.restitution();
    let q0 = 0.2;
    let o = from(&block, &Free, q0, 0.0, 200.0);
    let t1 = (1.0 / (1.0 - q0 / B)).acosh() / k();
    let mut v = e * k() * (B * B - (B - q0) * (B - q0)).sqrt();
    let mut accumulation = t1;
    let mut n = 1;
    let mut settle_predicted = None;
    while v > 1e-300 {
        let remaining_bound = 2.0 * v / (1.5 * G * B / H * (1.0 - e));
        if settle_predicted.is_none() && remaining_bound <= flexrock_core::bodies::rigid::ZENO_TIME
        {
            settle_predicted = Some((accumulation, n));
        }
        accumulation += 2.0 * (v / (k() * B)).atanh() / k();
        v *= e;
        n += 1;
    }
    let (t_settle, impacts) = settle_predicted.unwrap();
    let settle = first(&o, RigidEventKind::Settle);
    assert_eq!(o.n_settle, 1);
    assert_eq!(o.n_impact, impacts, "impacts before settling");
    assert!(
        (settle.t - t_settle).abs() < 1e-9 * t_settle,
        "settled at {} s, predicted {t_settle} s",
        settle.t
    );
    assert!(accumulation - settle.t < flexrock_core::bodies::rigid::ZENO_TIME);
    assert!(accumulation - settle.t > 0.0);
    assert_eq!(o.final_state.phase, RigidPhase::Rest);
    assert_eq!((o.final_state.q, o.final_state.qdot), (0.0, 0.0));
}

/// (6) Halving the step changes event times and peaks by far less than 1e-8 on one-sine pulses
/// of 1 s: amplitude 2.0 rocks a little and chatters to rest (about 300 impacts), 2.2 rocks with
/// 10 impacts, 2.5 overturns after an impact, 6.0 overturns at once. Measured: at most 2.4e-12
/// (s for times, m/s for velocities, relative for max |q|) from 1 ms to 0.5 ms steps.
#[test]
fn halving_the_step_changes_nothing_that_matters() {
    for block in [housner(), elastic_limit()] {
        for amplitude in [2.0, 2.2, 2.5, 6.0] {
            let pulse = SinePulse::new(amplitude, 1.0, 1.0, PulseShape::Antisymmetric);
            let run = |h: f64| {
                simulate_from(
                    &block,
                    &pulse,
                    InitialState { q: 0.0, qdot: 0.0 },
                    8.0,
                    &RigidSettings {
                        max_step: h,
                        ..RigidSettings::for_block(&block)
                    },
                )
                .unwrap()
            };
            let (coarse, fine) = (run(1e-3), run(5e-4));
            assert_eq!(coarse.events.len(), fine.events.len());
            let mut worst: f64 = 0.0;
            for (a, b) in coarse.events.iter().zip(&fine.events) {
                assert_eq!(a.kind, b.kind);
                worst = worst.max((a.t - b.t).abs());
                worst = worst.max((a.qdot_before - b.qdot_before).abs());
            }
            worst = worst.max((coarse.max_abs_q - fine.max_abs_q).abs() / coarse.max_abs_q);
            eprintln!(
                "a_up {:.4} A {amplitude}: {} events, overturned {:?}, max |q| {:.6}, worst change {worst:e}",
                block.uplift_acceleration(),
                coarse.events.len(),
                coarse.t_overturn,
                coarse.max_abs_q
            );
            assert!(worst < 1e-10, "A = {amplitude}: {worst:e}");
        }
    }
}

#[test]
fn meaningless_input_is_refused() {
    let bad = [f64::NAN, 0.0, -1.0, f64::INFINITY];
    for x in bad {
        assert!(RigidBlock::housner(x, B, G).is_err());
        assert!(RigidBlock::housner(H, x, G).is_err());
        assert!(RigidBlock::elastic_limit(H, B, x).is_err());
        let err = simulate_block(&housner(), &Free, x).unwrap_err();
        assert!(err.is_input_error(), "{err}");
    }
    let err = RigidBlock::housner(H, H, G).unwrap_err();
    assert!(err.to_string().contains("slender"), "{err}");
    for e in [f64::NAN, -0.1, 0.0, -0.0, 1.0, 1.0 + 1e-12, f64::INFINITY] {
        let err = housner().with_restitution(e).unwrap_err().to_string();
        assert!(
            err.starts_with("rigid.restitution = ") && err.contains("strictly between 0 and 1"),
            "{err}"
        );
    }
    for e in [1e-9, 0.9, 1.0 - 1e-12] {
        assert_eq!(housner().with_restitution(e).unwrap().restitution(), e);
    }
    let err = RigidBlock::with_uplift_acceleration(H, B, G, 0.9 * G * B / H).unwrap_err();
    assert!(err.to_string().contains("g B/H"), "{err}");
    for q in [B, -B, 2.0, f64::NAN] {
        let err = simulate_from(
            &housner(),
            &Free,
            InitialState { q, qdot: 0.0 },
            1.0,
            &RigidSettings::for_block(&housner()),
        )
        .unwrap_err();
        assert!(err.is_input_error(), "{err}");
    }
    for h in [0.0, f64::NAN, -1e-3] {
        let err = simulate_from(
            &housner(),
            &Free,
            InitialState { q: 0.0, qdot: 0.0 },
            1.0,
            &RigidSettings {
                max_step: h,
                ..RigidSettings::for_block(&housner())
            },
        )
        .unwrap_err();
        assert!(err.is_input_error(), "{err}");
    }
    // The full form's tolerances likewise.
    let full = housner().with_form(RigidForm::Full);
    for bad in [0.0, f64::NAN, -1e-10, f64::INFINITY] {
        for settings in [
            RigidSettings {
                rtol: bad,
                ..RigidSettings::for_block(&full)
            },
            RigidSettings {
                atol: bad,
                ..RigidSettings::for_block(&full)
            },
        ] {
            let err = simulate_from(
                &full,
                &Free,
                InitialState { q: 0.0, qdot: 0.0 },
                1.0,
                &settings,
            )
            .unwrap_err();
            assert!(err.is_input_error(), "{err}");
            assert!(
                err.to_string().contains("rigid.rtol") || err.to_string().contains("rigid.atol"),
                "{err}"
            );
        }
    }
    let err = simulate_block(&housner(), &Constant(1e6), 1.0).unwrap_err();
    assert!(err.to_string().contains("20 g"), "{err}");
    // A floor that is not a number ends the run with an error, not a panic or a hang.
    let err = simulate_block(&housner(), &Nan, 1.0).unwrap_err();
    assert!(!err.is_input_error(), "{err}");
}

/// Claims a peak of 1 m/s^2 and returns NaN after 0.1 s, once rocking has started.
struct Nan;

impl FloorMotion for Nan {
    fn acceleration(&self, t: f64) -> f64 {
        if t < 0.1 {
            -5.0
        } else {
            f64::NAN
        }
    }
    fn peak_acceleration(&self) -> f64 {
        5.0
    }
    fn kind(&self) -> &'static str {
        "nan"
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({ "kind": "nan" })
    }
    fn closed_form(&self, t: f64) -> ClosedForm {
        if t < 0.1 {
            ClosedForm::polynomial(0.0, &[-5.0], 0.1)
        } else {
            ClosedForm::polynomial(0.1, &[f64::NAN], f64::INFINITY)
        }
    }
}

/// The continuity the paper claims (book/src/model.md §7, rigid limit): the elastic model of the
/// reference body (H = 4 m, B = 0.7 m, 600 kg/m^3, h = 0.05) with E = 5e6 Pa times 1e2, 1e3, 1e4
/// (and 1e6, to show the trend) tends, under one-sine pulses, to the rigid block with the elastic
/// limit's uplift acceleration 1.1226 g B/H = 1.9273 m/s^2, not to Housner's block
/// (g B/H = 1.7168 m/s^2).
///
/// Measured (elastic minus elastic-limit block; times in s, max |q| in m; "ov" = overturned):
///
/// | Tp, A    | limit block              | E x 1e2            | E x 1e3            | E x 1e4            | E x 1e6            | Housner block        |
/// |----------|--------------------------|--------------------|--------------------|--------------------|--------------------|----------------------|
/// | 1.0, 2.2 | up 0.16991, max 0.20561  | +0.0333, -0.0211   | +0.0011, +0.0006   | +0.0001, -0.0006   | +2.4e-5, -1.0e-4   | -0.0274, +0.0142     |
/// | 1.0, 2.5 | up 0.14010, ov at 2.3997 | -0.0286, ov -0.498 | -0.0047, ov -0.096 | +0.0002, ov +0.057 | +2.4e-5, ov +0.0064| -0.0196, ov -0.224   |
/// | 1.0, 4.0 | up 0.08001, ov at 1.4518 | +0.0002, ov +0.051 | -0.0019, ov +0.0057| +0.0007, ov +4.2e-4| +2.4e-5, ov +4.2e-5| -0.0094, ov +0.0017  |
/// | 1.0, 6.0 | up 0.05204, ov at 0.6609 | +0.0138, ov -0.027 | +0.0054, ov -1.8e-4| +0.0008, ov -2.2e-4| +2.5e-5, ov -1.0e-5| -0.0059, ov -6.3e-4  |
/// | 0.8, 3.0 | up 0.08883, max 0.68570  | -0.0052, overturns | -0.0051, -0.0157   | -0.0003, -0.0133   | +2.4e-5, -0.0023   | -0.0113, overturns   |
/// | 0.5, 4.0 | up 0.04001, max 0.24838  | +0.0187, -0.0098   | -0.0059, -0.0023   | -0.0002, -0.0007   | +2.4e-5, -6.6e-5   | -0.0047, -5e-5       |
///
/// The uplift times converge to 2 h/omega = h T/pi (2.47e-5 s at E x 1e6), the lag of the damped
/// pre-uplift oscillator behind the quasi-static state; on top of it is the transient that the
/// pulse's initial jerk starts, of relative size about (A/a_up)(T/Tp), which falls like
/// T ~ E^(-1/2) and oscillates in sign (hence E x 1e2 can be closer than E x 1e3 in one case).
/// The rocking motion inherits a velocity at uplift of order beta1 A (2 pi/Tp)/omega from that
/// transient, so max |q| and the overturning time also converge like E^(-1/2), slowest for the
/// runs that pass near the unstable position (0.8 s, 3.0 reaches 0.98 B; 1.0 s, 2.5 overturns
/// slowly after an impact). The tolerances below are the E x 1e4 values with a margin of 1.5 to 2.
/// Housner's block uplifts 0.005-0.027 s earlier than the limit block; for large pulses its
/// overturning time is close (within 0.002 s at A = 4 and 6), but near the thresholds it is not:
/// it overturns under the 0.8 s, 3.0 m/s^2 pulse, which neither the limit block nor the elastic
/// body from E x 1e3 on overturns, and overturns 0.22 s earlier under 1.0 s, 2.5 m/s^2.
#[test]
fn a_stiff_elastic_body_tends_to_the_elastic_limit_block() {
    use flexrock_core::model::{Model, Overrides};
    use flexrock_core::physics::automaton::EventKind;

    struct Case {
        period: f64,
        amplitude: f64,
        /// Largest |difference| at E x 1e4 allowed in the first uplift time, max |q| and the
        /// overturning time.
        uplift: f64,
        max_q: f64,
        overturn: f64,
    }
    let case = |period, amplitude, uplift, max_q, overturn| Case {
        period,
        amplitude,
        uplift,
        max_q,
        overturn,
    };
    let cases = [
        case(1.0, 2.2, 3e-4, 1e-3, 0.0),
        case(1.0, 2.5, 5e-4, 0.0, 0.1),
        case(1.0, 4.0, 1.5e-3, 0.0, 1e-3),
        case(1.0, 6.0, 1.5e-3, 0.0, 5e-4),
        case(0.8, 3.0, 6e-4, 0.02, 0.0),
        case(0.5, 4.0, 4e-4, 1.5e-3, 0.0),
    ];
    let scales = [1e2, 1e3, 1e4, 1e6];
    let limit = elastic_limit();
    let housner = housner();
    let duration = 6.0;
    // Largest |difference| over the cases, per scale: first uplift, max |q|, overturning time.
    let mut worst = [[0.0_f64; 3]; 4];
    for c in &cases {
        let pulse = SinePulse::new(c.amplitude, c.period, 1.0, PulseShape::Antisymmetric);
        let rigid = simulate_block(&limit, &pulse, duration).unwrap();
        let reference = simulate_block(&housner, &pulse, duration).unwrap();
        let rigid_up = rigid.first_uplift.unwrap();
        let housner_up = reference.first_uplift.unwrap() - rigid_up;
        for (i, scale) in scales.iter().enumerate() {
            let text = format!(
                "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\n\
                 youngs_modulus = {:e}\ndamping_ratio = 0.05\ngravity = 9.81\n\
                 [excitation]\nkind = \"sine-pulse\"\namplitude = {}\nperiod = {}\ncycles = 1\n\
                 shape = \"antisymmetric\"\n[simulation]\nduration = {duration}\n",
                5e6 * scale,
                c.amplitude,
                c.period
            );
            let model = Model::from_toml_str(&text, &Overrides::default()).unwrap();
            let elastic = flexrock_core::simulate::simulate(&model).unwrap();
            let up = elastic
                .events
                .iter()
                .find(|e| e.kind == EventKind::Uplift)
                .expect("the elastic body lifts off")
                .t
                - rigid_up;
            let max_q = elastic.max_q.value.max(-elastic.min_q.value) - rigid.max_abs_q;
            let overturn = match (elastic.t_overturn, rigid.t_overturn) {
                (Some(a), Some(b)) => a - b,
                _ => 0.0,
            };
            eprintln!(
                "Tp {} A {} E x {scale:e}: uplift {up:+.6} max|q| {max_q:+.6} overturn {overturn:+.6} \
                 (overturned {} / limit {}; Housner uplift {housner_up:+.6})",
                c.period, c.amplitude, elastic.overturned, rigid.overturned
            );
            worst[i][0] = worst[i][0].max(up.abs());
            worst[i][1] = worst[i][1].max(max_q.abs());
            worst[i][2] = worst[i][2].max(overturn.abs());
            if *scale >= 1e3 {
                assert_eq!(
                    elastic.overturned, rigid.overturned,
                    "Tp {} A {}",
                    c.period, c.amplitude
                );
            }
            if *scale >= 1e4 {
                // Every landing of the elastic body is followed by an uplift about the other toe:
                // the impacts of the rigid block.
                assert_eq!(elastic.count(EventKind::Landing), rigid.n_impact);
                assert!(
                    up.abs() < housner_up.abs() / 5.0,
                    "closer to the limit than Housner's"
                );
            }
            if *scale == 1e6 {
                // What is left is the damping lag 2 h/omega (2.47e-5 s here).
                let lag = model.constants.damping_coefficient;
                assert!((up - lag).abs() < 0.1 * lag, "uplift {up:e}, lag {lag:e}");
            }
            if *scale == 1e4 {
                let what = format!("Tp {} A {} at E x 1e4", c.period, c.amplitude);
                assert!(up.abs() < c.uplift, "{what}: uplift {up:e}");
                if !rigid.overturned {
                    assert!(max_q.abs() < c.max_q, "{what}: max |q| {max_q:e}");
                } else {
                    assert!(overturn.abs() < c.overturn, "{what}: overturn {overturn:e}");
                }
            }
        }
    }
    eprintln!(
        "largest differences (uplift, max |q|, overturn) at E x 1e2, 1e3, 1e4, 1e6: {worst:?}"
    );
    // Measured: uplift 0.0333, 0.0059, 0.00081, 2.5e-5 s; max |q| 0.0211, 0.0157, 0.0133, 0.0023 m;
    // overturn 0.498, 0.096, 0.057, 0.0064 s.
    for metric in 0..3 {
        for i in 1..scales.len() {
            assert!(
                worst[i][metric] < worst[i - 1][metric],
                "metric {metric} does not shrink from E x {:e} to E x {:e}: {worst:?}",
                scales[i - 1],
                scales[i]
            );
        }
    }
    assert!(
        worst[3][0] < 3e-5 && worst[3][1] < 3e-3 && worst[3][2] < 1e-2,
        "{worst:?}"
    );
}

/// A block, a pulse and a restitution of the property below.
#[derive(Debug, Clone, Copy)]
struct TwoRulesCase {
    slenderness: f64,
    height: f64,
    full: bool,
    restitution: f64,
    beta: f64,
    ratio: f64,
    cycles: usize,
    symmetric: bool,
}

/// The two rules of overturning (src/rigid.rs) see the same motion until the block first
/// reaches its limit: their events agree one for one, to the bit, up to the default rule's
/// overturn (or the whole run). A block that cannot return has overturned by the default rule
/// too: it reached the limit before it was judged lost, or its free motion carries it there
/// within the long tail.
fn two_rules_agree(case: TwoRulesCase) -> Result<(), proptest::test_runner::TestCaseError> {
    let TwoRulesCase {
        slenderness,
        height,
        full,
        restitution,
        beta,
        ratio,
        cycles,
        symmetric,
    } = case;
    let form = if full {
        RigidForm::Full
    } else {
        RigidForm::SmallAngle
    };
    let block = |rule| {
        RigidBlock::housner(height, slenderness * height, G)
            .unwrap()
            .with_form(form)
            .with_restitution(restitution)
            .unwrap()
            .with_overturning(rule)
    };
    let (limit_rule, papers) = (
        block(RigidOverturning::ReachesLimit),
        block(RigidOverturning::CannotReturn),
    );
    let p = limit_rule.frequency();
    let period = 2.0 * std::f64::consts::PI / (ratio * p);
    let shape = if symmetric {
        PulseShape::Symmetric
    } else {
        PulseShape::Antisymmetric
    };
    let floor = SinePulse::new(beta * G * slenderness, period, cycles as f64, shape);
    let duration = cycles as f64 * period + 60.0 / p;
    // A block whose restitution is near 1, under a pulse that barely lifts it, can chatter
    // (impacts ever closer in time, a Zeno sequence) until the event budget stops its run
    // with a message. Until the limit both rules are the same motion, so they stop alike;
    // the papers' rule may also go on past the limit and chatter there.
    let (a, b) = match (
        simulate_block(&limit_rule, &floor, duration),
        simulate_block(&papers, &floor, duration),
    ) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(a), Err(b)) => {
            proptest::prop_assert_eq!(a.to_string(), b.to_string());
            return Ok(());
        }
        (Ok(a), Err(flexrock_core::integrate::SolverError::Failed { t, message, .. })) => {
            proptest::prop_assert!(
                a.t_overturn.is_some_and(|limit| t >= limit),
                "the papers' rule stopped at t = {t} before the limit: {message}"
            );
            return Ok(());
        }
        (a, b) => {
            proptest::prop_assert!(false, "one rule failed: {:?} / {:?}", a.err(), b.err());
            unreachable!()
        }
    };
    let end = a.t_overturn.unwrap_or(duration);
    let before = |o: &RigidOutcome| -> Vec<(f64, RigidEventKind)> {
        o.events
            .iter()
            .filter(|e| e.t < end && e.kind != RigidEventKind::Overturn)
            .map(|e| (e.t, e.kind))
            .collect()
    };
    proptest::prop_assert_eq!(before(&a), before(&b));
    if b.overturned {
        proptest::prop_assert!(
            a.overturned,
            "lost by the papers' rule only: {:?}",
            b.events.last()
        );
    }
    Ok(())
}

/// The case a random search found: restitution 0.99933 under a pulse 1.0016 times the tipping
/// acceleration chatters into the event budget by both rules, at the same instant.
#[test]
fn a_block_that_chatters_stops_alike_by_both_rules() {
    let case = TwoRulesCase {
        slenderness: 0.05,
        height: 0.5,
        full: false,
        restitution: 0.9993260349997758,
        beta: 1.0015594207325826,
        ratio: 8.94399621512907,
        cycles: 1,
        symmetric: false,
    };
    two_rules_agree(case).unwrap();
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig {
        cases: 300,
        failure_persistence: None,
        rng_seed: crate::common::proptest_seed(20_261_127),
        ..proptest::prelude::ProptestConfig::default()
    })]

    /// [`two_rules_agree`] on random slender blocks of both forms, random restitutions, and
    /// one- or two-cycle pulses of either shape from below uplift to ten times it.
    #[test]
    fn the_two_rules_agree_until_the_limit_is_reached(
        slenderness in 0.05f64..0.4,
        height in 0.5f64..5.0,
        full in proptest::bool::ANY,
        restitution in 0.3f64..1.0,
        beta in 0.9f64..10.0,
        ratio in 0.5f64..10.0,
        cycles in 1usize..3,
        symmetric in proptest::bool::ANY,
    ) {
        two_rules_agree(TwoRulesCase {
            slenderness,
            height,
            full,
            restitution,
            beta,
            ratio,
            cycles,
            symmetric,
        })?;
    }
}
