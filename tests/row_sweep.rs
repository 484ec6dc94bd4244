//! `flexrock sweep` on a row model: a small gap x amplitude map whose every verdict is checked
//! against `flexrock run` of that point's row and of each column alone; the verdict maps; bad
//! keys refused by name with nothing written; a sweep killed half-way resumes to the bytes of an
//! uninterrupted one.

use std::collections::HashMap;
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::common::{flexrock, flexrock_command, repo, scratch_dir};

fn ok(o: Output) -> Output {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

fn summary(dir: &Path) -> serde_json::Value {
    serde_json::from_slice(&std::fs::read(dir.join("summary.json")).unwrap()).unwrap()
}

/// models/row-pair.toml with the gap and the sine's amplitude of a point.
fn row_at(gap: &str, amplitude: &str) -> String {
    let text = std::fs::read_to_string(repo("models/row-pair.toml")).unwrap();
    assert!(text.contains("gaps = [0.02]") && text.contains("amplitude = 4.0"));
    text.replace("gaps = [0.02]", &format!("gaps = [{gap}]"))
        .replace("amplitude = 4.0", &format!("amplitude = {amplitude}"))
}

/// Column `i` of models/row-pair.toml as a single body under the same sine, by the exact method.
fn column_alone(i: usize, amplitude: &str) -> String {
    let youngs_modulus = ["5.0e6", "5.0e7"][i];
    format!(
        "[body]\nheight = 4.0\nwidth = 0.7\ndepth = 1.0\ndensity = 600.0\n\
         youngs_modulus = {youngs_modulus}\ndamping_ratio = 0.05\n\n\
         [excitation]\nkind = \"paper-sine\"\namplitude = {amplitude}\nperiod = 1.0\n\
         ramp = 0.412\n\n[simulation]\nduration = 6.0\n\n[solver]\nmethod = \"exact\"\n\
         output_dt = 0.005\n"
    )
}

/// `flexrock run` of a model text; its summary.json.
fn run_text(dir: &Path, name: &str, text: &str) -> serde_json::Value {
    let model = dir.join(format!("{name}.toml"));
    std::fs::write(&model, text).unwrap();
    let out = dir.join(name);
    ok(flexrock(&[
        "run",
        model.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]));
    summary(&out)
}

#[test]
fn every_verdict_of_a_map_is_what_the_row_and_each_column_alone_give() {
    let dir = scratch_dir("row-sweep-map");
    let out = dir.join("map");
    let o = ok(flexrock(&[
        "sweep",
        repo("models/row-pair.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "row.gaps=0.002,0.0535",
        "--vary",
        "excitation.amplitude=5.263,6.21",
        "--quiet",
    ]));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("sweep of 4 points"), "{stdout}");
    let mut seen: HashMap<String, usize> = HashMap::new();
    for (p, row) in crate::common::sweep_rows(&out).iter().enumerate() {
        assert_eq!(row["status"], "ok", "{row:?}");
        let (gap, amplitude) = (&row["row.gaps"], &row["excitation.amplitude"]);
        let together = run_text(&dir, &format!("row-{p}"), &row_at(gap, amplitude));
        let ended_by = together["overturned_column"].as_u64().map(|c| c as usize);
        assert_eq!(
            row["overturned_column"],
            ended_by.map_or(String::new(), |c| c.to_string())
        );
        assert_eq!(
            row["n_contacts"],
            together["n_impacts"].as_u64().unwrap().to_string()
        );
        for i in 0..2 {
            let alone = run_text(&dir, &format!("alone-{p}-{i}"), &column_alone(i, amplitude));
            let alone_over = alone["overturned"].as_bool().unwrap();
            let expected = match ended_by {
                Some(c) if c != i => "undecided",
                Some(_) if alone_over => "same",
                Some(_) => "toppled",
                None if alone_over => "saved",
                None => "same",
            };
            let verdict = &row[&format!("c{i}_verdict")];
            assert_eq!(verdict, expected, "point {p}, column {i}: {row:?}");
            assert_eq!(
                row[&format!("c{i}_alone_overturned")],
                alone_over.to_string()
            );
            *seen.entry(verdict.clone()).or_default() += 1;
        }
    }
    // The map holds both kinds of cell that a neighbour makes.
    assert!(
        seen.contains_key("saved") && seen.contains_key("toppled"),
        "{seen:?}"
    );
    // The verdict maps, one per column, as SVG and PNG.
    let svg = std::fs::read_to_string(out.join("verdicts.svg")).unwrap();
    for text in [
        "(a) column 0",
        "(b) column 1",
        "saved",
        "toppled",
        "gap g, every gap (m)",
    ] {
        assert!(svg.contains(text), "verdicts.svg lacks {text:?}");
    }
    let png = std::fs::read(out.join("verdicts.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG\r\n\x1a\n"));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("sweep.json")).unwrap()).unwrap();
    assert_eq!(json["plan"]["row_columns"], 2);
    assert_eq!(
        json["files"],
        serde_json::json!(["sweep.csv", "verdicts.svg", "verdicts.png", "sweep.json"])
    );
}

