//! `flexrock plot`, `flexrock run --plot` and `flexrock events` on real runs: the figures, their
//! panels and contents, the event table, and broken run directories refused with nothing written.

use crate::common;

use std::path::{Path, PathBuf};

use crate::common::{file_names, flexrock, scratch_dir};
use flexrock::figures::run::FIGURES;
use flexrock::writers::run_dir::RunData;

fn stderr_of(o: &std::process::Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Runs the reference model (with extra flags) into `dir/name` and returns that directory.
fn run_reference(dir: &Path, name: &str, extra: &[&str]) -> PathBuf {
    let out = dir.join(name);
    let o = common::run_reference(&out, extra);
    assert!(o.status.success(), "{}", stderr_of(&o));
    out
}

fn summary_json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

/// The rows of a run's events.csv as the csv crate reads them, by column name.
fn events_csv_rows(dir: &Path) -> Vec<csv::StringRecord> {
    let mut reader = csv::Reader::from_path(dir.join("events.csv")).unwrap();
    reader.records().map(|r| r.unwrap()).collect()
}

/// True when every element opened in `svg` is closed, in order (a well-formedness check of
/// the tags, enough to catch a truncated or interleaved file).
fn tags_balance(svg: &str) -> bool {
    let mut stack: Vec<&str> = Vec::new();
    let mut rest = svg;
    while let Some(start) = rest.find('<') {
        let Some(end) = rest[start..].find('>') else {
            return false;
        };
        let tag = &rest[start + 1..start + end];
        rest = &rest[start + end + 1..];
        if tag.starts_with('?') || tag.starts_with('!') || tag.ends_with('/') {
            continue;
        }
        if let Some(name) = tag.strip_prefix('/') {
            if stack.pop() != Some(name.trim()) {
                return false;
            }
        } else {
            stack.push(tag.split_whitespace().next().unwrap_or(""));
        }
    }
    stack.is_empty()
}

fn assert_figures(dir: &Path) {
    let titles: [&[&str]; 3] = [
        &[
            "(a)",
            "(d)",
            "a (m/s²)",
            "q (m)",
            "s, flexural part",
            "r, rocking part",
            "q\u{307} (m/s)",
            "uplift (",
            "landing (",
            "±sₙ",
        ],
        &[
            "(a)",
            "(c)",
            "F (N)",
            "r (m)",
            "s (m)",
            "this run",
            "model F(q)",
        ],
        &[
            "(a)",
            "(b)",
            "energy E (J)",
            "kinetic",
            "potential V(q)",
            "input work",
            "damping work",
            "net loss at events",
            "ΔE/Eₛ",
        ],
    ];
    for (name, titles) in FIGURES.iter().zip(titles) {
        let svg = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(svg.starts_with("<svg"), "{name}");
        assert!(svg.trim_end().ends_with("</svg>"), "{name}");
        assert!(tags_balance(&svg), "{name}: tags do not balance");
        for title in titles {
            assert!(svg.contains(title), "{name} lacks {title:?}");
        }
    }
}

#[test]
fn plot_draws_the_three_figures_of_a_run() {
    let dir = scratch_dir("plot-cli-draw");
    let run = run_reference(&dir, "run", &[]);
    let o = flexrock(&["plot", run.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for name in FIGURES {
        assert!(stdout.contains(name), "{stdout}");
    }
    assert_figures(&run);
    let mut expected = vec!["episodes.csv", "events.csv", "history.csv", "summary.json"];
    expected.extend(FIGURES);
    expected.sort();
    assert_eq!(file_names(&run), expected, "no temporaries are left");
}

#[test]
fn the_path_over_f_of_q_goes_beyond_uplift_and_the_curve_is_the_model_s() {
    let dir = scratch_dir("plot-cli-force");
    let run = run_reference(&dir, "run", &[]);
    let summary = summary_json(&run);
    let c = &summary["constants"];
    let s_n = c["uplift_displacement"].as_f64().unwrap();
    let width = c["width"].as_f64().unwrap();
    let ke = c["generalised_stiffness"].as_f64().unwrap();

    let data = RunData::read(&run).unwrap();
    let automaton = flexrock_core::physics::automaton::Automaton::new(&data.summary.constants);
    let panels = flexrock::figures::run::force_panels(&data, &automaton);
    let force = &panels[0];
    let path = force.series.iter().find(|s| s.name == "this run").unwrap();
    // The paper's example rocks (11 uplifts): its path leaves the linear branch.
    let beyond = path.points.iter().filter(|p| p.0.abs() > s_n).count();
    assert!(beyond > 10, "{beyond} points beyond s_n");
    assert!(path.points.iter().any(|p| p.0 > s_n) && path.points.iter().any(|p| p.0 < -s_n));
    // Beyond s_n the force falls: it is below the peak Ke s_n.
    for &(q, f) in &path.points {
        assert!(f.abs() <= ke * s_n * (1.0 + 1e-9), "F({q}) = {f}");
    }

    // The model's curve: zero at -B and B, Ke s_n at s_n (book/src/model.md §3, restoring force).
    let curve = force
        .series
        .iter()
        .find(|s| s.name == "model F(q)")
        .unwrap();
    let first = curve.points[0];
    let last = curve.points[curve.points.len() - 1];
    assert_eq!(first.0, -width);
    assert_eq!(last.0, width);
    assert!(first.1.abs() < 1e-9 * ke * s_n && last.1.abs() < 1e-9 * ke * s_n);
    let peak = curve.points.iter().find(|p| p.0 == s_n).unwrap();
    assert!((peak.1 - ke * s_n).abs() <= 1e-12 * ke * s_n, "{peak:?}");
    let half = curve
        .points
        .iter()
        .min_by(|a, b| (a.0 - 0.5 * s_n).abs().total_cmp(&(b.0 - 0.5 * s_n).abs()))
        .unwrap();
    assert!((half.1 - ke * half.0).abs() <= 1e-9 * ke * s_n);
}

#[test]
fn the_velocity_panel_marks_every_event_and_the_energy_books_close() {
    let dir = scratch_dir("plot-cli-books");
    let run = run_reference(&dir, "run", &[]);
    let summary = summary_json(&run);
    let data = RunData::read(&run).unwrap();
    let panels = flexrock::figures::run::motion_panels(&data);
    let velocity = &panels[3];
    let marked = |kind: &str| {
        velocity
            .series
            .iter()
            .find(|s| s.name.starts_with(kind))
            .map_or(0, |s| s.points.len())
    };
    assert_eq!(
        marked("uplift"),
        summary["n_uplift"].as_u64().unwrap() as usize
    );
    assert_eq!(
        marked("landing"),
        summary["n_landing"].as_u64().unwrap() as usize
    );
    assert_eq!(marked("overturn"), 0);

    // E(t) - E(0) = input work - damping work - lost at events + residual, on every row: the
    // figure's energies, work columns and event losses are the solver's books.
    let automaton = flexrock_core::physics::automaton::Automaton::new(&data.summary.constants);
    let lost = flexrock::figures::run::energy_lost_at_events(&data, &automaton);
    let energy = |r: &flexrock::writers::run_dir::HistoryRow| {
        automaton.kinetic_energy(r.qdot) + automaton.potential_energy(r.mode, r.q)
    };
    let e0 = energy(&data.history[0]);
    let scale = summary["energy_scale"].as_f64().unwrap();
    assert!(scale > 100.0, "{scale}");
    let mut lost_now = 0.0;
    let mut k = 0;
    let mut checked = 0;
    for (i, row) in data.history.iter().enumerate() {
        // The step curve's value just after the events at or before this row's time; the row
        // before an event (same t, previous mode) has not had the jump.
        while k < lost.len() && lost[k].0 <= row.t {
            lost_now = lost[k].1;
            k += 1;
        }
        let before_event = data
            .history
            .get(i + 1)
            .is_some_and(|next| next.t == row.t && next.mode != row.mode);
        if before_event {
            continue;
        }
        let closure =
            energy(row) - e0 - row.work_input + row.work_damping + lost_now - row.energy_residual;
        assert!(
            closure.abs() <= 1e-9 * scale,
            "t = {}: books do not close by {closure} J",
            row.t
        );
        checked += 1;
    }
    assert!(checked > 1000);
    assert!(lost_now.abs() > 1.0, "events change the energy: {lost_now}");
}

#[test]
fn run_with_plot_writes_the_figures_that_plot_draws() {
    let dir = scratch_dir("plot-cli-run-plot");
    let run = run_reference(&dir, "run", &["--plot"]);
    let mut expected = vec!["episodes.csv", "events.csv", "history.csv", "summary.json"];
    expected.extend(FIGURES);
    expected.sort();
    assert_eq!(file_names(&run), expected);
    assert_figures(&run);
    let from_run: Vec<Vec<u8>> = FIGURES
        .iter()
        .map(|name| std::fs::read(run.join(name)).unwrap())
        .collect();
    let o = flexrock(&["plot", run.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    for (name, bytes) in FIGURES.iter().zip(&from_run) {
        assert!(
            &std::fs::read(run.join(name)).unwrap() == bytes,
            "{name} differs between run --plot and plot"
        );
    }
}

#[test]
fn newmark_runs_are_plotted_too() {
    let dir = scratch_dir("plot-cli-newmark");
    let run = run_reference(&dir, "run", &["--method", "newmark", "--plot"]);
    assert_figures(&run);
    let o = flexrock(&["events", run.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr_of(&o));
}

/// A copy of a good run directory with one change, for the refusals below.
fn broken_copy(good: &Path, dir: &Path, name: &str, change: impl FnOnce(&Path)) -> PathBuf {
    let broken = dir.join(name);
    std::fs::create_dir_all(&broken).unwrap();
    for file in ["history.csv", "events.csv", "summary.json"] {
        std::fs::copy(good.join(file), broken.join(file)).unwrap();
    }
    // A figure of an earlier plot, which a refused plot must leave as it is.
    std::fs::write(broken.join(FIGURES[0]), "earlier figure").unwrap();
    change(&broken);
    broken
}

/// `flexrock plot DIR` must fail with exit 2, name `words`, and leave DIR as it was.
fn refused_plot(dir: &Path, words: &[&str]) -> String {
    let before = file_names(dir);
    let o = flexrock(&["plot", dir.to_str().unwrap()]);
    let stderr = stderr_of(&o);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    for word in words {
        assert!(stderr.contains(word), "expected {word:?} in {stderr}");
    }
    assert_eq!(file_names(dir), before, "files were written or removed");
    assert_eq!(
        std::fs::read_to_string(dir.join(FIGURES[0])).unwrap(),
        "earlier figure"
    );
    stderr
}

/// Rewrites a CSV file through the csv crate, dropping one column by name.
fn drop_column(path: &Path, column: &str) {
    let mut reader = csv::Reader::from_path(path).unwrap();
    let headers = reader.headers().unwrap().clone();
    let keep: Vec<usize> = (0..headers.len())
        .filter(|&i| &headers[i] != column)
        .collect();
    assert!(keep.len() < headers.len(), "{column} is not a column");
    let mut writer = csv::Writer::from_path(path.with_extension("tmp")).unwrap();
    writer
        .write_record(keep.iter().map(|&i| &headers[i]))
        .unwrap();
    for record in reader.records() {
        let record = record.unwrap();
        writer
            .write_record(keep.iter().map(|&i| &record[i]))
            .unwrap();
    }
    writer.flush().unwrap();
    drop(writer);
    std::fs::rename(path.with_extension("tmp"), path).unwrap();
}

#[test]
fn broken_run_directories_are_refused_and_nothing_is_written() {
    let dir = scratch_dir("plot-cli-broken");
    let good = run_reference(&dir, "good", &[]);

    let missing = broken_copy(&good, &dir, "no-events", |d| {
        std::fs::remove_file(d.join("events.csv")).unwrap()
    });
    refused_plot(&missing, &["events.csv", "flexrock run"]);
    let o = flexrock(&["events", missing.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    assert!(stderr_of(&o).contains("events.csv"));

    for column in ["q", "mode", "work_input"] {
        let no_column = broken_copy(&good, &dir, &format!("no-{column}"), |d| {
            drop_column(&d.join("history.csv"), column)
        });
        refused_plot(&no_column, &["history.csv", &format!("`{column}`")]);
    }

    let bad_value = broken_copy(&good, &dir, "bad-value", |d| {
        let path = d.join("history.csv");
        let text = std::fs::read_to_string(&path).unwrap();
        let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
        let mut fields: Vec<&str> = lines[4].split(',').collect();
        fields[3] = "abc"; // the column s
        lines[4] = fields.join(",");
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
    });
    refused_plot(
        &bad_value,
        &["history.csv", "line 5", "`s`", "abc", "number"],
    );

    let corrupt = broken_copy(&good, &dir, "corrupt-summary", |d| {
        let path = d.join("summary.json");
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::write(&path, &text[..text.len() / 2]).unwrap();
    });
    refused_plot(&corrupt, &["summary.json", "JSON"]);

    let no_key = broken_copy(&good, &dir, "summary-without-scale", |d| {
        let path = d.join("summary.json");
        let mut value: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        value.as_object_mut().unwrap().remove("energy_scale");
        std::fs::write(&path, serde_json::to_vec(&value).unwrap()).unwrap();
    });
    refused_plot(&no_key, &["summary.json", "`energy_scale`"]);

    let no_width = broken_copy(&good, &dir, "constants-without-width", |d| {
        let path = d.join("summary.json");
        let mut value: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        value["constants"].as_object_mut().unwrap().remove("width");
        std::fs::write(&path, serde_json::to_vec(&value).unwrap()).unwrap();
    });
    refused_plot(&no_width, &["summary.json", "`constants`", "`width`"]);

    let nothing = dir.join("does-not-exist");
    let o = flexrock(&["plot", nothing.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    assert!(!nothing.exists());
}

#[test]
fn columns_are_read_by_name_in_any_order() {
    let dir = scratch_dir("plot-cli-column-order");
    let good = run_reference(&dir, "good", &[]);
    let reordered = dir.join("reordered");
    std::fs::create_dir_all(&reordered).unwrap();
    for file in ["history.csv", "events.csv", "summary.json"] {
        std::fs::copy(good.join(file), reordered.join(file)).unwrap();
    }
    // Reverse the columns of history.csv and add one that flexrock does not know.
    let mut reader = csv::Reader::from_path(good.join("history.csv")).unwrap();
    let headers = reader.headers().unwrap().clone();
    let mut writer = csv::Writer::from_path(reordered.join("history.csv")).unwrap();
    let mut names: Vec<&str> = headers.iter().rev().collect();
    names.push("note");
    writer.write_record(&names).unwrap();
    for record in reader.records() {
        let record = record.unwrap();
        let mut fields: Vec<&str> = record.iter().rev().collect();
        fields.push("x");
        writer.write_record(&fields).unwrap();
    }
    writer.flush().unwrap();
    drop(writer);
    let a = RunData::read(&good).unwrap();
    let b = RunData::read(&reordered).unwrap();
    assert_eq!(a.history, b.history);
    assert_eq!(a.events, b.events);
}

#[test]
fn events_prints_one_aligned_row_per_event() {
    let dir = scratch_dir("plot-cli-events");
    let run = run_reference(&dir, "run", &[]);
    let o = flexrock(&["events", run.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stdout = String::from_utf8_lossy(&o.stdout).into_owned();
    let lines: Vec<&str> = stdout.lines().collect();
    let rows = events_csv_rows(&run);
    assert!(rows.len() > 10);
    assert_eq!(lines.len(), 1 + rows.len(), "{stdout}");
    for word in [
        "index",
        "t (s)",
        "kind",
        "from",
        "to",
        "q (m)",
        "qdot_before",
        "qdot_after",
    ] {
        assert!(lines[0].contains(word), "{}", lines[0]);
    }
    // Aligned: every row ends where the header ends (numbers right-aligned in the last column).
    for line in &lines[1..] {
        assert_eq!(line.len(), lines[0].len(), "{line}");
    }
    let summary = summary_json(&run);
    let count = |kind: &str| {
        lines[1..]
            .iter()
            .filter(|l| l.split_whitespace().nth(2) == Some(kind))
            .count()
    };
    assert_eq!(
        count("uplift"),
        summary["n_uplift"].as_u64().unwrap() as usize
    );
    assert_eq!(
        count("landing"),
        summary["n_landing"].as_u64().unwrap() as usize
    );
    // Each row is its CSV row: index, kind, modes, and the time to the printed digits.
    for (line, row) in lines[1..].iter().zip(&rows) {
        let cells: Vec<&str> = line.split_whitespace().collect();
        assert_eq!(cells[0], &row[0]);
        assert_eq!(cells[2], &row[2]);
        assert_eq!(cells[3], &row[3]);
        assert_eq!(cells[4], &row[4]);
        let t: f64 = cells[1].parse().unwrap();
        assert!((t - row[1].parse::<f64>().unwrap()).abs() < 1e-9, "{line}");
    }
}

#[test]
fn events_of_a_run_without_events_says_so() {
    let dir = scratch_dir("plot-cli-no-events");
    let model = dir.join("calm.toml");
    std::fs::write(
        &model,
        common::reference_body(
            "[excitation]\nkind = \"harmonic\"\namplitude = 0.2\nperiod = 1.0\n\n\
             [simulation]\nduration = 2.0\n",
        ),
    )
    .unwrap();
    let out = dir.join("run");
    let o = flexrock(&[
        "run",
        model.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--plot",
    ]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    assert!(events_csv_rows(&out).is_empty());
    let o = flexrock(&["events", out.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert_eq!(stdout.lines().count(), 1, "{stdout}");
    assert!(stdout.contains("no events"), "{stdout}");
    // Its velocity panel has no markers, and its figures are still drawn.
    let svg = std::fs::read_to_string(out.join(FIGURES[0])).unwrap();
    assert!(!svg.contains("uplift ("));
    assert!(svg.contains("q\u{307} (m/s)"));
}

/// `flexrock plot` on a row's output says that it is a row's, and how a row's figures are drawn,
/// rather than naming a single body's key that a row's summary lacks.
#[test]
fn plot_on_a_row_s_output_says_it_is_a_row_s() {
    let dir = scratch_dir("plot-cli-row").join("row");
    let o = flexrock(&[
        "run",
        common::repo("models/row-pair.toml").to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
        "--duration",
        "1",
    ]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let before = file_names(&dir);
    let o = flexrock(&["plot", dir.to_str().unwrap()]);
    let stderr = stderr_of(&o);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("row of columns") && stderr.contains("flexrock run --plot"),
        "{stderr}"
    );
    assert_eq!(file_names(&dir), before, "files were written or removed");
}
