//! The command line: the end-to-end run and every bad-input rule (message, exit code, no output).

use crate::common;

use crate::common::{flexrock, reference_model};

#[test]
fn run_writes_its_four_files_with_their_schemas() {
    let out = common::scratch_dir("cli-run").join("result");
    let o = common::run_reference(&out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("uplifts"), "{stdout}");

    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let mut lines = history.lines();
    assert_eq!(
        lines.next().unwrap(),
        "t,q,qdot,s,r,mode,floor_acc,F,energy_residual,work_input,work_damping"
    );
    let rows: Vec<&str> = lines.collect();
    // Every 0.005 s over 6 s (1201 points) plus both states at every event.
    assert!(rows.len() > 1201);
    assert!(rows[0].starts_with("0,0,0,"));

    let events = std::fs::read_to_string(out.join("events.csv")).unwrap();
    let mut lines = events.lines();
    assert_eq!(
        lines.next().unwrap(),
        "index,t,kind,from,to,q,qdot_before,qdot_after"
    );
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(first[0], "0");
    assert_eq!(first[2], "uplift");
    assert_eq!(first[3], "pre-uplift");
    assert!(first[4] == "rock-left" || first[4] == "rock-right");

    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    for key in [
        "max_q",
        "t_max_q",
        "min_q",
        "t_min_q",
        "n_uplift",
        "n_landing",
        "overturned",
        "t_overturn",
        "s_n",
        "T",
        "max_energy_residual",
        "statistics",
        "constants",
        "inputs",
        "solver",
        "flexrock_version",
    ] {
        assert!(summary.get(key).is_some(), "summary.json lacks {key}");
    }
    assert_eq!(summary["overturned"], false);
    assert!(summary["statistics"]["steps"].as_u64().unwrap() > 0);
    assert!(summary["statistics"]["rhs_evaluations"].as_u64().unwrap() > 0);
    assert!(summary["statistics"]["wall_time_s"].as_f64().unwrap() > 0.0);
    assert_eq!(summary["inputs"]["body"]["height"], 4.0);
    assert_eq!(
        summary["n_uplift"].as_u64().unwrap() as usize,
        events.lines().filter(|l| l.contains(",uplift,")).count()
    );
    // No temporary files are left behind.
    let names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 4, "{names:?}");
    assert!(names.contains(&"episodes.csv".to_string()), "{names:?}");
}

