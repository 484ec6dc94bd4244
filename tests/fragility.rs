//! `flexrock fragility`: the fit against the capacities the sweep's own rows give, a killed run
//! resumed to the same bytes, and bad input refused before anything is written.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::common::{self, ok, repo, scratch_dir};

/// A list file in `dir` naming the shipped records `names` by absolute path.
fn suite(dir: &Path, names: &[&str]) -> PathBuf {
    let list = dir.join("suite.list");
    let text: String = names
        .iter()
        .map(|n| format!("{}\n", repo("validation/records").join(n).display()))
        .collect();
    std::fs::write(&list, text).unwrap();
    list
}

fn fragility(records: &Path, out: &Path, extra: &[&str]) -> Command {
    let mut command = common::flexrock_command();
    command.args([
        "fragility",
        repo("models/elcentro1940.toml").to_str().unwrap(),
        "--records",
        records.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--quiet",
    ]);
    command.args(extra);
    command
}

fn refused(command: &mut Command, needle: &str) -> String {
    let o = command.output().unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(needle), "expected {needle:?} in: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap()
}

/// The three shipped records that overturn the body below 20 times their size.
const OVERTURNING: [&str; 3] = ["elCentro.AT2", "A-ELC180.AT2", "HEN-E.AT2"];

#[test]
fn the_fit_is_the_moments_of_the_capacities_the_sweep_rows_give() {
    let dir = scratch_dir("fragility-moments");
    let list = suite(&dir, &OVERTURNING);
    let out = dir.join("out");
    let args = ["--scale", "0.1:20", "--scan", "40", "--bootstrap", "0"];
    let mut last_fit = (0.0, 0.0);
    // The sweep's rows give the measures of each record scaled to its smallest overturning
    // scale, computed on the scaled samples: the capacities, by another road than the
    // command's (measure at scale 1 times scale^p).
    for (im, column) in [("pga", "pga_g"), ("arias", "arias_m_s"), ("cav", "cav_m_s")] {
        ok(&mut fragility(
            &list,
            &out,
            &[&args[..], &["--im", im]].concat(),
        ));
        let rows = common::sweep_rows(&out.join("sweep"));
        assert_eq!(rows.len(), 3);
        let logs: Vec<f64> = rows
            .iter()
            .map(|r| r[column].parse::<f64>().unwrap().ln())
            .collect();
        let mean = logs.iter().sum::<f64>() / 3.0;
        let squares: f64 = logs.iter().map(|y| (y - mean).powi(2)).sum();
        let summary = json(&out.join("fragility.json"));
        let fit = &summary["fits"][0];
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * b.abs();
        assert!(
            close(fit["theta"].as_f64().unwrap(), mean.exp()),
            "{im}: {fit}"
        );
        assert!(
            close(fit["beta"].as_f64().unwrap(), (squares / 3.0).sqrt()),
            "{im}: {fit}"
        );
        assert!(
            close(
                fit["beta_unbiased"].as_f64().unwrap(),
                (squares / 2.0).sqrt()
            ),
            "{im}: {fit}"
        );
        assert_eq!(fit["method"], "moments");
        assert_eq!(summary["im"], im);
        last_fit = (mean.exp(), (squares / 3.0).sqrt());
    }
    // The last (CAV, m/s): the tables name the unit, pelicun's columns are its own.
    let csv = std::fs::read_to_string(out.join("fragility.csv")).unwrap();
    assert!(
        csv.starts_with("state,im,theta_m_s,beta,beta_unbiased,theta_p5_m_s,"),
        "{csv}"
    );
    let pelicun = std::fs::read_to_string(out.join("fragility-pelicun.csv")).unwrap();
    let mut lines = pelicun.lines();
    assert_eq!(
        lines.next().unwrap(),
        "ID,Incomplete,Demand-Type,Demand-Unit,Demand-Offset,Demand-Directional,LS1-Family,\
         LS1-Theta_0,LS1-Theta_1,LS1-DamageStateWeights"
    );
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &row[..7],
        &[
            "flexrock.elcentro1940.overturning",
            "0",
            "Cumulative Absolute Velocity",
            "mps",
            "0",
            "0",
            "lognormal"
        ]
    );
    // Each record is named by its PEER AT2 title line (event, station, component), else by
    // its file's name (elCentro.AT2 has a title of another form), in fragility.json and on the
    // y axis of capacities.svg.
    let summary = json(&out.join("fragility.json"));
    let labels: Vec<&str> = (summary["records"].as_array().unwrap().iter())
        .map(|r| r["label"].as_str().unwrap())
        .collect();
    assert_eq!(
        labels,
        [
            "elCentro.AT2",
            "BORREGO MOUNTAIN, EL CENTRO ARRAY #9, 180",
            "CHI-CHI, HEN, E"
        ]
    );
    let svg = std::fs::read_to_string(out.join("capacities.svg")).unwrap();
    for label in ["elCentro.AT2", "CHI-CHI, HEN, E", "BORREGO MOUNTAIN"] {
        assert!(
            svg.lines().any(|l| l.trim().starts_with(label)),
            "{label} not in capacities.svg"
        );
    }
    // The legends give the fit's median and dispersion with the unit, as the moments above
    // give them (to the 3 and 2 digits they print): fragility.svg by the curve, capacities.svg
    // by the median's line.
    let number_after = |file: &str, needle: &str| -> f64 {
        let text = std::fs::read_to_string(out.join(file)).unwrap();
        let at = (text.find(needle)).unwrap_or_else(|| panic!("{needle} not in {file}"));
        let rest = &text[at + needle.len()..];
        rest[..rest.find([' ', ',', '<', '\n']).unwrap()]
            .parse()
            .unwrap()
    };
    let (theta, beta) = last_fit;
    let drawn = number_after("fragility.svg", "lognormal fit: θ = ");
    assert!((drawn / theta - 1.0).abs() < 5e-3, "{drawn} for {theta}");
    let drawn = number_after("fragility.svg", " m/s, β = ");
    assert!((drawn / beta - 1.0).abs() < 5e-2, "{drawn} for {beta}");
    let drawn = number_after("capacities.svg", "median θ = ");
    assert!((drawn / theta - 1.0).abs() < 5e-3, "{drawn} for {theta}");
}

