//! `--timings-apart`: the wall times go to timings.json and every other file a command writes is
//! the same bytes from run to run (what validation/check.sh compares with the committed evidence).

use crate::common;

use std::path::{Path, PathBuf};

use crate::common::{file_names, flexrock, reference_model};

/// Runs `flexrock <args> --out <dir>` twice into two directories; returns both.
fn twice(name: &str, args: &[&str]) -> (PathBuf, PathBuf, String) {
    let base = common::scratch_dir(name);
    let dirs: Vec<PathBuf> = ["first", "second"].iter().map(|d| base.join(d)).collect();
    let mut stdout = String::new();
    for dir in &dirs {
        let mut full: Vec<&str> = args.to_vec();
        full.extend(["--timings-apart", "--out", dir.to_str().unwrap()]);
        let o = flexrock(&full);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    }
    (dirs[0].clone(), dirs[1].clone(), stdout)
}

/// Every file but timings.json has the same bytes in both directories, and none holds the
/// commit flexrock was built from, which timings.json holds for the command's summary; returns
/// the wall times of timings.json of the first.
fn same_but_timings(a: &Path, b: &Path) -> serde_json::Map<String, serde_json::Value> {
    assert_eq!(file_names(a), file_names(b));
    for name in file_names(a) {
        if name != "timings.json" {
            let (x, y) = (
                std::fs::read(a.join(&name)).unwrap(),
                std::fs::read(b.join(&name)).unwrap(),
            );
            assert!(x == y, "{name} differs between two runs");
            let text = String::from_utf8_lossy(&x);
            assert!(!text.contains("flexrock_commit"), "{name} holds the commit");
            assert!(
                !text.contains("flexrock_dirty"),
                "{name} holds the dirty flag"
            );
        }
    }
    let text = std::fs::read_to_string(a.join("timings.json")).expect("timings.json written");
    let timings: serde_json::Map<String, serde_json::Value> = serde_json::from_str(&text).unwrap();
    let mut times = serde_json::Map::new();
    let mut commits = 0;
    for (key, value) in timings {
        if key.ends_with("wall_time_s") {
            assert!(value.as_f64().unwrap() > 0.0, "{key} = {value}");
            times.insert(key, value);
        } else if key.ends_with("/flexrock_commit") {
            assert_eq!(value, common::built_commit(), "{key}");
            commits += 1;
        } else {
            assert!(key.ends_with("/flexrock_dirty"), "{key}");
            assert!(value.is_boolean() || value.is_null(), "{key} = {value}");
        }
    }
    assert_eq!(commits, 1, "{text}");
    times
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn run_puts_its_wall_time_in_timings_json_and_nothing_else_changes() {
    let model = reference_model();
    let (a, b, stdout) = twice("timings-run", &["run", model.to_str().unwrap()]);
    let timings = same_but_timings(&a, &b);
    assert_eq!(
        timings.keys().collect::<Vec<_>>(),
        ["summary.json/statistics/wall_time_s"]
    );
    let summary = json(&a.join("summary.json"));
    assert!(summary["statistics"]["wall_time_s"].is_null());
    assert!(summary["statistics"]["steps"].as_u64().unwrap() > 0);
    assert!(!stdout.contains(" ms"), "{stdout}");
}

#[test]
fn compare_and_converge_keep_every_time_apart() {
    let model = reference_model();
    let (a, b, stdout) = twice(
        "timings-compare",
        &["compare", model.to_str().unwrap(), "--duration", "2"],
    );
    let timings = same_but_timings(&a, &b);
    assert_eq!(timings.len(), 2, "{timings:?}");
    let compare = json(&a.join("compare.json"));
    for side in ["reference", "newmark"] {
        assert!(compare[side]["statistics"]["wall_time_s"].is_null());
        assert!(timings.contains_key(&format!("compare.json/{side}/statistics/wall_time_s")));
    }
    assert!(!stdout.contains(" ms"), "{stdout}");

    let (a, b, _) = twice(
        "timings-converge",
        &[
            "converge",
            model.to_str().unwrap(),
            "--duration",
            "2",
            "--dt",
            "0.02,0.01",
            "--rtol",
            "1e-4",
        ],
    );
    let timings = same_but_timings(&a, &b);
    let converge = json(&a.join("convergence.json"));
    let cases = converge["cases"].as_array().unwrap();
    // The reference and every case.
    assert_eq!(timings.len(), 1 + cases.len());
    assert!(cases.iter().all(|c| c["wall_time_s"].is_null()));
    let csv = std::fs::read_to_string(a.join("convergence.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let column = header.iter().position(|c| *c == "wall_time_s").unwrap();
    for row in csv.lines().skip(1) {
        assert_eq!(row.split(',').nth(column), Some(""), "{row}");
    }
}

#[test]
fn without_the_flag_the_times_stay_where_they_were() {
    let out = common::scratch_dir("timings-inline").join("result");
    let o = common::run_reference(&out, &[]);
    assert!(o.status.success());
    assert!(!out.join("timings.json").exists());
    let summary = json(&out.join("summary.json"));
    assert!(summary["statistics"]["wall_time_s"].as_f64().unwrap() > 0.0);
    assert_eq!(summary["flexrock_commit"], common::built_commit());
    assert!(summary["flexrock_dirty"].is_boolean() || summary["flexrock_dirty"].is_null());
    assert!(String::from_utf8_lossy(&o.stdout).contains(" ms;"));
}

/// Every summary says which build made it: the version, the commit and whether the work tree
/// differed from it (a row's summary.json, sweep.json and `props --json` here; the others above).
#[test]
fn every_summary_names_the_commit_it_was_built_from() {
    let dir = common::scratch_dir("timings-commit");
    let row = dir.join("row");
    let o = flexrock(&[
        "run",
        common::repo("models/row-pair.toml").to_str().unwrap(),
        "--duration",
        "0.5",
        "--out",
        row.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let sweep = dir.join("sweep");
    let model = reference_model();
    let o = flexrock(&[
        "sweep",
        model.to_str().unwrap(),
        "--vary",
        "excitation.amplitude=1,2",
        "--set",
        "simulation.duration=0.5",
        "--quiet",
        "--out",
        sweep.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let props = flexrock(&["props", model.to_str().unwrap(), "--json"]);
    let summaries = [
        json(&row.join("summary.json")),
        json(&sweep.join("sweep.json")),
        serde_json::from_slice(&props.stdout).unwrap(),
    ];
    for summary in summaries {
        assert_eq!(summary["flexrock_version"], env!("CARGO_PKG_VERSION"));
        assert_eq!(summary["flexrock_commit"], common::built_commit());
        assert!(summary["flexrock_dirty"].is_boolean() || summary["flexrock_dirty"].is_null());
    }
}
