//! The Newmark solver: second-order convergence to the closed form before uplift, convergence to
//! the adaptive reference with events, the stability limit, and the compare/converge files.

use crate::common;

use crate::common::{flexrock, reference_model};

use std::path::Path;

use flexrock::commands::compare::compare;
use flexrock_core::integrate::SolverSettings;
use flexrock_core::model::{Model, Overrides};

/// Max |q - closed form| over the step ends of a Newmark run on a harmonic too weak to uplift.
fn closed_form_error(beta: f64, dt: f64) -> f64 {
    let text = common::reference_body(&format!(
        "[excitation]\nkind = \"harmonic\"\namplitude = 0.3\nperiod = 1.0\n\
         [simulation]\nduration = 6.0\n[solver]\nmethod = \"newmark\"\ndt = {dt}\n\
         newmark_beta = {beta}\noutput_dt = 0.04\n"
    ));
    let model = common::model(&text);
    let sol = flexrock::commands::run::simulate(&model).unwrap();
    assert!(sol.events.is_empty(), "too weak to uplift");

    // q'' + 2 h w q' + w^2 q = -beta1 A sin(W t), q(0) = q'(0) = 0: closed form.
    let c = &model.constants;
    let exact = common::damped_oscillator_response(c.omega, 0.05, c.beta1, 0.3, 1.0);
    sol.samples
        .iter()
        .map(|s| (s.q - exact(s.t)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn linear_acceleration_and_average_acceleration_converge_at_second_order() {
    for beta in [1.0 / 6.0, 0.25] {
        let errors: Vec<f64> = [0.04, 0.02, 0.01, 0.005]
            .iter()
            .map(|&dt| closed_form_error(beta, dt))
            .collect();
        for pair in errors.windows(2) {
            let order = (pair[0] / pair[1]).log2();
            assert!(
                (1.9..2.2).contains(&order),
                "beta = {beta}: errors {errors:?}, observed order {order}"
            );
        }
        assert!(errors[3] < 1e-4, "beta = {beta}: errors {errors:?}");
    }
}

/// The paper's example over 4 s (12+ events) with a reference and Newmark runs at `dts`.
fn event_errors(variant: &str, dts: &[f64]) -> Vec<(f64, f64, f64)> {
    let overrides = Overrides {
        duration: Some(4.0),
        ..Overrides::default()
    };
    let model = Model::load(&reference_model(), &overrides).unwrap();
    let reference = flexrock::commands::run::simulate_with(
        &model,
        &SolverSettings::Adaptive(model.reference_settings(1e-11).unwrap()),
    )
    .unwrap();
    assert!(reference.events.len() >= 12);
    dts.iter()
        .map(|&dt| {
            let settings = model.newmark_settings(Some(dt), Some(variant)).unwrap();
            let sol =
                flexrock::commands::run::simulate_with(&model, &SolverSettings::Newmark(settings))
                    .unwrap();
            let c = compare(&reference, &sol, model.solver.output_dt(), 0.3);
            assert_eq!(
                c.events.n_missed + c.events.n_spurious,
                0,
                "{variant} dt = {dt}"
            );
            (dt, c.events.max_abs_time_difference, c.peaks.peak_error)
        })
        .collect()
}

fn fitted_order(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let mx = points.iter().map(|p| p.0.ln()).sum::<f64>() / n;
    let my = points.iter().map(|p| p.1.ln()).sum::<f64>() / n;
    let sxy: f64 = points
        .iter()
        .map(|p| (p.0.ln() - mx) * (p.1.ln() - my))
        .sum();
    let sxx: f64 = points.iter().map(|p| (p.0.ln() - mx).powi(2)).sum();
    sxy / sxx
}

#[test]
fn with_events_newmark_converges_to_the_reference() {
    let dts = [0.005, 0.0025, 0.00125, 0.000625];
    let substep = event_errors("substep", &dts);
    let compensate = event_errors("compensate", &dts);
    // Sub-stepping is second order. Compensation changes mode up to one step late, so it is
    // first order, and its error depends on where the crossing falls within the step: its fitted
    // slope wanders between about 0.7 and 1 over short ranges of dt, while error / dt stays bounded.
    for (name, errors, least) in [("substep", &substep, 1.5), ("compensate", &compensate, 0.6)] {
        let times: Vec<(f64, f64)> = errors.iter().map(|e| (e.0, e.1)).collect();
        let peaks: Vec<(f64, f64)> = errors.iter().map(|e| (e.0, e.2)).collect();
        let (p_t, p_peak) = (fitted_order(&times), fitted_order(&peaks));
        assert!(
            p_t >= least && p_peak >= least,
            "{name}: {errors:?}: orders {p_t}, {p_peak}"
        );
        // First order at least: the error per unit dt does not grow as dt shrinks.
        let (first_t, first_peak) = (errors[0].1 / errors[0].0, errors[0].2 / errors[0].0);
        for e in errors {
            assert!(
                e.1 / e.0 <= 3.0 * first_t && e.2 / e.0 <= 3.0 * first_peak,
                "{name}: errors per unit dt grow: {e:?}"
            );
        }
    }
    // Sub-stepping to the crossing is at least as accurate as compensating at the step end.
    for (s, c) in substep.iter().zip(&compensate) {
        assert!(
            s.1 <= c.1 && s.2 <= c.2,
            "substep {s:?} vs compensate {c:?}"
        );
    }
}

#[test]
fn a_step_beyond_the_stability_limit_is_refused() {
    let base = common::reference_body(
        "[excitation]\nkind = \"harmonic\"\namplitude = 0.3\nperiod = 1.0\n\
         [simulation]\nduration = 6.0\n[solver]\nmethod = \"newmark\"\n",
    );
    // T = 1.55 s: linear acceleration is stable for dt < 0.5513 T = 0.8545 s.
    let text = format!("{base}dt = 0.86\n");
    let err = match Model::from_toml_str(&text, &Overrides::default()) {
        Ok(_) => panic!("dt = 0.86 s accepted"),
        Err(e) => e.to_string(),
    };
    for word in ["solver.dt", "0.86", "stable only for dt <", "0.5513 T"] {
        assert!(err.contains(word), "expected {word:?} in: {err}");
    }
    assert!(Model::from_toml_str(&format!("{base}dt = 0.85\n"), &Overrides::default()).is_ok());
    // Average acceleration (beta = 1/4) is unconditionally stable.
    let text = format!("{base}dt = 0.86\nnewmark_beta = 0.25\n");
    assert!(Model::from_toml_str(&text, &Overrides::default()).is_ok());

    // On the command line: exit code 2, the flag named, nothing written.
    let dir = common::scratch_dir("newmark-unstable");
    let out = dir.join("out");
    let o = flexrock(&[
        "compare",
        reference_model().to_str().unwrap(),
        "--dt",
        "0.9",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--dt = 0.9") && stderr.contains("stable"),
        "{stderr}"
    );
    assert!(!out.exists());
}

#[test]
fn keys_of_the_other_method_are_errors() {
    let base = common::reference_body(
        "[excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\nq0 = 0.05\n[solver]\n",
    );
    for (section, key) in [
        ("method = \"bdf\"\ndt = 0.02\n", "solver.dt"),
        (
            "method = \"esdirk34\"\nnewmark_beta = 0.25\n",
            "solver.newmark_beta",
        ),
        ("newmark_variant = \"substep\"\n", "solver.newmark_variant"),
        ("method = \"newmark\"\nrtol = 1e-6\n", "solver.rtol"),
        ("method = \"newmark\"\natol = 1e-9\n", "solver.atol"),
        (
            "method = \"newmark\"\nnewmark_variant = \"exact\"\n",
            "solver.newmark_variant",
        ),
        (
            "method = \"newmark\"\nnewmark_gamma = 0.4\n",
            "solver.newmark_gamma",
        ),
        ("method = \"newmark\"\ndt = 0.0\n", "solver.dt"),
    ] {
        let text = format!("{base}{section}");
        match Model::from_toml_str(&text, &Overrides::default()) {
            Ok(_) => panic!("accepted: {section}"),
            Err(e) => assert!(e.to_string().contains(key), "{key} not named in: {e}"),
        }
    }
}

#[test]
fn run_with_newmark_writes_the_usual_files() {
    let out = common::scratch_dir("newmark-run").join("result");
    let o = common::run_reference(
        &out,
        &[
            "--method",
            "newmark",
            "--dt",
            "0.02",
            "--variant",
            "substep",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["solver"]["method"], "newmark");
    assert_eq!(summary["solver"]["dt"], 0.02);
    assert_eq!(summary["solver"]["newmark_variant"], "substep");
    assert_eq!(summary["statistics"]["method"], "newmark-substep");
    assert_eq!(summary["n_uplift"], 11);
}

fn header(path: &Path) -> String {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .to_string()
}

#[test]
fn compare_writes_its_files_with_stable_columns() {
    let out = common::scratch_dir("newmark-compare").join("result");
    let o = flexrock(&[
        "compare",
        reference_model().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("matched") && stdout.contains("max q"),
        "{stdout}"
    );
    assert_eq!(
        header(&out.join("compare.csv")),
        "index,kind,from,to,t_reference,t_newmark,t_difference,q_reference,q_newmark,qdot_after_reference,qdot_after_newmark"
    );
    assert_eq!(
        header(&out.join("compare_history.csv")),
        "t,q_reference,q_newmark,q_difference,s_reference,s_newmark,r_reference,r_newmark,qdot_reference,qdot_newmark"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("compare.json")).unwrap()).unwrap();
    for key in [
        "n_matched",
        "n_missed",
        "n_spurious",
        "max_abs_time_difference",
    ] {
        assert!(summary["comparison"]["events"].get(key).is_some(), "{key}");
    }
    assert!(summary["comparison"]["peaks"]["peak_error"]
        .as_f64()
        .is_some());
    assert!(summary["comparison"]["grid"]["rms_q_difference"]
        .as_f64()
        .is_some());
    assert!(summary["reference"]["findings"]["s_never_exceeds_s_n"]
        .as_bool()
        .unwrap());
    assert_eq!(
        summary["newmark"]["solver"]["newmark_variant"],
        "compensate"
    );
    let svg = std::fs::read_to_string(out.join("compare.svg")).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("s (m)") && svg.contains("(d)"));
}

#[test]
fn converge_writes_its_files_with_stable_columns() {
    let out = common::scratch_dir("newmark-converge").join("result");
    let o = flexrock(&[
        "converge",
        reference_model().to_str().unwrap(),
        "--dt",
        "0.02,0.01",
        "--rtol",
        "1e-4,1e-6",
        "--duration",
        "2.0",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("orders against dt"), "{stdout}");
    assert!(stdout.contains("efficiency slope"), "{stdout}");
    let table = std::fs::read_to_string(out.join("convergence.csv")).unwrap();
    let mut lines = table.lines();
    assert_eq!(
        lines.next().unwrap(),
        "method,dt,rtol,max_q_error,max_event_time_error,peak_error,event_count_difference,unmatched_events,steps,rhs_evaluations,wall_time_s,max_energy_residual,status"
    );
    // 2 Newmark variants x 2 steps + 4 adaptive methods x 2 tolerances.
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 12, "{table}");
    assert!(rows[0].starts_with("newmark-compensate,0.02,,"));
    assert!(rows.iter().all(|r| r.ends_with(",ok")), "{table}");
    for name in [
        "convergence.json",
        "convergence_dt.svg",
        "convergence_work.svg",
    ] {
        assert!(out.join(name).exists(), "{name}");
    }
}

/// The sine-pulse model under sub-stepping Newmark at dt = 0.02 s with the pulse amplitude `a`.
fn substep_pulse(
    amplitude: f64,
) -> flexrock_core::error::Result<flexrock_core::integrate::solution::Solution> {
    let overrides = Overrides {
        method: Some("newmark".into()),
        dt: Some(0.02),
        newmark_variant: Some("substep".into()),
        settings: vec![flexrock_core::model::Setting::number(
            "excitation.amplitude",
            amplitude,
        )],
        ..Overrides::default()
    };
    let model = Model::load(&common::repo("models/sine-pulse.toml"), &overrides)?;
    flexrock::commands::run::simulate(&model)
}

#[test]
fn substep_resolves_an_uplift_and_landing_inside_one_step() {
    // Near 1.328 m/s^2 the pulse just reaches s_n: the body lifts off and lands again within
    // one 0.02 s step. Both events lie inside the step, in order, on the guard, each with q'
    // pointing across its guard; the landing is not taken back at the uplift's instant.
    let sol = substep_pulse(1.32813).expect("a grazing uplift is valid input");
    let s_n = 0.152365; // MODEL: 0.15237 m for the reference body
    assert!(sol.events.len() >= 2, "{:?}", sol.events);
    assert_eq!(common::event_against_its_direction(&sol), None);
    for pair in sol.events.windows(2) {
        assert!(pair[1].t > pair[0].t, "events at one instant: {pair:?}");
    }
    for e in &sol.events {
        assert!((e.q.abs() - s_n).abs() < 1e-5, "event off the guard: {e:?}");
    }
}

#[test]
fn substep_runs_every_amplitude_around_grazing_uplift() {
    // 200 amplitudes in [1.30, 1.36] m/s^2 straddle the smallest one that lifts the body.
    let mut failed = Vec::new();
    let mut lifted = 0;
    for i in 0..200 {
        let amplitude = 1.30 + 0.06 * i as f64 / 199.0;
        match substep_pulse(amplitude) {
            Ok(sol) => {
                lifted += usize::from(!sol.events.is_empty());
                if let Some(e) = common::event_against_its_direction(&sol) {
                    failed.push(format!("{amplitude}: {e}"));
                }
            }
            Err(e) => failed.push(format!("{amplitude}: {e}")),
        }
    }
    assert!(failed.is_empty(), "{} failed: {failed:#?}", failed.len());
    assert!(
        lifted > 0 && lifted < 200,
        "the range must straddle grazing ({lifted} lifted)"
    );
}

#[test]
fn converge_refuses_a_reference_no_tighter_than_its_cases() {
    // Against a reference at 1e-3, cases at 1e-4 and 1e-8 would show the reference's error.
    let dir = common::scratch_dir("converge-loose-reference");
    let model = reference_model();
    let out = dir.join("out");
    let o = flexrock(&[
        "converge",
        model.to_str().unwrap(),
        "--reference-rtol",
        "1e-3",
        "--rtol",
        "1e-4,1e-8",
        "--dt",
        "0.02",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--reference-rtol = 0.001") && err.contains("smallest --rtol (1e-8)"),
        "{err}"
    );
    assert!(!out.exists());
}