#[test]
fn a_killed_fragility_run_resumes_to_the_same_bytes() {
    let dir = scratch_dir("fragility-kill");
    let list = repo("validation/records/records.list");
    let args = [
        "--scale",
        "0.1:20",
        "--scan",
        "20",
        "--chunk-size",
        "1",
        "--threads",
        "1",
        "--bootstrap",
        "200",
    ];
    let reference = dir.join("reference");
    ok(&mut fragility(&list, &reference, &args));

    let out = dir.join("killed");
    common::kill_after_chunks(&mut fragility(&list, &out, &args), &out.join("sweep"), 2);
    assert!(!out.join("fragility.json").exists());
    let resumed = ok(&mut fragility(&list, &out, &args));
    let stdout = String::from_utf8_lossy(&resumed.stdout);
    assert!(stdout.contains("found done"), "{stdout}");
    assert!(
        !stdout.contains(" 0 found done"),
        "nothing was resumed: {stdout}"
    );
    for sub in ["", "sweep"] {
        let (a, b) = (reference.join(sub), out.join(sub));
        let names = common::file_names(&a);
        assert_eq!(names, common::file_names(&b));
        for name in names.iter().filter(|n| a.join(n).is_file()) {
            let (x, y) = (
                std::fs::read(a.join(name)).unwrap(),
                std::fs::read(b.join(name)).unwrap(),
            );
            if name == "fragility.json" || name == "sweep.json" {
                // The only difference allowed: where the output directory is.
                let strip = |bytes: &[u8], dir: &Path| {
                    String::from_utf8_lossy(bytes).replace(dir.to_str().unwrap(), "OUT")
                };
                assert_eq!(strip(&x, &reference), strip(&y, &out), "{sub}/{name}");
            } else {
                assert!(x == y, "{sub}/{name} differs after the resume");
            }
        }
    }
}

#[test]
fn bad_input_is_refused_before_anything_is_written() {
    let dir = scratch_dir("fragility-refused");
    let out = dir.join("out");
    let one = suite(&dir, &["elCentro.AT2"]);
    let stderr = refused(&mut fragility(&one, &out, &[]), "--records");
    assert!(stderr.contains("at least 2"), "{stderr}");
    assert!(!out.exists());
    let missing = dir.join("no-such-suite");
    let stderr = refused(&mut fragility(&missing, &out, &[]), "--records");
    assert!(stderr.contains("no such file or directory"), "{stderr}");
    let record = repo("validation/records/elCentro.AT2");
    let stderr = refused(&mut fragility(&record, &out, &[]), "--records");
    assert!(
        stderr.contains("is a record file (peer-at2), not a suite"),
        "{stderr}"
    );
    assert!(!out.exists());
    let list = repo("validation/records/records.list");
    let stderr = refused(&mut fragility(&list, &out, &["--im", "pgx"]), "--im");
    assert!(stderr.contains("pga, pgv, pgd, arias, cav, sa"), "{stderr}");
    refused(
        &mut fragility(&list, &out, &["--period", "0.5"]),
        "--period",
    );
    refused(&mut fragility(&list, &out, &["--scale", "0:2"]), "--scale");
    assert!(!out.exists());
    // No record overturns up to scale 0.2: every capacity is censored, no fit exists.
    let stderr = refused(
        &mut fragility(&list, &out, &["--scale", "0.1:0.2", "--scan", "3"]),
        "0 of 5 records reached the damage state",
    );
    assert!(stderr.contains("--records"), "{stderr}");
    assert!(!out.join("fragility.json").exists());
    assert!(!out.join("fragility.csv").exists());
}
