//! `flexrock report` on the committed validation inputs reproduces the committed
//! validation/REPORT.md byte for byte, and a summary with a key removed is an error naming the
//! file and the key.

use crate::common;

use std::path::Path;

use crate::common::{repo, scratch_dir};
use flexrock::commands::report::{report_text, write_report, ReportInputs};

fn inputs(results: &Path) -> ReportInputs {
    ReportInputs {
        compare_compensate: results.join("compare-compensate"),
        compare_substep: results.join("compare-substep"),
        converge: results.join("converge"),
        rigid: results.join("rigid"),
        figures_dir: "figures".to_string(),
        command: "validation/regenerate.sh".to_string(),
    }
}

/// The arguments validation/regenerate.sh passes, on `results`.
fn committed() -> ReportInputs {
    inputs(&repo("validation/results"))
}

#[test]
fn report_reproduces_the_committed_report() {
    let dir = scratch_dir("report-golden");
    let written = write_report(&committed(), &dir.join("REPORT.md")).expect("report written");
    let ours = std::fs::read_to_string(written).expect("report readable");
    let theirs =
        std::fs::read_to_string(repo("validation/REPORT.md")).expect("committed report readable");
    assert!(
        ours == theirs,
        "the report differs from validation/REPORT.md; first differing line: {:?}",
        ours.lines()
            .zip(theirs.lines())
            .find(|(a, b)| a != b)
            .or(Some(("(length)", "(length)")))
    );
}

#[test]
fn the_command_writes_the_committed_report() {
    let dir = scratch_dir("report-command");
    let results = repo("validation/results");
    let arg = |name: &str| results.join(name).display().to_string();
    let out = dir.join("REPORT.md");
    let output = common::flexrock(&[
        "report",
        "--compare-compensate",
        &arg("compare-compensate"),
        "--compare-substep",
        &arg("compare-substep"),
        "--converge",
        &arg("converge"),
        "--rigid",
        &arg("rigid"),
        "--figures",
        "figures",
        "--command",
        "validation/regenerate.sh",
        "--out",
        &out.display().to_string(),
    ]);
    assert!(output.status.success(), "{output:?}");
    assert_eq!(
        std::fs::read_to_string(out).unwrap(),
        std::fs::read_to_string(repo("validation/REPORT.md")).unwrap()
    );
}

/// A copy of the committed results under `name`, with `edit` applied to one file's text.
fn edited_copy(name: &str, file: &str, edit: impl Fn(&str) -> String) -> std::path::PathBuf {
    let dir = scratch_dir(name);
    for sub in ["compare-compensate", "compare-substep", "converge", "rigid"] {
        let from = repo("validation/results").join(sub);
        std::fs::create_dir_all(dir.join(sub)).unwrap();
        for entry in std::fs::read_dir(&from).unwrap() {
            let entry = entry.unwrap();
            std::fs::copy(entry.path(), dir.join(sub).join(entry.file_name())).unwrap();
        }
    }
    let path = dir.join(file);
    let text = std::fs::read_to_string(&path).unwrap();
    let edited = edit(&text);
    assert_ne!(edited, text, "the edit changed nothing in {file}");
    std::fs::write(&path, edited).unwrap();
    dir
}

/// Removes the line holding `"key":` from a JSON text (the key must be on a line of its own,
/// not the last of its object).
fn without_key(text: &str, key: &str) -> String {
    let needle = format!("\"{key}\":");
    let mut removed = false;
    text.lines()
        .filter(|l| {
            let hit = !removed && l.trim_start().starts_with(&needle);
            removed |= hit;
            !hit
        })
        .map(|l| format!("{l}\n"))
        .collect()
}