#[test]
fn bad_keys_of_a_row_are_refused_by_name_with_nothing_written() {
    let dir = scratch_dir("row-sweep-refused");
    let model = repo("models/row-pair.toml");
    let cases: [(&[&str], &[&str]); 8] = [
        (
            &["--vary", "row.gaps.1=lin:0.01:0.02:2"],
            &["row.gaps.1 = 0.01", "the row has 1 gap: row.gaps.0"],
        ),
        (
            &["--vary", "column.2.youngs_modulus=1e6,2e6"],
            &["column.2.youngs_modulus = 1e6", "the row has 2 columns"],
        ),
        (
            &["--vary", "body.youngs_modulus=1e6,2e6"],
            &["body.youngs_modulus = 1e6", "a row model has no [body]"],
        ),
        (
            &["--vary", "column.0.stiffness=1,2"],
            &["column.0.stiffness = 1", "unknown field `stiffness`"],
        ),
        (
            &[
                "--vary",
                "row.gaps=0.01,0.02",
                "--vary",
                "row.gaps.0=0.01,0.02",
            ],
            &["row.gaps.0", "sets a value that the axis row.gaps sets too"],
        ),
        (
            &["--vary", "row.gaps=tight,loose"],
            &["row.gaps = tight", "a gap is a number"],
        ),
        (
            &[
                "--vary",
                "excitation.amplitude=1,2",
                "--find-min",
                "excitation.period=0.5:2",
            ],
            &["--find-min", "a minimum search is not made for a row"],
        ),
        (
            &["--set", "column.5.width=1", "--vary", "row.gaps=0.01,0.02"],
            &["column.5.width = 1", "the row has 2 columns"],
        ),
    ];
    for (k, (args, needles)) in cases.iter().enumerate() {
        let out = dir.join(format!("out-{k}"));
        let mut all = vec![
            "sweep",
            model.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
            "--quiet",
        ];
        all.extend_from_slice(args);
        let o = flexrock(&all);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {stderr}");
        for needle in *needles {
            assert!(
                stderr.contains(needle),
                "{args:?}: {needle:?} not in {stderr}"
            );
        }
        assert!(!stderr.contains("panicked"), "{stderr}");
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
}

/// The 400-point gap x amplitude map of models/row-pair.toml, one thread, chunks of 8 points.
fn grid(out: &Path) -> Command {
    let mut command = flexrock_command();
    command.args([
        "sweep",
        repo("models/row-pair.toml").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--vary",
        "row.gaps=lin:0.002:0.1:20",
        "--vary",
        "excitation.amplitude=lin:1:10:20",
        "--chunk-size",
        "8",
        "--threads",
        "1",
        "--quiet",
    ]);
    command
}

fn files_of(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        .filter(|e| e.file_type().unwrap().is_file())
        .map(|e| {
            let name = e.file_name().to_string_lossy().into_owned();
            (name, std::fs::read(e.path()).unwrap())
        })
        .collect();
    files.sort();
    files
}

#[test]
fn a_row_sweep_killed_half_way_resumes_to_the_same_bytes() {
    let dir = scratch_dir("row-sweep-kill");
    let reference = dir.join("reference");
    ok(grid(&reference).output().unwrap());
    let killed = dir.join("killed");
    let mut child = grid(&killed)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let started = Instant::now();
    while crate::common::chunk_files(&killed).len() < 3 {
        if let Some(status) = child.try_wait().unwrap() {
            panic!("the sweep ended ({status}) before 3 chunks were written");
        }
        assert!(started.elapsed() < Duration::from_secs(120), "no chunks");
        std::thread::sleep(Duration::from_millis(1));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(!killed.join("sweep.csv").exists(), "killed after the end");
    let o = ok(grid(&killed).output().unwrap());
    let stdout = String::from_utf8_lossy(&o.stdout);
    let found: usize = stdout
        .split(" computed now, ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no count of points found done in {stdout}"));
    assert!(found >= 24, "{stdout}");
    assert_eq!(files_of(&killed), files_of(&reference));
    // A single body's sweep is refused in the row sweep's directory.
    let other = flexrock(&[
        "sweep",
        repo("models/pulse-map.toml").to_str().unwrap(),
        "--out",
        killed.to_str().unwrap(),
        "--vary",
        "excitation.amplitude=1,2",
        "--quiet",
    ]);
    assert_eq!(other.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&other.stderr).contains("another sweep"));
    assert_eq!(files_of(&killed), files_of(&reference));
}
