//! `flexrock run` on a row model: the files it writes, the same bytes twice, each column of a
//! row whose gaps never close written exactly as the column's own run writes it, and bad row
//! files refused by key with no output.

use crate::common::{refused, repo, run_model as run, scratch_dir};

#[test]
fn a_row_run_writes_every_column_and_the_impacts_the_same_twice() {
    let dir = scratch_dir("rows-pair");
    let model = repo("models/row-pair.toml");
    let (a, b) = (dir.join("a"), dir.join("b"));
    for out in [&a, &b] {
        let o = run(&model, out, &["--plot"]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let mut names: Vec<String> = std::fs::read_dir(&a)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "contacts.csv",
            "episodes-0.csv",
            "episodes-1.csv",
            "events-0.csv",
            "events-1.csv",
            "history-0.csv",
            "history-1.csv",
            "impacts.csv",
            "row_motion.png",
            "row_motion.svg",
            "row_shapes.png",
            "row_shapes.svg",
            "summary.json"
        ]
    );
    for name in &names {
        assert_eq!(
            std::fs::read(a.join(name)).unwrap(),
            std::fs::read(b.join(name)).unwrap(),
            "{name} differs between two runs"
        );
    }
    let impacts = std::fs::read_to_string(a.join("impacts.csv")).unwrap();
    let rows: Vec<&str> = impacts.lines().collect();
    assert_eq!(
        rows[0],
        "instant,t,contact,left,right,height,closing_velocity,separating_velocity,impulse,\
         instant_energy_lost"
    );
    assert!(rows.len() > 1, "the pair should strike: {impacts}");
    // Every impact is an event of both columns, at the same time.
    let events = |i: usize| std::fs::read_to_string(a.join(format!("events-{i}.csv"))).unwrap();
    for row in &rows[1..] {
        let t = row.split(',').nth(1).unwrap();
        for i in 0..2 {
            assert!(
                events(i)
                    .lines()
                    .any(|e| e.contains(&format!(",{t},impact,"))),
                "column {i} has no impact at {t}"
            );
        }
    }
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(a.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["method"], "exact");
    assert_eq!(summary["n_impacts"], rows.len() - 1);
    assert_eq!(summary["columns"].as_array().unwrap().len(), 2);
}