fn error_of(dir: &Path) -> String {
    match report_text(&inputs(dir)) {
        Ok(_) => panic!("the report was written from an incomplete file"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn a_summary_without_a_key_is_an_error_naming_the_key_and_the_file() {
    for (file, key) in [
        ("rigid/summary.json", "zeta_uplift"),
        ("rigid/summary.json", "T"),
        ("compare-compensate/compare.json", "max_abs_time_difference"),
        ("compare-substep/compare.json", "n_events"),
        ("compare-compensate/compare.json", "dt"),
        ("converge/convergence.json", "reference_method"),
        ("converge/convergence.json", "rtol"),
    ] {
        let dir = edited_copy("report-missing-key", file, |t| without_key(t, key));
        let message = error_of(&dir);
        assert!(
            message.contains(&format!("`{key}`")),
            "{file} without {key}: {message}"
        );
        assert!(
            message.contains(&dir.join(file).display().to_string()),
            "{file} without {key}: {message}"
        );
    }
}

#[test]
fn a_csv_without_a_column_is_an_error_naming_the_column_and_the_file() {
    for (file, column) in [
        ("compare-compensate/compare.csv", "t_newmark"),
        ("rigid/events.csv", "kind"),
    ] {
        let dir = edited_copy("report-missing-column", file, |t| {
            let (header, rest) = t.split_once('\n').unwrap();
            format!("{}\n{rest}", header.replacen(column, "renamed", 1))
        });
        let message = error_of(&dir);
        assert!(
            message.contains(&format!("`{column}`")),
            "{file} without {column}: {message}"
        );
        assert!(
            message.contains(&dir.join(file).display().to_string()),
            "{file} without {column}: {message}"
        );
    }
}

#[test]
fn the_numbers_come_from_the_files_not_from_the_text() {
    // A compare run at another step: the report says that step, and the stability limit follows
    // the file's beta and gamma.
    let dir = edited_copy("report-other-dt", "compare-compensate/compare.json", |t| {
        t.replace("\"dt\": 0.02,", "\"dt\": 0.01,")
    });
    let text = report_text(&inputs(&dir)).expect("report");
    assert!(
        text.contains("the exact solution vs Newmark dt = 0.01 s"),
        "{text}"
    );
    assert!(text.contains("(dt = 0.01 s)"), "{text}");
    assert!(text.contains("Newmark compensate dt = 0.01 | Newmark substep dt = 0.02"));
    let dir = edited_copy(
        "report-other-beta",
        "compare-compensate/compare.json",
        |t| {
            t.replace(
                "\"newmark_beta\": 0.16666666666666666,",
                "\"newmark_beta\": 0.0,",
            )
        },
    );
    let text = report_text(&inputs(&dir)).expect("report");
    // beta = 0: omega dt < 2, dt < T/pi = 0.318 T.
    assert!(text.contains("needs dt < 0.318 T"), "{text}");
}

#[test]
fn a_case_reads_back_what_converge_writes_nan_included() {
    let case = flexrock::commands::converge::Case {
        method: "newmark-substep".to_string(),
        dt: Some(0.02),
        rtol: None,
        max_q_error: 1e-3,
        max_event_time_error: f64::NAN,
        peak_error: 2e-3,
        event_count_difference: -1,
        unmatched_events: 1,
        steps: 300,
        rhs_evaluations: 533,
        wall_time_s: 1e-4,
        max_energy_residual: 0.5,
        status: "ok".to_string(),
    };
    let json = serde_json::to_string(&case).unwrap();
    assert!(json.contains("\"max_event_time_error\":null"), "{json}");
    let back: flexrock::commands::converge::Case = serde_json::from_str(&json).unwrap();
    assert!(back.max_event_time_error.is_nan());
    assert_eq!(back.rtol, None);
    assert_eq!(serde_json::to_string(&back).unwrap(), json);
    // A missing dt is an error, not None.
    let without_dt = json.replace("\"dt\":0.02,", "");
    let e = serde_json::from_str::<flexrock::commands::converge::Case>(&without_dt).unwrap_err();
    assert!(e.to_string().contains("`dt`"), "{e}");
}

#[test]
fn an_empty_time_in_compare_csv_reads_as_a_dash() {
    // An unmatched event has no Newmark time: the cell is empty and the report shows "-".
    let dir = edited_copy("report-empty-cell", "compare-compensate/compare.csv", |t| {
        let mut lines: Vec<String> = t.lines().map(str::to_string).collect();
        let mut cells: Vec<&str> = lines[1].split(',').collect();
        cells[5] = "";
        cells[6] = "";
        lines[1] = cells.join(",");
        lines.join("\n") + "\n"
    });
    let text = report_text(&inputs(&dir)).expect("report");
    assert!(
        text.contains("| 0 | uplift | pre-uplift -> rock-left | 0.520590 | - | - |"),
        "{text}"
    );
}

/// The rigid-limit run may be made with any method: the report names the method and the
/// setting its accuracy follows (rtol, dt, or none for the exact method), where it once
/// demanded `rtol` of every run.
#[test]
fn the_rigid_run_may_be_made_with_the_exact_method_or_newmark() {
    let model = repo("validation/models/rigid-free-rocking.toml");
    for (method, extra, named) in [
        ("exact", vec![], "exact. Housner"),
        (
            "newmark",
            vec!["--dt", "0.00001", "--set", "solver.newmark_beta=0.25"],
            "newmark-compensate at dt = 1e-5 s",
        ),
    ] {
        let dir = edited_copy(
            &format!("report-rigid-{method}"),
            "rigid/summary.json",
            |t| t.replace("\"bdf\"", "\"edited\""),
        );
        let mut args = vec![
            "run",
            model.to_str().unwrap(),
            "--method",
            method,
            "--timings-apart",
        ];
        args.extend(extra);
        let out = dir.join("rigid");
        args.extend(["--out", out.to_str().unwrap()]);
        let o = common::flexrock(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let text = report_text(&inputs(&dir)).unwrap_or_else(|e| panic!("{method}: {e}"));
        assert!(text.contains(named), "{method}: {text}");
    }
}
