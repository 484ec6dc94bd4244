//! `flexrock fem`: files and columns written, the stability warning, --compare, --modes, and the
//! [fem] input rules (message names the key, exit code 2, nothing written).

use crate::common;

use crate::common::{file_names, flexrock, reference_model};

#[test]
fn fem_writes_history_events_summary_and_figures() {
    let out = common::scratch_dir("fem-run").join("result");
    let o = flexrock(&[
        "fem",
        reference_model().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The paper's dt = 0.0071 s is beyond the linear acceleration limit of the 2 x 5 mesh.
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains("warning: fem.dt = 0.0071 s exceeds the stability limit 0.006"),
        "{stderr}"
    );

    let history = std::fs::read_to_string(out.join("fem_history.csv")).unwrap();
    let mut lines = history.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,floor_acc,q,flexural,rocking,slipping,shearing,top_velocity,\
         momentum_left_toe,momentum_right_toe,lowest_base_uy,base_states"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').take(11).map(|f| f.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 846, "6 s in steps of 0.0071 s");
    for r in &rows {
        // the four parts sum to q
        assert!((r[3] + r[4] + r[5] + r[6] - r[2]).abs() < 1e-12);
    }
    assert!(history.lines().nth(1).unwrap().ends_with(",XXX"));

    let events = std::fs::read_to_string(out.join("fem_events.csv")).unwrap();
    assert!(events.starts_with("t,node,x,from,to,rx,ry\n"));
    assert_eq!(events.lines().count(), 1 + 312);

    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fem_summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["dt_beyond_stability_limit"], true);
    assert_eq!(summary["warnings"].as_array().unwrap().len(), 1);
    assert_eq!(summary["scheme"], "linear-acceleration");
    assert_eq!(summary["settings"]["nx"], 2);
    assert_eq!(summary["settings"]["ny"], 5);
    assert_eq!(summary["body"]["poisson_ratio"], 0.25);
    let limit = summary["linear_acceleration_stability_limit"]
        .as_f64()
        .unwrap();
    let omega_max = summary["highest_frequency"].as_f64().unwrap();
    assert!((limit * omega_max - 12f64.sqrt()).abs() < 1e-9, "{limit}");
    // the paper's step lies beyond it, by less than 15 %
    assert!(limit < 0.0071 && limit > 0.0071 / 1.15, "{limit}");
    for key in [
        "flexrock_version",
        "wall_time_s",
        "inputs",
        "peaks",
        "uplifts",
        "sdof_T",
        "static_reactions",
    ] {
        assert!(summary.get(key).is_some(), "fem_summary.json lacks {key}");
    }
    let ry: f64 = summary["static_reactions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r[1].as_f64().unwrap())
        .sum();
    assert!((ry - 1680.0 * 9.81).abs() < 1e-6);

    assert_eq!(
        file_names(&out),
        [
            "fem_angular_momentum.svg",
            "fem_components.svg",
            "fem_deformed_shapes.svg",
            "fem_events.csv",
            "fem_history.csv",
            "fem_q_vs_r.svg",
            "fem_s_vs_r.svg",
            "fem_summary.json",
            "fem_top_velocity.svg",
        ]
    );
    let shapes = std::fs::read_to_string(out.join("fem_deformed_shapes.svg")).unwrap();
    // six shapes from 0.9 s to 1.4 s, each labelled with the time of its step
    assert_eq!(shapes.matches("t = ").count(), 6);
    assert!(shapes.contains("t = 0.90") && shapes.contains("t = 1.40"));
}

#[test]
fn stable_scheme_and_overrides_give_no_warning() {
    let out = common::scratch_dir("fem-avg").join("result");
    let o = flexrock(&[
        "fem",
        reference_model().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--scheme",
        "average-acceleration",
        "--nx",
        "4",
        "--ny",
        "10",
        "--dt",
        "0.01",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("fem_summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["settings"]["nx"], 4);
    assert_eq!(summary["settings"]["ny"], 10);
    assert_eq!(summary["settings"]["dt"], 0.01);
    assert_eq!(summary["dt_beyond_stability_limit"], false);
}

#[test]
fn compare_writes_the_table_and_overlaid_figures() {
    let out = common::scratch_dir("fem-compare").join("result");
    let o = flexrock(&[
        "fem",
        reference_model().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--compare",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for text in [
        "max q (m)",
        "uplifts",
        "SDOF uplift times",
        "FEM uplift times",
        "ds/dr",
    ] {
        assert!(stdout.contains(text), "{text} in {stdout}");
    }
    let table = std::fs::read_to_string(out.join("compare.csv")).unwrap();
    assert!(table.starts_with("quantity,sdof,fem\n"));
    let names = file_names(&out);
    for f in [
        "compare_q.svg",
        "compare_q_vs_r.svg",
        "compare_s_vs_r.svg",
        "sdof_history.csv",
        "fem_history.csv",
    ] {
        assert!(names.iter().any(|n| n == f), "{f} missing from {names:?}");
    }
}

#[test]
fn other_excitations_drive_the_fem_too() {
    let dir = common::scratch_dir("fem-harmonic");
    let model = dir.join("model.toml");
    std::fs::write(
        &model,
        common::reference_body(
            "[excitation]\nkind = \"harmonic\"\namplitude = 1.0\nperiod = 1.5\n\n\
             [simulation]\nduration = 1.0\n\n[fem]\nscheme = \"wilson-theta\"\ntheta = 1.4\n",
        ),
    )
    .unwrap();
    let out = dir.join("out");
    let o = flexrock(&[
        "fem",
        model.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let history = std::fs::read_to_string(out.join("fem_history.csv")).unwrap();
    let second: Vec<&str> = history.lines().nth(2).unwrap().split(',').collect();
    let t: f64 = second[0].parse().unwrap();
    let expected = (2.0 * std::f64::consts::PI * t / 1.5).sin();
    assert!((second[1].parse::<f64>().unwrap() - expected).abs() < 1e-9);
}

#[test]
fn modes_lists_periods_against_the_sdof_period() {
    let o = flexrock(&["fem", reference_model().to_str().unwrap(), "--modes"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for text in [
        "2 x 5 mesh",
        "T = 1.5500 s",
        "1.5948",
        "1.8263",
        "no P-Delta",
        "with P-Delta",
        "linear acceleration stable for dt <= 0.006",
    ] {
        assert!(stdout.contains(text), "{text} in {stdout}");
    }
}

/// The pushover of the reference body: on a rigid base plate it lifts off where the beam-column
/// model of book/src/model.md §7a (self-weight) does (q = 0.1895 m, base shear 8260 N/m x 0.1895 m
/// = 1565 N), and its pre-uplift stiffness is that model's 0.764 Ke; the flexible base opens well
/// before.
#[test]
fn pushover_writes_both_curves_against_the_sdof_force() {
    let out = common::scratch_dir("fem-pushover").join("result");
    let o = flexrock(&[
        "fem",
        reference_model().to_str().unwrap(),
        "--pushover",
        "--nx",
        "8",
        "--ny",
        "40",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        file_names(&out),
        ["pushover.csv", "pushover.json", "pushover.svg"]
    );
    let csv = std::fs::read_to_string(out.join("pushover.csv")).unwrap();
    assert!(csv.starts_with(
        "base,q,base_shear,load_factor,flexural,rocking,shearing,contact_nodes,heel_lifted,\
         uplift,approximate_contact,sdof_force\n"
    ));
    assert_eq!(
        csv.lines().filter(|l| l.starts_with("flexible,")).count(),
        400
    );
    assert_eq!(
        csv.lines()
            .filter(|l| l.starts_with("rigid-plate,"))
            .count(),
        400
    );
    // the SDOF column is F(q) of book/src/model.md §3: Ke q up to s_n = 0.15237 m, then falling
    let ke = 10807.7;
    for line in csv.lines().skip(1).take(400) {
        let f: Vec<f64> = line
            .split(',')
            .skip(1)
            .map(|x| x.parse().unwrap_or(f64::NAN))
            .collect();
        let (q, sdof) = (f[0], f[10]);
        let expected = if q <= 0.15237 {
            ke * q
        } else {
            ke * 0.15237 * (0.7 - q) / (0.7 - 0.15237)
        };
        assert!((sdof - expected).abs() < 1e-3 * ke * 0.15237, "q = {q}");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("pushover.json")).unwrap()).unwrap();
    assert_eq!(summary["p_delta"], true);
    assert_eq!(summary["nx"], 8);
    let curves = summary["curves"].as_array().unwrap();
    let (flexible, plate) = (&curves[0], &curves[1]);
    assert_eq!(flexible["base"], "flexible");
    assert_eq!(plate["base"], "rigid-plate");
    let plate_lift = plate["heel_lift_q"].as_f64().unwrap();
    assert!((plate_lift / 0.1895 - 1.0).abs() < 0.05, "{plate_lift}");
    let plate_peak = plate["peak_base_shear"].as_f64().unwrap();
    assert!((plate_peak / 1565.0 - 1.0).abs() < 0.05, "{plate_peak}");
    let k0 = plate["initial_stiffness_over_ke"].as_f64().unwrap();
    assert!((k0 / 0.764 - 1.0).abs() < 0.06, "{k0}");
    assert!(flexible["heel_lift_q"].as_f64().unwrap() < 0.5 * plate_lift);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("rigid-plate") && stdout.contains("s_n = 0.15237 m"));

    // --pushover is a mode of its own
    let o = flexrock(&[
        "fem",
        reference_model().to_str().unwrap(),
        "--pushover",
        "--compare",
    ]);
    assert_eq!(o.status.code(), Some(2));
}

/// A model with `[fem]` text that must be refused: exit 2, the key named, nothing written.
fn refused(name: &str, body_extra: &str, fem: &str) -> String {
    let text = common::reference_body(&format!(
        "[excitation]\nkind = \"free\"\n\n[simulation]\nduration = 1.0\n\n[fem]\n{fem}\n"
    ))
    .replace("gravity = 9.81\n", &format!("gravity = 9.81\n{body_extra}"));
    common::refused("fem", name, &text)
}

#[test]
fn bad_fem_keys_are_refused_by_name() {
    for (name, body_extra, fem, words) in [
        ("unknown", "", "nxx = 3", &["nxx"][..]),
        ("nx", "", "nx = 0", &["fem.nx", "1..=1000"][..]),
        ("ny", "", "ny = 5000", &["fem.ny", "5000"][..]),
        ("dt", "", "dt = -0.01", &["fem.dt", "greater than 0"][..]),
        ("duration", "", "duration = 0.0", &["fem.duration"][..]),
        (
            "scheme",
            "",
            "scheme = \"rk4\"",
            &["fem.scheme", "rk4", "wilson-theta"][..],
        ),
        (
            "theta",
            "",
            "scheme = \"wilson-theta\"\ntheta = 0.5",
            &["fem.theta", "[1, 3]"][..],
        ),
        (
            "theta-unused",
            "",
            "theta = 1.4",
            &["fem.theta", "not a parameter"][..],
        ),
        ("mu_s", "", "mu_s = -0.1", &["fem.mu_s", ">= 0"][..]),
        ("mu_k", "", "mu_k = 0.9", &["fem.mu_k", "cannot exceed"][..]),
        (
            "damping_period",
            "",
            "damping_period = 0.0",
            &["fem.damping_period"][..],
        ),
        ("p_delta", "", "p_delta = 1", &["p_delta"][..]),
        (
            "base",
            "",
            "base = \"rigid\"",
            &["fem.base", "\"rigid\"", "rigid-plate"][..],
        ),
        (
            "poisson",
            "poisson_ratio = 0.5\n",
            "",
            &["body.poisson_ratio", "[0, 0.5)"][..],
        ),
        (
            "poisson-negative",
            "poisson_ratio = -0.1\n",
            "",
            &["body.poisson_ratio"][..],
        ),
    ] {
        let stderr = refused(name, body_extra, fem);
        for w in words {
            assert!(stderr.contains(w), "{name}: expected {w:?} in {stderr}");
        }
    }
}

#[test]
fn bad_command_line_values_are_refused_too() {
    let dir = common::scratch_dir("fem-bad-flags");
    let out = dir.join("out");
    // The message names the flag the value came from, not the file's key.
    for (flag, value, key) in [
        ("--nx", "0", "--nx = 0"),
        ("--dt", "0", "--dt = 0"),
        ("--scheme", "euler", "--scheme = \"euler\""),
    ] {
        let o = flexrock(&[
            "fem",
            reference_model().to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            flag,
            value,
        ]);
        assert_eq!(o.status.code(), Some(2));
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains(key), "{stderr}");
        assert!(!stderr.contains("fem."), "{stderr}");
        assert!(!out.exists());
    }
}

#[test]
fn a_fem_section_the_analysis_refuses_does_not_stop_run() {
    let dir = common::scratch_dir("fem-section-run");
    let model = dir.join("model.toml");
    let text = std::fs::read_to_string(common::reference_model()).unwrap() + "\n[fem]\nnx = 0\n";
    std::fs::write(&model, text).unwrap();
    let o = common::flexrock(&[
        "run",
        model.to_str().unwrap(),
        "--out",
        dir.join("run").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = common::flexrock(&[
        "fem",
        model.to_str().unwrap(),
        "--out",
        dir.join("fem").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("fem.nx"));
    assert!(!dir.join("fem").exists());
}