/// A row whose gaps never close: each column's history.csv, events.csv and episodes.csv are the
/// bytes `flexrock run` writes for that column alone with the exact method.
#[test]
fn far_apart_columns_are_written_as_their_own_runs() {
    let dir = scratch_dir("rows-apart");
    let bodies = [
        "height = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5.0e6\ndamping_ratio = 0.05\n",
        "height = 3.0\nwidth = 0.8\ndensity = 500.0\nyoungs_modulus = 2.0e7\ndamping_ratio = 0.03\nself_weight = \"consistent\"\n",
    ];
    let excitation = "[excitation]\nkind = \"record\"\npath = \"RECORD\"\nformat = \"peer-at2\"\nunits = \"g\"\nscale = 1.5\ntail = 2.0\n\n[solver]\nmethod = \"exact\"\noutput_dt = 0.01\n"
        .replace("RECORD", repo("validation/records/elCentro.AT2").to_str().unwrap());
    let mut row = "[row]\ngaps = [50.0]\nrestitution = 0.5\n\n".to_string();
    for body in bodies {
        row += &format!("[[column]]\n{body}\n");
    }
    row += &excitation;
    std::fs::write(dir.join("row.toml"), &row).unwrap();
    let o = run(&dir.join("row.toml"), &dir.join("row"), &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for (i, body) in bodies.iter().enumerate() {
        let single = format!("[body]\n{body}\n{excitation}");
        let path = dir.join(format!("single-{i}.toml"));
        std::fs::write(&path, single).unwrap();
        let out = dir.join(format!("single-{i}"));
        let o = run(&path, &out, &[]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        for (row_name, single_name) in [
            (format!("history-{i}.csv"), "history.csv"),
            (format!("events-{i}.csv"), "events.csv"),
            (format!("episodes-{i}.csv"), "episodes.csv"),
        ] {
            let a = std::fs::read(dir.join("row").join(&row_name)).unwrap();
            let b = std::fs::read(out.join(single_name)).unwrap();
            assert!(a == b, "column {i}: {row_name} differs from the run alone");
        }
        let events = std::fs::read_to_string(out.join("events.csv")).unwrap();
        assert!(events.lines().count() > 3, "column {i} should rock");
    }
}

const ROW: &str = "[row]\ngaps = [0.02]\nrestitution = 0.5\n\n\
    [[column]]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5.0e6\n\n\
    [[column]]\nheight = 4.0\nwidth = 0.7\ndensity = 600.0\nyoungs_modulus = 5.0e7\n\n\
    [excitation]\nkind = \"paper-sine\"\namplitude = 4.0\nperiod = 1.0\nramp = 0.412\n\n\
    [simulation]\nduration = 2.0\n";

#[test]
fn bad_row_files_are_refused_by_key_with_no_output() {
    let cases: [(&str, String, &str); 9] = [
        (
            "gaps",
            ROW.replace("gaps = [0.02]", "gaps = [0.02, 0.01]"),
            "row.gaps = 2 gaps",
        ),
        (
            "gap-zero",
            ROW.replace("gaps = [0.02]", "gaps = [0.0]"),
            "row.gaps[0] = 0",
        ),
        (
            "restitution",
            ROW.replace("restitution = 0.5", "restitution = 1.2"),
            "row.restitution = 1.2",
        ),
        (
            "width",
            ROW.replacen("width = 0.7", "width = -0.7", 2).replacen(
                "width = -0.7",
                "width = 0.7",
                1,
            ),
            "column[1].width = -0.7",
        ),
        (
            "q0",
            ROW.replace(
                "youngs_modulus = 5.0e7\n",
                "youngs_modulus = 5.0e7\nq0 = 0.9\n",
            ),
            "column[1].q0 = 0.9",
        ),
        (
            "unknown-key",
            ROW.replace(
                "youngs_modulus = 5.0e7\n",
                "youngs_modulus = 5.0e7\nheigth = 2\n",
            ),
            "column[1]: unknown field `heigth`",
        ),
        (
            "method",
            ROW.to_string() + "[solver]\nmethod = \"bdf\"\n",
            "solver.method = \"bdf\"",
        ),
        (
            "table",
            ROW.to_string() + "[body]\nheight = 4.0\n",
            "unknown table `body`",
        ),
        (
            "overlap",
            ROW.replace(
                "youngs_modulus = 5.0e6\n",
                "youngs_modulus = 5.0e6\nq0 = 0.05\n",
            ),
            "overlap",
        ),
    ];
    for (name, text, expected) in cases {
        let message = refused("run", &format!("row-{name}"), &text);
        assert!(message.contains(expected), "{name}: {message}");
    }
}

/// The compliant contact law end to end: models/row-compliant.toml writes the same set of files
/// as the impact law, the same bytes twice; summary.json names the law, k and zeta and lists the
/// stretches of contact, each of which is a contact-start and a contact-end event of both
/// columns; impacts.csv has its header only.
#[test]
fn a_compliant_row_runs_end_to_end() {
    let dir = scratch_dir("rows-compliant");
    let model = repo("models/row-compliant.toml");
    let (a, b) = (dir.join("a"), dir.join("b"));
    for out in [&a, &b] {
        let o = run(&model, out, &[]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let stdout = String::from_utf8_lossy(&o.stdout);
        assert!(
            stdout.contains("compliant contacts (k = 1e7 N/m"),
            "{stdout}"
        );
    }
    let names = crate::common::file_names(&a);
    assert_eq!(names.len(), 9, "{names:?}");
    for name in &names {
        assert_eq!(
            std::fs::read(a.join(name)).unwrap(),
            std::fs::read(b.join(name)).unwrap(),
            "{name} differs between two runs"
        );
    }
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(a.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["method"], "tsit45");
    assert_eq!(summary["contact_law"]["law"], "compliant");
    assert_eq!(summary["contact_law"]["stiffness"], 1e7);
    let zeta = summary["contact_law"]["damping_ratio"].as_f64().unwrap();
    assert!(zeta > 0.2 && zeta < 0.3, "{zeta}");
    assert_eq!(summary["tolerances"]["rtol"], 1e-10);
    let stretches = summary["contact_stretches"].as_array().unwrap();
    assert!(stretches.len() >= 3, "{stretches:?}");
    for i in 0..2 {
        let events = std::fs::read_to_string(a.join(format!("events-{i}.csv"))).unwrap();
        for s in stretches {
            for (key, kind) in [("t_start", "contact-start"), ("t_end", "contact-end")] {
                let t = s[key].as_f64().unwrap();
                assert!(
                    events.contains(&format!(",{t},{kind},")),
                    "column {i} has no {kind} at {t}"
                );
            }
        }
    }
    let impacts = std::fs::read_to_string(a.join("impacts.csv")).unwrap();
    assert_eq!(impacts.lines().count(), 1, "{impacts}");
}

/// The rows of contacts.csv, split at commas.
fn contact_rows(dir: &std::path::Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(dir.join("contacts.csv")).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("t,contact,state,gap,closing_velocity,sliding_velocity,force,friction_force")
    );
    lines
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

/// contacts.csv of the impact law: one row per sample, the gap never below zero, no forces (its
/// forces are impulses), held exactly within the held stretches summary.json lists.
#[test]
fn the_impact_laws_contact_history_has_gaps_and_held_stretches() {
    let dir = scratch_dir("rows-contacts-impact");
    // The leaning pair of models/row-friction.toml under the impact law: held for seconds.
    let leaning = dir.join("leaning.toml");
    let text = std::fs::read_to_string(repo("models/row-friction.toml")).unwrap();
    let text: String = text
        .lines()
        .filter(|l| {
            !["contact", "stiffness", "friction", "method", "rtol", "atol"]
                .iter()
                .any(|k| l.starts_with(&format!("{k} ")))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&leaning, text).unwrap();
    let out = dir.join("leaning");
    let o = run(&leaning, &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    check_impact_contacts(&out, true);
    let out = dir.join("record");
    let o = run(&repo("models/row-record.toml"), &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    check_impact_contacts(&out, false);
}

/// The checks of contacts.csv of an impact-law row in `out`; `held` if it must hold some.
fn check_impact_contacts(out: &std::path::Path, must_hold: bool) {
    let out = out.to_path_buf();
    let rows = contact_rows(&out);
    // Every grid instant, for each of the two contacts (the record's row has three columns).
    let grid = |i: usize| {
        let history = std::fs::read_to_string(out.join(format!("history-{i}.csv"))).unwrap();
        history
            .lines()
            .skip(1)
            .map(|l| l.split(',').next().unwrap().to_string())
            .collect::<std::collections::BTreeSet<String>>()
    };
    let contacts = 1 + rows
        .iter()
        .map(|r| r[1].parse::<usize>().unwrap())
        .max()
        .unwrap();
    for c in 0..contacts {
        let times: std::collections::BTreeSet<String> = rows
            .iter()
            .filter(|r| r[1] == c.to_string())
            .map(|r| r[0].clone())
            .collect();
        let shared: std::collections::BTreeSet<String> =
            grid(c).intersection(&grid(c + 1)).cloned().collect();
        assert_eq!(times, shared, "contact {c}");
    }
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let held = summary["held_contacts"].as_array().unwrap();
    let mut held_rows = 0;
    for r in &rows {
        let (t, c, gap): (f64, usize, f64) = (
            r[0].parse().unwrap(),
            r[1].parse().unwrap(),
            r[3].parse().unwrap(),
        );
        assert!(gap >= -1e-9, "{r:?}");
        assert_eq!((r[6].as_str(), r[7].as_str()), ("", ""), "{r:?}");
        let inside = held.iter().any(|h| {
            h["contact"].as_u64() == Some(c as u64)
                && h["t_start"].as_f64().unwrap() <= t
                && h["t_end"].as_f64().is_none_or(|end| t < end)
        });
        assert_eq!(r[2] == "held", inside, "{r:?}");
        if inside {
            held_rows += 1;
            assert!(gap.abs() < 1e-9, "held but apart: {r:?}");
        }
    }
    eprintln!("{} contact rows, {held_rows} held", rows.len());
    assert_eq!(held_rows > 0, must_hold, "{held_rows} held rows");
}

/// Friction end to end: models/row-friction.toml sticks and slides; contacts.csv never holds a
/// friction force above mu times the contact force, its sticking faces do not slide, and each
/// change is an event of both columns.
#[test]
fn a_row_with_friction_sticks_and_slides() {
    let dir = scratch_dir("rows-friction");
    let out = dir.join("a");
    let o = run(&repo("models/row-friction.toml"), &out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("friction mu = 0.5"), "{stdout}");
    let rows = contact_rows(&out);
    let mut seen = std::collections::BTreeSet::new();
    for r in &rows {
        seen.insert(r[2].clone());
        let (force, friction): (f64, f64) = (r[6].parse().unwrap(), r[7].parse().unwrap());
        assert!(
            friction.abs() <= 0.5 * force.max(0.0) * (1.0 + 1e-9) + 1e-9,
            "{r:?}"
        );
        if r[2] == "sticking" {
            let sliding: f64 = r[5].parse().unwrap();
            assert!(sliding.abs() < 1e-8, "{r:?}");
        }
        if r[2] == "open" {
            assert_eq!((force, friction), (0.0, 0.0), "{r:?}");
        }
    }
    assert!(
        seen.contains("sliding") && seen.contains("sticking"),
        "{seen:?}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["row"]["friction"].as_f64(), Some(0.5));
    let stretches = summary["contact_stretches"].as_array().unwrap();
    let changes: u64 = stretches
        .iter()
        .map(|s| s["friction_changes"].as_u64().unwrap())
        .sum();
    for i in 0..2 {
        let events = std::fs::read_to_string(out.join(format!("events-{i}.csv"))).unwrap();
        let logged = events
            .lines()
            .filter(|l| l.contains(",friction-stick,") || l.contains(",friction-slip,"))
            .count() as u64;
        assert_eq!(logged, changes + stretches.len() as u64, "column {i}");
    }
}

#[test]
fn bad_contact_laws_are_refused_naming_the_stiffness() {
    let compliant =
        |keys: &str| ROW.replace("restitution = 0.5\n", &format!("restitution = 0.5\n{keys}"));
    for (name, keys, expected) in [
        (
            "missing",
            "contact = \"compliant\"\n",
            "row.stiffness = (missing)",
        ),
        (
            "zero",
            "contact = \"compliant\"\nstiffness = 0.0\n",
            "row.stiffness = 0",
        ),
        (
            "negative",
            "contact = \"compliant\"\nstiffness = -5e6\n",
            "row.stiffness = -5e6",
        ),
        (
            "impact",
            "contact = \"impact\"\nstiffness = 1e7\n",
            "row.stiffness = 1e7",
        ),
        ("default", "stiffness = 1e7\n", "row.stiffness = 1e7"),
    ] {
        let message = refused("run", &format!("row-stiffness-{name}"), &compliant(keys));
        assert!(message.contains(expected), "{name}: {message}");
    }
}

#[test]
fn solver_flags_are_refused_for_a_row() {
    let dir = scratch_dir("rows-flags");
    let model = dir.join("row.toml");
    std::fs::write(&model, ROW).unwrap();
    for (flags, expected) in [
        (vec!["--method", "bdf"], "--method = bdf"),
        (vec!["--check"], "--check = true"),
        (vec!["--rtol", "1e-8"], "--rtol = "),
        (vec!["--set", "row.restitution=0.3"], "--set"),
    ] {
        let out = dir.join("out");
        let o = run(&model, &out, &flags);
        assert_eq!(o.status.code(), Some(2), "{flags:?}");
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(stderr.contains(expected), "{flags:?}: {stderr}");
        assert!(!out.exists(), "{flags:?} left output");
    }
    // The message says which method a row has, for either contact law (a compliant row is
    // solved by tsit45, not by the exact method).
    let o = run(
        &repo("models/row-compliant.toml"),
        &dir.join("compliant"),
        &["--method", "exact"],
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--method = exact")
            && stderr.contains("the exact method under the impact law")
            && stderr.contains("tsit45 with its rtol and atol under the compliant law"),
        "{stderr}"
    );
    // --duration applies, and is checked as the flag.
    let o = run(&model, &dir.join("short"), &["--duration", "1.5"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("short/summary.json")).unwrap()).unwrap();
    assert_eq!(summary["duration"], 1.5);
    let o = run(&model, &dir.join("negative"), &["--duration=-1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--duration = -1"));
    // A mistake in the file is still the file's when --duration is given.
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, ROW.replacen("width = 0.7", "width = -0.7", 1)).unwrap();
    let o = run(&bad, &dir.join("bad-out"), &["--duration", "1.5"]);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("bad.toml") && stderr.contains("column[0].width = -0.7"),
        "{stderr}"
    );
}

/// Three columns a millimetre apart under El Centro: impacts accumulate, and the columns are held
/// together in stretches (summary.json lists them), pairs and all three at once; every column's
/// energy books still close, and the gaps never open negative beyond rounding.
#[test]
fn columns_pressed_together_under_a_record_are_held_and_their_books_close() {
    let dir = scratch_dir("rows-held");
    let text = std::fs::read_to_string(repo("models/row-record.toml"))
        .unwrap()
        .replace("gaps = [0.015, 0.01]", "gaps = [0.001, 0.001]")
        .replace("restitution = 0.6", "restitution = 0.3")
        .replace(
            "../validation/records/elCentro.AT2",
            repo("validation/records/elCentro.AT2").to_str().unwrap(),
        );
    let model = dir.join("row.toml");
    std::fs::write(&model, text).unwrap();
    let o = run(&model, &dir.join("out"), &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("of persistent contact"), "{stdout}");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("out/summary.json")).unwrap()).unwrap();
    let held = summary["held_contacts"].as_array().unwrap();
    assert!(held.len() > 5, "{held:?}");
    for stretch in held {
        let (start, end) = (
            stretch["t_start"].as_f64().unwrap(),
            stretch["t_end"].as_f64().unwrap(),
        );
        assert!(end > start, "{stretch}");
    }
    // Both contacts held at once at some instant: all three columns moving as one.
    let overlapping = held.iter().any(|a| {
        held.iter().any(|b| {
            a["contact"] != b["contact"]
                && a["t_start"].as_f64() < b["t_end"].as_f64()
                && b["t_start"].as_f64() < a["t_end"].as_f64()
        })
    });
    assert!(overlapping, "no instant with all three held");
    for column in summary["columns"].as_array().unwrap() {
        let residual = column["max_energy_residual"].as_f64().unwrap();
        let scale = column["energy_scale"].as_f64().unwrap();
        assert!(residual <= 1e-12 * scale, "{residual} of {scale}");
    }
}

/// `--shapes-at` draws the strip at the times given, sorted, even without --plot, with the other
/// files of the run; each panel's title names its time.
#[test]
fn the_strip_of_shapes_is_drawn_at_the_times_given() {
    let dir = scratch_dir("rows-shapes");
    let model = dir.join("row.toml");
    std::fs::write(&model, ROW).unwrap();
    let out = dir.join("out");
    let o = run(&model, &out, &["--shapes-at", "1.5, 0.25,0"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut names: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .collect();
    names.sort();
    assert!(names.contains(&"row_shapes.svg".to_string()), "{names:?}");
    assert!(names.contains(&"row_shapes.png".to_string()), "{names:?}");
    assert!(!names.contains(&"row_motion.svg".to_string()), "{names:?}");
    assert!(names.contains(&"summary.json".to_string()), "{names:?}");
    let svg = std::fs::read_to_string(out.join("row_shapes.svg")).unwrap();
    let at = |title: &str| {
        // A title follows its panel's label: "(a) t = 0 s".
        svg.lines()
            .position(|line| {
                line.trim().starts_with('(') && line.trim().ends_with(&format!(") {title}"))
            })
            .unwrap_or_else(|| panic!("no panel titled {title}"))
    };
    assert!(at("t = 0 s") < at("t = 0.25 s") && at("t = 0.25 s") < at("t = 1.5 s"));
    let png = std::fs::read(out.join("row_shapes.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

/// Bad times for the strip are refused naming the flag, the value and the rule, with exit code 2
/// and nothing written: an output directory from before keeps its files as they were.
#[test]
fn hostile_shape_times_are_refused_with_no_output() {
    let dir = scratch_dir("rows-shapes-hostile");
    let model = dir.join("row.toml");
    // The row of ROW runs 2 s.
    std::fs::write(&model, ROW).unwrap();
    let earlier = dir.join("earlier");
    std::fs::create_dir_all(&earlier).unwrap();
    std::fs::write(earlier.join("summary.json"), "kept").unwrap();
    for (value, rule) in [
        ("nan", "finite and within [0, 2] s"),
        ("1,inf", "finite and within [0, 2] s"),
        ("-0.5", "finite and within [0, 2] s"),
        ("2.5", "finite and within [0, 2] s"),
        ("1e308", "finite and within [0, 2] s"),
        ("1,,2", "is not a number"),
        ("one", "is not a number"),
        ("", "is not a number"),
        ("0,0.2,0.4,0.6,0.8,1,1.2,1.4,1.6", "at most 8 times"),
    ] {
        for out in [dir.join("new"), earlier.clone()] {
            let o = run(&model, &out, &["--plot", &format!("--shapes-at={value}")]);
            let stderr = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{value}: {stderr}");
            assert!(
                stderr.contains(&format!("--shapes-at = {value:?}"))
                    || stderr.contains(&format!("--shapes-at = {value}")),
                "{value}: {stderr}"
            );
            assert!(stderr.contains(rule), "{value}: {stderr}");
            assert!(!stderr.contains("panicked"), "{value}: {stderr}");
        }
        assert!(!dir.join("new").exists(), "{value}: output written");
        let names: Vec<_> = std::fs::read_dir(&earlier).unwrap().collect();
        assert_eq!(names.len(), 1, "{value}: files added");
        assert_eq!(
            std::fs::read_to_string(earlier.join("summary.json")).unwrap(),
            "kept"
        );
    }
    // A single body has no strip.
    let out = dir.join("single");
    let o = run(
        &repo("models/ichinose1986.toml"),
        &out,
        &["--shapes-at", "1.0"],
    );
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert!(
        stderr.contains("--shapes-at") && stderr.contains("applies only to a row model"),
        "{stderr}"
    );
    assert!(!out.exists());
}
