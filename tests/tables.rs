//! No table holds a value derived from an empty one: every column of sweep.csv, compare.csv,
//! convergence.csv, events.csv and episodes.csv is scanned, on runs made to have empty fields
//! (invalid and failed sweep points, a record without a period, a search that finds nothing,
//! Newmark missing events, a run that ends while rocking), for the rule that a derived field
//! is empty wherever a field it derives from is empty.

use std::collections::HashMap;
use std::path::Path;

use crate::common::{flexrock, repo, scratch_dir};

type Row = HashMap<String, String>;

fn table(path: &Path) -> (Vec<String>, Vec<Row>) {
    let mut reader = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let headers: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let rows = reader
        .records()
        .map(|r| {
            headers
                .iter()
                .cloned()
                .zip(r.unwrap().iter().map(String::from))
                .collect()
        })
        .collect();
    (headers, rows)
}

fn run(args: &[&str]) {
    let o = flexrock(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// For every row: where any of `sources` is empty, every one of `derived` is empty too.
fn derived_empty(name: &str, rows: &[Row], sources: &[&str], derived: &[&str]) -> usize {
    let mut seen = 0;
    for row in rows {
        if sources.iter().any(|s| row[*s].is_empty()) {
            seen += 1;
            for d in derived {
                assert_eq!(
                    row[*d], "",
                    "{name}: {d} holds a value beside an empty {sources:?}: {row:?}"
                );
            }
        }
    }
    seen
}

#[test]
fn sweep_rows_of_points_that_did_not_run_hold_nothing_derived() {
    let dir = scratch_dir("tables-sweep");
    let out = dir.join("out");
    // 300 m/s^2 is beyond 20 g and E = 1000 Pa buckles: invalid points beside valid ones.
    run(&[
        "sweep",
        repo("models/pulse-map.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.amplitude=1,4,300",
        "--vary",
        "body.youngs_modulus=5e6,1e3",
        "--quiet",
    ]);
    let (headers, rows) = table(&out.join("sweep.csv"));
    let after_reason: Vec<&str> = headers
        .iter()
        .skip_while(|h| *h != "reason")
        .skip(1)
        .map(String::as_str)
        .collect();
    let mut not_run = 0;
    for row in &rows {
        if row["status"] != "ok" {
            not_run += 1;
            assert!(!row["reason"].is_empty(), "{row:?}");
            for column in &after_reason {
                assert_eq!(
                    row[*column], "",
                    "{column} of a point that did not run: {row:?}"
                );
            }
        } else {
            assert_eq!(row["reason"], "");
        }
        // t_overturn exists exactly when the body overturned.
        assert_eq!(
            row["t_overturn"].is_empty(),
            row["overturned"] != "true",
            "{row:?}"
        );
    }
    assert_eq!(not_run, 4);
    assert!(rows.iter().any(|r| r["overturned"] == "true"));
}

#[test]
fn sweep_over_a_record_leaves_the_period_columns_empty() {
    let dir = scratch_dir("tables-record");
    let out = dir.join("out");
    run(&[
        "sweep",
        repo("models/elcentro1940.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.scale=0.5,1",
        "--set",
        "excitation.end=8",
        "--quiet",
    ]);
    let (_, rows) = table(&out.join("sweep.csv"));
    assert_eq!(rows.len(), 2);
    for row in &rows {
        assert_eq!(row["status"], "ok");
        // A record has no period: nothing is divided by one.
        assert_eq!(row["omega_p_over_p"], "");
        assert_eq!(row["T_over_Tp"], "");
        assert!(!row["amplitude_over_g_tan_alpha"].is_empty());
    }
}

#[test]
fn compare_rows_of_unmatched_events_hold_no_difference() {
    let dir = scratch_dir("tables-compare");
    let out = dir.join("out");
    // dt = 0.1 s misses 10 of the 22 events of the paper's example and adds one.
    run(&[
        "compare",
        repo("models/ichinose1986.toml").to_str().unwrap(),
        "--dt",
        "0.1",
        "--out",
        out.to_str().unwrap(),
    ]);
    let (_, rows) = table(&out.join("compare.csv"));
    let missed = derived_empty(
        "compare.csv",
        &rows,
        &["t_newmark"],
        &["t_difference", "q_newmark", "qdot_after_newmark"],
    );
    let spurious = derived_empty(
        "compare.csv",
        &rows,
        &["t_reference"],
        &["t_difference", "q_reference", "qdot_after_reference"],
    );
    assert!(
        missed >= 1 && spurious >= 1,
        "missed {missed}, spurious {spurious}"
    );
    for row in &rows {
        if !row["t_reference"].is_empty() && !row["t_newmark"].is_empty() {
            assert!(!row["t_difference"].is_empty(), "{row:?}");
        }
    }
}

#[test]
fn convergence_rows_hold_errors_only_beside_a_finished_case() {
    let dir = scratch_dir("tables-converge");
    let out = dir.join("out");
    run(&[
        "converge",
        repo("models/ichinose1986.toml").to_str().unwrap(),
        "--dt",
        "0.2,0.1",
        "--rtol",
        "1e-2",
        "--out",
        out.to_str().unwrap(),
    ]);
    let (headers, rows) = table(&out.join("convergence.csv"));
    assert!(headers.contains(&"status".to_string()));
    for row in &rows {
        // A Newmark case has a dt and no rtol, an adaptive one the reverse.
        assert_ne!(row["dt"].is_empty(), row["rtol"].is_empty(), "{row:?}");
        let errors = ["max_q_error", "max_event_time_error", "peak_error"];
        if row["status"] == "ok" {
            for e in errors {
                assert!(!row[e].is_empty(), "{e}: {row:?}");
            }
        } else {
            for e in errors {
                assert_eq!(row[e], "", "{e} of a case that did not finish: {row:?}");
            }
        }
    }
}

#[test]
fn events_and_episodes_hold_nothing_derived_from_what_did_not_happen() {
    let dir = scratch_dir("tables-episodes");
    for (name, model) in [
        ("paper", "models/ichinose1986.toml"),
        ("rigid", "validation/models/rigid-free-rocking.toml"),
        ("pulse", "models/sine-pulse.toml"),
    ] {
        let out = dir.join(name);
        run(&[
            "run",
            repo(model).to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        let (_, events) = table(&out.join("events.csv"));
        for row in &events {
            for (column, value) in row {
                assert!(
                    !value.is_empty(),
                    "events.csv of {model}: {column} empty in {row:?}"
                );
            }
        }
        let (_, episodes) = table(&out.join("episodes.csv"));
        assert!(!episodes.is_empty(), "{model}");
        derived_empty(name, &episodes, &["t_end"], &["duration"]);
        derived_empty(
            name,
            &episodes,
            &["qdot_before_uplift"],
            &["floor_acc_at_uplift"],
        );
        derived_empty(
            name,
            &episodes,
            &["floor_acc_at_uplift"],
            &["qdot_after_uplift"],
        );
        derived_empty(
            name,
            &episodes,
            &["qdot_before_uplift"],
            &[
                "kinetic_energy_before_uplift",
                "kinetic_energy_after_uplift",
            ],
        );
        for row in &episodes {
            assert_eq!(
                row["t_end"].is_empty(),
                row["ended_by"] == "run-end",
                "{row:?}"
            );
            for column in [
                "qdot_before_landing",
                "qdot_after_landing",
                "kinetic_energy_before_landing",
                "kinetic_energy_after_landing",
            ] {
                assert_eq!(
                    row[column].is_empty(),
                    row["ended_by"] != "landing",
                    "{row:?}"
                );
            }
        }
    }
}

/// Numbers far from 1 take an exponent, so that no field is longer than 37 characters and no
/// row of history.csv longer than 391 bytes: a motion of 1e-200 m, which the plain form writes
/// with 200 zeros, keeps the file within the bound the limits page gives, and `flexrock plot`
/// reads it back.
#[test]
fn history_rows_stay_within_their_bound_for_tiny_and_huge_numbers() {
    let out = scratch_dir("tables-tiny-numbers");
    let model = repo("models/ichinose1986.toml");
    run(&[
        "run",
        model.to_str().unwrap(),
        "--set",
        "simulation.qdot0=1e-200",
        "--set",
        "excitation.amplitude=0",
        "--duration",
        "2",
        "--method",
        "bdf",
        "--out",
        out.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let mut lines = text.lines();
    lines.next();
    let mut rows = 0;
    let mut tiny = 0;
    for line in lines {
        rows += 1;
        assert!(line.len() < 391, "{} bytes: {line}", line.len());
        for field in line.split(',') {
            assert!(field.len() <= 37, "{field}");
            if let Ok(x) = field.parse::<f64>() {
                if x != 0.0 && x.abs() < 1e-150 {
                    tiny += 1;
                    assert!(field.contains("e-"), "{field}");
                }
            }
        }
    }
    assert!(rows > 400 && tiny > 400, "{rows} rows, {tiny} tiny numbers");
    let header = text.lines().next().unwrap().len() + 1;
    assert!(text.len() <= header + rows * 391);
    run(&["plot", out.to_str().unwrap(), "--format", "svg"]);
}
