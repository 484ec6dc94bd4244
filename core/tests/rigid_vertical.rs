//! The rigid block on a floor that also moves vertically: gravity becomes g + a_v(t) in its
//! equation, its uplift acceleration and its pull towards the floor.
//!
//! The expected values are independent calculations written here: the first uplift by bisection
//! of |a(t)| = (g B/H)(1 + a_v(t)/g), the rocking by a plain fourth-order Runge-Kutta
//! integration in theta (rad) at a step of 1e-5 s with its own event handling, of
//! theta'' = -p^2 [(1 + a_v/g) sin(s alpha - theta) + (a/g) cos(s alpha - theta)] (the full
//! form) and of q'' = k^2 (1 + a_v/g)(q - s B) - (3/2) a (the small-angle form), and the closed
//! form scaling of a constant a_v, which is the same block under gravity g + a_v.

use flexrock_core::bodies::rigid::{
    simulate_shaken, RigidBlock, RigidEventKind, RigidForm, RigidOutcome, RigidSettings,
};
use flexrock_core::floor::{FloorMotion, PulseShape, Shaking, Shape, SinePulse};
use flexrock_core::integrate::InitialState;
use flexrock_core::model::{Model, Overrides};

use crate::common::Constant;

const H: f64 = 2.0;
const B: f64 = 0.4;
const G: f64 = 9.81;
const DURATION: f64 = 2.5;

fn horizontal() -> SinePulse {
    SinePulse::new(4.0, 0.5, 1.0, PulseShape::Antisymmetric)
}

fn vertical() -> SinePulse {
    SinePulse::new(3.0, 0.3, 2.0, PulseShape::Antisymmetric)
}

fn run(form: RigidForm, gravity: f64, v: Option<&dyn FloorMotion>) -> RigidOutcome {
    let block = RigidBlock::housner(H, B, gravity).unwrap().with_form(form);
    let h = horizontal();
    simulate_shaken(
        &block,
        &Shaking::new(&h, v),
        InitialState { q: 0.0, qdot: 0.0 },
        DURATION,
        &RigidSettings::for_block(&block),
    )
    .unwrap()
}

fn impacts(outcome: &RigidOutcome) -> Vec<(f64, f64)> {
    outcome
        .events
        .iter()
        .filter(|e| e.kind == RigidEventKind::Impact)
        .map(|e| (e.t, e.qdot_after))
        .collect()
}

/// The first time |a| exceeds (g B/H)(1 + a_v/g), by a scan at 1e-4 s and bisection.
fn first_uplift(a: impl Fn(f64) -> f64, a_v: impl Fn(f64) -> f64) -> f64 {
    let lifts = |t: f64| a(t).abs() > G * B / H * (1.0 + a_v(t) / G);
    let mut t = 0.0;
    while !lifts(t + 1e-4) {
        t += 1e-4;
    }
    let (mut lo, mut hi) = (t, t + 1e-4);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if lifts(mid) {
            hi = mid
        } else {
            lo = mid
        }
    }
    hi
}

/// The impacts (time, q' after in q = theta H units) of the block from its first uplift to
/// DURATION, by RK4 at `step` of x'' = f(t, x, side), x in the equation's own variable (theta or
/// q), `scale` its ratio to q; an impact where x crosses 0, located by bisection of one RK4
/// step from the step's start.
fn reference_impacts(
    accel: impl Fn(f64, f64, f64) -> f64,
    uplift_t: f64,
    side0: f64,
    restitution: f64,
    scale: f64,
    step: f64,
) -> Vec<(f64, f64)> {
    let rk4 = |t: f64, x: f64, v: f64, side: f64, h: f64| {
        let f = |t: f64, x: f64, v: f64| (v, accel(t, x, side));
        let (k1x, k1v) = f(t, x, v);
        let (k2x, k2v) = f(t + h / 2.0, x + h / 2.0 * k1x, v + h / 2.0 * k1v);
        let (k3x, k3v) = f(t + h / 2.0, x + h / 2.0 * k2x, v + h / 2.0 * k2v);
        let (k4x, k4v) = f(t + h, x + h * k3x, v + h * k3v);
        (
            x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x),
            v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v),
        )
    };
    let (mut t, mut x, mut v, mut side) = (uplift_t, 0.0, 0.0, side0);
    let mut out = Vec::new();
    while t < DURATION {
        let h = step.min(DURATION - t);
        let (x1, v1) = rk4(t, x, v, side, h);
        if t > uplift_t && side * x1 < 0.0 {
            let (mut lo, mut hi) = (0.0, h);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if side * rk4(t, x, v, side, mid).0 < 0.0 {
                    hi = mid
                } else {
                    lo = mid
                }
            }
            let vi = rk4(t, x, v, side, hi).1;
            t += hi;
            x = 0.0;
            v = restitution * vi;
            side = -side;
            out.push((t, v * scale));
            continue;
        }
        t += h;
        x = x1;
        v = v1;
    }
    out
}

