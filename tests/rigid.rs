//! The rigid block (src/rigid.rs) against closed forms of Housner's slender block. In q = theta H
//! units, rocking right: q'' = k^2 (q - B) - (3/2) a, k^2 = 3 g/(2 H); with x = q - B and a
//! constant floor acceleration the motion is x = x_e + (x0 - x_e) cosh(k t) + (v0/k) sinh(k t),
//! x_e = 3 a/(2 k^2) = a H/g, from which every expected value below is derived.

use flexrock::excitation::{FloorMotion, Free, Harmonic, PulseShape, SinePulse};
use flexrock::rigid::{
    simulate, simulate_from, RigidBlock, RigidEventKind, RigidOutcome, RigidPhase, RigidSettings,
};
use flexrock::solver::InitialState;

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
    // e = 1 - 1.5 sin^2(alpha) (MODEL.md eq. A7).
    assert!((b.restitution() - (1.0 - 1.5 * alpha.sin().powi(2))).abs() < 1e-15);
    assert!((b.restitution() - 0.955_427_531_837_477).abs() < 1e-14);
    assert!((b.uplift_acceleration() - G * B / H).abs() < 1e-15);
    let l = flexrock::constants::MODE_ROOT;
    let sigma = (l.cosh() + l.cos()) / (l.sinh() + l.sin());
    let factor = l.powi(3) / (8.0 * sigma);
    assert!((elastic_limit().uplift_acceleration() - factor * G * B / H).abs() < 1e-14);
    assert!((b.overturning_velocity() - k() * B).abs() < 1e-15);
}

/// A floor acceleration that is `value` from t = 0 on.
struct Constant(f64);

impl FloorMotion for Constant {
    fn acceleration(&self, t: f64) -> f64 {
        if t >= 0.0 {
            self.0
        } else {
            0.0
        }
    }
    fn peak_acceleration(&self) -> f64 {
        self.0.abs()
    }
    fn kind(&self) -> &'static str {
        "constant"
    }
    fn parameters(&self) -> serde_json::Value {
        serde_json::json!({ "kind": "constant", "value": self.0 })
    }
}

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

fn first(outcome: &RigidOutcome, kind: RigidEventKind) -> &flexrock::rigid::RigidEvent {
    outcome
        .events
        .iter()
        .find(|e| e.kind == kind)
        .unwrap_or_else(|| panic!("no {kind:?} in {:?}", outcome.events))
}

/// (1) Free rocking from q0 at rest reaches q = 0 at (1/k) acosh(1/(1 - q0/B)) (MODEL.md 7),
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
            let o = simulate(&block, &Constant(-sign * 0.999 * a_up), 5.0).unwrap();
            assert_eq!(o.n_uplift, 0);
            assert_eq!(o.final_state.phase, RigidPhase::Rest);
            assert_eq!(o.max_abs_q, 0.0);

            let o = simulate(&block, &Constant(-sign * 1.001 * a_up), 0.5).unwrap();
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
        let o = simulate(
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
        let o = simulate(&block, &Harmonic { amplitude, period }, 0.5).unwrap();
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
            let o = simulate(&block, &Constant(-c), 10.0).unwrap();
            let t = o.t_overturn.expect("overturns");
            assert!(
                (t - t_ov).abs() < 1e-12 * t_ov,
                "c = {c}: {t} against {t_ov}"
            );
            assert_eq!(o.n_uplift, 1);
            assert_eq!(o.n_impact, 0);

            let t = 0.7 * t_ov;
            let o = simulate(&block, &Constant(-c), t).unwrap();
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
        if settle_predicted.is_none() && remaining_bound <= flexrock::rigid::ZENO_TIME {
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
    assert!(accumulation - settle.t < flexrock::rigid::ZENO_TIME);
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
                    &RigidSettings { max_step: h },
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
        let err = simulate(&housner(), &Free, x).unwrap_err();
        assert!(err.is_input_error(), "{err}");
    }
    let err = RigidBlock::housner(H, H, G).unwrap_err();
    assert!(err.to_string().contains("slender"), "{err}");
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
            &RigidSettings { max_step: h },
        )
        .unwrap_err();
        assert!(err.is_input_error(), "{err}");
    }
    let err = simulate(&housner(), &Constant(1e6), 1.0).unwrap_err();
    assert!(err.to_string().contains("20 g"), "{err}");
    // A floor that is not a number ends the run with an error, not a panic or a hang.
    let err = simulate(&housner(), &Nan, 1.0).unwrap_err();
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
}