#[test]
fn props_prints_table_and_json() {
    let o = flexrock(&["props", reference_model().to_str().unwrap()]);
    assert!(o.status.success());
    let table = String::from_utf8_lossy(&o.stdout);
    assert!(table.contains("uplift displacement s_n"));
    assert!(table.contains("0.152365"));
    assert!(
        table.lines().all(|line| line == line.trim_end()),
        "a line of the table ends in spaces"
    );
    let o = flexrock(&["props", reference_model().to_str().unwrap(), "--json"]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let t = v["constants"]["period"].as_f64().unwrap();
    assert!((t - 1.55).abs() < 1e-4);
    assert!(v["constants"]["gravity_parameter_ratio"].as_f64().is_some());
}

const GOOD: &str = "[body]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\
damping_ratio = 0.05\n\n[excitation]\nkind = \"paper-sine\"\namplitude = 5.0\nperiod = 1.0\nramp = 0.412\n\n\
[simulation]\nduration = 1.0\n";

/// Runs a model text that must be refused; returns stderr after checking exit code and outputs.
fn refused(name: &str, model_text: &str) -> String {
    let stderr = common::refused("run", name, model_text);
    assert!(
        stderr.contains("model.toml"),
        "{name}: message does not name the file: {stderr}"
    );
    stderr
}

fn assert_mentions(stderr: &str, words: &[&str]) {
    for w in words {
        assert!(stderr.contains(w), "expected {w:?} in: {stderr}");
    }
}

#[test]
fn the_good_model_runs() {
    let dir = common::scratch_dir("good");
    let model = dir.join("model.toml");
    std::fs::write(&model, GOOD).unwrap();
    let o = flexrock(&[
        "run",
        model.to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn non_positive_sizes_densities_and_moduli() {
    for (key, from, to) in [
        ("body.height", "height = 4.0", "height = 0.0"),
        ("body.width", "width = 0.7", "width = -0.7"),
        ("body.density", "density = 600.0", "density = 0.0"),
        (
            "body.youngs_modulus",
            "youngs_modulus = 5.0e6",
            "youngs_modulus = -5.0e6",
        ),
        ("body.depth", "height = 4.0", "height = 4.0\ndepth = 0.0"),
        ("body.mass", "density = 600.0", "mass = -3.0"),
        (
            "body.flexural_rigidity",
            "youngs_modulus = 5.0e6",
            "flexural_rigidity = 0.0",
        ),
        ("body.period", "youngs_modulus = 5.0e6", "period = -1.0"),
        ("simulation.duration", "duration = 1.0", "duration = 0.0"),
        ("excitation.ramp", "ramp = 0.412", "ramp = -0.1"),
    ] {
        let stderr = refused(key, &GOOD.replacen(from, to, 1));
        assert_mentions(&stderr, &[key, "greater than 0"]);
    }
    let stderr = refused(
        "excitation.period",
        &GOOD.replacen("period = 1.0", "period = 0.0", 1),
    );
    assert_mentions(&stderr, &["excitation.period", "at least 0.001 s"]);
}

#[test]
fn damping_outside_the_unit_interval() {
    for value in ["1.0", "-0.01", "1.5"] {
        let stderr = refused(
            &format!("damping{value}"),
            &GOOD.replace("damping_ratio = 0.05", &format!("damping_ratio = {value}")),
        );
        assert_mentions(&stderr, &["body.damping_ratio", "[0, 1)"]);
    }
}

#[test]
fn landing_restitution_outside_zero_to_one() {
    for value in ["0.0", "-0.5", "1.5", "nan", "inf"] {
        let stderr = refused(
            &format!("restitution{value}"),
            &GOOD.replace(
                "damping_ratio = 0.05",
                &format!("damping_ratio = 0.05\nlanding_restitution = {value}"),
            ),
        );
        assert_mentions(&stderr, &["body.landing_restitution", "(0, 1]"]);
    }
    // The same rule for a value set from the command line, which the message names as such.
    let stderr = common::refused_with(
        "run",
        "restitution-set",
        GOOD,
        &["--set", "body.landing_restitution=1.25"],
    );
    assert_mentions(
        &stderr,
        &["--set body.landing_restitution = 1.25", "(0, 1]"],
    );
}

#[test]
fn damping_while_rocking_not_a_boolean() {
    for value in ["1", "\"no\"", "0.0"] {
        let stderr = refused(
            &format!("damping-while-rocking{value}"),
            &GOOD.replace(
                "damping_ratio = 0.05",
                &format!("damping_ratio = 0.05\ndamping_while_rocking = {value}"),
            ),
        );
        // The file's line, which names the key, and the rule.
        assert_mentions(
            &stderr,
            &[&format!("damping_while_rocking = {value}"), "boolean"],
        );
    }
    let stderr = common::refused_with(
        "run",
        "damping-while-rocking-set",
        GOOD,
        &["--set", "body.damping_while_rocking=yes"],
    );
    assert_mentions(&stderr, &["body.damping_while_rocking", "boolean"]);
}

/// `--set` and a sweep's `--vary` reach the landing restitution: at e = 1 the run is the one
/// without the key, byte for byte, and below 1 the landings take more of q'.
#[test]
fn landing_restitution_is_set_and_swept() {
    let dir = common::scratch_dir("cli-landing-restitution");
    let plain = dir.join("plain");
    let output = common::run_reference(&plain, &[]);
    assert!(output.status.success(), "{output:?}");
    let one = dir.join("one");
    let output = common::run_reference(&one, &["--set", "body.landing_restitution=1"]);
    assert!(output.status.success(), "{output:?}");
    for file in ["history.csv", "events.csv", "episodes.csv"] {
        assert_eq!(
            std::fs::read(plain.join(file)).unwrap(),
            std::fs::read(one.join(file)).unwrap(),
            "{file}"
        );
    }
    let lossy = dir.join("lossy");
    let output = common::run_reference(
        &lossy,
        &[
            "--set",
            "body.landing_restitution=0.5",
            "--set",
            "body.damping_while_rocking=false",
        ],
    );
    assert!(output.status.success(), "{output:?}");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(lossy.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["body"]["landing_restitution"], 0.5);
    assert_eq!(summary["body"]["damping_while_rocking"], false);
    assert_eq!(summary["inputs"]["body"]["landing_restitution"], 0.5);
    let plain_summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(plain.join("summary.json")).unwrap()).unwrap();
    assert!(plain_summary["body"].get("landing_restitution").is_none());
    assert!(plain_summary["inputs"]["body"]
        .get("landing_restitution")
        .is_none());

    let swept = dir.join("sweep");
    let output = common::flexrock(&[
        "sweep",
        common::reference_model().to_str().unwrap(),
        "--vary",
        "body.landing_restitution=0.5:1:0.25",
        "--quiet",
        "--out",
        swept.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{output:?}");
    let rows = common::sweep_rows(&swept);
    let values: Vec<&str> = rows
        .iter()
        .map(|r| r["body.landing_restitution"].as_str())
        .collect();
    assert_eq!(values, ["0.5", "0.75", "1"]);
    assert!(rows.iter().all(|r| r["status"] == "ok"), "{rows:?}");
    let peak = |r: &std::collections::HashMap<String, String>| -> f64 {
        r["max_abs_q_over_B"].parse().unwrap()
    };
    let width = summary["body"]["width"].as_f64().unwrap();
    let plain_peak = plain_summary["max_q"]
        .as_f64()
        .unwrap()
        .max(-plain_summary["min_q"].as_f64().unwrap())
        / width;
    assert_eq!(
        peak(&rows[2]),
        plain_peak,
        "e = 1 is the run without the key"
    );
    assert_ne!(peak(&rows[0]), plain_peak, "e = 0.5 changes the run");
}

#[test]
fn width_not_less_than_height() {
    let stderr = refused("squat-width", &GOOD.replace("width = 0.7", "width = 4.0"));
    assert_mentions(&stderr, &["body.width", "4", "less than the height"]);
}

#[test]
fn buckled_under_its_own_weight() {
    // E = 1 MPa: M g H^2/EI = 1680 * 9.81 * 16 / (1e6 * 0.7^3 / 12) = 9.22540 for the reference
    // body, beyond 7.837; quoted to 6 digits, not the 16 of a double (9.225404081632653).
    for (e, quoted) in [("1.0e6", "= 9.2254:"), ("1.0e3", "= 9225.4:")] {
        let stderr = refused(
            "buckled",
            &GOOD.replace("youngs_modulus = 5.0e6", &format!("youngs_modulus = {e}")),
        );
        assert_mentions(
            &stderr,
            &[
                "M g H^2/EI",
                quoted,
                "7.837",
                "buckles under its own weight",
            ],
        );
    }
}

/// A body that buckles only because of a `--set`: the message names the setting beside the file,
/// and nothing is written.
#[test]
fn buckled_by_a_setting_names_the_setting() {
    let stderr = common::refused_with(
        "run",
        "buckled-by-set",
        GOOD,
        &[
            "--set",
            "body.youngs_modulus=1e6",
            "--set",
            "excitation.amplitude=4.0",
        ],
    );
    assert_mentions(
        &stderr,
        &[
            "model.toml",
            "= 9.2254:",
            "buckles under its own weight",
            "with --set body.youngs_modulus=1000000.0",
        ],
    );
    // Only the body's settings: the excitation's plays no part in M g H^2/EI.
    assert!(!stderr.contains("excitation.amplitude"), "{stderr}");
    // An extreme value is quoted with its exponent, not as hundreds of digits.
    let stderr = common::refused_with(
        "run",
        "buckled-by-extreme-set",
        GOOD,
        &["--set", "body.youngs_modulus=1e-300"],
    );
    assert_mentions(&stderr, &["with --set body.youngs_modulus=1e-300"]);
}

#[test]
fn too_stiff_for_its_mass() {
    for (key, value) in [
        ("youngs_modulus = 5.0e6", "youngs_modulus = 1e300"),
        ("density = 600.0", "density = 1e-300"),
    ] {
        let stderr = refused("stiff", &GOOD.replace(key, value));
        assert_mentions(&stderr, &["pre-uplift period T", "at least 1e-4 s"]);
    }
}

#[test]
fn too_squat_for_the_model() {
    let stderr = refused(
        "squat",
        &GOOD
            .replace("height = 4.0", "height = 1.0")
            .replace("width = 0.7", "width = 0.5")
            .replace("5.0e6", "5.0e9"),
    );
    assert_mentions(&stderr, &["zetaL", "too squat"]);
}

#[test]
fn alternatives_both_or_neither() {
    let both = refused(
        "both-mass",
        &GOOD.replace("density = 600.0", "density = 600.0\nmass = 1680.0"),
    );
    assert_mentions(&both, &["body.density", "body.mass", "exactly one"]);
    let neither = refused("no-mass", &GOOD.replace("density = 600.0\n", ""));
    assert_mentions(&neither, &["body.density", "missing", "exactly one"]);
    let both = refused(
        "both-stiffness",
        &GOOD.replace(
            "youngs_modulus = 5.0e6",
            "youngs_modulus = 5.0e6\nperiod = 1.5",
        ),
    );
    assert_mentions(
        &both,
        &["body.youngs_modulus", "body.period", "exactly one"],
    );
    let neither = refused(
        "no-stiffness",
        &GOOD.replace("youngs_modulus = 5.0e6\n", ""),
    );
    assert_mentions(
        &neither,
        &[
            "body.youngs_modulus",
            "body.flexural_rigidity",
            "body.period",
        ],
    );
}

#[test]
fn unknown_keys_and_values() {
    let stderr = refused(
        "unknown-key",
        &GOOD.replace("height = 4.0", "height = 4.0\nheigth = 4.0"),
    );
    assert_mentions(&stderr, &["heigth"]);
    let stderr = refused(
        "unknown-section",
        &format!("{GOOD}\n[solvr]\nrtol = 1e-6\n"),
    );
    assert_mentions(&stderr, &["solvr"]);
    let stderr = refused("kind", &GOOD.replace("\"paper-sine\"", "\"sine\""));
    assert_mentions(&stderr, &["excitation.kind", "\"sine\"", "paper-sine"]);
    let stderr = refused(
        "ramp-harmonic",
        &GOOD.replace("\"paper-sine\"", "\"harmonic\""),
    );
    assert_mentions(&stderr, &["excitation.ramp", "not a parameter"]);
    let stderr = refused("no-amplitude", &GOOD.replace("amplitude = 5.0\n", ""));
    assert_mentions(&stderr, &["excitation.amplitude", "missing"]);
    let stderr = refused("method", &format!("{GOOD}\n[solver]\nmethod = \"rk4\"\n"));
    assert_mentions(&stderr, &["solver.method", "rk4", "bdf"]);
    let stderr = refused("rtol", &format!("{GOOD}\n[solver]\nrtol = 2.0\n"));
    assert_mentions(&stderr, &["solver.rtol", "[1e-14, 1e-2]"]);
    let stderr = refused(
        "constants",
        &GOOD.replace("height = 4.0", "height = 4.0\nconstants = \"rounded\""),
    );
    assert_mentions(&stderr, &["body.constants", "rounded"]);
    let stderr = refused(
        "q0",
        &GOOD.replace("duration = 1.0", "duration = 1.0\nq0 = 0.7"),
    );
    assert_mentions(&stderr, &["simulation.q0", "0.7", "|q0| < B"]);
    let stderr = refused("not-toml", "this is not toml");
    assert!(!stderr.is_empty());
    let stderr = refused(
        "string-for-number",
        &GOOD.replace("height = 4.0", "height = \"tall\""),
    );
    assert_mentions(&stderr, &["height"]);
}

#[test]
fn unreadable_file() {
    let dir = common::scratch_dir("missing");
    let out = dir.join("out");
    let o = flexrock(&[
        "run",
        dir.join("nope.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_mentions(&stderr, &["nope.toml", "cannot read"]);
    assert!(!out.exists());
}

#[test]
fn command_line_overrides_are_checked_too() {
    let dir = common::scratch_dir("override");
    let out = dir.join("out");
    let o = common::run_reference(&out, &["--rtol=-1"]);
    assert_eq!(o.status.code(), Some(2));
    assert_mentions(&String::from_utf8_lossy(&o.stderr), &["solver.rtol", "-1"]);
    assert!(!out.exists());
    // A negative number after a space is the flag's value, checked by its rule, not an unknown
    // flag of its own.
    for (flag, words) in [
        (
            "--duration",
            &["--duration", "simulation.duration", "-1", "greater than 0"][..],
        ),
        ("--dt", &["solver.dt", "-1"][..]),
        ("--atol", &["solver.atol", "-1"][..]),
    ] {
        let o = common::run_reference(&out, &[flag, "-1"]);
        assert_eq!(o.status.code(), Some(2), "{flag}");
        assert_mentions(&String::from_utf8_lossy(&o.stderr), words);
        assert!(!out.exists(), "{flag}");
    }
}

#[test]
fn loose_tolerances_are_refused() {
    // At rtol = 0.5 the paper's example logged 817 uplifts and an overturning (the truth: 11, none).
    for (flag, value, words) in [
        ("--rtol", "0.5", &["solver.rtol", "[1e-14, 1e-2]"][..]),
        ("--rtol", "1e-20", &["solver.rtol", "[1e-14, 1e-2]"][..]),
        ("--rtol", "NaN", &["solver.rtol"][..]),
        ("--atol", "0.01", &["solver.atol", "width"][..]),
    ] {
        let out = common::scratch_dir("loose").join("out");
        let o = common::run_reference(&out, &["--method", "bdf", flag, value]);
        assert_eq!(o.status.code(), Some(2), "{flag} {value}");
        assert_mentions(&String::from_utf8_lossy(&o.stderr), words);
        assert!(!out.exists());
    }
}

#[test]
fn floor_motions_beyond_physics_are_refused() {
    let harmonic = |amplitude: &str, period: &str| {
        GOOD.replace("kind = \"paper-sine\"", "kind = \"harmonic\"")
            .replace("ramp = 0.412\n", "")
            .replace("amplitude = 5.0", &format!("amplitude = {amplitude}"))
            .replace("period = 1.0", &format!("period = {period}"))
    };
    // tsit45 ran forever on a floor of 1e150 m/s^2.
    let stderr = refused("huge-amplitude", &harmonic("1e150", "1.0"));
    assert_mentions(
        &stderr,
        &[
            "excitation.amplitude",
            "beyond the limit of 196.133 m/s^2 (20 g)",
        ],
    );
    refused("just-beyond", &harmonic("-196.2", "1.0"));
    let stderr = refused("tiny-period", &harmonic("1.0", "1e-300"));
    assert_mentions(&stderr, &["excitation.period", "at least 0.001 s"]);
    // A ramp so long that the cubic's coefficients overflow, one so short that it is violent.
    let stderr = refused("long-ramp", &GOOD.replace("ramp = 0.412", "ramp = 1e300"));
    assert_mentions(&stderr, &["excitation.ramp", "beyond the limit"]);
    let stderr = refused("short-ramp", &GOOD.replace("ramp = 0.412", "ramp = 0.001"));
    assert_mentions(&stderr, &["excitation.ramp", "beyond the limit"]);
    let stderr = refused(
        "long-run",
        &GOOD.replace("duration = 1.0", "duration = 1e300"),
    );
    assert_mentions(&stderr, &["simulation.duration", "at most 1e4 s"]);
    // A record scaled beyond the limit.
    let record = format!(
        "{}\n[excitation]\nkind = \"record\"\npath = \"{}\"\nscale = 1e150\n[simulation]\n",
        GOOD.split("\n\n[excitation]").next().unwrap(),
        common::repo("validation/records/elCentro.AT2").display()
    );
    let stderr = refused("scaled-record", &record);
    assert_mentions(&stderr, &["excitation.scale", "peak floor acceleration"]);
    // One sample of 1e150 m/s^2 in the file itself: the record, not the scale, is to blame.
    let dir = common::scratch_dir("huge-sample-record");
    let csv = dir.join("huge.csv");
    std::fs::write(&csv, "t,acc\n0,0\n0.01,1e150\n0.02,0\n").unwrap();
    let record = format!(
        "{}\n[excitation]\nkind = \"record\"\npath = \"{}\"\nunits = \"m/s2\"\n[simulation]\n",
        GOOD.split("\n\n[excitation]").next().unwrap(),
        csv.display()
    );
    let stderr = refused("huge-sample", &record);
    assert_mentions(
        &stderr,
        &["excitation.path", "at t = 0.01 s", "beyond the limit"],
    );
}

#[test]
fn warnings_reach_stderr_and_the_summary() {
    // The paper's body stopped at 1.2 s, while it rocks: not "no overturning".
    let out = common::scratch_dir("warnings").join("out");
    let o = common::run_reference(
        &out,
        &[
            "--duration",
            "1.2",
            "--method",
            "bdf",
            "--rtol",
            "1e-2",
            "--atol",
            "1e-3",
        ],
    );
    assert!(o.status.success());
    let stdout = String::from_utf8_lossy(&o.stdout);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_mentions(
        &stdout,
        &["ended while rocking; no overturning within the duration"],
    );
    assert_mentions(
        &stdout,
        &[
            "excitation: paper-sine",
            // Each parameter with its unit.
            "amplitude = 5 m/s^2,",
            "period = 1 s,",
            "ramp = 0.412 s,",
            "peak floor acceleration",
        ],
    );
    assert_mentions(
        &stderr,
        &[
            "warning: the run ended while the body was rocking",
            "warning: M g H^2/EI",
        ],
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["ended_while_rocking"], true);
    let warnings = summary["warnings"].as_array().unwrap();
    assert!(warnings.iter().any(|w| w
        .as_str()
        .unwrap()
        .contains("ended while the body was rocking")));
    assert!(warnings
        .iter()
        .any(|w| w.as_str().unwrap().contains("0.235 of its buckling value")));
    // A body ten times stiffer, run to the end at a sound tolerance: no warning at all.
    let stiff = GOOD
        .replace("youngs_modulus = 5.0e6", "youngs_modulus = 5.0e7")
        .replace("amplitude = 5.0", "amplitude = 0.5")
        .replace("duration = 1.0", "duration = 3.0");
    let dir = common::scratch_dir("no-warnings");
    std::fs::write(dir.join("model.toml"), stiff).unwrap();
    let o = flexrock(&[
        "run",
        dir.join("model.toml").to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert!(o.status.success());
    assert!(
        !String::from_utf8_lossy(&o.stderr).contains("warning"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out/summary.json")).unwrap())
            .unwrap();
    assert_eq!(summary["warnings"].as_array().unwrap().len(), 0);
}

#[test]
fn a_large_energy_residual_is_a_warning() {
    // At the loosest tolerance allowed the paper's example loses a fifth of its energy scale.
    let out = common::scratch_dir("residual").join("out");
    let o = common::run_reference(
        &out,
        &["--method", "bdf", "--rtol", "1e-2", "--atol", "1e-3"],
    );
    assert!(o.status.success());
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_mentions(
        &stderr,
        &[
            "warning: the energy residual reached",
            "of the energy scale",
        ],
    );
    // The same run at the default tolerance does not warn about energy.
    let o = common::run_reference(&out, &[]);
    assert!(!String::from_utf8_lossy(&o.stderr).contains("energy residual"));
}

#[test]
fn a_record_model_needs_no_simulation_table() {
    let dir = common::scratch_dir("no-simulation");
    let text = format!(
        "{}\n[excitation]\nkind = \"record\"\npath = \"{}\"\n",
        GOOD.split("\n\n[excitation]").next().unwrap(),
        common::repo("validation/records/elCentro.AT2").display()
    );
    std::fs::write(dir.join("model.toml"), text).unwrap();
    let o = flexrock(&[
        "run",
        dir.join("model.toml").to_str().unwrap(),
        "--out",
        dir.join("out").to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Without a record the duration is still required, and the message says so.
    let stderr = refused(
        "no-simulation-harmonic",
        GOOD.split("\n[simulation]").next().unwrap(),
    );
    assert_mentions(&stderr, &["simulation.duration", "required"]);
}

/// A misspelt key or named value gets the closest right one; a number with a unit suffix gets
/// the unit its key takes.
#[test]
fn misspellings_and_unit_suffixes_get_a_hint() {
    let model = common::reference_model();
    let out = common::scratch_dir("cli-hints").join("out");
    for (setting, hint) in [
        ("excitation.amplitud=3", "did you mean `amplitude`?"),
        ("solver.method=tsit54", "did you mean \"tsit45\"?"),
        ("excitation.kind=sine_pulse", "did you mean \"sine-pulse\"?"),
        (
            "body.self_weight=consistant",
            "did you mean \"consistent\"?",
        ),
        ("excitation.amplitude=0.3g", "(m/s^2)"),
        ("body.youngs_modulus=5MPa", "(Pa)"),
    ] {
        let o = common::flexrock(&[
            "run",
            model.to_str().unwrap(),
            "--set",
            setting,
            "--out",
            out.to_str().unwrap(),
        ]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{setting}: {stderr}");
        assert!(stderr.contains(hint), "{setting}: {stderr}");
        assert!(!out.exists(), "{setting}: nothing is written");
    }
}

/// episodes.csv read as rows of column -> text.
fn episode_rows(dir: &std::path::Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut reader = csv::Reader::from_path(dir.join("episodes.csv")).expect("episodes.csv");
    let headers = reader.headers().unwrap().clone();
    reader
        .records()
        .map(|r| {
            headers
                .iter()
                .zip(r.unwrap().iter())
                .map(|(h, v)| (h.to_string(), v.to_string()))
                .collect()
        })
        .collect()
}

fn field(row: &std::collections::HashMap<String, String>, column: &str) -> f64 {
    row[column]
        .parse()
        .unwrap_or_else(|_| panic!("{column} = {:?}", row[column]))
}

/// Free rocking of a near-rigid body released at rest from q0 = B/2: the first episode is the
/// release itself, its peak is the release (|q| = q0 at t = 0, rotation q0/H), and it lands at
/// the slender rigid block's time (1/p) acosh(1/(1 - q0/B)), p = sqrt(3 g/(2 H)); the
/// next episode, about the other toe, is still under way when the run ends.
#[test]
fn episodes_of_free_rocking_follow_housners_closed_form() {
    let out = common::scratch_dir("cli-episodes-rigid").join("out");
    let model = common::repo("validation/models/rigid-free-rocking.toml");
    let o = flexrock(&[
        "run",
        model.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let rows = episode_rows(&out);
    assert_eq!(rows.len(), 2, "{rows:?}");
    let (h, b, g, q0) = (4.0_f64, 0.7_f64, 9.81_f64, 0.35_f64);
    let p = (3.0 * g / (2.0 * h)).sqrt();
    let landing = (1.0 / (1.0 - q0 / b)).acosh() / p;
    let first = &rows[0];
    assert_eq!(first["side"], "right");
    assert_eq!(first["ended_by"], "landing");
    assert_eq!(field(first, "t_start"), 0.0);
    assert!(((field(first, "t_end") - landing) / landing).abs() < 1e-3);
    assert!((field(first, "duration") - field(first, "t_end")).abs() < 1e-15);
    assert_eq!(field(first, "peak_abs_q"), q0);
    assert_eq!(field(first, "t_peak"), 0.0);
    assert!((field(first, "peak_rotation") - q0 / h).abs() < 1e-5);
    // Started rocking: no uplift, so nothing derived from one.
    for column in [
        "floor_acc_at_uplift",
        "qdot_before_uplift",
        "qdot_after_uplift",
    ] {
        assert_eq!(first[column], "", "{column}");
    }
    let second = &rows[1];
    assert_eq!(second["side"], "left");
    assert_eq!(second["ended_by"], "run-end");
    assert!((field(second, "t_start") - landing).abs() < 1e-3);
    for column in [
        "t_end",
        "duration",
        "qdot_before_landing",
        "qdot_after_landing",
    ] {
        assert_eq!(second[column], "", "{column}: nothing ended the episode");
    }
}

/// The kinetic energy before and after each impact, on the paper's example, from the model
/// chapter's closed form (book/src/model.md §5): M (int U^2) q'^2/2 before uplift and
/// M (int V^2) q'^2/2 while rocking, with M = 600 * 4 * 0.7 = 1680 kg, int U^2 = 1/4 for the
/// cantilever mode scaled to U(1) = 1, and int V^2 = (s_n^2/4 - 2 B s_n/L^2 + B^2/3)/(B - s_n)^2
/// (eq. 13) at the chapter's s_n = 0.1523652 m. The energy falls at every uplift and landing, by
/// the shares of the chapter's table (0.922927 and 0.968671).
#[test]
fn episodes_give_the_bodys_kinetic_energy_across_each_impact() {
    let out = common::scratch_dir("cli-episodes-energy").join("out");
    let o = common::run_reference(&out, &[]);
    assert!(o.status.success());
    let rows = episode_rows(&out);
    assert!(rows.len() >= 3);
    let (mass, b, s_n, l) = (
        1680.0_f64,
        0.7_f64,
        0.1523652_f64,
        1.875_104_068_711_961_f64,
    );
    let int_u2 = 0.25;
    let int_v2 =
        (s_n * s_n / 4.0 - 2.0 * b * s_n / (l * l) + b * b / 3.0) / ((b - s_n) * (b - s_n));
    let kinetic = |int: f64, qdot: f64| 0.5 * mass * int * qdot * qdot;
    let close = |a: f64, b: f64, what: &str| {
        assert!((a - b).abs() <= 1e-6 * b.abs(), "{what}: {a} against {b}");
    };
    let mut landings = 0;
    for row in &rows {
        let before = kinetic(int_u2, field(row, "qdot_before_uplift"));
        let after = kinetic(int_v2, field(row, "qdot_after_uplift"));
        close(
            field(row, "kinetic_energy_before_uplift"),
            before,
            "before uplift",
        );
        close(
            field(row, "kinetic_energy_after_uplift"),
            after,
            "after uplift",
        );
        close(after / before, 0.922927, "share kept at uplift");
        if row["ended_by"] == "landing" {
            let before = kinetic(int_v2, field(row, "qdot_before_landing"));
            let after = kinetic(int_u2, field(row, "qdot_after_landing"));
            close(
                field(row, "kinetic_energy_before_landing"),
                before,
                "before landing",
            );
            close(
                field(row, "kinetic_energy_after_landing"),
                after,
                "after landing",
            );
            close(after / before, 0.968671, "share kept at landing");
            landings += 1;
        } else {
            assert_eq!(row["kinetic_energy_before_landing"], "");
            assert_eq!(row["kinetic_energy_after_landing"], "");
        }
    }
    assert!(landings >= 3);
}

/// On the paper's example every episode is one uplift and the landing or overturning after it,
/// as events.csv has them; its peak is at least every sampled |q| in it; `--json` says the same
/// as `--csv`.
#[test]
fn episodes_agree_with_the_event_log_and_the_history() {
    let out = common::scratch_dir("cli-episodes-paper").join("out");
    let o = common::run_reference(&out, &[]);
    assert!(o.status.success());
    let rows = episode_rows(&out);
    let mut events = csv::Reader::from_path(out.join("events.csv")).unwrap();
    let events: Vec<Vec<String>> = events
        .records()
        .map(|r| r.unwrap().iter().map(str::to_string).collect())
        .collect();
    let uplifts: Vec<&Vec<String>> = events.iter().filter(|e| e[2] == "uplift").collect();
    assert!(uplifts.len() >= 3);
    assert_eq!(rows.len(), uplifts.len());
    let mut history = csv::Reader::from_path(out.join("history.csv")).unwrap();
    let headers = history.headers().unwrap().clone();
    let (t_col, q_col) = (
        headers.iter().position(|h| h == "t").unwrap(),
        headers.iter().position(|h| h == "q").unwrap(),
    );
    let samples: Vec<(f64, f64)> = history
        .records()
        .map(|r| {
            let r = r.unwrap();
            (r[t_col].parse().unwrap(), r[q_col].parse().unwrap())
        })
        .collect();
    for (row, uplift) in rows.iter().zip(&uplifts) {
        assert_eq!(row["t_start"], uplift[1]);
        let side = if uplift[4] == "rock-left" {
            "left"
        } else {
            "right"
        };
        assert_eq!(row["side"], side);
        let next = events
            .iter()
            .find(|e| e[1].parse::<f64>().unwrap() > field(row, "t_start") && e[2] != "uplift");
        match next {
            Some(end) => {
                assert_eq!(row["t_end"], end[1]);
                assert_eq!(row["ended_by"], end[2]);
                let duration = field(row, "t_end") - field(row, "t_start");
                assert!((field(row, "duration") - duration).abs() <= 1e-12);
            }
            None => assert_eq!(row["ended_by"], "run-end"),
        }
        let end = row["t_end"].parse().unwrap_or(f64::INFINITY);
        let sampled = samples
            .iter()
            .filter(|(t, _)| *t >= field(row, "t_start") && *t <= end)
            .map(|(_, q)| q.abs())
            .fold(0.0, f64::max);
        assert!(field(row, "peak_abs_q") >= sampled, "{row:?}: {sampled}");
        assert!(
            field(row, "peak_abs_q") <= sampled + 0.01,
            "{row:?}: {sampled}"
        );
    }
    let csv_out = flexrock(&["events", out.to_str().unwrap(), "--episodes"]);
    assert_eq!(
        csv_out.stdout,
        std::fs::read(out.join("episodes.csv")).unwrap()
    );
    let csv_out = flexrock(&["events", out.to_str().unwrap(), "--episodes", "--csv"]);
    assert_eq!(
        csv_out.stdout,
        std::fs::read(out.join("episodes.csv")).unwrap()
    );
    let json_out = flexrock(&["events", out.to_str().unwrap(), "--episodes", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&json_out.stdout).unwrap();
    let json = json.as_array().unwrap();
    assert_eq!(json.len(), rows.len());
    for (object, row) in json.iter().zip(&rows) {
        for (column, text) in row {
            match &object[column] {
                serde_json::Value::Null => assert_eq!(text, "", "{column}"),
                serde_json::Value::String(s) => assert_eq!(s, text, "{column}"),
                value => assert_eq!(value.as_f64().unwrap(), text.parse::<f64>().unwrap()),
            }
        }
    }
    // The events themselves, as CSV and as JSON: events.csv's rows, by column name.
    let events_csv = std::fs::read(out.join("events.csv")).unwrap();
    assert_eq!(
        flexrock(&["events", out.to_str().unwrap(), "--csv"]).stdout,
        events_csv
    );
    let json_out = flexrock(&["events", out.to_str().unwrap(), "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&json_out.stdout).unwrap();
    let json = json.as_array().unwrap();
    let mut reader = csv::Reader::from_reader(&events_csv[..]);
    let header = reader.headers().unwrap().clone();
    let events: Vec<csv::StringRecord> = reader.records().map(Result::unwrap).collect();
    assert!(!events.is_empty());
    assert_eq!(json.len(), events.len());
    for (object, row) in json.iter().zip(&events) {
        assert_eq!(object.as_object().unwrap().len(), header.len());
        for (column, text) in header.iter().zip(row) {
            match &object[column] {
                serde_json::Value::String(s) => assert_eq!(s, text, "{column}"),
                value => assert_eq!(value.as_f64().unwrap(), text.parse::<f64>().unwrap()),
            }
        }
    }
    // Both at once, or a directory without episodes.csv, is refused.
    let both = flexrock(&["events", out.to_str().unwrap(), "--csv", "--json"]);
    assert_eq!(both.status.code(), Some(2));
    std::fs::remove_file(out.join("episodes.csv")).unwrap();
    let missing = flexrock(&["events", out.to_str().unwrap(), "--episodes"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&missing.stderr).contains("episodes.csv"));
}

/// Every subcommand, as the README documents them.
const SUBCOMMANDS: [&str; 12] = [
    "props",
    "run",
    "plot",
    "events",
    "sweep",
    "record",
    "compare",
    "converge",
    "report",
    "fem",
    "completions",
    "man",
];

/// The completion scripts and the manual page come from the command's own definitions: each
/// names every subcommand, and the bash script is valid bash.
#[test]
fn completions_and_the_manual_page_name_every_subcommand() {
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let o = flexrock(&["completions", shell]);
        assert!(o.status.success(), "{shell}");
        let script = String::from_utf8_lossy(&o.stdout);
        for sub in SUBCOMMANDS {
            assert!(script.contains(sub), "{shell} completion lacks {sub}");
        }
        if shell == "bash" {
            let dir = common::scratch_dir("cli-completions");
            let file = dir.join("flexrock.bash");
            std::fs::write(&file, &o.stdout).unwrap();
            let check = std::process::Command::new("bash")
                .arg("-n")
                .arg(&file)
                .output()
                .expect("bash runs");
            assert!(
                check.status.success(),
                "{}",
                String::from_utf8_lossy(&check.stderr)
            );
        }
    }
    let o = flexrock(&["completions", "tcsh"]);
    assert_eq!(o.status.code(), Some(2));
    let o = flexrock(&["man"]);
    assert!(o.status.success());
    let page = String::from_utf8_lossy(&o.stdout);
    assert!(page.contains(".TH flexrock 1"), "{page}");
    for sub in SUBCOMMANDS {
        assert!(
            page.contains(&format!("flexrock\\-{sub}")) || page.contains(sub),
            "{sub}"
        );
    }
}

/// One rule for relative record paths: relative to the file that names them, and on the command
/// line relative to the current directory. `--set excitation.path=elCentro.AT2` run from a
/// directory that holds the record reads it there (the model file is elsewhere); from a directory
/// without it, the path is refused naming the full path it was looked for at. A sweep file's
/// `set` is relative to the sweep file.
#[test]
fn a_record_path_is_relative_to_where_it_was_given() {
    let dir = common::scratch_dir("cli-relative-paths");
    let model = common::repo("models/elcentro1940.toml");
    let record = common::repo("validation/records/elCentro.AT2");
    let here = dir.join("here");
    std::fs::create_dir_all(here.join("study/rec")).unwrap();
    std::fs::copy(&record, here.join("elCentro.AT2")).unwrap();
    std::fs::copy(&record, here.join("study/rec/short.AT2")).unwrap();
    let run_in = common::flexrock_in;
    let out = dir.join("out");
    let (model, out_s) = (model.to_str().unwrap(), out.to_str().unwrap());
    let o = run_in(
        &here,
        &[
            "run",
            model,
            "--set",
            "excitation.path=elCentro.AT2",
            "--set",
            "excitation.end=1",
            "--out",
            out_s,
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The models directory has no elCentro.AT2: the run read the one in the current directory.
    assert!(!common::repo("models/elCentro.AT2").exists());
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("here/elCentro.AT2"), "{summary}");

    // From a directory without the record, the path the model file itself would resolve
    // (../validation/records/...) is looked for beside the current directory, and the message
    // names that full path.
    let elsewhere = dir.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    let o = run_in(
        &elsewhere,
        &[
            "run",
            model,
            "--set",
            "excitation.path=../validation/records/elCentro.AT2",
            "--out",
            out_s,
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    let looked_at = dir.join("validation/records/elCentro.AT2");
    assert!(stderr.contains(&*looked_at.to_string_lossy()), "{stderr}");

    // Refused for another reason (a directory, not a record file): the message still names the
    // full path, by the flag that set it, and not as the model file's fault.
    std::fs::create_dir_all(here.join("rec.AT2")).unwrap();
    let o = run_in(
        &here,
        &[
            "run",
            model,
            "--set",
            "excitation.path=./study/../rec.AT2",
            "--out",
            out_s,
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&o.stderr);
    let full = format!("--set excitation.path: {}:", here.join("rec.AT2").display());
    assert!(stderr.starts_with(&format!("error: {full}")), "{stderr}");

    // A sweep file's `set` is relative to the sweep file, whatever the current directory.
    std::fs::write(
        here.join("study/sweep.toml"),
        "set = [\"excitation.path=rec/short.AT2\", \"excitation.end=0.5\"]\nvary = [\"excitation.scale=1,2\"]\n",
    )
    .unwrap();
    let sweep_file = here.join("study/sweep.toml");
    let o = run_in(
        &elsewhere,
        &[
            "sweep",
            model,
            "--sweep-file",
            sweep_file.to_str().unwrap(),
            "--out",
            dir.join("sweep").to_str().unwrap(),
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// `run --check` writes check.json: the run's error against the exact solution. Its largest
/// event-time error is the one read off the two event logs here (the run's, and the exact
/// method's own run), an exact run checks to zero, and without the flag there is no check.json.
#[test]
fn run_check_measures_the_run_against_the_exact_solution() {
    let read_events = |dir: &std::path::Path| -> Vec<(String, f64)> {
        let text = std::fs::read_to_string(dir.join("events.csv")).unwrap();
        text.lines()
            .skip(1)
            .map(|l| {
                let f: Vec<&str> = l.split(',').collect();
                (f[2].to_string(), f[1].parse().unwrap())
            })
            .collect()
    };
    let exact_dir = common::scratch_dir("run-check-exact");
    let o = common::run_reference(&exact_dir, &["--method", "exact", "--check"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let check: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(exact_dir.join("check.json")).unwrap())
            .unwrap();
    assert_eq!(check["method"], "exact");
    assert_eq!(
        check["comparison"]["events"]["max_abs_time_difference"],
        0.0
    );
    let exact = read_events(&exact_dir);

    for (method, below) in [("bdf", 1e-7), ("tsit45", 1e-8), ("newmark", 0.1)] {
        let dir = common::scratch_dir(&format!("run-check-{method}"));
        let o = common::run_reference(&dir, &["--method", method, "--check"]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let stdout = String::from_utf8_lossy(&o.stdout);
        assert!(
            stdout.contains("check against the exact solution: 22 of 22 events matched"),
            "{stdout}"
        );
        let check: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("check.json")).unwrap())
                .unwrap();
        let run = read_events(&dir);
        assert_eq!(run.len(), exact.len(), "{method}");
        let largest = run
            .iter()
            .zip(&exact)
            .map(|(a, b)| {
                assert_eq!(a.0, b.0, "{method}");
                (a.1 - b.1).abs()
            })
            .fold(0.0, f64::max);
        let reported = check["comparison"]["events"]["max_abs_time_difference"]
            .as_f64()
            .unwrap();
        assert!(
            (reported - largest).abs() <= 1e-15,
            "{method}: {reported} against {largest}"
        );
        assert!(reported > 0.0 && reported < below, "{method}: {reported}");
        assert_eq!(check["events"].as_array().unwrap().len(), exact.len());
    }
    let plain = common::scratch_dir("run-check-none");
    assert!(common::run_reference(&plain, &[]).status.success());
    assert!(!plain.join("check.json").exists());
}

/// A natural duration (a pulse's end and its tail, 0.58721358011 s + 20 s) is printed in the
/// run's header to 12 significant digits, not to the 16 of its double.
#[test]
fn the_header_prints_a_natural_duration_to_12_digits() {
    let out = common::scratch_dir("header-duration").join("out");
    let o = flexrock(&[
        "run",
        common::repo("models/zhang-makris.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout
            .lines()
            .next()
            .unwrap_or("")
            .contains("solution over 20.5872135801 s,"),
        "{stdout}"
    );
}

/// A row model given `--set` is refused naming the key and its value, not with the program's
/// own data structures.
#[test]
fn a_row_refuses_set_naming_the_key_and_the_value() {
    let row = common::repo("models/row-pair.toml");
    let out = common::scratch_dir("cli-row-set").join("out");
    let o = common::run_model(&row, &out, &["--set", "row.gaps=[0.01]"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--set row.gaps = [0.01]: not an option of a row model"),
        "{stderr}"
    );
    assert!(!stderr.contains("Setting {"), "{stderr}");
    assert!(!out.exists());
}

/// A command that takes one body says, of a row model, that it is a row, naming the file.
#[test]
fn single_body_commands_refuse_a_row_naming_the_file() {
    let row = common::repo("models/row-pair.toml");
    let path = row.to_str().unwrap();
    let out = common::scratch_dir("cli-row-single").join("out");
    let out = out.to_str().unwrap();
    for args in [
        vec!["props", path],
        vec!["props", path, "--set", "body.height=3"],
        vec!["compare", path, "--out", out],
        vec!["converge", path, "--out", out],
        vec!["fem", path, "--out", out],
        vec!["criteria", path, "--out", out],
    ] {
        let o = flexrock(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        assert!(
            stderr.contains(&format!("{path}: a model of a row of columns")),
            "{args:?}: {stderr}"
        );
        assert!(!stderr.contains("unknown field"), "{args:?}: {stderr}");
    }
    assert!(!std::path::Path::new(out).exists());
}

/// `--slenderness` is checked before anything is computed: 1 (B = H) and a slenderness whose
/// body the model refuses (B = 0.02 m of the paper's body buckles under its own weight) are
/// refused naming the flag.
#[test]
fn criteria_checks_every_slenderness_up_front() {
    for (value, rule) in [
        ("1", "above 0 and below 1"),
        (
            "0.005",
            "gives a body of width B = 0.02 m (H = 4 m) that the model refuses",
        ),
    ] {
        let message = common::refused_with(
            "criteria",
            &format!("slenderness-{value}"),
            &std::fs::read_to_string(reference_model()).unwrap(),
            &["--slenderness", value],
        );
        assert!(
            message.contains(&format!("--slenderness = {value}: ")) && message.contains(rule),
            "{message}"
        );
    }
}

/// `--set` solver keys stay when `--method` switches the family of methods: they were given for
/// that method, and meet its rules (before, `--set solver.dt=-1 --method newmark` ran at the
/// paper's 0.02 s).
#[test]
fn a_set_solver_key_survives_a_method_of_another_family() {
    let text = std::fs::read_to_string(common::repo("models/sine-pulse.toml")).unwrap();
    let message = common::refused_with(
        "run",
        "set-dt-newmark",
        &text,
        &["--set", "solver.dt=-1", "--method", "newmark"],
    );
    assert!(message.contains("--set solver.dt = -1"), "{message}");
    // Set beside the method, in either order.
    let message = common::refused_with(
        "run",
        "set-dt-set-newmark",
        &text,
        &["--set", "solver.dt=-1", "--set", "solver.method=newmark"],
    );
    assert!(message.contains("--set solver.dt = -1"), "{message}");
    let message = common::refused_with(
        "run",
        "set-rtol-newmark",
        &text,
        &["--set", "solver.rtol=1e-8", "--method", "newmark"],
    );
    assert!(
        message.contains("--set solver.rtol") && message.contains("newmark"),
        "{message}"
    );
}

/// `--set solver.method=exact` on a file that gives rtol is the file with its method changed:
/// refused as a file that says `method = "exact"` beside rtol is, with the same message (before,
/// the set method dropped the file's rtol and atol and ran).
#[test]
fn a_set_method_is_refused_as_the_same_method_written_in_the_file() {
    let body = "[body]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\
                [excitation]\nkind = \"free\"\n[simulation]\nduration = 1.0\nq0 = 0.01\n";
    let after_the_file = |message: &str| {
        let (_, rest) = message
            .split_once("model.toml")
            .unwrap_or_else(|| panic!("names the file: {message}"));
        rest.to_string()
    };
    let written = common::refused_with(
        "run",
        "method-written",
        &format!("{body}[solver]\nmethod = \"exact\"\nrtol = 1e-10\n"),
        &[],
    );
    let set = common::refused_with(
        "run",
        "method-set",
        &format!("{body}[solver]\nmethod = \"bdf\"\nrtol = 1e-10\n"),
        &["--set", "solver.method=exact"],
    );
    assert!(
        written.contains("solver.rtol = 1e-10") && written.contains("method = \"exact\""),
        "{written}"
    );
    assert_eq!(after_the_file(&set), after_the_file(&written));
    // A method whose rules the file's keys meet (of the same family) runs.
    let dir = common::scratch_dir("cli-method-set-same-family");
    let model = dir.join("model.toml");
    std::fs::write(
        &model,
        format!("{body}[solver]\nmethod = \"bdf\"\nrtol = 1e-10\n"),
    )
    .unwrap();
    let out = dir.join("out");
    let o = common::flexrock(&[
        "run",
        model.to_str().unwrap(),
        "--set",
        "solver.method=tsit45",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A relative record path is read from the directory of the model file: through a link to the
/// file, from beside the file it leads to (a model and its record stay a pair); after a linked
/// directory, `..` leads where the path says.
#[test]
fn a_record_path_is_read_beside_the_model_file() {
    let dir = common::scratch_dir("cli-record-links");
    let record = "t,acc\n0,0\n0.01,0.5\n0.02,0\n0.03,-0.5\n0.04,0\n";
    let model = |path: &str| {
        format!(
            "[body]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5e6\n\
             [excitation]\nkind = \"record\"\npath = \"{path}\"\nunits = \"m/s2\"\ntail = 0.1\n"
        )
    };
    // A linked file: a/link.toml -> ../b/model.toml, the record beside the target only.
    for sub in ["a", "b", "real/deep", "records"] {
        std::fs::create_dir_all(dir.join(sub)).unwrap();
    }
    std::fs::write(dir.join("b/r.csv"), record).unwrap();
    std::fs::write(dir.join("b/model.toml"), model("r.csv")).unwrap();
    std::os::unix::fs::symlink("../b/model.toml", dir.join("a/link.toml")).unwrap();
    // A linked directory: linked -> real/deep, the record in records/ beside the link, none in
    // real/records.
    std::fs::write(dir.join("records/r.csv"), record).unwrap();
    std::fs::write(dir.join("real/deep/model.toml"), model("../records/r.csv")).unwrap();
    std::os::unix::fs::symlink("real/deep", dir.join("linked")).unwrap();
    // Each record exists only where the rule leads.
    for model in ["a/link.toml", "linked/model.toml"] {
        let out = dir.join(format!("out-{}", model.replace('/', "-")));
        let o = common::run_model(&dir.join(model), &out, &[]);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{model}: {stderr}");
    }
}

/// A comparison in which no event happened prints no number derived from the empty set of
/// matched events.
#[test]
fn a_comparison_without_events_prints_no_nan() {
    let out = common::scratch_dir("cli-compare-no-events").join("out");
    let o = flexrock(&[
        "compare",
        reference_model().to_str().unwrap(),
        "--duration",
        "0.1",
        "--out",
        out.to_str().unwrap(),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(stdout.contains("event times: no event matched"), "{stdout}");
    assert!(!stdout.contains("NaN"), "{stdout}");
}