fn assert_close(found: &[(f64, f64)], expected: &[(f64, f64)], tol: f64) {
    assert_eq!(
        found.len(),
        expected.len(),
        "{found:?} against {expected:?}"
    );
    assert!(!expected.is_empty());
    for (f, e) in found.iter().zip(expected) {
        assert!((f.0 - e.0).abs() < tol, "t {} against {}", f.0, e.0);
        assert!((f.1 - e.1).abs() < tol * 10.0, "q' {} against {}", f.1, e.1);
    }
}

#[test]
fn the_full_block_under_vertical_shaking_matches_an_independent_integration() {
    let (h, v) = (horizontal(), vertical());
    let outcome = run(RigidForm::Full, G, Some(&v));
    let t_up = first_uplift(|t| h.acceleration(t), |t| v.acceleration(t));
    assert!((outcome.first_uplift.unwrap() - t_up).abs() < 1e-12);
    let alpha = (B / H).atan();
    let p2 = 3.0 * G / (2.0 * (H * H + B * B).sqrt());
    let e = 1.0 - 1.5 * alpha.sin().powi(2);
    let side0 = -h.acceleration(t_up).signum();
    let expected = reference_impacts(
        |t, theta, s| {
            let angle = s * alpha - theta;
            -p2 * ((1.0 + v.acceleration(t) / G) * angle.sin()
                + h.acceleration(t) / G * angle.cos())
        },
        t_up,
        side0,
        e,
        H,
        1e-5,
    );
    assert_close(&impacts(&outcome), &expected, 1e-9);
    // The vertical motion matters: without it the impacts move by far more than that.
    let still = impacts(&run(RigidForm::Full, G, None));
    assert!((still[0].0 - expected[0].0).abs() > 1e-3);
}

#[test]
fn the_small_angle_block_under_vertical_shaking_matches_an_independent_integration() {
    let (h, v) = (horizontal(), vertical());
    let outcome = run(RigidForm::SmallAngle, G, Some(&v));
    let t_up = first_uplift(|t| h.acceleration(t), |t| v.acceleration(t));
    assert!((outcome.first_uplift.unwrap() - t_up).abs() < 1e-12);
    let k2 = 1.5 * G / H;
    let e = (2.0 * H * H - B * B) / (2.0 * (H * H + B * B));
    let side0 = -h.acceleration(t_up).signum();
    let expected = reference_impacts(
        |t, q, s| k2 * (1.0 + v.acceleration(t) / G) * (q - s * B) - 1.5 * h.acceleration(t),
        t_up,
        side0,
        e,
        1.0,
        1e-5,
    );
    assert_close(&impacts(&outcome), &expected, 1e-9);
}

#[test]
fn a_constant_vertical_acceleration_is_the_same_block_under_gravity_g_plus_a_v() {
    for form in [RigidForm::SmallAngle, RigidForm::Full] {
        for c in [-3.0, 2.5] {
            let shaken = run(form, G, Some(&Constant(c)));
            let heavier = run(form, G + c, None);
            assert!((shaken.first_uplift.unwrap() - heavier.first_uplift.unwrap()).abs() < 1e-12);
            assert_eq!(shaken.overturned, heavier.overturned, "{form:?} {c}");
            assert_close(&impacts(&shaken), &impacts(&heavier), 1e-9);
            assert!((shaken.max_abs_q - heavier.max_abs_q).abs() < 1e-9);
        }
    }
    // A Shape is what the exact solver reads; a constant is a polynomial of degree 0.
    assert!(matches!(
        Constant(1.0).closed_form(0.0).shape,
        Shape::Polynomial { degree: 0, .. }
    ));
}

const MODEL: &str = r#"
[body]
height = 2.0
width = 0.4
mass = 1000.0
period = 0.05

[excitation]
kind = "sine-pulse"
amplitude = 4.0
period = 0.5
tail = 2.0
"#;

fn model(vertical: &str) -> Result<Model, flexrock_core::Error> {
    Model::from_toml_str(&format!("{MODEL}{vertical}"), &Overrides::default())
}

