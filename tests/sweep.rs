//! `flexrock sweep`: rows against separate runs and closed forms, invalid points, refused
//! requests, thread-count independence, resuming after kills, shards and their merge, the
//! minimum search against independent runs, and the rigid limit of the spectrum.

use crate::common;

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::common::{flexrock, flexrock_in, repo, scratch_dir};
use flexrock_core::model::{Model, Overrides, Setting};

fn number(row: &HashMap<String, String>, column: &str) -> f64 {
    row[column]
        .parse()
        .unwrap_or_else(|_| panic!("{column} = {:?} is not a number", row[column]))
}

fn run(args: &[&str]) -> std::process::Output {
    let o = flexrock(args);
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

fn pulse_model() -> PathBuf {
    repo("models/pulse-map.toml")
}

/// The pulse model with these keys set, as `flexrock run --set` would build it.
fn model_with(settings: &[(&str, &str)]) -> Model {
    let overrides = Overrides {
        settings: settings
            .iter()
            .map(|(k, v)| Setting::parse(&format!("{k}={v}")).unwrap())
            .collect(),
        ..Overrides::default()
    };
    Model::load(&pulse_model(), &overrides).expect("the model loads")
}

fn files_of(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    files.sort();
    files
}

#[test]
fn every_row_is_the_run_of_its_point_and_the_dimensionless_numbers_are_the_closed_forms() {
    let dir = scratch_dir("sweep-rows");
    run(&[
        "sweep",
        pulse_model().to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--vary",
        "excitation.amplitude=2,3.5,5",
        "--vary",
        "excitation.period=0.6,0.8",
        "--quiet",
    ]);
    let rows = crate::common::sweep_rows(&dir);
    assert_eq!(rows.len(), 6);
    let (h, b, g) = (4.0f64, 0.7f64, 9.81f64);
    let alpha = (b / h).atan();
    let p = (3.0 * g / (4.0 * 0.5 * (h * h + b * b).sqrt())).sqrt();
    let mut overturned = 0;
    for (i, row) in rows.iter().enumerate() {
        // The last axis varies fastest.
        let (a, tp) = (["2", "3.5", "5"][i / 2], ["0.6", "0.8"][i % 2]);
        assert_eq!(row["point"], i.to_string());
        assert_eq!(
            (
                row["excitation.amplitude"].as_str(),
                row["excitation.period"].as_str()
            ),
            (a, tp)
        );
        assert_eq!(row["status"], "ok");
        let model = model_with(&[("excitation.amplitude", a), ("excitation.period", tp)]);
        // Duration from the tail: one pulse plus 5 s.
        assert_eq!(model.duration, tp.parse::<f64>().unwrap() + 5.0);
        let solution = flexrock::commands::run::simulate(&model).unwrap();
        let max_q = solution.max_q.value.abs().max(solution.min_q.value.abs());
        assert_eq!(row["overturned"], solution.overturned.to_string());
        assert_eq!(
            row["n_uplift"],
            solution
                .count(flexrock_core::physics::automaton::EventKind::Uplift)
                .to_string()
        );
        assert_eq!(row["steps"], solution.stats.steps.to_string());
        let tol = 1e-12;
        assert!(
            (number(row, "max_abs_q_over_B") - max_q / b).abs() < tol,
            "{row:?}"
        );
        if solution.overturned {
            overturned += 1;
            assert_eq!(number(row, "t_overturn"), solution.t_overturn.unwrap());
            assert_eq!(number(row, "max_abs_q_over_B"), 1.0);
        }
        // Closed forms of book/src/model.md §3 (restoring force): after an uplift |s| peaks at s_n
        // (at the uplift), and r = q - s_n (B - q)/(B - s_n) grows with |q|.
        let s_n = model.constants.uplift_displacement;
        if row["n_uplift"] != "0" {
            assert!(
                (number(row, "max_abs_s_over_s_n") - 1.0).abs() < tol,
                "{row:?}"
            );
            let r = max_q - s_n * (b - max_q) / (b - s_n);
            assert!(
                (number(row, "max_abs_r_over_B") - r / b).abs() < tol,
                "{row:?}"
            );
        } else {
            assert_eq!(number(row, "max_abs_r_over_B"), 0.0);
        }
        let (a, tp): (f64, f64) = (a.parse().unwrap(), tp.parse().unwrap());
        let close = |column: &str, expected: f64| {
            let got = number(row, column);
            assert!(
                (got - expected).abs() <= 1e-13 * expected.abs(),
                "{column}: {got} against {expected}"
            );
        };
        close("alpha", alpha);
        close("p", p);
        close("amplitude_over_g_tan_alpha", a / (g * alpha.tan()));
        close("omega_p_over_p", 2.0 * std::f64::consts::PI / tp / p);
        close("T_over_Tp", model.constants.period / tp);
        close(
            "amplitude_over_uplift_acceleration",
            a / model.constants.quasi_static_uplift_acceleration,
        );
    }
    // models/pulse-map.toml: 3.5 m/s^2 at 0.8 s rocks without overturning, 5 m/s^2 overturns.
    assert!(overturned > 0 && overturned < 6, "{overturned}");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(summary["counts"]["ok"], 6);
    assert_eq!(summary["counts"]["overturned"], overturned);
    assert!(dir.join("map.svg").is_file());
}

#[test]
fn invalid_points_are_rows_with_their_reason_and_the_sweep_goes_on() {
    let dir = scratch_dir("sweep-invalid");
    run(&[
        "sweep",
        pulse_model().to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        // 300 m/s^2 is beyond the 20 g limit; a negative Young's modulus is no body.
        "--vary",
        "excitation.amplitude=1,300",
        "--vary",
        "body.youngs_modulus=5e6,-1",
        "--quiet",
    ]);
    let rows = crate::common::sweep_rows(&dir);
    let status: Vec<&str> = rows.iter().map(|r| r["status"].as_str()).collect();
    assert_eq!(status, ["ok", "invalid", "invalid", "invalid"]);
    assert!(
        rows[1]["reason"].contains("body.youngs_modulus"),
        "{}",
        rows[1]["reason"]
    );
    assert!(
        rows[2]["reason"].contains("excitation.amplitude"),
        "{}",
        rows[2]["reason"]
    );
    assert_eq!(rows[1]["overturned"], "");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(summary["counts"]["invalid"], 3);
}

#[test]
fn bad_requests_are_refused_before_anything_is_written() {
    let model = pulse_model();
    let model = model.to_str().unwrap();
    for (name, args, needle) in [
        (
            "unknown key",
            vec!["--vary", "excitation.ampltude=1,2"],
            "ampltude",
        ),
        (
            "bad range",
            vec!["--vary", "excitation.amplitude=3:1:0.5"],
            "--vary excitation.amplitude",
        ),
        ("no axis", vec![], "--vary"),
        (
            "twice",
            vec![
                "--vary",
                "excitation.period=1,2",
                "--vary",
                "excitation.period=3",
            ],
            "once",
        ),
        (
            "searched and varied",
            vec![
                "--vary",
                "excitation.amplitude=1,2",
                "--find-min",
                "excitation.amplitude=1:5",
            ],
            "once",
        ),
        (
            "empty interval",
            vec!["--find-min", "excitation.amplitude=5:1"],
            "--find-min",
        ),
        (
            "bad shard",
            vec!["--vary", "excitation.period=1,2", "--shard", "4/3"],
            "--shard",
        ),
        (
            "bad set",
            vec![
                "--vary",
                "excitation.period=1,2",
                "--set",
                "solver.methd=bdf",
            ],
            "methd",
        ),
        (
            "no match",
            vec!["--vary", "excitation.path=nowhere/*.AT2"],
            "matches no file",
        ),
        (
            "zero scan",
            vec!["--find-min", "excitation.amplitude=1:5", "--scan", "1"],
            "--scan",
        ),
        (
            "nan tol",
            vec!["--find-min", "excitation.amplitude=1:5", "--tol", "nan"],
            "--tol",
        ),
        (
            "zero chunk",
            vec!["--vary", "excitation.period=1,2", "--chunk-size", "0"],
            "--chunk-size",
        ),
        (
            "search beyond 20 g",
            vec!["--find-min", "excitation.amplitude=1:250"],
            "--find-min excitation.amplitude = 1:250: the search interval must lie within the \
             model's rules, and at its upper end, excitation.amplitude = 250, the model is \
             refused",
        ),
        (
            "rigid form without a search",
            vec!["--vary", "excitation.period=1,2", "--rigid-form", "full"],
            "--rigid-form",
        ),
        (
            "unknown rigid form",
            vec![
                "--find-min",
                "excitation.amplitude=1:5",
                "--rigid-form",
                "exact",
            ],
            "exact",
        ),
        (
            "zero threads",
            vec!["--vary", "excitation.period=1,2", "--threads", "0"],
            "--threads",
        ),
        (
            "huge axis",
            vec!["--vary", "excitation.period=lin:0.1:1:1000000000"],
            "1000000",
        ),
        (
            "too many points",
            vec![
                "--vary",
                "excitation.period=lin:0.1:1:1000000",
                "--vary",
                "excitation.amplitude=lin:0.1:1:1000",
            ],
            "at most",
        ),
        (
            "missing sweep file",
            vec!["--sweep-file", "/nonexistent/sweep.toml"],
            "sweep.toml",
        ),
        (
            "device sweep file",
            vec!["--sweep-file", "/dev/zero"],
            "character device",
        ),
    ] {
        let dir = scratch_dir(&format!("sweep-refused-{}", name.replace(' ', "-")));
        let out = dir.join("out");
        let mut all = vec!["sweep", model, "--out", out.to_str().unwrap(), "--quiet"];
        all.extend(args);
        let o = flexrock(&all);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{name}: {stderr}");
        assert!(stderr.contains(needle), "{name}: {stderr}");
        assert!(!out.exists(), "{name}: wrote {}", out.display());
    }
}

/// A sweep of 24 x 20 points over the pulse model, with the given extra arguments.
fn grid_sweep(out: &Path, extra: &[&str]) -> std::process::Command {
    let mut command = common::flexrock_command();
    command.args([
        "sweep",
        pulse_model().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.period=lin:0.3:1.5:24",
        "--vary",
        "excitation.amplitude=lin:1:8:20",
        "--quiet",
    ]);
    command.args(extra);
    command
}

fn status_ok(command: &mut std::process::Command) {
    let o = command.output().unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn the_output_is_the_same_whatever_the_thread_count_and_chunk_size() {
    let dir = scratch_dir("sweep-threads");
    let (one, two) = (dir.join("one"), dir.join("two"));
    status_ok(&mut grid_sweep(&one, &["--threads", "1"]));
    status_ok(&mut grid_sweep(
        &two,
        &["--threads", "2", "--chunk-size", "7"],
    ));
    let (a, b) = (files_of(&one), files_of(&two));
    assert_eq!(
        a.iter().map(|f| &f.0).collect::<Vec<_>>(),
        ["map.svg", "sweep.csv", "sweep.json"]
    );
    // The chunk size is part of the plan in sweep.json; the table and the map are the same.
    assert_eq!(a[0], b[0], "map.svg differs");
    assert_eq!(a[1], b[1], "sweep.csv differs");
}

#[test]
fn a_sweep_killed_at_random_moments_resumes_to_the_same_bytes() {
    let dir = scratch_dir("sweep-kill");
    let reference = dir.join("reference");
    let started = std::time::Instant::now();
    status_ok(&mut grid_sweep(
        &reference,
        &["--chunk-size", "16", "--threads", "2"],
    ));
    // The kill times are shares of the whole run's time on this machine, so that the sweep is
    // killed at every stage however fast the machine (and flexrock) is.
    let whole = started.elapsed().max(std::time::Duration::from_millis(20));
    let expected = files_of(&reference);

    let out = dir.join("killed");
    // A fixed pseudo-random sequence of kill times, 2 to 35 % of the whole run after the start.
    // A machine whose load falls can finish a run before three kills: then the run is made
    // again from nothing with kill times half as long, at most six times.
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut kills = 0;
    let mut whole = whole;
    for _ in 0..6 {
        if out.exists() {
            std::fs::remove_dir_all(&out).unwrap();
        }
        kills = 0;
        let mut finished = false;
        for _ in 0..200 {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            let delay = whole.mul_f64(0.02 + 0.33 * (state % 1000) as f64 / 1000.0);
            let mut child = grid_sweep(&out, &["--chunk-size", "16", "--threads", "2"])
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::piped())
                .spawn()
                .unwrap();
            std::thread::sleep(delay);
            match child.try_wait().unwrap() {
                Some(status) => {
                    assert!(status.success(), "a resumed run failed");
                    finished = true;
                    break;
                }
                None => {
                    // SIGKILL: no chance to clean up.
                    child.kill().unwrap();
                    child.wait().unwrap();
                    kills += 1;
                }
            }
        }
        if !finished {
            status_ok(&mut grid_sweep(
                &out,
                &["--chunk-size", "16", "--threads", "2"],
            ));
        }
        if kills >= 3 {
            break;
        }
        whole /= 2;
    }
    assert!(kills >= 3, "the sweep was killed only {kills} times");
    assert_eq!(files_of(&out), expected, "after {kills} kills");
    // Nothing left behind: no chunks, no temporary directories.
    assert_eq!(
        common::file_names(&out),
        ["map.svg", "sweep.csv", "sweep.json"]
    );
    // Running it again finds it done and changes nothing.
    let o = grid_sweep(&out, &["--chunk-size", "16", "--threads", "2"])
        .output()
        .unwrap();
    assert!(String::from_utf8_lossy(&o.stdout).contains("0 computed now"));
    assert_eq!(files_of(&out), expected);
}

#[test]
fn a_directory_of_another_sweep_is_refused_and_left_alone() {
    let dir = scratch_dir("sweep-other");
    status_ok(&mut grid_sweep(&dir, &[]));
    let before = files_of(&dir);
    let o = flexrock(&[
        "sweep",
        pulse_model().to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--vary",
        "excitation.period=0.5,0.6",
        "--quiet",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("another sweep"));
    assert_eq!(files_of(&dir), before);
    // The same sweep named by another path (from another directory) is recognised as done.
    let o = flexrock_in(
        &repo(""),
        &[
            "sweep",
            "models/pulse-map.toml",
            "--out",
            dir.to_str().unwrap(),
            "--vary",
            "excitation.period=lin:0.3:1.5:24",
            "--vary",
            "excitation.amplitude=lin:1:8:20",
            "--quiet",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("0 computed now"));
    assert_eq!(files_of(&dir), before);
}

#[test]
fn shards_run_as_separate_processes_merge_to_the_single_process_result() {
    let dir = scratch_dir("sweep-shards");
    let single = dir.join("single");
    status_ok(&mut grid_sweep(&single, &["--chunk-size", "25"]));
    let sharded = dir.join("sharded");
    let children: Vec<_> = (1..=3)
        .map(|k| {
            grid_sweep(
                &sharded,
                &["--chunk-size", "25", "--shard", &format!("{k}/3")],
            )
            .spawn()
            .unwrap()
        })
        .collect();
    for mut child in children {
        assert!(child.wait().unwrap().success());
    }
    let merged = dir.join("merged");
    run(&[
        "sweep",
        "merge",
        sharded.to_str().unwrap(),
        "--out",
        merged.to_str().unwrap(),
    ]);
    assert_eq!(files_of(&merged), files_of(&single));

    // A gap: shards 1 and 3 only.
    let refuse = |dirs: &[PathBuf], needle: &str| {
        let out = dir.join("refused");
        let mut args = vec!["sweep".to_string(), "merge".to_string()];
        args.extend(dirs.iter().map(|d| d.to_string_lossy().into_owned()));
        args.extend(["--out".to_string(), out.to_string_lossy().into_owned()]);
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = flexrock(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{stderr}");
        assert!(stderr.contains(needle), "{needle}: {stderr}");
        assert!(!out.exists());
    };
    let shard = |k: usize, n: usize| sharded.join(format!("shard-{k}-of-{n}"));
    refuse(&[shard(1, 3), shard(3, 3)], "gap");
    refuse(&[shard(1, 3), shard(2, 3)], "missing at the end");
    // An overlap: shard 1 of 2 covers shard 1 of 3 and part of 2.
    status_ok(&mut grid_sweep(
        &sharded,
        &["--chunk-size", "25", "--shard", "1/2"],
    ));
    refuse(&[shard(1, 2), shard(2, 3), shard(3, 3)], "overlap");
    // A shard of another sweep.
    let other = dir.join("other");
    status_ok(&mut grid_sweep(
        &other,
        &["--chunk-size", "20", "--shard", "2/3"],
    ));
    refuse(
        &[shard(1, 3), other.join("shard-2-of-3"), shard(3, 3)],
        "another sweep",
    );
}

#[test]
fn the_minimum_search_brackets_a_transition_and_reports_the_safe_band_above_it() {
    // book/src/model.md §7c (non-monotonic overturning): a one-cosine pulse of 0.7 s overturns the
    // reference body from about 15.8 m/s^2, leaves it standing in a band above about 21 m/s^2 and
    // overturns it again above about 23 m/s^2.
    let dir = scratch_dir("sweep-find-min");
    run(&[
        "sweep",
        pulse_model().to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--set",
        "excitation.shape=symmetric",
        "--vary",
        "excitation.period=0.7",
        "--find-min",
        "excitation.amplitude=0.5:60",
        "--scan",
        "120",
        "--tol",
        "1e-3",
        "--quiet",
    ]);
    let rows = crate::common::sweep_rows(&dir);
    let row = &rows[0];
    let (min, safe) = (number(row, "min_overturning"), number(row, "safe_below"));
    assert!(min - safe <= 1e-3 && min > safe, "{row:?}");
    // Independent runs at the ends of the bracket.
    let overturns = |a: f64| {
        let model = model_with(&[
            ("excitation.shape", "symmetric"),
            ("excitation.period", "0.7"),
            ("excitation.amplitude", &a.to_string()),
        ]);
        flexrock::commands::run::simulate(&model)
            .unwrap()
            .overturned
    };
    assert!(overturns(min) && !overturns(safe));
    // Every scanned value below the bracket stands: the bracket is the first transition.
    for i in 0..120 {
        let a = 0.5 + 59.5 * i as f64 / 119.0;
        if a < safe {
            assert!(
                !overturns(a),
                "{a} overturns below the reported minimum {min}"
            );
        }
    }
    // Two bands, with a standing value between them, checked by independent runs.
    assert_eq!(row["n_bands"], "2", "{row:?}");
    let bands: Vec<(f64, f64)> = row["overturning_bands"]
        .split(';')
        .map(|band| {
            let (lo, hi) = band.split_once('-').unwrap();
            (lo.parse().unwrap(), hi.parse().unwrap())
        })
        .collect();
    let gap_value = 0.5 * (bands[0].1 + bands[1].0);
    assert!(!overturns(gap_value), "{gap_value} is in the safe band");
    assert!(overturns(bands[0].1) && overturns(bands[1].0));
    assert_eq!(bands[1].1, 60.0);
    assert!(dir.join("spectrum.svg").is_file());
}

/// `--rigid-form full` searches Housner's block by the full equation: under the 0.8 s one-sine
/// pulse the reference block overturns from 3.033 m/s^2 instead of the small-angle form's
/// 2.998 m/s^2 (independent calculations, core/tests/rigid_forms.rs), to 0.2 %. sweep.csv says
/// so in a `rigid_form` column after Housner's two, and sweep.json in `find_min.rigid_form`;
/// the default sweep has neither, and the elastic body's and the rigid limit's columns are the
/// same in both. A sweep file's `rigid_form` does the same, and an unknown one is refused.
#[test]
fn a_full_form_sweep_searches_and_names_the_full_equations_block() {
    let dir = scratch_dir("sweep-rigid-form");
    let model = pulse_model();
    let model = model.to_str().unwrap();
    let search = [
        "--vary",
        "excitation.period=0.8",
        "--find-min",
        "excitation.amplitude=1.8:8",
        "--tol",
        "1e-4",
    ];
    let sweep = |out: &Path, extra: &[&str]| first_row_and_plan(model, out, &search, extra);
    let (default, default_json) = sweep(&dir.join("default"), &[]);
    let (full, full_json) = sweep(&dir.join("full"), &["--rigid-form", "full"]);
    assert!(!default.contains_key("rigid_form"), "{default:?}");
    assert_eq!(full["rigid_form"], "full");
    let small_angle = number(&default, "rigid_min_overturning");
    let housner = number(&full, "rigid_min_overturning");
    assert!((small_angle / 2.998 - 1.0).abs() < 2e-3, "{small_angle}");
    assert!((housner / 3.033 - 1.0).abs() < 2e-3, "{housner}");
    for column in ["min_overturning", "rigid_limit_min_overturning"] {
        assert_eq!(default[column], full[column], "{column}");
    }
    let plan = |json: &serde_json::Value| json.to_string();
    assert!(!plan(&default_json).contains("rigid_form"));
    assert!(
        plan(&full_json).contains("\"rigid_form\":\"full\""),
        "{full_json}"
    );
    let header = std::fs::read_to_string(dir.join("full").join("sweep.csv")).unwrap();
    let header = header.lines().next().unwrap();
    assert!(
        header.contains("rigid_amplitude_over_g_tan_alpha,rigid_form,rigid_limit_min_overturning"),
        "{header}"
    );

    // The same from a sweep file; an unknown form there is refused, naming the key.
    let from_file = sweep_from_file(
        &dir,
        model,
        "vary = [\"excitation.period=0.8\"]\nfind_min = \"excitation.amplitude=1.8:8\"\n\
         tol = 1e-4\nrigid_form = \"full\"\n",
    );
    assert_eq!(from_file, full);
    assert_sweep_file_refused(
        &dir,
        model,
        "find_min = \"excitation.amplitude=1.8:8\"\nrigid_form = \"exact\"\n",
        &["rigid_form", "exact"],
    );
}

/// The first row of sweep.csv and sweep.json of `flexrock sweep MODEL --out OUT ARGS EXTRA`.
fn first_row_and_plan(
    model: &str,
    out: &Path,
    args: &[&str],
    extra: &[&str],
) -> (HashMap<String, String>, serde_json::Value) {
    let mut all = vec!["sweep", model, "--out", out.to_str().unwrap(), "--quiet"];
    all.extend(args);
    all.extend(extra);
    run(&all);
    let json = serde_json::from_slice(&std::fs::read(out.join("sweep.json")).unwrap()).unwrap();
    (crate::common::sweep_rows(out).remove(0), json)
}

/// The first row of `flexrock sweep MODEL --sweep-file FILE`, FILE holding `text` (written under
/// `dir`, the output in `dir/file`).
fn sweep_from_file(dir: &Path, model: &str, text: &str) -> HashMap<String, String> {
    let file = dir.join("plan.toml");
    std::fs::write(&file, text).unwrap();
    let out = dir.join("file");
    run(&[
        "sweep",
        model,
        "--out",
        out.to_str().unwrap(),
        "--sweep-file",
        file.to_str().unwrap(),
        "--quiet",
    ]);
    crate::common::sweep_rows(&out).remove(0)
}

/// `flexrock sweep MODEL --sweep-file FILE`, FILE holding `text` (written under `dir`): refused
/// with exit code 2, a message holding each of `words`, and no output directory.
fn assert_sweep_file_refused(dir: &Path, model: &str, text: &str, words: &[&str]) {
    let file = dir.join("refused.toml");
    std::fs::write(&file, text).unwrap();
    let refused = dir.join("refused");
    let o = flexrock(&[
        "sweep",
        model,
        "--out",
        refused.to_str().unwrap(),
        "--sweep-file",
        file.to_str().unwrap(),
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    for word in words {
        assert!(stderr.contains(word), "{word}: {stderr}");
    }
    assert!(!refused.exists());
}

/// `--rigid-overturning cannot-return --rigid-restitution 0.9` make Housner's block Zhang and
/// Makris' (2001): on their block at omega_p/p = 5 (models/zhang-makris.toml) its smallest
/// overturning amplitude over g tan(alpha) falls where the paper puts it, between 3.00 and 3.01,
/// within 0.4 % (core/tests/published_rigid.rs: 3.0186). Each choice has its column after
/// Housner's two and its key in sweep.json; the default sweep has neither, and the elastic body's
/// and the rigid limit's columns do not change. A sweep file does the same. Refused, naming the
/// flag (or the file's key), without output: a restitution outside (0, 1), an unknown rule, and
/// either choice without a minimum search.
#[test]
fn housners_block_can_be_made_a_papers_and_says_so() {
    let dir = scratch_dir("sweep-rigid-choices");
    let model = crate::common::repo("models/zhang-makris.toml");
    let model = model.to_str().unwrap();
    let search = [
        "--find-min",
        "excitation.amplitude=2:20",
        "--scan",
        "200",
        "--tol",
        "1e-4",
    ];
    let sweep = |out: &Path, extra: &[&str]| first_row_and_plan(model, out, &search, extra);
    let choices = [
        "--rigid-overturning",
        "cannot-return",
        "--rigid-restitution",
        "0.9",
    ];
    let (default, default_json) = sweep(&dir.join("default"), &[]);
    let (papers, papers_json) = sweep(&dir.join("papers"), &choices);
    for column in ["rigid_overturning", "rigid_restitution"] {
        assert!(!default.contains_key(column), "{default:?}");
    }
    assert_eq!(papers["rigid_overturning"], "cannot-return");
    assert_eq!(papers["rigid_restitution"], "0.9");
    let beta = number(&papers, "rigid_amplitude_over_g_tan_alpha");
    assert!((3.00 * 0.996..=3.01 * 1.004).contains(&beta), "{beta}");
    for column in ["min_overturning", "rigid_limit_min_overturning"] {
        assert_eq!(default[column], papers[column], "{column}");
    }
    let find = &papers_json["plan"]["find_min"];
    assert_eq!(find["rigid_overturning"], "cannot-return", "{papers_json}");
    assert_eq!(find["rigid_restitution"], 0.9, "{papers_json}");
    assert!(!default_json.to_string().contains("rigid_overturning"));
    assert!(!default_json.to_string().contains("rigid_restitution"));
    let header = std::fs::read_to_string(dir.join("papers").join("sweep.csv")).unwrap();
    assert!(
        header.lines().next().unwrap().contains(
            "rigid_amplitude_over_g_tan_alpha,rigid_overturning,rigid_restitution,\
             rigid_limit_min_overturning"
        ),
        "{header}"
    );

    // The same from a sweep file.
    let from_file = sweep_from_file(
        &dir,
        model,
        "find_min = \"excitation.amplitude=2:20\"\nscan = 200\ntol = 1e-4\n\
         rigid_overturning = \"cannot-return\"\nrigid_restitution = 0.9\n",
    );
    assert_eq!(from_file, papers);

    // Refusals.
    let refused = dir.join("refused");
    let find_min: &[&str] = &["--find-min", "excitation.amplitude=2:20"];
    let vary: &[&str] = &["--vary", "excitation.amplitude=3,4"];
    for (extra, search, words) in [
        (
            &["--rigid-restitution", "1.5"][..],
            find_min,
            &["--rigid-restitution", "1.5", "between 0 and 1"][..],
        ),
        (
            &["--rigid-restitution", "1"][..],
            find_min,
            &["--rigid-restitution", "between 0 and 1"][..],
        ),
        (
            &["--rigid-restitution", "0"][..],
            find_min,
            &["--rigid-restitution", "between 0 and 1"][..],
        ),
        (
            &["--rigid-restitution", "NaN"][..],
            find_min,
            &["--rigid-restitution", "NaN"][..],
        ),
        (
            &["--rigid-overturning", "cannot-return"][..],
            vary,
            &["--rigid-overturning", "minimum search"][..],
        ),
        (
            &["--rigid-restitution", "0.9"][..],
            vary,
            &["--rigid-restitution", "minimum search"][..],
        ),
        (
            &["--rigid-overturning", "never"][..],
            find_min,
            &["never"][..],
        ),
    ] {
        let mut args = vec!["sweep", model, "--out", refused.to_str().unwrap()];
        args.extend(search);
        args.extend(extra);
        let o = flexrock(&args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {stderr}");
        for word in words {
            assert!(stderr.contains(word), "{extra:?}: {stderr}");
        }
        assert!(!refused.exists(), "{extra:?}");
    }
    assert_sweep_file_refused(
        &dir,
        model,
        "find_min = \"excitation.amplitude=2:20\"\nrigid_overturning = \"always\"\n",
        &["rigid_overturning", "always"],
    );
}

/// A rigid block's search that fails fails its point, saying which block, where and why,
/// instead of leaving the block's cells empty as if nothing had overturned: a restitution this
/// close to 1 under a cosine pulse that starts a hair (4e-11) above the tipping acceleration
/// makes Housner's block chatter until the event budget stops it. (A pulse exactly at the
/// tipping acceleration does not lift the block at all.)
#[test]
fn a_failed_rigid_search_fails_its_point() {
    let dir = scratch_dir("sweep-rigid-failure");
    let model = crate::common::repo("models/zhang-makris.toml");
    let model = model.to_str().unwrap();
    // g B/H of the model file's block is 2.4525 m/s^2 to the last bit.
    let tipping = 9.81 * 0.803_290_680_408_769_3 / 3.213_162_721_635_077;
    assert_eq!(tipping, 2.4525);
    let find_min = "excitation.amplitude=2.4525000001:20".to_string();
    let search = [
        "--set",
        "excitation.shape=symmetric",
        "--find-min",
        &find_min,
        "--scan",
        "50",
    ];
    let (row, _) = first_row_and_plan(
        model,
        &dir.join("near-1"),
        &search,
        &["--rigid-restitution", "0.999999999"],
    );
    assert_eq!(row["status"], "failed", "{row:?}");
    assert!(
        row["reason"].starts_with("Housner's rigid block at excitation.amplitude = 2.4525000001: ")
            && row["reason"].contains("events"),
        "{}",
        row["reason"]
    );
    assert_eq!(row["rigid_min_overturning"], "");
    // Housner's own restitution: the same search succeeds.
    let (row, _) = first_row_and_plan(model, &dir.join("housner"), &search, &[]);
    assert_eq!(row["status"], "ok", "{row:?}");
}

/// The continuity the paper asks for (its section 4): as E grows, the elastic body's smallest
/// overturning amplitude under a one-sine pulse tends to that of the rigid block the model
/// becomes, which lifts off at (L^3/(8 sigma)) g B/H = 1.1226 g B/H (src/rigid.rs). Measured:
/// the largest relative difference over pulse periods 0.3 to 2 s is 6.3 % at E x 1e2 and
/// 0.25 % at E x 1e4. Housner's block (uplift at g B/H) stays 1.2 % away at Tp = 2 s, where the
/// uplift threshold decides.
#[test]
fn the_spectrum_of_a_stiff_body_tends_to_the_rigid_limit() {
    let largest_difference = |youngs_modulus: &str| -> (f64, f64) {
        let dir = scratch_dir(&format!("sweep-rigid-{youngs_modulus}"));
        run(&[
            "sweep",
            pulse_model().to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
            "--set",
            &format!("body.youngs_modulus={youngs_modulus}"),
            "--vary",
            "excitation.period=0.3,0.5,0.8,1.2,2",
            "--find-min",
            "excitation.amplitude=0.5:40",
            "--tol",
            "1e-4",
            "--quiet",
        ]);
        let mut to_limit: f64 = 0.0;
        let mut to_housner: f64 = 0.0;
        for row in crate::common::sweep_rows(&dir) {
            let elastic = number(&row, "min_overturning");
            to_limit =
                to_limit.max((elastic / number(&row, "rigid_limit_min_overturning") - 1.0).abs());
            to_housner =
                to_housner.max((elastic / number(&row, "rigid_min_overturning") - 1.0).abs());
        }
        (to_limit, to_housner)
    };
    let (soft, _) = largest_difference("5e8");
    let (stiff, housner) = largest_difference("5e10");
    assert!(stiff < 5e-3, "E x 1e4: {stiff}");
    assert!(stiff < soft / 5.0, "E x 1e2: {soft}, E x 1e4: {stiff}");
    assert!(housner > 1e-2, "Housner's block: {housner}");
}

#[test]
fn records_and_scales_make_an_incremental_dynamic_analysis() {
    let dir = scratch_dir("sweep-ida");
    let out = dir.join("out");
    // Run from the repository, as a user types the pattern; the records' largest samples are
    // far below 20 g, 400 times El Centro's 0.35 g is not.
    let o = flexrock_in(
        &repo(""),
        &[
            "sweep",
            "models/elcentro1940.toml",
            "--out",
            out.to_str().unwrap(),
            "--vary",
            "excitation.path=validation/records/elCentro.AT2,validation/records/A-*.AT2",
            "--vary",
            "excitation.scale=1,2,400",
            "--set",
            "excitation.tail=1",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Not a terminal: no progress bar, nothing on standard error.
    assert!(
        o.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let rows = crate::common::sweep_rows(&out);
    let paths: Vec<&str> = rows.iter().map(|r| r["excitation.path"].as_str()).collect();
    assert_eq!(
        paths,
        [
            "validation/records/elCentro.AT2",
            "validation/records/elCentro.AT2",
            "validation/records/elCentro.AT2",
            "validation/records/A-ELC180.AT2",
            "validation/records/A-ELC180.AT2",
            "validation/records/A-ELC180.AT2",
        ]
    );
    for pair in rows.chunks(3) {
        assert_eq!(pair[2]["status"], "invalid");
        assert!(
            pair[2]["reason"].contains("excitation.scale"),
            "{}",
            pair[2]["reason"]
        );
        // The amplitude columns are the scaled record's peak: twice as large at scale 2.
        let ratio = number(&pair[1], "amplitude_over_g_tan_alpha")
            / number(&pair[0], "amplitude_over_g_tan_alpha");
        assert!((ratio - 2.0).abs() < 1e-12, "{ratio}");
        assert_eq!(pair[0]["omega_p_over_p"], "");
        // Each row is the run of its point.
        for row in &pair[..2] {
            let overrides = Overrides {
                settings: vec![
                    Setting::parse(&format!(
                        "excitation.path={}",
                        repo(&row["excitation.path"]).display()
                    ))
                    .unwrap(),
                    Setting::parse(&format!("excitation.scale={}", row["excitation.scale"]))
                        .unwrap(),
                    Setting::parse("excitation.tail=1").unwrap(),
                ],
                ..Overrides::default()
            };
            let model = Model::load(&repo("models/elcentro1940.toml"), &overrides).unwrap();
            let solution = flexrock::commands::run::simulate(&model).unwrap();
            assert_eq!(row["overturned"], solution.overturned.to_string());
            assert_eq!(row["steps"], solution.stats.steps.to_string());
        }
    }
}

#[test]
fn set_on_run_gives_the_run_of_the_edited_file() {
    let dir = scratch_dir("sweep-set-run");
    let text = std::fs::read_to_string(repo("models/sine-pulse.toml"))
        .unwrap()
        .replace("amplitude = 3.0 ", "amplitude = 3.5 ");
    assert!(text.contains("amplitude = 3.5"));
    let edited = dir.join("edited.toml");
    std::fs::write(&edited, text).unwrap();
    let (a, b) = (dir.join("a"), dir.join("b"));
    run(&[
        "run",
        edited.to_str().unwrap(),
        "--out",
        a.to_str().unwrap(),
    ]);
    run(&[
        "run",
        repo("models/sine-pulse.toml").to_str().unwrap(),
        "--out",
        b.to_str().unwrap(),
        "--set",
        "excitation.amplitude=3.5",
    ]);
    for file in ["history.csv", "events.csv"] {
        assert_eq!(
            std::fs::read(a.join(file)).unwrap(),
            std::fs::read(b.join(file)).unwrap(),
            "{file}"
        );
    }
    // A set value is checked by the file's rules, and the message names --set.
    let o = flexrock(&[
        "run",
        repo("models/sine-pulse.toml").to_str().unwrap(),
        "--out",
        dir.join("c").to_str().unwrap(),
        "--set",
        "excitation.period=-1",
    ]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr.contains("--set excitation.period = -1"), "{stderr}");
    assert!(!dir.join("c").exists());
}

#[test]
fn a_sweep_file_is_the_flags_written_down() {
    let dir = scratch_dir("sweep-file");
    let file = dir.join("plan.toml");
    std::fs::write(
        &file,
        "vary = [\"excitation.period=0.6,0.9\"]\nset = [\"excitation.shape=symmetric\"]\n\
         find_min = \"excitation.amplitude=1:12\"\nscan = 12\ntol = 0.01\n",
    )
    .unwrap();
    let (a, b) = (dir.join("a"), dir.join("b"));
    let model = pulse_model();
    let model = model.to_str().unwrap();
    run(&[
        "sweep",
        model,
        "--out",
        a.to_str().unwrap(),
        "--sweep-file",
        file.to_str().unwrap(),
    ]);
    run(&[
        "sweep",
        model,
        "--out",
        b.to_str().unwrap(),
        "--vary",
        "excitation.period=0.6,0.9",
        "--set",
        "excitation.shape=symmetric",
        "--find-min",
        "excitation.amplitude=1:12",
        "--scan",
        "12",
        "--tol",
        "0.01",
    ]);
    assert_eq!(files_of(&a), files_of(&b));
    // An unknown key of the sweep file is refused, naming it.
    std::fs::write(&file, "vary = [\"excitation.period=1,2\"]\nvry = 1\n").unwrap();
    let o = flexrock(&[
        "sweep",
        model,
        "--out",
        dir.join("c").to_str().unwrap(),
        "--sweep-file",
        file.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("vry"));
    assert!(!dir.join("c").exists());
}

#[test]
fn the_rows_in_memory_are_the_rows_of_sweep_csv() {
    use flexrock::commands::sweep::store;
    use flexrock_core::analysis::sweep::{Axis, Request, Sweep};
    let dir = scratch_dir("sweep-in-memory");
    status_ok(&mut grid_sweep(&dir, &[]));
    let request = Request {
        axes: vec![
            Axis::parse("excitation.period=lin:0.3:1.5:24", Path::new(".")).unwrap(),
            Axis::parse("excitation.amplitude=lin:1:8:20", Path::new(".")).unwrap(),
        ],
        ..Request::default()
    };
    let sweep = Sweep::new(&pulse_model(), request, Path::new(".")).unwrap();
    let rows = store::rows(&sweep, &store::Silent);
    let mut table = flexrock::writers::Table::new(
        &sweep
            .plan
            .columns()
            .iter()
            .map(String::as_str)
            .collect::<Vec<_>>(),
    );
    for row in rows {
        table.row(row);
    }
    let written = std::fs::read(dir.join("sweep.csv")).unwrap();
    assert_eq!(
        String::from_utf8(table.into_bytes()).unwrap(),
        String::from_utf8(written).unwrap()
    );
}

#[test]
fn rows_until_stops_starting_points_once_told() {
    use flexrock_core::analysis::sweep::{Axis, Request, Sweep};
    use std::sync::atomic::{AtomicUsize, Ordering};
    let request = Request {
        axes: vec![Axis::parse("excitation.period=lin:0.3:1.5:24", Path::new(".")).unwrap()],
        ..Request::default()
    };
    let sweep = Sweep::new(&pulse_model(), request, Path::new(".")).unwrap();
    let layout = sweep.plan.layout();
    let fields = |rows: Vec<flexrock_core::analysis::sweep::PointResult>| -> Vec<Vec<String>> {
        rows.iter().map(|r| r.fields(layout)).collect()
    };
    let all = fields(sweep.rows(0..sweep.points(), &|| {}));
    let until = sweep.rows_until(0..sweep.points(), &|| false);
    assert_eq!(until.map(fields), Some(all));
    // Told to stop once five points have asked: the other points are not computed.
    let asked = AtomicUsize::new(0);
    let stopped = sweep.rows_until(0..sweep.points(), &|| {
        asked.fetch_add(1, Ordering::SeqCst) >= 5
    });
    assert!(stopped.is_none());
    assert_eq!(asked.load(Ordering::SeqCst), sweep.points());
}

#[test]
fn a_record_held_in_memory_sweeps_as_its_file() {
    use flexrock_core::analysis::sweep::{Axis, Request, Sweep};
    use flexrock_core::floor::record::read_record;
    let model = repo("models/elcentro1940.toml");
    let axes = || vec![Axis::parse("excitation.scale=0.5,1", Path::new(".")).unwrap()];
    let from_file = Sweep::new(
        &model,
        Request {
            axes: axes(),
            ..Request::default()
        },
        Path::new("."),
    )
    .unwrap();
    // The same model naming a record that is no file, given in memory under that name (as
    // read without a format named).
    let text = std::fs::read_to_string(&model)
        .unwrap()
        .replace("../validation/records/elCentro.AT2", "in-memory.AT2")
        .replace("format = \"peer-at2\"", "");
    let record = read_record(&repo("validation/records/elCentro.AT2"), None, None).unwrap();
    let here = repo("models");
    let in_memory = Sweep::from_text(
        &text,
        &here,
        Request {
            axes: axes(),
            records: vec![("in-memory.AT2".to_string(), record)],
            ..Request::default()
        },
        &here,
    )
    .unwrap();
    assert!(!here.join("in-memory.AT2").exists());
    let layout = from_file.plan.layout();
    let rows = in_memory.rows(0..2, &|| {});
    assert!(rows.iter().all(|r| r.reason.is_empty()), "{rows:?}");
    let fields = |rows: &[flexrock_core::analysis::sweep::PointResult]| -> Vec<Vec<String>> {
        rows.iter().map(|r| r.fields(layout)).collect()
    };
    assert_eq!(fields(&rows), fields(&from_file.rows(0..2, &|| {})));
    // Its digest is of its samples, not of a file that cannot be read.
    let digest = &in_memory.plan.records[0].sha256;
    assert_eq!(digest.len(), 64, "{digest}");
}

#[test]
fn a_loose_tolerance_is_flagged_point_by_point_and_on_standard_error() {
    let dir = scratch_dir("sweep-loose");
    let sweep = |out: &Path, rtol: &str| {
        let o = flexrock(&[
            "sweep",
            pulse_model().to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--vary",
            "excitation.period=lin:0.6:1.2:7",
            "--vary",
            "excitation.amplitude=lin:1.5:3:7",
            "--set",
            "solver.method=bdf",
            "--set",
            &format!("solver.rtol={rtol}"),
            "--set",
            "solver.atol=1e-6",
        ]);
        assert!(o.status.success());
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let (loose, tight) = (dir.join("loose"), dir.join("tight"));
    let loose_stderr = sweep(&loose, "1e-2");
    let tight_stderr = sweep(&tight, "1e-8");
    assert!(tight_stderr.is_empty(), "{tight_stderr}");
    assert!(
        loose_stderr.contains("energy_residual_share"),
        "{loose_stderr}"
    );
    // Every point whose uplift count the loose run got wrong is flagged.
    let (loose, tight) = (
        crate::common::sweep_rows(&loose),
        crate::common::sweep_rows(&tight),
    );
    let mut wrong = 0;
    for (l, t) in loose.iter().zip(&tight) {
        assert!(number(t, "energy_residual_share") < 1e-2);
        if l["n_uplift"] != t["n_uplift"] {
            wrong += 1;
            assert!(number(l, "energy_residual_share") > 1e-2, "{l:?}");
        }
    }
    assert!(wrong > 0, "the loose map should get some points wrong");
}

#[test]
fn a_device_as_the_model_is_refused_not_read_forever() {
    let dir = scratch_dir("sweep-dev-zero");
    let out = dir.join("out");
    let o = flexrock(&[
        "sweep",
        "/dev/zero",
        "--vary",
        "excitation.amplitude=1,2",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("character device"));
    assert!(!out.exists());
}

/// A minimum search that finds no overturning value leaves empty every column derived from the
/// searched key (the amplitude ratios here), instead of showing the search's upper bound there:
/// plotted against omega_p / p, those bounds drew a plateau that does not exist. The columns the
/// key does not change (alpha, p, T, omega_p / p) keep their closed forms.
#[test]
fn no_derived_column_holds_a_value_where_its_source_is_empty() {
    let dir = scratch_dir("sweep-empty-derived");
    let out = dir.join("out");
    // 0.5-3 m/s^2 overturns the body under the shortest pulse of a log axis from 0.2 s to 3 s
    // only at the long periods (book/src/model.md §7c: the body needs
    // about 15.8 m/s^2 at 0.7 s).
    run(&[
        "sweep",
        pulse_model().to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "excitation.period=0.3,2.5",
        "--find-min",
        "excitation.amplitude=0.5:3",
        "--scan",
        "10",
        "--quiet",
    ]);
    let rows = crate::common::sweep_rows(&out);
    let model = model_with(&[]);
    let b = &model.body;
    let (g, alpha) = (b.gravity, (b.width / b.height).atan());
    let p = (3.0 * g / (4.0 * (b.height.hypot(b.width) / 2.0))).sqrt();
    let mut empty = 0;
    for row in &rows {
        assert_eq!(row["status"], "ok", "{row:?}");
        let tp: f64 = row["excitation.period"].parse().unwrap();
        let omega = number(row, "omega_p_over_p");
        assert!((omega - 2.0 * std::f64::consts::PI / tp / p).abs() < 1e-13 * omega);
        assert!((number(row, "alpha") - alpha).abs() < 1e-15);
        if row["min_overturning"].is_empty() {
            empty += 1;
            for derived in [
                "amplitude_over_g_tan_alpha",
                "amplitude_over_uplift_acceleration",
                "t_overturn",
            ] {
                assert_eq!(row[derived], "", "{derived} in {row:?}");
            }
        } else {
            let a = number(row, "min_overturning");
            let got = number(row, "amplitude_over_g_tan_alpha");
            let expected = a / (g * alpha.tan());
            assert!(
                (got - expected).abs() <= 1e-13 * expected,
                "{got} {expected}"
            );
        }
    }
    assert!(empty >= 1, "every point overturned: {rows:?}");
}

/// A sweep keeps no history, so the limit on history rows does not make a point of 1e4 s (2e6
/// rows of 0.005 s) invalid.
#[test]
fn a_point_of_the_longest_duration_runs() {
    let dir = scratch_dir("sweep-longest");
    run(&[
        "sweep",
        pulse_model().to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--vary",
        "simulation.duration=1e4",
        "--set",
        "solver.method=exact",
        "--quiet",
    ]);
    let rows = crate::common::sweep_rows(&dir);
    assert_eq!(rows[0]["status"], "ok", "{}", rows[0]["reason"]);
}
