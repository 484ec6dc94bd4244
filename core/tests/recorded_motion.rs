//! A sampled floor motion, piecewise linear between samples, against the exact solution of the
//! linear oscillator under piecewise-linear forcing (the Nigam-Jennings recurrence).

use crate::common;

use flexrock_core::floor::{FloorMotion, RecordedMotion};
use flexrock_core::integrate::adaptive::{solve, AdaptiveMethod, AdaptiveSettings};
use flexrock_core::integrate::{History, InitialState};
use flexrock_core::physics::automaton::Automaton;

/// Exact response of q'' + 2 h w q' + w^2 q = -beta a(t), a linear on each [k dt, (k+1) dt].
fn exact_response(w: f64, h: f64, beta: f64, dt: f64, a: &[f64], t_end: f64) -> Vec<(f64, f64)> {
    let wd = w * (1.0 - h * h).sqrt();
    let (mut q, mut v) = (0.0, 0.0);
    let mut out = vec![(0.0, 0.0)];
    let n = ((t_end / dt).round() as usize).min(a.len() - 1);
    for k in 0..n {
        // Forcing f0 + f1 tau on this interval; particular solution c0 + c1 tau.
        let f0 = -beta * a[k];
        let f1 = -beta * (a[k + 1] - a[k]) / dt;
        let c1 = f1 / (w * w);
        let c0 = (f0 - 2.0 * h * w * c1) / (w * w);
        // Homogeneous part from the interval's initial state.
        let (x0, x1) = (q - c0, v - c1);
        let b = (x1 + h * w * x0) / wd;
        let decay = (-h * w * dt).exp();
        let (c, s) = ((wd * dt).cos(), (wd * dt).sin());
        q = c0 + c1 * dt + decay * (x0 * c + b * s);
        v = c1 + decay * ((-h * w) * (x0 * c + b * s) + (-x0 * wd * s + b * wd * c));
        out.push(((k + 1) as f64 * dt, q));
    }
    out
}

#[test]
fn sampled_motion_matches_the_exact_piecewise_linear_response() {
    let model = common::model(&common::reference_body(
        "[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\n",
    ));
    let c = &model.constants;
    let automaton = Automaton::new(c);
    // A weak, irregular record (sum of incommensurate sines), sampled every 0.01 s for 8 s.
    let dt = 0.01;
    let samples: Vec<f64> = (0..=800)
        .map(|k| {
            let t = k as f64 * dt;
            0.25 * (2.3 * t).sin() + 0.2 * (7.1 * t + 0.3).sin() + 0.1 * (13.0 * t).cos()
        })
        .collect();
    let record = RecordedMotion::new("synthetic".into(), dt, samples.clone());
    assert_eq!(record.breakpoints().len(), samples.len());
    let exact = exact_response(c.omega, 0.05, c.beta1, dt, &samples, 8.0);
    for method in [AdaptiveMethod::Bdf, AdaptiveMethod::Esdirk34] {
        let settings = AdaptiveSettings {
            method,
            rtol: 1e-10,
            atol: 1e-12,
            output_dt: dt,
        };
        let sol = solve(
            &automaton,
            &record,
            InitialState { q: 0.0, qdot: 0.0 },
            8.0,
            &settings,
            History::Sampled,
        )
        .unwrap();
        assert!(sol.events.is_empty(), "weak enough not to uplift");
        let mut worst: f64 = 0.0;
        for (s, (t, q)) in sol.samples.iter().zip(&exact) {
            assert!((s.t - t).abs() < 1e-12);
            worst = worst.max((s.q - q).abs());
        }
        assert!(worst < 1e-9, "{method:?}: max |q - exact| = {worst:e} m");
    }
}

#[test]
fn after_the_record_the_floor_is_at_rest() {
    let record = RecordedMotion::new("r".into(), 0.5, vec![0.0, 1.0, -2.0]);
    assert_eq!(record.acceleration(0.25), 0.5);
    assert_eq!(record.acceleration(0.75), -0.5);
    assert_eq!(record.acceleration(1.0), -2.0);
    assert_eq!(record.acceleration(1.0 + 1e-9), 0.0);
    assert_eq!(record.acceleration(-0.1), 0.0);
}