#[test]
fn a_vertical_motion_of_zero_is_none_and_changes_nothing() {
    let plain = model("").unwrap();
    let zero = model("\n[excitation.vertical]\nratio = 0.0\n").unwrap();
    assert!(zero.vertical.is_none());
    for still in [
        "kind = \"free\"",
        "kind = \"harmonic\"\namplitude = 0.0\nperiod = 0.3",
    ] {
        let m = model(&format!("\n[excitation.vertical]\n{still}\n")).unwrap();
        assert!(m.vertical.is_none(), "{still}");
    }
    let block = RigidBlock::housner(H, B, G)
        .unwrap()
        .with_form(RigidForm::Full);
    let (a, b) = (
        flexrock_core::simulate_rigid(&plain, &block).unwrap(),
        flexrock_core::simulate_rigid(&zero, &block).unwrap(),
    );
    assert_eq!(format!("{:?}", a.events), format!("{:?}", b.events));
    // The elastic body runs as before.
    let (a, b) = (
        flexrock_core::simulate(&plain).unwrap(),
        flexrock_core::simulate(&zero).unwrap(),
    );
    assert_eq!(format!("{:?}", a.events), format!("{:?}", b.events));
}

#[test]
fn a_ratio_scales_the_horizontal_motion() {
    let m = model("\n[excitation.vertical]\nratio = -0.5\n").unwrap();
    let v = m.vertical.as_ref().unwrap();
    for t in [0.01, 0.13, 0.37, 0.6] {
        assert_eq!(v.acceleration(t), -0.5 * m.floor.acceleration(t));
    }
}

#[test]
fn a_floor_falling_faster_than_gravity_is_refused_with_the_time_it_starts() {
    // a_v = 3.5 x 4 sin(2 pi t/0.5) reaches -g first at t = (0.5/2 pi)(pi + asin(9.81/14)).
    let text = model("\n[excitation.vertical]\nratio = 3.5\n")
        .err()
        .expect("refused")
        .to_string();
    let t = 0.5 / (2.0 * std::f64::consts::PI) * (std::f64::consts::PI + (G / 14.0).asin());
    assert!(text.contains("excitation.vertical"), "{text}");
    assert!(text.contains("-g = -9.81 m/s^2"), "{text}");
    assert!(text.contains(&format!("{t:.9}")[..8]), "{t} in {text}");
    // Just within gravity it runs.
    assert!(model("\n[excitation.vertical]\nratio = 2.45\n").is_ok());
}

#[test]
fn the_elastic_body_refuses_vertical_motion_by_name() {
    let m = model("\n[excitation.vertical]\nratio = 0.5\n").unwrap();
    let text = flexrock_core::simulate(&m).unwrap_err().to_string();
    assert!(
        text.contains("excitation.vertical") && text.contains("rigid"),
        "{text}"
    );
}

#[test]
fn the_vertical_table_names_its_own_keys() {
    for (table, key) in [
        ("kind = \"ratio\"", "excitation.vertical.ratio"),
        (
            "ratio = 0.5\namplitude = 2.0",
            "excitation.vertical.amplitude",
        ),
        (
            "kind = \"harmonic\"\namplitude = 2.0",
            "excitation.vertical.period",
        ),
        ("kind = \"sine\"", "excitation.vertical.kind"),
        ("ratio = nan", "excitation.vertical.ratio"),
    ] {
        let text = model(&format!("\n[excitation.vertical]\n{table}\n"))
            .err()
            .expect("refused")
            .to_string();
        assert!(text.contains(key), "{table}: {text}");
    }
    let text = Model::from_toml_str(
        &MODEL.replace("kind = \"sine-pulse\"", "kind = \"ratio\""),
        &Overrides::default(),
    )
    .err()
    .expect("refused")
    .to_string();
    assert!(
        text.contains("excitation.kind") && text.contains("vertical"),
        "{text}"
    );
}

#[test]
fn a_record_pair_runs_for_the_longer_record_with_each_its_own_scale() {
    let h = crate::common::workspace_file("validation/records/elCentro.AT2");
    let v = crate::common::workspace_file("validation/records/A-ELC180.AT2");
    let text = format!(
        "[body]\nheight = 2.0\nwidth = 0.3\nmass = 1000.0\nperiod = 0.05\n\n\
         [excitation]\nkind = \"record\"\npath = {h:?}\n\n\
         [excitation.vertical]\nkind = \"record\"\npath = {v:?}\nscale = 0.5\n"
    );
    let m = Model::from_toml_str(&text, &Overrides::default()).unwrap();
    // 1559 samples at 0.02 s and 4000 at 0.01 s (their headers).
    assert_eq!(m.duration, 39.99);
    let vertical = m.vertical.as_ref().unwrap();
    // The vertical record is the same record read as a horizontal one, at half its scale.
    let horizontal_reading = Model::from_toml_str(
        &format!(
            "[body]\nheight = 2.0\nwidth = 0.3\nmass = 1000.0\nperiod = 0.05\n\n\
             [excitation]\nkind = \"record\"\npath = {v:?}\n"
        ),
        &Overrides::default(),
    )
    .unwrap();
    for t in [1.0, 8.59, 20.005] {
        assert_eq!(
            vertical.acceleration(t),
            0.5 * horizontal_reading.floor.acceleration(t)
        );
    }
}
